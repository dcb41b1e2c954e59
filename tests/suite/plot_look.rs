//! Every kind of chart the tool draws, drawn through the command line and read back from the SVG it wrote:
//!
//! * tick labels: on every numeric axis the labels sit where their values belong on a linear or a
//!   logarithmic scale (within [`TICK_PIXELS`]); a logarithmic axis therefore has no `0` label (log 0 is
//!   not a place on it), and its labels are powers of ten or 1-2-5 steps;
//! * the legend box (the one rectangle drawn with the legend's border colour) lies inside the picture and
//!   crosses no segment of a curve, band or marker and no bar drawn before it;
//! * the label of every limit and threshold line (on its translucent white box) covers no curve, band edge
//!   or marker of the data;
//! * every curve is drawn in a colour of the Okabe–Ito palette (or grey/black for reference lines), and two
//!   data series carry marker shapes of their own (greyscale);
//! * no text is a placeholder (`(SI)`, `inline`) and every axis title names its unit;
//! * the Welch picture draws its analytic curves before (behind) the estimate and its interval band
//!   translucent; the road density labels its class-limit lines on the line, not in the legend;
//! * the same input gives the same bytes (the scenario pictures drawn twice).
//!
//! The kinds are listed in [`KINDS`] with the command that draws them; `docs/gallery.md` shows one picture
//! of each (checked by [`the_gallery_shows_every_kind`]). `STOCHVIB_UPDATE_GALLERY=1` makes
//! [`every_chart_kind_is_fit_for_print`] copy the first picture of each kind into `docs/gallery/`.

use crate::common::{cli_within, root};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Duration;

const LIMIT: Duration = Duration::from_secs(900);
/// A tick label's pixel position against the scale through the first and last labels: plotters rounds
/// every position to a whole pixel (±0.5 px each for the label and the two labels defining the scale) and
/// labels carry four significant digits (≤ 5e-4 of the axis span: 0.2 px on a 400 px axis).
const TICK_PIXELS: f64 = 2.0;
/// The palette (Okabe & Ito 2008), the limit grey, black and the dark greys of reference lines.
const PALETTE: [&str; 11] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442", "#6E6E6E", "#000000", "#5A5A5A",
    "#282828",
];

/// One kind of chart: (kind, the stem or stem prefix of its pictures, the index of the command in
/// [`commands`] that draws it, a description for the gallery).
pub const KINDS: &[(&str, &str, usize, &str)] = &[
    ("input-density", "input-density", 0, "input density of a scenario"),
    ("transfer", "transfer-", 0, "|H(iω)|² of each output"),
    (
        "output-density",
        "output-density-",
        0,
        "output density with its cumulative variance (right axis)",
    ),
    (
        "input-coherence",
        "input-coherence",
        1,
        "squared coherence of the two tracks of a road",
    ),
    (
        "input-cross-spectrum",
        "input-cross-spectrum-",
        1,
        "co- and quad-spectrum of two tracks",
    ),
    (
        "weighted-density",
        "weighted-density-",
        2,
        "frequency-weighted density against the comfort scale",
    ),
    (
        "welch",
        "-welch",
        3,
        "Welch estimate of a Monte Carlo run against the analytic density",
    ),
    ("realizations", "-realizations", 3, "the first realizations of a run"),
    ("histogram", "-histogram", 3, "histogram of a run against N(M, σ)"),
    (
        "correlation",
        "-correlation",
        3,
        "correlation estimate against the model",
    ),
    ("rainflow", "-rainflow", 4, "rainflow ranges of a run against Dirlik"),
    (
        "nonlinear-density",
        "-histogram-log",
        5,
        "response density of a nonlinear run, three routes",
    ),
    (
        "road-density",
        "road-density-",
        6,
        "measured road density, χ² band, ISO 8608 fits and class limits",
    ),
    (
        "road-coherence",
        "road-coherence",
        6,
        "coherence of two measured tracks",
    ),
    (
        "exposure-time",
        "exposure-time-",
        7,
        "weighted acceleration of a record and its running r.m.s.",
    ),
    (
        "exposure-bands",
        "exposure-bands",
        7,
        "one-third-octave bands of a record against the comfort scale",
    ),
    (
        "fatigue-ranges",
        "fatigue-ranges",
        8,
        "rainflow ranges of a record against Dirlik",
    ),
    (
        "fatigue-matrix",
        "fatigue-matrix",
        8,
        "rainflow range–mean matrix of a record",
    ),
    (
        "book-bars",
        "seat-example-7-2-velocity",
        9,
        "band r.m.s. against limits (bars)",
    ),
    (
        "book-curves",
        "mine-hoist-frequencies",
        9,
        "a catalogue model's curves over a parameter",
    ),
    (
        "transient",
        "-transient",
        10,
        "σ(t) and mean(t) of a non-stationary response, exact route",
    ),
    (
        "workday-a8",
        "workday-a8",
        11,
        "daily exposure A(8): each task's share and the day against the limit value (bars)",
    ),
];

