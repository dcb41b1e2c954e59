//! Pictures of a measured road (`stochvib road PROFILE.csv --plots DIR`): per track the Welch estimate of
//! the spatial density G_d(n) with its χ² confidence band, the ISO 8608 fits (w = 2 and w free) and the ISO
//! 8608 class limits; for two tracks or more the squared coherence of the first two with its interval.
//!
//! Conventions as [`crate::road`]: n in cycles/m, G_d(n) one-sided in m³ (m² per cycle/m), n₀ = 0.1
//! cycles/m.

use super::chart::{file_stem, Band, Legend, LineChart, Series};
use crate::error::{Error, Result};
use crate::numbers::num;
use crate::spectrum::{IsoBound, IsoClass};
use crate::study::road_profile::{FitRow, RoadReport};
use std::path::{Path, PathBuf};

/// n₀ of ISO 8608, cycles/m.
const N0: f64 = 0.1;

/// Points of each fitted line and class limit.
const LINE_POINTS: usize = 60;

/// The ISO 8608 class limits between neighbouring classes: (label `A/B` … `G/H`, G_d(n₀) in m³), the upper
/// limit of the smoother class (ISO 8608:2016 Table 3: 32e-6·4^k m³ for k = 0 (A/B) … 6 (G/H)).
///
/// # Examples
/// ```
/// let l = stochvib::plot::road_plots::class_limits();
/// assert_eq!(l.len(), 7);
/// assert_eq!(l[1], ("B/C".to_string(), 128e-6));
/// ```
pub fn class_limits() -> Vec<(String, f64)> {
    IsoClass::ALL
        .windows(2)
        .filter_map(|w| w[0].g0(IsoBound::Upper).ok().map(|g| (format!("{}/{}", w[0], w[1]), g)))
        .collect()
}

/// `n` log-spaced points from `lo` to `hi` (both > 0).
fn log_points(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    let r = (hi / lo).ln();
    (0..n).map(|k| lo * (r * k as f64 / (n - 1) as f64).exp()).collect()
}

fn fit_name(fit: &FitRow) -> String {
    let w = if fit.waviness_mode.starts_with("fixed") {
        "w = 2".to_string()
    } else {
        format!("free w = {}", num(fit.waviness))
    };
    format!(
        "ISO 8608 fit, {w}: G_d(n0) = {} m³, class {}",
        num(fit.g0_m3),
        fit.class
    )
}

