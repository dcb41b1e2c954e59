//! The shard contract of a cluster run: which part of the realizations one process computes
//! (`stochvib simulate … --shard I --of N -o DIR/`), where it writes it, and what a rerun does.
//!
//! * Part I of N holds whole internal shards: internal shard b (of B = ⌈R/shard_size⌉) belongs to part
//!   ⌊b·N/B⌋ ([`Part`]), so N ≤ B. This is the "documented equivalent" of assigning realization i to part
//!   ⌊i·N/R⌋: it keeps the per-shard sums of a single-process run with the same `shard_size`, so that the
//!   merge is bit-identical to that run.
//! * The part writes `DIR/shard-<I>-of-<N>.h5` ([`Part::file_name`]), a complete run file of format 3
//!   written under a temporary name and renamed when complete, like every run file.
//! * A rerun of a part resumes its `.tmp`; a rerun of a finished part with the same run is a no-op (the
//!   run itself checks it, [`crate::simulate::run()`]); a finished file of another run under that name is
//!   never replaced (unless `--overwrite`).
//! * `--shard auto` reads I from the scheduler ([`resolve_part`]).

use crate::error::{Error, Result};
use crate::store::Part;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The part a process computes and where its index came from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ShardChoice {
    /// The part.
    pub part: Part,
    /// Where I and N came from (`--shard 3 --of 16`, `SLURM_ARRAY_TASK_ID=3, --of 16`, …).
    pub source: String,
    /// Warnings (e.g. an array smaller than N: the other indices must be submitted too).
    pub notes: Vec<String>,
}

/// Resolves `--shard SPEC --of N`: SPEC is an index I or `auto`.
///
/// With `auto`, I is `SLURM_ARRAY_TASK_ID` (a SLURM job array), else `JOB_COMPLETION_INDEX` (a Kubernetes
/// Indexed Job). N is `--of` when given (always give it: a resubmitted index `sbatch --array=7` runs in an
/// array of one task). Without `--of`, under SLURM only: N = `SLURM_ARRAY_TASK_COUNT` when the array is
/// `0..N-1` (`SLURM_ARRAY_TASK_MIN` = 0 and `SLURM_ARRAY_TASK_MAX` = N − 1) with N ≥ 2 (N = MAX + 1 when
/// `SLURM_ARRAY_TASK_COUNT` is not set); any other array
/// (a resubmitted subset, a stepped range, one task) is refused. `env(name)` reads the environment (a
/// parameter, so that tests need not change the process's environment).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `shard` or `of`: `auto` without a scheduler variable, a variable that
/// is not a non-negative integer, an N that cannot be inferred, an index outside [0, N), N = 0, an index
/// without `--of`.
///
/// # Examples
/// ```
/// use stochvib::study::resolve_part;
/// let env = |k: &str| match k {
///     "SLURM_ARRAY_TASK_ID" => Some("2".to_string()),
///     "SLURM_ARRAY_TASK_MIN" => Some("0".to_string()),
///     "SLURM_ARRAY_TASK_MAX" => Some("3".to_string()),
///     "SLURM_ARRAY_TASK_COUNT" => Some("4".to_string()),
///     _ => None,
/// };
/// let c = resolve_part("auto", None, &env).unwrap();
/// assert_eq!((c.part.index, c.part.count), (2, 4));
/// assert!(resolve_part("auto", None, &|_: &str| None).is_err());
/// assert_eq!(resolve_part("1", Some(3), &|_: &str| None).unwrap().part.index, 1);
/// ```
pub fn resolve_part(spec: &str, of: Option<usize>, env: &dyn Fn(&str) -> Option<String>) -> Result<ShardChoice> {
    let spec = spec.trim();
    if spec != "auto" {
        let index =
            int("--shard", spec).map_err(|_| Error::invalid("shard", spec, "expected an index 0, 1, … or `auto`"))?;
        let count = of.ok_or_else(|| {
            Error::invalid(
                "of",
                "<missing>",
                format!("--shard {index} needs --of N, the number of shards of the run"),
            )
        })?;
        return Ok(ShardChoice {
            part: Part::new(index, count)?,
            source: format!("--shard {index} --of {count}"),
            notes: Vec::new(),
        });
    }
    if let Some(id) = env("SLURM_ARRAY_TASK_ID") {
        return slurm_part(&id, of, env);
    }
    if let Some(id) = env("JOB_COMPLETION_INDEX") {
        let index = int("JOB_COMPLETION_INDEX", &id)?;
        let n = of.ok_or_else(|| {
            Error::invalid(
                "of",
                "<missing>",
                "--shard auto in a Kubernetes Indexed Job (JOB_COMPLETION_INDEX) needs --of N (= the Job's \
                 completions): Kubernetes does not tell a pod the number of completions",
            )
        })?;
        return Ok(ShardChoice {
            part: Part::new(index, n)?,
            source: format!("JOB_COMPLETION_INDEX={index}, --of {n}"),
            notes: Vec::new(),
        });
    }
    Err(Error::invalid(
        "shard",
        "auto",
        "no scheduler index in the environment: neither SLURM_ARRAY_TASK_ID (a SLURM job array, sbatch \
         --array=0-N-1) nor JOB_COMPLETION_INDEX (a Kubernetes Indexed Job) is set; outside a scheduler give \
         the index: --shard I --of N",
    ))
}

