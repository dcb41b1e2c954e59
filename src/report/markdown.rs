//! `--format markdown`: the `analyze`, `road` and `inspect` reports as markdown (headings, pipe tables) to
//! paste into a report, an issue or a wiki. The numbers follow the table rule of [`super::table`]: four
//! significant figures, one notation per column; JSON keeps every digit.

use super::table::{facts, Table, ToMarkdown};
use super::tables::TablesReport;
use super::verdict_report as vr;
use crate::error::Result;
use crate::fields::EverydayUnit;
use crate::models::results::Cell;
use crate::numbers::{num, sig4};
use crate::response::{Outcome, ResponseStatistics};
use crate::study::analysis::{AnalysisReport, OutputReport};
use crate::study::band_section::BandSection;
use crate::study::road_profile::{CoherenceRow, DensityRow, FitRow, RoadReport, TrackReport};
use crate::study::{ComfortVerdict, FatigueVerdict, VerdictAnalysis};
use std::fmt::Write as _;
use std::path::Path;

/// `value unit`, or `—` when absent.
fn with_unit(v: Option<f64>, unit: &str) -> String {
    v.map_or_else(
        || "—".to_string(),
        |x| format!("{} {unit}", sig4(x)).trim_end().to_string(),
    )
}

/// The square of a unit: `m²`, `(m/s^2)²`.
fn squared(unit: &str) -> String {
    if unit.chars().all(char::is_alphanumeric) {
        format!("{unit}²")
    } else {
        format!("({unit})²")
    }
}

/// A bullet list, one line each.
fn bullets(lines: &[String]) -> String {
    lines.iter().map(|l| format!("- {l}\n")).collect()
}

impl ToMarkdown for AnalysisReport {
    fn markdown(&self) -> String {
        let mut s = format!("# {}\n\n", self.title);
        s += &facts(&[
            ("scenario", format!("`{}`", self.scenario)),
            ("model", self.model.clone()),
            ("input", self.input.clone()),
            (
                "duration (peaks, exceedances)",
                EverydayUnit::HOUR.show(self.duration_s),
            ),
        ]);
        for o in &self.outputs {
            s += &output_markdown(self, o);
        }
        if let Some(v) = &self.verdicts {
            s += &v.markdown();
        }
        s
    }
}

/// One output: its facts, levels, variance methods and bands.
pub(super) fn output_markdown(r: &AnalysisReport, o: &OutputReport) -> String {
    let st = &o.statistics;
    let u = st.unit.as_str();
    let mut rows = vec![
        ("mean", with_unit(st.mean, u)),
        (
            "σ",
            st.sigma
                .map_or_else(|| st.variance_outcome.describe(), |x| format!("{} {u}", sig4(x))),
        ),
    ];
    if let Some(mc) = &o.monte_carlo {
        rows.push(("σ Monte Carlo", monte_carlo_cell(mc, u)));
    }
    rows.push((
        "3σ bounds",
        format!("{} to {}", with_unit(o.lower_3sigma, u), with_unit(o.upper_3sigma, u)),
    ));
    if let (Some((a, b)), Some(v)) = (r.band_rad_s, o.band_sigma) {
        let hz = |w: f64| sig4(w / (2.0 * std::f64::consts::PI));
        rows.push(("σ in the band", format!("{} {u} ({}–{} Hz)", sig4(v), hz(a), hz(b))));
    }
    rows.push(("ν0+ (zero up-crossings)", with_unit(st.zero_upcrossing_rate, "1/s")));
    rows.push(("bandwidth ε", with_unit(st.bandwidth, "")));
    rows.push(("expected largest peak", with_unit(o.expected_largest_peak, u)));
    let mut s = format!("\n## Output `{}` [{u}]\n\n{}", st.name, facts(&rows));
    if !o.levels.is_empty() {
        let col =
            |f: &dyn Fn(&crate::study::analysis::LevelRow) -> Option<f64>| o.levels.iter().map(f).collect::<Vec<_>>();
        let t = Table::default()
            .num(&format!("level [{u}]"), &col(&|l| Some(l.level)))
            .num("up-crossings [1/s]", &col(&|l| l.upcrossing_rate))
            .num(
                &format!("P(exceed in {})", EverydayUnit::HOUR.show(r.duration_s)),
                &col(&|l| l.exceedance_probability),
            );
        s += &format!("\n{}", t.markdown());
    }
    s += &format!("\n{}", methods_table(st).markdown());
    if let Some(b) = &o.bands {
        s += &bands_markdown(b);
    }
    s
}

