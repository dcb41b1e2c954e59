//! Structured fuzzing of the input files (scenario, reference and spectrum files) through the library's
//! entry points and the CLI; see `tests/fuzz/inputs.rs` for the invariants.
//!
//! ```text
//! cargo build --release                      # the CLI binary the harness also runs
//! cargo run --release --features campaigns --example fuzz -- --cases 20000 [--seed S] [--cli-every K] [--jobs J]
//!     [--timeout-ms T] [--findings DIR] [--no-minimize] [--no-special] [--bin PATH] [--budget-s S]
//!     [--totals FILE.json]
//! ```
//!
//! Prints a summary (cases, outcomes, findings by class and by signature) and writes one minimised
//! reproducer per signature under `DIR/inputs/` (default `target/fuzz-findings/inputs/`, with
//! `SUMMARY.txt` and `REPRODUCERS.md`). Exit status 1 if any asserted invariant was broken.

#[path = "../tests/fuzz/mod.rs"]
mod fuzz;

use fuzz::input_campaign::{self, Campaign, WorkerConfig};
use std::path::PathBuf;
use std::process::Command;
use std::sync::Arc;
use std::time::Duration;

fn usage() -> ! {
    eprintln!(
        "usage: fuzz --cases N [--seed S] [--cli-every K] [--jobs J] [--timeout-ms T] [--findings DIR] \
         [--no-minimize] [--no-special] [--bin PATH] [--budget-s S] [--totals FILE.json]"
    );
    std::process::exit(2)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--worker") {
        let cfg: WorkerConfig = serde_json::from_str(args.get(1).unwrap_or_else(|| usage())).expect("worker config");
        input_campaign::worker_main(&cfg);
    }
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let exe = std::env::current_exe().expect("own path");
    let mut cases = None;
    let mut seed = 1u64;
    let mut cli_every = 10u64;
    let mut jobs = 1u64;
    let mut timeout_ms = 2000u64;
    let mut findings = root.join("target/fuzz-findings");
    let mut minimize = true;
    let mut special = true;
    let mut budget = None;
    let mut totals: Option<PathBuf> = None;
    let mut bin = exe
        .parent()
        .and_then(|d| d.parent())
        .map(|d| d.join("stochvib"))
        .unwrap_or_default();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        let mut val = || it.next().unwrap_or_else(|| usage());
        match a.as_str() {
            "--cases" => cases = Some(val().parse().unwrap_or_else(|_| usage())),
            "--seed" => seed = val().parse().unwrap_or_else(|_| usage()),
            "--cli-every" => cli_every = val().parse().unwrap_or_else(|_| usage()),
            "--jobs" => jobs = val().parse().unwrap_or_else(|_| usage()),
            "--timeout-ms" => timeout_ms = val().parse().unwrap_or_else(|_| usage()),
            "--findings" => findings = PathBuf::from(val()),
            "--bin" => bin = PathBuf::from(val()),
            "--no-minimize" => minimize = false,
            "--no-special" => special = false,
            "--budget-s" => budget = Some(Duration::from_secs(val().parse().unwrap_or_else(|_| usage()))),
            "--totals" => totals = Some(PathBuf::from(val())),
            _ => usage(),
        }
    }
    let Some(cases) = cases else { usage() };
    if !bin.is_file() {
        eprintln!(
            "no CLI binary at {} (run `cargo build --release` first, or pass --bin)",
            bin.display()
        );
        std::process::exit(2);
    }
    let worker_exe = exe.clone();
    let c = Campaign {
        root: root.clone(),
        seed,
        cases,
        jobs,
        cli_every,
        limit: Duration::from_millis(timeout_ms),
        cli_limit: Duration::from_millis(timeout_ms * 5),
        special_limit: Duration::from_millis(timeout_ms),
        scratch: root.join("target/fuzz-scratch/inputs"),
        findings_dir: Some(findings.clone()),
        minimize,
        special,
        bin,
        worker: Arc::new(move |cfg: &WorkerConfig| {
            let mut cmd = Command::new(&worker_exe);
            cmd.arg("--worker").arg(serde_json::to_string(cfg).unwrap());
            cmd
        }),
        progress: true,
        budget,
    };
    let s = input_campaign::run(&c);
    println!("{}", s.render());
    if let Some(t) = totals {
        let json = s.totals_json();
        std::fs::write(&t, serde_json::to_string_pretty(&json).unwrap()).expect("write the totals");
    }
    println!("reproducers: {}", findings.join("inputs").display());
    if !s.hard().is_empty() {
        std::process::exit(1);
    }
}
