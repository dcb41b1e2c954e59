//! The findings of the fuzz campaigns of seeds 2830–2833, each a regression test: a message that named a
//! key the file does not have, a success that printed a non-finite number, an error that named no file,
//! key or flag, a reference table reported empty, a decay rate accepted in Hz. The expectations are the
//! names the user wrote and closed forms stated in each test, nothing computed by the code under test.

use crate::common::{self, root, tolerance::ROUNDING};
use std::path::{Path, PathBuf};
use stochvib::report::spectrum_report::Outcome;
use stochvib::scenario::{parse_document, parse_scenario, parse_spectrum};
use stochvib::spectrum::Convention;
use stochvib::Error;

fn scratch(tag: &str) -> PathBuf {
    common::scratch_dir("fuzz-findings", tag)
}

fn data_text(p: &str) -> String {
    std::fs::read_to_string(root().join("data").join(p)).unwrap()
}

fn spectra() -> PathBuf {
    root().join("spectra")
}

/// The (file, key, value) of an [`Error::File`], or a panic naming the error.
fn file_key(e: &Error) -> (PathBuf, String, String) {
    match e {
        Error::File { file, key, value, .. } => (file.clone(), key.clone(), value.clone()),
        other => panic!("not an error naming a file and key: {other:?}"),
    }
}

/// A bump stop with a clearance and no stiffness at all (neither `stiffness` nor the side's own): the
/// error names the side's key as missing (`<missing>`), the convention for a required key that is absent —
/// not a value `<derived>` of a key the file does not have.
#[test]
fn a_bump_stop_side_without_a_stiffness_is_named_missing() {
    let text = data_text("quarter-car-bump-stops.toml").replace("stiffness = \"300 kN/m\"\n", "\n");
    let path = root().join("data/quarter-car-bump-stops.toml");
    let e = parse_scenario(&text, &path, &spectra()).unwrap_err();
    let (file, key, value) = file_key(&e);
    assert_eq!(file, path);
    assert_eq!(key, "model.nonlinear[1].upper_stiffness", "{e}");
    assert_eq!(value, "<missing>", "{e}");
    assert!(e.to_string().contains("stiffness"), "{e}");
}

/// A nonlinear model whose linear part is unstable (a negative suspension stiffness under the bump stops)
/// fails in routes 1 and 3 (the report stage); the error names the file and its `model`, not a bare
/// numerical error.
#[test]
fn an_unstable_linear_part_of_a_nonlinear_model_is_named_in_the_file() {
    let text = data_text("quarter-car-bump-stops.toml").replace(
        "suspension_stiffness = \"20 kN/m\"",
        "suspension_stiffness = \"-20 kN/m\"",
    );
    let path = root().join("data/quarter-car-bump-stops.toml");
    let Ok(sc) = parse_scenario(&text, &path, &spectra()) else {
        return; // refused when read: named by the reader (the invariant holds)
    };
    let e = match sc.nonlinear_answers() {
        Err(e) => e,
        Ok(answers) => match stochvib::report::nonlinear_report(&sc, &answers.unwrap(), None) {
            Err(e) => e,
            Ok(_) => panic!("an unstable linear part gave a report"),
        },
    };
    let (file, key, _) = file_key(&e);
    assert_eq!(file, path);
    assert!(key.starts_with("model"), "{e}");
}

