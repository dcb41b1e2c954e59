//! Drawing a prepared chart on a plotters back end, the same look for every kind (see [`super::style`]):
//! the title above, tick labels in engineering notation at the decades of a logarithmic axis, interval
//! bands translucent and under everything, analytic curves next and behind the data, each data series in
//! its palette colour with its marker shape every few points, limit and threshold lines labelled on the
//! line, and the legend where the data are not ([`super::legend`]).

use super::chart::{BarChart, Legend, LineStyle, Marker, Prepared, Role, Series};
use super::legend::{self, Entry, Occupied, PixelBox, Sample, BAND_OPACITY, MARKER_R};
use super::style::{colour, log_tick_in, log_ticks, shape, tick_in, DESC_FONT, LABEL_FONT, TITLE_FONT};
use plotters::coord::ranged1d::{AsRangedCoord, SegmentValue, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

type Res = std::result::Result<(), String>;

/// Something that draws itself on any plotters back end.
pub(super) trait Draw {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Res;
}

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// Pixels of the x and y label areas.
const X_AREA: u32 = 48;
const Y_AREA: u32 = 80;

/// The area below the title, inside the outer margin.
/// The title is drawn smaller (down to [`SMALLEST_TITLE`] pixels) when it is wider than the picture.
fn titled<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
) -> std::result::Result<DrawingArea<DB, Shift>, String> {
    root.fill(&WHITE).map_err(err)?;
    let area = root.margin(12, 12, 12, 12);
    let width = area.dim_in_pixel().0;
    let wide = |size: u32| {
        area.estimate_text_size(title, &TextStyle::from((TITLE_FONT.0, size).into_font()))
            .is_ok_and(|(w, _)| w > width)
    };
    let size = (SMALLEST_TITLE..=TITLE_FONT.1)
        .rev()
        .find(|&s| !wide(s))
        .unwrap_or(SMALLEST_TITLE);
    area.titled(title, (TITLE_FONT.0, size)).map_err(err)
}

/// Smallest font of a long title, pixels (the size of the tick labels).
const SMALLEST_TITLE: u32 = 12;

/// A logarithmic axis over `r` with a tick at every decade (see [`log_ticks`]).
fn log_axis(r: (f64, f64), pixels: u32) -> impl AsRangedCoord<Value = f64, CoordDescType: ValueFormatter<f64>> {
    let (labelled, minor) = log_ticks(r, pixels as f64);
    (r.0..r.1)
        .log_scale()
        .with_key_points(labelled)
        .with_light_points(minor)
}

impl Draw for Prepared {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Res {
        let area = titled(root, &self.title)?;
        let (w, h) = area.dim_in_pixel();
        let (wx, hy) = (w.saturating_sub(2 * Y_AREA), h.saturating_sub(X_AREA));
        let (x, y) = (self.x.0..self.x.1, self.y.0..self.y.1);
        match (self.log_x, self.log_y) {
            (false, false) => draw_lines(root, &area, self, || (x.clone(), y.clone())),
            (true, false) => draw_lines(root, &area, self, || (log_axis(self.x, wx), y.clone())),
            (false, true) => draw_lines(root, &area, self, || (x.clone(), log_axis(self.y, hy))),
            (true, true) => draw_lines(root, &area, self, || (log_axis(self.x, wx), log_axis(self.y, hy))),
        }
    }
}

/// The legend rows of a line chart: bands, then the series (limits are labelled on the line instead).
fn line_entries(p: &Prepared) -> Vec<Entry> {
    if p.legend == Legend::Hidden {
        return Vec::new();
    }
    let bands = p.bands.iter().filter(|b| !b.name.is_empty()).map(|b| Entry {
        label: b.name.clone(),
        sample: Sample::Fill {
            rgb: colour(b.color.unwrap_or(0)),
            opacity: BAND_OPACITY,
        },
    });
    let secondary = p.secondary.iter().flat_map(|sa| sa.series.iter());
    let series = ordered(&p.series)
        .chain(secondary)
        .filter(|s| !s.name.is_empty() && s.role != Role::Limit)
        .map(|s| Entry {
            label: s.name.clone(),
            sample: Sample::Line {
                colour: s.color.unwrap_or(0),
                dashed: s.style == LineStyle::Dashed,
                width: if s.style == LineStyle::Markers { 0 } else { width(s) },
                shape: (s.role == Role::Data).then_some(s.color.unwrap_or(0)),
            },
        });
    bands.chain(series).collect()
}

