//! `optimize` cases: a shipped scenario with hostile `stochvib optimize` flags — parameters and their bounds
//! (`--param KEY=LOW:HIGH UNIT`), the objective (`--minimize`/`--maximize`), constraints (`--constraint "Q <=
//! VALUE UNIT"`), `--starts` and `--max-evaluations` — evaluated through the library as the CLI's handler
//! calls it. The invariants are those of [`super::commands`]: an error names the scenario file or the flag,
//! a success prints no NaN or infinity. An infeasible problem is an answer (printed) and a failure of the
//! CLI (status 1, "infeasible"), not a refusal.
//!
//! The searches are kept short (1–2 starts, at most 30 evaluations each) so that a case stays well inside
//! the per-case time limit; the scenarios are the cheap ones of `data/` (no delays, no nonlinear elements).

use super::commands::{clap_refusal as clap, fail, number_unit, ok, CommandCorpus, Context};
use super::inputs::{Case, Outcome};
use super::mutate::Rng;
use rand::RngExt;
use stochvib::optimize::{solve, Constraint, Goal, Param, Problem, Quantity, SolveOptions};
use toml::Value;

/// The scenarios of `data/` an optimize case may start from.
pub const SCENARIOS: [&str; 5] = [
    "data/quarter-car-model.toml",
    "data/quarter-car.toml",
    "data/operator-seat-verdicts.toml",
    "data/isolator-single.toml",
    "data/scraper-rigid-cab.toml",
];

fn pick<'a>(rng: &mut Rng, v: &[&'a str]) -> &'a str {
    v[rng.random_range(0..v.len())]
}

/// A hostile number, or `x` scaled by up to a decade either way.
fn number(rng: &mut Rng, x: f64, lo: f64, hi: f64) -> String {
    match rng.random_range(0..16) {
        0 => "NaN".into(),
        1 => "1e308".into(),
        2 => "-1".into(),
        3 => "0".into(),
        4 => "abc".into(),
        5 => "inf".into(),
        _ => format!("{:e}", x * 10f64.powf(rng.random_range(lo..hi))),
    }
}

/// One `--param KEY=LOW:HIGH UNIT` text from the scenario's numeric keys.
fn param(rng: &mut Rng, keys: &[(String, Value)]) -> String {
    let (key, v) = if keys.is_empty() || rng.random_bool(0.08) {
        let k = [
            "model.nope",
            "title",
            "input.spectrum",
            "model.element.99.stiffness",
            "",
            "model.",
        ];
        (pick(rng, &k).to_string(), Value::Float(1.0))
    } else {
        keys[rng.random_range(0..keys.len())].clone()
    };
    let (x, unit) = number_unit(&v);
    let unit = match rng.random_range(0..20) {
        0 => "furlong".to_string(),
        1 => String::new(),
        2 => "kg".to_string(),
        _ => unit,
    };
    let (lo, hi) = (number(rng, x, -1.0, 0.0), number(rng, x, 0.0, 1.0));
    let bounds = match rng.random_range(0..12) {
        0 => format!("{hi}:{lo} {unit}"),
        1 => format!("{lo}:{lo} {unit}"),
        2 => format!("{lo} {unit}:{hi} {unit}"),
        3 => lo.clone(),
        4 => format!("{lo}..{hi} {unit}"),
        _ => format!("{lo}:{hi} {unit}"),
    };
    if rng.random_bool(0.03) {
        return key;
    }
    format!("{key}={}", bounds.trim())
}

/// A quantity's text with the unit of its limits: of an output of the scenario, a verdict, or hostile.
fn quantity(rng: &mut Rng, outputs: &[(String, String)]) -> (String, String) {
    let (out, unit) = if outputs.is_empty() || rng.random_bool(0.05) {
        ("nope".to_string(), "m".to_string())
    } else {
        outputs[rng.random_range(0..outputs.len())].clone()
    };
    match rng.random_range(0..20) {
        0..=4 => (format!("sigma({out})"), unit),
        5..=7 => (format!("3sigma({out})"), unit),
        8 => (format!("peak3({out})"), unit),
        9 => (format!("a_w({out})"), "m/s^2".into()),
        10 => ("a_v".into(), "m/s^2".into()),
        11 => ("A8".into(), "m/s^2".into()),
        12 => ("VDV".into(), String::new()),
        13 => ("damage_rate".into(), "1/s".into()),
        14 => ("life".into(), "h".into()),
        15 => (format!("sigma({out}"), unit),
        16 => ("comfort".into(), String::new()),
        17 => (String::new(), String::new()),
        18 => (format!("SIGMA({out})"), unit),
        _ => (format!("sigma({out}))"), unit),
    }
}

/// One `--constraint` text.
fn constraint(rng: &mut Rng, outputs: &[(String, String)]) -> String {
    let (q, unit) = quantity(rng, outputs);
    let op = pick(rng, &["<=", "<=", ">=", ">=", "<", "==", ""]);
    let unit = match rng.random_range(0..16) {
        0 => "kg".into(),
        1 => String::new(),
        2 => "furlong".into(),
        _ => unit,
    };
    let v = number(rng, 1.0, -3.0, 1.0);
    format!("{q} {op} {v} {unit}").trim().to_string()
}

