//! The fast routes of parameter studies agree with the Lyapunov reference, and fall back to it (saying so)
//! where the integral table's condition check fails.
//!
//! * `response::ExactEvaluator` (integral table by Faddeev–LeVerrier polynomials, pivot-ratio check) and
//!   `scenario::Sweep::evaluate` against `response::variance_lyapunov` of the same point's scenario.
//! * `comfort::WeightedEvaluator` (input filter × W_k premultiplied, one scaled table integral per point)
//!   against `variance_lyapunov` of `comfort::weighted_output` (the cascade's Lyapunov covariance).
//!
//! Provenance of the expected values: the Lyapunov route is a different method (a Bartels–Stewart solve of
//! the augmented system's covariance equation, no polynomial coefficients), so agreement is a check of the
//! fast route, not of itself. The grids include stiff corners (natural frequencies four decades apart,
//! damping ratios from 0.005 to 2) where the table's Hurwitz elimination loses digits.

mod common;
use common::tolerance::CONDITION_CHECKED;
use std::path::Path;
use std::sync::Arc;
use stochvib::comfort::{weighted_output, WeightedEvaluator, WeightedRoute, Weighting};
use stochvib::models::operator_seat::OperatorSeat;
use stochvib::response::{variance_lyapunov, ExactEvaluator, Excitation, VarianceMethod};
use stochvib::scenario::{load_scenario, parse_scenario, Sweep, SweepMode, SweepParam, SweepSpec};
use stochvib::spectrum::{Domain, RationalSpectrum};
use stochvib::system::FrequencyResponse;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The scraper's sprung cab over cab frequency × damping × mass, 600 points × 4 outputs, stiff corner
/// included (ω₂ from 0.05 Hz to 40 Hz against the 2.9 Hz tyre mode, m₂ from 20 kg to 200 t, ζ₂ from
/// 0.005 to 2): every σ and λ₂ the sweep prints equals the Lyapunov value of that point's scenario within
/// CONDITION_CHECKED; the method column names the route that computed it.
#[test]
fn sweep_points_equal_lyapunov_over_a_grid_with_a_stiff_corner() {
    let sc = load_scenario(Path::new("data/scraper-sprung-cab.toml"), Path::new("spectra")).unwrap();
    let spec = SweepSpec::new(
        vec![
            SweepParam::parse("model.omega2=0.05 Hz..40 Hz:12:log").unwrap(),
            SweepParam::parse("model.zeta2=0.005..2:10:log").unwrap(),
            SweepParam::parse("model.m2=20 kg..200000 kg:5:log").unwrap(),
        ],
        SweepMode::Grid,
    )
    .unwrap();
    let sweep = Sweep::new(&sc, spec).unwrap();
    let (mut table, mut lyapunov) = (0, 0);
    let mut worst: f64 = 0.0;
    for p in 0..sweep.spec().n_points() {
        let fast = sweep.evaluate(p).unwrap();
        let point = sweep.scenario_at(p).unwrap();
        let names = point.model.system.outputs();
        for (st, name) in fast.iter().zip(sweep.outputs()) {
            let i = names.iter().position(|o| &o.name == name).unwrap();
            let reference = variance_lyapunov(point.model.system.as_ref(), &point.excitation, i).unwrap();
            let v = st.variance.unwrap();
            let e = rel(v, reference.variance);
            worst = worst.max(e);
            assert!(
                e <= CONDITION_CHECKED,
                "point {p}, {name}: {v} vs Lyapunov {}",
                reference.variance
            );
            if let (Some(l2), Ok(r2)) = (st.lambda2, reference.lambda2) {
                assert!(rel(l2, r2) <= CONDITION_CHECKED, "point {p}, {name}: λ₂ {l2} vs {r2}");
            }
            match st.method {
                VarianceMethod::IntegralTable => table += 1,
                VarianceMethod::Lyapunov => lyapunov += 1,
                m => panic!("point {p}: unexpected route {m:?}"),
            }
        }
    }
    eprintln!("table {table}, lyapunov fallback {lyapunov}, worst relative difference {worst:e}");
    assert!(table > 1000, "the table answered only {table} of 2400 values");
}

/// The stiff chains of the integral-table report (masses from 0.05 kg to 2·10⁶ kg, seeded family as in
/// `numerical_truth.rs`): through `ExactEvaluator`, every variance is either a table value within
/// CONDITION_CHECKED of Lyapunov, or the Lyapunov value itself with the method saying so — never a
/// table value that failed its check. The family contains points of both kinds.
#[test]
fn an_unreliable_table_point_falls_back_to_lyapunov_and_says_so() {
    use rand::SeedableRng;
    let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(151);
    let (mut table, mut fallback) = (0, 0);
    for case in 0..60 {
        let text = common::stiff_chain_text(&mut rng);
        let sc = parse_scenario(&text, Path::new("stiff-chain.toml"), Path::new("spectra")).unwrap();
        let sys = sc.model.system.as_ref();
        let ev = ExactEvaluator::new(&sc.excitation);
        let fast = ev.evaluate(sys, &sc.excitation, &[0, 1]).unwrap();
        for (i, st) in fast.iter().enumerate() {
            let reference = variance_lyapunov(sys, &sc.excitation, i).unwrap().variance;
            let v = st.variance.unwrap();
            match st.method {
                VarianceMethod::IntegralTable => {
                    table += 1;
                    assert!(
                        rel(v, reference) <= CONDITION_CHECKED,
                        "case {case}, output {i}: {v} vs {reference}"
                    );
                }
                VarianceMethod::Lyapunov => {
                    fallback += 1;
                    // the same solver on the same system: the same number
                    assert_eq!(v, reference, "case {case}, output {i}");
                }
                other => panic!("case {case}: unexpected route {other:?}"),
            }
        }
    }
    eprintln!("table {table}, fallback {fallback}");
    // this family is stiff enough that the Faddeev–LeVerrier residual rejects every point (measured: 120 of
    // 120); the scraper grid above has points of both kinds
    assert!(fallback > 0, "no fallback in the stiff family");
}

