//! `stochvib.Scenario`: a scenario file, or a system with its random input built in Python; its analysis
//! (the `stochvib analyze` report) and its Monte Carlo runs (`stochvib simulate`).

use crate::analysis;
use crate::convert::to_python;
use crate::errors::{call, detached, invalid_input, lib};
use crate::interrupt::run_interruptible;
use crate::names::catalogue;
use crate::nonlinear_run;
use crate::quantity;
use crate::spectrum::PySpectrum;
use crate::system::PySystem;
use crate::two_tracks::{self, TwoTrackArgs};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};
use pyo3::IntoPyObjectExt;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use stochvib::models::InputLayout;
use stochvib::quad_oscillatory::OscillatoryOptions;
use stochvib::report::{deterministic_report, reference_report, TablesReport};
use stochvib::response::Excitation;
use stochvib::scenario::{load_document, AnalysisOptions, Document, Scenario, ScenarioInput};
use stochvib::simulate::{suggest_step, RunOptions};
use stochvib::spectrum::{AtSpeed, Domain, Spectrum};
use stochvib::store::Compression;
use stochvib::study::{analysis_report, deterministic_tables, AnalysisReport};
use stochvib::Error;

/// A scenario: a model, its random input and what to report — read from a scenario file
/// (:meth:`load`) or built in Python (:meth:`from_system`). A file of ``data/`` may also hold a deterministic
/// model or a reference table of the sources; :meth:`analyze` then returns their tables.
#[pyclass(name = "Scenario", module = "stochvib", frozen)]
pub struct PyScenario {
    pub doc: Document,
}

impl PyScenario {
    /// The stochastic scenario, or an error saying what the document is.
    pub fn stochastic(&self, py: Python<'_>) -> PyResult<&Scenario> {
        match &self.doc {
            Document::Stochastic(sc) => Ok(sc),
            Document::Deterministic(d) => Err(crate::errors::not_applicable(
                py,
                format!(
                    "{}: `{}` is a deterministic model without a random input: there is nothing to simulate \
                     or to analyse statistically (tables() returns its result tables)",
                    d.path.display(),
                    d.kind
                ),
            )),
            Document::Reference(r) => Err(crate::errors::not_applicable(
                py,
                format!(
                    "{}: a reference table of the sources, not a scenario (tables() returns it)",
                    r.path.display()
                ),
            )),
        }
    }
}

/// No stationary response without asymptotic stability: `DivergentError` with the command-line tool's
/// diagnosis and hint (what to check), as `stochvib analyze` gives it for the same model in a file.
fn require_stable(py: Python<'_>, sys: &PySystem) -> PyResult<()> {
    let Some(ss) = sys.system.state_space() else {
        return Ok(());
    };
    let Err(e) = ss.require_stable() else {
        return Ok(());
    };
    let reason = match e {
        Error::InvalidParameter { value, reason, .. } => format!("{reason} ({value})"),
        other => other.to_string(),
    };
    let hint = if sys.kind == "transfer-function" {
        "D(s) has a root with Re s ≥ 0 (a pole in the right half-plane or on the axis)"
    } else {
        "check the stiffnesses, dampings and masses (or poles) of the model"
    };
    let quantity = format!("the stationary response of the {}", sys.description);
    let e = Error::Divergent {
        quantity: quantity.clone(),
        reason: format!("{reason}: {hint}"),
    };
    Err(crate::errors::raise(
        py,
        "DivergentError",
        &e.to_string(),
        &[
            ("quantity", quantity.into_py_any(py)?),
            ("reason", reason.into_py_any(py)?),
            ("hint", hint.into_py_any(py)?),
        ],
    ))
}

/// The temporal process a spectrum gives the system: itself, or a spatial one at `speed`.
fn temporal(py: Python<'_>, s: &Arc<dyn Spectrum>, speed: Option<f64>) -> PyResult<Arc<dyn Spectrum>> {
    match (s.domain(), speed) {
        (Domain::Temporal, _) => Ok(s.clone()),
        (Domain::Spatial, Some(v)) => Ok(Arc::new(call(py, || AtSpeed::new(s.clone(), v))?)),
        (Domain::Spatial, None) => lib(
            py,
            Err(Error::invalid(
                "speed",
                "<missing>",
                "the input spectrum is spatial (a road): give the speed to turn it into time",
            )),
        ),
    }
}

/// The excitation of `sys` by `inputs` (one spectrum, or one per input), following the rules of scenario
/// files for catalogue models (their input layout) and `positions` (m) for a track under several inputs.
fn excitation(
    py: Python<'_>,
    sys: &PySystem,
    inputs: &[Arc<dyn Spectrum>],
    speed: Option<f64>,
    positions: Option<Vec<f64>>,
    means: Vec<f64>,
) -> PyResult<Excitation> {
    if inputs.len() > 1 {
        let spectra = inputs
            .iter()
            .map(|s| temporal(py, s, speed))
            .collect::<PyResult<Vec<_>>>()?;
        let means = if means.len() == 1 {
            vec![means[0]; spectra.len()]
        } else {
            means
        };
        return call(py, || Excitation::independent(spectra, means));
    }
    if means.len() != 1 {
        return Err(invalid_input(py, "`mean`: one process needs one mean"));
    }
    let (s, mean) = (temporal(py, &inputs[0], speed)?, means[0]);
    let track = |positions: &[f64], gains: Vec<f64>| -> PyResult<Excitation> {
        let delays = if positions.iter().all(|p| *p == 0.0) {
            vec![0.0; positions.len()]
        } else {
            let Some(v) = speed else {
                return lib(
                    py,
                    Err(Error::invalid(
                        "speed",
                        "<missing>",
                        "the wheels are at different positions: the delays need a speed",
                    )),
                );
            };
            positions.iter().map(|p| p / v).collect()
        };
        call(py, || Excitation::track(s.clone(), delays, gains, mean))
    };
    match (positions, &sys.layout) {
        (Some(p), Some(InputLayout::Track { gains, .. })) if gains.len() == p.len() => track(&p, gains.clone()),
        (Some(p), _) => {
            let n = p.len();
            track(&p, vec![1.0; n])
        }
        (None, Some(InputLayout::Track { positions, gains })) => track(positions, gains.clone()),
        (None, Some(InputLayout::Single)) => call(py, || Excitation::single(s, mean)),
        (None, Some(InputLayout::TwoTracks { .. })) => Err(invalid_input(
            py,
            "the model stands on two tracks: give coherence= (the coherence model between the tracks) and \
             speed=",
        )),
        (None, None) if sys.system.n_inputs() == 1 => call(py, || Excitation::single(s, mean)),
        (None, None) => Err(invalid_input(
            py,
            format!(
                "the system has {} inputs: give one spectrum per input (independent processes) or \
                 `positions=` (one track felt by every input, positions in m behind the first)",
                sys.system.n_inputs()
            ),
        )),
    }
}

/// Spectra of the `input` argument: one Spectrum, a catalogue name or spectrum-file path (resolved as
/// `Spectrum.load` does), or a sequence of Spectrum objects.
fn input_spectra(py: Python<'_>, input: &Bound<'_, PyAny>) -> PyResult<Vec<Py<PySpectrum>>> {
    if let Ok(s) = input.cast::<PySpectrum>() {
        return Ok(vec![s.clone().unbind()]);
    }
    if input.is_instance_of::<pyo3::types::PyString>() || input.hasattr("__fspath__")? {
        let path: PathBuf = input.extract()?;
        let reference = path.to_string_lossy().into_owned();
        let f = call(py, || catalogue(None).resolve(&reference, None))?;
        return Ok(vec![Py::new(py, PySpectrum::from_file(f))?]);
    }
    let mut v = Vec::new();
    if let Ok(it) = input.try_iter() {
        for x in it {
            let x = x?;
            let s = x.cast::<PySpectrum>().map_err(|_| {
                invalid_input(
                    py,
                    format!(
                        "`input`: expected Spectrum objects, got {}",
                        x.repr().map(|r| r.to_string()).unwrap_or_default()
                    ),
                )
            })?;
            v.push(s.clone().unbind());
        }
    }
    if v.is_empty() {
        return Err(invalid_input(
            py,
            "`input`: expected a stochvib.Spectrum or a non-empty list of them (one per system input)",
        ));
    }
    Ok(v)
}

/// A report of the library.
enum AnyReport {
    Analysis(Box<AnalysisReport>),
    Tables(TablesReport),
}

/// The `stochvib analyze` report of a document (computed without the GIL): (what, dict, text).
fn document_report<'py>(py: Python<'py>, doc: &Document) -> PyResult<(String, Bound<'py, PyAny>, String)> {
    let r = detached(py, || {
        Ok(match doc {
            Document::Stochastic(sc) => AnyReport::Analysis(Box::new(analysis_report(sc)?)),
            Document::Deterministic(d) => AnyReport::Tables(deterministic_report(d, deterministic_tables(d)?)),
            Document::Reference(t) => AnyReport::Tables(reference_report(t)),
        })
    })?;
    match r {
        AnyReport::Analysis(r) => Ok(("analysis".into(), to_python(py, &r)?, r.to_string())),
        AnyReport::Tables(r) => Ok(("tables".into(), to_python(py, &r)?, r.to_string())),
    }
}

