//! The findings of the fuzz campaigns of seeds 2830–2835, each a regression test: a message that named a
//! key the file does not have, a success that printed a non-finite number, an error that named no file,
//! key or flag, a reference table reported empty, a decay rate accepted in Hz. The expectations are the
//! names the user wrote and closed forms stated in each test, nothing computed by the code under test.

use crate::common::{self, root, tolerance::ROUNDING};
use std::path::{Path, PathBuf};
use stochvib::scenario::{parse_document, parse_scenario, parse_spectrum};
use stochvib::spectrum::Convention;
use stochvib::study::spectrum_report::Outcome;
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

/// An error of the nonlinear routes or their report that names no key (an unstable linear part, a
/// quadrature that fails: bare numerical errors at the report stage before) is named as the file's `model`
/// with its kind; an error that names a key already passes unchanged. (The campaigns' reproducers of the
/// unstable case are not at hand, so the naming itself is tested on the shipped nonlinear scenario.)
#[test]
fn an_error_of_the_nonlinear_routes_is_named_in_the_file() {
    let path = root().join("data/quarter-car-bump-stops.toml");
    let sc = stochvib::scenario::load_scenario(&path, &spectra()).unwrap();
    let bare = Error::Numerical {
        what: "route 1".into(),
        reason: "the linear part is not asymptotically stable".into(),
    };
    let e = sc.name_model_error(bare);
    let (file, key, value) = file_key(&e);
    assert_eq!(
        (file, key.as_str(), value.as_str()),
        (path.clone(), "model", "quarter-car"),
        "{e}"
    );
    assert!(e.to_string().contains("not asymptotically stable"), "{e}");
    let named = Error::in_file(&path, "model.nonlinear[1].stiffness", "0", "must be > 0");
    assert_eq!(file_key(&sc.name_model_error(named)).1, "model.nonlinear[1].stiffness");
}

