//! The shard files of one run (`stochvib simulate --shard I --of N`) taken together: finding them, checking
//! that they belong to one run and cover every realization exactly once, and what a merged file records
//! about them (`/parts`).
//!
//! A shard file is a run file of format 3 holding one [`Part`] of the run: its own internal shards (whole
//! shards of `shard_size` realizations), their accumulators and checksums, and, with raw data, its own rows.
//! [`PartSet::open`] reads a set of them and refuses, naming the files and the shard indices to resubmit,
//! anything that would not reproduce the single-process run: files of another run (scenario, seed, options,
//! format or toolkit version differ), duplicates, overlaps, and missing shards.

use super::layout as L;
use super::{Part, RunFile, RunMetadata};
use crate::error::{Error, Result};
use ndarray::Array2;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Where the raw realizations of a merged file are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RawStorage {
    /// Virtual datasets that map the rows of the shard files (which must stay where the merged file
    /// expects them).
    Virtual,
    /// Copied into the merged file (`stochvib merge --copy`).
    Copied,
    /// The run stored no raw realizations.
    None,
}

impl RawStorage {
    /// The text of the `/parts@raw` attribute.
    pub fn label(&self) -> &'static str {
        match self {
            RawStorage::Virtual => "virtual",
            RawStorage::Copied => "copied",
            RawStorage::None => "none",
        }
    }

    /// Parses a label of [`RawStorage::label`].
    pub fn parse(text: &str) -> Option<RawStorage> {
        [RawStorage::Virtual, RawStorage::Copied, RawStorage::None]
            .into_iter()
            .find(|r| r.label() == text)
    }
}

/// What a merged file was merged from (its `/parts` group): one entry per shard file, in realization order.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct MergedFrom {
    /// Each shard file's path as the merged file references it: relative to the merged file's directory
    /// (unless absolute).
    pub files: Vec<String>,
    /// The first realization of each shard file.
    pub first_realizations: Vec<usize>,
    /// The number of realizations of each shard file.
    pub realizations: Vec<usize>,
    /// Where the raw realizations are.
    pub raw: RawStorage,
}

/// One source of a virtual dataset: a shard file and the rows it holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VirtualSource {
    /// The shard file as the merged file references it.
    pub file: String,
    /// Its realizations.
    pub realizations: std::ops::Range<usize>,
}

impl MergedFrom {
    /// Checks that the entries tile `0..n_realizations` in order, without gap or overlap.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `parts`.
    pub(crate) fn check(&self, n_realizations: usize) -> Result<()> {
        let n = self.files.len();
        if self.first_realizations.len() != n || self.realizations.len() != n {
            return Err(Error::invalid(
                "parts",
                n,
                "files, first realizations and counts differ in length",
            ));
        }
        let mut next = 0;
        for k in 0..n {
            if self.first_realizations[k] != next || self.realizations[k] == 0 {
                return Err(Error::invalid(
                    "parts",
                    &self.files[k],
                    format!("does not start at realization {next} or is empty"),
                ));
            }
            next += self.realizations[k];
        }
        if next != n_realizations {
            return Err(Error::invalid(
                "parts",
                next,
                format!("the parts hold {next} realizations, the run has {n_realizations}"),
            ));
        }
        Ok(())
    }

    /// The sources whose rows intersect `range` (realization indices of the whole run).
    pub fn sources(&self, range: std::ops::Range<usize>) -> Vec<VirtualSource> {
        (0..self.files.len())
            .filter_map(|k| {
                let r = self.first_realizations[k]..self.first_realizations[k] + self.realizations[k];
                (r.start < range.end && range.start < r.end).then(|| VirtualSource {
                    file: self.files[k].clone(),
                    realizations: r,
                })
            })
            .collect()
    }
}