/// Calls `f` with the progress callable of `stochvib._progress.make(progress)` and calls its `close`
/// afterwards, whatever happens; `progress` None means the default, True.
pub(crate) fn with_progress<T>(
    py: Python<'_>,
    progress: Option<Py<PyAny>>,
    f: impl FnOnce(Option<Py<PyAny>>) -> PyResult<T>,
) -> PyResult<T> {
    let progress = match progress {
        Some(p) => p,
        None => true.into_py_any(py)?,
    };
    let (call, close): (Py<PyAny>, Py<PyAny>) = py
        .import("stochvib._progress")?
        .getattr("make")?
        .call1((progress,))?
        .extract()?;
    let call = (!call.is_none(py)).then_some(call);
    let r = f(call);
    if !close.is_none(py) {
        let closed = close.call0(py);
        if r.is_ok() {
            closed?;
        }
    }
    r
}

/// The file of part `shard` = (I, N) of a run in the directory `path` (created), or `path` itself.
fn shard_path(
    py: Python<'_>,
    path: PathBuf,
    shard: Option<(usize, usize)>,
) -> PyResult<(PathBuf, Option<stochvib::store::Part>)> {
    let Some((index, count)) = shard else {
        return Ok((path, None));
    };
    let part = call(py, || stochvib::store::Part::new(index, count))?;
    lib(
        py,
        std::fs::create_dir_all(&path).map_err(|source| Error::Io {
            path: path.clone(),
            source,
        }),
    )?;
    Ok((stochvib::study::part_path(&path, part), Some(part)))
}

/// The study of `sc` over `params` (`KEY=VALUES` texts), a grid or, with `zip`, the k-th values together.
fn build_sweep<'a>(sc: &'a Scenario, params: &[String], zip: bool) -> stochvib::Result<stochvib::study::Sweep<'a>> {
    use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec};
    let params = params
        .iter()
        .map(|p| SweepParam::parse(p))
        .collect::<stochvib::Result<Vec<_>>>()?;
    let mode = if zip { SweepMode::Zip } else { SweepMode::Grid };
    Sweep::new(sc, SweepSpec::new(params, mode)?)
}

/// The part of a sweep in shards: `shard` = (I, N) with `path` the directory of the shard files.
fn sweep_part(
    py: Python<'_>,
    shard: Option<(usize, usize)>,
    path: Option<&Path>,
) -> PyResult<Option<stochvib::store::Part>> {
    match (shard, path) {
        (None, None) => Ok(None),
        (None, Some(_)) => Err(invalid_input(
            py,
            "`path`: names the directory of the shard files of sweep(..., shard=(I, N)); without shard \
             the study is returned, not written",
        )),
        (Some(_), None) => Err(invalid_input(
            py,
            "`shard`: needs path= (the directory of the shard files)",
        )),
        (Some((i, n)), Some(_)) => Ok(Some(call(py, || stochvib::store::Part::new(i, n))?)),
    }
}

/// `KEY=VALUES` texts (the CLI's `--param`) of a dict key → a range string or a sequence of values.
fn sweep_params(params: &Bound<'_, PyDict>) -> PyResult<Vec<String>> {
    let text = |v: &Bound<'_, PyAny>| -> PyResult<String> { Ok(v.str()?.to_cow()?.into_owned()) };
    params
        .iter()
        .map(|(k, v)| {
            let values = if v.is_instance_of::<pyo3::types::PyString>() {
                text(&v)?
            } else {
                v.try_iter()?
                    .map(|x| text(&x?))
                    .collect::<PyResult<Vec<_>>>()?
                    .join(",")
            };
            Ok(format!("{}={values}", text(&k)?))
        })
        .collect()
}

/// After a run that stopped early in this process, which goes on living: removes `<path>.tmp.owner` if it
/// names this process. The library writes that file while a run is being written (another process seeing a
/// live pid there refuses to touch the `.tmp`) and leaves it when its writer stops early; a CLI process that
/// stops exits, leaving a dead pid that is ignored, but the Python interpreter stays alive, so without this
/// the interrupted run could only be resumed from this same process.
fn release_claim(path: &Path) {
    let mut name = stochvib::store::tmp_path(path).into_os_string();
    name.push(stochvib::store::layout::OWNER_SUFFIX);
    let owner = PathBuf::from(name);
    if std::fs::read_to_string(&owner).is_ok_and(|s| s.trim() == std::process::id().to_string()) {
        let _ = std::fs::remove_file(owner);
    }
}

/// The Monte Carlo batch of every point of a sweep (`stochvib sweep --monte-carlo N`): Δt and duration as
/// given, the missing ones suggested from the scenario for `n` realizations, the batch's time checked.
fn sweep_monte_carlo(
    sc: &Scenario,
    sweep: &stochvib::study::Sweep,
    n: usize,
    (dt, duration): (Option<f64>, Option<f64>),
    (seed, shard_size, confidence): (u64, usize, f64),
) -> stochvib::Result<stochvib::study::SweepMonteCarlo> {
    let (dt_s, duration_s) = match (dt, duration) {
        (Some(dt), Some(d)) => (dt, d),
        _ => {
            let s = sc.suggest_step(n)?;
            (dt.unwrap_or(s.dt_s), duration.unwrap_or(s.duration_s))
        }
    };
    let m = stochvib::study::SweepMonteCarlo {
        realizations: n,
        duration_s,
        dt_s,
        seed,
        shard_size,
        confidence,
    };
    let hours = stochvib::simulate::resources::DEFAULT_MAX_HOURS;
    stochvib::study::check_monte_carlo_time(sweep, &m, hours)?;
    Ok(m)
}

/// Time step and duration: as given, the missing ones suggested from the system (with the reason).
pub(crate) fn step(sc: &Scenario, dt: Option<f64>, duration: Option<f64>) -> stochvib::Result<(f64, f64, String)> {
    if let (Some(dt), Some(d)) = (dt, duration) {
        return Ok((dt, d, "given".into()));
    }
    let s = suggest_step(&sc.run_input())?;
    Ok((
        dt.unwrap_or(s.dt_s),
        duration.unwrap_or(s.duration_s),
        format!("suggested: {}", s.reason),
    ))
}

/// The band `(ω₁, ω₂)` of a band-limited σ: two quantities in rad/s ("1 Hz" is 2π rad/s).
fn band(py: Python<'_>, band: Option<&Bound<'_, PyAny>>) -> PyResult<Option<(f64, f64)>> {
    let Some(b) = band.filter(|b| !b.is_none()) else {
        return Ok(None);
    };
    match quantity::sequence(py, b, "band_rad_s", "rad/s")?[..] {
        [low, high] => Ok(Some((low, high))),
        _ => Err(invalid_input(
            py,
            "`band_rad_s`: expected (low, high), two quantities in rad/s",
        )),
    }
}

/// An optional quantity argument as given in Python (a number or a unit string).
type QuantityArg<'a, 'py> = Option<&'a Bound<'py, PyAny>>;

/// The Monte Carlo batch of `monte_carlo` realizations, its quantities (Δt, duration, burn-in: s or unit
/// strings) read.
fn batch<'py>(
    py: Python<'py>,
    monte_carlo: Option<usize>,
    seed: u64,
    (dt, duration, burn_in): (QuantityArg<'_, 'py>, QuantityArg<'_, 'py>, QuantityArg<'_, 'py>),
) -> PyResult<Option<analysis::Batch>> {
    let dt = quantity::optional(py, dt, "dt", "s")?;
    let duration = quantity::optional(py, duration, "duration", "s")?;
    let burn_in = quantity::optional(py, burn_in, "burn_in", "s")?;
    Ok(monte_carlo.map(|n| (n, seed, dt, duration, burn_in)))
}