/// Series in drawing order: analytic curves first (behind), then the data, then limits.
fn ordered(series: &[Series]) -> impl Iterator<Item = &Series> {
    [Role::Analytic, Role::Data, Role::Limit]
        .into_iter()
        .flat_map(move |r| series.iter().filter(move |s| s.role == r))
}

fn width(s: &Series) -> u32 {
    match s.role {
        Role::Analytic => 3,
        Role::Data => 2,
        Role::Limit => 1,
    }
}

/// Indices of the points of `s` that carry its marker shape: every point of a marker series, about eight
/// points along a data line (shifted by the colour index so that two series' markers do not coincide),
/// none on analytic and limit lines.
fn marked(s: &Series) -> impl Iterator<Item = usize> + '_ {
    let n = s.points.len();
    let step = match (s.style, s.role) {
        (LineStyle::Markers, _) => 1,
        (_, Role::Data) => (n / 8).max(1),
        _ => 0,
    };
    let offset = if step > 1 {
        (s.color.unwrap_or(0) * step / 5 + step / 2) % step
    } else {
        0
    };
    (0..n).filter(move |i| step > 0 && i % step == offset)
}

/// Draws one series on a chart context through `$method` (`draw_series` or `draw_secondary_series`).
macro_rules! draw_series {
    ($chart:expr_2021, $method:ident, $s:expr_2021) => {{
        let s: &Series = $s;
        let k = s.color.unwrap_or(0);
        let c = colour(k);
        let stroke = c.stroke_width(width(s));
        match s.style {
            LineStyle::Solid => {
                $chart
                    .$method(LineSeries::new(s.points.iter().cloned(), stroke))
                    .map_err(err)?;
            }
            LineStyle::Dashed => {
                $chart
                    .$method(DashedLineSeries::new(s.points.iter().cloned(), 8, 5, stroke))
                    .map_err(err)?;
            }
            LineStyle::Markers => {}
        }
        let vertices = shape(k, MARKER_R);
        $chart
            .$method(marked(s).map(|i| EmptyElement::at(s.points[i]) + Polygon::new(vertices.clone(), c.filled())))
            .map_err(err)?;
    }};
}

/// A text drawn beside a line.
struct LineLabel {
    text: String,
    bbox: PixelBox,
    at: (i32, i32),
    pos: Pos,
    rgb: RGBColor,
}

/// Where a chart's data lie in pixels, and where its line labels go.
struct Layout {
    plot: PixelBox,
    occupied: Occupied,
    labels: Vec<LineLabel>,
    /// Labels of limit and threshold lines with no place clear of the data: legend entries instead.
    in_legend: Vec<Entry>,
}

/// Pixel geometry of a line chart, from the data → pixel maps of the primary and secondary axes.
struct Geometry<'a> {
    plot: PixelBox,
    map: &'a dyn Fn((f64, f64)) -> (i32, i32),
    map2: &'a dyn Fn((f64, f64)) -> (i32, i32),
    measure: &'a dyn Fn(&str) -> (i32, i32),
    /// The labels an earlier layout moved into the legend (not drawn on their lines); `None` in the first
    /// layout, which moves the labels that have no clear place.
    legend_has: Option<&'a [Entry]>,
}

