//! Monte Carlo end to end: every catalogue model with a finite-variance output against its analytic σ, the
//! HDF5 file read back by the crate and by h5py, interruption and resume, and the `simulate`/`inspect` CLI.
//!
//! Every statistical assertion is seeded (the suite is deterministic) and states the probability that it
//! would fail for a correct implementation under a fresh seed.

use crate::common;
use crate::common::SpawnSerial;
use std::path::{Path, PathBuf};
use stochvib::scenario::{load_scenario, Scenario};
use stochvib::simulate::{Route, RunOptions, RunSummary};
use stochvib::store::{tmp_path, OutputStatistics, RunFile, SignalGroup, Statistic};

/// Per-output false-failure probability of the coverage test. The catalogue below has 30 simulated outputs
/// (2 + 2 + 2 + 2 + 4 + 5 + 3 + 2 + 4 + 4), so by the union bound the whole coverage test fails falsely with
/// probability ≤ 30 · 2e-8 = 6e-7 ≤ 1e-6. The nominal level rests on the central limit theorem for the
/// mean of the independent per-realization time-average variances v_i (see `src/simulate/run.rs`); the v_i
/// are mildly skewed, so the level is approximate in the far tail — which is why the per-output level is set
/// well below the 1e-6 budget.
const P_FALSE: f64 = 2e-8;

use common::root;

fn scenario(name: &str) -> Scenario {
    load_scenario(&root().join("data").join(name), &root().join("spectra")).unwrap()
}

fn scratch_dir(tag: &str) -> PathBuf {
    crate::common::scratch_kept("mc-pipeline", tag)
}

/// Statistic `name` of a simulated output.
fn stat<'a>(o: &'a OutputStatistics, name: &str) -> &'a Statistic {
    o.get(name)
        .unwrap_or_else(|| panic!("{}: no statistic {name}", o.output))
}

fn fresh(path: &Path) -> &Path {
    let _ = std::fs::remove_file(path);
    let _ = std::fs::remove_file(tmp_path(path));
    path
}

