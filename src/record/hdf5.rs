//! Records as HDF5 datasets: one one-dimensional numeric dataset per channel, with its unit and sample
//! rate as attributes; read a block at a time (a hyperslab of every dataset), memory one block.
//!
//! # Layout
//! * Each channel is a one-dimensional dataset of any numeric type (converted to f64 on reading), named by
//!   its path (`/seat/z`); without `--dataset` every one-dimensional numeric dataset of the root group is a
//!   channel, in name order.
//! * `unit` (string attribute of the dataset): the unit of the values, e.g. `m/s^2`; required, unless stated
//!   with `--unit NAME=UNIT` (NAME the dataset's path without the leading `/`).
//! * `sample_rate` (numeric attribute, Hz) of the dataset or of its group; required unless stated with
//!   `--sample-rate`; every channel must have the same rate and the same length.
//!
//! h5py writes such a file with `f.create_dataset("z", data=a).attrs.update(unit="m/s^2", sample_rate=1000.0)`.

use super::source::{channel, check_rate, RecordInfo, RecordOptions, RecordReader, TimeBase};
use crate::error::{Error, Result};
use crate::io_rules::{check_input, HDF5_INPUT};
use hdf5::types::VarLenUnicode;
use ndarray::s;
use std::path::Path;

/// A record of HDF5 datasets being read (see the [module docs](self)).
pub struct Hdf5Record {
    info: RecordInfo,
    _file: hdf5::File,
    datasets: Vec<hdf5::Dataset>,
    len: usize,
    pos: usize,
}

/// Relative difference accepted between the `sample_rate` attributes of two channels (and a stated rate).
pub const RATE_MATCH: f64 = 1e-9;

impl Hdf5Record {
    /// Opens `path` and checks its datasets (see the [module docs](self)).
    ///
    /// # Errors
    /// The refusals of [`check_input`]; a file HDF5 cannot read; a missing dataset, or one that is not
    /// one-dimensional and numeric; a missing or unknown unit; missing, invalid or inconsistent sample rates;
    /// datasets of different lengths; an empty dataset. Each names the file and the dataset (and attribute).
    pub fn open(path: &Path, options: &RecordOptions) -> Result<Self> {
        check_input(path, HDF5_INPUT)?;
        let file = crate::store::open_sec2(path, crate::store::OpenMode::Read, |_| {})
            .map_err(crate::store::h5err(path, "not readable as an HDF5 file"))?;
        let names = if options.datasets.is_empty() {
            root_datasets(&file, path)?
        } else {
            options.datasets.clone()
        };
        let mut datasets = Vec::new();
        let mut channels = Vec::new();
        let mut rates: Vec<(String, f64)> = Vec::new();
        let mut len: Option<(String, usize)> = None;
        for name in &names {
            let key = format!("dataset {name}");
            let ds = file
                .dataset(name)
                .map_err(|e| Error::in_file(path, &key, name, format!("no such dataset ({e})")))?;
            if ds.ndim() != 1 {
                return Err(Error::in_file(
                    path,
                    &key,
                    format!("shape {:?}", ds.shape()),
                    "a channel must be a one-dimensional dataset",
                ));
            }
            let n = ds.size();
            match &len {
                None => len = Some((name.clone(), n)),
                Some((first, m)) if *m != n => {
                    return Err(Error::in_file(
                        path,
                        &key,
                        format!("{n} samples"),
                        format!("the channels differ in length: {first} has {m} samples"),
                    ))
                }
                _ => {}
            }
            let short = name.trim_start_matches('/').to_string();
            let unit = match (
                string_attr(&ds, "unit", path, &format!("{key}, attribute unit"))?,
                options.units.iter().find(|(n, _)| *n == short),
            ) {
                (Some(u), None) => u,
                (None, Some((_, u))) => u.clone(),
                (Some(u), Some((_, s))) => {
                    return Err(Error::in_file(
                        path,
                        format!("{key}, attribute unit"),
                        &u,
                        format!("the file gives this unit and --unit gives `{s}`: give one"),
                    ))
                }
                (None, None) => return Err(Error::in_file(
                    path,
                    format!("{key}, attribute unit"),
                    "<missing>",
                    "the dataset has no `unit` attribute: add one (e.g. `m/s^2`) or state it with --unit NAME=UNIT; \
                         a unit is never guessed",
                )),
            };
            channels.push(channel(path, &format!("{key}, attribute unit"), &short, &unit)?);
            if let Some(r) = rate_attr(&file, &ds, name, path)? {
                rates.push((name.clone(), r));
            }
            datasets.push(ds);
        }
        let (len_name, len) = len.ok_or_else(|| {
            Error::in_file(
                path,
                "datasets",
                "<none>",
                "the file has no one-dimensional numeric dataset in its root group",
            )
        })?;
        if len == 0 {
            return Err(Error::in_file(
                path,
                format!("dataset {len_name}"),
                "0 samples",
                "the record is empty",
            ));
        }
        let (sample_rate_hz, time_base) = resolve_rate(path, &rates, options.sample_rate_hz)?;
        Ok(Hdf5Record {
            info: RecordInfo {
                source: path.to_path_buf(),
                format: "HDF5",
                sample_rate_hz,
                time_base,
                channels,
                samples_hint: Some(len),
            },
            _file: file,
            datasets,
            len,
            pos: 0,
        })
    }
}

