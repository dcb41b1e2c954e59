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
