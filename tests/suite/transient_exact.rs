//! The exact route of non-stationary responses (differential Lyapunov equation by matrix exponentials)
//! against closed forms derived independently of the code: Caughey & Stumpf's oscillator started from
//! rest, first-order systems under ramped white noise, a quarter car accelerating on a w = 2 road (its
//! stationary ends in closed form), and a stationary input through the non-stationary path.

use crate::common;
use crate::common::rel;
use crate::common::tolerance::{
    ADAPTIVE_ROUTE, ERROR_ESTIMATE_FROM_REST, EXACT_TRANSITIONS, PRINTED_8_DIGITS, QUADRATURE, ZERO_BY_CANCELLATION,
};
use nalgebra::DMatrix;
use std::f64::consts::PI;
use std::sync::Arc;
use stochvib::models::quarter_car::QuarterCar;
use stochvib::response::{analyze_output, Excitation};
use stochvib::spectrum::{Domain, Exponential, IsoBound, IsoClass, PowerLaw, Spectrum};
use stochvib::system::{FrequencyResponse, OutputInfo, StateSpace};
use stochvib::transient::{
    input_model, propagate, solve, ConstantAcceleration, Envelope, ExactOptions, FixedSystem, InputModel, ModelAt,
    OutputSeries, SpeedProfile, Start, SystemFamily, TimeVaryingSystem, TransientInput,
};

/// The passenger quarter car (`common::passenger_quarter_car`) accelerating at `acceleration` from 5 to
/// 15 m/s (from t = 2 s) on the textbook's graded dirt road (Sukharev (2012) (8.69): spatial type 1,
/// D = 32 cm², α = 0.16 1/m), started stationary, with its exact route at `times`: the set-up the
/// evolutionary and the road-grid routes are checked against.
pub(crate) struct DirtRoadCar {
    pub mdof: stochvib::system::Mdof,
    pub ss: StateSpace,
    pub road: Arc<dyn Spectrum>,
    pub speed: SpeedProfile,
    pub exact: stochvib::transient::TransientSolution,
}

/// [`DirtRoadCar`] at `acceleration` (m/s²), the exact route evaluated at `times` (s).
pub(crate) fn dirt_road_car(acceleration: f64, times: &[f64]) -> DirtRoadCar {
    let mdof = crate::common::passenger_quarter_car().system().unwrap();
    let ss = mdof.state_space().unwrap().clone();
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(32e-4, 0.16, Domain::Spatial).unwrap());
    let speed = ConstantAcceleration {
        from_m_s: 5.0,
        to_m_s: 15.0,
        acceleration_m_s2: acceleration,
        start_s: 2.0,
    }
    .build()
    .unwrap();
    let model = input_model(road.as_ref(), Some(&speed)).unwrap();
    let exact = solve(
        &system(ss.clone(), model, Envelope::unit()),
        &Start::Stationary,
        times,
        &ExactOptions::default(),
    )
    .unwrap();
    DirtRoadCar {
        mdof,
        ss,
        road,
        speed,
        exact,
    }
}

/// `ss` driven by one input process (gain 1 at every input) as a time-invariant family.
pub(crate) fn system(ss: StateSpace, model: InputModel, envelope: Envelope) -> TimeVaryingSystem {
    let gains = vec![1.0; ss.b.ncols()];
    let fam = Arc::new(FixedSystem::new(ss, None, "test").unwrap());
    TimeVaryingSystem::new(
        fam,
        TransientInput {
            model,
            envelope,
            mean: 0.0,
            gains,
        },
    )
    .unwrap()
}

/// x″ + 2ζω₀x′ + ω₀²x = u, states (x, x′), output x in m.
pub(crate) fn oscillator(w0: f64, zeta: f64) -> StateSpace {
    StateSpace::new(
        DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w0 * w0, -2.0 * zeta * w0]),
        DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
        DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
        None,
        None,
        vec![OutputInfo::new("x", "m")],
    )
    .unwrap()
}

fn first_order(a: f64) -> StateSpace {
    StateSpace::new(
        DMatrix::from_element(1, 1, -a),
        DMatrix::from_element(1, 1, 1.0),
        DMatrix::from_element(1, 1, 1.0),
        None,
        None,
        vec![OutputInfo::new("y", "m")],
    )
    .unwrap()
}

