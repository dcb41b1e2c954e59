//! The `book` report: every worked example of the sources, printed value against computed value.

use serde::Serialize;

/// Differences above this relative size need a one-line explanation in the report.
pub const EXPLAIN_ABOVE: f64 = 0.02;

/// One line of the `book` report.
#[derive(Debug, Clone, Serialize)]
pub struct BookRow {
    /// Which worked example, with source and section, e.g. `Sukharev 8.6, Example 8.1 (conveyor idler)`.
    pub example: String,
    /// What is compared, e.g. `sigma_y`.
    pub quantity: String,
    /// SI unit of both values.
    pub unit: String,
    /// Value printed in the source, converted to SI (None when the source prints none).
    pub printed: Option<f64>,
    /// Value computed by stochvib (None when infinite/undefined; `explanation` says why).
    pub computed: Option<f64>,
    /// One line: why printed and computed differ by more than [`EXPLAIN_ABOVE`] (misprint, convention,
    /// unprinted parameter with the assumption stated, invalid approximation), or how it was computed.
    pub explanation: String,
}

impl BookRow {
    /// Relative difference (computed − printed)/printed.
    pub fn rel_diff(&self) -> Option<f64> {
        match (self.printed, self.computed) {
            (Some(p), Some(c)) if p != 0.0 => Some((c - p) / p),
            _ => None,
        }
    }
}

/// The whole `book` report.
#[derive(Debug, Clone, Serialize)]
pub struct BookReport {
    /// Every row, grouped by example in source order.
    pub rows: Vec<BookRow>,
}

/// Builds the report from every catalogue model's worked examples.
pub fn book_report() -> BookReport {
    BookReport {
        rows: crate::models::book_rows(),
    }
}

impl BookReport {
    /// Rows whose relative difference exceeds [`EXPLAIN_ABOVE`] but carry no explanation (must be empty).
    pub fn unexplained(&self) -> Vec<&BookRow> {
        self.rows
            .iter()
            .filter(|r| r.rel_diff().is_some_and(|d| d.abs() > EXPLAIN_ABOVE) && r.explanation.trim().is_empty())
            .collect()
    }
}

fn cell(v: Option<f64>) -> String {
    v.map(crate::error::num).unwrap_or_else(|| "—".into())
}

impl std::fmt::Display for BookReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut last = "";
        for r in &self.rows {
            if r.example != last {
                writeln!(f, "\n{}", r.example)?;
                writeln!(
                    f,
                    "  {:<34} {:<9} {:>12} {:>12} {:>9}  explanation",
                    "quantity", "unit", "printed", "computed", "rel.diff"
                )?;
                last = &r.example;
            }
            let d = r
                .rel_diff()
                .map(|d| format!("{:+.1}%", 100.0 * d))
                .unwrap_or_else(|| "—".into());
            writeln!(
                f,
                "  {:<34} {:<9} {:>12} {:>12} {:>9}  {}",
                r.quantity,
                r.unit,
                cell(r.printed),
                cell(r.computed),
                d,
                r.explanation
            )?;
        }
        Ok(())
    }
}
