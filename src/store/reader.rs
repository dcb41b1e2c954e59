//! Reading a run file back (its human-readable summary is [`crate::report::summarize`]).

use super::layout as L;
use super::parts::{MergedFrom, RawStorage};
use super::{
    h5err, Compression, OutputStatistics, Part, Provenance, PsdEstimate, RunMetadata, Signal, SignalGroup, Statistic,
};
use crate::error::{Error, Result};
use crate::estimate::Interval;
use hdf5::types::VarLenUnicode;
use hdf5::{File, Location};
use ndarray::{s, Array2};
use std::path::{Path, PathBuf};

/// A complete run file opened for reading.
///
/// Holds the HDF5 file open until dropped (or [`close`](RunFile::close)d): drop it before reopening the
/// same file for writing.
#[derive(Debug)]
pub struct RunFile {
    path: PathBuf,
    file: File,
    meta: RunMetadata,
    format_version: u32,
    toolkit_version: String,
    complete: bool,
    /// Completion of the file's own shards (`meta.local_shards()`, in order).
    completed_shards: Vec<bool>,
    /// What a merged file was merged from (`/parts`).
    merged_from: Option<MergedFrom>,
}

impl RunFile {
    /// Opens a complete run file.
    ///
    /// # Errors
    /// [`Error::Hdf5`] if the path ends in `.tmp` (the temporary file of an unfinished run), if it is not
    /// an HDF5 file or not a stochvib run file (a root attribute is missing or has the wrong type), if it
    /// was written by a newer format version, or if it lacks `@complete`.
    ///
    /// # Examples
    /// ```
    /// let err = stochvib::store::RunFile::open("no/such/run.h5").unwrap_err();
    /// assert!(err.to_string().contains("run.h5"));
    /// ```
    pub fn open(path: impl AsRef<Path>) -> Result<RunFile> {
        let path = path.as_ref();
        if path.to_string_lossy().ends_with(L::TMP_SUFFIX) {
            return Err(Error::Hdf5 {
                path: path.to_path_buf(),
                reason: "is the temporary file of an unfinished run, not a result: rerun the same command to \
                         resume it (or delete it)"
                    .into(),
            });
        }
        let run = Self::open_any(path)?;
        if !run.complete {
            let done = run.completed_shards().len();
            return Err(Error::Hdf5 {
                path: path.to_path_buf(),
                reason: format!(
                    "incomplete run file (no `@{}` attribute; {done} of {} shards written): it was not finished \
                     and is not a result",
                    L::ATTR_COMPLETE,
                    run.meta.n_shards()
                ),
            });
        }
        Ok(run)
    }

    /// Opens a run file whether complete or not (for inspection of an interrupted run).
    ///
    /// # Errors
    /// As [`open`](Self::open), except that `.tmp` names and a missing `@complete` are accepted.
    pub fn open_any(path: impl AsRef<Path>) -> Result<RunFile> {
        let path = path.as_ref().to_path_buf();
        if !path.exists() {
            return Err(Error::Hdf5 {
                path,
                reason: "no such file".into(),
            });
        }
        // the input rule: a FIFO or device would block or never end inside the HDF5 library
        crate::io_rules::check_input(&path, crate::io_rules::HDF5_INPUT)?;
        let file = super::open_sec2(&path, super::OpenMode::Read, |_| {})
            .map_err(h5err(&path, "not readable as an HDF5 file"))?;
        let meta = read_metadata(&file, &path)?;
        let format_version = attr_scalar::<u32>(&file, L::ATTR_FORMAT_VERSION, &path)?;
        let toolkit_version = attr_string(&file, L::ATTR_TOOLKIT_VERSION, &path)?;
        let complete = has_attr(&file, L::ATTR_COMPLETE) && attr_scalar::<u8>(&file, L::ATTR_COMPLETE, &path)? == 1;
        let completed_shards = read_shards_complete(&file, &path, meta.local_shards().len())?;
        let merged_from = read_parts_group(&file, &path, &meta)?;
        Ok(RunFile {
            path,
            file,
            meta,
            format_version,
            toolkit_version,
            complete,
            completed_shards,
            merged_from,
        })
    }

    /// Opens a shard file whose header a [`PartSet`](super::PartSet) already read and checked (`meta`,
    /// `format_version`, `toolkit_version`, complete): only the HDF5 file is opened, nothing is read.
    /// The caller makes sure the file is still the one it read (see [`PartFile::open`](super::PartFile::open)).
    ///
    /// # Errors
    /// [`Error::Hdf5`] if the file cannot be opened.
    pub(crate) fn open_known(
        path: &Path,
        meta: &RunMetadata,
        format_version: u32,
        toolkit_version: &str,
    ) -> Result<RunFile> {
        let file = super::open_sec2(path, super::OpenMode::Read, |_| {})
            .map_err(h5err(path, "not readable as an HDF5 file"))?;
        Ok(RunFile {
            path: path.to_path_buf(),
            file,
            meta: meta.clone(),
            format_version,
            toolkit_version: toolkit_version.to_string(),
            complete: true,
            completed_shards: vec![true; meta.local_shards().len()],
            merged_from: None,
        })
    }

    /// The fingerprint of the values every shard file of one run stores identically, and of its
    /// confidence levels ([`shared_fingerprint`]): the root attributes `@shared_crc32` and
    /// `@confidence_crc32` when the file has them, else computed from the file's groups.
    ///
    /// # Errors
    /// As [`shared_fingerprint`].
    pub(crate) fn shared_fingerprint(&self) -> Result<(u32, u32)> {
        if has_attr(&self.file, L::ATTR_SHARED_CRC32) && has_attr(&self.file, L::ATTR_CONFIDENCE_CRC32) {
            return Ok((
                attr_scalar(&self.file, L::ATTR_SHARED_CRC32, &self.path)?,
                attr_scalar(&self.file, L::ATTR_CONFIDENCE_CRC32, &self.path)?,
            ));
        }
        shared_fingerprint(&self.file, &self.path, &self.meta)
    }

