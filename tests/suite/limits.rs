//! The resource rule and the input rule, and checksums for every reader of run files: each case here
//! failed before — `sweep --param "…:18446744073709551615"` panicked ("capacity overflow"), `…:1000000000`
//! aborted allocating 32 GB, a grid too large for the disk started writing, `--duration 1e12` ran with no
//! estimate, an inline spectrum of 400 000 coefficients asked for 1.28 TB; `road` read a 2 GB file whole
//! (4.2 GB of memory, a 2 GB message), hung on a FIFO and read `/dev/zero` until memory ran out; `plot`
//! drew damaged run files that `inspect` rejects.

use crate::common::{self, listing, mkfifo, root};
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::Duration;

fn scratch(tag: &str) -> PathBuf {
    crate::common::scratch_dir("limits", tag)
}

/// Runs the tool in `cwd`; 600 s means it hung (a bound for
/// hangs only, generous for a machine whose cores are shared by a dozen processes).
fn cli(args: &[&str], cwd: &Path) -> Output {
    common::cli_within(args, cwd, Duration::from_secs(600))
}

/// What a refusal may use: "before any work" is checked with the kernel's resource limits, which do not
/// race the scheduler as a wall-time bound does — 30 s of CPU (the refusals take well under 1 s of CPU;
/// the work they refuse takes hours) and 2 GiB of address space (the work they refuse allocates from 3.5
/// GB up to terabytes). A child over either is stopped by a signal (SIGXCPU) or fails its allocation, and
/// does not exit with status 1.
const BEFORE_ANY_WORK: common::ChildLimits = common::ChildLimits {
    cpu_s: 30,
    memory: 2 << 30,
};

