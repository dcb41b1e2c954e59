//! Measured road profiles: uniformly sampled tracks, their CSV import and export, explicit resampling.

use super::Detrend;
use crate::error::{Error, Result};
use crate::numbers::num;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// One measured track (wheel path): a name and the elevations in m at the profile's sample points.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    /// Column name, e.g. `left`.
    pub name: String,
    /// Elevations in m, one per sample.
    pub elevation_m: Vec<f64>,
}

/// The kind of file [`Profile::write_csv`] writes, for the output rule ([`crate::io_rules::check_output`]):
/// a profile CSV as this toolkit writes it (`#` comment lines, then the header `distance [`).
pub const PROFILE_CSV: crate::io_rules::OutputKind = crate::io_rules::OutputKind {
    what: "profile CSV",
    recognizes: is_profile_csv,
    replaceable: false,
};

/// Whether the first line of `path` after its `#` comments (within its first 64 KiB) is a distance header.
fn is_profile_csv(path: &Path) -> bool {
    use std::io::Read;
    let Ok((file, _)) = crate::io_rules::open_input(path, crate::io_rules::CSV_INPUT) else {
        return false;
    };
    let mut head = Vec::new();
    if file.take(1 << 16).read_to_end(&mut head).is_err() {
        return false;
    }
    String::from_utf8_lossy(&head)
        .lines()
        .find(|l| !l.trim_start().starts_with('#'))
        .is_some_and(|l| l.trim_start_matches('\u{feff}').starts_with("distance ["))
}

/// A length unit accepted in a CSV header (`[m]`, `[mm]`, …).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LengthUnit {
    /// Kilometre (distance column only).
    Km,
    /// Metre.
    M,
    /// Centimetre.
    Cm,
    /// Millimetre.
    Mm,
    /// Micrometre, written `um`, `µm` or `μm`.
    Um,
}

impl LengthUnit {
    /// Parses a unit symbol: `km`, `m`, `cm`, `mm`, `um`, `µm`, `μm` (case-sensitive).
    ///
    /// # Errors
    /// [`Error::Unit`] for anything else, listing the accepted symbols.
    pub fn parse(symbol: &str) -> Result<Self> {
        match symbol.trim() {
            "km" => Ok(LengthUnit::Km),
            "m" => Ok(LengthUnit::M),
            "cm" => Ok(LengthUnit::Cm),
            "mm" => Ok(LengthUnit::Mm),
            "um" | "µm" | "μm" => Ok(LengthUnit::Um),
            other => Err(Error::Unit {
                text: other.to_string(),
                reason: "unknown length unit; accepted: m, cm, mm, um (µm), and km for the distance".into(),
            }),
        }
    }

    /// The symbol written in headers: `km`, `m`, `cm`, `mm`, `um`.
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Km => "km",
            LengthUnit::M => "m",
            LengthUnit::Cm => "cm",
            LengthUnit::Mm => "mm",
            LengthUnit::Um => "um",
        }
    }

    /// A value in this unit converted to m (one correctly rounded multiplication or division by a power
    /// of ten).
    ///
    /// # Formula
    /// km: v·10³, m: v, cm: v/10², mm: v/10³, um: v/10⁶.
    pub fn to_m(self, v: f64) -> f64 {
        match self {
            LengthUnit::Km => v * 1e3,
            LengthUnit::M => v,
            LengthUnit::Cm => v / 1e2,
            LengthUnit::Mm => v / 1e3,
            LengthUnit::Um => v / 1e6,
        }
    }

    /// A value in m converted to this unit (inverse of [`LengthUnit::to_m`]).
    pub fn from_m(self, v: f64) -> f64 {
        match self {
            LengthUnit::Km => v / 1e3,
            LengthUnit::M => v,
            LengthUnit::Cm => v * 1e2,
            LengthUnit::Mm => v * 1e3,
            LengthUnit::Um => v * 1e6,
        }
    }
}

