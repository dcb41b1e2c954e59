//! The fast evaluation paths agree with the plain dense references.
//!
//! * `response::OutputDensity` (modal partial fractions, or a Hessenberg solve for nearly defective A, or
//!   the system's own response without a state space) against `response::output_density` (a dense complex
//!   LU solve of (iωI − A) X = B per ω), on random stable systems with several inputs, D ≠ 0, E ≠ 0,
//!   delays and independent inputs.
//!
//! Provenance of the expected values: the dense solve is an independent method (a different factorisation
//! of the same H(iω) = C(iωI − A)⁻¹B + D + iωE); the closed forms are derived in the comments.

use crate::common;
use common::response_only::ResponseOnly;
use common::tolerance::{FACTORISATION, SIMD_DENSITY, TABULATED_DENSITY};
use nalgebra::DMatrix;
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::response::{output_density, Excitation, OutputDensity};
use stochvib::spectrum::{Domain, ExpCosine, Exponential, GaussCosineParameters, Spectrum};
use stochvib::system::{FrequencyResponse, OutputInfo, StateSpace};

/// SplitMix64: a small deterministic generator (no statistical claims are made from it; it only picks
/// test systems).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
    fn matrix(&mut self, r: usize, c: usize) -> DMatrix<f64> {
        DMatrix::from_fn(r, c, |_, _| self.next())
    }
}

/// A random stable state-space system: A = R − (max Re λ(R) + margin) I, so every eigenvalue has real
/// part ≤ −margin.
fn random_system(rng: &mut Rng, n: usize, m: usize, p: usize) -> StateSpace {
    let mut a = rng.matrix(n, n) * 3.0;
    let abscissa = a
        .complex_eigenvalues()
        .iter()
        .map(|l| l.re)
        .fold(f64::NEG_INFINITY, f64::max);
    let margin = 0.05 + 0.5 * (rng.next() + 1.0);
    for k in 0..n {
        a[(k, k)] -= abscissa + margin;
    }
    let outputs = (0..p).map(|k| OutputInfo::new(format!("y{k}"), "-")).collect();
    StateSpace::new(
        a,
        rng.matrix(n, m),
        rng.matrix(p, n),
        Some(rng.matrix(p, m)),
        Some(rng.matrix(p, m) * 0.1),
        outputs,
    )
    .unwrap()
}

/// Input spectra that stay well above underflow on the test grid (α = 300 s⁻² keeps the type-4 density
/// ≥ e^{-8} of its peak at 100 rad/s).
fn spectra() -> Vec<Arc<dyn Spectrum>> {
    let t = Domain::Temporal;
    vec![
        Arc::new(Exponential::new(1.0, 2.0, t).unwrap()),
        Arc::new(
            GaussCosineParameters {
                variance: 0.5,
                alpha: 300.0,
                beta: 4.0,
                domain: t,
            }
            .build()
            .unwrap(),
        ),
        Arc::new(
            ExpCosine {
                variance: 2.0,
                alpha: 0.7,
                beta: 2.5,
                domain: t,
            }
            .build()
            .unwrap(),
        ),
    ]
}

/// Frequencies covering the poles of the random systems (|λ| up to about 10 rad/s) and beyond.
fn omegas() -> Vec<f64> {
    (0..41).map(|k| 10f64.powf(-2.0 + 4.0 * k as f64 / 40.0)).collect()
}

