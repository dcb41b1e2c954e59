//! `stochvib.merge`, `merge_transient` and `merge_sweep`: the part files of a cluster run joined as
//! `stochvib merge OUT INPUTS…` joins them, one function per kind of run (the command-line tool tells the
//! kinds apart by the files; here each kind returns its own result type).

use crate::convert::to_python;
use crate::errors::{detached, invalid_input, lib};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use stochvib::study::merge_kind::{merge_kind, MergeKind};
use stochvib::study::{merge_runs, MergeOptions};

/// The Python function that joins files of `kind`.
fn function_of(kind: MergeKind) -> &'static str {
    match kind {
        MergeKind::Sweep => "merge_sweep",
        MergeKind::Transient => "merge_transient",
        MergeKind::Run => "merge",
    }
}

/// Refuses inputs of another kind than `want` (mixed kinds, the merged file among its parts, parts given to
/// the function of another kind), naming the function that joins what they are. Inputs that hold no parts
/// of a known kind go on to the merge, which says what is wrong with them.
fn require_kind(py: Python<'_>, output: &Path, inputs: &[PathBuf], want: MergeKind) -> PyResult<()> {
    let kind = lib(py, merge_kind(output, inputs))?;
    let stationary_parts = || -> PyResult<bool> {
        let (runs, _) = lib(py, stochvib::store::find_run_files(inputs, &[output]))?;
        Ok(runs
            .iter()
            .any(|r| r.extension().is_some_and(|e| e == "h5" || e == "hdf5")))
    };
    if kind == want || (kind == MergeKind::Run && (want == MergeKind::Sweep || !stationary_parts()?)) {
        return Ok(());
    }
    let what = match kind {
        MergeKind::Sweep => "shard files of a parameter study (sweep-shard-*.json)",
        MergeKind::Transient => "part files of a transient run",
        MergeKind::Run => "part files of a stationary Monte Carlo run",
    };
    Err(invalid_input(
        py,
        format!(
            "`inputs`: these are {what}: stochvib.{}(path, inputs) joins them",
            function_of(kind)
        ),
    ))
}

/// Joins the part files of a sharded run (``stochvib merge OUT INPUTS…``; ``inputs`` files or directories)
/// into the run file ``path``: ``(data, text)`` of the merge summary. ``transient``: the parts of a transient
/// run (``stochvib.merge_transient``), else of a stationary one (``stochvib.merge``).
#[pyfunction]
#[pyo3(signature = (path, inputs, *, copy=false, overwrite=false, confidence=None, transient=false))]
pub fn merge<'py>(
    py: Python<'py>,
    path: PathBuf,
    inputs: Vec<PathBuf>,
    copy: bool,
    overwrite: bool,
    confidence: Option<f64>,
    transient: bool,
) -> PyResult<(Bound<'py, PyAny>, String)> {
    let kind = if transient {
        MergeKind::Transient
    } else {
        MergeKind::Run
    };
    require_kind(py, &path, &inputs, kind)?;
    let opts = MergeOptions {
        copy,
        overwrite,
        confidence,
    };
    if transient {
        let s = detached(py, || {
            Ok(stochvib::study::merge_transient(&path, &inputs, &opts, &|_, _| {})?)
        })?;
        let text = format!(
            "merged {} realizations of a transient run into {}",
            s.n_realizations,
            s.path.display()
        );
        return Ok((to_python(py, &s)?, text));
    }
    let s = detached(py, || Ok(merge_runs(&path, &inputs, &opts, &|_, _| {})?))?;
    Ok((to_python(py, &s)?, s.to_string()))
}

/// Joins the shard files of a parameter study (``stochvib merge TABLE DIR/`` of ``stochvib sweep --shard``
/// parts) into the table ``path`` (CSV, JSON or HDF5 from its extension): the table's data as
/// ``stochvib sweep --json`` prints it.
#[pyfunction]
#[pyo3(signature = (path, inputs, *, overwrite=false))]
pub fn merge_sweep<'py>(
    py: Python<'py>,
    path: PathBuf,
    inputs: Vec<PathBuf>,
    overwrite: bool,
) -> PyResult<Bound<'py, PyAny>> {
    require_kind(py, &path, &inputs, MergeKind::Sweep)?;
    let json = detached(py, || {
        Ok(stochvib::study::merge_sweep(&path, &inputs, overwrite)?.to_json()?)
    })?;
    let v: serde_json::Value = serde_json::from_str(&json).map_err(|e| invalid_input(py, e.to_string()))?;
    to_python(py, &v)
}
