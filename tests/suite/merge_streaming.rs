//! `stochvib merge` of many shard files and of verdict runs: the merge reads every
//! file's header first, then folds the files one at a time; verdict scenarios (ISO 2631-1 metrics and
//! rainflow) run as cluster shards and merge bit-identically; `inspect` abbreviates long shard lists.
//!
//! Provenance of the expected values: every merged number is compared bit for bit (`f64::to_bits`) with a
//! different computation, the single-process run of the same scenario, seed and `--shard-size` (the
//! contract of `merge`); refusal and inspection texts are checked for the file names the test set up. No
//! number is written into this file.

use crate::common;
use crate::common::SpawnSerial;

use std::path::{Path, PathBuf};
use std::process::Command;
use stochvib::scenario::{load_scenario, Scenario};
use stochvib::simulate::RunOptions;
use stochvib::store::{Part, PsdEstimate, RainflowHistogram, RunFile};
use stochvib::study::{part_path, MergeOptions};

/// Serialises this binary's in-process HDF5 work with the spawning of child processes: a child forked while
/// a test thread holds an HDF5 file open inherits its descriptor and its flock(2) lock (until exec closes
/// it, or for the child's whole life if the fork fell between HDF5's open(2) and the close-on-exec flag),
/// and a later open of that file fails with "unable to lock file". Holding this lock around every in-process
/// run and merge, and around every spawn until the child has exec'd, makes that impossible.
static SPAWN: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn spawn_lock() -> std::sync::MutexGuard<'static, ()> {
    SPAWN.lock().unwrap_or_else(|e| e.into_inner())
}

fn scratch(name: &str) -> PathBuf {
    crate::common::scratch_dir("mstream", name)
}

fn scenario(file: &str) -> Scenario {
    load_scenario(&common::root().join("data").join(file), &common::root().join("spectra")).unwrap()
}

fn simulate(sc: &Scenario, o: &RunOptions, path: &Path) {
    let _g = spawn_lock();
    sc.simulate(o, path, &|_, _| {}).unwrap();
}

