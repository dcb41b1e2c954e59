//! The `stochvib workday` report: per task its duration, speed and health-weighted k·a_w per axis with its
//! share of the day's A(8) and its VDV; per axis the day's A(8) and VDV; the verdict against Directive
//! 2002/44/EC and ISO 2631-1 Annex B ([`WorkdayExposure`]).

use super::table::{facts, Table, ToMarkdown};
use super::verdict_report::health_lines;
use crate::comfort::Axis;
use crate::fields::EverydayUnit;
use crate::numbers::sig4;
use crate::study::workday::{TaskExposure, WorkdayExposure};
use serde::Serialize;
use std::fmt;

/// The report of a working day (text, markdown, JSON: the [`WorkdayExposure`] itself).
#[derive(Debug, Clone, Serialize)]
#[serde(transparent)]
pub struct WorkdayReport(pub WorkdayExposure);

/// The per-task table: task, scenario, speed, duration, k·a_w of each axis, the task's VDV on its
/// dominant axis.
pub fn task_table(day: &WorkdayExposure) -> Table {
    let axes: Vec<Axis> = day.axes.iter().map(|a| a.axis).collect();
    let tasks = &day.tasks;
    let mut t = Table::default()
        .text("task", tasks.iter().map(|t| t.task.name.clone()))
        .text("scenario", tasks.iter().map(|t| t.task.scenario.clone()))
        .num("speed [m/s]", &tasks.iter().map(|t| t.speed_m_s).collect::<Vec<_>>())
        .num(
            "duration [h]",
            &tasks
                .iter()
                .map(|t| Some(t.task.duration_s / 3600.0))
                .collect::<Vec<_>>(),
        );
    for axis in axes {
        let k = tasks
            .iter()
            .find_map(|t| t.axes.iter().find(|a| a.axis == axis))
            .map_or(1.0, |a| a.k);
        let head = if k == 1.0 {
            format!("a_w{} [m/s²]", axis.label())
        } else {
            format!("{}·a_w{} [m/s²]", crate::numbers::num(k), axis.label())
        };
        let weighted = |t: &TaskExposure| t.axes.iter().find(|a| a.axis == axis).map(|a| a.weighted);
        t = t.num(&head, &tasks.iter().map(weighted).collect::<Vec<_>>());
    }
    let top = |t: &TaskExposure, f: fn(&crate::study::workday::TaskAxis) -> f64| {
        t.axes
            .iter()
            .map(f)
            .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))))
    };
    t.num(
        "A(8) share [m/s²]",
        &tasks.iter().map(|t| top(t, |a| a.a8)).collect::<Vec<_>>(),
    )
    .num(
        "VDV [m/s^1.75]",
        &tasks.iter().map(|t| top(t, |a| a.vdv)).collect::<Vec<_>>(),
    )
}

/// The per-axis table of the day.
pub fn day_table(day: &WorkdayExposure) -> Table {
    Table::default()
        .text("axis", day.axes.iter().map(|a| a.axis.label()))
        .num("A(8) [m/s²]", &day.axes.iter().map(|a| Some(a.a8)).collect::<Vec<_>>())
        .num(
            "VDV [m/s^1.75]",
            &day.axes.iter().map(|a| Some(a.vdv)).collect::<Vec<_>>(),
        )
}

/// The lines under the tables: formulas, dominant axes, the Directive and Annex B checks.
pub fn day_lines(day: &WorkdayExposure) -> Vec<String> {
    let mut out = vec![
        "per axis A(8) = √(Σ (k a_w)² T / 8 h) and VDV = (Σ VDV_i⁴)^(1/4), VDV_i = (3 T_i)^(1/4) k a_w (stationary \
         Gaussian); health factors k = 1.4, 1.4, 1 for x, y, z (Directive 2002/44/EC Annex B; ISO 2631-1 7.2.3)"
            .to_string(),
        format!(
            "A(8) share of a task: k a_w √(T/8 h) on its largest axis; the day's A(8) is {} m/s² (axis {}), its \
             VDV {} m/s^1.75 (axis {})",
            sig4(day.verdict.a8),
            day.dominant_a8.label(),
            sig4(day.verdict.vdv.unwrap_or(f64::NAN)),
            day.dominant_vdv.label()
        ),
    ];
    out.extend(health_lines(&day.verdict));
    out
}

impl fmt::Display for WorkdayReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let d = &self.0;
        writeln!(f, "working day  {}  ({})", d.title, d.file)?;
        writeln!(
            f,
            "tasks        {} adding up to {}",
            d.tasks.len(),
            EverydayUnit::HOUR.show(d.total_duration_s)
        )?;
        writeln!(f)?;
        write!(f, "{}", task_table(d).aligned("  "))?;
        writeln!(f)?;
        write!(f, "{}", day_table(d).aligned("  "))?;
        for l in day_lines(d) {
            writeln!(f, "  {l}")?;
        }
        Ok(())
    }
}

impl ToMarkdown for WorkdayReport {
    fn markdown(&self) -> String {
        let d = &self.0;
        let mut s = format!("# {}\n\n", d.title);
        s += &facts(&[
            ("workday file", format!("`{}`", d.file)),
            ("tasks", d.tasks.len().to_string()),
            ("total duration", EverydayUnit::HOUR.show(d.total_duration_s)),
        ]);
        s += &format!("\n## Tasks\n\n{}", task_table(d).markdown());
        s += &format!("\n## The day\n\n{}\n", day_table(d).markdown());
        s += &day_lines(d).iter().map(|l| format!("- {l}\n")).collect::<String>();
        s
    }
}
