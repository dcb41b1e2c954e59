//! Route 2 of a model with nonlinear elements from Python: the time-domain Monte Carlo of the nonlinear
//! equations (`stochvib simulate` and `stochvib analyze --monte-carlo N` of such a scenario).

use stochvib::nonlinear::monte_carlo::{NonlinearRunOptions, NonlinearRunSummary};
use stochvib::scenario::Scenario;
use stochvib::simulate::RunOptions;
use stochvib::study::NonlinearAnswers;

/// The options of a route-2 run: `run` with the given Δt and duration, the missing ones suggested for route 2
/// (as the command-line tool does), the burn-in (s; None: computed from the slowest decay rate of the
/// Gaussian equivalent); and how the step was chosen.
pub fn options(
    sc: &Scenario,
    answers: &NonlinearAnswers,
    run: RunOptions,
    (dt, duration, burn_in): (Option<f64>, Option<f64>, Option<f64>),
) -> stochvib::Result<(NonlinearRunOptions, String)> {
    // named as the keyword is (the library names the command line's --burn-in)
    if let Some(b) = burn_in.filter(|b| !(b.is_finite() && *b >= 0.0)) {
        return Err(stochvib::Error::invalid("burn_in", b, "must be finite and >= 0 (s)"));
    }
    let (dt, duration, how) = match (dt, duration) {
        (Some(dt), Some(d)) => (dt, d, "given".to_string()),
        _ => {
            let s = sc.suggest_nonlinear_step(answers)?;
            (
                dt.unwrap_or(s.dt_s),
                duration.unwrap_or(s.duration_s),
                format!("suggested for route 2: {}", s.reason),
            )
        }
    };
    let opts = NonlinearRunOptions {
        run: RunOptions {
            dt_s: dt,
            duration_s: duration,
            ..run
        },
        burn_in_s: burn_in,
        halving_checks: None,
    };
    Ok((opts, how))
}

/// Route 2 into a temporary file (removed afterwards), as `stochvib analyze --monte-carlo N` runs it.
pub fn temporary(
    sc: &Scenario,
    answers: &NonlinearAnswers,
    opts: &NonlinearRunOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> stochvib::Result<NonlinearRunSummary> {
    sc.simulate_nonlinear_temporary(answers, opts, &std::env::temp_dir(), progress, |_| ())
        .map(|(s, _)| s)
}
