//! What a merge joins (`stochvib merge OUTPUT INPUTS…`, and the Python package's `merge`, `merge_sweep` and
//! `merge_transient`): the shard files of a parameter study, the part files of a transient run or those of a
//! stationary Monte Carlo run, one kind at a time; and the rule that the merged file is never one of its parts.

use crate::error::{Error, Result};
use crate::store::{find_run_files, RunFile};
use std::path::{Path, PathBuf};

/// The kind of files a merge's inputs hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MergeKind {
    /// Sweep shard files (`sweep-shard-<I>-of-<N>.json`), joined by [`super::merge_sweep`].
    Sweep,
    /// Part files of a transient run, joined by [`crate::study::merge_transient`].
    Transient,
    /// Part files of a stationary Monte Carlo run, joined by [`crate::study::merge_runs`].
    Run,
}

/// The kind of the files in `inputs` (files, or directories holding them), to be merged into `output`.
///
/// # Errors
/// [`Error::Hdf5`] naming `output` when the inputs hold sweep shard files and run files together, or when
/// `output` is one of the run's part files (see [`refuse_part_as_output`]); a directory or file that cannot
/// be read.
pub fn merge_kind(output: &Path, inputs: &[PathBuf]) -> Result<MergeKind> {
    let sweeps = super::find_sweep_shards(inputs)?;
    if let Some(sweep) = sweeps.first() {
        refuse_mixed(output, sweep, inputs)?;
        return Ok(MergeKind::Sweep);
    }
    refuse_part_as_output(output, inputs)?;
    let (runs, _) = find_run_files(inputs, &[output])?;
    let h5 = runs
        .iter()
        .find(|r| r.extension().is_some_and(|e| e == "h5" || e == "hdf5"));
    match h5 {
        Some(first) if crate::transient::monte_carlo::is_transient_run(RunFile::open(first)?.metadata()) => {
            Ok(MergeKind::Transient)
        }
        _ => Ok(MergeKind::Run),
    }
}

/// Refuses `inputs` that hold run files beside the sweep shard file `sweep` (one of theirs): a merge joins
/// one kind of file. [`super::merge_sweep`] asks this too, so that a library caller is refused as the
/// command line is (the table would otherwise be built without a word about the run files).
///
/// # Errors
/// [`Error::Hdf5`] naming `output`, a sweep shard file and a run file; a directory that cannot be read.
pub fn refuse_mixed(output: &Path, sweep: &Path, inputs: &[PathBuf]) -> Result<()> {
    let (mut runs, _) = find_run_files(inputs, &[output])?;
    runs.retain(|r| r.extension().is_none_or(|e| e != "json"));
    match runs.first() {
        Some(run) => Err(Error::Hdf5 {
            path: output.to_path_buf(),
            reason: format!(
                "the inputs hold both sweep shard files ({}) and run files ({}): merge one kind at a time",
                sweep.display(),
                run.display()
            ),
        }),
        None => Ok(()),
    }
}

/// The output rule of a merge: the merged file is never one of the part files it merges (named, or a part
/// file in a named directory); a whole run already there (an earlier merge) is what `overwrite` replaces.
///
/// # Errors
/// [`Error::Hdf5`] naming `output` when it is one of the parts; a directory that cannot be read.
pub fn refuse_part_as_output(output: &Path, inputs: &[PathBuf]) -> Result<()> {
    let (files, _) = find_run_files(inputs, &[])?;
    let named = inputs.iter().any(|i| crate::io_rules::same_file(i, output));
    let part = || {
        files.iter().any(|f| crate::io_rules::same_file(f, output))
            && RunFile::open_any(output).is_ok_and(|r| r.part().is_some())
    };
    if named || part() {
        return Err(Error::Hdf5 {
            path: output.to_path_buf(),
            reason: "is one of the shard files to merge: the merged file needs a name of its own (e.g. \
                     DIR/merged.h5); nothing was written"
                .into(),
        });
    }
    Ok(())
}
