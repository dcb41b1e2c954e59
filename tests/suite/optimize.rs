//! `stochvib optimize` and [`stochvib::optimize`]: optima against closed forms (quarter car under white
//! road velocity, base-excited oscillator, Warburton's tuned-mass absorber), an active and an inactive
//! constraint where the closed form puts them, an infeasible problem and bad input.

use crate::common;
use crate::common::tolerance::{OPTIMUM_INTERIOR, OPTIMUM_ON_CONSTRAINT};
use std::f64::consts::PI;
use std::path::PathBuf;
use stochvib::optimize::{solve, Constraint, Goal, Param, Problem, Quantity, Solution, SolveOptions};
use stochvib::scenario::{load_scenario, Scenario};

/// Quarter car (m_s = 400 kg, m_u = 40 kg, k_s = 20 kN/m, k_t = 200 kN/m, no tyre damping) on an ISO 8608
/// class C road without band limits (w = 2: the road velocity is white) at v = 20 m/s.
const QUARTER_CAR: &str = r#"
title = "Quarter car under white road velocity"
source = "test: closed forms of the white-velocity quarter car"
[model]
kind = "quarter-car"
sprung_mass = "400 kg"
unsprung_mass = "40 kg"
suspension_stiffness = "20 kN/m"
suspension_damping = "1.5 kN*s/m"
tyre_stiffness = "200 kN/m"
[input]
spectrum = { kind = "iso8608", class = "C", bound = "mean", unbounded = true }
speed = "20 m/s"
[analysis]
outputs = ["body_acc", "travel", "tyre_force"]
"#;

const M_S: f64 = 400.0;
const M_U: f64 = 40.0;
const K_S: f64 = 20e3;
const K_T: f64 = 200e3;

/// Two-sided density of the road velocity q̇ = v dq/dx for an ISO 8608 road with w = 2: the one-sided
/// cyclic spatial density G_d(n) = G_d(n₀)(n₀/n)² gives q̇ the one-sided cyclic temporal density
/// (2πf)²·G_d(f/v)/v = 4π²n₀²G_d(n₀)v, constant; two-sided angular: divide by 4π, S₀ = πn₀²G_d(n₀)v.
/// Class C: G_d(n₀) = 256·10⁻⁶ m³ at n₀ = 0.1 cycles/m (ISO 8608:2016 Table 3); S₀ = 1.608495·10⁻⁴ m²/s.
fn s0() -> f64 {
    PI * 0.1f64.powi(2) * 256e-6 * 20.0
}

/// Writes `text` as a scenario in a scratch directory and loads it.
fn scenario(tag: &str, text: &str) -> Scenario {
    let dir = common::scratch_dir("optimize", tag);
    let path = dir.join("scenario.toml");
    std::fs::write(&path, text).unwrap();
    load_scenario(&path, &common::root().join("spectra")).unwrap()
}

fn run(sc: &Scenario, params: &[&str], goal: Goal, objective: &str, constraints: &[&str]) -> Solution {
    let params = params.iter().map(|p| Param::parse(p).unwrap()).collect();
    let flag = if goal == Goal::Minimize {
        "--minimize"
    } else {
        "--maximize"
    };
    let objective = Quantity::parse(flag, objective, sc).unwrap();
    let constraints = constraints.iter().map(|c| Constraint::parse(c, sc).unwrap()).collect();
    let problem = Problem::new(sc, params, objective, goal, constraints).unwrap();
    solve(&problem, &SolveOptions::default()).unwrap()
}

/// Quarter car: with the state X = [x_s − x_u, ẋ_s, x_u − q, ẋ_u] driven by white q̇ of density S₀, the
/// stationary Lyapunov equation AP + PAᵀ + 2πS₀BBᵀ = 0 solved by hand (M = m_s + m_u) gives
///
/// σ²_acc = πS₀(k_t c² + k_s²M)/(c m_s²),  σ²_travel = πS₀M/c.
///
/// d/dc of (k_t c² + k_s²M)/c is k_t − k_s²M/c², zero at c_opt = k_s√(M/k_t) = 938.083152 N s/m, where
/// σ²_acc = 2πS₀k_s√(k_t M)/m_s² (σ_acc = 1.08861804 m/s²). These are the classical white-velocity
/// results (Gobbi & Mastinu 2001, J. Sound Vib. 245(3) 457–481, derive the same closed forms).
#[test]
fn quarter_car_comfort_optimum_is_ks_sqrt_m_over_kt() {
    let sc = scenario("qc-free", QUARTER_CAR);
    let a = run(
        &sc,
        &["model.suspension_damping=0.2:6 kN*s/m"],
        Goal::Minimize,
        "sigma(body_acc)",
        &[],
    );
    let m = M_S + M_U;
    let c_opt = K_S * (m / K_T).sqrt();
    let var_min = 2.0 * PI * s0() * K_S * (K_T * m).sqrt() / (M_S * M_S);
    assert!(common::rel(a.params[0].value, c_opt) < OPTIMUM_INTERIOR, "{a}");
    assert!(
        common::rel(a.value, var_min.sqrt()) < OPTIMUM_INTERIOR * OPTIMUM_INTERIOR,
        "{a}"
    );
    assert!(a.feasible && a.params[0].at_bound.is_none(), "{a}");
}

