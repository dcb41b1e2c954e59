//! Reference tables of the sources (`data/reference/`): the printed tables that the `book` report compares
//! with, transcribed exactly. They are not scenarios; `stochvib analyze` prints them as the tables they are.
//!
//! # Format
//! A root key `reference` names the table's kind: `sanitary-limits` (Sukharev 2012, Table 7.1; format of
//! [`SanitaryLimits::parse`]) or `scraper-table-8-1` (Sukharev 2012, Table 8.1; format of
//! [`parse_table_8_1`]).

use crate::error::{Error, Result};
use crate::models::operator_seat::SanitaryLimits;
use crate::models::results::{Cell, ResultTable};
use crate::models::scraper::parse_table_8_1;
use std::path::{Path, PathBuf};

/// The kinds of reference table, by the value of their `reference` key.
pub const REFERENCE_KINDS: &[&str] = &["sanitary-limits", "scraper-table-8-1"];

/// A reference table read from a file.
#[derive(Debug, Clone)]
pub struct ReferenceTable {
    /// The file.
    pub path: PathBuf,
    /// The `reference` key: the kind of table.
    pub reference: String,
    /// Title.
    pub title: String,
    /// Provenance.
    pub source: String,
    /// The table (in SI units).
    pub tables: Vec<ResultTable>,
}

impl ReferenceTable {
    /// Parses a reference file (`path` for messages).
    ///
    /// # Errors
    /// [`Error::Parse`], an unknown `reference` kind, or the table parser's [`Error::File`].
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let root: toml::Table = crate::fields::parse_toml(text, path)?;
        let get = |k: &str| root.get(k).and_then(|v| v.as_str()).unwrap_or("").to_string();
        let reference = get("reference");
        let tables = match reference.as_str() {
            "sanitary-limits" => {
                let lim = SanitaryLimits::parse(text, path)?;
                let mut t = ResultTable::new(
                    "Sanitary limits of vertical seat vibration per octave band (RMS)",
                    &[
                        ("centre", "Hz"),
                        ("acceleration", "m/s^2"),
                        ("acceleration level", "dB"),
                        ("velocity", "m/s"),
                        ("velocity level", "dB"),
                    ],
                )
                .with_note(format!(
                    "levels re {} m/s^2 and {} m/s (not printed in the source; these reproduce its dB columns)",
                    lim.reference_acceleration, lim.reference_velocity
                ));
                for b in &lim.bands {
                    t.push(vec![
                        b.centre_hz.into(),
                        b.acceleration.into(),
                        b.acceleration_db.into(),
                        b.velocity.into(),
                        b.velocity_db.into(),
                    ]);
                }
                vec![t]
            }
            "scraper-table-8-1" => {
                let (speeds, rows) = parse_table_8_1(text, path)?;
                let mut cols: Vec<(String, String)> = vec![
                    ("cab".into(), "-".into()),
                    ("output".into(), "-".into()),
                    ("unit".into(), "-".into()),
                ];
                for v in &speeds {
                    cols.push((format!("sigma at {v} m/s"), "row unit".into()));
                }
                let refs: Vec<(&str, &str)> = cols.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
                let mut t = ResultTable::new("Printed standard deviations of the scraper (Table 8.1)", &refs)
                    .with_note("printed values converted to SI (cm to m)");
                for r in &rows {
                    let (scale, unit) = if r.unit == "cm" {
                        (0.01, "m")
                    } else {
                        (1.0, r.unit.as_str())
                    };
                    let mut row: Vec<Cell> = vec![r.cab.clone().into(), r.output.clone().into(), unit.into()];
                    row.extend(r.values.iter().map(|v| Cell::from(v * scale)));
                    t.push(row);
                }
                vec![t]
            }
            other => {
                return Err(Error::File {
                    file: path.to_path_buf(),
                    key: "reference".into(),
                    value: other.to_string(),
                    reason: format!("unknown reference table; known: {}", REFERENCE_KINDS.join(", ")),
                })
            }
        };
        Ok(ReferenceTable {
            path: path.to_path_buf(),
            reference,
            title: get("title"),
            source: get("source"),
            tables,
        })
    }
}
