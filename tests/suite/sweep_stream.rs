//! `stochvib sweep`'s tables written while they are computed (`study::write_sweep_table`,
//! `study::stream_sweep_csv`, `study::Sweep::evaluate_into`): blocks of points are evaluated and
//! handed to a writer thread, so memory does not grow with the study.
//!
//! Provenance of the expected values:
//! * the whole table of the same study, built in memory by `study::compute_sweep` and written by
//!   `SweepResults::write`/`to_csv` (the path merge and the shard tables take): a streamed table must
//!   equal it byte for byte (CSV) or bit for bit in every dataset (HDF5), for blocks that do not divide the
//!   number of points, on one core and on all. For HDF5 both go through the same dataset writer, so the
//!   columns are also checked against their definitions:
//! * `Sweep::evaluate(p)` of each point alone, and the definitions of the derived columns written out in
//!   the test: σ = √D, M ∓ 3σ, ν₀⁺ = √(λ₂/D)/(2π); the value indices from `SweepSpec::indices`, the
//!   values of the keys as written, the failed points' messages from `evaluate`'s errors;
//! * `Sweep::evaluate_general` (the model rebuilt from its table and solved through its state space: a
//!   different route from the closed-form transfer polynomials the study takes) within
//!   `TRANSFER_POLYNOMIALS`, so the numbers are anchored outside the fast path.

use crate::common;
use crate::common::SpawnSerial;
use common::tolerance::TRANSFER_POLYNOMIALS;
use std::path::{Path, PathBuf};
use stochvib::scenario::{load_scenario, Scenario};
use stochvib::study::{compute_sweep, stream_sweep_csv, write_sweep_table, StreamOptions, SweepMonteCarlo};
use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec, FAILED_POINT};

fn scraper() -> Scenario {
    load_scenario(
        &crate::common::root().join("data/scraper-sprung-cab.toml"),
        &crate::common::root().join("spectra"),
    )
    .unwrap()
}

/// The grid study of `sc` over `params` (`KEY=VALUES` as on the command line).
fn grid<'a>(sc: &'a Scenario, params: &[&str]) -> Sweep<'a> {
    let params = params.iter().map(|p| SweepParam::parse(p).unwrap()).collect();
    Sweep::new(sc, SweepSpec::new(params, SweepMode::Grid).unwrap()).unwrap()
}

/// 37 cab frequencies × ζ₂ ∈ {0.2, −0.1, 0.3}: 111 points, the 37 with ζ₂ = −0.1 fail (a negative
/// damping ratio is refused by the model), so failed rows fall inside every block.
fn study(sc: &Scenario) -> Sweep<'_> {
    grid(sc, &["model.omega2=0.5 Hz..4 Hz:37", "model.zeta2=0.2,-0.1,0.3"])
}

fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir("sweep-stream", name)
}

fn opts(block_points: usize, parallel: bool) -> StreamOptions {
    StreamOptions { block_points, parallel }
}

/// Every attribute (as text) and every dataset (as the bits of its values) of a sweep table, by path.
fn h5_contents(path: &Path) -> Vec<(String, Vec<u64>, Vec<String>)> {
    use hdf5::types::VarLenUnicode;
    let _g = common::hdf5_serial();
    let f = hdf5::File::open(path).unwrap();
    let mut out = Vec::new();
    for a in f.attr_names().unwrap() {
        let attr = f.attr(&a).unwrap();
        let text = match attr.read_scalar::<VarLenUnicode>() {
            Ok(v) => vec![v.to_string()],
            Err(_) => match attr.read_raw::<VarLenUnicode>() {
                Ok(v) => v.iter().map(|s| s.to_string()).collect(),
                Err(_) => vec![format!("{:?}", attr.read_raw::<u64>().unwrap())],
            },
        };
        out.push((format!("@{a}"), Vec::new(), text));
    }
    let mut datasets = Vec::new();
    for g in ["params", "outputs", "errors"] {
        let group = f.group(g).unwrap();
        for m in group.member_names().unwrap() {
            let p = format!("{g}/{m}");
            match f.group(&p) {
                Ok(sub) => {
                    for d in sub.member_names().unwrap() {
                        datasets.push(format!("{p}/{d}"));
                    }
                }
                _ => {
                    datasets.push(p);
                }
            }
        }
    }
    datasets.push("value_index".into());
    for d in datasets {
        let ds = f.dataset(&d).unwrap();
        let desc = ds.dtype().unwrap().to_descriptor().unwrap();
        let (bits, text) = match desc {
            hdf5::types::TypeDescriptor::Float(_) => (
                ds.read_raw::<f64>().unwrap().iter().map(|v| v.to_bits()).collect(),
                Vec::new(),
            ),
            hdf5::types::TypeDescriptor::Unsigned(_) => (ds.read_raw::<u64>().unwrap(), Vec::new()),
            _ => (
                Vec::new(),
                ds.read_raw::<VarLenUnicode>()
                    .unwrap()
                    .iter()
                    .map(|s| s.to_string())
                    .collect(),
            ),
        };
        out.push((d, bits, text));
    }
    out
}

