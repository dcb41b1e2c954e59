//! A small chart layer over `plotters`: line charts (linear or logarithmic axes, bands, markers, an optional
//! linear secondary y axis), bar charts with limit markers and histograms with overlaid curves.
//!
//! Every chart renders to `<stem>.svg` and `<stem>.png` (800 × 500 pixels) in a directory. Text is drawn
//! with the bundled DejaVu Sans font (`assets/DejaVuSans.ttf`, registered once with
//! [`plotters::style::register_font`]), so no system font library (fontconfig, freetype) is needed.

use super::draw::{BarsWithRange, Draw};
use crate::error::{Error, Result};
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

/// What a series is, which decides its drawing order and look.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Role {
    /// A computed or measured curve (an estimate, a simulation, a fit): drawn over the analytic curves, in
    /// its palette colour with its marker shape every few points.
    #[default]
    Data,
    /// An analytic (exact, model) curve: drawn first, behind the data, wider, without markers.
    Analytic,
    /// A limit or threshold (a class limit, a boundary): thin, labelled on the line at its right end
    /// instead of in the legend.
    Limit,
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
    /// Data, analytic curve or limit.
    pub role: Role,
}

impl Series {
    /// A solid line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: LineStyle::Solid,
            color: None,
            role: Role::Data,
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
    /// Marks the series as an analytic curve (drawn behind the data).
    pub fn analytic(mut self) -> Self {
        self.role = Role::Analytic;
        self
    }
    /// Marks the series as a limit line (labelled on the line, not in the legend).
    pub fn limit(mut self) -> Self {
        self.role = Role::Limit;
        self
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

/// Where the legend box should go: the corner tried first. The legend is placed where it covers no data
/// (the preferred corner, the other corners, the middles of the edges, a grid, in that order), and outside
/// the plotting area, below it, when every such place holds data ([`crate::plot::legend`]).
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

    /// The series with the points the axes can draw, each with its colour, and a legend that counts the
    /// points left out (≤ 0 on a log axis).
    fn drawable_series(&self) -> Vec<Series> {
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
        series
    }

    /// The bands with the points the axes can draw; a band with an empty side is left out.
    fn drawable_bands(&self) -> Vec<Band> {
        let (lx, ly) = (self.log_x, self.log_y);
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
        bands
    }

    /// The secondary axis with the points it can draw (linear y), colours after the primary series', and
    /// its finite markers.
    fn drawable_secondary(&self) -> Option<SecondaryAxis> {
        self.secondary.as_ref().map(|sa| {
            let series = sa
                .series
                .iter()
                .enumerate()
                .map(|(k, s)| {
                    let (points, _) = filter_points(&s.points, self.log_x, false);
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
        })
    }

    /// The x range: `x_range`, else the padded extent of every drawn point and vertical marker.
    fn x_extent(&self, stem: &str, series: &[Series], bands: &[Band], vlines: &[Marker]) -> Result<(f64, f64)> {
        let mut xs: Vec<f64> = series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
        xs.extend(bands.iter().flat_map(|b| b.lower.iter().chain(&b.upper).map(|p| p.0)));
        xs.extend(vlines.iter().map(|m| m.at));
        Ok(match self.x_range {
            Some(r) => check_range("x_range", r, self.log_x)?,
            None => padded(&xs, self.log_x).map_err(|r| plot_error(stem, &r))?,
        })
    }

    /// The y range: `y_range`, else the padded extent of the points within x, the bands and the horizontal
    /// markers (on a log axis at most `max_decades` below the top).
    fn y_extent(
        &self,
        stem: &str,
        x: (f64, f64),
        series: &[Series],
        bands: &[Band],
        hlines: &[Marker],
    ) -> Result<(f64, f64)> {
        let ly = self.log_y;
        let mut ys: Vec<f64> = series
            .iter()
            .flat_map(|s| s.points.iter().filter(|p| p.0 >= x.0 && p.0 <= x.1).map(|p| p.1))
            .collect();
        ys.extend(bands.iter().flat_map(|b| b.lower.iter().chain(&b.upper).map(|p| p.1)));
        ys.extend(hlines.iter().map(|m| m.at));
        Ok(match self.y_range {
            Some(r) => check_range("y_range", r, ly)?,
            None => {
                if let (true, Some(dec)) = (ly, self.max_decades) {
                    let top = ys.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                    let floor = top * 10f64.powf(-dec.abs());
                    ys.retain(|v| *v >= floor);
                }
                padded(&ys, ly).map_err(|r| plot_error(stem, &r))?
            }
        })
    }

    fn prepare(&self, stem: &str) -> Result<Prepared> {
        let (lx, ly) = (self.log_x, self.log_y);
        let mut series = self.drawable_series();
        let bands = self.drawable_bands();
        let secondary = self.drawable_secondary();
        let n_points: usize =
            series.iter().map(|s| s.points.len()).sum::<usize>() + bands.iter().map(|b| b.lower.len()).sum::<usize>();
        if n_points == 0 {
            return Err(plot_error(
                stem,
                "nothing to plot (no finite point drawable on these axes)",
            ));
        }
        let vlines = drawable_markers(&self.vlines, lx);
        let hlines = drawable_markers(&self.hlines, ly);

        let x = self.x_extent(stem, &series, &bands, &vlines)?;
        let y = self.y_extent(stem, x, &series, &bands, &hlines)?;
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
pub(super) struct Prepared {
    pub(super) title: String,
    pub(super) x_label: String,
    pub(super) y_label: String,
    pub(super) log_x: bool,
    pub(super) log_y: bool,
    pub(super) x: (f64, f64),
    pub(super) y: (f64, f64),
    pub(super) series: Vec<Series>,
    pub(super) bands: Vec<Band>,
    pub(super) rects: Vec<(f64, f64, f64)>,
    pub(super) vlines: Vec<Marker>,
    pub(super) hlines: Vec<Marker>,
    pub(super) secondary: Option<SecondaryAxis>,
    pub(super) y2: Option<(f64, f64)>,
    pub(super) legend: Legend,
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
    check_picture_dir(dir)?;
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.to_path_buf(),
        source,
    })
}

/// Refuses a picture directory `dir` that exists and is not a directory, creating nothing: a command that
/// writes other files before its pictures (`simulate --plots`, `transient --plots`) asks this before its work.
///
/// # Errors
/// [`Error::Parse`] naming `dir` for a file, FIFO or device.
pub fn check_picture_dir(dir: &Path) -> Result<()> {
    match std::fs::metadata(dir) {
        Ok(m) if !m.is_dir() => Err(Error::Parse {
            file: dir.to_path_buf(),
            reason: "exists and is not a directory: the pictures go into a directory (-o DIR, --plots DIR); \
                     nothing was written"
                .into(),
        }),
        _ => Ok(()),
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

/// The markers a (log) axis can draw: finite, and positive on a log axis.
fn drawable_markers(markers: &[Marker], log: bool) -> Vec<Marker> {
    markers
        .iter()
        .filter(|m| m.at.is_finite() && (!log || m.at > 0.0))
        .cloned()
        .collect()
}