/// Caughey, T.K. & Stumpf, H.J. (1961), "Transient response of a dynamic system under random excitation",
/// J. Appl. Mech. 28(4), 563–566, in the crate's convention (white noise E[w(t)w(t+τ)] = 2πS₀δ(τ)): an
/// oscillator x″ + 2ζω₀x′ + ω₀²x = w started from rest has, with ω_d = ω₀√(1 − ζ²), a = ζω₀/ω_d,
/// e = e^{−2ζω₀t},
/// ```text
/// σ_x²(t) = πS₀/(2ζω₀³) {1 − e[1 + a sin 2ω_d t + 2a² sin² ω_d t]}
/// σ_v²(t) = πS₀/(2ζω₀)  {1 − e[1 − a sin 2ω_d t + 2a² sin² ω_d t]}
/// cov(x, v)(t) = (πS₀/ω_d²) e sin² ω_d t          (= ½ dσ_x²/dt)
/// ```
/// (derived by integrating P(t) = ∫₀ᵗ e^{As}Qe^{Aᵀs}ds in closed form). Spot values of σ_x² from an
/// independent scipy integration (DOP853 of the Lyapunov ODE) check this transcription: 0.001847321620 at
/// t = 0.1 s and 0.034181286033 at 0.5 s for ω₀ = 2π rad/s, ζ = 0.05, S₀ = 1.
#[test]
fn caughey_stumpf_oscillator_from_rest() {
    let (w0, z, s0): (f64, f64, f64) = (2.0 * PI, 0.05, 1.0);
    let closed = |t: f64| {
        let wd = w0 * (1.0 - z * z).sqrt();
        let a = z * w0 / wd;
        let e = (-2.0 * z * w0 * t).exp();
        let (s2, s1) = ((2.0 * wd * t).sin(), (wd * t).sin().powi(2));
        (
            PI * s0 / (2.0 * z * w0.powi(3)) * (1.0 - e * (1.0 + a * s2 + 2.0 * a * a * s1)),
            PI * s0 / (2.0 * z * w0) * (1.0 - e * (1.0 - a * s2 + 2.0 * a * a * s1)),
            PI * s0 / (wd * wd) * e * s1,
        )
    };
    assert!(rel(closed(0.1).0, 0.001847321620) < PRINTED_8_DIGITS);
    assert!(rel(closed(0.5).0, 0.034181286033) < PRINTED_8_DIGITS);
    let sys = system(oscillator(w0, z), InputModel::White { density: s0 }, Envelope::unit());
    let times: Vec<f64> = (1..=400).map(|k| k as f64 * 0.05).collect();
    let sol = solve(&sys, &Start::Rest, &times, &ExactOptions::default()).unwrap();
    assert_oscillator_moments(&sol.outputs[0], &times, closed);
    assert_eq!(
        sol.report.exact_steps, sol.report.steps,
        "a time-invariant system takes exact steps only"
    );
}

/// σ_x², σ_v² and cov(x, v) of an oscillator's output x (its rate v) at `times` against `expected(t)` =
/// (σ_x², σ_v², cov), each to [`EXACT_TRANSITIONS`] (the covariance relative to σ_xσ_v).
fn assert_oscillator_moments(o: &OutputSeries, times: &[f64], expected: impl Fn(f64) -> (f64, f64, f64)) {
    for (k, &t) in times.iter().enumerate() {
        let (sx2, sv2, cxv) = expected(t);
        assert!(
            rel(o.sigma[k].powi(2), sx2) < EXACT_TRANSITIONS,
            "σ_x² at {t}: {} vs {sx2}",
            o.sigma[k].powi(2)
        );
        assert!(
            rel(o.sigma_rate[k].powi(2), sv2) < EXACT_TRANSITIONS,
            "σ_v² at {t}: {} vs {sv2}",
            o.sigma_rate[k].powi(2)
        );
        let cov = o.rho[k] * o.sigma[k] * o.sigma_rate[k];
        assert!(
            (cov - cxv).abs() < EXACT_TRANSITIONS * (sx2 * sv2).sqrt(),
            "cov at {t}: {cov} vs {cxv}"
        );
    }
}

