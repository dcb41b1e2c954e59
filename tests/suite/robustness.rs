//! Robustness under careless or hostile use: every case here failed before its fix — a resume
//! that mixed a changed spectrum into an old run, two processes on one output, a kill during set-up, an
//! `--overwrite` that deleted first, sizes that panicked or aborted, damaged run files, values read with
//! the wrong unit or attributed to the wrong key, and files that hung the reader.

use crate::common;
use crate::common::SpawnSerial;
use common::root;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use stochvib::scenario::{load_scenario, Scenario};
use stochvib::simulate::RunOptions;
use stochvib::store::{tmp_path, RunFile};

fn dir(tag: &str) -> PathBuf {
    crate::common::scratch_dir("robust", tag)
}

fn cli(args: &[&str], cwd: &Path) -> Output {
    Command::new(crate::common::cli_bin())
        .current_dir(cwd)
        .env("STOCHVIB_SPECTRA", root().join("spectra"))
        .args(args)
        .output_serial()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A scenario and its spectrum file copied into `d` (so the spectrum can be edited).
fn local_scenario(d: &Path) -> PathBuf {
    std::fs::create_dir_all(d.join("spectra")).unwrap();
    std::fs::copy(
        root().join("spectra/conveyor-lump-load.toml"),
        d.join("spectra/lump.toml"),
    )
    .unwrap();
    let text = std::fs::read_to_string(root().join("data/conveyor-idler.toml"))
        .unwrap()
        .replace("spectrum = \"conveyor-lump-load\"", "spectrum = \"spectra/lump.toml\"");
    assert!(
        text.contains("spectra/lump.toml"),
        "the scenario names its spectrum by catalogue name"
    );
    std::fs::write(d.join("idler.toml"), text).unwrap();
    d.join("idler.toml")
}

fn load(path: &Path) -> Scenario {
    load_scenario(path, &root().join("spectra")).unwrap()
}

/// Runs `sc` and stops it after `shards` shards by a panic in the progress callback: the writer is dropped
/// and the `.tmp` stays, as after a kill.
fn interrupt(sc: &Scenario, opts: &RunOptions, out: &Path, shards: usize) {
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let _ = sc.simulate(opts, out, &|done, _| {
            if done >= shards {
                panic!("interrupted");
            }
        });
    }));
    assert!(r.is_err());
    assert!(tmp_path(out).exists() && !out.exists());
}

fn opts() -> RunOptions {
    let mut o = RunOptions {
        realizations: 8,
        duration_s: 2.0,
        dt_s: 0.01,
        seed: 11,
        ..RunOptions::default()
    };
    o.shard_size = 2;
    o
}

