//! Monte Carlo of a vehicle under a speed profile on roads synthesised on a spatial grid and sampled along
//! x(t), against the exact route (differential Lyapunov equation) on a rational road where both apply, and
//! against the evolutionary route on a band-limited ISO road.

use std::sync::Arc;
use stochvib::estimate::chi_squared_quantile;
use stochvib::spectrum::{IsoBound, IsoClass, PowerLaw, Spectrum};
use stochvib::system::FrequencyResponse;
use stochvib::transient::{
    input_model, road_grid_monte_carlo, solve_evolutionary, ConstantAcceleration, Envelope, EvolutionaryInput,
    FixedSystem, RoadGridOptions, SpeedProfile, Start,
};

/// A quarter car (m_s = 300, m_u = 40 kg, k_s = 20 kN/m, c_s = 1.5 kN s/m, k_t = 200 kN/m) accelerating at
/// 0.5 m/s² from 5 to 15 m/s (from t = 2 s) on the textbook's graded dirt road (Sukharev (2012) (8.69):
/// spatial type 1, D = 32 cm², α = 0.16 1/m), started in its stationary state. The exact route (the road's
/// spatial filter under v(t), `solve`) gives σ²(t); 1000 realizations of the road on a grid of Δx = 2 cm,
/// sampled along x(t), give the ensemble variance s²(t) at 61 times. For Gaussian responses
/// (R − 1)s²/σ² ~ χ²_{R−1}: the two-sided bounds at α = 10⁻⁶ split over the 122 (output, time) pairs
/// (Bonferroni) fail with probability ≤ 10⁻⁶ when both routes are right. The grid's own biases — the band
/// |Ω| ≤ π/Δx (the body's outputs lose below 10⁻⁵ of their variance) and the linear interpolation (≈
/// (ΩΔx)²/6 at the body mode, 10⁻⁴) — are far inside the bounds (about ±30 % at R = 1000).
#[test]
fn quarter_car_accelerating_on_a_grid_road_against_the_exact_route() {
    let times: Vec<f64> = (0..=60).map(|k| k as f64 * 0.5).collect();
    let crate::transient_exact::DirtRoadCar {
        mdof,
        ss,
        road,
        speed: v,
        exact,
    } = crate::transient_exact::dirt_road_car(0.5, &times);
    let opts = RoadGridOptions {
        dx: 0.02,
        substeps: 400,
        realizations: 1000,
        seed: 31,
    };
    let mc = road_grid_monte_carlo(&ss, road.as_ref(), &v, &times, &opts).unwrap();
    let r = opts.realizations as f64;
    let pairs = 2.0 * times.len() as f64;
    let a = 1e-6 / pairs;
    let (lo, hi) = (
        chi_squared_quantile(r - 1.0, a / 2.0).unwrap() / (r - 1.0),
        chi_squared_quantile(r - 1.0, 1.0 - a / 2.0).unwrap() / (r - 1.0),
    );
    for name in ["travel", "body_acc"] {
        let i = mdof.output_index(name).unwrap();
        for (k, t) in times.iter().enumerate() {
            let ratio = mc.variance[i][k] / exact.outputs[i].sigma[k].powi(2);
            assert!(
                lo <= ratio && ratio <= hi,
                "{name} at {t} s: s²/σ² = {ratio} outside [{lo}, {hi}]"
            );
        }
    }
    assert!(mc.run_in > 0.0);
}

