//! Monte Carlo of two correlated tracks (spectral synthesis with the Cholesky factor of the coherence
//! matrix in the gains) against the analytic values, and the cross-spectrum / coherence estimators with
//! their intervals.

use crate::common;
use common::tolerance::SPECTRAL_GRID_BIAS;
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::coherence::{ConstantCoherence, TwoTracks};
use stochvib::estimate::cross_spectrum;
use stochvib::response::Excitation;
use stochvib::simulate::{run, source_signals, standard_normal, stream, RunInput, RunOptions};
use stochvib::spectrum::{Domain, Exponential, Spectrum};

use common::two_wheel_body::{body, V};

#[test]
fn roll_and_bounce_of_two_coherent_tracks_by_monte_carlo() {
    // Closed forms (derived in `common::two_wheel_body::closed_form_variances`): bounce is driven by
    // (L + R)/2 with density S(1 + ρ)/2, roll by (L − R)/2 with S(1 − ρ)/2; each a single-input transfer
    // function whose exact Lyapunov variance is the analytic value. A synthesis that got the cross-spectrum wrong (phase
    // mixing, or no √(1 − ρ²) term) would move the roll variance by a factor of order one.
    let rho = 0.4;
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(1e-4, 0.2, Domain::Spatial).unwrap());
    let tracks = Arc::new(TwoTracks::new(road, Arc::new(ConstantCoherence::new(rho).unwrap()), V).unwrap());
    let exc = Excitation::two_tracks(tracks, &[(0, 0.0), (1, 0.0)]).unwrap();
    let sys = body();
    let (zb, zr) = common::two_wheel_body::closed_form_variances(rho);
    let closed = [zb, zr];
    let input = RunInput::new(
        &sys,
        &exc,
        vec![0, 1],
        source_signals(&exc, "m"),
        "two tracks, MC check",
    );
    let mut opts = RunOptions {
        realizations: 40,
        duration_s: 200.0,
        dt_s: 0.01,
        seed: 20240517,
        ..RunOptions::default()
    };
    // two outputs, each interval at 1 − 5e-7: false failure ≤ 1e-6 (Bonferroni; Student-t across 40
    // independent realizations of a time average over 200 s ≫ the 0.3 s correlation time, so near-normal)
    opts.confidence = 1.0 - 5e-7;
    let file = crate::common::scratch_kept("two-tracks-mc", "run").join("run.h5");
    let _ = std::fs::remove_file(&file);
    let mc = run(&input, &opts, &file, &|_, _| {}).unwrap();
    std::fs::remove_file(&file).unwrap();
    assert!(mc.notes.iter().any(|n| n.contains("spectral route")), "{:?}", mc.notes);
    for (o, oracle) in mc.outputs.iter().zip(closed) {
        let s = o.get("sigma_discrete").unwrap();
        // the synthesis is exact in expectation for the simulated (grid) process
        assert!(
            s.covers == Some(true),
            "{}: σ_d = {:e} not in [{:e}, {:e}]",
            o.output,
            s.analytic.unwrap(),
            s.interval.lower,
            s.interval.upper
        );
        // the grid process differs from the continuous one by the FFT grid's sampling of the spectrum
        let vd = s.analytic.unwrap().powi(2);
        assert!(
            (vd - oracle).abs() <= SPECTRAL_GRID_BIAS * oracle,
            "{}: {vd:e} vs {oracle:e}",
            o.output
        );
    }
}

#[test]
fn coherence_and_co_spectrum_intervals_cover_the_true_values() {
    // x = e_k (white, unit variance), y_k = e_{k−2} + n_k (n independent, unit variance), Δt = 0.01 s.
    // Exact: S_xx = Δt/2π, S_yy = 2Δt/2π, S_xy(ω) = (Δt/2π) e^{+2iωΔt} (R_xy(τ) = E[x(t+τ)y(t)] = δ at
    // τ = −2Δt), γ² = 1/2 at every ω, Re S_xy = (Δt/2π) cos 2ωΔt. The Hann window attenuates the
    // 2-sample shift by Σw_k w_{k+2}/Σw_k² ≈ 1 − 3e-4 (M = 256): negligible against the intervals.
    // 127 interior bins, two intervals each at 1 − 1e-6/254: false failure ≤ 1e-6 (Bonferroni).
    let (m, nd, dt) = (256usize, 64usize, 0.01);
    let n = m * nd + 2;
    let mut rng = stream(77, 0);
    let e: Vec<f64> = (0..n).map(|_| standard_normal(&mut rng)).collect();
    let x: Vec<f64> = e[2..].to_vec();
    let y: Vec<f64> = (0..n - 2).map(|k| e[k] + standard_normal(&mut rng)).collect();
    let c = cross_spectrum(&x, &y, m, dt).unwrap();
    assert_eq!(c.segments, nd);
    let conf = 1.0 - 1e-6 / 254.0;
    for j in 1..m / 2 {
        let w = c.omega[j];
        let g = c.coherence_interval(j, conf).unwrap();
        assert!(g.covers(0.5), "bin {j}: γ² = 0.5 not in [{}, {}]", g.lower, g.upper);
        let co = c.co_spectrum_interval(j, conf).unwrap();
        let exact = dt / (2.0 * PI) * (2.0 * w * dt).cos();
        assert!(
            co.covers(exact),
            "bin {j}: C = {exact:e} not in [{:e}, {:e}]",
            co.lower,
            co.upper
        );
    }
}
