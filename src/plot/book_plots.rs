//! The pictures of `stochvib book --plots DIR`: every catalogue model's data computed with the library and
//! drawn with the [`model_plots`](super::model_plots) chart functions.
//!
//! * Operator seat (Sukharev 7.6): octave-band RMS velocity and acceleration of Example 7.2 (harmonic base
//!   motion) and of the random `data/operator-seat.toml` scenario, against Table 7.1.
//! * Mine hoist (Dvornikov, Kondrakhin & Velebnik (2014)): ω₁, ω₂ and the sign-continuous renormalised mode
//!   components over ξ = ȳ/H, with the nodal point of the cofactor construction marked.
//! * Balancer bogie (Sukharev 8.5): D_y/D_x over r ∈ [2, 30] cm for ℓ ∈ {40, 60, 80} cm, ℓ₁ = ℓ/2, with the
//!   criterion (8.50) marked.
//! * Scraper (Sukharev 8.7): σ of x₁, x₂, cab travel and the finite accelerations over v = 2…20 m/s, sprung
//!   cab with the [`Table81Assumptions`] and the (8.66) road.

use super::chart::{BarChart, Legend, LineChart, Marker, Series};
use super::model_plots::{balancer_chart, mine_hoist_charts, octave_band_chart, scraper_chart};
use crate::error::{Error, Result};
use crate::models::balancer_bogie;
use crate::models::mine_hoist::MineHoist;
use crate::models::operator_seat::{self, BandCheck, SanitaryLimits, OCTAVE_CENTRES_HZ};
use crate::models::scraper::{self, Table81Assumptions};
use crate::numbers::num;
use crate::scenario::parse_scenario;
use crate::spectrum::two_pole_road::Form;
use std::path::{Path, PathBuf};

/// The book's type-1 road correlation decay for the balancer bogie (8.45): α = 0.035 1/cm = 3.5 1/m.
pub const BALANCER_ALPHA: f64 = 3.5;

/// Text of the random seat scenario (embedded at compile time, like Table 7.1).
const OPERATOR_SEAT_TOML: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/data/operator-seat.toml"));

/// A book picture: a line chart or a bar chart.
#[derive(Debug, Clone)]
pub enum BookChart {
    /// Curves.
    Line(LineChart),
    /// Octave-band bars against limits.
    Bar(BarChart),
}

impl BookChart {
    /// The chart's title.
    pub fn title(&self) -> &str {
        match self {
            BookChart::Line(c) => &c.title,
            BookChart::Bar(c) => &c.title,
        }
    }

    /// Writes `<stem>.svg` and `<stem>.png` into `dir`.
    ///
    /// # Errors
    /// Those of [`LineChart::render`] / [`BarChart::render`].
    pub fn render(&self, dir: &Path, stem: &str) -> Result<Vec<PathBuf>> {
        match self {
            BookChart::Line(c) => c.render(dir, stem),
            BookChart::Bar(c) => c.render(dir, stem),
        }
    }
}

/// One picture of the book set: file stem and chart.
#[derive(Debug, Clone)]
pub struct BookPicture {
    /// File stem (`<stem>.svg`, `<stem>.png`).
    pub stem: String,
    /// The chart with its data.
    pub chart: BookChart,
}

fn line(stem: &str, c: LineChart) -> BookPicture {
    BookPicture {
        stem: stem.into(),
        chart: BookChart::Line(c),
    }
}

fn bars(stem: &str, c: BarChart) -> BookPicture {
    BookPicture {
        stem: stem.into(),
        chart: BookChart::Bar(c),
    }
}

/// Seat pictures (velocity, acceleration) of one band check.
fn seat_pair(stem: &str, title: &str, checks: &[BandCheck]) -> Result<[BookPicture; 2]> {
    let v: Vec<f64> = checks.iter().map(|c| c.velocity_rms).collect();
    let vl: Vec<Option<f64>> = checks.iter().map(|c| Some(c.velocity_limit)).collect();
    let a: Vec<f64> = checks.iter().map(|c| c.acceleration_rms).collect();
    let al: Vec<Option<f64>> = checks.iter().map(|c| Some(c.acceleration_limit)).collect();
    Ok([
        bars(
            &format!("{stem}-velocity"),
            octave_band_chart(
                &format!("{title}: seat velocity vs Table 7.1"),
                &OCTAVE_CENTRES_HZ,
                &v,
                &vl,
                "RMS seat velocity",
                "m/s",
            )?,
        ),
        bars(
            &format!("{stem}-acceleration"),
            octave_band_chart(
                &format!("{title}: seat acceleration vs Table 7.1"),
                &OCTAVE_CENTRES_HZ,
                &a,
                &al,
                "RMS seat acceleration",
                "m/s²",
            )?,
        ),
    ])
}

