//! Integration tests of `stochvib::quad::integrate` against closed forms.

use crate::common;
use common::tolerance::{QUADRATURE, ROUNDING, ULPS};
use std::cell::Cell;
use std::f64::consts::{PI, SQRT_2};

use stochvib::quad::{integrate, QuadOptions, QuadResult};
use stochvib::Error;

const INF: f64 = f64::INFINITY;
const NINF: f64 = f64::NEG_INFINITY;

fn opts(rel_tol: f64) -> QuadOptions {
    QuadOptions {
        rel_tol,
        ..QuadOptions::default()
    }
}

fn with_bps(rel_tol: f64, bps: &[f64]) -> QuadOptions {
    QuadOptions {
        rel_tol,
        breakpoints: bps.to_vec(),
        ..QuadOptions::default()
    }
}

/// Checks the value to `rel` (relative to `exact`) and that the error estimate is an upper bound of
/// the true error that is not absurdly pessimistic (at most 1e3 times the true error, or at the level
/// of the tolerance / roundoff).
fn check(name: &str, r: &QuadResult, exact: f64, rel: f64) {
    let err = (r.value - exact).abs();
    assert!(
        err <= rel * exact.abs(),
        "{name}: value {} vs exact {exact} (error {err:e})",
        r.value
    );
    assert!(
        err <= r.abs_error,
        "{name}: error estimate {:e} is not an upper bound of the true error {err:e}",
        r.abs_error
    );
    assert!(
        r.abs_error <= rel * exact.abs(),
        "{name}: error estimate {:e} above tolerance",
        r.abs_error
    );
}

/// SDOF |H(ω)|² with H = 1/(ω0² − ω² + 2iζω0ω).
fn sdof(w0: f64, zeta: f64) -> impl Fn(f64) -> f64 {
    // (ω0−ω)(ω0+ω) instead of ω0²−ω²: no cancellation near the peak, so f is accurate to a few ε.
    move |w| 1.0 / (((w0 - w) * (w0 + w)).powi(2) + (2.0 * zeta * w0 * w).powi(2))
}

#[test]
fn polynomials_exact_to_degree_31() {
    // ∫_0^1 x^k dx = 1/(k+1) (elementary); K21 is exact for degree ≤ 31, G10 for degree ≤ 19, so for
    // k ≤ 19 the error estimate |K − G| vanishes and one rule application suffices.
    for k in 0..=31 {
        let r = integrate(|x| x.powi(k), 0.0, 1.0, &opts(1e-13)).unwrap();
        let exact = 1.0 / (k as f64 + 1.0);
        assert!((r.value - exact).abs() < ROUNDING, "k = {k}: {}", r.value);
        if k <= 19 {
            assert_eq!(r.evaluations, 21, "k = {k}: one rule application");
        }
    }
}

#[test]
fn finite_smooth_closed_forms() {
    // ∫_0^π sin x dx = 2 (elementary).
    check("sin", &integrate(f64::sin, 0.0, PI, &opts(1e-12)).unwrap(), 2.0, 1e-12);
    // ∫_0^100 cos x dx = sin 100 (elementary); ~16 oscillations.
    check(
        "cos",
        &integrate(f64::cos, 0.0, 100.0, &opts(1e-10)).unwrap(),
        100f64.sin(),
        1e-10,
    );
    // ∫_0^1 4/(1+x²) dx = π (arctan).
    check(
        "arctan",
        &integrate(|x| 4.0 / (1.0 + x * x), 0.0, 1.0, &opts(1e-13)).unwrap(),
        PI,
        1e-13,
    );
    // ∫_{-1}^{1} e^x dx = e − 1/e = 2 sinh 1.
    check(
        "exp",
        &integrate(f64::exp, -1.0, 1.0, &opts(1e-13)).unwrap(),
        2.0 * 1f64.sinh(),
        1e-13,
    );
    // ∫_0^1 dx / (x² + 1e-4) = 100 arctan(100) (arctan); a peak of width 1e-2 at the endpoint.
    let r = integrate(|x| 1.0 / (x * x + 1e-4), 0.0, 1.0, &opts(1e-11)).unwrap();
    check("lorentz", &r, 100.0 * 100f64.atan(), 1e-11);
}

