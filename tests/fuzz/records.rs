//! Record-command cases: a measured record (CSV) through `exposure` and `fatigue`, a road profile through
//! `coherence` and `iri`, and `weighting`, each with hostile flags — their generation, their evaluation
//! through the library as the CLI calls it (flag parsing included), and their CLI arguments. The
//! invariants are those of [`super::commands`]: an error names the record, the profile or a flag (the
//! inline `--model` table is named `--model`), quotes a bounded excerpt, and a success prints no NaN or
//! infinity.

use super::commands::{fail, ok};
use super::inputs::{Case, Failure, Outcome};
use super::mutate::Rng;
use rand::RngExt;
use std::path::Path;
use stochvib::units::Dim;
use stochvib::Error;

/// The record commands, in the order of [`pick_command`].
pub const COMMANDS: [&str; 5] = ["exposure", "fatigue", "coherence", "iri", "weighting"];

/// A record of 10 s at 100 Hz: three seat axes (m/s²) and a stress channel (MPa), sums of sines at
/// fixed frequencies and phases (the mutations bring the hostility).
pub fn record_csv() -> String {
    let mut s = String::from("time [s], x [m/s^2], y [m/s^2], z [m/s^2], stress [MPa]\n");
    let w = |f: f64, t: f64, phase: f64| (2.0 * std::f64::consts::PI * f * t + phase).sin();
    for k in 0..1000 {
        let t = k as f64 / 100.0;
        let x = 0.2 * w(1.5, t, 0.3) + 0.05 * w(7.0, t, 1.1);
        let y = 0.15 * w(2.5, t, 2.0) + 0.04 * w(11.0, t, 0.7);
        let z = 0.6 * w(4.0, t, 0.0) + 0.2 * w(9.0, t, 2.4) + 0.1 * w(17.0, t, 1.3);
        let stress = 50.0 + 40.0 * w(2.0, t, 0.5) + 12.0 * w(9.0, t, 1.9) + 4.0 * w(23.0, t, 0.2);
        s.push_str(&format!("{t:.2}, {x:.6}, {y:.6}, {z:.6}, {stress:.5}\n"));
    }
    s
}

fn pick<'a>(rng: &mut Rng, v: &[&'a str]) -> &'a str {
    v[rng.random_range(0..v.len())]
}

/// Pushes `name value` with probability `p`.
fn maybe(rng: &mut Rng, a: &mut Vec<String>, p: f64, name: &str, values: &[&str]) {
    if rng.random_bool(p) {
        a.push(name.to_string());
        a.push(pick(rng, values).to_string());
    }
}

/// The record options every record command shares.
fn record_flags(rng: &mut Rng, a: &mut Vec<String>) {
    maybe(
        rng,
        a,
        0.2,
        "--sample-rate",
        &["100", "50", "0", "-1", "NaN", "1e308", "1e-300", "inf"],
    );
    maybe(
        rng,
        a,
        0.15,
        "--unit",
        &[
            "x=m/s^2",
            "stress=MPa",
            "x",
            "z=furlong",
            "=m",
            "stress=m/s^2",
            "nope=m",
        ],
    );
    if rng.random_bool(0.05) {
        a.push("--decimal-comma".into());
    }
}

fn exposure_flags(rng: &mut Rng, a: &mut Vec<String>) {
    let axes = [
        "x=seat-surface:x",
        "y=seat-surface:y",
        "z=seat-surface:z",
        "z=seat-back:x",
        "stress=feet:z",
        "nope=seat-surface:z",
        "z=seat:z",
        "z=seat-surface:q",
        "z",
        "=seat-surface:z",
        "x=standing-floor:rz",
    ];
    for _ in 0..rng.random_range(0..3) {
        a.push("--axis".into());
        a.push(pick(rng, &axes).into());
    }
    maybe(rng, a, 0.2, "--motion-sickness", &["z", "x", "nope", "stress"]);
    maybe(
        rng,
        a,
        0.3,
        "--exposure",
        &[
            "8 h", "150 min", "0 h", "-1 h", "1e308 h", "NaN h", "8", "8 kg", "1e-300 s",
        ],
    );
    maybe(rng, a, 0.2, "--running", &["linear", "exponential", "cubic"]);
}

