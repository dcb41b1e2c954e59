//! Nonlinear elements, routes 1 and 3 and the splitting integrator, against values derived independently
//! in this file (closed forms, trapezoid rules on kink-aligned pieces, scalar root finding) and, as a
//! second check, against values printed with 9–12 digits by an independent scipy/mpmath computation
//! (quoted where used).
//!
//! Conventions: white noise of two-sided density S_f drives m x″ + c x′ + k x + F(x) = f with
//! E[f(t)f(t+τ)] = 2πS_f δ(τ); with m = k = 1 and c = 2ζ the linear variance is σ₀² = πS_f/(c k) and the
//! velocity variance of every such oscillator is σ_v² = πS_f/(c m) (the Fokker–Planck density of route 3
//! factorises: derivation in `docs/nonlinear.md`).

use crate::common;
use common::rel;
use common::tolerance::{
    PRINTED_8_DIGITS, QUADRATURE, RIGID_STOP, ROUTE1_ITERATION, SPLITTING_MIN_ORDER, TRAPEZOID_PIECEWISE,
};
use statrs::function::erf::erfc;
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::nonlinear::integrator::free_response;
use stochvib::nonlinear::*;
use stochvib::response::{analyze_output, Excitation};
use stochvib::spectrum::{Domain, RationalSpectrum};
use stochvib::system::{Attach, Drive, MassSpringDamper, Quantity};

fn phi(x: f64) -> f64 {
    (-0.5 * x * x).exp() / (2.0 * PI).sqrt()
}

fn cdf(x: f64) -> f64 {
    0.5 * erfc(-x / std::f64::consts::SQRT_2)
}

/// Trapezoid rule of f over [a, b] with n steps; the end values are taken 10⁻¹² of the width inside, so that
/// at a jump of f (a piece ending at a kink) each piece uses its own one-sided limit.
fn trapezoid(f: &dyn Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n).map(|i| f(a + i as f64 * h)).sum();
    let e = 1e-12 * (b - a);
    h * (0.5 * (f(a + e) + f(b - e)) + inner)
}

/// ∫ f over [a, b] by trapezoid pieces between the kinks (each piece smooth: the error of TRAPEZOID_PIECEWISE).
fn pieces(f: &dyn Fn(f64) -> f64, a: f64, b: f64, kinks: &[f64]) -> f64 {
    let mut pts = vec![a];
    pts.extend(kinks.iter().copied().filter(|k| *k > a && *k < b));
    pts.push(b);
    pts.sort_by(f64::total_cmp);
    pts.windows(2)
        .map(|w| trapezoid(f, w[0], w[1], (((w[1] - w[0]) * 2000.0).ceil() as usize).max(200)))
        .sum()
}

/// E[g(z)] for z ~ N(μ, s²) with kinks of g at `kinks` (steps of s/2000 over μ ± 12s).
fn expect(g: &dyn Fn(f64) -> f64, mu: f64, s: f64, kinks: &[f64]) -> f64 {
    let f = |u: f64| g(mu + s * u) * phi(u);
    let k: Vec<f64> = kinks.iter().map(|x| (x - mu) / s).collect();
    pieces(&f, -12.0, 12.0, &k)
}

/// F₀ and Stein's coefficient E[F(z)(z − μ)]/s² (= E[F′(z)] also for a discontinuous F).
fn numeric(f: &dyn Fn(f64) -> f64, mu: f64, s: f64, kinks: &[f64]) -> (f64, f64) {
    (
        expect(f, mu, s, kinks),
        expect(&|z| f(z) * (z - mu), mu, s, kinks) / (s * s),
    )
}

fn close(a: f64, b: f64, scale: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol * scale,
        "{what}: {a} vs {b} (scale {scale}, tol {tol})"
    );
}