/// y′ = −αy + w with E[w(t)w(s)] = 2πS₀(t)δ(t − s), S₀(t) = S₁t/T for t ≤ T (an intensity envelope that
/// ramps linearly), then S₁, from rest. With q = 2πS₁: Ṗ = −2αP + qt/T, so
/// ```text
/// P(t) = (q/T)[t/(2α) − (1 − e^{−2αt})/(4α²)]              (t ≤ T)
/// P(t) = q/(2α) + (P(T) − q/(2α)) e^{−2α(t − T)}          (t > T)
/// ```
/// (derived here). The intensity is linear between the knots 0 and T, so the route takes exact affine steps
/// (`stochvib::transient::affine_step`, one per stored time, no error estimate): equal to the closed form
/// to the rounding of exact transitions.
#[test]
fn first_order_under_linearly_ramped_intensity() {
    let (alpha, s1, tr) = (2.0, 0.5, 10.0);
    let q = 2.0 * PI * s1;
    let closed = |t: f64| {
        let ramp = |t: f64| q / tr * (t / (2.0 * alpha) - (1.0 - (-2.0 * alpha * t).exp()) / (4.0 * alpha * alpha));
        if t <= tr {
            ramp(t)
        } else {
            let s = q / (2.0 * alpha);
            s + (ramp(tr) - s) * (-2.0 * alpha * (t - tr)).exp()
        }
    };
    let env = Envelope::intensity(vec![0.0, tr], vec![0.0, 1.0]).unwrap();
    let sys = system(first_order(alpha), InputModel::White { density: s1 }, env);
    let times: Vec<f64> = (1..=150).map(|k| k as f64 * 0.1).collect();
    assert!(
        sys.affine_noise().is_some(),
        "an intensity table is affine between its knots"
    );
    let sol = solve(&sys, &Start::Rest, &times, &ExactOptions::default()).unwrap();
    for (k, &t) in times.iter().enumerate() {
        let p = sol.outputs[0].sigma[k].powi(2);
        assert!(rel(p, closed(t)) < EXACT_TRANSITIONS, "P({t}) = {p} vs {}", closed(t));
        assert_eq!(sol.error_estimate[k], 0.0, "exact steps carry no estimate");
    }
    // a published spot value of the same closed form (scipy DOP853, independent): P(5 s) = 0.373064127654
    assert!(rel(closed(5.0), 0.373064127654) < PRINTED_8_DIGITS);
    let r = sol.report;
    assert_eq!((r.exact_steps, r.steps, r.rejected), (150, 150, 0), "{r:?}");
    assert!(r.exponentials <= 3, "one block exponential per step length: {r:?}");
}

