//! The daily exposure of a working day made of several tasks (`stochvib workday FILE`): each task a scenario
//! with its `[analysis.comfort]` axes (optionally at another speed) and its daily duration, combined as ISO
//! 2631-1:1997 and Directive 2002/44/EC do, per axis with the health factors.
//!
//! # Format
//! ```toml
//! title = "Scraper operator, one shift"     # optional
//! [[task]]
//! name = "haul road"                        # optional (default: the scenario file's name)
//! scenario = "scraper-cab-comfort.toml"     # a scenario file with [analysis.comfort], relative to this file
//! speed = "8 m/s"                           # optional: the task's speed (replaces the scenario's)
//! duration = "5 h"                          # the task's daily duration, with its unit
//! [[task]]
//! scenario = "operator-seat-verdicts.toml"
//! duration = "90 min"
//! ```
//! The scenarios' own `exposure` is not used: each task lasts its `duration`. Every key is checked; a bare
//! number for `duration` is refused (it would be seconds), as are a duration under 1 s, tasks adding up to
//! more than 24 h, a scenario without `[analysis.comfort]` or without an axis that enters the Directive's
//! evaluation, a speed ≤ 0 or a speed for a scenario whose input is not a road — naming the workday file,
//! the key (`task[i].duration`), the value and the reason. An error inside a task's scenario names the task
//! and the scenario's own file and key.
//!
//! # Formula
//! Per task i and axis j ∈ {x, y, z}: the health-weighted a_w,ij (Wd for x, y; Wk for z) with the health
//! factor k_j (1.4, 1.4, 1; [`crate::comfort::directive_factor`]), computed exactly as `stochvib analyze`
//! does ([`verdict_analysis`](super::verdict_analysis())). Then (ISO 2631-1:1997 6.3.2 and Annex B; Directive
//! 2002/44/EC Annex B 1; UK Control of Vibration at Work Regulations 2005, Schedule 2):
//!
//! ```text
//! A(8)_j = √( Σ_i (k_j a_w,ij)² T_i / T₀ ),  T₀ = 8 h;          A(8) = max_j A(8)_j
//! VDV_ij = (3 T_i)^(1/4) k_j a_w,ij  (stationary Gaussian);     VDV_j = (Σ_i VDV_ij⁴)^(1/4);  VDV = max_j VDV_j
//! ```
//! and the day's A(8) and VDV are judged against the Directive's action and limit values and the Annex B
//! zones ([`ExposureVerdict`]).

use crate::comfort::{
    daily_exposure_a8_periods, vdv_gaussian, vdv_total, Axis, DirectiveLimits, ExposurePeriod, ExposureVerdict,
    HealthGuidanceZone,
};
use crate::error::{Error, Result};
use crate::fields::{read_text_file, EverydayUnit, Fields};
use crate::scenario::scenario_file::{load_scenario, parse_scenario, Scenario};
use crate::spectrum::Domain;
use crate::units::Dim;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Longest working day, s: the tasks of one day add up to at most 24 h.
pub const MAX_DAY_S: f64 = 24.0 * 3600.0;

/// One task of a working day, as written.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkdayTask {
    /// Name of the task.
    pub name: String,
    /// The scenario file as written in the workday file.
    pub scenario: String,
    /// The scenario file resolved against the workday file's directory.
    pub scenario_path: PathBuf,
    /// The task's speed, m/s, if given (replaces the scenario's).
    pub speed_m_s: Option<f64>,
    /// The task's daily duration, s.
    pub duration_s: f64,
}

/// A working day: its tasks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Workday {
    /// The workday file.
    pub path: PathBuf,
    /// Title.
    pub title: String,
    /// The tasks, in order.
    pub tasks: Vec<WorkdayTask>,
}

/// Reads a workday file (see the module docs).
///
/// # Errors
/// [`Error::Io`]/[`Error::Parse`] for an unreadable or non-TOML file; [`Error::File`] naming the key, the value
/// and the reason for a bad or missing key.
///
/// # Examples
/// ```
/// use stochvib::study::workday::load_workday;
/// let day = load_workday(std::path::Path::new("data/workday/scraper-operator.toml")).unwrap();
/// assert_eq!(day.tasks.len(), 3);
/// ```
pub fn load_workday(path: &Path) -> Result<Workday> {
    parse_workday(&read_text_file(path)?, path)
}