/// Minimise σ_acc subject to 3σ_travel ≤ d. With σ²_travel = πS₀M/c (above) the constraint is
/// c ≥ c_min = 9πS₀M/d², and σ²_acc is convex in c with its minimum at c_opt, so the optimum is
/// c* = max(c_opt, c_min). d = 40 mm: c_min = 1250.6763 N s/m > c_opt = 938.08: the constraint is active
/// and c* = c_min, where 3σ_travel = d exactly and σ_acc = 1.111054 m/s².
///
/// The search is SLSQP (the default here), and every start ends by its own stopping tests (a step below
/// `x_tolerance` of the range, or a change of the objective below its relative tolerance), none
/// `RoundoffLimited`: the `slsqp` crate runs those tests only at feasible points, and at c* the constraint's
/// value is the limit to a rounding, so a start whose last points fall a rounding above and below the limit
/// cannot stop unless a violation at rounding level counts as met (before it did, two of the four starts
/// here cycled at c* until `RoundoffLimited`).
#[test]
fn quarter_car_travel_constraint_active_where_the_closed_form_says() {
    let sc = scenario("qc-active", QUARTER_CAR);
    let a = run(
        &sc,
        &["model.suspension_damping=0.2:6 kN*s/m"],
        Goal::Minimize,
        "sigma(body_acc)",
        &["3sigma(travel) <= 40 mm"],
    );
    let m = M_S + M_U;
    let c_min = 9.0 * PI * s0() * m / 0.04f64.powi(2);
    assert!(c_min > K_S * (m / K_T).sqrt());
    assert!(common::rel(a.params[0].value, c_min) < OPTIMUM_ON_CONSTRAINT, "{a}");
    let var_acc = PI * s0() * (K_T * c_min * c_min + K_S * K_S * m) / (c_min * M_S * M_S);
    assert!(common::rel(a.value, var_acc.sqrt()) < OPTIMUM_ON_CONSTRAINT, "{a}");
    let c = &a.constraints[0];
    assert!(a.feasible && c.active && c.met, "{a}");
    assert!(common::rel(c.value, 0.04) < OPTIMUM_ON_CONSTRAINT, "{a}");
    assert_eq!(a.method, stochvib::optimize::Method::Slsqp, "{a}");
    for s in &a.starts {
        assert!(
            matches!(s.status.as_str(), "XtolReached" | "FtolReached"),
            "{:?}",
            a.starts
        );
    }
}

/// As above with d = 60 mm: c_min = 9πS₀M/d² = 555.8561 N s/m < c_opt, so the optimum is c_opt and the
/// constraint is inactive with the margin d − 3√(πS₀M/c_opt) = 60 − 46.186 mm.
#[test]
fn quarter_car_travel_constraint_inactive_where_the_closed_form_says() {
    let sc = scenario("qc-inactive", QUARTER_CAR);
    let a = run(
        &sc,
        &["model.suspension_damping=0.2:6 kN*s/m"],
        Goal::Minimize,
        "sigma(body_acc)",
        &["3sigma(travel) <= 60 mm"],
    );
    let m = M_S + M_U;
    let c_opt = K_S * (m / K_T).sqrt();
    assert!(common::rel(a.params[0].value, c_opt) < OPTIMUM_INTERIOR, "{a}");
    let margin = 0.06 - 3.0 * (PI * s0() * m / c_opt).sqrt();
    let c = &a.constraints[0];
    assert!(!c.active && c.met, "{a}");
    assert!(common::rel(c.margin, margin) < OPTIMUM_INTERIOR, "{a}");
}

/// 3σ_travel ≤ 5 mm needs c ≥ 9πS₀M/d² = 8.0·10⁴ N s/m, beyond the upper bound 6 kN s/m: infeasible. The
/// least violating point is the upper bound (σ_travel falls with c), where 3σ_travel = 3√(πS₀M/6000)
/// = 18.26 mm: the answer says the constraint cannot be met and by how much.
#[test]
fn quarter_car_infeasible_constraint_named_with_its_shortfall() {
    let sc = scenario("qc-infeasible", QUARTER_CAR);
    let a = run(
        &sc,
        &["model.suspension_damping=0.2:6 kN*s/m"],
        Goal::Minimize,
        "sigma(body_acc)",
        &["3sigma(travel) <= 5 mm"],
    );
    let at_bound = 3.0 * (PI * s0() * (M_S + M_U) / 6000.0).sqrt();
    assert!(!a.feasible, "{a}");
    assert_eq!(a.params[0].at_bound, Some("upper"), "{a}");
    let c = &a.constraints[0];
    assert!(!c.met && common::rel(c.value, at_bound) < OPTIMUM_ON_CONSTRAINT, "{a}");
    let v = a.violations();
    assert!(
        v.len() == 1 && v[0].contains("3sigma(travel) <= 5 mm") && v[0].contains("cannot be met"),
        "{v:?}"
    );
    assert!(common::rel(-c.margin, at_bound - 0.005) < OPTIMUM_ON_CONSTRAINT, "{a}");
}

