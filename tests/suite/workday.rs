//! The daily exposure of a working day of several tasks (`stochvib workday`): per axis
//! A(8) = √(Σ (k a_w,i)² T_i / 8 h) and VDV = (Σ VDV_i⁴)^{1/4} with the health factors (ISO 2631-1:1997 6.3.2,
//! Annex B; Directive 2002/44/EC Annex B), against the formulas evaluated here from per-task values obtained
//! independently, and the refusal of bad workday files (file, key, value, reason; nothing printed).
//!
//! Provenance of the per-task values: the seat tasks' a_w by the product-form integral of
//! `verdict_traps::seat_a_w` (ISO 2631-1 Annex A weightings times the model's frequency response and input
//! density; no state space); the scraper task at 6 m/s by `verdict_analysis` of the scenario text with its
//! speed replaced here (not by the workday's own speed override).

use super::verdict_traps::{seat_a_w, two_axis_text};
use crate::common;
use crate::common::SpawnSerial;
use common::tolerance::QUADRATURE;
use common::{rel, root};
use std::path::{Path, PathBuf};
use stochvib::comfort::{Axis, Weighting};
use stochvib::scenario::workday_file::{load_workday, parse_workday};
use stochvib::scenario::{load_scenario, parse_scenario};
use stochvib::study::verdict_analysis;
use stochvib::study::workday::workday_exposure;

const T0: f64 = 8.0 * 3600.0;

fn temp_dir(tag: &str) -> PathBuf {
    crate::common::scratch_kept("workday", tag)
}

fn data(f: &str) -> String {
    root().join("data").join(f).display().to_string()
}

/// A workday of three tasks: the two-axis seat (comfort purpose) 3 h, the catalogue seat 2.5 h, the
/// scraper cab at 6 m/s (its file says 10 m/s) 1 h.
fn three_tasks(dir: &Path) -> PathBuf {
    std::fs::write(dir.join("two-axis-seat.toml"), two_axis_text("comfort")).unwrap();
    let day = format!(
        "title = \"three tasks\"\n\
         [[task]]\nname = \"two axes\"\nscenario = \"two-axis-seat.toml\"\nduration = \"3 h\"\n\
         [[task]]\nscenario = \"{}\"\nduration = \"150 min\"\n\
         [[task]]\nname = \"scraper, slow\"\nscenario = \"{}\"\nspeed = \"6 m/s\"\nduration = \"1 h\"\n",
        data("operator-seat-verdicts.toml"),
        data("scraper-cab-comfort.toml")
    );
    let p = dir.join("day.toml");
    std::fs::write(&p, day).unwrap();
    p
}