/// Parses workday text read from `path` (scenario paths resolve against `path`'s directory).
///
/// # Errors
/// As [`load_workday`].
pub fn parse_workday(text: &str, path: &Path) -> Result<Workday> {
    let root = crate::fields::parse_toml(text, path)?;
    let f = Fields::new(path, "", &root);
    let stem = path
        .file_stem()
        .map_or("working day".into(), |s| s.to_string_lossy().into_owned());
    let title = f.opt_string("title")?.map_or(stem, str::to_string);
    let tasks = match f.require("task")? {
        toml::Value::Array(a) if !a.is_empty() => a,
        v => return Err(f.error("task", v, "expected one or more [[task]] tables")),
    };
    let mut out: Vec<WorkdayTask> = Vec::new();
    for (i, v) in tasks.iter().enumerate() {
        let key = format!("task[{i}]");
        let t = v.as_table().ok_or_else(|| f.error(&key, v, "expected a table"))?;
        let task = parse_task(&Fields::new(path, &key, t))?;
        let total: f64 = out.iter().map(|t| t.duration_s).sum::<f64>() + task.duration_s;
        if total > MAX_DAY_S {
            return Err(f.error(
                &format!("{key}.duration"),
                EverydayUnit::HOUR.show(task.duration_s),
                format!(
                    "the tasks add up to {} with this one, more than the 24 h of a day",
                    EverydayUnit::HOUR.show(total)
                ),
            ));
        }
        out.push(task);
    }
    f.finish()?;
    Ok(Workday {
        path: path.to_path_buf(),
        title,
        tasks: out,
    })
}

fn parse_task(f: &Fields) -> Result<WorkdayTask> {
    let scenario = f.string("scenario")?.to_string();
    let scenario_path = match f.file().parent() {
        Some(dir) => dir.join(&scenario),
        None => PathBuf::from(&scenario),
    };
    let name = match f.opt_string("name")? {
        Some(n) => n.to_string(),
        None => Path::new(&scenario)
            .file_stem()
            .map_or(scenario.clone(), |s| s.to_string_lossy().into_owned()),
    };
    let duration_s = f.everyday_quantity("duration", EverydayUnit::HOUR)?;
    f.at_least(
        "duration",
        duration_s,
        1.0,
        EverydayUnit::HOUR,
        "a task lasts at least a second; write e.g. duration = \"2 h\"",
    )?;
    let speed_m_s = f.opt_quantity("speed", Dim::VELOCITY)?;
    if let Some(v) = speed_m_s
        && v <= 0.0
    {
        return Err(f.error("speed", f.require("speed")?, "a speed must be > 0"));
    }
    f.finish()?;
    Ok(WorkdayTask {
        name,
        scenario,
        scenario_path,
        speed_m_s,
        duration_s,
    })
}

/// One axis of one task: k·a_w with the health factors.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskAxis {
    /// The axis (`x`, `y`, `z`).
    pub axis: Axis,
    /// The weighted output it was computed from (`<output>_<W>`).
    pub output: String,
    /// The health factor k.
    pub k: f64,
    /// a_w with the health weighting, m/s².
    pub a_w: f64,
    /// k·a_w, m/s².
    pub weighted: f64,
    /// This task's share of the day's A(8) on this axis, k·a_w·√(T_i/8 h), m/s².
    pub a8: f64,
    /// This task's VDV on this axis, (3T_i)^{1/4}·k·a_w, m/s^1.75.
    pub vdv: f64,
}

/// One task answered.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskExposure {
    /// The task as written.
    pub task: WorkdayTask,
    /// The scenario's title.
    pub scenario_title: String,
    /// The speed used, m/s (the task's or the scenario's), if the input has one.
    pub speed_m_s: Option<f64>,
    /// Per axis of the Directive's evaluation.
    pub axes: Vec<TaskAxis>,
}