/// An optimize case: `args[0]` the scenario (relative to the source tree), then the flags.
pub fn optimize_case(cc: &CommandCorpus, rng: &mut Rng, case: &mut Case) {
    let Some((rel, keys, outputs)) = (!cc.optimize_scenarios.is_empty())
        .then(|| cc.optimize_scenarios[rng.random_range(0..cc.optimize_scenarios.len())].clone())
    else {
        return;
    };
    case.origin = format!("optimize {rel}");
    case.file_name = std::path::Path::new(&rel)
        .file_name()
        .unwrap()
        .to_string_lossy()
        .into_owned();
    let mut a = vec![rel];
    let n = if rng.random_bool(0.03) {
        0
    } else {
        rng.random_range(1..4)
    };
    for _ in 0..n {
        a.push("--param".into());
        a.push(param(rng, &keys));
    }
    if rng.random_bool(0.05) && a.len() >= 3 {
        let twice = a[1..3].to_vec();
        a.extend(twice);
    }
    let goal = match rng.random_range(0..20) {
        0 => vec![],
        1 => vec!["--minimize", "--maximize"],
        2..=6 => vec!["--maximize"],
        _ => vec!["--minimize"],
    };
    for g in goal {
        a.push(g.into());
        a.push(quantity(rng, &outputs).0);
    }
    for _ in 0..rng.random_range(0..3) {
        a.push("--constraint".into());
        a.push(constraint(rng, &outputs));
    }
    a.push("--starts".into());
    a.push(pick(rng, &["1", "1", "2", "2", "0", "x"]).into());
    a.push("--max-evaluations".into());
    a.push(pick(rng, &["3", "10", "30", "30", "1", "0"]).into());
    case.args = a;
}

// ------------------------------------------------------------------------------------------------------
// Evaluation (as the CLI's handler in src/main/optimize_cli.rs: the flags parsed, the library called)
// ------------------------------------------------------------------------------------------------------

/// A flag's values in `args`.
fn values<'a>(args: &'a [String], name: &str) -> Vec<&'a str> {
    args.windows(2)
        .filter(|w| w[0] == name)
        .map(|w| w[1].as_str())
        .collect()
}

/// A count flag as clap parses it.
fn count(args: &[String], name: &str, default: usize) -> Result<usize, Box<Outcome>> {
    match values(args, name).last() {
        None => Ok(default),
        Some(v) => v.parse().map_err(|_| Box::new(clap(format!("{name} {v}")))),
    }
}

/// Evaluates an optimize case (no time limit; panics propagate).
pub fn evaluate(args: &[String], ctx: &Context) -> Outcome {
    run(args, ctx).unwrap_or_else(|o| *o)
}

fn run(args: &[String], ctx: &Context) -> Result<Outcome, Box<Outcome>> {
    let lib = |e: stochvib::Error, stage: &str| Box::new(fail(&e, stage));
    let refuse = |what: &str| Box::new(clap(what.to_string()));
    let params = values(args, "--param");
    let (min, max) = (values(args, "--minimize"), values(args, "--maximize"));
    if params.is_empty() {
        return Err(refuse("no --param"));
    }
    let (flag, goal, text) = match (min.last(), max.last()) {
        (Some(_), Some(_)) => return Err(refuse("--minimize with --maximize")),
        (None, None) => return Err(refuse("neither --minimize nor --maximize")),
        (Some(q), None) => ("--minimize", Goal::Minimize, *q),
        (None, Some(q)) => ("--maximize", Goal::Maximize, *q),
    };
    let starts = count(args, "--starts", 4)?;
    let max_evaluations = count(args, "--max-evaluations", 2000)?;
    let sc = stochvib::scenario::load_scenario(&ctx.root.join(&args[0]), &ctx.root.join("spectra"))
        .map_err(|e| lib(e, "load"))?;
    let params = params
        .iter()
        .map(|p| Param::parse(p))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| lib(e, "start"))?;
    if starts == 0 {
        return Err(lib(
            stochvib::Error::invalid("--starts", 0, "at least one start"),
            "start",
        ));
    }
    let objective = Quantity::parse(flag, text, &sc).map_err(|e| lib(e, "start"))?;
    let constraints = values(args, "--constraint")
        .iter()
        .map(|c| Constraint::parse(c, &sc))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| lib(e, "start"))?;
    let problem = Problem::new(&sc, params, objective, goal, constraints).map_err(|e| lib(e, "load"))?;
    let opts = SolveOptions {
        starts,
        max_evaluations,
        ..SolveOptions::default()
    };
    let answer = solve(&problem, &opts).map_err(|e| lib(e, "report"))?;
    let _ = format!("{answer}");
    Ok(ok(
        if answer.feasible {
            "optimize"
        } else {
            "optimize:infeasible"
        },
        &answer,
    ))
}

/// The CLI arguments of an optimize case.
pub fn cli_args(case: &Case, ctx: &Context, json: bool) -> Vec<String> {
    let mut a = vec![
        "optimize".to_string(),
        ctx.root.join(&case.args[0]).display().to_string(),
    ];
    a.extend(case.args[1..].iter().cloned());
    a.push("--spectra-dir".into());
    a.push(ctx.root.join("spectra").display().to_string());
    if json {
        a.push("--json".into());
    }
    a
}

/// Whether the CLI run of an infeasible answer (`lib` = `ok:optimize:infeasible`) failed as it should: status
/// 1 with "infeasible" and the answer printed.
pub fn infeasible_as_expected(lib: &str, out: &super::process::Output) -> Option<bool> {
    (lib == "ok:optimize:infeasible").then(|| {
        matches!(out.exit, super::process::Exit::Code(1))
            && out.stderr.contains("infeasible")
            && !out.stdout.trim().is_empty()
    })
}
