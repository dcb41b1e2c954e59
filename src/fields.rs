//! A TOML table reader that tracks which keys were asked for, converts physical values with units, and turns
//! every problem into an [`Error::File`] naming the file, the key, the value and the reason.

use crate::error::{Error, Result};
use crate::units::{self, Dim};
use std::cell::RefCell;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// How a model's table reader reads one numeric key (see [`Fields::read`]); the numeric builders of
/// parameter studies use it to read a swept value once, as the model's reader would.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KeyReading {
    /// A physical value of this dimension, SI number or string with a unit ([`Fields::quantity`]).
    Quantity(Dim),
    /// A frequency that must carry its unit, returned in rad/s or rad/m ([`Fields::angular_frequency`]).
    AngularFrequency(Dim),
    /// A plain finite number ([`Fields::number`]).
    Number,
}

/// The unit people write a duration or a distance in where it is not the SI one: a daily exposure in hours,
/// a design distance in kilometres. Keys read with it ([`Fields::everyday_quantity`]) refuse a bare number,
/// which would be read as seconds or metres (`exposure = 7` is 7 s, not 7 h).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EverydayUnit {
    /// The unit as written, e.g. `h`.
    pub symbol: &'static str,
    /// Its SI value (3600 for the hour, 1000 for the kilometre).
    pub si: f64,
    /// Its dimension.
    pub dim: Dim,
}

impl EverydayUnit {
    /// The hour: daily exposures, design lives, durations of a verdict.
    pub const HOUR: EverydayUnit = EverydayUnit {
        symbol: "h",
        si: 3600.0,
        dim: Dim::TIME,
    };
    /// The kilometre: design distances.
    pub const KILOMETRE: EverydayUnit = EverydayUnit {
        symbol: "km",
        si: 1000.0,
        dim: Dim::LENGTH,
    };

    /// An SI value written in this unit with up to 4 significant figures ([`crate::numbers::short`]), e.g.
    /// `0.008333 h`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fields::EverydayUnit;
    /// assert_eq!(EverydayUnit::HOUR.show(30.0), "0.008333 h");
    /// assert_eq!(EverydayUnit::HOUR.show(6.0 * 3600.0), "6 h");
    /// assert_eq!(EverydayUnit::KILOMETRE.show(2e8), "200000 km");
    /// ```
    pub fn show(&self, si_value: f64) -> String {
        format!("{} {}", crate::numbers::short(si_value / self.si), self.symbol)
    }
}

/// Largest input file read (scenario, spectrum, reference and limits files), bytes: the TOML kind of the
/// input rule ([`crate::io_rules::TOML_INPUT`]).
pub const MAX_INPUT_FILE_BYTES: u64 = 16 << 20;

/// Reads a text input file under the input rule ([`crate::io_rules::read_text`] with
/// [`crate::io_rules::TOML_INPUT`]): a regular file of at most [`MAX_INPUT_FILE_BYTES`], valid UTF-8.
/// FIFOs, devices and directories are refused before anything is read, so `/dev/zero` or a pipe cannot
/// hang the reader.
///
/// # Errors
/// [`Error::Io`] if the file cannot be opened; [`Error::Parse`] naming the file for a non-regular file, a
/// file that is too large, or text that is not UTF-8 (without echoing its content).
pub fn read_text_file(path: &Path) -> Result<String> {
    crate::io_rules::read_text(path, crate::io_rules::TOML_INPUT)
}

/// Parses TOML text read from `path`. The error names the line and column and the parser's reason, but
/// does not echo the file's content (a file that is not TOML may hold anything).
///
/// # Errors
/// [`Error::Parse`] naming the file.
pub fn parse_toml(text: &str, path: &Path) -> Result<toml::Table> {
    toml::from_str(text).map_err(|e: toml::de::Error| {
        let at = e
            .span()
            .map(|s| {
                let before = &text[..s.start.min(text.len())];
                let line = before.matches('\n').count() + 1;
                let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
                format!(" at line {line}, column {col}")
            })
            .unwrap_or_default();
        Error::Parse {
            file: path.to_path_buf(),
            reason: format!("not a valid TOML file{at}: {}", e.message().trim()),
        }
    })
}

thread_local! {
    /// The (file, dotted key path) queried on this thread while recording ([`record_keys`]); `None` when off.
    static QUERIED_KEYS: RefCell<Option<BTreeSet<(PathBuf, String)>>> = const { RefCell::new(None) };
}