/// The value `text` of the variable or flag `name` as a non-negative integer.
fn int(name: &str, text: &str) -> Result<usize> {
    text.trim()
        .parse::<usize>()
        .map_err(|_| Error::invalid("shard", format!("{name}={text}"), "expected a non-negative integer"))
}

/// `--shard auto` in a SLURM job array: the index `id` (`SLURM_ARRAY_TASK_ID`), N from `of` or from an
/// array 0..N-1 (see [`resolve_part`]).
fn slurm_part(id: &str, of: Option<usize>, env: &dyn Fn(&str) -> Option<String>) -> Result<ShardChoice> {
    let mut notes = Vec::new();
    let index = int("SLURM_ARRAY_TASK_ID", id)?;
    let read = |k: &str| env(k).map(|v| int(k, &v)).transpose();
    let (min, max, count) = (
        read("SLURM_ARRAY_TASK_MIN")?,
        read("SLURM_ARRAY_TASK_MAX")?,
        read("SLURM_ARRAY_TASK_COUNT")?,
    );
    // an array 0..N-1 says N: SLURM_ARRAY_TASK_COUNT, or MAX + 1 where COUNT is not set (older SLURM)
    let whole_array = matches!((min, max, count), (Some(0), Some(mx), c) if mx >= 1 && c.is_none_or(|c| c == mx + 1));
    let count_name = if count.is_some() {
        "SLURM_ARRAY_TASK_COUNT"
    } else {
        "SLURM_ARRAY_TASK_MAX+1"
    };
    let count = count.or(max.map(|mx| mx + 1));
    if let Some(why) = one_based(min, max, of) {
        if of.is_some_and(|n| index >= n) || of.is_none() {
            return Err(Error::invalid("shard", format!("SLURM_ARRAY_TASK_ID={index}"), why));
        }
        notes.push(why);
    }
    let (n, source) = match of {
        Some(n) => {
            if let (true, Some(c)) = (whole_array, count)
                && c < n
            {
                notes.push(format!(
                    "this array has {c} tasks (indices 0..{}) but the run has --of {n} shards: submit \
                         the indices {c}..{} too, or the merge will report them missing",
                    c - 1,
                    n - 1
                ));
            }
            (n, format!("SLURM_ARRAY_TASK_ID={index}, --of {n}"))
        }
        None if whole_array => {
            let c = count.unwrap_or(0);
            (
                c,
                format!("SLURM_ARRAY_TASK_ID={index} of {count_name}={c} (array 0..{})", c - 1),
            )
        }
        None => return Err(unknown_count(min, max, count)),
    };
    Ok(ShardChoice {
        part: Part::new(index, n)?,
        source,
        notes,
    })
}

/// The refusal of `--shard auto` without `--of` in an array that does not say N.
fn unknown_count(min: Option<usize>, max: Option<usize>, count: Option<usize>) -> Error {
    Error::invalid(
        "of",
        "<missing>",
        format!(
            "--shard auto cannot tell the number of shards from this array (SLURM_ARRAY_TASK_MIN={}, \
             SLURM_ARRAY_TASK_MAX={}, SLURM_ARRAY_TASK_COUNT={}): only an array 0..N-1 of N >= 2 tasks \
             says N, and a resubmitted index (sbatch --array=7) runs in an array of its own; give --of N",
            opt(min),
            opt(max),
            opt(count)
        ),
    )
}

/// The warning for a SLURM array numbered from 1 (`--array=1-N`, SLURM_ARRAY_TASK_MIN = 1): shard indices
/// are 0-based, so shard 0 would never run and task N would be out of range. `None` for any other array
/// (a resubmitted subset such as `--array=2,5` starts above 1 and is no mistake).
fn one_based(min: Option<usize>, max: Option<usize>, of: Option<usize>) -> Option<String> {
    let (Some(1), Some(mx)) = (min, max) else { return None };
    if of.is_some_and(|n| n != mx) {
        return None;
    }
    Some(format!(
        "this SLURM array is numbered from 1 (SLURM_ARRAY_TASK_MIN=1, SLURM_ARRAY_TASK_MAX={mx}) but shard indices \
         are 0-based: with --array=1-{mx} shard 0 is never computed and task {mx} is out of range; submit the \
         array as --array=0-{} (the merge names any shard that is missing)",
        mx - 1
    ))
}

fn opt(v: Option<usize>) -> String {
    v.map_or("unset".to_string(), |x| x.to_string())
}

/// The file of part `part` in the run directory `dir`: `dir/shard-<I>-of-<N>.h5`.
///
/// # Examples
/// ```
/// use stochvib::{study::part_path, store::Part};
/// let p = part_path(std::path::Path::new("runs/a"), Part::new(2, 4).unwrap());
/// assert_eq!(p, std::path::Path::new("runs/a/shard-2-of-4.h5"));
/// ```
pub fn part_path(dir: &Path, part: Part) -> PathBuf {
    dir.join(part.file_name())
}