/// One axis of the day.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DayAxis {
    /// The axis.
    pub axis: Axis,
    /// A(8) = √(Σ (k a_w,i)² T_i / 8 h), m/s².
    pub a8: f64,
    /// VDV = (Σ VDV_i⁴)^{1/4}, m/s^1.75.
    pub vdv: f64,
}

/// The daily exposure of a working day.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkdayExposure {
    /// Title.
    pub title: String,
    /// The workday file.
    pub file: String,
    /// Total duration of the tasks, s.
    pub total_duration_s: f64,
    /// Per task.
    pub tasks: Vec<TaskExposure>,
    /// Per axis over the day (x, y, z, those any task has).
    pub axes: Vec<DayAxis>,
    /// The axis with the highest A(8).
    pub dominant_a8: Axis,
    /// The axis with the highest VDV.
    pub dominant_vdv: Axis,
    /// The day's A(8) and VDV (the highest over the axes) against Directive 2002/44/EC (whole-body values)
    /// and ISO 2631-1 Annex B.
    pub verdict: ExposureVerdict,
}

/// The scenario of `task`, at its speed.
fn task_scenario(day: &Workday, i: usize, spectra_dir: &Path) -> Result<Scenario> {
    let task = &day.tasks[i];
    let in_task = |e: Error| match e {
        // an error inside the scenario names its own file and key; the workday key says which task
        Error::File { .. } | Error::Io { .. } | Error::Parse { .. } => Error::File {
            file: day.path.clone(),
            key: format!("task[{i}].scenario"),
            value: task.scenario.clone(),
            reason: e.to_string(),
        },
        other => other,
    };
    let Some(v) = task.speed_m_s else {
        return load_scenario(&task.scenario_path, spectra_dir).map_err(in_task);
    };
    let text = read_text_file(&task.scenario_path).map_err(in_task)?;
    let mut root = crate::fields::parse_toml(&text, &task.scenario_path).map_err(in_task)?;
    set_speed(&mut root, v);
    let text = toml::to_string(&root).map_err(|e| in_task(Error::invalid("speed", v, e.to_string())))?;
    parse_scenario(&text, &task.scenario_path, spectra_dir).map_err(in_task)
}

/// Writes `speed` (m/s) where the scenario keeps its speed: `[road]`, `[input]`, or every `[[input]]` table
/// that has one (the first when none has).
fn set_speed(root: &mut toml::Table, speed: f64) {
    let value = toml::Value::String(format!("{speed} m/s"));
    let key = if root.get("road").is_some_and(toml::Value::is_table) {
        "road"
    } else {
        "input"
    };
    match root.get_mut(key) {
        Some(toml::Value::Table(t)) => {
            t.insert("speed".into(), value);
        }
        Some(toml::Value::Array(a)) => {
            let with: Vec<usize> = (0..a.len()).filter(|&j| a[j].get("speed").is_some()).collect();
            for j in if with.is_empty() { vec![0] } else { with } {
                if let Some(t) = a.get_mut(j).and_then(toml::Value::as_table_mut) {
                    t.insert("speed".into(), value.clone());
                }
            }
        }
        _ => {}
    }
}