/// `Scenario.simulate` (`nonlinear` false) and `Scenario.simulate_nonlinear` (true): the run of one kind of
/// model into `path`, the other kind refused by name.
#[allow(clippy::too_many_arguments)]
fn simulate_run<'py>(
    py: Python<'py>,
    sc: &Scenario,
    nonlinear: bool,
    realizations: usize,
    path: PathBuf,
    dt: Option<&Bound<'py, PyAny>>,
    duration: Option<&Bound<'py, PyAny>>,
    seed: u64,
    shard_size: usize,
    store_raw: bool,
    compression: &str,
    route: &str,
    confidence: f64,
    overwrite: bool,
    progress: Option<Py<PyAny>>,
    shard: Option<(usize, usize)>,
    burn_in: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    analysis::require_kind(py, sc, nonlinear, ("simulate", "simulate_nonlinear"))?;
    let answers = call(py, || sc.nonlinear_answers())?;
    let (path, part) = shard_path(py, path, shard)?;
    let dt = quantity::optional(py, dt, "dt", "s")?;
    let duration = quantity::optional(py, duration, "duration", "s")?;
    let burn_in = quantity::optional(py, burn_in, "burn_in", "s")?;
    let compression: Compression = call(py, || compression.parse())?;
    let route = call(py, || route.parse())?;
    if overwrite && path.exists() {
        lib(
            py,
            std::fs::remove_file(&path).map_err(|source| Error::Io {
                path: path.clone(),
                source,
            }),
        )?;
    }
    let base = RunOptions {
        shard_size,
        store_raw,
        compression,
        route,
        confidence,
        part,
        realizations,
        seed,
        ..RunOptions::default()
    };
    if let Some(answers) = answers {
        let outcome = with_progress(py, progress, |cb| {
            run_interruptible(py, cb, |cb| {
                let (opts, how) = nonlinear_run::options(sc, &answers, base, (dt, duration, burn_in))?;
                sc.simulate_nonlinear(&answers, &opts, &path, cb).map(|s| (s, how))
            })
        });
        if outcome.is_err() {
            release_claim(&path);
        }
        let (summary, how) = outcome?;
        return py.import("stochvib.results")?.getattr("NonlinearRunResult")?.call1((
            to_python(py, &summary)?,
            summary.to_string(),
            how,
        ));
    }
    let outcome = with_progress(py, progress, |cb| {
        run_interruptible(py, cb, |cb| {
            let (dt, d, how) = step(sc, dt, duration)?;
            let opts = RunOptions {
                duration_s: d,
                dt_s: dt,
                ..base
            };
            sc.simulate(&opts, &path, cb).map(|s| (s, how))
        })
    });
    if outcome.is_err() {
        release_claim(&path);
    }
    let (summary, how) = outcome?;
    py.import("stochvib.results")?
        .getattr("RunResult")?
        .call1((to_python(py, &summary)?, summary.to_string(), how))
}

#[pymethods]
impl PyScenario {
    /// Reads a file of ``data/`` (a scenario, a deterministic model or a reference table). Spectrum names in
    /// ``[input] spectrum`` are looked up in the catalogue directory (see :meth:`Spectrum.load`).
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     The file (TOML).
    /// spectra_dir : str or os.PathLike, keyword-only, optional
    ///     The spectrum catalogue directory.
    ///
    /// Returns
    /// -------
    /// Scenario
    ///     :attr:`what` says "stochastic", "deterministic" or "reference".
    ///
    /// Raises
    /// ------
    /// FileError
    ///     A file that cannot be read or is invalid, naming the file, key, value and reason.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> stochvib.Scenario.load("data/conveyor-idler.toml").what
    /// 'stochastic'
    #[staticmethod]
    #[pyo3(signature = (path, *, spectra_dir=None))]
    fn load(py: Python<'_>, path: PathBuf, spectra_dir: Option<PathBuf>) -> PyResult<Self> {
        let cat = catalogue(spectra_dir);
        let doc = call(py, || load_document(&path, cat.dir()))?;
        Ok(PyScenario { doc })
    }

    /// A scenario of ``system`` driven by ``input`` — one :class:`Spectrum` (one process; a catalogue name
    /// or a spectrum-file path is loaded as :meth:`Spectrum.load` does) or a list with one spectrum per system
    /// input (independent processes).
    ///
    /// * A spatial (road) spectrum needs ``speed`` (m/s): S_t(ω) = S_Ω(ω/v)/v.
    /// * One process felt by several inputs: ``positions`` (m behind the first contact point; delays
    ///   ℓ/v), or the input layout of a catalogue model or scenario file; a single-input system needs neither.
    /// * ``mean``: the mean of the process (its unit), or one per independent process.
    /// * ``outputs``: the output names to report (default all); ``band_rad_s``: (ω₁, ω₂) in rad/s (or unit
    ///   strings: "1 Hz" is 2π rad/s) for
    ///   a band-limited σ; ``duration_s``: the duration for exceedance probabilities and expected peaks
    ///   (default 1 h); ``levels``: dict output name → levels (output's SI unit) for Rice crossing rates.
    ///
    /// A road of two coherent tracks (a scenario file's ``[[input]] road = { spectrum, coherence,
    /// track_width }``): ``input`` the spatial spectrum of each track, ``coherence`` the coherence model
    /// between the tracks (a dict as the file's ``coherence`` table, e.g. ``{"kind": "dodds-robson",
    /// "waviness": 2}``), ``track_width`` (m; default the model's), ``tracks`` the track of each system input
    /// ("left"/"right"; default the model's layout) and ``positions`` (m behind the first contact: the
    /// wheelbase delays ℓ/v; default the model's). A catalogue model on two tracks (``full-vehicle``) needs
    /// only ``coherence`` and ``speed``.
    ///
    /// Parameters
    /// ----------
    /// system : System
    ///     A stable system.
    /// input : Spectrum, str, os.PathLike or list of Spectrum
    ///     As above.
    /// speed : float or str, keyword-only, optional
    ///     m/s or a speed string ("72 km/h").
    /// positions : list of float or str, keyword-only, optional
    ///     m behind the first contact, one per system input.
    /// mean : float or str or list of them, keyword-only, optional
    ///     The process mean(s), in the process's unit; default 0.
    /// outputs : list of str, keyword-only, optional
    /// band_rad_s : (float or str, float or str), keyword-only, optional
    /// duration_s : float or str, keyword-only, default 3600 s
    /// levels : dict of str to list of float or str, keyword-only, optional
    /// title : str, keyword-only, optional
    /// coherence : dict, keyword-only, optional
    /// track_width : float or str, keyword-only, optional
    ///     m.
    /// tracks : list of str or int, keyword-only, optional
    ///
    /// Returns
    /// -------
    /// Scenario
    ///     A stochastic scenario, as a scenario file gives.
    ///
    /// Raises
    /// ------
    /// DivergentError
    ///     An unstable system (no stationary response).
    /// InvalidInputError
    ///     A spatial input without ``speed``, several inputs without ``positions`` or layout, a speed that is
    ///     not > 0, an unknown output, a bad coherence table.
    /// UnitError
    ///     A quantity string of the wrong dimension, naming the argument.
    ///
    /// Examples
    /// --------
    /// ẋ = −2x + u with u of correlation e^{−2|τ|}: σ_x² = (2/π)·∫ dω/(ω² + 4)² = 1/8.
    ///
    /// >>> import stochvib
    /// >>> sys = stochvib.System.state_space([[-2.0]], [[1.0]], [[1.0]], outputs=[("x", "m")])
    /// >>> sc = stochvib.Scenario.from_system(sys, stochvib.Spectrum.exponential(1.0, 2.0))
    /// >>> round(sc.analyze(progress=False)["x"].sigma ** 2, 9)
    /// 0.125
    #[staticmethod]
    #[pyo3(signature = (system, input, *, speed=None, positions=None, mean=None, outputs=None, band_rad_s=None, duration_s=None, levels=None, title=None, coherence=None, track_width=None, tracks=None))]
    #[allow(clippy::too_many_arguments)]
    fn from_system(
        py: Python<'_>,
        system: &Bound<'_, PySystem>,
        input: &Bound<'_, PyAny>,
        speed: Option<&Bound<'_, PyAny>>,
        positions: Option<&Bound<'_, PyAny>>,
        mean: Option<&Bound<'_, PyAny>>,
        outputs: Option<Vec<String>>,
        band_rad_s: Option<&Bound<'_, PyAny>>,
        duration_s: Option<&Bound<'_, PyAny>>,
        levels: Option<&Bound<'_, PyDict>>,
        title: Option<String>,
        coherence: Option<&Bound<'_, PyDict>>,
        track_width: Option<&Bound<'_, PyAny>>,
        tracks: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let sys = system.get();
        require_stable(py, sys)?;
        let speed = quantity::optional(py, speed, "speed", "m/s")?;
        let positions = positions
            .filter(|p| !p.is_none())
            .map(|p| quantity::sequence(py, p, "positions", "m"))
            .transpose()?;
        let duration_s = quantity::optional(py, duration_s, "duration_s", "s")?.unwrap_or(3600.0);
        let band_rad_s = band(py, band_rad_s)?;
        let spectra = input_spectra(py, input)?;
        let arcs: Vec<Arc<dyn Spectrum>> = spectra.iter().map(|s| s.get().spectrum.clone()).collect();
        let means = process_means(py, mean, &spectra)?;
        if let Some(v) = speed {
            if !(v.is_finite() && v > 0.0) {
                return lib(py, Err(Error::invalid("speed", v, "must be finite and > 0")));
            }
        }
        let two = TwoTrackArgs {
            coherence,
            track_width: quantity::optional(py, track_width, "track_width", "m")?,
            tracks: tracks.map(|t| two_tracks::track_indices(py, t)).transpose()?,
        };
        let (exc, coherence) = system_excitation(py, sys, &arcs, (speed, positions, &means), two)?;
        let names: Vec<String> = sys.system.outputs().iter().map(|o| o.name.clone()).collect();
        let index = |n: &str| call(py, || sys.system.output_index(n));
        let outputs = match outputs {
            None => (0..names.len()).collect(),
            Some(v) => v.iter().map(|n| index(n)).collect::<PyResult<Vec<_>>>()?,
        };
        lib(py, check_analysis_args(duration_s, band_rad_s))?;
        let level_list = output_levels(py, levels, sys.system.as_ref())?;
        let first = spectra[0].get();
        let reference = if first.name.is_empty() {
            "inline".to_string()
        } else {
            first.name.clone()
        };
        let title = title.unwrap_or_else(|| format!("{} driven by {}", sys.description, first.spectrum.describe()));
        let text = provenance_text(&title, sys, &arcs, speed, &means, &exc);
        let input = ScenarioInput {
            reference,
            spectrum: first.spectrum.clone(),
            unit: first.unit.clone(),
            origin: first.origin.clone(),
            spectrum_text: first.text.clone(),
            speed,
            mean: means[0],
            name: "input".into(),
            coherence,
            kurtosis: None,
        };
        let sc = Scenario {
            path: PathBuf::from("<python>"),
            text,
            title,
            source: "built in Python".into(),
            kind: sys.kind.clone(),
            model: sys.instance(),
            input: input.clone(),
            inputs: vec![input],
            spectra_dir: catalogue(None).dir().to_path_buf(),
            excitation: exc,
            analysis: AnalysisOptions {
                outputs,
                band: band_rad_s,
                duration: duration_s,
                levels: level_list,
                effort: OscillatoryOptions::default(),
                verdicts: Default::default(),
                bands: None,
                mission: None,
            },
            nonlinear: None,
            transient: None,
        };
        Ok(PyScenario {
            doc: Document::Stochastic(Box::new(sc)),
        })
    }

