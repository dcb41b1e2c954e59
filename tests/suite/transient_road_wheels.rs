//! The road-grid Monte Carlo for vehicles with several wheels (`transient::road_wheels_monte_carlo`):
//! wheels at positions along one track (the wheelbase delay read on the road, x(t) − ℓ) and wheels on two
//! tracks synthesised with their coherence, against the stationary quadrature at constant speed and
//! against the exact route of the bounce and roll combinations while accelerating.

use crate::common;
use crate::common::root;
use std::path::Path;
use std::sync::Arc;
use stochvib::coherence::{Coherence, ConstantCoherence, IsotropicCoherence};
use stochvib::estimate::chi_squared_quantile;
use stochvib::models::InputLayout;
use stochvib::response::analyze_output;
use stochvib::scenario::{load_scenario, parse_scenario};
use stochvib::spectrum::{Domain, Exponential, Spectrum};
use stochvib::system::FrequencyResponse;
use stochvib::transient::{
    input_model, road_wheels_monte_carlo, solve, ExactOptions, FixedSystem, RoadGridOptions, SpeedProfile, Start,
    TimeVaryingSystem, TransientInput, Wheel, WheelRoad,
};

/// The two-sided χ² bounds of s²/σ² for R realizations at the level 1 − α/2 each side.
fn chi2_bounds(r: usize, alpha: f64) -> (f64, f64) {
    let df = r as f64 - 1.0;
    (
        chi_squared_quantile(df, alpha / 2.0).unwrap() / df,
        chi_squared_quantile(df, 1.0 - alpha / 2.0).unwrap() / df,
    )
}

/// The wheels of a catalogue layout.
fn wheels(layout: &InputLayout) -> Vec<Wheel> {
    match layout {
        InputLayout::Track { positions, gains } => positions
            .iter()
            .zip(gains)
            .map(|(&position, &gain)| Wheel {
                track: 0,
                position,
                gain,
            })
            .collect(),
        InputLayout::TwoTracks {
            tracks,
            positions,
            gains,
            ..
        } => tracks
            .iter()
            .zip(positions)
            .zip(gains)
            .map(|((&track, &position), &gain)| Wheel { track, position, gain })
            .collect(),
        InputLayout::Single => vec![Wheel {
            track: 0,
            position: 0.0,
            gain: 1.0,
        }],
    }
}

/// At constant speed the grid run of the catalogue's half car (`data/half-car.toml`: one track, the rear
/// axle 2.7 m behind the front, ISO 8608 class C with its band, 10 m/s) and full vehicle
/// (`data/full-vehicle-two-tracks.toml`: four wheels on two tracks of the isotropic Dodds–Robson coherence
/// at a 1.5 m track width, 20 m/s) is stationary, with the variances of the stationary analysis of the same
/// files (`analyze_output`: quadrature of the inputs' cross-spectral matrix with the delays e^{−iωℓ/v},
/// not the grid). 300 realizations (seeds 7, 8) at 5 times 0.5 s apart: for Gaussian outputs
/// (R − 1)s²/σ² ~ χ²_{R−1}; α = 10⁻⁶ split over every (file, output, time) (Bonferroni) bounds the false
/// failure by 10⁻⁶. The grid's biases (band π/Δx beyond the road's 17.8 rad/m; interpolation ≤ (ΩΔx)²/6 at
/// the wheel hop) are below 1 %, inside the bounds (about ±30 %). The bounce (an absolute displacement)
/// is not compared: it follows the road's longest waves, which the periodic grid, a little longer than the
/// path, holds on bins ΔΩ = 2π/(NΔx) as wide as the band's lower edge (0.069 rad/m): a grid bias, not a
/// property of the route (measured s²/σ² = 1.58 at one time on the half car). The half car's body
/// acceleration passes the road's slope (dampers on the road: y contains E·u̇, u̇_j = v·h′(x − ℓ_j)), read from
/// the slope the grid synthesises with the track (every bin times iΩ).
#[test]
fn wheelbase_and_two_coherent_tracks_at_constant_speed_are_the_stationary_answer() {
    let spectra = root().join("spectra");
    let cases = [
        (
            "data/half-car.toml",
            10.0,
            vec!["pitch", "front_travel", "rear_travel", "body_acc"],
            7,
        ),
        (
            "data/full-vehicle-two-tracks.toml",
            20.0,
            vec!["pitch", "roll", "travel_fl", "travel_rr"],
            8,
        ),
    ];
    let times: Vec<f64> = (0..5).map(|k| 0.5 * k as f64).collect();
    let pairs: usize = cases.iter().map(|c| c.2.len() * times.len()).sum();
    let r = 300;
    let (lo, hi) = chi2_bounds(r, 1e-6 / pairs as f64);
    for (file, v, outputs, seed) in cases {
        let sc = load_scenario(&root().join(file), &spectra).unwrap();
        let ss = sc.model.system.state_space().unwrap().clone();
        let spectrum = sc.inputs[0].spectrum.clone();
        assert_eq!(spectrum.domain(), Domain::Spatial, "{file}");
        let coherence: Option<Arc<dyn Coherence>> = match sc.model.layout {
            InputLayout::TwoTracks { .. } => Some(Arc::new(IsotropicCoherence::new(1.5, 2.0).unwrap())),
            _ => None,
        };
        let road = WheelRoad {
            spectrum,
            coherence,
            wheels: wheels(&sc.model.layout),
        };
        let speed = SpeedProfile::constant(v).unwrap();
        // v·Δt = Δx: the hold interpolates the road as finely as the grid does
        let opts = RoadGridOptions {
            dx: 0.02,
            substeps: (0.5 * v / 0.02_f64).round() as usize,
            realizations: r,
            seed,
        };
        let mc = road_wheels_monte_carlo(&ss, &road, &speed, &times, &opts).unwrap();
        let sys = sc.model.system.as_ref();
        for name in outputs {
            let i = sys.output_index(name).unwrap();
            let var = analyze_output(sys, &sc.excitation, i).unwrap().variance.unwrap();
            for (k, t) in times.iter().enumerate() {
                let ratio = mc.variance[ss.output_index(name).unwrap()][k] / var;
                assert!(
                    lo <= ratio && ratio <= hi,
                    "{file} {name} at {t} s: s²/σ² = {ratio} outside [{lo}, {hi}]"
                );
            }
        }
    }
}