fn merge(out: &Path, inputs: &[PathBuf]) -> stochvib::error::Result<stochvib::study::MergeSummary> {
    let _g = spawn_lock();
    stochvib::study::merge_runs(out, inputs, &MergeOptions::default(), &|_, _| {})
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn psd_bits(p: &[PsdEstimate]) -> Vec<(String, Vec<u64>, u32)> {
    p.iter()
        .map(|e| {
            let mut v = bits(&[&e.omega[..], &e.density, &e.lower, &e.upper].concat());
            v.extend(bits(e.analytic.as_deref().unwrap_or(&[])));
            v.extend(bits(e.expected.as_deref().unwrap_or(&[])));
            v.extend([e.confidence.to_bits(), e.dof.to_bits()]);
            (e.output.clone(), v, e.checksum())
        })
        .collect()
}

/// (output, unit, bits of edges, counts, overflow, Dirlik counts).
type RainflowBits = (String, String, Vec<u64>, Vec<u64>, u64, Vec<u64>);

fn rainflow_bits(r: &[RainflowHistogram]) -> Vec<RainflowBits> {
    r.iter()
        .map(|h| {
            (
                h.output.clone(),
                h.unit.clone(),
                bits(&h.edges),
                bits(&h.counts),
                h.overflow.to_bits(),
                bits(h.dirlik.as_deref().unwrap_or(&[])),
            )
        })
        .collect()
}

/// The merged file's statistics (with every verdict statistic), densities and rainflow histograms are
/// those of the single-process run, bit for bit.
fn assert_same_results(merged: &Path, whole: &Path) {
    let _g = spawn_lock();
    let (m, w) = (RunFile::open(merged).unwrap(), RunFile::open(whole).unwrap());
    assert_eq!(
        common::stored_statistic_bits(&m.statistics().unwrap()),
        common::stored_statistic_bits(&w.statistics().unwrap()),
        "statistics"
    );
    assert_eq!(psd_bits(&m.psd().unwrap()), psd_bits(&w.psd().unwrap()), "densities");
    assert_eq!(
        rainflow_bits(&m.rainflow().unwrap()),
        rainflow_bits(&w.rainflow().unwrap()),
        "rainflow"
    );
    assert_eq!(m.metadata(), w.metadata(), "metadata");
    m.verify().unwrap();
}

/// The catalogue's verdict scenario (weighted a_w, VDV, MTVV, crest factor of the seat; rainflow damage of
/// the seat spring) computed as N = 1, 2, 3 cluster shards in a shuffled order and merged from another
/// order equals the single-process run: every statistic (VDV/MTVV/crest-factor/damage intervals and
/// their analytic values) and the rainflow histogram with its Dirlik counts.
#[test]
fn verdict_runs_merge_bit_identically() {
    let sc = scenario("operator-seat-verdicts.toml");
    let dir = scratch("verdicts");
    // 7 realizations in shards of 2: B = 4 internal shards, the last of one realization; 4 s records
    // (MTVV needs 1 s) at the scenario's 5 ms step
    let opts = |part| RunOptions {
        shard_size: 2,
        part,
        realizations: 7,
        duration_s: 4.0,
        dt_s: 0.005,
        seed: 18,
        ..RunOptions::default()
    };
    let whole = dir.join("whole.h5");
    simulate(&sc, &opts(None), &whole);
    {
        let _g = spawn_lock();
        let w = RunFile::open(&whole).unwrap();
        let names: Vec<String> = w
            .statistics()
            .unwrap()
            .iter()
            .flat_map(|o| o.statistics.iter().map(|s| s.name.clone()).collect::<Vec<_>>())
            .collect();
        for n in ["vdv", "mtvv", "crest_factor", "damage_rate"] {
            assert!(
                names.iter().any(|s| s == n),
                "the run has no `{n}` statistic: {names:?}"
            );
        }
        assert!(!w.rainflow().unwrap().is_empty(), "the run has no rainflow histogram");
    }
    for n in [1, 2, 3] {
        let parts = dir.join(format!("n{n}"));
        std::fs::create_dir_all(&parts).unwrap();
        let mut files: Vec<PathBuf> = (0..n)
            .rev()
            .map(|i| {
                let p = Part::new(i, n).unwrap();
                let path = part_path(&parts, p);
                simulate(&sc, &opts(Some(p)), &path);
                path
            })
            .collect();
        files.rotate_left(n / 2);
        let merged = dir.join(format!("merged-{n}.h5"));
        merge(&merged, &files).unwrap();
        assert_same_results(&merged, &whole);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

fn h5_root_attr_remove(path: &Path, name: &str) {
    let _g = spawn_lock();
    let f = hdf5::File::open_rw(path).unwrap();
    f.delete_attr(name).unwrap();
}

fn h5_root_attr_set_u32(path: &Path, name: &str, value: u32) {
    let _g = spawn_lock();
    let f = hdf5::File::open_rw(path).unwrap();
    f.delete_attr(name).unwrap();
    f.new_attr::<u32>().create(name).unwrap().write_scalar(&value).unwrap();
}

fn stochvib(args: &[&str]) -> String {
    let mut c = Command::new(crate::common::cli_bin());
    c.args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    let child = {
        let _g = spawn_lock();
        c.spawn_serial().unwrap()
    };
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Forty one-realization shard files (the many-small-files case the streaming merge is for), given in
/// reverse order, merge to the single-process run bit for bit; a file without the stored fingerprint
/// (`@shared_crc32`, as written before it existed) is fingerprinted from its groups and merges the same;
/// a file whose fingerprint disagrees is refused, naming it, and nothing is written. `inspect` of the
/// merged file lists the first shard files and "… and 36 more"; `--json` lists all forty.
#[test]
fn many_small_shards_merge_and_inspect_abbreviates() {
    let sc = scenario("conveyor-idler.toml");
    let dir = scratch("many");
    const R: usize = 40;
    let opts = |part| RunOptions {
        shard_size: 1,
        part,
        realizations: R,
        duration_s: 1.0,
        dt_s: 0.01,
        seed: 5,
        ..RunOptions::default()
    };
    let whole = dir.join("whole.h5");
    simulate(&sc, &opts(None), &whole);
    let parts = dir.join("parts");
    std::fs::create_dir_all(&parts).unwrap();
    let files: Vec<PathBuf> = (0..R)
        .rev()
        .map(|i| {
            let p = Part::new(i, R).unwrap();
            let path = part_path(&parts, p);
            simulate(&sc, &opts(Some(p)), &path);
            path
        })
        .collect();
    // a file as written before the fingerprint attributes existed
    h5_root_attr_remove(&files[3], "shared_crc32");
    h5_root_attr_remove(&files[3], "confidence_crc32");
    let merged = dir.join("merged.h5");
    let s = merge(&merged, &files).unwrap();
    assert_eq!(s.files.len(), R);
    assert_same_results(&merged, &whole);

    // inspect: abbreviated text, full JSON
    let text = stochvib(&["inspect", merged.to_str().unwrap()]);
    let line = text.lines().find(|l| l.contains("merged from")).unwrap();
    assert!(line.contains("… and 36 more"), "{line}");
    assert!(
        line.contains("shard-00-of-40.h5") && !line.contains("shard-39-of-40.h5"),
        "{line}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&stochvib(&["inspect", "--json", merged.to_str().unwrap()])).unwrap();
    let listed = json.to_string();
    for i in [0, 17, 39] {
        assert!(
            listed.contains(&format!("shard-{i:02}-of-40.h5")),
            "--json lacks shard {i}"
        );
    }

    // a damaged fingerprint: refused, naming the file; no output written
    let bad = &files[5];
    let stored = {
        let _g = spawn_lock();
        hdf5::File::open(bad)
            .unwrap()
            .attr("shared_crc32")
            .unwrap()
            .read_scalar::<u32>()
            .unwrap()
    };
    h5_root_attr_set_u32(bad, "shared_crc32", stored ^ 1);
    let out = dir.join("refused.h5");
    let err = merge(&out, &files).unwrap_err().to_string();
    assert!(
        err.contains(&bad.file_name().unwrap().to_string_lossy().to_string()),
        "{err}"
    );
    assert!(err.contains("analytic values differ"), "{err}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