/// One shard file of a [`PartSet`]: what its header says. The file itself is closed (a set of a thousand
/// shard files holds no HDF5 file open); [`PartFile::open`] opens it again to read its data.
#[derive(Debug, Clone)]
pub struct PartFile {
    /// The file as found.
    pub path: PathBuf,
    /// Its part.
    pub part: Part,
    /// Its metadata (with its part).
    pub meta: RunMetadata,
    /// Its format version.
    pub format_version: u32,
    /// The toolkit version that wrote it.
    pub toolkit_version: String,
    /// The fingerprint of the values every shard file of the run stores identically (analytic values,
    /// densities, histogram edges: [`RunFile`]'s `@shared_crc32`).
    pub shared: u32,
    /// The fingerprint of the confidence levels of its intervals (`@confidence_crc32`).
    pub confidence: u32,
    /// Size and modification time when its header was read (a replaced file is detected).
    stamp: (u64, Option<std::time::SystemTime>),
}

fn stamp(path: &Path) -> (u64, Option<std::time::SystemTime>) {
    std::fs::metadata(path)
        .map(|m| (m.len(), m.modified().ok()))
        .unwrap_or((0, None))
}

impl PartFile {
    /// The rows of the accumulators `names` and the shard checksums of `run` (this part's file, opened by
    /// [`PartFile::open`]), one row per local shard.
    ///
    /// # Errors
    /// A missing accumulator; a file without checksums (format 1), which cannot be merged.
    pub(crate) fn shard_rows(&self, run: &RunFile, names: &[&str]) -> Result<(Vec<Array2<f64>>, Array2<u32>)> {
        let accs = names
            .iter()
            .map(|n| run.read_accumulator_rows(n))
            .collect::<Result<Vec<_>>>()?;
        let sums = run.shard_checksum_rows()?.ok_or_else(|| Error::Hdf5 {
            path: self.path.clone(),
            reason: "a shard file without checksums (format 1): cannot be merged".into(),
        })?;
        Ok((accs, sums))
    }

    /// Opens the shard file again to read its data, without reading its header again: its size and
    /// modification time must still be those of when [`PartSet::open`] read it.
    ///
    /// # Errors
    /// [`Error::Hdf5`] if the file changed since, or cannot be opened.
    pub fn open(&self) -> Result<RunFile> {
        if stamp(&self.path) != self.stamp {
            return Err(Error::Hdf5 {
                path: self.path.clone(),
                reason: "the file changed while the merge read it (size or modification time differ from when its \
                         header was read): merge again"
                    .into(),
            });
        }
        RunFile::open_known(&self.path, &self.meta, self.format_version, &self.toolkit_version)
    }
}

/// A complete, consistent set of shard files of one run, in shard order.
#[derive(Debug)]
pub struct PartSet {
    /// The run's metadata (without a part).
    pub meta: RunMetadata,
    /// The toolkit version that wrote every file.
    pub toolkit_version: String,
    /// The shard files, sorted by their first internal shard.
    pub parts: Vec<PartFile>,
    /// Files of the inputs that were not used, with the reason (unfinished `.tmp` files of a directory).
    pub ignored: Vec<(PathBuf, String)>,
}

/// The run files named by `inputs`: a directory stands for its `*.h5` files (sorted by name; unfinished
/// `*.h5.tmp` files are returned separately), a file for itself. Files in `exclude` (compared after
/// resolving symbolic links) are left out, so that a merge's own output in the directory is not an input.
///
/// # Errors
/// [`Error::Io`] for an input that does not exist or a directory that cannot be read.
pub fn find_run_files(inputs: &[PathBuf], exclude: &[&Path]) -> Result<(Vec<PathBuf>, Vec<PathBuf>)> {
    let canon = |p: &Path| p.canonicalize().unwrap_or_else(|_| p.to_path_buf());
    let excluded: Vec<PathBuf> = exclude.iter().map(|p| canon(p)).collect();
    let mut files = Vec::new();
    let mut unfinished = Vec::new();
    for input in inputs {
        let io = |source| Error::Io {
            path: input.clone(),
            source,
        };
        let meta = std::fs::metadata(input).map_err(io)?;
        if meta.is_dir() {
            let mut names: Vec<PathBuf> = std::fs::read_dir(input)
                .map_err(io)?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .collect();
            names.sort();
            for p in names {
                let name = p
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default();
                if name.ends_with(".h5") && p.is_file() {
                    files.push(p);
                } else if name.ends_with(&format!(".h5{}", L::TMP_SUFFIX)) {
                    unfinished.push(p);
                }
            }
        } else {
            files.push(input.clone());
        }
    }
    files.retain(|f| !excluded.contains(&canon(f)));
    let mut seen = Vec::new();
    files.retain(|f| {
        let c = canon(f);
        let new = !seen.contains(&c);
        seen.push(c);
        new
    });
    Ok((files, unfinished))
}

