//! Reading a workday file (`stochvib workday FILE`): a working day made of several tasks, each a scenario
//! file with its daily duration and optionally another speed; and the scenario of a task at its speed. What
//! the day's exposure is, is computed by [`crate::study::workday`].
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

use super::scenario_file::{load_scenario, parse_scenario, Scenario};
use crate::error::{Error, Result};
use crate::fields::{read_text_file, EverydayUnit, Fields};
use crate::units::Dim;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Longest working day, s: the tasks of one day add up to at most 24 h.
pub const MAX_DAY_S: f64 = crate::comfort::MAX_DAILY_EXPOSURE_S;

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
/// use stochvib::scenario::workday_file::load_workday;
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

impl Workday {
    /// The scenario of task `i`, at the task's speed, with the spectrum names resolved in `spectra_dir`.
    ///
    /// # Errors
    /// The scenario's errors, named by the task's key (`task[i].scenario`) with the scenario's own file and key
    /// in the reason.
    pub fn task_scenario(&self, i: usize, spectra_dir: &Path) -> Result<Scenario> {
        let (day, task) = (self, &self.tasks[i]);
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
