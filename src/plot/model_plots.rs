//! Catalogue-model pictures from plain data: octave-band RMS against the seat limits (Table 7.1),
//! mine-hoist natural frequencies and renormalised mode components over ξ, balancer-bogie D_y/D_x over the
//! wheel radius r for several base lengths ℓ, and scraper σ's over speed.

use super::chart::{BarChart, Legend, LineChart, Marker, Series};
use crate::error::{Error, Result};
use crate::numbers::num;

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

/// Octave-band RMS values against limits (e.g. Table 7.1 for the operator seat): a bar per band centre
/// (Hz), green at or below its limit, red above, blue without a limit.
///
/// # Errors
/// [`Error::InvalidParameter`] when lengths differ or a value is not finite.
///
/// # Examples
/// ```
/// // Table 7.1 acceleration limits, m/s² (1, 2, 4 Hz)
/// let c = stochvib::plot::model_plots::octave_band_chart("Seat", &[1.0, 2.0, 4.0], &[0.3, 0.9, 0.2],
///     &[Some(1.10), Some(0.79), Some(0.57)], "RMS acceleration", "m/s²").unwrap();
/// assert_eq!(c.categories, vec!["1", "2", "4"]);
/// ```
pub fn octave_band_chart(
    title: &str,
    centres_hz: &[f64],
    rms: &[f64],
    limits: &[Option<f64>],
    quantity: &str,
    unit: &str,
) -> Result<BarChart> {
    same_length("rms", rms.len(), centres_hz.len())?;
    same_length("limits", limits.len(), centres_hz.len())?;
    BarChart::new(
        title,
        "octave band centre frequency [Hz]",
        format!("{quantity} [{unit}]"),
        centres_hz.iter().map(|f| num(*f)).collect(),
        rms.to_vec(),
        limits.to_vec(),
    )
}

/// Curves over a common abscissa: one series per (name, values).
fn curves_over(title: &str, x: &[f64], x_label: &str, y_label: &str, curves: &[(&str, &[f64])]) -> Result<LineChart> {
    let mut c = LineChart::new(title, x_label, y_label);
    for (name, y) in curves {
        same_length(name, y.len(), x.len())?;
        c.series
            .push(Series::line(*name, x.iter().cloned().zip(y.iter().cloned()).collect()));
    }
    Ok(c)
}

/// Mine hoist: natural frequencies (rad/s) of each mode against the position parameter ξ (dimensionless),
/// and, as a second chart, the renormalised mode components against ξ.
///
/// Returns `(frequencies, components)`.
///
/// # Errors
/// [`Error::InvalidParameter`] when a curve's length differs from `xi`'s.
///
/// # Examples
/// ```
/// let xi = [0.0, 0.5, 1.0];
/// let (f, m) = stochvib::plot::model_plots::mine_hoist_charts("Hoist", &xi,
///     &[("ω₁", &[5.0, 5.4, 6.0][..])], &[("mode 1, cage", &[1.0, 0.8, 0.5][..])]).unwrap();
/// assert_eq!(f.x_label, "position ξ [1]");
/// assert_eq!(m.series.len(), 1);
/// ```
pub fn mine_hoist_charts(
    title: &str,
    xi: &[f64],
    frequencies: &[(&str, &[f64])],
    components: &[(&str, &[f64])],
) -> Result<(LineChart, LineChart)> {
    let f = curves_over(
        &format!("Natural frequencies over ξ: {title}"),
        xi,
        "position ξ [1]",
        "natural frequency ω [rad/s]",
        frequencies,
    )?;
    let mut m = curves_over(
        &format!("Renormalised mode components over ξ: {title}"),
        xi,
        "position ξ [1]",
        "mode component Φ̄ [1]",
        components,
    )?;
    m.hlines.push(Marker::new(0.0, ""));
    Ok((f, m))
}

/// Balancer bogie: D_y/D_x against the wheel radius r (m), one curve per base length ℓ (m), with the
/// criterion σ_y/σ_x ≤ 0.5 (D_y/D_x ≤ 0.25) marked.
///
/// # Errors
/// [`Error::InvalidParameter`] when a curve's length differs from `r`'s.
///
/// # Examples
/// ```
/// let r = [0.05, 0.1, 0.15];
/// let c = stochvib::plot::model_plots::balancer_chart("Bogie", &r, &[(0.6, vec![0.4, 0.3, 0.25])]).unwrap();
/// assert_eq!(c.series[0].name, "ℓ = 0.6 m");
/// ```
pub fn balancer_chart(title: &str, r: &[f64], by_length: &[(f64, Vec<f64>)]) -> Result<LineChart> {
    let names: Vec<String> = by_length.iter().map(|(l, _)| format!("ℓ = {} m", num(*l))).collect();
    let curves: Vec<(&str, &[f64])> = names
        .iter()
        .zip(by_length)
        .map(|(n, (_, v))| (n.as_str(), v.as_slice()))
        .collect();
    let mut c = curves_over(title, r, "wheel radius r [m]", "variance ratio D_y/D_x [1]", &curves)?;
    c.hlines
        .push(Marker::new(0.25, "criterion σ_y/σ_x = 0.5 (D_y/D_x = 0.25)"));
    Ok(c)
}

/// Scraper: standard deviations against speed v (m/s), one curve per named output (all in `unit`).
///
/// # Errors
/// [`Error::InvalidParameter`] when a curve's length differs from `speeds`'.
///
/// # Examples
/// ```
/// let c = stochvib::plot::model_plots::scraper_chart("Scraper", &[5.0, 10.0, 15.0],
///     &[("cab acceleration", &[0.5, 1.0, 1.4][..])], "m/s²").unwrap();
/// assert_eq!(c.y_label, "standard deviation σ [m/s²]");
/// ```
pub fn scraper_chart(title: &str, speeds: &[f64], sigmas: &[(&str, &[f64])], unit: &str) -> Result<LineChart> {
    let mut c = curves_over(
        title,
        speeds,
        "speed v [m/s]",
        &format!("standard deviation σ [{unit}]"),
        sigmas,
    )?;
    // few speeds: show the computed points too
    let markers: Vec<Series> = c
        .series
        .iter()
        .enumerate()
        .map(|(k, s)| Series::markers("", s.points.clone()).with_color(k))
        .collect();
    c.series.extend(markers);
    c.legend = Legend::UpperLeft;
    Ok(c)
}
