//! A small chart layer over `plotters`: line charts (linear or logarithmic axes, bands, markers, an optional
//! linear secondary y axis), bar charts with limit markers and histograms with overlaid curves.
//!
//! Every chart renders to `<stem>.svg` and `<stem>.png` (800 × 500 pixels) in a directory. Text is drawn
//! with the bundled DejaVu Sans font (`assets/DejaVuSans.ttf`, registered once with
//! [`plotters::style::register_font`]), so no system font library (fontconfig, freetype) is needed.

use crate::error::{Error, Result};
use plotters::coord::ranged1d::{AsRangedCoord, SegmentValue, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// Width of every rendered image, pixels.
pub const WIDTH: u32 = 800;
/// Height of every rendered image, pixels.
pub const HEIGHT: u32 = 500;

/// DejaVu Sans (Bitstream Vera licence, see `assets/LICENSE-DejaVu.txt`).
static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Registers the bundled font under the generic family names once per process.
fn ensure_font() -> Result<()> {
    static STATE: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    STATE
        .get_or_init(|| {
            for family in ["sans-serif", "serif", "monospace"] {
                plotters::style::register_font(family, FontStyle::Normal, FONT)
                    .map_err(|_| "the bundled font assets/DejaVuSans.ttf could not be parsed".to_string())?;
            }
            Ok(())
        })
        .clone()
        .map_err(|reason| plot_error("font registration", reason))
}

fn plot_error(what: &str, reason: impl Into<String>) -> Error {
    Error::Numerical {
        what: format!("plot {what}"),
        reason: reason.into(),
    }
}

/// Colours used for series by index (the "tab10" palette).
const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

fn colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LineStyle {
    /// Solid line through the points.
    Solid,
    /// Dashed line through the points.
    Dashed,
    /// One filled circle per point, no line.
    Markers,
}

/// One named series of (x, y) points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text (empty: no legend entry).
    pub name: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line, dashes or markers.
    pub style: LineStyle,
    /// Palette index; `None` uses the series' position in the chart.
    pub color: Option<usize>,
}

impl Series {
    /// A solid line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: LineStyle::Solid,
            color: None,
        }
    }
    /// A dashed line.
    pub fn dashed(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            style: LineStyle::Dashed,
            ..Series::line(name, points)
        }
    }
    /// Markers only.
    pub fn markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            style: LineStyle::Markers,
            ..Series::line(name, points)
        }
    }
    /// Sets the palette index of the colour.
    pub fn with_color(mut self, index: usize) -> Self {
        self.color = Some(index);
        self
    }
}

/// A shaded band between two curves (e.g. a confidence interval); the polygon is `lower` followed by
/// `upper` reversed.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Legend text.
    pub name: String,
    /// Lower edge points.
    pub lower: Vec<(f64, f64)>,
    /// Upper edge points.
    pub upper: Vec<(f64, f64)>,
    /// Palette index; `None` uses the first colour.
    pub color: Option<usize>,
}

/// A labelled vertical or horizontal line at a coordinate value.
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    /// Coordinate of the line (x for vertical, y for horizontal lines).
    pub at: f64,
    /// Legend text (empty: no legend entry).
    pub label: String,
}

impl Marker {
    /// A marker at `at` labelled `label`.
    pub fn new(at: f64, label: impl Into<String>) -> Self {
        Marker {
            at,
            label: label.into(),
        }
    }
}

/// Where the legend box goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    /// Upper right corner of the plotting area.
    UpperRight,
    /// Upper left corner.
    UpperLeft,
    /// Lower left corner.
    LowerLeft,
    /// Lower right corner.
    LowerRight,
    /// No legend.
    Hidden,
}

/// A linear secondary y axis on the right of a [`LineChart`] (shares the x axis).
#[derive(Debug, Clone, PartialEq)]
pub struct SecondaryAxis {
    /// Axis label with quantity and unit.
    pub y_label: String,
    /// Series drawn against this axis.
    pub series: Vec<Series>,
    /// Horizontal lines against this axis.
    pub hlines: Vec<Marker>,
}