#[test]
fn catalogue_monte_carlo_sigma_covers_analytic() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
                                         // (file, Δt s, duration s, expected route, number of simulated outputs). Δt resolves the fastest
                                         // dynamics (and, for the spectral route, puts the Nyquist frequency above the input band: quarter car
                                         // 2.83 cycles/m · 20 m/s = 56.6 Hz < 1/(2·0.005 s) = 100 Hz) and makes track delays whole steps
                                         // (balancer bogie 0.6 m / 5 m/s = 0.12 s = 12 steps; half car 2.7 m / 10 m/s = 0.27 s = 27 steps).
                                         // Durations resolve the lower edge of the road band: the ISO road density grows like ω⁻² down to
                                         // 0.011 cycles/m · v, and a grid Δω = 2π/T coarser than that edge misses a visible part of the
                                         // displacement variance (half car at 10 m/s: edge 0.69 rad/s, so T = 60 s, Δω = 0.105 rad/s).
                                         // The conveyor idler is also forced through the spectral route: the only single-input (non-track)
                                         // spectral case, checking the periodic steady state computed in the frequency domain and the discrete
                                         // variance of an independent input.
    let cases: [(&str, f64, f64, Route, usize); 10] = [
        ("balancer-bogie.toml", 0.01, 10.0, Route::Spectral, 2),
        ("conveyor-idler.toml", 0.01, 40.0, Route::Spectral, 2),
        ("conveyor-idler.toml", 0.01, 10.0, Route::Exact, 2),
        ("scraper-rigid-cab.toml", 0.005, 10.0, Route::Exact, 2),
        ("scraper-sprung-cab.toml", 0.01, 10.0, Route::Exact, 4),
        ("half-car.toml", 0.01, 60.0, Route::Spectral, 5),
        ("operator-seat.toml", 0.01, 10.0, Route::Exact, 3),
        ("isolator-single.toml", 0.01, 10.0, Route::Exact, 2),
        ("isolator-two-stage.toml", 0.005, 10.0, Route::Exact, 4),
        ("quarter-car.toml", 0.005, 20.0, Route::Spectral, 4),
    ];
    let dir = scratch_dir("catalogue");
    let mut total = 0;
    let mut failures = Vec::new();
    for (k, (file, dt, dur, route, n_out)) in cases.iter().enumerate() {
        let sc = scenario(file);
        let mut opts = RunOptions {
            realizations: 600,
            duration_s: *dur,
            dt_s: *dt,
            seed: 1000 + k as u64,
            ..RunOptions::default()
        };
        opts.confidence = 1.0 - P_FALSE;
        if k == 1 {
            opts.route = Route::Spectral;
        }
        let out = dir.join(format!("{k}-{}", file.replace(".toml", ".h5")));
        let s = sc.simulate(&opts, fresh(&out), &|_, _| {}).unwrap();
        assert_eq!(s.route, *route, "{file}: route");
        assert_eq!(s.outputs.len(), *n_out, "{file}: simulated outputs {:?}", s.skipped);
        total += s.outputs.len();
        for o in &s.outputs {
            let (sigma, mean) = (stat(o, "sigma"), stat(o, "mean"));
            let (sa, sd) = (sigma.analytic.unwrap(), stat(o, "sigma_discrete").analytic.unwrap());
            let reference = match s.route {
                // Exact route: the simulated samples are exactly those of the stationary response, so the
                // discrete variance (stationary covariance of the Van Loan discretisation, discrete Lyapunov
                // equation) equals the analytic one (continuous Lyapunov / integral table) up to the
                // factorisation error.
                Route::Exact => {
                    assert!(
                        (sd - sa).abs() <= common::tolerance::FACTORISATION * sa,
                        "{file}/{}: discrete {sd:e} vs analytic {sa:e}",
                        o.output
                    );
                    sa
                }
                // Spectral route: the synthesised input is the spectrum on the FFT grid (truncated at Nyquist,
                // piecewise constant between bins), so the Monte Carlo estimates without bias the variance of
                // that discretised process (module docs of src/simulate/run.rs), computed exactly from the
                // discrete transfer function. That is the reference: testing the analytic σ instead would make
                // the false-failure probability depend on the ratio of the deterministic grid bias to the
                // interval width (with 600 realizations the quarter car's tyre force, bias 0.75 %, already
                // falls outside). The grid bias itself must stay small, as the grids cover the input band
                // (tolerance::SPECTRAL_GRID_BIAS).
                _ => {
                    assert!(
                        (sd - sa).abs() < common::tolerance::SPECTRAL_GRID_BIAS * sa,
                        "{file}/{}: discrete {sd:e} vs analytic {sa:e}",
                        o.output
                    );
                    sd
                }
            };
            eprintln!(
                "{file:<26} {:<13} analytic σ {sa:.6e}  discrete σ {sd:.6e}  MC σ {:.6e} [{:.6e}, {:.6e}]",
                o.output, sigma.interval.estimate, sigma.interval.lower, sigma.interval.upper
            );
            if !sigma.interval.covers(reference) {
                failures.push(format!(
                    "{file}/{}: {reference:e} not in {:?}",
                    o.output, sigma.interval
                ));
            }
            // the mean of the zero-mean fluctuation covers 0 (same confidence; its 30 assertions are covered
            // by a second union bound of 6e-7)
            assert!(mean.interval.covers(0.0), "{file}/{}: {:?}", o.output, mean.interval);
        }
    }
    assert_eq!(total, 30, "the union bound above counts 30 outputs");
    assert!(failures.is_empty(), "{failures:#?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn delays_must_be_whole_steps_and_bad_options_are_refused() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let dir = scratch_dir("errors");
    let sc = scenario("half-car.toml");
    // half car: wheelbase delay 2.7 m / 10 m/s = 0.27 s, not a multiple of 0.007 s (0.27/0.007 = 38.57)
    let e = sc
        .simulate(
            &RunOptions {
                realizations: 4,
                duration_s: 2.0,
                dt_s: 0.007,
                seed: 1,
                ..RunOptions::default()
            },
            &dir.join("a.h5"),
            &|_, _| {},
        )
        .unwrap_err();
    assert!(e.to_string().contains("not an integer number of steps"), "{e}");
    // the exact route cannot represent a pure delay
    let mut o = RunOptions {
        realizations: 4,
        duration_s: 2.0,
        dt_s: 0.01,
        seed: 1,
        ..RunOptions::default()
    };
    o.route = Route::Exact;
    assert!(sc.simulate(&o, &dir.join("b.h5"), &|_, _| {}).is_err());
    // one realization gives no interval; too short a record gives no Welch segment
    assert!(sc
        .simulate(
            &RunOptions {
                realizations: 1,
                duration_s: 2.0,
                dt_s: 0.01,
                seed: 1,
                ..RunOptions::default()
            },
            &dir.join("c.h5"),
            &|_, _| {}
        )
        .is_err());
    assert!(sc
        .simulate(
            &RunOptions {
                realizations: 4,
                duration_s: 0.05,
                dt_s: 0.01,
                seed: 1,
                ..RunOptions::default()
            },
            &dir.join("d.h5"),
            &|_, _| {}
        )
        .is_err());
    assert!(!dir.join("a.h5").exists() && !tmp_path(&dir.join("a.h5")).exists());
    let _ = std::fs::remove_dir_all(&dir);
}