/// Options of the CSV reader.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CsvReadOptions {
    /// Largest distance of a sample from the uniform grid d₀ + k·h, relative to the step h (default 0.01:
    /// printed distances rounded to 1 % of a step still pass; anything coarser must be resampled
    /// explicitly).
    pub step_tolerance: f64,
    /// Fewest data rows accepted (default 2, the minimum that defines a step).
    pub min_rows: usize,
}

impl Default for CsvReadOptions {
    fn default() -> Self {
        CsvReadOptions {
            step_tolerance: 0.01,
            min_rows: 2,
        }
    }
}

/// Options of the CSV writer.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvWriteOptions {
    /// Unit of the distance column (default m).
    pub distance_unit: LengthUnit,
    /// Unit of the elevation columns (default m).
    pub elevation_unit: LengthUnit,
    /// Digits after the decimal point of the distance, in its unit; `None` (default) writes the shortest
    /// text that reads back to the same f64.
    pub distance_decimals: Option<usize>,
    /// Digits after the decimal point of the elevations, in their unit; `None` (default) as above.
    pub elevation_decimals: Option<usize>,
    /// Comment lines written first, each prefixed with `# `.
    pub comments: Vec<String>,
}

impl Default for CsvWriteOptions {
    fn default() -> Self {
        CsvWriteOptions {
            distance_unit: LengthUnit::M,
            elevation_unit: LengthUnit::M,
            distance_decimals: None,
            elevation_decimals: None,
            comments: Vec::new(),
        }
    }
}

/// A road profile as read from a file, before the check of a uniform step: distances and tracks as
/// given. [`RawProfile::to_uniform`] checks the step; [`RawProfile::resample_to`] interpolates onto a
/// uniform grid explicitly.
///
/// # Formula
/// CSV layout (comma-separated, UTF-8):
/// ```text
/// # comment lines start with '#' (leading blanks allowed); empty lines are skipped
/// distance [m], left [mm], right [mm]        header: first non-comment line, every column `name [unit]`
/// 0.00, 1.234, -0.567                        data: distance first, then one value per track
/// ```
/// Units: distance m, cm, mm, um or km; elevations m, cm, mm, um. Values are converted to m by
/// [`LengthUnit::to_m`].
///
/// # Errors
/// [`RawProfile::parse_csv`] returns [`Error::File`] naming the file, the line and column (as the key),
/// the value and the reason for: no header, a column without `[unit]`, an unknown unit, an empty or
/// repeated column name, fewer than 2 columns, a row with the wrong number of values, a blank, NaN,
/// infinite or unparsable value, a distance that does not increase, fewer rows than required.
///
/// # Examples
/// ```
/// use stochvib::road::{CsvReadOptions, RawProfile};
/// use std::path::Path;
/// let text = "# two tracks\ndistance [m], left [mm], right [mm]\n0.0, 1.0, 2.0\n0.1, 1.5, 2.5\n0.25, 1.0, 1.0\n";
/// let raw = RawProfile::parse_csv(text, Path::new("demo.csv"), &CsvReadOptions::default()).unwrap();
/// assert_eq!(raw.tracks[1].elevation_m[1], 0.0025);
/// // the step is not uniform (0.1 then 0.15): to_uniform refuses, naming the line
/// let err = raw.to_uniform(0.01).unwrap_err().to_string();
/// assert!(err.contains("demo.csv") && err.contains("line"), "{err}");
/// // explicit resampling is offered instead
/// let p = raw.resample_to(0.05).unwrap();
/// assert_eq!(p.len(), 6);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RawProfile {
    /// The file the profile came from (for messages).
    pub source: PathBuf,
    /// Distances in m, strictly increasing.
    pub distance_m: Vec<f64>,
    /// The tracks, elevations in m.
    pub tracks: Vec<Track>,
    /// Header of the distance column as written, e.g. `distance [m]`.
    pub distance_header: String,
    /// The line number (1-based) of each data row.
    pub lines: Vec<usize>,
}