/// Category axes (bar charts): their x labels are names, not a scale.
const BAR_KINDS: &[&str] = &["book-bars", "workday-a8"];

/// The commands, run from the source tree; `{D}` is the output directory, `{R}` the records' directory.
pub fn commands() -> Vec<Vec<&'static str>> {
    let sim = |s: &'static str, n: &'static str| {
        vec![
            "simulate",
            s,
            "--realizations",
            n,
            "--duration",
            "5",
            "--dt",
            "0.01",
            "--seed",
            "7",
            "--store-raw",
            "-o",
            "{D}/run.h5",
            "--plots",
            "{D}",
        ]
    };
    vec![
        vec!["plot", "data/quarter-car.toml", "-o", "{D}"],
        vec!["plot", "data/full-vehicle-two-tracks.toml", "-o", "{D}"],
        vec!["plot", "data/scraper-cab-comfort.toml", "-o", "{D}"],
        sim("data/conveyor-idler.toml", "8"),
        sim("data/operator-seat-verdicts.toml", "4"),
        sim("data/duffing-white-noise.toml", "4"),
        vec!["road", "data/measured-profile.csv", "--plots", "{D}"],
        vec!["exposure", "{R}/seat-record.csv", "--plots", "{D}"],
        vec![
            "fatigue",
            "{R}/axle-record.csv",
            "--sn-slope",
            "5",
            "--sn-range",
            "160 MPa",
            "--sn-cycles",
            "2e6",
            "--plots",
            "{D}",
        ],
        vec!["book", "--plots", "{D}"],
        vec!["transient", "data/quarter-car-accelerating.toml", "--plots", "{D}"],
        vec!["workday", "data/workday/scraper-operator.toml", "--plots", "{D}"],
    ]
}

/// Writes the two records of [`commands`] into `dir`: a seat acceleration (z, m/s², 400 Hz, 10 s) and an axle
/// stress (MPa, 400 Hz, 10 s), each a sum of sines of incommensurate frequencies (deterministic bytes).
pub fn write_records(dir: &Path) {
    let rows = |header: &str, f: &dyn Fn(f64) -> f64| {
        let mut s = format!("{header}\n");
        for k in 0..4000 {
            let t = k as f64 / 400.0;
            s += &format!("{t:.4},{:.5}\n", f(t));
        }
        s
    };
    let tau = std::f64::consts::TAU;
    let seat = |t: f64| 0.6 * (tau * 1.7 * t).sin() + 0.3 * (tau * 4.3 * t + 1.0).sin() + 0.15 * (tau * 11.9 * t).sin();
    let axle = |t: f64| 40.0 + 60.0 * (tau * 2.1 * t).sin() + 25.0 * (tau * 7.7 * t + 0.5).sin();
    std::fs::write(dir.join("seat-record.csv"), rows("t [s],z [m/s^2]", &seat)).unwrap();
    std::fs::write(dir.join("axle-record.csv"), rows("t [s],s [MPa]", &axle)).unwrap();
}

