//! `stochvib sweep --verdicts`: every point's σ, a_w, a_v, A(8), VDV, damage rate and life against
//! `stochvib analyze --json` of the scenario file with the value written in by hand.

use crate::common;
use crate::common::tolerance::SWEEP_AGAINST_ANALYZE;
use serde_json::Value;
use std::time::Duration;

fn json_of(args: &[&str], cwd: &std::path::Path) -> Value {
    let o = common::cli_within(args, cwd, Duration::from_secs(300));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The operator seat with comfort and fatigue verdicts swept over the seat stiffness (5000 and 8000 N/m):
/// each row's swept value is the SI number in a column `model.stiffness [kg s^-2]`, and every quantity equals
/// what `analyze` prints for a copy of the scenario file whose `stiffness = "6500 N/m"` line is rewritten
/// to the point's value (the reader, the exact routes and the verdicts run on a file the sweep never saw).
#[test]
fn verdict_columns_equal_analyze_of_the_substituted_files() {
    let root = common::root();
    let base = std::fs::read_to_string(root.join("data/operator-seat-verdicts.toml")).unwrap();
    assert!(base.contains("stiffness = \"6500 N/m\""));
    let sweep = json_of(
        &[
            "sweep",
            "data/operator-seat-verdicts.toml",
            "--param",
            "model.stiffness=5000 N/m,8000 N/m",
            "--verdicts",
            "--json",
        ],
        &root,
    );
    let cols: Vec<&str> = sweep["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert_eq!(cols[1], "model.stiffness [kg s^-2]", "{cols:?}");
    let col = |name: &str| cols.iter().position(|c| c.starts_with(name)).unwrap() - 1; // values skip `point`
    let dir = common::scratch_dir("sweep-verdicts", "files");
    for (row, k) in sweep["rows"].as_array().unwrap().iter().zip([5000.0, 8000.0]) {
        let v = row["values"].as_array().unwrap();
        assert_eq!(num(&v[0]), k);
        let file = dir.join(format!("seat-{k}.toml"));
        std::fs::write(
            &file,
            base.replace("stiffness = \"6500 N/m\"", &format!("stiffness = \"{k} N/m\"")),
        )
        .unwrap();
        let a = json_of(&["analyze", file.to_str().unwrap(), "--json"], &root);
        let comfort = &a["verdicts"]["comfort"];
        let fatigue = &a["verdicts"]["fatigue"];
        let methods = fatigue["methods"].as_array().unwrap();
        let expected = [
            ("sigma(seat)", num(&a["outputs"][0]["statistics"]["sigma"])),
            ("sigma(travel)", num(&a["outputs"][1]["statistics"]["sigma"])),
            ("a_w(seat_acc)", num(&comfort["axes"][0]["a_w"])),
            ("a_v", num(&comfort["a_v"])),
            ("A8", num(&comfort["health"]["verdict"]["a8"])),
            ("VDV", num(&comfort["health"]["verdict"]["vdv"])),
            (
                "damage_rate",
                methods.iter().map(|m| num(&m["damage_rate"])).fold(0.0, f64::max),
            ),
            (
                "life",
                methods.iter().map(|m| num(&m["life_s"])).fold(f64::INFINITY, f64::min),
            ),
        ];
        for (name, want) in expected {
            let got = num(&v[col(name)]);
            assert!(
                common::rel(got, want) < SWEEP_AGAINST_ANALYZE,
                "{name} at {k} N/m: {got} vs analyze {want}"
            );
        }
    }
}

/// The CSV form: a header with the units, one line per point, numbers that read back.
#[test]
fn verdict_csv_has_units_in_the_header() {
    let root = common::root();
    let o = common::cli_within(
        &[
            "sweep",
            "data/operator-seat-verdicts.toml",
            "--param",
            "model.stiffness=5 kN/m,8 kN/m",
            "--verdicts",
        ],
        &root,
        Duration::from_secs(300),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8(o.stdout).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert!(
        header.starts_with("point,model.stiffness [kg s^-2],sigma(seat) [m],"),
        "{header}"
    );
    assert!(
        header.contains("a_v [m/s^2]") && header.contains("life [s]") && header.ends_with(",error"),
        "{header}"
    );
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(first[1].parse::<f64>().unwrap(), 5000.0);
    assert_eq!(lines.count(), 1);
}
