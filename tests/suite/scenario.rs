//! Scenario files: parsing, bad input naming file/key/reason, and agreement of the variance methods on
//! the shipped examples.

use crate::common;
use common::tolerance::{EXACT, QUADRATURE};
use std::path::{Path, PathBuf};
use stochvib::scenario::{load_scenario, parse_scenario};
use stochvib::study::analysis_report;
use stochvib::Error;

fn spectra() -> PathBuf {
    crate::common::root().join("spectra")
}

fn data(name: &str) -> PathBuf {
    crate::common::root().join("data").join(name)
}

/// The quarter car with the (8.66) consistent two-pole road (rational): Lyapunov, integral table and
/// quadrature agree for every output; the body acceleration is finite because S ~ ω⁻⁴ (and infinite
/// under the one-pole (8.69) road, see `tests/response.rs`).
#[test]
fn quarter_car_three_methods_agree_on_rational_road() {
    let text = std::fs::read_to_string(data("quarter-car.toml")).unwrap();
    let text = text.replace("spectrum = \"iso8608-c\"", "spectrum = \"book-8-66\"");
    let sc = parse_scenario(&text, &data("quarter-car.toml"), &spectra()).unwrap();
    let r = analysis_report(&sc).unwrap();
    assert_eq!(r.outputs.len(), 4);
    for o in &r.outputs {
        let st = &o.statistics;
        let reference = st
            .variance
            .unwrap_or_else(|| panic!("{}: {:?}", st.name, st.variance_outcome));
        for m in &st.methods {
            let v = m
                .value()
                .unwrap_or_else(|| panic!("{} {:?}: {:?}", st.name, m.method, m.outcome));
            assert!(
                (v - reference).abs() <= QUADRATURE * reference,
                "{} {:?}",
                st.name,
                m.method
            );
        }
    }
}

/// The shipped ISO-road quarter car: quadrature only (non-rational input), finite everywhere because the
/// ISO band limits the input; the 3σ bound is M ± 3σ by construction of the report.
#[test]
fn quarter_car_iso_road_report() {
    let sc = load_scenario(&data("quarter-car.toml"), &spectra()).unwrap();
    let r = analysis_report(&sc).unwrap();
    for o in &r.outputs {
        let s = o.statistics.sigma.unwrap();
        assert!((o.upper_3sigma.unwrap() - 3.0 * s).abs() <= EXACT * s);
        assert!(o.statistics.methods[0].value().is_none());
        assert!(o.band_sigma.unwrap() <= s * (1.0 + EXACT));
    }
}

fn err(text: &str) -> (String, String, String) {
    match parse_scenario(text, Path::new("bad-scenario.toml"), &spectra()) {
        Err(e @ Error::File { .. }) => {
            let msg = e.to_string();
            let Error::File { key, reason, .. } = e else {
                unreachable!()
            };
            (key, reason, msg)
        }
        other => panic!("expected a file error, got {other:?}"),
    }
}

const TF: &str = "[model]\nkind = \"transfer-function\"\nnumerator = [1.0]\ndenominator = [100.0, 2.0, 1.0]\noutput = { name = \"x\", unit = \"m\" }\n";

