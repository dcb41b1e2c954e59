//! Records as CSV text: a header naming every column with its unit, an optional time column, one row per
//! sample; read row by row with the `csv` crate under the input rule (a regular file, at most
//! [`RECORD_CSV_INPUT`]'s size, every line at most [`MAX_LINE_BYTES`] long), memory one block.
//!
//! # Format
//! ```text
//! # comment lines start with '#'; blank lines are skipped
//! time [s], seat_x [m/s^2], seat_y [m/s^2], seat_z [m/s^2]      header: every column `name [unit]`
//! 0.000, 0.012, -0.003, 0.154                                    one row per sample
//! ```
//! * Delimiter: `,`, `;` or a tab, taken from the header line (the first of tab, `;`, `,` that it contains);
//!   fields may be quoted.
//! * Decimal separator: the point; a decimal comma (`0,154`) only when stated ([`RecordOptions::decimal_comma`]),
//!   and then the delimiter must be `;` or a tab. A comma in a number is never guessed to be a decimal comma.
//! * Units: in the header, `name [unit]`; a column without one needs its unit stated
//!   ([`RecordOptions::units`]), else it is refused. Accelerations in m/s², mm/s², `gn` (standard gravity;
//!   `g` alone is refused as ambiguous), rad/s²; stresses in Pa, kPa, MPa, N/mm^2; strains in `um/m`,
//!   `ustrain`.
//! * Time base: a column whose unit is a time (s, ms, min, h) is the time column; otherwise the sample rate
//!   must be stated. With a time column the rate is estimated from the first [`RATE_ROWS`] rows and every
//!   row is checked: time must increase, no step longer than 1.5 steps (missing samples), no step off by
//!   more than [`STEP_TOLERANCE`] of a step, and the rate of the whole record within [`RATE_TOLERANCE`] of
//!   the first rows' (and of a stated rate).
//! * Values: finite numbers; a blank field (a missing sample), NaN, infinity or text is refused.
//!
//! Every refusal names the file, the line (and column) and the value, with the reason.

use super::source::{channel, check_rate, Channel, RecordInfo, RecordOptions, RecordReader, TimeBase};
use crate::error::{Error, Result};
use crate::io_rules::{open_input, InputKind, MAX_LINE_BYTES};
use crate::units::Dim;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

/// Record files as CSV: streamed, so the limit is the time a read takes, not memory: 64 GiB (about 10⁹ rows
/// of three channels).
pub const RECORD_CSV_INPUT: InputKind = InputKind {
    what: "record CSV file",
    max_bytes: Some(64 << 30),
    too_large_hint: "split the record into files of a shift each, or store it as HDF5",
};

/// Rows from which the sample rate of a time column is estimated.
pub const RATE_ROWS: usize = 1024;

/// Largest deviation of one time step from the record's step, relative (rounding of printed times).
pub const STEP_TOLERANCE: f64 = 0.25;

/// Largest relative difference between the rate of the first [`RATE_ROWS`] rows, the rate of the whole
/// record and a stated rate.
pub const RATE_TOLERANCE: f64 = 1e-3;

/// A reader that refuses a line longer than [`MAX_LINE_BYTES`] (the bounded-line rule of
/// [`crate::io_rules`]) before the CSV parser buffers it.
struct LineLimited<R> {
    inner: R,
    since_newline: usize,
}

impl<R: Read> Read for LineLimited<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        for &b in &buf[..n] {
            if b == b'\n' {
                self.since_newline = 0;
            } else {
                self.since_newline += 1;
                if self.since_newline > MAX_LINE_BYTES {
                    return Err(std::io::Error::new(
                        std::io::ErrorKind::InvalidData,
                        format!(
                            "a line is longer than the {MAX_LINE_BYTES} bytes a line may have (is it a text file?)"
                        ),
                    ));
                }
            }
        }
        Ok(n)
    }
}

/// A CSV record being read (see the [module docs](self)).
pub struct CsvRecord {
    info: RecordInfo,
    reader: csv::Reader<LineLimited<BufReader<std::fs::File>>>,
    row: csv::ByteRecord,
    columns: usize,
    /// (column, factor to SI) of each channel
    value_columns: Vec<(usize, f64)>,
    time: Option<TimeCheck>,
    decimal_comma: bool,
    /// rows read ahead to estimate the rate, not yet handed out: (line, values)
    ahead: std::collections::VecDeque<(u64, Vec<f64>)>,
    /// lines of the file before the CSV reader's first line (comments above the header)
    line_offset: u64,
}

