//! Monte Carlo engine: value stability, exactness of the generators and of the discretisation, thread- and
//! shard-independence, Welch and correlation estimates against analytic values.
//!
//! Every statistical assertion is seeded (so the suite is deterministic) and states the probability that
//! it would fail for a correct implementation under a fresh seed.

use crate::common;
use common::tolerance::{EXACT, FACTORISATION, POISSON_GRID_VARIANCE, WELCH_WINDOW_BIAS};
use nalgebra::DMatrix;
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::estimate::{ensemble_correlation, time_correlation, variance_interval_known_mean, RunningMoments, Welch};
use stochvib::response::{variance_lyapunov, Excitation};
use stochvib::simulate::{
    augmented_response, run_batch, shaping_simulator, standard_normal, stream, Amplitudes, GaussMarkov, RoadTrack,
    RoadTrackGrid, Shard, SpectralGenerator,
};
use stochvib::spectrum::{Domain, ExpCosine, Exponential, Spectrum};
use stochvib::system::{OutputInfo, StateSpace};

/// Confidence of each single statistical assertion: false failure 1e-6.
const CONF: f64 = 1.0 - 1e-6;

#[test]
fn value_stability_of_streams() {
    // Regression guard, not a correctness oracle: these are the first five N(0,1) variates of realizations 0
    // and 3 of seed 42 under the documented derivation (GENERATOR: xoshiro256++ seeded by
    // splitmix64(s ⊕ splitmix64(i ⊕ 0x6a09e667f3bcc909)), rand_distr StandardNormal), recorded once by a
    // hand run. They change only if the derivation, rand's xoshiro256++ or rand_distr's ziggurat change —
    // which would silently change every stored result (the rand "value-stability" test pattern).
    let pinned: [(u64, [f64; 5]); 2] = [
        (
            0,
            [
                -0.7255888055873096,
                -0.22321567714790205,
                1.719061915438537,
                -0.732244594558439,
                -1.1850257369223869,
            ],
        ),
        (
            3,
            [
                -1.1203760532758607,
                -1.070643710002461,
                -1.145843084530373,
                0.4738853701676432,
                -0.03507401727710212,
            ],
        ),
    ];
    for (i, want) in pinned {
        let mut r = stream(42, i);
        for (k, w) in want.iter().enumerate() {
            assert_eq!(
                standard_normal(&mut r).to_bits(),
                w.to_bits(),
                "realization {i}, sample {k}"
            );
        }
    }
}

/// Values at step `k` of N independent realizations (one sample per realization, so the N values are i.i.d.
/// N(0, σ²) exactly: a stationary Gaussian start propagated by an exact recursion).
fn shaping_samples(gm: &GaussMarkov, seed: u64, n: u64, k: usize) -> Vec<f64> {
    run_batch(
        seed,
        0..n,
        || vec![0.0; (k + 1) * gm.n_outputs()],
        |buf, _, rng| {
            let mut x = vec![0.0; gm.n_states()];
            gm.initial_state(rng, &mut x);
            gm.advance(&mut x, rng, buf);
            buf[k * gm.n_outputs()]
        },
    )
    .into_results()
}

fn spectral_samples(g: &SpectralGenerator, seed: u64, n: u64, k: usize) -> Vec<f64> {
    run_batch(
        seed,
        0..n,
        || (g.scratch(), vec![0.0; g.len()]),
        |(sc, out), _, rng| {
            g.generate(rng, sc, out).unwrap();
            out[k]
        },
    )
    .into_results()
}

#[test]
fn shaping_generators_have_the_analytic_variance() {
    // N σ̂²/D ~ χ²_N exactly (i.i.d. zero-mean normal samples, one per realization); the interval fails to
    // cover D with probability 1e-6 per model. Analytic D: the type's parameter (K(0) = D).
    let t1 = Exponential::new(1.5, 2.0, Domain::Temporal).unwrap();
    let t3 = ExpCosine {
        variance: 2.0,
        alpha: 0.5,
        beta: 3.0,
        domain: Domain::Temporal,
    }
    .build()
    .unwrap();
    for (name, s, d) in [("type 1", &t1 as &dyn Spectrum, 1.5), ("type 3", &t3, 2.0)] {
        let gm = shaping_simulator(s, 0.01).unwrap();
        // the discrete model is stationary with exactly variance D (Lyapunov, to factorisation accuracy)
        assert!((gm.output_covariance()[(0, 0)] - d).abs() < FACTORISATION * d, "{name}");
        let x = shaping_samples(&gm, 11, 20_000, 200);
        let v = variance_interval_known_mean(&x, 0.0, CONF).unwrap();
        assert!(v.covers(d), "{name}: D = {d} not in [{}, {}]", v.lower, v.upper);
    }
}