/// Every element's Gaussian expectations against quadrature of the force law (Stein's form for the
/// coefficient), at x ~ N(0.3, 0.8²), v ~ N(−0.2, 0.6²); and against the values printed with 12 digits by an
/// independent scipy computation (gauss_equiv.py of the project's research notes: cubic k₁ = 2, k₃ = 0.5
/// → E[F] = 0.901500000000, k_eq = 3.095; upper stop k_c = 10, d = 0.5 → 2.290757585789, 4.012936743171;
/// Coulomb F_c = 1.5 → −0.391675979455, c_eq = 1.886916138465; bilinear c_r = 3, c_c = 1 → E[F] =
/// 0.105083337159, c_eq = 1.738882680364; quadratic q_r = 2, q_c = 0.5 → 0.056226371874, 0.962708342897).
#[test]
fn gaussian_equivalents_match_quadrature_and_printed_values() {
    let (mx, sx, mv, sv) = (0.3, 0.8, -0.2, 0.6);
    let m = ElementMoments {
        mean_x: mx,
        sigma_x: sx,
        mean_v: mv,
        sigma_v: sv,
    };
    let total = |law: &dyn ForceLaw, e: Equivalent, vel: bool| -> (f64, f64) {
        let (k, c) = law.linear_part();
        let mu = if vel { mv } else { mx };
        let lin = if vel { c } else { k };
        (
            e.mean_force + lin * mu,
            if vel { e.damping + c } else { e.stiffness + k },
        )
    };
    // cubic spring
    let cubic = CubicSpring::new(2.0, 0.5).unwrap();
    let (f0, k) = total(&cubic, cubic.gaussian(&m), false);
    let (nf, nk) = numeric(&|x| 2.0 * x + 0.5 * x.powi(3), mx, sx, &[]);
    close(f0, nf, 1.0, TRAPEZOID_PIECEWISE, "cubic E[F]");
    close(k, nk, 1.0, TRAPEZOID_PIECEWISE, "cubic k_eq");
    close(f0, 0.9015, 1.0, PRINTED_8_DIGITS, "cubic printed");
    // two-sided stop
    let stop = BumpStop::new(Some((0.5, 10.0)), Some((0.7, 10.0))).unwrap();
    let e = stop.gaussian(&m);
    let f = |x: f64| 10.0 * (x - 0.5).max(0.0) - 10.0 * (-0.7 - x).max(0.0);
    let (nf, nk) = numeric(&f, mx, sx, &[0.5, -0.7]);
    close(e.mean_force, nf, 1.0, TRAPEZOID_PIECEWISE, "stop E[F]");
    close(e.stiffness, nk, 1.0, TRAPEZOID_PIECEWISE, "stop k_eq");
    let up = BumpStop::new(Some((0.5, 10.0)), None).unwrap().gaussian(&m);
    close(
        up.mean_force,
        2.290757585789,
        1.0,
        PRINTED_8_DIGITS,
        "upper stop printed E[F]",
    );
    close(
        up.stiffness,
        4.012936743171,
        1.0,
        PRINTED_8_DIGITS,
        "upper stop printed k_eq",
    );
    // bilinear damper (linear part c̄ v plus Δ|v|)
    let bil = BilinearDamper::new(3.0, 1.0).unwrap();
    let (f0, c) = total(&bil, bil.gaussian(&m), true);
    let (nf, nc) = numeric(&|v| if v > 0.0 { 3.0 * v } else { v }, mv, sv, &[0.0]);
    close(f0, nf, 1.0, TRAPEZOID_PIECEWISE, "bilinear E[F]");
    close(c, nc, 1.0, TRAPEZOID_PIECEWISE, "bilinear c_eq");
    close(f0, 0.105083337159, 1.0, PRINTED_8_DIGITS, "bilinear printed E[F]");
    close(c, 1.738882680364, 1.0, PRINTED_8_DIGITS, "bilinear printed c_eq");
    // quadratic damper
    let quad = QuadraticDamper::new(2.0, 0.5).unwrap();
    let e = quad.gaussian(&m);
    let (nf, nc) = numeric(&|v| if v > 0.0 { 2.0 * v * v } else { -0.5 * v * v }, mv, sv, &[0.0]);
    close(e.mean_force, nf, 1.0, TRAPEZOID_PIECEWISE, "quadratic E[F]");
    close(e.damping, nc, 1.0, TRAPEZOID_PIECEWISE, "quadratic c_eq");
    close(e.mean_force, 0.056226371874, 1.0, PRINTED_8_DIGITS, "quadratic printed");
    close(
        e.damping,
        0.962708342897,
        1.0,
        PRINTED_8_DIGITS,
        "quadratic printed c_eq",
    );
    // Coulomb friction (Stein's coefficient of a jump)
    let fr = CoulombFriction::new(1.5).unwrap();
    let e = fr.gaussian(&m);
    let (nf, nc) = numeric(&|v| 1.5 * v.signum(), mv, sv, &[0.0]);
    close(e.mean_force, nf, 1.0, TRAPEZOID_PIECEWISE, "Coulomb E[F]");
    close(e.damping, nc, 1.0, TRAPEZOID_PIECEWISE, "Coulomb c_eq");
    close(e.mean_force, -0.391675979455, 1.0, PRINTED_8_DIGITS, "Coulomb printed");
    close(e.damping, 1.886916138465, 1.0, PRINTED_8_DIGITS, "Coulomb printed c_eq");
    // tyre contact: remainder −k_t (x − s₀)₊ at s ~ N(0.02, 0.012²) deflection... of the spring
    let tyre = TyreContact::new(200.0, 4.0).unwrap(); // s₀ = 0.02
    let mt = ElementMoments {
        mean_x: -0.005,
        sigma_x: 0.012,
        ..Default::default()
    };
    let e = tyre.gaussian(&mt);
    let (nf, nk) = numeric(&|x| -200.0 * (x - 0.02).max(0.0), -0.005, 0.012, &[0.02]);
    close(e.mean_force, nf, 4.0, TRAPEZOID_PIECEWISE, "tyre E[F]");
    close(e.stiffness, nk, 200.0, TRAPEZOID_PIECEWISE, "tyre k_eq");
}

