//! A scenario's non-stationary analysis (`stochvib transient`): the scenario's system, input, speed
//! profile, envelope and schedules as a [`TimeVaryingSystem`], the exact route on the reported times, the
//! crossing rates, the running ISO 2631-1 weighted r.m.s. a_w(t) of the comfort axes, and the extremes of
//! the mission (`docs/transients.md`).

use crate::error::{Error, Result};
use crate::fields::Fields;
use crate::models::InputLayout;
use crate::scenario::transient_keys::{ScheduledKey, TransientSpec};
use crate::scenario::Scenario;
use crate::system::StateSpace;
use crate::transient::{
    check_stability, input_model, solve, solve_evolutionary, EvolutionaryInput, EvolutionarySolution, ExactOptions,
    ExtraSource, FamilyBuilder, FixedSystem, MatrixCoherence, Schedule, ScheduledSystem, SpeedProfile, Start,
    SystemFamily, TimeVaryingSystem, TransientInput, TransientSolution, Wheel, WheelRoad,
};
use std::path::Path;
use std::sync::Arc;

/// Stored times of the exact route when `[transient] step` is absent: duration/400.
pub const DEFAULT_INTERVALS: usize = 400;

/// A scenario set up for the transient routes.
#[derive(Debug, Clone)]
pub struct TransientSetup {
    /// The system (the model with the weighted outputs of `[analysis.comfort]` appended) and its input.
    pub sys: TimeVaryingSystem,
    /// The reported outputs (indices into the system's outputs): `[analysis] outputs`, then the weighted.
    pub outputs: Vec<usize>,
    /// Per comfort axis: (the acceleration output, its weighted output), indices into the system's outputs.
    pub weighted: Vec<(usize, usize)>,
    /// The start.
    pub start: Start,
    /// The reported (stored) times: 0, Δ, …, T.
    pub times: Vec<f64>,
    /// Error control of the exact route.
    pub options: ExactOptions,
    /// Time-invariant and started in its stationary state (Vanmarcke's stationary form applies).
    pub stationary: bool,
}

/// The scenario's `[transient]` keys, or an error naming the missing duration.
fn spec_of(sc: &Scenario) -> Result<(&TransientSpec, f64)> {
    let missing = |why: &str| Error::File {
        file: sc.path.clone(),
        key: "transient.duration".into(),
        value: "<missing>".into(),
        reason: why.into(),
    };
    let spec = sc.transient.as_deref().ok_or_else(|| {
        missing("a transient analysis needs a [transient] section with the duration of the time window, e.g. duration = \"20 s\"")
    })?;
    let d = spec
        .duration
        .ok_or_else(|| missing("the time window [0, duration] of the transient analysis, e.g. duration = \"20 s\""))?;
    Ok((spec, d))
}

/// The reported times 0, Δ, …, T with Δ = `step` rounded to divide T (DEFAULT_INTERVALS without a step).
pub fn report_times(duration: f64, step: Option<f64>) -> Vec<f64> {
    let n = step.map_or(DEFAULT_INTERVALS, |s| ((duration / s).round() as usize).max(1));
    (0..=n).map(|k| duration * k as f64 / n as f64).collect()
}