/// A chart of curves against x, optionally logarithmic on either axis.
///
/// Points that cannot be drawn are dropped rather than failing: non-finite values always; x ≤ 0 on a
/// logarithmic x axis and y ≤ 0 on a logarithmic y axis, with a note "(k points ≤ 0 not shown)" appended to
/// the series' legend text; points outside an explicit `y_range` (or below the `max_decades` floor)
/// silently.
///
/// # Examples
/// ```
/// use stochvib::plot::{LineChart, Series};
/// let dir = std::env::temp_dir().join("stochvib-doc-linechart");
/// let mut c = LineChart::new("Parabola", "time t [s]", "displacement x [m]");
/// c.series.push(Series::line("x = t²", (0..50).map(|i| (i as f64 * 0.1, (i as f64 * 0.1).powi(2))).collect()));
/// let files = c.render(&dir, "parabola").unwrap();
/// assert_eq!(files.len(), 2);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LineChart {
    /// Title (names the scenario).
    pub title: String,
    /// x axis label with quantity and unit.
    pub x_label: String,
    /// y axis label with quantity and unit.
    pub y_label: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Curves.
    pub series: Vec<Series>,
    /// Shaded bands (drawn under the curves).
    pub bands: Vec<Band>,
    /// Vertical lines.
    pub vlines: Vec<Marker>,
    /// Horizontal lines (primary axis).
    pub hlines: Vec<Marker>,
    /// Explicit x range (otherwise the data's, padded).
    pub x_range: Option<(f64, f64)>,
    /// Explicit y range (otherwise the data's, padded).
    pub y_range: Option<(f64, f64)>,
    /// On a logarithmic y axis, show at most this many decades below the largest value.
    pub max_decades: Option<f64>,
    /// Optional secondary (right, linear) y axis.
    pub secondary: Option<SecondaryAxis>,
    /// Legend position.
    pub legend: Legend,
}

impl LineChart {
    /// An empty chart with linear axes.
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        LineChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            log_x: false,
            log_y: false,
            series: Vec::new(),
            bands: Vec::new(),
            vlines: Vec::new(),
            hlines: Vec::new(),
            x_range: None,
            y_range: None,
            max_decades: None,
            secondary: None,
            legend: Legend::UpperRight,
        }
    }

    /// Writes `<stem>.svg` and `<stem>.png` into `dir` (created if missing) and returns their paths.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a bad stem or range; [`Error::Numerical`] with `what = "plot …"`:
    /// "nothing to plot" when no drawable point remains, or the drawing back end's message;
    /// [`Error::Io`] when the directory cannot be created.
    pub fn render(&self, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
        let p = self.prepare(stem)?;
        render_both(dir, stem, &p)
    }

    fn prepare(&self, stem: &str) -> Result<Prepared> {
        let (lx, ly) = (self.log_x, self.log_y);
        let mut series: Vec<Series> = Vec::new();
        for (k, s) in self.series.iter().enumerate() {
            let (points, dropped) = filter_points(&s.points, lx, ly);
            let mut s2 = s.clone();
            s2.color = Some(s.color.unwrap_or(k));
            if dropped > 0 {
                s2.name = format!("{} ({dropped} points ≤ 0 not shown)", s.name);
            }
            s2.points = points;
            series.push(s2);
        }
        let mut bands = Vec::new();
        for b in &self.bands {
            let (lower, _) = filter_points(&b.lower, lx, ly);
            let (upper, _) = filter_points(&b.upper, lx, ly);
            if !lower.is_empty() && !upper.is_empty() {
                bands.push(Band {
                    lower,
                    upper,
                    ..b.clone()
                });
            }
        }
        let secondary = self.secondary.as_ref().map(|sa| {
            let series = sa
                .series
                .iter()
                .enumerate()
                .map(|(k, s)| {
                    let (points, _) = filter_points(&s.points, lx, false);
                    Series {
                        points,
                        color: Some(s.color.unwrap_or(self.series.len() + k)),
                        ..s.clone()
                    }
                })
                .collect::<Vec<_>>();
            SecondaryAxis {
                series,
                hlines: sa.hlines.iter().filter(|m| m.at.is_finite()).cloned().collect(),
                y_label: sa.y_label.clone(),
            }
        });
        let n_points: usize =
            series.iter().map(|s| s.points.len()).sum::<usize>() + bands.iter().map(|b| b.lower.len()).sum::<usize>();
        if n_points == 0 {
            return Err(plot_error(
                stem,
                "nothing to plot (no finite point drawable on these axes)",
            ));
        }
        let vlines: Vec<Marker> = self
            .vlines
            .iter()
            .filter(|m| m.at.is_finite() && (!lx || m.at > 0.0))
            .cloned()
            .collect();
        let hlines: Vec<Marker> = self
            .hlines
            .iter()
            .filter(|m| m.at.is_finite() && (!ly || m.at > 0.0))
            .cloned()
            .collect();

        // x range
        let mut xs: Vec<f64> = series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
        xs.extend(bands.iter().flat_map(|b| b.lower.iter().chain(&b.upper).map(|p| p.0)));
        xs.extend(vlines.iter().map(|m| m.at));
        let x = match self.x_range {
            Some(r) => check_range("x_range", r, lx)?,
            None => padded(&xs, lx).map_err(|r| plot_error(stem, &r))?,
        };
        // y range
        let mut ys: Vec<f64> = series
            .iter()
            .flat_map(|s| s.points.iter().filter(|p| p.0 >= x.0 && p.0 <= x.1).map(|p| p.1))
            .collect();
        ys.extend(bands.iter().flat_map(|b| b.lower.iter().chain(&b.upper).map(|p| p.1)));
        ys.extend(hlines.iter().map(|m| m.at));
        let y = match self.y_range {
            Some(r) => check_range("y_range", r, ly)?,
            None => {
                if let (true, Some(dec)) = (ly, self.max_decades) {
                    let top = ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                    let floor = top * 10f64.powf(-dec.abs());
                    ys.retain(|v| *v >= floor);
                }
                padded(&ys, ly).map_err(|r| plot_error(stem, &r))?
            }
        };
        let clip = |pts: &mut Vec<(f64, f64)>| pts.retain(|p| p.1 >= y.0 && p.1 <= y.1 && p.0 >= x.0 && p.0 <= x.1);
        for s in &mut series {
            clip(&mut s.points);
        }
        let secondary = secondary.map(|mut sa| {
            for s in &mut sa.series {
                s.points.retain(|p| p.0 >= x.0 && p.0 <= x.1);
            }
            sa
        });
        let y2 = secondary.as_ref().map(|sa| {
            let mut v: Vec<f64> = sa.series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).collect();
            v.extend(sa.hlines.iter().map(|m| m.at));
            v.push(0.0);
            padded(&v, false).map_err(|r| plot_error(stem, &r))
        });
        let y2 = y2.transpose()?;
        Ok(Prepared {
            title: self.title.clone(),
            x_label: self.x_label.clone(),
            y_label: self.y_label.clone(),
            log_x: lx,
            log_y: ly,
            x,
            y,
            series,
            bands,
            rects: Vec::new(),
            vlines,
            hlines,
            secondary,
            y2,
            legend: self.legend,
        })
    }
}