/// The Directive's axes of task `i`.
fn task_exposure(day: &Workday, i: usize, spectra_dir: &Path) -> Result<TaskExposure> {
    let task = &day.tasks[i];
    let sc = task_scenario(day, i, spectra_dir)?;
    let refuse = |reason: String| Error::File {
        file: day.path.clone(),
        key: format!("task[{i}].scenario"),
        value: task.scenario.clone(),
        reason,
    };
    let road = sc.inputs.iter().any(|i| i.spectrum.domain() == Domain::Spatial);
    if task.speed_m_s.is_some() && !road {
        return Err(Error::File {
            file: day.path.clone(),
            key: format!("task[{i}].speed"),
            value: format!("{} m/s", crate::numbers::short(task.speed_m_s.unwrap_or_default())),
            reason: "the scenario's input is not a road (its spectrum is temporal): a speed would change nothing"
                .into(),
        });
    }
    let Some(spec) = &sc.analysis.verdicts.comfort else {
        return Err(refuse(
            "the scenario has no [analysis.comfort] section: name its acceleration outputs as ISO 2631-1 axes".into(),
        ));
    };
    let comfort = super::verdict_analysis::comfort_verdict(&sc, spec)?;
    let health = comfort
        .health
        .ok_or_else(|| refuse(comfort.health_note.unwrap_or_default()))?;
    let t = task.duration_s;
    let axes = health
        .axes
        .iter()
        .map(|a| {
            Ok(TaskAxis {
                axis: a.term.axis,
                output: a.output.clone(),
                k: a.term.k,
                a_w: a.term.a_w,
                weighted: a.term.weighted,
                a8: crate::comfort::daily_exposure_a8(a.term.weighted, t)?,
                vdv: vdv_gaussian(a.term.weighted, t)?,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(TaskExposure {
        task: task.clone(),
        scenario_title: sc.title.clone(),
        speed_m_s: sc.input.speed,
        axes,
    })
}

/// The day's A(8) and VDV of `axis` over the tasks that have it (`None` when none has).
fn day_axis(tasks: &[TaskExposure], axis: Axis) -> Result<Option<DayAxis>> {
    let rows: Vec<(f64, &TaskAxis)> = tasks
        .iter()
        .filter_map(|t| t.axes.iter().find(|a| a.axis == axis).map(|a| (t.task.duration_s, a)))
        .collect();
    if rows.is_empty() {
        return Ok(None);
    }
    let periods: Vec<ExposurePeriod> = rows
        .iter()
        .map(|(t, a)| ExposurePeriod {
            a_w: a.weighted,
            duration_s: *t,
        })
        .collect();
    let vdvs: Vec<f64> = rows.iter().map(|(_, a)| a.vdv).collect();
    Ok(Some(DayAxis {
        axis,
        a8: daily_exposure_a8_periods(&periods)?,
        vdv: vdv_total(&vdvs)?,
    }))
}

/// The daily exposure of `day` (see the module docs), with the scenario names resolved in `spectra_dir`.
///
/// # Formula
/// See the module docs.
///
/// # Errors
/// A task's scenario errors (named by the task's key), a scenario without an axis of the Directive's
/// evaluation, the numerical errors of the weighted outputs.
///
/// # Examples
/// ```no_run
/// use stochvib::study::workday::{load_workday, workday_exposure};
/// let day = load_workday(std::path::Path::new("data/workday/scraper-operator.toml")).unwrap();
/// let e = workday_exposure(&day, std::path::Path::new("spectra")).unwrap();
/// println!("A(8) = {} m/s² ({:?})", e.verdict.a8, e.dominant_a8);
/// ```
pub fn workday_exposure(day: &Workday, spectra_dir: &Path) -> Result<WorkdayExposure> {
    let tasks = (0..day.tasks.len())
        .map(|i| task_exposure(day, i, spectra_dir))
        .collect::<Result<Vec<_>>>()?;
    let mut axes = Vec::new();
    for axis in [Axis::X, Axis::Y, Axis::Z] {
        axes.extend(day_axis(&tasks, axis)?);
    }
    let top =
        |f: fn(&DayAxis) -> f64| (axes.iter().max_by(|a, b| f(a).total_cmp(&f(b)))).expect("every task has an axis");
    let (a8, vdv) = (top(|a| a.a8), top(|a| a.vdv));
    let verdict = ExposureVerdict::assess_with(
        a8.a8,
        Some(vdv.vdv),
        None,
        &DirectiveLimits::WHOLE_BODY,
        &HealthGuidanceZone::ISO_2631_1,
    )?;
    Ok(WorkdayExposure {
        title: day.title.clone(),
        file: day.path.display().to_string(),
        total_duration_s: day.tasks.iter().map(|t| t.duration_s).sum(),
        dominant_a8: a8.axis,
        dominant_vdv: vdv.axis,
        tasks,
        axes,
        verdict,
    })
}
