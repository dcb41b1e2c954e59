//! Monte Carlo check pictures from plain data (the engine hands in slices): realization excerpts, the
//! histogram of an output against N(M_y, σ_y), the Welch estimate with its interval band against the
//! analytic density, and the correlation estimate against the model.

use super::chart::{Band, Histogram, Legend, LineChart, Marker, Series};
use crate::error::{Error, Result};
use crate::numbers::num;
use std::f64::consts::PI;

fn same_length(name: &str, n: usize, expected: usize) -> Result<()> {
    if n == expected {
        Ok(())
    } else {
        Err(Error::invalid(
            name,
            format!("{n} values"),
            format!("need one per abscissa ({expected})"),
        ))
    }
}

/// Excerpts of realizations: several named series against time t (s).
///
/// # Errors
/// [`Error::InvalidParameter`] when a series' length differs from `t`'s.
///
/// # Examples
/// ```
/// let t: Vec<f64> = (0..100).map(|k| k as f64 * 0.01).collect();
/// let y: Vec<f64> = t.iter().map(|t| (6.0 * t).sin()).collect();
/// let c = stochvib::plot::mc_plots::realizations_chart("Run 1", &t, &[("run 0", &y[..])], "body displacement", "m").unwrap();
/// assert_eq!(c.y_label, "body displacement [m]");
/// ```
pub fn realizations_chart(
    title: &str,
    t: &[f64],
    runs: &[(&str, &[f64])],
    quantity: &str,
    unit: &str,
) -> Result<LineChart> {
    let mut c = LineChart::new(title, "time t [s]", format!("{quantity} [{unit}]"));
    for (name, y) in runs {
        same_length(name, y.len(), t.len())?;
        c.series
            .push(Series::line(*name, t.iter().cloned().zip(y.iter().cloned()).collect()));
    }
    Ok(c)
}

/// Histogram of samples (normalised to a probability density) against the Gaussian density of N(M, σ),
/// with M and the 3σ bounds M ± 3σ marked.
///
/// # Formula
/// p(y) = exp(−(y − M)²/(2σ²)) / (σ√(2π)), drawn over M ± 4σ and the sample range.
///
/// # Errors
/// [`Error::InvalidParameter`] for σ ≤ 0 or a non-finite M.
///
/// # Examples
/// ```
/// let s: Vec<f64> = (0..500).map(|k| ((k * 7919) % 1000) as f64 / 1000.0 - 0.5).collect();
/// let h = stochvib::plot::mc_plots::histogram_chart("Run", &s, 0.0, 0.29, "travel", "m", None).unwrap();
/// assert_eq!(h.vlines.len(), 3);
/// ```
pub fn histogram_chart(
    title: &str,
    samples: &[f64],
    mean: f64,
    sigma: f64,
    quantity: &str,
    unit: &str,
    bins: Option<usize>,
) -> Result<Histogram> {
    crate::error::require_positive("sigma", sigma)?;
    crate::error::require_finite("mean", mean)?;
    let mut h = Histogram::new(
        title,
        format!("{quantity} y [{unit}]"),
        format!("probability density [{}]", super::style::per_unit(unit)),
        samples.to_vec(),
    );
    h.bins = bins;
    let finite = samples.iter().cloned().filter(|v| v.is_finite());
    let lo = finite.clone().fold(mean - 4.0 * sigma, f64::min);
    let hi = finite.fold(mean + 4.0 * sigma, f64::max);
    let pts = (0..=300)
        .map(|k| {
            let y = lo + (hi - lo) * k as f64 / 300.0;
            let z = (y - mean) / sigma;
            (y, (-0.5 * z * z).exp() / (sigma * (2.0 * PI).sqrt()))
        })
        .collect();
    h.curves
        .push(Series::line(format!("N(M, σ): M = {}, σ = {} {unit}", num(mean), num(sigma)), pts).analytic());
    h.vlines = vec![
        Marker::new(mean, "M"),
        Marker::new(mean - 3.0 * sigma, "M ± 3σ"),
        Marker::new(mean + 3.0 * sigma, ""),
    ];
    Ok(h)
}

