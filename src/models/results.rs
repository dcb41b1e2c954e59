//! Results of deterministic models (no random input): the natural frequencies, modes, static parts, time
//! maxima and harmonic responses that `stochvib analyze` prints for a deterministic scenario file, as plain
//! tables with named, unit-carrying columns (serialisable to JSON).

use crate::error::Result;
use serde::Serialize;
use std::fmt::Debug;

/// A model whose results are deterministic: the articles' hoists and chains.
///
/// # Examples
/// ```
/// use stochvib::models::{results::DeterministicModel, three_mass_hoist::ThreeMassHoist};
/// let tables = ThreeMassHoist::illustrative().results().unwrap();
/// assert_eq!(tables[0].columns[1].unit, "rad/s");
/// ```
pub trait DeterministicModel: Debug + Send + Sync {
    /// One line: model, parameters, source.
    fn description(&self) -> String;
    /// Every result of the model, as tables.
    ///
    /// # Errors
    /// A numerical failure of the model's computations (e.g. a singular matrix).
    fn results(&self) -> Result<Vec<ResultTable>>;
}

/// A column of a [`ResultTable`]: a quantity and its SI unit (`-` for labels and dimensionless numbers).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Column {
    /// Name, e.g. `omega`.
    pub name: String,
    /// SI unit, e.g. `rad/s`.
    pub unit: String,
}

/// One cell: a number in its column's unit, or a label.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Cell {
    /// A value in the column's unit.
    Number(f64),
    /// A label (row name, method).
    Text(String),
}

impl From<f64> for Cell {
    fn from(v: f64) -> Self {
        Cell::Number(v)
    }
}

impl From<&str> for Cell {
    fn from(v: &str) -> Self {
        Cell::Text(v.to_string())
    }
}

impl From<String> for Cell {
    fn from(v: String) -> Self {
        Cell::Text(v)
    }
}

/// A titled table of results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResultTable {
    /// What the table shows, with the source equations.
    pub title: String,
    /// The columns.
    pub columns: Vec<Column>,
    /// The rows, one cell per column.
    pub rows: Vec<Vec<Cell>>,
    /// How the values were computed or checked.
    pub note: Option<String>,
}

impl ResultTable {
    /// An empty table with columns given as `(name, unit)`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::results::ResultTable;
    /// let mut t = ResultTable::new("Natural frequencies", &[("mode", "-"), ("omega", "rad/s")]);
    /// t.push(vec!["1".into(), 12.5.into()]);
    /// assert_eq!(t.rows.len(), 1);
    /// ```
    pub fn new(title: &str, columns: &[(&str, &str)]) -> Self {
        ResultTable {
            title: title.to_string(),
            columns: columns
                .iter()
                .map(|(n, u)| Column {
                    name: n.to_string(),
                    unit: u.to_string(),
                })
                .collect(),
            rows: Vec::new(),
            note: None,
        }
    }

    /// Appends a row (one cell per column).
    pub fn push(&mut self, row: Vec<Cell>) {
        debug_assert_eq!(row.len(), self.columns.len());
        self.rows.push(row);
    }

    /// Sets the note.
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.note = Some(note.into());
        self
    }
}