    /// Every row of the accumulator `name` (one per internal shard of the file, in order) in one read.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for an unknown name; [`Error::Hdf5`] on read failure.
    pub(crate) fn read_accumulator_rows(&self, name: &str) -> Result<Array2<f64>> {
        if !self.meta.accumulators.iter().any(|a| a.0 == name) {
            return Err(Error::invalid("accumulator", name, "not in this run"));
        }
        let what = format!("{}/{name}", L::GROUP_SHARDS);
        let d = self
            .file
            .dataset(&what)
            .map_err(h5err(&self.path, "opening an accumulator"))?;
        let len = self.meta.accumulators.iter().find(|a| a.0 == name).map_or(0, |a| a.1);
        check_shape(&d, &[self.meta.local_shards().len(), len], &self.path, &what)?;
        d.read_2d::<f64>().map_err(h5err(&self.path, "reading an accumulator"))
    }

    /// The checksums of every internal shard of the file (rows as in
    /// [`shard_checksums`](Self::shard_checksums)) in one read; `None` for format 1 (no checksums).
    ///
    /// # Errors
    /// [`Error::Hdf5`] on read failure.
    pub(crate) fn shard_checksum_rows(&self) -> Result<Option<Array2<u32>>> {
        if self.format_version < 2 {
            return Ok(None);
        }
        let what = format!("{}/{}", L::GROUP_SHARDS, L::DS_SHARDS_CHECKSUMS);
        let d = self
            .file
            .dataset(&what)
            .map_err(h5err(&self.path, "opening /shards/checksums"))?;
        check_checksum_shape(&d, &self.meta, &self.path)?;
        d.read_2d::<u32>()
            .map(Some)
            .map_err(h5err(&self.path, "reading /shards/checksums"))
    }

    /// The open file (for the optional groups read by [`super::transient_series`]).
    pub(super) fn h5(&self) -> &File {
        &self.file
    }

    /// The shape and the chunk shape of the dataset `path` (e.g. `outputs/travel`), or the reason it cannot
    /// be opened.
    pub fn dataset_shape(&self, path: &str) -> std::result::Result<(Vec<usize>, Vec<usize>), String> {
        match self.file.dataset(path) {
            Ok(ds) => Ok((ds.shape(), ds.chunk().unwrap_or_default())),
            Err(e) => Err(e.to_string()),
        }
    }

    /// The part of the run this file holds (a shard file), or `None` for a whole run.
    pub fn part(&self) -> Option<Part> {
        self.meta.part
    }

    /// What a merged file was merged from (`None` for a file written by one `simulate`).
    pub fn merged_from(&self) -> Option<&MergedFrom> {
        self.merged_from.as_ref()
    }

    /// For a merged file with virtual raw datasets: checks that the shard files holding `range` exist where
    /// HDF5 looks for them (relative names against the merged file's directory), so that a moved shard file
    /// is an error, not rows of fill values.
    fn check_virtual_sources(&self, range: std::ops::Range<usize>) -> Result<()> {
        let Some(m) = self.merged_from.as_ref().filter(|m| m.raw == RawStorage::Virtual) else {
            return Ok(());
        };
        let dir = self
            .path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        for src in m.sources(range) {
            let p = Path::new(&src.file);
            let resolved = if p.is_absolute() { p.to_path_buf() } else { dir.join(p) };
            if !resolved.is_file() {
                return Err(Error::Hdf5 {
                    path: self.path.clone(),
                    reason: format!(
                        "the raw realizations {}..{} are virtual: they live in the shard file `{}` (relative to \
                         the merged file's directory), which is not at {}: move the shard files back (the merged \
                         file and its shard directory may move together), or merge again with --copy",
                        src.realizations.start,
                        src.realizations.end,
                        src.file,
                        resolved.display()
                    ),
                });
            }
        }
        Ok(())
    }

    /// The row of internal shard `shard` (a global index) in the file's `/shards/*` datasets.
    fn shard_row(&self, shard: usize) -> Result<usize> {
        let s = self.meta.local_shards();
        if s.contains(&shard) {
            return Ok(shard - s.start);
        }
        Err(Error::invalid(
            "shard",
            shard,
            match self.meta.part {
                Some(p) => format!(
                    "shard file {} of {} holds the internal shards {}..{}",
                    p.index, p.count, s.start, s.end
                ),
                None => format!("the run has {} shards", self.meta.n_shards()),
            },
        ))
    }