/// Two tracks of constant coherence ρ = 0.4 under a body in bounce and roll on two wheels
/// (`common::two_wheels`), accelerating from 5 to 15 m/s at 1 m/s² on a rational road (spatial exponential,
/// D = 1 cm², α = 0.2 1/m). For constant ρ the pair is exactly u_L = a s₁ + b s₂, u_R = a s₁ − b s₂ with s₁,
/// s₂ independent tracks of the one-track density and a = √((1 + ρ)/2), b = √((1 − ρ)/2) (then
/// S_LL = S_RR = (a² + b²)S = S and S_LR = (a² − b²)S = ρS at every wavenumber), so the exact route of two
/// independent rational sources felt with gains (a, a) and (b, −b) (`TimeVaryingSystem::with_sources`, the
/// road's filter under v(t)) gives σ²(t) of the two coherent tracks. The grid run synthesises the tracks
/// another way (the coherence's Cholesky row per bin). 400 realizations (seed 9) at 17 times; α = 10⁻⁶ over
/// the 34 (output, time) pairs (Bonferroni): false failure ≤ 10⁻⁶.
#[test]
fn two_tracks_of_constant_coherence_accelerating_against_the_exact_route() {
    let rho: f64 = 0.4;
    let road = r#"{ kind = "exponential", domain = "spatial", variance = "1 cm^2", alpha = "0.2 1/m" }"#;
    let text = crate::common::two_wheels(
        "",
        "[1, 1]",
        &format!("[input]\nspectrum = {road}\nspeed = \"10 m/s\"\n"),
    );
    let sc = parse_scenario(&text, Path::new("t.toml"), &root().join("spectra")).unwrap();
    let ss = sc.model.system.state_space().unwrap().clone();
    let spectrum: Arc<dyn Spectrum> = Arc::new(Exponential::new(1e-4, 0.2, Domain::Spatial).unwrap());
    let speed = common::accelerating_5_to_15();
    let times: Vec<f64> = (0..17).map(|k| 0.5 * k as f64).collect();
    let (a, b) = (((1.0 + rho) / 2.0).sqrt(), ((1.0 - rho) / 2.0).sqrt());
    let model = || input_model(spectrum.as_ref(), Some(&speed)).unwrap();
    let fam = Arc::new(FixedSystem::new(ss.clone(), None, "two wheels").unwrap());
    let input = TransientInput {
        model: model(),
        envelope: stochvib::transient::Envelope::unit(),
        mean: 0.0,
        gains: vec![a, a],
    };
    let second = stochvib::transient::ExtraSource {
        model: model(),
        gains: vec![b, -b],
        mean: 0.0,
    };
    let sys2 = TimeVaryingSystem::with_sources(fam, input, vec![second]).unwrap();
    let exact = solve(&sys2, &Start::Stationary, &times, &ExactOptions::default()).unwrap();
    let road = WheelRoad {
        spectrum: spectrum.clone(),
        coherence: Some(Arc::new(ConstantCoherence::new(rho).unwrap())),
        wheels: vec![
            Wheel {
                track: 0,
                position: 0.0,
                gain: 1.0,
            },
            Wheel {
                track: 1,
                position: 0.0,
                gain: 1.0,
            },
        ],
    };
    let opts = RoadGridOptions {
        dx: 0.02,
        substeps: 375,
        realizations: 400,
        seed: 9,
    };
    let mc = road_wheels_monte_carlo(&ss, &road, &speed, &times, &opts).unwrap();
    let (lo, hi) = chi2_bounds(opts.realizations, 1e-6 / (2.0 * times.len() as f64));
    let sys = sc.model.system.as_ref();
    for name in ["bounce", "roll"] {
        let i = sys.output_index(name).unwrap();
        for (k, t) in times.iter().enumerate() {
            let ratio = mc.variance[i][k] / exact.outputs[i].sigma[k].powi(2);
            assert!(
                lo <= ratio && ratio <= hi,
                "{name} at {t} s: s²/σ² = {ratio} outside [{lo}, {hi}]"
            );
        }
    }
}