/// A white-noise oscillator m = k = 1, c = 2ζ = 0.2 with σ₀² = 1 (S_f = 0.2/π) and the nonlinear elements.
fn oscillator(elements: Vec<(&str, Arc<dyn ForceLaw>)>, damping: f64, s_f: f64) -> (NonlinearModel, Excitation) {
    let lin = MassSpringDamper {
        mass: 1.0,
        stiffness: 1.0,
        damping,
        drive: Drive::Force,
    }
    .build()
    .unwrap()
    .with_output("x", Quantity::Displacement(vec![1.0]))
    .unwrap()
    .with_output("v", Quantity::Velocity(vec![1.0]))
    .unwrap();
    let els = elements
        .into_iter()
        .map(|(name, law)| NonlinearElement {
            name: name.into(),
            law,
            point: vec![1.0],
            to: Attach::Ground,
        })
        .collect();
    let white = Arc::new(RationalSpectrum::new(vec![s_f], vec![1.0], Domain::Temporal).unwrap());
    (
        NonlinearModel::new(&lin, els).unwrap(),
        Excitation::single(white, 0.0).unwrap(),
    )
}

fn duffing(eps: f64) -> (NonlinearModel, Excitation) {
    oscillator(
        vec![("cubic", Arc::new(CubicSpring::new(0.0, eps).unwrap()))],
        0.2,
        0.2 / PI,
    )
}

fn route1(model: &NonlinearModel, exc: &Excitation) -> Route1 {
    linearize(model, exc, &Route1Options::default())
        .unwrap()
        .converged()
        .expect("route 1 converges")
        .clone()
}

/// Route 1 of the Duffing oscillator is the root of 3εσ⁴ + σ² − σ₀² = 0 (Caughey 1963): σ² =
/// (√(1 + 12εσ₀²) − 1)/(6ε), at εσ₀² = 0.1, 1, 10 (printed by the research notes: 0.805399496,
/// 0.434258546, 0.166666667).
#[test]
fn route1_duffing_is_the_root_of_the_quadratic() {
    for (eps, printed) in [(0.1, 0.805399496), (1.0, 0.434258546), (10.0, 0.166666667)] {
        let (model, exc) = duffing(eps);
        let r = route1(&model, &exc);
        let s2 = r.moments[0].sigma_x.powi(2);
        let root = ((1.0 + 12.0 * eps).sqrt() - 1.0) / (6.0 * eps);
        assert!(rel(s2, root) < ROUTE1_ITERATION, "ε = {eps}: {s2} vs {root}");
        assert!(rel(s2, printed) < 1e-8, "ε = {eps}: {s2} vs printed {printed}");
        // the output statistics carry route 1's σ and mean
        let st = r.output_statistics(&exc, &Default::default()).unwrap();
        assert!(rel(st[0].variance.unwrap(), root) < ROUTE1_ITERATION);
        assert_eq!(st[0].mean, Some(0.0));
    }
}

/// The exact Duffing density p(x) ∝ exp(−(x²/2 + εx⁴/4)) (σ₀ = 1) by a trapezoid rule written here
/// (exponentially convergent for this analytic, fast-decaying integrand: h = 10⁻³ on [−12, 12]) against
/// route 3's adaptive quadrature; σ², kurtosis and the exact rate ν⁺(a) = p(a)σ_v/√(2π) (σ_v = 1), and the
/// printed values (quadrature = Bessel-K closed form = parabolic-cylinder form to 1e-13 in the research
/// notes): σ² = 0.817561403867, 0.467919916974, 0.188902429350 and κ = 2.729455136, 2.430154806, 2.272992561.
#[test]
fn route3_duffing_matches_the_exact_density() {
    let printed = [
        (0.1, 0.817561403867, 2.729455136),
        (1.0, 0.467919916974, 2.430154806),
        (10.0, 0.188902429350, 2.272992561),
    ];
    for (eps, var_p, kurt_p) in printed {
        let (model, exc) = duffing(eps);
        let st = WhiteNoiseOscillator::from_model(&model, &exc)
            .unwrap()
            .stationary()
            .unwrap();
        let q = |x: f64| (-(0.5 * x * x + 0.25 * eps * x.powi(4))).exp();
        let z = trapezoid(&q, -12.0, 12.0, 24_000);
        let m2 = trapezoid(&|x| x * x * q(x), -12.0, 12.0, 24_000) / z;
        let m4 = trapezoid(&|x| x.powi(4) * q(x), -12.0, 12.0, 24_000) / z;
        assert!(rel(st.variance, m2) < QUADRATURE, "ε = {eps}: {} vs {m2}", st.variance);
        assert!(rel(st.kurtosis, m4 / (m2 * m2)) < QUADRATURE);
        assert!(rel(st.variance, var_p) < PRINTED_8_DIGITS);
        assert!(rel(st.kurtosis, kurt_p) < PRINTED_8_DIGITS);
        assert!(st.mean.abs() < 1e-12);
        for a in [0.0, 1.0, 2.0] {
            let exact = q(a) / z / (2.0 * PI).sqrt();
            assert!(rel(st.upcrossing_rate(a), exact) < QUADRATURE, "ε = {eps}, a = {a}");
        }
    }
    // the printed rates at ε = 1 (research notes): 2.061453e-01, 9.737615e-02, 5.109832e-04
    let (model, exc) = duffing(1.0);
    let st = WhiteNoiseOscillator::from_model(&model, &exc)
        .unwrap()
        .stationary()
        .unwrap();
    for (a, p) in [(0.0, 2.061453e-1), (1.0, 9.737615e-2), (2.0, 5.109832e-4)] {
        assert!(rel(st.upcrossing_rate(a), p) < 1e-6, "a = {a}");
    }
}