/// Operator seat (Sukharev 7.6): octave-band RMS seat velocity and acceleration of Example 7.2
/// (u = 0.0035 sin 6πt m) and of the random scenario `data/operator-seat.toml` (spectra looked up in
/// `spectra_dir`), against Table 7.1. Four pictures: `seat-example-7-2-{velocity,acceleration}`,
/// `seat-random-{velocity,acceleration}`.
///
/// # Formula
/// Harmonic: the sinusoid's RMS A λ/√2, A λ²/√2 in the band containing λ/2π, 0 elsewhere; random:
/// σ² = 2∫_band |H(iω)|² S_u(ω) dω per band ([`operator_seat::random_band_rms`]).
///
/// # Errors
/// A broken Table 7.1 or scenario file; a spectrum missing from `spectra_dir`; quadrature failures.
///
/// # Examples
/// ```no_run
/// let p = stochvib::plot::book_plots::seat_pictures(stochvib::scenario::Catalogue::bundled().dir()).unwrap();
/// assert_eq!(p.len(), 4);
/// ```
pub fn seat_pictures(spectra_dir: &Path) -> Result<Vec<BookPicture>> {
    let limits = SanitaryLimits::table_7_1()?;
    let (seat, au, lambda) = operator_seat::example_7_2();
    let harmonic = seat.assess_harmonic(au, lambda, &limits)?;
    let sc = parse_scenario(OPERATOR_SEAT_TOML, Path::new("data/operator-seat.toml"), spectra_dir)?;
    let sys = sc.model.system.as_ref();
    let index = |name: &str| {
        sys.outputs()
            .iter()
            .position(|o| o.name == name)
            .ok_or_else(|| Error::invalid("output", name, "not an output of the operator-seat model"))
    };
    let v = operator_seat::random_band_rms(sys, &sc.excitation, index("seat_vel")?)?;
    let a = operator_seat::random_band_rms(sys, &sc.excitation, index("seat_acc")?)?;
    let random = operator_seat::assess(&v, &a, &limits)?;
    let mut out = Vec::new();
    out.extend(seat_pair(
        "seat-example-7-2",
        "Operator seat, Example 7.2 (Sukharev 7.6), u = 3.5 mm sin 6πt",
        &harmonic,
    )?);
    out.extend(seat_pair(
        "seat-random",
        &format!("Operator seat (Sukharev 7.6), random floor `{}`", sc.input.reference),
        &random,
    )?);
    Ok(out)
}