/// Runs every command into its own directory under `base` and returns the directories.
pub fn draw_all(base: &Path) -> Vec<PathBuf> {
    let records = base.join("records");
    std::fs::create_dir_all(&records).unwrap();
    write_records(&records);
    let mut dirs = Vec::new();
    for (i, cmd) in commands().iter().enumerate() {
        let d = base.join(format!("cmd{i}"));
        std::fs::create_dir_all(&d).unwrap();
        let args: Vec<String> = cmd
            .iter()
            .map(|a| {
                a.replace("{D}", d.to_str().unwrap())
                    .replace("{R}", records.to_str().unwrap())
            })
            .collect();
        let o = cli_within(&args, &root(), LIMIT);
        assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
        dirs.push(d);
    }
    dirs
}

/// One element of an SVG: tag name, attributes, text content (for `<text>`).
#[derive(Debug, Clone)]
struct El {
    tag: String,
    attrs: BTreeMap<String, String>,
    text: String,
}

impl El {
    fn num(&self, k: &str) -> f64 {
        self.attrs.get(k).and_then(|v| v.parse().ok()).unwrap_or(f64::NAN)
    }
    fn get(&self, k: &str) -> &str {
        self.attrs.get(k).map(String::as_str).unwrap_or("")
    }
    fn points(&self) -> Vec<(f64, f64)> {
        self.get("points")
            .split_whitespace()
            .filter_map(|p| p.split_once(','))
            .map(|(x, y)| (x.parse().unwrap(), y.parse().unwrap()))
            .collect()
    }
}

fn unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

/// The elements of `svg` in document order.
fn parse(svg: &str) -> Vec<El> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        if rest.starts_with('/') || rest.starts_with('?') || rest.starts_with('!') {
            continue;
        }
        let end = rest.find('>').unwrap();
        let head = &rest[..end];
        let tag: String = head.chars().take_while(|c| c.is_ascii_alphanumeric()).collect();
        let mut attrs = BTreeMap::new();
        let mut a = &head[tag.len()..];
        while let Some(eq) = a.find("=\"") {
            let name = a[..eq].trim().to_string();
            let close = a[eq + 2..].find('"').unwrap();
            attrs.insert(name, unescape(&a[eq + 2..eq + 2 + close]));
            a = &a[eq + 2 + close + 1..];
        }
        let text = if tag == "text" {
            unescape(rest[end + 1..].split("</text>").next().unwrap().trim())
        } else {
            String::new()
        };
        out.push(El { tag, attrs, text });
    }
    out
}

/// The value of a tick label: `0.25`, `-3`, `1.5e-6`, `10⁻¹²`, `2×10⁻⁹`.
fn label_value(s: &str) -> Option<f64> {
    let sup = |c: char| "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().position(|d| d == c);
    let power = |p: &str| -> Option<f64> {
        let e = p.strip_prefix("10")?;
        let (neg, digits) = match e.strip_prefix('⁻') {
            Some(d) => (true, d),
            None => (false, e),
        };
        let mut n = 0i32;
        for c in digits.chars() {
            n = n * 10 + sup(c)? as i32;
        }
        (!digits.is_empty()).then(|| 10f64.powi(if neg { -n } else { n }))
    };
    if let Some((m, p)) = s.split_once('×') {
        return Some(m.parse::<f64>().ok()? * power(p)?);
    }
    power(s).or_else(|| s.parse().ok())
}

/// An axis' labels: (value, pixel) by pixel.
type Axis = Vec<(f64, f64)>;

/// The numeric axes of a picture: y labels (anchor end or start, centred vertically: grouped by x, placed
/// at y) and x labels (anchor middle, hanging: grouped by y, placed at x).
fn axes(els: &[El], category_x: bool) -> Vec<(String, Axis)> {
    let mut groups: BTreeMap<(String, i64), Axis> = BTreeMap::new();
    let mut text_values = BTreeMap::<(String, i64), Vec<Option<f64>>>::new();
    for e in els.iter().filter(|e| e.tag == "text" && e.get("transform").is_empty()) {
        let (anchor, dy) = (e.get("text-anchor"), e.get("dy"));
        let key = match (anchor, dy) {
            ("end" | "start", "0.5ex") => (format!("y-{anchor}"), e.num("x") as i64),
            ("middle", "0.76em") if !category_x && e.num("font-size") < 12.0 => ("x".to_string(), e.num("y") as i64),
            _ => continue,
        };
        let v = label_value(&e.text);
        text_values.entry(key.clone()).or_default().push(v);
        let at = if key.0 == "x" { e.num("x") } else { e.num("y") };
        if let Some(v) = v {
            groups.entry(key).or_default().push((v, at));
        }
    }
    groups
        .into_iter()
        .filter(|(k, g)| g.len() >= 2 && text_values[k].iter().all(Option::is_some))
        .map(|(k, mut g)| {
            g.sort_by(|a, b| a.1.total_cmp(&b.1));
            (format!("{} at {}", k.0, k.1), g)
        })
        .collect()
}