/// The checks of a time column.
struct TimeCheck {
    column: usize,
    to_s: f64,
    name: String,
    /// step h, s (stated, or from the first rows)
    step: f64,
    t0: f64,
    last: Option<(u64, f64)>,
    rows: u64,
    first_rows_rate: f64,
    stated: bool,
}

impl CsvRecord {
    /// Opens `path` and reads its header and first rows.
    ///
    /// # Errors
    /// The refusals of [`open_input`]; a missing header; a column without a unit or with an unknown unit;
    /// more than one time column; no time base; a decimal comma with `,` as delimiter; the errors of the
    /// first rows (see the [module docs](self)).
    pub fn open(path: &Path, options: &RecordOptions) -> Result<Self> {
        let (file, size) = open_input(path, RECORD_CSV_INPUT)?;
        let mut buf = BufReader::with_capacity(1 << 16, file);
        let (header_line, delimiter, skipped_bytes) = find_header(&mut buf, path)?;
        if options.decimal_comma && delimiter == b',' {
            return Err(Error::in_file(
                path,
                format!("line {header_line} (header)"),
                "delimiter `,`",
                "a decimal comma needs `;` or a tab between the fields",
            ));
        }
        let mut reader = csv::ReaderBuilder::new()
            .delimiter(delimiter)
            .has_headers(false)
            .flexible(true)
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .from_reader(LineLimited {
                inner: buf,
                since_newline: 0,
            });
        let mut row = csv::ByteRecord::new();
        let line_offset = header_line - 1;
        let header_ok = reader
            .read_byte_record(&mut row)
            .map_err(|e| csv_error(path, e, line_offset))?;
        if !header_ok {
            return Err(missing_header(path));
        }
        let (channels, value_columns, time) = parse_header(&row, header_line, path, options)?;
        let columns = row.len();
        let time = time.map(|(column, to_s, name)| TimeCheck {
            column,
            to_s,
            name,
            step: f64::NAN,
            t0: f64::NAN,
            last: None,
            rows: 0,
            first_rows_rate: f64::NAN,
            stated: false,
        });
        let (sample_rate_hz, time_base) = match (&time, options.sample_rate_hz) {
            (Some(t), _) => (f64::NAN, TimeBase::TimeColumn(t.name.clone())),
            (None, Some(r)) => (check_rate(r)?, TimeBase::Stated),
            (None, None) => {
                return Err(Error::in_file(
                    path,
                    format!("line {header_line} (header)"),
                    "no time column",
                    "the record has no time base: give a time column (a column with a time unit, e.g. `time [s]`) \
                     or state the sample rate (--sample-rate)",
                ))
            }
        };
        let mut rec = CsvRecord {
            info: RecordInfo {
                source: path.to_path_buf(),
                format: "CSV",
                sample_rate_hz,
                time_base,
                channels,
                samples_hint: None,
            },
            reader,
            row,
            columns,
            value_columns,
            time,
            decimal_comma: options.decimal_comma,
            ahead: Default::default(),
            line_offset,
        };
        rec.read_ahead(options.sample_rate_hz)?;
        let data_bytes = size.saturating_sub(skipped_bytes + rec.reader.position().byte()) as f64;
        let consumed = rec.reader.position().byte().max(1) as f64;
        rec.info.samples_hint = Some((rec.ahead.len() as f64 * (1.0 + data_bytes / consumed)) as usize);
        Ok(rec)
    }

