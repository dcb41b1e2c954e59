//! The Monte Carlo verdict values of `stochvib analyze --monte-carlo N` beside the analytic ones: per
//! weighted output a_w, the VDV of the simulated records and scaled to the daily exposure, ISO 2631-1's
//! basic-method check and the governing metric; per fatigue output the rainflow damage rate against
//! Dirlik's; and, for every interval that misses its analytic value, whether the discretisation bias or
//! chance is the cause. [`crate::report::mc_verdicts_text`] prints them.

use crate::estimate::Interval;
use crate::simulate::{coverage_cause, RunBasicMethod, RunSummary};
use serde::Serialize;

/// One Monte Carlo statistic beside its analytic value.
#[derive(Debug, Clone, Serialize)]
pub struct McValue {
    /// The run output.
    pub output: String,
    /// What it is (`a_w`, `VDV`, `damage rate`).
    pub quantity: String,
    /// Unit.
    pub unit: String,
    /// The analytic value the interval is compared with.
    pub analytic: Option<f64>,
    /// The exact value of the simulated discrete process (σ of the discretised process), if known.
    pub discrete: Option<f64>,
    /// The Monte Carlo estimate and interval (serialised flat: `estimate`, `lower`, `upper`, `confidence`).
    #[serde(flatten)]
    pub interval: Interval,
    /// Whether the interval covers the analytic value.
    pub covers: Option<bool>,
    /// Why it does not cover (discretisation bias or chance).
    pub cause: Option<String>,
}

/// The Monte Carlo verdict section.
#[derive(Debug, Clone, Serialize)]
pub struct McVerdicts {
    /// Record duration T = NΔt of the realizations, s.
    pub duration_s: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// Realizations.
    pub realizations: usize,
    /// a_w, VDV (over T) and damage rates.
    pub values: Vec<McValue>,
    /// ISO 2631-1's basic-method check per weighted output, from the simulated records.
    pub basic_method: Vec<RunBasicMethod>,
}

/// Why a damage rate is not compared: no realization counted a damaging cycle (all below the endurance
/// limit), so the run bounds the rate of damaging cycles — by Garwood's −ln(α/2)/(R·T) for none in R·T
/// seconds — but not the damage rate, since a cycle's damage has no upper bound.
fn no_damaging_cycle(s: &crate::store::Statistic, run: &RunSummary) -> Option<String> {
    let a = s.analytic?;
    if s.covers.is_some() || s.interval.estimate != 0.0 || a <= 0.0 {
        return None;
    }
    let total = run.n_realizations as f64 * run.n_samples as f64 * run.dt_s;
    let (_, bound) = crate::estimate::poisson_rate_interval(0.0, total, s.interval.confidence).ok()?;
    Some(format!(
        "not compared: no realization counted a damaging cycle (every amplitude below the endurance limit) in \
         the run's {} s, so the run bounds the rate of damaging cycles (≤ {} /s at {} %) but not the damage \
         rate; the analytic rate {} /s predicts a Miner damage of {} over the whole run (more realizations or \
         a longer --duration resolve it)",
        crate::numbers::num(total),
        crate::numbers::num(bound),
        crate::numbers::num(100.0 * s.interval.confidence),
        crate::numbers::num(a),
        crate::numbers::num(a * total)
    ))
}

/// The verdict statistics of a run (empty values when it has no verdict channels).
pub fn mc_verdicts(run: &RunSummary) -> Option<McVerdicts> {
    let mut values = Vec::new();
    for o in &run.outputs {
        let is_weighted = o.get("vdv").is_some();
        let picks: &[(&str, &str)] = if is_weighted {
            &[("sigma", "a_w"), ("vdv", "VDV over T")]
        } else {
            &[("damage_rate", "damage rate")]
        };
        for (name, quantity) in picks {
            let Some(s) = o.get(name) else { continue };
            values.push(McValue {
                output: o.output.clone(),
                quantity: quantity.to_string(),
                unit: s.unit.clone(),
                analytic: s.analytic,
                discrete: (*name == "sigma")
                    .then(|| o.get("sigma_discrete").and_then(|d| d.analytic))
                    .flatten(),
                interval: s.interval,
                covers: s.covers,
                cause: if *name == "sigma" {
                    coverage_cause(o)
                } else {
                    no_damaging_cycle(s, run)
                },
            });
        }
    }
    if values.is_empty() {
        return None;
    }
    Some(McVerdicts {
        duration_s: run.n_samples as f64 * run.dt_s,
        dt_s: run.dt_s,
        realizations: run.n_realizations,
        values,
        basic_method: run.basic_method.clone(),
    })
}
