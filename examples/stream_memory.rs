//! Streams a 10⁸-sample realization of a type-1 (rational) input through an SDOF oscillator to running
//! statistics in constant memory, and reports peak resident memory and throughput.
//!
//! The input filter and the oscillator form one augmented Gauss–Markov system discretised exactly (Van
//! Loan); samples are produced in chunks of 4096 and folded into Welford moments, so memory does not grow
//! with the record length.
//!
//! Run: `cargo run --release --example stream_memory [samples]` (default 10⁸; `1e9` for the 10⁹-sample check:
//! a 10⁹-sample realization with peak memory < 100 MB).

use std::sync::Arc;
use std::time::Instant;
use stochvib::estimate::RunningMoments;
use stochvib::response::{variance_lyapunov, Excitation};
use stochvib::simulate::{augmented_response, stream};
use stochvib::spectrum::{Domain, Exponential};
use stochvib::system::StateSpace;

fn peak_rss_kib() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() -> stochvib::Result<()> {
    let total: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse::<f64>().ok())
        .map_or(100_000_000, |v| v as u64);
    let ss = StateSpace::oscillator(10.0, 0.05)?;
    let exc = Excitation::single(Arc::new(Exponential::new(1.0, 3.0, Domain::Temporal)?), 0.0)?;
    let dt = 0.01;
    let gm = augmented_response(&ss, &exc, &[0], dt)?;
    let analytic = variance_lyapunov(&ss, &exc, 0)?.variance;
    let rss0 = peak_rss_kib();
    let t0 = Instant::now();
    let mut s = gm.stream(stream(2024, 0));
    let mut buf = vec![0.0; 4096];
    let mut m = RunningMoments::default();
    let mut left = total;
    while left > 0 {
        let k = left.min(buf.len() as u64) as usize;
        s.fill(&mut buf[..k]);
        m.extend(&buf[..k]);
        left -= k as u64;
    }
    let secs = t0.elapsed().as_secs_f64();
    println!("samples            {}", m.count());
    println!("time-average mean  {:.6e}  (analytic 0)", m.mean());
    println!(
        "time-average var   {:.6e}  (Lyapunov {:.6e}, ratio {:.5})",
        m.variance(),
        analytic,
        m.variance() / analytic
    );
    println!(
        "elapsed            {secs:.2} s  ({:.1} Msamples/s)",
        m.count() as f64 / secs / 1e6
    );
    println!(
        "peak RSS (VmHWM)   {} KiB before streaming, {} KiB after",
        rss0.map_or("?".into(), |v| v.to_string()),
        peak_rss_kib().map_or("?".into(), |v| v.to_string())
    );
    println!(
        "record size if held in memory: {:.0} MiB",
        total as f64 * 8.0 / 1048576.0
    );
    if let Some(peak) = peak_rss_kib() {
        let mb = peak as f64 * 1024.0 / 1e6;
        println!(
            "peak RSS {mb:.1} MB < 100 MB: {}",
            if mb < 100.0 { "yes" } else { "NO" }
        );
    }
    Ok(())
}