/// Mine hoist (Dvornikov, Kondrakhin & Velebnik (2014), printed parameters): ω₁, ω₂ (rad/s) and the sign-continuous
/// renormalised mode components (drum, sheave, load) over ξ = ȳ/H at `n_points` values ([`MineHoist::sweep`]), with
/// the nodal point ξ* = (L − l₂*)/H ([`MineHoist::node_closed_form`]) marked on both charts and ω₁ there
/// ([`MineHoist::modes`]) as a point. Pictures `mine-hoist-frequencies`, `mine-hoist-modes`.
///
/// # Errors
/// `n_points` < 2; eigen-solver failures.
///
/// # Examples
/// ```
/// let p = stochvib::plot::book_plots::mine_hoist_pictures(11).unwrap();
/// assert_eq!(p[0].stem, "mine-hoist-frequencies");
/// ```
pub fn mine_hoist_pictures(n_points: usize) -> Result<Vec<BookPicture>> {
    let h = MineHoist::printed();
    let s = h.sweep(n_points)?;
    let xi: Vec<f64> = s.iter().map(|p| p.xi).collect();
    let w1: Vec<f64> = s.iter().map(|p| p.omega1).collect();
    let w2: Vec<f64> = s.iter().map(|p| p.omega2).collect();
    let comp = |mode: usize, k: usize| -> Vec<f64> {
        s.iter()
            .map(|p| if mode == 1 { p.mode1[k] } else { p.mode2[k] })
            .collect()
    };
    let comps: Vec<(String, Vec<f64>)> = [1usize, 2]
        .iter()
        .flat_map(|&j| {
            ["drum", "sheave", "load"]
                .iter()
                .enumerate()
                .map(move |(k, part)| (format!("mode {j}, {part}"), comp(j, k)))
                .collect::<Vec<_>>()
        })
        .collect();
    let comp_refs: Vec<(&str, &[f64])> = comps.iter().map(|(n, v)| (n.as_str(), v.as_slice())).collect();
    let (mut f, mut m) = mine_hoist_charts(
        "single-end mine hoist, printed parameters (Dvornikov et al. (2014), Figs. 2a, 2b)",
        &xi,
        &[("ω₁", &w1), ("ω₂", &w2)],
        &comp_refs,
    )?;
    let p = h.params();
    let l2_node = h.node_closed_form()?;
    let xi_node = (p.max_hanging_length - l2_node) / p.lift_height;
    let w1_node = h.modes(l2_node)?.omega[1];
    // legend in a free band below the curves
    let ys = comps.iter().flat_map(|(_, v)| v.iter().cloned());
    let (lo, hi) = ys.fold((0.0f64, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
    m.y_range = Some((lo - 0.7 * (hi - lo), hi + 0.05 * (hi - lo)));
    m.legend = Legend::LowerRight;
    let label = format!("node U: ξ* = {}", num(xi_node));
    f.vlines.push(Marker::new(xi_node, label.clone()));
    m.vlines.push(Marker::new(xi_node, label));
    f.series.push(
        Series::markers(
            format!("ω₁ at the node = {} rad/s", num(w1_node)),
            vec![(xi_node, w1_node)],
        )
        .with_color(0),
    );
    Ok(vec![line("mine-hoist-frequencies", f), line("mine-hoist-modes", m)])
}

/// Balancer bogie (Sukharev 8.5, (8.49)): D_y/D_x over r = 2…30 cm (0.5 cm steps) for ℓ = 40, 60, 80 cm,
/// ℓ₁ = ℓ/2, type-1 road α = [`BALANCER_ALPHA`], criterion σ_y/σ_x ≤ 0.5 ⇔ D_y/D_x ≤ 0.25 marked, and the
/// book's worked example (r = 11, 15 cm, ℓ = 60 cm) as points. Picture `balancer-bogie`.
///
/// # Errors
/// None in practice (valid constant parameters; kept for [`balancer_bogie::sweep`]).
///
/// # Examples
/// ```
/// let p = stochvib::plot::book_plots::balancer_picture().unwrap();
/// assert_eq!(p.stem, "balancer-bogie");
/// ```
pub fn balancer_picture() -> Result<BookPicture> {
    let r: Vec<f64> = (4..=60).map(|k| k as f64 / 200.0).collect();
    let ells = [0.4, 0.6, 0.8];
    let mut by_length = Vec::new();
    for &l in &ells {
        let s = balancer_bogie::sweep(BALANCER_ALPHA, &r, &[l], &[0.5])?;
        by_length.push((l, s.iter().map(|p| p.ratio).collect::<Vec<f64>>()));
    }
    let mut c = balancer_chart(
        "Balancer bogie, D_y/D_x over r (Sukharev 8.5, (8.49)), type-1 road α = 0.035 1/cm, ℓ₁ = ℓ/2",
        &r,
        &by_length,
    )?;
    let ex = balancer_bogie::sweep(BALANCER_ALPHA, &[0.11, 0.15], &[0.6], &[0.5])?;
    c.series.push(
        Series::markers(
            "book example, ℓ = 0.6 m, r = 0.11, 0.15 m",
            ex.iter().map(|p| (p.r, p.ratio)).collect(),
        )
        .with_color(1),
    );
    Ok(line("balancer-bogie", c))
}

/// Scraper, sprung cab (Sukharev 8.7, (8.65)) with the given [`Table81Assumptions`] (the book set uses the
/// defaults) on the (8.66) road in the assumptions' form:
/// σ over v = 2, 3, …, 20 m/s of the displacements x₁, x₂ and the cab travel x₂ − x₁ (m) and of the
/// accelerations ẍ₁, ẍ₂ (m/s²) ([`scraper::respond`]). An output whose variance is infinite at any speed
/// is left out and named in the title. Pictures `scraper-displacements`, `scraper-accelerations`.
///
/// # Errors
/// Invalid assumptions; response failures other than divergence.
///
/// # Examples
/// ```no_run
/// use stochvib::models::scraper::Table81Assumptions;
/// let p = stochvib::plot::book_plots::scraper_pictures(&Table81Assumptions::default()).unwrap();
/// assert_eq!(p.len(), 2);
/// ```
pub fn scraper_pictures(assumptions: &Table81Assumptions) -> Result<Vec<BookPicture>> {
    let a = *assumptions;
    let (_, sprung) = a.models()?;
    let inst = sprung.instance()?;
    let road = scraper::book_road_8_66(a.road_form)?;
    let speeds: Vec<f64> = (2..=20).map(|v| v as f64).collect();
    let stats = speeds
        .iter()
        .map(|&v| scraper::respond(&inst, road.clone(), v))
        .collect::<Result<Vec<_>>>()?;
    let sigmas = |name: &str| -> Option<Vec<f64>> {
        stats
            .iter()
            .map(|st| st.iter().find(|o| o.name == name).and_then(|o| o.sigma))
            .collect()
    };
    let road_name = match a.road_form {
        Form::Consistent => "road (8.66), consistent form",
        Form::AsPrinted => "road (8.66) as printed",
    };
    let assumed = format!(
        "m₁ = {} t, ω₀ = {} rad/s, ζ₁ = {}, m₂ = {} t, f₂ = {} Hz, ζ₂ = {}",
        num(a.m1 / 1e3),
        num(a.omega1),
        num(a.zeta1),
        num(a.m2 / 1e3),
        num(a.omega2 / (2.0 * std::f64::consts::PI)),
        num(a.zeta2)
    ) + " assumed";
    let mut out = Vec::new();
    for (stem, what, unit, outputs) in [
        (
            "scraper-displacements",
            "displacements",
            "m",
            &[
                ("x1", "frame x₁"),
                ("x2", "cab x₂"),
                ("cab_travel", "cab travel x₂ − x₁"),
            ][..],
        ),
        (
            "scraper-accelerations",
            "accelerations",
            "m/s²",
            &[("x1_acc", "frame ẍ₁"), ("x2_acc", "cab ẍ₂")][..],
        ),
    ] {
        let mut curves: Vec<(&str, Vec<f64>)> = Vec::new();
        let mut skipped: Vec<&str> = Vec::new();
        for (name, label) in outputs {
            match sigmas(name) {
                Some(v) => curves.push((label, v)),
                None => skipped.push(label),
            }
        }
        let mut title = format!("Scraper, sprung cab (Sukharev 8.7, (8.65)): σ of {what} over speed");
        if !skipped.is_empty() {
            title.push_str(&format!(" ({} omitted: infinite variance)", skipped.join(", ")));
        }
        let refs: Vec<(&str, &[f64])> = curves.iter().map(|(n, v)| (*n, v.as_slice())).collect();
        let mut c = scraper_chart(&title, &speeds, &refs, unit)?;
        // the road and the assumed parameters as legend entries without points (grey)
        c.series.push(Series::line(road_name, vec![]).with_color(7));
        c.series.push(Series::line(assumed.clone(), vec![]).with_color(7));
        out.push(line(stem, c));
    }
    Ok(out)
}

/// Every book picture, computed with the library (spectra for the random seat scenario from the catalogue
/// in `spectra_dir`).
///
/// # Errors
/// As [`seat_pictures`], [`mine_hoist_pictures`], [`balancer_picture`], [`scraper_pictures`].
/// (`n_points` = 201 for the mine hoist.)
///
/// # Examples
/// ```no_run
/// let p = stochvib::plot::book_plots::book_pictures(std::path::Path::new("spectra")).unwrap();
/// assert_eq!(p.len(), 9);
/// ```
pub fn book_pictures(spectra_dir: &Path) -> Result<Vec<BookPicture>> {
    let mut out = seat_pictures(spectra_dir)?;
    out.extend(mine_hoist_pictures(201)?);
    out.push(balancer_picture()?);
    out.extend(scraper_pictures(&Table81Assumptions::default())?);
    Ok(out)
}

/// Writes every [`book_pictures`] picture (spectra from `spectra_dir`) into `dir` (created if missing) as SVG
/// and PNG (800 × 500);
/// returns the written paths (SVG, PNG per picture).
///
/// # Errors
/// As [`book_pictures`]; I/O and rendering errors.
///
/// # Examples
/// ```no_run
/// use std::path::Path;
/// let files = stochvib::plot::book_plots(Path::new("book-plots"), Path::new("spectra")).unwrap();
/// assert_eq!(files.len(), 18);
/// ```
pub fn book_plots(dir: &Path, spectra_dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for p in book_pictures(spectra_dir)? {
        files.extend(p.chart.render(dir, &p.stem)?);
    }
    Ok(files)
}