impl Geometry<'_> {
    fn layout(&self, p: &Prepared) -> Layout {
        let mut l = Layout {
            plot: self.plot,
            occupied: Occupied::default(),
            labels: Vec::new(),
            in_legend: Vec::new(),
        };
        for r in &p.rects {
            let (a, b) = ((self.map)((r.0, p.y.0.max(0.0))), (self.map)((r.1, r.2)));
            l.occupied.boxes.push(PixelBox {
                x0: a.0.min(b.0),
                y0: a.1.min(b.1),
                x1: a.0.max(b.0),
                y1: a.1.max(b.1),
            });
        }
        for b in &p.bands {
            l.occupied.polyline(b.lower.iter().map(|q| (self.map)(*q)));
            l.occupied.polyline(b.upper.iter().map(|q| (self.map)(*q)));
        }
        for s in p.series.iter().filter(|s| s.role != Role::Limit) {
            self.occupy(&mut l.occupied, s, self.map);
        }
        for s in p.secondary.iter().flat_map(|sa| sa.series.iter()) {
            self.occupy(&mut l.occupied, s, self.map2);
        }
        // what a line label must not cover: the data (not the limit and threshold lines it labels)
        let data = l.occupied.clone();
        for s in p.series.iter().filter(|s| s.role == Role::Limit) {
            self.occupy(&mut l.occupied, s, self.map);
        }
        for s in p.series.iter().filter(|s| s.role == Role::Limit && !s.name.is_empty()) {
            if let Some(last) = s.points.last() {
                let short = s.name.split(": ").next().unwrap_or(&s.name);
                let along = s.points.iter().rev().map(|q| (self.map)(*q));
                let at = self.clear_of_data(&l, &data, short, (self.map)(*last), along);
                let sample = Sample::Line {
                    colour: s.color.unwrap_or(7),
                    dashed: s.style == LineStyle::Dashed,
                    width: 1,
                    shape: None,
                };
                let rgb = colour(s.color.unwrap_or(7));
                let draw = |l: &mut Layout, at| self.label_at_end(l, short, at, rgb);
                self.place_line_label(&mut l, short, (at, (self.map)(*last)), sample, draw);
            }
        }
        for (k, m) in p.vlines.iter().enumerate() {
            let (a, b) = ((self.map)((m.at, p.y.0)), (self.map)((m.at, p.y.1)));
            l.occupied.polyline([a, b]);
            self.label_vline(&mut l, m, a.0, k, &data);
        }
        let y2 = p
            .secondary
            .iter()
            .flat_map(|sa| sa.hlines.iter().map(|m| (m, self.map2)));
        for (m, map) in p.hlines.iter().map(|m| (m, self.map)).chain(y2) {
            let (a, b) = (map((p.x.0, m.at)), map((p.x.1, m.at)));
            l.occupied.polyline([a, b]);
            let along = (0..).map(|k| (self.plot.x1 - 3 - LABEL_STEP * k, a.1));
            let along = along.take_while(|q| q.0 > self.plot.x0);
            let first = (self.plot.x1 - 3, a.1 - 2);
            let at = self.clear_of_data(&l, &data, &m.label, first, along);
            let draw = |l: &mut Layout, at| self.label_at_end(l, &m.label, at, RGBColor(40, 40, 40));
            self.place_line_label(&mut l, &m.label, (at, first), Sample::Stroke { width: 1 }, draw);
        }
        l
    }

    fn occupy(&self, o: &mut Occupied, s: &Series, map: &dyn Fn((f64, f64)) -> (i32, i32)) {
        if s.style != LineStyle::Markers {
            o.polyline(s.points.iter().map(|q| map(*q)));
        }
        for i in marked(s) {
            let c = map(s.points[i]);
            let r = MARKER_R + 1;
            o.boxes.push(PixelBox {
                x0: c.0 - r,
                y0: c.1 - r,
                x1: c.0 + r,
                y1: c.1 + r,
            });
        }
    }

    /// Where the label `text` of a line goes (the `at` of [`Self::label_at_end`]): `first` (the line's
    /// right end) when the label placed from there covers none of the `data`; else the first point of
    /// `along` (points of the line from its right end) where the label above the line, or else below it,
    /// is clear of them; `None` when no place is.
    fn clear_of_data(
        &self,
        l: &Layout,
        data: &Occupied,
        text: &str,
        first: (i32, i32),
        along: impl Iterator<Item = (i32, i32)>,
    ) -> Option<(i32, i32)> {
        if text.is_empty() {
            return Some(first);
        }
        let (w, h) = (self.measure)(text);
        let clear = |at: (i32, i32)| {
            let b = self.end_label_box(l, at, (w, h));
            let inside = b.y0 >= self.plot.y0 && b.y1 <= self.plot.y1 && b.x0 >= self.plot.x0;
            inside && !data.touches(b.grown(LABEL_PAD))
        };
        if clear(first) {
            return Some(first);
        }
        along
            .map(|q| (q.0.min(self.plot.x1 - 3), q.1))
            .flat_map(|q| [(q.0, q.1 - 2), (q.0, q.1 + h + 4)])
            .find(|&at| clear(at))
    }

    /// Draws the label `text` of a limit or threshold line at `at` (by `draw`); without a clear place (`at`
    /// None) the first layout moves it into the legend (with `sample`), a later one draws it at `first`
    /// unless the legend already has it.
    fn place_line_label(
        &self,
        l: &mut Layout,
        text: &str,
        (at, first): (Option<(i32, i32)>, (i32, i32)),
        sample: Sample,
        draw: impl FnOnce(&mut Layout, (i32, i32)),
    ) {
        let in_legend = self.legend_has.map(|lg| lg.iter().any(|e| e.label == text));
        match (at, in_legend) {
            (Some(at), None | Some(false)) => draw(l, at),
            (None, None) => l.in_legend.push(Entry {
                label: text.to_string(),
                sample,
            }),
            (None, Some(false)) => draw(l, first),
            (_, Some(true)) => {}
        }
    }

    /// The box of a label of size `(w, h)` ending at `at` (right, bottom), moved inside the plot and left
    /// of the earlier labels of `l` it would cover.
    fn end_label_box(&self, l: &Layout, at: (i32, i32), (w, h): (i32, i32)) -> PixelBox {
        let mut x1 = at.0.min(self.plot.x1 - 3);
        let y1 = if at.1 - h < self.plot.y0 { at.1 + h + 4 } else { at.1 };
        let mut b = PixelBox {
            x0: x1 - w,
            y0: y1 - h,
            x1,
            y1,
        };
        for _ in 0..8 {
            match l.labels.iter().find(|o| o.bbox.overlaps(&b.grown(LABEL_PAD))) {
                Some(o) => x1 = o.bbox.x0 - 8,
                None => break,
            }
            b = PixelBox { x0: x1 - w, x1, ..b };
        }
        let x1 = x1.max(self.plot.x0 + w + 3);
        PixelBox { x0: x1 - w, x1, ..b }
    }

    /// A label ending at `at` (right, bottom), moved inside the plot and left of earlier labels it would
    /// cover.
    fn label_at_end(&self, l: &mut Layout, text: &str, at: (i32, i32), rgb: RGBColor) {
        if text.is_empty() {
            return;
        }
        let (w, h) = (self.measure)(text);
        let b = self.end_label_box(l, at, (w, h));
        self.push_label(l, text, (b.x1, b.y1), Pos::new(HPos::Right, VPos::Bottom), rgb, (w, h));
    }

    /// A vertical line's label near the top of the plot, right of the line (left of it near the right
    /// edge), staggered down by the line's index so that neighbouring lines' labels do not overlap; when
    /// that place covers `data` or an earlier label, the first row further down (then the other side of the
    /// line) that is clear of both; in the legend when none is.
    fn label_vline(&self, l: &mut Layout, m: &Marker, px: i32, k: usize, data: &Occupied) {
        if m.label.is_empty() {
            return;
        }
        let (w, h) = (self.measure)(&m.label);
        let row = |j: i32| self.plot.y0 + 3 + j * (h + 3) + h;
        let right = if px + 4 + w <= self.plot.x1 { px + 4 + w } else { px - 4 };
        let first = (right, row((k % 4) as i32));
        let other = if right == px - 4 { px + 4 + w } else { px - 4 };
        let clear = |c: (i32, i32)| {
            let b = PixelBox {
                x0: c.0 - w,
                y0: c.1 - h,
                x1: c.0,
                y1: c.1,
            };
            let inside = b.x0 > self.plot.x0 && b.x1 < self.plot.x1 && b.y1 < self.plot.y1;
            let b = b.grown(LABEL_PAD);
            inside && !data.touches(b) && !l.labels.iter().any(|o| o.bbox.overlaps(&b))
        };
        let rows = (k % 4) as i32..(self.plot.y1 - self.plot.y0) / (h + 3);
        let corner = std::iter::once(first)
            .chain(rows.flat_map(|j| [(right, row(j)), (other, row(j))]))
            .find(|&c| clear(c));
        let rgb = if k == 0 { BLACK } else { RGBColor(70, 70, 70) };
        let pos = Pos::new(HPos::Right, VPos::Bottom);
        let draw = |l: &mut Layout, c| self.push_label(l, &m.label, c, pos, rgb, (w, h));
        self.place_line_label(l, &m.label, (corner, first), Sample::Stroke { width: 1 }, draw);
    }

    /// Records a label whose right-bottom corner is `corner`, and its box as occupied.
    fn push_label(&self, l: &mut Layout, text: &str, corner: (i32, i32), pos: Pos, rgb: RGBColor, (w, h): (i32, i32)) {
        let bbox = PixelBox {
            x0: corner.0 - w,
            y0: corner.1 - h,
            x1: corner.0,
            y1: corner.1,
        }
        .grown(LABEL_PAD);
        l.occupied.boxes.push(bbox);
        l.labels.push(LineLabel {
            text: text.to_string(),
            bbox,
            at: corner,
            pos,
            rgb,
        });
    }
}

