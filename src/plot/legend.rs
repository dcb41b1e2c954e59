//! The legend of a chart, placed where the data are not: the pixels the data occupy (curve segments, bars,
//! markers, line labels) are collected first, then the legend box goes into the first place among the
//! preferred corner, the other three corners, the middles of the top and bottom edges, then every place of
//! a 12-pixel grid over the plotting area (the nearest to the preferred corner first) that touches none of
//! them; when every place touches data, the chart is drawn shorter and the legend goes outside, below the
//! x axis label.

use super::chart::Legend;
use super::style::{colour, shape, LABEL_FONT};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Colour of the legend's border (only the legend is drawn with it, which lets a reader of the SVG find it).
pub const BORDER: RGBColor = RGBColor(64, 64, 64);
/// Opacity of interval bands (their fill and their legend sample).
pub const BAND_OPACITY: f64 = 0.25;
/// Radius of a marker shape, pixels.
pub const MARKER_R: i32 = 4;
const PAD: i32 = 6;
const SAMPLE_W: i32 = 30;
const GAP: i32 = 6;
/// Clearance kept between the legend and the data, pixels.
const CLEAR: i32 = 4;

/// How an entry's sample is drawn.
#[derive(Debug, Clone, Copy)]
pub enum Sample {
    /// A line of the palette colour `colour` (dashed or not, `width` pixels) with the marker `shape`.
    Line {
        /// Palette index.
        colour: usize,
        /// Dashed or solid.
        dashed: bool,
        /// Stroke width, pixels (0: no line, a marker only).
        width: u32,
        /// Palette index of the marker shape, if any.
        shape: Option<usize>,
    },
    /// A translucent fill (a band) or an opaque one (`opacity` 1, a bar).
    Fill {
        /// Colour.
        rgb: RGBColor,
        /// Opacity, 0 to 1.
        opacity: f64,
    },
    /// A black stroke (a limit across bars).
    Stroke {
        /// Stroke width, pixels.
        width: u32,
    },
}

/// One row of the legend.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Text.
    pub label: String,
    /// Sample.
    pub sample: Sample,
}

/// A pixel rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelBox {
    /// Left.
    pub x0: i32,
    /// Top.
    pub y0: i32,
    /// Right.
    pub x1: i32,
    /// Bottom.
    pub y1: i32,
}

impl PixelBox {
    /// The box grown by `d` pixels on every side.
    pub fn grown(self, d: i32) -> PixelBox {
        PixelBox {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }
    /// Whether the two boxes share a pixel.
    pub fn overlaps(&self, o: &PixelBox) -> bool {
        self.x0 <= o.x1 && o.x0 <= self.x1 && self.y0 <= o.y1 && o.y0 <= self.y1
    }
    /// Whether the segment a–b passes through the box (Liang–Barsky clipping).
    fn cut_by(&self, a: (i32, i32), b: (i32, i32)) -> bool {
        if a.0.max(b.0) < self.x0 || a.0.min(b.0) > self.x1 || a.1.max(b.1) < self.y0 || a.1.min(b.1) > self.y1 {
            return false;
        }
        let (dx, dy) = ((b.0 - a.0) as f64, (b.1 - a.1) as f64);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let edges = [
            (-dx, (a.0 - self.x0) as f64),
            (dx, (self.x1 - a.0) as f64),
            (-dy, (a.1 - self.y0) as f64),
            (dy, (self.y1 - a.1) as f64),
        ];
        for (p, q) in edges {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else if p < 0.0 {
                t0 = t0.max(q / p);
            } else {
                t1 = t1.min(q / p);
            }
        }
        t0 <= t1
    }
}

/// What the data occupy, in pixels.
#[derive(Debug, Default, Clone)]
pub struct Occupied {
    /// Curve segments.
    pub segments: Vec<((i32, i32), (i32, i32))>,
    /// Bars, markers and labels.
    pub boxes: Vec<PixelBox>,
}

impl Occupied {
    /// Adds the segments of a polyline.
    pub fn polyline(&mut self, pts: impl IntoIterator<Item = (i32, i32)>) {
        let pts: Vec<(i32, i32)> = pts.into_iter().collect();
        self.segments.extend(pts.windows(2).map(|w| (w[0], w[1])));
        if let [p] = pts.as_slice() {
            self.segments.push((*p, *p));
        }
    }
    /// Whether anything lies in `b`.
    pub fn touches(&self, b: PixelBox) -> bool {
        self.boxes.iter().any(|o| o.overlaps(&b)) || self.segments.iter().any(|s| b.cut_by(s.0, s.1))
    }
}

/// Width and height of the legend box of `entries`, pixels.
///
/// # Errors
/// The font back end's message.
pub fn size<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, entries: &[Entry]) -> Result<(i32, i32), String> {
    let mut w = 0;
    for e in entries {
        w = w.max(
            area.estimate_text_size(&e.label, &TextStyle::from(LABEL_FONT.into_font()))
                .map_err(|e| e.to_string())?
                .0 as i32,
        );
    }
    Ok((PAD + SAMPLE_W + GAP + w + PAD, 2 * PAD + ROW * entries.len() as i32))
}

