//! Monte Carlo of non-stationary responses against closed forms: the ensemble σ(t) of an oscillator started
//! from rest (Caughey & Stumpf) at every stored time, the per-realization maxima against Rice's bound, and
//! a run split into cluster parts and merged against the single-process run, bit for bit.

use crate::common;
use crate::common::tolerance::EXACT_TRANSITIONS;
use crate::transient_exact::{oscillator, system};
use std::f64::consts::PI;
use stochvib::extremes::Barrier;
use stochvib::models::quarter_car::QuarterCar;
use stochvib::spectrum::{IsoBound, IsoClass, PowerLaw};
use stochvib::store::{Compression, Part};
use stochvib::study::merge_transient;
use stochvib::system::FrequencyResponse;
use stochvib::transient::monte_carlo::read_transient_run;
use stochvib::transient::{
    input_model, run_transient, solve, Envelope, ExactOptions, InputModel, McGrid, McGridSpec, Start,
    TimeVaryingSystem, TransientRunInput, TransientRunOptions,
};

const W0: f64 = 2.0 * PI;
const ZETA: f64 = 0.05;
const S0: f64 = 1.0;

fn oscillator_system() -> TimeVaryingSystem {
    system(
        oscillator(W0, ZETA),
        InputModel::White { density: S0 },
        Envelope::unit(),
    )
}

/// Caughey & Stumpf (1961) σ_x²(t) of the oscillator from rest (see `transient_exact`), written out here.
fn caughey_stumpf_var(t: f64) -> f64 {
    let wd = W0 * (1.0 - ZETA * ZETA).sqrt();
    let a = ZETA * W0 / wd;
    let e = (-2.0 * ZETA * W0 * t).exp();
    PI * S0 / (2.0 * ZETA * W0.powi(3))
        * (1.0 - e * (1.0 + a * (2.0 * wd * t).sin() + 2.0 * a * a * (wd * t).sin().powi(2)))
}

/// A fresh path for `name` in this process's scratch directory (earlier files of the name removed).
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = crate::common::scratch_path("transient-mc", name);
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    let _ = std::fs::remove_file(&p);
    let _ = std::fs::remove_file(stochvib::store::tmp_path(&p));
    p
}

fn options(realizations: usize, grid: McGrid, part: Option<Part>) -> TransientRunOptions {
    TransientRunOptions {
        realizations,
        grid,
        seed: 20261127,
        shard_size: 2500,
        confidence: 0.95,
        store_raw: false,
        compression: Compression::None,
        part,
        overwrite: false,
        max_hours: stochvib::simulate::resources::DEFAULT_MAX_HOURS,
    }
}

fn run(
    sys: &TimeVaryingSystem,
    grid: McGrid,
    realizations: usize,
    part: Option<Part>,
    out: &std::path::Path,
) -> stochvib::transient::TransientRunSummary {
    run_from(sys, (Start::Rest, vec![0]), grid, realizations, part, out)
}

fn run_from(
    sys: &TimeVaryingSystem,
    (start, outputs): (Start, Vec<usize>),
    grid: McGrid,
    realizations: usize,
    part: Option<Part>,
    out: &std::path::Path,
) -> stochvib::transient::TransientRunSummary {
    let times = grid.stored_times();
    let exact = solve(sys, &start, &times, &ExactOptions::default()).unwrap();
    let input = TransientRunInput {
        sys,
        outputs,
        start,
        exact: &exact,
        stationary: false,
        scenario_text: "oscillator from rest under white noise (test)".into(),
        provenance: vec![],
    };
    run_transient(&input, &options(realizations, grid, part), out, &|_, _| {}).unwrap()
}

/// The grid of the oscillator runs: 2.5 s in steps of 0.01 s, every 5th step stored (51 times).
fn two_and_a_half_seconds() -> McGrid {
    McGridSpec {
        duration_s: 2.5,
        dt_s: 0.01,
        store_every: 5,
    }
    .build()
    .unwrap()
}