/// The values of dataset `name` of the file at `path`.
fn h5_read<T: hdf5::H5Type>(path: &Path, name: &str) -> Vec<T> {
    let _g = common::hdf5_serial();
    hdf5::File::open(path)
        .unwrap()
        .dataset(name)
        .unwrap()
        .read_raw()
        .unwrap()
}

/// CSV streamed in blocks of 1, 10 (not dividing 111) and 1000 points, on one core and on all, to a file
/// and to a writer: the same text as the whole table's `to_csv`, byte for byte; the failed points are the
/// 37 with ζ₂ = −0.1.
#[test]
fn streamed_csv_is_the_whole_table_byte_for_byte() {
    let sc = scraper();
    let sweep = study(&sc);
    let n = sweep.spec().n_points();
    let whole = compute_sweep(&sweep, 0..n, true, None, &|_, _| {}).unwrap();
    assert_eq!(whole.errors.len(), 37);
    assert!(whole.errors.iter().all(|(p, _)| p % 3 == 1), "{:?}", whole.errors);
    let expected = whole.to_csv();
    let dir = scratch("csv");
    for (block, parallel) in [(1, false), (10, true), (10, false), (1000, true)] {
        let path = dir.join(format!("t-{block}-{parallel}.csv"));
        let t = write_sweep_table(&sweep, &path, false, None, opts(block, parallel), &|_, _| {}).unwrap();
        assert_eq!((t.n_points, &t.errors), (n, &whole.errors));
        assert_eq!(std::fs::read_to_string(&path).unwrap(), expected, "block {block}");
        let mut buf = Vec::new();
        let t = stream_sweep_csv(
            &sweep,
            &mut buf,
            Path::new("<buffer>"),
            None,
            opts(block, parallel),
            &|_, _| {},
        )
        .unwrap();
        assert_eq!(t.errors, whole.errors);
        assert_eq!(String::from_utf8(buf).unwrap(), expected, "block {block}");
        assert!(!dir.join(format!("t-{block}-{parallel}.csv.tmp")).exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every number of the CSV table is the text `format!("{:.9e}")` (core::fmt) gives its definition from the
/// one-point evaluation: M, σ = √D, D, M ∓ 3σ, λ₂, ν₀⁺ = √(λ₂/D)/(2π), empty where there is none. The
/// scraper's outputs have M = 0, so M + 3σ = −(M − 3σ) on every row (the writer cuts its text from the
/// lower bound's), and the failed rows have no numbers.
#[test]
fn csv_numbers_are_the_text_of_their_definitions() {
    let sc = scraper();
    let sweep = study(&sc);
    let mut buf = Vec::new();
    stream_sweep_csv(
        &sweep,
        &mut buf,
        Path::new("<buffer>"),
        None,
        opts(10, true),
        &|_, _| {},
    )
    .unwrap();
    let text = String::from_utf8(buf).unwrap();
    let two_pi = 2.0 * std::f64::consts::PI;
    let fmt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.9e}"));
    let mut rows = 0;
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (p, name) = (f[0].parse::<usize>().unwrap(), f[3]);
        let Ok(stats) = sweep.evaluate(p) else {
            assert!(f[6..13].iter().all(|v| v.is_empty()), "{line}");
            continue;
        };
        let j = sweep.outputs().iter().position(|o| o.as_str() == name).unwrap();
        let s = &stats[j];
        let (m, d) = (s.mean.unwrap(), s.variance.unwrap());
        assert_eq!(m, 0.0, "{line}");
        let sigma = d.sqrt();
        let nu = s.lambda2.map(|l| (l / d).sqrt() / two_pi);
        let want = [
            Some(m),
            Some(sigma),
            Some(d),
            Some(m - 3.0 * sigma),
            Some(m + 3.0 * sigma),
            s.lambda2,
            nu,
        ];
        for (k, w) in want.into_iter().enumerate() {
            assert_eq!(f[6 + k], fmt(w), "column {} of {line}", 6 + k);
        }
        rows += 1;
    }
    assert_eq!(rows, 74 * sweep.outputs().len());
}

/// HDF5 streamed in blocks of 10 and 7 (neither divides 111) equals the whole table written at once in
/// every attribute and in the bits of every dataset; each column equals its definition from the
/// one-point evaluation, and the values are anchored on the state-space route.
#[test]
fn streamed_hdf5_equals_the_whole_table_and_its_definitions() {
    let sc = scraper();
    let sweep = study(&sc);
    let n = sweep.spec().n_points();
    let dir = scratch("h5");
    let whole_path = dir.join("whole.h5");
    let whole = compute_sweep(&sweep, 0..n, true, None, &|_, _| {}).unwrap();
    whole.write(&whole_path, false).unwrap();
    let reference = h5_contents(&whole_path);
    assert!(reference.iter().any(|d| d.0 == "outputs/x2_acc/zero_upcrossing_rate"));
    for (block, parallel) in [(10, true), (7, false)] {
        let path = dir.join(format!("s-{block}.h5"));
        let t = write_sweep_table(&sweep, &path, false, None, opts(block, parallel), &|_, _| {}).unwrap();
        assert_eq!(t.errors, whole.errors);
        let got = h5_contents(&path);
        assert_eq!(got.len(), reference.len());
        for (g, r) in got.iter().zip(&reference) {
            assert_eq!(g, r, "{} (block {block})", r.0);
        }
    }
    // the columns against their definitions, point by point
    let path = dir.join("s-10.h5");
    let two_pi = 2.0 * std::f64::consts::PI;
    for (j, name) in sweep.outputs().iter().enumerate() {
        let col = |c: &str| h5_read::<f64>(&path, &format!("outputs/{name}/{c}"));
        let (mean, var, sigma, lo, hi, l2, nu) = (
            col("mean"),
            col("variance"),
            col("sigma"),
            col("lower_3sigma"),
            col("upper_3sigma"),
            col("lambda2"),
            col("zero_upcrossing_rate"),
        );
        let method = h5_read::<u8>(&path, &format!("outputs/{name}/method"));
        for p in 0..n {
            match sweep.evaluate(p) {
                Err(_) => {
                    assert_eq!(method[p], 255, "{name} at failed point {p}");
                    assert!([mean[p], var[p], sigma[p], lo[p], hi[p], l2[p], nu[p]]
                        .iter()
                        .all(|v| v.is_nan()));
                }
                Ok(stats) => {
                    let s = &stats[j];
                    assert_eq!(method[p], 1, "{name} at {p}: the integral table");
                    // every output has a finite mean and variance here; λ₂ is infinite (None, NaN in
                    // the file) for x2_acc, whose derivative's density decays too slowly
                    let (m, d) = (s.mean.unwrap(), s.variance.unwrap());
                    let bits = |v: f64| v.to_bits();
                    assert_eq!((mean[p], var[p]), (m, d), "{name} at {p}");
                    assert_eq!(bits(l2[p]), bits(s.lambda2.unwrap_or(f64::NAN)), "{name} at {p}");
                    assert_eq!(sigma[p], d.sqrt());
                    assert_eq!((lo[p], hi[p]), (m - 3.0 * d.sqrt(), m + 3.0 * d.sqrt()));
                    let nu_def = s.lambda2.map_or(f64::NAN, |l| (l / d).sqrt() / two_pi);
                    assert_eq!(bits(nu[p]), bits(nu_def), "{name} at {p}");
                    if p % 10 == 0 {
                        let g = &sweep.evaluate_general(p).unwrap()[j];
                        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
                        assert!(rel(d, g.variance.unwrap()) <= TRANSFER_POLYNOMIALS, "{name} at {p}");
                        assert_eq!(s.lambda2.is_some(), g.lambda2.is_some(), "{name} at {p}");
                        if let (Some(l), Some(gl)) = (s.lambda2, g.lambda2) {
                            assert!(rel(l, gl) <= TRANSFER_POLYNOMIALS, "{name} at {p}");
                        }
                    }
                }
            }
        }
    }
    // the value indices, the keys' values as written, the failed points and their reasons in point order
    let _g = common::hdf5_serial();
    let f = hdf5::File::open(&path).unwrap();
    let idx = f.dataset("value_index").unwrap();
    assert_eq!(idx.shape(), [n, 2]);
    let idx: Vec<u64> = idx.read_raw().unwrap();
    for p in 0..n {
        let want: Vec<u64> = sweep.spec().indices(p).iter().map(|&i| i as u64).collect();
        assert_eq!(&idx[2 * p..2 * p + 2], &want[..], "point {p}");
    }
    let text = |name: &str| -> Vec<String> {
        let v = f
            .dataset(name)
            .unwrap()
            .read_raw::<hdf5::types::VarLenUnicode>()
            .unwrap();
        v.iter().map(|s| s.to_string()).collect()
    };
    assert_eq!(text("params/1"), ["0.2", "-0.1", "0.3"]);
    let pts: Vec<u64> = f.dataset("errors/point").unwrap().read_raw().unwrap();
    assert_eq!(pts, (0..n as u64).filter(|p| p % 3 == 1).collect::<Vec<_>>());
    for (&p, m) in pts.iter().zip(text("errors/message")) {
        assert_eq!(m, sweep.evaluate(p as usize).unwrap_err().to_string());
    }
    drop(f);
    drop(_g);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// With a Monte Carlo batch per point the table is streamed point by point with its Monte Carlo values:
/// a streamed CSV and HDF5 table equal the whole table's, the failed point (ζ₂ = −0.1) has no batch and
/// is marked, and progress counts every point once, in order, up to the total.
#[test]
fn streamed_tables_with_monte_carlo_equal_the_whole_table() {
    let sc = scraper();
    let sweep = grid(&sc, &["model.zeta2=0.2,-0.1,0.4"]);
    let mc = Some(SweepMonteCarlo {
        realizations: 4,
        duration_s: 20.0,
        dt_s: 0.01,
        seed: 7,
        shard_size: 2,
        confidence: 0.95,
    });
    let dir = scratch("mc");
    let whole = compute_sweep(&sweep, 0..3, true, mc, &|_, _| {}).unwrap();
    let n_out = sweep.outputs().len();
    assert!(whole
        .values
        .iter()
        .enumerate()
        .all(|(i, v)| v.mc.is_some() == (i / n_out != 1)));
    assert_eq!(whole.errors.iter().map(|e| e.0).collect::<Vec<_>>(), [1]);
    let whole_h5 = dir.join("whole.h5");
    whole.write(&whole_h5, false).unwrap();
    let seen = std::sync::Mutex::new(Vec::new());
    let progress = |done: usize, total: usize| {
        assert_eq!(total, 3);
        seen.lock().unwrap().push(done);
    };
    let csv = dir.join("s.csv");
    let t = write_sweep_table(&sweep, &csv, false, mc, opts(2, true), &progress).unwrap();
    assert_eq!(t.errors, whole.errors);
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), whole.to_csv());
    assert_eq!(*seen.lock().unwrap(), [1, 2, 3]);
    let h5 = dir.join("s.h5");
    write_sweep_table(&sweep, &h5, false, mc, opts(2, true), &progress).unwrap();
    assert_eq!(h5_contents(&h5), h5_contents(&whole_h5));
    assert_eq!(h5_read::<u8>(&h5, "outputs/x1/method")[1], 255);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A sink that fails after `left` bytes.
struct Failing {
    left: usize,
}

impl std::io::Write for Failing {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if buf.len() > self.left {
            return Err(std::io::Error::other("device full"));
        }
        self.left -= buf.len();
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A write that fails on the writer thread in the middle of a study (2000 points, 1.6 MB of CSV, past the
/// 1 MiB output buffer) is the error returned, naming the sink; a table that exists is not replaced without
/// `overwrite` (its bytes unchanged) and is replaced with it; a block of 0 points, an unknown extension
/// and a directory are refused; nothing is left behind.
#[test]
fn stream_errors_name_the_sink_and_lose_nothing() {
    let sc = scraper();
    let big = grid(&sc, &["model.omega2=0.5 Hz..4 Hz:1000", "model.zeta2=0.2,0.3"]);
    let e = stream_sweep_csv(
        &big,
        Failing { left: 5000 },
        Path::new("<pipe>"),
        None,
        opts(50, true),
        &|_, _| {},
    )
    .unwrap_err();
    assert!(
        matches!(&e, stochvib::Error::Io { source, .. } if source.to_string() == "device full"),
        "{e}"
    );
    assert!(e.to_string().contains("<pipe>"), "{e}");
    let sweep = study(&sc);
    let dir = scratch("errors");
    let path = dir.join("t.h5");
    std::fs::write(&path, b"a user's file").unwrap();
    let e = write_sweep_table(&sweep, &path, false, None, opts(16, true), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("already exists") && e.contains("--overwrite"), "{e}");
    assert_eq!(std::fs::read(&path).unwrap(), b"a user's file");
    // a file that is not a sweep table is never replaced, with or without --overwrite (the output rule)
    let e = write_sweep_table(&sweep, &path, true, None, opts(16, true), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("is not a sweep table"), "{e}");
    assert_eq!(std::fs::read(&path).unwrap(), b"a user's file");
    // a sweep table is replaced with --overwrite
    std::fs::remove_file(&path).unwrap();
    write_sweep_table(&sweep, &path, false, None, opts(16, true), &|_, _| {}).unwrap();
    write_sweep_table(&sweep, &path, true, None, opts(16, true), &|_, _| {}).unwrap();
    assert_eq!(h5_read::<f64>(&path, "outputs/x1/sigma").len(), 111);
    let e = write_sweep_table(&sweep, &dir.join("t.txt"), false, None, opts(16, true), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains(".csv, .json or .h5"), "{e}");
    let e = write_sweep_table(&sweep, &dir.join("z.csv"), false, None, opts(0, true), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("block_points") && e.contains("at least one point"), "{e}");
    std::fs::create_dir_all(dir.join("d.csv")).unwrap();
    let e = write_sweep_table(&sweep, &dir.join("d.csv"), true, None, opts(16, true), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("is a directory"), "{e}");
    let mut left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["d.csv", "t.h5"], "no temporary or partial file is left");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `evaluate_into` writes every row, each equal to `evaluate` of that point alone, over a range that
/// starts off a chunk boundary and spans several of its 256-point chunks; a failed point's row is
/// `FAILED_POINT` and its reason is the error `evaluate` gives for it. The buffer starts filled with
/// another value, so an unwritten row would show.
#[test]
fn evaluate_into_rows_equal_single_point_evaluations() {
    let sc = scraper();
    let sweep = grid(&sc, &["model.omega2=0.5 Hz..4 Hz:400", "model.zeta2=0.2,-0.1,0.3"]);
    let n_out = sweep.outputs().len();
    let (first, last) = (300, 1000);
    let sentinel = stochvib::response::PointStatistics {
        mean: Some(-1.0),
        variance: Some(-1.0),
        lambda2: None,
        method: stochvib::response::VarianceMethod::LyapunovDelays,
    };
    for parallel in [false, true] {
        let mut rows = vec![sentinel; (last - first) * n_out];
        let errors = sweep.evaluate_into(first..last, parallel, &mut rows);
        assert_eq!(
            errors.iter().map(|e| e.0).collect::<Vec<_>>(),
            (first..last).filter(|p| p % 3 == 1).collect::<Vec<_>>()
        );
        for (k, row) in rows.chunks(n_out).enumerate() {
            let p = first + k;
            match sweep.evaluate(p) {
                Ok(stats) => assert_eq!(row, &stats[..], "point {p}"),
                Err(e) => {
                    assert!(row.iter().all(|s| *s == FAILED_POINT), "point {p}");
                    let why = &errors.iter().find(|x| x.0 == p).unwrap().1;
                    assert_eq!(why, &e.to_string());
                }
            }
        }
    }
}

/// The command line streams too: over 16 900 points (two of its 16 384-point blocks) the CSV it prints
/// equals the file it writes with `-o`, and both equal the library's whole table; a reader that closes
/// the pipe early (`| head`) ends the program quietly, with status 0 and nothing on stderr but the path
/// line.
#[test]
fn cli_stdout_and_file_tables_are_the_same() {
    use std::io::Read;
    let dir = scratch("cli");
    let file = dir.join("t.csv");
    let args = [
        "sweep",
        "data/scraper-sprung-cab.toml",
        "--param",
        "model.omega2=0.5 Hz..4 Hz:130",
        "--param",
        "model.zeta2=0.1..0.5:130",
    ];
    let bin = crate::common::cli_bin();
    let out = std::process::Command::new(bin)
        .current_dir(crate::common::root())
        .args(args)
        .output_serial()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut with_file: Vec<&str> = args.to_vec();
    with_file.extend(["-o", file.to_str().unwrap()]);
    let o = std::process::Command::new(bin)
        .current_dir(crate::common::root())
        .args(&with_file)
        .output_serial()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.success() && err.contains("wrote 16900 points (0 failed)"),
        "{err}"
    );
    let sc = scraper();
    let sweep = grid(&sc, &["model.omega2=0.5 Hz..4 Hz:130", "model.zeta2=0.1..0.5:130"]);
    let whole = compute_sweep(&sweep, 0..16900, true, None, &|_, _| {})
        .unwrap()
        .to_csv();
    assert_eq!(String::from_utf8(out.stdout).unwrap(), whole);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), whole);
    // a reader that stops after the first bytes
    let mut child = std::process::Command::new(bin)
        .current_dir(crate::common::root())
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn_serial()
        .unwrap();
    let mut first = [0u8; 64];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap(); // dropped: the pipe closes
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("rror"), "{err}");
    assert!(whole.as_bytes().starts_with(&first));
    std::fs::remove_dir_all(&dir).unwrap();
}