/// A profile with a cell of 1e308 mm (10³⁰⁵ m: its square overflows f64) replayed through the quarter car
/// is refused naming the profile, the cell (line and column, as the profile is read: beyond 10¹⁰⁰ m) and
/// the value, instead of a report with infinite σ and r.m.s.
#[test]
fn a_replay_of_a_profile_beyond_f64_range_is_refused_naming_the_cell() {
    use stochvib::study::replay::{replay_scenario, ScenarioReplayOptions};
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
    assert_eq!(key, format!("line {}, column 2 `left`", row + 1), "{e}");
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
    let r = stochvib::study::spectrum_report(&f, Convention::TwoSidedAngular);
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
    let e = stochvib::study::analysis_report(&sc).unwrap_err();
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
        (
            text.replace("speeds = [\"5 m/s\", \"10 m/s\", \"15 m/s\"]", "speeds = []"),
            "speeds",
        ),
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
        let e = parse_spectrum(&doc, file)
            .err()
            .unwrap_or_else(|| panic!("alpha = {alpha} accepted"));
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

/// The invalid parameter's name of an error, or a panic naming the error.
fn parameter(e: &Error) -> String {
    match e {
        Error::InvalidParameter { name, .. } => name.clone(),
        other => panic!("not an invalid parameter: {other:?}"),
    }
}

/// `stochvib fatigue`'s S–N flags are named as written when the curve refuses them (the record-command
/// family of the harness found `amplitude`, `k`, `C` and `cycles`, the library's names).
#[test]
fn the_sn_curve_of_the_fatigue_flags_names_the_flag() {
    use stochvib::record::{sn_curve_from_flags, SnPoint};
    let cases: [(f64, SnPoint, f64, Option<&str>, &str); 7] = [
        (0.0, SnPoint::Amplitude("80 MPa"), 2e6, None, "--sn-slope"),
        (f64::NAN, SnPoint::Amplitude("80 MPa"), 2e6, None, "--sn-slope"),
        (3.0, SnPoint::Amplitude("-5 MPa"), 2e6, None, "--sn-amplitude"),
        (3.0, SnPoint::Range("-5 MPa"), 2e6, None, "--sn-range"),
        (3.0, SnPoint::Amplitude("80 MPa"), 0.0, None, "--sn-cycles"),
        (3.0, SnPoint::Range("1e-300 MPa"), 1.0, None, "--sn-range"),
        (3.0, SnPoint::Amplitude("80 MPa"), 2e6, Some("20 m"), "--endurance"),
    ];
    for (k, point, cycles, endurance, flag) in cases {
        let e = sn_curve_from_flags(k, point, cycles, endurance).unwrap_err();
        assert_eq!(parameter(&e), flag, "{e}");
    }
    sn_curve_from_flags(3.0, SnPoint::Range("160 MPa"), 2e6, Some("20 MPa")).unwrap();
}

/// `stochvib weighting` at a frequency or sample rate where the weighting overflows f64 is refused naming
/// the flag (it printed NaN before); a sample rate the digital filter refuses is named `--sample-rate`.
#[test]
fn a_weighting_beyond_f64_range_is_refused_naming_the_flag() {
    use stochvib::comfort::Weighting;
    use stochvib::study::weighting_table::WeightingReport;
    let e = WeightingReport::new(Weighting::Wc, &[1e308], None).unwrap_err();
    assert_eq!(parameter(&e), "--frequency", "{e}");
    let e = WeightingReport::new(Weighting::We, &[], Some(1e308)).unwrap_err();
    assert_eq!(parameter(&e), "--sample-rate", "{e}");
    let e = WeightingReport::new(Weighting::We, &[], Some(0.0)).unwrap_err();
    assert_eq!(parameter(&e), "--sample-rate", "{e}");
    WeightingReport::new(Weighting::Wk, &[1.0, 2.0, 4.0], Some(1000.0)).unwrap();
}

/// `stochvib iri` of a temporal spectrum names the spectrum the user gave (it was a bare "does not apply"),
/// and the band of a spectrum without an upper edge is `null` in JSON, not infinity.
#[test]
fn iri_names_a_temporal_spectrum_and_writes_an_unbounded_band_as_null() {
    let catalogue = stochvib::scenario::Catalogue::new(spectra());
    let temporal = catalogue.resolve("type1", None).unwrap();
    let e = stochvib::study::road_numbers::iri_report(&temporal, None).unwrap_err();
    assert_eq!(parameter(&e), "spectrum", "{e}");
    assert!(e.to_string().contains("type1"), "{e}");
    let road = catalogue.resolve("book-8-66", None).unwrap();
    let r = stochvib::study::road_numbers::iri_report(&road, None).unwrap();
    let json = serde_json::to_value(&r).unwrap();
    assert!(json["expected"]["band_cycles_per_m"][1].is_null(), "{json}");
    assert!(!format!("{r}").contains("inf"), "{r}");
}

/// `stochvib coherence --segment 2` names the flag, not the estimator's "segment length".
#[test]
fn the_coherence_segment_is_named_as_the_flag() {
    let profile = root().join("data/measured-profile.csv");
    let e = stochvib::study::road_numbers::coherence_report(None, Some(&profile), &[], Some(2), 0.95).unwrap_err();
    assert_eq!(parameter(&e), "--segment", "{e}");
}

/// A record whose stress cycles all stay below the endurance limit does no damage: the life is not a
/// finite number, so `stochvib fatigue` refuses naming the record's channel instead of printing an
/// infinite life; an axis without an ISO 2631-1 weighting (rz on the standing floor) is named as the
/// `--axis` the user wrote.
#[test]
fn a_record_without_damage_and_an_axis_without_weighting_are_refused_by_name() {
    use stochvib::record::{
        evaluate_exposure, evaluate_fatigue, open_record, sn_curve_from_flags, AxisAssignment, ExposureOptions,
        FatigueOptions, MeanStressCorrection, RecordOptions, SnPoint,
    };
    let d = scratch("records");
    let file = d.join("record.csv");
    std::fs::write(&file, crate::fuzz::records::record_csv()).unwrap();
    // the stress channel's amplitudes are below 60 MPa (50 + 40 + 12 + 4 MPa at most, about a mean of 50)
    let (sn, sn_dim) = sn_curve_from_flags(5.0, SnPoint::Amplitude("2000 MPa"), 2e6, Some("1000 MPa")).unwrap();
    let options = FatigueOptions {
        channel: Some("stress".into()),
        sn,
        sn_dim,
        mean_stress: MeanStressCorrection::None,
        gate: None,
        segment_len: None,
    };
    let mut reader = open_record(&file, &RecordOptions::default()).unwrap();
    let e = evaluate_fatigue(reader.as_mut(), &options).unwrap_err();
    let (named, key, _) = file_key(&e);
    assert_eq!((named, key.as_str()), (file.clone(), "channel"), "{e}");
    assert!(e.to_string().contains("no damage"), "{e}");
    let options = ExposureOptions {
        axes: vec![AxisAssignment::parse("x=standing-floor:rz").unwrap()],
        ..ExposureOptions::default()
    };
    let mut reader = open_record(&file, &RecordOptions::default()).unwrap();
    let e = evaluate_exposure(reader.as_mut(), &options).unwrap_err();
    assert_eq!(parameter(&e), "--axis", "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A profile of `rows` rows of the shipped two-track profile (its comments dropped) at `dir/name`, with
/// `edit` applied to the data lines.
fn short_profile(dir: &Path, name: &str, rows: usize, edit: impl Fn(Vec<String>) -> Vec<String>) -> PathBuf {
    let text = data_text("measured-profile.csv");
    let lines: Vec<String> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .take(rows)
        .map(str::to_string)
        .collect();
    let body = edit(lines).join("\n");
    let p = dir.join(name);
    std::fs::write(&p, format!("distance [m], left [mm], right [mm]\n{body}\n")).unwrap();
    p
}

/// Findings of seeds 2834 and 2835 (`error-not-a-flag`): `stochvib coherence` named the estimator's
/// `confidence`, `record length` and `segments`, `stochvib iri` the IRI's `profile length` and `step`. Now a
/// confidence outside (0, 1) is `--confidence`; a segment longer than the profile (or leaving one segment)
/// is `--segment` when the flag gave it, else the profile's columns; a profile shorter than the IRI needs
/// (11 m plus the 250 mm base: 226 samples at 0.05 m) or sampled coarser than 11 m (a distance column in km:
/// Δx = 50 m) names the profile file and the column.
#[test]
fn coherence_and_iri_name_the_flag_or_the_profile() {
    use stochvib::study::road_numbers::{coherence_report, iri_report};
    let d = scratch("road-numbers");
    let whole = root().join("data/measured-profile.csv");
    for c in [f64::NAN, 0.0, 1.0, 1.5] {
        let e = coherence_report(None, Some(&whole), &[], None, c).unwrap_err();
        assert_eq!(parameter(&e), "--confidence", "{e}");
    }
    // 10,000 samples: a segment of 2^20 is longer than the profile
    let e = coherence_report(None, Some(&whole), &[], Some(1 << 20), 0.95).unwrap_err();
    assert_eq!(parameter(&e), "--segment", "{e}");
    assert!(e.to_string().contains("10000 samples"), "{e}");
    // 15 rows: the default segment (16, or the largest even number ≤ 15: 14) leaves one segment
    let short = short_profile(&d, "short.csv", 15, |l| l);
    let e = coherence_report(None, Some(&short), &[], None, 0.95).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!((file, key.as_str()), (short.clone(), "column left and right"), "{e}");
    let catalogue = stochvib::scenario::Catalogue::new(spectra());
    let road = catalogue.resolve("iso8608-c", None).unwrap();
    let e = iri_report(&road, Some(&short)).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!((file, key.as_str()), (short, "column left"), "{e}");
    assert!(e.to_string().contains("11 m"), "{e}");
    let km = short_profile(&d, "km.csv", 400, |l| l);
    std::fs::write(
        &km,
        std::fs::read_to_string(&km)
            .unwrap()
            .replace("distance [m]", "distance [km]"),
    )
    .unwrap();
    let e = iri_report(&road, Some(&km)).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!((file, key.as_str()), (km, "column left"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Findings of seeds 2834 and 2835 (`non-finite-result`): `stochvib iri` of a profile with a cell of 1e308
/// (mm: 1e305 m) printed an IRI of `inf` m/km; it is refused naming the profile and the cell (line 602: the
/// header is line 1) as the profile is read (beyond 10¹⁰⁰ m). `stochvib fatigue --ultimate "1e308 MPa"` (1e314 Pa, beyond f64) echoed an infinite ultimate
/// strength; a record quantity whose SI value is not finite is refused naming the flag.
#[test]
fn an_iri_or_a_flag_beyond_f64_is_refused_by_name() {
    use stochvib::record::{parse_quantity, quantity_of_dim};
    let d = scratch("beyond-f64");
    let huge = short_profile(&d, "huge.csv", 1200, |mut l| {
        l[600] = "30.00,1e308,-1.0".into();
        l
    });
    let catalogue = stochvib::scenario::Catalogue::new(spectra());
    let road = catalogue.resolve("iso8608-h", None).unwrap();
    let e = stochvib::study::road_numbers::iri_report(&road, Some(&huge)).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!((file, key.as_str()), (huge, "line 602, column 2 `left`"), "{e}");
    assert!(e.to_string().contains("larger in magnitude"), "{e}");
    let stress = stochvib::units::Dim::new(-1, 1, -2);
    let e = quantity_of_dim("--ultimate", "1e308 MPa", stress).unwrap_err();
    assert_eq!(parameter(&e), "--ultimate", "{e}");
    let e = parse_quantity("1e308 MPa", "--sn-amplitude").unwrap_err();
    assert_eq!(parameter(&e), "--sn-amplitude", "{e}");
    assert_eq!(quantity_of_dim("--ultimate", "500 MPa", stress).unwrap(), 5e8);
    let _ = std::fs::remove_dir_all(&d);
}

/// Findings of seeds 2834 and 2835 (`phantom-key`): a quadratic damper without any coefficient was
/// reported as `model.nonlinear[0].coefficient = <derived>` (the file has no such key): it is `<missing>`
/// now. A constant-acceleration speed profile starting at 2·10²³ s (its times collapse in rounding: 10 s
/// after 2·10²³ s is 2·10²³ s again) was blamed on `input.speed_profile.time[2]` (the keys are `from`,
/// `to`, `acceleration`, `start`): it names `start` with its value.
#[test]
fn a_missing_damper_coefficient_and_a_collapsing_speed_profile_name_keys_of_the_file() {
    let path = root().join("data/quarter-car-model.toml");
    let text = data_text("quarter-car-model.toml")
        + "\n[[model.nonlinear]]\nkind = \"quadratic-damper\"\nacross = \"suspension\"\n";
    let e = parse_scenario(&text, &path, &spectra()).unwrap_err();
    let (_, key, value) = file_key(&e);
    assert_eq!(
        (key.as_str(), value.as_str()),
        ("model.nonlinear[0].coefficient", "<missing>"),
        "{e}"
    );
    let path = root().join("data/quarter-car-accelerating.toml");
    let text = data_text("quarter-car-accelerating.toml").replace("start = \"1 s\"", "start = \"2e23 s\"");
    let e = parse_scenario(&text, &path, &spectra()).unwrap_err();
    let (_, key, value) = file_key(&e);
    assert_eq!(key, "input.speed_profile.start", "{e}");
    assert!(value.contains("2e23"), "{e}");
}

/// Finding of seeds 2834 and 2835 (`error-without-file-key`): the accelerating quarter car with an output
/// weight of −1.6·10¹³ on the wheel's acceleration is found unstable only by the report's check of the
/// system and its excitation ("max Re(eigenvalue) > 0"), which named no file; the error now names the
/// file's `model`.
#[test]
fn an_unstable_system_found_by_the_report_names_the_model() {
    let path = root().join("data/quarter-car-accelerating.toml");
    let text = data_text("quarter-car-accelerating.toml").replacen(
        "quantity = \"acceleration\"\npoint = [1, 0]",
        "quantity = \"acceleration\"\npoint = [1, -16209687282898.85]",
        1,
    );
    let sc = parse_scenario(&text, &path, &spectra()).unwrap();
    let e = stochvib::study::analysis_report(&sc).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!((file, key.as_str()), (path, "model"), "{e}");
    assert!(e.to_string().contains("stable"), "{e}");
}

/// Finding of seed 2834 (`typo-accepted`, a harness misjudgement): a workday task's `scenario` renamed to
/// `sscenario` and back to `scenario` was expected to be refused as a typo (the typo vocabulary holds no
/// workday keys); the harness no longer expects a key renamed back to its shipped name to be refused. A
/// real typo of the key is refused by the reader, naming the key.
#[test]
fn a_workday_key_renamed_back_is_no_typo_and_a_real_typo_is_refused() {
    let corpus = crate::fuzz::inputs::Corpus::load(&root());
    let case = crate::fuzz::inputs::generate(&corpus, 2834, 89476);
    assert_eq!(case.kind, crate::fuzz::inputs::DocKind::Workday, "{}", case.describe());
    assert!(case.must_reject.is_empty(), "{:?}", case.must_reject);
    let path = root().join("data/workday/scraper-operator.toml");
    let text = data_text("workday/scraper-operator.toml").replacen("scenario = ", "sscenario = ", 1);
    let e = stochvib::scenario::workday_file::parse_workday(&text, &path).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!(file, path);
    assert!(key.contains("sscenario") || key.contains("scenario"), "{e}");
}

/// Found while adding the transient case family: `[transient] duration = "1e9 s"` at the scenario's step of
/// 0.05 s asks for 2·10¹⁰ reported times (160 GB of times alone), and `stochvib transient` aborted on the
/// allocation; more than 10⁶ reported times are refused before anything is allocated, naming
/// `transient.step`, the count and the cap.
#[test]
fn a_transient_of_too_many_reported_times_is_refused_by_key() {
    let path = root().join("data/quarter-car-accelerating.toml");
    let text = data_text("quarter-car-accelerating.toml").replacen("duration = \"15 s\"", "duration = \"1e9 s\"", 1);
    let sc = parse_scenario(&text, &path, &spectra()).unwrap();
    let e = stochvib::study::transient_run::transient_setup(&sc).unwrap_err();
    let (file, key, _) = file_key(&e);
    assert_eq!((file, key.as_str()), (path, "transient.step"), "{e}");
    assert!(e.to_string().contains("2e10 reported times"), "{e}");
}

/// A transient Monte Carlo batch of 10⁹ realizations started at once and wrote a run file of hundreds of
/// gigabytes before anything told the user: it is refused before anything is written, naming
/// `--monte-carlo` with the time estimate and the `--max-hours` cap, like the stationary runs (and a batch
/// whose file does not fit on the disk is refused likewise). The estimate is a lower bound (one normal draw
/// per state and step, at most 2·10⁸ draws per second per thread): 10¹² realizations of the accelerating
/// quarter car's 1200 steps of at least 4 states take at least 4.8·10¹⁵ / (2·10⁸ P) s, 139 days on P = 2
/// threads and above 24 h for any P < 277. Nothing is left in the output directory.
#[test]
fn a_transient_batch_beyond_the_time_cap_is_refused_before_writing() {
    let dir = scratch("transient-batch-cap");
    let out = dir.join("run.h5");
    let scenario = root().join("data/quarter-car-accelerating.toml");
    let err = common::cli_fails(
        1,
        &[
            "transient",
            scenario.to_str().unwrap(),
            "--monte-carlo",
            "1000000000000",
            "-o",
            out.to_str().unwrap(),
        ],
        &root(),
    );
    assert!(
        err.contains("--monte-carlo") && err.contains("would take at least"),
        "{err}"
    );
    assert!(err.contains("--max-hours"), "{err}");
    assert!(common::listing(&dir).is_empty(), "{:?}", common::listing(&dir));
}

/// `optimize --starts 10¹²` kept every start's result and ran without an estimate: it is refused before the
/// search, naming `starts`, because 10¹² results of at least 100 bytes each (10¹⁴ bytes) exceed the memory
/// of any machine this runs on.
#[test]
fn an_optimisation_of_absurdly_many_starts_is_refused_by_name() {
    let err = common::cli_fails(
        1,
        &[
            "optimize",
            "data/quarter-car-model.toml",
            "--param",
            "model.suspension_damping=0.2:6 kN*s/m",
            "--minimize",
            "sigma(body_acc)",
            "--starts",
            "1000000000000",
        ],
        &root(),
    );
    assert!(err.contains("--starts") && err.contains("1000000000000"), "{err}");
    assert!(err.contains("fewer --starts"), "{err}");
}

/// Found by the CLI-command family (seed 16): `simulate --plots FILE`, where FILE is a regular file (or a
/// FIFO), wrote the whole run file and only then failed on the pictures, with a message ending "nothing was
/// written". The picture directory is now checked before the run: the command fails naming the flag's
/// target and leaves no run file, no `.tmp` and the target as it was; `transient --plots` does the same before
/// its exact route.
#[test]
fn simulate_and_transient_check_their_picture_directory_before_the_work() {
    let dir = scratch("plots-before-work");
    std::fs::create_dir_all(&dir).unwrap();
    let pictures = dir.join("pictures.csv");
    std::fs::write(&pictures, "a, b\n1, 2\n").unwrap();
    let run = dir.join("run.h5");
    let p = |x: &Path| x.to_str().unwrap().to_string();
    let simulate = [
        "simulate",
        "data/conveyor-idler.toml",
        "--realizations",
        "4",
        "--duration",
        "2",
        "--dt",
        "0.01",
        "-o",
        &p(&run),
        "--plots",
        &p(&pictures),
    ];
    let err = common::cli_fails(1, &simulate, &root());
    assert!(err.contains("pictures.csv") && err.contains("not a directory"), "{err}");
    let transient = [
        "transient",
        "data/quarter-car-accelerating.toml",
        "--plots",
        &p(&pictures),
    ];
    let err = common::cli_fails(1, &transient, &root());
    assert!(err.contains("pictures.csv") && err.contains("not a directory"), "{err}");
    assert_eq!(std::fs::read_to_string(&pictures).unwrap(), "a, b\n1, 2\n");
    assert_eq!(
        common::listing(&dir),
        vec!["pictures.csv".to_string()],
        "only the target is there"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Found by the CLI-command family (seed 2838, case 2379): `simulate --shard 2 --of 3 --duration NaN -o
/// run.h5` created the run directory `run.h5` and then refused `--duration`, leaving an empty directory
/// behind. The options are checked before the directory is made: nothing is created. And `spectrum
/// --frequency inf` said "invalid frequency inf" without naming the flag (seed 2838, case 2821): it names
/// `--frequency` (and `--omega` for `--omega`).
#[test]
fn a_refused_shard_run_creates_nothing_and_spectrum_names_its_frequency_flag() {
    let dir = scratch("refused-shard");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.h5");
    let args = [
        "simulate",
        "data/conveyor-idler.toml",
        "--realizations",
        "4",
        "--duration",
        "NaN",
        "--dt",
        "0.01",
        "--shard",
        "2",
        "--of",
        "3",
        "-o",
        out.to_str().unwrap(),
    ];
    let err = common::cli_fails(1, &args, &root());
    assert!(err.contains("--duration") && err.contains("NaN"), "{err}");
    assert!(common::listing(&dir).is_empty(), "{:?}", common::listing(&dir));
    // `--frequency 1e308` (the input fuzzer, seed 77, case 9161): finite, but its 2πf is not: the density
    // was printed at ω = inf; refused now, the value in exponent form
    for (flag, value) in [("--frequency", "inf"), ("--omega", "NaN"), ("--frequency", "1e308")] {
        let err = common::cli_fails(1, &["spectrum", "book-8-45", flag, value], &root());
        assert!(err.contains(&format!("`{flag}` = {value}")), "{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Found by the CLI-command family (seed 2838, case 7104): `analyze --max-subintervals 0` was refused as
/// "invalid parameter `max_subintervals`", the library's field: the flags of the quadrature effort are named
/// as the flags (`--max-subintervals`, `--rel-tol`, `--max-half-periods`) with the value typed.
#[test]
fn the_quadrature_effort_flags_are_named_as_flags() {
    for (flag, value) in [
        ("--max-subintervals", "0"),
        ("--rel-tol", "NaN"),
        ("--max-half-periods", "0"),
    ] {
        let err = common::cli_fails(1, &["analyze", "data/conveyor-idler.toml", flag, value], &root());
        assert!(err.contains(&format!("`{flag}` = {value}")), "{err}");
    }
}

/// Left open by the CLI-command family: `transient --monte-carlo -o TARGET` checked its target only after
/// the exact route, so a refused target cost the route's work and left its pictures behind. The target is
/// now checked with the picture directory, before any work: the scenario itself as `-o` is refused and
/// no picture is written.
#[test]
fn a_transient_run_checks_its_target_before_the_exact_route() {
    let dir = scratch("transient-target-first");
    std::fs::create_dir_all(&dir).unwrap();
    let scenario = dir.join("car.toml");
    std::fs::copy(root().join("data/quarter-car-accelerating.toml"), &scenario).unwrap();
    let before = std::fs::read(&scenario).unwrap();
    let pictures = dir.join("pictures");
    let p = |x: &Path| x.to_str().unwrap().to_string();
    let args = [
        "transient",
        &p(&scenario),
        "--monte-carlo",
        "4",
        "-o",
        &p(&scenario),
        "--overwrite",
        "--plots",
        &p(&pictures),
    ];
    let err = common::cli_fails(1, &args, &root());
    assert!(err.contains("car.toml"), "{err}");
    assert_eq!(std::fs::read(&scenario).unwrap(), before, "the scenario is untouched");
    let drawn = std::fs::read_dir(&pictures).map(|d| d.count()).unwrap_or(0);
    assert_eq!(drawn, 0, "no picture before the target was checked");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Found in the final review: `transient --road-grid --road-step 1e-30` panicked ("attempt to multiply with
/// overflow": ⌈step·v/Δx⌉ cast to an integer count), and `--substeps` of 2⁶⁴ − 1 overflowed the product of
/// intervals and substeps. Both counts are now formed in f64 and bounded (`MAX_STEPS_PER_REALIZATION`)
/// before any work, and the error names the flag; nothing is written. "Before any work" includes the
/// exact route and the analytic curves (seconds for this scenario): the size is checked right after the
/// scenario is read, on the road grid and on the exact route's own Monte Carlo alike, so each refusal here
/// takes milliseconds. The exact route's case also asks for its pictures (`--plots`), which the exact route
/// draws before a Monte Carlo starts: none may exist after the refusal.
#[test]
fn a_tiny_road_step_or_huge_substeps_is_refused_by_its_flag() {
    let dir = scratch("road-step-bound");
    std::fs::create_dir_all(&dir).unwrap();
    let run = dir.join("run.h5");
    let pictures = dir.join("pictures");
    let p = |x: &Path| x.to_str().unwrap().to_string();
    let plots = p(&pictures);
    let base = [
        "transient",
        "data/quarter-car-accelerating.toml",
        "--monte-carlo",
        "4",
        "-o",
        &p(&run),
    ];
    let huge = "18446744073709551615";
    let cases: [(&str, &[&str]); 3] = [
        ("--road-step", &["--road-grid", "--road-step", "1e-30"]),
        ("--substeps", &["--road-grid", "--substeps", huge]),
        ("--substeps", &["--substeps", huge, "--plots", &plots]),
    ];
    for (flag, extra) in cases {
        let mut args = base.to_vec();
        args.extend(extra);
        let err = common::cli_fails(1, &args, &root());
        assert!(
            err.contains(flag) && err.contains("per realization"),
            "{extra:?}: {err}"
        );
    }
    assert!(common::listing(&dir).is_empty(), "nothing written");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Found in the final review: `optimize --pareto … --points 18446744073709551615` searched on with no
/// estimate. The front is now checked after its two ends: its list against the memory, and its inner
/// searches, each costing about one end's search, against `--max-hours`. A million points under a cap of
/// 3.6 s needs every search to take under 3.6 µs; one evaluation of the quarter car alone takes longer.
#[test]
fn a_pareto_front_of_absurdly_many_points_is_refused_by_name() {
    let base = [
        "optimize",
        "data/quarter-car-model.toml",
        "--param",
        "model.suspension_damping=0.2:6 kN*s/m",
        "--minimize",
        "sigma(body_acc)",
        "--pareto",
        "sigma(travel)",
    ];
    for extra in [
        &["--points", "18446744073709551615"][..],
        &["--points", "1000000", "--max-hours", "0.001"][..],
    ] {
        let mut args = base.to_vec();
        args.extend(extra);
        let err = common::cli_fails(1, &args, &root());
        assert!(err.contains("--points") && err.contains("fewer --points"), "{err}");
    }
}