fn fatigue_flags(rng: &mut Rng, a: &mut Vec<String>) {
    maybe(rng, a, 0.85, "--channel", &["stress", "x", "nope", "z"]);
    a.push("--sn-slope".into());
    a.push(pick(rng, &["3", "5", "0", "-3", "NaN", "1e308", "1e-300", "40"]).into());
    let points = [
        "80 MPa",
        "160 MPa",
        "0 MPa",
        "-5 MPa",
        "1e308 MPa",
        "80",
        "80 furlong",
        "80 m/s^2",
        "1e-300 MPa",
        "NaN MPa",
    ];
    let which = if rng.random_bool(0.5) {
        "--sn-amplitude"
    } else {
        "--sn-range"
    };
    if rng.random_bool(0.95) {
        a.push(which.into());
        a.push(pick(rng, &points).into());
    }
    maybe(
        rng,
        a,
        0.3,
        "--sn-cycles",
        &["2e6", "0", "-1", "NaN", "1e308", "1", "1e-300"],
    );
    maybe(
        rng,
        a,
        0.2,
        "--endurance",
        &["20 MPa", "0 MPa", "1e308 MPa", "20 m", "-1 MPa"],
    );
    maybe(
        rng,
        a,
        0.3,
        "--mean-stress",
        &["none", "goodman", "gerber", "swt", "bogus"],
    );
    maybe(
        rng,
        a,
        0.3,
        "--ultimate",
        &["500 MPa", "10 MPa", "0 MPa", "-1 MPa", "500 m", "1e308 MPa"],
    );
    maybe(rng, a, 0.2, "--gate", &["1 MPa", "0 MPa", "1e308 MPa", "-1 MPa", "1 m"]);
    maybe(
        rng,
        a,
        0.2,
        "--segment",
        &["0", "1", "2", "64", "1048576", "18446744073709551615"],
    );
}

fn coherence_flags(rng: &mut Rng, a: &mut Vec<String>) {
    let models = [
        "{ kind = \"dodds-robson\", waviness = 2 }",
        "{ kind = \"dodds-robson\", waviness = -1 }",
        "{ kind = \"dodds-robson\", waviness = nan }",
        "{ kind = \"constant\", value = 0.5 }",
        "{ kind = \"constant\", value = 2 }",
        "{ kind = \"ammon-bormann\" }",
        "{ kind = \"nope\" }",
        "{ kind = \"tabulated\", frequencies = [\"0.1 cycles/m\", \"1 cycles/m\"], values = [0.9, 0.1] }",
        "{ kind = \"tabulated\", frequencies = [], values = [] }",
        "not a table",
        "{ kind = \"dodds-robson\", waviness = 2, extra = 1 }",
    ];
    maybe(rng, a, 0.6, "--model", &models);
    maybe(
        rng,
        a,
        0.3,
        "--track-width",
        &["1.5 m", "0 m", "-1 m", "1e308 m", "NaN m", "1.5", "1.5 kg"],
    );
    maybe(
        rng,
        a,
        0.3,
        "--frequency",
        &["0.1,1,10", "0", "-1", "NaN", "1e308", "0.01", "1e-300"],
    );
    maybe(
        rng,
        a,
        0.2,
        "--segment",
        &["0", "1", "2", "64", "1048576", "18446744073709551615"],
    );
    maybe(rng, a, 0.15, "--confidence", &["0.95", "0", "1", "NaN", "1.5"]);
}

/// A record-command case: `args[0]` is the command, then its flags; the file is the record (exposure,
/// fatigue), the profile (coherence's `--profile`, iri's `--profile`) or unused (weighting).
pub fn record_case(cc: &super::commands::CommandCorpus, rng: &mut Rng, case: &mut Case) {
    let cmd = COMMANDS[rng.random_range(0..COMMANDS.len())];
    let mut a = vec![cmd.to_string()];
    match cmd {
        "exposure" | "fatigue" => {
            record_file(rng, case);
            if cmd == "exposure" {
                exposure_flags(rng, &mut a)
            } else {
                fatigue_flags(rng, &mut a)
            }
            record_flags(rng, &mut a);
        }
        "coherence" | "iri" => {
            super::commands::profile_case(cc, rng, case, 0..3);
            if cmd == "coherence" {
                coherence_flags(rng, &mut a);
            } else {
                let spectra = ["iso8608-c", "iso8608-a", "book-8-66", "type1", "nope", "iso8608-h"];
                a.push(pick(rng, &spectra).into());
            }
            // the profile is optional for both
            if rng.random_bool(0.85) {
                a.push("--profile".into());
                a.push("<file>".into());
            }
        }
        _ => {
            case.file_name = "unused.csv".into();
            let names = ["Wk", "Wd", "Wc", "We", "Wj", "Wb", "Wf", "Wz", "wk", ""];
            a.push(pick(rng, &names).into());
            maybe(
                rng,
                &mut a,
                0.4,
                "--frequency",
                &["1,2,4", "0", "-1", "NaN", "1e308", "1e-300"],
            );
            maybe(
                rng,
                &mut a,
                0.4,
                "--sample-rate",
                &["200", "1", "0", "NaN", "1e308", "1e-300", "-5"],
            );
        }
    }
    case.origin = format!("{cmd} {}", case.origin).trim().to_string();
    case.args = a;
}

