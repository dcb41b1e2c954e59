//! `stochvib merge`: the shard files of a cluster run into one run file, bit-identical to the run of one
//! process with the same scenario, seed, options and `--shard-size`.
//!
//! # Formula
//! Part I of N holds whole internal shards ([`Part`](crate::store::Part)); the merge checks that the parts
//! cover every internal shard b = 0 … B−1 exactly once ([`PartSet::open`]), copies each shard's
//! accumulators (the time averages m_i, v_i and the Welch sums) in the order b = 0, 1, …, B−1, and finishes
//! the statistics with the code of a single-process run (`simulate`'s `finish`): the values are the same
//! floating-point operations in the same order, so they are bit-identical, for any N and any order of the
//! inputs. The analytic values, the analytic density and the expected Welch estimate are taken from the shard files (they are the same
//! numbers in every file, which is checked).
//!
//! # Raw realizations
//! By default the merged file's raw datasets are HDF5 virtual datasets that map the rows of every shard
//! file (the merged file stays small): the shard files must stay where the merged file expects them — their
//! paths are stored relative to the merged file's directory, so the merged file and the run directory may
//! move together. With `copy` the rows are copied into the merged file, which then stands alone.

use crate::error::{Error, Result};
use crate::estimate::Welch;
use crate::simulate::accumulators::{Moments, WelchAccumulator};
use crate::simulate::bands;
use crate::simulate::verdicts::{set_analytic, VerdictChannels};
use crate::simulate::{density_estimate, output_statistics, write_band_tables, Analytic, OutputFold};
use crate::store::{
    tmp_path, MergeOptions, OutputStatistics, PartFile, PartSet, PsdEstimate, RainflowHistogram, RawStorage,
    ResponseHistogram, RunFile, RunMetadata, RunWriter, Signal, SignalGroup,
};
use ndarray::{Array2, ArrayView1};
use serde::Serialize;
use std::path::{Path, PathBuf};

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
        write_band_tables(f, &self.outputs)
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
/// use stochvib::simulate::RunOptions;
/// use stochvib::study::{merge_runs, part_path, MergeOptions};
/// use stochvib::store::{Part, RunFile};
/// use std::path::Path;
/// let sc = load_scenario(Path::new("data/conveyor-idler.toml"), Path::new("spectra")).unwrap();
/// let dir = std::env::temp_dir().join(format!("stochvib-doc-merge-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let opts = |part| RunOptions {
///     realizations: 20,
///     duration_s: 2.0,
///     dt_s: 0.01,
///     seed: 3,
///     shard_size: 5,
///     part,
///     ..RunOptions::default()
/// };
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
    refuse_shard_output(out)?;
    // pass 1: every file's header and the fingerprint of its shared values; the files are closed again
    let set = PartSet::open(inputs, &[out, &tmp])?;
    let meta = set.meta.clone();
    crate::nonlinear::monte_carlo::refuse_other_version(&meta, &set.parts[0].path)?;
    let raw = opts.raw_storage(meta.store_raw);
    check_shared_values(&set)?;
    let first = &set.parts[0];
    let shared = Shared::read(first)?;
    let confidence = merge_confidence(opts, &set, &shared.stats)?;
    let from = set.merged_from(out, raw);
    let mut writer = RunWriter::create_merged(out, &meta, opts.create_options(), &from)?;
    // a merge refused from here on (a damaged shard found in pass 2) leaves no .tmp of its own behind
    let mut created = RemoveOnError((!writer.resumed()).then(|| writer.tmp_path().to_path_buf()));
    let n_shards = meta.n_shards();
    let names: Vec<&str> = meta.accumulators.iter().map(|a| a.0.as_str()).collect();
    // the statistics, as a single-process run finishes them
    let welch = welch_of(&meta)?;
    let mut folds = output_folds(&meta, &names, &first.path, &welch)?;
    progress(0, n_shards);
    // pass 2: the files one at a time in realization order (one open file; memory independent of their
    // number), each file's shards in one block
    for p in &set.parts {
        fold_part(p, &meta, &names, raw, &mut folds, &mut writer)?;
        progress(p.meta.local_shards().end, n_shards);
    }
    let (mut stats, psds) = finish_outputs(&meta, folds, &shared, &welch, confidence, &first.path)?;
    let rainflow = finish_channels(&mut writer, &meta, confidence, &shared, &first.path, &mut stats)?;
    let path = writer.finish_with(&stats, &rainflow, &psds)?;
    created.0 = None;
    Ok(MergeSummary {
        path,
        files: set.parts.iter().map(|p| p.path.clone()).collect(),
        n_realizations: meta.n_realizations,
        n_shards,
        raw,
        outputs: stats,
        notes: merge_notes(&set, raw, &from.files),
    })
}