fn monte_carlo_cell(mc: &crate::study::analysis::MonteCarloColumn, u: &str) -> String {
    match (&mc.sigma, mc.covered) {
        (Some(iv), Some(c)) => format!(
            "{} {u} [{}, {}] ({} %, {} realizations, {}); covers the analytic σ: {}",
            sig4(iv.estimate),
            sig4(iv.lower),
            sig4(iv.upper),
            num(100.0 * iv.confidence),
            mc.realizations,
            mc.method,
            if c { "yes" } else { "NO" }
        ),
        _ => format!("— {}", mc.note.as_deref().unwrap_or("")),
    }
}

/// Every variance method: value (`~` not converged, parentheses unreliable), error estimate, difference.
fn methods_table(st: &ResponseStatistics) -> Table {
    let numbers: Vec<Option<f64>> = st
        .methods
        .iter()
        .map(|m| match &m.outcome {
            Outcome::Value { value, .. } | Outcome::Unreliable { value, .. } => Some(*value),
            Outcome::NotConverged { estimate, .. } => Some(*estimate),
            _ => None,
        })
        .collect();
    let written = crate::numbers::sig_column(&numbers);
    let value = |i: usize| match &st.methods[i].outcome {
        Outcome::Value { .. } => written[i].clone(),
        Outcome::NotConverged { .. } => format!("~{}", written[i]),
        Outcome::Unreliable { .. } => format!("({})", written[i]),
        Outcome::Divergent { .. } => "infinite".into(),
        _ => "—".into(),
    };
    let note = |o: &Outcome| match o {
        Outcome::Value { .. } => String::new(),
        Outcome::Divergent { reason } | Outcome::NotApplicable { reason } => reason.clone(),
        Outcome::NotConverged { reason, .. } => format!("not converged: {reason}"),
        Outcome::Unreliable { reason, .. } => format!("unreliable, not used: {reason}"),
        Outcome::Failed { reason } => format!("failed: {reason}"),
    };
    let error = |o: &Outcome| match o {
        Outcome::Value { error_estimate, .. } => *error_estimate,
        Outcome::NotConverged { error_estimate, .. } => Some(*error_estimate),
        _ => None,
    };
    Table::default()
        .text("variance method", st.methods.iter().map(|m| m.method.name()))
        .raw(
            &format!("variance [{}]", squared(&st.unit)),
            (0..st.methods.len()).map(value),
        )
        .num(
            "error est.",
            &st.methods.iter().map(|m| error(&m.outcome)).collect::<Vec<_>>(),
        )
        .num("rel. diff", &st.methods.iter().map(|m| m.rel_diff).collect::<Vec<_>>())
        .text("note", st.methods.iter().map(|m| note(&m.outcome)))
}

