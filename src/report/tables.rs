//! The `stochvib analyze` report of a deterministic model or a reference table: titled tables of results
//! with named, unit-carrying columns.

use crate::models::results::{Cell, ResultTable};
use crate::numbers::num;
use crate::scenario::{DeterministicScenario, ReferenceTable};
use serde::Serialize;
use std::fmt;

/// Tables of results read from, or computed for, one file.
#[derive(Debug, Clone, Serialize)]
pub struct TablesReport {
    /// `deterministic model` or `reference table`.
    pub what: String,
    /// Title of the file.
    pub title: String,
    /// The file.
    pub file: String,
    /// The model kind or the reference table's kind.
    pub kind: String,
    /// One line: the model with its parameters and source, or the table's source.
    pub description: String,
    /// A remark for the reader (e.g. what a reference table is used for).
    pub note: Option<String>,
    /// The tables.
    pub tables: Vec<ResultTable>,
}

/// The report of a deterministic scenario: its model's result tables `tables`
/// ([`crate::study::deterministic_tables`]).
pub fn deterministic_report(d: &DeterministicScenario, tables: Vec<ResultTable>) -> TablesReport {
    TablesReport {
        what: "deterministic model".into(),
        title: d.title.clone(),
        file: d.path.display().to_string(),
        kind: d.kind.clone(),
        description: d.model.description(),
        note: Some("no random input: the model's deterministic results (nothing to simulate)".into()),
        tables,
    }
}

/// The report of a reference table: the table as printed, in SI units.
pub fn reference_report(r: &ReferenceTable) -> TablesReport {
    TablesReport {
        what: "reference table".into(),
        title: r.title.clone(),
        file: r.path.display().to_string(),
        kind: r.reference.clone(),
        description: r.source.clone(),
        note: Some(
            "a table printed in the sources, transcribed exactly; not a scenario: `stochvib book` compares the \
             models with it"
                .into(),
        ),
        tables: r.tables.clone(),
    }
}

fn cell(c: &Cell) -> String {
    match c {
        Cell::Number(v) => num(*v),
        Cell::Text(t) => t.clone(),
    }
}

impl fmt::Display for TablesReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{:<9} {}  ({})",
            self.what.split(' ').next_back().unwrap_or(""),
            self.title,
            self.file
        )?;
        writeln!(f, "kind      {} ({})", self.kind, self.what)?;
        if !self.description.is_empty() {
            writeln!(f, "about     {}", self.description)?;
        }
        if let Some(n) = &self.note {
            writeln!(f, "note      {n}")?;
        }
        for t in &self.tables {
            writeln!(f)?;
            writeln!(f, "{}", t.title)?;
            let heads: Vec<String> = t
                .columns
                .iter()
                .map(|c| {
                    if c.unit == "-" {
                        c.name.clone()
                    } else {
                        format!("{} [{}]", c.name, c.unit)
                    }
                })
                .collect();
            let cells: Vec<Vec<String>> = t.rows.iter().map(|r| r.iter().map(cell).collect()).collect();
            let widths: Vec<usize> = (0..heads.len())
                .map(|j| {
                    cells
                        .iter()
                        .map(|r| r.get(j).map_or(0, |s| s.chars().count()))
                        .chain([heads[j].chars().count()])
                        .max()
                        .unwrap_or(0)
                })
                .collect();
            let line = |row: &[String]| {
                row.iter()
                    .zip(&widths)
                    .map(|(s, w)| format!("{s:>w$}", w = *w))
                    .collect::<Vec<_>>()
                    .join("  ")
            };
            writeln!(f, "  {}", line(&heads))?;
            for r in &cells {
                writeln!(f, "  {}", line(r))?;
            }
            if let Some(n) = &t.note {
                writeln!(f, "  ({n})")?;
            }
        }
        Ok(())
    }
}
