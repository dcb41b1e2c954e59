//! Systems and response statistics: the three variance methods against each other and against closed
//! forms derived in the comments; divergence; bad input.

use crate::common;
use common::rel;
use common::tolerance::{EXACT, FACTORISATION, PRINTED_6_DIGITS, QUADRATURE, SMALL_DECOMPOSITION};
use nalgebra::DMatrix;
use proptest::prelude::*;
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::response::{
    analyze_output, band_variance, variance_integral_table, variance_lyapunov, variance_quadrature, ExactEvaluator,
    Excitation, PointStatistics, VarianceMethod,
};
use stochvib::spectrum::{Domain, ExpCosine, Exponential, GaussCosineParameters, RationalSpectrum, Spectrum};
use stochvib::system::{
    Attach, Drive, Element, FrequencyResponse, MassSpringDamper, Mdof, OutputInfo, Quantity, StateSpace,
    TransferFunction,
};
use stochvib::Error;

/// Ideal white noise of two-sided level S₀: N(ω²) = S₀, D(ω²) = 1.
fn white(s0: f64) -> Arc<dyn Spectrum> {
    Arc::new(RationalSpectrum::new(vec![s0], vec![1.0], Domain::Temporal).unwrap())
}

fn sdof(wn: f64, zeta: f64) -> TransferFunction {
    // ẍ + 2ζω ẋ + ω² x = u
    TransferFunction::new(
        vec![1.0],
        vec![wn * wn, 2.0 * zeta * wn, 1.0],
        OutputInfo::new("x", "m"),
    )
    .unwrap()
}

/// SDOF oscillator under ideal white noise of two-sided level S₀: σ² = π S₀ / (2 ζ ω_n³)
/// (∫|1/(ω_n² − ω² + 2iζω_nω)|² dω = π/(2ζω_n³), Crandall & Mark; Newland eq. 7.20 with S₀ two-sided).
#[test]
fn sdof_white_noise_closed_form() {
    for (wn, zeta, s0) in [(10.0, 0.05, 2.0), (26.4575, 0.2, 0.0909), (3.0, 0.7, 1e-3)] {
        let sys = sdof(wn, zeta);
        let exc = Excitation::single(white(s0), 0.0).unwrap();
        let expected = PI * s0 / (2.0 * zeta * wn.powi(3));
        let l = variance_lyapunov(&sys, &exc, 0).unwrap();
        assert!(
            rel(l.variance, expected) < FACTORISATION,
            "lyap {} vs {expected}",
            l.variance
        );
        let t = variance_integral_table(&sys, &exc, 0, 0).unwrap();
        assert!(rel(t, expected) < FACTORISATION, "table {t} vs {expected}");
        let q = variance_quadrature(&sys, &exc, 0).unwrap();
        assert!(rel(q.value, expected) < QUADRATURE, "quad {} vs {expected}", q.value);
        // velocity variance πS₀/(2ζω_n) = λ₂
        assert!(rel(l.lambda2.unwrap(), PI * s0 / (2.0 * zeta * wn)) < FACTORISATION);
        // λ₄ (acceleration variance) diverges for white noise through an SDOF displacement
        assert!(matches!(l.lambda4, Err(Error::Divergent { .. })));
    }
}

/// The keys of the top-level object of compact JSON `text`, in their order (as written, escapes kept).
fn top_level_keys(text: &str) -> Vec<String> {
    let (mut keys, mut key) = (Vec::new(), String::new());
    let (mut depth, mut in_string, mut escaped, mut at_key) = (0, false, false, false);
    for c in text.chars() {
        if in_string {
            if !escaped && c == '"' {
                in_string = false;
                if at_key {
                    keys.push(std::mem::take(&mut key));
                    at_key = false;
                }
            } else {
                escaped = !escaped && c == '\\';
                if at_key {
                    key.push(c);
                }
            }
            continue;
        }
        match c {
            '"' => in_string = true,
            '{' | '[' => {
                depth += 1;
                at_key = c == '{' && depth == 1;
            }
            '}' | ']' => depth -= 1,
            ',' => at_key = depth == 1,
            _ => {}
        }
    }
    keys
}

