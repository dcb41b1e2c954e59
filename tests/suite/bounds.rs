//! Bounds that mean something: each case here was accepted before and gave a silent wrong answer or did
//! nothing — `kurtosis = 1e9` ran and reported σ = 0 with exit 0 (analytic 1.9e-2); a flat track was
//! classified "class A" with a fitted waviness of −4.46 from rounding noise; `sweep --monte-carlo 0` failed
//! every point and exited 0; `a8_limit` below `a8_action` was accepted; `--track` was ignored on a
//! two-track road, and other flags without effect were ignored silently; a 1-based SLURM array got no
//! warning; a run of many realizations wrote its accumulators' fill before computing.

use crate::common::{self, root};
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::Duration;
use stochvib::simulate::{LaplaceGrid, LaplaceMovingAverage};
use stochvib::spectrum::{Domain, Exponential};

fn scratch(tag: &str) -> PathBuf {
    common::scratch_dir("bounds", tag)
}

fn cli(args: &[&str], cwd: &Path) -> Output {
    common::cli_within(args, cwd, Duration::from_secs(120))
}

fn fails(code: i32, args: &[&str], cwd: &Path) -> String {
    common::cli_fails(code, args, cwd)
}

/// A small run file `name` of the conveyor idler in `dir` (4 realizations of 2 s).
fn small_run(dir: &Path, name: &str) {
    let sc = root().join("data/conveyor-idler.toml");
    let args = [
        "simulate",
        sc.to_str().unwrap(),
        "--realizations",
        "4",
        "--duration",
        "2",
        "--dt",
        "0.01",
    ];
    let o = cli(&[&args[..], &["-o", name]].concat(), dir);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// The quarter car on its class C road with `[input] kurtosis = k`.
fn kurtosis_scenario(dir: &Path, k: &str) -> PathBuf {
    let text = std::fs::read_to_string(root().join("data/quarter-car-model.toml")).unwrap();
    let p = dir.join(format!("kurtosis-{k}.toml"));
    std::fs::write(
        &p,
        text.replace("speed = \"20 m/s\"", &format!("speed = \"20 m/s\"\nkurtosis = {k}")),
    )
    .unwrap();
    p
}

/// The bound of the Laplace moving average on its grid is 3 + r·(N − 3), r = Σf⁴/(Σf²)² of the kernel
/// f_l = N^{−1/2}[s₀ + 2Σ_{0<j<N/2} s_j cos(2πjl/N) + s_{N/2}(−1)^l], s_j = √(S(ω_j)Δω), computed here by direct
/// cosine sums (no FFT): the increments' kurtosis 3(1 + ν̃) may not exceed N, the most N numbers can have
/// (docs of `LaplaceMovingAverage`). Just below it the generator is built, just above it is refused naming
/// `kurtosis`, the bound and what changes it.
#[test]
fn the_kurtosis_bound_is_three_plus_r_times_n_minus_three() {
    let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
    let (n, dt) = (64usize, 0.1);
    let dw = 2.0 * std::f64::consts::PI / (n as f64 * dt);
    let sj: Vec<f64> = (0..=n / 2)
        .map(|j| (stochvib::spectrum::Spectrum::density(&s, j as f64 * dw) * dw).sqrt())
        .collect();
    let f: Vec<f64> = (0..n)
        .map(|l| {
            let mut v = sj[0] + sj[n / 2] * if l % 2 == 0 { 1.0 } else { -1.0 };
            for (j, s) in sj.iter().enumerate().take(n / 2).skip(1) {
                v += 2.0 * s * (2.0 * std::f64::consts::PI * (j * l) as f64 / n as f64).cos();
            }
            v / (n as f64).sqrt()
        })
        .collect();
    let s2: f64 = f.iter().map(|v| v * v).sum();
    let r = f.iter().map(|v| v.powi(4)).sum::<f64>() / (s2 * s2);
    let bound = 3.0 + r * (n as f64 - 3.0);
    let lma = LaplaceMovingAverage::new(
        &s,
        LaplaceGrid {
            dt,
            n,
            kurtosis: bound * (1.0 - 1e-9),
        },
    )
    .unwrap();
    assert!(
        (lma.kernel_ratio() / r - 1.0).abs() < 1e-9,
        "{} vs {r}",
        lma.kernel_ratio()
    );
    let e = LaplaceMovingAverage::new(
        &s,
        LaplaceGrid {
            dt,
            n,
            kurtosis: bound * (1.0 + 1e-9),
        },
    )
    .unwrap_err()
    .to_string();
    for part in ["kurtosis", "at most", &format!("{bound:.4}"), "longer realizations"] {
        assert!(e.contains(part), "{part}: {e}");
    }
}

/// `kurtosis = 1e9` is refused before anything is written, naming the file, `input.kurtosis`, the bound of
/// the run's grid and the fix; a kurtosis of 0.9 of that bound runs and passes the distribution-free check
/// of its Monte Carlo variance (a correct run fails it with probability ≤ 2·10⁻⁷ per output).
#[test]
fn kurtosis_beyond_the_grid_is_refused_and_one_within_runs() {
    let d = scratch("kurtosis");
    let sc = kurtosis_scenario(&d, "1e9");
    let args = ["simulate", sc.to_str().unwrap(), "--realizations", "20", "-o", "k.h5"];
    let e = fails(1, &args, &d);
    for part in [
        "kurtosis-1e9.toml",
        "input.kurtosis",
        "at most 3 + r·(N − 3) =",
        "longer realizations",
    ] {
        assert!(e.contains(part), "{part}: {e}");
    }
    assert!(!d.join("k.h5").exists() && !d.join("k.h5.tmp").exists());
    // the bound of this grid, from the message, and a run at 0.9 of it
    let bound: f64 = e
        .split("(N − 3) = ")
        .nth(1)
        .unwrap()
        .split(':')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let sc = kurtosis_scenario(&d, &format!("{}", (0.9 * bound).floor()));
    let o = cli(
        &["simulate", sc.to_str().unwrap(), "--realizations", "100", "-o", "ok.h5"],
        &d,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&d);
}

/// A profile whose density cannot be estimated or fitted is refused, naming the file and the column: a
/// constant track, a straight line (what is left after its trend is rounding noise of order 10⁻¹⁶ of the
/// elevations), zeros, two rows, fifteen rows. `road` refused none of the flat ones before (class A,
/// w = −4.46), and `replay` and a `measured-profile` spectrum read the same profiles.
#[test]
fn flat_constant_and_short_profiles_are_refused_not_classified() {
    let d = scratch("flat");
    let write = |name: &str, rows: usize, z: &dyn Fn(usize) -> f64| {
        let mut t = String::from("distance [m], left [mm], right [mm]\n");
        for k in 0..rows {
            t.push_str(&format!("{:.2},{:.3},{:.3}\n", k as f64 * 0.05, z(k), z(k)));
        }
        std::fs::write(d.join(name), t).unwrap();
    };
    write("constant.csv", 5000, &|_| 5.0);
    write("ramp.csv", 5000, &|k| 1.0 + 0.001 * k as f64);
    write("zeros.csv", 5000, &|_| 0.0);
    write("two.csv", 2, &|k| k as f64);
    write("fifteen.csv", 15, &|k| (k as f64).sin());
    for (file, why) in [
        ("constant.csv", "flat"),
        ("ramp.csv", "flat"),
        ("zeros.csv", "flat"),
        ("two.csv", "too few rows"),
        ("fifteen.csv", "too few rows"),
    ] {
        let o = cli(&["road", file], &d);
        let e = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{file}: {e}");
        assert!(
            e.contains(file) && e.contains("column left") && e.contains(why),
            "{file}: {e}"
        );
        // refused, not classified: no report, no fitted waviness, no "segment length = 2" for two rows
        assert!(o.stdout.is_empty(), "{}", String::from_utf8_lossy(&o.stdout));
        assert!(
            !e.contains("waviness") && !e.contains("segment length") && !e.contains("panicked"),
            "{e}"
        );
    }
    let sc = root().join("data/quarter-car.toml");
    let e = fails(1, &["replay", sc.to_str().unwrap(), "ramp.csv"], &d);
    assert!(e.contains("ramp.csv") && e.contains("flat"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Elevations whose squares leave the range of f64 are refused, naming the file and the column: one of
/// 10²⁰⁰ mm in row 10 (line 12: the header is line 1), for `road`, `iri --profile` and `replay` (it read "variance
/// estimate: must be finite … the profile is too short or too coarse"); a track of at most 10⁻³⁰⁰ mm, for
/// `road` (it read "the track is flat"); a profile built from arrays, by track and sample; a Welch density
/// whose squares overflow, by bin.
#[test]
fn profiles_whose_squares_leave_f64_are_refused_naming_the_column() {
    let d = scratch("magnitudes");
    let write = |name: &str, z: &dyn Fn(usize) -> f64| {
        let mut t = String::from("distance [m], left [mm], right [mm]\n");
        for k in 0..2000 {
            t.push_str(&format!("{:.2},{:e},{:e}\n", k as f64 * 0.05, z(k), 0.5 * z(k)));
        }
        std::fs::write(d.join(name), t).unwrap();
    };
    let rough = |k: usize| (0.7 * k as f64).sin() + (0.13 * k as f64).cos();
    write("huge.csv", &|k| if k == 10 { 1e200 } else { rough(k) });
    write("tiny.csv", &|k| 1e-300 * rough(k));
    let sc = root().join("data/quarter-car.toml");
    let sc = sc.to_str().unwrap();
    for args in [
        vec!["road", "huge.csv"],
        vec!["iri", "iso8608-c", "--profile", "huge.csv"],
        vec!["replay", sc, "huge.csv"],
    ] {
        let e = fails(1, &args, &d);
        assert!(
            e.contains("huge.csv") && e.contains("line 12, column 2 `left`") && e.contains("1e197 m"),
            "{args:?}: {e}"
        );
    }
    let e = fails(1, &["road", "tiny.csv"], &d);
    assert!(
        e.contains("tiny.csv") && e.contains("column left") && e.contains("below") && !e.contains("flat"),
        "{e}"
    );
    // profiles made from arrays (the Python package) get the same bound, naming the track and the sample
    let track = stochvib::road::Track {
        name: "left".into(),
        elevation_m: vec![0.0, 1e197, 0.0],
    };
    let e = stochvib::road::Profile::new(0.05, 0.0, vec![track])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("track `left` sample 1") && e.contains("larger in magnitude"),
        "{e}"
    );
    // a Welch estimate whose squares overflow names the bin and the cause ("variance estimate = inf" before)
    let x: Vec<f64> = (0..1024).map(|k| 1e197 * (0.3 * k as f64).sin()).collect();
    let est = stochvib::estimate::Welch::new(256, 0.01).unwrap().estimate(&x).unwrap();
    let e = est.intervals(0.95).unwrap_err().to_string();
    assert!(e.contains("density at bin") && e.contains("1e150"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Counts below what a batch needs are refused naming the flag: `sweep --monte-carlo 0` (which failed every
/// point and exited 0), `--monte-carlo 1`, `analyze --monte-carlo 1`, `simulate --realizations 0`,
/// `--shard-size 0`, `--max-hours 0`, `--of 0`.
#[test]
fn zero_counts_are_refused_naming_the_flag() {
    let d = scratch("counts");
    let sc = root().join("data/quarter-car-model.toml");
    let sc = sc.to_str().unwrap();
    let p = "model.sprung_mass=300 kg,310 kg";
    for (args, flag) in [
        (vec!["sweep", sc, "--param", p, "--monte-carlo", "0"], "--monte-carlo 0"),
        (vec!["sweep", sc, "--param", p, "--monte-carlo", "1"], "--monte-carlo 1"),
        (vec!["analyze", sc, "--monte-carlo", "1"], "--monte-carlo 1"),
        (
            vec!["simulate", sc, "--realizations", "0", "-o", "x.h5"],
            "--realizations 0",
        ),
        (
            vec!["simulate", sc, "--realizations", "4", "--shard-size", "0", "-o", "x.h5"],
            "--shard-size",
        ),
        (
            vec!["simulate", sc, "--realizations", "4", "--max-hours", "0", "-o", "x.h5"],
            "--max-hours",
        ),
        (
            vec![
                "simulate",
                sc,
                "--realizations",
                "4",
                "--shard",
                "0",
                "--of",
                "0",
                "-o",
                ".",
            ],
            "--of",
        ),
    ] {
        let e = fails(1, &args, &d);
        assert!(e.contains(flag), "{flag}: {e}");
    }
    assert!(common::listing(&d).is_empty(), "{:?}", common::listing(&d));
    let _ = std::fs::remove_dir_all(&d);
}

/// The Directive's limit values must lie above its action values: `a8_limit` below the default action value
/// 0.5 m/s², `a8_action` above the default limit 1.15 m/s², `vdv_limit` below `vdv_action` are refused naming
/// the key the file gives and both values.
#[test]
fn an_action_value_above_its_limit_is_refused() {
    let d = scratch("limits");
    let text = std::fs::read_to_string(root().join("data/operator-seat-verdicts.toml")).unwrap();
    for (line, key) in [
        ("a8_limit = \"0.4 m/s^2\"", "a8_limit"),
        ("a8_action = \"2 m/s^2\"", "a8_action"),
        ("vdv_action = 12\nvdv_limit = 10", "vdv_limit"),
    ] {
        let t = text.replacen("[analysis.comfort]\n", &format!("[analysis.comfort]\n{line}\n"), 1);
        let p = d.join("limits.toml");
        std::fs::write(&p, t).unwrap();
        let e = stochvib::scenario::load_scenario(&p, &root().join("spectra"))
            .unwrap_err()
            .to_string();
        for part in [
            &format!("analysis.comfort.{key}"),
            "above the exposure action value",
            "limits.toml",
        ] {
            assert!(e.contains(part), "{part}: {e}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// Options that would change nothing are errors naming them: `--track` on a road of two tracks, the Monte
/// Carlo flags of `sweep` and `analyze` without `--monte-carlo`, `--json` with `-o`, `--overwrite` without
/// `-o`, `--compression` without `--store-raw`, `--stream-tail` on a route that does not stream, `--copy`
/// and `--confidence` for sweep shard files, `--convention` for a run file's pictures, `--full` with
/// `--json`.
#[test]
fn options_without_effect_are_errors() {
    let d = scratch("ignored");
    let r = root();
    let s = |p: &str| r.join(p).display().to_string();
    let (qc, two, profile) = (
        s("data/quarter-car-model.toml"),
        s("data/full-vehicle-two-tracks.toml"),
        s("data/measured-profile.csv"),
    );
    let quarter = s("data/quarter-car.toml");
    let p = "model.sprung_mass=300 kg,310 kg";
    // a sweep shard directory and a run file for the merge and plot cases
    let shards = d.join("shards");
    let o = cli(
        &[
            "sweep",
            &qc,
            "--param",
            p,
            "--shard",
            "0",
            "--of",
            "1",
            "-o",
            shards.to_str().unwrap(),
        ],
        &d,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    small_run(&d, "run.h5");
    let cases: Vec<(i32, Vec<&str>, &str)> = vec![
        (1, vec!["replay", &two, &profile, "--track", "left"], "--track"),
        (2, vec!["sweep", &qc, "--param", p, "--seed", "3"], "--monte-carlo"),
        (
            2,
            vec!["sweep", &qc, "--param", p, "--confidence", "0.9"],
            "--monte-carlo",
        ),
        (1, vec!["sweep", &qc, "--param", p, "--dt", "0.01"], "--dt"),
        (1, vec!["analyze", &qc, "--duration", "4"], "--duration"),
        (2, vec!["analyze", &qc, "--seed", "4"], "--monte-carlo"),
        (2, vec!["sweep", &qc, "--param", p, "--json", "-o", "t.csv"], "--json"),
        (2, vec!["sweep", &qc, "--param", p, "--overwrite"], "--overwrite"),
        (2, vec!["replay", &quarter, &profile, "--overwrite"], "--overwrite"),
        (
            2,
            vec![
                "simulate",
                &qc,
                "--realizations",
                "4",
                "--compression",
                "fast",
                "-o",
                "c.h5",
            ],
            "--store-raw",
        ),
        (
            1,
            vec![
                "simulate",
                &qc,
                "--realizations",
                "4",
                "--stream-tail",
                "1e-3",
                "--route",
                "exact",
                "-o",
                "c.h5",
            ],
            "--stream-tail",
        ),
        (1, vec!["merge", "t.csv", "shards", "--copy"], "--copy"),
        (
            1,
            vec!["merge", "t.csv", "shards", "--confidence", "0.9"],
            "--confidence",
        ),
        (
            1,
            vec!["plot", "run.h5", "-o", "pics", "--convention", "two-sided-angular"],
            "--convention",
        ),
        (2, vec!["spectra", "--json", "--full"], "--full"),
    ];
    for (code, args, flag) in cases {
        let e = fails(code, &args, &d);
        assert!(e.contains(flag), "`{}`: {e}", args.join(" "));
    }
    assert!(!d.join("t.csv").exists() && !d.join("c.h5").exists() && !d.join("pics").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// A SLURM array numbered from 1 (`--array=1-4`, SLURM_ARRAY_TASK_MIN=1) is warned about: shard indices are
/// 0-based, so shard 0 would never run; its task 4 is refused saying so. A resubmitted subset
/// (`--array=2,3`: MIN=2) is no mistake and gets no warning.
#[test]
fn a_one_based_slurm_array_is_warned_about() {
    let env = |id: &'static str, min: &'static str, max: &'static str| {
        move |k: &str| match k {
            "SLURM_ARRAY_TASK_ID" => Some(id.to_string()),
            "SLURM_ARRAY_TASK_MIN" => Some(min.to_string()),
            "SLURM_ARRAY_TASK_MAX" => Some(max.to_string()),
            "SLURM_ARRAY_TASK_COUNT" => Some("4".to_string()),
            _ => None,
        }
    };
    let c = stochvib::study::resolve_part("auto", Some(4), &env("2", "1", "4")).unwrap();
    assert_eq!(c.part.index, 2);
    assert!(
        c.notes
            .iter()
            .any(|n| n.contains("0-based") && n.contains("--array=0-3")),
        "{:?}",
        c.notes
    );
    let e = stochvib::study::resolve_part("auto", Some(4), &env("4", "1", "4"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("0-based") && e.contains("--array=0-3"), "{e}");
    let e = stochvib::study::resolve_part("auto", None, &env("1", "1", "4"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("0-based"), "{e}");
    let c = stochvib::study::resolve_part("auto", Some(4), &env("2", "2", "3")).unwrap();
    assert!(c.notes.is_empty(), "{:?}", c.notes);
    // the CLI prints the warning
    let d = scratch("slurm");
    let o = std::process::Command::new(crate::common::cli_bin())
        .current_dir(&d)
        .args(["simulate", root().join("data/conveyor-idler.toml").to_str().unwrap()])
        .args([
            "--realizations",
            "8",
            "--shard-size",
            "2",
            "--duration",
            "2",
            "--dt",
            "0.01",
        ])
        .args([
            "--shard",
            "auto",
            "--of",
            "4",
            "-o",
            "run",
            "--spectra-dir",
            root().join("spectra").to_str().unwrap(),
        ])
        .envs([
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "4"),
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.success() && err.contains("warning:") && err.contains("0-based"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A run's accumulators are allocated without fill: a run of 2·10⁷ realizations in shards of one (4·10⁷
/// shard rows of moments and Welch sums, about 3 GB on paper) starts at once, its `.tmp` takes almost no
/// disk before the shards are computed (a sparse file; before, the fill was written at about 1 GB/s), and
/// the estimate line gives the file's size.
#[test]
fn a_large_run_does_not_write_its_accumulators_before_computing() {
    let d = scratch("sparse");
    let sc = root().join("data/conveyor-idler.toml");
    let mut child = std::process::Command::new(crate::common::cli_bin())
        .current_dir(&d)
        .args([
            "simulate",
            sc.to_str().unwrap(),
            "--realizations",
            "20000000",
            "--shard-size",
            "1",
        ])
        .args([
            "--duration",
            "0.32",
            "--dt",
            "0.01",
            "--max-hours",
            "1000",
            "-o",
            "big.h5",
        ])
        .args(["--spectra-dir", root().join("spectra").to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let tmp = d.join("big.h5.tmp");
    let t0 = std::time::Instant::now();
    while !tmp.exists() && t0.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(50));
    }
    std::thread::sleep(Duration::from_millis(500));
    use std::os::unix::fs::MetadataExt;
    let m = std::fs::metadata(&tmp).expect("the run's .tmp");
    let _ = child.kill();
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("estimate: 20000000 realizations") && err.contains("a file of"),
        "{err}"
    );
    assert!(m.len() > 1 << 30, "apparent size {}", m.len());
    assert!(
        m.blocks() * 512 < m.len() / 10,
        "{} bytes allocated of {}",
        m.blocks() * 512,
        m.len()
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A run file's datasets and attributes are bounded before they are read: a density dataset declared with
/// 2³¹ elements (16 GiB of f64, none of it stored: a chunked dataset never written) is refused naming the
/// file and the dataset instead of allocating 16 GiB; a scenario attribute of 17 MiB of text, more than the
/// 16 MiB a scenario file may have, is refused naming the attribute.
#[test]
fn a_run_file_declaring_huge_data_is_refused_not_read() {
    let d = scratch("hdf5");
    small_run(&d, "run.h5");
    let _g = common::hdf5_serial();
    let (huge, text) = (d.join("huge-psd.h5"), d.join("huge-text.h5"));
    std::fs::copy(d.join("run.h5"), &huge).unwrap();
    std::fs::copy(d.join("run.h5"), &text).unwrap();
    let signal = {
        let f = hdf5::File::open_rw(&huge).unwrap();
        let psd = f.group("psd").unwrap();
        let name = psd.member_names().unwrap().into_iter().next().expect("a density group");
        let g = psd.group(&name).unwrap();
        g.unlink("omega").unwrap();
        g.new_dataset::<f64>()
            .chunk(1 << 16)
            .shape(1usize << 31)
            .create("omega")
            .unwrap();
        name
    };
    let e = stochvib::store::RunFile::open(&huge)
        .and_then(|r| r.psd())
        .unwrap_err()
        .to_string();
    for part in [
        "huge-psd.h5",
        &format!("psd/{signal}/omega"),
        "2147483648 elements",
        "damaged",
    ] {
        assert!(e.contains(part), "{part}: {e}");
    }
    {
        let f = hdf5::File::open_rw(&text).unwrap();
        f.delete_attr("scenario").unwrap();
        let big: hdf5::types::VarLenUnicode = "#".repeat(17 << 20).parse().unwrap();
        f.new_attr::<hdf5::types::VarLenUnicode>()
            .create("scenario")
            .unwrap()
            .write_scalar(&big)
            .unwrap();
    }
    let e = stochvib::store::RunFile::open(&text)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        e.contains("huge-text.h5") && e.contains("scenario") && e.contains("bytes of text"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