/// Splits `name [unit]` into (name, unit).
fn parse_header_cell(cell: &str) -> Option<(&str, &str)> {
    let cell = cell.trim();
    let open = cell.rfind('[')?;
    let rest = cell[open + 1..].strip_suffix(']')?;
    Some((cell[..open].trim(), rest.trim()))
}
/// The first row that is neither empty nor a comment: its line number and its text, without a UTF-8
/// byte-order mark (spreadsheet exports), which is not part of the first column's name.
///
/// # Errors
/// No such row; the reader's errors.
fn header_row<R: std::io::BufRead>(
    lines: &mut crate::io_rules::BoundedLines<R>,
    file: &Path,
) -> Result<(usize, String)> {
    loop {
        match lines.next_line()? {
            None => {
                return Err(Error::in_file(
                    file,
                    "header",
                    "<missing>",
                    "no header row: the file has only comments or empty lines; expected e.g. \
                     `distance [m], left [mm], right [mm]`",
                ))
            }
            Some((i, l)) if !skipped(l) => return Ok((i, l.strip_prefix('\u{feff}').unwrap_or(l).to_string())),
            Some(_) => {}
        }
    }
}

/// The columns of a profile as its rows are read: the distance in m, each track's elevation in m, and the
/// line of each row.
struct Columns {
    distance_m: Vec<f64>,
    values: Vec<Vec<f64>>,
    row_lines: Vec<usize>,
}

impl Columns {
    /// Adds the row `row` of line `line`, its cells in the header's units (`header`: the cells and units).
    ///
    /// # Errors
    /// A row of another number of values than the header, a value that is not a number, a distance that does
    /// not increase.
    fn push_row(&mut self, line: usize, row: &str, header: (&[&str], &[LengthUnit]), file: &Path) -> Result<()> {
        let (cells, units) = header;
        let ncol = cells.len();
        let fields: Vec<&str> = row.split(',').collect();
        if fields.len() != ncol {
            return Err(Error::in_file(
                file,
                format!("line {line}"),
                row.trim(),
                format!(
                    "{} values; the header has {ncol} columns (is the file comma-separated, with no \
                 missing value?)",
                    fields.len()
                ),
            ));
        }
        for (c, field) in fields.iter().enumerate() {
            let key = || format!("line {line}, column {} `{}`", c + 1, cells[c].trim());
            let vm = units[c].to_m(parse_value(field, file, &key)?);
            if c == 0 {
                if let Some(&prev) = self.distance_m.last()
                    && vm <= prev
                {
                    return Err(Error::in_file(
                        file,
                        key(),
                        field.trim(),
                        format!(
                            "distance must increase strictly; the previous row (line {}) has {} m",
                            self.row_lines.last().copied().unwrap_or(0),
                            prev
                        ),
                    ));
                }
                self.distance_m.push(vm);
            } else {
                self.values[c - 1].push(vm);
            }
        }
        self.row_lines.push(line);
        Ok(())
    }
}

/// Whether a line is blank or a `#` comment.
fn skipped(line: &str) -> bool {
    let t = line.trim_start_matches('\u{feff}').trim();
    t.is_empty() || t.starts_with('#')
}

