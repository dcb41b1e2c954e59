//! Writing a run: temporary name, shard by shard, rename on completion, resume after interruption.

use super::checksum::crc32_f64;

/// Raw data of a shard from which its checksums are computed on a second thread, beside the write.
const OVERLAP_CHECKSUM_BYTES: usize = 1 << 20;

/// The checksums of a shard: each raw array (row-major little-endian bytes), then each accumulator.
fn shard_sums(inputs: &[ArrayView2<'_, f64>], outputs: &[ArrayView2<'_, f64>], accumulators: &[&[f64]]) -> Vec<u32> {
    inputs
        .iter()
        .chain(outputs)
        .map(|a| crc32_f64(a.as_standard_layout().as_slice().unwrap_or(&[])))
        .chain(accumulators.iter().map(|a| crc32_f64(a)))
        .collect()
}
use super::chunks;
use super::layout as L;
use super::parts::{MergedFrom, RawStorage};
use super::reader::{read_metadata, read_shards_complete};
use super::{h5err, open_sec2, tmp_path, Compression, OpenMode, OutputStatistics, PsdEstimate, RunMetadata};
use crate::error::{Error, Result};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, File, Location};
use ndarray::{s, ArrayView2};
use std::path::{Path, PathBuf};

/// Writes one run file; see [`crate::store`] for the layout and the interruption guarantees.
///
/// Dropping a writer without [`RunWriter::finish`] closes the file and leaves `<final>.tmp` for a later
/// resume; no file ever appears under the final name unless the run is complete.
#[derive(Debug)]
pub struct RunWriter {
    meta: RunMetadata,
    final_path: PathBuf,
    tmp: PathBuf,
    /// Completion of the file's own internal shards (`meta.local_shards()`, in order).
    completed: Vec<bool>,
    resumed: bool,
    overwrite: bool,
    notes: Vec<String>,
    // Handles: datasets first so that they are dropped before the file.
    inputs: Vec<Dataset>,
    outputs: Vec<Dataset>,
    accumulators: Vec<Dataset>,
    shards_complete: Dataset,
    checksums: Dataset,
    file: File,
}

/// How [`RunWriter::create_with`] treats what is already there.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CreateOptions {
    /// Replace an existing finished run file at the final rename (only a stochvib run file is ever
    /// replaced), and discard an interrupted run of different settings instead of refusing.
    pub overwrite: bool,
    /// Never resume: an existing `.tmp` that no live process is writing is replaced by a fresh file (a merge
    /// starts over, since its sources may have changed).
    pub restart: bool,
}

/// What a `.tmp` in the way is.
enum Existing {
    /// Resumable: same run.
    Resume(Box<RunWriter>),
    /// Another process is writing it.
    Busy(String),
    /// Nothing worth keeping (unreadable, or another run without a completed shard): replace it.
    Replace(String),
    /// Another run with completed shards: refuse (unless overwriting).
    Different(String, usize),
    /// Not an HDF5 file at all (not a run this toolkit left): refuse (unless overwriting).
    Foreign,
}

impl RunWriter {
    /// Starts a run that will end up at `final_path`, or resumes an interrupted one; an existing finished
    /// file is refused ([`RunWriter::create_with`] with default options).
    ///
    /// # Errors
    /// As [`RunWriter::create_with`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::store::{RunMetadata, RunWriter, RunFile, Signal, Compression};
    /// use ndarray::Array2;
    /// let dir = std::env::temp_dir().join(format!("stochvib-doc-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir).unwrap();
    /// let path = dir.join("doc.h5");
    /// # let _ = std::fs::remove_file(&path);
    /// let meta = RunMetadata {
    ///     scenario_text: "[run]\n".into(), seed: 7, generator: "xoshiro256++".into(), dt: 0.01,
    ///     n_samples: 4, n_realizations: 2, shard_size: 2,
    ///     inputs: vec![Signal::new("road", "m")], outputs: vec![Signal::new("x1", "m")],
    ///     accumulators: vec![], store_raw: true, compression: Compression::None, provenance: vec![], part: None,
    /// };
    /// let mut w = RunWriter::create(&path, &meta).unwrap();
    /// let u = Array2::from_shape_fn((2, 4), |(i, k)| (i * 4 + k) as f64);
    /// w.write_shard(0, &[u.view()], &[u.view()], &[]).unwrap();
    /// let done = w.finish().unwrap();
    /// let run = RunFile::open(&done).unwrap();
    /// assert_eq!(run.read_signal(stochvib::store::SignalGroup::Outputs, "x1", 1).unwrap(), vec![4.0, 5.0, 6.0, 7.0]);
    /// # drop(run); std::fs::remove_file(&done).unwrap();
    /// ```
    pub fn create(final_path: impl AsRef<Path>, meta: &RunMetadata) -> Result<RunWriter> {
        Self::create_with(final_path, meta, CreateOptions::default())
    }

    /// Starts a run that will end up at `final_path`, or resumes an interrupted one.
    ///
    /// The run is written to `<final_path>.tmp` (see [`tmp_path`]). A fresh `.tmp` is built under a name of
    /// this process's own and appears under the `.tmp` name only when its skeleton is complete (claimed by
    /// an atomic hard link), so a kill during set-up never leaves a `.tmp` that cannot be resumed. An
    /// existing `.tmp` of the same run (same metadata and provenance, same toolkit version) is reopened and
    /// [`completed_shards`](Self::completed_shards) says which shards are on disk (a completed shard whose
    /// checksum fails is recomputed). A `.tmp` that cannot be read, or holds another run without any
    /// completed shard, is replaced with a note ([`RunWriter::notes`]); another run with completed shards is
    /// refused unless `options.overwrite`. A `.tmp` another process is writing is never touched. Only files
    /// this process created are ever deleted.
    ///
    /// # Errors
    /// - [`Error::InvalidParameter`] if `meta` fails [`RunMetadata::validate`].
    /// - [`Error::Hdf5`] if `final_path` is a directory or not a regular file, if it already exists and
    ///   `options.overwrite` is not set (a finished run is never overwritten silently) or it is not a
    ///   stochvib run file, if its directory does not exist, if another process is writing the run (named by
    ///   its pid), if the `.tmp` holds a different run with completed shards (the message lists what
    ///   differs), or if HDF5 fails.
    pub fn create_with(final_path: impl AsRef<Path>, meta: &RunMetadata, options: CreateOptions) -> Result<RunWriter> {
        Self::create_inner(final_path.as_ref(), meta, options, None)
    }

    /// Starts the file of a merge (`stochvib merge`): a whole run (`meta.part` is `None`) whose `/parts`
    /// group records the shard files it comes from, and whose raw datasets, with
    /// [`RawStorage::Virtual`], are virtual datasets mapping each shard file's rows (the merged file stays
    /// small; see `docs/run-file-format.md` for what happens when the shard files move). An existing `.tmp`
    /// is never resumed (as with [`CreateOptions::restart`]).
    ///
    /// # Errors
    /// As [`RunWriter::create_with`]; [`Error::InvalidParameter`] if `meta` is a part, or if `from` does not
    /// tile the realizations `0..n_realizations`.
    pub fn create_merged(
        final_path: impl AsRef<Path>,
        meta: &RunMetadata,
        options: CreateOptions,
        from: &MergedFrom,
    ) -> Result<RunWriter> {
        if meta.part.is_some() {
            return Err(Error::invalid("part", "a part", "a merged file holds the whole run"));
        }
        from.check(meta.n_realizations)?;
        let options = CreateOptions {
            restart: true,
            ..options
        };
        Self::create_inner(final_path.as_ref(), meta, options, Some(from))
    }