    /// The checksums stored for internal shard `shard`: CRC-32 of its rows of every raw input, raw output,
    /// then accumulator (format ≥ 2; empty for format 1).
    ///
    /// # Errors
    /// As [`read_accumulator`](Self::read_accumulator).
    pub fn shard_checksums(&self, shard: usize) -> Result<Vec<u32>> {
        let row = self.shard_row(shard)?;
        if self.format_version < 2 {
            return Ok(Vec::new());
        }
        self.file
            .dataset(&format!("{}/{}", L::GROUP_SHARDS, L::DS_SHARDS_CHECKSUMS))
            .and_then(|d| d.read_slice_1d::<u32, _>(s![row, ..]))
            .map(|a| a.to_vec())
            .map_err(h5err(&self.path, "reading /shards/checksums"))
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The run's metadata (root attributes and signal lists).
    pub fn metadata(&self) -> &RunMetadata {
        &self.meta
    }

    /// `@format_version` of the file.
    pub fn format_version(&self) -> u32 {
        self.format_version
    }

    /// `@toolkit_version` of the file (crate version of the writer).
    pub fn toolkit_version(&self) -> &str {
        &self.toolkit_version
    }

    /// Whether `@complete` is set.
    pub fn is_complete(&self) -> bool {
        self.complete
    }

    /// Indices of the completed shards, ascending (global indices: of a shard file, only its own).
    pub fn completed_shards(&self) -> Vec<usize> {
        let first = self.meta.local_shards().start;
        (0..self.completed_shards.len())
            .filter(|&i| self.completed_shards[i])
            .map(|i| first + i)
            .collect()
    }

    /// Realization `realization` of a raw signal, `n_samples` values at t = k·dt.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if raw data are not stored, the name is unknown or the index is out of
    /// range; [`Error::Hdf5`] on read failure.
    pub fn read_signal(&self, group: SignalGroup, name: &str, realization: usize) -> Result<Vec<f64>> {
        Ok(self
            .read_signals(group, name, realization..realization + 1)?
            .into_raw_vec_and_offset()
            .0)
    }

    /// Realizations `range` of a raw signal as a `[range.len(), n_samples]` array (one read).
    ///
    /// # Errors
    /// As [`read_signal`](Self::read_signal).
    pub fn read_signals(&self, group: SignalGroup, name: &str, range: std::ops::Range<usize>) -> Result<Array2<f64>> {
        if !self.meta.store_raw {
            return Err(Error::invalid(
                "signal",
                name,
                "this run did not store raw realizations",
            ));
        }
        let list = match group {
            SignalGroup::Inputs => &self.meta.inputs,
            SignalGroup::Outputs => &self.meta.outputs,
        };
        if !list.iter().any(|s| s.name == name) {
            let known: Vec<&str> = list.iter().map(|s| s.name.as_str()).collect();
            return Err(Error::invalid(
                "signal",
                name,
                format!("not in /{} (has: {})", group.group_name(), known.join(", ")),
            ));
        }
        let local = self.meta.local_realizations();
        if range.start > range.end || range.start < local.start || range.end > local.end {
            return Err(Error::invalid(
                "realization",
                format!("{range:?}"),
                match self.meta.part {
                    Some(p) => format!(
                        "shard file {} of {} holds the realizations {}..{} of the run's {}",
                        p.index, p.count, local.start, local.end, self.meta.n_realizations
                    ),
                    None => format!("the run has {} realizations", self.meta.n_realizations),
                },
            ));
        }
        self.check_virtual_sources(range.clone())?;
        let ds = self
            .file
            .dataset(&format!("{}/{}", group.group_name(), name))
            .map_err(h5err(&self.path, "opening a signal dataset"))?;
        ds.read_slice_2d::<f64, _>(s![range.start - local.start..range.end - local.start, ..])
            .map_err(h5err(&self.path, "reading a signal"))
    }

    /// The accumulator vector `name` of shard `shard`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for an unknown name or a shard out of range; [`Error::Hdf5`] on read
    /// failure.
    pub fn read_accumulator(&self, name: &str, shard: usize) -> Result<Vec<f64>> {
        if !self.meta.accumulators.iter().any(|a| a.0 == name) {
            return Err(Error::invalid("accumulator", name, "not in this run"));
        }
        let row = self.shard_row(shard)?;
        let ds = self
            .file
            .dataset(&format!("{}/{}", L::GROUP_SHARDS, name))
            .map_err(h5err(&self.path, "opening an accumulator"))?;
        ds.read_slice_1d::<f64, _>(s![row, ..])
            .map(|a| a.to_vec())
            .map_err(h5err(&self.path, "reading an accumulator"))
    }

    /// All statistics in the file, in the order of the run's inputs then outputs.
    ///
    /// # Errors
    /// [`Error::Hdf5`] if a statistics group is malformed.
    pub fn statistics(&self) -> Result<Vec<OutputStatistics>> {
        let p = &self.path;
        let parent = self
            .file
            .group(L::GROUP_STATISTICS)
            .map_err(h5err(p, "opening /statistics"))?;
        let mut out = Vec::new();
        for sig in self.meta.inputs.iter().chain(&self.meta.outputs) {
            if !parent.link_exists(&sig.name) {
                continue;
            }
            let g = parent
                .group(&sig.name)
                .map_err(h5err(p, "opening a statistics group"))?;
            let names = attr_string_list(&g, L::ATTR_NAMES, p)?;
            let mut statistics = Vec::new();
            for name in names {
                let ds = g
                    .dataset(&name)
                    .map_err(h5err(p, &format!("opening statistic `{name}`")))?;
                let estimate = ds.read_scalar::<f64>().map_err(h5err(p, "reading a statistic"))?;
                let analytic = if has_attr(&ds, L::ATTR_ANALYTIC) {
                    Some(attr_scalar::<f64>(&ds, L::ATTR_ANALYTIC, p)?)
                } else {
                    None
                };
                let covers = if has_attr(&ds, L::ATTR_COVERS) {
                    Some(attr_scalar::<u8>(&ds, L::ATTR_COVERS, p)? != 0)
                } else {
                    None
                };
                let st = Statistic {
                    name,
                    interval: Interval {
                        estimate,
                        lower: attr_scalar(&ds, L::ATTR_LOWER, p)?,
                        upper: attr_scalar(&ds, L::ATTR_UPPER, p)?,
                        confidence: attr_scalar(&ds, L::ATTR_CONFIDENCE, p)?,
                    },
                    unit: attr_string(&ds, L::ATTR_UNIT, p)?,
                    method: attr_string(&ds, L::ATTR_METHOD, p)?,
                    analytic,
                    covers,
                };
                if self.format_version >= 2 {
                    let stored = attr_scalar::<u32>(&ds, L::ATTR_CRC32, p)?;
                    if stored != st.checksum() {
                        return Err(damaged(p, &format!("statistics/{}/{}", sig.name, st.name)));
                    }
                }
                statistics.push(st);
            }
            out.push(OutputStatistics {
                output: sig.name.clone(),
                unit: attr_string(&g, L::ATTR_UNIT, p)?,
                n_used: attr_scalar(&g, L::ATTR_N_USED, p)?,
                statistics,
            });
        }
        Ok(out)
    }

    /// All density estimates in the file, in the order of the run's inputs then outputs.
    ///
    /// # Errors
    /// [`Error::Hdf5`] if a density group is malformed.
    pub fn psd(&self) -> Result<Vec<PsdEstimate>> {
        let p = &self.path;
        let parent = self.file.group(L::GROUP_PSD).map_err(h5err(p, "opening /psd"))?;
        let mut out = Vec::new();
        for sig in self.meta.inputs.iter().chain(&self.meta.outputs) {
            if !parent.link_exists(&sig.name) {
                continue;
            }
            let g = parent.group(&sig.name).map_err(h5err(p, "opening a density group"))?;
            let read = |name: &str| -> Result<Vec<f64>> {
                read_whole(&g, name, MAX_LIST_LEN, p, &format!("psd/{}/{name}", sig.name))
            };
            let est = PsdEstimate {
                output: sig.name.clone(),
                unit: attr_string(&g, L::ATTR_UNIT, p)?,
                omega: read(L::DS_OMEGA)?,
                density: read(L::DS_DENSITY)?,
                lower: read(L::DS_LOWER)?,
                upper: read(L::DS_UPPER)?,
                analytic: if g.link_exists(L::DS_ANALYTIC) {
                    Some(read(L::DS_ANALYTIC)?)
                } else {
                    None
                },
                expected: if g.link_exists(L::DS_EXPECTED) {
                    Some(read(L::DS_EXPECTED)?)
                } else {
                    None
                },
                dof: attr_scalar(&g, L::ATTR_DOF, p)?,
                confidence: attr_scalar(&g, L::ATTR_CONFIDENCE, p)?,
                method: attr_string(&g, L::ATTR_METHOD, p)?,
            };
            if self.format_version >= 2 {
                let stored = attr_scalar::<u32>(&g, L::ATTR_CRC32, p)?;
                if stored != est.checksum() {
                    return Err(damaged(p, &format!("psd/{}", sig.name)));
                }
            }
            check_psd(&est, p)?;
            out.push(est);
        }
        Ok(out)
    }

    /// The response histograms of a nonlinear run (`/response_histogram`, optional: empty when the file
    /// has none), each checked against its `@crc32`.
    ///
    /// # Errors
    /// [`Error::Hdf5`] if a histogram is malformed or its checksum does not match.
    pub fn response_histograms(&self) -> Result<Vec<super::ResponseHistogram>> {
        let p = &self.path;
        if !self.file.link_exists(L::GROUP_RESPONSE_HISTOGRAM) {
            return Ok(Vec::new());
        }
        let parent = self
            .file
            .group(L::GROUP_RESPONSE_HISTOGRAM)
            .map_err(h5err(p, "opening /response_histogram"))?;
        let mut out = Vec::new();
        for sig in &self.meta.outputs {
            if parent.link_exists(&sig.name) {
                let g = parent
                    .group(&sig.name)
                    .map_err(h5err(p, "opening a response histogram"))?;
                out.push(super::ResponseHistogram::read(&g, &sig.name, p)?);
            }
        }
        Ok(out)
    }

    /// The rainflow range histograms of the run's fatigue verdict channels (`/rainflow`, optional: empty
    /// when the file has none), each checked against its `@crc32`.
    ///
    /// # Errors
    /// [`Error::Hdf5`] if a histogram group is malformed or its checksum does not match.
    pub fn rainflow(&self) -> Result<Vec<super::RainflowHistogram>> {
        let p = &self.path;
        if !self.file.link_exists(L::GROUP_RAINFLOW) {
            return Ok(Vec::new());
        }
        let parent = self
            .file
            .group(L::GROUP_RAINFLOW)
            .map_err(h5err(p, "opening /rainflow"))?;
        let mut out = Vec::new();
        for sig in &self.meta.outputs {
            if !parent.link_exists(&sig.name) {
                continue;
            }
            let g = parent.group(&sig.name).map_err(h5err(p, "opening a rainflow group"))?;
            let read = |name: &str| -> Result<Vec<f64>> {
                read_whole(&g, name, MAX_LIST_LEN, p, &format!("rainflow/{}/{name}", sig.name))
            };
            let h = super::RainflowHistogram {
                output: sig.name.clone(),
                unit: attr_string(&g, L::ATTR_UNIT, p)?,
                edges: read(L::DS_EDGES)?,
                counts: read(L::DS_COUNTS)?,
                overflow: attr_scalar(&g, L::ATTR_OVERFLOW, p)?,
                dirlik: if g.link_exists(L::DS_DIRLIK) {
                    Some(read(L::DS_DIRLIK)?)
                } else {
                    None
                },
            };
            if attr_scalar::<u32>(&g, L::ATTR_CRC32, p)? != h.checksum() || h.edges.len() != h.counts.len() + 1 {
                return Err(damaged(p, &format!("rainflow/{}", sig.name)));
            }
            out.push(h);
        }
        Ok(out)
    }

    /// Checks every checksum of the file: the rows of every completed shard (raw data and accumulators),
    /// the statistics and the density estimates (format ≥ 2; a format-1 file has none to check).
    ///
    /// # Errors
    /// [`Error::Hdf5`] naming the first damaged dataset ("checksum mismatch: the file is damaged").
    pub fn verify(&self) -> Result<Verification> {
        if self.format_version < 2 {
            return Ok(Verification {
                checked: 0,
                format_version: self.format_version,
            });
        }
        let p = &self.path;
        let shards = self.file.group(L::GROUP_SHARDS).map_err(h5err(p, "opening /shards"))?;
        let sums = shards
            .dataset(L::DS_SHARDS_CHECKSUMS)
            .map_err(h5err(p, "opening /shards/checksums"))?;
        let names = attr_string_list(&sums, L::ATTR_CHECKED, p)?;
        check_checksum_shape(&sums, &self.meta, p)?;
        let table = sums.read_2d::<u32>().map_err(h5err(p, "reading /shards/checksums"))?;
        if table.nrows() != self.meta.local_shards().len() || table.ncols() < names.len() {
            return Err(damaged(p, "shards/checksums"));
        }
        let mut checked = 0;
        let first_row = self.meta.local_realizations().start;
        for shard in self.completed_shards() {
            let range = self.meta.shard_range(shard);
            let row = self.shard_row(shard)?;
            if names.iter().any(|n| !n.starts_with(L::GROUP_SHARDS)) {
                self.check_virtual_sources(range.clone())?;
            }
            let range = range.start - first_row..range.end - first_row;
            for (j, name) in names.iter().enumerate() {
                let ds = self.file.dataset(name).map_err(h5err(p, &format!("opening {name}")))?;
                let crc = if name.starts_with(L::GROUP_SHARDS) {
                    let a = ds
                        .read_slice_1d::<f64, _>(s![row, ..])
                        .map_err(h5err(p, &format!("reading {name}")))?;
                    crate::store::checksum::crc32_f64(a.as_slice().unwrap_or(&[]))
                } else {
                    let a = ds
                        .read_slice_2d::<f64, _>(s![range.clone(), ..])
                        .map_err(h5err(p, &format!("reading {name}")))?;
                    crate::store::checksum::crc32_f64(a.as_standard_layout().as_slice().unwrap_or(&[]))
                };
                if crc != table[(row, j)] {
                    return Err(damaged(p, &format!("{name} (shard {shard})")));
                }
                checked += 1;
            }
        }
        checked += self.statistics()?.iter().map(|s| s.statistics.len()).sum::<usize>();
        checked += self.psd()?.len();
        Ok(Verification {
            checked,
            format_version: self.format_version,
        })
    }

    /// Closes the file (the same as dropping the value).
    pub fn close(self) {}
}

/// The result of [`RunFile::verify`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Verification {
    /// Checksums that matched (shard rows of every checked dataset, statistics, density estimates).
    pub checked: usize,
    /// Format version of the file (version 1 files carry no checksums).
    pub format_version: u32,
}

