//! The pictures of the measured-record commands: `stochvib exposure RECORD --plots DIR` (per axis the
//! weighted time history with its running r.m.s.; the one-third-octave band spectrum against the ISO 2631-1
//! comfort scale) and `stochvib fatigue RECORD --plots DIR` (the rainflow range histogram against Dirlik's
//! expected count; the range–mean matrix).

use super::chart::{Band, Legend, LineChart, Marker, Series};
use crate::comfort::ComfortReaction;
use crate::error::Result;
use crate::numbers::{num, sig4};
use crate::record::{AxisEvaluation, ExposureEvaluation, FatigueEvaluation};
use std::path::{Path, PathBuf};

/// A file-name-safe stem from a channel name.
fn stem(prefix: &str, name: &str) -> String {
    let safe: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("{prefix}-{safe}")
}

/// The weighted signal of one axis over time: its envelope (largest and smallest sample per time bin), the
/// running r.m.s. (largest per bin), a_w and the MTVV.
///
/// # Examples
/// See [`exposure_plots`].
pub fn time_history_chart(e: &ExposureEvaluation, a: &AxisEvaluation) -> LineChart {
    let hours = e.duration_s > 2.0 * 3600.0;
    let (scale, unit) = if hours { (1.0 / 3600.0, "h") } else { (1.0, "s") };
    let upper: Vec<(f64, f64)> = a.envelope.iter().map(|b| (b.time_s * scale, b.max)).collect();
    let lower: Vec<(f64, f64)> = a.envelope.iter().map(|b| (b.time_s * scale, b.min)).collect();
    let running: Vec<(f64, f64)> = a
        .envelope
        .iter()
        .filter(|b| b.running_rms.is_finite())
        .map(|b| (b.time_s * scale, b.running_rms))
        .collect();
    let mut c = LineChart::new(
        format!(
            "{} ({}-weighted, {} {}): weighted acceleration and running r.m.s.",
            a.channel,
            a.weighting,
            a.location.label(),
            a.axis.label()
        ),
        format!("time [{unit}]"),
        format!(
            "{}-weighted acceleration a_w(t) [{}]",
            a.weighting,
            a.weighting.quantity().unit
        ),
    );
    c.bands.push(Band {
        name: "a_w(t): smallest to largest sample per time bin".into(),
        lower,
        upper,
        color: Some(0),
    });
    c.series.push(
        Series::line(
            format!("running r.m.s., τ = {} s (linear), largest per bin", num(e.tau_s)),
            running,
        )
        .with_color(1),
    );
    c.hlines.push(Marker::new(
        a.metrics.a_w,
        format!("a_w = {} (whole record)", sig4(a.metrics.a_w)),
    ));
    if let Some(m) = a.metrics.mtvv {
        c.hlines.push(Marker::new(m, format!("MTVV = {}", sig4(m))));
    }
    c.legend = Legend::LowerRight;
    c
}

/// The one-third-octave band r.m.s. of every axis (staircases over the bands) against the lower bounds of
/// the ISO 2631-1 Annex C comfort reactions; `None` without band values above 0 (a zero record: the
/// logarithmic axis has no place for them).
pub fn band_chart(e: &ExposureEvaluation) -> Option<LineChart> {
    let mut c = LineChart::new(
        format!(
            "{}: one-third-octave bands against the ISO 2631-1 comfort scale",
            e.record
                .source
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
        ),
        "frequency f [Hz]",
        "band r.m.s. of the weighted acceleration [m/s²]",
    );
    c.log_x = true;
    c.log_y = true;
    c.max_decades = Some(5.0);
    let mut top: f64 = 0.0;
    for (i, a) in e.axes.iter().chain(&e.motion_sickness).enumerate() {
        let Some(bands) = &a.bands else { continue };
        let mut stairs = Vec::with_capacity(2 * bands.len());
        // a band of r.m.s. 0 has no place on the logarithmic axis (a channel that is zero has none at all)
        for b in bands.iter().filter(|b| b.rms > 0.0) {
            stairs.push((b.band.lower_hz, b.rms));
            stairs.push((b.band.upper_hz, b.rms));
            top = top.max(b.rms);
        }
        if stairs.is_empty() {
            continue;
        }
        c.series
            .push(Series::line(format!("{} ({})", a.channel, a.weighting), stairs).with_color(i));
    }
    if c.series.is_empty() {
        return None;
    }
    for r in ComfortReaction::ALL.iter().skip(1) {
        let at = r.range().0;
        if at <= 4.0 * top.max(0.1) {
            c.hlines.push(Marker::new(
                at,
                format!("{} from {} m/s² (overall a_v)", r.label(), num(at)),
            ));
        }
    }
    c.legend = Legend::LowerLeft;
    Some(c)
}

/// Writes the exposure pictures into `dir`: `exposure-time-<channel>` per evaluated channel and
/// `exposure-bands` (SVG and PNG each).
///
/// # Errors
/// The errors of [`LineChart::render`].
pub fn exposure_plots(e: &ExposureEvaluation, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for a in e.axes.iter().chain(&e.motion_sickness) {
        files.extend(time_history_chart(e, a).render(dir, &stem("exposure-time", &a.channel))?);
    }
    if let Some(c) = band_chart(e) {
        files.extend(c.render(dir, "exposure-bands")?);
    }
    Ok(files)
}

