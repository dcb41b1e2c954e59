//! What a rerun of one part of a cluster run does when the part's file is already there
//! ([`crate::study::shard`] holds the rest of the shard contract): a finished file of the same run is the
//! result (a no-op), anything else in the way is refused.

use super::plan::Plan;
use super::run::summary_of_file;
use super::{RunOptions, RunSummary};
use crate::error::{Error, Result};
use crate::store::{metadata_differences, RunFile, RunMetadata};
use std::path::Path;

/// The summary of `out` when it is already the finished shard file of this run (a rerun is a no-op);
/// `None` when there is nothing there (or `--overwrite` asks to replace it), or when the run is not a part.
///
/// # Errors
/// [`Error::Hdf5`] when `out` is something else: a shard file of another run (naming what differs), not
/// a complete run file, or a damaged one (a checksum fails: [`RunFile::verify`]). Nothing is replaced or
/// deleted.
pub(crate) fn finished_part(
    meta: &RunMetadata,
    plan: &Plan,
    out: &Path,
    opts: &RunOptions,
) -> Result<Option<RunSummary>> {
    let Some(part) = meta.part else { return Ok(None) };
    if !out.is_file() || opts.overwrite {
        return Ok(None);
    }
    let in_the_way = |reason: String| Error::Hdf5 {
        path: out.to_path_buf(),
        reason,
    };
    let run = RunFile::open(out).map_err(|e| {
        in_the_way(format!(
            "is in the way of shard {} of {} and is not its finished file ({e}); nothing is overwritten: remove \
             it, choose another run directory, or pass --overwrite",
            part.index, part.count
        ))
    })?;
    let mut differ = metadata_differences(run.metadata(), meta);
    if run.toolkit_version() != crate::store::layout::TOOLKIT_VERSION {
        differ.push(format!("toolkit version ({})", run.toolkit_version()));
    }
    if run.metadata().part != meta.part {
        differ.push("shard index or count".into());
    }
    if !differ.is_empty() {
        return Err(in_the_way(format!(
            "holds a finished shard file of another run (differs in {}); nothing is overwritten: use another run \
             directory for this run, or pass --overwrite",
            differ.join(", ")
        )));
    }
    // a finished file is the result only if its checksums hold (as `inspect` checks them)
    run.verify().map_err(|e| {
        in_the_way(format!(
            "is the finished file of shard {} of {} but is damaged ({e}); nothing is overwritten: pass --overwrite \
             to compute the shard again",
            part.index, part.count
        ))
    })?;
    let note = format!(
        "shard {} of {} is already complete in {}: nothing to do (a rerun of a finished shard is a no-op)",
        part.index,
        part.count,
        out.display()
    );
    summary_of_file(&run, plan, vec![note]).map(Some)
}