/// Base-excited oscillator (ω₀ = 2π·1.5 rad/s) under white base acceleration ü of density S₀ = 0.01: in the
/// relative coordinate z = x − u, m z̈ + c ż + k z = −m ü, so the model is a unit mass on a mount to ground
/// driven by the force −m ü (white, density m²S₀), and the absolute acceleration is ẍ = −(c ż + k z)/m: σ_ẍ
/// is σ of the mount's element force over m = 1 kg. H(s) = (ω₀² + 2ζω₀s)/(s² + 2ζω₀s + ω₀²) and the
/// integral table I₂ = π(B₀²/A₀ + B₁²/A₂)/A₁ give σ²_ẍ = πS₀ω₀(1 + 4ζ²)/(2ζ), least at ζ = ½ (d/dζ of
/// 1/(2ζ) + 2ζ vanishes), σ²_min = 2πS₀ω₀. ζ = ½ is c = 2ζ√(km) = √k = ω₀ (m = 1 kg).
#[test]
fn base_excited_oscillator_absolute_acceleration_optimum_is_zeta_half() {
    let w0 = 2.0 * PI * 1.5;
    let text = format!(
        r#"
title = "SDOF under white base acceleration, relative coordinate"
source = "test"
[model]
kind = "mdof"
coordinates = [{{ name = "z", unit = "m", mass = "1 kg" }}]
forces = [[1.0]]
[[model.element]]
name = "mount"
point = [1.0]
to = "ground"
stiffness = "{k} N/m"
damping = "5 N*s/m"
[[model.output]]
name = "mount_force"
quantity = "element-force"
element = "mount"
[input]
spectrum = {{ kind = "rational", unit = "N", numerator = [0.01], denominator = [1.0] }}
"#,
        k = w0 * w0
    );
    let sc = scenario("sdof", &text);
    let a = run(
        &sc,
        &["model.element.0.damping=1:40 N*s/m"],
        Goal::Minimize,
        "sigma(mount_force)",
        &[],
    );
    assert!(common::rel(a.params[0].value, w0) < OPTIMUM_INTERIOR, "{a}");
    assert!(
        common::rel(a.value, (2.0 * PI * 0.01 * w0).sqrt()) < OPTIMUM_INTERIOR * OPTIMUM_INTERIOR,
        "{a}"
    );
}

/// A main mass M = 1 kg on a spring K = 1 N/m (ω_M = 1 rad/s, undamped) with an absorber m = μM on a spring
/// k_a and damper c_a; f = ω_a/ω_M = √(k_a/m), ζ_a = c_a/(2√(k_a m)). `forces` drives the main mass (case F)
/// or both masses in proportion to their mass (case A: base acceleration in coordinates relative to the
/// base, −M ü and −m ü); the objective is σ of the main mass's (relative) displacement.
fn absorber(tag: &str, force_point: &str, mu: f64) -> Scenario {
    let text = format!(
        r#"
title = "Tuned-mass absorber on an undamped main system"
source = "test: Warburton (1982)"
[model]
kind = "mdof"
coordinates = [{{ name = "main", unit = "m", mass = "1 kg" }}, {{ name = "absorber", unit = "m", mass = "{mu} kg" }}]
forces = [{force_point}]
[[model.element]]
name = "main_spring"
point = [1.0, 0.0]
to = "ground"
stiffness = "1 N/m"
[[model.element]]
name = "absorber"
point = [0.0, 1.0]
to = [1.0, 0.0]
stiffness = "{k} N/m"
damping = "{c} N*s/m"
[[model.output]]
name = "main"
quantity = "displacement"
point = [1.0, 0.0]
[input]
spectrum = {{ kind = "rational", unit = "N", numerator = [1.0], denominator = [1.0] }}
"#,
        k = mu * 0.9 * 0.9,
        c = 2.0 * mu * 0.1 * 0.9,
    );
    scenario(tag, &text)
}

/// The optimum (f, ζ) of an absorber problem over k_a ∈ [0.6, 1.2]·μ, c_a ∈ [0.02, 0.5]·μ.
fn absorber_optimum(sc: &Scenario, mu: f64) -> (f64, f64) {
    let params = [
        format!("model.element.1.stiffness={}:{} N/m", 0.6 * mu, 1.2 * mu),
        format!("model.element.1.damping={}:{} N*s/m", 0.02 * mu, 0.5 * mu),
    ];
    let p: Vec<&str> = params.iter().map(String::as_str).collect();
    let a = run(sc, &p, Goal::Minimize, "sigma(main)", &[]);
    let (k, c) = (a.params[0].value, a.params[1].value);
    ((k / mu).sqrt(), c / (2.0 * (k * mu).sqrt()))
}

/// Warburton (1982), "Optimum absorber parameters for various combinations of response and excitation
/// parameters", Earthquake Eng. Struct. Dyn. 10, 381–401: for white-noise force on the undamped main mass,
/// the displacement variance is least at f = √(1 + μ/2)/(1 + μ), ζ = √(μ(1 + 3μ/4)/(4(1 + μ)(1 + μ/2))).
/// At μ = 0.05: f = 0.96421223, ζ = 0.10977223 (an independent Lyapunov + Nelder–Mead minimisation in
/// scipy agreed to 8 digits).
#[test]
fn warburton_absorber_under_white_force() {
    let mu = 0.05;
    let sc = absorber("warburton-f", "[1.0, 0.0]", mu);
    let (f, z) = absorber_optimum(&sc, mu);
    let f_opt = (1.0 + mu / 2.0).sqrt() / (1.0 + mu);
    let z_opt = (mu * (1.0 + 0.75 * mu) / (4.0 * (1.0 + mu) * (1.0 + mu / 2.0))).sqrt();
    assert!(common::rel(f, f_opt) < OPTIMUM_INTERIOR, "f = {f}, expected {f_opt}");
    assert!(common::rel(z, z_opt) < OPTIMUM_INTERIOR, "ζ = {z}, expected {z_opt}");
}