/// The spectrum file is part of the run's identity: after editing it, the interrupted run is refused with a
/// message naming the spectrum (before the fix the old shards were kept and new ones appended); with
/// `overwrite` it is discarded and the run starts afresh.
#[test]
fn a_resume_never_mixes_a_changed_spectrum() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("identity");
    let scen = local_scenario(&d);
    let out = d.join("run.h5");
    interrupt(&load(&scen), &opts(), &out, 2);
    let spec = d.join("spectra/lump.toml");
    let text = std::fs::read_to_string(&spec).unwrap();
    let edited = text.replace("alpha = \"0.5 1/s\"", "alpha = \"0.7 1/s\"");
    assert_ne!(text, edited, "the spectrum file has an alpha to edit");
    std::fs::write(&spec, edited).unwrap();
    let err = load(&scen).simulate(&opts(), &out, &|_, _| {}).unwrap_err().to_string();
    assert!(err.contains("spectrum (changed since the interrupted run)"), "{err}");
    assert!(err.contains("--overwrite"), "{err}");
    // the same settings as the interrupted run resume it
    std::fs::write(&spec, &text).unwrap();
    let s = load(&scen).simulate(&opts(), &out, &|_, _| {}).unwrap();
    assert_eq!(s.resumed_shards, 2);
    // a changed spectrum with overwrite: the interrupted run is discarded, with a note
    std::fs::remove_file(&out).unwrap();
    interrupt(&load(&scen), &opts(), &out, 1);
    std::fs::write(&spec, text.replace("alpha = \"0.5 1/s\"", "alpha = \"0.7 1/s\"")).unwrap();
    let mut o = opts();
    o.overwrite = true;
    let s = load(&scen).simulate(&o, &out, &|_, _| {}).unwrap();
    assert_eq!(s.resumed_shards, 0);
    assert!(
        s.notes.iter().any(|n| n.contains("discarded the interrupted run")),
        "{:?}",
        s.notes
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Two processes on one output: the second is told that another process (with its pid) is writing the run,
/// and touches nothing; the first finishes normally (before the fix the loser deleted the winner's `.tmp`).
#[test]
fn a_second_process_on_the_same_output_is_refused_and_harmless() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("concurrent");
    let out = d.join("run.h5");
    let args = |o: &Path| -> Vec<String> {
        [
            "simulate",
            root().join("data/conveyor-idler.toml").to_str().unwrap(),
            "--realizations",
            "400",
            "--duration",
            "40",
            "--dt",
            "0.01",
            "--shard-size",
            "20",
            "-o",
            o.to_str().unwrap(),
        ]
        .iter()
        .map(|s| s.to_string())
        .collect()
    };
    let mut first = Command::new(crate::common::cli_bin())
        .args(args(&out))
        .stderr(std::process::Stdio::piped())
        .spawn_serial()
        .unwrap();
    let t0 = std::time::Instant::now();
    while !tmp_path(&out).exists() {
        assert!(
            t0.elapsed().as_secs() < 60,
            "the first run never created its temporary file"
        );
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let second = Command::new(crate::common::cli_bin())
        .args(args(&out))
        .output_serial()
        .unwrap();
    let first_done = first.wait().unwrap();
    let msg = stderr(&second);
    assert!(!second.status.success(), "{msg}");
    // the first run may have finished before the second looked (a busy machine): then the second is told
    // the run exists, which only a finished first run can have written; otherwise it names the first's pid
    if !msg.contains("already exists") {
        assert!(
            msg.contains("another process") && msg.contains(&format!("pid {}", first.id())),
            "{msg}"
        );
    }
    assert!(first_done.success());
    RunFile::open(&out).unwrap().verify().unwrap();
    let _ = std::fs::remove_dir_all(&d);
}

/// A kill during set-up leaves at most an unclaimed file of a dead process, never a `.tmp`; a `.tmp` that
/// cannot be read (an HDF5 file cut short) is replaced by the next run with a note instead of asking the user
/// to delete it.
#[test]
fn a_damaged_or_unclaimed_temporary_file_is_restarted() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("setup");
    let sc = load(&root().join("data/conveyor-idler.toml"));
    let out = d.join("run.h5");
    // an unclaimed file left by a process that no longer exists (pid 2^22 + 1 is above Linux's pid_max)
    let stale = d.join("run.h5.tmp.4194305.123456789");
    std::fs::write(&stale, b"\x89HDF\r\n\x1a\n partial").unwrap();
    // a `.tmp` cut short in its first kilobyte
    let good = d.join("good.h5");
    sc.simulate(&opts(), &good, &|_, _| {}).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    std::fs::write(tmp_path(&out), &bytes[..1024]).unwrap();
    let s = sc.simulate(&opts(), &out, &|_, _| {}).unwrap();
    assert!(s.notes.iter().any(|n| n.contains("replaced")), "{:?}", s.notes);
    assert!(!stale.exists(), "the dead process's unclaimed file is removed");
    assert!(RunFile::open(&out).is_ok());
    let _ = std::fs::remove_dir_all(&d);
}

