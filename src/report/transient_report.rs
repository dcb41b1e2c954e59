//! What `stochvib transient` prints: the exact curves at a selection of the reported times, the expected
//! up-crossings and the extremes table of the mission, and with `--monte-carlo` the Monte Carlo σ(t) beside
//! the exact one with its verdict (every number in full in `--json`).

use super::table::{facts, Table};
use crate::numbers::short;
use crate::study::transient_answers::{MissionRow, OutputOverTime, StationaryExtremes, TransientAnalysis};
use crate::study::transient_mc::SigmaComparison;
use std::fmt;

/// Rows of a printed time table (the JSON has every reported time).
pub const PRINTED_ROWS: usize = 21;

/// Indices of at most `rows` evenly spread times of `n`, the first and the last among them.
pub fn printed_indices(n: usize, rows: usize) -> Vec<usize> {
    if n <= rows {
        return (0..n).collect();
    }
    let mut v: Vec<usize> = (0..rows).map(|k| (k * (n - 1) + (rows - 1) / 2) / (rows - 1)).collect();
    v.dedup();
    v
}

/// The time table of one output.
fn output_table(times: &[f64], o: &OutputOverTime) -> Table {
    let idx = printed_indices(times.len(), PRINTED_ROWS);
    // NaN (the evolutionary route where its assumption fails) prints as a dash
    let col =
        |v: &[f64]| -> Vec<Option<f64>> { idx.iter().map(|&k| v.get(k).copied().filter(|x| !x.is_nan())).collect() };
    let (sigma_head, mean_head) = match &o.weighted_of {
        Some(_) => (format!("a_w(t) [{}]", o.unit), format!("mean [{}]", o.unit)),
        None => (format!("σ(t) [{}]", o.unit), format!("mean(t) [{}]", o.unit)),
    };
    let mut t = Table::default()
        .num("t [s]", &col(times))
        .num(&mean_head, &col(&o.mean))
        .num(&sigma_head, &col(&o.sigma));
    if !o.nu0_plus.is_empty() {
        t = t.num("ν₀⁺(t) [Hz]", &col(&o.nu0_plus));
    }
    for (b, rates) in &o.upcrossing_rates {
        t = t.num(&format!("ν⁺({} {}) [Hz]", short(*b), o.unit), &col(rates));
    }
    t
}

impl fmt::Display for TransientAnalysis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "{}", self.title)?;
        writeln!(f, "  {}", self.description)?;
        writeln!(f, "  start: {:?}; {}", self.start, self.route)?;
        for o in &self.outputs {
            match &o.weighted_of {
                Some(a) => writeln!(f, "\n{} (ISO 2631-1 weighted {a}: running r.m.s. a_w(t))", o.name)?,
                None => writeln!(f, "\n{} [{}]", o.name, o.unit)?,
            }
            if o.sigma.is_empty() {
                writeln!(f, "  no finite σ: {}", o.note.as_deref().unwrap_or(""))?;
                continue;
            }
            if let Some(n) = &o.note {
                writeln!(f, "  {n}")?;
            }
            write!(f, "{}", output_table(&self.times, o).aligned("  "))?;
        }
        self.fmt_extremes(f)?;
        for n in &self.notes {
            writeln!(f, "note: {n}")?;
        }
        Ok(())
    }
}

impl TransientAnalysis {
    fn fmt_extremes(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(t) = self.stationary_table() {
            writeln!(f, "\n{}", self.stationary_heading())?;
            write!(f, "{}", t.aligned("  "))?;
        }
        if let Some(t) = self.mission_table() {
            writeln!(f, "\n{}", self.mission_heading())?;
            write!(f, "{}", t.aligned("  "))?;
        }
        Ok(())
    }

    fn stationary_heading(&self) -> String {
        format!(
            "Stationary extremes of max |y| over T = {} s (the system frozen at the window's end, in its \
             stationary state)",
            short(self.mission_duration)
        )
    }

    fn mission_heading(&self) -> String {
        format!(
            "Mission of T = {} s: expected up-crossings of +b and P(max |y| > b within T)",
            short(self.mission_duration)
        )
    }

    /// The stationary extremes of the outputs that have them (None: none has).
    fn stationary_table(&self) -> Option<Table> {
        let st: Vec<_> = self
            .stationary
            .iter()
            .filter_map(|(n, s)| s.as_ref().map(|s| (n, s)))
            .collect();
        if st.is_empty() {
            return None;
        }
        let pf =
            |p: Option<crate::extremes::PeakFactor>, s: &StationaryExtremes| p.map(|p| s.mean.abs() + p.mean * s.sigma);
        let col = |g: &dyn Fn(&StationaryExtremes) -> Option<f64>| st.iter().map(|s| g(s.1)).collect::<Vec<_>>();
        Some(
            Table::default()
                .text("output", st.iter().map(|s| s.0.clone()))
                .num("σ", &col(&|s| Some(s.sigma)))
                .num("ν₀⁺ [Hz]", &col(&|s| Some(s.nu0_plus)))
                .num("δ (Vanmarcke)", &col(&|s| Some(s.delta)))
                .num("E max|y| Davenport", &col(&|s| pf(s.davenport, s)))
                .num("E max|y| Der Kiureghian", &col(&|s| pf(s.der_kiureghian, s))),
        )
    }