    /// The ``stochvib analyze`` report of a stochastic scenario of a linear model: an :class:`AnalysisResult`
    /// (σ, 3σ bounds, crossing rates, every variance method with its error estimate, per output). A model with
    /// nonlinear elements raises :class:`InvalidInputError` naming :meth:`analyze_nonlinear`; a deterministic
    /// model or a reference table raises :class:`NotApplicableError` (their tables: :meth:`tables`).
    ///
    /// ``monte_carlo=N`` adds the Monte Carlo column (σ from N realizations with its 95 % interval and
    /// whether it covers the analytic σ; the run file goes to a temporary directory and is removed), with
    /// master ``seed``, time step ``dt`` (s) and realization ``duration`` (s) (suggested from the system
    /// when not given) and a progress bar (``progress``: True, False or a callable(done, total)).
    ///
    /// ``rel_tol``, ``max_subintervals`` and ``max_half_periods`` override the effort of the quadratures
    /// (the scenario's ``[analysis.quadrature]``; the CLI's ``--rel-tol``, ``--max-subintervals``,
    /// ``--max-half-periods``; defaults 1e-10, 2000, 10 000).
    ///
    /// Parameters
    /// ----------
    /// monte_carlo : int, keyword-only, optional
    ///     N realizations for the Monte Carlo column (none by default).
    /// seed : int, keyword-only, default 1
    /// dt, duration : float or str, keyword-only, optional
    ///     s, or time strings.
    /// progress : bool or callable, keyword-only, default True
    ///     True (or None): a bar; False: nothing; a callable(done, total).
    /// rel_tol : float, keyword-only, default 1e-10
    /// max_subintervals : int, keyword-only, default 2000
    /// max_half_periods : int, keyword-only, default 10 000
    ///
    /// Returns
    /// -------
    /// AnalysisResult
    ///     One :class:`OutputResult` per output. An infinite variance or a quadrature that does not converge
    ///     is reported in it, not raised.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     A model with nonlinear elements; a bad option.
    /// NotApplicableError
    ///     A deterministic model or a reference table.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> r = stochvib.Scenario.load("data/conveyor-idler.toml").analyze(progress=False)
    /// >>> r["y"].unit, r["y"].sigma > 0
    /// ('m', True)
    #[pyo3(signature = (*, monte_carlo=None, seed=1, dt=None, duration=None, progress=None, rel_tol=None, max_subintervals=None, max_half_periods=None))]
    #[allow(clippy::too_many_arguments)]
    fn analyze<'py>(
        &self,
        py: Python<'py>,
        monte_carlo: Option<usize>,
        seed: u64,
        dt: Option<&Bound<'py, PyAny>>,
        duration: Option<&Bound<'py, PyAny>>,
        progress: Option<Py<PyAny>>,
        rel_tol: Option<f64>,
        max_subintervals: Option<usize>,
        max_half_periods: Option<usize>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = analysis::tuned(py, self.stochastic(py)?, (rel_tol, max_subintervals, max_half_periods))?;
        let batch = batch(py, monte_carlo, seed, (dt, duration, None))?;
        analysis::linear(py, &sc, batch, progress)
    }

    /// Routes 1 and 3 of a scenario with nonlinear elements (``[[model.nonlinear]]``; ``stochvib analyze`` of
    /// such a file): a :class:`NonlinearResult` (route 1, statistical linearisation, and route 3, the exact
    /// stationary density where it applies). A linear model raises :class:`InvalidInputError` naming
    /// :meth:`analyze`.
    ///
    /// ``monte_carlo=N`` adds route 2 (the time-domain Monte Carlo of the nonlinear equations, as ``stochvib
    /// analyze --monte-carlo N``: ``seed``, Δt ``dt`` and the realization ``duration`` in s suggested for
    /// route 2 when not given, ``burn_in`` in s, default from the slowest decay rate of the Gaussian
    /// equivalent; ``progress`` as for :meth:`analyze`). ``rel_tol``, ``max_subintervals``,
    /// ``max_half_periods`` as for :meth:`analyze`.
    ///
    /// Parameters
    /// ----------
    /// monte_carlo : int, keyword-only, optional
    ///     N realizations of route 2 (none by default).
    /// seed, dt, duration, progress, rel_tol, max_subintervals, max_half_periods
    ///     As for :meth:`analyze` (s for ``dt`` and ``duration``).
    /// burn_in : float or str, keyword-only, optional
    ///     s, or a time string.
    ///
    /// Returns
    /// -------
    /// NonlinearResult
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     A linear model; a bad option.
    /// NotApplicableError
    ///     A deterministic model or a reference table.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> r = stochvib.Scenario.load("data/duffing-white-noise.toml").analyze_nonlinear(progress=False)
    /// >>> r["x"].route1() < r["x"].exact() < 0.01  # a hardening spring: below the linear σ₀ = 1 cm
    /// True
    #[pyo3(signature = (*, monte_carlo=None, seed=1, dt=None, duration=None, progress=None, rel_tol=None, max_subintervals=None, max_half_periods=None, burn_in=None))]
    #[allow(clippy::too_many_arguments)]
    fn analyze_nonlinear<'py>(
        &self,
        py: Python<'py>,
        monte_carlo: Option<usize>,
        seed: u64,
        dt: Option<&Bound<'py, PyAny>>,
        duration: Option<&Bound<'py, PyAny>>,
        progress: Option<Py<PyAny>>,
        rel_tol: Option<f64>,
        max_subintervals: Option<usize>,
        max_half_periods: Option<usize>,
        burn_in: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = analysis::tuned(py, self.stochastic(py)?, (rel_tol, max_subintervals, max_half_periods))?;
        let batch = batch(py, monte_carlo, seed, (dt, duration, burn_in))?;
        analysis::nonlinear(py, &sc, batch, progress)
    }

    /// The exact statistics at every point of a parameter study (``stochvib sweep SCENARIO --param … --json``).
    ///
    /// Parameters
    /// ----------
    /// params : dict
    ///     A scenario key (``"model.c"``, ``"input.speed"``, ``"model.element.0.stiffness"``) → its values: a
    ///     sequence of numbers or strings with units, or a range string ``"A..B:n"`` / ``"A..B:n:log"``.
    /// zip : bool, keyword-only
    ///     The k-th values of every key together instead of the grid of every combination.
    /// monte_carlo : int, keyword-only, optional
    ///     Realizations of a seeded Monte Carlo batch at every point (``stochvib sweep --monte-carlo N``):
    ///     σ with its interval and whether it covers the exact σ (:meth:`SweepResult.monte_carlo`).
    /// seed, dt, duration, shard_size, confidence : keyword-only
    ///     Of the batches: master seed (the same at every point), time step and realization duration (s or
    ///     a unit string; suggested from the scenario when not given), realizations per shard, confidence
    ///     of the intervals.
    /// progress : bool or callable, keyword-only
    ///     With ``monte_carlo`` or ``shard``: a bar on stderr (True), none (False) or a callable(done, total)
    ///     per point.
    /// shard : (int, int), keyword-only, optional
    ///     ``(I, N)``: evaluate only part I of N of the points into the shard file
    ///     ``path/sweep-shard-<I>-of-<N>.json`` (``stochvib sweep --shard I --of N -o DIR``); a rerun whose
    ///     file is already there for the same study does nothing. :func:`stochvib.merge_sweep` joins the parts.
    /// path : path, keyword-only, optional
    ///     With ``shard``: the directory of the shard files (created).
    /// overwrite : bool, keyword-only
    ///     With ``shard``: replace a shard file of another study.
    ///
    /// Returns
    /// -------
    /// SweepResult
    ///     ``statistic(output, name)`` as an array of the study's shape; a failed point is NaN, its reason
    ///     in ``rows``. With ``shard``, only the part's points hold numbers (``points``), and ``path`` is the
    ///     shard file.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown key, a bad value or range, keys of different lengths with ``zip``, fewer than 2
    ///     realizations, a batch that would take longer than 24 h.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    /// >>> r = sc.sweep({"model.c": ["50 kN/m", "100 kN/m"]})
    /// >>> r.statistic("y", "mean").round(12).tolist()  # the static deflection M_F / c = 10 kN / c
    /// [0.2, 0.1]
    #[pyo3(signature = (params, *, zip=false, monte_carlo=None, seed=1, dt=None, duration=None, shard_size=50, confidence=0.95, progress=None, shard=None, path=None, overwrite=false))]
    #[allow(clippy::too_many_arguments)]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        params: &Bound<'py, PyDict>,
        zip: bool,
        monte_carlo: Option<usize>,
        seed: u64,
        dt: Option<&Bound<'py, PyAny>>,
        duration: Option<&Bound<'py, PyAny>>,
        shard_size: usize,
        confidence: f64,
        progress: Option<Py<PyAny>>,
        shard: Option<(usize, usize)>,
        path: Option<PathBuf>,
        overwrite: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = self.stochastic(py)?;
        let part = sweep_part(py, shard, path.as_deref())?;
        let params = sweep_params(params)?;
        let (dt, duration) = (
            quantity::optional(py, dt, "dt", "s")?,
            quantity::optional(py, duration, "duration", "s")?,
        );
        if monte_carlo.is_some_and(|n| n < 2) {
            return Err(invalid_input(
                py,
                "`monte_carlo`: a Monte Carlo batch needs at least 2 realizations (the interval of σ is taken \
                 across realizations)",
            ));
        }
        let compute = |cb: &(dyn Fn(usize, usize) + Sync)| -> stochvib::Result<(String, Option<PathBuf>)> {
            let sweep = build_sweep(sc, &params, zip)?;
            let mc = match monte_carlo {
                None => None,
                Some(n) => Some(sweep_monte_carlo(
                    sc,
                    &sweep,
                    n,
                    (dt, duration),
                    (seed, shard_size, confidence),
                )?),
            };
            let n = sweep.spec().n_points();
            match (part, &path) {
                (Some(part), Some(dir)) => {
                    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
                        path: dir.clone(),
                        source,
                    })?;
                    let (file, sh, _) = stochvib::study::run_sweep_shard(&sweep, part, dir, true, mc, overwrite, cb)?;
                    Ok((sh.results.to_json()?, Some(file)))
                }
                _ => Ok((
                    stochvib::study::compute_sweep(&sweep, 0..n, true, mc, cb)?.to_json()?,
                    None,
                )),
            }
        };
        let (json, file) = match (monte_carlo, shard) {
            (None, None) => detached(py, || Ok(compute(&|_, _| ())?))?,
            _ => with_progress(py, progress, |cb| run_interruptible(py, cb, compute))?,
        };
        let v: serde_json::Value = serde_json::from_str(&json).map_err(|e| invalid_input(py, e.to_string()))?;
        py.import("stochvib.results")?
            .getattr("SweepResult")?
            .call1((to_python(py, &v)?, file))
    }

    /// The verdicts of every point of a parameter study (``stochvib sweep SCENARIO --param … --verdicts
    /// --json``): the swept values and every number :meth:`analyze` reports as a verdict — σ of each output,
    /// a_w of each comfort axis, a_v, A(8), VDV, the largest damage rate and the shortest life — each point
    /// being the scenario file with the values substituted and read again.
    ///
    /// Parameters
    /// ----------
    /// params : dict
    ///     A scenario key → its values, as for :meth:`sweep`.
    /// zip : bool, keyword-only
    ///     The k-th values of every key together instead of the grid of every combination.
    ///
    /// Returns
    /// -------
    /// VerdictTable
    ///     ``columns`` (with their SI units), ``rows`` (``point``, ``values``, ``error``);
    ///     ``column(name)`` as an array of the study's shape; ``to_csv()`` is the command's CSV.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown key, a bad value or range, keys of different lengths with ``zip``.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    /// >>> t = sc.sweep_verdicts({"model.c": ["50 kN/m", "100 kN/m"]})
    /// >>> t.columns[:2]
    /// ['point', 'model.c [kg s^-2]']
    /// >>> t.column("model.c [kg s^-2]").tolist()
    /// [50000.0, 100000.0]
    #[pyo3(signature = (params, *, zip=false))]
    fn sweep_verdicts<'py>(
        &self,
        py: Python<'py>,
        params: &Bound<'py, PyDict>,
        zip: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = self.stochastic(py)?;
        let params = sweep_params(params)?;
        let json = detached(py, || {
            let sweep = build_sweep(sc, &params, zip)?;
            let shape: Vec<usize> = match sweep.spec().mode {
                stochvib::study::SweepMode::Grid => sweep.spec().params.iter().map(|p| p.values.len()).collect(),
                stochvib::study::SweepMode::Zip => vec![sweep.spec().n_points()],
            };
            let t = stochvib::study::sweep_verdicts::sweep_verdicts(&sweep)?;
            Ok((t.to_json()?, t.to_csv(), shape))
        })?;
        let (json, csv, shape) = json;
        let v: serde_json::Value = serde_json::from_str(&json).map_err(|e| invalid_input(py, e.to_string()))?;
        py.import("stochvib.results")?
            .getattr("VerdictTable")?
            .call1((to_python(py, &v)?, csv, shape))
    }

    /// The parameters that minimise (or maximise) a response quantity under constraints (``stochvib optimize
    /// SCENARIO --param … --minimize … --json``): several COBYLA runs from spread starts over the box of the
    /// bounds, each point analysed exactly.
    ///
    /// Parameters
    /// ----------
    /// params : dict
    ///     A scenario key → its bounds: ``(low, high)`` (numbers in SI units or strings with units) or
    ///     ``"LOW:HIGH UNIT"``, e.g. ``{"model.suspension_damping": ("0.2 kN*s/m", "6 kN*s/m")}``.
    /// minimize, maximize : str, keyword-only
    ///     Exactly one: the quantity, ``sigma(OUTPUT)``, ``3sigma(OUTPUT)``, ``peak3(OUTPUT)``,
    ///     ``a_w(OUTPUT)``, ``a_v``, ``A8``, ``VDV``, ``damage_rate``, ``life``.
    /// constraints : sequence of str, keyword-only
    ///     ``"QUANTITY <= VALUE UNIT"`` or ``"QUANTITY >= VALUE UNIT"``, e.g. ``"3sigma(travel) <= 40 mm"``.
    /// starts : int, keyword-only
    ///     Starts: the centre of the box, then Halton points.
    /// max_evaluations : int, keyword-only
    ///     Most evaluations per start.
    ///
    /// Returns
    /// -------
    /// OptimizeResult
    ///     ``value`` (SI), ``params`` (each ``key``, ``value``, ``text``, ``at_bound``), ``constraints``,
    ///     ``feasible`` and ``violations`` (an infeasible problem is answered with its least violating point,
    ///     not raised; the command-line tool then exits with an error).
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown key or quantity, bounds the wrong way round, both or neither of minimize/maximize.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    /// >>> r = sc.optimize({"model.c": ("50 kN/m", "200 kN/m")}, minimize="sigma(y)", starts=1)
    /// >>> r.params[0].at_bound  # σ of the deflection falls with the stiffness
    /// 'upper'
    #[pyo3(signature = (params, *, minimize=None, maximize=None, constraints=vec![], starts=4, max_evaluations=2000))]
    #[allow(clippy::too_many_arguments)]
    fn optimize<'py>(
        &self,
        py: Python<'py>,
        params: &Bound<'py, PyDict>,
        minimize: Option<String>,
        maximize: Option<String>,
        constraints: Vec<String>,
        starts: usize,
        max_evaluations: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = self.stochastic(py)?;
        let task = crate::optimize::Task {
            minimize,
            maximize,
            constraints,
            starts,
            max_evaluations,
        };
        let (data, text) = crate::optimize::optimize(py, sc, params, task)?;
        py.import("stochvib.results")?
            .getattr("OptimizeResult")?
            .call1((data, text))
    }

    /// The Pareto front of two quantities, both minimised (``stochvib optimize SCENARIO --param …
    /// --minimize FIRST --pareto SECOND --points N [--plots DIR] --json``): the ε-constraint method, FIRST
    /// minimised with SECOND held below a ladder of limits between its values at the two single-objective
    /// optima (Haimes, Lasdon & Wismer 1971).
    ///
    /// Parameters
    /// ----------
    /// params : dict
    ///     As :meth:`optimize`.
    /// minimize, pareto : str, keyword-only
    ///     The two quantities (as :meth:`optimize`'s), both minimised.
    /// constraints : sequence of str, keyword-only
    ///     Constraints every point meets, as :meth:`optimize`'s.
    /// points : int, keyword-only
    ///     Points of the front, its two ends included (≥ 2).
    /// plots : str or path, keyword-only, optional
    ///     A directory to draw the front into (``pareto-front.svg`` and ``.png``, as ``--plots``).
    /// starts, max_evaluations : int, keyword-only
    ///     Per search, as :meth:`optimize`.
    ///
    /// Returns
    /// -------
    /// ParetoFront
    ///     ``points`` (each ``params``, ``values``, ``limit``, ``feasible``) in order of increasing first
    ///     quantity, ``values`` an (N, 2) array, ``to_csv()`` the command's CSV, ``plots`` the pictures.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     As :meth:`optimize`; fewer than 2 points; an end of the front that meets not every constraint.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    /// >>> fr = sc.pareto({"model.c": ("50 kN/m", "200 kN/m")}, minimize="sigma(y)", pareto="sigma(y_vel)", points=3, starts=1)
    /// >>> fr.values.shape, fr.quantities, fr.units
    /// ((3, 2), ['sigma(y)', 'sigma(y_vel)'], ['m', 'm/s'])
    #[pyo3(signature = (params, *, minimize, pareto, constraints=vec![], points=7, plots=None, starts=4, max_evaluations=2000))]
    #[allow(clippy::too_many_arguments)]
    fn pareto<'py>(
        &self,
        py: Python<'py>,
        params: &Bound<'py, PyDict>,
        minimize: String,
        pareto: String,
        constraints: Vec<String>,
        points: usize,
        plots: Option<PathBuf>,
        starts: usize,
        max_evaluations: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = self.stochastic(py)?;
        let task = crate::optimize::Task {
            minimize: Some(minimize),
            maximize: None,
            constraints,
            starts,
            max_evaluations,
        };
        let (data, csv, files) = crate::optimize::front(py, sc, params, task, (pareto, points, plots))?;
        py.import("stochvib.results")?
            .getattr("ParetoFront")?
            .call1((data, csv, files))
    }

    /// The non-stationary response of a scenario with a ``[transient]`` section (``stochvib transient
    /// SCENARIO --json``): σ(t), the mean and the crossing rates at the reported times by the exact route,
    /// the mission extremes; with ``monte_carlo=N`` a seeded batch of the same transient whose σ(t) is
    /// compared with the exact one (simultaneous level 1 − 10⁻³ over the reported times).
    ///
    /// Parameters
    /// ----------
    /// monte_carlo : int, keyword-only, optional
    ///     Realizations of the batch.
    /// path : path, keyword-only, optional
    ///     Its run file (HDF5; written as ``path.tmp`` and renamed, an interrupted run resumes); None: a
    ///     temporary file, removed afterwards. With ``shard=(I, N)`` the run directory receiving
    ///     ``shard-<I>-of-<N>.h5`` (:func:`stochvib.merge` joins the parts).
    /// seed, substeps, shard_size, confidence, store_raw, overwrite : keyword-only
    ///     Master seed (realization i uses the stream (seed, i)); integration steps per reported interval;
    ///     realizations per shard; confidence of the per-time intervals and of the DKW band of the maxima;
    ///     keep every realization; replace a finished run file.
    /// progress : bool or callable, keyword-only
    ///     A bar (True), none (False) or a callable(done, total).
    ///
    /// Returns
    /// -------
    /// TransientResult
    ///     ``times``, ``outputs[name]`` (``sigma``, ``mean``, ``nu0_plus`` arrays over ``times``),
    ///     ``mission``; ``monte_carlo`` and ``sigma_comparison`` with a batch. ``to_dict()`` is the
    ///     ``--json`` of ``stochvib transient``.
    ///
    /// Raises
    /// ------
    /// InvalidInputError, FileError
    ///     No ``[transient]`` section, a bad schedule, a model with nonlinear elements.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> r = stochvib.Scenario.load("data/quarter-car-accelerating.toml").transient()
    /// >>> float(r.times[0]), float(r.times[-1])
    /// (0.0, 15.0)
    #[pyo3(signature = (*, monte_carlo=None, path=None, seed=1, substeps=4, shard_size=50, confidence=0.95, store_raw=false, overwrite=false, progress=None, shard=None))]
    #[allow(clippy::too_many_arguments)]
    fn transient<'py>(
        &self,
        py: Python<'py>,
        monte_carlo: Option<usize>,
        path: Option<PathBuf>,
        seed: u64,
        substeps: usize,
        shard_size: usize,
        confidence: f64,
        store_raw: bool,
        overwrite: bool,
        progress: Option<Py<PyAny>>,
        shard: Option<(usize, usize)>,
    ) -> PyResult<Bound<'py, PyAny>> {
        use crate::transient::{transient, Batch};
        let sc = self.stochastic(py)?;
        if shard.is_some() && path.is_none() {
            return Err(invalid_input(
                py,
                "`shard`: needs path= (the run directory of the shard files)",
            ));
        }
        let part = shard
            .map(|(i, n)| call(py, || stochvib::store::Part::new(i, n)))
            .transpose()?;
        let batch = monte_carlo.map(|n| Batch {
            opts: stochvib::study::transient_mc::TransientMcOptions {
                realizations: n,
                substeps,
                seed,
                shard_size,
                confidence,
                store_raw,
                compression: Compression::default(),
                part,
                overwrite,
                max_hours: stochvib::simulate::resources::DEFAULT_MAX_HOURS,
            },
            path,
        });
        let place = |p: PathBuf| -> stochvib::Result<PathBuf> {
            let Some(part) = part else { return Ok(p) };
            std::fs::create_dir_all(&p).map_err(|source| Error::Io {
                path: p.clone(),
                source,
            })?;
            Ok(stochvib::study::part_path(&p, part))
        };
        let progress = if batch.is_some() {
            progress
        } else {
            Some(false.into_py_any(py)?)
        };
        let a = with_progress(py, progress, |cb| {
            run_interruptible(py, cb, |cb| transient(sc, batch.map(|b| (b, &place as _)), cb))
        })?;
        let (mc, sigma, notes) = match &a.monte_carlo {
            Some((s, c, n)) => (Some(s), Some(c), n.clone()),
            None => (None, None, Vec::new()),
        };
        let data = serde_json::json!({ "exact": a.exact, "monte_carlo": mc, "sigma": sigma });
        let mut text = a.exact.to_string();
        if let Some(c) = sigma {
            text.push_str(&c.to_string());
        }
        py.import("stochvib.results")?
            .getattr("TransientResult")?
            .call1((to_python(py, &data)?, text, notes))
    }

    /// The result tables of a deterministic model (a hoist, a chain) or of a reference table of the sources
    /// — the ``stochvib analyze`` report of such a file — as a :class:`TablesResult`. A stochastic scenario
    /// raises :class:`NotApplicableError` (use :meth:`analyze`).
    ///
    /// Returns
    /// -------
    /// TablesResult
    ///
    /// Raises
    /// ------
    /// NotApplicableError
    ///     A stochastic scenario.
    fn tables<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if let Document::Stochastic(sc) = &self.doc {
            return Err(crate::errors::not_applicable(
                py,
                format!(
                    "{}: a stochastic scenario: analyze() returns its statistics",
                    sc.path.display()
                ),
            ));
        }
        let (_, data, text) = document_report(py, &self.doc)?;
        py.import("stochvib.results")?
            .getattr("TablesResult")?
            .call1((data, text))
    }

    /// Runs a seeded Monte Carlo batch of ``realizations`` into the HDF5 file ``path`` (readable by h5py;
    /// the layout is described in the README) and returns a :class:`RunResult` with its statistics.
    ///
    /// ``dt`` (s) and ``duration`` (s, per realization) are suggested from the system when not given.
    /// Realization i uses the random stream (seed, i): results are identical for any thread count. The file
    /// is written as ``path + ".tmp"`` and renamed when complete; a run stopped by Ctrl-C
    /// (KeyboardInterrupt, checked after every shard of ``shard_size`` realizations) leaves only that
    /// ``.tmp``, and the same call resumes it. An existing ``path`` is never overwritten unless
    /// ``overwrite=True``. ``store_raw`` keeps every realization (``compression``: "none", "fast", "best",
    /// "deflate:N"); ``route``: "auto", "exact" or "spectral"; ``confidence`` of the intervals.
    /// ``progress``: True (a bar on stderr, tqdm's when installed), False, or a callable(done, total).
    /// The GIL is released while the run computes. ``shard=(I, N)`` runs part I of N of the run (as
    /// ``stochvib simulate --shard I --of N -o DIR``): ``path`` is then the run directory (created) that
    /// receives ``shard-<I>-of-<N>.h5``; :func:`stochvib.merge` joins the parts.
    ///
    /// A model with nonlinear elements raises :class:`InvalidInputError` naming :meth:`simulate_nonlinear`.
    ///
    /// Parameters
    /// ----------
    /// realizations : int
    ///     N ≥ 2.
    /// path : str or os.PathLike
    ///     The run file (HDF5) to write; with ``shard``, the run directory.
    /// dt, duration : float or str, keyword-only, optional
    ///     Δt and the duration of one realization, in s or time strings ("10 ms"); suggested when not given.
    /// seed : int, keyword-only, default 1
    ///     The master seed.
    /// shard_size : int, keyword-only, default 50
    ///     Realizations between checkpoints (and Ctrl-C checks).
    /// store_raw : bool, keyword-only, default False
    /// compression : str, keyword-only, default "none"
    ///     "none", "fast", "best" or "deflate:N" (with ``store_raw``).
    /// route : {"auto", "exact", "spectral"}, keyword-only, default "auto"
    /// confidence : float, keyword-only, default 0.95
    ///     Of the intervals, in (0, 1).
    /// overwrite : bool, keyword-only, default False
    /// progress : bool or callable, keyword-only, default True
    ///     True (or None): a bar; False: nothing; a callable(done, total).
    /// shard : (int, int), keyword-only, optional
    ///     (I, N): part I of N.
    ///
    /// Returns
    /// -------
    /// RunResult
    ///     The run file's path and the statistics with their intervals.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     A bad argument (fewer than 2 realizations, an unknown route or compression, a bad shard);
    ///     the model is of the other kind (the message names the other method).
    /// UnitError
    ///     ``dt``, ``duration`` or ``burn_in`` strings that are not times.
    /// FileError
    ///     ``path`` exists (without ``overwrite``) or cannot be written.
    /// NotApplicableError
    ///     A deterministic model or a reference table.
    /// KeyboardInterrupt
    ///     Ctrl-C: the ``.tmp`` file is kept for resuming.
    ///
    /// Examples
    /// --------
    /// >>> import pathlib, tempfile, stochvib
    /// >>> sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    /// >>> with tempfile.TemporaryDirectory() as d:
    /// ...     r = sc.simulate(2, pathlib.Path(d) / "run.h5", dt=0.01, duration=5.0, progress=False)
    /// ...     r.n_realizations, r.path.is_file()
    /// (2, True)
    #[pyo3(signature = (realizations, path, *, dt=None, duration=None, seed=1, shard_size=50, store_raw=false, compression="none", route="auto", confidence=0.95, overwrite=false, progress=None, shard=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate<'py>(
        &self,
        py: Python<'py>,
        realizations: usize,
        path: PathBuf,
        dt: Option<&Bound<'py, PyAny>>,
        duration: Option<&Bound<'py, PyAny>>,
        seed: u64,
        shard_size: usize,
        store_raw: bool,
        compression: &str,
        route: &str,
        confidence: f64,
        overwrite: bool,
        progress: Option<Py<PyAny>>,
        shard: Option<(usize, usize)>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = self.stochastic(py)?;
        simulate_run(
            py,
            sc,
            false,
            realizations,
            path,
            dt,
            duration,
            seed,
            shard_size,
            store_raw,
            compression,
            route,
            confidence,
            overwrite,
            progress,
            shard,
            None,
        )
    }

    /// Route 2 of a model with nonlinear elements into the HDF5 file ``path``: the nonlinear equations in
    /// time, as ``stochvib simulate`` of such a file, returning a :class:`NonlinearRunResult` (Δt and the
    /// duration suggested for route 2 when not given; ``burn_in`` in s, default from the slowest decay rate
    /// of the Gaussian equivalent). The other arguments as for :meth:`simulate`. A linear model raises
    /// :class:`InvalidInputError` naming :meth:`simulate`.
    ///
    /// Parameters
    /// ----------
    /// realizations : int
    ///     N ≥ 2.
    /// path : str or os.PathLike
    ///     The run file (HDF5) to write; with ``shard``, the run directory.
    /// dt, duration : float or str, keyword-only, optional
    ///     Δt and the duration of one realization, in s or time strings ("10 ms"); suggested when not given.
    /// seed : int, keyword-only, default 1
    ///     The master seed.
    /// shard_size : int, keyword-only, default 50
    ///     Realizations between checkpoints (and Ctrl-C checks).
    /// store_raw : bool, keyword-only, default False
    /// compression : str, keyword-only, default "none"
    ///     "none", "fast", "best" or "deflate:N" (with ``store_raw``).
    /// route : {"auto", "exact", "spectral"}, keyword-only, default "auto"
    /// confidence : float, keyword-only, default 0.95
    ///     Of the intervals, in (0, 1).
    /// overwrite : bool, keyword-only, default False
    /// progress : bool or callable, keyword-only, default True
    ///     True (or None): a bar; False: nothing; a callable(done, total).
    /// shard : (int, int), keyword-only, optional
    ///     (I, N): part I of N.
    /// burn_in : float or str, keyword-only, optional
    ///     s, or a time string.
    ///
    /// Returns
    /// -------
    /// NonlinearRunResult
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     A bad argument (fewer than 2 realizations, an unknown route or compression, a bad shard);
    ///     the model is of the other kind (the message names the other method).
    /// UnitError
    ///     ``dt``, ``duration`` or ``burn_in`` strings that are not times.
    /// FileError
    ///     ``path`` exists (without ``overwrite``) or cannot be written.
    /// NotApplicableError
    ///     A deterministic model or a reference table.
    /// KeyboardInterrupt
    ///     Ctrl-C: the ``.tmp`` file is kept for resuming.
    ///
    /// Examples
    /// --------
    /// >>> import pathlib, tempfile, stochvib
    /// >>> sc = stochvib.Scenario.load("data/duffing-white-noise.toml")
    /// >>> with tempfile.TemporaryDirectory() as d:
    /// ...     r = sc.simulate_nonlinear(2, pathlib.Path(d) / "run.h5", dt=0.01, duration=5.0, progress=False)
    /// ...     r.n_realizations, r.burn_in_s > 0
    /// (2, True)
    #[pyo3(signature = (realizations, path, *, dt=None, duration=None, seed=1, shard_size=50, store_raw=false, compression="none", route="auto", confidence=0.95, overwrite=false, progress=None, shard=None, burn_in=None))]
    #[allow(clippy::too_many_arguments)]
    fn simulate_nonlinear<'py>(
        &self,
        py: Python<'py>,
        realizations: usize,
        path: PathBuf,
        dt: Option<&Bound<'py, PyAny>>,
        duration: Option<&Bound<'py, PyAny>>,
        seed: u64,
        shard_size: usize,
        store_raw: bool,
        compression: &str,
        route: &str,
        confidence: f64,
        overwrite: bool,
        progress: Option<Py<PyAny>>,
        shard: Option<(usize, usize)>,
        burn_in: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sc = self.stochastic(py)?;
        simulate_run(
            py,
            sc,
            true,
            realizations,
            path,
            dt,
            duration,
            seed,
            shard_size,
            store_raw,
            compression,
            route,
            confidence,
            overwrite,
            progress,
            shard,
            burn_in,
        )
    }

    /// The density of output ``output`` (a name) under the scenario's input, as an array shaped as the
    /// argument: the two-sided S_y(ω) at ``omega`` (rad/s; rad/m along a road has become time through the
    /// speed), or the one-sided G_y(f) = 4π S_y(2πf) at ``f`` (Hz, scipy.signal.welch's). ``convention``
    /// as for :meth:`Spectrum.density`. Delays, several inputs and catalogue layouts are included; for the
    /// weighted density use a system from :meth:`System.weighted`.
    ///
    /// Parameters
    /// ----------
    /// output : str
    ///     An output name.
    /// omega : array_like, optional
    ///     ω in rad/s, any shape.
    /// f : array_like, keyword-only, optional
    ///     f in Hz instead. Exactly one of ``omega`` and ``f``.
    /// convention : str, keyword-only, optional
    ///     As for :meth:`Spectrum.density`.
    ///
    /// Returns
    /// -------
    /// float or numpy.ndarray of float64
    ///     In (output unit)² per rad/s (per Hz with ``f``), shaped as the argument.
    ///
    /// Raises
    /// ------
    /// InvalidInputError
    ///     An unknown output; both or neither of ``omega`` and ``f``; a convention that does not belong.
    /// NotApplicableError
    ///     A deterministic model or a reference table.
    ///
    /// Examples
    /// --------
    /// >>> import stochvib
    /// >>> sc = stochvib.Scenario.load("data/conveyor-idler.toml")
    /// >>> sc.output_density("y", [0.0, 1.0]).shape
    /// (2,)
    #[pyo3(signature = (output, omega=None, *, f=None, convention=None))]
    fn output_density<'py>(
        &self,
        py: Python<'py>,
        output: &str,
        omega: Option<&Bound<'py, PyAny>>,
        f: Option<&Bound<'py, PyAny>>,
        convention: Option<&str>,
    ) -> PyResult<Bound<'py, PyAny>> {
        use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
        let sc = self.stochastic(py)?;
        let sys = &*sc.model.system;
        let i = call(py, || sys.output_index(output))?;
        let od = call(py, || stochvib::response::OutputDensity::new(sys, &sc.excitation, i))?;
        let (conv, x) = crate::spectrum::density_argument(py, omega, f, convention)?;
        let shape = x.shape().to_vec();
        // SAFETY: every element is written by `convert_density` before the array is returned.
        let out = unsafe { PyArrayDyn::<f64>::new(py, shape.clone(), false) };
        {
            let xr = x.readonly();
            let mut rw = out.readwrite();
            let (xs, os) = (xr.as_slice()?, rw.as_slice_mut()?);
            let eval = |w: &[f64], o: &mut [f64]| o.iter_mut().zip(w).for_each(|(y, &w)| *y = od.density(w));
            crate::errors::detached_if(py, xs.len(), crate::spectrum::DETACH_MIN_POINTS / 16, || {
                crate::spectrum::convert_density(eval, conv, xs, os);
                Ok(())
            })?;
        }
        crate::spectrum::scalar_or_array(py, out, shape.is_empty())
    }

    /// Title of the scenario.
    #[getter]
    fn title(&self) -> &str {
        match &self.doc {
            Document::Stochastic(sc) => &sc.title,
            Document::Deterministic(d) => &d.title,
            Document::Reference(r) => &r.title,
        }
    }

    /// The file ("<python>" for a scenario built in Python).
    #[getter]
    fn path(&self) -> PathBuf {
        match &self.doc {
            Document::Stochastic(sc) => sc.path.clone(),
            Document::Deterministic(d) => d.path.clone(),
            Document::Reference(r) => r.path.clone(),
        }
    }

    /// "stochastic", "deterministic" or "reference".
    #[getter]
    fn what(&self) -> &'static str {
        match &self.doc {
            Document::Stochastic(_) => "stochastic",
            Document::Deterministic(_) => "deterministic",
            Document::Reference(_) => "reference",
        }
    }

    /// The model kind ("" for a reference table).
    #[getter]
    fn kind(&self) -> &str {
        match &self.doc {
            Document::Stochastic(sc) => &sc.kind,
            Document::Deterministic(d) => &d.kind,
            Document::Reference(_) => "",
        }
    }

    /// The scenario's system (stochastic scenarios).
    #[getter]
    fn system(&self, py: Python<'_>) -> PyResult<PySystem> {
        let sc = self.stochastic(py)?;
        Ok(PySystem::from_instance(&sc.model, &sc.kind))
    }

    /// The random input as written (a road spectrum before the speed turns it into time).
    #[getter]
    fn input(&self, py: Python<'_>) -> PyResult<PySpectrum> {
        let sc = self.stochastic(py)?;
        let i = &sc.input;
        Ok(PySpectrum {
            spectrum: i.spectrum.clone(),
            unit: i.unit.clone(),
            name: i.reference.clone(),
            description: String::new(),
            source: String::new(),
            text: i.spectrum_text.clone(),
            origin: i.origin.clone(),
        })
    }

    /// ``[input] speed`` in m/s, or None.
    #[getter]
    fn speed(&self, py: Python<'_>) -> PyResult<Option<f64>> {
        Ok(self.stochastic(py)?.input.speed)
    }

    /// The names of the outputs the analysis reports.
    #[getter]
    fn outputs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let sc = self.stochastic(py)?;
        let all = sc.model.system.outputs();
        PyList::new(py, sc.analysis.outputs.iter().map(|&i| all[i].name.clone()))
    }

    /// The scenario file's text (a TOML description for a scenario built in Python).
    #[getter]
    fn text(&self, py: Python<'_>) -> PyResult<String> {
        Ok(self.stochastic(py)?.text.clone())
    }

    fn __repr__(&self) -> String {
        format!(
            "<stochvib.Scenario {} ({}): {}>",
            self.title(),
            self.what(),
            self.path().display()
        )
    }
}