/// The header's cells and their units (the distance first), checked: at least two columns, each
/// `name [unit]` with a known unit (km for the distance only), names non-empty and distinct.
fn parse_header<'h>(header: &'h str, header_line: usize, file: &Path) -> Result<(Vec<&'h str>, Vec<LengthUnit>)> {
    let cells: Vec<&str> = header.split(',').collect();
    if cells.len() < 2 {
        return Err(Error::in_file(
            file,
            format!("line {header_line} (header)"),
            header.trim(),
            format!(
                "found {} column; need a distance column and at least one track, comma-separated, e.g. \
                 `distance [m], left [mm], right [mm]`",
                cells.len()
            ),
        ));
    }
    let mut names: Vec<&str> = Vec::with_capacity(cells.len());
    let mut units = Vec::with_capacity(cells.len());
    for (c, cell) in cells.iter().enumerate() {
        let key = format!("line {header_line} (header), column {}", c + 1);
        let (name, unit) = parse_header_cell(cell).ok_or_else(|| {
            Error::in_file(
                file,
                key.clone(),
                cell.trim(),
                "missing unit: write the column as `name [unit]` with unit m, cm, mm or um (distance also km)",
            )
        })?;
        if name.is_empty() {
            return Err(Error::in_file(file, key, cell.trim(), "empty column name"));
        }
        if names.contains(&name) {
            return Err(Error::in_file(
                file,
                key,
                cell.trim(),
                format!("column name `{name}` repeated"),
            ));
        }
        let u = LengthUnit::parse(unit).map_err(|e| {
            let reason = match e {
                Error::Unit { reason, .. } => reason,
                other => other.to_string(),
            };
            Error::in_file(file, key.clone(), cell.trim(), reason)
        })?;
        if c > 0 && u == LengthUnit::Km {
            return Err(Error::in_file(
                file,
                key,
                cell.trim(),
                "km is accepted for the distance only; elevations in m, cm, mm or um",
            ));
        }
        names.push(name);
        units.push(u);
    }
    Ok((cells, units))
}

/// One value of a data row: not blank, a number, finite.
fn parse_value(field: &str, file: &Path, key: &dyn Fn() -> String) -> Result<f64> {
    let t = field.trim();
    if t.is_empty() {
        return Err(Error::in_file(file, key(), "<blank>", "blank value"));
    }
    let v: f64 = t.parse().map_err(|_| Error::in_file(file, key(), t, "not a number"))?;
    if !v.is_finite() {
        return Err(Error::in_file(
            file,
            key(),
            t,
            "not finite (NaN or infinity); gaps must be filled or the profile split before import",
        ));
    }
    Ok(v)
}

/// The largest |elevation| of a profile read from a file, m: above it the sums of squares of a Welch density
/// (up to N² x² for N ≤ 10⁹ samples) or of a replayed response could leave the range of f64 (1.8·10³⁰⁸).
/// No road comes near it; such a value is a unit error or a corrupt file.
pub const MAX_ELEVATION_M: f64 = 1e100;

impl Track {
    /// The first sample larger in magnitude than [`MAX_ELEVATION_M`], with the reason to give (the caller
    /// names where it is: a file's line and column, or the track and the index).
    fn beyond_max_elevation(&self) -> Option<(usize, String)> {
        let k = self.elevation_m.iter().position(|v| v.abs() > MAX_ELEVATION_M)?;
        let why = format!(
            "larger in magnitude than {MAX_ELEVATION_M:e} m: the squared sums of a density or a response would \
             leave the range of f64; check the unit"
        );
        Some((k, why))
    }
}

impl RawProfile {
    /// Reads a CSV file (see the type's formula) under the input rule: a regular file of at most
    /// [`crate::io_rules::CSV_INPUT`]'s size (FIFOs, devices and directories refused before anything is
    /// read), line by line, each line at most [`crate::io_rules::MAX_LINE_BYTES`] long; memory holds the
    /// parsed numbers only, and the read stops with the numbers when they would take more than a quarter of
    /// the available memory.
    ///
    /// # Errors
    /// [`Error::Io`] if the file cannot be read; the refusals of [`crate::io_rules::open_input`];
    /// otherwise as [`RawProfile::parse_csv`].
    pub fn read_csv(path: &Path, options: &CsvReadOptions) -> Result<Self> {
        let (file, _) = crate::io_rules::open_input(path, crate::io_rules::CSV_INPUT)?;
        RawProfile::parse_reader(std::io::BufReader::with_capacity(1 << 16, file), path, options)
    }