const ROW: i32 = 18;

/// The top-left corner of the legend inside `plot` (see the module docs), or `None` when every place
/// touches data.
pub fn place(plot: PixelBox, size: (i32, i32), occupied: &Occupied, preferred: Legend) -> Option<(i32, i32)> {
    let m = 8;
    let (left, right) = (plot.x0 + m, plot.x1 - m - size.0);
    let (top, bottom) = (plot.y0 + m, plot.y1 - m - size.1);
    if right < left || bottom < top {
        return None;
    }
    let first = match preferred {
        Legend::UpperLeft => (left, top),
        Legend::LowerLeft => (left, bottom),
        Legend::LowerRight => (right, bottom),
        _ => (right, top),
    };
    let mid_x = (left + right) / 2;
    let named = [
        (right, top),
        (left, top),
        (right, bottom),
        (left, bottom),
        (mid_x, top),
        (mid_x, bottom),
    ];
    // then every place of a grid, the nearest to the preferred corner first
    let mut grid: Vec<(i32, i32)> = (left..=right)
        .step_by(GRID)
        .flat_map(|x| (top..=bottom).step_by(GRID).map(move |y| (x, y)))
        .collect();
    grid.sort_by_key(|&(x, y)| ((x - first.0).abs() + (y - first.1).abs(), x, y));
    std::iter::once(first).chain(named).chain(grid).find(|&(x, y)| {
        let b = PixelBox {
            x0: x,
            y0: y,
            x1: x + size.0,
            y1: y + size.1,
        };
        !occupied.touches(b.grown(CLEAR))
    })
}

/// Step of the grid of places tried after the corners, pixels.
const GRID: usize = 12;

/// Draws the legend box with its top-left corner at `at` (absolute pixels of `root`).
///
/// # Errors
/// The back end's message.
pub fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    at: (i32, i32),
    size: (i32, i32),
    entries: &[Entry],
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let corner = (at.0 + size.0, at.1 + size.1);
    root.draw(&Rectangle::new([at, corner], WHITE.filled())).map_err(err)?;
    root.draw(&Rectangle::new([at, corner], BORDER.stroke_width(1)))
        .map_err(err)?;
    let text = LABEL_FONT
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (i, e) in entries.iter().enumerate() {
        let y = at.1 + PAD + ROW * i as i32 + ROW / 2;
        let x = at.0 + PAD;
        draw_sample(root, (x, y), e.sample).map_err(err)?;
        root.draw(&Text::new(e.label.clone(), (x + SAMPLE_W + GAP, y), text.clone()))
            .map_err(err)?;
    }
    Ok(())
}

fn draw_sample<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    sample: Sample,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    match sample {
        Sample::Line {
            colour: k,
            dashed,
            width,
            shape: marker,
        } => {
            let c = colour(k);
            let pieces: Vec<(i32, i32)> = match (width, dashed) {
                (0, _) => vec![],
                (_, true) => vec![(0, 8), (13, 21), (26, SAMPLE_W)],
                _ => vec![(0, SAMPLE_W)],
            };
            for (a, b) in pieces {
                root.draw(&PathElement::new(vec![(x + a, y), (x + b, y)], c.stroke_width(width)))?;
            }
            if let Some(s) = marker {
                root.draw(&Polygon::new(
                    shape(s, MARKER_R)
                        .into_iter()
                        .map(|(dx, dy)| (x + SAMPLE_W / 2 + dx, y + dy))
                        .collect::<Vec<_>>(),
                    c.filled(),
                ))?;
            }
            Ok(())
        }
        Sample::Fill { rgb, opacity } => root.draw(&Rectangle::new(
            [(x, y - 6), (x + SAMPLE_W, y + 6)],
            rgb.mix(opacity).filled(),
        )),
        Sample::Stroke { width } => root.draw(&PathElement::new(
            vec![(x, y), (x + SAMPLE_W, y)],
            BLACK.stroke_width(width),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_segment_through_a_box_is_found_and_one_beside_it_is_not() {
        let b = PixelBox {
            x0: 10,
            y0: 10,
            x1: 20,
            y1: 20,
        };
        assert!(b.cut_by((0, 0), (30, 30)));
        assert!(b.cut_by((15, 15), (15, 15)));
        assert!(!b.cut_by((0, 0), (30, 5)));
        assert!(!b.cut_by((0, 25), (25, 25)));
    }

    #[test]
    fn the_legend_leaves_a_corner_with_data_for_a_free_one() {
        let plot = PixelBox {
            x0: 0,
            y0: 0,
            x1: 400,
            y1: 300,
        };
        // a curve along the top edge: both upper corners are taken
        let mut occ = Occupied::default();
        occ.polyline([(0, 20), (400, 20)]);
        let at = place(plot, (100, 50), &occ, Legend::UpperRight).unwrap();
        assert_eq!(at, (292, 242));
        // data everywhere: no place inside
        occ.boxes.push(PixelBox {
            x0: 0,
            y0: 0,
            x1: 400,
            y1: 300,
        });
        assert_eq!(place(plot, (100, 50), &occ, Legend::UpperRight), None);
    }
}