/// The error of a command that must fail with exit status 1 (not a panic, not a signal), before any work
/// ([`BEFORE_ANY_WORK`]).
fn refused(args: &[&str], cwd: &Path) -> String {
    let o = common::cli_limited(args, cwd, Duration::from_secs(600), Some(BEFORE_ANY_WORK));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(
        o.status.code(),
        Some(1),
        "`{}` did not refuse before any work (within {BEFORE_ANY_WORK:?}): {:?}\n{err}",
        args.join(" "),
        o.status
    );
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// Grid and range counts are parsed and multiplied with overflow checks and caps: a count of 2⁶⁴ − 1 or
/// 10⁹ values of one key, a grid of 10¹⁸ points, each refused at once naming `--param`; a grid of 10¹²
/// points (about 500 TB of CSV) refused by the disk check with both sizes; 10⁶ points with a Monte Carlo
/// batch of 10⁵ realizations of 1000 samples each (10¹⁴ samples: at least 69 h on 2 threads) refused by
/// its time estimate naming `--max-hours`. Nothing is written.
#[test]
fn sweep_sizes_are_checked_before_any_work() {
    let d = scratch("sweep");
    let sc = root().join("data/scraper-sprung-cab.toml");
    let sc = sc.to_str().unwrap();
    for count in ["18446744073709551615", "1000000000"] {
        let range = format!("model.zeta2=0.1..0.4:{count}");
        let e = refused(&["sweep", sc, "--param", &range, "-o", "t.csv"], &d);
        assert!(e.contains("param") && e.contains("at most 1000000 values"), "{e}");
    }
    let grid = |n: &str| {
        vec![
            format!("model.zeta2=0.1..0.4:{n}"),
            format!("model.zeta1=0.05..0.2:{n}"),
            format!("input.speed=5..20:{n}"),
        ]
    };
    let g = grid("1000000");
    let e = refused(
        &[
            "sweep", sc, "--param", &g[0], "--param", &g[1], "--param", &g[2], "-o", "t.csv",
        ],
        &d,
    );
    assert!(
        e.contains("param") && e.contains("more than 9.007199254740992e15 points"),
        "{e}"
    );
    let g = grid("1000000");
    let e = refused(&["sweep", sc, "--param", &g[0], "--param", &g[1], "-o", "t.h5"], &d);
    assert!(
        e.contains("1000000000000 points") && e.contains("free on the disk") && e.contains("TiB"),
        "{e}"
    );
    let e = refused(
        &[
            "sweep",
            sc,
            "--param",
            &g[0],
            "--monte-carlo",
            "100000",
            "--dt",
            "0.01",
            "--duration",
            "10",
        ],
        &d,
    );
    assert!(
        e.contains("monte-carlo") && e.contains("--max-hours") && e.contains("at least"),
        "{e}"
    );
    assert!(listing(&d).is_empty(), "{:?}", listing(&d));
    let _ = std::fs::remove_dir_all(&d);
}

/// A JSON table is built whole in memory: 10¹⁰ points (4·10¹⁰ rows) need far more than any machine has,
/// and are refused naming the memory and the streamed formats.
#[test]
fn a_json_table_larger_than_memory_is_refused() {
    let d = scratch("json");
    let sc = root().join("data/scraper-sprung-cab.toml");
    let e = refused(
        &[
            "sweep",
            sc.to_str().unwrap(),
            "--param",
            "model.zeta2=0.1..0.4:100000",
            "--param",
            "input.speed=5..20:100000",
            "-o",
            "t.json",
        ],
        &d,
    );
    assert!(e.contains("of memory") && e.contains(".csv or .h5"), "{e}");
    // the limit it met: the memory needed and the memory available, and the flag that sets the points
    assert!(
        e.contains("needs about") && e.contains("are available") && e.contains("--param"),
        "{e}"
    );
    assert!(listing(&d).is_empty());
    let _ = std::fs::remove_dir_all(&d);
}

/// The memory a JSON study is sized by holds per row (point × output) its `OutputValues` and the evaluated
/// `PointStatistics` by value, no heap: `PointStatistics` is three `Option<f64>` (16 bytes each: tag and
/// value at 8-byte alignment) and a one-byte method enum, 56 bytes after padding; the Monte Carlo values
/// are three `f64` and a `bool` (32 bytes, the `bool` leaving a niche for the `Option`); 56 + 32 = 88 bytes
/// a row, 144 with the evaluated statistics (docs/library.md, "Statistics types").
#[test]
fn a_json_table_row_holds_the_point_statistics_by_value() {
    use std::mem::size_of;
    use stochvib::response::PointStatistics;
    use stochvib::study::sweep_table::{McValues, OutputValues};
    assert_eq!(size_of::<PointStatistics>(), 56);
    assert_eq!(size_of::<Option<McValues>>(), 32);
    assert_eq!(size_of::<OutputValues>() + size_of::<PointStatistics>(), 144);
}

/// `simulate` prints its estimate before the work, and refuses a run whose computing time (a lower bound:
/// one normal draw per sample) exceeds `--max-hours`: `--duration 1e12` (10¹⁴ samples per realization),
/// 10⁹ realizations of 10⁵ samples (here the disk check may come first); the cap is `--max-hours`'s. A step
/// that makes the count overflow is refused naming `duration`.
#[test]
fn long_runs_are_refused_with_their_estimate() {
    let d = scratch("long");
    let sc = root().join("data/conveyor-idler.toml");
    let simulate = |realizations: &str, dt: &str, duration: &str, extra: &[&str]| {
        let mut a = vec![
            "simulate",
            sc.to_str().unwrap(),
            "--realizations",
            realizations,
            "--dt",
            dt,
        ];
        a.extend(["--duration", duration, "-o", "r.h5"]);
        a.extend(extra);
        refused(&a, &d)
    };
    let e = simulate("10", "0.01", "1e12", &[]);
    assert!(e.contains("estimate: 10 realizations × 100000000000000 samples"), "{e}");
    assert!(e.contains("would take at least") && e.contains("--max-hours 24"), "{e}");
    // the cap is the option's: 400 samples (at least 1 µs) under a cap of 10⁻¹² h (3.6 ns) are refused too
    let e = simulate("4", "0.01", "1", &["--max-hours", "1e-12"]);
    assert!(
        e.contains("would take at least") && e.contains("--max-hours 1e-12"),
        "{e}"
    );
    let e = simulate("1000000000", "0.01", "1000", &[]);
    assert!(
        e.contains("realizations") && (e.contains("--max-hours") || e.contains("free on the disk")),
        "{e}"
    );
    let e = simulate("10", "1e-300", "10", &[]);
    assert!(e.contains("duration") && e.contains("samples per realization"), "{e}");
    assert!(listing(&d).is_empty(), "{:?}", listing(&d));
    let _ = std::fs::remove_dir_all(&d);
}

/// A rational spectrum of 400 000 (or 20 000) denominator coefficients is refused at once, naming the
/// key, the count and the cap, instead of building a companion matrix of 1.28 TB (or running 50 s and
/// aborting at 3.2 GB); so is a transfer function of such degree.
#[test]
fn polynomials_of_huge_degree_are_refused() {
    let d = scratch("degree");
    for n in [400_000usize, 20_000] {
        let coefficients = vec!["1.0"; n].join(", ");
        let text = std::fs::read_to_string(root().join("data/conveyor-idler.toml"))
            .unwrap()
            .replace(
                "spectrum = \"conveyor-lump-load\"   # sigma_F = 2 kN, alpha = 0.5 1/s",
                &format!(
                "spectrum = {{ kind = \"rational\", unit = \"N\", numerator = [1.0], denominator = [{coefficients}] }}"
            ),
            );
        assert!(text.contains("kind = \"rational\""));
        std::fs::write(d.join("huge.toml"), text).unwrap();
        let e = refused(&["analyze", "huge.toml"], &d);
        assert!(
            e.contains("denominator") && e.contains(&format!("{n} coefficients")),
            "{e}"
        );
        assert!(e.contains("256") && e.len() < 2000, "{e}");
    }
    let e = stochvib::system::TransferFunction::new(
        vec![1.0],
        vec![1.0; 1000],
        stochvib::system::OutputInfo::new("y", "m"),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("denominator") && e.contains("1000 coefficients"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// The input rule for every file input: a FIFO (which would block), a device (`/dev/zero` never ends) and
/// a directory are refused before anything is read — profiles and records (`road`, `replay`, `exposure`,
/// `fatigue`, `coherence`, `iri`; CSV, WAV, HDF5), scenario files (`analyze`, `transient`, `optimize`,
/// `report`), workday and spectrum files, run files (`inspect`, `plot`, `report`, `check-run`), sweep shard
/// files (`merge`); a 2 GiB profile is refused
/// by its size at once (it used to take 4.2 GB of memory), without reading it.
#[test]
fn file_inputs_refuse_fifos_devices_and_huge_files() {
    let _serial = common::hdf5_serial(); // no fork while a file of this binary is open
    let d = scratch("inputs");
    for name in ["p.csv", "s.toml", "r.h5", "sweep-shard-0-of-1.json", "w.wav"] {
        mkfifo(&d.join(name));
    }
    let quarter = root().join("data/quarter-car.toml");
    let q = quarter.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec!["road", "p.csv"],
        vec!["road", "/dev/zero"],
        vec!["road", "."],
        vec!["replay", q, "p.csv"],
        vec!["replay", q, "/dev/zero"],
        vec!["analyze", "s.toml"],
        vec!["analyze", "/dev/zero"],
        vec!["inspect", "r.h5"],
        vec!["plot", "r.h5", "-o", "pictures"],
        vec!["merge", "t.csv", "sweep-shard-0-of-1.json"],
        // the commands that came later: records, profiles of the record commands, workday, spectrum,
        // transient, optimize and report files, check-run
        vec!["exposure", "p.csv"],
        vec!["exposure", "w.wav"],
        vec!["exposure", "r.h5"],
        vec!["fatigue", "p.csv", "--sn-slope", "3", "--sn-amplitude", "80 MPa"],
        vec!["coherence", "--profile", "p.csv"],
        vec!["iri", "iso8608-c", "--profile", "p.csv"],
        vec!["workday", "s.toml"],
        vec!["spectrum", "s.toml"],
        vec!["spectrum", "."],
        vec!["transient", "s.toml"],
        vec![
            "optimize",
            "s.toml",
            "--param",
            "model.zeta=0.1:0.2",
            "--minimize",
            "sigma(y)",
        ],
        vec!["report", "s.toml", "-o", "x.html"],
        vec!["report", "r.h5", "-o", "x.html"],
        vec!["report", q, "--run", "r.h5", "-o", "x.html"],
        vec!["check-run", "r.h5"],
    ];
    for args in cases {
        let e = refused(&args, &d);
        assert!(
            e.contains("not a regular file") || e.contains("is a directory"),
            "{}: {e}",
            args.join(" ")
        );
    }
    let big = d.join("big.csv");
    std::fs::File::create(&big).unwrap().set_len(2 << 30).unwrap(); // sparse: takes no disk
    let e = refused(&["road", "big.csv"], &d);
    assert!(
        e.contains("2147483648 bytes is larger than the 1073741824 bytes"),
        "{e}"
    );
    assert!(e.len() < 1000, "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Every message quotes a bounded excerpt of a bad value: a 10 MB CSV cell, a 40 000-value row and a
/// line of 1 MB without a newline give messages of a few hundred bytes that name the file, the line and
/// the size of what was cut (before: a 10 MB message).
#[test]
fn bad_values_are_quoted_as_bounded_excerpts() {
    let d = scratch("excerpt");
    let header = "distance [m], left [mm]\n0,1\n";
    let cell = format!("{header}0.1,{}x\n0.2,1\n", "9".repeat(60_000));
    let row = format!("{header}0.1,2{}\n", ",3".repeat(20_000));
    let line = format!("{header}{}", "7".repeat(1 << 20));
    for (name, text, said) in [
        ("cell.csv", cell, "bytes)"),
        ("row.csv", row, "(40005 bytes)"),
        ("line.csv", line, "longer than the 65536 bytes"),
    ] {
        std::fs::write(d.join(name), text).unwrap();
        let e = refused(&["road", name], &d);
        assert!(e.contains(name) && e.contains("line 3") && e.contains(said), "{e}");
        assert!(e.len() < 700, "{} bytes: {e}", e.len());
    }
    // a library error built from a huge value shows an excerpt, whatever the constructor
    let e = stochvib::Error::invalid("param", "x".repeat(1 << 20), "bad").to_string();
    assert!(e.len() < 300 && e.contains("(1048576 bytes)"), "{e}");
    let e = stochvib::Error::InvalidParameter {
        name: "param".into(),
        value: "y".repeat(1 << 20),
        reason: "bad".into(),
    }
    .to_string();
    assert!(e.len() < 300 && e.contains("(1048576 bytes)"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// `plot` verifies every checksum of a run file as `inspect` does: a flipped bit in a raw sample (which the
/// pictures read) or in an accumulator of the last shard (which they do not) makes `plot` fail naming the
/// file and the damaged dataset, and write nothing; the library's `run_plots` refuses the same file, and so
/// does `report` (of the run file, and of its scenario with `--run`).
#[test]
fn plot_verifies_checksums_like_inspect() {
    let _serial = common::hdf5_serial(); // no fork while a file of this binary is open
    use stochvib::store::{RunFile, SignalGroup};
    let d = scratch("plot-damaged");
    let sc =
        stochvib::scenario::load_scenario(&root().join("data/conveyor-idler.toml"), &root().join("spectra")).unwrap();
    let mut o = stochvib::simulate::RunOptions {
        realizations: 8,
        duration_s: 2.0,
        dt_s: 0.01,
        seed: 11,
        ..Default::default()
    };
    o.shard_size = 2;
    o.store_raw = true;
    let good = d.join("good.h5");
    sc.simulate(&o, &good, &|_, _| {}).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    // values whose 8 bytes occur once in the file: flipping them damages exactly that dataset
    let once = |v: &f64| bytes.windows(8).filter(|w| *w == v.to_le_bytes()).count() == 1;
    let (raw, acc) = {
        let run = RunFile::open(&good).unwrap();
        let raw = run.read_signal(SignalGroup::Outputs, "y", 1).unwrap();
        let raw = *raw.iter().find(|v| once(v)).unwrap();
        let acc = run
            .metadata()
            .accumulators
            .iter()
            .find_map(|(name, _)| {
                let a = run.read_accumulator(name, 3).unwrap();
                a.into_iter().find(once).map(|v| (name.clone(), v))
            })
            .unwrap();
        (raw, acc)
    };
    let flip = |v: f64, tag: &str| -> PathBuf {
        let at = bytes.windows(8).position(|w| w == v.to_le_bytes()).unwrap();
        let mut b = bytes.clone();
        b[at] ^= 0x10;
        let p = d.join(format!("{tag}.h5"));
        std::fs::write(&p, b).unwrap();
        p
    };
    for (p, part) in [(flip(raw, "raw"), "outputs/y".to_string()), (flip(acc.1, "acc"), acc.0)] {
        let pictures = d.join("pictures");
        let e = refused(&["plot", p.to_str().unwrap(), "-o", pictures.to_str().unwrap()], &d);
        assert!(
            e.contains(p.to_str().unwrap()) && e.contains("damaged") && e.contains(&part),
            "{e}"
        );
        assert!(!pictures.exists());
        let e = stochvib::plot::run_plots(&p, &pictures, &root().join("spectra"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("checksum mismatch") && e.contains(&part), "{e}");
        assert!(!pictures.exists());
        // `report` reads run files too: of the run alone, and as the `--run` of its scenario
        let sc_path = root().join("data/conveyor-idler.toml");
        for args in [
            vec!["report", p.to_str().unwrap(), "-o", "r.html"],
            vec![
                "report",
                sc_path.to_str().unwrap(),
                "--run",
                p.to_str().unwrap(),
                "-o",
                "r.html",
            ],
        ] {
            let e = refused(&args, &d);
            assert!(
                e.contains(p.to_str().unwrap()) && e.contains("damaged") && e.contains(&part),
                "{e}"
            );
            assert!(!d.join("r.html").exists());
        }
    }
    let out = cli(&["plot", good.to_str().unwrap(), "-o", "pictures"], &d);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let _ = std::fs::remove_dir_all(&d);
}
