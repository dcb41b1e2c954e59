//! The weighted acceleration of a comfort axis (`[analysis.comfort]`) as a picture: its one-sided density
//! in Hz, its one-third-octave band r.m.s. values, and the ISO 2631-1 Annex C comfort reaction scale.

use super::chart::{Legend, LineChart, Marker, SecondaryAxis, Series};
use crate::comfort::ComfortReaction;
use crate::error::Result;
use crate::numbers::num;
use crate::scenario::Scenario;
use crate::study::scenario_curves::{weighted_density, WeightedDensity};

/// Comfort axis `axis` of the scenario's `[analysis.comfort]`: the density of the weighted acceleration
/// a_w(t) = W(s)·y(t) (log–log, one-sided in Hz), and on the secondary axis the r.m.s. value of every
/// one-third-octave band (IEC 61260-1 base-10 edges, [`bands_covering`](crate::comfort::bands_covering))
/// drawn as a staircase over the bands, the overall a_w, and the lower bounds of the ISO 2631-1:1997 Annex C comfort reactions
/// ([`ComfortReaction::range`]: 0.315 m/s² "a little uncomfortable", 0.5, 0.8, 1.25, 2 m/s² "extremely
/// uncomfortable"; those up to twice the largest value drawn, at least the first; the scale applies to the
/// overall value, so the bars show where it comes from).
///
/// # Formula
/// G_w(f) = 4π·S_w(2πf) with S_w(ω) = |W(iω)|²·S_y(ω) the two-sided density of the weighted output
/// ([`weighted_output`](crate::comfort::weighted_output), [`output_density`](crate::response::output_density));
/// band r.m.s. = (∫_{f₁}^{f₂} G_w df)^{1/2} ([`band_rms`](crate::comfort::band_rms)); a_w = (Σ band mean
/// squares)^{1/2} over the drawn range; computed by [`weighted_density`].
///
/// # Errors
/// Those of [`weighted_density`]: an axis index the scenario does not have, a model without a state-space
/// form, the errors of the weighting and the band quadrature.
///
/// # Examples
/// ```
/// use stochvib::scenario::load_scenario;
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/operator-seat-verdicts.toml"), Path::new("spectra")).unwrap();
/// let c = stochvib::plot::comfort_plots::weighted_density_chart(&sc, 0).unwrap();
/// assert_eq!(c.series.len(), 1);
/// // 23 one-third octaves from 0.5 to 80 Hz: 46 staircase points
/// assert_eq!(c.secondary.as_ref().unwrap().series[0].points.len(), 46);
/// ```
pub fn weighted_density_chart(sc: &Scenario, axis: usize) -> Result<LineChart> {
    let WeightedDensity {
        name,
        weighting,
        range_hz: (lo, hi),
        density,
        bands: stairs,
        a_w,
    } = weighted_density(sc, axis)?;
    let mut hlines = vec![Marker::new(
        a_w,
        format!("a_w = {} m/s² ({} to {} Hz)", num(a_w), num(lo), num(hi)),
    )];
    // the reactions up to twice the largest value drawn (always the first threshold, 0.315 m/s²), so that
    // the bars stay readable on the linear axis
    let top = 2.0 * stairs.iter().fold(a_w, |m, p| m.max(p.1));
    for r in ComfortReaction::ALL.iter().skip(1) {
        let at = r.range().0;
        if at <= top || hlines.len() == 1 {
            hlines.push(Marker::new(at, format!("{} from {} m/s²", r.label(), num(at))));
        }
    }
    let mut chart = LineChart::new(
        format!("{name} ({weighting}-weighted): one-third-octave bands against the ISO 2631-1 comfort scale"),
        "frequency f [Hz]",
        format!("one-sided density G(f) of {name} [(m/s²)²/Hz]"),
    );
    chart.log_x = true;
    chart.log_y = true;
    chart.max_decades = Some(8.0);
    chart.series.push(Series::line(format!("density of {name}"), density));
    chart.secondary = Some(SecondaryAxis {
        y_label: "one-third-octave band r.m.s. [m/s²]".into(),
        series: vec![Series::dashed("band r.m.s. (one-third octaves)", stairs)],
        hlines,
    });
    chart.legend = Legend::UpperRight;
    Ok(chart)
}

/// The daily exposure of a working day (`stochvib workday --plots`, `stochvib report WORKDAY.toml`) as
/// bars: each task's share k·a_w·√(T/8 h) on its largest axis (no limit: a share is not an exposure), then
/// the day's A(8) of every axis against the exposure limit value of Directive 2002/44/EC (1.15 m/s²; the
/// action value is in the report's verdict).
///
/// # Errors
/// The errors of [`super::BarChart::new`].
pub fn workday_chart(day: &crate::study::workday::WorkdayExposure) -> Result<super::BarChart> {
    let share = |t: &crate::study::workday::TaskExposure| t.axes.iter().map(|a| a.a8).fold(0.0, f64::max);
    let mut names: Vec<String> = day.tasks.iter().map(|t| t.task.name.clone()).collect();
    let mut values: Vec<f64> = day.tasks.iter().map(share).collect();
    let mut limits: Vec<Option<f64>> = vec![None; names.len()];
    for a in &day.axes {
        names.push(format!("the day, axis {}", a.axis.label()));
        values.push(a.a8);
        limits.push(Some(day.verdict.directive_a8.limit));
    }
    super::BarChart::new(
        format!("{}: daily exposure A(8)", day.title),
        "task (its share on its largest axis) and the day (health weighting k = 1.4 for x and y, 1 for z)",
        "A(8) [m/s²]",
        names,
        values,
        limits,
    )
}