fn bands_markdown(b: &BandSection) -> String {
    let Some(t) = &b.table else {
        return format!("\nbands: — {}\n", b.note.as_deref().unwrap_or(""));
    };
    let col = |f: &dyn Fn(&crate::comfort::BandRow) -> f64| t.rows.iter().map(|r| Some(f(r))).collect::<Vec<_>>();
    let table = Table::default()
        .text("band", t.rows.iter().map(|r| r.band.label()))
        .num("f_m [Hz]", &col(&|r| r.band.centre_hz))
        .num("f_1 [Hz]", &col(&|r| r.band.lower_hz))
        .num("f_2 [Hz]", &col(&|r| r.band.upper_hz))
        .num("r.m.s.", &col(&|r| r.rms))
        .num("mean square", &col(&|r| r.mean_square));
    let cover = t
        .coverage()
        .map_or(String::new(), |c| format!(" ({} % of σ²)", sig4(100.0 * c)));
    format!(
        "\nBand r.m.s. (IEC 61260-1 base 10): {}\n\n{}\nΣ band mean squares {}{cover}\n",
        t.chosen_by,
        table.markdown(),
        sig4(t.sum_mean_square)
    )
}

impl ToMarkdown for VerdictAnalysis {
    fn markdown(&self) -> String {
        let mut s = String::new();
        if let Some(c) = &self.comfort {
            s += &comfort_markdown(c);
        }
        if let Some(x) = &self.fatigue {
            s += &fatigue_markdown(x);
        }
        if let Some(x) = &self.seat_factor {
            s += &format!("\n## Seat factor\n\n```text\n{}\n```\n", x.lines().join("\n"));
        }
        s
    }
}

fn comfort_markdown(c: &ComfortVerdict) -> String {
    let (head, health_head) = vr::comfort_headings(c);
    let mut s = format!(
        "\n## {head}\n\n{}\n{}",
        vr::comfort_table(c).markdown(),
        bullets(&vr::comfort_lines(c))
    );
    s += &format!("\n## {health_head}\n\n");
    match &c.health {
        Some(h) => {
            s += &vr::health_table(h).markdown();
            let mut lines = vec![format!("dominant axis {}", h.dominant)];
            lines.extend(h.notes.iter().cloned());
            lines.extend(vr::health_lines(&h.verdict));
            s += &format!("\n{}", bullets(&lines));
        }
        None => s += &bullets(&[c.health_note.clone().unwrap_or_default()]),
    }
    s
}

fn fatigue_markdown(x: &FatigueVerdict) -> String {
    let mut s = format!(
        "\n## {}\n\n{}\n{}",
        vr::fatigue_heading(x),
        bullets(&vr::fatigue_lines(x)),
        vr::fatigue_table(x).markdown()
    );
    if let Some(v) = vr::fatigue_verdict_line(x) {
        s += &format!("\n{v}\n");
    }
    s
}

impl ToMarkdown for TablesReport {
    fn markdown(&self) -> String {
        let mut s = format!("# {}\n\n", self.title);
        let mut rows = vec![
            ("file", format!("`{}`", self.file)),
            ("kind", format!("{} ({})", self.kind, self.what)),
        ];
        if !self.description.is_empty() {
            rows.push(("about", self.description.clone()));
        }
        if let Some(n) = &self.note {
            rows.push(("note", n.clone()));
        }
        s += &facts(&rows);
        for t in &self.tables {
            s += &format!("\n## {}\n\n", t.title);
            let mut table = Table::default();
            for (j, c) in t.columns.iter().enumerate() {
                let head = if c.unit == "-" {
                    c.name.clone()
                } else {
                    format!("{} [{}]", c.name, c.unit)
                };
                let cells: Vec<&Cell> = t.rows.iter().filter_map(|r| r.get(j)).collect();
                table = if cells.iter().all(|c| matches!(c, Cell::Number(_))) {
                    let v: Vec<Option<f64>> = cells
                        .iter()
                        .map(|c| if let Cell::Number(x) = c { Some(*x) } else { None })
                        .collect();
                    table.num(&head, &v)
                } else {
                    let text = cells.iter().map(|c| match c {
                        Cell::Number(x) => sig4(*x),
                        Cell::Text(t) => t.clone(),
                    });
                    table.text(&head, text)
                };
            }
            s += &table.markdown();
            if let Some(n) = &t.note {
                s += &format!("\n{n}\n");
            }
        }
        s
    }
}