/// Step along a horizontal line between the places tried for its label, pixels.
const LABEL_STEP: i32 = 12;

/// Room kept around a line label, pixels (the estimated text width is a little short of the rendered one).
const LABEL_PAD: i32 = 3;

/// Draws the line labels, each on a translucent white ground so that it reads over the curves.
fn draw_labels<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, labels: &[LineLabel]) -> Res {
    for l in labels {
        let b = l.bbox;
        root.draw(&Rectangle::new([(b.x0, b.y0), (b.x1, b.y1)], WHITE.mix(0.75).filled()))
            .map_err(err)?;
        let style = LABEL_FONT.into_font().color(&l.rgb).pos(l.pos);
        root.draw(&Text::new(l.text.clone(), l.at, style)).map_err(err)?;
    }
    Ok(())
}

fn plot_box<DB: DrawingBackend, CT: CoordTranslate>(area: &DrawingArea<DB, CT>) -> PixelBox {
    let (x, y) = area.get_pixel_range();
    PixelBox {
        x0: x.start,
        y0: y.start,
        x1: x.end - 1,
        y1: y.end - 1,
    }
}

fn measure<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>) -> impl Fn(&str) -> (i32, i32) + '_ {
    move |t: &str| {
        area.estimate_text_size(t, &TextStyle::from(LABEL_FONT.into_font()))
            .map(|(w, h)| (w as i32, h as i32))
            .unwrap_or((6 * t.chars().count() as i32, 12))
    }
}