    fn create_inner(
        final_path: &Path,
        meta: &RunMetadata,
        options: CreateOptions,
        merged: Option<&MergedFrom>,
    ) -> Result<RunWriter> {
        meta.validate()?;
        let final_path = final_path.to_path_buf();
        check_final_path(&final_path, options.overwrite)?;
        let tmp = tmp_path(&final_path);
        remove_stale_claims(&tmp);
        let mut notes = Vec::new();
        for _attempt in 0..3 {
            if tmp.exists() {
                let found = match Self::examine(&final_path, &tmp, meta) {
                    Existing::Resume(w) if options.restart => {
                        drop(w);
                        Existing::Replace("a merge always starts over".into())
                    }
                    other => other,
                };
                match found {
                    Existing::Resume(w) => {
                        let mut w = *w;
                        w.overwrite = options.overwrite;
                        w.notes.extend(notes);
                        write_owner(&tmp);
                        return Ok(w);
                    }
                    Existing::Busy(who) => {
                        return Err(Error::Hdf5 {
                            path: tmp,
                            reason: format!(
                                "another process {who} is writing this run: wait for it to finish, or choose \
                                 another output"
                            ),
                        })
                    }
                    Existing::Replace(why) => notes.push(format!("replaced {}: {why}", tmp.display())),
                    Existing::Different(diff, done) if options.overwrite => notes.push(format!(
                        "discarded the interrupted run {} ({done} shards written; differs in {diff}) as --overwrite \
                         asks",
                        tmp.display()
                    )),
                    Existing::Foreign if options.overwrite => notes.push(format!(
                        "replaced {}: it was not an HDF5 file (not an interrupted run), as --overwrite asks",
                        tmp.display()
                    )),
                    Existing::Foreign => {
                        return Err(Error::Hdf5 {
                            path: tmp,
                            reason: "is in the way of this run's temporary file and is not an HDF5 file (not a run \
                                     this toolkit interrupted): it is never removed silently; remove it, choose \
                                     another output, or pass --overwrite to replace it"
                                .into(),
                        })
                    }
                    Existing::Different(diff, done) => {
                        return Err(Error::Hdf5 {
                            path: tmp,
                            reason: format!(
                                "an interrupted run with {done} completed shards is in the way and differs in {diff}: \
                                 rerun with the original settings to resume it, or pass --overwrite to discard it"
                            ),
                        })
                    }
                }
                // replace: build a fresh file and rename it over the `.tmp` (atomic; no window without a file)
                let w = Self::create_fresh(final_path.clone(), tmp.clone(), meta, true, merged)?;
                return Ok(RunWriter {
                    overwrite: options.overwrite,
                    notes,
                    ..w
                });
            }
            match Self::create_fresh(final_path.clone(), tmp.clone(), meta, false, merged) {
                Ok(w) => {
                    return Ok(RunWriter {
                        overwrite: options.overwrite,
                        notes,
                        ..w
                    })
                }
                // another process claimed the `.tmp` first: look at it again
                Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(e),
            }
        }
        Err(Error::Hdf5 {
            path: tmp,
            reason: "other processes keep creating and removing this run's temporary file: choose another output"
                .into(),
        })
    }

    /// Decides what to do with an existing `.tmp`.
    fn examine(final_path: &Path, tmp: &Path, meta: &RunMetadata) -> Existing {
        if let Some(pid) = owner_alive(tmp) {
            return Existing::Busy(format!("(pid {pid})"));
        }
        if !is_hdf5(tmp) {
            return Existing::Foreign;
        }
        let file = match open_file(tmp, OpenMode::ReadWrite, meta.compression) {
            Ok(f) => f,
            Err(err) if err.to_string().contains("unable to lock") => {
                return Existing::Busy("(HDF5 holds its lock)".into())
            }
            Err(err) => return Existing::Replace(format!("not readable as an HDF5 file ({err})")),
        };
        let stored = match read_metadata(&file, tmp) {
            Ok(m) => m,
            Err(err) => return Existing::Replace(format!("not a readable run ({err})")),
        };
        let done = read_shards_complete(&file, tmp, stored.local_shards().len())
            .map(|c| c.iter().filter(|x| **x).count())
            .unwrap_or(0);
        let toolkit = attr_string_of(&file, L::ATTR_TOOLKIT_VERSION).unwrap_or_default();
        let mut differ = metadata_differences(&stored, meta);
        if toolkit != L::TOOLKIT_VERSION {
            differ.push(format!(
                "toolkit version (written by stochvib {toolkit}, this is {}; a run is only resumed by the version \
                 that started it, which guarantees bit-identical results)",
                L::TOOLKIT_VERSION
            ));
        }
        if !differ.is_empty() {
            drop(file);
            return if done == 0 {
                Existing::Replace(format!(
                    "another run without a completed shard (differs in {})",
                    differ.join(", ")
                ))
            } else {
                Existing::Different(differ.join(", "), done)
            };
        }
        match Self::reopen(final_path.to_path_buf(), tmp.to_path_buf(), meta, file) {
            Ok(w) => Existing::Resume(Box::new(w)),
            Err(e) => Existing::Replace(format!("cannot be resumed ({e})")),
        }
    }

    /// Builds a fresh run file under a name of this process's own, then claims `tmp` with it: by an atomic
    /// hard link (fails with `AlreadyExists` if another process claimed it first) or, with `replace`, by a
    /// rename over the existing `.tmp`.
    fn create_fresh(
        final_path: PathBuf,
        tmp: PathBuf,
        meta: &RunMetadata,
        replace: bool,
        merged: Option<&MergedFrom>,
    ) -> Result<RunWriter> {
        let unique = claim_path(&tmp);
        let build = || -> Result<RunWriter> {
            let w = Self::build(final_path.clone(), unique.clone(), meta, merged)?;
            let io = |source| Error::Io {
                path: tmp.clone(),
                source,
            };
            if replace {
                std::fs::rename(&unique, &tmp).map_err(io)?;
            } else {
                std::fs::hard_link(&unique, &tmp).map_err(io)?;
                std::fs::remove_file(&unique).map_err(io)?;
            }
            write_owner(&tmp);
            Ok(RunWriter { tmp: tmp.clone(), ..w })
        };
        let r = build();
        // only this process's own file is ever removed
        let _ = std::fs::remove_file(&unique);
        r
    }

    /// Creates every group, dataset and attribute of a run in a new file `path`.
    fn build(final_path: PathBuf, path: PathBuf, meta: &RunMetadata, merged: Option<&MergedFrom>) -> Result<RunWriter> {
        let e = |what: &str| h5err(&path, what);
        let file =
            open_file(&path, OpenMode::CreateExcl, meta.compression).map_err(e("cannot create the temporary file"))?;
        let virtual_raw = merged.filter(|m| m.raw == RawStorage::Virtual && meta.store_raw);
        let version = if meta.part.is_some() || virtual_raw.is_some() {
            L::FORMAT_VERSION_PARTS
        } else {
            L::FORMAT_VERSION
        };
        write_root_attrs(&file, meta, version).map_err(e("writing root attributes"))?;
        if let Some(m) = merged {
            write_parts_group(&file, m).map_err(e("writing /parts"))?;
        }

        let n_shards = meta.local_shards().len();
        let inputs = create_signals(&file, &path, L::GROUP_INPUTS, &meta.inputs, meta, virtual_raw)?;
        let outputs = create_signals(&file, &path, L::GROUP_OUTPUTS, &meta.outputs, meta, virtual_raw)?;
        let shards = file.create_group(L::GROUP_SHARDS).map_err(e("creating /shards"))?;
        let (shards_complete, checksums, accumulators) = create_shard_sets(&shards, &path, meta)?;
        file.create_group(L::GROUP_STATISTICS)
            .map_err(e("creating /statistics"))?;
        file.create_group(L::GROUP_PSD).map_err(e("creating /psd"))?;
        drop(shards);
        file.flush().map_err(e("flushing"))?;
        Ok(RunWriter {
            meta: meta.clone(),
            final_path,
            tmp: path,
            completed: vec![false; n_shards],
            resumed: false,
            overwrite: false,
            notes: Vec::new(),
            inputs,
            outputs,
            accumulators,
            shards_complete,
            checksums,
            file,
        })
    }

    /// Reopens an interrupted run of the same metadata; completed shards whose checksums fail are marked
    /// pending again (they are recomputed).
    fn reopen(final_path: PathBuf, tmp: PathBuf, meta: &RunMetadata, file: File) -> Result<RunWriter> {
        let open_set = |group: &str, name: &str| -> Result<Dataset> {
            file.dataset(&format!("{group}/{name}"))
                .map_err(h5err(&tmp, &format!("opening dataset {group}/{name}")))
        };
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        if meta.store_raw {
            for s in &meta.inputs {
                inputs.push(open_set(L::GROUP_INPUTS, &s.name)?);
            }
            for s in &meta.outputs {
                outputs.push(open_set(L::GROUP_OUTPUTS, &s.name)?);
            }
        }
        let mut accumulators = Vec::new();
        for (name, _) in &meta.accumulators {
            accumulators.push(open_set(L::GROUP_SHARDS, name)?);
        }
        let shards_complete = open_set(L::GROUP_SHARDS, L::DS_SHARDS_COMPLETE)?;
        let checksums = open_set(L::GROUP_SHARDS, L::DS_SHARDS_CHECKSUMS)?;
        let mut completed = read_shards_complete(&file, &tmp, meta.local_shards().len())?;
        let mut w = RunWriter {
            meta: meta.clone(),
            final_path,
            tmp,
            completed: vec![false; meta.local_shards().len()],
            resumed: true,
            overwrite: false,
            notes: Vec::new(),
            inputs,
            outputs,
            accumulators,
            shards_complete,
            checksums,
            file,
        };
        let mut damaged = Vec::new();
        let first = meta.local_shards().start;
        for (local, done) in completed.iter_mut().enumerate() {
            if *done && !w.shard_intact(first + local)? {
                *done = false;
                damaged.push((first + local).to_string());
            }
        }
        if !damaged.is_empty() {
            w.notes.push(format!(
                "shards {} of the interrupted run failed their checksums and are recomputed",
                damaged.join(", ")
            ));
        }
        w.completed = completed;
        Ok(w)
    }