/// An ISO 8608 power law without its band has no finite density at Ω = 0 on the grid: refused, naming the
/// density; a standing start (v(0) = 0) has no run-in: refused.
#[test]
fn grid_road_refusals() {
    let car = crate::common::passenger_quarter_car();
    let ss = car.system().unwrap().state_space().unwrap().clone();
    let times: Vec<f64> = (0..=4).map(|k| k as f64 * 0.5).collect();
    let opts = RoadGridOptions {
        dx: 0.05,
        substeps: 10,
        realizations: 4,
        seed: 1,
    };
    let v = SpeedProfile::constant(10.0).unwrap();
    let unbounded = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, None).unwrap();
    let e = road_grid_monte_carlo(&ss, &unbounded, &v, &times, &opts)
        .unwrap_err()
        .to_string();
    assert!(e.contains("band"), "{e}");
    let banded = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some((0.011, 2.83))).unwrap();
    let stop = SpeedProfile::table(vec![0.0, 2.0], vec![0.0, 10.0]).unwrap();
    let e = road_grid_monte_carlo(&ss, &banded, &stop, &times, &opts)
        .unwrap_err()
        .to_string();
    assert!(e.contains("v(0) > 0"), "{e}");
    assert!(road_grid_monte_carlo(&ss, &banded, &v, &times, &opts).is_ok());
}

/// The evolutionary route on a road without an exact route (ISO 8608 class C with its band 0.011–2.83
/// cycles/m) against Monte Carlo on grid roads: the quarter car of the test above accelerating slowly
/// (0.25 m/s² from 10 to 15 m/s, from t = 2 s), started stationary. Where the route reports Σ(t) with lag
/// estimate δ(t), the true variance lies in [Σ(1 − δ), Σ(1 + δ)] (δ bounds the error in the tests against
/// the exact route and Priestley's exact variance); 1000 grid roads (Δx = 2 cm, the band lies far inside
/// π/Δx) give s²(t), and (R − 1)s²/P ~ χ²_{R−1}: the bounds at α = 10⁻⁶ split over the 122 (output, time)
/// pairs, widened by δ, fail with probability ≤ 10⁻⁶.
#[test]
fn evolutionary_route_on_a_band_limited_road_against_grid_monte_carlo() {
    let car = crate::common::passenger_quarter_car();
    let mdof = car.system().unwrap();
    let ss = mdof.state_space().unwrap().clone();
    let road: Arc<dyn Spectrum> =
        Arc::new(PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some((0.011, 2.83))).unwrap());
    assert!(input_model(road.as_ref(), Some(&SpeedProfile::constant(10.0).unwrap())).is_err());
    let v = ConstantAcceleration {
        from_m_s: 10.0,
        to_m_s: 15.0,
        acceleration_m_s2: 0.25,
        start_s: 2.0,
    }
    .build()
    .unwrap();
    let times: Vec<f64> = (0..=60).map(|k| k as f64 * 0.5).collect();
    let fam = FixedSystem::new(ss.clone(), None, "quarter car").unwrap();
    let input = EvolutionaryInput {
        spectrum: road.clone(),
        speed: Some(v.clone()),
        envelope: Envelope::unit(),
        mean: 0.0,
        gains: vec![1.0],
    };
    let evo = solve_evolutionary(&fam, &input, &Start::Stationary, &times, 0.05).unwrap();
    let opts = RoadGridOptions {
        dx: 0.02,
        substeps: 400,
        realizations: 1000,
        seed: 47,
    };
    let mc = road_grid_monte_carlo(&ss, road.as_ref(), &v, &times, &opts).unwrap();
    let r = opts.realizations as f64;
    let a = 1e-6 / (2.0 * times.len() as f64);
    let (lo, hi) = (
        chi_squared_quantile(r - 1.0, a / 2.0).unwrap() / (r - 1.0),
        chi_squared_quantile(r - 1.0, 1.0 - a / 2.0).unwrap() / (r - 1.0),
    );
    for name in ["travel", "body_acc"] {
        let i = mdof.output_index(name).unwrap();
        for (k, t) in times.iter().enumerate() {
            let sigma2 = evo.solution.outputs[i].sigma[k].powi(2);
            let delta = evo.error_estimate[i][k];
            assert!(sigma2.is_finite() && delta <= 0.05, "{name} at {t} s: δ = {delta}");
            let ratio = mc.variance[i][k] / sigma2;
            assert!(
                lo * (1.0 - delta) <= ratio && ratio <= hi * (1.0 + delta),
                "{name} at {t} s: s²/Σ = {ratio} outside [{lo}, {hi}] widened by δ = {delta}"
            );
        }
    }
}