/// What `stochvib inspect --json` prints: the run's identity, sizes and statistics.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RunInfo {
    /// The file.
    pub path: PathBuf,
    /// Format version of the writer.
    pub format_version: u32,
    /// Toolkit version of the writer.
    pub toolkit_version: String,
    /// Master seed.
    pub seed: u64,
    /// Random generator and synthesis method.
    pub generator: String,
    /// Time step, s.
    pub dt: f64,
    /// Samples per realization.
    pub n_samples: usize,
    /// Realizations.
    pub n_realizations: usize,
    /// Shards.
    pub n_shards: usize,
    /// The part of the run a shard file holds (`None` for a whole run).
    pub part: Option<Part>,
    /// The realizations the file holds (all of them but for a shard file).
    pub realizations: std::ops::Range<usize>,
    /// What a merged file was merged from.
    pub merged_from: Option<MergedFrom>,
    /// Whether raw realizations are stored.
    pub store_raw: bool,
    /// Output signal names.
    pub outputs: Vec<String>,
    /// Statistics of every signal that has them.
    pub statistics: Vec<OutputStatistics>,
}

impl RunFile {
    /// The run's identity, sizes and statistics ([`RunInfo`]).
    ///
    /// # Errors
    /// As [`RunFile::statistics`].
    pub fn info(&self) -> Result<RunInfo> {
        let m = &self.meta;
        Ok(RunInfo {
            path: self.path.clone(),
            format_version: self.format_version,
            toolkit_version: self.toolkit_version.clone(),
            seed: m.seed,
            generator: m.generator.clone(),
            dt: m.dt,
            n_samples: m.n_samples,
            n_realizations: m.n_realizations,
            n_shards: m.n_shards(),
            part: m.part,
            realizations: m.local_realizations(),
            merged_from: self.merged_from.clone(),
            store_raw: m.store_raw,
            outputs: m.outputs.iter().map(|s| s.name.clone()).collect(),
            statistics: self.statistics()?,
        })
    }
}