/// Warburton (1982), as above, for white base acceleration and the displacement of the main mass relative
/// to the base: f = √(1 − μ/2)/(1 + μ), ζ = √(μ(1 − μ/4)/(4(1 + μ)(1 − μ/2))); at μ = 0.05 f = 0.94040084,
/// ζ = 0.10980613.
#[test]
fn warburton_absorber_under_white_base_acceleration() {
    let mu = 0.05;
    let sc = absorber("warburton-a", &format!("[1.0, {mu}]"), mu);
    let (f, z) = absorber_optimum(&sc, mu);
    let f_opt = (1.0 - mu / 2.0).sqrt() / (1.0 + mu);
    let z_opt = (mu * (1.0 - 0.25 * mu) / (4.0 * (1.0 + mu) * (1.0 - mu / 2.0))).sqrt();
    assert!(common::rel(f, f_opt) < OPTIMUM_INTERIOR, "f = {f}, expected {f_opt}");
    assert!(common::rel(z, z_opt) < OPTIMUM_INTERIOR, "ζ = {z}, expected {z_opt}");
}

/// Maximising: the largest σ_travel over c ∈ [0.2, 6] kN s/m is at the lower bound (σ²_travel = πS₀M/c
/// falls with c), and the answer says the parameter is at its lower bound.
#[test]
fn maximum_at_a_bound_is_named() {
    let sc = scenario("qc-max", QUARTER_CAR);
    let a = run(
        &sc,
        &["model.suspension_damping=0.2:6 kN*s/m"],
        Goal::Maximize,
        "sigma(travel)",
        &[],
    );
    assert_eq!(a.params[0].at_bound, Some("lower"), "{a}");
    let expected = (PI * s0() * (M_S + M_U) / 200.0).sqrt();
    assert!(common::rel(a.value, expected) < OPTIMUM_ON_CONSTRAINT, "{a}");
}

fn data_dir() -> PathBuf {
    common::root().join("data")
}

fn catalogue_quarter_car() -> Scenario {
    load_scenario(
        &data_dir().join("quarter-car-model.toml"),
        &common::root().join("spectra"),
    )
    .unwrap()
}

/// Bounds the wrong way round, a parameter the scenario does not have, an unknown quantity, an output the
/// model does not have, a limit of the wrong dimension: each refused with the flag and the reason.
#[test]
fn bad_input_is_refused_clearly() {
    let e = Param::parse("model.suspension_damping=6:0.2 kN*s/m")
        .unwrap_err()
        .to_string();
    assert!(e.contains("--param") && e.contains("wrong way round"), "{e}");
    let sc = catalogue_quarter_car();
    let q = || Quantity::parse("--minimize", "sigma(body_acc)", &sc).unwrap();
    let p = vec![Param::parse("model.no_such_key=1:2 kN/m").unwrap()];
    let e = Problem::new(&sc, p, q(), Goal::Minimize, vec![])
        .unwrap_err()
        .to_string();
    assert!(e.contains("model.no_such_key") && e.contains("no such value"), "{e}");
    let e = Quantity::parse("--minimize", "comfort", &sc).unwrap_err().to_string();
    assert!(e.contains("--minimize") && e.contains("unknown quantity"), "{e}");
    let e = Quantity::parse("--minimize", "sigma(seat)", &sc)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no output `seat`") && e.contains("body_acc"), "{e}");
    let e = Constraint::parse("3sigma(travel) <= 40 kg", &sc)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--constraint") && e.contains("dimension"), "{e}");
    let e = Quantity::parse("--minimize", "a_v", &sc).unwrap_err().to_string();
    assert!(e.contains("[analysis.comfort]"), "{e}");
}

/// The command: the catalogue quarter car (m_s = 300 kg) with the travel constraint prints the optimum and
/// names the constraint; an infeasible one fails (status 1) naming the constraint and its shortfall.
#[test]
fn command_prints_the_answer_and_fails_when_infeasible() {
    let root = common::root();
    let args = [
        "optimize",
        "data/quarter-car-model.toml",
        "--param",
        "model.suspension_damping=0.2:6 kN*s/m",
        "--minimize",
        "sigma(body_acc)",
        "--constraint",
        "3sigma(travel) <= 40 mm",
    ];
    let o = common::cli_within(&args, &root, std::time::Duration::from_secs(120));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}\n{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        out.contains("minimum of sigma(body_acc)") && out.contains("3sigma(travel) <= 40 mm"),
        "{out}"
    );
    let mut bad = args;
    bad[7] = "3sigma(travel) <= 1 mm";
    let err = common::cli_fails(1, &bad, &root);
    assert!(
        err.contains("infeasible") && err.contains("3sigma(travel) <= 1 mm") && err.contains("beyond"),
        "{err}"
    );
    let err = common::cli_fails(
        1,
        &[
            "optimize",
            "data/quarter-car-model.toml",
            "--param",
            "model.suspension_damping=6:0.2 kN*s/m",
            "--minimize",
            "sigma(body_acc)",
        ],
        &root,
    );
    assert!(err.contains("wrong way round"), "{err}");
}

/// σ_acc against σ_travel of `sc` over c ∈ [0.2, 6] kN s/m, without constraints.
fn comfort_travel(sc: &Scenario) -> stochvib::optimize::ParetoProblem<'_> {
    stochvib::optimize::ParetoProblem {
        base: sc,
        params: vec![Param::parse("model.suspension_damping=0.2:6 kN*s/m").unwrap()],
        quantities: [
            Quantity::parse("--minimize", "sigma(body_acc)", sc).unwrap(),
            Quantity::parse("--pareto", "sigma(travel)", sc).unwrap(),
        ],
        constraints: Vec::new(),
    }
}

