//! What every record reader yields: the channels with their units, the sample rate and how it was
//! established, and the samples block by block in SI units.

use crate::error::{Error, Result};
use crate::units::Dim;
use std::path::{Path, PathBuf};

/// One channel (column, dataset or WAV channel) of a record.
///
/// # Formula
/// value in SI = value as stored × `to_si`; `dim` is the SI dimension of the unit as written (m/s² has
/// m s^-2, rad/s² has s^-2, MPa has m^-1 kg s^-2, µm/m is dimensionless).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Channel {
    /// Name, e.g. `seat_z`.
    pub name: String,
    /// The unit as written in the file or given on the command line, e.g. `m/s^2`, `mm/s^2`, `MPa`.
    pub unit: String,
    /// Factor from the stored value to SI.
    pub to_si: f64,
    /// SI dimension.
    #[serde(skip)]
    pub dim: Dim,
}

/// How the sample rate of a record was established.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeBase {
    /// A time column, checked row by row (its name and unit).
    TimeColumn(String),
    /// Stated on the command line (`--sample-rate`).
    Stated,
    /// A `sample_rate` attribute of the HDF5 datasets.
    Attribute(String),
    /// The WAV header.
    WavHeader,
}

impl std::fmt::Display for TimeBase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TimeBase::TimeColumn(name) => write!(f, "from the time column `{name}`"),
            TimeBase::Stated => write!(f, "as stated: --sample-rate, or fs from Python"),
            TimeBase::Attribute(dataset) => write!(f, "from the `sample_rate` attribute of {dataset} or its group"),
            TimeBase::WavHeader => write!(f, "from the WAV header"),
        }
    }
}

/// The description of a record: its file, channels and sample rate.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RecordInfo {
    /// The file.
    pub source: PathBuf,
    /// The format: `CSV`, `HDF5`, `WAV`.
    pub format: &'static str,
    /// Sample rate f_s, Hz.
    pub sample_rate_hz: f64,
    /// How f_s was established.
    pub time_base: TimeBase,
    /// The channels, in file order (the time column excluded).
    pub channels: Vec<Channel>,
    /// Samples per channel: exact for HDF5 and WAV (from the header), an estimate from the file size and the
    /// first rows for CSV; used to choose segment lengths before the record has been read.
    pub samples_hint: Option<usize>,
}

impl RecordInfo {
    /// The index of the channel named `name`.
    ///
    /// # Errors
    /// [`Error::File`] naming the record and listing its channels.
    pub fn channel(&self, name: &str) -> Result<usize> {
        self.channels.iter().position(|c| c.name == name).ok_or_else(|| {
            Error::in_file(
                &self.source,
                "channel",
                name,
                format!(
                    "no such channel; the record has {}",
                    self.channels
                        .iter()
                        .map(|c| format!("`{}`", c.name))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })
    }

    /// Checks that channel `index` has dimension `dim` (its unit written as `what`, e.g. an acceleration).
    ///
    /// # Errors
    /// [`Error::File`] naming the record, the channel and its unit.
    pub fn require_dim(&self, index: usize, dim: Dim, what: &str) -> Result<()> {
        let c = &self.channels[index];
        if c.dim == dim {
            return Ok(());
        }
        Err(Error::in_file(
            &self.source,
            format!("channel `{}`", c.name),
            format!("[{}]", c.unit),
            format!(
                "the unit has dimension {}, but {what} is needed (dimension {dim})",
                c.dim
            ),
        ))
    }
}

/// A record read block by block: memory is one block, whatever the record's length.
pub trait RecordReader {
    /// The record's description.
    fn info(&self) -> &RecordInfo;

    /// Reads the next samples of every channel, at most `max` per channel, into `out[c]` (cleared first), in
    /// SI units. Returns the number of samples per channel read, 0 at the end of the record.
    ///
    /// # Errors
    /// A malformed part of the file, named by line (CSV), dataset (HDF5) or frame (WAV), with its value and
    /// the reason.
    fn read_block(&mut self, out: &mut [Vec<f64>], max: usize) -> Result<usize>;
}

/// Options of [`open_record`]: what the file itself does not say.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RecordOptions {
    /// Sample rate stated by the user, Hz (required without a time column; checked against one).
    pub sample_rate_hz: Option<f64>,
    /// Units given for channels whose header has none, or for every WAV channel: (channel, unit).
    pub units: Vec<(String, String)>,
    /// CSV: the decimal separator is a comma (`1,25`); the field delimiter must then be `;` or a tab.
    pub decimal_comma: bool,
    /// HDF5: the datasets to read (paths); empty: every one-dimensional numeric dataset of the root group.
    pub datasets: Vec<String>,
    /// WAV: the channel names, one per channel (default `ch1`, `ch2`, …).
    pub channel_names: Vec<String>,
    /// WAV: the physical value of full scale (sample value 1.0 of a float file, the largest integer of an
    /// integer file), with its unit, e.g. `50 m/s^2`.
    pub full_scale: Option<String>,
}

/// Opens a record by its extension: `.csv`, `.txt` ([`super::csv::CsvRecord`]), `.h5`, `.hdf5`
/// ([`super::hdf5::Hdf5Record`]), `.wav` ([`super::wav::WavRecord`]).
///
/// # Errors
/// An unknown extension (naming the accepted ones); the errors of the readers.
pub fn open_record(path: &Path, options: &RecordOptions) -> Result<Box<dyn RecordReader>> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "csv" | "txt" | "tsv" => Ok(Box::new(super::csv::CsvRecord::open(path, options)?)),
        "h5" | "hdf5" => Ok(Box::new(super::hdf5::Hdf5Record::open(path, options)?)),
        "wav" => Ok(Box::new(super::wav::WavRecord::open(path, options)?)),
        _ => Err(Error::in_file(
            path,
            "extension",
            format!(".{ext}"),
            "unknown record format: a record is a CSV (.csv, .txt, .tsv), HDF5 (.h5, .hdf5) or WAV (.wav) file",
        )),
    }
}

