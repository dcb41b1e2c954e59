//! `Scenario.optimize`: the parameters of a scenario that minimise or maximise a response quantity under
//! constraints (`stochvib optimize`), answered as an `OptimizeResult`.

use crate::convert::to_python;
use crate::errors::{detached, invalid_input};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use stochvib::optimize::{solve, Constraint, Goal, Param, Problem, Quantity, SolveOptions};
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
    if task.starts == 0 {
        return Err(invalid_input(py, "`starts`: at least one start is needed"));
    }
    let solution = detached(py, || {
        let params = params
            .iter()
            .map(|p| Param::parse(p))
            .collect::<stochvib::Result<Vec<_>>>()?;
        let objective = Quantity::parse(flag, &objective, sc)?;
        let constraints = task
            .constraints
            .iter()
            .map(|c| Constraint::parse(c, sc))
            .collect::<stochvib::Result<Vec<_>>>()?;
        let problem = Problem::new(sc, params, objective, goal, constraints)?;
        let opts = SolveOptions {
            starts: task.starts,
            max_evaluations: task.max_evaluations,
            ..SolveOptions::default()
        };
        Ok(solve(&problem, &opts)?)
    })?;
    Ok((to_python(py, &solution)?, solution.to_string()))
}
