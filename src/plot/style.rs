//! The look every chart shares: the colour-blind-safe palette, the marker shapes that keep series apart in
//! greyscale, the fonts, and the tick labels (engineering notation at the decades of a logarithmic axis).
//!
//! # Palette
//! The eight colours of Okabe and Ito (M. Okabe, K. Ito, *Color Universal Design (CUD): how to make figures
//! and presentations that are friendly to colorblind people*, J*FLY, 2008; recommended by B. Wong, *Points
//! of view: Color blindness*, Nature Methods 8, 441, 2011), in the order blue, vermillion, bluish green,
//! reddish purple, orange, sky blue, yellow, grey (the palette's black, lightened to a mid grey so that
//! reference lines stay behind the data). Series of the same colour index also get the same marker shape,
//! and no two of the first eight share a shape, so a chart printed in greyscale still tells them apart.

use plotters::style::RGBColor;

/// The Okabe–Ito palette (see the module docs), by series index.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(240, 228, 66),  // yellow
    RGBColor(110, 110, 110), // grey (black, lightened)
];

/// The colour of series index `i`.
pub fn colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Title font (family, pixels).
pub const TITLE_FONT: (&str, u32) = ("sans-serif", 18);
/// Axis description font.
pub const DESC_FONT: (&str, u32) = ("sans-serif", 15);
/// Tick labels, legend and line labels.
pub const LABEL_FONT: (&str, u32) = ("sans-serif", 12);

/// Vertices (pixels, around the point) of the marker shape of series index `i`: circle, square, triangle
/// up, diamond, triangle down, pentagon, hexagon, star — one shape per palette colour.
pub fn shape(i: usize, r: i32) -> Vec<(i32, i32)> {
    let polygon = |n: usize, phase: f64, radius: f64| -> Vec<(i32, i32)> {
        (0..n)
            .map(|k| {
                let a = phase + std::f64::consts::TAU * k as f64 / n as f64;
                ((radius * a.cos()).round() as i32, (radius * a.sin()).round() as i32)
            })
            .collect()
    };
    let rf = r as f64;
    let up = -std::f64::consts::FRAC_PI_2;
    match i % PALETTE.len() {
        0 => polygon(12, 0.0, rf),
        1 => vec![(-r, -r), (r, -r), (r, r), (-r, r)],
        2 => polygon(3, up, rf * 1.25),
        3 => polygon(4, up, rf * 1.3),
        4 => polygon(3, -up, rf * 1.25),
        5 => polygon(5, up, rf * 1.2),
        6 => polygon(6, 0.0, rf * 1.15),
        _ => (0..10)
            .map(|k| {
                let rad = if k % 2 == 0 { rf * 1.4 } else { rf * 0.6 };
                let a = up + std::f64::consts::TAU * k as f64 / 10.0;
                ((rad * a.cos()).round() as i32, (rad * a.sin()).round() as i32)
            })
            .collect(),
    }
}