    /// Parses CSV text; `file` names the source in error messages.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn parse_csv(text: &str, file: &Path, options: &CsvReadOptions) -> Result<Self> {
        RawProfile::parse_reader(text.as_bytes(), file, options)
    }

    /// Parses CSV read from `reader` one line at a time; `file` names the source in error messages.
    ///
    /// # Errors
    /// See the type's `# Errors`; a line longer than [`crate::io_rules::MAX_LINE_BYTES`]; numbers that would
    /// take more than a quarter of the available memory.
    pub fn parse_reader(reader: impl std::io::BufRead, file: &Path, options: &CsvReadOptions) -> Result<Self> {
        let mut lines = crate::io_rules::BoundedLines::new(reader, file);
        let (header_line, header) = header_row(&mut lines, file)?;
        let (cells, units) = parse_header(&header, header_line, file)?;
        let ncol = cells.len();
        let budget = crate::io_rules::available_memory().map_or(u128::MAX, |m| m / 4);
        let row_bytes = (8 * ncol + 8) as u128;
        let mut columns = Columns {
            distance_m: Vec::new(),
            values: vec![Vec::new(); ncol - 1],
            row_lines: Vec::new(),
        };
        while let Some((line, row)) = lines.next_line()? {
            if skipped(row) {
                continue;
            }
            if (columns.row_lines.len() as u128 + 1) * row_bytes > budget {
                return Err(Error::in_file(
                    file,
                    format!("line {line}"),
                    format!("{} rows", columns.row_lines.len()),
                    format!(
                        "the profile's numbers would take more than {} (a quarter of the available memory): split \
                         the record into sections, or resample it to a coarser step",
                        crate::io_rules::bytes_text(budget)
                    ),
                ));
            }
            columns.push_row(line, row, (&cells, &units), file)?;
        }
        let Columns {
            distance_m,
            values,
            row_lines,
        } = columns;
        let min_rows = options.min_rows.max(2);
        if distance_m.len() < min_rows {
            return Err(Error::in_file(
                file,
                "rows",
                distance_m.len().to_string(),
                format!("too few data rows: need at least {min_rows}"),
            ));
        }
        let tracks = cells[1..]
            .iter()
            .zip(values)
            .map(|(cell, elevation_m)| Track {
                name: parse_header_cell(cell).map_or_else(String::new, |(n, _)| n.to_string()),
                elevation_m,
            })
            .collect();
        Ok(RawProfile {
            source: file.to_path_buf(),
            distance_m,
            tracks,
            distance_header: cells[0].trim().to_string(),
            lines: row_lines,
        })
    }

    /// The uniformly sampled profile, after checking that every distance lies within `step_tolerance`·h
    /// of the grid d₀ + k·h, h = (d_last − d₀)/(N − 1). Never resamples.
    ///
    /// # Errors
    /// [`Error::File`] at the first row off the grid, naming its line, its distance, the step found there
    /// and the uniform step; an elevation beyond [`MAX_ELEVATION_M`] (its line and column); an invalid
    /// tolerance.
    pub fn to_uniform(&self, step_tolerance: f64) -> Result<Profile> {
        if !(step_tolerance.is_finite() && step_tolerance > 0.0) {
            return Err(Error::invalid(
                "step_tolerance",
                step_tolerance,
                "must be finite and > 0",
            ));
        }
        let n = self.distance_m.len();
        let d0 = self.distance_m[0];
        let h = (self.distance_m[n - 1] - d0) / (n - 1) as f64;
        for k in 1..n {
            let d = self.distance_m[k];
            let off = d - (d0 + k as f64 * h);
            if off.abs() > step_tolerance * h {
                let local = d - self.distance_m[k - 1];
                return Err(Error::in_file(
                    &self.source,
                    format!("line {}, column 1 `{}`", self.lines[k], self.distance_header),
                    format!("{d} m"),
                    format!(
                        "non-uniform step: the step found here is {} m (previous row at {} m) while the \
                         uniform step over the file is {} m; this row is {} m off the grid d0 + k·h \
                         (tolerance {step_tolerance}·h). Resample explicitly with `resample_to(step)` \
                         (linear interpolation) if that is acceptable",
                        num(local),
                        num(self.distance_m[k - 1]),
                        num(h),
                        num(off)
                    ),
                ));
            }
        }
        self.check_magnitudes()?;
        Profile::new(h, d0, self.tracks.clone())
    }

    /// Refuses an elevation larger in magnitude than [`MAX_ELEVATION_M`], naming its line and column.
    fn check_magnitudes(&self) -> Result<()> {
        for (t, tr) in self.tracks.iter().enumerate() {
            if let Some((k, why)) = tr.beyond_max_elevation() {
                return Err(Error::in_file(
                    &self.source,
                    format!("line {}, column {} `{}`", self.lines[k], t + 2, tr.name),
                    format!("{:e} m", tr.elevation_m[k]),
                    why,
                ));
            }
        }
        Ok(())
    }

    /// Linear interpolation of every track onto the uniform grid d₀ + k·`step_m`, k = 0.. while
    /// ≤ d_last. The explicit alternative to [`RawProfile::to_uniform`] for irregular data.
    ///
    /// # Formula
    /// ```text
    /// x_k = d₀ + k s,   y(x_k) = y_i + (y_{i+1} − y_i)(x_k − d_i)/(d_{i+1} − d_i),   d_i ≤ x_k ≤ d_{i+1}
    /// ```
    /// No anti-alias filter is applied: resampling to a coarser step folds the content above the new
    /// Nyquist frequency 1/(2s) into the band; linear interpolation also attenuates the content near the
    /// old Nyquist frequency (gain sinc² of the triangle kernel).
    ///
    /// # Errors
    /// `step_m` not finite and > 0; a grid of fewer than 2 points; an elevation beyond [`MAX_ELEVATION_M`]
    /// (its line and column).
    pub fn resample_to(&self, step_m: f64) -> Result<Profile> {
        crate::error::require_positive("step", step_m)?;
        self.check_magnitudes()?;
        let d = &self.distance_m;
        let n_in = d.len();
        let d0 = d[0];
        let span = d[n_in - 1] - d0;
        // a relative 1e-12 of slack so that a grid point equal to d_last up to rounding is kept
        let count = (span / step_m * (1.0 + 1e-12)).floor() as usize + 1;
        if count < 2 {
            return Err(Error::invalid(
                "step",
                step_m,
                format!("longer than the profile ({span} m): the resampled grid would have one point"),
            ));
        }
        let mut tracks: Vec<Track> = self
            .tracks
            .iter()
            .map(|t| Track {
                name: t.name.clone(),
                elevation_m: Vec::with_capacity(count),
            })
            .collect();
        let mut i = 0;
        for k in 0..count {
            let x = (d0 + k as f64 * step_m).min(d[n_in - 1]);
            while i + 2 < n_in && d[i + 1] < x {
                i += 1;
            }
            let t = ((x - d[i]) / (d[i + 1] - d[i])).clamp(0.0, 1.0);
            for (out, inp) in tracks.iter_mut().zip(&self.tracks) {
                let (y0, y1) = (inp.elevation_m[i], inp.elevation_m[i + 1]);
                out.elevation_m.push(y0 + (y1 - y0) * t);
            }
        }
        Profile::new(step_m, d0, tracks)
    }
}