/// The exact law of an oscillator with a two-sided elastic stop (clearance d, contact stiffness κk), σ₀ = 1:
/// p(x) ∝ exp(−x²/2 − κ(|x| − d)₊²/2). Beyond d the exponent is −(1+κ)(x − μ_c)²/2 − κd²/(2(1+κ)) with
/// μ_c = κd/(1+κ), s_c² = 1/(1+κ); with h = (d − μ_c)/s_c, Q = 1 − Φ(h), C = e^{−κd²/(2(1+κ))}:
/// Z/√(2π) = (2Φ(d) − 1) + 2C s_c Q and E[x²]Z/√(2π) = (2Φ(d) − 1) − 2dφ(d) + 2C s_c[μ_c²Q + 2μ_c s_c φ(h) +
/// s_c²(hφ(h) + Q)] (the truncated normal moments); the rigid wall (κ → ∞) is the normal law truncated to
/// [−d, d], σ² = 1 − 2dφ(d)/(2Φ(d) − 1).
fn stop_exact(d: f64, kappa: f64) -> (f64, f64) {
    let inner = 2.0 * cdf(d) - 1.0;
    let (mu, s) = (kappa * d / (1.0 + kappa), (1.0 / (1.0 + kappa)).sqrt());
    let (h, c) = (
        ((d - kappa * d / (1.0 + kappa)) * (1.0 + kappa).sqrt()),
        (-kappa * d * d / (2.0 * (1.0 + kappa))).exp(),
    );
    let q = 1.0 - cdf(h);
    let z = inner + 2.0 * c * s * q;
    let m2 = inner - 2.0 * d * phi(d) + 2.0 * c * s * (mu * mu * q + 2.0 * mu * s * phi(h) + s * s * (h * phi(h) + q));
    // p(d) = e^{−d²/2}/Z = φ(d)/(Z/√(2π)), and ν⁺(d) = p(d)σ_v/√(2π) with σ_v = 1
    (m2 / z, phi(d) / z / (2.0 * PI).sqrt())
}

/// Route 3 of the two-sided stop against the closed form above (d = 1, κ = 10, 100; research notes'
/// printed values σ² = 0.502821990335, 0.356896891537 and ν⁺(d) = 0.1164840540, 0.1307081185), and the
/// very stiff stop (κ = 10⁶) against the rigid wall's closed form within RIGID_STOP.
#[test]
fn route3_bump_stop_matches_closed_forms_and_the_rigid_limit() {
    for (kappa, var_p, rate_p) in [
        (10.0, 0.502821990335, 0.1164840540),
        (100.0, 0.356896891537, 0.1307081185),
    ] {
        let (model, exc) = oscillator(
            vec![(
                "stop",
                Arc::new(BumpStop::new(Some((1.0, kappa)), Some((1.0, kappa))).unwrap()),
            )],
            0.2,
            0.2 / PI,
        );
        let st = WhiteNoiseOscillator::from_model(&model, &exc)
            .unwrap()
            .stationary()
            .unwrap();
        let (var, rate) = stop_exact(1.0, kappa);
        assert!(
            rel(st.variance, var) < QUADRATURE,
            "κ = {kappa}: {} vs {var}",
            st.variance
        );
        assert!(rel(st.upcrossing_rate(1.0), rate) < QUADRATURE);
        assert!(rel(var, var_p) < PRINTED_8_DIGITS && rel(rate, rate_p) < PRINTED_8_DIGITS);
        // the regime: contact entries per second = ν⁺(d) + ν⁺(−d) (symmetric), fraction P(|x| > d)
        let (fraction, entries) = st.regime(0).unwrap().unwrap();
        assert!(rel(entries, 2.0 * rate) < QUADRATURE);
        assert!(fraction > 0.0 && fraction < 1.0);
    }
    for d in [0.5, 1.0, 2.0] {
        let rigid = 1.0 - 2.0 * d * phi(d) / (2.0 * cdf(d) - 1.0);
        let (model, exc) = oscillator(
            vec![("stop", Arc::new(BumpStop::new(Some((d, 1e6)), Some((d, 1e6))).unwrap()))],
            0.2,
            0.2 / PI,
        );
        let st = WhiteNoiseOscillator::from_model(&model, &exc)
            .unwrap()
            .stationary()
            .unwrap();
        assert!(
            (st.variance - rigid).abs() < RIGID_STOP,
            "d = {d}: {} vs rigid {rigid}",
            st.variance
        );
        assert!(rel(st.variance, stop_exact(d, 1e6).0) < QUADRATURE);
    }
}