/// The rate: the attributes (all equal), checked against a stated one, or the stated one.
fn resolve_rate(path: &Path, rates: &[(String, f64)], stated: Option<f64>) -> Result<(f64, TimeBase)> {
    let Some((first, r0)) = rates.first() else {
        return match stated {
            Some(r) => Ok((check_rate(r)?, TimeBase::Stated)),
            None => Err(Error::in_file(
                path,
                "attribute sample_rate",
                "<missing>",
                "the record has no time base: give the datasets (or their group) a `sample_rate` attribute in Hz, or \
                 state the rate (--sample-rate)",
            )),
        };
    };
    for (name, r) in rates {
        if ((r - r0) / r0).abs() > RATE_MATCH {
            return Err(Error::in_file(
                path,
                format!("dataset {name}, attribute sample_rate"),
                format!("{r} Hz"),
                format!("inconsistent sample rates: {first} has {r0} Hz"),
            ));
        }
    }
    if let Some(s) = stated
        && ((s - r0) / r0).abs() > RATE_MATCH
    {
        return Err(Error::in_file(
            path,
            format!("dataset {first}, attribute sample_rate"),
            format!("{r0} Hz"),
            format!("inconsistent sample rates: --sample-rate states {s} Hz"),
        ));
    }
    Ok((*r0, TimeBase::Attribute(first.clone())))
}

/// The `sample_rate` attribute of the dataset, else of its group (Hz, finite and > 0).
fn rate_attr(file: &hdf5::File, ds: &hdf5::Dataset, name: &str, path: &Path) -> Result<Option<f64>> {
    let group_path = match name.trim_end_matches('/').rfind('/') {
        Some(0) | None => "/".to_string(),
        Some(i) => name[..i].to_string(),
    };
    let from_group = || file.group(&group_path).ok().and_then(|g| g.attr("sample_rate").ok());
    let Some(attr) = ds.attr("sample_rate").ok().or_else(from_group) else {
        return Ok(None);
    };
    let key = format!("dataset {name}, attribute sample_rate");
    let r = attr
        .read_scalar::<f64>()
        .map_err(|e| Error::in_file(path, &key, "<unreadable>", format!("not a number: {e}")))?;
    if !(r.is_finite() && r > 0.0) {
        return Err(Error::in_file(path, &key, r, "a sample rate must be finite and > 0 Hz"));
    }
    Ok(Some(r))
}

/// The longest fixed-length text attribute read, bytes (a unit is a few characters).
const FIXED_TEXT_MAX: usize = 256;

