//! What `stochvib transient` prints: the exact curves at a selection of the reported times, the expected
//! up-crossings and the extremes table of the mission, and with `--monte-carlo` the Monte Carlo σ(t) beside
//! the exact one with its verdict (every number in full in `--json`).

use super::table::Table;
use crate::numbers::short;
use crate::study::transient_answers::{OutputOverTime, TransientAnalysis};
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
        let st: Vec<_> = self
            .stationary
            .iter()
            .filter_map(|(n, s)| s.as_ref().map(|s| (n, s)))
            .collect();
        if !st.is_empty() {
            writeln!(
                f,
                "\nStationary extremes of max |y| over T = {} s (the system frozen at the window's end, in its \
                 stationary state)",
                short(self.mission_duration)
            )?;
            let pf = |p: Option<crate::extremes::PeakFactor>,
                      s: &crate::study::transient_answers::StationaryExtremes| {
                p.map(|p| s.mean.abs() + p.mean * s.sigma)
            };
            let t = Table::default()
                .text("output", st.iter().map(|s| s.0.clone()))
                .num("σ", &st.iter().map(|s| Some(s.1.sigma)).collect::<Vec<_>>())
                .num("ν₀⁺ [Hz]", &st.iter().map(|s| Some(s.1.nu0_plus)).collect::<Vec<_>>())
                .num("δ (Vanmarcke)", &st.iter().map(|s| Some(s.1.delta)).collect::<Vec<_>>())
                .num(
                    "E max|y| Davenport",
                    &st.iter().map(|s| pf(s.1.davenport, s.1)).collect::<Vec<_>>(),
                )
                .num(
                    "E max|y| Der Kiureghian",
                    &st.iter().map(|s| pf(s.1.der_kiureghian, s.1)).collect::<Vec<_>>(),
                );
            write!(f, "{}", t.aligned("  "))?;
        }
        if self.mission.is_empty() {
            return Ok(());
        }
        writeln!(
            f,
            "\nMission of T = {} s: expected up-crossings of +b and P(max |y| > b within T)",
            short(self.mission_duration)
        )?;
        let m = &self.mission;
        let t = Table::default()
            .text("output", m.iter().map(|r| r.output.clone()))
            .text("b", m.iter().map(|r| format!("{} {}", short(r.level), r.unit)))
            .num(
                "E N⁺(b)",
                &m.iter().map(|r| Some(r.expected_upcrossings)).collect::<Vec<_>>(),
            )
            .num(
                "P integrated rate",
                &m.iter().map(|r| Some(r.p_integrated_rate)).collect::<Vec<_>>(),
            )
            .num("P Poisson (stat.)", &m.iter().map(|r| r.p_poisson).collect::<Vec<_>>())
            .num(
                "P Vanmarcke (stat.)",
                &m.iter().map(|r| r.p_vanmarcke).collect::<Vec<_>>(),
            )
            .num(
                "P Der Kiureghian (stat.)",
                &m.iter().map(|r| r.p_der_kiureghian).collect::<Vec<_>>(),
            );
        write!(f, "{}", t.aligned("  "))
    }
}

/// The Monte Carlo σ(t) of every simulated output beside the exact σ(t), with the verdicts.
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
                .num("exact σ", &col(|r| r.1))
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
                "  per-time intervals cover the exact σ at {} % of the {} times",
                short(100.0 * c.coverage),
                c.rows.len()
            )?;
            writeln!(f, "  verdict: {}", c.verdict())?;
        }
        Ok(())
    }
}
