//! Everything that ran can be drawn, every model can be replayed, and an installed binary works anywhere:
//! before, `simulate … --store-raw --plots DIR` and `plot RUN.h5` failed on runs with comfort axes
//! ("`seat_acc_Wk` is not an output of the stored scenario", exit 1 after a complete run); `replay` refused
//! every model whose base input enters through a damper (a derivative feedthrough E u̇); and the spectrum
//! catalogue was found through the build directory, so a copied binary could not find `iso8608-d`.

use crate::common::{self, root, tolerance, SpawnSerial};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use stochvib::scenario::load_scenario;
use stochvib::study::replay::{replay_scenario, ScenarioReplayOptions};

fn scratch(tag: &str) -> PathBuf {
    crate::common::scratch_dir("drawn", tag)
}

fn run(exe: &Path, args: &[&str], cwd: &Path) -> Output {
    Command::new(exe)
        .current_dir(cwd)
        .env_remove("STOCHVIB_SPECTRA")
        .args(args)
        .output_serial()
        .unwrap()
}

fn stochvib(args: &[&str], cwd: &Path) -> Output {
    let o = run(Path::new(crate::common::cli_bin()), args, cwd);
    assert!(
        o.status.success(),
        "`{}`: {}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// A run of a scenario with a comfort axis and raw data is drawn by `simulate --plots` and by `plot`: every
/// output, the weighted one `seat_acc_Wk` included, gets its Welch, realization, histogram and correlation
/// pictures; the weighted output's model correlation comes from the scenario's system extended by the Wk
/// filter, and its K(0) is the weighted output's analytic variance.
#[test]
fn a_run_with_comfort_axes_is_drawn() {
    let _serial = common::hdf5_serial(); // no fork while a file of this binary is open
    let d = scratch("comfort");
    let sc = root().join("data/operator-seat-verdicts.toml");
    let run_file = d.join("run.h5");
    let (pics, pics2) = (d.join("pictures"), d.join("again"));
    stochvib(
        &[
            "simulate",
            sc.to_str().unwrap(),
            "--realizations",
            "4",
            "--dt",
            "0.002",
            "--duration",
            "8",
            "--store-raw",
            "--spectra-dir",
            root().join("spectra").to_str().unwrap(),
            "-o",
            run_file.to_str().unwrap(),
            "--plots",
            pics.to_str().unwrap(),
        ],
        &d,
    );
    stochvib(&["plot", run_file.to_str().unwrap(), "-o", pics2.to_str().unwrap()], &d);
    for dir in [&pics, &pics2] {
        let n = common::listing(dir);
        for kind in ["welch", "realizations", "histogram", "correlation"] {
            for ext in ["svg", "png"] {
                let f = format!("seat_acc_Wk-{kind}.{ext}");
                assert!(n.contains(&f), "{f} missing in {n:?}");
            }
        }
    }
    let charts = stochvib::plot::run_plots::run_charts(&run_file, &root().join("spectra")).unwrap();
    let w = charts.iter().find(|c| c.output == "seat_acc_Wk").unwrap();
    let c = w.correlation.as_ref().unwrap();
    assert!(c.series[1].name.contains("of the scenario"), "{}", c.series[1].name);
    let k0 = c.series[1].points[0].1;
    let sigma = stochvib::store::RunFile::open(&run_file)
        .unwrap()
        .statistics()
        .unwrap()
        .iter()
        .find(|s| s.output == "seat_acc_Wk")
        .unwrap()
        .get("sigma")
        .unwrap()
        .analytic
        .unwrap();
    // the model's K(0) is the integral of the weighted density up to the Nyquist frequency; the Wk filter
    // (band-limited at 400 Hz, above the 250 Hz of Δt = 2 ms) leaves a tail above it of a few per cent
    assert!(
        k0 > 0.5 * sigma * sigma && k0 <= sigma * sigma * (1.0 + 1e-6),
        "K(0) = {k0}, σ² = {}",
        sigma * sigma
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// |H(iω)| of ẍ₁ for the scraper with a rigid cab, m₁ẍ₁ + b₁ẋ₁ + c₁x₁ = c₁q + b₁q̇ (book (8.64)), in
/// ω₁² = c₁/m₁ and ζ₁ = b₁/(2m₁ω₁): H(iω) = −ω²(ω₁² + 2iζ₁ω₁ω)/(ω₁² − ω² + 2iζ₁ω₁ω); for x₁ without the −ω².
fn scraper_gain(omega: f64, omega1: f64, zeta1: f64, acceleration: bool) -> f64 {
    let num = (omega1.powi(4) + (2.0 * zeta1 * omega1 * omega).powi(2)).sqrt();
    let den = ((omega1 * omega1 - omega * omega).powi(2) + (2.0 * zeta1 * omega1 * omega).powi(2)).sqrt();
    num / den * if acceleration { omega * omega } else { 1.0 }
}

/// The amplitude √(a² + b²) of the least-squares fit y ≈ a sin ωt + b cos ωt + c (exact for a pure
/// sinusoid over any window).
fn fitted_amplitude(t: &[f64], y: &[f64], omega: f64) -> f64 {
    use nalgebra::{DMatrix, DVector};
    let x = DMatrix::from_fn(t.len(), 3, |k, j| match j {
        0 => (omega * t[k]).sin(),
        1 => (omega * t[k]).cos(),
        _ => 1.0,
    });
    let coef = (x.transpose() * &x)
        .lu()
        .solve(&(x.transpose() * DVector::from_column_slice(y)))
        .unwrap();
    coef[0].hypot(coef[1])
}

/// `replay` of a model whose base input enters through a damper: the scraper with a rigid cab on a
/// sinusoidal profile (A = 1 cm, λ = 2 m, 200 samples per period) at its scenario speed of 10 m/s. After
/// the transient (skip 100 m = 10 s, 18 decay times 1/(ζ₁ω₁)), the amplitudes of x₁ and of ẍ₁ — whose
/// output has the derivative feedthrough (b₁/m₁)·q̇ — are |H(iω)|·A with ω = 2πv/λ, to
/// `REPLAY_SINE_AMPLITUDE`. The sprung cab (the cab on mounts) replays through the command-line tool.
#[test]
fn replay_of_a_derivative_base_input_matches_the_frequency_response() {
    let d = scratch("replay-sine");
    let (amplitude, wavelength, step, n) = (0.01, 2.0, 0.01, 20_001);
    let mut csv = String::from("distance [m], left [m]\n");
    for k in 0..n {
        let x = k as f64 * step;
        csv.push_str(&format!(
            "{x},{}\n",
            amplitude * (2.0 * std::f64::consts::PI * x / wavelength).sin()
        ));
    }
    let profile = d.join("sine.csv");
    std::fs::write(&profile, csv).unwrap();
    let sc = load_scenario(&root().join("data/scraper-rigid-cab.toml"), &root().join("spectra")).unwrap();
    let opts = ScenarioReplayOptions {
        skip_m: Some(100.0),
        detrend: stochvib::road::Detrend::Mean,
        ..Default::default()
    };
    let r = replay_scenario(&sc, &profile, &opts).unwrap();
    let v = r.replay.speed_m_s;
    let omega = 2.0 * std::f64::consts::PI * v / wavelength;
    // the scenario's parameters: ω₁ = 18.5 rad/s, ζ₁ = 0.1 (data/scraper-rigid-cab.toml)
    let (omega1, zeta1) = (18.5, 0.1);
    let kept = r.replay.history[0].len();
    let t: Vec<f64> = (0..kept)
        .map(|k| (r.replay.skip_samples + k) as f64 * r.replay.dt_s)
        .collect();
    for o in &r.outputs {
        let name = &o.replayed.name;
        let expected = amplitude * scraper_gain(omega, omega1, zeta1, name == "x1_acc");
        let got = fitted_amplitude(&t, &r.replay.history[o.index], omega);
        assert!(
            common::rel(got, expected) <= tolerance::REPLAY_SINE_AMPLITUDE,
            "{name}: amplitude {got} vs |H(iω)|·A = {expected}"
        );
    }
    assert!(r.outputs.iter().any(|o| o.replayed.name == "x1_acc"));
    // the cab on mounts, through the command-line tool, with its history written
    let sprung = root().join("data/scraper-sprung-cab.toml");
    let o = stochvib(
        &[
            "replay",
            sprung.to_str().unwrap(),
            profile.to_str().unwrap(),
            "--skip",
            "100",
            "--spectra-dir",
            root().join("spectra").to_str().unwrap(),
            "-o",
            "history.csv",
        ],
        &d,
    );
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("x2_acc"), "{out}");
    let _ = std::fs::remove_dir_all(&d);
}

/// The binary copied alone to an empty directory (as `cargo install` leaves it) analyses a scenario that
/// names `iso8608-d` from the built-in catalogue, lists the catalogue, and never names the build directory
/// in a message; a `./spectra` directory still wins over the built-in catalogue.
#[test]
fn an_installed_binary_works_from_an_empty_directory() {
    let d = scratch("installed");
    let bin = d.join("bin");
    let work = d.join("work");
    std::fs::create_dir_all(&bin).unwrap();
    std::fs::create_dir_all(&work).unwrap();
    let exe = bin.join("stochvib");
    std::fs::copy(crate::common::cli_bin(), &exe).unwrap();
    let text = std::fs::read_to_string(root().join("data/quarter-car.toml"))
        .unwrap()
        .replace("spectrum = \"iso8608-c\"", "spectrum = \"iso8608-d\"");
    assert!(text.contains("iso8608-d"));
    std::fs::write(work.join("car.toml"), &text).unwrap();
    std::fs::write(work.join("missing.toml"), text.replace("iso8608-d", "iso8608-z")).unwrap();
    let build_dir = crate::common::root().display().to_string();
    let build_dir = build_dir.as_str();
    let analyze = run(&exe, &["analyze", "car.toml", "--json"], &work);
    let out = String::from_utf8_lossy(&analyze.stdout);
    assert!(analyze.status.success(), "{}", String::from_utf8_lossy(&analyze.stderr));
    assert!(out.contains("iso8608-d") && !out.contains(build_dir), "{out}");
    let spectra = run(&exe, &["spectra"], &work);
    let listed = String::from_utf8_lossy(&spectra.stdout);
    assert!(
        spectra.status.success() && listed.contains("iso8608-d") && !listed.contains(build_dir),
        "{listed}"
    );
    let missing = run(&exe, &["analyze", "missing.toml"], &work);
    let e = String::from_utf8_lossy(&missing.stderr);
    assert!(
        !missing.status.success() && e.contains("iso8608-z") && e.contains("<built-in>"),
        "{e}"
    );
    assert!(!e.contains(build_dir), "{e}");
    // an override directory wins: class E under the name iso8608-d (G_d four times that of class D) gives
    // twice the σ of every output of this linear model
    let sigma = |o: &Output| -> f64 {
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v["outputs"][0]["statistics"]["sigma"].as_f64().unwrap()
    };
    std::fs::create_dir_all(work.join("spectra")).unwrap();
    let d_text = std::fs::read_to_string(root().join("spectra/iso8608-d.toml")).unwrap();
    let rougher = d_text.replace("class = \"D\"", "class = \"E\"");
    assert_ne!(rougher, d_text, "the class D file names its class");
    std::fs::write(work.join("spectra/iso8608-d.toml"), rougher).unwrap();
    let local = run(&exe, &["analyze", "car.toml", "--json"], &work);
    assert!(local.status.success(), "{}", String::from_utf8_lossy(&local.stderr));
    let ratio = sigma(&local) / sigma(&analyze);
    assert!(common::rel(ratio, 2.0) <= tolerance::EXACT, "σ ratio {ratio}");
    let _ = std::fs::remove_dir_all(&d);
}