    /// Reads the first [`RATE_ROWS`] rows; with a time column, estimates the rate from them.
    fn read_ahead(&mut self, stated: Option<f64>) -> Result<()> {
        let mut values = Vec::new();
        while self.ahead.len() < RATE_ROWS {
            match self.next_row(&mut values)? {
                Some(line) => self.ahead.push_back((line, values.clone())),
                None => break,
            }
        }
        if self.ahead.is_empty() {
            return Err(Error::in_file(
                &self.info.source,
                "rows",
                "0",
                "the record has a header but no data rows (an empty or truncated file)",
            ));
        }
        let Some(t) = &mut self.time else { return Ok(()) };
        let (n, first, last) = (self.ahead.len(), &self.ahead[0], &self.ahead[self.ahead.len() - 1]);
        let (t_first, t_last) = (first.1[t.column], last.1[t.column]);
        if n < 2 || t_last <= t_first {
            return Err(Error::in_file(
                &self.info.source,
                format!("line {}, column `{}`", last.0, t.name),
                t_last / t.to_s,
                "cannot establish a sample rate: the time column needs at least two rows with increasing time",
            ));
        }
        let step = (t_last - t_first) / (n - 1) as f64;
        t.first_rows_rate = 1.0 / step;
        t.step = step;
        if let Some(r) = stated {
            let r = check_rate(r)?;
            if ((1.0 / step - r) / r).abs() > RATE_TOLERANCE {
                return Err(Error::in_file(
                    &self.info.source,
                    format!("lines {} to {}, column `{}`", first.0, last.0, t.name),
                    format!("{} Hz", crate::numbers::num(1.0 / step)),
                    format!("inconsistent sample rates: the time column gives this rate, --sample-rate states {r} Hz"),
                ));
            }
            t.step = 1.0 / r;
            t.stated = true;
        }
        self.info.sample_rate_hz = 1.0 / t.step;
        let rows: Vec<(u64, f64)> = self.ahead.iter().map(|(l, v)| (*l, v[t.column])).collect();
        for (line, time) in rows {
            check_time(t, &self.info.source, line, time)?;
        }
        Ok(())
    }

    /// Parses the next data row into `values` (every column in SI, the time in s); returns its line, or
    /// `None` at the end.
    fn next_row(&mut self, values: &mut Vec<f64>) -> Result<Option<u64>> {
        let path = &self.info.source;
        loop {
            let offset = self.line_offset;
            if !self
                .reader
                .read_byte_record(&mut self.row)
                .map_err(|e| csv_error(path, e, offset))?
            {
                return Ok(None);
            }
            let line = self.row.position().map_or(0, |p| p.line()) + offset;
            if self.row.len() == 1 && self.row[0].is_empty() {
                continue; // a blank line
            }
            if self.row.len() != self.columns {
                return Err(Error::in_file(
                    path,
                    format!("line {line}"),
                    crate::io_rules::excerpt(&String::from_utf8_lossy(self.row.as_slice())),
                    format!(
                        "{} fields; the header has {} columns (a missing sample, or another delimiter?)",
                        self.row.len(),
                        self.columns
                    ),
                ));
            }
            values.clear();
            for c in 0..self.columns {
                values.push(self.field_value(line, c)?);
            }
            if let Some(t) = &self.time {
                values[t.column] *= t.to_s;
            }
            return Ok(Some(line));
        }
    }

    /// The number in column `c` of the current row (not yet scaled).
    fn field_value(&self, line: u64, c: usize) -> Result<f64> {
        let raw = &self.row[c];
        let text = std::str::from_utf8(raw).map_err(|_| {
            Error::in_file(
                &self.info.source,
                format!("line {line}, column {}", c + 1),
                "<bytes>",
                "not UTF-8 text",
            )
        })?;
        let key = || format!("line {line}, column {}", c + 1);
        if text.is_empty() {
            return Err(Error::in_file(
                &self.info.source,
                key(),
                "<blank>",
                "missing sample: a record must have a value in every column of every row",
            ));
        }
        let parsed = if self.decimal_comma {
            // only a stated decimal comma becomes a point
            text.replace(',', ".").parse::<f64>()
        } else {
            text.parse::<f64>()
        };
        let v = parsed.map_err(|_| {
            let hint = if !self.decimal_comma && text.contains(',') {
                " (a decimal comma is read only when stated: --decimal-comma)"
            } else {
                ""
            };
            Error::in_file(
                &self.info.source,
                key(),
                crate::io_rules::excerpt(text),
                format!("not a number{hint}"),
            )
        })?;
        if !v.is_finite() {
            return Err(Error::in_file(
                &self.info.source,
                key(),
                text,
                "not finite (NaN or infinity): gaps and overloads must be repaired or the record split before the \
                 evaluation",
            ));
        }
        Ok(v)
    }
}

impl RecordReader for CsvRecord {
    fn info(&self) -> &RecordInfo {
        &self.info
    }

    fn read_block(&mut self, out: &mut [Vec<f64>], max: usize) -> Result<usize> {
        for o in out.iter_mut() {
            o.clear();
        }
        let mut values = Vec::with_capacity(self.columns);
        let mut n = 0;
        while n < max {
            if let Some((_, row)) = self.ahead.pop_front() {
                emit(out, &self.value_columns, &row);
                n += 1;
                continue;
            }
            match self.next_row(&mut values)? {
                Some(line) => {
                    if let Some(t) = &mut self.time {
                        check_time(t, &self.info.source, line, values[t.column])?;
                    }
                    emit(out, &self.value_columns, &values);
                    n += 1;
                }
                None => {
                    self.finish_time()?;
                    break;
                }
            }
        }
        Ok(n)
    }
}