/// A histogram of samples, normalised to a probability density (or raw counts), with overlaid curves (e.g.
/// the Gaussian density) and vertical markers (e.g. M ± 3σ).
///
/// # Examples
/// ```
/// use stochvib::plot::{Histogram, Marker};
/// let dir = std::env::temp_dir().join("stochvib-doc-histogram");
/// let data: Vec<f64> = (0..200).map(|i| ((i * 37) % 101) as f64 / 100.0).collect();
/// let mut h = Histogram::new("Uniform-ish", "value x [m]", "probability density [1/m]", data);
/// h.vlines.push(Marker::new(0.5, "centre"));
/// assert_eq!(h.render(&dir, "uniform").unwrap().len(), 2);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Title.
    pub title: String,
    /// x axis label with quantity and unit.
    pub x_label: String,
    /// y axis label (density: 1/unit of x; counts: "count").
    pub y_label: String,
    /// The samples (non-finite ones are ignored).
    pub data: Vec<f64>,
    /// Number of bins; `None`: ⌈2 n^{1/3}⌉ (Rice rule), at least 5.
    pub bins: Option<usize>,
    /// Normalise bar heights to a probability density (count / (n · bin width)); otherwise counts.
    pub density: bool,
    /// Curves drawn over the bars.
    pub curves: Vec<Series>,
    /// Vertical lines.
    pub vlines: Vec<Marker>,
    /// Legend position.
    pub legend: Legend,
}