fn small_opts(seed: u64) -> RunOptions {
    let mut o = RunOptions {
        realizations: 8,
        duration_s: 2.0,
        dt_s: 0.01,
        seed,
        ..RunOptions::default()
    };
    o.shard_size = 2;
    o
}

#[test]
fn run_file_read_back_by_crate_and_h5py() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let dir = scratch_dir("readback");
    let sc = scenario("conveyor-idler.toml");
    let mut opts = RunOptions {
        realizations: 6,
        duration_s: 3.0,
        dt_s: 0.01,
        seed: 77,
        ..RunOptions::default()
    };
    opts.shard_size = 4;
    opts.store_raw = true;
    let path = dir.join("run.h5");
    let s = sc.simulate(&opts, fresh(&path), &|_, _| {}).unwrap();
    assert_eq!(s.path, path);
    assert!(!tmp_path(&path).exists());
    // the crate's reader: metadata, raw rows, statistics equal to the summary
    let run = RunFile::open(&path).unwrap();
    let m = run.metadata();
    assert_eq!((m.seed, m.n_realizations, m.n_samples, m.shard_size), (77, 6, 300, 4));
    assert_eq!(m.scenario_text, sc.text);
    let names: Vec<&str> = m.outputs.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["y", "y_vel"]);
    let raw = run.read_signals(SignalGroup::Outputs, "y", 0..6).unwrap();
    assert_eq!(raw.dim(), (6, 300));
    let stats = run.statistics().unwrap();
    // the summary's statistics are those stored in the file, to the last bit
    assert_eq!(stats, s.outputs);
    for o in &s.outputs {
        let var = stat(o, "variance");
        // the time-average variance of the stored raw rows is the MC variance estimate (the same samples;
        // summed here left to right, by the run in eight partial sums: equal to rounding)
        if o.output == "y" {
            let v: f64 = raw
                .rows()
                .into_iter()
                .map(|r| r.iter().map(|x| x * x).sum::<f64>() / 300.0)
                .sum::<f64>()
                / 6.0;
            assert!((v - var.interval.estimate).abs() <= common::tolerance::EXACT * v);
        }
    }
    let psd = run.psd().unwrap();
    assert_eq!(psd.len(), 2);
    assert_eq!(psd[0].omega.len(), psd[0].density.len());
    drop(run);
    // h5py: an independent reader of the same file
    let script = r#"
import sys
try:
    import h5py
except ImportError:
    print("h5py is missing: run `bash scripts/ensure-deps.sh --with-h5py`"); sys.exit(3)
f = h5py.File(sys.argv[1], "r")
a = f.attrs
assert int(a["format_version"]) == 2, a["format_version"]
assert int(a["seed"]) == 77 and int(a["n_realizations"]) == 6 and int(a["n_samples"]) == 300
assert float(a["dt"]) == 0.01 and int(a["complete"]) == 1  # a float64 attribute: stored bit for bit
assert f["outputs/y"].shape == (6, 300), f["outputs/y"].shape
for o in ("y", "y_vel"):
    s = f["statistics/" + o + "/sigma"]
    assert s.shape == (), s.shape
    assert float(s.attrs["lower"]) <= float(s[()]) <= float(s.attrs["upper"])
    n = f["psd/" + o + "/omega"].shape
    for d in ("density", "lower", "upper", "analytic"):
        assert f["psd/" + o + "/" + d].shape == n, (o, d)
