//! Worked examples of the source documents: one row per printed number, with the value stochvib computes
//! and, where they differ by more than [`EXPLAIN_ABOVE`], the reason. Every catalogue model contributes its
//! rows; the `book` report ([`crate::report::book`]) prints them.

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

/// Every catalogue model's worked-example rows for the `book` report, in source order.
pub fn book_rows() -> Vec<BookRow> {
    let mut rows = Vec::new();
    rows.extend(super::balancer_bogie::book_rows());
    rows.extend(super::conveyor_idler::book_rows());
    rows.extend(super::scraper::book_rows());
    rows.extend(super::isolation::book_rows());
    rows.extend(super::half_car::book_rows());
    rows.extend(super::operator_seat::book_rows());
    rows.extend(super::three_mass_hoist::book_rows());
    rows.extend(super::dynamic_stiffness_chain::book_rows());
    rows.extend(super::mine_hoist::book_rows());
    rows
}