/// The headers of `files` as shard files; every file is closed again at once (memory and open files
/// independent of their number). A file that is not a complete shard file is a problem.
fn open_headers(files: Vec<PathBuf>, problems: &mut Vec<String>) -> Vec<PartFile> {
    let mut opened = Vec::new();
    for f in files {
        let st = stamp(&f);
        let read = RunFile::open(&f).and_then(|run| {
            let values = match run.metadata().part {
                Some(part) => Some((part, run.shared_fingerprint()?)),
                None => None,
            };
            Ok((run, values))
        });
        match read {
            Err(e) => problems.push(format!("{}: not a complete run file ({e})", f.display())),
            Ok((run, None)) => problems.push(format!(
                "{}: a whole run (written without --shard), not a shard file",
                run.path().display()
            )),
            Ok((run, Some((part, (shared, confidence))))) => {
                opened.push(PartFile {
                    part,
                    meta: run.metadata().clone(),
                    format_version: run.format_version(),
                    toolkit_version: run.toolkit_version().to_string(),
                    shared,
                    confidence,
                    stamp: st,
                    path: f,
                });
            }
        }
    }
    opened
}

/// The run (its metadata without a part, and the toolkit version) that most files share, and its files in
/// shard order; every other file is a foreign-file problem naming what differs.
fn the_run(opened: Vec<PartFile>, problems: &mut Vec<String>) -> ((RunMetadata, String), Vec<PartFile>) {
    let mut groups: Vec<((RunMetadata, String), Vec<usize>)> = Vec::new();
    for (k, p) in opened.iter().enumerate() {
        let id = (p.meta.whole(), p.toolkit_version.clone());
        match groups.iter_mut().find(|(g, _)| *g == id) {
            Some((_, members)) => members.push(k),
            None => groups.push((id, vec![k])),
        }
    }
    groups.sort_by_key(|g| std::cmp::Reverse(g.1.len()));
    let ((meta, toolkit_version), members) = groups[0].clone();
    for ((other, version), list) in &groups[1..] {
        let mut differ = super::writer::metadata_differences(&meta, other);
        if *version != toolkit_version {
            differ.push(format!(
                "toolkit version ({version} instead of {toolkit_version}: only shards computed by one \
                 version are guaranteed to merge bit-identically)"
            ));
        }
        for &k in list {
            problems.push(format!(
                "{}: foreign shard file: belongs to another run than the {} other file(s) (differs in {})",
                opened[k].path.display(),
                members.len(),
                differ.join(", ")
            ));
        }
    }
    let mut parts: Vec<PartFile> = Vec::new();
    for (k, p) in opened.into_iter().enumerate() {
        if members.contains(&k) {
            parts.push(p);
        }
    }
    parts.sort_by_key(|p| (p.meta.local_shards().start, p.part.count, p.path.clone()));
    ((meta, toolkit_version), parts)
}

/// A problem for every group of files that hold the same internal shard (`owners[b]`: the files holding
/// shard b): duplicates of one shard, or overlapping splits.
fn report_overlaps(parts: &[PartFile], owners: &[Vec<usize>], problems: &mut Vec<String>) {
    let mut reported = Vec::new();
    for list in owners.iter().filter(|l| l.len() > 1) {
        if reported.contains(list) {
            continue;
        }
        reported.push(list.clone());
        let first = &parts[list[0]];
        let same = list.iter().all(|&k| parts[k].part == first.part);
        let described: Vec<String> = list.iter().map(|&k| describe(&parts[k])).collect();
        problems.push(if same {
            format!(
                "duplicate shard {} of {}: {} hold the same realizations; keep one of them",
                first.part.index,
                first.part.count,
                described.join(" and ")
            )
        } else {
            format!(
                "overlapping shard files: {} hold some of the same realizations (different --of); keep the \
                 files of one split",
                described.join(" and ")
            )
        });
    }
}

