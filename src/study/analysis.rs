//! The `stochvib analyze` report: per output, the mean, σ, 3σ bounds, crossing rates and every variance
//! method with its value and its relative difference to the reference, as computed; [`crate::report::analysis_text`]
//! prints it.

use crate::error::Result;
use crate::response::{analyze_output_with, band_variance, ResponseStatistics};
use crate::scenario::Scenario;
use serde::Serialize;

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
    pub bands: Option<super::band_section::BandSection>,
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
    pub verdicts: Option<super::VerdictAnalysis>,
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
        let bands = super::band_section::band_section(sc, i, &st);
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
            Some(super::verdict_analysis(sc).map_err(|e| sc.name_model_error(e))?)
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