/// The ensemble variance at every stored time against σ_x²(t) of Caughey & Stumpf. The steps are the exact
/// transitions of the oscillator (Van Loan), so each state is exactly Gaussian and (R − 1)s²/σ² ~ χ²_{R−1}.
/// With N = R − 1 and x = ln(2K/p) for K = 50 stored times after t = 0, the Laurent–Massart bounds
/// P(χ² − N ≥ 2√(Nx) + 2x) ≤ e^{−x} and P(N − χ² ≥ 2√(Nx)) ≤ e^{−x} and the union over the K times give a
/// false-failure probability ≤ p = 0.9·10⁻⁶. The means: |m̂| ≤ zσ/√R with z = 6.0 (two-sided normal tail
/// 2.0e-9 per time, ≤ 10⁻⁷ over the K times; the mean is exactly N(0, σ²/R)): ≤ 10⁻⁶ in all. t = 0 is
/// exactly 0 (from rest).
#[test]
fn ensemble_variance_from_rest_against_caughey_stumpf() {
    let _serial = common::hdf5_serial();
    let grid = two_and_a_half_seconds();
    let r = 20_000usize;
    let s = run(&oscillator_system(), grid, r, None, &scratch("cs.h5"));
    assert_eq!(s.n_realizations, r);
    let (_, series) = read_transient_run(&s.path).unwrap();
    let o = &series.outputs[0];
    assert_eq!(o.sigma[0], 0.0);
    let closed: Vec<f64> = series.times.iter().map(|&t| caughey_stumpf_var(t).sqrt()).collect();
    assert_sigma_chi2(&o.sigma, &closed, r, 0.9e-6, "x");
    for (j, &t) in series.times.iter().enumerate().skip(1) {
        assert!(
            o.mean[j].abs() <= 6.0 * closed[j] / (r as f64).sqrt(),
            "t = {t}: mean {}",
            o.mean[j]
        );
        assert!((o.exact_sigma[j] / closed[j] - 1.0).abs() < EXACT_TRANSITIONS);
    }
}

/// (R − 1)s²/σ² ~ χ²_{R−1} at every stored time after the first: the Laurent–Massart bounds with
/// x = ln(2K/p) and a union over the K times keep the false-failure probability of all checks ≤ p.
fn assert_sigma_chi2(sigma: &[f64], exact: &[f64], r: usize, p: f64, what: &str) {
    let k = (sigma.len() - 1) as f64;
    let n = (r - 1) as f64;
    let x = (2.0 * k / p).ln();
    for j in 1..sigma.len() {
        let chi = n * (sigma[j] / exact[j]).powi(2);
        assert!(
            chi - n <= 2.0 * (n * x).sqrt() + 2.0 * x,
            "{what} [{j}]: s = {} vs σ = {}",
            sigma[j],
            exact[j]
        );
        assert!(
            n - chi <= 2.0 * (n * x).sqrt(),
            "{what} [{j}]: s = {} vs σ = {}",
            sigma[j],
            exact[j]
        );
    }
}

/// The quarter car of `transient_exact::quarter_car_accelerating_on_a_w2_road` (5 → 15 m/s in 10 s on an
/// ISO class D road of waviness 2, started in its stationary state at 5 m/s) by Monte Carlo against the
/// exact route (itself checked there against closed forms and an independent ODE solution): the ensemble σ
/// of the body acceleration and the suspension travel at every stored time (χ² bounds as in
/// [`ensemble_variance_from_rest_against_caughey_stumpf`], false-failure probability ≤ 10⁻⁶ for both
/// outputs together). The steps freeze v at their midpoints; with v linear in t the frozen noise intensity
/// equals the step's mean, and the remaining second-order error (≈ (Δt)²|F|·v̇/v ≈ 10⁻⁵ relative here) is far
/// below the ±6 % the sampling allows.
#[test]
fn quarter_car_accelerating_by_monte_carlo() {
    let _serial = common::hdf5_serial();
    // the passenger-car corner with a 400 kg body
    let car = QuarterCar {
        sprung_mass: 400.0,
        ..common::passenger_quarter_car()
    }
    .build()
    .unwrap();
    let mdof = car.system().unwrap();
    let road = PowerLaw::iso8608(IsoClass::D, IsoBound::GeometricMean, None).unwrap();
    let v = common::accelerating_5_to_15();
    let sys = system(
        mdof.state_space().unwrap().clone(),
        input_model(&road, Some(&v)).unwrap(),
        Envelope::unit(),
    );
    let outputs = vec![
        mdof.output_index("body_acc").unwrap(),
        mdof.output_index("travel").unwrap(),
    ];
    let grid = McGridSpec {
        duration_s: 12.0,
        dt_s: 0.005,
        store_every: 40,
    }
    .build()
    .unwrap();
    let r = 20_000usize;
    let s = run_from(&sys, (Start::Stationary, outputs), grid, r, None, &scratch("qc.h5"));
    let (_, series) = read_transient_run(&s.path).unwrap();
    for o in &series.outputs {
        assert_sigma_chi2(&o.sigma, &o.exact_sigma, r, 0.5e-6, &o.output);
    }
}

