//! Cluster shards and parameter studies: `simulate --shard I --of N`, `merge`, `sweep`.
//!
//! Provenance of the expected values:
//! * Merged files are compared with a different computation: the single-process run of the same scenario,
//!   seed and `--shard-size` (the contract), bit for bit (`f64::to_bits`), statistics, densities and raw
//!   realizations; no number is written into this file.
//! * Refusal messages are checked for the file names and shard indices the test itself set up.
//! * Sweep values are compared with `stochvib analyze` of the substituted scenario (the full analysis, whose
//!   reference variance is the Lyapunov solution: a different exact method than the sweep's integral
//!   table), and the evaluator with closed forms derived in the comments.

use crate::common;
use crate::common::SpawnSerial;

use std::path::{Path, PathBuf};
use std::process::Command;
use stochvib::response::{analyze_output, ExactEvaluator, Excitation, VarianceMethod};
use stochvib::scenario::{load_scenario, Scenario};
use stochvib::simulate::RunOptions;
use stochvib::spectrum::{Domain, Exponential, GaussCosineParameters};
use stochvib::store::{Compression, Part, PsdEstimate, RunFile, SignalGroup};
use stochvib::study::{part_path, resolve_part, MergeOptions};
use stochvib::system::{OutputInfo, StateSpace, TransferFunction};

// ---- tolerances -------------------------------------------------------------------------------------------
/// Sweep (integral table) against `analyze` (Lyapunov): two exact methods through eigen-/polynomial
/// factorisations of well-conditioned 5-state systems (the suite's factorisation tolerance).
const EXACT_METHODS: f64 = common::tolerance::FACTORISATION;
/// Closed form against the integral table of a 2-state problem: a few ulps of the table's elimination.
const CLOSED_FORM: f64 = common::tolerance::EXACT;
/// Sweep and `analyze` on the quadrature route: the same adaptive quadrature of the same integrand, with
/// the density evaluated by two code paths (the reference dense solve and the factored evaluator), which
/// the quadrature requests to relative 1e-10.
const SAME_QUADRATURE: f64 = common::tolerance::QUADRATURE;

/// Realizations of the test run, and realizations per internal shard: B = ⌈37/4⌉ = 10 internal shards,
/// the last of one realization.
const R: usize = 37;
const SHARD_SIZE: usize = 4;
const B: usize = 10;

/// Serialises the spawning of child processes with the in-process writers of this test binary. HDF5 locks a
/// file with flock(2); a child forked by another test thread while a writer's descriptor is open inherits
/// its lock until exec closes it (close-on-exec), and a merge opening that file in that instant fails with
/// "unable to lock file" (seen once in a loaded full run). Spawns hold this lock until the child has exec'd;
/// in-process runs and merges hold it while their files are open.
static SPAWN: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn spawn_lock() -> std::sync::MutexGuard<'static, ()> {
    SPAWN.lock().unwrap_or_else(|e| e.into_inner())
}

/// `sc.simulate` under [`SPAWN`].
fn simulate(sc: &Scenario, o: &RunOptions, path: &Path) -> stochvib::simulate::RunSummary {
    let _g = spawn_lock();
    sc.simulate(o, path, &|_, _| {}).unwrap()
}

/// `stochvib::study::merge_runs` under [`SPAWN`].
fn merge_runs(
    out: &Path,
    inputs: &[PathBuf],
    opts: &MergeOptions,
    progress: &dyn Fn(usize, usize),
) -> stochvib::error::Result<stochvib::study::MergeSummary> {
    let _g = spawn_lock();
    stochvib::study::merge_runs(out, inputs, opts, progress)
}

fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir("shards", name)
}

fn root() -> PathBuf {
    common::root()
}

fn idler() -> Scenario {
    load_scenario(&root().join("data/conveyor-idler.toml"), &root().join("spectra")).unwrap()
}

fn opts(seed: u64, part: Option<Part>) -> RunOptions {
    RunOptions {
        shard_size: SHARD_SIZE,
        store_raw: true,
        part,
        realizations: R,
        duration_s: 1.0,
        dt_s: 0.01,
        seed,
        ..RunOptions::default()
    }
}

/// Runs part `i` of `n` of the idler run with `seed` into `dir`.
fn run_part(sc: &Scenario, dir: &Path, i: usize, n: usize, seed: u64) -> PathBuf {
    let p = Part::new(i, n).unwrap();
    let path = part_path(dir, p);
    simulate(sc, &opts(seed, Some(p)), &path);
    path
}