impl Histogram {
    /// A density-normalised histogram of `data` with no curves or markers.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
        data: Vec<f64>,
    ) -> Self {
        Histogram {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            data,
            bins: None,
            density: true,
            curves: Vec::new(),
            vlines: Vec::new(),
            legend: Legend::UpperRight,
        }
    }

    /// Bin edges and heights: `(x0, x1, height)` per bin.
    ///
    /// # Errors
    /// [`Error::Numerical`] "nothing to plot" when no sample is finite; [`Error::InvalidParameter`] for
    /// `bins = Some(0)`.
    pub fn bars(&self) -> Result<Vec<(f64, f64, f64)>> {
        let data: Vec<f64> = self.data.iter().cloned().filter(|v| v.is_finite()).collect();
        if data.is_empty() {
            return Err(plot_error("histogram", "nothing to plot (no finite sample)"));
        }
        let n = data.len();
        let bins = match self.bins {
            Some(0) => return Err(Error::invalid("bins", 0, "need at least one bin")),
            Some(b) => b,
            None => ((2.0 * (n as f64).cbrt()).ceil() as usize).max(5),
        };
        let lo = data.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = data.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        if lo.abs().max(hi.abs()) > MAX_DRAWABLE {
            return Err(plot_error(
                "histogram",
                format!(
                    "samples reach {:e}, outside the range a picture can draw",
                    lo.abs().max(hi.abs())
                ),
            ));
        }
        let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 0.5, hi + 0.5) };
        let w = (hi - lo) / bins as f64;
        let mut counts = vec![0usize; bins];
        for v in &data {
            let k = (((v - lo) / w).floor() as usize).min(bins - 1);
            counts[k] += 1;
        }
        let scale = if self.density { 1.0 / (n as f64 * w) } else { 1.0 };
        Ok(counts
            .iter()
            .enumerate()
            .map(|(k, &c)| (lo + k as f64 * w, lo + (k + 1) as f64 * w, c as f64 * scale))
            .collect())
    }

    /// Writes `<stem>.svg` and `<stem>.png` into `dir` and returns their paths.
    ///
    /// # Errors
    /// As [`LineChart::render`] and [`Histogram::bars`].
    pub fn render(&self, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
        let rects = self.bars()?;
        let mut lc = LineChart::new(&self.title, &self.x_label, &self.y_label);
        lc.series = self
            .curves
            .iter()
            .enumerate()
            .map(|(k, s)| Series {
                color: Some(s.color.unwrap_or(k + 1)),
                ..s.clone()
            })
            .collect();
        lc.vlines = self.vlines.clone();
        lc.legend = self.legend;
        // the bars take part in the range: their corners as an invisible band
        lc.bands.push(Band {
            name: String::new(),
            lower: rects.iter().map(|r| (r.0, 0.0)).collect(),
            upper: rects.iter().map(|r| (r.1, r.2)).collect(),
            color: None,
        });
        let mut p = lc.prepare(stem)?;
        p.bands.clear();
        p.rects = rects;
        render_both(dir, stem, &p)
    }
}

/// Bars for categories, each optionally with a limit: a bar at or below its limit is green, above it red,
/// without a limit blue; limits are black horizontal strokes across the bar.
///
/// # Examples
/// ```
/// use stochvib::plot::BarChart;
/// let dir = std::env::temp_dir().join("stochvib-doc-bars");
/// let c = BarChart::new("Seat", "octave band centre [Hz]", "RMS acceleration [m/s²]",
///     vec!["1".into(), "2".into()], vec![0.5, 0.9], vec![Some(1.1), Some(0.79)]).unwrap();
/// assert_eq!(c.render(&dir, "bars").unwrap().len(), 2);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BarChart {
    /// Title.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label with quantity and unit.
    pub y_label: String,
    /// Category names.
    pub categories: Vec<String>,
    /// One value per category.
    pub values: Vec<f64>,
    /// One optional limit per category.
    pub limits: Vec<Option<f64>>,
}

impl BarChart {
    /// Validated bar chart.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when the lengths differ or a value or limit is not finite;
    /// [`Error::Numerical`] "nothing to plot" for no categories.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
        categories: Vec<String>,
        values: Vec<f64>,
        limits: Vec<Option<f64>>,
    ) -> Result<Self> {
        if categories.is_empty() {
            return Err(plot_error("bar chart", "nothing to plot (no categories)"));
        }
        if values.len() != categories.len() || limits.len() != categories.len() {
            return Err(Error::invalid(
                "values/limits",
                format!("{} values, {} limits", values.len(), limits.len()),
                format!("need one per category ({})", categories.len()),
            ));
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return Err(Error::invalid("values", v, "bar values must be finite"));
        }
        if let Some(l) = limits.iter().flatten().find(|v| !v.is_finite()) {
            return Err(Error::invalid("limits", l, "limits must be finite"));
        }
        Ok(BarChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            categories,
            values,
            limits,
        })
    }

    /// Writes `<stem>.svg` and `<stem>.png` into `dir` and returns their paths.
    ///
    /// # Errors
    /// As [`LineChart::render`].
    pub fn render(&self, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
        if self.categories.is_empty() || self.values.len() != self.categories.len() {
            return Err(plot_error(
                stem,
                "nothing to plot (no categories, or values do not match them)",
            ));
        }
        let mut all: Vec<f64> = self.values.clone();
        all.extend(self.limits.iter().flatten());
        all.push(0.0);
        let lo = all.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = all.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 1.0, hi + 1.0) };
        let y = (lo - 0.08 * (hi - lo) * (lo < 0.0) as u8 as f64, hi + 0.08 * (hi - lo));
        render_both(dir, stem, &BarsWithRange(self, y))
    }
}