#[test]
fn infinite_range_closed_forms() {
    // ∫_{-∞}^{∞} dx/(1+x²) = π (arctan).
    check(
        "cauchy",
        &integrate(|x| 1.0 / (1.0 + x * x), NINF, INF, &opts(1e-12)).unwrap(),
        PI,
        1e-12,
    );
    // ∫_0^∞ e^{-x} dx = 1.
    check(
        "exp tail",
        &integrate(|x| (-x).exp(), 0.0, INF, &opts(1e-12)).unwrap(),
        1.0,
        1e-12,
    );
    // ∫_{-∞}^0 e^{x} dx = 1 (the head map).
    check(
        "exp head",
        &integrate(f64::exp, NINF, 0.0, &opts(1e-12)).unwrap(),
        1.0,
        1e-12,
    );
    // ∫_{-∞}^{∞} e^{-x²} dx = √π (Gaussian integral).
    let r = integrate(|x| (-x * x).exp(), NINF, INF, &opts(1e-12)).unwrap();
    check("gauss", &r, PI.sqrt(), 1e-12);
    // ∫_0^∞ x e^{-x} sin x dx = 2ab/(a²+b²)² at a = b = 1 = 1/2 (Laplace transform of x sin bx).
    let r = integrate(|x| x * (-x).exp() * x.sin(), 0.0, INF, &opts(1e-11)).unwrap();
    check("x exp sin", &r, 0.5, 1e-11);
    // ∫_0^∞ dx/(1+x⁴) = π/(2√2) (residues).
    let r = integrate(|x| 1.0 / (1.0 + x.powi(4)), 0.0, INF, &opts(1e-12)).unwrap();
    check("quartic", &r, PI / (2.0 * SQRT_2), 1e-12);
    // ∫_1^∞ dx/x² = 1.
    check(
        "power tail",
        &integrate(|x| 1.0 / (x * x), 1.0, INF, &opts(1e-12)).unwrap(),
        1.0,
        1e-12,
    );
    // ∫_{-∞}^{-2} dx/x² = 1/2.
    check(
        "power head",
        &integrate(|x| 1.0 / (x * x), NINF, -2.0, &opts(1e-12)).unwrap(),
        0.5,
        1e-12,
    );
    // ∫_{-∞}^{∞} e^{-(x-1000)²} dx = √π with the peak given as a breakpoint.
    let r = integrate(
        |x| (-(x - 1000.0).powi(2)).exp(),
        NINF,
        INF,
        &with_bps(1e-12, &[1000.0]),
    )
    .unwrap();
    check("shifted gauss", &r, PI.sqrt(), 1e-12);
}

#[test]
fn sharp_resonance_with_breakpoint() {
    // ∫_{-∞}^{∞} dω / ((ω0²−ω²)² + (2ζω0ω)²) = π/(2ζω0³): the white-noise SDOF variance integral
    // (e.g. Crandall & Mark, Random Vibration in Mechanical Systems, 1963; Newland, eq. 7.20).
    let (w0, zeta) = (50.0f64, 1e-3);
    let exact = PI / (2.0 * zeta * w0.powi(3));
    let f = sdof(w0, zeta);

    let r = integrate(&f, NINF, INF, &with_bps(1e-10, &[w0])).unwrap();
    check("resonance (-inf, inf), bp [50]", &r, exact, 1e-10);
    println!("resonance (-inf, inf), breakpoints [50]: {} evaluations", r.evaluations);

    let r = integrate(&f, NINF, INF, &with_bps(1e-10, &[-w0, w0])).unwrap();
    check("resonance (-inf, inf), bp [-50, 50]", &r, exact, 1e-10);
    println!(
        "resonance (-inf, inf), breakpoints [-50, 50]: {} evaluations",
        r.evaluations
    );

    // Even integrand: half of it on [0, ∞).
    let r = integrate(&f, 0.0, INF, &with_bps(1e-10, &[w0])).unwrap();
    check("resonance [0, inf), bp [50]", &r, exact / 2.0, 1e-10);
    println!("resonance [0, inf), breakpoints [50]: {} evaluations", r.evaluations);

    // Without the breakpoint it must still converge (the peak is found adaptively), at a higher cost.
    let r = integrate(&f, 0.0, INF, &opts(1e-10)).unwrap();
    check("resonance [0, inf), no bp", &r, exact / 2.0, 1e-10);
    println!("resonance [0, inf), no breakpoints: {} evaluations", r.evaluations);
}