/// An oscillator ẍ + 2ζω₀ẋ + ω₀²x = w (ω₀ = 2π rad/s, ζ = 0.05) from rest under white noise whose intensity
/// e(t) ramps linearly from 0.2 at t = 0 to 1 at T = 3 s and stays (S₀(t) = e(t)S₀): the exact affine steps
/// against P(t) = ∫₀ᵗ e(s)·e^{A(t−s)}QQᵀe^{Aᵀ(t−s)} ds (Q = √(2πS₀)·[0; 1]), evaluated in the test by
/// composite Simpson quadrature (`common::simpson`, 4000 intervals per second, split at the kink T of e: the
/// integrand is smooth on each part, its fourth derivative about ω₀⁴ ≈ 1.6·10³ times its size, so the
/// error h⁴·max|f⁗|/180 ≈ 3.5·10⁻¹⁴ relative, h = 2.5·10⁻⁴ s) with the closed-form transition of the
/// underdamped oscillator
/// (σ = ζω₀, ω_d = ω₀√(1 − ζ²)):
/// ```text
/// e^{Aτ} = e^{−στ}[[cos ω_dτ + (σ/ω_d) sin ω_dτ, sin ω_dτ/ω_d], [−ω₀² sin ω_dτ/ω_d, cos ω_dτ − (σ/ω_d) sin ω_dτ]]
/// ```
/// No matrix exponential and no Lyapunov equation in the reference.
#[test]
fn oscillator_under_affine_intensity_against_quadrature() {
    let (w0, z, s0, tr) = (2.0 * PI, 0.05, 1.0, 3.0);
    let env = Envelope::intensity(vec![0.0, tr], vec![0.2, 1.0]).unwrap();
    let e = |s: f64| if s < tr { 0.2 + 0.8 * s / tr } else { 1.0 };
    let (sg, wd) = (z * w0, w0 * (1.0 - z * z).sqrt());
    // the column e^{Aτ}[0; 1]: the transition of a unit velocity impulse
    let col = |tau: f64| {
        let d = (-sg * tau).exp();
        let (c, sn) = ((wd * tau).cos(), (wd * tau).sin());
        (d * sn / wd, d * (c - sg / wd * sn))
    };
    // ∫₀ᵗ of one entry of e(s)·e^{A(t−s)}[0; 1][0; 1]ᵀe^{Aᵀ(t−s)}, split at the kink T of e
    let entry = |t: f64, pick: fn((f64, f64)) -> f64| {
        let f = |s: f64| e(s) * pick(col(t - s));
        let part = |a: f64, b: f64| {
            let panels = 2 * (2000.0 * (b - a)).ceil() as usize;
            common::simpson(f, a, b, panels)
        };
        let whole = if t <= tr {
            part(0.0, t)
        } else {
            part(0.0, tr) + part(tr, t)
        };
        2.0 * PI * s0 * whole
    };
    // (σ_x², σ_v², cov(x, v))
    let reference = |t: f64| {
        (
            entry(t, |(x, _)| x * x),
            entry(t, |(_, v)| v * v),
            entry(t, |(x, v)| x * v),
        )
    };
    let sys = system(oscillator(w0, z), InputModel::White { density: s0 }, env);
    assert!(sys.affine_noise().is_some());
    let times: Vec<f64> = (1..=10).map(|k| k as f64 * 0.5).collect();
    let sol = solve(&sys, &Start::Rest, &times, &ExactOptions::default()).unwrap();
    assert_oscillator_moments(&sol.outputs[0], &times, reference);
    assert_eq!(sol.report.exact_steps, sol.report.steps, "{:?}", sol.report);
}

/// A family that answers the constant model but says it may vary: the exact route then cannot see the
/// affine structure and takes its midpoint steps with step doubling (the route for general time variation).
#[derive(Debug)]
struct SaysVarying(FixedSystem);

impl SystemFamily for SaysVarying {
    fn at(&self, t: f64) -> stochvib::Result<ModelAt> {
        self.0.at(t)
    }
    fn is_constant(&self) -> bool {
        false
    }
    fn describe(&self) -> String {
        "says varying".into()
    }
}