/// The rainflow range histogram (cycles per range bin, from the range–mean matrix) against Dirlik's expected
/// count from the record's own spectral moments.
pub fn range_histogram_chart(e: &FatigueEvaluation) -> LineChart {
    let hist = e.matrix.range_histogram();
    let w = e.matrix.range_width;
    let counts: Vec<(f64, f64)> = hist
        .iter()
        .filter(|(_, n)| *n > 0.0)
        .map(|(lo, n)| (lo + 0.5 * w, *n))
        .collect();
    let (sym, unit, scale) = stress_axis(e);
    let counts: Vec<(f64, f64)> = counts.into_iter().map(|(r, n)| (r * scale, n)).collect();
    let mut c = LineChart::new(
        format!("Rainflow ranges of {}", e.channel),
        format!("{} range Δ{sym} [{unit}]", quantity_of(&sym)),
        format!("cycles per range bin (bin width {} {unit})", num(w * scale)),
    );
    c.log_y = true;
    c.series.push(Series::markers("rainflow count (ASTM E1049)", counts));
    if let Some(m) = &e.moments {
        let edges: Vec<f64> = (0..=hist.len()).map(|i| i as f64 * w).collect();
        let expected = crate::simulate::verdicts::dirlik_counts(m, &edges, e.duration_s);
        let pts: Vec<(f64, f64)> = expected
            .iter()
            .enumerate()
            .filter(|(_, n)| **n > 0.0)
            .map(|(i, n)| ((i as f64 + 0.5) * w * scale, *n))
            .collect();
        c.series
            .push(Series::line("Dirlik's expected count (the record's Welch moments)", pts).analytic());
    }
    c.max_decades = Some(8.0);
    c
}

/// The range–mean matrix as markers, one series per decade of counts.
pub fn matrix_chart(e: &FatigueEvaluation) -> LineChart {
    let m = &e.matrix;
    let (sym, unit, scale) = stress_axis(e);
    let mut by_decade: std::collections::BTreeMap<i32, Vec<(f64, f64)>> = Default::default();
    for (i, row) in m.counts.iter().enumerate() {
        for (j, &n) in row.iter().enumerate() {
            if n > 0.0 {
                let p = (
                    (m.mean_origin + (j as f64 + 0.5) * m.mean_width) * scale,
                    (i as f64 + 0.5) * m.range_width * scale,
                );
                by_decade.entry(n.log10().floor() as i32).or_default().push(p);
            }
        }
    }
    let mut c = LineChart::new(
        format!("Rainflow matrix of {}", e.channel),
        format!("cycle mean {sym}_m [{unit}]"),
        format!("cycle range Δ{sym} [{unit}]"),
    );
    for (k, (d, pts)) in by_decade.into_iter().enumerate() {
        c.series.push(
            Series::markers(
                format!("{} to {} cycles per cell", num(10f64.powi(d)), num(10f64.powi(d + 1))),
                pts,
            )
            .with_color(k),
        );
    }
    c.legend = Legend::UpperRight;
    c
}

/// The fatigue charts' axis in the unit the record's channel is written in: (symbol, unit, factor from SI to
/// that unit): `S` for a stress (a unit of dimension Pa, e.g. MPa), `ε` for a strain (dimensionless, e.g.
/// µm/m), the channel's name for another quantity (a force, a torque); the SI unit when the channel is
/// not among the record's (it always is: [`FatigueEvaluation::channel`] is built from it).
fn stress_axis(e: &FatigueEvaluation) -> (String, String, f64) {
    let c = e
        .record
        .channels
        .iter()
        .find(|c| format!("{} [{}]", c.name, c.unit) == e.channel);
    let Some(c) = c.filter(|c| c.to_si.is_finite() && c.to_si > 0.0) else {
        return ("S".into(), "SI unit".into(), 1.0);
    };
    let sym = if c.dim == crate::units::Dim::new(-1, 1, -2) {
        "S".to_string()
    } else if c.dim == crate::units::Dim::DIMENSIONLESS {
        "ε".to_string()
    } else {
        format!("({})", c.name)
    };
    (sym, c.unit.clone(), 1.0 / c.to_si)
}

/// The quantity a symbol of [`stress_axis`] stands for.
fn quantity_of(sym: &str) -> &'static str {
    match sym {
        "S" => "stress",
        "ε" => "strain",
        _ => "load",
    }
}

/// Writes the fatigue pictures into `dir`: `fatigue-ranges` and `fatigue-matrix` (SVG and PNG each).
///
/// # Errors
/// The errors of [`LineChart::render`].
pub fn fatigue_plots(e: &FatigueEvaluation, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = range_histogram_chart(e).render(dir, "fatigue-ranges")?;
    files.extend(matrix_chart(e).render(dir, "fatigue-matrix")?);
    Ok(files)
}
