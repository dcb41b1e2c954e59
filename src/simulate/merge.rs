//! `stochvib merge`: the shard files of a cluster run into one run file, bit-identical to the run of one
//! process with the same scenario, seed, options and `--shard-size`.
//!
//! # Formula
//! Part I of N holds whole internal shards ([`Part`](crate::store::Part)); the merge checks that the parts
//! cover every internal shard b = 0 … B−1 exactly once ([`PartSet::open`]), copies each shard's
//! accumulators (the time averages m_i, v_i and the Welch sums) in the order b = 0, 1, …, B−1, and finishes
//! the statistics with the code of a single-process run ([`super::finish`]): the values are the same
//! floating-point operations in the same order, so they are bit-identical, for any N and any order of the
//! inputs. The analytic values, the analytic density and the expected Welch estimate are taken from the shard files (they are the same
//! numbers in every file, which is checked).
//!
//! # Raw realizations
//! By default the merged file's raw datasets are HDF5 virtual datasets that map the rows of every shard
//! file (the merged file stays small): the shard files must stay where the merged file expects them — their
//! paths are stored relative to the merged file's directory, so the merged file and the run directory may
//! move together. With `copy` the rows are copied into the merged file, which then stands alone.

use super::finish::{density_estimate, output_statistics, read_output, Analytic};
use crate::error::{Error, Result};
use crate::estimate::Welch;
use crate::store::{tmp_path, CreateOptions, OutputStatistics, PartSet, RawStorage, RunWriter, SignalGroup};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Options of [`merge_runs`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MergeOptions {
    /// Copy the raw realizations into the merged file instead of referencing the shard files.
    pub copy: bool,
    /// Replace an existing finished run file at `out` (at the final rename).
    pub overwrite: bool,
    /// Confidence of the intervals; default: that of the shard files (which must then agree).
    pub confidence: Option<f64>,
}

/// What [`merge_runs`] did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MergeSummary {
    /// The merged file.
    pub path: PathBuf,
    /// The shard files, in shard order.
    pub files: Vec<PathBuf>,
    /// Realizations of the run.
    pub n_realizations: usize,
    /// Internal shards of the run.
    pub n_shards: usize,
    /// Where the raw realizations are.
    pub raw: RawStorage,
    /// The statistics of every output, as stored in the merged file.
    pub outputs: Vec<OutputStatistics>,
    /// Remarks (ignored files, where the raw data live).
    pub notes: Vec<String>,
}

impl std::fmt::Display for MergeSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "merged    {}", self.path.display())?;
        writeln!(
            f,
            "from      {} shard files, {} realizations in {} internal shards; raw data {}",
            self.files.len(),
            self.n_realizations,
            self.n_shards,
            self.raw.label()
        )?;
        for n in &self.notes {
            writeln!(f, "note      {n}")?;
        }
        writeln!(
            f,
            "{:<14} {:>13} {:>13} {:>27}  covers",
            "output", "analytic σ", "MC σ", "interval"
        )?;
        for o in &self.outputs {
            let Some(s) = o.get("sigma") else { continue };
            let iv = &s.interval;
            writeln!(
                f,
                "{:<14} {:>13.6e} {:>13.6e} [{:.6e}, {:.6e}]  {} ({} %)",
                o.output,
                s.analytic.unwrap_or(f64::NAN),
                iv.estimate,
                iv.lower,
                iv.upper,
                if s.covers == Some(true) { "yes" } else { "NO" },
                100.0 * iv.confidence
            )?;
        }
        Ok(())
    }
}