/// The Pareto front of comfort against travel for the white-velocity quarter car, c ∈ [0.2, 6] kN s/m.
/// With σ²_acc(c) = πS₀(k_t c² + k_s²M)/(c m_s²) and σ²_travel(c) = πS₀M/c (above), σ_travel falls with c
/// everywhere and σ_acc rises for c > c_opt, so the front is the curve (σ_acc(c), σ_travel(c)) for
/// c ∈ [c_opt, 6000]: its ends are c_opt (min σ_acc, interior) and the upper bound (min σ_travel), and the
/// point with the limit ε on σ_travel sits where the limit is active, c = πS₀M/ε², with σ_acc(c) there.
#[test]
fn quarter_car_pareto_front_of_comfort_and_travel_is_the_closed_form_curve() {
    use stochvib::optimize::pareto;
    let sc = scenario("qc-pareto", QUARTER_CAR);
    let problem = comfort_travel(&sc);
    let front = pareto(&problem, 5, &SolveOptions::default()).unwrap();
    assert_eq!(front.points.len(), 5);
    let m = M_S + M_U;
    let acc = |c: f64| (PI * s0() * (K_T * c * c + K_S * K_S * m) / (c * M_S * M_S)).sqrt();
    let travel = |c: f64| (PI * s0() * m / c).sqrt();
    let c_opt = K_S * (m / K_T).sqrt();
    let first = &front.points[0];
    assert!(common::rel(first.params[0], c_opt) < OPTIMUM_INTERIOR, "{first:?}");
    let last = &front.points[4];
    assert!(common::rel(last.params[0], 6000.0) < OPTIMUM_ON_CONSTRAINT, "{last:?}");
    for p in &front.points[1..4] {
        let eps = p.limit.unwrap();
        let c = PI * s0() * m / (eps * eps);
        assert!(p.feasible);
        assert!(common::rel(p.params[0], c) < OPTIMUM_ON_CONSTRAINT, "{p:?} vs c = {c}");
        assert!(common::rel(p.values[0], acc(c)) < OPTIMUM_ON_CONSTRAINT, "{p:?}");
        assert!(common::rel(p.values[1], travel(c)) < OPTIMUM_ON_CONSTRAINT, "{p:?}");
    }
    for w in front.points.windows(2) {
        assert!(
            w[0].values[0] < w[1].values[0] && w[0].values[1] > w[1].values[1],
            "{:?}",
            front.points
        );
    }
    assert!(front
        .to_csv()
        .starts_with("point,model.suspension_damping [SI],sigma(body_acc) [m/s^2],sigma(travel) [m],"));
}

/// `stochvib optimize --pareto`: the front as a CSV table (a header with the units, one row per point, the
/// first quantity rising and the second falling along it), and `--points 1` refused by its flag.
#[test]
fn command_prints_the_pareto_front() {
    let root = common::root();
    let mut args = vec![
        "optimize",
        "data/quarter-car-model.toml",
        "--param",
        "model.suspension_damping=0.2:6 kN*s/m",
        "--minimize",
        "sigma(body_acc)",
        "--pareto",
        "sigma(travel)",
        "--points",
        "3",
    ];
    let o = common::cli_within(&args, &root, std::time::Duration::from_secs(300));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}\n{}", String::from_utf8_lossy(&o.stderr));
    let mut lines = out.lines();
    assert_eq!(
        lines.next().unwrap(),
        "point,model.suspension_damping [SI],sigma(body_acc) [m/s^2],sigma(travel) [m],limit,feasible"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').skip(1).take(3).map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 3, "{out}");
    for w in rows.windows(2) {
        assert!(w[0][1] < w[1][1] && w[0][2] > w[1][2], "{out}");
    }
    args[9] = "1";
    let err = common::cli_fails(1, &args, &root);
    assert!(err.contains("--points"), "{err}");
}

/// σ²_tyre of the white-velocity quarter car without tyre damping (M = m_s + m_u), from the stationary
/// Lyapunov equation of the state [x_s − x_u, ẋ_s, x_u − q, ẋ_u] driven by q̇ solved symbolically (sympy):
/// πS₀[k_t c²M² + k_s²M³ − 2k_s k_t m_s m_u M + k_t² m_s² m_u]/(c m_s²).
fn tyre_force_variance(c: f64) -> f64 {
    let m = M_S + M_U;
    PI * s0()
        * (K_T * c * c * m * m + K_S * K_S * m.powi(3) - 2.0 * K_S * K_T * M_S * M_U * m + K_T * K_T * M_S * M_S * M_U)
        / (c * M_S * M_S)
}

