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

/// The verdict columns travel with the study into every table form and through a cluster run: the
/// operator seat over three stiffnesses (5, 6.5 and 8 kN/m) with `--verdicts` written as an HDF5 table and
/// as two shard files merged into HDF5 and CSV.
///
/// Provenance: the values of `verdict_columns_equal_analyze_of_the_substituted_files` (the verdicts
/// against `analyze` of files written by hand) are the same computation; here
/// * the HDF5 `verdicts/<k>` column of σ(seat) and σ(travel) (each point's scenario read again and solved
///   by the exact evaluator) equals the table's own `outputs/<name>/sigma` (the sweep's numeric path, a
///   different route) within `SWEEP_AGAINST_ANALYZE`;
/// * every other verdict column equals the one-row-per-point table of `sweep_verdicts` bit for bit, and
///   the merged shards equal the whole table bit for bit (each point is evaluated alone, so a split into
///   parts cannot change it); the merged CSV is the whole study's verdict CSV byte for byte.
#[test]
fn verdict_columns_in_hdf5_and_in_merged_shards() {
    use stochvib::scenario::load_scenario;
    use stochvib::store::Part;
    use stochvib::study::{merge_sweep, run_sweep_shard, write_sweep_table, StreamOptions};
    use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec};
    let sc = load_scenario(
        &crate::common::root().join("data/operator-seat-verdicts.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap();
    let spec = || {
        let p = SweepParam::parse("model.stiffness=5 kN/m,6.5 kN/m,8 kN/m").unwrap();
        SweepSpec::new(vec![p], SweepMode::Grid).unwrap()
    };
    let sweep = Sweep::new(&sc, spec()).unwrap().with_verdicts().unwrap();
    let want = stochvib::study::sweep_verdicts::sweep_verdicts(&sweep).unwrap();
    assert!(want.rows.iter().all(|r| r.error.is_none()), "{:?}", want.rows);
    let dir = common::scratch_dir("sweep-verdicts", "h5-shards");
    let whole = dir.join("whole.h5");
    let quiet = |_: usize, _: usize| {};
    write_sweep_table(&sweep, &whole, false, None, StreamOptions::default(), &quiet).unwrap();
    let shards = dir.join("shards");
    std::fs::create_dir_all(&shards).unwrap();
    for i in 0..2 {
        let (path, ..) =
            run_sweep_shard(&sweep, Part::new(i, 2).unwrap(), &shards, false, None, false, &quiet).unwrap();
        let text = std::fs::read_to_string(path).unwrap();
        assert!(
            text.contains("\"verdicts\""),
            "a shard file without its verdicts: {text}"
        );
    }
    // a run file beside the shards is refused by the library as by `stochvib merge`, naming both kinds
    // (it was left out without a word)
    let run = dir.join("A0.h5");
    std::fs::write(&run, b"a run file\n").unwrap();
    let mixed = merge_sweep(&dir.join("mixed.h5"), &[shards.clone(), run.clone()], false)
        .unwrap_err()
        .to_string();
    assert!(
        mixed.contains("both sweep shard files") && mixed.contains("A0.h5") && mixed.contains("sweep-shard-"),
        "{mixed}"
    );
    assert!(!dir.join("mixed.h5").exists());
    let merged = dir.join("merged.h5");
    merge_sweep(&merged, std::slice::from_ref(&shards), false).unwrap();
    merge_sweep(&dir.join("merged.csv"), std::slice::from_ref(&shards), false).unwrap();
    assert_eq!(std::fs::read_to_string(dir.join("merged.csv")).unwrap(), want.to_csv());
    let quantities: Vec<String> = want.columns[2..]
        .iter()
        .map(|c| c.split(" [").next().unwrap().to_string())
        .collect();
    for file in [&whole, &merged] {
        let _g = common::hdf5_serial();
        let f = hdf5::File::open(file).unwrap();
        for (k, q) in quantities.iter().enumerate() {
            let ds = f.dataset(&format!("verdicts/{k}")).unwrap();
            let name = ds
                .attr("quantity")
                .unwrap()
                .read_scalar::<hdf5::types::VarLenUnicode>()
                .unwrap();
            assert_eq!(name.as_str(), q);
            let col: Vec<f64> = ds.read_raw().unwrap();
            for (row, got) in want.rows.iter().zip(&col) {
                assert_eq!(
                    got.to_bits(),
                    row.values[1 + k].unwrap().to_bits(),
                    "{q} in {}",
                    file.display()
                );
            }
            if let Some(out) = q.strip_prefix("sigma(").and_then(|r| r.strip_suffix(')')) {
                let fast: Vec<f64> = f.dataset(&format!("outputs/{out}/sigma")).unwrap().read_raw().unwrap();
                for (a, b) in col.iter().zip(&fast) {
                    assert!(
                        common::rel(*a, *b) < SWEEP_AGAINST_ANALYZE,
                        "{q}: {a} vs the sweep's {b}"
                    );
                }
            }
        }
    }
}