/// The statistics of the verdict channels, the bands and a nonlinear run's response histograms, appended
/// to `stats` as a single-process run appends them; returns the rainflow histograms.
fn finish_channels(
    writer: &mut RunWriter,
    meta: &RunMetadata,
    confidence: f64,
    shared: &Shared,
    first: &Path,
    stats: &mut [OutputStatistics],
) -> Result<Vec<RainflowHistogram>> {
    let rainflow = finish_verdicts(writer, meta, confidence, &shared.stats, &shared.rainflow, first, stats)?;
    finish_bands(writer, meta, confidence, &shared.stats, first, stats)?;
    crate::nonlinear::monte_carlo::finish_merged(writer, meta, confidence, &shared.stats, &shared.histograms, stats)?;
    Ok(rainflow)
}

/// Refuses shard files whose shared values (analytic values, densities) differ from the first's.
fn check_shared_values(set: &PartSet) -> Result<()> {
    let first = &set.parts[0];
    for p in &set.parts[1..] {
        if p.shared != first.shared {
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
    Ok(())
}

/// The values every shard file stores alike, read from the first file (checked against its checksums).
struct Shared {
    stats: Vec<OutputStatistics>,
    psd: Vec<PsdEstimate>,
    rainflow: Vec<RainflowHistogram>,
    histograms: Vec<ResponseHistogram>,
}

impl Shared {
    fn read(first: &PartFile) -> Result<Shared> {
        let run = first.open()?;
        Ok(Shared {
            stats: run.statistics()?,
            psd: run.psd()?,
            rainflow: run.rainflow()?,
            histograms: run.response_histograms()?,
        })
    }
}

/// The confidence of the merged intervals: `opts.confidence`, else that of the shard files, which must
/// agree.
fn merge_confidence(opts: &MergeOptions, set: &PartSet, stats0: &[OutputStatistics]) -> Result<f64> {
    if let Some(c) = opts.confidence {
        return Ok(c);
    }
    let first = &set.parts[0];
    if let Some(p) = set.parts[1..].iter().find(|p| p.confidence != first.confidence) {
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
    Ok(stats0
        .iter()
        .flat_map(|o| &o.statistics)
        .map(|s| s.interval.confidence)
        .next()
        .unwrap_or(0.95))
}

/// The Welch estimator of the run, from the length of its Welch accumulators.
fn welch_of(meta: &RunMetadata) -> Result<Welch> {
    let bins = meta
        .accumulators
        .iter()
        .find(|a| a.0.ends_with(":welch"))
        .map(|a| a.1 - 2)
        .ok_or_else(|| Error::Numerical {
            what: "merge".into(),
            reason: "the run has no Welch accumulator".into(),
        })?;
    Welch::new(2 * (bins - 1), meta.dt)
}

/// The fold of one output and the columns of its moment and Welch accumulators.
type Fold = (usize, usize, OutputFold);

/// The time averages and Welch sums of every output, folded shard by shard as a single-process run reads
/// them back: nothing folded yet.
fn output_folds(meta: &RunMetadata, names: &[&str], first: &Path, welch: &Welch) -> Result<Vec<Fold>> {
    meta.outputs
        .iter()
        .map(|sig| {
            let at = |name: String| {
                names.iter().position(|n| *n == name).ok_or_else(|| Error::Hdf5 {
                    path: first.to_path_buf(),
                    reason: format!("no accumulator `{name}`"),
                })
            };
            Ok((
                at(Moments::name(&sig.name))?,
                at(WelchAccumulator::name(&sig.name))?,
                OutputFold::new(welch),
            ))
        })
        .collect()
}

/// Pass 2 for one shard file: its accumulator rows checked and folded, and its shards written (copied or
/// adopted) into the merged file.
fn fold_part(
    p: &PartFile,
    meta: &RunMetadata,
    names: &[&str],
    raw: RawStorage,
    folds: &mut [Fold],
    writer: &mut RunWriter,
) -> Result<()> {
    let run = p.open()?;
    let local = p.meta.local_shards();
    let (accs, sums) = p.shard_rows(&run, names)?;
    if accs.iter().any(|a| a.nrows() != local.len()) || sums.nrows() != local.len() {
        return Err(Error::Hdf5 {
            path: p.path.clone(),
            reason: format!("its /shards datasets do not have one row per shard ({})", local.len()),
        });
    }
    let raw_columns = if meta.store_raw {
        meta.inputs.len() + meta.outputs.len()
    } else {
        0
    };
    verify_rows(&p.path, &p.meta, names, &accs, &sums, raw_columns)?;
    for (r, b) in local.clone().enumerate() {
        let rows = meta.shard_range(b).len();
        for (jm, jw, fold) in folds.iter_mut() {
            fold.add(
                rows,
                meta.shard_size,
                &accs[*jm].row(r).to_vec(),
                &accs[*jw].row(r).to_vec(),
            )?;
        }
    }
    if raw == RawStorage::Copied {
        for (r, b) in local.clone().enumerate() {
            let rows: Vec<Vec<f64>> = accs.iter().map(|a| a.row(r).to_vec()).collect();
            copy_shard(p, &run, meta, b, &rows, sums.row(r), writer)?;
        }
    } else {
        let views: Vec<_> = accs.iter().map(|a| a.view()).collect();
        writer.adopt_shards(local.start, &views, sums.view())?;
    }
    Ok(())
}

/// Copies the raw rows of shard `b`, checked against their checksums `sums`, with its accumulator rows
/// `accs` into the merged file.
fn copy_shard(
    p: &PartFile,
    run: &RunFile,
    meta: &RunMetadata,
    b: usize,
    accs: &[Vec<f64>],
    sums: ArrayView1<'_, u32>,
    writer: &mut RunWriter,
) -> Result<()> {
    let range = meta.shard_range(b);
    let read = |g: SignalGroup, list: &[Signal]| -> Result<Vec<Array2<f64>>> {
        list.iter()
            .map(|s| run.read_signals(g, &s.name, range.clone()))
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
    let acc_refs: Vec<&[f64]> = accs.iter().map(|a| a.as_slice()).collect();
    writer.write_shard(b, &iv, &ov, &acc_refs)
}

/// The statistics and density estimate of every output from its folds, finished as a single-process run
/// finishes them, with the analytic values and densities the shard files share.
fn finish_outputs(
    meta: &RunMetadata,
    folds: Vec<Fold>,
    shared: &Shared,
    welch: &Welch,
    confidence: f64,
    first: &Path,
) -> Result<(Vec<OutputStatistics>, Vec<PsdEstimate>)> {
    let mut stats = Vec::new();
    let mut psds = Vec::new();
    for (sig, (_, _, fold)) in meta.outputs.iter().zip(folds) {
        let (m, v, ws) = (fold.mean, fold.mean_square, fold.welch);
        let stored = shared.stats.iter().find(|s| s.output == sig.name);
        let analytic = stored.and_then(Analytic::from_statistics).ok_or_else(|| Error::Hdf5 {
            path: first.to_path_buf(),
            reason: format!("no analytic values stored for output `{}`", sig.name),
        })?;
        stats.push(output_statistics(sig, &analytic, &m, &v, confidence)?);
        let stored_psd = shared.psd.iter().find(|e| e.output == sig.name);
        let dens = stored_psd.and_then(|e| e.analytic.clone());
        let mut psd = density_estimate(sig, welch, &ws, confidence, |omega| match &dens {
            Some(d) if d.len() != omega.len() => Err(Error::Hdf5 {
                path: first.to_path_buf(),
                reason: format!("its analytic density of `{}` has another length", sig.name),
            }),
            _ => Ok(dens.clone()),
        })?;
        // the expected estimate depends on the plan only (not on the realizations): every shard file stores
        // the same numbers (checked above), which a single-process run computes
        psd.expected = match stored_psd.and_then(|e| e.expected.clone()) {
            Some(e) if e.len() != psd.omega.len() => {
                return Err(Error::Hdf5 {
                    path: first.to_path_buf(),
                    reason: format!("its expected density of `{}` has another length", sig.name),
                })
            }
            e => e,
        };
        psds.push(psd);
    }
    Ok((stats, psds))
}

/// The remarks of a merge: ignored files, and where virtual raw datasets read from.
fn merge_notes(set: &PartSet, raw: RawStorage, files: &[String]) -> Vec<String> {
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
            crate::store::abbreviated_list(files, crate::store::LISTED_FILES)
        ));
    }
    notes
}

/// Removes the temporary file a merge created when the merge returns with an error before its final rename
/// (nothing is left of a refused merge); `None` once renamed, or for a `.tmp` the merge resumed.
struct RemoveOnError(Option<PathBuf>);

impl Drop for RemoveOnError {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Refuses a merged file `out` that is an existing shard file of a cluster run (`merge SHARD-0 SHARD-1 …`
/// takes the first shard for the output): a shard file is never written over, whatever `--overwrite` says.
fn refuse_shard_output(out: &Path) -> Result<()> {
    if !crate::io_rules::starts_with(out, crate::io_rules::HDF5_SIGNATURE) {
        return Ok(());
    }
    let part = crate::store::RunFile::open_any(out).ok().and_then(|run| run.part());
    match part {
        None => Ok(()),
        Some(p) => Err(Error::Hdf5 {
            path: out.to_path_buf(),
            reason: format!(
                "is a shard file of a cluster run (shard {} of {}), not a merged file: a shard file is never \
                 written over; the first argument of merge is the merged file — `stochvib merge MERGED.h5 SHARDS…` \
                 (list this file among the shards); nothing was written",
                p.index, p.count
            ),
        }),
    }
}

/// Refuses a shard file whose accumulator rows (`accs[j]`, one row per internal shard of the file) do not
/// match their checksums (column `raw_columns + j` of `sums`), before anything of it is folded: the error
/// names the file, the dataset, the internal shard and the part to compute again.
fn verify_rows(
    path: &Path,
    meta: &crate::store::RunMetadata,
    names: &[&str],
    accs: &[ndarray::Array2<f64>],
    sums: &ndarray::Array2<u32>,
    raw_columns: usize,
) -> Result<()> {
    for ((j, a), name) in accs.iter().enumerate().zip(names) {
        for (r, row) in a.rows().into_iter().enumerate() {
            let row = row.as_standard_layout();
            let crc = crate::store::checksum::crc32_f64(row.as_slice().unwrap_or(&[]));
            if sums.get((r, raw_columns + j)) == Some(&crc) {
                continue;
            }
            let again = meta.part.map_or(String::new(), |p| {
                format!(
                    "; compute it again (stochvib simulate … --shard {} --of {} --overwrite, the same settings) and \
                     merge again",
                    p.index, p.count
                )
            });
            return Err(Error::Hdf5 {
                path: path.to_path_buf(),
                reason: format!(
                    "checksum mismatch in shards/{name} (internal shard {}): this shard file is damaged (its data are \
                     not what was written){again}",
                    meta.local_shards().start + r
                ),
            });
        }
    }
    Ok(())
}

/// The verdict statistics of a merged run (`vdv`, `mtvv`, `crest_factor` of every comfort channel,
/// `damage_rate` of every fatigue channel, appended to their outputs' statistics as a single-process run
/// appends them) and its rainflow histograms, from the merged accumulators of every internal shard in
/// order ([`VerdictChannels::finish`], the code of a single-process run). The analytic values (VDV of the
/// Gaussian weighted output, Dirlik's damage rate), the histogram edges, unit and Dirlik counts depend on
/// the plan only: they are taken from the first shard file (`stats0`, `rain0`; every shard file stores the
/// same, which [`PartSet::open`] checked).
///
/// # Errors
/// A verdict statistic or histogram missing from the shard file; [`VerdictChannels::finish`]'s errors.
fn finish_verdicts(
    writer: &RunWriter,
    meta: &crate::store::RunMetadata,
    confidence: f64,
    stats0: &[OutputStatistics],
    rain0: &[crate::store::RainflowHistogram],
    first: &Path,
    stats: &mut [OutputStatistics],
) -> Result<Vec<crate::store::RainflowHistogram>> {
    let channels = VerdictChannels::from_layout(&meta.accumulators, meta.shard_size)?;
    if channels.is_empty() {
        return Ok(Vec::new());
    }
    let missing = |what: String| Error::Hdf5 {
        path: first.to_path_buf(),
        reason: format!("no {what} stored, although the run has its verdict accumulators: the file is damaged"),
    };
    let stored = |output: &str, name: &str| {
        stats0
            .iter()
            .find(|o| o.output == output)
            .and_then(|o| o.get(name))
            .ok_or_else(|| missing(format!("statistic `{name}` of `{output}`")))
    };
    let rows: Vec<usize> = (0..meta.n_shards()).map(|b| meta.shard_range(b).len()).collect();
    let duration = meta.dt * meta.n_samples as f64;
    let (comfort, fatigue) = channels.finish(
        &|name, b| writer.read_accumulator(name, b),
        &rows,
        meta.shard_size,
        duration,
        confidence,
    )?;
    for (output, mut extra) in comfort {
        let st = stored(&output, "vdv")?;
        if let Some(vdv) = st.analytic {
            set_analytic(&mut extra, "vdv", vdv);
        }
        // the stored method says which law the analytic value is of (Gaussian or non-Gaussian)
        if let Some(v) = extra.iter_mut().find(|s| s.name == "vdv") {
            v.method = st.method.clone();
        }
        if let Some(st) = stats.iter_mut().find(|s| s.output == output) {
            st.statistics.extend(extra);
        }
    }
    let mut histograms = Vec::new();
    for (output, mut st, mut h) in fatigue {
        let kept = stored(&output, "damage_rate")?;
        st.analytic = kept.analytic;
        st.covers = st.analytic.map(|a| st.interval.covers(a));
        // the stored method says whether Dirlik's Gaussian rate was withdrawn (a non-Gaussian output)
        st.method = kept.method.clone();
        if let Some(s) = stats.iter_mut().find(|s| s.output == output) {
            s.statistics.push(st);
        }
        let r = rain0
            .iter()
            .find(|r| r.output == output)
            .ok_or_else(|| missing(format!("rainflow histogram of `{output}`")))?;
        if r.edges.len() != h.counts.len() + 1 {
            return Err(missing(format!(
                "rainflow histogram of `{output}` with {} bins",
                h.counts.len()
            )));
        }
        h.edges = r.edges.clone();
        h.dirlik = r.dirlik.clone();
        h.unit = r.unit.clone();
        histograms.push(h);
    }
    Ok(histograms)
}

/// The band r.m.s. statistics of a merged run (`band_rms[…]`, `band_rms_expected[…]`, appended to their
/// outputs' statistics as a single-process run appends them), from the merged band accumulators of every
/// internal shard in order ([`crate::simulate::bands`], the code of a single-process run). The band labels and their
/// analytic and expected values depend on the plan only: they are taken from the first shard file.
///
/// # Errors
/// Band accumulators without their statistics in the shard file (a damaged file); a damaged accumulator.
fn finish_bands(
    writer: &RunWriter,
    meta: &crate::store::RunMetadata,
    confidence: f64,
    stats0: &[OutputStatistics],
    first: &Path,
    stats: &mut [OutputStatistics],
) -> Result<()> {
    let shards: Vec<(usize, usize)> = (0..meta.n_shards()).map(|b| (b, meta.shard_range(b).len())).collect();
    for sig in &meta.outputs {
        let name = bands::accumulator_name(&sig.name);
        if !meta.accumulators.iter().any(|a| a.0 == name) {
            continue;
        }
        let stored = stats0.iter().find(|o| o.output == sig.name);
        let (labels, analytic, expected) = stored.map(bands::stored_bands).unwrap_or_default();
        let per_band = bands::read_bands(
            &|n, b| writer.read_accumulator(n, b),
            &sig.name,
            &shards,
            meta.shard_size,
        )?;
        if labels.is_empty() || labels.len() != per_band.len() {
            return Err(Error::Hdf5 {
                path: first.to_path_buf(),
                reason: format!(
                    "its band accumulator of `{}` holds {} bands but {} band statistics are stored: the file is \
                     damaged",
                    sig.name,
                    per_band.len(),
                    labels.len()
                ),
            });
        }
        let extra = bands::band_statistics(&sig.unit, &labels, &per_band, &analytic, &expected, confidence)?;
        if let Some(st) = stats.iter_mut().find(|s| s.output == sig.name) {
            st.statistics.extend(extra);
        }
    }
    Ok(())
}