/// `stochvib transient --monte-carlo 200` on the catalogue's full vehicle (`data/full-vehicle-two-tracks.toml`,
/// four wheels on two Dodds–Robson tracks at 20 m/s) with a `[transient]` window of 2 s: the command takes
/// the road grid of two tracks by itself (no exact route), its generator names the two tracks and the
/// wheelbase, and the run's σ(t) of every output lies inside the simultaneous χ² band around the stationary
/// analysis of the file (the analytic column reads `stationary σ`) at all 5 times: `compare_sigma` at
/// α = 10⁻⁶/7 per output fails with probability ≤ 10⁻⁶ for the 7 outputs. Under a speed profile the run has
/// no analytic curve (NaN) and says so.
#[test]
fn transient_command_runs_two_tracks_and_a_wheelbase_on_the_road_grid() {
    use crate::common::{cli_within, scratch_dir};
    use stochvib::study::transient_mc::compare_sigma;
    use stochvib::transient::monte_carlo::read_transient_run;
    let dir = scratch_dir("transient-road-wheels", "cli");
    let text = std::fs::read_to_string(root().join("data/full-vehicle-two-tracks.toml")).unwrap()
        + "\n[transient]\nduration = \"2 s\"\nstep = \"0.5 s\"\nstart = \"stationary\"\n";
    std::fs::write(dir.join("car.toml"), &text).unwrap();
    let limit = std::time::Duration::from_secs(900);
    let o = cli_within(
        &[
            "transient",
            "car.toml",
            "--monte-carlo",
            "200",
            "--seed",
            "4",
            "-o",
            "car.h5",
        ],
        &dir,
        limit,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("stationary σ"), "{out}");
    let (file, series) = read_transient_run(&dir.join("car.h5")).unwrap();
    let generator = &file.metadata().generator;
    assert!(
        generator.contains("2 track(s)") && generator.contains("x(t) - l_j"),
        "{generator}"
    );
    assert_eq!(series.outputs.len(), 7);
    for c in compare_sigma(&series, 1e-6 / 7.0).unwrap() {
        assert!(c.rows.iter().all(|r| r.1.is_finite()), "{}", c.output);
        assert!(c.outside.is_empty(), "{}: {}", c.output, c.verdict());
    }
    // under a speed profile: no analytic curve, a note says so
    let accelerating = text.replace(
        "speed = \"20 m/s\"",
        "speed_profile = { from = \"15 m/s\", to = \"20 m/s\", acceleration = \"2.5 m/s^2\" }",
    );
    assert_ne!(accelerating, text);
    std::fs::write(dir.join("acc.toml"), &accelerating).unwrap();
    let o = cli_within(
        &["transient", "acc.toml", "--monte-carlo", "20", "-o", "acc.h5"],
        &dir,
        limit,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("no analytic σ(t)"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