/// Everything needed to draw a line chart or histogram, after filtering and range finding.
struct Prepared {
    title: String,
    x_label: String,
    y_label: String,
    log_x: bool,
    log_y: bool,
    x: (f64, f64),
    y: (f64, f64),
    series: Vec<Series>,
    bands: Vec<Band>,
    rects: Vec<(f64, f64, f64)>,
    vlines: Vec<Marker>,
    hlines: Vec<Marker>,
    secondary: Option<SecondaryAxis>,
    y2: Option<(f64, f64)>,
    legend: Legend,
}

fn filter_points(points: &[(f64, f64)], log_x: bool, log_y: bool) -> (Vec<(f64, f64)>, usize) {
    let finite: Vec<(f64, f64)> = points
        .iter()
        .cloned()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let kept: Vec<(f64, f64)> = finite
        .iter()
        .cloned()
        .filter(|p| (!log_x || p.0 > 0.0) && (!log_y || p.1 > 0.0))
        .collect();
    let dropped = finite.len() - kept.len();
    (kept, dropped)
}

fn check_range(name: &str, r: (f64, f64), log: bool) -> Result<(f64, f64)> {
    if !(r.0.is_finite() && r.1.is_finite() && r.0 < r.1) || (log && r.0 <= 0.0) {
        return Err(Error::invalid(
            name,
            format!("[{}, {}]", r.0, r.1),
            if log {
                "need 0 < low < high on a logarithmic axis"
            } else {
                "need finite low < high"
            },
        ));
    }
    Ok(r)
}

/// Largest magnitude a picture draws: beyond it the axis arithmetic (range, padding, ticks) overflows.
pub const MAX_DRAWABLE: f64 = 1e300;

/// The data range padded by 4 % (of the decades on a log axis); a single value gets a unit-width (linear)
/// or factor-10 (log) range. Refuses values beyond ±[`MAX_DRAWABLE`] (or below 1/MAX_DRAWABLE on a log
/// axis), whose range cannot be computed, with the reason.
fn padded(values: &[f64], log: bool) -> std::result::Result<(f64, f64), String> {
    if let Some(v) = values
        .iter()
        .find(|x| x.is_finite() && (x.abs() > MAX_DRAWABLE || (log && **x > 0.0 && **x < 1.0 / MAX_DRAWABLE)))
    {
        return Err(format!(
            "value {v:e} is outside the range a picture can draw (|x| ≤ {MAX_DRAWABLE:e}): the data are damaged or \
             diverge"
        ));
    }
    Ok(padded_range(values, log))
}

fn padded_range(values: &[f64], log: bool) -> (f64, f64) {
    let v: Vec<f64> = values
        .iter()
        .cloned()
        .filter(|x| x.is_finite() && (!log || *x > 0.0))
        .collect();
    if v.is_empty() {
        return if log { (0.1, 10.0) } else { (0.0, 1.0) };
    }
    let lo = v.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    if log {
        if hi / lo < 1.0 + 1e-9 {
            return (lo / 3.0, hi * 3.0);
        }
        let f = (hi / lo).powf(0.04);
        (lo / f, hi * f)
    } else {
        if hi - lo <= 1e-12 * hi.abs().max(lo.abs()) {
            let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            return (lo - d, hi + d);
        }
        let d = 0.04 * (hi - lo);
        (lo - d, hi + d)
    }
}

/// Tick label on an axis spanning `range`: a value within 1e-9 of the axis' magnitude of zero is rounding
/// noise of the tick placement (e.g. `-2.7e-20` on a 1e-3 axis) and is labelled `0`.
fn tick_in(v: f64, range: (f64, f64)) -> String {
    if v.abs() <= 1e-9 * range.0.abs().max(range.1.abs()) {
        return "0".into();
    }
    tick(v)
}