/// The passenger quarter car (`common::passenger_quarter_car`) under white road velocity whose intensity
/// follows the speed of `common::accelerating_5_to_15` (the structure of a w = 2 road under that speed):
/// the exact affine steps against the step-doubling route (midpoint transitions, Richardson, rel_tol 1e-9)
/// of the same system, a different integration. They agree within the step-doubling route's own error
/// estimate (relative to each state's largest variance over the window) plus rounding, and the affine steps
/// are one per stored time and knot instead of thousands.
#[test]
fn affine_steps_agree_with_step_doubling_within_its_estimate() {
    let mdof = crate::common::passenger_quarter_car().system().unwrap();
    let ss = mdof.state_space().unwrap().clone();
    let v = common::accelerating_5_to_15();
    let env = Envelope::intensity(v.knots().to_vec(), v.knots().iter().map(|t| v.speed(*t)).collect()).unwrap();
    let input = || TransientInput {
        model: InputModel::White { density: 1e-4 },
        envelope: env.clone(),
        mean: 0.0,
        gains: vec![1.0; ss.b.ncols()],
    };
    let fixed = || FixedSystem::new(ss.clone(), None, "car").unwrap();
    let affine = TimeVaryingSystem::new(Arc::new(fixed()), input()).unwrap();
    let doubling = TimeVaryingSystem::new(Arc::new(SaysVarying(fixed())), input()).unwrap();
    assert!(affine.affine_noise().is_some() && doubling.affine_noise().is_none());
    let times: Vec<f64> = (1..=80).map(|k| k as f64 * 0.25).collect();
    let (p0, m0) = affine.start(&Start::Stationary).unwrap();
    let run = |sys: &TimeVaryingSystem| {
        let mut out: Vec<(DMatrix<f64>, f64)> = Vec::new();
        let mut keep = |_: usize, _: f64, p: &DMatrix<f64>, _: &nalgebra::DVector<f64>, err: f64| {
            out.push((p.clone(), err));
            Ok(())
        };
        let report = propagate(sys, p0.clone(), m0.clone(), &times, &ExactOptions::default(), &mut keep).unwrap();
        (out, report)
    };
    let ((pa, rep_a), (pd, rep_d)) = (run(&affine), run(&doubling));
    let n = ss.a.nrows();
    let largest: Vec<f64> = (0..n)
        .map(|i| pa.iter().map(|(p, _)| p[(i, i)]).fold(0.0, f64::max))
        .collect();
    for (k, ((a, _), (d, est))) in pa.iter().zip(&pd).enumerate() {
        for i in 0..n {
            let err = (a[(i, i)] - d[(i, i)]).abs() / largest[i];
            assert!(
                err <= est + EXACT_TRANSITIONS,
                "state {i} at {}: {err} above {est}",
                times[k]
            );
        }
    }
    assert_eq!((rep_a.exact_steps, rep_a.rejected), (rep_a.steps, 0), "{rep_a:?}");
    // the steps end at stored times and knots and are at most a hundredth of the window (0.2 s): two per
    // stored interval of 0.25 s, of two lengths, one block exponential each
    assert!(
        rep_a.steps <= 2 * times.len() + v.knots().len() && rep_a.exponentials <= 4,
        "{rep_a:?}"
    );
    assert!(
        rep_d.steps > 10 * rep_a.steps && rep_d.exponentials > 100 * rep_a.exponentials,
        "{rep_d:?} {rep_a:?}"
    );
}

/// The same system with an amplitude envelope a(t) = t/T (intensity a² = t²/T²), from rest:
/// Ṗ = −2αP + q t²/T², whose solution with P(0) = 0 is (derived here, particular solution At² + Bt + C)
/// ```text
/// P(t) = (q/T²)[t²/(2α) − t/(2α²) + (1 − e^{−2αt})/(4α³)]
/// ```
#[test]
fn first_order_under_amplitude_ramp() {
    let (alpha, s1, tr) = (1.5, 0.2, 4.0);
    let closed = |t: f64| amplitude_ramp_variance(alpha, s1, tr, t);
    let sys = system(
        first_order(alpha),
        InputModel::White { density: s1 },
        Envelope::ramp(tr).unwrap(),
    );
    let times: Vec<f64> = (1..=40).map(|k| k as f64 * 0.1).collect();
    let sol = solve(&sys, &Start::Rest, &times, &ExactOptions::default()).unwrap();
    for (k, &t) in times.iter().enumerate() {
        let p = sol.outputs[0].sigma[k].powi(2);
        assert!(rel(p, closed(t)) < ADAPTIVE_ROUTE, "P({t}) = {p} vs {}", closed(t));
    }
}

/// P(t) of [`first_order_under_amplitude_ramp`] (q = 2πS₁).
fn amplitude_ramp_variance(alpha: f64, s1: f64, tr: f64, t: f64) -> f64 {
    let q = 2.0 * PI * s1;
    q / (tr * tr)
        * (t * t / (2.0 * alpha) - t / (2.0 * alpha * alpha) + (1.0 - (-2.0 * alpha * t).exp()) / (4.0 * alpha.powi(3)))
}

