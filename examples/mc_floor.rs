//! Monte Carlo routes against their floors, in one process, in alternating rounds (a change of load hits
//! both sides of a ratio alike): the one-FFT route, whose floor is, per realization, its N + 2 normals and one
//! inverse real FFT of length N; the exact route (8 realizations in lockstep), whose floor is its normals
//! (one per state and step, 8 streams drawn side by side as the route draws them); the streamed spectral
//! route (FIR overlap-save, `simulate::FirSynthesis`), whose floor is its normals and its forward and inverse
//! real FFT per segment. One thread; process CPU time (user + sys) and wall time of every job, the smallest
//! of `--rounds` rounds; a markdown table on stdout.
//!
//! Run: `cargo run --release --features campaigns --example mc_floor [-- --realizations R --samples N --rounds K]`
//! (defaults 200, 2¹⁶, 5; the model is the SDOF of `benches/common`, as `compare_rust`'s Monte Carlo jobs).

#[path = "../benches/common/mod.rs"]
mod common;

use common::{floor_rounds, McStreamed};

fn arg(args: &[String], name: &str, default: usize) -> usize {
    args.windows(2)
        .find(|w| w[0] == name)
        .and_then(|w| w[1].parse().ok())
        .unwrap_or(default)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (r, n, rounds) = (
        arg(&args, "--realizations", 200),
        arg(&args, "--samples", 1 << 16),
        arg(&args, "--rounds", 5),
    );
    let fir = McStreamed::new(n).fir;
    let (f, hop, taps) = (fir.fft_len(), fir.hop(), fir.taps());
    let best = floor_rounds(r, n, rounds);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("{r} realizations x {n} samples, 1 thread, best of {rounds} alternating rounds; FIR: {taps} taps, FFT {f}, hop {hop}; load {}", load.split(' ').next().unwrap_or("?"));
    println!();
    println!("| job | CPU | wall | route / floor (CPU) | route / floor (wall) |");
    println!("| --- | --- | --- | --- | --- |");
    for (k, b) in best.iter().enumerate() {
        let ratio = if k % 2 == 0 {
            let fl = &best[k + 1];
            format!("{:.3}x | {:.3}x", b.cpu_s / fl.cpu_s, b.wall_s / fl.wall_s)
        } else {
            "floor | floor".to_string()
        };
        println!(
            "| {} | {:.1} ms | {:.1} ms | {ratio} |",
            b.name,
            b.cpu_s * 1e3,
            b.wall_s * 1e3
        );
    }
}
