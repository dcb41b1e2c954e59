//! The daily exposure of a working day made of several tasks (`stochvib workday FILE`): each task a scenario
//! with its `[analysis.comfort]` axes (optionally at another speed) and its daily duration, combined as ISO
//! 2631-1:1997 and Directive 2002/44/EC do, per axis with the health factors.
//!
//! The workday file is read by [`crate::scenario::workday_file`] (its format is described there).
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
use crate::scenario::workday_file::Workday;
use crate::spectrum::Domain;
use serde::Serialize;
use std::path::Path;

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
    pub task: crate::scenario::workday_file::WorkdayTask,
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

/// The Directive's axes of task `i`.
fn task_exposure(day: &Workday, i: usize, spectra_dir: &Path) -> Result<TaskExposure> {
    let task = &day.tasks[i];
    let sc = day.task_scenario(i, spectra_dir)?;
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
/// use stochvib::scenario::workday_file::load_workday;
/// use stochvib::study::workday::workday_exposure;
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
