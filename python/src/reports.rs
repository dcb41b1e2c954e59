//! `stochvib.replay`, `stochvib.workday` and `stochvib.inspect`: the reports of `stochvib replay`,
//! `stochvib workday` and `stochvib inspect`, computed by the library functions those commands call. Each
//! returns `(json, text)`: the command's `--json` text (byte for byte) and its text report; the Python side
//! (`stochvib/files.py`) wraps them in typed results.

use crate::errors::{detached, invalid_input};
use crate::names::catalogue;
use crate::quantity;
use crate::scenario::PyScenario;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use stochvib::road::Start;
use stochvib::store::RunFile;
use stochvib::study::replay::{replay_scenario, ScenarioReplayOptions};

/// `(json, text)` of a report, as the command-line tool prints it with and without `--json`.
fn printed<T: serde::Serialize + std::fmt::Display>(py: Python<'_>, r: &T) -> PyResult<(String, String)> {
    let json = serde_json::to_string_pretty(r).map_err(|e| invalid_input(py, format!("serialising a report: {e}")))?;
    Ok((json + "\n", r.to_string()))
}

/// The scenario of `scenario`: a `Scenario` (its stochastic scenario) or a scenario file path.
fn scenario_of(
    py: Python<'_>,
    scenario: &Bound<'_, PyAny>,
    spectra_dir: Option<PathBuf>,
) -> PyResult<stochvib::scenario::Scenario> {
    if let Ok(sc) = scenario.cast::<PyScenario>() {
        return Ok(sc.get().stochastic(py)?.clone());
    }
    let path: PathBuf = scenario
        .extract()
        .map_err(|_| invalid_input(py, "`scenario`: expected a Scenario or a scenario file path"))?;
    let cat = catalogue(spectra_dir);
    detached(py, || Ok(stochvib::scenario::load_scenario(&path, cat.dir())?))
}

/// Replays the road profile ``profile`` (CSV) through the model of ``scenario`` (``stochvib replay
/// SCENARIO PROFILE``): ``(json, text)`` of the report. ``speed`` (m/s or a unit string; default the
/// scenario's), ``skip`` (m or a unit string; default the settling length), ``zero_start``, ``track``,
/// ``detrend`` ("linear" or "mean"), ``history`` (the CSV of every output's history, ``-o``) with
/// ``overwrite``.
#[pyfunction]
#[pyo3(signature = (scenario, profile, *, speed=None, skip=None, zero_start=false, track=None, detrend="linear", history=None, overwrite=false, spectra_dir=None))]
#[allow(clippy::too_many_arguments)]
pub fn replay<'py>(
    py: Python<'py>,
    scenario: &Bound<'py, PyAny>,
    profile: PathBuf,
    speed: Option<&Bound<'py, PyAny>>,
    skip: Option<&Bound<'py, PyAny>>,
    zero_start: bool,
    track: Option<String>,
    detrend: &str,
    history: Option<PathBuf>,
    overwrite: bool,
    spectra_dir: Option<PathBuf>,
) -> PyResult<(String, String)> {
    let detrend = crate::names::detrend(py, detrend)?;
    let opts = ScenarioReplayOptions {
        speed_m_s: quantity::optional(py, speed, "speed", "m/s")?,
        skip_m: quantity::optional(py, skip, "skip", "m")?,
        start: if zero_start { Start::Zero } else { Start::Static },
        track,
        detrend,
    };
    let sc = scenario_of(py, scenario, spectra_dir)?;
    let r = detached(py, || {
        let mut inputs = sc.source_files();
        inputs.push(profile.clone());
        let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
        if let Some(out) = &history {
            // the output rule before the work, as the command-line tool
            stochvib::io_rules::check_output(out, &stochvib::road::replay::HISTORY_CSV, &inputs, overwrite)?;
        }
        // the library names the flag the command-line tool takes; here the argument is `speed`
        let r = replay_scenario(&sc, &profile, &opts).map_err(|e| e.renamed("--speed", "speed"))?;
        if let Some(out) = &history {
            r.replay.write_csv_from(out, overwrite, &inputs)?;
        }
        Ok(r)
    })?;
    printed(py, &r)
}

/// The daily exposure of the working day in the workday file ``path`` (``stochvib workday FILE``):
/// ``(json, text, markdown)`` of the report.
#[pyfunction]
#[pyo3(signature = (path, *, spectra_dir=None))]
pub fn workday(py: Python<'_>, path: PathBuf, spectra_dir: Option<PathBuf>) -> PyResult<(String, String, String)> {
    use stochvib::report::table::ToMarkdown;
    let cat = catalogue(spectra_dir);
    let r = detached(py, || {
        let day = stochvib::scenario::workday_file::load_workday(&path)?;
        Ok(stochvib::report::WorkdayReport(
            stochvib::study::workday::workday_exposure(&day, cat.dir())?,
        ))
    })?;
    let (json, text) = printed(py, &r)?;
    Ok((json, text, r.markdown()))
}

/// The summary of the Monte Carlo run file ``path`` (``stochvib inspect FILE``): ``(json, text,
/// markdown)``, after the checks the command makes first (every checksum). An unfinished run (``.tmp``)
/// raises as ``stochvib inspect --json`` does.
#[pyfunction]
pub fn inspect(py: Python<'_>, path: PathBuf) -> PyResult<(String, String, String)> {
    let (info, text, markdown) = detached(py, || {
        let run = RunFile::open(&path)?;
        // the checks of the command's child process (`check-run --full`), in its order: the same first error
        run.statistics()?;
        run.psd()?;
        run.verify()?;
        Ok((
            run.info()?,
            stochvib::report::summarize(&path)?,
            stochvib::report::inspect_markdown(&path)?,
        ))
    })?;
    let json =
        serde_json::to_string_pretty(&info).map_err(|e| invalid_input(py, format!("serialising a report: {e}")))?;
    Ok((json + "\n", text, markdown))
}
