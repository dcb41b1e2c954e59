//! Pictures of a transient Monte Carlo run (`stochvib plot run.h5` of `stochvib transient --monte-carlo`):
//! per output, the Monte Carlo σ(t) with its per-time interval band against the exact σ(t), and the
//! empirical distribution of the per-realization maxima of |y| with its DKW band against the analytic
//! distribution (Poisson at the integrated Rice rate). And the exact answers of a scenario with
//! `[transient]` (`stochvib transient SCENARIO --plots DIR`, `stochvib report`): per output σ(t) and
//! mean(t) by the exact route.

use super::chart::{file_stem, Band, Legend, LineChart, Series};
use crate::error::Result;
use crate::store::transient_series::{TransientOutput, TransientSeries};
use crate::store::RunFile;
use crate::study::transient_answers::{OutputOverTime, TransientAnalysis};
use std::path::{Path, PathBuf};

/// σ(t) of one output: the Monte Carlo estimate and its interval band against the exact curve.
pub fn sigma_chart(series: &TransientSeries, o: &TransientOutput) -> LineChart {
    let zip = |y: &[f64]| series.times.iter().copied().zip(y.iter().copied()).collect::<Vec<_>>();
    let mut c = LineChart::new(
        format!("{}: standard deviation over time", o.output),
        "time t [s]",
        format!("σ(t) of {} [{}]", o.output, o.unit),
    );
    c.bands.push(Band {
        name: format!("{} % interval (χ²)", 100.0 * series.confidence),
        lower: zip(&o.sigma_lower),
        upper: zip(&o.sigma_upper),
        color: Some(0),
    });
    c.series
        .push(Series::line(format!("Monte Carlo ({} realizations)", o.max_y.len()), zip(&o.sigma)).with_color(0));
    c.series
        .push(Series::dashed("exact (differential Lyapunov)", zip(&o.exact_sigma)).with_color(1));
    c.legend = Legend::LowerRight;
    c
}

/// The distribution of max |y| over the mission: empirical with its DKW band ±ε, and the analytic one.
pub fn maxima_chart(series: &TransientSeries, o: &TransientOutput) -> LineChart {
    let r = o.max_abs_y.len() as f64;
    let eps = series.dkw_epsilon;
    let emp: Vec<(f64, f64)> = o
        .max_abs_y
        .iter()
        .enumerate()
        .map(|(k, x)| (*x, (k + 1) as f64 / r))
        .collect();
    let mut c = LineChart::new(
        format!("{}: distribution of the largest |y| of the mission", o.output),
        format!("level b [{}]", o.unit),
        "P(max |y| ≤ b)",
    );
    c.bands.push(Band {
        name: format!("DKW band ±{eps:.3}"),
        lower: emp.iter().map(|(x, p)| (*x, (p - eps).max(0.0))).collect(),
        upper: emp.iter().map(|(x, p)| (*x, (p + eps).min(1.0))).collect(),
        color: Some(0),
    });
    c.series.push(Series::line("empirical", emp).with_color(0));
    let analytic: Vec<(f64, f64)> = o
        .levels
        .iter()
        .copied()
        .zip(o.cdf_max_abs_y_rice.iter().copied())
        .collect();
    c.series
        .push(Series::dashed("Poisson, integrated Rice rate", analytic).with_color(1));
    if o.cdf_max_abs_y_vanmarcke.iter().all(|v| v.is_finite()) {
        let v: Vec<(f64, f64)> = o
            .levels
            .iter()
            .copied()
            .zip(o.cdf_max_abs_y_vanmarcke.iter().copied())
            .collect();
        c.series.push(Series::dashed("Vanmarcke (1975)", v).with_color(2));
    }
    c.legend = Legend::LowerRight;
    c
}

/// The pictures of a transient run (`<output>-sigma`, `<output>-maxima`), or None for another run file.
///
/// # Errors
/// The store's errors (a damaged series fails its checksum); [`crate::Error::Io`] writing the pictures.
pub fn transient_plots(path: &Path, dir: &Path) -> Result<Option<Vec<PathBuf>>> {
    let run = RunFile::open(path)?;
    let Some(series) = run.transient()? else {
        return Ok(None);
    };
    let mut files = Vec::new();
    for o in &series.outputs {
        let s = file_stem(&o.output);
        files.extend(sigma_chart(&series, o).render(dir, &format!("{s}-sigma"))?);
        files.extend(maxima_chart(&series, o).render(dir, &format!("{s}-maxima"))?);
    }
    Ok(Some(files))
}

/// σ(t) and mean(t) of one output by the exact route (for a weighted output the running r.m.s. a_w(t));
/// `None` for an output without a finite σ.
pub fn exact_chart(a: &TransientAnalysis, o: &OutputOverTime) -> Option<LineChart> {
    if o.sigma.is_empty() {
        return None;
    }
    let zip = |y: &[f64]| a.times.iter().copied().zip(y.iter().copied()).collect::<Vec<_>>();
    let (title, sigma, y) = match &o.weighted_of {
        Some(w) => (
            format!("{}: running r.m.s. of the ISO 2631-1 weighted {w} over time", o.name),
            "running r.m.s. a_w(t), exact (differential Lyapunov)".to_string(),
            format!("a_w(t) of {} [{}]", o.name, o.unit),
        ),
        None => (
            format!("{}: standard deviation and mean over time", o.name),
            "σ(t), exact (differential Lyapunov)".to_string(),
            format!("σ(t) and mean(t) of {} [{}]", o.name, o.unit),
        ),
    };
    let mut c = LineChart::new(title, "time t [s]", y);
    c.series
        .push(Series::line(sigma, zip(&o.sigma)).analytic().with_color(0));
    if o.weighted_of.is_none() {
        c.series
            .push(Series::dashed("mean(t), exact", zip(&o.mean)).analytic().with_color(1));
    }
    c.legend = Legend::LowerRight;
    Some(c)
}

/// The pictures of the exact transient answers: `<output>-transient` per output with a finite σ.
///
/// # Errors
/// The errors of [`LineChart::render`].
pub fn exact_plots(a: &TransientAnalysis, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for o in &a.outputs {
        if let Some(c) = exact_chart(a, o) {
            files.extend(c.render(dir, &format!("{}-transient", file_stem(&o.name)))?);
        }
    }
    Ok(files)
}
