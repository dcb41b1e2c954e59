//! Monte Carlo of a scenario's transient (`stochvib transient --monte-carlo N`): the run of
//! [`crate::transient::run_transient`] on the scenario's setup, and the comparison of the ensemble σ(t)
//! with the exact curve, with a verdict that holds for every reported time at once.

use super::transient_run::TransientSetup;
use crate::error::{Error, Result};
use crate::estimate::chi2_interval;
use crate::scenario::Scenario;
use crate::store::transient_series::TransientSeries;
use crate::store::{Compression, Part};
use crate::transient::{
    run_transient, McGrid, TransientRunInput, TransientRunOptions, TransientRunSummary, TransientSolution,
};
use std::path::Path;

/// Options of a transient Monte Carlo run of a scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientMcOptions {
    /// Realizations.
    pub realizations: usize,
    /// Integration steps per reported interval (the realizations are stepped exactly for coefficients
    /// frozen at each step's midpoint).
    pub substeps: usize,
    /// Master seed.
    pub seed: u64,
    /// Realizations per shard.
    pub shard_size: usize,
    /// Confidence of the intervals and of the DKW band.
    pub confidence: f64,
    /// Store every realization at the reported times.
    pub store_raw: bool,
    /// Compression of the raw data.
    pub compression: Compression,
    /// The part of a cluster run.
    pub part: Option<Part>,
    /// Replace a finished file.
    pub overwrite: bool,
    /// Refuse a batch whose computing time's lower bound exceeds this many hours.
    pub max_hours: f64,
}

/// The outputs a run simulates: the reported outputs with a finite σ and crossing rates (the analytic
/// distribution of the maxima needs them), and a note for each one left out.
pub fn simulated_outputs(setup: &TransientSetup, sol: &TransientSolution) -> (Vec<usize>, Vec<String>) {
    let mut notes = Vec::new();
    let outputs = setup
        .outputs
        .iter()
        .copied()
        .filter(|&i| {
            let o = &sol.outputs[i];
            match o.unavailable.as_ref().or(o.rate_note.as_ref()) {
                Some(why) => {
                    notes.push(format!("`{}` is not simulated: {why}", o.name));
                    false
                }
                None => true,
            }
        })
        .collect();
    (outputs, notes)
}

/// Runs the Monte Carlo batch of the scenario's transient into `out` (resuming an interrupted run).
///
/// # Errors
/// No output to simulate; the errors of [`run_transient`] (options, store, an existing finished file).
pub fn simulate_transient(
    sc: &Scenario,
    setup: &TransientSetup,
    sol: &TransientSolution,
    opts: &TransientMcOptions,
    out: &Path,
    progress: &dyn Fn(usize, usize),
) -> Result<(TransientRunSummary, Vec<String>)> {
    let (outputs, notes) = simulated_outputs(setup, sol);
    if outputs.is_empty() {
        return Err(Error::NotApplicable {
            method: "transient Monte Carlo".into(),
            reason: format!(
                "no reported output has a finite σ and crossing rates: {}",
                notes.join("; ")
            ),
        });
    }
    let duration = *setup.times.last().unwrap_or(&0.0);
    let intervals = setup.times.len() - 1;
    if opts.substeps == 0 {
        return Err(Error::invalid("substeps", 0, "must be >= 1"));
    }
    let dt = duration / (intervals * opts.substeps) as f64;
    let grid = McGrid::new(duration, dt, opts.substeps)?;
    let input = TransientRunInput {
        sys: &setup.sys,
        outputs,
        start: setup.start.clone(),
        exact: sol,
        stationary: setup.stationary,
        scenario_text: sc.text.clone(),
        provenance: sc.run_input().provenance,
    };
    let run = TransientRunOptions {
        realizations: opts.realizations,
        grid,
        seed: opts.seed,
        shard_size: opts.shard_size,
        confidence: opts.confidence,
        store_raw: opts.store_raw,
        compression: opts.compression,
        part: opts.part,
        overwrite: opts.overwrite,
        max_hours: opts.max_hours,
    };
    Ok((run_transient(&input, &run, out, progress)?, notes))
}