fn psd_bits(p: &[PsdEstimate]) -> Vec<Vec<u64>> {
    p.iter()
        .map(|e| {
            let mut v: Vec<u64> = [&e.omega, &e.density, &e.lower, &e.upper]
                .into_iter()
                .flatten()
                .map(|x| x.to_bits())
                .collect();
            v.extend(e.analytic.iter().flatten().map(|x| x.to_bits()));
            // the exact mean of the estimate (window ⊛ sampled density) must be carried by the merge too
            assert!(e.expected.is_some(), "{}: no expected estimate", e.output);
            v.extend(e.expected.iter().flatten().map(|x| x.to_bits()));
            v.extend([e.confidence.to_bits(), e.checksum() as u64]);
            v.push(e.dof.to_bits());
            v
        })
        .collect()
}

fn assert_same_run(merged: &Path, whole: &Path) {
    let (m, w) = (RunFile::open(merged).unwrap(), RunFile::open(whole).unwrap());
    assert_eq!(
        common::stored_statistic_bits(&m.statistics().unwrap()),
        common::stored_statistic_bits(&w.statistics().unwrap()),
        "statistics"
    );
    assert_eq!(
        psd_bits(&m.psd().unwrap()),
        psd_bits(&w.psd().unwrap()),
        "Welch densities"
    );
    assert_eq!(m.metadata(), w.metadata(), "metadata");
    for (g, list) in [
        (SignalGroup::Inputs, &w.metadata().inputs),
        (SignalGroup::Outputs, &w.metadata().outputs),
    ] {
        for s in list.iter() {
            let a = m.read_signals(g, &s.name, 0..R).unwrap();
            let b = w.read_signals(g, &s.name, 0..R).unwrap();
            assert!(
                a.iter().zip(b.iter()).all(|(x, y)| x.to_bits() == y.to_bits()),
                "raw {} of {}",
                s.name,
                merged.display()
            );
        }
    }
    m.verify().unwrap();
}

/// The merge of N shard files equals the single-process run bit for bit, for N = 1, 2, 3, 4, 7, 10 = B, the
/// parts computed in a shuffled order and given to the merge in another shuffled order (or as their
/// directory); raw data read through the virtual datasets, and copied with `copy`; compressed shards too.
#[test]
fn merged_run_is_bit_identical_for_any_split_and_order() {
    let sc = idler();
    let dir = scratch("bit");
    let whole = dir.join("whole.h5");
    simulate(&sc, &opts(7, None), &whole);
    for n in [1, 2, 3, 4, 7, B] {
        let parts = dir.join(format!("n{n}"));
        std::fs::create_dir_all(&parts).unwrap();
        // computed in the order n-1, 0, n-2, 1, ... and listed to the merge rotated by n/2
        let mut order: Vec<usize> = Vec::new();
        let (mut lo, mut hi) = (0, n);
        while lo < hi {
            hi -= 1;
            order.push(hi);
            if lo < hi {
                order.push(lo);
                lo += 1;
            }
        }
        let files: Vec<PathBuf> = order.iter().map(|&i| run_part(&sc, &parts, i, n, 7)).collect();
        let mut listed = files.clone();
        listed.rotate_left(n / 2);
        let merged = dir.join(format!("merged-{n}.h5"));
        let s = merge_runs(&merged, &listed, &MergeOptions::default(), &|_, _| {}).unwrap();
        assert_eq!(s.n_shards, B);
        assert_same_run(&merged, &whole);
        // the merged file is small: its raw datasets are virtual
        if n > 1 {
            let raw = std::fs::metadata(&whole).unwrap().len();
            assert!(
                std::fs::metadata(&merged).unwrap().len() < raw / 2,
                "merged file not small"
            );
        }
        if n == 4 {
            let copied = dir.join("copied-4.h5");
            let opts = MergeOptions {
                copy: true,
                ..MergeOptions::default()
            };
            merge_runs(&copied, std::slice::from_ref(&parts), &opts, &|_, _| {}).unwrap();
            assert_same_run(&copied, &whole);
            let from = RunFile::open(&copied).unwrap().merged_from().cloned().unwrap();
            assert_eq!(from.raw, stochvib::store::RawStorage::Copied);
        }
    }
    // compressed shards behind virtual datasets
    let comp = |part| RunOptions {
        compression: Compression::DEFLATE_FAST,
        ..opts(11, part)
    };
    let zwhole = dir.join("zwhole.h5");
    simulate(&sc, &comp(None), &zwhole);
    let zdir = dir.join("z");
    std::fs::create_dir_all(&zdir).unwrap();
    for i in [2, 0, 1] {
        let p = Part::new(i, 3).unwrap();
        simulate(&sc, &comp(Some(p)), &part_path(&zdir, p));
    }
    let zm = dir.join("zmerged.h5");
    merge_runs(&zm, std::slice::from_ref(&zdir), &MergeOptions::default(), &|_, _| {}).unwrap();
    assert_same_run(&zm, &zwhole);
    std::fs::remove_dir_all(&dir).unwrap();
}