/// `--overwrite` validates and plans first and replaces the old run only when the new one is complete;
/// an output that is one of the inputs, a directory, a device, or a file that is not a run file is refused.
#[test]
fn overwrite_checks_first_and_replaces_only_run_files() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("overwrite");
    let scen = local_scenario(&d);
    let sc = load(&scen);
    let out = d.join("run.h5");
    sc.simulate(&opts(), &out, &|_, _| {}).unwrap();
    let before = std::fs::read(&out).unwrap();
    // an invalid option with --overwrite: nothing is touched
    let o = cli(
        &[
            "simulate",
            scen.to_str().unwrap(),
            "--realizations",
            "4",
            "--dt",
            "0",
            "--duration",
            "1",
        ],
        &d,
    );
    assert!(!o.status.success());
    let o = cli(
        &[
            "simulate",
            scen.to_str().unwrap(),
            "--realizations",
            "4",
            "--dt",
            "0",
            "--duration",
            "1",
            "--overwrite",
            "-o",
            out.to_str().unwrap(),
        ],
        &d,
    );
    assert!(!o.status.success() && stderr(&o).contains("dt"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&out).unwrap(), before, "the old run is intact");
    // the scenario itself as output, with --overwrite: refused, the scenario intact
    let scen_text = std::fs::read_to_string(&scen).unwrap();
    let mut ov = opts();
    ov.overwrite = true;
    let e = sc.simulate(&ov, &scen, &|_, _| {}).unwrap_err().to_string();
    assert!(e.contains("is an input of the run"), "{e}");
    assert_eq!(std::fs::read_to_string(&scen).unwrap(), scen_text);
    // the spectrum file too
    let e = sc
        .simulate(&ov, &d.join("spectra/lump.toml"), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("is an input of the run"), "{e}");
    // a directory, /dev/null, a text file
    let e = sc.simulate(&ov, &d, &|_, _| {}).unwrap_err().to_string();
    assert!(e.contains("is a directory"), "{e}");
    let e = sc
        .simulate(&ov, Path::new("/dev/null"), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a regular file"), "{e}");
    std::fs::write(d.join("notes.txt"), "keep me").unwrap();
    let e = sc
        .simulate(&ov, &d.join("notes.txt"), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a stochvib run file"), "{e}");
    // without --overwrite an existing run is refused; with it, replaced by the new one at the end
    let e = sc.simulate(&opts(), &out, &|_, _| {}).unwrap_err().to_string();
    assert!(e.contains("already exists") && e.contains("--overwrite"), "{e}");
    let mut o2 = ov.clone();
    o2.seed = 99;
    sc.simulate(&o2, &out, &|_, _| {}).unwrap();
    assert_eq!(RunFile::open(&out).unwrap().metadata().seed, 99);
    let _ = std::fs::remove_dir_all(&d);
}

/// Sizes a user controls are checked before anything is allocated: a huge `base_inputs` (was a capacity
/// overflow panic), a realization too long for the memory (was an abort on an 8 GB allocation), a run too
/// large for the disk (was ~146 GB of accumulators pre-allocated). Each fails at once with the numbers.
#[test]
fn sizes_are_checked_before_allocating() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("sizes");
    let text = std::fs::read_to_string(root().join("data/quarter-car.toml"))
        .unwrap()
        .replace("base_inputs = 1", "base_inputs = 1152921504606846976");
    std::fs::write(d.join("huge.toml"), text).unwrap();
    let o = cli(&["analyze", "huge.toml"], &d);
    assert!(
        !o.status.success() && stderr(&o).contains("model.base_inputs"),
        "{}",
        stderr(&o)
    );
    let sc = load(&root().join("data/conveyor-idler.toml"));
    // 2·10⁹ samples per realization of 3 signals kept as raw records (≥ 16 GB per thread just for the
    // samples), or on the whole-record spectral route (N-point FFT buffers): refused with the numbers. A
    // statistics-only exact run of that length streams in blocks and is accepted
    // (`a_huge_statistics_only_exact_run_streams`).
    let t0 = std::time::Instant::now();
    let mut raw = RunOptions {
        realizations: 4,
        duration_s: 2.0e7,
        dt_s: 0.01,
        seed: 1,
        ..RunOptions::default()
    };
    raw.store_raw = true;
    let mut spectral = RunOptions {
        realizations: 4,
        duration_s: 2.0e7,
        dt_s: 0.01,
        seed: 1,
        ..RunOptions::default()
    };
    spectral.route = stochvib::simulate::Route::Spectral;
    for (k, long) in [raw, spectral].iter().enumerate() {
        let e = sc
            .simulate(long, &d.join(format!("long{k}.h5")), &|_, _| {})
            .unwrap_err()
            .to_string();
        assert!(e.contains("of memory") && e.contains("GiB"), "{e}");
        assert!(!d.join(format!("long{k}.h5.tmp")).exists());
    }
    // 10¹³ realizations: the accumulators alone need ~10¹⁶ bytes
    let many = RunOptions {
        realizations: 10_000_000_000_000,
        duration_s: 2.0,
        dt_s: 0.01,
        seed: 1,
        ..RunOptions::default()
    };
    let e = sc
        .simulate(&many, &d.join("many.h5"), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("would take about") && e.contains("free on the disk"), "{e}");
    assert!(t0.elapsed().as_secs() < 30, "the checks must come before the work");
    assert!(!d.join("many.h5.tmp").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// The memory check knows that a statistics-only run of the exact route streams: 2·10⁹ samples per
/// realization are planned with the same bytes as 10⁵ (memory O(block), not O(N)), far below what the
/// whole record would need; a bounded run of 2 realizations × 2·10⁶ samples (122 blocks of the default
/// 2¹⁴ steps) runs to the end on that route.
#[test]
fn a_huge_statistics_only_exact_run_streams() {
    use stochvib::simulate::{planned_memory, resources::memory_bytes, Route};
    let d = dir("huge-exact");
    let sc = load(&root().join("data/conveyor-idler.toml"));
    let input = sc.run_input();
    let planned = |duration: f64| {
        planned_memory(
            &input,
            &RunOptions {
                realizations: 4,
                duration_s: duration,
                dt_s: 0.01,
                seed: 1,
                ..RunOptions::default()
            },
        )
        .unwrap()
    };
    let (short, huge) = (planned(1.0e3), planned(2.0e7));
    assert_eq!((short.route, huge.route), (Route::Exact, Route::Exact));
    assert_eq!(
        short.bytes, huge.bytes,
        "the block memory does not depend on the duration"
    );
    // the whole record of one realization alone is N·8 bytes per signal: 16 GB at N = 2·10⁹
    let whole = memory_bytes(
        2_000_000_000,
        1,
        1,
        &RunOptions {
            realizations: 4,
            duration_s: 2.0e7,
            dt_s: 0.01,
            seed: 1,
            ..RunOptions::default()
        },
        1,
    );
    assert!(
        whole >= 16_000_000_000 && huge.bytes < 64 << 20,
        "{} vs {whole}",
        huge.bytes
    );
    let o = RunOptions {
        realizations: 2,
        duration_s: 2.0e4,
        dt_s: 0.01,
        seed: 3,
        ..RunOptions::default()
    };
    let s = sc.simulate(&o, &d.join("long.h5"), &|_, _| {}).unwrap();
    assert_eq!((s.route, s.n_samples), (Route::Exact, 2_000_000));
    let _ = std::fs::remove_dir_all(&d);
}

/// A statistics-only run of the exact route generates its realizations in blocks with memory O(block);
/// the statistics and densities are bit-identical for any block size (1, 7, 1000 steps and whole
/// realizations), because the draws, the running sums and the Welch segments come in the same order.
#[test]
fn exact_route_statistics_are_bit_identical_for_any_block_size() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("blocks");
    let sc = load(&root().join("data/scraper-sprung-cab.toml"));
    let mut bits = Vec::new();
    for (k, block) in [1usize, 7, 1000, usize::MAX].into_iter().enumerate() {
        let mut o = RunOptions {
            realizations: 6,
            duration_s: 4.0,
            dt_s: 0.01,
            seed: 5,
            ..RunOptions::default()
        };
        o.shard_size = 4;
        o.block_steps = block;
        let out = d.join(format!("b{k}.h5"));
        let s = sc.simulate(&o, &out, &|_, _| {}).unwrap();
        let mut v = common::statistic_bits(&s);
        v.extend(common::psd_bits(&out));
        bits.push(v);
    }
    assert!(bits.windows(2).all(|w| w[0] == w[1]));
    let _ = std::fs::remove_dir_all(&d);
}

/// Damaged run files are reported, never read as if intact: a flipped bit in a statistic, in a density or
/// in the metadata fails its checksum; `inspect` (which verifies every checksum in a child process) says
/// the file is damaged; a picture of data beyond the drawable range is refused instead of spinning.
#[test]
fn damaged_run_files_are_reported() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("damaged");
    let sc = load(&root().join("data/conveyor-idler.toml"));
    let mut o = opts();
    o.store_raw = true;
    let good = d.join("good.h5");
    let s = sc.simulate(&o, &good, &|_, _| {}).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    let flip_value = |v: f64, tag: &str| -> PathBuf {
        let pat = v.to_le_bytes();
        let at = bytes
            .windows(8)
            .position(|w| w == pat)
            .unwrap_or_else(|| panic!("{tag}: value not in the file"));
        let mut b = bytes.clone();
        b[at] ^= 0x10;
        let p = d.join(format!("{tag}.h5"));
        std::fs::write(&p, b).unwrap();
        p
    };
    // a statistic's estimate
    let sigma = s.outputs[0].get("sigma").unwrap().interval.estimate;
    let p = flip_value(sigma, "stat");
    let e = RunFile::open(&p).and_then(|r| r.statistics()).unwrap_err().to_string();
    assert!(e.contains("checksum mismatch"), "{e}");
    let inspect = cli(&["inspect", p.to_str().unwrap()], &d);
    assert!(
        !inspect.status.success() && stderr(&inspect).contains("damaged"),
        "{}",
        stderr(&inspect)
    );
    // a raw sample: only the full verification reads it
    let raw = RunFile::open(&good)
        .unwrap()
        .read_signal(stochvib::store::SignalGroup::Outputs, "y", 3)
        .unwrap();
    let p = flip_value(raw[17], "raw");
    let e = RunFile::open(&p).and_then(|r| r.verify()).unwrap_err().to_string();
    assert!(e.contains("checksum mismatch") && e.contains("outputs/y"), "{e}");
    let inspect = cli(&["inspect", "--json", p.to_str().unwrap()], &d);
    assert!(
        !inspect.status.success() && stderr(&inspect).contains("damaged"),
        "{}",
        stderr(&inspect)
    );
    // the intact file verifies
    let v = RunFile::open(&good).unwrap().verify().unwrap();
    assert!(v.checked > 0 && v.format_version == 2);
    let _ = std::fs::remove_dir_all(&d);
}

