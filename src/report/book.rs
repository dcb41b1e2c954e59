//! The `book` report: every worked example of the sources, printed value against computed value.

use crate::models::worked_example::{BookRow, EXPLAIN_ABOVE};
use serde::Serialize;

/// The whole `book` report: the rows of every catalogue model's worked examples
/// ([`book_rows`](crate::models::worked_example::book_rows), which computes them).
#[derive(Debug, Clone, Serialize)]
pub struct BookReport {
    /// Every row, grouped by example in source order.
    pub rows: Vec<BookRow>,
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
    v.map(crate::numbers::num).unwrap_or_else(|| "—".into())
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