/// The record CSV with 0–2 mutations of the profile mutator (cells, header, rows, delimiters).
fn record_file(rng: &mut Rng, case: &mut Case) {
    let mut lines: Vec<String> = record_csv().lines().map(str::to_string).collect();
    for _ in 0..rng.random_range(0..3) {
        let d = super::commands::mutate_profile(rng, &mut lines);
        case.raw.push(d);
    }
    let mut out = lines.join("\n");
    out.push('\n');
    case.bytes = out.into_bytes();
    case.origin = "record.csv".into();
    case.file_name = "record.csv".into();
}

// ------------------------------------------------------------------------------------------------------
// Evaluation (as the CLI's handlers in src/main/record_cli.rs: the flags parsed, the library called)
// ------------------------------------------------------------------------------------------------------

/// A step of an evaluation: its value, or the outcome that ends the case (a refusal).
type Step<T> = Result<T, Box<Outcome>>;

/// A flag's values in `args` (repeatable flags give several).
fn values<'a>(args: &'a [String], name: &str) -> Vec<&'a str> {
    args.windows(2)
        .filter(|w| w[0] == name)
        .map(|w| w[1].as_str())
        .collect()
}

fn one<'a>(args: &'a [String], name: &str) -> Option<&'a str> {
    values(args, name).last().copied()
}

/// A refusal by the argument parser (clap) or by the handler's own flag parsing, which names the flag.
fn flag_refusal(flag: &str, value: &str, why: &str) -> Box<Outcome> {
    Box::new(fail(&Error::invalid(flag, value, why), "start"))
}

fn clap(what: String) -> Box<Outcome> {
    Box::new(Outcome::Err(Failure {
        variant: "Clap".into(),
        message: format!("the command line refuses {what}"),
        file: None,
        key: None,
        value: None,
        stage: "start".into(),
    }))
}

/// A number flag as clap parses it (`None`: absent; `Err`: clap refuses it).
fn number<T: std::str::FromStr>(args: &[String], name: &str) -> Step<Option<T>> {
    match one(args, name) {
        None => Ok(None),
        Some(v) => v.parse().map(Some).map_err(|_| clap(format!("{name} {v}"))),
    }
}

/// A comma-separated list of numbers as clap parses it.
fn numbers(args: &[String], name: &str) -> Step<Vec<f64>> {
    match one(args, name) {
        None => Ok(Vec::new()),
        Some(v) => v
            .split(',')
            .map(|x| x.parse().map_err(|_| clap(format!("{name} {v}"))))
            .collect(),
    }
}

fn record_options(args: &[String]) -> Step<stochvib::record::RecordOptions> {
    let units = values(args, "--unit")
        .iter()
        .map(|u| {
            u.split_once('=')
                .map(|(n, v)| (n.trim().to_string(), v.trim().to_string()))
                .ok_or_else(|| flag_refusal("--unit", u, "expected NAME=UNIT"))
        })
        .collect::<Step<Vec<_>>>()?;
    Ok(stochvib::record::RecordOptions {
        sample_rate_hz: number(args, "--sample-rate")?,
        units,
        decimal_comma: args.iter().any(|a| a == "--decimal-comma"),
        ..Default::default()
    })
}

/// Evaluates a record-command case whose file is at `path`.
pub fn evaluate(path: &Path, args: &[String], spectra: &Path) -> Outcome {
    let r = match args[0].as_str() {
        "exposure" => eval_exposure(path, args),
        "fatigue" => eval_fatigue(path, args),
        "coherence" => eval_coherence(path, args),
        "iri" => eval_iri(path, args, spectra),
        _ => eval_weighting(args),
    };
    r.unwrap_or_else(|o| *o)
}