/// Tick label: up to 4 significant digits, plain in [1e-3, 1e5), otherwise `1.5e-6`.
fn tick(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let s = format!("{v:.2e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        };
        format!("{m}e{e}")
    }
}

/// Something that draws itself on any plotters back end.
trait Draw {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> std::result::Result<(), String>;
}

struct BarsWithRange<'a>(&'a BarChart, (f64, f64));

/// Renders with both back ends; a panic inside plotters is turned into an error.
fn render_both<T: Draw>(dir: &Path, stem: &str, item: &T) -> Result<Vec<PathBuf>> {
    if stem.is_empty() || stem.contains(['/', '\\']) || stem == "." || stem == ".." {
        return Err(Error::invalid(
            "stem",
            stem,
            "need a plain file name without directories",
        ));
    }
    ensure_font()?;
    picture_dir(dir)?;
    let svg = dir.join(format!("{stem}.svg"));
    let png = dir.join(format!("{stem}.png"));
    let run = |f: &dyn Fn(&Path) -> std::result::Result<(), String>, path: &Path| -> Result<()> {
        let staged = crate::io_rules::Staged::begin(path, PICTURE, &[], true)?;
        let tmp = staged.temporary();
        match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(tmp))) {
            Ok(Ok(())) => staged.commit().map(|_| ()),
            Ok(Err(reason)) => Err(plot_error(&path.display().to_string(), reason)),
            Err(_) => Err(plot_error(&path.display().to_string(), "the drawing back end panicked")),
        }
    };
    run(
        &|tmp| {
            let root = SVGBackend::new(tmp, (WIDTH, HEIGHT)).into_drawing_area();
            item.draw(&root)?;
            root.present().map_err(|e| e.to_string())
        },
        &svg,
    )?;
    run(
        &|tmp| {
            let root = BitMapBackend::new(tmp, (WIDTH, HEIGHT)).into_drawing_area();
            item.draw(&root)?;
            root.present().map_err(|e| e.to_string())
        },
        &png,
    )?;
    Ok(vec![svg, png])
}

/// The kind of the pictures every command writes (`<stem>.svg`, `<stem>.png`), for the output rule
/// ([`crate::io_rules::check_output`]): an existing picture of the same name is replaced (a picture
/// directory is drawn again and again); anything else under that name — another kind of file, a directory,
/// a link, a FIFO, a device — is refused.
pub const PICTURE: crate::io_rules::OutputKind = crate::io_rules::OutputKind {
    what: "picture (SVG or PNG)",
    recognizes: is_picture,
    replaceable: true,
};

/// Whether the existing file `path` is a picture of the format of its extension.
fn is_picture(path: &Path) -> bool {
    match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => crate::io_rules::starts_with(path, b"<svg") || crate::io_rules::starts_with(path, b"<?xml"),
        Some("png") => crate::io_rules::starts_with(path, b"\x89PNG\r\n\x1a\n"),
        _ => false,
    }
}

/// Creates the picture directory `dir` if missing; refuses a `dir` that exists and is not a directory.
///
/// # Errors
/// [`Error::Parse`] naming `dir` for a file, FIFO or device; [`Error::Io`] if it cannot be created.
pub fn picture_dir(dir: &Path) -> Result<()> {
    if let Ok(m) = std::fs::metadata(dir)
        && !m.is_dir()
    {
        return Err(Error::Parse {
            file: dir.to_path_buf(),
            reason: "exists and is not a directory: the pictures go into a directory (-o DIR, --plots DIR); \
                     nothing was written"
                .into(),
        });
    }
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })
}

fn legend_position(l: Legend) -> Option<SeriesLabelPosition> {
    match l {
        Legend::UpperRight => Some(SeriesLabelPosition::UpperRight),
        Legend::UpperLeft => Some(SeriesLabelPosition::UpperLeft),
        Legend::LowerLeft => Some(SeriesLabelPosition::LowerLeft),
        Legend::LowerRight => Some(SeriesLabelPosition::LowerRight),
        Legend::Hidden => None,
    }
}

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

const TITLE_FONT: (&str, u32) = ("sans-serif", 18);
const DESC_FONT: (&str, u32) = ("sans-serif", 15);
const LABEL_FONT: (&str, u32) = ("sans-serif", 12);

