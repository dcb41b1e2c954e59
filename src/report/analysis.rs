//! The `stochvib analyze` report: per output, the mean, σ, 3σ bounds, crossing rates and every variance
//! method with its value and its relative difference to the reference.

use crate::error::Result;
use crate::response::{analyze_output_with, band_variance, Outcome, ResponseStatistics};
use crate::scenario::Scenario;
use serde::Serialize;
use std::fmt;

/// A level and its Rice up-crossing rate and exceedance probability within the scenario's duration.
#[derive(Debug, Clone, Serialize)]
pub struct LevelRow {
    /// Level in the output's SI unit.
    pub level: f64,
    /// Up-crossings per second (per metre for a spatial system).
    pub upcrossing_rate: Option<f64>,
    /// Probability of at least one up-crossing in the duration (Poisson).
    pub exceedance_probability: Option<f64>,
}

/// One output's section of the report.
#[derive(Debug, Clone, Serialize)]
pub struct OutputReport {
    /// The statistics, with every method.
    pub statistics: ResponseStatistics,
    /// Lower 3σ bound.
    pub lower_3sigma: Option<f64>,
    /// Upper 3σ bound.
    pub upper_3sigma: Option<f64>,
    /// σ over the scenario's band, if one is given.
    pub band_sigma: Option<f64>,
    /// Why the band σ is missing, if it is.
    pub band_note: Option<String>,
    /// Expected largest value within the duration (Davenport).
    pub expected_largest_peak: Option<f64>,
    /// Crossing rates at M + 3σ and at the scenario's levels.
    pub levels: Vec<LevelRow>,
    /// Monte Carlo column (`analyze --monte-carlo N`), if requested.
    pub monte_carlo: Option<MonteCarloColumn>,
    /// Band r.m.s. table (`[analysis] bands`), if requested.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bands: Option<super::band_report::BandSection>,
}

/// The Monte Carlo σ of one output against the analytic σ (see [`crate::simulate::run()`]).
#[derive(Debug, Clone, Serialize)]
pub struct MonteCarloColumn {
    /// Realizations.
    pub realizations: usize,
    /// Route taken (exact or spectral).
    pub method: String,
    /// MC σ with its interval; `None` if the output was not simulated.
    pub sigma: Option<crate::estimate::Interval>,
    /// Exact σ of the simulated discretised process (differs from the analytic σ on the spectral route).
    pub discrete_sigma: Option<f64>,
    /// Whether the interval covers the analytic σ.
    pub covered: Option<bool>,
    /// Why the output was not simulated.
    pub note: Option<String>,
}

/// Adds the Monte Carlo column of a run to the report's outputs (matched by name).
pub fn attach_monte_carlo(report: &mut AnalysisReport, run: &crate::simulate::RunSummary) {
    report.monte_carlo_verdicts = super::mc_verdicts::mc_verdicts(run);
    for o in &mut report.outputs {
        let name = &o.statistics.name;
        let base = MonteCarloColumn {
            realizations: run.n_realizations,
            method: run.route.name().to_string(),
            sigma: None,
            discrete_sigma: None,
            covered: None,
            note: None,
        };
        o.monte_carlo = if let Some(s) = run.statistic(name, "sigma") {
            Some(MonteCarloColumn {
                sigma: Some(s.interval),
                discrete_sigma: run.statistic(name, "sigma_discrete").and_then(|d| d.analytic),
                covered: s.covers,
                ..base
            })
        } else {
            run.skipped.iter().find(|s| &s.name == name).map(|s| MonteCarloColumn {
                note: Some(s.reason.clone()),
                ..base
            })
        };
    }
}

/// The whole analysis report.
#[derive(Debug, Clone, Serialize)]
pub struct AnalysisReport {
    /// Scenario title.
    pub title: String,
    /// Scenario file.
    pub scenario: String,
    /// Model description.
    pub model: String,
    /// Input description.
    pub input: String,
    /// Band in rad/s, if any.
    pub band_rad_s: Option<(f64, f64)>,
    /// Duration in s for exceedances and peaks.
    pub duration_s: f64,
    /// One section per reported output.
    pub outputs: Vec<OutputReport>,
    /// The comfort/exposure and fatigue verdicts (`[analysis.comfort]`, `[analysis.fatigue]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdicts: Option<crate::study::VerdictAnalysis>,
    /// The Monte Carlo a_w, VDV, damage rate and basic-method check beside the analytic values
    /// (`--monte-carlo N` of a scenario with verdicts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub monte_carlo_verdicts: Option<super::mc_verdicts::McVerdicts>,
    /// The static compression of every spring under gravity, for the kinds that define it
    /// ([`crate::study::static_sag`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub static_sag: Option<Vec<crate::study::static_sag::StaticSag>>,
}