/// The integrated-white route of the exact evaluator: the white-velocity quarter car's variances by one
/// Lyapunov solve of the realization of H(s)/s equal the closed forms σ²_acc = πS₀(k_t c² + k_s²M)/(c m_s²),
/// σ²_travel = πS₀M/c and σ²_tyre (above) to rounding, and the quadrature of the output density within its
/// tolerance; the body's absolute displacement (H(0) = 1) has an infinite variance, as quadrature says;
/// λ₂ of the travel equals quadrature's, and `variances_only` leaves it out.
#[test]
fn integrated_white_road_velocity_has_an_exact_lyapunov_route() {
    use crate::common::tolerance::{EXACT_TRANSITIONS, QUADRATURE};
    use stochvib::response::{spectral_moment_quadrature, variance_quadrature, ExactEvaluator, VarianceMethod};
    let sc = scenario("qc-white-route", QUARTER_CAR);
    let sys = sc.model.system.as_ref();
    let idx = |o: &str| sys.output_index(o).unwrap();
    let outputs = [idx("body_acc"), idx("travel"), idx("tyre_force"), idx("body")];
    let ev = ExactEvaluator::new(&sc.excitation);
    assert_eq!(ev.method(Some(4)), VarianceMethod::Lyapunov);
    let st = ev.evaluate(sys, &sc.excitation, &outputs).unwrap();
    let (c, m) = (1500.0, M_S + M_U);
    let closed = [
        PI * s0() * (K_T * c * c + K_S * K_S * m) / (c * M_S * M_S),
        PI * s0() * m / c,
        tyre_force_variance(c),
    ];
    for ((s, &want), &i) in st.iter().zip(&closed).zip(&outputs) {
        let v = s.variance.unwrap();
        assert_eq!(s.method, VarianceMethod::Lyapunov);
        assert!(common::rel(v, want) < EXACT_TRANSITIONS, "output {i}: {v} vs {want}");
        let q = variance_quadrature(sys, &sc.excitation, i).unwrap().value;
        assert!(common::rel(v, q) < QUADRATURE, "output {i}: {v} vs quadrature {q}");
    }
    assert!(st[3].variance.is_none(), "{:?}", st[3]);
    assert!(variance_quadrature(sys, &sc.excitation, outputs[3]).is_err());
    let l2 = spectral_moment_quadrature(sys, &sc.excitation, outputs[1], 2)
        .unwrap()
        .value;
    assert!(common::rel(st[1].lambda2.unwrap(), l2) < QUADRATURE);
    let only = ev.variances_only().evaluate(sys, &sc.excitation, &outputs).unwrap();
    assert!(only.iter().all(|s| s.lambda2.is_none()));
    assert_eq!(only[1].variance, st[1].variance);
}

/// The analytic sensitivities: for the white-velocity quarter car, d/dc of σ²_acc = πS₀(k_t c² + k_s²M)/(c m_s²)
/// is πS₀(k_t − k_s²M/c²)/m_s² and of σ²_travel = πS₀M/c is −πS₀M/c², so dσ/dc = (dσ²/dc)/(2σ) (sympy's
/// derivative of its Lyapunov solution agrees); checked at c = 1.5 kN s/m for σ_acc and 3σ_travel, and
/// against central finite differences of the evaluated quantities (step 10⁻⁴c).
#[test]
fn variance_sensitivities_match_the_closed_form_and_finite_differences() {
    use crate::common::tolerance::{GRADIENT_CLOSED_FORM, GRADIENT_FINITE_DIFFERENCE};
    let sc = scenario("qc-gradient", QUARTER_CAR);
    let params = vec![Param::parse("model.suspension_damping=0.2:6 kN*s/m").unwrap()];
    let objective = Quantity::parse("--minimize", "sigma(body_acc)", &sc).unwrap();
    let travel = Constraint::parse("3sigma(travel) <= 40 mm", &sc).unwrap();
    let problem = Problem::new(&sc, params, objective, Goal::Minimize, vec![travel]).unwrap();
    let (c, m) = (1500.0, M_S + M_U);
    let g = problem.gradients(&[c]).unwrap().unwrap();
    let acc = (PI * s0() * (K_T * c * c + K_S * K_S * m) / (c * M_S * M_S)).sqrt();
    let d_acc = PI * s0() * (K_T - K_S * K_S * m / (c * c)) / (M_S * M_S) / (2.0 * acc);
    let tr = (PI * s0() * m / c).sqrt();
    let d_3tr = 3.0 * (-PI * s0() * m / (c * c)) / (2.0 * tr);
    assert!(
        common::rel(g.objective[0], d_acc) < GRADIENT_CLOSED_FORM,
        "{g:?} vs {d_acc}"
    );
    assert!(
        common::rel(g.constrained[0][0], d_3tr) < GRADIENT_CLOSED_FORM,
        "{g:?} vs {d_3tr}"
    );
    let h = 1e-4 * c;
    let (p, q) = (problem.evaluate(&[c + h]).unwrap(), problem.evaluate(&[c - h]).unwrap());
    let fd_acc = (p.objective - q.objective) / (2.0 * h);
    let fd_tr = (p.constrained[0] - q.constrained[0]) / (2.0 * h);
    assert!(
        common::rel(g.objective[0], fd_acc) < GRADIENT_FINITE_DIFFERENCE,
        "{g:?} vs {fd_acc}"
    );
    assert!(
        common::rel(g.constrained[0][0], fd_tr) < GRADIENT_FINITE_DIFFERENCE,
        "{g:?} vs {fd_tr}"
    );
}