/// The Monte Carlo σ(t) of one output against the exact σ(t).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SigmaComparison {
    /// Output.
    pub output: String,
    /// Unit.
    pub unit: String,
    /// Realizations.
    pub realizations: usize,
    /// Confidence of the per-time intervals (as stored).
    pub confidence: f64,
    /// Per reported time: (t, exact σ, Monte Carlo σ, lower, upper) of the per-time interval.
    pub rows: Vec<(f64, f64, f64, f64, f64)>,
    /// Fraction of the times whose per-time interval covers the exact σ.
    pub coverage: f64,
    /// The simultaneous level 1 − α of the verdict (Bonferroni over the K times).
    pub simultaneous_confidence: f64,
    /// Times at which the exact σ is outside the simultaneous interval.
    pub outside: Vec<f64>,
}

impl SigmaComparison {
    /// `agree` or `DISAGREE at t = …`.
    pub fn verdict(&self) -> String {
        match self.outside.first() {
            None => format!(
                "agree: the exact σ(t) lies inside the simultaneous {} % band at every one of the {} times",
                100.0 * self.simultaneous_confidence,
                self.rows.len()
            ),
            Some(t) => format!(
                "DISAGREE: the exact σ lies outside the simultaneous {} % band at {} of {} times (first t = {t} s)",
                100.0 * self.simultaneous_confidence,
                self.outside.len(),
                self.rows.len()
            ),
        }
    }
}

/// The comparison of every output of a run's series, with a verdict at the simultaneous level 1 − α.
///
/// # Formula
/// At each of the K times, σ̂² (R − 1)/σ² ~ χ²_{R−1} for the Gaussian response of a linear system, so
/// [σ̂²(R−1)/χ²_{R−1}(1 − α/2K), σ̂²(R−1)/χ²_{R−1}(α/2K)] covers σ² at every time at once with probability
/// ≥ 1 − α (Bonferroni). A time with σ = 0 exactly (a start at rest) counts as inside when
/// |σ̂ − σ| ≤ 10⁻¹² max σ.
///
/// # Errors
/// α outside (0, 1); fewer than 2 realizations.
pub fn compare_sigma(series: &TransientSeries, alpha: f64) -> Result<Vec<SigmaComparison>> {
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(Error::invalid("alpha", alpha, "must be in (0, 1)"));
    }
    let k = series.times.len().max(1);
    let level = 1.0 - alpha / k as f64;
    series
        .outputs
        .iter()
        .map(|o| {
            let r = o.max_y.len();
            let scale = o.exact_sigma.iter().copied().fold(0.0, f64::max);
            let mut rows = Vec::with_capacity(k);
            let mut outside = Vec::new();
            let mut covered = 0usize;
            for (j, &t) in series.times.iter().enumerate() {
                let (ex, est) = (o.exact_sigma[j], o.sigma[j]);
                let iv = chi2_interval(est * est, r as f64 - 1.0, level)?;
                let tiny = (ex - est).abs() <= 1e-12 * scale;
                if !(tiny || (iv.lower.sqrt() <= ex && ex <= iv.upper.sqrt())) {
                    outside.push(t);
                }
                if tiny || (o.sigma_lower[j] <= ex && ex <= o.sigma_upper[j]) {
                    covered += 1;
                }
                rows.push((t, ex, est, o.sigma_lower[j], o.sigma_upper[j]));
            }
            Ok(SigmaComparison {
                output: o.output.clone(),
                unit: o.unit.clone(),
                realizations: r,
                confidence: series.confidence,
                coverage: covered as f64 / k as f64,
                rows,
                simultaneous_confidence: 1.0 - alpha,
                outside,
            })
        })
        .collect()
}
