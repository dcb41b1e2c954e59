//! Every file of `data/` runs through a command, the one registry of model kinds agrees with the files and
//! the docs, deterministic models print results that agree with their independent routes, and `simulate`
//! suggests its time step when none is given.

use crate::common;
use crate::common::SpawnSerial;
use common::root;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use stochvib::models::quarter_car::QuarterCar;
use stochvib::scenario::{kind_names, load_document, Document, Family, MODEL_KINDS};
use stochvib::system::FrequencyResponse;

fn bin() -> Command {
    let mut c = Command::new(crate::common::cli_bin());
    c.current_dir(root());
    c
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output_serial().unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn data_files() -> Vec<PathBuf> {
    let mut out = Vec::new();
    for dir in ["data", "data/reference"] {
        for e in std::fs::read_dir(root().join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "toml") {
                out.push(p.strip_prefix(root()).unwrap().to_path_buf());
            }
        }
    }
    out.sort();
    out
}

#[test]
fn every_data_file_runs_through_analyze() {
    let files = data_files();
    assert!(files.len() >= 15, "{files:?}");
    for f in &files {
        let f = f.to_str().unwrap();
        let o = run(&["analyze", f]);
        assert!(o.status.success(), "{f}: {}", text(&o));
        let out = String::from_utf8_lossy(&o.stdout);
        let doc = load_document(&root().join(f), &root().join("spectra")).unwrap();
        match doc {
            Document::Stochastic(sc) => {
                for &i in &sc.analysis.outputs {
                    let name = &sc.model.system.outputs()[i].name;
                    assert!(out.contains(&format!("output {name} [")), "{f}: {name} missing\n{out}");
                }
            }
            Document::Deterministic(d) => {
                assert!(out.contains("deterministic model"), "{f}\n{out}");
                for t in d.model.results().unwrap() {
                    assert!(out.contains(&t.title), "{f}: table `{}` missing\n{out}", t.title);
                }
            }
            Document::Reference(r) => {
                assert!(
                    f.starts_with("data/reference/"),
                    "{f}: reference tables live in data/reference/"
                );
                assert!(
                    out.contains("reference table") && out.contains(&r.tables[0].title),
                    "{f}\n{out}"
                );
            }
        }
        // and as JSON
        let j = run(&["analyze", f, "--json"]);
        assert!(j.status.success(), "{f} --json: {}", text(&j));
        let _: serde_json::Value = serde_json::from_slice(&j.stdout).unwrap();
    }
}