/// The sensitivities on the rational-input route (the augmented system): the tuned-mass absorber under
/// white force, σ of the main mass over the absorber's stiffness and damping, against central finite
/// differences of the evaluated σ (step 10⁻⁴ of each value).
#[test]
fn variance_sensitivities_of_the_absorber_match_finite_differences() {
    use crate::common::tolerance::GRADIENT_FINITE_DIFFERENCE;
    let mu = 0.05;
    let sc = absorber("absorber-gradient", "[1.0, 0.0]", mu);
    let params = vec![
        Param::parse(&format!("model.element.1.stiffness={}:{} N/m", 0.6 * mu, 1.2 * mu)).unwrap(),
        Param::parse(&format!("model.element.1.damping={}:{} N*s/m", 0.02 * mu, 0.5 * mu)).unwrap(),
    ];
    let objective = Quantity::parse("--minimize", "sigma(main)", &sc).unwrap();
    let problem = Problem::new(&sc, params, objective, Goal::Minimize, Vec::new()).unwrap();
    let x = [0.9 * mu, 0.1 * mu];
    let g = problem.gradients(&x).unwrap().unwrap();
    for (k, &xk) in x.iter().enumerate() {
        let h = 1e-4 * xk;
        let mut p = x;
        let mut q = x;
        p[k] += h;
        q[k] -= h;
        let fd = (problem.evaluate(&p).unwrap().objective - problem.evaluate(&q).unwrap().objective) / (2.0 * h);
        assert!(
            common::rel(g.objective[k], fd) < GRADIENT_FINITE_DIFFERENCE,
            "{k}: {g:?} vs {fd}"
        );
    }
}

/// The KKT check at the answers: on the active travel constraint (d = 40 mm) the objective's gradient is the
/// constraint's times a positive multiplier, μ = (σ_acc'/σ_acc)/(3σ_travel'·(−1)/d) in unit coordinates
/// (from the closed-form derivatives above at c* = 9πS₀M/d²; the answer is within `OPTIMUM_ON_CONSTRAINT` of
/// c*, where both derivatives vary by O(1) relative per relative change of c, so μ is compared within
/// `OPTIMUM_INTERIOR`); at the interior optimum (d = 60 mm) the gradient vanishes and the inactive
/// constraint's multiplier is 0.
#[test]
fn kkt_check_at_the_quarter_car_optima() {
    use stochvib::optimize::KKT_TOLERANCE;
    let sc = scenario("qc-kkt", QUARTER_CAR);
    let p = ["model.suspension_damping=0.2:6 kN*s/m"];
    let a = run(&sc, &p, Goal::Minimize, "sigma(body_acc)", &["3sigma(travel) <= 40 mm"]);
    let k = a.kkt.as_ref().expect("gradients on the exact route");
    let m = M_S + M_U;
    let c = 9.0 * PI * s0() * m / 0.04f64.powi(2);
    let var_acc = PI * s0() * (K_T * c * c + K_S * K_S * m) / (c * M_S * M_S);
    let rel_acc = PI * s0() * (K_T - K_S * K_S * m / (c * c)) / (M_S * M_S) / (2.0 * var_acc);
    let rel_3tr = 3.0 * (PI * s0() * m / (c * c)) / (2.0 * (PI * s0() * m / c).sqrt()) / 0.04;
    assert!(k.satisfied && k.residual <= KKT_TOLERANCE, "{a}");
    assert!(
        common::rel(k.multipliers[0], rel_acc / rel_3tr) < OPTIMUM_INTERIOR,
        "{a}"
    );
    let text = a.to_string();
    assert!(text.contains("KKT") && text.contains("satisfied"), "{text}");
    let b = run(&sc, &p, Goal::Minimize, "sigma(body_acc)", &["3sigma(travel) <= 60 mm"]);
    let k = b.kkt.as_ref().unwrap();
    assert!(
        k.satisfied && k.multipliers[0] == 0.0 && k.residual <= KKT_TOLERANCE,
        "{b}"
    );
}

/// The picture of the front: its markers are the table's points (the values `to_csv` prints, read back),
/// and `render` writes the SVG and PNG; the command writes `pareto-front.svg` with `--plots`.
#[test]
fn pareto_front_picture_holds_the_table_points() {
    use stochvib::optimize::pareto;
    use stochvib::plot::pareto_plots::pareto_chart;
    let sc = scenario("qc-pareto-picture", QUARTER_CAR);
    let problem = comfort_travel(&sc);
    let front = pareto(&problem, 4, &SolveOptions::default()).unwrap();
    let table: Vec<(f64, f64)> = front
        .to_csv()
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').skip(2).take(2).map(|x| x.parse().unwrap()).collect();
            (v[0], v[1])
        })
        .collect();
    let chart = pareto_chart(&sc.title, &front);
    assert_eq!(chart.series[0].points, table);
    let dir = common::scratch_dir("optimize", "pareto-picture");
    let files = chart.render(&dir, "pareto-front").unwrap();
    assert!(files
        .iter()
        .all(|f| f.exists() && std::fs::metadata(f).unwrap().len() > 0));
    let svg = std::fs::read_to_string(&files[0]).unwrap();
    assert!(
        svg.contains("Pareto front") && svg.contains("sigma(travel) [m]"),
        "{svg}"
    );

    let out = common::scratch_dir("optimize", "pareto-picture-cli");
    let out_s = out.to_string_lossy().to_string();
    let args = [
        "optimize",
        "data/quarter-car-model.toml",
        "--param",
        "model.suspension_damping=0.2:6 kN*s/m",
        "--minimize",
        "sigma(body_acc)",
        "--pareto",
        "sigma(travel)",
        "--points",
        "3",
        "--plots",
        &out_s,
    ];
    let o = common::cli_within(&args, &common::root(), std::time::Duration::from_secs(300));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(out.join("pareto-front.svg")).unwrap();
    assert!(svg.trim_start().starts_with("<svg") && svg.contains("Pareto front"));
    assert!(out.join("pareto-front.png").exists());
}