/// Route 1 of a one-sided stop (upper side only, d = 1, κ = 10, σ₀ = 1): the mean and variance solve
/// μ + κ[(μ − d)Φ(h) + σφ(h)] = 0 and σ² = 1/(1 + κΦ(h)), h = (μ − d)/σ, solved here by bisection in μ
/// inside a damped fixed point in σ² (research notes: μ = −0.21033888, σ² = 0.61796483; the exact values,
/// −0.16798343 and 0.74647609, are route 3's).
#[test]
fn route1_one_sided_stop_mean_shift() {
    let (d, kappa) = (1.0, 10.0);
    let mut s2: f64 = 1.0;
    let mut mu = 0.0;
    for _ in 0..2000 {
        let s = s2.sqrt();
        let g = |m: f64| m + kappa * ((m - d) * cdf((m - d) / s) + s * phi((m - d) / s));
        let (mut lo, mut hi) = (-50.0, 50.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                hi = mid
            } else {
                lo = mid
            }
        }
        mu = 0.5 * (lo + hi);
        s2 = 0.5 * s2 + 0.5 / (1.0 + kappa * cdf((mu - d) / s));
    }
    let (model, exc) = oscillator(
        vec![("stop", Arc::new(BumpStop::new(Some((d, kappa)), None).unwrap()))],
        0.2,
        0.2 / PI,
    );
    let r = route1(&model, &exc);
    assert!(
        (r.moments[0].mean_x - mu).abs() < ROUTE1_ITERATION,
        "{} vs {mu}",
        r.moments[0].mean_x
    );
    assert!(rel(r.moments[0].sigma_x.powi(2), s2) < ROUTE1_ITERATION);
    assert!(rel(mu, -0.21033888) < 1e-7 && rel(s2, 0.61796483) < 1e-7);
    assert!(rel(r.output_means[0], mu) < ROUTE1_ITERATION);
    let st = WhiteNoiseOscillator::from_model(&model, &exc)
        .unwrap()
        .stationary()
        .unwrap();
    assert!(rel(st.mean, -0.16798343) < 1e-7 && rel(st.variance, 0.74647609) < 1e-7);
}

/// The mean shift of an asymmetric damper (jacking), route 1 against its Gaussian closed form: for
/// m y″ + F_d(y′) + k y = f with white f (acceleration density S₀ = S_f/m²), the stationary mean equation
/// k μ = −E[F_d] is exact and E[y′] = 0; a Gaussian y′ gives E[F_d] = (c_r − c_c)σ_v/√(2π) with
/// σ_v² = πS₀m/c̄, c̄ = (c_r + c_c)/2: μ = −(c_r − c_c)σ_v/(√(2π)k). m = k = 1, c_r = 0.6, c_c = 0.2,
/// S₀ = 1/π: μ = −0.4√2.5/√(2π) = −0.252313 (research notes, printed to 6 digits).
#[test]
fn route1_jacking_matches_the_gaussian_closed_form() {
    let (model, exc) = oscillator(
        vec![("damper", Arc::new(BilinearDamper::new(0.6, 0.2).unwrap()))],
        0.0,
        1.0 / PI,
    );
    let r = route1(&model, &exc);
    let sv = (PI * (1.0 / PI) / 0.4f64).sqrt();
    let mu = -0.4 * sv / (2.0 * PI).sqrt();
    assert!(rel(r.mean_q[0], mu) < ROUTE1_ITERATION, "{} vs {mu}", r.mean_q[0]);
    assert!(rel(mu, -0.252313) < 5e-6);
    assert!(rel(r.moments[0].sigma_v, sv) < ROUTE1_ITERATION);
}