    /// The row of internal shard `shard` (a global index) in this file's `/shards/*` datasets, and its rows
    /// in the raw datasets.
    fn local(&self, shard: usize) -> Option<(usize, std::ops::Range<usize>)> {
        let shards = self.meta.local_shards();
        if !shards.contains(&shard) {
            return None;
        }
        let first_row = self.meta.local_realizations().start;
        let r = self.meta.shard_range(shard);
        Some((shard - shards.start, r.start - first_row..r.end - first_row))
    }

    /// The local row of `shard`, or an error saying which shards this file holds.
    fn local_or_err(&self, shard: usize) -> Result<(usize, std::ops::Range<usize>)> {
        self.local(shard).ok_or_else(|| {
            let s = self.meta.local_shards();
            Error::invalid(
                "shard",
                shard,
                match self.meta.part {
                    Some(p) => format!(
                        "shard file {} of {} holds the internal shards {}..{}",
                        p.index, p.count, s.start, s.end
                    ),
                    None => format!("the run has {} shards", self.meta.n_shards()),
                },
            )
        })
    }

    /// Whether the stored data of a completed shard match their checksums.
    fn shard_intact(&self, shard: usize) -> Result<bool> {
        let (row, _) = self.local_or_err(shard)?;
        let stored = self
            .checksums
            .read_slice_1d::<u32, _>(s![row, ..])
            .map_err(h5err(&self.tmp, "reading /shards/checksums"))?;
        let now = self.shard_checksums(shard)?;
        Ok(stored.iter().zip(&now).all(|(a, b)| a == b) && stored.len() >= now.len())
    }

    /// The checksums of shard `shard` as stored on disk now (raw rows, then accumulators).
    fn shard_checksums(&self, shard: usize) -> Result<Vec<u32>> {
        let (row, range) = self.local_or_err(shard)?;
        let e = |what: &str| h5err(&self.tmp, what);
        let mut out = Vec::new();
        for ds in self.inputs.iter().chain(&self.outputs) {
            let a = ds
                .read_slice_2d::<f64, _>(s![range.clone(), ..])
                .map_err(e("reading a shard for its checksum"))?;
            out.push(crc32_f64(a.as_standard_layout().as_slice().unwrap_or(&[])));
        }
        for ds in &self.accumulators {
            let a = ds
                .read_slice_1d::<f64, _>(s![row, ..])
                .map_err(e("reading an accumulator for its checksum"))?;
            out.push(crc32_f64(a.as_slice().unwrap_or(&[])));
        }
        Ok(out)
    }

    /// Remarks on what [`create_with`](Self::create_with) found (a replaced or discarded `.tmp`, recomputed
    /// shards).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The run's metadata.
    pub fn metadata(&self) -> &RunMetadata {
        &self.meta
    }

    /// The temporary file being written.
    pub fn tmp_path(&self) -> &Path {
        &self.tmp
    }

    /// Whether [`create`](Self::create) reopened an interrupted run.
    pub fn resumed(&self) -> bool {
        self.resumed
    }

    /// Indices of the shards already on disk, ascending (global indices: of a shard file, only its own).
    pub fn completed_shards(&self) -> Vec<usize> {
        self.meta.local_shards().filter(|&b| self.is_completed(b)).collect()
    }

    /// Indices of the shards still to be written, ascending (global indices: of a shard file, only its own).
    pub fn pending_shards(&self) -> Vec<usize> {
        self.meta.local_shards().filter(|&b| !self.is_completed(b)).collect()
    }

    fn is_completed(&self, shard: usize) -> bool {
        self.local(shard).is_some_and(|(row, _)| self.completed[row])
    }

    /// Writes shard `shard`: its rows of every input and output, and its accumulator vectors.
    ///
    /// `inputs[j]` and `outputs[j]` are `[rows, n_samples]` arrays (rows = length of
    /// [`RunMetadata::shard_range`]) in the order of [`RunMetadata::inputs`] / [`RunMetadata::outputs`];
    /// both must be empty slices when raw data are not stored. `accumulators[j]` has the length declared
    /// in [`RunMetadata::accumulators`]. Each array is written with one hyperslab write; then the file is
    /// flushed, the shard is marked complete and the file is flushed again.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a shard index out of range, an already completed shard, a wrong
    /// number of arrays or a wrong shape; [`Error::Hdf5`] if writing fails.
    pub fn write_shard(
        &mut self,
        shard: usize,
        inputs: &[ArrayView2<'_, f64>],
        outputs: &[ArrayView2<'_, f64>],
        accumulators: &[&[f64]],
    ) -> Result<()> {
        let (row, range) = self.local_or_err(shard)?;
        if self.completed[row] {
            return Err(Error::invalid(
                "shard",
                shard,
                "already written (completed shards cannot be rewritten)",
            ));
        }
        let rows = range.len();
        for (field, arrays, expected) in [
            ("inputs", inputs, self.inputs.len()),
            ("outputs", outputs, self.outputs.len()),
        ] {
            if arrays.len() != expected {
                let why = if self.meta.store_raw {
                    format!("expected {expected} arrays, one per declared signal")
                } else {
                    "raw realizations are not stored in this run: pass an empty slice".to_string()
                };
                return Err(Error::invalid(field, arrays.len(), why));
            }
            for a in arrays {
                if a.dim() != (rows, self.meta.n_samples) {
                    return Err(Error::invalid(
                        field,
                        format!("array of shape {:?}", a.dim()),
                        format!("shard {shard} needs shape ({rows}, {})", self.meta.n_samples),
                    ));
                }
            }
        }
        if accumulators.len() != self.accumulators.len() {
            return Err(Error::invalid(
                "accumulators",
                accumulators.len(),
                format!("expected {} vectors", self.accumulators.len()),
            ));
        }
        for (a, (name, len)) in accumulators.iter().zip(&self.meta.accumulators) {
            if a.len() != *len {
                return Err(Error::invalid(
                    name,
                    a.len(),
                    format!("accumulator length must be {len}"),
                ));
            }
        }
        // the checksums are computed on another thread while the rows are written (or filtered): the data
        // are read once more from memory, but that pass is off the write's critical path
        let sums = std::thread::scope(|scope| -> Result<Vec<u32>> {
            let bytes: usize = inputs.iter().chain(outputs).map(|a| a.len() * 8).sum();
            let sums =
                (bytes >= OVERLAP_CHECKSUM_BYTES).then(|| scope.spawn(|| shard_sums(inputs, outputs, accumulators)));
            self.write_rows(range, inputs, outputs)?;
            Ok(match sums {
                Some(h) => h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)),
                None => shard_sums(inputs, outputs, accumulators),
            })
        })?;
        self.finish_shard(row, accumulators, sums)
    }