/// A uniformly sampled road profile: one or more tracks (wheel paths) sampled at distances
/// d_k = d₀ + k·Δx, k = 0..N.
///
/// # Formula
/// ```text
/// distance of sample k:  d_k = distance0_m + k · step_m   (m);   tracks[t].elevation_m[k] in m
/// ```
/// CSV import ([`Profile::read_csv`]) reads a [`RawProfile`] and requires a uniform step
/// ([`RawProfile::to_uniform`]); export ([`Profile::write_csv`]) writes the layout described there.
///
/// # Errors
/// [`Profile::new`] rejects a step that is not finite and > 0, a non-finite d₀, no track, tracks of
/// different lengths or fewer than 2 samples, non-finite elevations or elevations beyond
/// [`MAX_ELEVATION_M`] (naming track and index), and empty or repeated track names.
///
/// # Examples
/// ```
/// use stochvib::road::{CsvWriteOptions, LengthUnit, Profile, Track};
/// let p = Profile::new(0.5, 10.0, vec![Track { name: "left".into(), elevation_m: vec![0.001, 0.002, 0.0] }])
///     .unwrap();
/// assert_eq!(p.distance_m(2), 11.0);
/// let opts = CsvWriteOptions { elevation_unit: LengthUnit::Mm, ..Default::default() };
/// assert!(p.to_csv_string(&opts).starts_with("distance [m], left [mm]\n10,1\n"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Sample step Δx in m.
    pub step_m: f64,
    /// Distance of the first sample in m.
    pub distance0_m: f64,
    /// The tracks, all of the same length.
    pub tracks: Vec<Track>,
}