/// An analysis and a parameter study carry one statistics type, [`PointStatistics`]: under ideal white
/// noise an SDOF oscillator has σ² = πS₀/(2ζω_n³) and λ₂ = πS₀/(2ζω_n) (closed forms of
/// `sdof_white_noise_closed_form`); the analysis's statistics (`st.values`, read through `st.mean`,
/// `st.variance`, `st.bounds(3.0)`) and the sweep evaluator's give them both, each naming its route (the
/// analysis's reference is the first exact route, Lyapunov; the evaluator takes the integral table). The
/// analysis's JSON (`analyze --json`) stays flat in its order, without the statistics' own `method`.
#[test]
fn analysis_and_sweep_share_one_statistics_type() {
    let (wn, zeta, s0): (f64, f64, f64) = (10.0, 0.05, 2.0);
    let (variance, lambda2) = (PI * s0 / (2.0 * zeta * wn.powi(3)), PI * s0 / (2.0 * zeta * wn));
    let sys = sdof(wn, zeta);
    let exc = Excitation::single(white(s0), 0.0).unwrap();
    let st = analyze_output(&sys, &exc, 0).unwrap();
    let fast = ExactEvaluator::new(&exc).evaluate(&sys, &exc, &[0]).unwrap()[0];
    let point: PointStatistics = st.values;
    assert_eq!(
        (point.method, fast.method),
        (VarianceMethod::Lyapunov, VarianceMethod::IntegralTable)
    );
    for p in [point, fast] {
        assert_eq!(p.mean, Some(0.0));
        assert!(rel(p.variance.unwrap(), variance) < FACTORISATION, "{p:?}");
        assert!(rel(p.lambda2.unwrap(), lambda2) < FACTORISATION, "{p:?}");
    }
    assert_eq!(
        (st.variance, st.sigma, st.bounds(3.0)),
        (point.variance, point.sigma(), point.bounds(3.0))
    );
    assert_eq!(st.zero_upcrossing_rate, point.zero_upcrossing_rate());
    let json = serde_json::to_string(&st).unwrap();
    let order = [
        "name",
        "unit",
        "mean",
        "methods",
        "variance",
        "variance_outcome",
        "sigma",
        "lambda2",
        "lambda2_outcome",
        "lambda4",
        "lambda4_outcome",
        "zero_upcrossing_rate",
        "bandwidth",
    ];
    assert_eq!(top_level_keys(&json), order, "{json}");
    assert_eq!(
        top_level_keys(r#"{"a":{"b":[1,{"c":2}]},"d\"e":"f,\"g","h":3}"#),
        ["a", "d\\\"e", "h"]
    );
}

/// Conveyor idler of textbook Example 8.1 (m = 100 kg, c = 70 kN/m, ζ = 0.2, σ_F = 2 kN, α = 0.5 1/s):
/// exact σ_y² = (D_F/m²)(α + 2ζω₀)/(2ζω₀³(ω₀² + α² + 2αζω₀)) (derived by hand with the I₃ entry of the integral table),
/// σ_y = 0.0291235 m (the closed form evaluated outside the crate with Python; scipy's Lyapunov solution gives
/// the same, tests/models_ch8.rs); the three methods must reproduce the closed form.
#[test]
fn exponential_load_through_sdof_closed_form() {
    let (m, c, zeta, df, alpha): (f64, f64, f64, f64, f64) = (100.0, 7.0e4, 0.2, 4.0e6, 0.5);
    let w0 = (c / m).sqrt();
    let sys = TransferFunction::new(
        vec![1.0 / m],
        vec![w0 * w0, 2.0 * zeta * w0, 1.0],
        OutputInfo::new("y", "m"),
    )
    .unwrap();
    let load = Arc::new(Exponential::new(df, alpha, Domain::Temporal).unwrap());
    let exc = Excitation::single(load, 1.0e4).unwrap();
    let expected = df / (m * m) * (alpha + 2.0 * zeta * w0)
        / (2.0 * zeta * w0.powi(3) * (w0 * w0 + alpha * alpha + 2.0 * alpha * zeta * w0));
    let st = analyze_output(&sys, &exc, 0).unwrap();
    for mv in &st.methods {
        let v = mv
            .value()
            .unwrap_or_else(|| panic!("{:?}: {:?}", mv.method, mv.outcome));
        assert!(
            rel(v, expected) < FACTORISATION.max(QUADRATURE),
            "{:?}: {v} vs {expected}",
            mv.method
        );
    }
    assert!(rel(st.sigma.unwrap(), 0.0291235) < PRINTED_6_DIGITS);
    // mean M_y = M_F / c
    assert!(rel(st.mean.unwrap(), 1.0e4 / c) < EXACT);
    // velocity variance (D_F/m²) α / (2ζω₀(ω₀² + α² + 2αζω₀))
    let v2 = df / (m * m) * alpha / (2.0 * zeta * w0 * (w0 * w0 + alpha * alpha + 2.0 * alpha * zeta * w0));
    assert!(rel(st.lambda2.unwrap(), v2) < FACTORISATION);
}

/// Two wheels on one track through first-order wheel filters W = 1/(1 + Ts), mixed (1 − p, p):
/// D_y = ((1−p)² + p²) D_Z + 2p(1−p) R_Z(τ), with b = 1/T, D_Z = D b/(α + b),
/// R_Z(τ) = D (b² e^{−ατ} − αb e^{−bτ})/(b² − α²) (residues of S_x|W|² e^{iωτ}; textbook (8.47)–(8.49)).
/// Only quadrature handles the delay; the exact methods must say they do not apply.
#[test]
fn two_wheel_delayed_input_closed_form() {
    let (d, alpha, t, p, tau) = (2.0, 1.5, 0.4, 0.3, 0.7);
    let b = 1.0 / t;
    // two inputs, one output y = (1−p) W u₁ + p W u₂: state per wheel
    let a = DMatrix::from_row_slice(2, 2, &[-b, 0.0, 0.0, -b]);
    let bm = DMatrix::from_row_slice(2, 2, &[b, 0.0, 0.0, b]);
    let c = DMatrix::from_row_slice(1, 2, &[1.0 - p, p]);
    let sys = StateSpace::new(a, bm, c, None, None, vec![OutputInfo::new("y", "m")]).unwrap();
    let x = Arc::new(Exponential::new(d, alpha, Domain::Temporal).unwrap());
    let exc = Excitation::track(x, vec![0.0, tau], vec![1.0, 1.0], 0.0).unwrap();
    let dz = d * b / (alpha + b);
    let rz = d * (b * b * (-alpha * tau).exp() - alpha * b * (-b * tau).exp()) / (b * b - alpha * alpha);
    let expected = ((1.0 - p).powi(2) + p * p) * dz + 2.0 * p * (1.0 - p) * rz;
    let q = variance_quadrature(&sys, &exc, 0).unwrap();
    assert!(rel(q.value, expected) < QUADRATURE, "{} vs {expected}", q.value);
    assert!(variance_lyapunov(&sys, &exc, 0).is_err());
    assert!(variance_integral_table(&sys, &exc, 0, 0).is_err());
    // with τ = 0 the exact methods apply and agree: D_y = D_Z (weights sum to 1)
    let x = Arc::new(Exponential::new(d, alpha, Domain::Temporal).unwrap());
    let exc0 = Excitation::track(x, vec![0.0, 0.0], vec![1.0, 1.0], 0.0).unwrap();
    assert!(rel(variance_lyapunov(&sys, &exc0, 0).unwrap().variance, dz) < FACTORISATION);
}

fn base_excited(m: f64, k: f64, b: f64) -> Mdof {
    MassSpringDamper {
        mass: m,
        stiffness: k,
        damping: b,
        drive: Drive::Base,
    }
    .build()
    .unwrap()
    .with_output("x", Quantity::Displacement(vec![1.0]))
    .unwrap()
    .with_output("x_acc", Quantity::Acceleration(vec![1.0]))
    .unwrap()
    .with_output("travel", Quantity::Deflection(0))
    .unwrap()
}

/// A damped base-excited mass under a type-1 road: S_u ~ ω⁻² and |H_acc|² ~ (bω/m)², so S_acc tends to a
/// constant and the acceleration variance is infinite: every method says so, none returns a number.
/// A band-limited variance is finite and agrees with the displacement route: over any band
/// ∫ω⁴ S_x = ∫ S_acc.
#[test]
fn acceleration_divergence_detected() {
    let sys = base_excited(100.0, 1.0e4, 300.0);
    let road = Arc::new(Exponential::new(1e-4, 2.0, Domain::Temporal).unwrap());
    let exc = Excitation::single(road, 0.0).unwrap();
    let st = analyze_output(&sys, &exc, 1).unwrap();
    assert!(st.variance.is_none() && st.sigma.is_none());
    assert!(
        st.variance_outcome.describe().contains("band"),
        "{:?}",
        st.variance_outcome
    );
    assert!(matches!(
        variance_quadrature(&sys, &exc, 1),
        Err(Error::Divergent { .. })
    ));
    assert!(matches!(variance_lyapunov(&sys, &exc, 1), Err(Error::Divergent { .. })));
    assert!(matches!(
        variance_integral_table(&sys, &exc, 1, 0),
        Err(Error::Divergent { .. })
    ));
    let band = band_variance(&sys, &exc, 1, 0.0, 2.0 * PI * 80.0).unwrap();
    assert!(band.value.is_finite() && band.value > 0.0);
    // the displacement and the travel are finite and the three methods agree
    for i in [0, 2] {
        let st = analyze_output(&sys, &exc, i).unwrap();
        let r = st.variance.unwrap();
        for mv in &st.methods {
            assert!(
                rel(mv.value().unwrap(), r) < QUADRATURE,
                "{:?} {:?}",
                mv.method,
                mv.outcome
            );
        }
    }
    // with a two-pole input, S = 1/((1 + ω²)(4 + ω²)) ~ ω⁻⁴, the acceleration variance is finite
    let smooth = Arc::new(RationalSpectrum::new(vec![1.0], vec![4.0, 5.0, 1.0], Domain::Temporal).unwrap());
    let exc2 = Excitation::single(smooth, 0.0).unwrap();
    let st = analyze_output(&sys, &exc2, 1).unwrap();
    let r = st.variance.unwrap();
    for mv in &st.methods {
        assert!(rel(mv.value().unwrap(), r) < QUADRATURE, "{:?}", mv.method);
    }
}

/// The MDOF direct dynamic-stiffness response equals its state-space realisation (the oracle pair).
#[test]
fn mdof_direct_response_matches_state_space() {
    let sys = base_excited(100.0, 1.0e4, 300.0);
    let ss = sys.state_space().unwrap();
    for w in [0.0, 0.3, 7.0, 10.0, 55.0, 400.0] {
        let a = sys.response(w);
        let b = ss.response(w);
        for (x, y) in a.iter().zip(b.iter()) {
            assert!(
                (x - y).norm() <= SMALL_DECOMPOSITION * x.norm().max(1.0),
                "ω = {w}: {x} vs {y}"
            );
        }
    }
}

/// Bad input is rejected with errors, never a panic.
#[test]
fn bad_systems_rejected() {
    // unstable system
    let unstable = TransferFunction::new(vec![1.0], vec![-1.0, 1.0], OutputInfo::new("x", "m")).unwrap();
    let exc = Excitation::single(Arc::new(Exponential::new(1.0, 1.0, Domain::Temporal).unwrap()), 0.0).unwrap();
    assert!(matches!(
        variance_lyapunov(&unstable, &exc, 0),
        Err(Error::InvalidParameter { .. })
    ));
    // singular mass matrix
    let z = DMatrix::zeros(2, 2);
    let r = Mdof::new(
        &[("a", "m"), ("b", "m")],
        DMatrix::from_diagonal_element(2, 2, 0.0),
        z.clone(),
        z.clone(),
        DMatrix::zeros(2, 0),
        DMatrix::zeros(2, 0),
        DMatrix::zeros(2, 0),
    );
    assert!(matches!(r, Err(Error::InvalidParameter { .. })));
    // zero mass of a coordinate
    assert!(Mdof::from_elements(&[("x", "m")], &[0.0], vec![], 0, &[]).is_err());
    // mismatched dimensions
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -1.0]);
    assert!(StateSpace::new(
        a.clone(),
        DMatrix::zeros(3, 1),
        DMatrix::zeros(1, 2),
        None,
        None,
        vec![OutputInfo::new("y", "m")]
    )
    .is_err());
    assert!(StateSpace::new(a, DMatrix::zeros(2, 1), DMatrix::zeros(1, 2), None, None, vec![]).is_err());
    // excitation with the wrong number of inputs
    let two = Excitation::track(
        Arc::new(Exponential::new(1.0, 1.0, Domain::Temporal).unwrap()),
        vec![0.0, 0.1],
        vec![1.0, 1.0],
        0.0,
    )
    .unwrap();
    assert!(variance_quadrature(&sdof(1.0, 0.1), &two, 0).is_err());
    // spatial spectrum straight into a temporal system
    let spatial = Arc::new(Exponential::new(1.0, 1.0, Domain::Spatial).unwrap());
    assert!(Excitation::single(spatial, 0.0).is_err());
}