#[test]
fn spectral_generator_has_the_grid_variance() {
    // Rayleigh synthesis: x_k is a sum of independent zero-mean normals, so x_k ~ N(0, D_N) exactly and the
    // χ²_N interval (one sample per realization) misses D_N with probability 1e-6 per model.
    // D_N itself is checked against its derived value: by Poisson summation the full grid sum
    // Σ_{all j} S(ω_j)Δω equals Σ_m K(mT), T = NΔt, so D_N = D + 2Σ_{m≥1} K(mT) − tail, where the tail
    // Σ_{|j|>N/2} (half weight at N/2) is the integral 2∫_{ω_N}^∞ S dω up to an Euler–Maclaurin term
    // (tolerance::POISSON_GRID_VARIANCE):
    //   type 1: tail = (2D/π)(π/2 − atan(ω_N/α));  type 3: tail = (D/π)[π − atan((ω_N−β)/α) − atan((ω_N+β)/α)]
    // (from S₃ = (D/2π)[α/(α² + (ω−β)²) + α/(α² + (ω+β)²)]).
    let dt = 0.01;
    let wn = PI / dt;
    let t1 = Exponential::new(1.5, 2.0, Domain::Temporal).unwrap();
    let t3 = ExpCosine {
        variance: 2.0,
        alpha: 0.5,
        beta: 3.0,
        domain: Domain::Temporal,
    }
    .build()
    .unwrap();
    let tail1 = 2.0 * 1.5 / PI * (PI / 2.0 - (wn / 2.0).atan());
    let tail3 = 2.0 / PI * (PI - ((wn - 3.0) / 0.5).atan() - ((wn + 3.0) / 0.5).atan());
    for (name, s, d, tail) in [
        ("type 1", &t1 as &dyn Spectrum, 1.5, tail1),
        ("type 3", &t3, 2.0, tail3),
    ] {
        let g = SpectralGenerator::new(s, dt, 2048, Amplitudes::Rayleigh).unwrap();
        let dn = g.grid_variance();
        let t = 2048.0 * dt;
        let periodic: f64 = (1..20).map(|m| 2.0 * s.correlation(m as f64 * t).unwrap()).sum();
        let want = d + periodic - tail;
        assert!(
            (dn - want).abs() < POISSON_GRID_VARIANCE * d,
            "{name}: D_N = {dn}, derived {want}"
        );
        let x = spectral_samples(&g, 12, 20_000, 100);
        let v = variance_interval_known_mean(&x, 0.0, CONF).unwrap();
        assert!(v.covers(dn), "{name}: D_N = {dn} not in [{}, {}]", v.lower, v.upper);
    }
}

/// The unit-mass oscillator with both states as outputs (x in m, ẋ in m/s).
fn sdof(w: f64, z: f64) -> StateSpace {
    let o = StateSpace::oscillator(w, z).unwrap();
    StateSpace::new(
        o.a.clone(),
        o.b.clone(),
        DMatrix::identity(2, 2),
        None,
        None,
        vec![OutputInfo::new("x", "m"), OutputInfo::new("v", "m/s")],
    )
    .unwrap()
}

#[test]
fn exact_discretisation_has_no_time_step_bias() {
    // SDOF ẍ + 2ζωẋ + ω²x = u with a type-1 input, simulated through the augmented (filter + oscillator)
    // system discretised by Van Loan at a coarse step (Δt = 0.02 s ≈ T/31).
    let ss = sdof(10.0, 0.05);
    let exc = Excitation::single(Arc::new(Exponential::new(1.0, 3.0, Domain::Temporal).unwrap()), 0.0).unwrap();
    let gm = augmented_response(&ss, &exc, &[0], 0.02).unwrap();
    // (1) discrete stationarity Φ P Φᵀ + Q_d = P: the Lyapunov covariance is exactly invariant under the
    // discrete recursion, for any Δt (identity of Van Loan's integrals), so no bias at any step.
    let (phi, qd, p) = (&gm.discretization().phi, &gm.discretization().qd, gm.state_covariance());
    let resid = phi * p * phi.transpose() + qd - p;
    assert!(resid.amax() < EXACT * p.amax(), "{resid:e}");
    // (2) the output variance equals the independent analytic Lyapunov variance of the response module
    let d = variance_lyapunov(&ss, &exc, 0).unwrap().variance;
    assert!((gm.output_covariance()[(0, 0)] - d).abs() < FACTORISATION * d);
    // (3) across-realization variance of x at step 300 (one sample per realization, i.i.d. N(0, D) exactly):
    // χ²_N interval misses D with probability 1e-6.
    let x = shaping_samples(&gm, 13, 20_000, 300);
    let v = variance_interval_known_mean(&x, 0.0, CONF).unwrap();
    assert!(v.covers(d), "D = {d:e} not in [{:e}, {:e}]", v.lower, v.upper);
}