/// `mean=` of `from_system`: nothing (0), one quantity, or one per process, each a number in its spectrum's unit
/// or a string with a unit of that dimension ("5 cm").
///
/// # Errors
/// `UnitError` naming `mean` (`mean[i]`); `InvalidInputError` for anything else.
fn process_means(py: Python<'_>, mean: Option<&Bound<'_, PyAny>>, spectra: &[Py<PySpectrum>]) -> PyResult<Vec<f64>> {
    let one = |m: &Bound<'_, PyAny>, name: &str, s: &Py<PySpectrum>| {
        let unit = &s.get().unit;
        match stochvib::units::unit_dim(unit) {
            Some(d) => quantity::of_dim(py, m, name, d),
            None => quantity::quantity(py, m, name, unit),
        }
    };
    match mean {
        None => Ok(vec![0.0]),
        Some(m) if m.is_instance_of::<PyString>() || m.extract::<f64>().is_ok() => {
            Ok(vec![one(m, "mean", &spectra[0])?])
        }
        Some(m) => {
            let items: Vec<Bound<'_, PyAny>> = m
                .try_iter()
                .map_err(|_| invalid_input(py, "`mean`: expected a number or one number per input"))?
                .collect::<PyResult<_>>()?;
            items
                .iter()
                .enumerate()
                .map(|(i, x)| one(x, &format!("mean[{i}]"), &spectra[i.min(spectra.len() - 1)]))
                .collect()
        }
    }
}