/// Modal analysis: two equal masses m joined by k and each to ground by k: ω² = k/m and 3k/m
/// (textbook chapter 2.4, symmetric/antisymmetric modes); a free–free pair has a rigid mode ω = 0.
#[test]
fn modal_analysis_closed_forms() {
    let (m, k) = (2.0, 50.0);
    let els = vec![
        Element {
            name: "a".into(),
            point: vec![1.0, 0.0],
            to: Attach::Ground,
            stiffness: k,
            damping: 0.0,
        },
        Element {
            name: "b".into(),
            point: vec![0.0, 1.0],
            to: Attach::Ground,
            stiffness: k,
            damping: 0.0,
        },
        Element {
            name: "c".into(),
            point: vec![1.0, 0.0],
            to: Attach::Point(vec![0.0, 1.0]),
            stiffness: k,
            damping: 0.0,
        },
    ];
    let sys = Mdof::from_elements(&[("x1", "m"), ("x2", "m")], &[m, m], els, 0, &[]).unwrap();
    let (w, phi) = sys.modes().unwrap();
    assert!(rel(w[0], (k / m).sqrt()) < EXACT && rel(w[1], (3.0 * k / m).sqrt()) < EXACT);
    // mass-normalised: φᵀ M φ = I
    let g = phi.transpose() * sys.mass() * &phi;
    assert!((g - DMatrix::identity(2, 2)).amax() < EXACT);
    let free = vec![Element {
        name: "c".into(),
        point: vec![1.0, -1.0],
        to: Attach::Ground,
        stiffness: k,
        damping: 0.0,
    }];
    let sys = Mdof::from_elements(&[("x1", "m"), ("x2", "m")], &[m, m], free, 0, &[]).unwrap();
    let (w, _) = sys.modes().unwrap();
    assert_eq!(w[0], 0.0);
    assert!(rel(w[1], (2.0 * k / m).sqrt()) < EXACT);
}