impl ToMarkdown for RoadReport {
    fn markdown(&self) -> String {
        let mut s = format!("# Road profile `{}`\n\n", self.file);
        s += &facts(&[
            ("samples", self.samples.to_string()),
            ("step", format!("{} m", sig4(self.step_m))),
            ("length", format!("{} m", sig4(self.length_m))),
            (
                "Welch segments",
                format!(
                    "{} samples, K = {}, ν = {}",
                    self.segment_len,
                    self.segments,
                    sig4(self.dof)
                ),
            ),
            ("detrend", format!("{:?}", self.detrend).to_lowercase()),
            ("confidence", format!("{} %", num(100.0 * self.confidence))),
        ]);
        for t in &self.tracks {
            s += &track_markdown(t);
        }
        if let Some((l, r)) = &self.coherence_tracks {
            let rows: Vec<&CoherenceRow> = self.coherence.iter().collect();
            let col = |f: fn(&CoherenceRow) -> f64| rows.iter().map(|r| Some(f(r))).collect::<Vec<_>>();
            let t = Table::default()
                .num("n [cycles/m]", &col(|r| r.n))
                .num("γ²", &col(|r| r.squared_coherence))
                .num("lower", &col(|r| r.lower))
                .num("upper", &col(|r| r.upper));
            s += &format!(
                "\n## Squared coherence of {l} and {r} (Fisher-z interval)\n\n{}",
                t.markdown()
            );
        }
        s
    }
}

fn track_markdown(t: &TrackReport) -> String {
    let fits = &t.fits;
    let col = |f: fn(&FitRow) -> f64| fits.iter().map(|r| Some(f(r))).collect::<Vec<_>>();
    let fit_table = Table::default()
        .text("ISO 8608 fit", fits.iter().map(|f| f.waviness_mode.clone()))
        .num("G_d(n0) [m³]", &col(|f| f.g0_m3))
        .num("lower", &col(|f| f.g0_interval.0))
        .num("upper", &col(|f| f.g0_interval.1))
        .num("w", &col(|f| f.waviness))
        .num("w lower", &col(|f| f.waviness_interval.0))
        .num("w upper", &col(|f| f.waviness_interval.1))
        .text("class", fits.iter().map(|f| f.class.clone()))
        .num("reduced χ²", &col(|f| f.reduced_chi2))
        .num("p (fit)", &col(|f| f.fit_p_value))
        .text(
            "power law",
            fits.iter()
                .map(|f| if f.describes_the_road { "fits" } else { "does NOT fit" }),
        );
    let d = &t.density;
    let dcol = |f: fn(&DensityRow) -> f64| d.iter().map(|r| Some(f(r))).collect::<Vec<_>>();
    let density = Table::default()
        .num("n [cycles/m]", &dcol(|r| r.n))
        .num("G_d [m³]", &dcol(|r| r.g_d))
        .num("lower", &dcol(|r| r.lower))
        .num("upper", &dcol(|r| r.upper));
    format!(
        "\n## Track {}\n\n{}\n{}\n### Density (every bin)\n\n{}",
        t.name,
        facts(&[
            ("σ", format!("{} m", sig4(t.sigma_m))),
            ("IRI (golden car, 80 km/h)", format!("{} m/km", sig4(t.iri_m_per_km))),
        ]),
        fit_table.markdown(),
        density.markdown()
    )
}