/// The error estimate of a start from rest under an envelope that starts at 0 (the amplitude ramp above,
/// closed form P(t)): the variance grows from 0 like t³, and the midpoint rule's error on ∫₀ʰs²ds relative
/// to the value is 1/4 whatever the step, so an error measured relative to each step's own variance cannot
/// be met (the steps at the start shrink to nothing) and sums to O(0.1). Measured relative to the largest
/// variance over the window, the estimate is small (below [`ERROR_ESTIMATE_FROM_REST`], the route's tolerance
/// 1e-9 per step over its steps), bounds the true error on the same scale at every time, and the steps stay
/// below 10⁴.
#[test]
fn error_estimate_from_rest_is_relative_to_the_window() {
    let (alpha, s1, tr) = (1.5, 0.2, 4.0);
    let sys = system(
        first_order(alpha),
        InputModel::White { density: s1 },
        Envelope::ramp(tr).unwrap(),
    );
    let times: Vec<f64> = (1..=80).map(|k| k as f64 * 0.1).collect();
    let sol = solve(&sys, &Start::Rest, &times, &ExactOptions::default()).unwrap();
    let largest = times
        .iter()
        .map(|t| amplitude_ramp_variance(alpha, s1, tr, t.min(tr)))
        .fold(0.0, f64::max);
    let after = |t: f64| {
        // beyond the ramp the intensity is q: P relaxes from P(T) to q/(2α)
        let s = PI * s1 / alpha;
        s + (amplitude_ramp_variance(alpha, s1, tr, tr) - s) * (-2.0 * alpha * (t - tr)).exp()
    };
    let largest = largest.max(after(times[times.len() - 1]));
    for (k, &t) in times.iter().enumerate() {
        let exact = if t <= tr {
            amplitude_ramp_variance(alpha, s1, tr, t)
        } else {
            after(t)
        };
        let err = (sol.outputs[0].sigma[k].powi(2) - exact).abs() / largest;
        assert!(
            err <= sol.error_estimate[k] + 1e-15,
            "t = {t}: error {err} above {}",
            sol.error_estimate[k]
        );
    }
    assert!(
        sol.report.max_error_estimate < ERROR_ESTIMATE_FROM_REST,
        "estimate {}",
        sol.report.max_error_estimate
    );
    assert!(sol.report.steps < 10_000, "{:?}", sol.report);
}

/// A quarter car (m_s = 400, m_u = 40 kg, k_s = 20 kN/m, c_s = 1.5 kN s/m, k_t = 200 kN/m) accelerating from
/// 5 to 15 m/s in 10 s on an ISO 8608 class D road (G_d(n₀) = 1024e-6 m³, w = 2, no band), started in its
/// stationary state at 5 m/s. The road velocity is white with S₀(v) = πn₀²G_d v (the slope of a w = 2 road
/// is white in space), and a white velocity input gives the closed forms (Newland's quarter car under white
/// road velocity; derived from the 4-state Lyapunov equation)
/// ```text
/// σ²_acc = πS₀(k_t c_s² + k_s²(m_s + m_u))/(c_s m_s²),     σ²_travel = πS₀(m_s + m_u)/c_s
/// ```
/// at the two constant speeds: the route must equal them at t = 0 and long after the ramp. In between, the
/// values of an independent scipy integration (DOP853 of the Lyapunov ODE, rtol 1e-11) at t = 2, 5, 10 s.
#[test]
fn quarter_car_accelerating_on_a_w2_road() {
    let (ms, mu, ks, cs, kt) = (400.0, 40.0, 20e3, 1.5e3, 200e3);
    let car = QuarterCar {
        sprung_mass: ms,
        unsprung_mass: mu,
        suspension_stiffness: ks,
        suspension_damping: cs,
        tyre_stiffness: kt,
        tyre_damping: 0.0,
    }
    .build()
    .unwrap();
    let mdof = car.system().unwrap();
    let ss = mdof.state_space().unwrap().clone();
    let road = PowerLaw::iso8608(IsoClass::D, IsoBound::GeometricMean, None).unwrap();
    let v = common::accelerating_5_to_15();
    let model = input_model(&road, Some(&v)).unwrap();
    assert!(matches!(model, InputModel::WhiteSlope { .. }));
    let sys = system(ss, model, Envelope::unit());
    let acc = mdof.output_index("body_acc").unwrap();
    let travel = mdof.output_index("travel").unwrap();
    assert!(
        sys.unavailable(mdof.output_index("body").unwrap()).is_some(),
        "body displacement is unbounded"
    );
    let times = [0.0, 2.0, 5.0, 10.0, 40.0];
    assert!(
        sys.affine_noise().is_some(),
        "a w = 2 road under a piecewise-linear speed: affine intensity"
    );
    let sol = solve(&sys, &Start::Stationary, &times, &ExactOptions::default()).unwrap();
    assert_eq!(
        (
            sol.report.exact_steps,
            sol.report.rejected,
            sol.report.max_error_estimate
        ),
        (sol.report.steps, 0, 0.0),
        "exact affine steps: {:?}",
        sol.report
    );
    // the steps end at stored times and knots, and are at most a hundredth of the window
    assert!(
        sol.report.steps <= 100 + times.len() + v.knots().len(),
        "{:?}",
        sol.report
    );
    assert!(sol.report.exponentials <= 8, "one per step length: {:?}", sol.report);
    let stationary = |v: f64| {
        let s0 = PI * 0.01 * 1024e-6 * v;
        (
            (PI * s0 * (kt * cs * cs + ks * ks * (ms + mu)) / (cs * ms * ms)).sqrt(),
            (PI * s0 * (ms + mu) / cs).sqrt(),
        )
    };
    let (a5, t5) = stationary(5.0);
    let (a15, t15) = stationary(15.0);
    assert!(rel(sol.outputs[acc].sigma[0], a5) < EXACT_TRANSITIONS);
    assert!(rel(sol.outputs[travel].sigma[0], t5) < EXACT_TRANSITIONS);
    assert!(rel(sol.outputs[acc].sigma[4], a15) < EXACT_TRANSITIONS);
    assert!(rel(sol.outputs[travel].sigma[4], t15) < EXACT_TRANSITIONS);
    for (k, printed) in [(1, 1.34758706), (2, 1.61455138), (3, 1.98111810)] {
        assert!(
            rel(sol.outputs[acc].sigma[k], printed) < PRINTED_8_DIGITS,
            "σ_acc({}) = {}",
            times[k],
            sol.outputs[acc].sigma[k]
        );
    }
}