/// Zero nonlinearity gives the linear answers bit for bit: a quarter car whose damper is a bilinear damper
/// with equal coefficients, plus a cubic spring with k₃ = 0 and friction of zero force, has route 1's
/// statistics identical to the linear car's (the equivalent system is the linear part itself).
#[test]
fn zero_nonlinearity_is_the_linear_model_bit_for_bit() {
    use stochvib::models::quarter_car::QuarterCar;
    let road = Arc::new(stochvib::spectrum::PowerLaw::iso_class(stochvib::spectrum::IsoClass::C).unwrap());
    let exc = Excitation::road(road, 20.0, &[0.0]).unwrap();
    let car = common::passenger_quarter_car();
    let linear = car.system().unwrap();
    let base = QuarterCar {
        suspension_damping: 0.0,
        ..car
    }
    .build()
    .unwrap()
    .system()
    .unwrap();
    let across = |name: &str, law: Arc<dyn ForceLaw>| NonlinearElement {
        name: name.into(),
        law,
        point: vec![1.0, 0.0],
        to: Attach::Point(vec![0.0, 1.0]),
    };
    let model = NonlinearModel::new(
        &base,
        vec![
            across("damper", Arc::new(BilinearDamper::new(1.5e3, 1.5e3).unwrap())),
            across("cubic", Arc::new(CubicSpring::new(0.0, 0.0).unwrap())),
            across("friction", Arc::new(CoulombFriction::new(0.0).unwrap())),
        ],
    )
    .unwrap();
    assert!(model.is_linear());
    let r = route1(&model, &exc);
    let st = r.output_statistics(&exc, &Default::default()).unwrap();
    for (i, s) in st.iter().enumerate() {
        let l = analyze_output(&linear, &exc, i).unwrap();
        assert_eq!(s.variance.map(f64::to_bits), l.variance.map(f64::to_bits), "output {i}");
        assert_eq!(s.lambda2.map(f64::to_bits), l.lambda2.map(f64::to_bits), "output {i}");
        assert_eq!(s.mean, Some(0.0));
    }
}

/// Route 1 reports non-convergence with its reason: friction the excitation cannot overcome (σ_v → 0), and
/// a softening spring whose Gaussian equivalent loses its stiffness.
#[test]
fn route1_non_convergence_is_an_outcome_with_a_reason() {
    // friction 100× the force level: the element sticks
    let (model, exc) = oscillator(
        vec![("friction", Arc::new(CoulombFriction::new(100.0).unwrap()))],
        0.2,
        0.2 / PI,
    );
    match linearize(&model, &exc, &Route1Options::default()).unwrap() {
        Route1Outcome::NotConverged { reason, advice, .. } => {
            assert!(reason.contains("stick") || reason.contains("settle"), "{reason}");
            assert!(advice.contains("route 2"), "{advice}");
        }
        Route1Outcome::Converged(r) => panic!("sticking friction converged: {:?}", r.moments),
    }
    // softening: k₃ = −1 with σ₀² = 1: k_eq = 1 − 3σ² < 0 has no Gaussian equivalent
    let (model, exc) = oscillator(
        vec![("soft", Arc::new(CubicSpring::new(0.0, -1.0).unwrap()))],
        0.2,
        0.2 / PI,
    );
    match linearize(&model, &exc, &Route1Options::default()).unwrap() {
        Route1Outcome::NotConverged { reason, .. } => {
            assert!(reason.contains("stationary") || reason.contains("settle"), "{reason}")
        }
        Route1Outcome::Converged(r) => panic!("softening spring converged: {:?}", r.moments),
    }
    assert!(WhiteNoiseOscillator::from_model(&model, &exc)
        .unwrap()
        .stationary()
        .is_err());
}

/// A weakly softening spring (k₃ = −0.01 with k = 1, σ₀ = 1) has a converged Gaussian equivalent but no
/// stationary density: V(x) = x²/2 − 0.01x⁴/4 rises to a barrier at x_b = √(k/|k₃|) = 10 of height
/// V_b = k²/(4|k₃|) = 25 and falls without bound beyond it. β = c/(πS_f) = 1 here, so route 3 must say it
/// does not apply, naming the barrier: βV = 25 at |x| = 10 m (6 significant digits as printed).
#[test]
fn route3_softening_spring_names_its_barrier() {
    let (model, exc) = duffing(-0.01);
    let r = route1(&model, &exc);
    assert!(r.moments[0].sigma_x.is_finite());
    let e = WhiteNoiseOscillator::from_model(&model, &exc)
        .unwrap()
        .stationary()
        .expect_err("a softening potential has no normalisable density");
    let text = e.to_string();
    assert!(text.contains("barrier of βV = 25 at x = "), "{text}");
    assert!(text.contains("x = -10 m") || text.contains("x = 10 m"), "{text}");
}