/// Test hook for the key reference: `record_keys(true)` starts recording, on this thread, the file and the
/// dotted path of every key a [`Fields`] reader asks for (array indices written `[]`: `input[].spectrum`);
/// `record_keys(false)` stops and returns what was recorded. Off by default: a query then costs one
/// thread-local read.
#[doc(hidden)]
pub fn record_keys(on: bool) -> BTreeSet<(PathBuf, String)> {
    QUERIED_KEYS.with(|k| std::mem::replace(&mut *k.borrow_mut(), on.then(BTreeSet::new)).unwrap_or_default())
}

/// `input[2].road` → `input[].road`.
fn without_indices(path: &str) -> String {
    let mut out = String::with_capacity(path.len());
    let mut in_index = false;
    for c in path.chars() {
        match c {
            '[' => in_index = true,
            ']' => {
                in_index = false;
                out.push_str("[]");
            }
            _ if in_index => {}
            _ => out.push(c),
        }
    }
    out
}

/// A TOML table being read from a file.
#[derive(Debug)]
pub struct Fields<'a> {
    file: PathBuf,
    prefix: String,
    table: &'a toml::Table,
    used: RefCell<BTreeSet<String>>,
}

impl<'a> Fields<'a> {
    /// Wraps `table` read from `file`; `prefix` is the dotted path of the table ("" at the root).
    pub fn new(file: &Path, prefix: &str, table: &'a toml::Table) -> Self {
        Fields {
            file: file.to_path_buf(),
            prefix: prefix.to_string(),
            table,
            used: RefCell::new(BTreeSet::new()),
        }
    }