/// Per-realization summary used by the determinism test: time mean and variance of x, Welch sums.
fn pipeline(seed: u64, range: std::ops::Range<u64>) -> Shard<(RunningMoments, stochvib::estimate::WelchSums)> {
    let ss = sdof(10.0, 0.05);
    let exc = Excitation::single(Arc::new(Exponential::new(1.0, 3.0, Domain::Temporal).unwrap()), 0.0).unwrap();
    let gm = augmented_response(&ss, &exc, &[0], 0.01).unwrap();
    let welch = Welch::new(256, 0.01).unwrap();
    run_batch(
        seed,
        range,
        || (vec![0.0; 2048], welch.scratch()),
        |(buf, ws), _, rng| {
            let mut x = vec![0.0; gm.n_states()];
            gm.initial_state(rng, &mut x);
            gm.advance(&mut x, rng, buf);
            let mut m = RunningMoments::default();
            m.extend(buf);
            let mut sums = welch.sums();
            welch.accumulate(buf, &mut sums, ws).unwrap();
            (m, sums)
        },
    )
}

fn fold(shard: &Shard<(RunningMoments, stochvib::estimate::WelchSums)>) -> (RunningMoments, Vec<f64>) {
    let mut m = RunningMoments::default();
    let mut w = Welch::new(256, 0.01).unwrap().sums();
    for (a, b) in shard.results() {
        m.merge(a);
        w.merge(b).unwrap();
    }
    (m, w.sum)
}

#[test]
fn threads_and_shards_are_bit_identical() {
    let n = 24;
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let two = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let a = fold(&one.install(|| pipeline(99, 0..n)));
    let b = fold(&two.install(|| pipeline(99, 0..n)));
    let shards = vec![
        pipeline(99, 13..24),
        pipeline(99, 0..5),
        pipeline(99, 5..6),
        pipeline(99, 6..13),
    ];
    let c = fold(&Shard::merge_all(shards).unwrap());
    for other in [&b, &c] {
        assert_eq!(a.0.count(), other.0.count());
        assert_eq!(a.0.mean().to_bits(), other.0.mean().to_bits());
        assert_eq!(a.0.variance().to_bits(), other.0.variance().to_bits());
        assert!(a.1.iter().zip(&other.1).all(|(x, y)| x.to_bits() == y.to_bits()));
    }
    // a non-adjacent merge is refused
    assert!(pipeline(99, 0..2).merge(pipeline(99, 3..4)).is_err());
}

#[test]
fn welch_covers_the_analytic_density() {
    // One long exact type-1 record (AR(1) samples, D = 1, α = 1, Δt = 0.01 s, 2²⁰ samples), M = 4096
    // (segment 40.96 s), K = 511 segments, ν ≈ 968. Five bins, each at confidence 1 − 1e-8: by the union bound
    // the nominal false-failure probability is ≤ 5e-8; the χ²_ν law is Welch's two-moment approximation, and
    // the two orders of magnitude below 1e-6 are the margin for its tail error.
    // Compared values: (i) the exact mean of the estimator, E Ŝ = window-smoothed density of the sampled
    // process, from K_d(m) = D φ^m (φ = e^{−αΔt}); (ii) the analytic S(ω) = αD/(π(α² + ω²)), which differs
    // from (i) by the window smoothing and aliasing (derived in tolerance::WELCH_WINDOW_BIAS, together ≤ 1 %)
    // — both far inside the ≈ ±25 % half-width.
    let (d, alpha, dt) = (1.0, 1.0, 0.01);
    let s = Exponential::new(d, alpha, Domain::Temporal).unwrap();
    let gm = shaping_simulator(&s, dt).unwrap();
    let mut x = vec![0.0; 1 << 20];
    gm.stream(stream(21, 0)).fill(&mut x);
    let welch = Welch::new(4096, dt).unwrap();
    let est = welch.estimate(&x).unwrap();
    assert_eq!(est.segments, 511);
    let phi = (-alpha * dt).exp();
    for j in [1usize, 3, 10, 30, 100] {
        let iv = est.interval(j, 1.0 - 1e-8).unwrap();
        let expected = welch.expected(|m| d * phi.powi(m as i32), j);
        let analytic = s.density(est.omega[j]);
        assert!(
            (expected / analytic - 1.0).abs() < WELCH_WINDOW_BIAS,
            "bin {j}: smoothing bias larger than derived"
        );
        assert!(
            iv.covers(expected),
            "bin {j}: E Ŝ = {expected:e} not in [{:e}, {:e}]",
            iv.lower,
            iv.upper
        );
        assert!(
            iv.covers(analytic),
            "bin {j}: S = {analytic:e} not in [{:e}, {:e}]",
            iv.lower,
            iv.upper
        );
    }
}