/// Random stable state-space systems (modal blocks with random ζ, ω) with random rational inputs:
/// Lyapunov, integral table and quadrature agree.
fn random_case(ws: &[f64], zs: &[f64], gains: &[f64], a_in: f64, b_in: f64) -> (StateSpace, Excitation) {
    let n = 2 * ws.len();
    let mut a = DMatrix::zeros(n, n);
    let mut b = DMatrix::zeros(n, 1);
    let mut c = DMatrix::zeros(1, n);
    for (k, ((w, z), g)) in ws.iter().zip(zs).zip(gains).enumerate() {
        a[(2 * k, 2 * k + 1)] = 1.0;
        a[(2 * k + 1, 2 * k)] = -w * w;
        a[(2 * k + 1, 2 * k + 1)] = -2.0 * z * w;
        b[(2 * k + 1, 0)] = 1.0;
        c[(0, 2 * k)] = *g;
        c[(0, 2 * k + 1)] = 0.3 * g;
    }
    let sys = StateSpace::new(a, b, c, None, None, vec![OutputInfo::new("y", "m")]).unwrap();
    let input: Arc<dyn Spectrum> = Arc::new(
        ExpCosine {
            variance: 1.0,
            alpha: a_in,
            beta: b_in,
            domain: Domain::Temporal,
        }
        .build()
        .unwrap(),
    );
    (sys, Excitation::single(input, 0.0).unwrap())
}