/// A text attribute of `ds`: `Ok(None)` when there is none; its text (trimmed) when it is a string of one
/// value, variable- or fixed-length, ASCII or UTF-8 (h5py writes `str` as variable-length UTF-8, `bytes` and
/// MATLAB's `h5writeatt` fixed-length ASCII; a list of one string is a one-element array).
///
/// # Errors
/// [`Error::File`] naming `key` when the attribute holds something else: a number, several values, a
/// fixed-length string longer than [`FIXED_TEXT_MAX`] bytes, text that is not UTF-8.
fn string_attr(ds: &hdf5::Dataset, name: &str, path: &Path, key: &str) -> Result<Option<String>> {
    use hdf5::types::{FixedAscii, FixedUnicode, TypeDescriptor as TD, VarLenAscii};
    let Ok(a) = ds.attr(name) else {
        return Ok(None);
    };
    let refuse = |value: String, why: String| Error::in_file(path, key, value, why);
    let unreadable = |e: hdf5::Error| refuse("<unreadable>".into(), format!("not readable as text: {e}"));
    let td = a.dtype().and_then(|t| t.to_descriptor()).map_err(unreadable)?;
    if a.size() != 1 {
        return Err(refuse(
            format!("{} values", a.size()),
            "one text is needed (e.g. `m/s^2`)".into(),
        ));
    }
    let first = |v: Vec<String>| v.into_iter().next().unwrap_or_default();
    let text = match td {
        TD::VarLenUnicode => a
            .read_raw::<VarLenUnicode>()
            .map(|v| first(v.iter().map(|s| s.to_string()).collect())),
        TD::VarLenAscii => a
            .read_raw::<VarLenAscii>()
            .map(|v| first(v.iter().map(|s| s.to_string()).collect())),
        TD::FixedAscii(n) if n <= FIXED_TEXT_MAX => a
            .read_raw::<FixedAscii<FIXED_TEXT_MAX>>()
            .map(|v| first(v.iter().map(|s| s.to_string()).collect())),
        TD::FixedUnicode(n) if n <= FIXED_TEXT_MAX => a
            .read_raw::<FixedUnicode<FIXED_TEXT_MAX>>()
            .map(|v| first(v.iter().map(|s| s.to_string()).collect())),
        TD::FixedAscii(n) | TD::FixedUnicode(n) => {
            return Err(refuse(
                format!("a text of {n} bytes"),
                format!("longer than the {FIXED_TEXT_MAX} bytes read: a unit is a few characters"),
            ))
        }
        other => {
            return Err(refuse(
                "<not text>".into(),
                format!("the attribute holds {other}, not text (a unit is written as a string, e.g. `m/s^2`)"),
            ))
        }
    }
    .map_err(unreadable)?;
    Ok(Some(text.trim().to_string()))
}

/// Every one-dimensional numeric dataset of the root group, in name order.
fn root_datasets(file: &hdf5::File, path: &Path) -> Result<Vec<String>> {
    let names = file
        .member_names()
        .map_err(crate::store::h5err(path, "listing the root group"))?;
    let mut out: Vec<String> = names
        .into_iter()
        .filter(|n| {
            file.dataset(n).is_ok_and(|d| {
                d.ndim() == 1
                    && d.dtype().is_ok_and(|t| {
                        matches!(
                            t.to_descriptor(),
                            Ok(hdf5::types::TypeDescriptor::Float(_)
                                | hdf5::types::TypeDescriptor::Integer(_)
                                | hdf5::types::TypeDescriptor::Unsigned(_))
                        )
                    })
            })
        })
        .map(|n| format!("/{n}"))
        .collect();
    out.sort();
    Ok(out)
}

impl RecordReader for Hdf5Record {
    fn info(&self) -> &RecordInfo {
        &self.info
    }

    fn read_block(&mut self, out: &mut [Vec<f64>], max: usize) -> Result<usize> {
        let n = max.min(self.len - self.pos);
        for ((o, ds), ch) in out.iter_mut().zip(&self.datasets).zip(&self.info.channels) {
            o.clear();
            if n == 0 {
                continue;
            }
            let key = format!("dataset /{}", ch.name);
            let block = ds.read_slice_1d::<f64, _>(s![self.pos..self.pos + n]).map_err(|e| {
                Error::in_file(
                    &self.info.source,
                    &key,
                    "<unreadable>",
                    format!("samples {}..{}: {e}", self.pos, self.pos + n),
                )
            })?;
            o.extend(block.iter().map(|v| v * ch.to_si));
            if let Some(i) = o.iter().position(|v| !v.is_finite()) {
                return Err(not_finite(&self.info.source, &key, self.pos + i, block[i]));
            }
        }
        self.pos += n;
        Ok(n)
    }
}

/// A non-finite sample of a binary record, named by its index.
pub(crate) fn not_finite(file: &Path, key: &str, index: usize, value: f64) -> Error {
    Error::in_file(
        file,
        format!("{key}, sample {index}"),
        value,
        "not finite (NaN or infinity): gaps and overloads must be repaired or the record split before the evaluation",
    )
}