/// The cab-floor input of `data/operator-seat-verdicts.toml` (a rational spectrum; the scenario's values).
fn seat_input() -> Excitation {
    let s = RationalSpectrum::new(
        vec![9.978705857784458],
        vec![124596039.48735943, -448861.0914846832, 404.2589962686201, 1.0],
        Domain::Temporal,
    )
    .unwrap();
    Excitation::single(Arc::new(s), 0.0).unwrap()
}

/// W_k-weighted seat acceleration over seat stiffness × damping, 24 × 24 points from a soft, nearly
/// undamped seat (300 N/m, 2 N s/m) to a stiff, overdamped one (3·10⁷ N/m, 2·10⁵ N s/m): the evaluator's
/// a_w equals the Lyapunov covariance of the weighted cascade within CONDITION_CHECKED (a_w², the
/// variance, compared), and a fallback point carries the Lyapunov value.
#[test]
fn weighted_evaluator_equals_lyapunov_over_a_seat_grid() {
    let exc = seat_input();
    let ev = WeightedEvaluator::new(&exc, Weighting::Wk).unwrap();
    let (mut table, mut fallback) = (0, 0);
    for i in 0..24 {
        let k = 300.0 * 10f64.powf(5.0 * i as f64 / 23.0);
        for j in 0..24 {
            let b = 2.0 * 10f64.powf(5.0 * j as f64 / 23.0);
            let seat = OperatorSeat::new(80.0, 26.0, k, b).unwrap().instance().unwrap();
            let ss = seat.system.state_space().unwrap();
            let out = ss.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
            let fast = ev.a_w(ss, out, &exc).unwrap();
            let w = weighted_output(ss, out, &Weighting::Wk).unwrap();
            let reference = variance_lyapunov(&w, &exc, 0).unwrap().variance;
            match fast.route {
                WeightedRoute::Residues => {
                    table += 1;
                    let e = rel(fast.a_w * fast.a_w, reference);
                    assert!(
                        e <= CONDITION_CHECKED,
                        "k {k}, b {b}: {} vs {reference} ({e:e})",
                        fast.a_w.powi(2)
                    );
                }
                WeightedRoute::LyapunovFallback => {
                    fallback += 1;
                    assert_eq!(fast.a_w, reference.sqrt());
                }
            }
        }
    }
    eprintln!("table {table}, fallback {fallback}");
    assert!(
        table > 24 * 24 / 2,
        "the residues answered only {table} of {} points",
        24 * 24
    );
    // Near-coincident poles: the seat's poles on W_k's upward-step poles (f₆ = 3.35 Hz, Q₆ = 0.91, ISO
    // 2631-1 Table A.2; ζ = 1/(2Q₆)), and a critically damped seat (a double pole, ζ = 1). The residues
    // cancel: the point must come from the Lyapunov route and say so.
    let m_pr = 5.0 / 7.0 * 80.0 + 26.0; // reduced mass of the seat model, kg (Sukharev 2012, 7.6)
    let w6 = 2.0 * std::f64::consts::PI * 3.35;
    for (k, b) in [
        (m_pr * w6 * w6, m_pr * w6 / 0.91),
        (6500.0, 2.0 * (6500.0 * m_pr).sqrt()),
    ] {
        let seat = OperatorSeat::new(80.0, 26.0, k, b).unwrap().instance().unwrap();
        let ss = seat.system.state_space().unwrap();
        let out = ss.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
        let fast = ev.a_w(ss, out, &exc).unwrap();
        assert_eq!(fast.route, WeightedRoute::LyapunovFallback, "k {k}, b {b}");
        let w = weighted_output(ss, out, &Weighting::Wk).unwrap();
        assert_eq!(fast.a_w, variance_lyapunov(&w, &exc, 0).unwrap().variance.sqrt());
    }
}

/// The evaluator refuses what it cannot do, naming the reason: delayed inputs, a non-acceleration output.
#[test]
fn weighted_evaluator_errors() {
    let s = seat_input().spectra()[0].clone();
    let delayed = Excitation::track(s, vec![0.0, 0.1], vec![1.0, 1.0], 0.0).unwrap();
    assert!(WeightedEvaluator::new(&delayed, Weighting::Wk).is_err());
    let exc = seat_input();
    let ev = WeightedEvaluator::new(&exc, Weighting::Wk).unwrap();
    let seat = OperatorSeat::new(80.0, 26.0, 6500.0, 600.0)
        .unwrap()
        .instance()
        .unwrap();
    let ss = seat.system.state_space().unwrap();
    let travel = ss.outputs().iter().position(|o| o.unit == "m").unwrap();
    let e = ev.a_w(ss, travel, &exc).unwrap_err().to_string();
    assert!(e.contains("acceleration"), "{e}");
}
