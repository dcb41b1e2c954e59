//! Bounded corruption of HDF5 run files: a fixed seed, 40 damaged copies of small run files
//! written by the library (statistics only; raw data; raw data with deflate:1; a road scenario on the
//! spectral route) and of the `.tmp` files their interrupted runs leave, through `stochvib inspect`,
//! `inspect --json`, `plot` and the resuming `simulate`.
//!
//! Asserted for every command (classification in `tests/fuzz/runs.rs`): no crash (signal), no panic, no
//! hang, a non-zero exit has an `error:` line naming the file, and an exit 0 prints the same statistics,
//! density estimates and pictures as the intact file (a resumed run: the same statistics as the
//! uninterrupted run, bit for bit). The reference outputs are the same commands on the intact files,
//! whose resumed statistics are first checked against the library's own uninterrupted run.
//!
//! The long campaign is `cargo run --release --features campaigns --example corrupt_runs -- --cases 1000`.

use crate::fuzz;

use fuzz::runs::{self, Config};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::time::Duration;

/// Fixed master seed of the bounded run.
const SEED: u64 = 16;
/// Cases: about 0.1 s each (2–3 short CLI runs).
const CASES: u64 = 40;
/// Time limit of one command (they take about 0.05 s on intact files).
const COMMAND_LIMIT: Duration = Duration::from_secs(30);

const CHILD_ENV: &str = "STOCHVIB_FUZZ_RUN_FILES_CHILD";

/// Child half of the set-up: runs a variant and aborts after `k` shards, leaving its `.tmp`. Without the
/// environment variable it does nothing.
#[test]
#[ignore = "child process of run_files_survive_corruption"]
fn fuzz_run_files_child() {
    let Ok(spec) = std::env::var(CHILD_ENV) else { return };
    let mut it = spec.splitn(3, '\n');
    let (v, k, p) = (it.next().unwrap(), it.next().unwrap(), it.next().unwrap());
    runs::child_abort(
        &crate::common::root(),
        v.parse().unwrap(),
        Path::new(p),
        k.parse().unwrap(),
    );
}

#[test]
fn run_files_survive_corruption() {
    let root = crate::common::root();
    let tmp = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let exe = std::env::current_exe().expect("own path");
    let cfg = Config {
        root,
        bin: PathBuf::from(crate::common::cli_bin()),
        work: crate::common::scratch_path("fuzz-run-files", "work"),
        findings_dir: Some(tmp.join("fuzz-findings")),
        cases: CASES,
        seed: SEED,
        limit: COMMAND_LIMIT,
        jobs: 1,
        child: Arc::new(move |v: usize, p: &Path, k: usize| {
            let mut c = Command::new(&exe);
            c.args([
                "--ignored",
                "--exact",
                "fuzz_run_files::fuzz_run_files_child",
                "--nocapture",
                "--test-threads=1",
            ])
            .env(CHILD_ENV, format!("{v}\n{k}\n{}", p.display()));
            c
        }),
        progress: false,
    };
    let s = runs::run(&cfg);
    let _ = std::fs::remove_dir_all(&cfg.work);
    assert_eq!(s.cases, CASES);
    assert!(
        s.hard().is_empty(),
        "broken invariants (reproducers in {}):\n{}",
        tmp.join("fuzz-findings/runs").display(),
        s.render()
    );
}