/// Reads the run metadata from the root attributes and the signal / shard groups.
pub(crate) fn read_metadata(file: &File, path: &Path) -> Result<RunMetadata> {
    let version = attr_scalar::<u32>(file, L::ATTR_FORMAT_VERSION, path)?;
    if version > L::NEWEST_FORMAT_VERSION {
        return Err(Error::Hdf5 {
            path: path.to_path_buf(),
            reason: format!(
                "format version {version} is newer than this stochvib understands ({}); use a newer stochvib",
                L::NEWEST_FORMAT_VERSION
            ),
        });
    }
    let usize_attr = |name: &str| -> Result<usize> {
        let v = attr_scalar::<u64>(file, name, path)?;
        usize::try_from(v).map_err(|_| bad(path, name, "does not fit in usize"))
    };
    let compression_label = attr_string(file, L::ATTR_COMPRESSION, path)?;
    let compression = Compression::parse(&compression_label).map_err(|_| {
        bad(
            path,
            L::ATTR_COMPRESSION,
            &format!("unknown compression {compression_label:?}"),
        )
    })?;
    let (inputs, outputs) = read_signal_lists(file, path)?;
    let accumulators = read_accumulator_list(file, path)?;
    let meta = RunMetadata {
        scenario_text: attr_string(file, L::ATTR_SCENARIO, path)?,
        seed: attr_scalar::<u64>(file, L::ATTR_SEED, path)?,
        generator: attr_string(file, L::ATTR_GENERATOR, path)?,
        dt: attr_scalar::<f64>(file, L::ATTR_DT, path)?,
        n_samples: usize_attr(L::ATTR_N_SAMPLES)?,
        n_realizations: usize_attr(L::ATTR_N_REALIZATIONS)?,
        shard_size: usize_attr(L::ATTR_SHARD_SIZE)?,
        inputs,
        outputs,
        accumulators,
        store_raw: attr_scalar::<u8>(file, L::ATTR_STORE_RAW, path)? != 0,
        compression,
        provenance: if version >= 2 {
            read_provenance(file, path)?
        } else {
            vec![]
        },
        part: if version >= 3 && has_attr(file, L::ATTR_PART_INDEX) {
            let index = usize_attr(L::ATTR_PART_INDEX)?;
            let count = usize_attr(L::ATTR_PART_COUNT)?;
            Some(Part::new(index, count).map_err(|e| bad(path, L::ATTR_PART_INDEX, &e.to_string()))?)
        } else {
            None
        },
    };
    check_metadata(file, path, version, &meta, &usize_attr)?;
    Ok(meta)
}