/// The gains of the one input process at the system inputs, or why the exact route cannot take the layout.
fn gains(sc: &Scenario) -> Result<Vec<f64>> {
    let refuse = |reason: String| Error::NotApplicable {
        method: "transient analysis".into(),
        reason,
    };
    if sc.inputs.len() != 1 {
        return Err(refuse(
            "several [[input]] sources: the evolutionary route and the road-grid Monte Carlo take one random \
             input ([input]); the exact route takes several when every one is rational (a rational or w = 2 \
             temporal spectrum, a rational road), e.g. a band-limited road and a force; otherwise not available"
                .into(),
        ));
    }
    match &sc.model.layout {
        InputLayout::Single => Ok(vec![1.0]),
        InputLayout::Track { positions, gains } if positions.iter().all(|p| *p == positions[0]) => Ok(gains.clone()),
        InputLayout::Track { positions, .. } => Err(refuse(format!(
            "the wheels are at different positions ({positions:?} m): a pure delay is not finite-dimensional, and \
             under a varying speed it varies in time, so the exact and evolutionary routes have no form of it; \
             use `stochvib transient --monte-carlo N` (the road-grid Monte Carlo reads each wheel's road at \
             x(t) - l), or a model with one contact point"
        ))),
        InputLayout::TwoTracks { .. } => Err(refuse(
            "a road of two tracks: their coherence is not a rational function, so the pair has no finite shaping \
             filter (no exact route), and the evolutionary route takes one process; use `stochvib transient \
             --monte-carlo N` (the road-grid Monte Carlo synthesises the two tracks with their coherence)"
                .into(),
        )),
    }
}

/// The gains of each independent `[[input]]` source at the model inputs (the one `[input]`: [`gains`]).
///
/// # Errors
/// A road of two tracks (its coherence is not rational: no finite filter of the pair); a source whose
/// inputs are at different positions (a pure delay is not finite-dimensional, and under a varying speed it
/// varies in time); an excitation that is not one of independent sources.
fn source_gains(sc: &Scenario) -> Result<Vec<Vec<f64>>> {
    if sc.inputs.len() == 1 {
        return Ok(vec![gains(sc)?]);
    }
    let refuse = |reason: String| Error::NotApplicable {
        method: "exact (differential Lyapunov) route".into(),
        reason,
    };
    let crate::response::Excitation::Sources { sources, inputs } = &sc.excitation else {
        return Err(refuse("the [[input]] tables do not form independent sources".into()));
    };
    sources
        .iter()
        .enumerate()
        .map(|(k, src)| {
            let name = &sc.inputs[k].name;
            if let crate::response::Source::Matrix(_) = src {
                return Err(refuse(format!(
                    "input `{name}` is a road of two tracks: their coherence is not a rational function, so the \
                     pair has no finite shaping filter; not available: give each wheel line its own \
                     one-track road, or use the stationary analyses"
                )));
            }
            if inputs.iter().any(|m| m.source == k && m.delay != 0.0) {
                return Err(refuse(format!(
                    "input `{name}` reaches its model inputs at different positions: a pure delay is not \
                     finite-dimensional, and under a varying speed it varies in time; not available: use a \
                     model with one contact point per source"
                )));
            }
            Ok(inputs
                .iter()
                .map(|m| if m.source == k { m.gain } else { 0.0 })
                .collect())
        })
        .collect()
}