/// A stationary input through the non-stationary path: the quarter car on the textbook's graded dirt road
/// (Sukharev (2012) (8.69): spatial type 1, D = 32 cm², α = 0.16 1/m) at a constant 10 m/s, started from
/// rest, reaches the stationary σ of `analyze_output` (Lyapunov and quadrature of the output density) after
/// the transient; started in the stationary state it stays there.
#[test]
fn stationary_input_through_the_transient_path() {
    let car = crate::common::passenger_quarter_car();
    let mdof = car.system().unwrap();
    let road: Arc<dyn Spectrum> = Arc::new(Exponential::new(32e-4, 0.16, Domain::Spatial).unwrap());
    let exc = Excitation::road(road.clone(), 10.0, &[0.0]).unwrap();
    let v = SpeedProfile::constant(10.0).unwrap();
    let sys = system(
        mdof.state_space().unwrap().clone(),
        input_model(road.as_ref(), Some(&v)).unwrap(),
        Envelope::unit(),
    );
    let times: Vec<f64> = (0..=60).map(|k| k as f64).collect();
    let rest = solve(&sys, &Start::Rest, &times, &ExactOptions::default()).unwrap();
    let stat = solve(&sys, &Start::Stationary, &times, &ExactOptions::default()).unwrap();
    for name in ["body", "body_acc", "travel", "tyre_force"] {
        let i = mdof.output_index(name).unwrap();
        let st = analyze_output(&mdof, &exc, i).unwrap();
        let sigma = st.sigma.unwrap();
        assert!(
            rel(rest.outputs[i].sigma[60], sigma) < QUADRATURE,
            "{name}: {} vs {sigma}",
            rest.outputs[i].sigma[60]
        );
        assert!(rest.outputs[i].sigma[1] < sigma, "{name} starts below its stationary σ");
        for k in [0, 7, 60] {
            assert!(rel(stat.outputs[i].sigma[k], sigma) < QUADRATURE, "{name} at {k} s");
        }
        match st.zero_upcrossing_rate {
            Some(nu) => assert!(rel(stat.outputs[i].nu0_plus(30), nu) < QUADRATURE, "{name}: ν₀⁺"),
            // the tyre force follows the road, whose velocity has a white component on this road: no rate
            None => assert!(
                stat.outputs[i].rate_note.is_some() && stat.outputs[i].nu0_plus(30).is_nan(),
                "{name}"
            ),
        }
    }
}