/// The metadata read from a file of format `version` against its checksum, its own rules, the shard count,
/// the part attributes and the raw datasets' shapes.
fn check_metadata(
    file: &File,
    path: &Path,
    version: u32,
    meta: &RunMetadata,
    usize_attr: &dyn Fn(&str) -> Result<usize>,
) -> Result<()> {
    if version >= 2 && attr_scalar::<u32>(file, L::ATTR_METADATA_CRC32, path)? != meta.digest() {
        return Err(damaged(
            path,
            "the run metadata (root attributes, signal lists, provenance)",
        ));
    }
    meta.validate().map_err(|e| Error::Hdf5 {
        path: path.to_path_buf(),
        reason: format!("inconsistent run metadata: {e}"),
    })?;
    if usize_attr(L::ATTR_N_SHARDS)? != meta.n_shards() {
        return Err(bad(
            path,
            L::ATTR_N_SHARDS,
            "does not equal ceil(n_realizations / shard_size)",
        ));
    }
    check_part_attributes(path, meta, usize_attr)?;
    if meta.store_raw {
        check_raw_shapes(file, path, meta)?;
    }
    Ok(())
}

/// The input and output signal lists of a run file (`names` and `units` of `/inputs` and `/outputs`).
fn read_signal_lists(file: &File, path: &Path) -> Result<(Vec<Signal>, Vec<Signal>)> {
    let mut signals = Vec::new();
    for g in [L::GROUP_INPUTS, L::GROUP_OUTPUTS] {
        let group = file
            .group(g)
            .map_err(h5err(path, &format!("missing group /{g}: not a stochvib run file")))?;
        let names = attr_string_list(&group, L::ATTR_NAMES, path)?;
        let units = attr_string_list(&group, L::ATTR_UNITS_LIST, path)?;
        if names.len() != units.len() {
            return Err(bad(
                path,
                g,
                "the `names` and `units` attributes have different lengths",
            ));
        }
        signals.push(
            names
                .into_iter()
                .zip(units)
                .map(|(name, unit)| Signal { name, unit })
                .collect::<Vec<_>>(),
        );
    }
    let outputs = signals.pop().unwrap_or_default();
    let inputs = signals.pop().unwrap_or_default();
    Ok((inputs, outputs))
}

/// The accumulators of `/shards`: each dataset's name and row length.
fn read_accumulator_list(file: &File, path: &Path) -> Result<Vec<(String, usize)>> {
    let shards = file
        .group(L::GROUP_SHARDS)
        .map_err(h5err(path, "missing group /shards: not a stochvib run file"))?;
    let mut accumulators = Vec::new();
    for name in attr_string_list(&shards, L::ATTR_ACCUMULATORS, path)? {
        let ds = shards
            .dataset(&name)
            .map_err(h5err(path, &format!("missing accumulator dataset /shards/{name}")))?;
        let len = ds
            .shape()
            .get(1)
            .copied()
            .ok_or_else(|| bad(path, &name, "accumulator is not 2-D"))?;
        accumulators.push((name, len));
    }
    Ok(accumulators)
}

/// The part attributes of a shard file (first shard, shard count, first realization, realization count)
/// agree with its part index and count.
fn check_part_attributes(path: &Path, meta: &RunMetadata, usize_attr: &dyn Fn(&str) -> Result<usize>) -> Result<()> {
    if meta.part.is_some() {
        let (sh, r) = (meta.local_shards(), meta.local_realizations());
        for (name, want) in [
            (L::ATTR_FIRST_SHARD, sh.start),
            (L::ATTR_PART_SHARDS, sh.len()),
            (L::ATTR_FIRST_REALIZATION, r.start),
            (L::ATTR_PART_REALIZATIONS, r.len()),
        ] {
            if usize_attr(name)? != want {
                return Err(bad(path, name, "does not match the part index and count"));
            }
        }
    }
    Ok(())
}