/// Whether the labels of `axis` sit on a linear (`log = false`) or logarithmic scale through its first and
/// last labels.
fn fits(axis: &[(f64, f64)], log: bool) -> bool {
    let f = |v: f64| if log { v.log10() } else { v };
    if log && axis.iter().any(|p| p.0 <= 0.0) {
        return false;
    }
    let (a, b) = (axis[0], axis[axis.len() - 1]);
    if f(a.0) == f(b.0) {
        return false;
    }
    axis.iter()
        .all(|p| (a.1 + (f(p.0) - f(a.0)) / (f(b.0) - f(a.0)) * (b.1 - a.1) - p.1).abs() <= TICK_PIXELS)
}

/// Checks one picture; returns the number of logarithmic axes it has.
fn check_picture(path: &Path, kind: &str) -> usize {
    let svg = std::fs::read_to_string(path).unwrap();
    let els = parse(&svg);
    let mut logs = 0;
    for (name, axis) in axes(&els, BAR_KINDS.contains(&kind)) {
        let (lin, log) = (fits(&axis, false), fits(&axis, true));
        assert!(
            lin || log,
            "{}: axis {name}: labels off their scale: {axis:?}",
            path.display()
        );
        if log && !lin {
            logs += 1;
            // decades, or 1-2-5 steps inside fewer than three decades
            for w in axis.windows(2) {
                let r = (w[0].0 / w[1].0).max(w[1].0 / w[0].0);
                let decade = (r.log10() - r.log10().round()).abs() < 1e-6;
                assert!(decade || r <= 5.0 + 1e-9, "{}: axis {name}: step {r}", path.display());
            }
        }
    }
    check_legend(path, &els);
    check_axis_titles(path, &els, BAR_KINDS.contains(&kind));
    check_line_labels(path, &els);
    check_colours(path, &els);
    logs
}

/// No text is a placeholder (`(SI)` for a unit, `inline` for a spectrum written in the scenario); every axis
/// title (the rotated y titles, the centred x title under the axis) names its unit in brackets, or is a
/// count of cycles; the x axis of a bar chart names categories.
fn check_axis_titles(path: &Path, els: &[El], category_x: bool) {
    for e in els.iter().filter(|e| e.tag == "text") {
        let placeholder = e.text.contains("(SI)") || e.text.split([' ', ',', ':']).any(|w| w == "inline");
        assert!(!placeholder, "{}: placeholder text `{}`", path.display(), e.text);
        let y_title = e.get("transform").starts_with("rotate");
        let x_title = e.get("text-anchor") == "middle" && e.get("dy") == "-0.5ex" && !category_x;
        if y_title || x_title {
            assert!(
                e.text.contains('[') && e.text.contains(']') || e.text.starts_with("cycles"),
                "{}: axis title without a unit: `{}`",
                path.display(),
                e.text
            );
        }
    }
}

/// The curves, bands and markers of the data: drawn in a colour of the palette (not the greys and black
/// of axes, grid, limit and threshold lines), wider than a hair line or filled.
fn is_data(e: &El) -> bool {
    let data_colour = |c: &str| PALETTE[..7].contains(&c);
    match e.tag.as_str() {
        "polyline" => data_colour(e.get("stroke")) && e.get("stroke-width") != "1",
        "polygon" => data_colour(e.get("fill")),
        _ => false,
    }
}