/// max over ω of |fast − dense| / dense.
fn max_rel_diff(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> f64 {
    let fast = OutputDensity::new(sys, exc, i).unwrap();
    omegas()
        .iter()
        .map(|&w| {
            let (f, d) = (fast.density(w), output_density(sys, exc, i, w));
            assert!(d > 0.0, "dense density must be positive at ω = {w}: {d}");
            (f - d).abs() / d
        })
        .fold(0.0, f64::max)
}

#[test]
fn output_density_fast_equals_dense_on_random_systems() {
    let mut rng = Rng(20261122);
    let sp = spectra();
    for case in 0..40 {
        let n = 1 + case % 9;
        let m = 1 + case % 3;
        let p = 1 + (case / 3) % 3;
        let sys = random_system(&mut rng, n, m, p);
        // a track with distinct, repeated and zero delays
        let delays: Vec<f64> = (0..m).map(|j| [0.0, 0.13, 0.0, 0.4][(j + case) % 4]).collect();
        let gains: Vec<f64> = (0..m).map(|_| 0.5 + rng.next()).collect();
        let track = Excitation::track(sp[case % 3].clone(), delays, gains, 0.0).unwrap();
        let indep =
            Excitation::independent((0..m).map(|j| sp[(case + j) % 3].clone()).collect(), vec![0.0; m]).unwrap();
        for i in 0..p {
            for exc in [&track, &indep] {
                let d = max_rel_diff(&sys, exc, i);
                assert!(
                    d < FACTORISATION,
                    "case {case} (n = {n}, m = {m}), output {i}: rel diff {d:e}"
                );
            }
        }
    }
}

/// A nearly defective A (a Jordan block hidden by a random similarity) forces the Hessenberg route.
#[test]
fn output_density_fast_equals_dense_for_defective_a() {
    let mut rng = Rng(7);
    let sp = spectra();
    for case in 0..6 {
        let n = 3 + case % 3;
        let mut j = DMatrix::zeros(n, n);
        for k in 0..n {
            j[(k, k)] = -1.5;
            if k + 1 < n {
                j[(k, k + 1)] = 1.0;
            }
        }
        let mut t = rng.matrix(n, n);
        for k in 0..n {
            t[(k, k)] += 3.0;
        }
        let a = &t * j * t.clone().try_inverse().unwrap();
        let sys = StateSpace::new(
            a,
            rng.matrix(n, 2),
            rng.matrix(1, n),
            Some(rng.matrix(1, 2)),
            Some(rng.matrix(1, 2)),
            vec![OutputInfo::new("y", "-")],
        )
        .unwrap();
        let exc = Excitation::track(sp[case % 3].clone(), vec![0.0, 0.25], vec![1.0, -0.7], 0.0).unwrap();
        let d = max_rel_diff(&sys, &exc, 0);
        assert!(d < FACTORISATION, "case {case}: rel diff {d:e}");
    }
}

/// Critically damped oscillator (a double pole −ω₀, exactly defective): closed form
/// H(iω) = 1/(ω₀² − ω² + 2iω₀ω), |H|² = 1/(ω₀² + ω²)², under S(ω) = Dα/(π(α² + ω²)).
#[test]
fn output_density_fast_critically_damped_closed_form() {
    let w0 = 4.0;
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w0 * w0, -2.0 * w0]);
    let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
    let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
    let ss = StateSpace::new(a, b, c, None, None, vec![OutputInfo::new("x", "m")]).unwrap();
    let exc = Excitation::single(Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()), 0.0).unwrap();
    let fast = OutputDensity::new(&ss, &exc, 0).unwrap();
    for w in omegas() {
        let closed = 1.0 / (w0 * w0 + w * w).powi(2) * 2.0 / (PI * (4.0 + w * w));
        let got = fast.density(w);
        assert!(
            (got - closed).abs() < FACTORISATION * closed,
            "ω = {w}: {got} vs {closed}"
        );
    }
}

#[test]
fn output_density_fast_without_state_space() {
    let mut rng = Rng(99);
    let sp = spectra();
    let sys = ResponseOnly(random_system(&mut rng, 4, 3, 2));
    let track = Excitation::track(sp[1].clone(), vec![0.0, 0.2, 0.2], vec![1.0, 0.5, -0.8], 0.0).unwrap();
    let indep = Excitation::independent(sp.clone(), vec![0.0; 3]).unwrap();
    for exc in [&track, &indep] {
        for i in 0..2 {
            let d = max_rel_diff(&sys, exc, i);
            assert!(d < FACTORISATION, "output {i}: rel diff {d:e}");
        }
    }
}

#[test]
fn output_density_fast_rejects_bad_arguments() {
    let mut rng = Rng(3);
    let sys = random_system(&mut rng, 2, 2, 1);
    let exc1 = Excitation::single(spectra()[0].clone(), 0.0).unwrap();
    assert!(
        OutputDensity::new(&sys, &exc1, 0).is_err(),
        "one input for a two-input system"
    );
    let exc2 = Excitation::track(spectra()[0].clone(), vec![0.0, 0.1], vec![1.0, 1.0], 0.0).unwrap();
    assert!(
        OutputDensity::new(&sys, &exc2, 1).is_err(),
        "output 1 of a one-output system"
    );
    assert!(OutputDensity::new(&sys, &exc2, 0).is_ok());
}

