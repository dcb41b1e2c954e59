//! `Scenario.analyze` and `Scenario.analyze_nonlinear`: one method and one result type per kind of model —
//! the report of a linear model (`AnalysisResult`, `stochvib analyze`) and routes 1 to 3 of a model with
//! nonlinear elements (`NonlinearResult`, `stochvib analyze` of such a file). Each refuses the other kind
//! with `InvalidInputError` naming the method that takes it.

use crate::convert::to_python;
use crate::errors::{call, detached, invalid_input};
use crate::interrupt::run_interruptible;
use crate::nonlinear_run;
use crate::scenario::{step, with_progress};
use pyo3::prelude::*;
use std::borrow::Cow;
use stochvib::scenario::Scenario;
use stochvib::simulate::{run_temporary, RunOptions};
use stochvib::study::{analysis_report, attach_monte_carlo};

/// The quadrature effort given in Python: `rel_tol`, `max_subintervals`, `max_half_periods`.
pub type Effort = (Option<f64>, Option<usize>, Option<usize>);

/// A Monte Carlo column asked for: realizations, master seed, Δt (s), realization duration (s), burn-in (s).
pub type Batch = (usize, u64, Option<f64>, Option<f64>, Option<f64>);

/// `sc` with the effort given over its `[analysis.quadrature]` (as the CLI's `--rel-tol`,
/// `--max-subintervals`, `--max-half-periods`: the given values replace the scenario's, then the whole is
/// validated).
pub fn tuned<'a>(py: Python<'_>, sc: &'a Scenario, (rel_tol, sub, half): Effort) -> PyResult<Cow<'a, Scenario>> {
    if rel_tol.is_none() && sub.is_none() && half.is_none() {
        return Ok(Cow::Borrowed(sc));
    }
    let mut sc = sc.clone();
    let e = &mut sc.analysis.effort;
    e.rel_tol = rel_tol.unwrap_or(e.rel_tol);
    e.max_subintervals = sub.unwrap_or(e.max_subintervals);
    e.max_half_periods = half.unwrap_or(e.max_half_periods);
    call(py, || e.validate())?;
    Ok(Cow::Owned(sc))
}

/// Refuses a model of the other kind than `nonlinear` says, naming the function of its kind: `what` is
/// the pair (linear function, nonlinear function), e.g. ("analyze", "analyze_nonlinear").
pub fn require_kind(py: Python<'_>, sc: &Scenario, nonlinear: bool, (linear, other): (&str, &str)) -> PyResult<()> {
    let has = sc.nonlinear_model().is_some();
    if has == nonlinear {
        return Ok(());
    }
    let (model, function) = if has {
        ("has nonlinear elements ([[model.nonlinear]])", other)
    } else {
        ("is linear (no [[model.nonlinear]])", linear)
    };
    Err(invalid_input(
        py,
        format!(
            "{}: the model {model}: call stochvib.{function}() (Scenario.{function}()) for such a model",
            sc.path.display()
        ),
    ))
}

/// The `stochvib analyze` report of a linear scenario, with the Monte Carlo column of `batch`.
pub fn linear<'py>(
    py: Python<'py>,
    sc: &Scenario,
    batch: Option<Batch>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    require_kind(py, sc, false, ("analyze", "analyze_nonlinear"))?;
    let mut r = detached(py, || Ok(analysis_report(sc)?))?;
    if let Some((n, seed, dt, duration, _)) = batch {
        let summary = with_progress(py, progress, |cb| {
            run_interruptible(py, cb, |cb| {
                let (dt, d, _) = step(sc, dt, duration)?;
                let opts = RunOptions {
                    realizations: n,
                    duration_s: d,
                    dt_s: dt,
                    seed,
                    ..RunOptions::default()
                };
                run_temporary(&sc.run_input(), &opts, &std::env::temp_dir(), cb, |_| ()).map(|(s, _)| s)
            })
        })?;
        attach_monte_carlo(&mut r, &summary);
    }
    py.import("stochvib.results")?
        .getattr("AnalysisResult")?
        .call1((to_python(py, &r)?, r.to_string()))
}

/// Routes 1 and 3 of a scenario with nonlinear elements, and route 2 (the time-domain Monte Carlo of the
/// nonlinear equations) with `batch`, as `stochvib analyze [--monte-carlo N]` of such a file.
pub fn nonlinear<'py>(
    py: Python<'py>,
    sc: &Scenario,
    batch: Option<Batch>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    require_kind(py, sc, true, ("analyze", "analyze_nonlinear"))?;
    let Some(answers) = call(py, || sc.nonlinear_answers())? else {
        return Err(invalid_input(py, "the model has no nonlinear elements"));
    };
    let mc = match batch {
        None => None,
        Some((n, seed, dt, duration, burn_in)) => Some(with_progress(py, progress, |cb| {
            run_interruptible(py, cb, |cb| {
                let run = RunOptions {
                    realizations: n,
                    seed,
                    ..RunOptions::default()
                };
                let (opts, _) = nonlinear_run::options(sc, &answers, run, (dt, duration, burn_in))?;
                // an escaped response is route 2's outcome, reported beside routes 1 and 3 (as the CLI does)
                match nonlinear_run::temporary(sc, &answers, &opts, cb) {
                    Ok(s) => Ok(Ok(s)),
                    Err(e) => stochvib::study::escaped(&e).map(Err).ok_or(e),
                }
            })
        })?),
    };
    let r = call(py, || match &mc {
        Some(Err(reason)) => stochvib::study::nonlinear_report_escaped(sc, &answers, reason),
        Some(Ok(s)) => stochvib::study::nonlinear_report(sc, &answers, Some(s)),
        None => stochvib::study::nonlinear_report(sc, &answers, None),
    })?;
    py.import("stochvib.results")?
        .getattr("NonlinearResult")?
        .call1((to_python(py, &r)?, r.to_string()))
}