/// The `inspect` report of a run file as markdown: its settings, the statistics with their intervals and
/// analytic values, the density estimates and the rainflow histograms.
///
/// # Errors
/// As [`crate::store::RunFile::open_any`] and its readers.
pub fn inspect_markdown(path: &Path) -> Result<String> {
    let run = crate::store::RunFile::open_any(path)?;
    let info = run.info();
    let m = run.metadata();
    let mut s = format!("# Run file `{}`\n\n", path.display());
    let realizations = info.as_ref().map_or(m.n_realizations, |i| i.realizations.len());
    s += &facts(&[
        ("seed", m.seed.to_string()),
        ("generator", m.generator.clone()),
        ("Δt", format!("{} s", sig4(m.dt))),
        (
            "samples per realization",
            format!("{} ({} s)", m.n_samples, sig4(m.n_samples as f64 * m.dt)),
        ),
        ("realizations", realizations.to_string()),
        (
            "raw realizations",
            if m.store_raw { "stored" } else { "not stored" }.into(),
        ),
    ]);
    s += &statistics_markdown(&run.statistics()?);
    let psd = run.psd()?;
    if !psd.is_empty() {
        let _ = write!(s, "\n## Density estimates (two-sided S(ω))\n\n");
        let t = Table::default()
            .text("signal", psd.iter().map(|e| e.output.clone()))
            .raw("points", psd.iter().map(|e| e.omega.len()))
            .num(
                "ω low [rad/s]",
                &psd.iter().map(|e| e.omega.first().copied()).collect::<Vec<_>>(),
            )
            .num(
                "ω high [rad/s]",
                &psd.iter().map(|e| e.omega.last().copied()).collect::<Vec<_>>(),
            )
            .num("dof", &psd.iter().map(|e| Some(e.dof)).collect::<Vec<_>>())
            .text("method", psd.iter().map(|e| e.method.clone()));
        s += &t.markdown();
    }
    s += &rainflow_markdown(&run.rainflow()?);
    Ok(s)
}

fn statistics_markdown(stats: &[crate::store::OutputStatistics]) -> String {
    let rows: Vec<(&str, &crate::store::Statistic)> = stats
        .iter()
        .flat_map(|o| o.statistics.iter().map(move |x| (o.output.as_str(), x)))
        .collect();
    if rows.is_empty() {
        return String::new();
    }
    let col = |f: fn(&crate::store::Statistic) -> Option<f64>| rows.iter().map(|r| f(r.1)).collect::<Vec<_>>();
    let t = Table::default()
        .text("signal", rows.iter().map(|r| r.0))
        .text("statistic", rows.iter().map(|r| r.1.name.clone()))
        .num("estimate", &col(|x| Some(x.interval.estimate)))
        .num("lower", &col(|x| Some(x.interval.lower)))
        .num("upper", &col(|x| Some(x.interval.upper)))
        .num("confidence", &col(|x| Some(x.interval.confidence)))
        .num("analytic", &col(|x| x.analytic))
        .text(
            "covers",
            rows.iter()
                .map(|r| r.1.covers.map_or("—", |c| if c { "yes" } else { "NO" })),
        )
        .text("unit", rows.iter().map(|r| r.1.unit.clone()));
    format!("\n## Statistics\n\n{}", t.markdown())
}

fn rainflow_markdown(h: &[crate::store::RainflowHistogram]) -> String {
    if h.is_empty() {
        return String::new();
    }
    let t = Table::default()
        .text("signal", h.iter().map(|x| x.output.clone()))
        .raw("bins", h.iter().map(|x| x.counts.len()))
        .num(
            "top range",
            &h.iter().map(|x| x.edges.last().copied()).collect::<Vec<_>>(),
        )
        .text("unit", h.iter().map(|x| x.unit.clone()))
        .num(
            "cycles per realization",
            &h.iter().map(|x| Some(x.counts.iter().sum::<f64>())).collect::<Vec<_>>(),
        )
        .num("above the top", &h.iter().map(|x| Some(x.overflow)).collect::<Vec<_>>())
        .num(
            "Dirlik expects",
            &h.iter()
                .map(|x| x.dirlik.as_ref().map(|d| d.iter().sum::<f64>()))
                .collect::<Vec<_>>(),
        );
    format!("\n## Rainflow range histograms\n\n{}", t.markdown())
}