#[test]
fn a_day_of_tasks_combines_a8_and_vdv_per_axis_as_the_standard() {
    let dir = temp_dir("three");
    let day = load_workday(&three_tasks(&dir)).unwrap();
    let e = workday_exposure(&day, &root().join("spectra")).unwrap();
    // per-task values, independently
    let seat2 = load_scenario(
        &root().join("data/operator-seat-verdicts.toml"),
        &root().join("spectra"),
    )
    .unwrap();
    let seat1 = parse_scenario(&two_axis_text("comfort"), &dir.join("x.toml"), &root().join("spectra")).unwrap();
    let (x1, z1, z2) = (
        seat_a_w(&seat1, Weighting::Wd),
        seat_a_w(&seat1, Weighting::Wk),
        seat_a_w(&seat2, Weighting::Wk),
    );
    let scraper_text = std::fs::read_to_string(root().join("data/scraper-cab-comfort.toml")).unwrap();
    assert!(scraper_text.contains("speed = \"10 m/s\""));
    let slow = parse_scenario(
        &scraper_text.replace("speed = \"10 m/s\"", "speed = \"6 m/s\""),
        &root().join("data/scraper-cab-comfort.toml"),
        &root().join("spectra"),
    )
    .unwrap();
    let z3 = verdict_analysis(&slow).unwrap().comfort.unwrap().axes[0].a_w;
    let (t1, t2, t3) = (3.0 * 3600.0, 2.5 * 3600.0, 3600.0);
    // A(8)_x = √((1.4 a_wx)² T1/T0): only task 1 has x; A(8)_z = √(Σ a_wz,i² T_i/T0)
    let a8x = ((1.4 * x1).powi(2) * t1 / T0).sqrt();
    let a8z = ((z1 * z1 * t1 + z2 * z2 * t2 + z3 * z3 * t3) / T0).sqrt();
    // VDV_z = (Σ ((3T_i)^{1/4} a_wz,i)⁴)^{1/4}
    let vdv = |a: f64, t: f64| (3.0 * t).powf(0.25) * a;
    let vdvx = vdv(1.4 * x1, t1);
    let vdvz = (vdv(z1, t1).powi(4) + vdv(z2, t2).powi(4) + vdv(z3, t3).powi(4)).powf(0.25);
    let axis = |a: Axis| e.axes.iter().find(|d| d.axis == a).unwrap();
    assert_eq!(e.axes.len(), 2, "x and z");
    assert!(rel(axis(Axis::X).a8, a8x) < QUADRATURE, "{} vs {a8x}", axis(Axis::X).a8);
    assert!(rel(axis(Axis::Z).a8, a8z) < QUADRATURE, "{} vs {a8z}", axis(Axis::Z).a8);
    assert!(rel(axis(Axis::X).vdv, vdvx) < QUADRATURE);
    assert!(rel(axis(Axis::Z).vdv, vdvz) < QUADRATURE);
    // the day's values are the highest axis'
    assert!(rel(e.verdict.a8, a8x.max(a8z)) < QUADRATURE);
    assert!(rel(e.verdict.vdv.unwrap(), vdvx.max(vdvz)) < QUADRATURE);
    assert_eq!(e.dominant_a8, if a8x > a8z { Axis::X } else { Axis::Z });
    // the task at its own speed, and the per-task rows
    assert_eq!(e.tasks[2].speed_m_s, Some(6.0));
    assert_eq!(e.tasks[1].task.name, "operator-seat-verdicts");
    assert_eq!(e.total_duration_s, t1 + t2 + t3);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn two_tasks_of_one_kind_equal_one_task_of_their_summed_duration() {
    // closed form: Σ a² T_i = a² ΣT_i and Σ 3T_i a⁴ = 3(ΣT_i) a⁴, so splitting a task changes nothing
    let dir = temp_dir("split");
    let seat = data("operator-seat-verdicts.toml");
    let write = |name: &str, tasks: &[&str]| {
        let body: String = tasks
            .iter()
            .map(|d| format!("[[task]]\nscenario = \"{seat}\"\nduration = \"{d}\"\n"))
            .collect();
        let p = dir.join(name);
        std::fs::write(&p, body).unwrap();
        workday_exposure(&load_workday(&p).unwrap(), &root().join("spectra")).unwrap()
    };
    let split = write("split.toml", &["2 h", "3 h"]);
    let whole = write("whole.toml", &["5 h"]);
    assert!(rel(split.verdict.a8, whole.verdict.a8) < QUADRATURE);
    assert!(rel(split.verdict.vdv.unwrap(), whole.verdict.vdv.unwrap()) < QUADRATURE);
    std::fs::remove_dir_all(&dir).unwrap();
}

fn refused(text: &str, parts: &[&str]) {
    let dir = temp_dir("bad");
    let p = dir.join("bad-day.toml");
    std::fs::write(&p, text).unwrap();
    let e = match parse_workday(text, &p) {
        Err(e) => e.to_string(),
        Ok(day) => workday_exposure(&day, &root().join("spectra")).unwrap_err().to_string(),
    };
    for part in ["bad-day.toml"].iter().chain(parts) {
        assert!(e.contains(part), "`{part}` not in: {e}");
    }
    // the command prints nothing to stdout and fails
    let o = std::process::Command::new(crate::common::cli_bin())
        .args(["workday", p.to_str().unwrap()])
        .current_dir(root())
        .output_serial()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(o.stdout.is_empty());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_workday_files_are_refused_with_file_key_value_and_reason() {
    let seat = data("operator-seat-verdicts.toml");
    let task = |extra: &str| format!("[[task]]\nscenario = \"{seat}\"\n{extra}\n");
    refused(&task("duration = 5"), &["task[0].duration", "duration = \"5 h\""]);
    refused(&task("duration = \"0.5 s\""), &["task[0].duration", "implausible"]);
    refused(
        &(task("duration = \"10 h\"") + &task("duration = \"10 h\"") + &task("duration = \"5 h\"")),
        &["task[2].duration", "5 h", "25 h", "24 h"],
    );
    refused(
        &task("duration = \"2 h\"\nspeed = \"-3 m/s\""),
        &["task[0].speed", "> 0"],
    );
    // the seat's input is a cab-floor motion in time: a speed would silently change nothing
    refused(
        &task("duration = \"2 h\"\nspeed = \"5 m/s\""),
        &["task[0].speed", "5 m/s", "not a road"],
    );
    refused(
        &task("duration = \"2 h\"\ndurtion = \"1 h\""),
        &["task[0].durtion", "unknown key"],
    );
    refused("title = \"no tasks\"\n", &["task", "missing"]);
    refused(
        "[[task]]\nscenario = \"no-such-file.toml\"\nduration = \"1 h\"\n",
        &["task[0].scenario", "no-such-file.toml"],
    );
    refused(
        &format!(
            "[[task]]\nscenario = \"{}\"\nduration = \"1 h\"\n",
            data("quarter-car.toml")
        ),
        &["task[0].scenario", "quarter-car.toml", "[analysis.comfort]"],
    );
    // an error inside the task's scenario names the task and the scenario's own file and key
    let dir = temp_dir("inner");
    let inner = dir.join("bare-exposure.toml");
    let text = std::fs::read_to_string(&seat)
        .unwrap()
        .replace("exposure = \"6 h\"", "exposure = 6");
    std::fs::write(&inner, text).unwrap();
    refused(
        &format!("[[task]]\nscenario = \"{}\"\nduration = \"1 h\"\n", inner.display()),
        &[
            "task[0].scenario",
            "bare-exposure.toml",
            "analysis.comfort.exposure",
            "exposure = \"6 h\"",
        ],
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_workday_command_prints_text_markdown_and_json() {
    let run = |args: &[&str]| {
        let o = std::process::Command::new(crate::common::cli_bin())
            .args(args)
            .current_dir(root())
            .output_serial()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap()
    };
    let f = "data/workday/scraper-operator.toml";
    let text = run(&["workday", f]);
    for part in [
        "haul, loaded",
        "return, empty",
        "A(8) [m/s²]",
        "Directive 2002/44/EC  A(8)",
        "verdict:",
    ] {
        assert!(text.contains(part), "`{part}` not in:\n{text}");
    }
    let md = run(&["workday", f, "--format", "markdown"]);
    assert!(
        md.contains("| task | scenario |") && md.contains("|---|---|---:|"),
        "{md}"
    );
    let j: serde_json::Value = serde_json::from_str(&run(&["workday", f, "--json"])).unwrap();
    assert_eq!(j["tasks"].as_array().unwrap().len(), 3);
    assert_eq!(j["tasks"][0]["axes"][0]["axis"], "z");
    assert!(j["verdict"]["a8"].as_f64().unwrap() > 0.0);
    let j2: serde_json::Value = serde_json::from_str(&run(&["workday", f, "--format", "json"])).unwrap();
    assert_eq!(j, j2);
}