/// Welch estimate of a one-sided density G(f) (per Hz) with its confidence band against the analytic
/// density, log–log. `f`, `estimate`, `lower`, `upper` share one grid; `analytic` is (f, G(f)) on any grid.
/// Points ≤ 0 (e.g. the f = 0 bin) are dropped by the log axes with a note in the legend.
///
/// # Errors
/// [`Error::InvalidParameter`] when lengths differ or `confidence` is not in (0, 1).
///
/// # Examples
/// ```
/// let f: Vec<f64> = (1..50).map(|k| k as f64).collect();
/// let g: Vec<f64> = f.iter().map(|f| 1.0 / (1.0 + f * f)).collect();
/// let lo: Vec<f64> = g.iter().map(|g| 0.8 * g).collect();
/// let hi: Vec<f64> = g.iter().map(|g| 1.25 * g).collect();
/// let a: Vec<(f64, f64)> = f.iter().cloned().zip(g.iter().cloned()).collect();
/// let c = stochvib::plot::mc_plots::welch_chart("Run", &f, &g, &lo, &hi, 0.95, &a, "travel", "m").unwrap();
/// assert!(c.log_x && c.log_y);
/// ```
#[allow(clippy::too_many_arguments)]
pub fn welch_chart(
    title: &str,
    f: &[f64],
    estimate: &[f64],
    lower: &[f64],
    upper: &[f64],
    confidence: f64,
    analytic: &[(f64, f64)],
    quantity: &str,
    unit: &str,
) -> Result<LineChart> {
    same_length("estimate", estimate.len(), f.len())?;
    same_length("lower", lower.len(), f.len())?;
    same_length("upper", upper.len(), f.len())?;
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(Error::invalid("confidence", confidence, "must be in (0, 1)"));
    }
    let u2 = if unit.chars().all(|c| c.is_alphanumeric()) {
        format!("{unit}²")
    } else {
        format!("({unit})²")
    };
    let mut c = LineChart::new(
        title,
        "frequency f [Hz]",
        format!("density G(f), one-sided, of {quantity} [{u2}/Hz]"),
    );
    c.log_x = true;
    c.log_y = true;
    let zip = |y: &[f64]| f.iter().cloned().zip(y.iter().cloned()).collect::<Vec<_>>();
    c.bands.push(Band {
        name: format!("{} % interval", num(100.0 * confidence)),
        lower: zip(lower),
        upper: zip(upper),
        color: Some(0),
    });
    c.series
        .push(Series::line("Welch estimate", zip(estimate)).with_color(0));
    c.series.push(
        Series::dashed("analytic density", analytic.to_vec())
            .with_color(1)
            .analytic(),
    );
    c.legend = Legend::LowerLeft;
    Ok(c)
}

/// Correlation estimate K̂(τ) against the model K(τ), against lag τ (s), with an optional interval band.
///
/// # Errors
/// [`Error::InvalidParameter`] when lengths differ.
///
/// # Examples
/// ```
/// let tau: Vec<f64> = (0..100).map(|k| k as f64 * 0.02).collect();
/// let k: Vec<f64> = tau.iter().map(|t| (-t).exp()).collect();
/// let c = stochvib::plot::mc_plots::correlation_chart("Run", &tau, &k, &k, None, "travel", "m").unwrap();
/// assert_eq!(c.series.len(), 2);
/// ```
pub fn correlation_chart(
    title: &str,
    lags: &[f64],
    estimate: &[f64],
    model: &[f64],
    band: Option<(&[f64], &[f64])>,
    quantity: &str,
    unit: &str,
) -> Result<LineChart> {
    same_length("estimate", estimate.len(), lags.len())?;
    same_length("model", model.len(), lags.len())?;
    let u2 = if unit.chars().all(|c| c.is_alphanumeric()) {
        format!("{unit}²")
    } else {
        format!("({unit})²")
    };
    let mut c = LineChart::new(title, "lag τ [s]", format!("correlation K(τ) of {quantity} [{u2}]"));
    let zip = |y: &[f64]| lags.iter().cloned().zip(y.iter().cloned()).collect::<Vec<_>>();
    if let Some((lo, hi)) = band {
        same_length("band lower", lo.len(), lags.len())?;
        same_length("band upper", hi.len(), lags.len())?;
        c.bands.push(Band {
            name: "interval of the estimate".into(),
            lower: zip(lo),
            upper: zip(hi),
            color: Some(0),
        });
    }
    c.series
        .push(Series::line("estimate K̂(τ)", zip(estimate)).with_color(0));
    c.series
        .push(Series::dashed("model K(τ)", zip(model)).with_color(1).analytic());
    c.hlines.push(Marker::new(0.0, ""));
    Ok(c)
}