/// `levels=` of `from_system`: output name → levels, each a number in the output's SI unit or a string with a
/// unit of its dimension ("3 cm").
///
/// # Errors
/// `UnitError` naming `levels[name][i]`; an unknown output; `InvalidInputError` for anything else.
fn output_levels(
    py: Python<'_>,
    levels: Option<&Bound<'_, PyDict>>,
    sys: &dyn stochvib::system::FrequencyResponse,
) -> PyResult<Vec<(usize, Vec<f64>)>> {
    let Some(d) = levels else { return Ok(Vec::new()) };
    d.iter()
        .map(|(k, v)| {
            let name: String = k.extract()?;
            let i = call(py, || sys.output_index(&name))?;
            let unit = &sys.outputs()[i].unit;
            let what = format!("levels[{name:?}]");
            let vals = match stochvib::units::unit_dim(unit) {
                Some(dim) => quantity::sequence_of_dim(py, &v, &what, dim)?,
                None => quantity::sequence(py, &v, &what, unit)?,
            };
            Ok((i, vals))
        })
        .collect()
}

/// The excitation of `sys`'s inputs by the spectra `arcs` (speed, wheel positions, means): on a road of two
/// tracks when `two` names one or the system stands on two tracks (with the coherence's description), else
/// one track or independent inputs.
fn system_excitation(
    py: Python<'_>,
    sys: &PySystem,
    arcs: &[Arc<dyn Spectrum>],
    (speed, positions, means): (Option<f64>, Option<Vec<f64>>, &[f64]),
    two: TwoTrackArgs<'_, '_>,
) -> PyResult<(Excitation, Option<String>)> {
    let on_two_tracks = two.given() || matches!(sys.layout, Some(InputLayout::TwoTracks { .. }));
    if !on_two_tracks {
        return Ok((excitation(py, sys, arcs, speed, positions, means.to_vec())?, None));
    }
    if arcs.len() != 1 || means.len() != 1 {
        return Err(invalid_input(
            py,
            "a road of two tracks is one spectrum (that of each track) with one mean",
        ));
    }
    let (e, d) = two_tracks::excitation(
        py,
        (&sys.layout, sys.system.n_inputs()),
        &arcs[0],
        (speed, positions, means[0]),
        two,
    )?;
    Ok((e, Some(d)))
}