/// The problem of internal shards no file holds: the shard indices to resubmit in the split most files
/// use, with their realizations, and the unfinished files found for them.
fn missing_shards(meta: &RunMetadata, parts: &[PartFile], missing: &[usize], unfinished: &[PathBuf]) -> String {
    let n_shards = meta.n_shards();
    let mut counts: Vec<(usize, usize)> = Vec::new();
    for p in parts {
        match counts.iter_mut().find(|c| c.0 == p.part.count) {
            Some(c) => c.1 += 1,
            None => counts.push((p.part.count, 1)),
        }
    }
    counts.sort_by_key(|c| std::cmp::Reverse(c.1));
    let n = counts[0].0;
    let mut indices: Vec<usize> = missing.iter().map(|&b| Part::owner(b, n_shards, n)).collect();
    indices.dedup();
    let ranges: Vec<String> = indices
        .iter()
        .map(|&i| {
            let s = Part { index: i, count: n }.shards(n_shards);
            let (a, z) = (meta.shard_range(s.start).start, meta.shard_range(s.end - 1).end);
            format!("{i} (realizations {a}..{z})")
        })
        .collect();
    let list = indices.iter().map(|i| i.to_string()).collect::<Vec<_>>().join(",");
    let mut r = format!(
        "missing shard(s) {} of {n}: no file holds their realizations; resubmit exactly these indices with \
         the same parameters (SLURM: sbatch --array={list} ...; otherwise stochvib simulate ... --shard I \
         --of {n} for each I), then merge again",
        ranges.join(", ")
    );
    let expected: Vec<String> = indices
        .iter()
        .map(|&i| Part { index: i, count: n }.file_name() + L::TMP_SUFFIX)
        .collect();
    let interrupted: Vec<&PathBuf> = unfinished
        .iter()
        .filter(|u| {
            u.file_name()
                .is_some_and(|f| expected.iter().any(|e| *e == f.to_string_lossy()))
        })
        .collect();
    if !interrupted.is_empty() {
        let list: Vec<String> = interrupted.iter().map(|p| p.display().to_string()).collect();
        let _ = write!(r, " (unfinished: {}; rerunning the shard resumes it)", list.join(", "));
    }
    r
}

impl PartSet {
    /// Opens the shard files of `inputs` (see [`find_run_files`]; `exclude` as there) and checks them.
    ///
    /// # Errors
    /// [`Error::Hdf5`] with one message that lists every problem found, naming the files: no files; a file
    /// that is not a complete shard file (a whole run, an unreadable or unfinished file); files of different
    /// runs (the fields that differ; the toolkit version must be the same, since only the version that
    /// computed a shard guarantees bit-identical results); two files holding the same realizations
    /// (duplicates or overlapping splits); realizations no file holds (the shard indices to resubmit, and
    /// unfinished `.tmp` files found for them).
    pub fn open(inputs: &[PathBuf], exclude: &[&Path]) -> Result<PartSet> {
        let (files, unfinished) = find_run_files(inputs, exclude)?;
        let where_ = inputs
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ");
        let fail = |reason: String| Error::Hdf5 {
            path: inputs.first().cloned().unwrap_or_default(),
            reason,
        };
        if files.is_empty() {
            let mut r = format!("no shard files (*.h5) in {where_}");
            if !unfinished.is_empty() {
                let _ = write!(r, "; unfinished: {}", names(&unfinished));
            }
            return Err(fail(r));
        }
        let mut problems = Vec::new();
        let opened = open_headers(files, &mut problems);
        if opened.is_empty() {
            return Err(fail(format!("no shard files to merge:\n  {}", problems.join("\n  "))));
        }
        let ((meta, toolkit_version), parts) = the_run(opened, &mut problems);
        // coverage of the internal shards
        let n_shards = meta.n_shards();
        let mut owners: Vec<Vec<usize>> = vec![Vec::new(); n_shards];
        for (k, p) in parts.iter().enumerate() {
            for b in p.meta.local_shards() {
                owners[b].push(k);
            }
        }
        report_overlaps(&parts, &owners, &mut problems);
        let missing: Vec<usize> = (0..n_shards).filter(|&b| owners[b].is_empty()).collect();
        if !missing.is_empty() {
            problems.push(missing_shards(&meta, &parts, &missing, &unfinished));
        }
        if !problems.is_empty() {
            return Err(fail(format!(
                "cannot merge the shard files of {where_}:\n  {}",
                problems.join("\n  ")
            )));
        }
        let ignored = unfinished
            .into_iter()
            .map(|u| {
                (
                    u,
                    "unfinished shard file (ignored: another file holds its realizations)".to_string(),
                )
            })
            .collect();
        Ok(PartSet {
            meta,
            toolkit_version,
            parts,
            ignored,
        })
    }