/// The time-varying system of the scenario's sources: the first is the [`TransientInput`] (with the
/// envelope), the others [`ExtraSource`]s.
fn sources_system(
    sc: &Scenario,
    spec: &TransientSpec,
    fam: Arc<dyn SystemFamily>,
    speed: Option<&SpeedProfile>,
) -> Result<TimeVaryingSystem> {
    let mut gains = source_gains(sc)?.into_iter();
    let input = TransientInput {
        model: input_model(sc.inputs[0].spectrum.as_ref(), speed)?,
        envelope: spec.envelope.clone(),
        mean: sc.inputs[0].mean,
        gains: gains.next().unwrap_or_default(),
    };
    let extra = sc.inputs[1..]
        .iter()
        .zip(gains)
        .map(|(inp, gains)| {
            Ok(ExtraSource {
                model: input_model(inp.spectrum.as_ref(), speed)?,
                gains,
                mean: inp.mean,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    TimeVaryingSystem::with_sources(fam, input, extra)
}

/// The speed profile of the input: `[input.speed_profile]`, else the constant `[input] speed`.
fn speed_of(sc: &Scenario, spec: &TransientSpec) -> Result<Option<SpeedProfile>> {
    match (&spec.speed_profile, sc.input.speed) {
        (Some(v), _) => Ok(Some(v.clone())),
        (None, Some(v)) => SpeedProfile::constant(v).map(Some),
        (None, None) => Ok(None),
    }
}

/// The comfort axes of `[analysis.comfort]`.
fn axes(sc: &Scenario) -> Vec<crate::scenario::ComfortAxisSpec> {
    sc.analysis
        .verdicts
        .comfort
        .as_ref()
        .map(|c| c.axes.clone())
        .unwrap_or_default()
}

/// What rebuilds the model at the scheduled values: the file, the kind, the speed, the `[model]` table.
#[derive(Debug)]
struct Rebuild {
    path: std::path::PathBuf,
    kind: String,
    speed: Option<f64>,
    table: toml::Table,
    /// A copy of `table` whose scheduled keys are overwritten at every call (every call sets all of them,
    /// so it holds what a fresh copy with the keys set would): the copy of the whole table per frozen time
    /// was a tenth of a scheduled transient's run. A call that finds it in use copies `table` instead.
    working: std::sync::Mutex<Option<toml::Table>>,
    keys: Vec<ScheduledKey>,
    axes: Vec<crate::scenario::ComfortAxisSpec>,
}

/// The family of the scenario's system: fixed, or rebuilt from the `[model]` table with the scheduled keys
/// substituted at every time.
fn family(sc: &Scenario, spec: &TransientSpec) -> Result<(Arc<dyn SystemFamily>, Vec<usize>)> {
    let ss = sc.model.system.state_space().ok_or_else(|| Error::NotApplicable {
        method: "transient analysis".into(),
        reason: "the model has no state-space form".into(),
    })?;
    let (ext, weighted) = super::verdict_run::with_weighted_outputs(ss, &axes(sc))?;
    if spec.schedules.is_empty() {
        let fixed = FixedSystem::new(ext, None, &sc.model.description)?;
        return Ok((Arc::new(fixed), weighted));
    }
    let root = crate::fields::parse_toml(&sc.text, &sc.path)?;
    let rebuild = Rebuild {
        path: sc.path.clone(),
        kind: sc.kind.clone(),
        speed: sc.input.speed,
        table: root
            .get("model")
            .and_then(|m| m.as_table())
            .cloned()
            .unwrap_or_default(),
        working: std::sync::Mutex::new(None),
        keys: spec.schedules.clone(),
        axes: axes(sc),
    };
    let build: Arc<FamilyBuilder> = Arc::new(move |values: &[f64]| {
        let ss = rebuild.model_at(values)?;
        Ok((super::verdict_run::with_weighted_outputs(&ss, &rebuild.axes)?.0, None))
    });
    let schedules = spec
        .schedules
        .iter()
        .map(|s| Schedule {
            name: format!("model.{}", s.key),
            unit: "SI".into(),
            profile: s.profile.clone(),
        })
        .collect();
    let fam = ScheduledSystem::new(schedules, build, &sc.model.description);
    Ok((Arc::new(fam), weighted))
}

impl Rebuild {
    /// The model's state space with the scheduled keys set to `values` (SI).
    fn model_at(&self, values: &[f64]) -> Result<StateSpace> {
        let mut guard = self.working.try_lock().ok();
        let mut copy;
        let t: &mut toml::Table = match guard.as_deref_mut() {
            Some(slot) => slot.get_or_insert_with(|| self.table.clone()),
            None => {
                copy = self.table.clone();
                &mut copy
            }
        };
        for (k, v) in self.keys.iter().zip(values) {
            let v = &match &k.rope {
                Some(r) => r
                    .value(*v)
                    .map_err(|e| file_error(&self.path, &format!("model.{}", k.key), v, &e.to_string()))?,
                None => *v,
            };
            super::sweep::set_key(t, &k.key, toml::Value::Float(*v))
                .map_err(|why| file_error(&self.path, &format!("model.{}", k.key), v, &why))?;
        }
        let f = Fields::new(&self.path, "model", t);
        let ctx = crate::scenario::ModelContext {
            speed: self.speed,
            several_inputs: false,
        };
        match crate::scenario::build_model(&self.kind, &f, ctx)? {
            crate::scenario::BuiltModel::Stochastic(m) => {
                m.system.state_space().cloned().ok_or_else(|| Error::NotApplicable {
                    method: "transient analysis".into(),
                    reason: "the scheduled model has no state-space form".into(),
                })
            }
            crate::scenario::BuiltModel::Deterministic(_) => Err(file_error(
                &self.path,
                "model.kind",
                &self.kind,
                "a deterministic model has no random input",
            )),
        }
    }
}

fn file_error(path: &Path, key: &str, value: impl std::fmt::Display, reason: &str) -> Error {
    Error::File {
        file: path.to_path_buf(),
        key: key.into(),
        value: value.to_string(),
        reason: reason.into(),
    }
}

/// The reported outputs (`[analysis] outputs`, then the weighted ones) and per comfort axis (its
/// acceleration output, its weighted output), from the weighted outputs' indices.
fn reported(sc: &Scenario, weighted: &[usize]) -> (Vec<usize>, Vec<(usize, usize)>) {
    let p = sc.model.system.outputs().len();
    let weighted: Vec<(usize, usize)> = weighted
        .iter()
        .enumerate()
        .map(|(j, &w)| (sc.analysis.verdicts.comfort.as_ref().map_or(0, |c| c.axes[j].output), w))
        .collect();
    let mut outputs: Vec<usize> = sc.analysis.outputs.iter().copied().filter(|i| *i < p).collect();
    outputs.extend(weighted.iter().map(|w| w.1));
    (outputs, weighted)
}

/// Refuses a model with nonlinear elements.
fn require_linear(sc: &Scenario) -> Result<()> {
    if sc.nonlinear.is_some() {
        return Err(Error::NotApplicable {
            method: "transient analysis".into(),
            reason: "the model has [[model.nonlinear]] elements: the transient routes are linear".into(),
        });
    }
    Ok(())
}

/// The scenario set up for the transient routes.
///
/// # Errors
/// A scenario without `[transient] duration`; nonlinear elements; several sources or wheels at different
/// positions; an input without an exact route (the library's reason); a schedule under which the system
/// is unstable at some time (file, key `transient.schedule`, the time and the eigenvalue); a step that gives
/// more than [`MAX_REPORTED_TIMES`] reported times (key `transient.step`). A reason that names no key is
/// given as the file's `transient` section.
pub fn transient_setup(sc: &Scenario) -> Result<TransientSetup> {
    setup_of(sc).map_err(|e| match e {
        e @ (Error::File { .. } | Error::Io { .. } | Error::Parse { .. }) => e,
        // a reason of the library (no exact route for this input, nonlinear elements) is the section's
        other => file_error(&sc.path, "transient", "[transient]", &other.to_string()),
    })
}

/// Most reported times of a transient analysis (the exact route keeps its moments at each of them, the Monte
/// Carlo route its accumulators): 10⁶, some tens of MB for a few outputs.
pub const MAX_REPORTED_TIMES: f64 = 1e6;

/// The reported times of `spec` over `duration`, refused beyond [`MAX_REPORTED_TIMES`] (naming the step,
/// the count and the cap) before anything is allocated.
fn checked_times(sc: &Scenario, spec: &TransientSpec, duration: f64) -> Result<Vec<f64>> {
    let count = spec.step.map(|s| (duration / s).round());
    if let (Some(s), Some(n)) = (spec.step, count)
        && (n.is_nan() || n > MAX_REPORTED_TIMES)
    {
        return Err(file_error(
            &sc.path,
            "transient.step",
            format!("{s} s"),
            &format!(
                "{n:e} reported times over the duration {duration} s: more than the {MAX_REPORTED_TIMES:e} the \
                 transient routes keep in memory; give a longer step or a shorter duration"
            ),
        ));
    }
    Ok(report_times(duration, spec.step))
}

fn setup_of(sc: &Scenario) -> Result<TransientSetup> {
    let (spec, duration) = spec_of(sc)?;
    require_linear(sc)?;
    let (fam, weighted) = family(sc, spec)?;
    let times = checked_times(sc, spec, duration)?;
    let mut check: Vec<f64> = times.clone();
    check.extend(fam.knots().into_iter().filter(|t| *t <= duration));
    check_stability(fam.as_ref(), &check).map_err(|e| unstable(sc, spec, e))?;
    let speed = speed_of(sc, spec)?;
    let sys = sources_system(sc, spec, fam, speed.as_ref())?;
    let (outputs, weighted) = reported(sc, &weighted);
    let stationary = sys.is_invariant() && spec.start == Start::Stationary;
    Ok(TransientSetup {
        sys,
        outputs,
        weighted,
        start: spec.start.clone(),
        times,
        options: ExactOptions {
            rel_tol: spec.rel_tol.unwrap_or(ExactOptions::default().rel_tol),
            ..ExactOptions::default()
        },
        stationary,
    })
}

/// An instability found on the schedule (or the fixed model) as a file error naming the time.
fn unstable(sc: &Scenario, spec: &TransientSpec, e: Error) -> Error {
    match e {
        Error::InvalidParameter { name, value, reason } => {
            let key = if spec.schedules.is_empty() {
                "model"
            } else {
                "transient.schedule"
            };
            file_error(&sc.path, key, value, &format!("{name}: {reason}"))
        }
        other => other,
    }
}

/// Solves the exact route of `setup` at its reported times.
///
/// # Errors
/// The errors of [`solve`] (a stationary start of a system without a stationary state, a stated state of
/// the wrong length).
pub fn exact_solution(sc: &Scenario, setup: &TransientSetup) -> Result<TransientSolution> {
    solve(&setup.sys, &setup.start, &setup.times, &setup.options).map_err(|e| match e {
        Error::InvalidParameter { name, value, reason } if name == "state" => {
            file_error(&sc.path, "transient.state", value, &reason)
        }
        Error::NotApplicable { method, reason } if method == "stationary start" => {
            file_error(&sc.path, "transient.start", "stationary", &reason)
        }
        other => other,
    })
}

/// Whether the scenario's input has an exact (differential Lyapunov) route: a rational or white input, a
/// rational road, a w = 2 road without a band (for several sources: every one). A road under wheels at
/// different positions or on two tracks has none (`stochvib transient --monte-carlo` takes the road grid);
/// otherwise `stochvib transient` takes the evolutionary route.
///
/// # Errors
/// A scenario without `[transient] duration`; an invalid speed profile.
pub fn has_exact_route(sc: &Scenario) -> Result<bool> {
    let (spec, _) = spec_of(sc)?;
    let speed = speed_of(sc, spec)?;
    if sc.inputs.len() == 1 && speed.is_some() && matches!(wheel_road(sc), Ok(Some(_))) {
        return Ok(false); // a road under wheels at positions or on two tracks: the road grid
    }
    Ok(sc.inputs.iter().all(|inp| {
        !matches!(
            input_model(inp.spectrum.as_ref(), speed.as_ref()),
            Err(Error::NotApplicable { .. })
        )
    }))
}

/// A scenario solved by the evolutionary-spectrum route ([`solve_evolutionary`]).
#[derive(Debug, Clone)]
pub struct EvolutionarySetup {
    /// The solution (NaN where its error estimate exceeds the threshold).
    pub solution: EvolutionarySolution,
    /// The reported outputs, as [`TransientSetup::outputs`].
    pub outputs: Vec<usize>,
    /// The comfort axes, as [`TransientSetup::weighted`].
    pub weighted: Vec<(usize, usize)>,
    /// The model, its schedules and its input in one line.
    pub description: String,
}

/// The evolutionary route of a scenario whose input has no exact route (tabulated, measured, band-limited
/// spectra): the frozen system at every reported time under the input's evolutionary spectrum, with the
/// threshold `[transient] max_error` on its error estimate (default
/// [`crate::transient::evolutionary::DEFAULT_MAX_ERROR`]).
///
/// # Errors
/// The layout and stability errors of [`transient_setup`]; the errors of [`solve_evolutionary`] (no time where
/// the slow-variation assumption holds: "not available: use Monte Carlo"; a stated start).
pub fn evolutionary_setup(sc: &Scenario) -> Result<EvolutionarySetup> {
    let (spec, duration) = spec_of(sc)?;
    require_linear(sc)?;
    let gains = gains(sc)?;
    let (fam, weighted) = family(sc, spec)?;
    let times = report_times(duration, spec.step);
    let input = EvolutionaryInput {
        spectrum: sc.input.spectrum.clone(),
        speed: speed_of(sc, spec)?,
        envelope: spec.envelope.clone(),
        mean: sc.input.mean,
        gains,
    };
    let max_error = spec
        .max_error
        .unwrap_or(crate::transient::evolutionary::DEFAULT_MAX_ERROR);
    let solution = solve_evolutionary(fam.as_ref(), &input, &spec.start, &times, max_error).map_err(|e| match e {
        Error::NotApplicable { method, reason } if reason.starts_with("a stated start") => {
            file_error(&sc.path, "transient.state", "<state>", &format!("{method}: {reason}"))
        }
        other => other,
    })?;
    let (outputs, weighted) = reported(sc, &weighted);
    Ok(EvolutionarySetup {
        solution,
        outputs,
        weighted,
        description: format!("{}; {} (no exact route)", fam.describe(), sc.input.spectrum.describe()),
    })
}

/// The wheels of the scenario's one road when they are at different positions or on two tracks (the
/// road-grid route reads the road under each, [`WheelRoad`]), or `None` for one contact position.
///
/// # Formula
/// Wheel j of the stationary excitation, delayed by τ_j at the stationary speed v, is at ℓ_j = vτ_j on the
/// road; two tracks keep their coherence, taken from the excitation's spectral matrix at v
/// ([`MatrixCoherence`]).
///
/// # Errors
/// Several `[[input]]` sources (the road-grid route takes one road).
pub fn wheel_road(sc: &Scenario) -> Result<Option<WheelRoad>> {
    use crate::response::{Excitation, Source};
    let spectrum = sc.input.spectrum.clone();
    let v = sc.input.speed.unwrap_or(1.0);
    let road = |coherence: Option<Arc<dyn crate::coherence::Coherence>>, wheels: Vec<Wheel>| {
        let moved = wheels.iter().any(|w| w.position != wheels[0].position);
        (moved || coherence.is_some()).then(|| WheelRoad {
            spectrum: spectrum.clone(),
            coherence,
            wheels,
        })
    };
    match (&sc.excitation, &sc.model.layout) {
        (Excitation::Sources { sources, inputs }, _) if sources.len() == 1 => {
            let coherence: Option<Arc<dyn crate::coherence::Coherence>> = match &sources[0] {
                Source::Matrix(m) => Some(Arc::new(MatrixCoherence::new(m.clone(), v)?)),
                Source::Process(_) => None,
            };
            let wheels = inputs
                .iter()
                .map(|m| Wheel {
                    track: m.component,
                    position: m.delay * v,
                    gain: m.gain,
                })
                .collect();
            Ok(road(coherence, wheels))
        }
        (Excitation::Sources { .. }, _) => Err(Error::NotApplicable {
            method: "road-grid Monte Carlo".into(),
            reason: "several [[input]] sources: it takes one road (of one or two tracks)".into(),
        }),
        (_, InputLayout::Track { positions, gains }) => Ok(road(
            None,
            positions
                .iter()
                .zip(gains)
                .map(|(&position, &gain)| Wheel {
                    track: 0,
                    position,
                    gain,
                })
                .collect(),
        )),
        _ => Ok(None),
    }
}

/// A scenario set up for the road-grid Monte Carlo ([`crate::transient::run_road_grid`]).
#[derive(Debug, Clone)]
pub struct RoadGridSetup {
    /// The model with the weighted outputs appended, its inputs combined into one (the road under the
    /// wheels, B·g and D·g with the layout's gains g).
    pub ss: StateSpace,
    /// v(t).
    pub speed: SpeedProfile,
    /// The reported outputs, as [`TransientSetup::outputs`].
    pub outputs: Vec<usize>,
    /// The reported times.
    pub times: Vec<f64>,
    /// The model's own states (the first of `ss`'s states; the comfort weighting filters follow).
    pub model_states: usize,
    /// The upper edge of the road's band, rad/m (∞ for a road without one).
    pub band_edge: f64,
    /// The wheels at positions or on two tracks (then `ss` keeps one input per wheel), or `None` (one
    /// contact position: the inputs combined into one).
    pub wheels: Option<WheelRoad>,
}

/// The scenario set up for the road-grid Monte Carlo: a road (spatial spectrum) under a speed profile (or
/// the constant `[input] speed`), a fixed linear model with one contact position, no envelope, a zero mean,
/// and a stationary start (the run-in at v(0) > 0 puts every realization in its stationary state at t = 0).
///
/// # Errors
/// Each condition that does not hold, as a file error on the `transient` section with the reason; the
/// errors of [`transient_setup`] that do not concern the input's route.
pub fn road_grid_setup(sc: &Scenario) -> Result<RoadGridSetup> {
    road_grid_of(sc).map_err(|e| match e {
        e @ (Error::File { .. } | Error::Io { .. } | Error::Parse { .. }) => e,
        other => file_error(&sc.path, "transient", "[transient]", &other.to_string()),
    })
}

fn road_grid_of(sc: &Scenario) -> Result<RoadGridSetup> {
    let (spec, duration) = spec_of(sc)?;
    require_linear(sc)?;
    let refuse = |reason: &str| Error::NotApplicable {
        method: "road-grid Monte Carlo".into(),
        reason: reason.into(),
    };
    let speed = speed_of(sc, spec)?.filter(|_| sc.input.spectrum.domain() == crate::spectrum::Domain::Spatial);
    let speed = speed.ok_or_else(|| refuse("it takes a road (spatial) spectrum under a speed or a speed profile"))?;
    if !spec.schedules.is_empty() || !spec.envelope.is_unit() || sc.input.mean != 0.0 {
        return Err(refuse(
            "it takes a fixed model (no [[transient.schedule]]), no envelope and a zero-mean road",
        ));
    }
    if spec.start != Start::Stationary {
        return Err(refuse(
            "it starts every realization in its stationary state at v(0) (a run-in): give start = \"stationary\"",
        ));
    }
    let wheels = wheel_road(sc)?;
    let (fam, weighted) = family(sc, spec)?;
    let ext = fam.at(0.0)?.ss;
    if wheels.is_some() {
        let (outputs, _) = reported(sc, &weighted);
        return Ok(RoadGridSetup {
            ss: ext,
            speed,
            outputs,
            times: checked_times(sc, spec, duration)?,
            model_states: sc.model.system.state_space().map_or(0, |m| m.n_states()),
            band_edge: sc.input.spectrum.support().1,
            wheels,
        });
    }
    let g = gains(sc)?;
    let g = nalgebra::DMatrix::from_column_slice(g.len(), 1, &g);
    let b = &ext.b * &g;
    let d = &ext.d * &g;
    let e = &ext.e * &g;
    let ss = StateSpace::new(
        ext.a.clone(),
        b,
        ext.c.clone(),
        Some(d),
        Some(e),
        crate::system::FrequencyResponse::outputs(&ext).to_vec(),
    )?;
    let (outputs, _) = reported(sc, &weighted);
    Ok(RoadGridSetup {
        ss,
        speed,
        outputs,
        times: checked_times(sc, spec, duration)?,
        model_states: sc.model.system.state_space().map_or(0, |m| m.n_states()),
        band_edge: sc.input.spectrum.support().1,
        wheels: None,
    })
}