/// Merges the shard files of `inputs` (directories stand for their `*.h5` files) into the run file `out`
/// (see the module docs). `progress(done, total)` is called after every internal shard. `out` is written
/// as `<out>.tmp` and renamed when complete; an existing `out` is never replaced without
/// `opts.overwrite`, and no input is modified.
///
/// # Errors
/// [`PartSet::open`]'s refusals (foreign, duplicate, overlapping, missing shards, naming the files and the
/// indices to resubmit); shard files whose analytic values or confidence levels disagree; a damaged shard
/// (checksum); the writer's errors.
///
/// # Examples
/// ```
/// use stochvib::scenario::load_scenario;
/// use stochvib::simulate::{merge_runs, part_path, MergeOptions, RunOptions};
/// use stochvib::store::{Part, RunFile};
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/conveyor-idler.toml"), Path::new("spectra")).unwrap();
/// let dir = std::env::temp_dir().join(format!("stochvib-doc-merge-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let opts = |part| RunOptions { shard_size: 5, part, ..RunOptions::new(20, 2.0, 0.01, 3) };
/// let whole = sc.simulate(&opts(None), &dir.join("whole.h5"), &|_, _| {}).unwrap();
/// for i in [1, 0] {
///     let p = Part::new(i, 2).unwrap();
///     sc.simulate(&opts(Some(p)), &part_path(&dir, p), &|_, _| {}).unwrap();
/// }
/// let merged = merge_runs(&dir.join("merged.h5"), &[dir.join("shard-0-of-2.h5"), dir.join("shard-1-of-2.h5")],
///     &MergeOptions::default(), &|_, _| {}).unwrap();
/// assert_eq!(merged.outputs, whole.outputs); // bit for bit
/// # std::fs::remove_dir_all(&dir).unwrap();
/// ```
pub fn merge_runs(
    out: &Path,
    inputs: &[PathBuf],
    opts: &MergeOptions,
    progress: &dyn Fn(usize, usize),
) -> Result<MergeSummary> {
    let tmp = tmp_path(out);
    let set = PartSet::open(inputs, &[out, &tmp])?;
    let meta = set.meta.clone();
    let raw = match (meta.store_raw, opts.copy) {
        (false, _) => RawStorage::None,
        (true, true) => RawStorage::Copied,
        (true, false) => RawStorage::Virtual,
    };
    // what every shard file says about the analytic values, the density and the confidence
    let first = &set.parts[0];
    let stats0 = first.run.statistics()?;
    let psd0 = first.run.psd()?;
    for p in &set.parts[1..] {
        let (s, d) = (p.run.statistics()?, p.run.psd()?);
        let analytic =
            |st: &[OutputStatistics]| -> Vec<Option<Analytic>> { st.iter().map(Analytic::from_statistics).collect() };
        // the analytic and the expected density, bit for bit
        let dens = |d: &[crate::store::PsdEstimate]| -> Vec<[Option<Vec<u64>>; 2]> {
            let bits = |v: &Option<Vec<f64>>| v.as_ref().map(|a| a.iter().map(|x| x.to_bits()).collect());
            d.iter().map(|e| [bits(&e.analytic), bits(&e.expected)]).collect()
        };
        if analytic(&s) != analytic(&stats0) || dens(&d) != dens(&psd0) {
            return Err(Error::Hdf5 {
                path: p.path.clone(),
                reason: format!(
                    "its analytic values differ from those of {} although the run is the same: one of them is \
                     damaged",
                    first.path.display()
                ),
            });
        }
    }
    let confidence = match opts.confidence {
        Some(c) => c,
        None => {
            let conf = |p: &crate::store::PartFile| -> Result<Vec<u64>> {
                Ok(p.run
                    .statistics()?
                    .iter()
                    .flat_map(|o| o.statistics.iter().map(|s| s.interval.confidence.to_bits()))
                    .collect())
            };
            let c0 = conf(first)?;
            for p in &set.parts[1..] {
                if conf(p)? != c0 {
                    return Err(Error::invalid(
                        "confidence",
                        p.path.display(),
                        format!(
                            "the shard files were run with different --confidence ({} and {}): give the merge \
                             --confidence",
                            first.path.display(),
                            p.path.display()
                        ),
                    ));
                }
            }
            c0.first().map(|b| f64::from_bits(*b)).unwrap_or(0.95)
        }
    };
    let from = set.merged_from(out, raw);
    let mut writer = RunWriter::create_merged(
        out,
        &meta,
        CreateOptions {
            overwrite: opts.overwrite,
            ..CreateOptions::default()
        },
        &from,
    )?;
    let n_shards = meta.n_shards();
    let names: Vec<&str> = meta.accumulators.iter().map(|a| a.0.as_str()).collect();
    progress(0, n_shards);
    for b in 0..n_shards {
        let p = set.file_of(b).ok_or_else(|| Error::Numerical {
            what: "merge".into(),
            reason: format!("no shard file holds internal shard {b} (checked before: a bug)"),
        })?;
        let accs = names
            .iter()
            .map(|n| p.run.read_accumulator(n, b))
            .collect::<Result<Vec<_>>>()?;
        let acc_refs: Vec<&[f64]> = accs.iter().map(|a| a.as_slice()).collect();
        let sums = p.run.shard_checksums(b)?;
        if raw == RawStorage::Copied {
            let range = meta.shard_range(b);
            let read = |g: SignalGroup, list: &[crate::store::Signal]| -> Result<Vec<ndarray::Array2<f64>>> {
                list.iter()
                    .map(|s| p.run.read_signals(g, &s.name, range.clone()))
                    .collect()
            };
            let ins = read(SignalGroup::Inputs, &meta.inputs)?;
            let outs = read(SignalGroup::Outputs, &meta.outputs)?;
            for (j, a) in ins.iter().chain(&outs).enumerate() {
                let crc = crate::store::checksum::crc32_f64(a.as_standard_layout().as_slice().unwrap_or(&[]));
                if sums.get(j) != Some(&crc) {
                    return Err(Error::Hdf5 {
                        path: p.path.clone(),
                        reason: format!("checksum mismatch in the raw rows of shard {b}: the file is damaged"),
                    });
                }
            }
            let iv: Vec<_> = ins.iter().map(|a| a.view()).collect();
            let ov: Vec<_> = outs.iter().map(|a| a.view()).collect();
            writer.write_shard(b, &iv, &ov, &acc_refs)?;
        } else {
            writer.adopt_shard(b, &acc_refs, &sums)?;
        }
        progress(b + 1, n_shards);
    }
    // the statistics, as a single-process run finishes them
    let bins = meta
        .accumulators
        .iter()
        .find(|a| a.0.ends_with(":welch"))
        .map(|a| a.1 - 2)
        .ok_or_else(|| Error::Numerical {
            what: "merge".into(),
            reason: "the run has no Welch accumulator".into(),
        })?;
    let welch = Welch::new(2 * (bins - 1), meta.dt)?;
    let acc = |name: &str, shard: usize| writer.read_accumulator(name, shard);
    let mut stats = Vec::new();
    let mut psds = Vec::new();
    for sig in &meta.outputs {
        let (m, v, ws) = read_output(&acc, &meta, &sig.name, &welch)?;
        let stored = stats0.iter().find(|s| s.output == sig.name);
        let analytic = stored.and_then(Analytic::from_statistics).ok_or_else(|| Error::Hdf5 {
            path: first.path.clone(),
            reason: format!("no analytic values stored for output `{}`", sig.name),
        })?;
        stats.push(output_statistics(sig, &analytic, &m, &v, confidence)?);
        let stored_psd = psd0.iter().find(|e| e.output == sig.name);
        let dens = stored_psd.and_then(|e| e.analytic.clone());
        let mut psd = density_estimate(sig, &welch, &ws, confidence, |omega| match &dens {
            Some(d) if d.len() != omega.len() => Err(Error::Hdf5 {
                path: first.path.clone(),
                reason: format!("its analytic density of `{}` has another length", sig.name),
            }),
            _ => Ok(dens.clone()),
        })?;
        // the expected estimate depends on the plan only (not on the realizations): every shard file stores
        // the same numbers (checked above), which a single-process run computes
        psd.expected = match stored_psd.and_then(|e| e.expected.clone()) {
            Some(e) if e.len() != psd.omega.len() => {
                return Err(Error::Hdf5 {
                    path: first.path.clone(),
                    reason: format!("its expected density of `{}` has another length", sig.name),
                })
            }
            e => e,
        };
        psds.push(psd);
    }
    writer.write_statistics(&stats)?;
    for psd in &psds {
        writer.write_psd(psd)?;
    }
    let path = writer.finish()?;
    let mut notes: Vec<String> = set
        .ignored
        .iter()
        .map(|(p, why)| format!("{}: {why}", p.display()))
        .collect();
    if raw == RawStorage::Virtual {
        notes.push(format!(
            "the raw realizations are virtual datasets reading the shard files ({}, relative to the merged file's \
             directory): keep them there (move the merged file and the shard directory together), or merge with \
             --copy",
            from.files.join(", ")
        ));
    }
    Ok(MergeSummary {
        path,
        files: set.parts.iter().map(|p| p.path.clone()).collect(),
        n_realizations: meta.n_realizations,
        n_shards,
        raw,
        outputs: stats,
        notes,
    })
}
