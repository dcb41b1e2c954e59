//! Scenarios with nonlinear elements (`[[model.nonlinear]]`, [`crate::scenario::nonlinear_keys`]): their three
//! routes — route 1 (statistical linearization, an approximation), route 3 (the exact density, where it
//! applies) and route 2 (nonlinear Monte Carlo into a run file).

use crate::error::Result;
use crate::nonlinear::monte_carlo::{
    run_nonlinear, suggest_nonlinear_step, NonlinearRunInput, NonlinearRunOptions, NonlinearRunSummary,
};
use crate::nonlinear::{linearize, NonlinearModel, Route1Options, Route1Outcome, Stationary, WhiteNoiseOscillator};
use crate::response::{analyze_output_with, ResponseStatistics};
use crate::scenario::Scenario;
use crate::simulate::StepSuggestion;
use crate::system::FrequencyResponse;
use std::path::Path;

/// The analytic answers of a nonlinear scenario: route 1 with its output statistics, the linear part's
/// statistics, and route 3 or why it does not apply.
#[derive(Debug, Clone)]
pub struct NonlinearAnswers {
    /// Route 1's outcome.
    pub route1: Route1Outcome,
    /// Route 1's statistics of every output (with route 1's means), if it converged.
    pub route1_statistics: Option<Vec<ResponseStatistics>>,
    /// The linear part's statistics of every output, if it has a stationary response.
    pub linear_statistics: Option<Vec<ResponseStatistics>>,
    /// Route 3's exact law, or why it does not apply.
    pub route3: std::result::Result<Stationary, String>,
}

impl Scenario {
    /// The nonlinear model, if the scenario has `[[model.nonlinear]]` elements.
    pub fn nonlinear_model(&self) -> Option<&NonlinearModel> {
        self.nonlinear.as_deref()
    }

    /// Routes 1 and 3 of a nonlinear scenario (see [`NonlinearAnswers`]); `None` for a linear scenario.
    ///
    /// # Errors
    /// An excitation that does not fit the model.
    pub fn nonlinear_answers(&self) -> Result<Option<NonlinearAnswers>> {
        let Some(model) = self.nonlinear_model() else {
            return Ok(None);
        };
        self.answers_of(model).map(Some).map_err(|e| self.name_model_error(e))
    }

    /// An error of the nonlinear routes or of a report, naming the file's `model` (its linear part and
    /// elements) unless it names a key already: an unstable linear part, a system found unstable with its
    /// excitation, a quadrature of the model's response that fails.
    pub fn name_model_error(&self, e: crate::Error) -> crate::Error {
        match e {
            e @ crate::Error::File { .. } => e,
            e => crate::Error::in_file(&self.path, "model", &self.kind, e.to_string()),
        }
    }

    fn answers_of(&self, model: &NonlinearModel) -> Result<NonlinearAnswers> {
        let opts = Route1Options {
            effort: self.analysis.effort.clone(),
            ..Route1Options::default()
        };
        let route1 = linearize(model, &self.excitation, &opts)?;
        let route1_statistics = match route1.converged() {
            Some(r) => Some(r.output_statistics(&self.excitation, &self.analysis.effort)?),
            None => None,
        };
        let lin = model.linear();
        let linear_statistics = match lin.state_space().map(|ss| ss.require_stable()) {
            Some(Ok(())) => Some(
                (0..lin.outputs().len())
                    .map(|r| analyze_output_with(lin, &self.excitation, r, &self.analysis.effort))
                    .collect::<Result<Vec<_>>>()?,
            ),
            _ => None,
        };
        let route3 = WhiteNoiseOscillator::from_model(model, &self.excitation)
            .and_then(|o| o.stationary().map_err(|e| e.to_string()));
        Ok(NonlinearAnswers {
            route1,
            route1_statistics,
            linear_statistics,
            route3,
        })
    }

    /// The subject of a route-2 run of this scenario with the `answers` of routes 1 and 3.
    ///
    /// # Panics
    /// Never for a nonlinear scenario (the caller has its answers).
    pub fn nonlinear_run_input<'a>(&'a self, answers: &'a NonlinearAnswers) -> NonlinearRunInput<'a> {
        let model = self.nonlinear_model().expect("a nonlinear scenario");
        let base = self.run_input();
        NonlinearRunInput {
            model,
            excitation: &self.excitation,
            outputs: self.analysis.outputs.clone(),
            input_signals: self.input_signals(),
            scenario_text: self.text.clone(),
            provenance: base.provenance.clone(),
            source_files: base.source_files.clone(),
            kurtosis: self.process_kurtosis(),
            levels: self.analysis.levels.clone(),
            route1: answers.route1.converged(),
            route1_statistics: answers.route1_statistics.as_deref(),
            linear_statistics: answers.linear_statistics.as_deref(),
            route3: answers.route3.as_ref().ok(),
        }
    }

    /// A time step and duration for route 2 ([`suggest_nonlinear_step`]).
    ///
    /// # Errors
    /// As [`suggest_nonlinear_step`].
    pub fn suggest_nonlinear_step(&self, answers: &NonlinearAnswers) -> Result<StepSuggestion> {
        suggest_nonlinear_step(&self.nonlinear_run_input(answers))
    }

    /// Route 2 of this scenario into the HDF5 file `out` ([`run_nonlinear`]).
    ///
    /// # Errors
    /// As [`run_nonlinear`]; a linear scenario.
    pub fn simulate_nonlinear(
        &self,
        answers: &NonlinearAnswers,
        opts: &NonlinearRunOptions,
        out: &Path,
        progress: &dyn Fn(usize, usize),
    ) -> Result<NonlinearRunSummary> {
        run_nonlinear(&self.nonlinear_run_input(answers), opts, out, progress)
    }
}

impl Scenario {
    /// Route 2 into a temporary file `stochvib-nonlinear-<pid>.h5` in `dir`, handed to `then` (e.g. to draw
    /// its pictures) and removed afterwards, whether the run succeeded or not.
    ///
    /// # Errors
    /// As [`Scenario::simulate_nonlinear`].
    pub fn simulate_nonlinear_temporary<T>(
        &self,
        answers: &NonlinearAnswers,
        opts: &NonlinearRunOptions,
        dir: &Path,
        progress: &dyn Fn(usize, usize),
        then: impl FnOnce(&Path) -> T,
    ) -> Result<(NonlinearRunSummary, T)> {
        struct Remove(std::path::PathBuf);
        impl Drop for Remove {
            fn drop(&mut self) {
                let _ = std::fs::remove_file(&self.0);
                let _ = std::fs::remove_file(crate::store::tmp_path(&self.0));
            }
        }
        let guard = Remove(dir.join(format!("stochvib-nonlinear-{}.h5", std::process::id())));
        drop(Remove(guard.0.clone())); // a leftover of an earlier process with the same id
        let s = self.simulate_nonlinear(answers, opts, &guard.0, progress)?;
        let t = then(&guard.0);
        Ok((s, t))
    }
}