    /// The shard file holding internal shard `shard`.
    pub fn file_of(&self, shard: usize) -> Option<&PartFile> {
        self.parts.iter().find(|p| p.meta.local_shards().contains(&shard))
    }

    /// What a merged file at `out` records about these files, with the file paths relative to `out`'s
    /// directory.
    pub fn merged_from(&self, out: &Path, raw: RawStorage) -> MergedFrom {
        let dir = out
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        MergedFrom {
            files: self.parts.iter().map(|p| relative_path(dir, &p.path)).collect(),
            first_realizations: self.parts.iter().map(|p| p.meta.local_realizations().start).collect(),
            realizations: self.parts.iter().map(|p| p.meta.local_realizations().len()).collect(),
            raw,
        }
    }
}

fn describe(p: &PartFile) -> String {
    let r = p.meta.local_realizations();
    format!(
        "{} (shard {} of {}, realizations {}..{})",
        p.path.display(),
        p.part.index,
        p.part.count,
        r.start,
        r.end
    )
}

fn names(files: &[PathBuf]) -> String {
    files
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `target` relative to the directory `dir` (both resolved to absolute paths with symbolic links followed
/// where they exist), e.g. `runs/a/shard-0-of-2.h5` from `runs/`: `a/shard-0-of-2.h5`; `../x.h5` when the
/// target is outside. Falls back to the absolute path when there is no common root.
///
/// # Examples
/// ```ignore
/// // (private) relative_path(Path::new("/a/b"), Path::new("/a/c/d.h5")) == "../c/d.h5"
/// ```
pub(crate) fn relative_path(dir: &Path, target: &Path) -> String {
    let abs = |p: &Path| -> PathBuf {
        p.canonicalize().unwrap_or_else(|_| {
            std::env::current_dir()
                .map(|c| c.join(p))
                .unwrap_or_else(|_| p.to_path_buf())
        })
    };
    let (d, t) = (abs(dir), abs(target));
    let dc: Vec<_> = d.components().collect();
    let tc: Vec<_> = t.components().collect();
    let common = dc.iter().zip(&tc).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return t.display().to_string();
    }
    let mut rel = PathBuf::new();
    for _ in common..dc.len() {
        rel.push("..");
    }
    for c in &tc[common..] {
        rel.push(c.as_os_str());
    }
    rel.display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative paths against hand-written expectations.
    #[test]
    fn relative_paths() {
        assert_eq!(relative_path(Path::new("/a/b"), Path::new("/a/c/d.h5")), "../c/d.h5");
        assert_eq!(relative_path(Path::new("/a"), Path::new("/a/c/d.h5")), "c/d.h5");
        assert_eq!(relative_path(Path::new("/a/b"), Path::new("/a/b/d.h5")), "d.h5");
    }

    /// A tiling is accepted; a gap, an overlap and a short total are refused.
    #[test]
    fn merged_from_tiles() {
        let m = |firsts: Vec<usize>, counts: Vec<usize>| MergedFrom {
            files: vec!["a".into(), "b".into()],
            first_realizations: firsts,
            realizations: counts,
            raw: RawStorage::None,
        };
        assert!(m(vec![0, 5], vec![5, 5]).check(10).is_ok());
        assert!(m(vec![0, 6], vec![5, 4]).check(10).is_err());
        assert!(m(vec![0, 4], vec![5, 6]).check(10).is_err());
        assert!(m(vec![0, 5], vec![5, 4]).check(10).is_err());
        assert_eq!(m(vec![0, 5], vec![5, 5]).sources(4..6).len(), 2);
        assert_eq!(m(vec![0, 5], vec![5, 5]).sources(5..6)[0].file, "b");
    }
}