    /// Writes the rows `range` of every input and output (filtered on all threads when compressed).
    fn write_rows(
        &self,
        range: std::ops::Range<usize>,
        inputs: &[ArrayView2<'_, f64>],
        outputs: &[ArrayView2<'_, f64>],
    ) -> Result<()> {
        let e = |what: &str| h5err(&self.tmp, what);
        for (ds, a) in self
            .inputs
            .iter()
            .chain(&self.outputs)
            .zip(inputs.iter().chain(outputs))
        {
            match self.meta.compression {
                Compression::None => {
                    let a = a.as_standard_layout();
                    ds.write_slice(&a, s![range.clone(), ..])
                        .map_err(e("writing a shard"))?;
                }
                // Filtered here on all threads, stored as is (HDF5 would filter serially).
                Compression::Deflate { level } => {
                    let chunk = raw_chunk(&self.meta);
                    // local rows start at a multiple of shard_size, hence of the chunk's rows
                    let filtered = chunks::filter_block(a.view(), range.start, chunk, level);
                    chunks::write_filtered(ds, &filtered).map_err(e("writing a compressed shard"))?;
                }
            }
        }
        Ok(())
    }

    /// Writes a shard's accumulators and checksums, flushes, marks it complete and flushes again.
    fn finish_shard(&mut self, row: usize, accumulators: &[&[f64]], mut sums: Vec<u32>) -> Result<()> {
        let e = |what: &str| h5err(&self.tmp, what);
        for (ds, a) in self.accumulators.iter().zip(accumulators) {
            ds.write_slice(*a, s![row, ..]).map_err(e("writing an accumulator"))?;
        }
        sums.resize(self.checksums.shape()[1], 0);
        self.checksums
            .write_slice(&sums[..], s![row, ..])
            .map_err(e("writing shard checksums"))?;
        self.file.flush().map_err(e("flushing a shard"))?;
        self.shards_complete
            .write_slice(&[1u8][..], s![row..row + 1])
            .map_err(e("marking a shard complete"))?;
        self.file.flush().map_err(e("flushing a shard marker"))?;
        self.completed[row] = true;
        Ok(())
    }

    /// Records shard `shard` of a merged file whose raw datasets are virtual (or absent): its accumulator
    /// vectors and the checksums of its rows as the shard file stored them (raw rows, then accumulators;
    /// the raw rows are read through the virtual datasets when the file is verified).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if the file stores raw data of its own (use
    /// [`write_shard`](Self::write_shard)), for a shard out of range or already written, wrong accumulator
    /// lengths, or checksums of the accumulators that do not match them; [`Error::Hdf5`] if writing fails.
    pub fn adopt_shard(&mut self, shard: usize, accumulators: &[&[f64]], checksums: &[u32]) -> Result<()> {
        if self.meta.store_raw
            && !self
                .inputs
                .iter()
                .chain(&self.outputs)
                .all(|d| d.layout() == hdf5::plist::dataset_create::Layout::Virtual)
        {
            return Err(Error::invalid(
                "shard",
                shard,
                "this file stores its raw data itself: write the rows with write_shard",
            ));
        }
        let (row, _) = self.local_or_err(shard)?;
        if self.completed[row] {
            return Err(Error::invalid("shard", shard, "already written"));
        }
        if accumulators.len() != self.accumulators.len() {
            return Err(Error::invalid(
                "accumulators",
                accumulators.len(),
                format!("expected {} vectors", self.accumulators.len()),
            ));
        }
        for (a, (name, len)) in accumulators.iter().zip(&self.meta.accumulators) {
            if a.len() != *len {
                return Err(Error::invalid(
                    name,
                    a.len(),
                    format!("accumulator length must be {len}"),
                ));
            }
        }
        let raw = if self.meta.store_raw {
            self.inputs.len() + self.outputs.len()
        } else {
            0
        };
        if checksums.len() < raw + accumulators.len() {
            return Err(Error::invalid(
                "checksums",
                checksums.len(),
                "one per raw signal and accumulator",
            ));
        }
        for (j, a) in accumulators.iter().enumerate() {
            if crc32_f64(a) != checksums[raw + j] {
                return Err(Error::invalid(
                    &self.meta.accumulators[j].0,
                    shard,
                    "does not match its checksum: the shard file is damaged",
                ));
            }
        }
        self.finish_shard(row, accumulators, checksums.to_vec())
    }

    /// Records the consecutive shards `first..first + k` of a merged file whose raw datasets are virtual (or
    /// absent) at once, as [`adopt_shard`](Self::adopt_shard) does one by one: `accumulators[j]` holds row
    /// r = the accumulator vector of shard `first + r` (k rows), `checksums` row r its checksums (raw rows,
    /// then accumulators). One write per dataset and two flushes for the whole block (a merge of a
    /// thousand one-shard files would otherwise spend its time in per-shard writes and flushes).
    ///
    /// # Errors
    /// As [`adopt_shard`](Self::adopt_shard), for every shard of the block; [`Error::InvalidParameter`] if
    /// the arrays do not have k rows or the block leaves the file's shards.
    pub(crate) fn adopt_shards(
        &mut self,
        first: usize,
        accumulators: &[ArrayView2<'_, f64>],
        checksums: ArrayView2<'_, u32>,
    ) -> Result<()> {
        let k = checksums.nrows();
        if k == 0 {
            return Ok(());
        }
        if self.meta.store_raw
            && !self
                .inputs
                .iter()
                .chain(&self.outputs)
                .all(|d| d.layout() == hdf5::plist::dataset_create::Layout::Virtual)
        {
            return Err(Error::invalid(
                "shard",
                first,
                "this file stores its raw data itself: write the rows with write_shard",
            ));
        }
        let (row0, _) = self.local_or_err(first)?;
        let (last, _) = self.local_or_err(first + k - 1)?;
        if let Some(r) = (row0..=last).find(|&r| self.completed[r]) {
            return Err(Error::invalid("shard", first + r - row0, "already written"));
        }
        if accumulators.len() != self.accumulators.len() {
            return Err(Error::invalid(
                "accumulators",
                accumulators.len(),
                format!("expected {} blocks", self.accumulators.len()),
            ));
        }
        for (a, (name, len)) in accumulators.iter().zip(&self.meta.accumulators) {
            if a.dim() != (k, *len) {
                return Err(Error::invalid(
                    name,
                    format!("block of shape {:?}", a.dim()),
                    format!("{k} shards need shape ({k}, {len})"),
                ));
            }
        }
        let raw = if self.meta.store_raw {
            self.inputs.len() + self.outputs.len()
        } else {
            0
        };
        if checksums.ncols() < raw + accumulators.len() {
            return Err(Error::invalid(
                "checksums",
                checksums.ncols(),
                "one per raw signal and accumulator",
            ));
        }
        for (j, a) in accumulators.iter().enumerate() {
            for (r, row) in a.rows().into_iter().enumerate() {
                let row = row.as_standard_layout();
                if crc32_f64(row.as_slice().unwrap_or(&[])) != checksums[(r, raw + j)] {
                    return Err(Error::invalid(
                        &self.meta.accumulators[j].0,
                        first + r,
                        "does not match its checksum: the shard file is damaged",
                    ));
                }
            }
        }
        let e = |what: &str| h5err(&self.tmp, what);
        let rows = row0..row0 + k;
        for (ds, a) in self.accumulators.iter().zip(accumulators) {
            ds.write_slice(&a.as_standard_layout(), s![rows.clone(), ..])
                .map_err(e("writing accumulators"))?;
        }
        let width = self.checksums.shape()[1];
        let mut sums = ndarray::Array2::<u32>::zeros((k, width));
        let n = width.min(checksums.ncols());
        sums.slice_mut(s![.., ..n]).assign(&checksums.slice(s![.., ..n]));
        self.checksums
            .write_slice(&sums, s![rows.clone(), ..])
            .map_err(e("writing shard checksums"))?;
        self.file.flush().map_err(e("flushing shards"))?;
        self.shards_complete
            .write_slice(&vec![1u8; k][..], s![rows.clone()])
            .map_err(e("marking shards complete"))?;
        self.file.flush().map_err(e("flushing shard markers"))?;
        for r in rows {
            self.completed[r] = true;
        }
        Ok(())
    }

    /// Reads back the accumulator `name` of a completed shard (to rebuild statistics when resuming).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for an unknown name or a shard not completed; [`Error::Hdf5`] on read
    /// failure.
    pub fn read_accumulator(&self, name: &str, shard: usize) -> Result<Vec<f64>> {
        let j = self
            .meta
            .accumulators
            .iter()
            .position(|a| a.0 == name)
            .ok_or_else(|| Error::invalid("accumulator", name, "not declared in the run metadata"))?;
        if !self.is_completed(shard) {
            return Err(Error::invalid("shard", shard, "not a completed shard"));
        }
        let (row, _) = self.local_or_err(shard)?;
        self.accumulators[j]
            .read_slice_1d::<f64, _>(s![row, ..])
            .map(|a| a.to_vec())
            .map_err(h5err(&self.tmp, "reading an accumulator"))
    }

    /// Writes (or replaces) the statistics of some signals under `/statistics/<signal>`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if a signal name is not one of the run's inputs or outputs or a
    /// statistic name is invalid or repeated; [`Error::Hdf5`] if writing fails.
    pub fn write_statistics(&mut self, stats: &[OutputStatistics]) -> Result<()> {
        for st in stats {
            self.check_signal_name("statistics", &st.output)?;
            let names: Vec<&str> = st.statistics.iter().map(|s| s.name.as_str()).collect();
            for (i, n) in names.iter().enumerate() {
                super::check_name("statistic", n)?;
                if names[..i].contains(n) {
                    return Err(Error::invalid("statistic", n, "duplicate name"));
                }
            }
        }
        let e = |what: &str| h5err(&self.tmp, what);
        let parent = self.file.group(L::GROUP_STATISTICS).map_err(e("opening /statistics"))?;
        for st in stats {
            if parent.link_exists(&st.output) {
                parent.unlink(&st.output).map_err(e("replacing statistics"))?;
            }
            let g = parent
                .create_group(&st.output)
                .map_err(e("creating a statistics group"))?;
            write_scalar_attr(&g, L::ATTR_N_USED, st.n_used).map_err(e("writing n_used"))?;
            write_str_attr(&g, L::ATTR_UNIT, &st.unit).map_err(e("writing a unit"))?;
            let names: Vec<&str> = st.statistics.iter().map(|s| s.name.as_str()).collect();
            write_str_list_attr(&g, L::ATTR_NAMES, &names).map_err(e("writing statistic names"))?;
            for s in &st.statistics {
                let ds = g
                    .new_dataset::<f64>()
                    .shape(())
                    .create(s.name.as_str())
                    .map_err(e("creating a statistic"))?;
                ds.write_scalar(&s.interval.estimate)
                    .map_err(e("writing a statistic"))?;
                let w = || -> hdf5::Result<()> {
                    write_scalar_attr(&ds, L::ATTR_LOWER, s.interval.lower)?;
                    write_scalar_attr(&ds, L::ATTR_UPPER, s.interval.upper)?;
                    write_scalar_attr(&ds, L::ATTR_CONFIDENCE, s.interval.confidence)?;
                    write_str_attr(&ds, L::ATTR_UNIT, &s.unit)?;
                    write_str_attr(&ds, L::ATTR_METHOD, &s.method)?;
                    write_scalar_attr(&ds, L::ATTR_CRC32, s.checksum())?;
                    if let Some(a) = s.analytic {
                        write_scalar_attr(&ds, L::ATTR_ANALYTIC, a)?;
                        if let Some(c) = s.covers {
                            write_scalar_attr(&ds, L::ATTR_COVERS, u8::from(c))?;
                        }
                    }
                    Ok(())
                };
                w().map_err(e("writing statistic attributes"))?;
            }
        }
        self.file.flush().map_err(e("flushing statistics"))
    }

    /// Writes (or replaces) a spectral density estimate under `/psd/<signal>`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if the signal is unknown, the arrays are empty or of different lengths,
    /// or an ω is negative or not finite; [`Error::Hdf5`] if writing fails.
    pub fn write_psd(&mut self, psd: &PsdEstimate) -> Result<()> {
        self.check_signal_name("psd", &psd.output)?;
        let n = psd.omega.len();
        if n == 0 {
            return Err(Error::invalid("psd.omega", "[]", "needs at least one frequency"));
        }
        for (field, len) in [
            ("psd.density", psd.density.len()),
            ("psd.lower", psd.lower.len()),
            ("psd.upper", psd.upper.len()),
            ("psd.analytic", psd.analytic.as_ref().map_or(n, |a| a.len())),
            ("psd.expected", psd.expected.as_ref().map_or(n, |a| a.len())),
        ] {
            if len != n {
                return Err(Error::invalid(
                    field,
                    len,
                    format!("length must equal that of omega ({n})"),
                ));
            }
        }
        if let Some(w) = psd.omega.iter().find(|w| !(w.is_finite() && **w >= 0.0)) {
            return Err(Error::invalid(
                "psd.omega",
                w,
                "angular frequencies must be finite and >= 0",
            ));
        }
        let e = |what: &str| h5err(&self.tmp, what);
        let parent = self.file.group(L::GROUP_PSD).map_err(e("opening /psd"))?;
        if parent.link_exists(&psd.output) {
            parent.unlink(&psd.output).map_err(e("replacing a density estimate"))?;
        }
        let g = parent
            .create_group(&psd.output)
            .map_err(e("creating a density group"))?;
        let w = || -> hdf5::Result<()> {
            write_str_attr(&g, L::ATTR_CONVENTION, L::PSD_CONVENTION)?;
            write_str_attr(&g, L::ATTR_UNIT, &psd.unit)?;
            write_scalar_attr(&g, L::ATTR_DOF, psd.dof)?;
            write_scalar_attr(&g, L::ATTR_CONFIDENCE, psd.confidence)?;
            write_str_attr(&g, L::ATTR_METHOD, &psd.method)?;
            write_scalar_attr(&g, L::ATTR_CRC32, psd.checksum())?;
            let mut sets = vec![
                (L::DS_OMEGA, &psd.omega),
                (L::DS_DENSITY, &psd.density),
                (L::DS_LOWER, &psd.lower),
                (L::DS_UPPER, &psd.upper),
            ];
            if let Some(a) = &psd.analytic {
                sets.push((L::DS_ANALYTIC, a));
            }
            if let Some(a) = &psd.expected {
                sets.push((L::DS_EXPECTED, a));
            }
            for (name, data) in sets {
                g.new_dataset_builder().with_data(data.as_slice()).create(name)?;
            }
            Ok(())
        };
        w().map_err(e("writing a density estimate"))?;
        self.file.flush().map_err(e("flushing a density estimate"))
    }

    /// Writes (or replaces) a rainflow range histogram under `/rainflow/<output>` (the group is created
    /// on first use).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] if the signal is unknown or the array lengths do not fit (edges = counts
    /// + 1); [`Error::Hdf5`] if writing fails.
    pub fn write_rainflow(&mut self, h: &super::RainflowHistogram) -> Result<()> {
        self.check_signal_name("rainflow", &h.output)?;
        if h.edges.len() != h.counts.len() + 1 || h.dirlik.as_ref().is_some_and(|d| d.len() != h.counts.len()) {
            return Err(Error::invalid(
                "rainflow.edges",
                h.edges.len(),
                "need one more edge than counts",
            ));
        }
        let e = |what: &str| h5err(&self.tmp, what);
        let parent = if self.file.link_exists(L::GROUP_RAINFLOW) {
            self.file.group(L::GROUP_RAINFLOW).map_err(e("opening /rainflow"))?
        } else {
            self.file
                .create_group(L::GROUP_RAINFLOW)
                .map_err(e("creating /rainflow"))?
        };
        if parent.link_exists(&h.output) {
            parent.unlink(&h.output).map_err(e("replacing a rainflow histogram"))?;
        }
        let g = parent.create_group(&h.output).map_err(e("creating a rainflow group"))?;
        let w = || -> hdf5::Result<()> {
            write_str_attr(&g, L::ATTR_UNIT, &h.unit)?;
            write_scalar_attr(&g, L::ATTR_OVERFLOW, h.overflow)?;
            write_scalar_attr(&g, L::ATTR_CRC32, h.checksum())?;
            g.new_dataset_builder()
                .with_data(h.edges.as_slice())
                .create(L::DS_EDGES)?;
            g.new_dataset_builder()
                .with_data(h.counts.as_slice())
                .create(L::DS_COUNTS)?;
            if let Some(d) = &h.dirlik {
                g.new_dataset_builder().with_data(d.as_slice()).create(L::DS_DIRLIK)?;
            }
            Ok(())
        };
        w().map_err(e("writing a rainflow histogram"))?;
        self.file.flush().map_err(e("flushing a rainflow histogram"))
    }

    /// Writes the response histogram of a nonlinear run's output under `/response_histogram/<output>`
    /// (replacing an existing one).
    ///
    /// # Errors
    /// An output that is not one of the run's; HDF5 failures.
    pub fn write_response_histogram(&mut self, h: &super::ResponseHistogram) -> Result<()> {
        self.check_signal_name("response_histogram", &h.output)?;
        let e = |what: &str| h5err(&self.tmp, what);
        let parent = if self.file.link_exists(L::GROUP_RESPONSE_HISTOGRAM) {
            self.file
                .group(L::GROUP_RESPONSE_HISTOGRAM)
                .map_err(e("opening /response_histogram"))?
        } else {
            self.file
                .create_group(L::GROUP_RESPONSE_HISTOGRAM)
                .map_err(e("creating /response_histogram"))?
        };
        h.write(&parent, &self.tmp)?;
        self.file.flush().map_err(e("flushing a response histogram"))
    }

    /// The open `.tmp` file and its path (for the optional groups written by [`super::transient_series`]).
    pub(super) fn h5(&self) -> (&File, &Path) {
        (&self.file, &self.tmp)
    }

    fn check_signal_name(&self, field: &str, name: &str) -> Result<()> {
        if self
            .meta
            .inputs
            .iter()
            .chain(&self.meta.outputs)
            .any(|s| s.name == name)
        {
            Ok(())
        } else {
            Err(Error::invalid(field, name, "not an input or output of this run"))
        }
    }

    /// Writes the results of a finished run (its statistics, then every rainflow histogram and density
    /// estimate, in order) and completes it ([`RunWriter::finish`]).
    ///
    /// # Errors
    /// Those of [`RunWriter::write_statistics`], [`RunWriter::write_rainflow`], [`RunWriter::write_psd`] and
    /// [`RunWriter::finish`].
    pub fn finish_with(
        mut self,
        stats: &[OutputStatistics],
        rainflow: &[super::RainflowHistogram],
        psds: &[PsdEstimate],
    ) -> Result<PathBuf> {
        self.write_statistics(stats)?;
        for r in rainflow {
            self.write_rainflow(r)?;
        }
        for psd in psds {
            self.write_psd(psd)?;
        }
        self.finish()
    }

    /// Completes the run: checks that every shard is written, sets `@complete`, closes every handle,
    /// syncs the file to disk and renames `<final>.tmp` to `<final>`.
    ///
    /// # Errors
    /// [`Error::Hdf5`] listing the missing shards if any is not written (the writer is dropped, the `.tmp`
    /// stays for a resume), or if closing, syncing or renaming fails.
    pub fn finish(self) -> Result<PathBuf> {
        let missing = self.pending_shards();
        if !missing.is_empty() {
            let shown: Vec<String> = missing.iter().take(10).map(|i| i.to_string()).collect();
            return Err(Error::Hdf5 {
                path: self.tmp.clone(),
                reason: format!(
                    "cannot finish: {} of {} shards not written (first: {}); the temporary file is kept for a resume",
                    missing.len(),
                    self.completed.len(),
                    shown.join(", ")
                ),
            });
        }
        let RunWriter {
            meta,
            final_path,
            tmp,
            overwrite,
            inputs,
            outputs,
            accumulators,
            shards_complete,
            checksums,
            file,
            ..
        } = self;
        let e = |what: &str| h5err(&tmp, what);
        drop((inputs, outputs, accumulators, shards_complete, checksums));
        if meta.part.is_some() {
            // what every part of the run stores identically, for a merge to compare in one read
            let (shared, confidence) = super::reader::shared_fingerprint(&file, &tmp, &meta)?;
            write_scalar_attr(&file, L::ATTR_SHARED_CRC32, shared).map_err(e("writing @shared_crc32"))?;
            write_scalar_attr(&file, L::ATTR_CONFIDENCE_CRC32, confidence).map_err(e("writing @confidence_crc32"))?;
        }
        if !file
            .attr_names()
            .map_err(e("listing root attributes"))?
            .iter()
            .any(|n| n == L::ATTR_COMPLETE)
        {
            write_scalar_attr(&file, L::ATTR_COMPLETE, 1u8).map_err(e("writing @complete"))?;
        }
        file.flush().map_err(e("flushing"))?;
        file.close().map_err(e("closing"))?;
        let io = |err: std::io::Error| Error::Io {
            path: tmp.clone(),
            source: err,
        };
        std::fs::File::open(&tmp).and_then(|f| f.sync_all()).map_err(io)?;
        // the old run (with --overwrite) is replaced only here, atomically; without it, a file that appeared
        // under the final name meanwhile is not replaced
        if !overwrite && final_path.exists() {
            return Err(Error::Hdf5 {
                path: final_path,
                reason: format!(
                    "appeared while this run was being written; the finished run is kept as {}",
                    tmp.display()
                ),
            });
        }
        if overwrite {
            check_final_path(&final_path, true)?;
        }
        std::fs::rename(&tmp, &final_path).map_err(io)?;
        let _ = std::fs::remove_file(owner_path(&tmp));
        if let Some(dir) = final_path.parent().filter(|d| !d.as_os_str().is_empty()) {
            // Make the rename itself durable; best effort (not every platform can open a directory).
            let _ = std::fs::File::open(dir).and_then(|d| d.sync_all());
        }
        Ok(final_path)
    }
}

/// Opens the writer's file ([`open_sec2`]) with its file-access options.
///
/// The chunk shape of the raw datasets of a file: [`L::chunk_shape`], with at most as many rows as the file
/// holds (a part file that holds only the last, short internal shard of a run has fewer rows than a chunk;
/// HDF5 refuses chunks larger than a fixed-size dataset). Its rows still divide every local start row.
fn raw_chunk(meta: &RunMetadata) -> (usize, usize) {
    let (rows, cols) = L::chunk_shape(meta.n_samples, meta.shard_size);
    (rows.min(meta.local_realizations().len().max(1)), cols)
}

/// Uncompressed raw datasets get no chunk cache (0 bytes): every shard write covers whole chunks (see
/// [`L::chunk_shape`]), and a chunk that does not fit the cache is written by HDF5 straight from the
/// caller's buffer to the file. With HDF5's default 1 MiB cache, a 1 MiB chunk is "cacheable" and every
/// byte is first copied into the cache and then written out: one extra memcpy of the whole run (and
/// glibc's memcpy of such buffers is slow on some machines, see benches/HISTORY.md). Compressed shards are filtered
/// by the writer and stored with `H5Dwrite_chunk` (see `chunks.rs`), which bypasses the cache; HDF5's
/// default cache is kept for them.
fn open_file(path: &Path, mode: OpenMode, compression: Compression) -> hdf5::Result<File> {
    open_sec2(path, mode, |b| {
        if compression == Compression::None {
            // nslots and w0 are HDF5's defaults (521, 0.75); only the size changes.
            b.with_fapl(|p| p.chunk_cache(521, 0, 0.75));
        }
    })
}

/// Fields of two metadata records that differ (empty if identical): the fields, and each identifying
/// provenance part by name.
pub(crate) fn metadata_differences(a: &RunMetadata, b: &RunMetadata) -> Vec<String> {
    let mut d = Vec::new();
    let mut check = |same: bool, name: &str| {
        if !same {
            d.push(name.to_string())
        }
    };
    check(a.scenario_text == b.scenario_text, "scenario");
    check(a.seed == b.seed, "seed");
    check(a.generator == b.generator, "generator");
    check(a.dt.to_bits() == b.dt.to_bits(), "dt");
    check(a.n_samples == b.n_samples, "n_samples");
    check(a.n_realizations == b.n_realizations, "n_realizations");
    check(a.shard_size == b.shard_size, "shard_size");
    check(a.inputs == b.inputs, "inputs");
    check(a.outputs == b.outputs, "outputs");
    check(a.accumulators == b.accumulators, "accumulators");
    check(a.store_raw == b.store_raw, "store_raw");
    check(a.compression == b.compression, "compression");
    let ident = |m: &RunMetadata| -> Vec<(String, String)> {
        m.provenance
            .iter()
            .filter(|p| p.identifies)
            .map(|p| (p.name.clone(), p.text.clone()))
            .collect()
    };
    let (pa, pb) = (ident(a), ident(b));
    let text_of = |p: &[(String, String)], name: &str| p.iter().find(|(n, _)| n == name).map(|(_, t)| t.clone());
    let (va, vb) = (text_of(&pa, GENERATOR_VERSION), text_of(&pb, GENERATOR_VERSION));
    if va != vb {
        d.push(generator_version_difference(va, vb));
    }
    for (name, text) in pb.iter().filter(|(n, _)| n != GENERATOR_VERSION) {
        match pa.iter().find(|(n, _)| n == name) {
            Some((_, old)) if old == text => {}
            Some(_) => d.push(format!("{name} (changed since the interrupted run)")),
            None => d.push(format!("{name} (not recorded by the interrupted run)")),
        }
    }
    for (name, _) in pa.iter().filter(|(n, _)| n != GENERATOR_VERSION) {
        if !pb.iter().any(|(n, _)| n == name) {
            d.push(format!("{name} (recorded by the interrupted run, absent now)"));
        }
    }
    d
}

/// The name of the identifying provenance part that holds a route's generator version (the way a seed's
/// random numbers become realizations; a route that changes it deliberately records a new version).
pub const GENERATOR_VERSION: &str = "generator_version";

/// What [`metadata_differences`] says when two runs' generator versions differ (`None`: not recorded, i.e.
/// written before the route recorded its version).
fn generator_version_difference(a: Option<String>, b: Option<String>) -> String {
    let show =
        |v: Option<String>| v.unwrap_or_else(|| "1 (not recorded: written before versions were recorded)".into());
    format!(
        "generator version ({} against {}: the two versions turn a seed into different realizations, so their \
         shards are never mixed; start the run again into a new file, or resume or merge it with the stochvib \
         build that wrote it)",
        show(a),
        show(b)
    )
}

/// Names of the datasets whose shard rows `/shards/checksums` covers, in column order.
fn checked_datasets(meta: &RunMetadata) -> Vec<String> {
    let mut out = Vec::new();
    if meta.store_raw {
        for s in &meta.inputs {
            out.push(format!("{}/{}", L::GROUP_INPUTS, s.name));
        }
        for s in &meta.outputs {
            out.push(format!("{}/{}", L::GROUP_OUTPUTS, s.name));
        }
    }
    for (name, _) in &meta.accumulators {
        out.push(format!("{}/{name}", L::GROUP_SHARDS));
    }
    out
}

/// The output rule ([`crate::io_rules::check_output`]) for a run file: refuses a final path that is a
/// directory or not a regular file, one whose directory is missing, and an existing file unless `overwrite`
/// and it is a stochvib run file (an HDF5 file with `@format_version`).
fn check_final_path(final_path: &Path, overwrite: bool) -> Result<()> {
    crate::io_rules::check_output(final_path, &super::RUN_FILE, &[], overwrite)
}

/// Whether `path` starts with the HDF5 signature.
fn is_hdf5(path: &Path) -> bool {
    crate::io_rules::starts_with(path, crate::io_rules::HDF5_SIGNATURE)
}

/// Whether `path` is an HDF5 file with a `@format_version` root attribute.
pub(crate) fn is_run_file(path: &Path) -> bool {
    is_hdf5(path)
        && open_sec2(path, OpenMode::Read, |_| {})
            .map(|f| {
                f.attr_names()
                    .map(|n| n.iter().any(|x| x == L::ATTR_FORMAT_VERSION))
                    .unwrap_or(false)
            })
            .unwrap_or(false)
}

/// A string root attribute, if readable.
fn attr_string_of(file: &File, name: &str) -> Option<String> {
    file.attr(name)
        .and_then(|a| a.read_scalar::<VarLenUnicode>())
        .ok()
        .map(|v| v.as_str().to_string())
}

/// The name under which this process builds a fresh `.tmp` before claiming it:
/// `<tmp>.<pid>.<nanoseconds>`.
fn claim_path(tmp: &Path) -> PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let mut name = tmp.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(format!(".{}.{nanos}", std::process::id()));
    tmp.with_file_name(name)
}

/// `<tmp>.owner`.
fn owner_path(tmp: &Path) -> PathBuf {
    let mut name = tmp.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(L::OWNER_SUFFIX);
    tmp.with_file_name(name)
}

/// Records this process as the writer of `tmp` (best effort: only used for messages).
fn write_owner(tmp: &Path) {
    let _ = std::fs::write(owner_path(tmp), std::process::id().to_string());
}

/// The pid recorded as the writer of `tmp`, if it is another process that is still alive.
fn owner_alive(tmp: &Path) -> Option<u32> {
    let pid: u32 = std::fs::read_to_string(owner_path(tmp)).ok()?.trim().parse().ok()?;
    (pid != std::process::id() && process_alive(pid)).then_some(pid)
}

pub use crate::io_rules::process_alive;

/// Removes fresh files of dead processes that never claimed the `.tmp` (`<tmp>.<pid>.<nanos>` left by a
/// kill during set-up).
fn remove_stale_claims(tmp: &Path) {
    let (Some(dir), Some(stem)) = (tmp.parent(), tmp.file_name().map(|n| n.to_string_lossy().into_owned())) else {
        return;
    };
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for entry in rd.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = name.strip_prefix(&format!("{stem}.")) else {
            continue;
        };
        let mut parts = rest.split('.');
        let (Some(pid), Some(nanos), None) = (parts.next(), parts.next(), parts.next()) else {
            continue;
        };
        if let (Ok(pid), true) = (pid.parse::<u32>(), nanos.chars().all(|c| c.is_ascii_digit()))
            && !process_alive(pid)
        {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Creates the virtual dataset `/<group>/<name>` of shape `[n_realizations, n_samples]` mapping the rows of
/// every shard file's dataset of the same name (fill value NaN: rows whose shard file cannot be opened read
/// as NaN, never as plausible zeros).
fn create_virtual(
    group: &hdf5::Group,
    gname: &str,
    name: &str,
    meta: &RunMetadata,
    from: &MergedFrom,
) -> hdf5::Result<Dataset> {
    use hdf5::{Hyperslab, Selection, SliceOrIndex};
    let rows = |r: std::ops::Range<usize>| {
        Selection::from(Hyperslab::from(vec![SliceOrIndex::from(r), SliceOrIndex::from(..)]))
    };
    let shape = (meta.n_realizations, meta.n_samples);
    let mut b = group.new_dataset::<f64>().shape(shape).fill_value(f64::NAN);
    for (k, file) in from.files.iter().enumerate() {
        let (r0, n) = (from.first_realizations[k], from.realizations[k]);
        b = b.virtual_map(
            file.as_str(),
            format!("/{gname}/{name}"),
            (n, meta.n_samples),
            rows(0..n),
            shape,
            rows(r0..r0 + n),
        );
    }
    b.create(name)
}

/// Writes `/parts` of a merged file.
fn write_parts_group(file: &File, m: &MergedFrom) -> hdf5::Result<()> {
    let g = file.create_group(L::GROUP_PARTS)?;
    let files: Vec<&str> = m.files.iter().map(|f| f.as_str()).collect();
    write_str_list_attr(&g, L::ATTR_PART_FILES, &files)?;
    for (name, values) in [
        (L::ATTR_PART_FIRST_REALIZATIONS, &m.first_realizations),
        (L::ATTR_PART_REALIZATION_COUNTS, &m.realizations),
    ] {
        let v: Vec<u64> = values.iter().map(|&x| x as u64).collect();
        g.new_attr::<u64>().shape(v.len()).create(name)?.write(&v[..])?;
    }
    write_str_attr(&g, L::ATTR_RAW_STORAGE, m.raw.label())
}

fn write_root_attrs(file: &File, m: &RunMetadata, version: u32) -> hdf5::Result<()> {
    let prov = file.create_group(L::GROUP_PROVENANCE)?;
    for p in &m.provenance {
        write_str_attr(&prov, &p.name, &p.text)?;
    }
    let identifies: Vec<&str> = m
        .provenance
        .iter()
        .filter(|p| p.identifies)
        .map(|p| p.name.as_str())
        .collect();
    write_str_list_attr(&prov, L::ATTR_IDENTIFIES, &identifies)?;
    write_scalar_attr(file, L::ATTR_METADATA_CRC32, m.digest())?;
    write_scalar_attr(file, L::ATTR_FORMAT_VERSION, version)?;
    if let Some(p) = m.part {
        let (shards, rows) = (m.local_shards(), m.local_realizations());
        for (name, v) in [
            (L::ATTR_PART_INDEX, p.index),
            (L::ATTR_PART_COUNT, p.count),
            (L::ATTR_FIRST_SHARD, shards.start),
            (L::ATTR_PART_SHARDS, shards.len()),
            (L::ATTR_FIRST_REALIZATION, rows.start),
            (L::ATTR_PART_REALIZATIONS, rows.len()),
        ] {
            write_scalar_attr(file, name, v as u64)?;
        }
    }
    write_str_attr(file, L::ATTR_TOOLKIT_VERSION, L::TOOLKIT_VERSION)?;
    write_str_attr(file, L::ATTR_SCENARIO, &m.scenario_text)?;
    write_scalar_attr(file, L::ATTR_SEED, m.seed)?;
    write_str_attr(file, L::ATTR_GENERATOR, &m.generator)?;
    write_scalar_attr(file, L::ATTR_DT, m.dt)?;
    write_str_attr(file, L::ATTR_UNITS, L::UNITS_VALUE)?;
    write_scalar_attr(file, L::ATTR_N_SAMPLES, m.n_samples as u64)?;
    write_scalar_attr(file, L::ATTR_N_REALIZATIONS, m.n_realizations as u64)?;
    write_scalar_attr(file, L::ATTR_SHARD_SIZE, m.shard_size as u64)?;
    write_scalar_attr(file, L::ATTR_N_SHARDS, m.n_shards() as u64)?;
    write_scalar_attr(file, L::ATTR_STORE_RAW, u8::from(m.store_raw))?;
    write_str_attr(file, L::ATTR_COMPRESSION, &m.compression.label())?;
    Ok(())
}

pub(super) fn write_scalar_attr<T: hdf5::H5Type>(loc: &Location, name: &str, value: T) -> hdf5::Result<()> {
    loc.new_attr::<T>().shape(()).create(name)?.write_scalar(&value)
}

fn to_vlu(text: &str) -> hdf5::Result<VarLenUnicode> {
    text.parse::<VarLenUnicode>()
        .map_err(|err| hdf5::Error::from(format!("text {text:?} cannot be stored: {err}")))
}

pub(super) fn write_str_attr(loc: &Location, name: &str, value: &str) -> hdf5::Result<()> {
    let v = to_vlu(value)?;
    loc.new_attr::<VarLenUnicode>().shape(()).create(name)?.write_scalar(&v)
}

fn write_str_list_attr(loc: &Location, name: &str, values: &[&str]) -> hdf5::Result<()> {
    let v = values.iter().map(|t| to_vlu(t)).collect::<hdf5::Result<Vec<_>>>()?;
    let attr = loc.new_attr::<VarLenUnicode>().shape(v.len()).create(name)?;
    if !v.is_empty() {
        attr.write(&v[..])?;
    }
    Ok(())
}

/// The group `gname` of `signals` (their names and units as attributes) and, when the run stores raw data,
/// one dataset per signal (virtual over the part files of a merge `virtual_raw`), in signal order.
fn create_signals(
    file: &File,
    path: &Path,
    gname: &str,
    signals: &[super::Signal],
    meta: &RunMetadata,
    virtual_raw: Option<&MergedFrom>,
) -> Result<Vec<Dataset>> {
    let e = |what: &str| h5err(path, what);
    let group = file.create_group(gname).map_err(e("creating a signal group"))?;
    let names: Vec<&str> = signals.iter().map(|s| s.name.as_str()).collect();
    let units: Vec<&str> = signals.iter().map(|s| s.unit.as_str()).collect();
    write_str_list_attr(&group, L::ATTR_NAMES, &names).map_err(e("writing signal names"))?;
    write_str_list_attr(&group, L::ATTR_UNITS_LIST, &units).map_err(e("writing signal units"))?;
    let mut sets = Vec::new();
    if let Some(m) = virtual_raw {
        for s in signals {
            let ds = create_virtual(&group, gname, &s.name, meta, m).map_err(e("creating a virtual dataset"))?;
            write_str_attr(&ds, L::ATTR_UNIT, &s.unit).map_err(e("writing a unit"))?;
            sets.push(ds);
        }
    } else if meta.store_raw {
        let rows = meta.local_realizations().len();
        for s in signals {
            let b = group
                .new_dataset::<f64>()
                .shape((rows, meta.n_samples))
                .chunk(raw_chunk(meta));
            let b = match meta.compression {
                // Allocated in full now and never filled: a shard write changes raw data only.
                Compression::None => b
                    .alloc_time(Some(hdf5::dataset::AllocTime::Early))
                    .fill_time(hdf5::dataset::FillTime::Never),
                Compression::Deflate { level } => b.shuffle().deflate(level),
            };
            let ds = b.create(s.name.as_str()).map_err(e("creating a signal dataset"))?;
            write_str_attr(&ds, L::ATTR_UNIT, &s.unit).map_err(e("writing a unit"))?;
            sets.push(ds);
        }
    }
    Ok(sets)
}

/// The datasets of `/shards`: `complete` (filled with 0), the checksums with the names of the datasets they
/// check, and one accumulator dataset per accumulator of `meta`.
fn create_shard_sets(
    shards: &hdf5::Group,
    path: &Path,
    meta: &RunMetadata,
) -> Result<(Dataset, Dataset, Vec<Dataset>)> {
    let e = |what: &str| h5err(path, what);
    let n_shards = meta.local_shards().len();
    let acc_names: Vec<&str> = meta.accumulators.iter().map(|a| a.0.as_str()).collect();
    write_str_list_attr(shards, L::ATTR_ACCUMULATORS, &acc_names).map_err(e("writing accumulator names"))?;
    let shards_complete = shards
        .new_dataset::<u8>()
        .shape(n_shards)
        .alloc_time(Some(hdf5::dataset::AllocTime::Early))
        .fill_value(0u8)
        .fill_time(hdf5::dataset::FillTime::Alloc)
        .create(L::DS_SHARDS_COMPLETE)
        .map_err(e("creating /shards/complete"))?;
    let checked = checked_datasets(meta);
    // Allocated in full now and never filled (as the raw data): the file system gives the space as the
    // shards are written (a sparse file), so a run of 10⁹ realizations does not write gigabytes of fill
    // before computing; a row is read only once `complete` (filled with 0 above) says it was written.
    let checksums = shards
        .new_dataset::<u32>()
        .shape((n_shards, checked.len().max(1)))
        .alloc_time(Some(hdf5::dataset::AllocTime::Early))
        .fill_time(hdf5::dataset::FillTime::Never)
        .create(L::DS_SHARDS_CHECKSUMS)
        .map_err(e("creating /shards/checksums"))?;
    let refs: Vec<&str> = checked.iter().map(|s| s.as_str()).collect();
    write_str_list_attr(&checksums, L::ATTR_CHECKED, &refs).map_err(e("writing checksum names"))?;
    let mut accumulators = Vec::new();
    for (name, len) in &meta.accumulators {
        let ds = shards
            .new_dataset::<f64>()
            .shape((n_shards, *len))
            .alloc_time(Some(hdf5::dataset::AllocTime::Early))
            .fill_time(hdf5::dataset::FillTime::Never)
            .create(name.as_str())
            .map_err(e("creating an accumulator dataset"))?;
        accumulators.push(ds);
    }
    Ok((shards_complete, checksums, accumulators))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::{RunFile, Signal, SignalGroup};
    use ndarray::Array2;

    fn meta(compression: Compression) -> RunMetadata {
        RunMetadata {
            scenario_text: "[run]\n".into(),
            seed: 3,
            generator: "test".into(),
            dt: 0.5,
            n_samples: 64,
            n_realizations: 4,
            shard_size: 2,
            inputs: vec![],
            outputs: vec![Signal::new("y", "m")],
            accumulators: vec![],
            store_raw: true,
            compression,
            provenance: vec![],
            part: None,
        }
    }

    fn cache_bytes(w: &RunWriter) -> usize {
        w.outputs[0]
            .access_plist()
            .expect("dataset access list")
            .chunk_cache()
            .nbytes
    }

    /// Uncompressed raw datasets are written without a chunk cache (see `open_file`), on a fresh file
    /// and after a resume; with deflate HDF5's default cache (non-zero in every HDF5 version) is kept. The
    /// data read back are the values written (x[i, k] = 64 i + k).
    #[test]
    fn chunk_cache_is_off_only_for_uncompressed_runs() {
        let dir = std::env::temp_dir().join(format!("stochvib-writer-unit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let data = Array2::from_shape_fn((4, 64), |(i, k)| (64 * i + k) as f64);
        for (tag, comp) in [("none", Compression::None), ("deflate", Compression::DEFLATE_FAST)] {
            let path = dir.join(format!("{tag}.h5"));
            let _ = std::fs::remove_file(&path);
            let _ = std::fs::remove_file(tmp_path(&path));
            let m = meta(comp);
            let mut w = RunWriter::create(&path, &m).unwrap();
            assert_eq!(cache_bytes(&w) == 0, comp == Compression::None, "{tag}, fresh file");
            w.write_shard(0, &[], &[data.slice(ndarray::s![0..2, ..])], &[])
                .unwrap();
            drop(w);
            let mut w = RunWriter::create(&path, &m).unwrap();
            assert!(w.resumed());
            assert_eq!(cache_bytes(&w) == 0, comp == Compression::None, "{tag}, resumed");
            w.write_shard(1, &[], &[data.slice(ndarray::s![2..4, ..])], &[])
                .unwrap();
            let done = w.finish().unwrap();
            let run = RunFile::open(&done).unwrap();
            let back = run.read_signals(SignalGroup::Outputs, "y", 0..4).unwrap();
            assert_eq!(back, data, "{tag}");
            drop(run);
            std::fs::remove_file(&done).unwrap();
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