fn lib<T>(r: stochvib::Result<T>, stage: &str) -> Step<T> {
    r.map_err(|e| Box::new(fail(&e, stage)))
}

fn eval_exposure(path: &Path, args: &[String]) -> Step<Outcome> {
    use stochvib::record::{AxisAssignment, ExposureOptions, RunningRms};
    let axes = values(args, "--axis")
        .iter()
        .map(|s| AxisAssignment::parse(s))
        .collect::<stochvib::Result<Vec<_>>>();
    let running = match one(args, "--running") {
        None | Some("linear") => RunningRms::Linear,
        Some("exponential") => RunningRms::Exponential,
        Some(other) => return Err(clap(format!("--running {other}"))),
    };
    let exposure_s = match one(args, "--exposure") {
        None => None,
        Some(t) => {
            Some(stochvib::units::parse_as(t, Dim::TIME).map_err(|e| flag_refusal("--exposure", t, &e.to_string()))?)
        }
    };
    let options = ExposureOptions {
        axes: lib(axes, "start")?,
        motion_sickness: values(args, "--motion-sickness")
            .iter()
            .map(|s| s.to_string())
            .collect(),
        exposure_s,
        running,
        ..ExposureOptions::default()
    };
    let mut reader = lib(stochvib::record::open_record(path, &record_options(args)?), "load")?;
    let r = lib(stochvib::record::evaluate_exposure(reader.as_mut(), &options), "report")?;
    let rep = stochvib::report::record_report::ExposureReport(r);
    let _ = format!("{rep}");
    Ok(ok("exposure", &rep))
}

/// An amplitude-like flag in SI with the S–N curve's dimension (as the handler's `same_dim`).
fn same_dim(flag: &str, text: &str, dim: Dim) -> Step<f64> {
    lib(stochvib::record::quantity_of_dim(flag, text, dim), "start")
}

fn sn_curve(args: &[String]) -> Step<(stochvib::fatigue::SnCurve, Dim)> {
    use stochvib::record::SnPoint;
    let slope: f64 = number(args, "--sn-slope")?.ok_or_else(|| clap("no --sn-slope".into()))?;
    let cycles: f64 = number(args, "--sn-cycles")?.unwrap_or(2e6);
    let point = match (one(args, "--sn-amplitude"), one(args, "--sn-range")) {
        (Some(p), None) => SnPoint::Amplitude(p),
        (None, Some(p)) => SnPoint::Range(p),
        (Some(_), Some(_)) => return Err(clap("--sn-amplitude with --sn-range".into())),
        (None, None) => return Err(flag_refusal("--sn-amplitude", "<none>", "give the S–N curve's point")),
    };
    let sn = stochvib::record::sn_curve_from_flags(slope, point, cycles, one(args, "--endurance"));
    lib(sn, "start")
}

fn eval_fatigue(path: &Path, args: &[String]) -> Step<Outcome> {
    use stochvib::record::{FatigueOptions, MeanStressCorrection};
    let (sn, sn_dim) = sn_curve(args)?;
    let ultimate = || -> Step<f64> {
        let t = one(args, "--ultimate").ok_or_else(|| flag_refusal("--mean-stress", "", "needs --ultimate"))?;
        same_dim("--ultimate", t, sn_dim)
    };
    let mean_stress = match one(args, "--mean-stress").unwrap_or("none") {
        "none" => MeanStressCorrection::None,
        "goodman" => MeanStressCorrection::Goodman { ultimate: ultimate()? },
        "gerber" => MeanStressCorrection::Gerber { ultimate: ultimate()? },
        "swt" => MeanStressCorrection::Swt,
        other => return Err(flag_refusal("--mean-stress", other, "unknown")),
    };
    let gate = match one(args, "--gate") {
        None => None,
        Some(t) => Some(same_dim("--gate", t, sn_dim)?),
    };
    let options = FatigueOptions {
        channel: one(args, "--channel").map(str::to_string),
        sn,
        sn_dim,
        mean_stress,
        gate,
        segment_len: number(args, "--segment")?,
    };
    let mut reader = lib(stochvib::record::open_record(path, &record_options(args)?), "load")?;
    let r = lib(stochvib::record::evaluate_fatigue(reader.as_mut(), &options), "report")?;
    let rep = stochvib::report::record_report::FatigueReport(r);
    let _ = format!("{rep}");
    Ok(ok("fatigue", &rep))
}