/// Every kind of bad input names the file, the key and the reason.
#[test]
fn bad_scenarios_name_file_key_reason() {
    let (k, _, msg) = err(&format!("{TF}[input]\nspectrum = \"no-such-road\"\n"));
    assert_eq!(k, "input.spectrum");
    assert!(msg.contains("bad-scenario.toml"));
    let (k, r, _) = err(&format!("{TF}[input]\nspectrum = \"book-8-69\"\n"));
    assert_eq!(k, "input.speed");
    assert!(r.contains("spatial"), "{r}");
    let (k, _, _) = err(&format!("{TF}[input]\nspectrum = \"type1\"\nsped = \"3 m/s\"\n"));
    assert_eq!(k, "input.sped");
    let (k, _, _) = err(&format!("{TF}[input]\nspectrum = \"book-8-69\"\nspeed = \"3 kg\"\n"));
    assert_eq!(k, "input.speed");
    let (k, _, _) = err(&format!(
        "{TF}[input]\nspectrum = \"type1\"\n[analysis]\noutputs = [\"y\"]\n"
    ));
    assert_eq!(k, "analysis.outputs");
    let (k, _, _) = err("[model]\nkind = \"warp-drive\"\n[input]\nspectrum = \"type1\"\n");
    assert_eq!(k, "model.kind");
    let (k, _, _) = err("[input]\nspectrum = \"type1\"\n");
    assert_eq!(k, "model");
    // a zero mass in a generic mdof
    let mdof = "[model]\nkind = \"mdof\"\nbase_inputs = 1\ncoordinates = [{ name = \"x\", unit = \"m\", mass = \"0 kg\" }]\n[[model.element]]\nname = \"k\"\npoint = [1]\nto = \"base 0\"\nstiffness = \"1 kN/m\"\n[[model.output]]\nname = \"x\"\nquantity = \"displacement\"\npoint = [1]\n[input]\nspectrum = \"type1\"\n";
    let (k, r, _) = err(mdof);
    assert!(k.starts_with("model.coordinates"), "{k}: {r}");
    // negative stiffness
    let (k, _, _) = err(&mdof.replace("0 kg", "10 kg").replace("1 kN/m", "-1 kN/m"));
    assert!(k.starts_with("model"), "{k}");
    // element attached to a base input that does not exist
    let (k, _, _) = err(&mdof.replace("0 kg", "10 kg").replace("base 0", "base 3"));
    assert_eq!(k, "model.element[0].to");
    // inline spectrum with a negative variance
    let (k, _, _) = err(&format!(
        "{TF}[input]\nspectrum = {{ kind = \"exponential\", variance = -1.0, alpha = 2.0 }}\n"
    ));
    assert_eq!(k, "input.spectrum.variance");
    // not TOML at all
    assert!(matches!(
        parse_scenario("[model", Path::new("x.toml"), &spectra()),
        Err(Error::Parse { .. })
    ));
}

/// An unstable system in a scenario: refused when the file is loaded, naming the file and the `[model]`
/// table (|H|² would integrate to a finite but meaningless number: no stationary response exists).
#[test]
fn unstable_scenario_is_refused() {
    let text = format!(
        "{}[input]\nspectrum = \"type1\"\n",
        TF.replace("[100.0, 2.0, 1.0]", "[100.0, -2.0, 1.0]")
    );
    let e = parse_scenario(&text, Path::new("u.toml"), &spectra())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("stable") && e.contains("u.toml") && e.contains("key `model.denominator`"),
        "{e}"
    );
}

/// The generic-matrix form of an mdof scenario builds the same model as the element form of the quarter
/// car: M = diag(300, 40) kg, C = [[k_s, −k_s], [−k_s, k_s + k_t]], B = [[b_s, −b_s], [−b_s, b_s]],
/// K_u = [0, k_t]ᵀ (assembled by hand from the element list of data/quarter-car.toml); the variances agree.
#[test]
fn mdof_matrix_form_equals_element_form() {
    let (ks, kt, bs) = (2.0e4, 2.0e5, 1.5e3);
    let text = format!(
        "[model]\nkind = \"mdof\"\nbase_inputs = 1\ncoordinates = [{{ name = \"body\", unit = \"m\" }}, {{ name = \"wheel\", unit = \"m\" }}]\n\
         mass_matrix = [[300.0, 0.0], [0.0, 40.0]]\n\
         stiffness_matrix = [[{ks}, {mks}], [{mks}, {kst}]]\n\
         damping_matrix = [[{bs}, {mbs}], [{mbs}, {bs}]]\n\
         base_stiffness = [[0.0], [{kt}]]\n\
         [[model.output]]\nname = \"body\"\nquantity = \"displacement\"\npoint = [1, 0]\n\
         [input]\nspectrum = \"book-8-66\"\nspeed = \"20 m/s\"\n",
        mks = -ks,
        kst = ks + kt,
        mbs = -bs
    );
    let a = parse_scenario(&text, Path::new("m.toml"), &spectra()).unwrap();
    let va = analysis_report(&a).unwrap().outputs[0].statistics.variance.unwrap();
    let t = std::fs::read_to_string(data("quarter-car.toml"))
        .unwrap()
        .replace("iso8608-c", "book-8-66");
    let b = parse_scenario(&t, &data("quarter-car.toml"), &spectra()).unwrap();
    let vb = analysis_report(&b).unwrap().outputs[0].statistics.variance.unwrap();
    assert!((va - vb).abs() <= EXACT * vb, "{va} vs {vb}");
    // a non-symmetric stiffness matrix is refused, naming the key
    let bad = text.replace(&format!("[[{ks}, {}]", -ks), &format!("[[{ks}, 5.0]"));
    let e = parse_scenario(&bad, Path::new("m.toml"), &spectra())
        .unwrap_err()
        .to_string();
    assert!(e.contains("model.stiffness_matrix") && e.contains("symmetric"), "{e}");
}