/// Rice's inequality P(max_{[0,T]} y > b) ≤ P(y(0) > b) + E N⁺(b) (the first passage needs an up-crossing
/// when y(0) < b), and a sampled maximum never exceeds the continuous one: from rest (y(0) = 0 < b) the Monte
/// Carlo fraction p̂ of realizations with max y > b must stay below ∫₀ᵀν⁺(b, t)dt from the exact route up to
/// the sampling error. Hoeffding: P(p̂ − p ≥ ε) ≤ e^{−2Rε²}, ε = √(ln 10⁶/(2R)) makes the false-failure
/// probability ≤ 10⁻⁶ per level, two levels. The same holds for |y| with the two-sided rate. For
/// contrast the fraction must exceed P(y(T) > b) (a single time, a lower bound) by the same ε.
#[test]
fn maxima_below_the_integrated_rice_rate() {
    let _serial = common::hdf5_serial();
    let grid = two_and_a_half_seconds();
    let r = 20_000usize;
    let sys = oscillator_system();
    let s = run(&sys, grid, r, None, &scratch("max.h5"));
    let (_, series) = read_transient_run(&s.path).unwrap();
    let o = &series.outputs[0];
    let exact = solve(&sys, &Start::Rest, &series.times, &ExactOptions::default()).unwrap();
    let eps = ((1e6f64).ln() / (2.0 * r as f64)).sqrt();
    let sigma_end = caughey_stumpf_var(2.5).sqrt();
    for b in [2.0 * sigma_end, 2.5 * sigma_end] {
        for (barrier, maxima) in [(Barrier::OneSided, &o.max_y), (Barrier::TwoSided, &o.max_abs_y)] {
            let p_hat = maxima.iter().filter(|m| **m > b).count() as f64 / r as f64;
            let bound = exact.expected_crossings(0, b, barrier).expected;
            assert!(p_hat <= bound + eps, "{barrier:?} b = {b}: p̂ = {p_hat} > E N = {bound}");
            let single = barrier.crossings_per_cycle() * 0.5 * statrs::function::erf::erfc(b / sigma_end / 2f64.sqrt());
            assert!(
                p_hat >= single - eps,
                "{barrier:?} b = {b}: p̂ = {p_hat} < P(y(T) > b) = {single}"
            );
        }
    }
}

/// A run split into two cluster parts and merged gives the statistics of the single-process run bit for bit
/// (same streams per realization, the same fold of the shards in order).
#[test]
fn parts_merge_bit_identically() {
    let _serial = common::hdf5_serial();
    let grid = McGridSpec {
        duration_s: 1.0,
        dt_s: 0.01,
        store_every: 10,
    }
    .build()
    .unwrap();
    let sys = oscillator_system();
    let whole = run(&sys, grid, 5000, None, &scratch("whole.h5"));
    let parts: Vec<_> = (0..2)
        .map(|i| {
            let p = Part::new(i, 2).unwrap();
            run(&sys, grid, 5000, Some(p), &scratch(&format!("part{i}.h5"))).path
        })
        .collect();
    let merged = merge_transient(
        &scratch("merged.h5"),
        &parts,
        &stochvib::study::MergeOptions::default(),
        &|_, _| {},
    )
    .unwrap();
    let (_, a) = read_transient_run(&whole.path).unwrap();
    let (_, b) = read_transient_run(&merged.path).unwrap();
    let bits = |v: &Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (x, y) in a.outputs[0].arrays().into_iter().zip(b.outputs[0].arrays()) {
        assert_eq!(bits(x), bits(y));
    }
    assert_eq!(bits(&a.outputs[0].max_abs_y), bits(&b.outputs[0].max_abs_y));
    assert_eq!(
        common::stored_statistic_bits(&whole.outputs),
        common::stored_statistic_bits(&merged.outputs)
    );
}
