//! Corruption of HDF5 run files and of interrupted runs' `.tmp` files; see `tests/fuzz/runs.rs` for the
//! corruptions and the classification.
//!
//! ```text
//! cargo build --release                      # the CLI binary the harness runs
//! cargo run --release --features campaigns --example corrupt_runs -- --cases 1000 [--seed S] [--jobs J] [--timeout-ms T]
//!     [--findings DIR] [--bin PATH]
//! ```
//!
//! Prints a summary (command outcomes by class, findings by signature) and writes one reproducer per
//! signature (the damaged file and a `CASE.txt` with the base run, the offsets and bits) under
//! `DIR/runs/` (default `target/fuzz-findings/runs/`). Exit status 1 if any asserted class occurred.

#[path = "../tests/fuzz/mod.rs"]
mod fuzz;

use fuzz::runs::{self, Config};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::time::Duration;

fn usage() -> ! {
    eprintln!("usage: corrupt_runs --cases N [--seed S] [--jobs J] [--timeout-ms T] [--findings DIR] [--bin PATH]");
    std::process::exit(2)
}

fn main() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--child-abort") {
        let (Some(v), Some(p), Some(k)) = (args.get(1), args.get(2), args.get(3)) else {
            usage()
        };
        runs::child_abort(&root, v.parse().unwrap(), Path::new(p), k.parse().unwrap());
    }
    let exe = std::env::current_exe().expect("own path");
    let mut cases = None;
    let mut seed = 1u64;
    let mut jobs = 1u64;
    let mut timeout_ms = 20_000u64;
    let mut findings = root.join("target/fuzz-findings");
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
            "--jobs" => jobs = val().parse().unwrap_or_else(|_| usage()),
            "--timeout-ms" => timeout_ms = val().parse().unwrap_or_else(|_| usage()),
            "--findings" => findings = PathBuf::from(val()),
            "--bin" => bin = PathBuf::from(val()),
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
    let child_exe = exe.clone();
    let cfg = Config {
        root: root.clone(),
        bin,
        work: root.join("target/fuzz-scratch/runs"),
        findings_dir: Some(findings.clone()),
        cases,
        seed,
        limit: Duration::from_millis(timeout_ms),
        jobs,
        child: Arc::new(move |v: usize, p: &Path, k: usize| {
            let mut c = Command::new(&child_exe);
            c.arg("--child-abort").arg(v.to_string()).arg(p).arg(k.to_string());
            c
        }),
        progress: true,
    };
    let s = runs::run(&cfg);
    println!("{}", s.render());
    println!("reproducers: {}", findings.join("runs").display());
    if !s.hard().is_empty() {
        std::process::exit(1);
    }
}