/// `density_into` (vectorised for the CPU's widest SIMD unit) against its oracle `density` (scalar, libm):
/// exactly the same values where both evaluate the same arithmetic (the rational kinds, the chunked
/// `AtSpeed` override), and within [`SIMD_DENSITY`] relative (or 4 subnormal spacings) where
/// `density_into` uses the vectorised `exp`/`ln` or powers by multiplication (Gaussian, Gauss-cosine, ISO
/// 8608 power law) and within [`TABULATED_DENSITY`] for the tabulated law's table-driven power (its table
/// 1/(1 + x²) at nodes a factor 1.7 apart: slopes −2 < p < 0 and |p ln(ω/ω_k)| ≤ 2 ln 1.7 < 1.1, inside
/// that tolerance's range); on a grid through the tails down to the subnormal range of the
/// Gaussian (ω up to 100 rad/s), not a multiple of any block, and an output buffer shorter than the grid
/// (only its length is filled).
#[test]
fn density_into_equals_density() {
    use stochvib::spectrum::two_pole_road::Form;
    use stochvib::spectrum::{
        AtSpeed, BandWhiteParameters, Convention, Gaussian, IsoBound, IsoClass, PowerLaw, RationalSpectrum, Tabulated,
        TwoPoleRoad, ISO_BAND,
    };
    let t = Domain::Temporal;
    let mut all: Vec<(Arc<dyn Spectrum>, bool)> = spectra().into_iter().map(|s| (s, true)).collect();
    all[1].1 = false; // Gauss-cosine
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(32e-4, 0.16, Domain::Spatial).unwrap());
    all.push((Arc::new(AtSpeed::new(road, 10.0).unwrap()), true));
    all.push((
        Arc::new(RationalSpectrum::new(vec![1.0, 0.5], vec![1.0, 0.3, 0.02], t).unwrap()),
        true,
    ));
    all.push((
        Arc::new(
            BandWhiteParameters {
                convention: Convention::TwoSidedAngular,
                level: 0.1,
                lo: 1.0,
                hi: 50.0,
                domain: t,
            }
            .build()
            .unwrap(),
        ),
        true,
    ));
    all.push((
        Arc::new(
            TwoPoleRoad {
                dq: 1e-3,
                alpha: 0.3,
                beta: 12.0,
                form: Form::Consistent,
            }
            .build()
            .unwrap(),
        ),
        true,
    ));
    all.push((Arc::new(Gaussian::new(1.0, 2.0, t).unwrap()), false));
    let iso = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some(ISO_BAND)).unwrap();
    all.push((Arc::new(AtSpeed::new(Arc::new(iso), 20.0).unwrap()), false));
    let x: Vec<f64> = (0..12).map(|k| 0.1 * 1.7f64.powi(k)).collect();
    let v: Vec<f64> = x.iter().map(|x| 1.0 / (1.0 + x * x)).collect();
    all.push((
        Arc::new(Tabulated::new(Convention::TwoSidedAngular, x, v, t).unwrap()),
        false,
    ));
    let mut grid: Vec<f64> = (0..1000).map(|k| -5.0 + 0.0173 * k as f64).collect();
    grid.extend((0..2001).map(|k| 0.05 * k as f64));
    let n = grid.len() - 223;
    let last = all.len() - 1; // the tabulated density
    for (i, (s, exact)) in all.iter().enumerate() {
        let tol = if i == last { TABULATED_DENSITY } else { SIMD_DENSITY };
        let mut out = vec![-1.0; n];
        s.density_into(&grid, &mut out);
        for (k, o) in out.iter().enumerate() {
            let d = s.density(grid[k]);
            let close = (o - d).abs() <= tol * d.abs() || (o - d).abs() <= 4.0 * 5e-324;
            assert!(
                if *exact { o.to_bits() == d.to_bits() } else { close },
                "{} at ω = {}: {o:e} vs {d:e}",
                s.describe(),
                grid[k]
            );
        }
        let mut long = vec![-1.0; grid.len() + 200];
        s.density_into(&grid, &mut long);
        assert!(
            long[grid.len()..].iter().all(|v| *v == -1.0),
            "entries past the grid untouched"
        );
    }
}

/// `solve_continuous_lyapunov` (one Schur form reused by the refinement, refinement skipped at rounding
/// level) on badly scaled systems. Independent reference: for A = S⁻¹ÃS and Q = S⁻¹Q̃S⁻ᵀ with a diagonal
/// S, the solution is X = S⁻¹X̃S⁻ᵀ, where X̃ solves the well-scaled equation (Ã, Q̃) by the dense
/// Kronecker oracle. Entries are compared relative to √(X_ii X_jj) (the scale of a covariance entry).
#[test]
fn lyapunov_badly_scaled_matches_scaled_dense_oracle() {
    use stochvib::linalg::{solve_continuous_lyapunov, solve_continuous_lyapunov_dense};
    let mut rng = Rng(424242);
    for case in 0..12 {
        let n = 2 + case % 6;
        let at = random_system(&mut rng, n, 1, 1).a;
        let g = rng.matrix(n, 2);
        let qt = &g * g.transpose() + DMatrix::identity(n, n) * 0.1;
        // scales 10^{-3} … 10^{3}, not powers of two
        let s: Vec<f64> = (0..n)
            .map(|k| 10f64.powf(-3.0 + 6.0 * k as f64 / (n - 1) as f64) * 1.37)
            .collect();
        let a = DMatrix::from_fn(n, n, |i, j| at[(i, j)] * s[j] / s[i]);
        let q = DMatrix::from_fn(n, n, |i, j| qt[(i, j)] / (s[i] * s[j]));
        let xt = solve_continuous_lyapunov_dense(&at, &qt).unwrap();
        let expect = DMatrix::from_fn(n, n, |i, j| xt[(i, j)] / (s[i] * s[j]));
        let x = solve_continuous_lyapunov(&a, &q).unwrap();
        for i in 0..n {
            for j in 0..n {
                let scale = (expect[(i, i)] * expect[(j, j)]).sqrt();
                let err = (x[(i, j)] - expect[(i, j)]).abs() / scale;
                assert!(err < FACTORISATION, "case {case}, n = {n}, entry ({i}, {j}): {err:e}");
            }
        }
    }
}