    /// The file being read.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// Dotted path of `key` inside the file.
    pub fn path(&self, key: &str) -> String {
        if self.prefix.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.prefix)
        }
    }

    /// An [`Error::File`] for `key` with `value` and `reason`.
    pub fn error(&self, key: &str, value: impl std::fmt::Display, reason: impl Into<String>) -> Error {
        Error::File {
            file: self.file.clone(),
            key: self.path(key),
            value: crate::io_rules::excerpt(&value.to_string()),
            reason: reason.into(),
        }
    }

    /// Wraps any crate error raised while using `key` so that it names the file and key.
    pub fn wrap(&self, key: &str, e: Error) -> Error {
        match e {
            Error::File { .. } => e,
            other => {
                // a key the constructor says is missing (a required value that no key gave) stays `<missing>`
                let missing = matches!(&other, Error::InvalidParameter { value, .. } if value == "<missing>");
                let value = self
                    .lookup(key)
                    .map(|v| v.to_string())
                    .unwrap_or_else(|| if missing { "<missing>" } else { "<derived>" }.into());
                self.error(key, value, other.to_string())
            }
        }
    }

    /// Wraps a constructor's [`Error::InvalidParameter`] so that it names the file key of the same name as the
    /// parameter (constructors name their parameters after the file keys); any other error, and a parameter
    /// that is no key of the table (a value derived from other keys, e.g. the times of a constant
    /// acceleration, or a default of absent keys) is attributed to `fallback` when the table has it. A
    /// parameter the constructor reports as `<missing>` keeps its name.
    pub fn wrap_param(&self, e: Error, fallback: &str) -> Error {
        let key = match &e {
            // the edges of a `band = [low, high]` key
            Error::InvalidParameter { name, .. } if name == "band.low" => "band[0]".to_string(),
            Error::InvalidParameter { name, .. } if name == "band.high" => "band[1]".to_string(),
            Error::InvalidParameter { name, value, .. }
                if value == "<missing>" || self.lookup(name).is_some() || self.table.get(fallback).is_none() =>
            {
                name.clone()
            }
            _ => fallback.to_string(),
        };
        self.wrap(&key, e)
    }

    /// The value of `key` in the table: a key, `name[i]` (an element of the array `name`), or a dotted path
    /// of these into nested tables (`axle[1].track_width`).
    fn lookup(&self, key: &str) -> Option<&'a toml::Value> {
        if let Some(v) = self.table.get(key) {
            return Some(v);
        }
        let step = |t: &'a toml::Table, part: &str| -> Option<&'a toml::Value> {
            match part.strip_suffix(']').and_then(|p| p.split_once('[')) {
                Some((name, i)) => t.get(name)?.as_array()?.get(i.parse::<usize>().ok()?),
                None => t.get(part),
            }
        };
        let mut parts = key.split('.');
        let mut v = step(self.table, parts.next()?)?;
        for part in parts {
            v = step(v.as_table()?, part)?;
        }
        Some(v)
    }

    /// The raw value of `key`, marking it used.
    pub fn get(&self, key: &str) -> Option<&'a toml::Value> {
        QUERIED_KEYS.with(|k| {
            if let Some(keys) = k.borrow_mut().as_mut() {
                keys.insert((self.file.clone(), without_indices(&self.path(key))));
            }
        });
        self.used.borrow_mut().insert(key.to_string());
        self.table.get(key)
    }

    /// A required raw value.
    ///
    /// # Errors
    /// Missing key.
    pub fn require(&self, key: &str) -> Result<&'a toml::Value> {
        self.get(key)
            .ok_or_else(|| self.error(key, "<missing>", "required key is missing"))
    }

    /// A required string.
    ///
    /// # Errors
    /// Missing key or not a string.
    pub fn string(&self, key: &str) -> Result<&'a str> {
        let v = self.require(key)?;
        v.as_str().ok_or_else(|| self.error(key, v, "expected a string"))
    }

    /// An optional string.
    ///
    /// # Errors
    /// Present but not a string.
    pub fn opt_string(&self, key: &str) -> Result<Option<&'a str>> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => v
                .as_str()
                .map(Some)
                .ok_or_else(|| self.error(key, v, "expected a string")),
        }
    }

    /// A required physical value of dimension `dim`: a number (already SI) or a string with units.
    ///
    /// # Errors
    /// Missing key, wrong type, unknown unit, wrong dimension, non-finite value.
    pub fn quantity(&self, key: &str, dim: Dim) -> Result<f64> {
        let v = self.require(key)?;
        units::parse_value(v, dim).map_err(|reason| self.error(key, v, reason))
    }

    /// An optional physical value of dimension `dim`.
    ///
    /// # Errors
    /// As [`Fields::quantity`] when present.
    pub fn opt_quantity(&self, key: &str, dim: Dim) -> Result<Option<f64>> {
        match self.get(key) {
            None => Ok(None),
            Some(_) => self.quantity(key, dim).map(Some),
        }
    }

    /// A required duration or distance written with its unit (`"7 h"`, `"30 min"`, `"200000 km"`), returned in
    /// SI (s, m). A bare number is refused, with the fix in the message: where people think in hours or
    /// kilometres, `exposure = 7` read as 7 s would be a silently wrong verdict.
    ///
    /// # Errors
    /// Missing key, bare number (the reason shows `key = "<number> <unit>"`), unknown unit, wrong dimension.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fields::{EverydayUnit, Fields};
    /// let t: toml::Table = toml::from_str("exposure = \"90 min\"\nlife = 7").unwrap();
    /// let f = Fields::new(std::path::Path::new("s.toml"), "analysis", &t);
    /// assert_eq!(f.everyday_quantity("exposure", EverydayUnit::HOUR).unwrap(), 5400.0);
    /// let e = f.everyday_quantity("life", EverydayUnit::HOUR).unwrap_err().to_string();
    /// assert!(e.contains("analysis.life") && e.contains("life = \"7 h\""), "{e}");
    /// ```
    pub fn everyday_quantity(&self, key: &str, unit: EverydayUnit) -> Result<f64> {
        let v = self.require(key)?;
        if let Some(x) = v.as_float().or_else(|| v.as_integer().map(|i| i as f64)) {
            let si = match unit.dim {
                d if d == Dim::TIME => "s",
                d if d == Dim::LENGTH => "m",
                _ => "SI units",
            };
            return Err(self.error(
                key,
                v,
                format!(
                    "a bare number has no unit here (it would be read as {x} {si}, i.e. {}): write the unit, e.g. \
                     {key} = \"{x} {}\" (or \"{x} {si}\" if {si} were meant)",
                    unit.show(x),
                    unit.symbol
                ),
            ));
        }
        self.quantity(key, unit.dim)
    }

    /// As [`Fields::everyday_quantity`] for an optional key.
    ///
    /// # Errors
    /// As [`Fields::everyday_quantity`] when present.
    pub fn opt_everyday_quantity(&self, key: &str, unit: EverydayUnit) -> Result<Option<f64>> {
        match self.get(key) {
            None => Ok(None),
            Some(_) => self.everyday_quantity(key, unit).map(Some),
        }
    }

    /// Refuses an SI value `value` of `key` below `minimum` (both in SI), naming the value as written and
    /// in `unit`, with `why` the reason the bound holds.
    ///
    /// # Errors
    /// [`Error::File`] when `value < minimum`.
    pub fn at_least(&self, key: &str, value: f64, minimum: f64, unit: EverydayUnit, why: &str) -> Result<()> {
        if value >= minimum {
            return Ok(());
        }
        let written = self
            .table
            .get(key)
            .map_or_else(|| "<derived>".to_string(), |v| v.to_string());
        Err(self.error(
            key,
            format!("{written} = {}", unit.show(value)),
            format!("implausible: less than {} ({why})", unit.show(minimum)),
        ))
    }

    /// A frequency-like value that must carry its unit (`Hz`, `rad/s`, `cycles/m`, `rad/m`): a bare number
    /// is rejected because it would be ambiguous between cyclic and angular units. Returns rad/s or rad/m.
    ///
    /// # Errors
    /// Missing key, bare number, unknown unit, wrong dimension.
    pub fn angular_frequency(&self, v: &toml::Value, key: &str, dim: Dim) -> Result<f64> {
        match v.as_str() {
            Some(_) => units::parse_value(v, dim).map_err(|reason| self.error(key, v, reason)),
            None => Err(self.error(
                key,
                v,
                "a frequency must carry its unit (e.g. \"2 Hz\", \"12 rad/s\", \"0.1 cycles/m\", \"0.6 rad/m\"): a bare \
                 number would be ambiguous between cyclic and angular frequency",
            )),
        }
    }

    /// A required array of plain numbers.
    ///
    /// # Errors
    /// Missing key, not an array, non-numeric or non-finite entries.
    pub fn numbers(&self, key: &str) -> Result<Vec<f64>> {
        let v = self.require(key)?;
        let arr = v
            .as_array()
            .ok_or_else(|| self.error(key, v, "expected an array of numbers"))?;
        arr.iter()
            .enumerate()
            .map(|(i, x)| {
                let f = x.as_float().or_else(|| x.as_integer().map(|n| n as f64));
                match f {
                    Some(f) => crate::units::check_magnitude(f).map_err(|r| self.error(&format!("{key}[{i}]"), x, r)),
                    None => Err(self.error(&format!("{key}[{i}]"), x, "expected a finite number")),
                }
            })
            .collect()
    }

    /// A required plain number (dimensionless, or a density whose convention is named elsewhere).
    ///
    /// # Errors
    /// Missing key, not a finite number.
    pub fn number(&self, key: &str) -> Result<f64> {
        self.number_in(key, "")
    }

    /// A required plain number whose unit is fixed by the format (`unit`, e.g. `(rad/m)·m^a`; empty for a
    /// dimensionless number): a quantity with a unit is refused saying that the key takes the number alone,
    /// in that unit.
    ///
    /// # Errors
    /// Missing key, not a finite number.
    ///
    /// # Examples
    /// ```
    /// let t: toml::Table = toml::from_str("omega_p = \"1 rad/m\"").unwrap();
    /// let f = stochvib::fields::Fields::new(std::path::Path::new("s.toml"), "road.coherence", &t);
    /// let e = f.number_in("omega_p", "(rad/m)·m^a").unwrap_err().to_string();
    /// assert!(e.contains("without a unit") && e.contains("(rad/m)·m^a"), "{e}");
    /// ```
    pub fn number_in(&self, key: &str, unit: &str) -> Result<f64> {
        let v = self.require(key)?;
        match v.as_float().or_else(|| v.as_integer().map(|n| n as f64)) {
            Some(f) => crate::units::check_magnitude(f).map_err(|r| self.error(key, v, r)),
            None => match v.as_str() {
                Some(t) if crate::units::parse_quantity(t).is_ok() => {
                    let what = if unit.is_empty() {
                        "a plain (dimensionless) number".to_string()
                    } else {
                        format!("a plain number in {unit}")
                    };
                    Err(self.error(
                        key,
                        v,
                        format!("`{key}` is {what}, written without a unit (a unit text is not read here)"),
                    ))
                }
                _ => Err(self.error(key, v, "expected a finite number")),
            },
        }
    }

    /// The value of `key` read as `reading` says (what a model's table reader does for that key).
    ///
    /// # Formula
    /// [`KeyReading::Quantity`]: [`Fields::quantity`]; [`KeyReading::AngularFrequency`]:
    /// [`Fields::angular_frequency`] (rad/s from `Hz` or `rad/s`); [`KeyReading::Number`]: [`Fields::number`].
    ///
    /// # Errors
    /// Those of the reader named by `reading`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fields::{Fields, KeyReading};
    /// use stochvib::units::Dim;
    /// let t: toml::Table = toml::from_str("omega2 = \"1 Hz\"\nzeta2 = 0.3").unwrap();
    /// let f = Fields::new(std::path::Path::new("s.toml"), "model", &t);
    /// let w = f.read("omega2", KeyReading::AngularFrequency(Dim::FREQUENCY)).unwrap();
    /// assert!((w - 2.0 * std::f64::consts::PI).abs() < 1e-15);
    /// assert_eq!(f.read("zeta2", KeyReading::Number).unwrap(), 0.3);
    /// ```
    pub fn read(&self, key: &str, reading: KeyReading) -> Result<f64> {
        match reading {
            KeyReading::Quantity(dim) => self.quantity(key, dim),
            KeyReading::AngularFrequency(dim) => {
                let v = self.require(key)?;
                self.angular_frequency(v, key, dim)
            }
            KeyReading::Number => self.number(key),
        }
    }

    /// A required sub-table.
    ///
    /// # Errors
    /// Missing key or not a table.
    pub fn table(&self, key: &str) -> Result<&'a toml::Table> {
        let v = self.require(key)?;
        v.as_table().ok_or_else(|| self.error(key, v, "expected a table"))
    }

    /// A [`Fields`] reader of the required sub-table `key` (dotted path `prefix.key`).
    ///
    /// # Errors
    /// Missing key or not a table.
    pub fn sub(&self, key: &str) -> Result<Fields<'a>> {
        let t = self.table(key)?;
        Ok(Fields::new(&self.file, &self.path(key), t))
    }

    /// A required matrix written as an array of rows of plain (SI) numbers.
    ///
    /// # Errors
    /// Missing key, not an array of rows, rows of different lengths, non-finite entries.
    pub fn matrix(&self, key: &str) -> Result<nalgebra::DMatrix<f64>> {
        let rows = self.number_rows(key)?;
        let ncols = rows.first().map_or(0, Vec::len);
        if let Some(i) = rows.iter().position(|r| r.len() != ncols) {
            return Err(self.error(
                &format!("{key}[{i}]"),
                rows[i].len(),
                "rows must all have the same length",
            ));
        }
        let data: Vec<f64> = rows.concat();
        Ok(nalgebra::DMatrix::from_row_slice(rows.len(), ncols, &data))
    }

    /// A required array of rows of finite numbers; the rows may differ in length (e.g. the numerators of
    /// several inputs).
    ///
    /// # Errors
    /// Missing key, not an array of arrays, an entry that is not a finite number (named `key[i][j]`).
    pub fn number_rows(&self, key: &str) -> Result<Vec<Vec<f64>>> {
        let v = self.require(key)?;
        let rows = v
            .as_array()
            .ok_or_else(|| self.error(key, v, "expected an array of rows"))?;
        rows.iter()
            .enumerate()
            .map(|(i, r)| {
                let r = r
                    .as_array()
                    .ok_or_else(|| self.error(&format!("{key}[{i}]"), r, "expected a row (array of numbers)"))?;
                r.iter()
                    .enumerate()
                    .map(|(j, x)| {
                        x.as_float()
                            .or_else(|| x.as_integer().map(|n| n as f64))
                            .ok_or_else(|| self.error(&format!("{key}[{i}][{j}]"), x, "expected a finite number"))
                            .and_then(|v| {
                                crate::units::check_magnitude(v)
                                    .map_err(|r| self.error(&format!("{key}[{i}][{j}]"), x, r))
                            })
                    })
                    .collect()
            })
            .collect()
    }

    /// The keys of the table as written, with their values, in the table's order.
    pub fn entries(&self) -> impl Iterator<Item = (&'a String, &'a toml::Value)> + use<'a> {
        self.table.iter()
    }

    /// Fails on any key that was never read: catches typos such as `alpah`.
    ///
    /// # Errors
    /// The first unknown key.
    pub fn finish(&self) -> Result<()> {
        let used = self.used.borrow();
        for (k, v) in self.table {
            if !used.contains(k) {
                let mut known: Vec<&str> = used.iter().map(|s| s.as_str()).collect();
                known.sort();
                return Err(self.error(k, v, format!("unknown key (known keys here: {})", known.join(", "))));
            }
        }
        Ok(())
    }
}