print("%r %r" % (float(f["statistics/y/sigma"][()]), float(f["statistics/y_vel/sigma"][()])))
"#;
    let out = std::process::Command::new("python3")
        .arg("-c")
        .arg(script)
        .arg(&path)
        .output_serial()
        .expect("python3 must be installed (scripts/ensure-deps.sh --with-h5py)");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "h5py check FAILED: {stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let got: Vec<f64> = stdout.split_whitespace().map(|t| t.parse().unwrap()).collect();
    let sigmas: Vec<f64> = s.outputs.iter().map(|o| stat(o, "sigma").interval.estimate).collect();
    assert_eq!(got, sigmas);
    let _ = std::fs::remove_dir_all(&dir);
}

const KILL_ENV: &str = "STOCHVIB_MC_PIPELINE_KILL_PATH";

/// Child half of `killed_run_leaves_no_final_file_and_resumes`: when started by it (environment variable
/// set), runs 4 shards and aborts the process after the second. Without the variable it does nothing.
#[test]
#[ignore = "child process of killed_run_leaves_no_final_file_and_resumes"]
fn child_interrupted_run() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let Ok(path) = std::env::var(KILL_ENV) else { return };
    let sc = scenario("conveyor-idler.toml");
    let _ = sc.simulate(&small_opts(5), Path::new(&path), &|done, _| {
        if done >= 2 {
            std::process::abort();
        }
    });
    unreachable!("the run must abort after two shards");
}

