//! The fast routes of parameter studies agree with the Lyapunov reference, and fall back to it (saying so)
//! where the integral table's condition check fails.
//!
//! * `response::ExactEvaluator` (integral table by Faddeev–LeVerrier polynomials, pivot-ratio check) and
//!   `study::Sweep::evaluate` against `response::variance_lyapunov` of the same point's scenario.
//! * `comfort::WeightedEvaluator` (input filter × W_k premultiplied, one scaled table integral per point)
//!   against `variance_lyapunov` of `comfort::weighted_output` (the cascade's Lyapunov covariance).
//!
//! Provenance of the expected values: the Lyapunov route is a different method (a Bartels–Stewart solve of
//! the augmented system's covariance equation, no polynomial coefficients), so agreement is a check of the
//! fast route, not of itself. The grids include stiff corners (natural frequencies four decades apart,
//! damping ratios from 0.005 to 2) where the table's Hurwitz elimination loses digits.

use crate::common;
use common::tolerance::{CONDITION_CHECKED, TRANSFER_POLYNOMIALS};
use std::path::Path;
use std::sync::Arc;
use stochvib::comfort::{weighted_output, WeightedEvaluator, WeightedRoute, Weighting};
use stochvib::models::operator_seat::OperatorSeat;
use stochvib::response::{variance_lyapunov, ExactEvaluator, Excitation, VarianceMethod};
use stochvib::scenario::{load_scenario, parse_scenario};
use stochvib::spectrum::{Domain, RationalSpectrum};
use stochvib::study::{Sweep, SweepMode, SweepParam, SweepPath, SweepSpec};
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
    let sc = load_scenario(
        &crate::common::root().join("data/scraper-sprung-cab.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap();
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
        let sc = parse_scenario(
            &text,
            Path::new("stiff-chain.toml"),
            &crate::common::root().join("spectra"),
        )
        .unwrap();
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
            let seat = OperatorSeat {
                operator_mass: 80.0,
                seat_mass: 26.0,
                stiffness: k,
                damping: b,
            }
            .build()
            .unwrap()
            .instance()
            .unwrap();
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
        let seat = OperatorSeat {
            operator_mass: 80.0,
            seat_mass: 26.0,
            stiffness: k,
            damping: b,
        }
        .build()
        .unwrap()
        .instance()
        .unwrap();
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
    let seat = OperatorSeat {
        operator_mass: 80.0,
        seat_mass: 26.0,
        stiffness: 6500.0,
        damping: 600.0,
    }
    .build()
    .unwrap()
    .instance()
    .unwrap();
    let ss = seat.system.state_space().unwrap();
    let travel = ss.outputs().iter().position(|o| o.unit == "m").unwrap();
    let e = ev.a_w(ss, travel, &exc).unwrap_err().to_string();
    assert!(e.contains("acceleration"), "{e}");
}

/// Whether two optional statistics agree within `tol` relative (both absent, both zero, or close).
fn close(a: Option<f64>, b: Option<f64>, tol: f64) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(x), Some(y)) => x == y || (x - y).abs() <= tol * x.abs().max(y.abs()),
        _ => false,
    }
}