#[test]
fn resonance_family_error_estimates_are_bounds() {
    // Same closed form over a range of ω0 and ζ on [0, ∞) with the peak as breakpoint.
    for &w0 in &[0.1f64, 1.0, 50.0, 3000.0] {
        for &zeta in &[1e-4, 1e-3, 0.02, 0.3] {
            let exact = PI / (4.0 * zeta * w0.powi(3));
            let r = integrate(sdof(w0, zeta), 0.0, INF, &with_bps(1e-10, &[w0])).unwrap();
            check(&format!("w0 = {w0}, zeta = {zeta}"), &r, exact, 1e-10);
        }
    }
}

#[test]
fn endpoint_singularities() {
    // ∫_0^1 x^{-1/2} dx = 2.
    let r = integrate(|x| 1.0 / x.sqrt(), 0.0, 1.0, &opts(1e-10)).unwrap();
    check("1/sqrt(x)", &r, 2.0, QUADRATURE);
    // ∫_0^1 ln x dx = −1.
    let r = integrate(f64::ln, 0.0, 1.0, &opts(1e-10)).unwrap();
    check("ln x", &r, -1.0, 1e-10);
    // ∫_0^∞ x^{-1/2} e^{-x} dx = Γ(1/2) = √π.
    let r = integrate(|x| (-x).exp() / x.sqrt(), 0.0, INF, &opts(1e-9)).unwrap();
    check("gamma(1/2)", &r, PI.sqrt(), 1e-9);
}

#[test]
fn kink_at_breakpoint_is_exact() {
    // ∫_{-1}^{2} |x| dx = 1/2 + 2 = 5/2; with the kink as breakpoint each piece is a polynomial.
    let r = integrate(f64::abs, -1.0, 2.0, &with_bps(1e-12, &[0.0])).unwrap();
    assert!((r.value - 2.5).abs() < ULPS);
    assert_eq!(r.evaluations, 42);
}

#[test]
fn cancelling_integral_converges_to_roundoff() {
    // ∫_{-1}^{1} x³ dx = 0 (odd): no relative tolerance can be met on 0; returns with a roundoff-level
    // error estimate rather than failing.
    let r = integrate(|x| x.powi(3), -1.0, 1.0, &QuadOptions::default()).unwrap();
    assert!(r.value.abs() <= r.abs_error && r.abs_error < ROUNDING, "{r:?}");
}

#[test]
fn non_integrable_singularity_is_reported() {
    // ∫_0^1 dx/x diverges: must be an error carrying the estimate, never a silent finite value.
    let o = QuadOptions {
        max_subintervals: 50,
        ..QuadOptions::default()
    };
    match integrate(|x| 1.0 / x, 0.0, 1.0, &o) {
        Err(Error::Quadrature {
            estimate,
            abs_error,
            evaluations,
            reason,
            ..
        }) => {
            assert!(estimate.is_finite() && abs_error > 0.0 && evaluations > 0);
            assert!(reason.contains("maximum of 50 subintervals"), "{reason}");
        }
        other => panic!("expected Error::Quadrature, got {other:?}"),
    }
    // Also with the default (large) budget.
    assert!(matches!(
        integrate(|x| 1.0 / x, 0.0, 1.0, &QuadOptions::default()),
        Err(Error::Quadrature { .. })
    ));
    // A non-decaying integrand on an infinite range: ∫_0^∞ 1 dx = ∞.
    assert!(matches!(
        integrate(|_| 1.0, 0.0, INF, &QuadOptions::default()),
        Err(Error::Quadrature { .. })
    ));
    // ∫_0^∞ dx/(1+x) = ∞ (logarithmic divergence).
    assert!(matches!(
        integrate(|x| 1.0 / (1.0 + x), 0.0, INF, &QuadOptions::default()),
        Err(Error::Quadrature { .. })
    ));
}