/// Every raw dataset of a run with raw data is [realizations of the file, n_samples].
fn check_raw_shapes(file: &File, path: &Path, meta: &RunMetadata) -> Result<()> {
    for (g, list) in [(L::GROUP_INPUTS, &meta.inputs), (L::GROUP_OUTPUTS, &meta.outputs)] {
        for sig in list.iter() {
            let ds = file
                .dataset(&format!("{g}/{}", sig.name))
                .map_err(h5err(path, &format!("missing dataset /{g}/{}", sig.name)))?;
            if ds.shape() != [meta.local_realizations().len(), meta.n_samples] {
                return Err(bad(
                    path,
                    &format!("{g}/{}", sig.name),
                    &format!(
                        "shape {:?} is not [realizations of the file, n_samples] = [{}, {}]",
                        ds.shape(),
                        meta.local_realizations().len(),
                        meta.n_samples
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The fingerprint of the values every shard file of one run stores identically (they depend on the run's
/// plan, not on its realizations), and of the confidence levels of its intervals: CRC-32 of (every
/// statistic's name and the bits of its `@analytic` value or a marker for none; every density's analytic
/// and expected arrays; every rainflow histogram's edges and Dirlik counts, each as CRC-32 and length),
/// and CRC-32 of the bits of every statistic's `@confidence`. Reads attributes and those arrays only.
///
/// # Errors
/// [`Error::Hdf5`] if a statistics, density or histogram group is malformed.
pub(crate) fn shared_fingerprint(file: &File, p: &Path, meta: &RunMetadata) -> Result<(u32, u32)> {
    let mut shared: Vec<f64> = Vec::new();
    let mut confidence: Vec<f64> = Vec::new();
    let marker = f64::from_bits(u64::MAX);
    let crc_of = |g: &hdf5::Group, name: &str, what: &str| -> Result<f64> {
        if !g.link_exists(name) {
            return Ok(marker);
        }
        let v: Vec<f64> = read_whole(g, name, MAX_LIST_LEN, p, &format!("{what}/{name}"))?;
        Ok(f64::from_bits(
            super::checksum::crc32_f64(&v) as u64 | ((v.len() as u64) << 32),
        ))
    };
    let signals: Vec<&Signal> = meta.inputs.iter().chain(&meta.outputs).collect();
    if file.link_exists(L::GROUP_STATISTICS) {
        let parent = file
            .group(L::GROUP_STATISTICS)
            .map_err(h5err(p, "opening /statistics"))?;
        for sig in &signals {
            if !parent.link_exists(&sig.name) {
                continue;
            }
            let g = parent
                .group(&sig.name)
                .map_err(h5err(p, "opening a statistics group"))?;
            for name in attr_string_list(&g, L::ATTR_NAMES, p)? {
                let ds = g
                    .dataset(&name)
                    .map_err(h5err(p, &format!("opening statistic `{name}`")))?;
                shared.push(f64::from_bits(super::checksum::crc32(name.as_bytes()) as u64));
                shared.push(if has_attr(&ds, L::ATTR_ANALYTIC) {
                    attr_scalar::<f64>(&ds, L::ATTR_ANALYTIC, p)?
                } else {
                    marker
                });
                confidence.push(attr_scalar::<f64>(&ds, L::ATTR_CONFIDENCE, p)?);
            }
        }
    }
    for (group, datasets) in [
        (L::GROUP_PSD, [L::DS_ANALYTIC, L::DS_EXPECTED]),
        (L::GROUP_RAINFLOW, [L::DS_EDGES, L::DS_DIRLIK]),
    ] {
        if !file.link_exists(group) {
            continue;
        }
        let parent = file.group(group).map_err(h5err(p, &format!("opening /{group}")))?;
        for sig in &signals {
            if !parent.link_exists(&sig.name) {
                continue;
            }
            let g = parent.group(&sig.name).map_err(h5err(p, "opening a density group"))?;
            for d in datasets {
                shared.push(crc_of(&g, d, &format!("{group}/{}", sig.name))?);
            }
        }
    }
    Ok((
        super::checksum::crc32_f64(&shared),
        super::checksum::crc32_f64(&confidence),
    ))
}

/// How many file names a text report lists before it abbreviates ([`abbreviated_list`]).
pub const LISTED_FILES: usize = 4;

/// `items` joined by ", ", or the first `first` of them followed by "… and N more" when there are more
/// than `first + 1` (a text report of a merge of a thousand shard files stays one short line; `--json`
/// keeps the full list).
///
/// # Examples
/// ```
/// use stochvib::store::abbreviated_list;
/// let names: Vec<String> = (0..10).map(|i| format!("s{i}.h5")).collect();
/// assert_eq!(abbreviated_list(&names, 3), "s0.h5, s1.h5, s2.h5, … and 7 more");
/// assert_eq!(abbreviated_list(&names[..4], 3), "s0.h5, s1.h5, s2.h5, s3.h5");
/// ```
pub fn abbreviated_list(items: &[String], first: usize) -> String {
    if items.len() <= first + 1 {
        return items.join(", ");
    }
    format!("{}, … and {} more", items[..first].join(", "), items.len() - first)
}

/// `/parts` of a merged file, checked against the run's realizations.
fn read_parts_group(file: &File, path: &Path, meta: &RunMetadata) -> Result<Option<MergedFrom>> {
    if !file.link_exists(L::GROUP_PARTS) {
        return Ok(None);
    }
    let g = file.group(L::GROUP_PARTS).map_err(h5err(path, "opening /parts"))?;
    let list = |name: &str| -> Result<Vec<usize>> {
        g.attr(name)
            .and_then(|a| {
                if a.size() > MAX_LIST_LEN {
                    return Err(format!("{} entries, more than a merge has shard files", a.size()).into());
                }
                a.read_raw::<u64>()
            })
            .map(|v| v.into_iter().map(|x| x as usize).collect())
            .map_err(|e| missing_or(&g, name, path, e))
    };
    let raw_label = attr_string(&g, L::ATTR_RAW_STORAGE, path)?;
    let from = MergedFrom {
        files: attr_string_list(&g, L::ATTR_PART_FILES, path)?,
        first_realizations: list(L::ATTR_PART_FIRST_REALIZATIONS)?,
        realizations: list(L::ATTR_PART_REALIZATION_COUNTS)?,
        raw: RawStorage::parse(&raw_label)
            .ok_or_else(|| bad(path, "parts@raw", &format!("unknown raw storage {raw_label:?}")))?,
    };
    from.check(meta.n_realizations)
        .map_err(|e| bad(path, "parts", &e.to_string()))?;
    Ok(Some(from))
}

/// The `/shards/complete` flags.
pub(crate) fn read_shards_complete(file: &File, path: &Path, n_shards: usize) -> Result<Vec<bool>> {
    let d = file
        .dataset(&format!("{}/{}", L::GROUP_SHARDS, L::DS_SHARDS_COMPLETE))
        .map_err(h5err(path, "opening /shards/complete"))?;
    if d.size() != n_shards {
        return Err(bad(
            path,
            "shards/complete",
            &format!("has {} entries, expected {n_shards}", d.size()),
        ));
    }
    let flags = d.read_raw::<u8>().map_err(h5err(path, "reading /shards/complete"))?;
    if flags.len() != n_shards {
        return Err(bad(
            path,
            "shards/complete",
            &format!("has {} entries, expected {n_shards}", flags.len()),
        ));
    }
    Ok(flags.into_iter().map(|f| f == 1).collect())
}

/// The parts of `/provenance`, sorted by name (the order of [`RunMetadata::digest`]).
fn read_provenance(file: &File, path: &Path) -> Result<Vec<Provenance>> {
    let g = file
        .group(L::GROUP_PROVENANCE)
        .map_err(h5err(path, "missing group /provenance"))?;
    let identifies = attr_string_list(&g, L::ATTR_IDENTIFIES, path)?;
    let mut names = g.attr_names().map_err(h5err(path, "listing /provenance"))?;
    names.retain(|n| n != L::ATTR_IDENTIFIES);
    names.sort();
    names
        .into_iter()
        .map(|n| {
            Ok(Provenance {
                text: attr_string(&g, &n, path)?,
                identifies: identifies.contains(&n),
                name: n,
            })
        })
        .collect()
}

/// Values of a density estimate a reader can use: finite, non-negative, ascending ω, equal lengths.
fn check_psd(e: &PsdEstimate, path: &Path) -> Result<()> {
    let n = e.omega.len();
    let lens = [
        e.density.len(),
        e.lower.len(),
        e.upper.len(),
        e.analytic.as_ref().map_or(n, |a| a.len()),
    ];
    let ok = n > 0
        && lens.iter().all(|&l| l == n)
        && e.omega.windows(2).all(|w| w[1] > w[0])
        && e.omega
            .iter()
            .chain(&e.density)
            .chain(&e.lower)
            .chain(&e.upper)
            .all(|v| v.is_finite() && *v >= 0.0)
        && e.dof.is_finite()
        && e.dof > 0.0;
    if ok {
        Ok(())
    } else {
        Err(bad(
            path,
            &format!("psd/{}", e.output),
            "holds values no density estimate can have (lengths, order, negative or non-finite numbers): the file is damaged",
        ))
    }
}

/// A checksum mismatch.
pub(super) fn damaged(path: &Path, what: &str) -> Error {
    Error::Hdf5 {
        path: path.to_path_buf(),
        reason: format!("checksum mismatch in {what}: the file is damaged (its data are not what was written)"),
    }
}

fn bad(path: &Path, what: &str, reason: &str) -> Error {
    Error::Hdf5 {
        path: path.to_path_buf(),
        reason: format!("`{what}`: {reason}"),
    }
}

fn has_attr(loc: &Location, name: &str) -> bool {
    loc.attr_names().map(|n| n.iter().any(|x| x == name)).unwrap_or(false)
}

fn missing_or(loc: &Location, name: &str, path: &Path, e: hdf5::Error) -> Error {
    if has_attr(loc, name) {
        bad(path, &format!("{}@{name}", loc.name()), &format!("unreadable: {e}"))
    } else {
        bad(
            path,
            &format!("{}@{name}", loc.name()),
            "attribute missing: not a stochvib run file (or a damaged one)",
        )
    }
}

pub(super) fn attr_scalar<T: hdf5::H5Type>(loc: &Location, name: &str, path: &Path) -> Result<T> {
    loc.attr(name)
        .and_then(|a| a.read_scalar::<T>())
        .map_err(|e| missing_or(loc, name, path, e))
}

/// Most bytes of the strings of one attribute: the longest string a writer stores is the scenario's text,
/// a TOML file of at most 16 MiB (the input rule); more is a damaged file or one this toolkit did not write.
pub(crate) const MAX_ATTRIBUTE_BYTES: usize = crate::fields::MAX_INPUT_FILE_BYTES as usize;

/// Most elements of a list attribute or of a dataset that is read whole (names, density estimates,
/// histograms): a run has a few dozen signals and at most 513 density bins.
pub(crate) const MAX_LIST_LEN: usize = 1 << 20;

/// Refuses strings of more than [`MAX_ATTRIBUTE_BYTES`] read from attribute `name`.
fn bounded_strings(loc: &Location, name: &str, path: &Path, bytes: usize) -> Result<()> {
    if bytes > MAX_ATTRIBUTE_BYTES {
        return Err(bad(
            path,
            &format!("{}@{name}", loc.name()),
            &format!(
                "holds {bytes} bytes of text, more than the {MAX_ATTRIBUTE_BYTES} a run file's attribute has: the \
                 file is damaged or was not written by stochvib"
            ),
        ));
    }
    Ok(())
}

pub(super) fn attr_string(loc: &Location, name: &str, path: &Path) -> Result<String> {
    let s = loc
        .attr(name)
        .and_then(|a| a.read_scalar::<VarLenUnicode>())
        .map(|v| v.as_str().to_string())
        .map_err(|e| missing_or(loc, name, path, e))?;
    bounded_strings(loc, name, path, s.len())?;
    Ok(s)
}

fn attr_string_list(loc: &Location, name: &str, path: &Path) -> Result<Vec<String>> {
    let attr = loc.attr(name).map_err(|e| missing_or(loc, name, path, e))?;
    if attr.size() == 0 {
        return Ok(Vec::new());
    }
    if attr.size() > MAX_LIST_LEN {
        return Err(bad(
            path,
            &format!("{}@{name}", loc.name()),
            &format!(
                "lists {} names, more than the {MAX_LIST_LEN} a run file has: the file is damaged",
                attr.size()
            ),
        ));
    }
    let v: Vec<String> = attr
        .read_raw::<VarLenUnicode>()
        .map(|v| v.into_iter().map(|x| x.as_str().to_string()).collect())
        .map_err(|e| missing_or(loc, name, path, e))?;
    bounded_strings(loc, name, path, v.iter().map(String::len).sum())?;
    Ok(v)
}

/// Reads dataset `name` of `g` whole, refusing (before reading) one of more than `max` elements: a damaged
/// or foreign file may declare a dataset far larger than what is stored (an unwritten chunked dataset).
pub(crate) fn read_whole<T: hdf5::H5Type>(
    g: &hdf5::Group,
    name: &str,
    max: usize,
    path: &Path,
    what: &str,
) -> Result<Vec<T>> {
    let d = g.dataset(name).map_err(h5err(path, &format!("opening {what}")))?;
    if d.size() > max {
        return Err(bad(
            path,
            what,
            &format!(
                "has {} elements, more than the {max} a run file has there: the file is damaged",
                d.size()
            ),
        ));
    }
    d.read_raw::<T>().map_err(h5err(path, &format!("reading {what}")))
}

/// Refuses a `/shards/checksums` table that does not have one row per internal shard of the file and at
/// most [`MAX_LIST_LEN`] columns, before it is read whole.
fn check_checksum_shape(d: &hdf5::Dataset, meta: &RunMetadata, path: &Path) -> Result<()> {
    let shape = d.shape();
    if shape.len() != 2 || shape[0] != meta.local_shards().len() || shape[1] > MAX_LIST_LEN {
        return Err(bad(
            path,
            "shards/checksums",
            &format!(
                "has the shape {shape:?}, expected {} rows (one per shard): the file is damaged",
                meta.local_shards().len()
            ),
        ));
    }
    Ok(())
}

/// Refuses a dataset whose shape is not `expected` before it is read whole.
fn check_shape(d: &hdf5::Dataset, expected: &[usize], path: &Path, what: &str) -> Result<()> {
    if d.shape() != expected {
        return Err(bad(
            path,
            what,
            &format!(
                "has the shape {:?}, expected {expected:?}: the file is damaged",
                d.shape()
            ),
        ));
    }
    Ok(())
}