fn eval_coherence(path: &Path, args: &[String]) -> Step<Outcome> {
    let width_text = one(args, "--track-width").unwrap_or("1.5 m");
    let width = stochvib::units::parse_as(width_text, Dim::LENGTH)
        .map_err(|e| flag_refusal("--track-width", width_text, &e.to_string()))?;
    let model = match one(args, "--model") {
        None => None,
        Some(t) => Some(lib(stochvib::scenario::coherence_from_toml(t, width), "load")?),
    };
    let profile = one(args, "--profile").map(|_| path);
    let confidence: f64 = number(args, "--confidence")?.unwrap_or(0.95);
    let r = stochvib::study::road_numbers::coherence_report(
        model,
        profile,
        &numbers(args, "--frequency")?,
        number(args, "--segment")?,
        confidence,
    );
    let r = lib(r, "report")?;
    let _ = format!("{r}");
    Ok(ok("coherence", &r))
}

fn eval_iri(path: &Path, args: &[String], spectra: &Path) -> Step<Outcome> {
    let catalogue = stochvib::scenario::Catalogue::new(spectra);
    let spectrum = lib(catalogue.resolve(&args[1], None), "load")?;
    let profile = one(args, "--profile").map(|_| path);
    let r = lib(stochvib::study::road_numbers::iri_report(&spectrum, profile), "report")?;
    let _ = format!("{r}");
    Ok(ok("iri", &r))
}

fn eval_weighting(args: &[String]) -> Step<Outcome> {
    let w = lib(stochvib::comfort::Weighting::parse(&args[1]), "start")?;
    let r = stochvib::study::weighting_table::WeightingReport::new(
        w,
        &numbers(args, "--frequency")?,
        number(args, "--sample-rate")?,
    );
    let r = lib(r, "report")?;
    let _ = format!("{r}");
    Ok(ok("weighting", &r))
}

/// The CLI arguments of a record-command case whose file is at `path`.
pub fn cli_args(case: &Case, path: &Path, spectra: &Path) -> Vec<String> {
    let file = path.display().to_string();
    let mut a: Vec<String> = vec![case.args[0].clone()];
    match case.args[0].as_str() {
        "exposure" | "fatigue" => a.push(file.clone()),
        "iri" => a.extend(["--spectra-dir".to_string(), spectra.display().to_string()]),
        _ => {}
    }
    a.extend(
        case.args[1..]
            .iter()
            .map(|x| if x == "<file>" { file.clone() } else { x.clone() }),
    );
    a
}

/// Whether an error named `name` names a positional argument of the case's command by its role, with the
/// value the user typed in its message: `iri`'s `spectrum`, `weighting`'s `weighting` (they have no flag).
pub fn names_a_positional(case: &Case, name: &str, message: &str) -> bool {
    let role = match case.args.first().map(String::as_str) {
        Some("iri") => "spectrum",
        Some("weighting") => "weighting",
        _ => return false,
    };
    name == role && case.args.get(1).is_some_and(|v| message.contains(v.as_str()))
}

/// Whether the CLI's stderr names a positional argument of the case's command with the value typed: quoted
/// (`"Wz"`), or as the parameter of its role (`` `spectrum` = type1``; an empty one `` `weighting` = ""``).
pub fn cli_names_a_positional(case: &Case, stderr: &str) -> bool {
    let Some(v) = case.args.get(1).filter(|v| !v.starts_with("--")) else {
        return false;
    };
    let role = match case.args[0].as_str() {
        "iri" => "spectrum",
        "weighting" => "weighting",
        _ => return !v.is_empty() && stderr.contains(&format!("\"{v}\"")),
    };
    // an empty positional is named by its role, its value quoted: `weighting` = ""
    if v.is_empty() {
        return stderr.contains(&format!("`{role}` = \"\""));
    }
    stderr.contains(&format!("\"{v}\"")) || stderr.contains(&format!("`{role}` = {v}"))
}

/// A command line for the reproducers.
pub fn command_line(case: &Case, file: &str) -> String {
    let args: Vec<String> = case.args[1..]
        .iter()
        .map(|x| if x == "<file>" { file.to_string() } else { x.clone() })
        .collect();
    match case.args[0].as_str() {
        "exposure" | "fatigue" => format!("stochvib {} {file} {}", case.args[0], args.join(" ")),
        c => format!("stochvib {c} {}", args.join(" ")),
    }
}