/// Both searches on the white-velocity quarter car: SLSQP with the analytic gradients and COBYLA find the
/// interior optimum c_opt = k_s√(M/k_t) (`quarter_car_comfort_optimum_is_ks_sqrt_m_over_kt`) and the optimum
/// c* = 9πS₀M/d² on the active travel constraint d = 40 mm
/// (`quarter_car_travel_constraint_active_where_the_closed_form_says`), each within the same named
/// tolerance as there; the default (`auto`) takes SLSQP on these σ problems, and SLSQP needs fewer
/// evaluations than COBYLA.
#[test]
fn slsqp_and_cobyla_find_the_quarter_car_optima() {
    use stochvib::optimize::Method;
    let sc = scenario("qc-methods", QUARTER_CAR);
    let m = M_S + M_U;
    let (c_opt, c_min) = (K_S * (m / K_T).sqrt(), 9.0 * PI * s0() * m / 0.04f64.powi(2));
    let solve_with = |method: Method, constraints: &[&str]| {
        let params = vec![Param::parse("model.suspension_damping=0.2:6 kN*s/m").unwrap()];
        let objective = Quantity::parse("--minimize", "sigma(body_acc)", &sc).unwrap();
        let constraints = constraints.iter().map(|c| Constraint::parse(c, &sc).unwrap()).collect();
        let problem = Problem::new(&sc, params, objective, Goal::Minimize, constraints).unwrap();
        assert_eq!(problem.path(), "affine model");
        let opts = SolveOptions {
            method,
            ..SolveOptions::default()
        };
        solve(&problem, &opts).unwrap()
    };
    let mut evaluations = Vec::new();
    for method in [Method::Slsqp, Method::Cobyla] {
        let free = solve_with(method, &[]);
        assert_eq!(free.method, method, "{free}");
        assert!(common::rel(free.params[0].value, c_opt) < OPTIMUM_INTERIOR, "{free}");
        let on = solve_with(method, &["3sigma(travel) <= 40 mm"]);
        assert!(common::rel(on.params[0].value, c_min) < OPTIMUM_ON_CONSTRAINT, "{on}");
        assert!(on.feasible && on.constraints[0].active, "{on}");
        assert!(on
            .to_string()
            .contains(if method == Method::Slsqp { "SLSQP" } else { "COBYLA" }));
        evaluations.push(free.evaluations + on.evaluations);
    }
    assert!(evaluations[0] < evaluations[1], "SLSQP {evaluations:?} COBYLA");
    assert_eq!(solve_with(Method::Auto, &[]).method, Method::Slsqp);
}

/// A problem without analytic gradients (the catalogue quarter car's ISO 8608 road is band-limited, so its σ
/// has no exact route and is computed by quadrature of the output density): `auto` takes COBYLA, and
/// `--method slsqp` is refused naming the flag and what to use instead.
#[test]
fn slsqp_is_refused_without_gradients_and_auto_takes_cobyla() {
    use stochvib::optimize::Method;
    let sc = catalogue_quarter_car();
    let problem = |sc| {
        let params = vec![Param::parse("model.suspension_damping=0.5:4 kN*s/m").unwrap()];
        let objective = Quantity::parse("--minimize", "sigma(body_acc)", sc).unwrap();
        Problem::new(sc, params, objective, Goal::Minimize, vec![]).unwrap()
    };
    let pb = problem(&sc);
    assert!(!pb.has_gradients());
    let e = Method::Slsqp.for_problem(&pb).unwrap_err().to_string();
    assert!(e.contains("--method") && e.contains("cobyla"), "{e}");
    assert_eq!(Method::Auto.for_problem(&pb).unwrap(), Method::Cobyla);
    assert!(Method::parse("newton").unwrap_err().to_string().contains("--method"));
}

/// The affine model of the search (stiffness and damping enter the matrices affinely) gives the values of
/// the scenario reader's model at points across the box, within `AFFINE_MODEL` (the matrices agree to
/// rounding); a mass enters through M⁻¹, so a problem over the sprung mass rebuilds the model per point.
#[test]
fn affine_model_gives_the_values_of_the_readers_model() {
    use crate::common::tolerance::AFFINE_MODEL;
    let sc = scenario("qc-affine", QUARTER_CAR);
    let problem = |params: &[&str]| {
        let params = params.iter().map(|p| Param::parse(p).unwrap()).collect();
        let objective = Quantity::parse("--minimize", "sigma(body_acc)", &sc).unwrap();
        let travel = Constraint::parse("3sigma(travel) <= 40 mm", &sc).unwrap();
        Problem::new(&sc, params, objective, Goal::Minimize, vec![travel]).unwrap()
    };
    let pb = problem(&[
        "model.suspension_damping=0.2:6 kN*s/m",
        "model.suspension_stiffness=10:40 kN/m",
        "model.tyre_stiffness=100:400 kN/m",
    ]);
    assert_eq!(pb.path(), "affine model");
    for x in [
        [200.0, 10e3, 100e3],
        [6000.0, 40e3, 400e3],
        [777.0, 13e3, 350e3],
        [4321.0, 39e3, 123e3],
    ] {
        let (a, r) = (pb.evaluate(&x).unwrap(), pb.evaluate_by_reader(&x).unwrap());
        assert!(common::rel(a.objective, r.objective) < AFFINE_MODEL, "{a:?} {r:?}");
        assert!(
            common::rel(a.constrained[0], r.constrained[0]) < AFFINE_MODEL,
            "{a:?} {r:?}"
        );
    }
    assert_eq!(problem(&["model.sprung_mass=300:500 kg"]).path(), "model table");
}