/// The labels written on limit and threshold lines (each on a translucent white box drawn after the data)
/// cover no curve, band edge or marker of the data.
fn check_line_labels(path: &Path, els: &[El]) {
    let is_label = |e: &El| e.tag == "rect" && e.get("fill") == "#FFFFFF" && e.get("opacity") == "0.75";
    let Some(first) = els.iter().position(is_label) else {
        return;
    };
    for l in els.iter().filter(|e| is_label(e)) {
        let (x, y, w, h) = (l.num("x"), l.num("y"), l.num("width"), l.num("height"));
        let inner = (x + 1.0, y + 1.0, x + w - 1.0, y + h - 1.0);
        // the label's text ends at the box's right-bottom corner less the box's 3-pixel margin
        let at = |t: &El| (t.num("x") - (x + w - 3.0)).abs() <= 1.0 && (t.num("y") - (y + h - 3.0)).abs() <= 1.0;
        let text = els
            .iter()
            .find(|t| t.tag == "text" && at(t))
            .map_or("", |t| t.text.as_str());
        for e in els[..first].iter().filter(|e| is_data(e)) {
            for (a, c) in segments(e) {
                assert!(
                    !crosses(inner, a, c),
                    "{}: the line label `{text}` {inner:?} covers a {} segment {a:?}–{c:?} of the data",
                    path.display(),
                    e.tag
                );
            }
        }
    }
}

fn segments(e: &El) -> Vec<((f64, f64), (f64, f64))> {
    match e.tag.as_str() {
        "polyline" => {
            let p = e.points();
            let mut s: Vec<_> = p.windows(2).map(|w| (w[0], w[1])).collect();
            if p.len() == 1 {
                s.push((p[0], p[0]));
            }
            s
        }
        "polygon" => {
            let p = e.points();
            (0..p.len()).map(|i| (p[i], p[(i + 1) % p.len()])).collect()
        }
        "rect" => {
            let (x, y, w, h) = (e.num("x"), e.num("y"), e.num("width"), e.num("height"));
            vec![
                ((x, y), (x + w, y)),
                ((x + w, y), (x + w, y + h)),
                ((x, y + h), (x + w, y + h)),
                ((x, y), (x, y + h)),
            ]
        }
        _ => Vec::new(),
    }
}

/// Whether segment a–b meets the open box (x0, y0)–(x1, y1) (Liang–Barsky).
fn crosses(b: (f64, f64, f64, f64), a: (f64, f64), c: (f64, f64)) -> bool {
    let (dx, dy) = (c.0 - a.0, c.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-dx, a.0 - b.0), (dx, b.2 - a.0), (-dy, a.1 - b.1), (dy, b.3 - a.1)] {
        if p == 0.0 {
            if q <= 0.0 {
                return false;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    t0 < t1
}

fn check_legend(path: &Path, els: &[El]) {
    let Some(k) = els.iter().position(|e| e.tag == "rect" && e.get("stroke") == "#404040") else {
        return;
    };
    let l = &els[k];
    let b = (
        l.num("x"),
        l.num("y"),
        l.num("x") + l.num("width"),
        l.num("y") + l.num("height"),
    );
    assert!(
        b.0 >= 0.0 && b.1 >= 0.0 && b.2 <= 800.0 && b.3 <= 500.0,
        "{}: legend {b:?} outside",
        path.display()
    );
    let inner = (b.0 + 1.0, b.1 + 1.0, b.2 - 1.0, b.3 - 1.0);
    // the legend's white fill is the element before its border; what was drawn before that is the chart
    for e in &els[..k.saturating_sub(1)] {
        let grid = ["#EEEEEE", "#CDCDCD"].contains(&e.get("stroke"));
        let background = e.tag == "rect" && e.num("width") >= 800.0;
        if grid || background {
            continue;
        }
        for (a, c) in segments(e) {
            assert!(
                !crosses(inner, a, c),
                "{}: the legend {b:?} covers a {} segment {a:?}–{c:?}",
                path.display(),
                e.tag
            );
        }
    }
}

fn check_colours(path: &Path, els: &[El]) {
    for e in els
        .iter()
        .filter(|e| e.tag == "polyline" && e.get("stroke-width") != "1")
    {
        let c = e.get("stroke");
        assert!(PALETTE.contains(&c), "{}: curve in colour {c}", path.display());
    }
}

/// The kind of a picture file's stem, the longest matching pattern.
fn kind_of(stem: &str) -> Option<&'static str> {
    KINDS
        .iter()
        .filter(|k| stem == k.1 || stem.starts_with(k.1) || stem.ends_with(k.1))
        .max_by_key(|k| k.1.len())
        .map(|k| k.0)
}

fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir("plot-look", name)
}