/// `duration_s` finite and > 0; `band_rad_s`, when given, 0 ≤ low < high < ∞.
fn check_analysis_args(duration_s: f64, band_rad_s: Option<(f64, f64)>) -> stochvib::Result<()> {
    if !(duration_s.is_finite() && duration_s > 0.0) {
        return Err(Error::invalid("duration_s", duration_s, "must be finite and > 0"));
    }
    match band_rad_s {
        Some((a, b)) if !(a >= 0.0 && b > a && b.is_finite()) => Err(Error::invalid(
            "band_rad_s",
            format!("({a}, {b})"),
            "need 0 <= low < high < inf",
        )),
        _ => Ok(()),
    }
}

/// The provenance stored with Monte Carlo runs of a scenario built in Python (there is no scenario file): a
/// TOML description of the model and the input.
fn provenance_text(
    title: &str,
    sys: &PySystem,
    arcs: &[Arc<dyn Spectrum>],
    speed: Option<f64>,
    means: &[f64],
    exc: &Excitation,
) -> String {
    let mut prov = toml::Table::new();
    prov.insert(
        "generated_by".into(),
        "the stochvib Python package (Scenario.from_system)".into(),
    );
    prov.insert("title".into(), title.into());
    let mut model = toml::Table::new();
    model.insert("kind".into(), sys.kind.clone().into());
    model.insert("description".into(), sys.description.clone().into());
    prov.insert("model".into(), model.into());
    let mut inp = toml::Table::new();
    inp.insert(
        "spectra".into(),
        toml::Value::Array(arcs.iter().map(|s| s.describe().into()).collect()),
    );
    if let Some(v) = speed {
        inp.insert("speed".into(), v.into());
    }
    inp.insert(
        "mean".into(),
        toml::Value::Array(means.iter().map(|&m| m.into()).collect()),
    );
    inp.insert("excitation".into(), format!("{exc:?}").into());
    prov.insert("input".into(), inp.into());
    toml::to_string(&prov).unwrap_or_default()
}