#[test]
fn correlation_estimates_match_k_of_tau() {
    // (8.11) across realizations: type 3 (D = 2, α = 0.5, β = 3) exact samples at steps 200 and 200 + m;
    // the interval is exact for Gaussian pairs (see ensemble_correlation); two lags at 1 − 5e-7 each, so
    // the false-failure probability is ≤ 1e-6. Analytic K(τ) = D e^{−α|τ|} cos βτ.
    let s = ExpCosine {
        variance: 2.0,
        alpha: 0.5,
        beta: 3.0,
        domain: Domain::Temporal,
    }
    .build()
    .unwrap();
    let dt = 0.01;
    let gm = shaping_simulator(&s, dt).unwrap();
    let lags = [10usize, 50];
    let pairs = run_batch(
        31,
        0..20_000,
        || vec![0.0; 251],
        |buf, _, rng| {
            let mut x = vec![0.0; gm.n_states()];
            gm.initial_state(rng, &mut x);
            gm.advance(&mut x, rng, buf);
            (buf[200], buf[200 + lags[0]], buf[200 + lags[1]])
        },
    )
    .into_results();
    let x0: Vec<f64> = pairs.iter().map(|p| p.0).collect();
    for (k, &m) in lags.iter().enumerate() {
        let xm: Vec<f64> = pairs.iter().map(|p| if k == 0 { p.1 } else { p.2 }).collect();
        let kt = s.correlation(m as f64 * dt).unwrap();
        let iv = ensemble_correlation(&x0, &xm, 1.0 - 5e-7).unwrap();
        assert!(iv.covers(kt), "lag {m}: K = {kt} not in [{}, {}]", iv.lower, iv.upper);
    }
    // Time average over one record of L = 2²⁰ samples (known mean 0): Bartlett's variance
    // Var K̂(m) ≈ (1/L) Σ_r [K(r)² + K(r+m)K(r−m)] from the exact discrete autocovariance; the error is a
    // sum of many weakly dependent terms, so |K̂ − K| ≤ 6 sd is the Gaussian approximation (≈ 2e-9 nominal).
    let mut rec = vec![0.0; 1 << 20];
    gm.stream(stream(32, 0)).fill(&mut rec);
    let khat = time_correlation(&rec, 50, Some(0.0)).unwrap();
    let kd = |r: i64| s.correlation(r as f64 * dt).unwrap();
    for m in [0i64, 10, 50] {
        let var: f64 = (-3000i64..=3000)
            .map(|r| kd(r) * kd(r) + kd(r + m) * kd(r - m))
            .sum::<f64>()
            / rec.len() as f64;
        let err = khat[m as usize] - kd(m);
        assert!(
            err.abs() < 6.0 * var.sqrt(),
            "lag {m}: K̂ = {}, K = {}, sd = {}",
            khat[m as usize],
            kd(m),
            var.sqrt()
        );
    }
}

#[test]
fn road_track_wheels_see_delayed_copies() {
    // Spectral profile of the textbook road (8.45) at 10 m/s, Δt = 0.005 s (Δx = 5 cm), axle base 2.5 m =
    // 50 samples: the rear wheel's input is the front wheel's input 50 samples earlier (circularly), exactly.
    let q = Exponential::new(2.25e-4, 3.5, Domain::Spatial).unwrap();
    let grid = |offsets: &'static [f64]| RoadTrackGrid {
        speed: 10.0,
        dt: 0.005,
        n: 1024,
        offsets,
    };
    let road = RoadTrack::spectral(&q, grid(&[0.0, 2.5]), Amplitudes::Rayleigh).unwrap();
    let mut sc = road.scratch();
    let mut u = vec![0.0; 2 * 1024];
    road.generate(&mut stream(5, 0), &mut sc, &mut u).unwrap();
    for k in 0..1024 {
        assert_eq!(u[2 * k + 1], u[2 * ((k + 1024 - 50) % 1024)]);
    }
    // offsets off the grid are refused with the reason
    let e = RoadTrack::spectral(&q, grid(&[0.0, 2.51]), Amplitudes::Rayleigh).unwrap_err();
    assert!(e.to_string().contains("integer multiple"), "{e}");
    // a temporal spectrum is refused
    let t = Exponential::new(1.0, 1.0, Domain::Temporal).unwrap();
    assert!(RoadTrack::shaping(&t, RoadTrackGrid { n: 10, ..grid(&[0.0]) }).is_err());
}

#[test]
fn white_noise_component_is_rejected() {
    // S = 1 + 1/(1 + ω²) tends to a constant: a white component, samples not meaningful.
    let r = stochvib::spectrum::RationalSpectrum::new(vec![2.0, 1.0], vec![1.0, 1.0], Domain::Temporal).unwrap();
    assert!(shaping_simulator(&r, 0.01).is_err());
}