/// Runs every analysis of the scenario.
///
/// # Errors
/// Only when the scenario's system and excitation do not fit together (or the system is found unstable),
/// named as the file's `model`; divergent or inapplicable methods are reported inside.
pub fn analysis_report(sc: &Scenario) -> Result<AnalysisReport> {
    let sys = sc.model.system.as_ref();
    let mut outputs = Vec::new();
    for &i in &sc.analysis.outputs {
        // an error naming no key (a system found unstable here, not when the file was read) names the model
        let st =
            analyze_output_with(sys, &sc.excitation, i, &sc.analysis.effort).map_err(|e| sc.name_model_error(e))?;
        let bounds = st.bounds(3.0);
        let (band_sigma, band_note) = match sc.analysis.band {
            None => (None, None),
            Some((a, b)) => match band_variance(sys, &sc.excitation, i, a, b) {
                Ok(q) => (Some(q.value.sqrt()), None),
                Err(e) => (None, Some(e.to_string())),
            },
        };
        let mut level_values: Vec<f64> = bounds.map(|b| vec![b.1]).unwrap_or_default();
        for (j, lv) in &sc.analysis.levels {
            if *j == i {
                level_values.extend(lv);
            }
        }
        let levels = level_values
            .into_iter()
            .map(|a| LevelRow {
                level: a,
                upcrossing_rate: st.upcrossing_rate(a),
                exceedance_probability: st.exceedance_probability(a, sc.analysis.duration),
            })
            .collect();
        let bands = super::band_report::band_section(sc, i, &st);
        outputs.push(OutputReport {
            bands,
            lower_3sigma: bounds.map(|b| b.0),
            upper_3sigma: bounds.map(|b| b.1),
            band_sigma,
            band_note,
            expected_largest_peak: st.expected_largest_peak(sc.analysis.duration),
            levels,
            monte_carlo: None,
            statistics: st,
        });
    }
    Ok(AnalysisReport {
        title: sc.title.clone(),
        scenario: sc.path.display().to_string(),
        model: sc.model.description.clone(),
        input: input_description(sc),
        band_rad_s: sc.analysis.band,
        duration_s: sc.analysis.duration,
        outputs,
        verdicts: if sc.analysis.verdicts.is_empty() {
            None
        } else {
            Some(crate::study::verdict_analysis(sc).map_err(|e| sc.name_model_error(e))?)
        },
        monte_carlo_verdicts: None,
        static_sag: crate::study::static_sag::static_sag(sc)
            .transpose()
            .map_err(|e| sc.name_model_error(e))?,
    })
}

/// The scenario's input as a report line: the spectrum as written (each `[[input]]` table with its name and a
/// road's coherence) and the speed.
pub(crate) fn input_description(sc: &Scenario) -> String {
    if sc.inputs.len() <= 1 && sc.input.coherence.is_none() {
        format!(
            "{}{}",
            crate::scenario::input_as_written(&sc.input, &sc.path),
            sc.input.speed.map(|v| format!(" at {v} m/s")).unwrap_or_default()
        )
    } else {
        // `[[input]]` tables: name, spectrum, coherence of a road
        let each: Vec<String> = sc
            .inputs
            .iter()
            .map(|i| {
                format!(
                    "{}: {}{}",
                    i.name,
                    crate::scenario::input_as_written(i, &sc.path),
                    i.coherence
                        .as_ref()
                        .map(|c| format!(", two tracks, {c}"))
                        .unwrap_or_default()
                )
            })
            .collect();
        format!(
            "{}{}",
            each.join("; "),
            sc.input.speed.map(|v| format!(" at {v} m/s")).unwrap_or_default()
        )
    }
}

fn opt(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.6e}")).unwrap_or_else(|| "—".into())
}