/// Appends one row's channels, in SI, to the block.
#[inline]
fn emit(out: &mut [Vec<f64>], columns: &[(usize, f64)], row: &[f64]) {
    for (o, &(c, to_si)) in out.iter_mut().zip(columns) {
        o.push(row[c] * to_si);
    }
}

impl CsvRecord {
    /// At the end: the rate of the whole record against the first rows' (and the stated one).
    fn finish_time(&mut self) -> Result<()> {
        let Some(t) = &self.time else { return Ok(()) };
        let Some((line, last)) = t.last else { return Ok(()) };
        if t.rows < 2 {
            return Ok(());
        }
        let whole = (t.rows - 1) as f64 / (last - t.t0);
        let reference = 1.0 / t.step;
        if ((whole - reference) / reference).abs() > RATE_TOLERANCE {
            return Err(Error::in_file(
                &self.info.source,
                format!("line {line}, column `{}`", t.name),
                format!("{} s", crate::numbers::num(last / t.to_s)),
                format!(
                    "inconsistent sample rate: the whole record ({} rows) has {} Hz, {} {} Hz (tolerance {})",
                    t.rows,
                    crate::numbers::num(whole),
                    if t.stated {
                        "--sample-rate states"
                    } else {
                        "its first rows have"
                    },
                    crate::numbers::num(reference),
                    RATE_TOLERANCE
                ),
            ));
        }
        Ok(())
    }
}

/// One row's time against the previous row's and the step.
fn check_time(t: &mut TimeCheck, file: &Path, line: u64, time: f64) -> Result<()> {
    let key = || format!("line {line}, column `{}`", t.name);
    let shown = || format!("{} s", crate::numbers::num(time));
    match t.last {
        None => t.t0 = time,
        Some((prev_line, prev)) => {
            let dt = time - prev;
            if dt <= 0.0 {
                return Err(Error::in_file(
                    file,
                    key(),
                    shown(),
                    format!(
                        "non-monotone time: the previous row (line {prev_line}) has {} s",
                        crate::numbers::num(prev)
                    ),
                ));
            }
            if dt > 1.5 * t.step {
                return Err(Error::in_file(
                    file,
                    key(),
                    shown(),
                    format!(
                        "missing samples: {} s after the previous row (line {prev_line}), {:.1} steps of {} s; a \
                         record must be sampled without gaps (split it at the gap)",
                        crate::numbers::num(dt),
                        dt / t.step,
                        crate::numbers::num(t.step)
                    ),
                ));
            }
            if (dt - t.step).abs() > STEP_TOLERANCE * t.step {
                return Err(Error::in_file(
                    file,
                    key(),
                    shown(),
                    format!(
                        "inconsistent sample rate: a step of {} s after the previous row (line {prev_line}), the record's \
                         step is {} s",
                        crate::numbers::num(dt),
                        crate::numbers::num(t.step)
                    ),
                ));
            }
        }
    }
    t.last = Some((line, time));
    t.rows += 1;
    Ok(())
}

/// Skips comment and blank lines up to the header; returns its line number, the delimiter and the bytes
/// skipped before it.
fn find_header(buf: &mut BufReader<std::fs::File>, path: &Path) -> Result<(u64, u8, u64)> {
    let mut line_no = 0u64;
    let mut skipped = 0u64;
    loop {
        let peek = buf.fill_buf().map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        if peek.is_empty() {
            return Err(missing_header(path));
        }
        let end = peek.iter().position(|&b| b == b'\n');
        let Some(end) = end else {
            if peek.len() > MAX_LINE_BYTES {
                return Err(Error::in_file(
                    path,
                    format!("line {}", line_no + 1),
                    "<long line>",
                    format!("the line is longer than the {MAX_LINE_BYTES} bytes a line may have"),
                ));
            }
            // the last line of the file (no newline): the header, or nothing
            let text = String::from_utf8_lossy(peek).to_string();
            return header_or_skip(&text, line_no + 1, skipped).ok_or_else(|| missing_header(path));
        };
        line_no += 1;
        let text = String::from_utf8_lossy(&peek[..end]).to_string();
        if let Some(h) = header_or_skip(&text, line_no, skipped) {
            return Ok(h);
        }
        buf.consume(end + 1);
        skipped += end as u64 + 1;
    }
}