#[test]
fn every_chart_kind_is_fit_for_print() {
    let base = scratch("all");
    let dirs = draw_all(&base);
    let mut seen: BTreeMap<&str, PathBuf> = BTreeMap::new();
    let mut log_axes = 0;
    for (i, d) in dirs.iter().enumerate() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(d).unwrap().map(|e| e.unwrap().path()).collect();
        files.sort();
        for f in files.iter().filter(|f| f.extension().is_some_and(|e| e == "svg")) {
            let stem = f.file_stem().unwrap().to_string_lossy().into_owned();
            let kind = kind_of(&stem).unwrap_or("book-curves");
            log_axes += check_picture(f, kind);
            if KINDS.iter().any(|k| k.0 == kind && k.2 == i) {
                seen.entry(kind).or_insert_with(|| f.clone());
            }
        }
    }
    let missing: Vec<&str> = KINDS.iter().map(|k| k.0).filter(|k| !seen.contains_key(k)).collect();
    assert!(missing.is_empty(), "kinds not drawn: {missing:?}");
    assert!(log_axes >= 20, "only {log_axes} logarithmic axes checked");
    check_welch_and_road(&seen);
    if std::env::var("STOCHVIB_UPDATE_GALLERY").as_deref() == Ok("1") {
        let g = root().join("docs/gallery");
        std::fs::create_dir_all(&g).unwrap();
        for (kind, f) in &seen {
            std::fs::copy(f, g.join(format!("{kind}.svg"))).unwrap();
        }
        write_records(&g);
    }
    let _ = std::fs::remove_dir_all(&base);
}

/// Analytic curves behind the estimate, a translucent band; class limits labelled on the line.
fn check_welch_and_road(seen: &BTreeMap<&str, PathBuf>) {
    let welch = parse(&std::fs::read_to_string(&seen["welch"]).unwrap());
    let first = |colour: &str, width: &str| {
        welch
            .iter()
            .position(|e| e.tag == "polyline" && e.get("stroke") == colour && e.get("stroke-width") == width)
    };
    let (analytic, estimate) = (first("#D55E00", "3"), first("#0072B2", "2"));
    assert!(
        analytic.is_some() && estimate.is_some() && analytic < estimate,
        "{analytic:?} {estimate:?}"
    );
    let band = welch
        .iter()
        .find(|e| e.tag == "polygon" && e.get("fill") == "#0072B2")
        .unwrap();
    assert!(band.num("opacity") < 0.5, "band opacity {}", band.num("opacity"));
    let road = parse(&std::fs::read_to_string(&seen["road-density"]).unwrap());
    let legend = road
        .iter()
        .position(|e| e.tag == "rect" && e.get("stroke") == "#404040")
        .unwrap();
    let limits: Vec<usize> = (0..road.len())
        .filter(|&i| road[i].tag == "text" && road[i].text.starts_with("class limit"))
        .collect();
    assert!(!limits.is_empty(), "no class limit labelled");
    assert!(limits.iter().all(|&i| i < legend), "a class limit is in the legend");
    check_marker_shapes(&seen["output-density"]);
}

/// Greyscale: the two data series of an output density (the density and its cumulative variance) carry
/// marker shapes of different vertex counts (circle, square), each in its series' palette colour.
fn check_marker_shapes(path: &Path) {
    let els = parse(&std::fs::read_to_string(path).unwrap());
    let mut shapes: BTreeMap<String, std::collections::BTreeSet<usize>> = BTreeMap::new();
    for e in els
        .iter()
        .filter(|e| e.tag == "polygon" && PALETTE[..7].contains(&e.get("fill")))
    {
        let p = e.points();
        let span = |f: fn(&(f64, f64)) -> f64| {
            let v: Vec<f64> = p.iter().map(f).collect();
            v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
        };
        if span(|q| q.0) <= 12.0 && span(|q| q.1) <= 12.0 {
            shapes.entry(e.get("fill").to_string()).or_default().insert(p.len());
        }
    }
    assert!(shapes.len() >= 2, "{}: markers in {shapes:?}", path.display());
    let counts: Vec<&std::collections::BTreeSet<usize>> = shapes.values().collect();
    assert!(
        counts.iter().all(|c| c.len() == 1) && counts[0] != counts[1],
        "{}: marker shapes {shapes:?}",
        path.display()
    );
}