/// The unit of a channel parsed into (factor to SI, dimension), with `g` refused (the gram in this
/// toolkit's units) in favour of `gn` (standard gravity 9.806 65 m/s², ISO 80000-3).
///
/// # Errors
/// The reason, as text (the caller names the file and the channel).
pub fn parse_unit(unit: &str) -> std::result::Result<(f64, Dim), String> {
    let u = unit.trim();
    if u.is_empty() {
        return Err("empty unit".into());
    }
    if u == "gn" || u == "g_n" || u == "g0" {
        return Ok((9.806_65, Dim::ACCELERATION));
    }
    if u == "g" || u == "G" {
        return Err(
            "`g` is ambiguous (gram or standard gravity): write `gn` for standard gravity 9.80665 m/s^2, or m/s^2"
                .into(),
        );
    }
    if u == "1" || u == "-" {
        return Ok((1.0, Dim::DIMENSIONLESS));
    }
    if let Some(f) = micro_strain(u) {
        return Ok((f, Dim::DIMENSIONLESS));
    }
    match crate::units::parse_quantity(&format!("1 {u}")) {
        Ok((v, d)) => Ok((v, d)),
        Err(Error::Unit { reason, .. }) => Err(reason),
        Err(e) => Err(e.to_string()),
    }
}

/// Strain units: `ustrain`, `µstrain`, `microstrain` (10⁻⁶), `strain` (1).
fn micro_strain(u: &str) -> Option<f64> {
    match u {
        "ustrain" | "µstrain" | "μstrain" | "microstrain" | "µε" | "με" => Some(1e-6),
        "strain" => Some(1.0),
        _ => None,
    }
}

/// A channel from its name and unit text; `file` and `key` name it in the error.
///
/// # Errors
/// [`Error::File`] with the reason of [`parse_unit`].
pub fn channel(file: &Path, key: &str, name: &str, unit: &str) -> Result<Channel> {
    let (to_si, dim) = parse_unit(unit).map_err(|r| Error::in_file(file, key, format!("[{unit}]"), r))?;
    Ok(Channel {
        name: name.to_string(),
        unit: unit.trim().to_string(),
        to_si,
        dim,
    })
}

/// Checks a stated sample rate: finite and > 0.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `--sample-rate`.
pub fn check_rate(rate_hz: f64) -> Result<f64> {
    if rate_hz.is_finite() && rate_hz > 0.0 {
        Ok(rate_hz)
    } else {
        Err(Error::invalid(
            "--sample-rate",
            rate_hz,
            "a sample rate must be finite and > 0 Hz",
        ))
    }
}

/// A quantity in a record's units, `"100 MPa"`, `"1500 ustrain"`, `"0.5 gn"`: (SI value, dimension), with the
/// units of [`parse_unit`]; `what` names it in the error (a flag).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `what` for a missing or non-finite number (also once converted to SI)
/// or an unknown unit.
///
/// # Examples
/// ```
/// use stochvib::record::parse_quantity;
/// use stochvib::units::Dim;
/// assert_eq!(parse_quantity("100 MPa", "--sn-amplitude").unwrap(), (1e8, Dim::new(-1, 1, -2)));
/// assert_eq!(parse_quantity("100MPa", "--sn-amplitude").unwrap().0, 1e8);
/// assert!(parse_quantity("100", "--sn-amplitude").is_err());
/// ```
pub fn parse_quantity(text: &str, what: &str) -> Result<(f64, Dim)> {
    let t = text.trim();
    // the number, then the unit with or without a space (`100 MPa`, `100MPa`), as the scenario's quantities
    let (number, unit) = crate::units::split_number(t).map_or((t, ""), |(n, u)| (n, u.trim()));
    let v: f64 = number
        .parse()
        .map_err(|_| Error::invalid(what, text, "expected a number and a unit, e.g. `100 MPa`"))?;
    if !v.is_finite() {
        return Err(Error::invalid(what, text, "the number must be finite"));
    }
    if unit.is_empty() {
        return Err(Error::invalid(
            what,
            text,
            "a unit is required (e.g. `100 MPa`, `800 ustrain`): never guessed",
        ));
    }
    let (to_si, dim) = parse_unit(unit).map_err(|r| Error::invalid(what, text, r))?;
    if !(v * to_si).is_finite() {
        return Err(Error::invalid(
            what,
            text,
            format!("in SI units ({unit} is {to_si:e} SI) the value is beyond the range of f64"),
        ));
    }
    Ok((v * to_si, dim))
}
