//! `stochvib merge` of a transient run: the part files of a cluster run into one run file whose statistics
//! are bit-identical to those of a single-process run (the counterpart of [`super::merge_runs`], which does
//! not handle transient runs).
//!
//! # Formula
//! The accumulators of every internal shard b = 0 … B−1 are adopted (or copied) in shard order and finished
//! by the code of a single-process run ([`crate::transient::monte_carlo::finish_merged`]); the analytic side
//! is taken from the first part file (every part file stores the same, which the shared fingerprint checks).

use crate::error::{Error, Result};
use crate::store::{MergeOptions, PartSet, RawStorage, RunFile, RunMetadata, RunWriter, SignalGroup};
use crate::transient::monte_carlo::finish_merged;
use crate::transient::TransientRunSummary;
use ndarray::Array2;
use std::path::{Path, PathBuf};

/// Merges the shard files `inputs` of a transient run into `out` (see the module docs); `progress(done,
/// total)` counts internal shards.
///
/// # Errors
/// As [`super::merge_runs`]; part files whose exact values differ; a shard file without its `/transient`
/// group.
pub fn merge_transient(
    out: &Path,
    inputs: &[PathBuf],
    opts: &MergeOptions,
    progress: &dyn Fn(usize, usize),
) -> Result<TransientRunSummary> {
    let tmp = crate::store::tmp_path(out);
    let set = PartSet::open(inputs, &[out, &tmp])?;
    let meta = set.meta.clone();
    let first = &set.parts[0];
    if let Some(p) = set.parts[1..].iter().find(|p| p.shared != first.shared) {
        return Err(Error::Hdf5 {
            path: p.path.clone(),
            reason: format!(
                "its exact values differ from those of {}: one of them is damaged",
                first.path.display()
            ),
        });
    }
    let stored = first.open()?.transient()?.ok_or_else(|| Error::Hdf5 {
        path: first.path.clone(),
        reason: "a transient shard file without its /transient group: the file is damaged".into(),
    })?;
    let confidence = opts.confidence.unwrap_or(stored.confidence);
    let raw = opts.raw_storage(meta.store_raw);
    let from = set.merged_from(out, raw);
    let mut writer = RunWriter::create_merged(out, &meta, opts.create_options(), &from)?;
    adopt_parts(&mut writer, &set, raw, progress)?;
    let notes = set
        .ignored
        .iter()
        .map(|(p, why)| format!("{}: {why}", p.display()))
        .collect();
    finish_merged(writer, &meta, &stored, confidence, notes)
}

/// Copies (or references) every part's shards into the merged writer, in shard order.
fn adopt_parts(writer: &mut RunWriter, set: &PartSet, raw: RawStorage, progress: &dyn Fn(usize, usize)) -> Result<()> {
    let meta = &set.meta;
    let names: Vec<&str> = meta.accumulators.iter().map(|a| a.0.as_str()).collect();
    progress(0, meta.n_shards());
    for p in &set.parts {
        let run = p.open()?;
        let local = p.meta.local_shards();
        let (accs, sums) = p.shard_rows(&run, &names)?;
        if raw == RawStorage::Copied {
            copy_rows(writer, &run, meta, local.clone(), &accs)?;
        } else {
            let views: Vec<_> = accs.iter().map(|a| a.view()).collect();
            writer.adopt_shards(local.start, &views, sums.view())?;
        }
        progress(local.end, meta.n_shards());
    }
    Ok(())
}

/// The raw rows and accumulators of the shards `local` of `run`, written into the merged file.
fn copy_rows(
    writer: &mut RunWriter,
    run: &RunFile,
    meta: &RunMetadata,
    local: std::ops::Range<usize>,
    accs: &[Array2<f64>],
) -> Result<()> {
    for (r, b) in local.enumerate() {
        let range = meta.shard_range(b);
        let outs = meta
            .outputs
            .iter()
            .map(|s| run.read_signals(SignalGroup::Outputs, &s.name, range.clone()))
            .collect::<Result<Vec<_>>>()?;
        let ov: Vec<_> = outs.iter().map(|a| a.view()).collect();
        let rows: Vec<Vec<f64>> = accs.iter().map(|a| a.row(r).to_vec()).collect();
        let refs: Vec<&[f64]> = rows.iter().map(|a| a.as_slice()).collect();
        writer.write_shard(b, &[], &ov, &refs)?;
    }
    Ok(())
}