/// The legend's place outside the plotting area `plot`: below the x axis label, at the bottom of `area`,
/// aligned with the plot's left edge (or the area's right edge when it is wider than the plot).
fn below<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, plot: PixelBox, size: (i32, i32)) -> (i32, i32) {
    let (x, y) = area.get_pixel_range();
    (plot.x0.min(x.end - size.0 - 2).max(x.start), y.end - size.1 - 2)
}

/// The legend's place: inside where the data are not, else `None` (the caller makes room outside).
fn legend_place(entries: &[Entry], size: (i32, i32), l: &Layout, preferred: Legend) -> Option<Option<(i32, i32)>> {
    if entries.is_empty() {
        return Some(None);
    }
    legend::place(l.plot, size, &l.occupied, preferred).map(Some)
}

fn draw_lines<DB, X, Y>(
    root: &DrawingArea<DB, Shift>,
    area: &DrawingArea<DB, Shift>,
    p: &Prepared,
    axes: impl Fn() -> (X, Y),
) -> Res
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let build = |extra: i32| {
        let (xr, yr) = axes();
        ChartBuilder::on(area)
            .x_label_area_size(X_AREA)
            .y_label_area_size(Y_AREA)
            .right_y_label_area_size(if p.secondary.is_some() { Y_AREA } else { 0 })
            .margin_bottom(extra)
            .build_cartesian_2d(xr, yr)
            .map_err(err)
    };
    let layout = |chart: &ChartContext<DB, Cartesian2d<X::CoordDescType, Y::CoordDescType>>,
                  legend_has: Option<&[Entry]>| {
        let plot = plot_box(chart.plotting_area());
        let y2 = p.y2.unwrap_or((0.0, 1.0));
        let map = |q: (f64, f64)| chart.backend_coord(&q);
        let map2 = |q: (f64, f64)| {
            let t = (q.1 - y2.0) / (y2.1 - y2.0);
            (
                map((q.0, p.y.0)).0,
                plot.y1 - (t * (plot.y1 - plot.y0) as f64).round() as i32,
            )
        };
        let m = measure(area);
        Geometry {
            plot,
            map: &map,
            map2: &map2,
            measure: &m,
            legend_has,
        }
        .layout(p)
    };
    let mut chart = build(0)?;
    let mut l = layout(&chart, None);
    let mut entries = line_entries(p);
    entries.append(&mut l.in_legend);
    let size = legend::size(area, &entries)?;
    let at = match legend_place(&entries, size, &l, p.legend) {
        Some(at) => at,
        None => {
            chart = build(size.1 + 8)?;
            l = layout(&chart, Some(&entries));
            Some(below(area, l.plot, size))
        }
    };
    match (&p.secondary, p.y2) {
        (Some(sa), Some(y2)) => {
            // the secondary coordinates must be set before the primary mesh is drawn, or the primary labels
            // are drawn on the right-hand axis too
            let mut dc = chart.set_secondary_coord(axes().0, y2.0..y2.1);
            draw_primary(&mut dc, p)?;
            dc.configure_secondary_axes()
                .y_desc(sa.y_label.as_str())
                .y_label_formatter(&|v| tick_in(*v, y2))
                .axis_desc_style(DESC_FONT)
                .label_style(LABEL_FONT)
                .draw()
                .map_err(err)?;
            for s in ordered(&sa.series) {
                draw_series!(dc, draw_secondary_series, s);
            }
            for m in &sa.hlines {
                let line = vec![(p.x.0, m.at), (p.x.1, m.at)];
                dc.draw_secondary_series(DashedLineSeries::new(line, 3, 3, RGBColor(90, 90, 90).stroke_width(1)))
                    .map_err(err)?;
            }
        }
        _ => draw_primary(&mut chart, p)?,
    }
    draw_labels(root, &l.labels)?;
    match at {
        Some(at) => legend::draw(root, at, size, &entries),
        None => Ok(()),
    }
}