/// The splitting integrator is second order on a problem with a known answer: the free oscillation
/// x″ + x + κ(x − d)₊ = 0 from x = 0, ẋ = V > d. Outside contact x = V sin t, which reaches d at
/// t₁ = arcsin(d/V) and spends π + 2t₁ of each period below d; in contact x″ + (1+κ)x = κd, an oscillation
/// of ω_c = √(1+κ) about x_c = κd/(1+κ) from x = d with ẋ = v_d = √(V² − d²), which returns to d after
/// (π − 2θ)/ω_c, tan θ = ω_c(d − x_c)/v_d. So T = π + 2 arcsin(d/V) + (π − 2θ)/ω_c and the state after T
/// is (0, V). V = 1, d = ½, κ = 100: T = 4.489970231227194 (research notes, DOP853 with event location:
/// 4.48997023). The error envelope (worst over n … n+9 steps per period) falls by at least
/// 8^SPLITTING_MIN_ORDER from n = 100 to 800; with a stop that is never reached the scheme is the exact
/// linear flow.
#[test]
fn splitting_integrator_is_second_order_through_contact() {
    let (v, d, kappa) = (1.0f64, 0.5f64, 100.0f64);
    let wc = (1.0 + kappa).sqrt();
    let xc = kappa * d / (1.0 + kappa);
    let vd = (v * v - d * d).sqrt();
    let theta = (wc * (d - xc) / vd).atan();
    let period = PI + 2.0 * (d / v).asin() + (PI - 2.0 * theta) / wc;
    assert!(rel(period, 4.489970231227194) < 1e-14);
    let lin = MassSpringDamper {
        mass: 1.0,
        stiffness: 1.0,
        damping: 0.0,
        drive: Drive::Force,
    }
    .build()
    .unwrap();
    let stop = NonlinearElement {
        name: "stop".into(),
        law: Arc::new(BumpStop::new(Some((d, kappa)), None).unwrap()),
        point: vec![1.0],
        to: Attach::Ground,
    };
    let model = NonlinearModel::new(&lin, vec![stop]).unwrap();
    let envelope = |n: usize| {
        (n..n + 10)
            .map(|m| {
                let (q, qd) = free_response(&model, &[0.0], &[v], period / m as f64, m).unwrap();
                q[0].hypot(qd[0] - v)
            })
            .fold(0.0, f64::max)
    };
    let (e1, e8) = (envelope(100), envelope(800));
    let order = (e1 / e8).log2() / 3.0;
    assert!(
        order >= SPLITTING_MIN_ORDER,
        "observed order {order:.3} (errors {e1:.3e}, {e8:.3e})"
    );
    assert!(e8 < 1e-3, "{e8}");
    // below the clearance: exact (the kicks are zero)
    let (q, qd) = free_response(&model, &[0.0], &[0.4], 0.1, 50).unwrap();
    assert!((q[0] - 0.4 * 5.0f64.sin()).abs() < 1e-12 && (qd[0] - 0.4 * 5.0f64.cos()).abs() < 1e-12);
}

/// Every law's [`Kernel`](stochvib::nonlinear::Kernel) (route 2's closed forms with the constants of a step)
/// gives the bits of the law's own trait methods, at and around the kinks and at ±0, one point at a time and
/// lane by lane (`Kernel::impulses`, the realizations route 2 steps in lockstep).
#[test]
fn kernels_give_the_bits_of_their_laws() {
    let laws: Vec<Box<dyn ForceLaw>> = vec![
        Box::new(BumpStop::new(Some((0.07, 3e5)), Some((0.05, 2e5))).unwrap()),
        Box::new(BumpStop::new(None, Some((0.05, 2e5))).unwrap()),
        Box::new(TyreContact::new(2e5, 3335.4).unwrap()),
        Box::new(BilinearDamper::new(2200.0, 800.0).unwrap()),
        Box::new(BilinearDamper::new(800.0, 2200.0).unwrap()),
        Box::new(BilinearDamper::new(1.0, 1.0).unwrap()),
    ];
    let (kappa, tau) = (1.0 / 300.0 + 1.0 / 40.0, 0.5 * 0.0027);
    let points = [
        -0.2, -0.05, -0.049, -1e-9, -0.0, 0.0, 1e-9, 0.0166, 0.0167, 0.07, 0.0700001, 0.3,
    ];
    for law in &laws {
        let k = law.kernel(kappa, tau).expect("a kernel");
        for &x in &points {
            for &v in &points {
                assert_eq!(
                    k.force(x, v).to_bits(),
                    law.force(x, v).to_bits(),
                    "{law:?} F({x}, {v})"
                );
                let (a, b) = (k.impulse(x, v), law.impulse(x, v, kappa, tau));
                assert_eq!(a.to_bits(), b.to_bits(), "{law:?} J({x}, {v})");
            }
            assert_eq!(k.engaged(x), law.engaged(x), "{law:?} engaged({x})");
            // the lanes of realizations stepped in lockstep: the bits of the law, lane by lane
            let (mut by_v, mut by_x) = ([0.0; 12], [0.0; 12]);
            k.impulses(&[x; 12], &points, &mut by_v);
            k.impulses(&points, &[x; 12], &mut by_x);
            for (l, &p) in points.iter().enumerate() {
                let (a, b) = (law.impulse(x, p, kappa, tau), law.impulse(p, x, kappa, tau));
                assert_eq!(by_v[l].to_bits(), a.to_bits(), "{law:?} lanes J({x}, {p})");
                assert_eq!(by_x[l].to_bits(), b.to_bits(), "{law:?} lanes J({p}, {x})");
            }
        }
    }
}