/// Log–log chart of track `track` of a road report: the measured density Ĝ_d(n) (bins n > 0), its χ²
/// confidence band, the ISO 8608 fits G_d(n₀)(n/n₀)^{−w} over their fitted bands, and the ISO 8608 class
/// limits G(n₀)(n/n₀)^{−2} ([`class_limits`]) of the fitted classes and of one class more on either side.
///
/// # Formula
/// Fit lines: G_d(n) = Ĝ_d(n₀)·(n/n₀)^{−ŵ} for n in the fit's band. Class limit between classes k and k+1:
/// G_d(n) = 32·4^k·10⁻⁶ m³ ·(n/n₀)^{−2} over the measured bins' n range. The y range is that of the band
/// (a factor 2 beyond its lowest and highest edge); the limits are clipped to it.
///
/// # Errors
/// [`Error::InvalidParameter`] for a track index out of range; [`Error::Numerical`] "nothing to plot"
/// when the track has no bin with n > 0 and a positive density.
///
/// # Examples
/// ```
/// use stochvib::study::road_profile::{road_report, RoadReportOptions};
/// let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/measured-profile.csv");
/// let r = road_report(&p, &RoadReportOptions::default()).unwrap();
/// let c = stochvib::plot::road_plots::road_density_chart(&r, 0).unwrap();
/// assert!(c.log_x && c.log_y);
/// assert!(c.series.iter().any(|s| s.name.starts_with("class limit B/C")));
/// ```
pub fn road_density_chart(report: &RoadReport, track: usize) -> Result<LineChart> {
    let t = report.tracks.get(track).ok_or_else(|| {
        Error::invalid(
            "track",
            track,
            format!("the profile has {} tracks", report.tracks.len()),
        )
    })?;
    let rows: Vec<_> = t
        .density
        .iter()
        .filter(|r| r.n > 0.0 && r.g_d > 0.0 && r.g_d.is_finite())
        .collect();
    if rows.is_empty() {
        return Err(Error::Numerical {
            what: format!("plot road density of {}", t.name),
            reason: "nothing to plot: no bin with n > 0 and a positive density".into(),
        });
    }
    let pc = report.confidence * 100.0;
    let mut chart = LineChart::new(
        format!("Road density of track {}: {}", t.name, report.file),
        "spatial frequency n [cycles/m]",
        "density G_d(n), one-sided [m³ = m²/(cycles/m)]",
    );
    chart.log_x = true;
    chart.log_y = true;
    chart.bands.push(Band {
        name: format!("{} % χ² interval (ν = {:.1})", num(pc), report.dof),
        lower: rows.iter().map(|r| (r.n, r.lower)).collect(),
        upper: rows.iter().map(|r| (r.n, r.upper)).collect(),
        color: Some(0),
    });
    chart.series.push(
        Series::line(
            format!("Welch estimate Ĝ_d(n), {} segments", report.segments),
            rows.iter().map(|r| (r.n, r.g_d)).collect(),
        )
        .with_color(0),
    );
    for (k, fit) in t.fits.iter().enumerate() {
        let (lo, hi) = fit.band;
        if !(lo > 0.0 && hi > lo) {
            continue;
        }
        let pts = log_points(lo, hi, LINE_POINTS)
            .into_iter()
            .map(|n| (n, fit.g0_m3 * (n / N0).powf(-fit.waviness)))
            .collect();
        chart.series.push(Series::line(fit_name(fit), pts).with_color(1 + k));
    }
    let (n_lo, n_hi) = (rows[0].n, rows[rows.len() - 1].n);
    // the y range is the data's (the class limits are clipped to it)
    let y_lo = rows
        .iter()
        .map(|r| r.lower)
        .filter(|v| *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    let y_hi = rows
        .iter()
        .map(|r| r.upper)
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    if y_lo.is_finite() && y_hi > y_lo {
        chart.y_range = Some((y_lo / 2.0, y_hi * 2.0));
    }
    // the limits of the fitted classes, and one more class on either side
    let index = |c: &str| IsoClass::ALL.iter().position(|k| k.to_string() == c);
    let fitted: Vec<usize> = t.fits.iter().filter_map(|f| index(&f.class)).collect();
    let (c_lo, c_hi) = (
        fitted.iter().copied().min().unwrap_or(0),
        fitted.iter().copied().max().unwrap_or(IsoClass::ALL.len() - 1),
    );
    for (k, (label, g)) in class_limits().into_iter().enumerate() {
        if k + 2 < c_lo || k > c_hi + 1 {
            continue;
        }
        let pts = log_points(n_lo, n_hi, LINE_POINTS)
            .into_iter()
            .map(|n| (n, g * (n / N0).powi(-2)))
            .collect();
        chart.series.push(
            Series::dashed(format!("class limit {label}: {} m³ at n0, w = 2", num(g)), pts)
                .with_color(7)
                .limit(),
        );
    }
    chart.legend = Legend::UpperRight;
    Ok(chart)
}

/// Chart of the squared coherence γ̂²(n) of the first two tracks of a road report with its Fisher-z
/// interval (log n axis, γ² from 0 to 1), or `None` for a profile of one track.
///
/// # Errors
/// [`Error::Numerical`] "nothing to plot" when no bin has n > 0.
pub fn road_coherence_chart(report: &RoadReport) -> Result<Option<LineChart>> {
    let Some((l, r)) = &report.coherence_tracks else {
        return Ok(None);
    };
    let rows: Vec<_> = report
        .coherence
        .iter()
        .filter(|c| c.n > 0.0 && c.squared_coherence.is_finite())
        .collect();
    if rows.is_empty() {
        return Err(Error::Numerical {
            what: "plot road coherence".into(),
            reason: "nothing to plot: no bin with n > 0".into(),
        });
    }
    let mut chart = LineChart::new(
        format!("Squared coherence of tracks {l} and {r}: {}", report.file),
        "spatial frequency n [cycles/m]",
        "squared coherence γ² [-]",
    );
    chart.log_x = true;
    chart.y_range = Some((0.0, 1.05));
    chart.bands.push(Band {
        name: format!("{} % Fisher-z interval", num(report.confidence * 100.0)),
        lower: rows.iter().map(|c| (c.n, c.lower.max(0.0))).collect(),
        upper: rows.iter().map(|c| (c.n, c.upper.min(1.0))).collect(),
        color: Some(0),
    });
    chart.series.push(
        Series::line(
            format!("γ̂²(n) of {l} and {r}"),
            rows.iter().map(|c| (c.n, c.squared_coherence)).collect(),
        )
        .with_color(0),
    );
    chart.legend = Legend::LowerLeft;
    Ok(Some(chart))
}

/// Writes the pictures of a road report into `dir`: `road-density-<track>` per track and, for two tracks or
/// more, `road-coherence`, each as `.svg` and `.png`; returns the paths written.
///
/// # Errors
/// As [`road_density_chart`], [`road_coherence_chart`] and [`LineChart::render`].
pub fn road_plots(report: &RoadReport, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for (k, t) in report.tracks.iter().enumerate() {
        files.extend(road_density_chart(report, k)?.render(dir, &format!("road-density-{}", file_stem(&t.name)))?);
    }
    if let Some(c) = road_coherence_chart(report)? {
        files.extend(c.render(dir, "road-coherence")?);
    }
    Ok(files)
}