/// Draws one series on a chart context through `$method` (`draw_series` or `draw_secondary_series`).
macro_rules! draw_series {
    ($chart:expr_2021, $method:ident, $s:expr_2021) => {{
        let s: &Series = $s;
        let c = colour(s.color.unwrap_or(0));
        let anno = match s.style {
            LineStyle::Solid => $chart
                .$method(LineSeries::new(s.points.iter().cloned(), c.stroke_width(2)))
                .map_err(err)?,
            LineStyle::Dashed => $chart
                .$method(DashedLineSeries::new(s.points.iter().cloned(), 8, 5, c.stroke_width(2)))
                .map_err(err)?,
            LineStyle::Markers => $chart
                .$method(s.points.iter().map(|p| Circle::new(*p, 3, c.filled())))
                .map_err(err)?,
        };
        if !s.name.is_empty() {
            let style = s.style;
            let markers = style == LineStyle::Markers;
            anno.label(s.name.clone()).legend(move |(x, y)| {
                let path = if markers { vec![] } else { vec![(0, 0), (20, 0)] };
                let dot = if markers { c.filled() } else { c.mix(0.0).filled() };
                EmptyElement::at((x, y)) + Circle::new((10, 0), 3, dot) + PathElement::new(path, c.stroke_width(2))
            });
        }
    }};
}

impl Draw for Prepared {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let (x, y) = (self.x.0..self.x.1, self.y.0..self.y.1);
        match (self.log_x, self.log_y) {
            (false, false) => draw_lines(root, self, x, y),
            (true, false) => draw_lines(root, self, x.log_scale(), y),
            (false, true) => draw_lines(root, self, x, y.log_scale()),
            (true, true) => draw_lines(root, self, x.log_scale(), y.log_scale()),
        }
    }
}

fn draw_lines<DB, X, Y>(root: &DrawingArea<DB, Shift>, p: &Prepared, xr: X, yr: Y) -> std::result::Result<(), String>
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64> + Clone,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(root)
        .caption(&p.title, TITLE_FONT)
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(80)
        .right_y_label_area_size(if p.secondary.is_some() { 80 } else { 0 })
        .build_cartesian_2d(xr.clone(), yr)
        .map_err(err)?;
    match (&p.secondary, p.y2) {
        (Some(sa), Some(y2)) => {
            // the secondary coordinates must be set before the primary mesh is drawn, or the primary labels
            // are drawn on the right-hand axis too
            let mut dc = chart.set_secondary_coord(xr, y2.0..y2.1);
            draw_primary(&mut dc, p)?;
            dc.configure_secondary_axes()
                .y_desc(sa.y_label.as_str())
                .y_label_formatter(&|v| tick_in(*v, y2))
                .axis_desc_style(DESC_FONT)
                .label_style(LABEL_FONT)
                .draw()
                .map_err(err)?;
            for s in &sa.series {
                draw_series!(dc, draw_secondary_series, s);
            }
            for m in &sa.hlines {
                let c = RGBColor(90, 90, 90);
                let anno = dc
                    .draw_secondary_series(DashedLineSeries::new(
                        vec![(p.x.0, m.at), (p.x.1, m.at)],
                        3,
                        3,
                        c.stroke_width(1),
                    ))
                    .map_err(err)?;
                if !m.label.is_empty() {
                    anno.label(m.label.clone())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(1)));
                }
            }
            if let Some(pos) = legend_position(p.legend) {
                dc.configure_series_labels()
                    .position(pos)
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .label_font(LABEL_FONT)
                    .draw()
                    .map_err(err)?;
            }
        }
        _ => {
            draw_primary(&mut chart, p)?;
            if let Some(pos) = legend_position(p.legend) {
                chart
                    .configure_series_labels()
                    .position(pos)
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .label_font(LABEL_FONT)
                    .draw()
                    .map_err(err)?;
            }
        }
    }
    Ok(())
}