/// Every point of `sweep` three ways: the public `evaluate`, the numeric path alone and the general path
/// (model rebuilt from its substituted table, Faddeev–LeVerrier polynomials of its state space, or
/// Lyapunov where a check fails). `evaluate` gives the numeric path's result where it answers and the
/// general path's elsewhere. The scraper kinds' numeric path runs the integral table on closed-form
/// transfer polynomials (other arithmetic than the state-space route), so where it answers it must give
/// the general path's error, or every statistic within `TRANSFER_POLYNOMIALS` of it: both sides are
/// exact routes whose table values passed the pivot-ratio check (estimated error ≤ 1e-9 each) or are
/// Lyapunov solutions. Where both sides computed an output by Lyapunov they solve the same state-space
/// matrices (the numeric builder writes the rebuilt model's matrices, bit for bit), so the numbers must be
/// identical. Returns (numeric Ok, numeric Err, declined) counts.
fn numeric_against_general(sweep: &Sweep) -> (usize, usize, usize) {
    let (mut ok, mut err, mut declined) = (0, 0, 0);
    let mut worst: f64 = 0.0;
    for p in 0..sweep.spec().n_points() {
        let general = sweep.evaluate_general(p).map_err(|e| e.to_string());
        let public = sweep.evaluate(p).map_err(|e| e.to_string());
        match sweep.evaluate_numeric(p).map(|r| r.map_err(|e| e.to_string())) {
            Some(numeric) => {
                assert_eq!(public, numeric, "point {p}: evaluate differs from the numeric path");
                match (&numeric, &general) {
                    (Ok(n), Ok(g)) => {
                        ok += 1;
                        for (k, (a, b)) in n.iter().zip(g).enumerate() {
                            for (what, x, y) in [
                                ("mean", a.mean, b.mean),
                                ("variance", a.variance, b.variance),
                                ("λ₂", a.lambda2, b.lambda2),
                            ] {
                                assert!(
                                    close(x, y, TRANSFER_POLYNOMIALS),
                                    "point {p}, output {k}, {what}: numeric {x:?} vs general {y:?}"
                                );
                                if let (Some(x), Some(y)) = (x, y)
                                    && x != y
                                {
                                    let e = (x - y).abs() / x.abs().max(y.abs());
                                    worst = worst.max(e);
                                }
                            }
                            if a.method == VarianceMethod::Lyapunov && b.method == VarianceMethod::Lyapunov {
                                assert_eq!(a, b, "point {p}, output {k}: the same Lyapunov solve");
                            }
                        }
                    }
                    (Err(_), Err(_)) => err += 1,
                    _ => panic!("point {p}: numeric {numeric:?} vs general {general:?}"),
                }
            }
            None => {
                assert_eq!(public, general, "point {p}: evaluate differs from the general path");
                // the builder declines only where the general path fails (it names the error)
                assert!(
                    general.is_err(),
                    "point {p}: declined although the general path succeeds"
                );
                declined += 1;
            }
        }
    }
    eprintln!("worst relative difference numeric vs general: {worst:e}");
    (ok, err, declined)
}