#[test]
fn killed_run_leaves_no_final_file_and_resumes() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let dir = scratch_dir("kill");
    let path = dir.join("killed.h5");
    fresh(&path);
    let status = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--ignored",
            "--exact",
            "mc_pipeline::child_interrupted_run",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(KILL_ENV, &path)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status_serial()
        .unwrap();
    assert!(!status.success(), "the child must have been aborted");
    assert!(
        !path.exists(),
        "a killed run must not leave a file under the final name"
    );
    assert!(
        tmp_path(&path).exists(),
        "the killed run's temporary file must remain for resuming"
    );
    assert!(
        RunFile::open(tmp_path(&path)).is_err(),
        "RunFile::open must refuse the .tmp"
    );
    assert!(RunFile::open(&path).is_err());
    let sc = scenario("conveyor-idler.toml");
    let resumed = sc.simulate(&small_opts(5), &path, &|_, _| {}).unwrap();
    assert_eq!(resumed.resumed_shards, 2);
    assert_eq!(resumed.n_shards, 4);
    let whole_path = dir.join("whole.h5");
    let whole = sc.simulate(&small_opts(5), fresh(&whole_path), &|_, _| {}).unwrap();
    assert_eq!(whole.resumed_shards, 0);
    let bits = |s: &RunSummary| -> Vec<u64> {
        s.outputs
            .iter()
            .flat_map(|o| {
                let (s, m) = (stat(o, "sigma").interval, stat(o, "mean").interval);
                [s.estimate, s.lower, s.upper, m.estimate]
            })
            .map(f64::to_bits)
            .collect()
    };
    assert_eq!(bits(&resumed), bits(&whole), "resumed statistics must be bit-identical");
    let (a, b) = (RunFile::open(&path).unwrap(), RunFile::open(&whole_path).unwrap());
    let (pa, pb) = (a.psd().unwrap(), b.psd().unwrap());
    for (x, y) in pa.iter().zip(&pb) {
        assert_eq!(
            x.density.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            y.density.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
    }
    drop((a, b));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn simulate_and_inspect_cli() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let dir = scratch_dir("cli");
    let path = dir.join("cli.h5");
    fresh(&path);
    let bin = crate::common::cli_bin();
    let out = std::process::Command::new(bin)
        .current_dir(root())
        .args([
            "simulate",
            "data/conveyor-idler.toml",
            "--realizations",
            "20",
            "--duration",
            "5",
            "--dt",
            "0.01",
        ])
        .args(["--seed", "9", "--shard-size", "5", "--store-raw", "--json", "-o"])
        .arg(&path)
        .output_serial()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("shard 4/4"), "progress: {stderr}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["route"], "exact");
    assert_eq!(v["n_realizations"], 20);
    assert_eq!(v["outputs"].as_array().unwrap().len(), 2);
    // a finished file is not overwritten
    let again = std::process::Command::new(bin)
        .current_dir(root())
        .args([
            "simulate",
            "data/conveyor-idler.toml",
            "--realizations",
            "20",
            "--duration",
            "5",
            "--dt",
            "0.01",
            "-o",
        ])
        .arg(&path)
        .output_serial()
        .unwrap();
    assert!(!again.status.success());
    let inspect = std::process::Command::new(bin)
        .arg("inspect")
        .arg(&path)
        .output_serial()
        .unwrap();
    assert!(inspect.status.success());
    let text = String::from_utf8_lossy(&inspect.stdout);
    assert!(text.contains("complete") && text.contains("y_vel"), "{text}");
    let inspect = std::process::Command::new(bin)
        .args(["inspect", "--json"])
        .arg(&path)
        .output_serial()
        .unwrap();
    let j: serde_json::Value = serde_json::from_slice(&inspect.stdout).unwrap();
    assert_eq!(j["n_realizations"], 20);
    assert_eq!(j["seed"], 9);
    assert_eq!(j["statistics"].as_array().unwrap().len(), 2);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Raw input processes are stored beside the outputs, on both routes. Exact route (conveyor idler, lump
/// load K_F = D_F e^{−α|τ|}, D_F = 4e6 N²): the recorded input is the shaping-filter output, stationary
/// from the start, so across 400 independent realizations the per-realization time-averaged variances v_i
/// have mean D_F; their Student-t interval at confidence 1 − 1e-7 covers D_F (false failure ≤ 1e-7, CLT
/// over 400 realizations). Spectral route (half car on a road): the stored road rows are the synthesised
/// profile, and the front/rear relation is checked in the model tests; here only shape and unit.
#[test]
fn raw_inputs_are_stored_on_both_routes() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let dir = scratch_dir("raw-inputs");
    let sc = scenario("conveyor-idler.toml");
    let mut opts = RunOptions {
        realizations: 400,
        duration_s: 20.0,
        dt_s: 0.01,
        seed: 4242,
        ..RunOptions::default()
    };
    opts.store_raw = true;
    opts.shard_size = 100;
    let out = dir.join("conveyor.h5");
    let s = sc.simulate(&opts, fresh(&out), &|_, _| {}).unwrap();
    assert_eq!(s.route, Route::Exact);
    let f = RunFile::open(&out).unwrap();
    let meta = f.metadata();
    assert_eq!(meta.inputs.len(), 1);
    assert_eq!(meta.inputs[0].name, "input");
    assert_eq!(meta.inputs[0].unit, "N");
    let x = f.read_signals(SignalGroup::Inputs, "input", 0..400).unwrap();
    let v: Vec<f64> = x
        .rows()
        .into_iter()
        .map(|r| r.iter().map(|a| a * a).sum::<f64>() / r.len() as f64)
        .collect();
    let iv = stochvib::estimate::mean_interval(&v, 1.0 - 1e-7).unwrap();
    assert!(iv.covers(4.0e6), "{iv:?}");
    let sc = scenario("half-car.toml");
    let mut opts = RunOptions {
        realizations: 4,
        duration_s: 20.0,
        dt_s: 0.01,
        seed: 7,
        ..RunOptions::default()
    };
    opts.store_raw = true;
    let out = dir.join("half-car.h5");
    let s = sc.simulate(&opts, fresh(&out), &|_, _| {});
    match s {
        Ok(_) => {
            let f = RunFile::open(&out).unwrap();
            assert_eq!(f.metadata().inputs[0].name, "road");
            assert_eq!(f.metadata().inputs[0].unit, "m");
            let r = f.read_signals(SignalGroup::Inputs, "road", 0..4).unwrap();
            assert_eq!(r.nrows(), 4);
            assert!(r.iter().any(|v| *v != 0.0));
        }
        Err(e) => panic!("{e}"),
    }
}