#[test]
fn non_finite_integrand_is_reported() {
    let o = QuadOptions::default();
    match integrate(|_| f64::NAN, 0.0, 1.0, &o) {
        Err(Error::Quadrature { reason, .. }) => assert!(reason.contains("integrand not finite at x ="), "{reason}"),
        other => panic!("expected Error::Quadrature, got {other:?}"),
    }
    // NaN on part of the range only.
    let r = integrate(|x| if x > 0.7 { f64::NAN } else { 1.0 }, 0.0, 1.0, &o);
    match r {
        Err(Error::Quadrature { reason, .. }) => assert!(reason.contains("integrand not finite at x = "), "{reason}"),
        other => panic!("expected Error::Quadrature, got {other:?}"),
    }
    // Infinite values on an infinite range.
    assert!(matches!(
        integrate(|x| 1.0 / (x - 3.0), 0.0, INF, &o),
        Err(Error::Quadrature { .. })
    ));
    // Overflowing integrand.
    assert!(matches!(
        integrate(|_| f64::MAX, 0.0, 10.0, &o),
        Err(Error::Quadrature { .. })
    ));
}

#[test]
fn invalid_input_is_rejected() {
    let o = QuadOptions::default();
    assert!(matches!(
        integrate(|x| x, f64::NAN, 1.0, &o),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        integrate(|x| x, 0.0, f64::NAN, &o),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        integrate(|x| x, 2.0, 1.0, &o),
        Err(Error::InvalidParameter { .. })
    ));
    assert!(matches!(
        integrate(|x| x, INF, NINF, &o),
        Err(Error::InvalidParameter { .. })
    ));
}

#[test]
fn empty_range_is_zero_without_evaluations() {
    let calls = Cell::new(0usize);
    let f = |x: f64| {
        calls.set(calls.get() + 1);
        x
    };
    assert_eq!(integrate(f, 1.5, 1.5, &QuadOptions::default()).unwrap().value, 0.0);
    assert_eq!(integrate(f, INF, INF, &QuadOptions::default()).unwrap().value, 0.0);
    assert_eq!(calls.get(), 0);
}

#[test]
fn evaluation_count_is_exact_and_endpoints_never_evaluated() {
    // The reported count equals the calls made, and f is never called at the limits or at ±∞.
    let calls = Cell::new(0usize);
    let f = |x: f64| {
        calls.set(calls.get() + 1);
        assert!(x.is_finite() && x != 0.0 && x != 50.0, "evaluated at {x}");
        sdof(50.0, 1e-3)(x)
    };
    let r = integrate(f, 0.0, INF, &with_bps(1e-10, &[50.0])).unwrap();
    assert_eq!(r.evaluations, calls.get());
}

#[test]
fn zero_subinterval_budget_does_not_panic() {
    // max_subintervals = 0: the initial partition is still evaluated; no bisection is allowed.
    let o = QuadOptions {
        max_subintervals: 0,
        ..QuadOptions::default()
    };
    let r = integrate(|x| x * x, 0.0, 1.0, &o).unwrap();
    assert!((r.value - 1.0 / 3.0).abs() < ULPS);
    assert!(matches!(
        integrate(f64::sqrt, 0.0, 1.0, &o),
        Err(Error::Quadrature { .. })
    ));
}
