//! `stochvib optimize`: the argument struct and its handler, which parse, call the library and print.

use std::path::PathBuf;
use stochvib::optimize::{
    pareto, solve, Constraint, Goal, Method, Param, ParetoProblem, Problem, Quantity, SolveOptions,
};
use stochvib::scenario::load_scenario;

/// `stochvib optimize SCENARIO --param KEY=LOW:HIGH … --minimize QUANTITY [--constraint …]`.
#[derive(clap::Args)]
pub struct OptimizeArgs {
    /// Scenario file (TOML, see data/).
    scenario: PathBuf,
    /// KEY=LOW:HIGH: a value of the scenario file and its bounds with a unit, e.g.
    /// `model.suspension_damping=0.2:6 kN*s/m` (repeatable).
    #[arg(long = "param", value_name = "KEY=LOW:HIGH", required = true)]
    params: Vec<String>,
    /// The quantity to minimise: sigma(OUTPUT), 3sigma(OUTPUT), peak3(OUTPUT), a_w(OUTPUT), a_v, A8, VDV,
    /// damage_rate, life, static_sag(ELEMENT).
    #[arg(
        long,
        value_name = "QUANTITY",
        required_unless_present = "maximize",
        conflicts_with = "maximize"
    )]
    minimize: Option<String>,
    /// The quantity to maximise (same names as --minimize).
    #[arg(long, value_name = "QUANTITY")]
    maximize: Option<String>,
    /// "QUANTITY <= VALUE UNIT" or "QUANTITY >= VALUE UNIT", e.g. "3sigma(travel) <= 40 mm" (repeatable).
    #[arg(long = "constraint", value_name = "CONSTRAINT")]
    constraints: Vec<String>,
    /// The search: auto (SLSQP with the analytic gradients where the problem has them, else COBYLA), slsqp
    /// or cobyla.
    #[arg(long, value_name = "METHOD", default_value = "auto")]
    method: String,
    /// Number of starts (the centre of the box, then Halton points).
    #[arg(long, default_value_t = 4)]
    starts: usize,
    /// Most evaluations per start.
    #[arg(long, default_value_t = 2000)]
    max_evaluations: usize,
    /// Refuse a search whose time estimate (a lower bound: n + 1 evaluations per start, each as long as the
    /// centre's) exceeds this many hours.
    #[arg(long, value_name = "H", default_value_t = stochvib::simulate::resources::DEFAULT_MAX_HOURS)]
    max_hours: f64,
    /// A second quantity, also minimised: print the Pareto front of --minimize and this one (ε-constraint
    /// method: --minimize with this quantity held below a ladder of limits) as a CSV table instead of one
    /// optimum.
    #[arg(long, value_name = "QUANTITY", requires = "minimize")]
    pareto: Option<String>,
    /// Points of the Pareto front, its two ends included (with --pareto).
    #[arg(long, default_value_t = 7, requires = "pareto")]
    points: usize,
    /// With --pareto: also draw the front into this directory (`pareto-front.svg` and `.png`).
    #[arg(long, value_name = "DIR", requires = "pareto")]
    plots: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    spectra: super::SpectraDir,
}

/// Runs the optimisation and prints the answer; an infeasible problem prints the least violating point and
/// fails with the constraints it cannot meet.
pub fn optimize(a: OptimizeArgs) -> anyhow::Result<()> {
    let catalogue = a.spectra.catalogue();
    let sc = load_scenario(&a.scenario, catalogue.dir())?;
    let params = a
        .params
        .iter()
        .map(|p| Param::parse(p))
        .collect::<Result<Vec<_>, _>>()?;
    let (flag, goal, text) = match (&a.minimize, &a.maximize) {
        (Some(q), _) => ("--minimize", Goal::Minimize, q),
        (None, Some(q)) => ("--maximize", Goal::Maximize, q),
        (None, None) => anyhow::bail!("give --minimize QUANTITY or --maximize QUANTITY"),
    };
    if a.starts == 0 {
        anyhow::bail!("--starts 0: at least one start is needed");
    }
    let objective = Quantity::parse(flag, text, &sc)?;
    let constraints = a
        .constraints
        .iter()
        .map(|c| Constraint::parse(c, &sc))
        .collect::<Result<Vec<_>, _>>()?;
    let opts = SolveOptions {
        method: Method::parse(&a.method)?,
        starts: a.starts,
        max_evaluations: a.max_evaluations,
        max_hours: a.max_hours,
        ..SolveOptions::default()
    };
    if let Some(second) = &a.pareto {
        let problem = ParetoProblem {
            quantities: [objective, Quantity::parse("--pareto", second, &sc)?],
            base: &sc,
            params,
            constraints,
        };
        return print_front(&problem, a.points, &opts, a.json, a.plots.as_deref());
    }
    let problem = Problem::new(&sc, params, objective, goal, constraints)?;
    let answer = solve(&problem, &opts).map_err(|e| match e {
        // the search's own limits, named by their flags
        stochvib::Error::InvalidParameter { name, value, reason } if name == "starts" || name == "max hours" => {
            let name = if name == "starts" { "--starts" } else { "--max-hours" }.to_string();
            stochvib::Error::InvalidParameter { name, value, reason }
        }
        other => other,
    })?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&answer)?);
    } else {
        print!("{answer}");
    }
    if !answer.feasible {
        anyhow::bail!("infeasible: {}", answer.violations().join("; "));
    }
    Ok(())
}

/// `--pareto`: the front of `problem` with `points` points, printed as CSV (JSON with `json`), drawn into
/// `plots` when given.
fn print_front(
    problem: &ParetoProblem,
    points: usize,
    opts: &SolveOptions,
    json: bool,
    plots: Option<&std::path::Path>,
) -> anyhow::Result<()> {
    if let Some(dir) = plots {
        stochvib::plot::chart::check_picture_dir(dir)?;
    }
    let front = pareto(problem, points, opts)?;
    if let Some(dir) = plots {
        let title = problem.base.title.as_str();
        for f in stochvib::plot::pareto_plots::pareto_chart(title, &front).render(dir, "pareto-front")? {
            eprintln!("wrote {}", f.display());
        }
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&front)?);
    } else {
        print!("{}", front.to_csv());
    }
    Ok(())
}
