//! A report table built column by column, written as aligned text or as a markdown (GitHub pipe) table.
//!
//! # Formula
//! Numeric columns hold [`REPORT_SIGNIFICANT`](crate::numbers::REPORT_SIGNIFICANT) significant figures in one
//! notation per column ([`sig_column`]): fixed when every value of the column is between 10⁻³ and 10⁴ in
//! magnitude, scientific otherwise; a missing value is `—`. Text columns are left-aligned, numeric ones
//! right-aligned (markdown: `---:`).

use crate::numbers::sig_column;

/// How a report is printed: `--format text|markdown|json` (`--json` is `--format json`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum ReportFormat {
    /// Aligned plain text (the default).
    #[default]
    Text,
    /// Markdown: headings and pipe tables, to paste into a report or an issue.
    Markdown,
    /// JSON: every field, full precision.
    Json,
}

/// A table: a header per column and the cells, column by column.
///
/// # Examples
/// ```
/// use stochvib::report::table::Table;
/// let t = Table::default()
///     .text("axis", ["x", "z"])
///     .num("a_w [m/s²]", &[Some(0.4123), Some(12.0)]);
/// assert_eq!(t.markdown(), "| axis | a_w [m/s²] |\n|---|---:|\n| x | 0.4123 |\n| z | 12.00 |\n");
/// assert_eq!(t.aligned("  "), "  axis  a_w [m/s²]\n  x         0.4123\n  z          12.00\n");
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    heads: Vec<String>,
    numeric: Vec<bool>,
    cells: Vec<Vec<String>>,
}

impl Table {
    /// Adds a left-aligned text column.
    pub fn text<S: ToString>(mut self, head: &str, cells: impl IntoIterator<Item = S>) -> Self {
        self.heads.push(head.to_string());
        self.numeric.push(false);
        self.cells.push(cells.into_iter().map(|c| c.to_string()).collect());
        self
    }

    /// Adds a right-aligned numeric column, written by [`sig_column`].
    pub fn num(mut self, head: &str, values: &[Option<f64>]) -> Self {
        self.heads.push(head.to_string());
        self.numeric.push(true);
        self.cells.push(sig_column(values));
        self
    }

    /// Adds a right-aligned column of numbers (or words) formatted by the caller, e.g. counts.
    pub fn raw<S: ToString>(mut self, head: &str, cells: impl IntoIterator<Item = S>) -> Self {
        self.heads.push(head.to_string());
        self.numeric.push(true);
        self.cells.push(cells.into_iter().map(|c| c.to_string()).collect());
        self
    }

    /// Number of rows (the longest column).
    pub fn rows(&self) -> usize {
        self.cells.iter().map(Vec::len).max().unwrap_or(0)
    }

    fn cell(&self, col: usize, row: usize) -> &str {
        self.cells[col].get(row).map_or("", String::as_str)
    }

    /// The table as aligned text, every line starting with `indent`.
    pub fn aligned(&self, indent: &str) -> String {
        let width = |j: usize| {
            (0..self.rows())
                .map(|i| self.cell(j, i).chars().count())
                .chain([self.heads[j].chars().count()])
                .max()
                .unwrap_or(0)
        };
        let widths: Vec<usize> = (0..self.heads.len()).map(width).collect();
        let line = |cells: Vec<&str>| {
            let parts: Vec<String> = cells
                .iter()
                .zip(&widths)
                .zip(&self.numeric)
                .map(|((c, w), num)| if *num { format!("{c:>w$}") } else { format!("{c:<w$}") })
                .collect();
            format!("{indent}{}\n", parts.join("  ").trim_end())
        };
        let mut out = line(self.heads.iter().map(String::as_str).collect());
        for i in 0..self.rows() {
            out += &line((0..self.heads.len()).map(|j| self.cell(j, i)).collect());
        }
        out
    }

    /// The table as a markdown pipe table (`|` in a cell escaped).
    pub fn markdown(&self) -> String {
        let esc = |s: &str| s.replace('|', "\\|");
        let row = |cells: Vec<String>| format!("| {} |\n", cells.join(" | "));
        let mut out = row(self.heads.iter().map(|h| esc(h)).collect());
        let rule: Vec<&str> = self.numeric.iter().map(|n| if *n { "---:" } else { "---" }).collect();
        out += &format!("|{}|\n", rule.join("|"));
        for i in 0..self.rows() {
            out += &row((0..self.heads.len()).map(|j| esc(self.cell(j, i))).collect());
        }
        out
    }
}

/// A report written as markdown (`--format markdown`): headings, key–value lists and pipe tables.
pub trait ToMarkdown {
    /// The report as markdown text.
    fn markdown(&self) -> String;
}

/// A two-column markdown table of (quantity, value) pairs, the values as given.
///
/// # Examples
/// ```
/// use stochvib::report::table::facts;
/// assert_eq!(facts(&[("model", "quarter car".into())]), "| quantity | value |\n|---|---|\n| model | quarter car |\n");
/// ```
pub fn facts(rows: &[(&str, String)]) -> String {
    Table::default()
        .text("quantity", rows.iter().map(|r| r.0))
        .text("value", rows.iter().map(|r| r.1.clone()))
        .markdown()
}