/// `Some((line, delimiter, skipped))` when `text` is the header line, `None` for a comment or blank line.
fn header_or_skip(text: &str, line: u64, skipped: u64) -> Option<(u64, u8, u64)> {
    let t = text.trim_start_matches('\u{feff}').trim();
    if t.is_empty() || t.starts_with('#') {
        return None;
    }
    let delimiter = if t.contains('\t') {
        b'\t'
    } else if t.contains(';') {
        b';'
    } else {
        b','
    };
    Some((line, delimiter, skipped))
}

fn missing_header(path: &Path) -> Error {
    Error::in_file(
        path,
        "header",
        "<missing>",
        "no header row (an empty file, or only comments): expected e.g. `time [s], seat_z [m/s^2]`",
    )
}

fn csv_error(path: &Path, e: csv::Error, line_offset: u64) -> Error {
    let line = e.position().map(|p| p.line() + line_offset);
    let reason = match e.kind() {
        csv::ErrorKind::Io(io) => io.to_string(),
        csv::ErrorKind::Utf8 { .. } => "not UTF-8 text".to_string(),
        _ => e.to_string(),
    };
    Error::in_file(
        path,
        line.map_or_else(|| "read".to_string(), |l| format!("line {l}")),
        "<record>",
        reason,
    )
}

/// `name [unit]` → (name, Some(unit)); `name` → (name, None).
fn split_header_cell(cell: &str) -> (&str, Option<&str>) {
    let cell = cell.trim();
    if let Some(open) = cell.rfind('[')
        && let Some(unit) = cell[open + 1..].strip_suffix(']')
    {
        return (cell[..open].trim(), Some(unit.trim()));
    }
    (cell, None)
}

type Header = (Vec<Channel>, Vec<(usize, f64)>, Option<(usize, f64, String)>);

/// The channels (every column but the time column), their columns and factors, and the time column.
fn parse_header(row: &csv::ByteRecord, line: u64, path: &Path, options: &RecordOptions) -> Result<Header> {
    let mut channels = Vec::new();
    let mut value_columns = Vec::new();
    let mut time: Option<(usize, f64, String)> = None;
    let mut names: Vec<String> = Vec::new();
    for (c, raw) in row.iter().enumerate() {
        let cell = String::from_utf8_lossy(raw).trim_start_matches('\u{feff}').to_string();
        let key = format!("line {line} (header), column {}", c + 1);
        let (name, unit) = split_header_cell(&cell);
        if name.is_empty() {
            return Err(Error::in_file(path, key, cell.trim(), "empty column name"));
        }
        if names.iter().any(|n| n == name) {
            return Err(Error::in_file(
                path,
                key,
                cell.trim(),
                format!("column name `{name}` repeated"),
            ));
        }
        names.push(name.to_string());
        let stated = options.units.iter().find(|(n, _)| n == name).map(|(_, u)| u.as_str());
        let unit = match (unit, stated) {
            (Some(u), None) => u.to_string(),
            (None, Some(u)) => u.to_string(),
            (Some(u), Some(s)) => {
                return Err(Error::in_file(
                    path,
                    key,
                    cell.trim(),
                    format!("the header gives the unit `{u}` and --unit gives `{s}`: give one"),
                ))
            }
            (None, None) => {
                return Err(Error::in_file(
                    path,
                    key,
                    cell.trim(),
                    "column without a unit: write it as `name [unit]` (e.g. `seat_z [m/s^2]`) or state it with \
                     --unit NAME=UNIT; a unit is never guessed",
                ))
            }
        };
        let ch = channel(path, &key, name, &unit)?;
        if ch.dim == Dim::TIME {
            if let Some((_, _, other)) = &time {
                return Err(Error::in_file(
                    path,
                    key,
                    cell.trim(),
                    format!("a second time column (the first is `{other}`)"),
                ));
            }
            time = Some((c, ch.to_si, name.to_string()));
        } else {
            value_columns.push((c, ch.to_si));
            channels.push(ch);
        }
    }
    if channels.is_empty() {
        return Err(Error::in_file(
            path,
            format!("line {line} (header)"),
            crate::io_rules::excerpt(&names.join(", ")),
            "no data column besides the time",
        ));
    }
    for (n, _) in &options.units {
        if !names.contains(n) {
            return Err(Error::invalid("--unit", n, "the record has no column of this name"));
        }
    }
    Ok((channels, value_columns, time))
}