/// Mesh, bars, bands, series and marker lines against the primary axes.
fn draw_primary<'a, DB, X, Y>(chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>, p: &Prepared) -> Res
where
    DB: DrawingBackend + 'a,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let label = |log: bool, range: (f64, f64)| {
        move |v: &f64| {
            if log {
                log_tick_in(*v, range)
            } else {
                tick_in(*v, range)
            }
        }
    };
    let (fx, fy) = (label(p.log_x, p.x), label(p.log_y, p.y));
    chart
        .configure_mesh()
        .x_desc(p.x_label.as_str())
        .y_desc(p.y_label.as_str())
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .axis_desc_style(DESC_FONT)
        .label_style(LABEL_FONT)
        .light_line_style(RGBColor(238, 238, 238))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()
        .map_err(err)?;
    let bar = colour(0);
    for r in &p.rects {
        let corners = [(r.0, p.y.0.max(0.0)), (r.1, r.2)];
        chart
            .draw_series([
                Rectangle::new(corners, bar.mix(0.35).filled()),
                Rectangle::new(corners, bar.stroke_width(1)),
            ])
            .map_err(err)?;
    }
    for b in &p.bands {
        let mut poly = b.lower.clone();
        poly.extend(b.upper.iter().rev().cloned());
        let fill = colour(b.color.unwrap_or(0)).mix(BAND_OPACITY).filled();
        chart
            .draw_series(std::iter::once(Polygon::new(poly, fill)))
            .map_err(err)?;
    }
    for s in ordered(&p.series) {
        draw_series!(chart, draw_series, s);
    }
    for (k, m) in p.vlines.iter().enumerate() {
        let c = if k == 0 { BLACK } else { RGBColor(90, 90, 90) };
        let line = vec![(m.at, p.y.0), (m.at, p.y.1)];
        chart
            .draw_series(DashedLineSeries::new(line, 6, 4, c.stroke_width(1)))
            .map_err(err)?;
    }
    for m in &p.hlines {
        let line = vec![(p.x.0, m.at), (p.x.1, m.at)];
        chart
            .draw_series(DashedLineSeries::new(line, 6, 4, BLACK.stroke_width(1)))
            .map_err(err)?;
    }
    Ok(())
}

/// A bar chart with its y range.
pub(super) struct BarsWithRange<'a>(pub &'a BarChart, pub (f64, f64));

/// Bar colours: within the limit bluish green (light), over it vermillion (dark), without a limit blue —
/// told apart in greyscale by their lightness.
fn bar_groups() -> [(&'static str, RGBColor, f64); 3] {
    [
        ("within limit", colour(2), 0.45),
        ("over limit", colour(1), 0.95),
        ("no limit", colour(0), 0.75),
    ]
}

fn bar_group(value: f64, limit: Option<f64>) -> usize {
    match limit {
        Some(l) if value <= l => 0,
        Some(_) => 1,
        None => 2,
    }
}

impl BarsWithRange<'_> {
    fn entries(&self) -> Vec<Entry> {
        let b = self.0;
        let groups = bar_groups();
        let mut e: Vec<Entry> = (0..3)
            .filter(|g| (0..b.values.len()).any(|i| bar_group(b.values[i], b.limits[i]) == *g))
            .map(|g| Entry {
                label: groups[g].0.into(),
                sample: Sample::Fill {
                    rgb: groups[g].1,
                    opacity: groups[g].2,
                },
            })
            .collect();
        if b.limits.iter().any(Option::is_some) {
            e.push(Entry {
                label: "limit".into(),
                sample: Sample::Stroke { width: 3 },
            });
        }
        e
    }
}