proptest! {
    #![proptest_config(crate::common::proptest_config(48))]
    #[test]
    fn prop_three_methods_agree(
        w1 in 0.5f64..20.0, w2 in 0.5f64..20.0, z1 in 0.02f64..0.9, z2 in 0.02f64..0.9,
        g1 in -2.0f64..2.0, g2 in 0.1f64..2.0, a_in in 0.1f64..5.0, b_in in 0.0f64..10.0,
    ) {
        let (sys, exc) = random_case(&[w1, w2], &[z1, z2], &[g1, g2], a_in, b_in);
        let l = variance_lyapunov(&sys, &exc, 0).unwrap().variance;
        let t = variance_integral_table(&sys, &exc, 0, 0).unwrap();
        let q = variance_quadrature(&sys, &exc, 0).unwrap().value;
        prop_assert!(rel(l, t) < FACTORISATION, "lyap {} table {}", l, t);
        prop_assert!(rel(l, q) < FACTORISATION, "lyap {} quad {}", l, q);
    }
}

/// A non-rational input (type 4) has no exact method; quadrature still answers and the exact methods say
/// why they do not apply.
#[test]
fn non_rational_input_uses_quadrature() {
    let sys = sdof(5.0, 0.1);
    let exc = Excitation::single(
        Arc::new(
            GaussCosineParameters {
                variance: 1.0,
                alpha: 2.0,
                beta: 5.0,
                domain: Domain::Temporal,
            }
            .build()
            .unwrap(),
        ),
        0.0,
    )
    .unwrap();
    let st = analyze_output(&sys, &exc, 0).unwrap();
    assert!(st.variance.is_some());
    assert!(st.methods[0].outcome.describe().contains("not rational"));
    assert!(st.methods[2].value().is_some());
}