/// The quarter car (`common::quarter_car_scenario`) accelerating at 1 m/s² from 5 to 15 m/s (from t = 1 s)
/// on `road`, started in its stationary state, 8 s reported every 0.1 s.
fn accelerating_on(road: &str) -> String {
    crate::common::quarter_car_scenario()
        .title("quarter car accelerating on a grid road")
        .outputs(&["body_acc", "travel"])
        .then(&format!(
            "[input]\nspectrum = {road}\n[input.speed_profile]\nfrom = \"5 m/s\"\nto = \"15 m/s\"\n\
             acceleration = \"1 m/s^2\"\nstart = \"1 s\"\n[analysis]\noutputs = [\"body_acc\", \"travel\"]\n\
             [transient]\nduration = \"8 s\"\nstep = \"0.1 s\"\nstart = \"stationary\"\n"
        ))
        .text()
}

/// `stochvib transient --monte-carlo 200 --road-grid` on a rational road (spatial exponential correlation,
/// D = 32 cm², α = 0.16 1/m), where the exact route (the road's filter under v(t)) also applies: the run
/// file's ensemble σ(t) of both outputs lies inside the simultaneous χ² band of `compare_sigma` at every one
/// of the 81 times. For the Gaussian response (R − 1)s²/σ² ~ χ²_{R−1}; α = 5·10⁻⁷ per output, so a false
/// failure has probability ≤ 10⁻⁶ when both routes are right. The grid's biases at the default step
/// (ΩΔx ≤ 0.1 at the fastest mode: ≤ 0.2 % of the variance) are far inside the band (about ±40 % at
/// R = 200). Two shards merged by `stochvib merge` give the single run's statistics bit for bit, and
/// `plot` draws σ(t). On an ISO 8608 road with its band edges (no exact route) the command takes the road
/// grid by itself and compares with the evolutionary route.
#[test]
fn transient_command_runs_the_road_grid_against_the_exact_route() {
    use crate::common::{cli_within, scratch_dir};
    use stochvib::study::transient_mc::compare_sigma;
    use stochvib::transient::monte_carlo::read_transient_run;
    let dir = scratch_dir("transient-road-grid", "cli");
    let text =
        accelerating_on(r#"{ kind = "exponential", domain = "spatial", variance = "32 cm^2", alpha = "0.16 1/m" }"#);
    std::fs::write(dir.join("road.toml"), text).unwrap();
    let limit = std::time::Duration::from_secs(900);
    let run = |extra: &[&str]| {
        let mut args = vec![
            "transient",
            "road.toml",
            "--monte-carlo",
            "200",
            "--road-grid",
            "--seed",
            "3",
        ];
        args.extend_from_slice(extra);
        let o = cli_within(&args, &dir, limit);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let out = run(&["-o", "one.h5"]);
    assert!(out.contains("Monte Carlo σ(t) of travel"), "{out}");
    // the analytic column is labelled by the route that produced it
    assert!(out.contains("exact σ") && !out.contains("evolutionary σ"), "{out}");
    let (file, series) = read_transient_run(&dir.join("one.h5")).unwrap();
    assert!(
        file.metadata().generator.contains("spatial grid"),
        "{}",
        file.metadata().generator
    );
    assert_eq!(series.times.len(), 81);
    for c in compare_sigma(&series, 5e-7).unwrap() {
        assert!(c.outside.is_empty(), "{}: {}", c.output, c.verdict());
    }
    run(&["--shard", "0", "--of", "2", "-o", "parts"]);
    run(&["--shard", "1", "--of", "2", "-o", "parts"]);
    let m = cli_within(&["merge", "merged.h5", "parts"], &dir, limit);
    assert!(m.status.success(), "{}", String::from_utf8_lossy(&m.stderr));
    let merged = read_transient_run(&dir.join("merged.h5")).unwrap().1;
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (a, b) in series.outputs.iter().zip(&merged.outputs) {
        assert_eq!(bits(&a.sigma), bits(&b.sigma), "{}", a.output);
        assert_eq!(bits(&a.max_abs_y), bits(&b.max_abs_y), "{}", a.output);
    }
    let p = cli_within(&["plot", "one.h5", "-o", "pictures"], &dir, limit);
    assert!(p.status.success(), "{}", String::from_utf8_lossy(&p.stderr));
    assert!(dir.join("pictures/travel-sigma.svg").is_file());
    let iso = accelerating_on(r#""iso8608-c""#);
    std::fs::write(dir.join("iso.toml"), iso).unwrap();
    let o = cli_within(
        &["transient", "iso.toml", "--monte-carlo", "20", "-o", "iso.h5"],
        &dir,
        limit,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let iso_out = String::from_utf8_lossy(&o.stdout);
    assert!(
        iso_out.contains("evolutionary σ") && !iso_out.contains("exact σ"),
        "{iso_out}"
    );
    let generator = read_transient_run(&dir.join("iso.h5"))
        .unwrap()
        .0
        .metadata()
        .generator
        .clone();
    assert!(generator.contains("spatial grid"), "{generator}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The default road step of the catalogue's accelerating quarter car (`data/quarter-car-accelerating.toml`,
/// 5 → 20 m/s, with a comfort axis on `body_acc`) follows the rule Δx = 0.1·v_ref/ω_max with v_ref = 5 m/s
/// and ω_max the largest |λ| of the quarter car's own A = [[0, I], [−M⁻¹K, −M⁻¹C]] (M = diag(300, 40) kg,
/// K = [[20, −20], [−20, 220]] kN/m, C = [[1.5, −1.5], [−1.5, 1.5]] kN s/m, assembled here by hand; the wheel
/// hop at about 75 rad/s), not the ISO 2631-1 weighting filter's band-limit poles (hundreds of rad/s, a step
/// under 1 mm). On a road band-limited below ω_max/v_ref (an ISO road to 0.5 cycles/m, Ω_hi = π rad/m) the
/// step is 0.1/Ω_hi.
#[test]
fn default_road_step_from_the_model_poles_and_the_road_band() {
    use nalgebra::DMatrix;
    use stochvib::study::transient_mc::default_road_step;
    use stochvib::study::transient_run::road_grid_setup;
    let path = crate::common::root().join("data/quarter-car-accelerating.toml");
    let sc = stochvib::scenario::load_scenario(&path, &crate::common::root().join("spectra")).unwrap();
    let setup = road_grid_setup(&sc).unwrap();
    assert!(setup.ss.a.nrows() > 4, "the comfort filter's states are appended");
    let (ms, mu) = (300.0, 40.0);
    let (ks, cs, kt) = (20e3, 1.5e3, 200e3);
    let mut a = DMatrix::zeros(4, 4);
    a[(0, 2)] = 1.0;
    a[(1, 3)] = 1.0;
    let (k, c) = ([[ks, -ks], [-ks, ks + kt]], [[cs, -cs], [-cs, cs]]);
    for (i, m) in [ms, mu].iter().enumerate() {
        for j in 0..2 {
            a[(2 + i, j)] = -k[i][j] / m;
            a[(2 + i, 2 + j)] = -c[i][j] / m;
        }
    }
    let w_max = a.complex_eigenvalues().iter().map(|l| l.norm()).fold(0.0, f64::max);
    assert!((70.0..80.0).contains(&w_max), "{w_max}");
    let expected = 0.1 * 5.0 / w_max;
    let dx = default_road_step(&setup);
    assert!((dx / expected - 1.0).abs() < 1e-9, "{dx} vs {expected}");
    let banded = stochvib::study::transient_run::RoadGridSetup {
        band_edge: std::f64::consts::PI,
        ..setup
    };
    assert!((default_road_step(&banded) - 0.1 / std::f64::consts::PI).abs() < 1e-15);
}