/// A sample of 1.7e308 (stored with a valid checksum) makes the picture fail with the reason, quickly.
#[test]
fn pictures_refuse_values_they_cannot_draw() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    use stochvib::plot::Histogram;
    let h = Histogram::new("t", "x", "density", vec![0.0, 1.0, 1.7e308, -1.7e308]);
    let t0 = std::time::Instant::now();
    let e = h.render(&dir("draw"), "h").unwrap_err().to_string();
    assert!(e.contains("outside the range a picture can draw"), "{e}");
    assert!(t0.elapsed().as_secs() < 5);
}

/// Each value is read in its own unit and each error names the key the user wrote (before the fixes: a mean
/// of "5 kg" was read as 5 m, a level "5 kg" as 5 m, a NaN level printed NaN rates, duplicate output names
/// passed, `outputs = []` printed nothing and exited 0, element errors were reported under
/// `model.coordinates` with the whole array, a negative band-white level under `band`, `zeta1 = -0.1` as
/// `model.b1 <derived>`, a 1e308 mass and a singular mass matrix as "not asymptotically stable" without file
/// or key).
#[test]
fn values_are_checked_and_errors_name_the_key_written() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("keys");
    let qc = std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap();
    let cases: Vec<(&str, String, &str)> = vec![
        ("mean", qc.replace("speed = \"20 m/s\"", "speed = \"20 m/s\"\nmean = \"5 kg\""), "input.mean"),
        ("level", qc.replace("travel = [\"5 cm\", \"8 cm\"]", "travel = [\"5 kg\"]"), "analysis.levels.travel"),
        ("nan", qc.replace("travel = [\"5 cm\", \"8 cm\"]", "travel = [nan]"), "analysis.levels.travel"),
        ("dup", qc.replace("name = \"body_acc\"", "name = \"body\""), "model.output"),
        ("empty", qc.replace("band = [\"0.5 Hz\", \"80 Hz\"]", "outputs = []"), "analysis.outputs"),
        ("negk", qc.replacen("stiffness = \"20 kN/m\"", "stiffness = \"-20 kN/m\"", 1), "model.element[0].stiffness"),
        ("nanpoint", qc.replacen("point = [1, 0]", "point = [nan, 0]", 1), "model.element[0].point[0]"),
        ("heavy", qc.replace("mass = \"300 kg\"", "mass = 1e308"), "model.coordinates[0].mass"),
        (
            "zeta",
            "[model]\nkind = \"scraper-rigid-cab\"\nm1 = \"20 t\"\nomega1 = \"18 rad/s\"\nzeta1 = -0.1\n[input]\n\
             spectrum = \"book-8-66\"\nspeed = \"10 m/s\"\n"
                .into(),
            "model.zeta1",
        ),
        (
            "singular",
            "[model]\nkind = \"mdof\"\nbase_inputs = 1\ncoordinates = [{ name = \"a\", unit = \"m\" }, { name = \"b\", \
             unit = \"m\" }]\nmass_matrix = [[1.0, 1.0], [1.0, 1.0]]\nstiffness_matrix = [[2.0, -1.0], [-1.0, 2.0]]\n\
             base_stiffness = [[1.0], [0.0]]\n[[model.output]]\nname = \"a\"\nquantity = \"displacement\"\npoint = \
             [1, 0]\n[input]\nspectrum = \"type1\"\n"
                .into(),
            "model.mass_matrix",
        ),
        (
            "unstable",
            "[model]\nkind = \"transfer-function\"\nnumerator = [1.0]\ndenominator = [-1.0, 1.0]\noutput = { name = \
             \"x\", unit = \"m\" }\n[input]\nspectrum = \"type1\"\n"
                .into(),
            "key `model.denominator`",
        ),
    ];
    for (tag, text, key) in cases {
        let f = d.join(format!("{tag}.toml"));
        std::fs::write(&f, text).unwrap();
        let o = cli(&["analyze", f.to_str().unwrap()], &d);
        let e = stderr(&o);
        assert!(
            !o.status.success(),
            "{tag}: must fail\n{}",
            String::from_utf8_lossy(&o.stdout)
        );
        assert!(
            e.contains(f.file_name().unwrap().to_str().unwrap()),
            "{tag}: names the file: {e}"
        );
        assert!(e.contains(key), "{tag}: names {key}: {e}");
        assert!(e.len() < 600, "{tag}: no dump of whole tables: {e}");
    }
    // a negative band-white level is the `level` key's fault, not the band's
    let bw = d.join("bw.toml");
    std::fs::write(
        &bw,
        "kind = \"band-white\"\nconvention = \"one-sided-cyclic\"\nlevel = -1.0\nband = [\"1 Hz\", \"10 Hz\"]\n",
    )
    .unwrap();
    let o = cli(&["spectrum", bw.to_str().unwrap()], &d);
    assert!(
        !o.status.success() && stderr(&o).contains("key `level`"),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Smaller holes: a catalogue name cannot leave the catalogue (`../../..`), a file that is not TOML is not
/// echoed, a FIFO or a device is refused instead of read without end, and the temporary run of a killed
/// `analyze --monte-carlo` is removed by the next one.
#[test]
fn smaller_holes_are_closed() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    let d = dir("small");
    let qc = std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap();
    std::fs::write(
        d.join("escape.toml"),
        qc.replace("spectrum = \"iso8608-c\"", "spectrum = \"../../../etc/passwd\""),
    )
    .unwrap();
    let o = cli(&["analyze", "escape.toml"], &d);
    assert!(
        !o.status.success() && stderr(&o).contains("input.spectrum"),
        "{}",
        stderr(&o)
    );
    let o = cli(&["spectrum", "..%2F..%2Fsecret"], &d);
    assert!(!o.status.success());
    std::fs::write(d.join("secret.toml"), "password hunter2 is here\n").unwrap();
    let o = cli(&["analyze", "secret.toml"], &d);
    assert!(!o.status.success() && !stderr(&o).contains("hunter2"), "{}", stderr(&o));
    let o = cli(&["analyze", "/dev/zero"], &d);
    assert!(
        !o.status.success() && stderr(&o).contains("not a regular file"),
        "{}",
        stderr(&o)
    );
    let fifo = d.join("fifo.toml");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status_serial()
        .map(|s| s.success())
        .unwrap_or(false);
    if made {
        let o = cli(&["analyze", fifo.to_str().unwrap()], &d);
        assert!(
            !o.status.success() && stderr(&o).contains("not a regular file"),
            "{}",
            stderr(&o)
        );
    }
    // a killed `analyze --monte-carlo` (process gone) left its temporary run in the temporary directory
    let tmpdir = d.join("tmp");
    std::fs::create_dir_all(&tmpdir).unwrap();
    let left = tmpdir.join("stochvib-run-4194305.h5.tmp");
    std::fs::write(&left, vec![0u8; 4096]).unwrap();
    let o = Command::new(crate::common::cli_bin())
        .current_dir(root())
        .env("TMPDIR", &tmpdir)
        .args([
            "analyze",
            "data/conveyor-idler.toml",
            "--monte-carlo",
            "4",
            "--duration",
            "2",
            "--dt",
            "0.01",
        ])
        .output_serial()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!left.exists(), "the dead process's temporary run is removed");
    assert_eq!(
        std::fs::read_dir(&tmpdir).unwrap().count(),
        0,
        "and this run's own is gone too"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Findings of the 20,000-case fuzz campaign (seed 2026;
/// `cargo run --release --features campaigns --example fuzz`), each of which failed before its fix: extreme magnitudes (1e300, 1e-320) overflowed into NaN/inf results or
/// errors at derived keys; a catalogue model's own error (a badly scaled mass matrix) named no file; a
/// Lyapunov solve on a stiff two-stage isolator (m₂ = 8.25e-9 kg) printed a negative variance and σ = NaN;
/// the mine hoist's node bisection never ended for a 2^60 m rope and its closed form divided by a
/// subnormal rope mass; an ISO 8608 spectrum without `domain` was refused under a key not in the file; and
/// misspelt keys of the Table 8.1 transcription were accepted.
#[test]
fn fuzz_campaign_findings_are_fixed() {
    let _serial = common::hdf5_serial(); // see its docs: no fork while a file is open
    use stochvib::response::{analyze_output, Outcome, VarianceMethod};
    use stochvib::scenario::{load_document, parse_scenario, Document};
    let d = dir("fuzzfound");
    let spectra = root().join("spectra");
    let write = |name: &str, text: &str| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let base = std::fs::read_to_string(root().join("data/isolator-two-stage.toml")).unwrap();
    // (a) magnitudes outside 1e-100..1e100 are refused at the key written
    for (from, to, key) in [
        ("\"200 kg\"", "\"1e300 kg\"", "mass_2"),
        ("\"200 kg\"", "1e-320", "mass_2"),
    ] {
        assert!(base.contains(from), "the isolator's mass_2 is {from}");
        let p = write("big.toml", &base.replacen(from, to, 1));
        let e = load_scenario(&p, &spectra).unwrap_err().to_string();
        assert!(
            e.contains("big.toml") && e.contains(key) && e.contains("working range"),
            "{e}"
        );
    }
    // (b) a model's own failure names the file and the model
    let p = write("scaled.toml", &base.replacen("\"200 kg\"", "1152921504606846976", 1));
    let e = load_scenario(&p, &spectra).unwrap_err().to_string();
    assert!(
        e.contains("scaled.toml") && e.contains("model.kind") && e.contains("badly scaled"),
        "{e}"
    );
    // (c) a negative Lyapunov variance is reported unreliable, never used: σ is absent, not NaN
    let text = base.replacen("\"200 kg\"", "8.251932708077918e-9", 1);
    let sc = parse_scenario(&text, Path::new("stiff.toml"), &spectra).unwrap();
    for i in 0..sc.model.system.outputs().len() {
        let st = analyze_output(sc.model.system.as_ref(), &sc.excitation, i).unwrap();
        assert!(st.variance.is_none_or(|v| v.is_finite() && v >= 0.0), "{st:?}");
        let lyap = &st
            .methods
            .iter()
            .find(|m| m.method == VarianceMethod::Lyapunov)
            .unwrap()
            .outcome;
        assert!(
            lyap.value().is_none_or(|v| v >= 0.0),
            "a negative variance is used: {lyap:?}"
        );
        if let Outcome::Unreliable { value, reason } = lyap {
            assert!(*value < 0.0 && reason.contains("negative"), "{reason}");
        }
    }
    // (d) the mine hoist: a 2^60 m rope ends (bisection to a relative tolerance); a subnormal-free node
    let hoist = std::fs::read_to_string(root().join("data/mine-hoist.toml")).unwrap();
    assert!(hoist.contains("max_hanging_length = \"700 m\""));
    let p = write(
        "hoist.toml",
        &hoist.replace(
            "max_hanging_length = \"700 m\"",
            "max_hanging_length = 1152921504606846976",
        ),
    );
    let (tx, rx) = std::sync::mpsc::channel();
    let p2 = p.clone();
    std::thread::spawn(move || {
        let r = match load_document(&p2, &root().join("spectra")) {
            Ok(Document::Deterministic(dd)) => stochvib::study::deterministic_tables(&dd).map(|_| ()),
            Ok(_) => Ok(()),
            Err(e) => Err(e),
        };
        let _ = tx.send(r.map_err(|e| e.to_string()));
    });
    let r = rx
        .recv_timeout(std::time::Duration::from_secs(60))
        .expect("the deterministic report of a 2^60 m rope ends");
    if let Err(e) = r {
        assert!(e.contains("hoist.toml") && e.contains("model"), "{e}");
    }
    // (e) ISO 8608 without `domain` is spatial
    let iso = std::fs::read_to_string(root().join("spectra/iso8608-c.toml")).unwrap();
    let no_domain: String = iso
        .lines()
        .filter(|l| !l.starts_with("domain"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(no_domain, iso);
    let p = write("iso.toml", &no_domain);
    let s = stochvib::scenario::load_spectrum(&p).unwrap();
    assert_eq!(s.spectrum.domain(), stochvib::spectrum::Domain::Spatial);
    // (e') a band edge of 0 is reported at the array element written, not at a derived `band.low`
    let iso_g = std::fs::read_to_string(root().join("spectra/iso8608-g.toml")).unwrap();
    let with_band = format!(
        "{}band = [\"0 cycles/m\", \"2.83 cycles/m\"]\n",
        iso_g.replace("band = ", "old_band = ")
    );
    assert!(!iso_g.contains("old_band"));
    let p = write("band.toml", &with_band.replace("old_band = ", "# "));
    let e = stochvib::scenario::load_spectrum(&p).unwrap_err().to_string();
    assert!(
        e.contains("band.toml") && e.contains("key `band[0]`") && e.contains("0 cycles/m"),
        "{e}"
    );
    // (f) the Table 8.1 transcription refuses misspelt and unknown keys
    let t81 = std::fs::read_to_string(root().join("data/reference/table-8-1.toml")).unwrap();
    for (from, to) in [
        ("printed_symbol", "printed_symbl"),
        ("status =", "stauts ="),
        ("sqrt_dq", "sqrt_dqq"),
    ] {
        let p = write("t81.toml", &t81.replacen(from, to, 1));
        let e = load_document(&p, &spectra).unwrap_err().to_string();
        assert!(
            e.contains("t81.toml") && e.contains(to.trim_end_matches(" =")),
            "{from} -> {to}: {e}"
        );
    }
}