    /// The mission table: E N⁺(b) and P(max |y| > b) by the integrated rate and the end-state methods.
    fn mission_table(&self) -> Option<Table> {
        let m = &self.mission;
        if m.is_empty() {
            return None;
        }
        let col = |g: &dyn Fn(&MissionRow) -> Option<f64>| m.iter().map(g).collect::<Vec<_>>();
        Some(
            Table::default()
                .text("output", m.iter().map(|r| r.output.clone()))
                .text("b", m.iter().map(|r| format!("{} {}", short(r.level), r.unit)))
                .num("E N⁺(b)", &col(&|r| Some(r.expected_upcrossings)))
                .num("P integrated rate", &col(&|r| Some(r.p_integrated_rate)))
                .num("P Poisson (stat.)", &col(&|r| r.p_poisson))
                .num("P Vanmarcke (stat.)", &col(&|r| r.p_vanmarcke))
                .num("P Der Kiureghian (stat.)", &col(&|r| r.p_der_kiureghian)),
        )
    }
}

/// The transient answers as a section of the hand-over report (`## Transient response and mission
/// extremes`): the exact route, per output its time table ([`PRINTED_ROWS`] times), the stationary
/// extremes, the mission table and the notes; the same tables as `stochvib transient`.
pub fn transient_markdown(a: &TransientAnalysis) -> String {
    let mut s = "## Transient response and mission extremes\n\n".to_string();
    s += &facts(&[
        ("system", a.description.clone()),
        ("start", format!("{:?}", a.start).to_lowercase()),
        (
            "exact route",
            format!(
                "{} steps ({} exact), {} matrix exponentials, accumulated relative error estimate {:.1e}",
                a.report.steps, a.report.exact_steps, a.report.exponentials, a.report.max_error_estimate
            ),
        ),
        ("mission duration T", format!("{} s", short(a.mission_duration))),
    ]);
    for o in &a.outputs {
        s += &match &o.weighted_of {
            Some(w) => format!("\n### {} (ISO 2631-1 weighted {w}: running r.m.s. a_w(t))\n\n", o.name),
            None => format!("\n### {} [{}]\n\n", o.name, o.unit),
        };
        if let Some(n) = &o.note {
            s += &format!("{n}\n\n");
        }
        if !o.sigma.is_empty() {
            s += &output_table(&a.times, o).markdown();
        }
    }
    if let Some(t) = a.stationary_table() {
        s += &format!(
            "\n### Stationary extremes\n\n{}\n\n{}",
            a.stationary_heading(),
            t.markdown()
        );
    }
    if let Some(t) = a.mission_table() {
        s += &format!("\n### Mission\n\n{}\n\n{}", a.mission_heading(), t.markdown());
    }
    s += &a.notes.iter().map(|n| format!("\n- note: {n}")).collect::<String>();
    s + "\n"
}

/// The Monte Carlo σ(t) of every simulated output beside the analytic σ(t) of the route that produced it
/// (the column is headed `exact σ` or `evolutionary σ`), with the verdicts.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SigmaComparisons(pub Vec<SigmaComparison>);

impl fmt::Display for SigmaComparisons {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in &self.0 {
            writeln!(
                f,
                "\nMonte Carlo σ(t) of {} [{}], {} realizations, {} % intervals per time",
                c.output,
                c.unit,
                c.realizations,
                short(100.0 * c.confidence)
            )?;
            let idx = printed_indices(c.rows.len(), PRINTED_ROWS);
            let col = |g: fn(&(f64, f64, f64, f64, f64)) -> f64| -> Vec<Option<f64>> {
                idx.iter().map(|&k| Some(g(&c.rows[k]))).collect()
            };
            let t = Table::default()
                .num("t [s]", &col(|r| r.0))
                .num(&format!("{} σ", c.route), &col(|r| r.1))
                .num("Monte Carlo σ", &col(|r| r.2))
                .num("lower", &col(|r| r.3))
                .num("upper", &col(|r| r.4))
                .text(
                    "covers",
                    idx.iter().map(|&k| {
                        let r = &c.rows[k];
                        if r.3 <= r.1 && r.1 <= r.4 || r.1 == r.2 {
                            "yes"
                        } else {
                            "no"
                        }
                    }),
                );
            write!(f, "{}", t.aligned("  "))?;
            writeln!(
                f,
                "  per-time intervals cover the {} σ at {} % of the {} times",
                c.route,
                short(100.0 * c.coverage),
                c.rows.len()
            )?;
            writeln!(f, "  verdict: {}", c.verdict())?;
        }
        Ok(())
    }
}
