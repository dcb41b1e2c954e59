//! `Scenario.optimize`: the parameters of a scenario that minimise or maximise a response quantity under
//! constraints (`stochvib optimize`), answered as an `OptimizeResult`.

use crate::convert::to_python;
use crate::errors::{detached, invalid_input};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;
use stochvib::optimize::{pareto, solve, Constraint, Goal, Param, ParetoProblem, Problem, Quantity, SolveOptions};
use stochvib::scenario::Scenario;

/// What to optimise: the goal and its quantity's text, the constraints' texts, the starts and evaluations.
pub struct Task {
    pub minimize: Option<String>,
    pub maximize: Option<String>,
    pub constraints: Vec<String>,
    pub starts: usize,
    pub max_evaluations: usize,
}

/// `KEY=LOW:HIGH` texts (the CLI's `--param`) of a dict key → `"LOW:HIGH UNIT"` or a pair (low, high) of
/// numbers (SI) or strings with units.
fn param_texts(py: Python<'_>, params: &Bound<'_, PyDict>) -> PyResult<Vec<String>> {
    let text = |v: &Bound<'_, PyAny>| -> PyResult<String> { Ok(v.str()?.to_cow()?.into_owned()) };
    params
        .iter()
        .map(|(k, v)| {
            let range = if v.is_instance_of::<PyString>() {
                text(&v)?
            } else {
                let pair: Vec<Bound<'_, PyAny>> = v.try_iter()?.collect::<PyResult<_>>()?;
                let [lo, hi] = pair.as_slice() else {
                    return Err(invalid_input(
                        py,
                        format!("params[{}]: expected (low, high) or \"LOW:HIGH UNIT\"", text(&k)?),
                    ));
                };
                format!("{}:{}", text(lo)?, text(hi)?)
            };
            Ok(format!("{}={range}", text(&k)?))
        })
        .collect()
}

/// Solves the problem (without the GIL) and returns `(data, text)` of the answer: the `stochvib optimize
/// --json` data and the command-line tool's text.
pub fn optimize<'py>(
    py: Python<'py>,
    sc: &Scenario,
    params: &Bound<'py, PyDict>,
    task: Task,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let params = param_texts(py, params)?;
    let opts = task.options(py)?;
    let (flag, goal, objective) = match (task.minimize, task.maximize) {
        (Some(q), None) => ("minimize", Goal::Minimize, q),
        (None, Some(q)) => ("maximize", Goal::Maximize, q),
        _ => {
            return Err(invalid_input(
                py,
                "give exactly one of minimize= and maximize= (a quantity such as \"sigma(body_acc)\")",
            ))
        }
    };
    let solution = detached(py, || {
        let (params, constraints) = parsed(sc, &params, &task.constraints)?;
        let objective = Quantity::parse(flag, &objective, sc)?;
        let problem = Problem::new(sc, params, objective, goal, constraints)?;
        Ok(solve(&problem, &opts)?)
    })?;
    Ok((to_python(py, &solution)?, solution.to_string()))
}

impl Task {
    /// The search's options.
    fn options(&self, py: Python<'_>) -> PyResult<SolveOptions> {
        if self.starts == 0 {
            return Err(invalid_input(py, "`starts`: at least one start is needed"));
        }
        Ok(SolveOptions {
            starts: self.starts,
            max_evaluations: self.max_evaluations,
            ..SolveOptions::default()
        })
    }
}

/// The parameters (`KEY=LOW:HIGH` texts) and the constraints of a problem on `sc`.
fn parsed(sc: &Scenario, params: &[String], constraints: &[String]) -> stochvib::Result<(Vec<Param>, Vec<Constraint>)> {
    let params = params
        .iter()
        .map(|p| Param::parse(p))
        .collect::<stochvib::Result<Vec<_>>>()?;
    let constraints = constraints
        .iter()
        .map(|c| Constraint::parse(c, sc))
        .collect::<stochvib::Result<Vec<_>>>()?;
    Ok((params, constraints))
}

/// A Pareto front as Python receives it: the `--json` data, the `--pareto` CSV, the pictures written.
pub type Front<'py> = (Bound<'py, PyAny>, String, Vec<PathBuf>);

/// The Pareto front of `task.minimize` and `second` with `points` points (`stochvib optimize --pareto SECOND
/// --points N [--plots DIR]`), solved without the GIL, drawn into `plots` (`pareto-front.svg`, `.png`).
pub fn front<'py>(
    py: Python<'py>,
    sc: &Scenario,
    params: &Bound<'py, PyDict>,
    task: Task,
    (second, points, plots): (String, usize, Option<PathBuf>),
) -> PyResult<Front<'py>> {
    let params = param_texts(py, params)?;
    let first = task.minimize.clone().ok_or_else(|| {
        invalid_input(
            py,
            "a Pareto front needs minimize= (its first quantity; both are minimised)",
        )
    })?;
    let opts = task.options(py)?;
    let (front, files) = detached(py, || {
        if let Some(dir) = &plots {
            stochvib::plot::chart::check_picture_dir(dir)?;
        }
        let (params, constraints) = parsed(sc, &params, &task.constraints)?;
        let problem = ParetoProblem {
            quantities: [
                Quantity::parse("minimize", &first, sc)?,
                Quantity::parse("pareto", &second, sc)?,
            ],
            base: sc,
            params,
            constraints,
        };
        let front = pareto(&problem, points, &opts)?;
        let files = match &plots {
            Some(dir) => stochvib::plot::pareto_plots::pareto_chart(&sc.title, &front).render(dir, "pareto-front")?,
            None => Vec::new(),
        };
        Ok((front, files))
    })?;
    Ok((to_python(py, &front)?, front.to_csv(), files))
}