/// Rice crossing statistics of an SDOF oscillator under white noise: λ₂/λ₀ = ω_n² exactly
/// (λ₀ = πS₀/(2ζω_n³), λ₂ = πS₀/(2ζω_n)), so ν₀⁺ = ω_n/(2π); ν_a⁺ = ν₀⁺ e^{−a²/(2σ²)};
/// P(exceed a in T) = 1 − exp(−ν_a⁺T); Davenport's expected largest peak
/// σ(√(2 ln ν₀⁺T) + γ/√(2 ln ν₀⁺T)) with γ = 0.5772156649.
#[test]
fn rice_crossing_rates_sdof_white_noise() {
    let (wn, zeta, s0) = (2.0 * PI * 3.0, 0.05, 0.02);
    let sys = sdof(wn, zeta);
    let exc = Excitation::single(white(s0), 0.0).unwrap();
    let st = analyze_output(&sys, &exc, 0).unwrap();
    let sigma = (PI * s0 / (2.0 * zeta * wn.powi(3))).sqrt();
    let nu0 = wn / (2.0 * PI);
    assert!(rel(st.zero_upcrossing_rate.unwrap(), nu0) < FACTORISATION);
    let a = 2.5 * sigma;
    let nua = nu0 * (-(2.5f64 * 2.5) / 2.0).exp();
    assert!(rel(st.upcrossing_rate(a).unwrap(), nua) < FACTORISATION);
    let t = 600.0;
    assert!(rel(st.exceedance_probability(a, t).unwrap(), 1.0 - (-nua * t).exp()) < FACTORISATION);
    let r = (2.0 * (nu0 * t).ln()).sqrt();
    let peak = sigma * (r + 0.5772156649015329 / r);
    assert!(rel(st.expected_largest_peak(t).unwrap(), peak) < FACTORISATION);
    // bounds are M ± 3σ
    let (lo, hi) = st.bounds(3.0).unwrap();
    assert!(rel(hi, 3.0 * sigma) < FACTORISATION && rel(lo, -3.0 * sigma) < FACTORISATION);
    // white-noise SDOF displacement: λ₄ infinite, so no bandwidth parameter is claimed
    assert!(st.lambda4.is_none() && st.bandwidth.is_none());
}

/// The cross-spectral-matrix route H S_u Hᴴ (dense, general) equals the per-output delayed-sum route used
/// by quadrature, for a two-wheel track with delays (an oracle for the fast path).
#[test]
fn cross_spectral_matrix_matches_fast_path() {
    let two = {
        let a = DMatrix::from_row_slice(2, 2, &[-3.0, 0.0, 1.0, -5.0]);
        let b = DMatrix::from_row_slice(2, 2, &[3.0, 0.0, 0.0, 5.0]);
        let c = DMatrix::from_row_slice(2, 2, &[1.0, 0.5, 0.0, 1.0]);
        StateSpace::new(
            a,
            b,
            c,
            None,
            None,
            vec![OutputInfo::new("p", "m"), OutputInfo::new("q", "m")],
        )
        .unwrap()
    };
    let x = Arc::new(
        ExpCosine {
            variance: 1.0,
            alpha: 0.7,
            beta: 2.0,
            domain: Domain::Temporal,
        }
        .build()
        .unwrap(),
    );
    let exc = Excitation::track(x, vec![0.0, 0.37], vec![1.0, -0.6], 0.0).unwrap();
    for w in [0.0, 0.5, 2.0, 9.0] {
        let h = two.response(w);
        let su = exc.matrix(w);
        let sy = &h * su * h.adjoint();
        for i in 0..2 {
            let fast = stochvib::response::output_density(&two, &exc, i, w);
            assert!(
                (sy[(i, i)].re - fast).abs() <= EXACT * fast.abs().max(1e-300),
                "ω={w} i={i}"
            );
            assert!(sy[(i, i)].im.abs() <= EXACT * fast.abs().max(1e-300));
        }
    }
}