#[test]
fn registry_agrees_with_the_files_the_error_and_the_docs() {
    // every file's kind is registered, and every registered example file exists and is of that kind
    for f in data_files().iter().filter(|f| !f.starts_with("data/reference")) {
        let t: toml::Table = toml::from_str(&std::fs::read_to_string(root().join(f)).unwrap()).unwrap();
        let kind = t["model"]["kind"].as_str().unwrap();
        assert!(
            kind_names().contains(&kind),
            "{}: kind {kind} not registered",
            f.display()
        );
    }
    for k in MODEL_KINDS {
        if k.example.is_empty() {
            assert_eq!(
                k.family,
                Family::Generic,
                "{}: a catalogue model needs an example file",
                k.name
            );
            continue;
        }
        let t: toml::Table = toml::from_str(&std::fs::read_to_string(root().join(k.example)).unwrap()).unwrap();
        assert_eq!(t["model"]["kind"].as_str(), Some(k.name), "{}", k.example);
        let doc = load_document(&root().join(k.example), &root().join("spectra")).unwrap();
        assert_eq!(matches!(doc, Document::Stochastic(_)), k.stochastic, "{}", k.name);
    }
    // the unknown-kind error lists every kind of the registry
    let dir = crate::common::scratch_path("data-files", "kinds");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[model]\nkind = \"hovercraft\"\n[input]\nspectrum = \"type1\"\n").unwrap();
    let o = run(&["analyze", bad.to_str().unwrap()]);
    assert!(!o.status.success());
    let msg = text(&o);
    assert!(msg.contains("model.kind") && msg.contains("hovercraft"), "{msg}");
    for k in kind_names() {
        assert!(msg.contains(k), "unknown-kind error does not list {k}: {msg}");
    }
    // `stochvib models` lists them, and the model catalogue page (docs/models.md) names every kind
    let models = String::from_utf8_lossy(&run(&["models"]).stdout).into_owned();
    let catalogue = std::fs::read_to_string(root().join("docs/models.md")).unwrap();
    for k in MODEL_KINDS {
        assert!(models.contains(k.name) && models.contains(k.summary), "{}", k.name);
        assert!(
            catalogue.contains(&format!("`{}`", k.name)),
            "docs/models.md does not document kind {}",
            k.name
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The deterministic tables carry the independent routes side by side: the closed-form frequencies (16)
/// of the three-mass hoist against the eigenvalues of its chain (agree to 1e-9 relative, the
/// FACTORISATION tolerance), the mine hoist's node by the corrected closed form against root finding on
/// the eigenvectors (bisection to 1e-9 m: agree to 1e-6 m), and the chain's recursion against the dense
/// solve (the note states the agreement).
#[test]
fn deterministic_results_agree_with_their_independent_routes() {
    let j = |f: &str| -> serde_json::Value {
        let o = run(&["analyze", f, "--json"]);
        assert!(o.status.success(), "{}", text(&o));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let hoist = j("data/three-mass-hoist.toml");
    let freq = &hoist["tables"][0]["rows"];
    for r in freq.as_array().unwrap().iter().skip(1) {
        let (closed, modal) = (r[1].as_f64().unwrap(), r[3].as_f64().unwrap());
        assert!(
            (closed - modal).abs() <= common::tolerance::FACTORISATION * closed,
            "{r}"
        );
    }
    let mine = j("data/mine-hoist.toml");
    let node = &mine["tables"][1]["rows"];
    let (a, b) = (node[0][1].as_f64().unwrap(), node[1][1].as_f64().unwrap());
    assert!((a - b).abs() < 1e-6, "node {a} vs {b}");
    let chain = j("data/dynamic-stiffness-chain.toml");
    let note = chain["tables"][0]["note"].as_str().unwrap();
    let agree: f64 = note
        .rsplit("agrees to ")
        .next()
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(agree < 1e-12, "{note}");
    // a deterministic file cannot be simulated, and says so
    let o = run(&[
        "simulate",
        "data/mine-hoist.toml",
        "--realizations",
        "4",
        "-o",
        "/nonexistent/x.h5",
    ]);
    assert!(!o.status.success());
    assert!(text(&o).contains("deterministic model"), "{}", text(&o));
}

/// The catalogue quarter car and the same car written as a generic `mdof` scenario are the same system:
/// their frequency responses agree to rounding, and both equal the hand-derived transfer function of the
/// module docs, H_body(s) = k_t (c_s s + k_s) / Δ(s).
#[test]
fn quarter_car_model_matches_its_transfer_function_and_the_mdof_file() {
    let (ms, mu, ks, cs, kt) = (300.0, 40.0, 20e3, 1.5e3, 200e3);
    let car = QuarterCar {
        sprung_mass: ms,
        unsprung_mass: mu,
        suspension_stiffness: ks,
        suspension_damping: cs,
        tyre_stiffness: kt,
        tyre_damping: 0.0,
    }
    .build()
    .unwrap()
    .system()
    .unwrap();
    let Document::Stochastic(file) =
        load_document(&root().join("data/quarter-car.toml"), &root().join("spectra")).unwrap()
    else {
        panic!("stochastic")
    };
    for w in [0.3, 2.0, 8.0, 25.0, 70.0, 300.0] {
        let s = nalgebra::Complex::new(0.0, w);
        let delta = s.powi(4) * (ms * mu)
            + s.powi(3) * (cs * (ms + mu))
            + s * s * (ms * (ks + kt) + mu * ks)
            + s * (cs * kt)
            + ks * kt;
        let h = (s * cs + ks) * kt / delta;
        let a = car.response(w);
        let b = file.model.system.response(w);
        assert!(
            (a[(0, 0)] - h).norm() <= 1e-12 * h.norm(),
            "ω = {w}: {} vs {h}",
            a[(0, 0)]
        );
        for i in 0..4 {
            assert!(
                (a[(i, 0)] - b[(i, 0)]).norm() <= 1e-12 * b[(i, 0)].norm().max(1e-300),
                "ω = {w}, output {i}"
            );
        }
    }
}

/// `simulate` without `--dt`/`--duration` takes the suggested ones and says what it chose.
#[test]
fn simulate_suggests_its_step() {
    let dir = crate::common::scratch_path("data-files", "suggest");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.h5");
    let _ = std::fs::remove_file(&out);
    let o = run(&[
        "simulate",
        "data/conveyor-idler.toml",
        "--realizations",
        "4",
        "--json",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("time step") && stderr.contains("(suggested:"),
        "{stderr}"
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // the suggestion of `suggest_step`, as printed
    let sc =
        stochvib::scenario::load_scenario(&root().join("data/conveyor-idler.toml"), &root().join("spectra")).unwrap();
    let s = stochvib::simulate::suggest_step(&sc.run_input()).unwrap();
    assert_eq!(v["dt_s"].as_f64(), Some(s.dt_s));
    assert!(Path::new(&out).is_file());
    let _ = std::fs::remove_dir_all(&dir);
}