impl fmt::Display for AnalysisReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "scenario  {}  ({})", self.title, self.scenario)?;
        writeln!(f, "model     {}", self.model)?;
        writeln!(f, "input     {}", self.input)?;
        if let Some(sag) = &self.static_sag {
            let each: Vec<String> = sag
                .iter()
                .map(|s| format!("{} {} m", s.element, crate::numbers::sig4(s.deflection_m)))
                .collect();
            writeln!(f, "sag       static compression under gravity: {}", each.join(", "))?;
        }
        for o in &self.outputs {
            let s = &o.statistics;
            writeln!(f)?;
            writeln!(f, "output {} [{}]", s.name, s.unit)?;
            writeln!(f, "  mean          {}", opt(s.mean))?;
            match s.sigma {
                Some(sig) => writeln!(f, "  sigma         {sig:.6e}")?,
                None => writeln!(f, "  sigma         {}", s.variance_outcome.describe())?,
            }
            if let Some(mc) = &o.monte_carlo {
                match (&mc.sigma, mc.covered) {
                    (Some(iv), Some(c)) => writeln!(
                        f,
                        "  sigma MC      {:.6e}  [{:.6e}, {:.6e}] ({} %, {} realizations, {})  covers analytic: {}{}",
                        iv.estimate,
                        iv.lower,
                        iv.upper,
                        100.0 * iv.confidence,
                        mc.realizations,
                        mc.method,
                        if c { "yes" } else { "NO" },
                        mc.discrete_sigma
                            .map(|d| format!("  (discrete-process σ {d:.6e})"))
                            .unwrap_or_default()
                    )?,
                    _ => writeln!(f, "  sigma MC      — {}", mc.note.as_deref().unwrap_or(""))?,
                }
            }
            writeln!(f, "  3σ bounds     [{}, {}]", opt(o.lower_3sigma), opt(o.upper_3sigma))?;
            if let (Some((a, b)), true) = (self.band_rad_s, o.band_sigma.is_some() || o.band_note.is_some()) {
                let band = format!(
                    "{:.3}–{:.3} Hz",
                    a / (2.0 * std::f64::consts::PI),
                    b / (2.0 * std::f64::consts::PI)
                );
                match (o.band_sigma, &o.band_note) {
                    (Some(v), _) => writeln!(f, "  sigma {band}  {v:.6e}")?,
                    (None, Some(n)) => writeln!(f, "  sigma {band}  — {n}")?,
                    _ => {}
                }
            }
            match s.rate_note() {
                None => writeln!(
                    f,
                    "  ν0+ (zero up-crossings) {} /s   bandwidth ε {}",
                    opt(s.zero_upcrossing_rate),
                    opt(s.bandwidth)
                )?,
                Some(why) => writeln!(f, "  ν0+ (zero up-crossings) — ({why})")?,
            }
            writeln!(
                f,
                "  expected largest peak in {} s: {}",
                self.duration_s,
                opt(o.expected_largest_peak)
            )?;
            for l in &o.levels {
                writeln!(
                    f,
                    "  level {:.6e}: up-crossing rate {} /s, P(exceed in {} s) {}",
                    l.level,
                    opt(l.upcrossing_rate),
                    self.duration_s,
                    opt(l.exceedance_probability)
                )?;
            }
            writeln!(
                f,
                "  {:<17} {:>14} {:>11} {:>11}  note",
                "variance method", "value", "error est.", "rel. diff"
            )?;
            for m in &s.methods {
                let (value, error, note) = match &m.outcome {
                    Outcome::Value { value, error_estimate } => (
                        format!("{value:.6e}"),
                        error_estimate.map(|e| format!("{e:.1e}")),
                        String::new(),
                    ),
                    Outcome::Divergent { reason } => ("infinite".into(), None, reason.clone()),
                    Outcome::NotConverged {
                        estimate,
                        error_estimate,
                        reason,
                        ..
                    } => (
                        format!("~{estimate:.6e}"),
                        Some(format!("{error_estimate:.1e}")),
                        format!("not converged: {reason}"),
                    ),
                    Outcome::Unreliable { value, reason } => (
                        format!("({value:.6e})"),
                        None,
                        format!("unreliable, not used: {reason}"),
                    ),
                    Outcome::NotApplicable { reason } => ("—".into(), None, reason.clone()),
                    Outcome::Failed { reason } => ("—".into(), None, format!("failed: {reason}")),
                };
                writeln!(
                    f,
                    "  {:<17} {:>14} {:>11} {:>11}  {}",
                    m.method.name(),
                    value,
                    error.unwrap_or_else(|| "—".into()),
                    m.rel_diff.map(|e| format!("{e:.1e}")).unwrap_or_else(|| "—".into()),
                    note
                )?;
            }
            if let Some(b) = &o.bands {
                write!(f, "{b}")?;
            }
        }
        if let Some(v) = &self.verdicts {
            write!(f, "{v}")?;
        }
        if let Some(v) = &self.monte_carlo_verdicts {
            write!(f, "{v}")?;
        }
        Ok(())
    }
}