impl Profile {
    /// Validates and builds a profile.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(step_m: f64, distance0_m: f64, tracks: Vec<Track>) -> Result<Self> {
        crate::error::require_positive("step", step_m)?;
        crate::error::require_finite("distance0", distance0_m)?;
        if tracks.is_empty() {
            return Err(Error::invalid("tracks", 0, "a profile needs at least one track"));
        }
        let n = tracks[0].elevation_m.len();
        for (t, tr) in tracks.iter().enumerate() {
            if tr.name.trim().is_empty() {
                return Err(Error::invalid(&format!("tracks[{t}].name"), "\"\"", "empty track name"));
            }
            if tracks[..t].iter().any(|o| o.name == tr.name) {
                return Err(Error::invalid(
                    &format!("tracks[{t}].name"),
                    &tr.name,
                    "track name repeated",
                ));
            }
            if tr.elevation_m.len() != n {
                return Err(Error::invalid(
                    &format!("track `{}`", tr.name),
                    tr.elevation_m.len(),
                    format!(
                        "has a different number of samples than track `{}` ({n})",
                        tracks[0].name
                    ),
                ));
            }
            if let Some(k) = tr.elevation_m.iter().position(|v| !v.is_finite()) {
                return Err(Error::invalid(
                    &format!("track `{}` sample {k}", tr.name),
                    tr.elevation_m[k],
                    "elevation must be finite",
                ));
            }
            if let Some((k, why)) = tr.beyond_max_elevation() {
                return Err(Error::invalid(
                    &format!("track `{}` sample {k}", tr.name),
                    format!("{:e} m", tr.elevation_m[k]),
                    why,
                ));
            }
        }
        if n < 2 {
            return Err(Error::invalid("samples", n, "a profile needs at least 2 samples"));
        }
        Ok(Profile {
            step_m,
            distance0_m,
            tracks,
        })
    }

    /// Reads a CSV file with the default [`CsvReadOptions`] and requires a uniform step.
    ///
    /// # Errors
    /// As [`RawProfile::read_csv`] and [`RawProfile::to_uniform`].
    pub fn read_csv(path: &Path) -> Result<Self> {
        Profile::read_csv_with(path, &CsvReadOptions::default())
    }

    /// Reads a CSV file with the given options and requires a uniform step.
    ///
    /// # Errors
    /// As [`RawProfile::read_csv`] and [`RawProfile::to_uniform`].
    pub fn read_csv_with(path: &Path, options: &CsvReadOptions) -> Result<Self> {
        RawProfile::read_csv(path, options)?.to_uniform(options.step_tolerance)
    }

    /// Number of samples N per track.
    pub fn len(&self) -> usize {
        self.tracks[0].elevation_m.len()
    }
    /// Always false (N ≥ 2).
    pub fn is_empty(&self) -> bool {
        false
    }
    /// Distance of sample k in m: d₀ + k·Δx.
    pub fn distance_m(&self, k: usize) -> f64 {
        self.distance0_m + k as f64 * self.step_m
    }
    /// Length covered, (N − 1)·Δx in m.
    pub fn length_m(&self) -> f64 {
        (self.len() - 1) as f64 * self.step_m
    }
    /// The track named `name`.
    ///
    /// # Errors
    /// No such track (the message lists the names).
    pub fn track(&self, name: &str) -> Result<&Track> {
        self.tracks.iter().find(|t| t.name == name).ok_or_else(|| {
            Error::invalid(
                "track",
                name,
                format!(
                    "no such track; the profile has {}",
                    self.tracks
                        .iter()
                        .map(|t| format!("`{}`", t.name))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })
    }

    /// The profile with every track detrended ([`Detrend`]).
    pub fn detrended(&self, detrend: Detrend) -> Profile {
        let mut p = self.clone();
        for t in &mut p.tracks {
            detrend.apply_in_place(&mut t.elevation_m);
        }
        p
    }

    /// Linear interpolation onto another uniform step (see [`RawProfile::resample_to`]).
    ///
    /// # Errors
    /// As [`RawProfile::resample_to`].
    pub fn resample_to(&self, step_m: f64) -> Result<Profile> {
        RawProfile {
            source: PathBuf::from("<profile>"),
            distance_m: (0..self.len()).map(|k| self.distance_m(k)).collect(),
            tracks: self.tracks.clone(),
            distance_header: "distance [m]".into(),
            lines: (0..self.len()).collect(),
        }
        .resample_to(step_m)
    }

    /// The CSV text of the profile (layout of [`RawProfile`]).
    ///
    /// # Formula
    /// Distances are written as d₀ + k·Δx converted to the distance unit, elevations converted to the
    /// elevation unit; with `None` decimals each number is the shortest text that parses back to the
    /// same f64 (so a file in m reads back bit for bit; in another unit the conversion there and back can
    /// differ by one rounding).
    pub fn to_csv_string(&self, options: &CsvWriteOptions) -> String {
        let fmt = |v: f64, decimals: Option<usize>| match decimals {
            Some(d) => format!("{v:.d$}"),
            None => format!("{v}"),
        };
        let mut s = String::with_capacity(self.len() * (self.tracks.len() + 1) * 12);
        for c in &options.comments {
            let _ = writeln!(s, "# {c}");
        }
        let _ = write!(s, "distance [{}]", options.distance_unit.symbol());
        for t in &self.tracks {
            let _ = write!(s, ", {} [{}]", t.name, options.elevation_unit.symbol());
        }
        s.push('\n');
        for k in 0..self.len() {
            s.push_str(&fmt(
                options.distance_unit.from_m(self.distance_m(k)),
                options.distance_decimals,
            ));
            for t in &self.tracks {
                s.push(',');
                s.push_str(&fmt(
                    options.elevation_unit.from_m(t.elevation_m[k]),
                    options.elevation_decimals,
                ));
            }
            s.push('\n');
        }
        s
    }

    /// Writes the profile as CSV ([`Profile::to_csv_string`]) to `path` under the output rule
    /// ([`crate::io_rules::Staged`]): through a temporary file renamed into place, so that a failed write
    /// never leaves a half-written file under the final name; an existing profile CSV written by this
    /// toolkit is replaced, anything else (another kind of file, a directory, link, FIFO or device) is not.
    ///
    /// # Errors
    /// The refusals of [`crate::io_rules::check_output`]; [`Error::Io`] naming the path.
    pub fn write_csv(&self, path: &Path, options: &CsvWriteOptions) -> Result<()> {
        let staged = crate::io_rules::Staged::begin(path, PROFILE_CSV, &[], true)?;
        std::fs::write(staged.temporary(), self.to_csv_string(options)).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        staged.commit().map(|_| ())
    }
}