/// A profile with a cell of 1e308 mm (10³⁰⁵ m: its square overflows f64) replayed through the quarter car
/// is refused naming the profile, the track and the value, instead of a report with infinite σ and r.m.s.
#[test]
fn a_replay_of_a_profile_beyond_f64_range_is_refused_naming_the_cell() {
    use stochvib::scenario::replay::{replay_scenario, ScenarioReplayOptions};
    let d = scratch("huge-cell");
    let csv = std::fs::read_to_string(root().join("data/measured-profile.csv")).unwrap();
    let mut lines: Vec<String> = csv.lines().map(str::to_string).collect();
    let header = lines.iter().position(|l| !l.starts_with('#')).unwrap();
    let row = header + 500;
    let cells: Vec<&str> = lines[row].split(',').collect();
    let mut changed: Vec<String> = cells.iter().map(|c| c.to_string()).collect();
    changed[1] = "1e308".into();
    lines[row] = changed.join(",");
    let profile = d.join("profile.csv");
    std::fs::write(&profile, lines.join("\n") + "\n").unwrap();
    let sc = stochvib::scenario::load_scenario(&root().join("data/quarter-car.toml"), &spectra()).unwrap();
    let e = replay_scenario(&sc, &profile, &ScenarioReplayOptions::default()).unwrap_err();
    let (file, key, value) = file_key(&e);
    assert_eq!(file, profile, "{e}");
    assert!(key.contains("track"), "{e}");
    assert!(value.contains("e305"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// The (8.66) road at α = 2⁶⁰ 1/m: its correlation K(τ) = D (α e^{−βτ} − β e^{−ατ})/(α − β) is finite at
/// every lag (symmetric in α and β; for α ≫ β it is D e^{−βτ} α/(α − β)), not NaN.
#[test]
fn the_two_pole_road_correlation_is_finite_at_an_extreme_alpha() {
    let text = std::fs::read_to_string(spectra().join("book-8-66.toml"))
        .unwrap()
        .replace("alpha = \"0.3 1/m\"", "alpha = \"1152921504606846976 1/m\"");
    let f = parse_spectrum(&text, Path::new("book-8-66.toml")).unwrap();
    let r = stochvib::report::spectrum_report(&f, Convention::TwoSidedAngular);
    let (dq, a, b) = (0.035f64 * 0.035, 2f64.powi(60), 12.0);
    for (tau, exact, _) in &r.correlation {
        let Outcome::Value(k) = exact else {
            panic!("no correlation at τ = {tau}: {exact:?}")
        };
        let expected = dq * (a * (-b * tau).exp() - b * (-a * tau).exp()) / (a - b);
        assert!((k - expected).abs() <= ROUNDING * dq, "τ = {tau}: {k} vs {expected}");
    }
}

/// A report value that is not finite is given as "no value" with its reason, never as NaN.
#[test]
fn a_non_finite_value_of_the_spectrum_report_is_no_value() {
    let o: Outcome = Ok(f64::NAN).into();
    assert!(matches!(o, Outcome::NoValue { .. }), "{o:?}");
    let o: Outcome = Ok(f64::INFINITY).into();
    assert!(matches!(o, Outcome::NoValue { .. }), "{o:?}");
}

/// A stress so small that every method's damage rate underflows to 0 (stress factor 10⁻¹⁰⁰ Pa/m: σ⁵ ≈
/// 10⁻⁵⁰⁰ Pa⁵ is below the smallest f64) is refused naming the fatigue section, instead of an infinite
/// life, safety factor and spread.
#[test]
fn a_damage_rate_that_underflows_is_refused_not_an_infinite_life() {
    let text = data_text("operator-seat-verdicts.toml")
        .replace("stress_factor = \"1.29313e10 Pa/m\"", "stress_factor = \"1e-100 Pa/m\"");
    let path = root().join("data/operator-seat-verdicts.toml");
    let sc = parse_scenario(&text, &path, &spectra()).unwrap();
    let e = stochvib::report::analysis_report(&sc).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!(file, path);
    assert!(key.starts_with("analysis.fatigue"), "{e}");
    assert!(e.to_string().contains("damage rate"), "{e}");
}

/// Table 8.1 with an empty `row` list (or no speed) is refused naming the key, not reported empty.
#[test]
fn a_reference_table_without_rows_is_refused() {
    let path = root().join("data/reference/table-8-1.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let head = &text[..text.find("[[row]]").unwrap()];
    for (doc, key) in [
        (format!("{head}\nrow = []\n"), "row"),
        (text.replace("speeds = [\"5 m/s\", \"10 m/s\", \"15 m/s\"]", "speeds = []"), "speeds"),
    ] {
        let e = match parse_document(&doc, &path, &spectra()) {
            Err(e) => e,
            Ok(_) => panic!("a table without {key} was accepted"),
        };
        assert_eq!(file_key(&e).1, key, "{e}");
    }
}

/// A decay rate is not a frequency: `alpha = "1 Hz"` (2π rad/s as a frequency) is refused for the
/// exponential correlation, whatever the domain; `1/s` and `1/cm` are rates; `beta = "3 Hz"` of an
/// exp-cosine correlation (a frequency) stays accepted.
#[test]
fn a_decay_rate_in_hz_is_refused() {
    let text = std::fs::read_to_string(spectra().join("book-8-45.toml")).unwrap();
    let bare: String = text
        .lines()
        .filter(|l| !l.starts_with("domain") && !l.starts_with("unit"))
        .map(|l| format!("{l}\n"))
        .collect();
    let file = Path::new("book-8-45.toml");
    for alpha in ["1 Hz", "2 rad/s", "1 cycles/m", "3 kHz"] {
        let doc = bare.replace("alpha = \"0.035 1/cm\"", &format!("alpha = \"{alpha}\""));
        let e = parse_spectrum(&doc, file).err().unwrap_or_else(|| panic!("alpha = {alpha} accepted"));
        assert_eq!(file_key(&e).1, "alpha", "{e}");
    }
    parse_spectrum(&bare.replace("0.035 1/cm", "0.5 1/s"), file).unwrap();
    parse_spectrum(&text, file).unwrap();
    parse_spectrum(
        &std::fs::read_to_string(spectra().join("cab-floor-3hz.toml")).unwrap(),
        Path::new("cab-floor-3hz.toml"),
    )
    .unwrap();
}

/// The test helper `cli_within` reads the child's pipes while it runs: a command that prints more than a
/// pipe holds (64 KiB on Linux) — here a CSV sweep table of 4000 points, about 60 bytes a line — finishes
/// instead of blocking on a full pipe until the helper declares it hung.
#[test]
fn the_cli_helper_reads_more_than_a_pipe_holds() {
    let d = scratch("large-output");
    let sc = root().join("data/quarter-car-model.toml");
    let o = common::cli_within(
        &[
            "sweep",
            sc.to_str().unwrap(),
            "--param",
            "model.sprung_mass=250 kg..350 kg:4000",
        ],
        &d,
        std::time::Duration::from_secs(600),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stdout.len() > 64 << 10, "{} bytes", o.stdout.len());
    let _ = std::fs::remove_dir_all(&d);
}