/// The numeric builder of `scraper-sprung-cab` over cab frequency × damping ratio × cab mass × speed,
/// 6 × 5 × 4 × 3 = 360 points × 4 outputs, including the stiff corner (ω₂ 0.05 Hz against m₂ = 200 t),
/// a cab mount without damper (ζ₂ = 0: still asymptotically stable in exact arithmetic, through the tyre
/// damping b₁, but barely so where the cab hardly moves m₁), values the model refuses (ζ₂ < 0, m₂ = 0)
/// and a speed the input refuses (−1 m/s). Expected counts from the grid: the reader and the model accept
/// a point when ζ₂ ∈ {0.3, 0, 0.005, 2}, m₂ ∈ {2 t, 20 kg, 200 t} and v ∈ {10, 30} m/s: 6·4·3·2 = 144
/// points, each answered by the numeric path (a value, or the evaluator's error); the other 216 are
/// declined and fail on the general path.
#[test]
fn numeric_builder_equals_general_path_sprung_cab() {
    let sc = load_scenario(
        &crate::common::root().join("data/scraper-sprung-cab.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap();
    let spec = SweepSpec::new(
        vec![
            SweepParam::parse("model.omega2=0.05 Hz..40 Hz:6:log").unwrap(),
            SweepParam::parse("model.zeta2=0.3,-0.1,0,0.005,2").unwrap(),
            SweepParam::parse("model.m2=2000 kg,0 kg,20 kg,200000 kg").unwrap(),
            SweepParam::parse("input.speed=10 m/s,-1 m/s,30 m/s").unwrap(),
        ],
        SweepMode::Grid,
    )
    .unwrap();
    let sweep = Sweep::new(&sc, spec).unwrap();
    assert_eq!(
        sweep.path(),
        &SweepPath::Numeric {
            kind: "scraper-sprung-cab".into()
        }
    );
    let (ok, err, declined) = numeric_against_general(&sweep);
    eprintln!("numeric ok {ok}, numeric error {err}, declined {declined}");
    assert_eq!(ok + err, 144);
    assert_eq!(declined, 216);
    assert!(ok >= 6 * 3 * 3 * 2, "every point with a damped cab mount has a value");
    // the stiff corner sends some outputs to Lyapunov inside the numeric path: both routes are exercised
    let methods: Vec<VarianceMethod> = (0..360)
        .filter_map(|p| sweep.evaluate_numeric(p).and_then(|r| r.ok()))
        .flatten()
        .map(|s| s.method)
        .collect();
    assert!(methods.contains(&VarianceMethod::IntegralTable) && methods.contains(&VarianceMethod::Lyapunov));
}

/// The numeric builder of `scraper-rigid-cab` over ω₁ × ζ₁ × m₁ (ζ₁ < 0 refused by the reader, ζ₁ = 0
/// undamped); then a key of the schema that conflicts with the file (b₁ while the file gives ζ₁): the
/// reader refuses it ("not both"), so the study cannot even start, and says why.
#[test]
fn numeric_builder_equals_general_path_rigid_cab() {
    let sc = load_scenario(
        &crate::common::root().join("data/scraper-rigid-cab.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap();
    let spec = SweepSpec::new(
        vec![
            SweepParam::parse("model.omega1=5 rad/s..40 rad/s:5").unwrap(),
            SweepParam::parse("model.zeta1=0.1,-1,0.5,0").unwrap(),
            SweepParam::parse("model.m1=30 t,5 t").unwrap(),
        ],
        SweepMode::Grid,
    )
    .unwrap();
    let sweep = Sweep::new(&sc, spec).unwrap();
    assert!(matches!(sweep.path(), SweepPath::Numeric { .. }));
    let (ok, err, declined) = numeric_against_general(&sweep);
    eprintln!("numeric ok {ok}, numeric error {err}, declined {declined}");
    // valid: ζ₁ ∈ {0.1, 0.5}: 5·2·2 = 20 points; ζ₁ = −1: 10 declined by the reader; ζ₁ = 0: an
    // undamped single mass, not asymptotically stable: the evaluator's error on both paths (10 points)
    assert_eq!((ok, err, declined), (20, 10, 10));
    // a key in the schema that conflicts with the file's (b1 while the file gives zeta1): every point
    // declined, and the general path's message names the conflict
    let spec = SweepSpec::new(vec![SweepParam::parse("model.b1=1e5,2e5").unwrap()], SweepMode::Grid).unwrap();
    let e = Sweep::new(&sc, spec).unwrap_err().to_string();
    assert!(e.contains("not both"), "{e}");
}

/// The study says which path it takes and why: a key outside the numeric builder's keys (`model.kind`)
/// and a kind without a numeric builder both take the model-table path, name the reason, and give the
/// general path's numbers; the numeric path declines every point there.
#[test]
fn fallback_is_taken_and_said_outside_the_schema() {
    let sc = load_scenario(
        &crate::common::root().join("data/scraper-sprung-cab.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap();
    let spec = SweepSpec::new(
        vec![
            SweepParam::parse("model.kind=scraper-sprung-cab").unwrap(),
            SweepParam::parse("model.zeta2=0.2,0.4").unwrap(),
        ],
        SweepMode::Grid,
    )
    .unwrap();
    let sweep = Sweep::new(&sc, spec).unwrap();
    match sweep.path() {
        SweepPath::ModelTable { reason } => assert!(reason.contains("`model.kind`"), "{reason}"),
        other => panic!("expected the model-table path, got {other:?}"),
    }
    assert!(sweep.path().to_string().contains("model.kind"));
    for p in 0..2 {
        assert!(sweep.evaluate_numeric(p).is_none());
        assert_eq!(sweep.evaluate(p).unwrap(), sweep.evaluate_general(p).unwrap());
    }
    let qc = load_scenario(
        &crate::common::root().join("data/quarter-car-model.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap();
    let spec = SweepSpec::new(
        vec![SweepParam::parse("model.suspension_damping=1 kN*s/m,2 kN*s/m").unwrap()],
        SweepMode::Grid,
    )
    .unwrap();
    let sweep = Sweep::new(&qc, spec).unwrap();
    match sweep.path() {
        SweepPath::ModelTable { reason } => assert!(reason.contains("no numeric builder"), "{reason}"),
        other => panic!("expected the model-table path, got {other:?}"),
    }
    assert!(sweep.evaluate_numeric(0).is_none());
}

/// `WeightedEvaluator::a_w_rational` on the seat's closed-form transfer function
/// (`OperatorSeat::seat_acc_transfer`, s²(bs + c)/(m_pr s² + bs + c)) over the same 24 × 24 seat grid as
/// above: every residue value equals the Lyapunov covariance of the weighted cascade of the model's state
/// space (a different method and a different realisation) within CONDITION_CHECKED, and the state-space
/// entry `a_w` within CONDITION_CHECKED too (both carry the residue sum's estimated error ≤ 1e-9); the two
/// near-coincident-pole points fall back to Lyapunov and say so.
#[test]
fn weighted_evaluator_on_transfer_polynomials_equals_lyapunov() {
    let exc = seat_input();
    let ev = WeightedEvaluator::new(&exc, Weighting::Wk).unwrap();
    let mut residues = 0;
    for i in 0..24 {
        let k = 300.0 * 10f64.powf(5.0 * i as f64 / 23.0);
        for j in 0..24 {
            let b = 2.0 * 10f64.powf(5.0 * j as f64 / 23.0);
            let seat = OperatorSeat {
                operator_mass: 80.0,
                seat_mass: 26.0,
                stiffness: k,
                damping: b,
            }
            .build()
            .unwrap();
            let (num, den) = seat.seat_acc_transfer();
            let fast = ev.a_w_rational(&num, &den, &exc).unwrap();
            let m = seat.instance().unwrap();
            let ss = m.system.state_space().unwrap();
            let out = ss.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
            let w = weighted_output(ss, out, &Weighting::Wk).unwrap();
            let reference = variance_lyapunov(&w, &exc, 0).unwrap().variance;
            let e = rel(fast.a_w * fast.a_w, reference);
            assert!(
                e <= CONDITION_CHECKED,
                "k {k}, b {b}: {} vs {reference} ({e:e})",
                fast.a_w.powi(2)
            );
            let by_ss = ev.a_w(ss, out, &exc).unwrap().a_w;
            assert!(
                rel(fast.a_w, by_ss) <= CONDITION_CHECKED,
                "k {k}, b {b}: {} vs {by_ss}",
                fast.a_w
            );
            if fast.route == WeightedRoute::Residues {
                residues += 1;
            }
        }
    }
    assert!(residues > 24 * 24 / 2, "the residues answered only {residues} points");
    let m_pr = 5.0 / 7.0 * 80.0 + 26.0; // reduced mass of the seat model, kg (Sukharev 2012, 7.6)
    let w6 = 2.0 * std::f64::consts::PI * 3.35; // W_k's f₆ (ISO 2631-1 Table A.2)
    for (k, b) in [
        (m_pr * w6 * w6, m_pr * w6 / 0.91),
        (6500.0, 2.0 * (6500.0 * m_pr).sqrt()),
    ] {
        let seat = OperatorSeat {
            operator_mass: 80.0,
            seat_mass: 26.0,
            stiffness: k,
            damping: b,
        }
        .build()
        .unwrap();
        let (num, den) = seat.seat_acc_transfer();
        let fast = ev.a_w_rational(&num, &den, &exc).unwrap();
        assert_eq!(fast.route, WeightedRoute::LyapunovFallback, "k {k}, b {b}");
        let m = seat.instance().unwrap();
        let ss = m.system.state_space().unwrap();
        let out = ss.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
        let w = weighted_output(ss, out, &Weighting::Wk).unwrap();
        let reference = variance_lyapunov(&w, &exc, 0).unwrap().variance;
        assert!(rel(fast.a_w * fast.a_w, reference) <= CONDITION_CHECKED, "k {k}, b {b}");
    }
    // refused: a delayed (two-gain) evaluator, a numerator two degrees above the denominator
    let s = seat_input().spectra()[0].clone();
    let two = Excitation::track(s, vec![0.0, 0.0], vec![1.0, 1.0], 0.0).unwrap();
    let ev2 = WeightedEvaluator::new(&two, Weighting::Wk).unwrap();
    assert!(ev2.a_w_rational(&[1.0], &[1.0, 1.0], &two).is_err());
    assert!(ev.a_w_rational(&[0.0, 0.0, 0.0, 1.0], &[1.0, 1.0], &exc).is_err());
}