impl Draw for BarsWithRange<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Res {
        let (b, y) = (self.0, self.1);
        let area = titled(root, &b.title)?;
        let n = b.categories.len();
        // plotters' segmented 0..k has k + 1 segments (the end is inclusive); one category keeps 0..1
        let last = if n >= 2 { n - 1 } else { n };
        let build = |extra: i32| {
            ChartBuilder::on(&area)
                .x_label_area_size(X_AREA)
                .y_label_area_size(Y_AREA)
                .margin_bottom(extra)
                .build_cartesian_2d((0..last).into_segmented(), y.0..y.1)
                .map_err(err)
        };
        let entries = self.entries();
        let size = legend::size(&area, &entries)?;
        let mut chart = build(0)?;
        let at = match legend_place(&entries, size, &self.layout(&chart), Legend::UpperLeft) {
            Some(at) => at,
            None => {
                chart = build(size.1 + 8)?;
                Some(below(&area, plot_box(chart.plotting_area()), size))
            }
        };
        self.draw_bars(&mut chart)?;
        match at {
            Some(at) => legend::draw(root, at, size, &entries),
            None => Ok(()),
        }
    }
}

type BarCoord = Cartesian2d<
    plotters::coord::ranged1d::SegmentedCoord<plotters::coord::types::RangedCoordusize>,
    plotters::coord::types::RangedCoordf64,
>;

impl BarsWithRange<'_> {
    fn layout<DB: DrawingBackend>(&self, chart: &ChartContext<DB, BarCoord>) -> Layout {
        let b = self.0;
        let mut occupied = Occupied::default();
        for (i, (&v, limit)) in b.values.iter().zip(&b.limits).enumerate() {
            let p0 = chart.backend_coord(&(SegmentValue::Exact(i), 0.0));
            let p1 = chart.backend_coord(&(SegmentValue::Exact(i + 1), v));
            occupied.boxes.push(PixelBox {
                x0: p0.0.min(p1.0),
                y0: p0.1.min(p1.1),
                x1: p0.0.max(p1.0),
                y1: p0.1.max(p1.1),
            });
            if let Some(l) = *limit {
                let a = chart.backend_coord(&(SegmentValue::Exact(i), l));
                let c = chart.backend_coord(&(SegmentValue::Exact(i + 1), l));
                occupied.polyline([(a.0, a.1 - 2), (c.0, c.1 - 2), (c.0, c.1 + 2), (a.0, a.1 + 2)]);
            }
        }
        Layout {
            plot: plot_box(chart.plotting_area()),
            occupied,
            labels: Vec::new(),
            in_legend: Vec::new(),
        }
    }

    fn draw_bars<DB: DrawingBackend>(&self, chart: &mut ChartContext<DB, BarCoord>) -> Res {
        let (b, y) = (self.0, self.1);
        let (n, cats) = (b.categories.len(), &b.categories);
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
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(err)?;
        let groups = bar_groups();
        let bars = (0..n).map(|i| {
            let (_, c, opacity) = groups[bar_group(b.values[i], b.limits[i])];
            let corners = [(SegmentValue::Exact(i), 0.0), (SegmentValue::Exact(i + 1), b.values[i])];
            let mut fill = Rectangle::new(corners.clone(), c.mix(opacity).filled());
            let mut edge = Rectangle::new(corners, c.stroke_width(1));
            fill.set_margin(0, 0, 8, 8);
            edge.set_margin(0, 0, 8, 8);
            [fill, edge]
        });
        chart.draw_series(bars.flatten()).map_err(err)?;
        let limits = (0..n).filter_map(|i| {
            b.limits[i].map(|l| {
                let line = vec![(SegmentValue::Exact(i), l), (SegmentValue::Exact(i + 1), l)];
                PathElement::new(line, BLACK.stroke_width(3))
            })
        });
        chart.draw_series(limits).map_err(err)?;
        Ok(())
    }
}
