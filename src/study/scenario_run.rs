//! A scenario's Monte Carlo run (`stochvib simulate`): route 2 for a model with nonlinear elements
//! ([`super::nonlinear_run`]), the system extended by the weighted outputs when the scenario asks for
//! verdicts ([`super::verdict_run`]), else the scenario's own run input.

use crate::error::Result;
use crate::scenario::Scenario;
use crate::simulate::{RunInput, RunOptions, RunSummary};
use std::path::Path;

impl Scenario {
    /// Runs a Monte Carlo batch of this scenario into the HDF5 file `out` ([`crate::simulate::run()`]).
    ///
    /// # Errors
    /// As [`crate::simulate::run()`].
    pub fn simulate(&self, opts: &RunOptions, out: &Path, progress: &dyn Fn(usize, usize)) -> Result<RunSummary> {
        // a model with nonlinear elements: route 2 with its default burn-in and checks
        if let Some(answers) = self.nonlinear_answers()? {
            let o = crate::nonlinear::monte_carlo::NonlinearRunOptions {
                run: opts.clone(),
                burn_in_s: None,
                halving_checks: None,
            };
            return self.simulate_nonlinear(&answers, &o, out, progress).map(|s| s.run);
        }
        self.with_simulated_input(|input| crate::simulate::run(input, opts, out, progress))
            .map_err(|e| self.name_run_error(e))
    }

    /// Calls `f` with the subject of this scenario's Monte Carlo run as [`Scenario::simulate`] runs it: with
    /// verdicts the system extended by the weighted outputs and the verdict channels
    /// ([`super::verdict_run::with_verdict_input`]), else [`Scenario::run_input`].
    ///
    /// # Errors
    /// Those of building the verdict system; what `f` returns.
    pub fn with_simulated_input<T>(&self, f: impl FnOnce(&RunInput) -> Result<T>) -> Result<T> {
        if self.analysis.verdicts.is_empty() {
            f(&self.run_input())
        } else {
            super::verdict_run::with_verdict_input(self, f)
        }
    }
}