/// Mesh, bars, bands, series and marker lines against the primary axes.
fn draw_primary<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    p: &Prepared,
) -> std::result::Result<(), String>
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_desc(p.x_label.as_str())
        .y_desc(p.y_label.as_str())
        .x_label_formatter(&|v| tick_in(*v, p.x))
        .y_label_formatter(&|v| tick_in(*v, p.y))
        .axis_desc_style(DESC_FONT)
        .label_style(LABEL_FONT)
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(200, 200, 200))
        .draw()
        .map_err(err)?;
    for r in &p.rects {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(r.0, p.y.0.max(0.0)), (r.1, r.2)],
                colour(0).mix(0.45).filled(),
            )))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(r.0, p.y.0.max(0.0)), (r.1, r.2)],
                colour(0).stroke_width(1),
            )))
            .map_err(err)?;
    }
    for b in &p.bands {
        let c = colour(b.color.unwrap_or(0));
        let mut poly = b.lower.clone();
        poly.extend(b.upper.iter().rev().cloned());
        let anno = chart
            .draw_series(std::iter::once(Polygon::new(poly, c.mix(0.22).filled())))
            .map_err(err)?;
        if !b.name.is_empty() {
            anno.label(b.name.clone())
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], c.mix(0.22).filled()));
        }
    }
    for s in &p.series {
        draw_series!(chart, draw_series, s);
    }
    for (k, m) in p.vlines.iter().enumerate() {
        let c = if k == 0 { BLACK } else { RGBColor(90, 90, 90) };
        let anno = chart
            .draw_series(DashedLineSeries::new(
                vec![(m.at, p.y.0), (m.at, p.y.1)],
                6,
                4,
                c.stroke_width(1),
            ))
            .map_err(err)?;
        if !m.label.is_empty() {
            anno.label(m.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(1)));
        }
    }
    for m in &p.hlines {
        let anno = chart
            .draw_series(DashedLineSeries::new(
                vec![(p.x.0, m.at), (p.x.1, m.at)],
                6,
                4,
                BLACK.stroke_width(1),
            ))
            .map_err(err)?;
        if !m.label.is_empty() {
            anno.label(m.label.clone())
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(1)));
        }
    }
    Ok(())
}

impl Draw for BarsWithRange<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> std::result::Result<(), String> {
        let (b, y) = (self.0, self.1);
        root.fill(&WHITE).map_err(err)?;
        let n = b.categories.len();
        // plotters' segmented 0..k has k + 1 segments (the end is inclusive); one category keeps 0..1
        let last = if n >= 2 { n - 1 } else { n };
        let mut chart = ChartBuilder::on(root)
            .caption(&b.title, TITLE_FONT)
            .margin(12)
            .x_label_area_size(48)
            .y_label_area_size(80)
            .build_cartesian_2d((0..last).into_segmented(), y.0..y.1)
            .map_err(err)?;
        let cats = &b.categories;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(n + 1)
            .x_desc(b.x_label.as_str())
            .y_desc(b.y_label.as_str())
            .x_label_formatter(&|v| match v {
                SegmentValue::CenterOf(i) => cats.get(*i).cloned().unwrap_or_default(),
                _ => String::new(),
            })
            .y_label_formatter(&|v| tick_in(*v, y))
            .axis_desc_style(DESC_FONT)
            .label_style(LABEL_FONT)
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        let pass = RGBColor(44, 160, 44);
        let fail = RGBColor(214, 39, 40);
        let none = colour(0);
        type Member = Box<dyn Fn(f64, Option<f64>) -> bool>;
        let groups: [(&str, RGBColor, Member); 3] = [
            ("within limit", pass, Box::new(|v, l| l.is_some_and(|l| v <= l))),
            ("over limit", fail, Box::new(|v, l| l.is_some_and(|l| v > l))),
            ("no limit", none, Box::new(|_, l| l.is_none())),
        ];
        for (name, c, member) in groups.iter() {
            let bars: Vec<_> = (0..n)
                .filter(|&i| member(b.values[i], b.limits[i]))
                .map(|i| {
                    let mut r = Rectangle::new(
                        [(SegmentValue::Exact(i), 0.0), (SegmentValue::Exact(i + 1), b.values[i])],
                        c.mix(0.8).filled(),
                    );
                    r.set_margin(0, 0, 8, 8);
                    r
                })
                .collect();
            if bars.is_empty() {
                continue;
            }
            let c = *c;
            chart
                .draw_series(bars)
                .map_err(err)?
                .label(*name)
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], c.mix(0.8).filled()));
        }
        let limits: Vec<_> = (0..n)
            .filter_map(|i| {
                b.limits[i].map(|l| {
                    PathElement::new(
                        vec![(SegmentValue::Exact(i), l), (SegmentValue::Exact(i + 1), l)],
                        BLACK.stroke_width(3),
                    )
                })
            })
            .collect();
        if !limits.is_empty() {
            chart
                .draw_series(limits)
                .map_err(err)?
                .label("limit")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(3)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(LABEL_FONT)
            .draw()
            .map_err(err)?;
        Ok(())
    }
}

/// A file-name-safe version of a signal name: ASCII letters, digits, `-` and `_` kept, anything else `_`.
pub(crate) fn file_stem(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}