/// Tick positions of a logarithmic axis over `range` spanning `pixels`: `(labelled, unlabelled)`.
///
/// Every decade inside the range gets a tick; decades are labelled every `k`-th one, `k` the smallest
/// stride that leaves at least [`MIN_LABEL_GAP`] pixels between labels (1 — every decade — whenever they
/// fit). A range holding fewer than three decades is labelled at 1, 2 and 5 × 10ⁿ (and at every integer
/// multiple when that still gives fewer than three labels); multiples 2…9 of each decade are unlabelled
/// ticks when the axis spans at most six decades.
pub fn log_ticks(range: (f64, f64), pixels: f64) -> (Vec<f64>, Vec<f64>) {
    let (lo, hi) = range;
    let (e0, e1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let inside = |v: &f64| *v >= lo * (1.0 - 1e-12) && *v <= hi * (1.0 + 1e-12);
    let multiples = |ms: &[f64]| -> Vec<f64> {
        (e0..=e1)
            .flat_map(|e| ms.iter().map(move |m| m * 10f64.powi(e)))
            .filter(inside)
            .collect()
    };
    let decades = multiples(&[1.0]);
    let all: Vec<f64> = (1..10).map(f64::from).collect();
    let minor = if decades.len() <= 7 {
        multiples(&all)
    } else {
        decades.clone()
    };
    if decades.len() >= 3 {
        let fit = (pixels / MIN_LABEL_GAP).floor().max(2.0) as usize;
        let stride = decades.len().div_ceil(fit).max(1) as i32;
        let labelled = decades
            .iter()
            .cloned()
            .filter(|v| (v.log10().round() as i32).rem_euclid(stride) == 0)
            .collect();
        return (labelled, minor);
    }
    let one_two_five = multiples(&[1.0, 2.0, 5.0]);
    let labelled = if one_two_five.len() >= 3 {
        one_two_five
    } else {
        multiples(&all)
    };
    (labelled, minor)
}

/// Least distance between two labels of a logarithmic axis, pixels.
pub const MIN_LABEL_GAP: f64 = 22.0;

/// Label of a tick on a logarithmic axis spanning `range`: plain numbers when the whole axis lies within
/// 0.01 … 10⁴, otherwise every label in engineering notation, `10⁻¹²` or `2×10⁻¹²` (never `0`, since every
/// tick of a logarithmic axis is positive).
pub fn log_tick_in(v: f64, range: (f64, f64)) -> String {
    if range.0 >= 1e-2 * (1.0 - 1e-9) && range.1 < 1e4 {
        tick(v)
    } else {
        power_tick(v)
    }
}

/// `v` as a power of ten, `10⁻¹²`, or a multiple of one, `2×10⁻¹²`.
pub fn power_tick(v: f64) -> String {
    let e = (v.log10() + 1e-9).floor() as i32;
    let m = v / 10f64.powi(e);
    let power = format!("10{}", superscript(e));
    if (m - 1.0).abs() < 1e-6 {
        power
    } else {
        format!("{}×{power}", tick(m))
    }
}

/// `n` in superscript digits (`-12` → `⁻¹²`).
pub fn superscript(n: i32) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d.to_digit(10).unwrap_or(0) as usize],
        })
        .collect()
}

/// Tick label on a linear axis spanning `range`: a value within 1e-9 of the axis' magnitude of zero is
/// rounding noise of the tick placement (e.g. `-2.7e-20` on a 1e-3 axis) — the tick plotters meant at 0 —
/// and is labelled `0`.
pub fn tick_in(v: f64, range: (f64, f64)) -> String {
    if v.abs() <= 1e-9 * range.0.abs().max(range.1.abs()) {
        return "0".into();
    }
    tick(v)
}

/// Tick label: up to 4 significant digits, plain in [1e-3, 1e5), otherwise `1.5e-6`.
pub fn tick(v: f64) -> String {
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

/// The reciprocal of a unit for an axis label: `1/m`, and `1/(m/s^2)` for a compound unit (never the
/// ambiguous `1/m/s^2`).
pub fn per_unit(unit: &str) -> String {
    if unit.contains(['/', ' ', '*', '·']) {
        format!("1/({unit})")
    } else {
        format!("1/{unit}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_labels_are_powers_of_ten_never_zero() {
        let wide = (1e-13, 1.0);
        assert_eq!(log_tick_in(1e-12, wide), "10⁻¹²");
        assert_eq!(log_tick_in(2e-9, wide), "2×10⁻⁹");
        assert_eq!(log_tick_in(0.1, wide), "10⁻¹");
        assert_eq!(log_tick_in(1.0, wide), "10⁰");
        assert_eq!(log_tick_in(0.1, (0.05, 20.0)), "0.1");
        assert_eq!(power_tick(1e5), "10⁵");
        assert_eq!(power_tick(1e-300), "10⁻³⁰⁰");
    }

    #[test]
    fn every_decade_is_labelled_when_they_fit() {
        // 1e-12 … 1e-2: eleven decades on 380 pixels (34 px each)
        let (labelled, _) = log_ticks((0.9e-12, 1.1e-2), 380.0);
        assert_eq!(labelled.len(), 11);
        // 41 decades on 380 pixels: 17 labels fit, so every third decade (10⁻³⁹, 10⁻³⁶, …, 10⁰)
        let (labelled, minor) = log_ticks((1e-40, 1.0), 380.0);
        assert_eq!(labelled.len(), 14);
        assert_eq!(minor.len(), 41);
        // within one decade: 1, 2, 5 or every integer multiple
        assert_eq!(log_ticks((1.5, 30.0), 380.0).0, vec![2.0, 5.0, 10.0, 20.0]);
        assert_eq!(log_ticks((2.5, 8.0), 380.0).0, vec![3.0, 4.0, 5.0, 6.0, 7.0, 8.0]);
    }
}