/// Route 1 computes the variance of each element's deflection and rate once per placement (the damper and
/// the bump stop across one suspension share theirs) and the distinct ones side by side. Neither may change
/// a number: every element's σ_x and σ_v are, bit for bit, the square roots of its own output rows'
/// variances on the final equivalent system (`output_variance`, one at a time on this thread), and route 1
/// and its output statistics are the same bits in a pool of one thread and of two.
#[test]
fn route1_shares_a_placement_and_gives_the_bits_on_any_threads() {
    use stochvib::system::FrequencyResponse as _;
    let root = common::root();
    let sc = stochvib::scenario::load_scenario(&root.join("data/quarter-car-bump-stops.toml"), &root.join("spectra"))
        .unwrap();
    let model = sc.nonlinear_model().expect("a nonlinear scenario");
    let names: Vec<&str> = model.elements().iter().map(|e| e.name.as_str()).collect();
    assert_eq!(names, ["damper", "stops", "tyre_contact"], "the scenario's elements");
    let exc = &sc.excitation;
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let r = route1(model, exc);
            let st = r.output_statistics(exc, &Default::default()).unwrap();
            (r, st)
        })
    };
    let ((one, st1), (two, st2)) = (run(1), run(2));
    let bits = |r: &Route1| -> Vec<u64> {
        let m = r.moments.iter().flat_map(|m| [m.mean_x, m.sigma_x, m.sigma_v]);
        let c = r
            .coefficients
            .iter()
            .flat_map(|q| [q.mean_force, q.stiffness, q.damping]);
        m.chain(c)
            .chain(r.output_means.iter().copied())
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(&one), bits(&two), "route 1 on 1 and 2 threads");
    assert_eq!(one.iterations, two.iterations);
    assert_eq!(
        format!("{st1:?}"),
        format!("{st2:?}"),
        "output statistics on 1 and 2 threads"
    );
    // each element against its own rows (the stop's rows are the damper's: the same points)
    let p = model.linear().outputs().len();
    let sigma = |row: usize| {
        let (v, _) = output_variance(&one.equivalent, exc, row, &Default::default()).unwrap();
        v.max(0.0).sqrt()
    };
    for (i, (e, m)) in model.elements().iter().zip(&one.moments).enumerate() {
        assert_eq!(m.sigma_x.to_bits(), sigma(p + 2 * i).to_bits(), "{}: σ_x", e.name);
        assert_eq!(m.sigma_v.to_bits(), sigma(p + 2 * i + 1).to_bits(), "{}: σ_v", e.name);
    }
    assert_eq!(one.moments[0].sigma_x.to_bits(), one.moments[1].sigma_x.to_bits());
    assert_ne!(one.moments[0].sigma_x.to_bits(), one.moments[2].sigma_x.to_bits());
}

/// A failure of a shared row names the element that reads it. A base-driven oscillator under white base
/// displacement has an absolute displacement of finite variance (|H|² ~ ω⁻²) and an absolute velocity of
/// infinite variance (ω²|H|² → const): a cubic spring to the ground reads only σ_x, a quadratic damper at
/// the same place reads σ_v too, computed for the spring's rate row. The reason must name the damper's own
/// output (`damper:v`), as when each element computed its own rows, and not the spring's.
#[test]
fn route1_failure_on_a_shared_row_names_the_element_that_reads_it() {
    let lin = MassSpringDamper {
        mass: 1.0,
        stiffness: 1.0,
        damping: 0.2,
        drive: Drive::Base,
    }
    .build()
    .unwrap()
    .with_output("x", Quantity::Displacement(vec![1.0]))
    .unwrap();
    let element = |name: &str, law: Arc<dyn ForceLaw>| NonlinearElement {
        name: name.into(),
        law,
        point: vec![1.0],
        to: Attach::Ground,
    };
    let model = NonlinearModel::new(
        &lin,
        vec![
            element("spring", Arc::new(CubicSpring::new(0.0, 0.1).unwrap())),
            element("damper", Arc::new(QuadraticDamper::new(0.05, 0.05).unwrap())),
        ],
    )
    .unwrap();
    let white = Arc::new(RationalSpectrum::new(vec![0.01], vec![1.0], Domain::Temporal).unwrap());
    let exc = Excitation::single(white, 0.0).unwrap();
    match linearize(&model, &exc, &Route1Options::default()).unwrap() {
        Route1Outcome::NotConverged { reason, .. } => {
            assert!(reason.starts_with("`damper:v`"), "{reason}");
            assert!(!reason.contains("spring:v"), "{reason}");
        }
        Route1Outcome::Converged(r) => panic!("an infinite velocity variance converged: {:?}", r.moments),
    }
}