/// A state of zero variance (the roll of a symmetric body whose two wheels read one track with gains
/// (1, 1), `common::two_wheels`: the two wheels' terms of the roll cancel, so its computed variance is
/// rounding noise) under a time-varying input: the car accelerates on a rational road (spatial exponential,
/// D = 1 cm², α = 0.2 1/m) from 5 to 15 m/s at 2 m/s², then holds 15 m/s to t = 20 s. The relative error
/// control cannot step on it (refused after 2·10⁶ steps at t ≈ 10⁻¹⁰ s). What the test asks once it can,
/// started from rest and stationary: the route completes in few steps,
/// the roll σ stays at rounding level (below 10⁻⁶ of the roll σ the same run gives with gains (1, −1)), and
/// after 15 s at constant speed (the slowest mode, the bounce, decays as e^{−ζωt} with ζω = 2.5 1/s) the
/// bounce σ is the stationary σ at 15 m/s of `analyze_output` (Lyapunov and quadrature of the output
/// density, an independent method). Without a rounding floor the route stalled here (refused after 2·10⁶
/// steps at t ≈ 3·10⁻¹¹ s): the roll's variance, and the difference of its step-doubling estimates, are
/// the normwise rounding of the Van Loan exponential, a few ε·max|Q_d| whatever the step.
#[test]
fn a_state_of_zero_variance_does_not_stall_the_error_control() {
    use std::path::Path;
    let road = r#"{ kind = "exponential", domain = "spatial", variance = "1 cm^2", alpha = "0.2 1/m" }"#;
    let input = format!("[input]\nspectrum = {road}\nspeed = \"15 m/s\"\n");
    let sc = stochvib::scenario::parse_scenario(
        &crate::common::two_wheels("", "[1, 1]", &input),
        Path::new("t.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap();
    let model = sc.model.system.as_ref();
    let (bounce, roll) = (
        model.output_index("bounce").unwrap(),
        model.output_index("roll").unwrap(),
    );
    let ss = model.state_space().unwrap().clone();
    let speed = ConstantAcceleration {
        from_m_s: 5.0,
        to_m_s: 15.0,
        acceleration_m_s2: 2.0,
        start_s: 0.0,
    }
    .build()
    .unwrap();
    let spectrum = Exponential::new(1e-4, 0.2, Domain::Spatial).unwrap();
    let sys = |gains: Vec<f64>| {
        let input = TransientInput {
            model: input_model(&spectrum, Some(&speed)).unwrap(),
            envelope: Envelope::unit(),
            mean: 0.0,
            gains,
        };
        TimeVaryingSystem::new(
            Arc::new(FixedSystem::new(ss.clone(), None, "two wheels").unwrap()),
            input,
        )
        .unwrap()
    };
    let (same, opposite) = (sys(vec![1.0, 1.0]), sys(vec![1.0, -1.0]));
    let times: Vec<f64> = (0..=40).map(|k| 0.5 * k as f64).collect();
    let sigma = analyze_output(model, &sc.excitation, bounce).unwrap().sigma.unwrap();
    for start in [Start::Rest, Start::Stationary] {
        let sol = solve(&same, &start, &times, &ExactOptions::default()).unwrap();
        let scale = solve(&opposite, &start, &times, &ExactOptions::default()).unwrap();
        assert!(sol.report.steps < 10_000, "{start:?}: {:?}", sol.report);
        assert!(
            sol.report.max_error_estimate < ERROR_ESTIMATE_FROM_REST,
            "{start:?}: {:?}",
            sol.report
        );
        for (k, t) in times.iter().enumerate().skip(1) {
            let (r, s) = (sol.outputs[roll].sigma[k], scale.outputs[roll].sigma[k]);
            assert!(
                r <= ZERO_BY_CANCELLATION * s,
                "{start:?}: roll σ {r} at {t} s against {s}"
            );
        }
        let end = sol.outputs[bounce].sigma[40];
        assert!(
            rel(end, sigma) < QUADRATURE,
            "{start:?}: bounce σ {end} against {sigma}"
        );
    }
}