#[test]
fn the_same_input_gives_the_same_bytes() {
    let (a, b) = (scratch("same-a"), scratch("same-b"));
    for d in [&a, &b] {
        let o = cli_within(
            &["plot", "data/quarter-car.toml", "-o", d.to_str().unwrap()],
            &root(),
            LIMIT,
        );
        assert!(o.status.success());
    }
    let names = crate::common::listing(&a);
    assert_eq!(names, crate::common::listing(&b));
    assert!(names.len() >= 6);
    for n in names {
        assert!(
            std::fs::read(a.join(&n)).unwrap() == std::fs::read(b.join(&n)).unwrap(),
            "{n} differs"
        );
    }
}

#[test]
fn the_checks_find_a_zero_on_a_log_axis_and_a_covering_legend() {
    // a log axis labelled 1e-3, 1e-2, 0: not on a linear nor a logarithmic scale
    let axis = [(1e-3, 100.0), (1e-2, 200.0), (0.0, 300.0)];
    assert!(!fits(&axis, false) && !fits(&axis, true));
    assert!(fits(&[(1e-3, 100.0), (1e-2, 200.0), (1e-1, 300.0)], true));
    assert_eq!(label_value("10⁻¹²"), Some(1e-12));
    assert_eq!(label_value("2×10⁻⁹"), Some(2e-9));
    // a curve through the legend box
    let svg = "<svg><polyline stroke=\"#0072B2\" points=\"0,0 100,100 \"/><rect x=\"40\" y=\"40\" width=\"20\" \
               height=\"20\" fill=\"#FFFFFF\"/><rect x=\"40\" y=\"40\" width=\"20\" height=\"20\" fill=\"none\" \
               stroke=\"#404040\"/></svg>";
    let r = std::panic::catch_unwind(|| check_legend(Path::new("t.svg"), &parse(svg)));
    assert!(r.is_err());
    // a threshold label over a curve of the data, and the same label beside it
    let label = |y: u32| {
        format!(
            "<svg><polyline stroke=\"#0072B2\" stroke-width=\"2\" points=\"0,50 100,50 \"/><polyline \
             stroke=\"#282828\" stroke-width=\"1\" points=\"0,{y} 100,{y} \"/><rect x=\"40\" y=\"{}\" \
             width=\"50\" height=\"12\" opacity=\"0.75\" fill=\"#FFFFFF\" stroke=\"none\"/><text x=\"88\" \
             y=\"{y}\">comfort limit</text></svg>",
            y - 12
        )
    };
    let over = label(56);
    let r = std::panic::catch_unwind(|| check_line_labels(Path::new("t.svg"), &parse(&over)));
    assert!(r.is_err(), "a label over the data passes");
    check_line_labels(Path::new("t.svg"), &parse(&label(30)));
}

#[test]
fn the_gallery_shows_every_kind() {
    let page = std::fs::read_to_string(root().join("docs/gallery.md")).unwrap();
    let cmds = commands();
    for (kind, _, cmd, _) in KINDS {
        let picture = format!("gallery/{kind}.svg");
        assert!(
            page.contains(&format!("]({picture})")),
            "docs/gallery.md does not show {picture}"
        );
        let svg = root().join("docs").join(&picture);
        check_picture(&svg, kind);
        let shown = cmds[*cmd]
            .iter()
            .map(|a| a.replace("{D}", "pictures").replace("{R}", "docs/gallery"))
            .map(|a| if a.contains(' ') { format!("\"{a}\"") } else { a })
            .collect::<Vec<_>>()
            .join(" ");
        assert!(
            page.contains(&format!("stochvib {shown}")),
            "docs/gallery.md lacks `stochvib {shown}`"
        );
    }
}