fn merge_err(out: &Path, inputs: &[PathBuf]) -> String {
    merge_runs(out, inputs, &MergeOptions::default(), &|_, _| {})
        .unwrap_err()
        .to_string()
}

/// Missing, duplicate, overlapping and foreign shard files and a whole run are refused with messages that
/// name them and the indices to resubmit; nothing is written, and an existing output is never replaced.
#[test]
fn merge_refuses_incomplete_or_mixed_shard_sets() {
    let sc = idler();
    let dir = scratch("refuse");
    let parts = dir.join("parts");
    std::fs::create_dir_all(&parts).unwrap();
    for i in [0, 1, 3] {
        run_part(&sc, &parts, i, 4, 7);
    }
    let out = dir.join("merged.h5");
    // 1. shard 2 of 4 missing: internal shards ⌈2·10/4⌉ = 5 .. ⌈3·10/4⌉ = 8, realizations 20..32
    let e = merge_err(&out, std::slice::from_ref(&parts));
    assert!(e.contains("missing shard(s) 2 (realizations 20..32) of 4"), "{e}");
    assert!(e.contains("--array=2 "), "{e}");
    assert!(!out.exists() && !stochvib::store::tmp_path(&out).exists());
    run_part(&sc, &parts, 2, 4, 7);
    // 2. a duplicate of shard 1
    let dup = parts.join("copy-of-1.h5");
    std::fs::copy(parts.join("shard-1-of-4.h5"), &dup).unwrap();
    let e = merge_err(&out, std::slice::from_ref(&parts));
    assert!(e.contains("duplicate shard 1 of 4"), "{e}");
    assert!(e.contains("copy-of-1.h5") && e.contains("shard-1-of-4.h5"), "{e}");
    std::fs::remove_file(&dup).unwrap();
    // 3. an overlapping split: shard 0 of 2 holds internal shards 0..5, as shards 0 and 1 of 4 do
    let other = dir.join("other");
    std::fs::create_dir_all(&other).unwrap();
    let half = run_part(&sc, &other, 0, 2, 7);
    let mut inputs = vec![parts.clone(), half.clone()];
    let e = merge_err(&out, &inputs);
    assert!(
        e.contains("overlapping shard files") && e.contains("shard-0-of-2.h5"),
        "{e}"
    );
    // ... while a split that tiles (shard 0 of 2 with shards 2, 3 of 4) merges like the single run
    inputs = vec![half, parts.join("shard-2-of-4.h5"), parts.join("shard-3-of-4.h5")];
    let whole = dir.join("whole.h5");
    simulate(&sc, &opts(7, None), &whole);
    merge_runs(&out, &inputs, &MergeOptions::default(), &|_, _| {}).unwrap();
    assert_same_run(&out, &whole);
    // 4. an existing merged file is not replaced
    let before = std::fs::read(&out).unwrap();
    let e = merge_err(&out, std::slice::from_ref(&parts));
    assert!(e.contains("already exists"), "{e}");
    assert_eq!(std::fs::read(&out).unwrap(), before);
    // 5. a foreign shard (another seed) and a whole run in the directory
    let foreign_dir = dir.join("foreign");
    std::fs::create_dir_all(&foreign_dir).unwrap();
    let foreign = run_part(&sc, &foreign_dir, 2, 4, 8);
    let renamed = parts.join("zz-shard-2-from-seed-8.h5");
    std::fs::copy(&foreign, &renamed).unwrap();
    std::fs::copy(&whole, parts.join("whole-run.h5")).unwrap();
    let out2 = dir.join("merged2.h5");
    let e = merge_err(&out2, std::slice::from_ref(&parts));
    assert!(
        e.contains("zz-shard-2-from-seed-8.h5: foreign shard file") && e.contains("seed"),
        "{e}"
    );
    assert!(e.contains("whole-run.h5: a whole run"), "{e}");
    assert!(!out2.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

fn stochvib(args: &[&str], env: &[(&str, &str)]) -> (bool, String, String) {
    let mut c = Command::new(crate::common::cli_bin());
    c.current_dir(root()).args(args);
    for k in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_MIN",
        "SLURM_ARRAY_TASK_MAX",
        "SLURM_ARRAY_TASK_COUNT",
        "JOB_COMPLETION_INDEX",
    ] {
        c.env_remove(k);
    }
    for (k, v) in env {
        c.env(k, v);
    }
    let child = {
        let _g = spawn_lock();
        c.stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn_serial()
            .unwrap()
    };
    let o = child.wait_with_output().unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn sim_args<'a>(dir: &'a str, shard: &'a str, of: Option<&'a str>) -> Vec<&'a str> {
    let mut a = vec![
        "simulate",
        "data/conveyor-idler.toml",
        "--realizations",
        "37",
        "--duration",
        "1",
        "--dt",
        "0.01",
        "--seed",
        "7",
        "--shard-size",
        "4",
        "--shard",
        shard,
    ];
    if let Some(n) = of {
        a.extend(["--of", n]);
    }
    a.extend(["-o", dir]);
    a
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// `--shard auto` takes I (and N for a whole SLURM array 0..N-1) from the scheduler's variables, set here
/// on the child process; without a scheduler, or where N cannot be known, it fails with the reason.
#[test]
fn shard_auto_reads_the_scheduler_environment() {
    let dir = scratch("auto");
    let d = format!("{}/", dir.display());
    let slurm = [
        ("SLURM_ARRAY_TASK_ID", "1"),
        ("SLURM_ARRAY_TASK_MIN", "0"),
        ("SLURM_ARRAY_TASK_MAX", "2"),
        ("SLURM_ARRAY_TASK_COUNT", "3"),
    ];
    let (ok, _, err) = stochvib(&sim_args(&d, "auto", None), &slurm);
    assert!(ok, "{err}");
    assert!(
        err.contains("SLURM_ARRAY_TASK_ID=1 of SLURM_ARRAY_TASK_COUNT=3"),
        "{err}"
    );
    assert_eq!(files_in(&dir), ["shard-1-of-3.h5"]);
    // SLURM without SLURM_ARRAY_TASK_COUNT: N = SLURM_ARRAY_TASK_MAX + 1 for an array 0..MAX
    let min_max = [
        ("SLURM_ARRAY_TASK_ID", "0"),
        ("SLURM_ARRAY_TASK_MIN", "0"),
        ("SLURM_ARRAY_TASK_MAX", "2"),
    ];
    let (ok, _, err) = stochvib(&sim_args(&d, "auto", None), &min_max);
    assert!(
        ok && err.contains("SLURM_ARRAY_TASK_ID=0 of SLURM_ARRAY_TASK_MAX+1=3"),
        "{err}"
    );
    assert_eq!(files_in(&dir), ["shard-0-of-3.h5", "shard-1-of-3.h5"]);
    std::fs::remove_file(dir.join("shard-0-of-3.h5")).unwrap();
    // a resubmitted index runs in an array of one task: N must be given
    let resubmitted = [
        ("SLURM_ARRAY_TASK_ID", "2"),
        ("SLURM_ARRAY_TASK_MIN", "2"),
        ("SLURM_ARRAY_TASK_MAX", "2"),
        ("SLURM_ARRAY_TASK_COUNT", "1"),
    ];
    let (ok, _, err) = stochvib(&sim_args(&d, "auto", None), &resubmitted);
    assert!(!ok && err.contains("give --of N"), "{err}");
    let (ok, _, err) = stochvib(&sim_args(&d, "auto", Some("3")), &resubmitted);
    assert!(ok, "{err}");
    // Kubernetes: the index from JOB_COMPLETION_INDEX, N from --of only
    let k8s = [("JOB_COMPLETION_INDEX", "0")];
    let (ok, _, err) = stochvib(&sim_args(&d, "auto", None), &k8s);
    assert!(
        !ok && err.contains("JOB_COMPLETION_INDEX") && err.contains("--of N"),
        "{err}"
    );
    let (ok, _, err) = stochvib(&sim_args(&d, "auto", Some("3")), &k8s);
    assert!(ok, "{err}");
    assert_eq!(
        files_in(&dir),
        ["shard-0-of-3.h5", "shard-1-of-3.h5", "shard-2-of-3.h5"]
    );
    // no scheduler
    let (ok, _, err) = stochvib(&sim_args(&d, "auto", Some("3")), &[]);
    assert!(!ok && err.contains("no scheduler index"), "{err}");
    // the three parts merge
    let out = dir.join("../auto-merged.h5");
    let (ok, _, err) = stochvib(&["merge", out.to_str().unwrap(), &d], &[]);
    assert!(ok, "{err}");
    let _ = std::fs::remove_file(&out);
    // the library function with the same variables
    let env = |k: &str| slurm.iter().find(|(n, _)| *n == k).map(|(_, v)| v.to_string());
    assert_eq!(resolve_part("auto", None, &env).unwrap().part, Part::new(1, 3).unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Bad shard arguments get a clear error and write nothing: an index outside [0, N), more shards than
/// internal shards (naming --shard-size) or than realizations, an index without --of.
#[test]
fn bad_shard_arguments_are_refused() {
    let dir = scratch("bad");
    let d = format!("{}/", dir.display());
    let (ok, _, err) = stochvib(&sim_args(&d, "4", Some("4")), &[]);
    assert!(!ok && err.contains("[0, 4)"), "{err}");
    let (ok, _, err) = stochvib(&sim_args(&d, "0", Some("11")), &[]);
    assert!(
        !ok && err.contains("--shard-size") && err.contains("--of <= 10"),
        "{err}"
    );
    let (ok, _, err) = stochvib(&sim_args(&d, "0", Some("40")), &[]);
    assert!(!ok && err.contains("37 realizations"), "{err}");
    let (ok, _, err) = stochvib(&sim_args(&d, "1", None), &[]);
    assert!(!ok && err.contains("needs --of N"), "{err}");
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A rerun of a finished shard is a no-op (the file is not rewritten); a finished shard of another run
/// under the same name is never replaced.
#[test]
fn shard_rerun_is_a_no_op() {
    let dir = scratch("rerun");
    let d = format!("{}/", dir.display());
    let (ok, _, err) = stochvib(&sim_args(&d, "1", Some("3")), &[]);
    assert!(ok, "{err}");
    let f = dir.join("shard-1-of-3.h5");
    let (bytes, mtime) = (
        std::fs::read(&f).unwrap(),
        std::fs::metadata(&f).unwrap().modified().unwrap(),
    );
    let (ok, out, err) = stochvib(&sim_args(&d, "1", Some("3")), &[]);
    assert!(ok, "{err}");
    assert!(
        out.contains("already complete") && out.contains("nothing to do"),
        "{out}"
    );
    assert_eq!(std::fs::read(&f).unwrap(), bytes);
    assert_eq!(std::fs::metadata(&f).unwrap().modified().unwrap(), mtime);
    let mut other = sim_args(&d, "1", Some("3"));
    other[9] = "8"; // --seed 8
    let (ok, _, err) = stochvib(&other, &[]);
    assert!(!ok && err.contains("another run") && err.contains("seed"), "{err}");
    assert_eq!(std::fs::read(&f).unwrap(), bytes);
    std::fs::remove_dir_all(&dir).unwrap();
}

fn python(script: &str, args: &[&str], cwd: &Path) -> String {
    let child = {
        let _g = spawn_lock();
        Command::new("python3")
            .current_dir(cwd)
            .arg("-c")
            .arg(script)
            .args(args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn_serial()
            .expect("python3 with h5py is required (bash scripts/test.sh installs it)")
    };
    let o = child.wait_with_output().unwrap();
    assert!(
        o.status.success(),
        "python failed: {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// h5py reads the merged raw realizations through the virtual datasets, equal to the single-process run's;
/// the merged file and its shard directory can move together (relative source paths, resolved against the
/// merged file's directory whatever the working directory); a moved-away shard directory reads as NaN in
/// h5py and is an error naming the shard file in stochvib.
#[test]
fn virtual_raw_data_are_readable_by_h5py() {
    let sc = idler();
    let dir = scratch("vds");
    let whole = dir.join("whole.h5");
    simulate(&sc, &opts(5, None), &whole);
    let runs = dir.join("runs");
    std::fs::create_dir_all(&runs).unwrap();
    for i in 0..3 {
        run_part(&sc, &runs, i, 3, 5);
    }
    let merged = dir.join("merged.h5");
    merge_runs(
        &merged,
        std::slice::from_ref(&runs),
        &MergeOptions::default(),
        &|_, _| {},
    )
    .unwrap();
    let check = r#"
import sys, h5py, numpy as np
m, w = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r')
for g in ('inputs', 'outputs'):
    for name in w[g].attrs['names']:
        d = m[g][name]
        assert d.is_virtual, (g, name)
        assert d.shape == w[g][name].shape
        assert np.array_equal(d[...], w[g][name][...]), (g, name)
assert list(m['parts'].attrs['files']) == ['runs/shard-0-of-3.h5', 'runs/shard-1-of-3.h5', 'runs/shard-2-of-3.h5']
assert m['parts'].attrs['raw'] == 'virtual'
assert int(m.attrs['format_version']) == 3
print('ok')
"#;
    let w = whole.to_str().unwrap();
    assert_eq!(python(check, &[merged.to_str().unwrap(), w], &dir).trim(), "ok");
    // move both to another directory; read from an unrelated working directory
    let moved = dir.join("moved");
    std::fs::create_dir_all(&moved).unwrap();
    std::fs::rename(&merged, moved.join("merged.h5")).unwrap();
    std::fs::rename(&runs, moved.join("runs")).unwrap();
    let m2 = moved.join("merged.h5");
    assert_eq!(python(check, &[m2.to_str().unwrap(), w], Path::new("/")).trim(), "ok");
    assert_same_run(&m2, &whole);
    // the shard directory moves away: fill values (NaN) in h5py, an error in stochvib
    std::fs::rename(moved.join("runs"), dir.join("elsewhere")).unwrap();
    let nan =
        "import sys, h5py, numpy as np\nprint(bool(np.isnan(h5py.File(sys.argv[1], 'r')['outputs/y'][...]).all()))";
    assert_eq!(python(nan, &[m2.to_str().unwrap()], &dir).trim(), "True");
    let run = RunFile::open(&m2).unwrap();
    let e = run.read_signal(SignalGroup::Outputs, "y", 0).unwrap_err().to_string();
    assert!(e.contains("runs/shard-0-of-3.h5") && e.contains("--copy"), "{e}");
    assert!(run.verify().is_err());
    drop(run);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The exact evaluator against closed forms, and its three routes against `analyze_output`.
///
/// First-order low-pass H(s) = 1/(1 + T s) under K(τ) = D e^{−α|τ|}, S(ω) = αD/(π(α² + ω²)). With
/// β = 1/T and ∫dω/((α²+ω²)(β²+ω²)) = π/(αβ(α+β)), ∫ω² dω/((α²+ω²)(β²+ω²)) = π/(α+β):
/// D_y = αD/(πT²)·π/(αβ(α+β)) = D/(1 + αT) and λ₂ = αD/(πT²)·π/(α+β) = αD/(T(1 + αT)).
/// The mean: M_y = H(0)·M = M.
#[test]
fn exact_evaluator_matches_closed_forms_and_analyze() {
    let (d, alpha, t, mean) = (2.0, 3.0, 0.25, 0.7);
    let exc = Excitation::single(
        std::sync::Arc::new(Exponential::new(d, alpha, Domain::Temporal).unwrap()),
        mean,
    )
    .unwrap();
    let sys = TransferFunction::new(vec![1.0], vec![1.0, t], OutputInfo::new("y", "m")).unwrap();
    let st = ExactEvaluator::new(&exc).evaluate(&sys, &exc, &[0]).unwrap()[0];
    assert_eq!(st.method, VarianceMethod::IntegralTable);
    let want_var = d / (1.0 + alpha * t);
    let want_l2 = alpha * d / (t * (1.0 + alpha * t));
    assert!(
        common::rel(st.variance.unwrap(), want_var) < CLOSED_FORM,
        "{st:?} vs {want_var}"
    );
    assert!(
        common::rel(st.lambda2.unwrap(), want_l2) < CLOSED_FORM,
        "{st:?} vs {want_l2}"
    );
    assert!(common::rel(st.mean.unwrap(), mean) < CLOSED_FORM);
    // Lyapunov route: two independent rational processes into a 2-input system
    let two = Excitation::independent(
        vec![
            std::sync::Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()),
            std::sync::Arc::new(Exponential::new(0.5, 7.0, Domain::Temporal).unwrap()),
        ],
        vec![0.0, 0.0],
    )
    .unwrap();
    let osc = StateSpace::oscillator(6.0, 0.2).unwrap();
    let b2 = nalgebra::DMatrix::from_row_slice(2, 2, &[0.0, 0.3, 1.0, -0.5]);
    let sys2 = StateSpace::new(
        osc.a.clone(),
        b2,
        osc.c.clone(),
        None,
        None,
        vec![OutputInfo::new("x", "m")],
    )
    .unwrap();
    let st2 = ExactEvaluator::new(&two).evaluate(&sys2, &two, &[0]).unwrap()[0];
    assert_eq!(st2.method, VarianceMethod::Lyapunov);
    let full = analyze_output(&sys2, &two, 0).unwrap();
    assert_eq!(st2.variance, full.variance);
    // quadrature route: a non-rational (type 4) input
    let g = Excitation::single(
        std::sync::Arc::new(
            GaussCosineParameters {
                variance: 1e-3,
                alpha: 20.0,
                beta: 15.0,
                domain: Domain::Temporal,
            }
            .build()
            .unwrap(),
        ),
        0.0,
    )
    .unwrap();
    let st3 = ExactEvaluator::new(&g).evaluate(&osc, &g, &[0]).unwrap()[0];
    assert_eq!(st3.method, VarianceMethod::Quadrature);
    let full = analyze_output(&osc, &g, 0).unwrap();
    assert!(common::rel(st3.variance.unwrap(), full.variance.unwrap()) < SAME_QUADRATURE);
}

fn sweep_json(args: &[&str]) -> serde_json::Value {
    let (ok, out, err) = stochvib(args, &[]);
    assert!(ok, "{err}");
    serde_json::from_str(&out).unwrap()
}

fn analyze_sigmas(text: &str, dir: &Path, name: &str) -> Vec<(String, Option<f64>, Option<f64>)> {
    let f = dir.join(name);
    std::fs::write(&f, text).unwrap();
    let spectra = root().join("spectra");
    let (ok, out, err) = stochvib(
        &[
            "analyze",
            f.to_str().unwrap(),
            "--json",
            "--spectra-dir",
            spectra.to_str().unwrap(),
        ],
        &[],
    );
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    v["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| {
            let s = &o["statistics"];
            (
                s["name"].as_str().unwrap().to_string(),
                s["sigma"].as_f64(),
                s["mean"].as_f64(),
            )
        })
        .collect()
}

/// Every point of a sweep equals `stochvib analyze` of the scenario with that point's values written into
/// it (model keys, the speed, and a key outside the fast path), and a sweep in shards merges into the same
/// table as the whole sweep.
#[test]
fn sweep_matches_analyze_of_the_substituted_scenario() {
    let dir = scratch("sweep");
    let base = std::fs::read_to_string(root().join("data/scraper-sprung-cab.toml")).unwrap();
    type Case<'a> = (&'a str, Vec<&'a str>, fn(&str, &str, &str) -> String);
    let cases: [Case; 2] = [
        (
            "model",
            vec![
                "--param",
                "model.omega2=1 Hz..2 Hz:3",
                "--param",
                "model.zeta2=0.2,0.35",
            ],
            |base, a, b| {
                base.replace("omega2 = \"1.5 Hz\"", &format!("omega2 = \"{a}\""))
                    .replace("zeta2 = 0.3", &format!("zeta2 = {b}"))
            },
        ),
        (
            "speed",
            vec![
                "--param",
                "input.speed=5 m/s,15 m/s",
                "--param",
                "model.zeta1=0.1,0.2",
                "--zip",
            ],
            |base, a, b| {
                base.replace("speed = \"10 m/s\"", &format!("speed = \"{a}\""))
                    .replace("zeta1 = 0.1", &format!("zeta1 = {b}"))
            },
        ),
    ];
    for (tag, params, substitute) in cases {
        let mut args = vec!["sweep", "data/scraper-sprung-cab.toml", "--json"];
        args.extend(params.iter());
        let t = sweep_json(&args);
        let rows = t["rows"].as_array().unwrap();
        let keys: Vec<String> = t["identity"]["params"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| p[0].as_str().unwrap().to_string())
            .collect();
        let n_points = t["n_points"].as_u64().unwrap() as usize;
        for p in 0..n_points {
            let row0 = rows.iter().find(|r| r["point"] == p).unwrap();
            let a = row0["params"][&keys[0]]
                .as_str()
                .map(String::from)
                .unwrap_or_else(|| row0["params"][&keys[0]].to_string());
            let b = row0["params"][&keys[1]]
                .as_str()
                .map(String::from)
                .unwrap_or_else(|| row0["params"][&keys[1]].to_string());
            let text = substitute(&base, &a, &b);
            assert_ne!(text, base, "{tag}: the substitution changed nothing");
            for (name, sigma, mean) in analyze_sigmas(&text, &dir, &format!("{tag}-{p}.toml")) {
                let r = rows
                    .iter()
                    .find(|r| r["point"] == p && r["output"] == name.as_str())
                    .unwrap();
                match (sigma, r["sigma"].as_f64()) {
                    (Some(x), Some(y)) => {
                        assert!(common::rel(x, y) < EXACT_METHODS, "{tag} point {p} {name}: {x} vs {y}")
                    }
                    (x, y) => assert_eq!(x.is_some(), y.is_some(), "{tag} point {p} {name}"),
                }
                // M_y = H(0)·0 for the zero-mean road: zero up to the rounding of H(0) in either code
                let scale = sigma.unwrap_or(1.0);
                assert!(
                    (mean.unwrap() - r["mean"].as_f64().unwrap()).abs() <= EXACT_METHODS * scale,
                    "{name}"
                );
            }
        }
    }
    // a key outside the fast path (the input's mean) on the quadrature route (ISO road), against analyze
    let qbase = std::fs::read_to_string(root().join("data/quarter-car-model.toml")).unwrap();
    let t = sweep_json(&[
        "sweep",
        "data/quarter-car-model.toml",
        "--json",
        "--param",
        "input.mean=0.01,0.02",
    ]);
    for (p, m) in [(0, "0.01"), (1, "0.02")] {
        let text = qbase.replace("speed = \"20 m/s\"", &format!("speed = \"20 m/s\"\nmean = {m}"));
        for (name, sigma, mean) in analyze_sigmas(&text, &dir, &format!("q-{p}.toml")) {
            let r = t["rows"]
                .as_array()
                .unwrap()
                .iter()
                .find(|r| r["point"] == p && r["output"] == name.as_str())
                .unwrap();
            assert!(
                common::rel(sigma.unwrap(), r["sigma"].as_f64().unwrap()) < SAME_QUADRATURE,
                "{name}"
            );
            let (x, y) = (mean.unwrap(), r["mean"].as_f64().unwrap());
            assert!(
                (x - y).abs() <= CLOSED_FORM * x.abs().max(sigma.unwrap()),
                "{name}: {x} vs {y}"
            );
        }
    }
    // shards: three parts in reverse order merge into the whole table, byte for byte
    let sdir = dir.join("shards");
    let sd = format!("{}/", sdir.display());
    let sweep_args = [
        "sweep",
        "data/scraper-sprung-cab.toml",
        "--param",
        "model.omega2=1 Hz..2 Hz:4",
        "--param",
        "model.zeta2=0.2,0.3",
    ];
    let whole = dir.join("whole.csv");
    let mut a = sweep_args.to_vec();
    a.extend(["-o", whole.to_str().unwrap()]);
    assert!(stochvib(&a, &[]).0);
    for i in ["2", "0"] {
        let mut a = sweep_args.to_vec();
        a.extend(["--shard", i, "--of", "3", "-o", &sd]);
        let (ok, _, err) = stochvib(&a, &[]);
        assert!(ok, "{err}");
    }
    let merged = dir.join("merged.csv");
    let (ok, _, err) = stochvib(&["merge", merged.to_str().unwrap(), &sd], &[]);
    assert!(
        !ok && err.contains("missing shard(s) 1 of 3") && err.contains("--array=1 "),
        "{err}"
    );
    let mut a = sweep_args.to_vec();
    a.extend(["--shard", "1", "--of", "3", "-o", &sd]);
    assert!(stochvib(&a, &[]).0);
    let (ok, _, err) = stochvib(&["merge", merged.to_str().unwrap(), &sd], &[]);
    assert!(ok, "{err}");
    assert_eq!(
        std::fs::read_to_string(&merged).unwrap(),
        std::fs::read_to_string(&whole).unwrap()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
