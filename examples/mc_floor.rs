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

use common::{exact_floor, McExact, McSpectral, McStreamed, OneFftFloor, StreamedFloor};
use std::hint::black_box;
use std::time::Instant;
use stochvib::simulate::{LANES, LANE_DRAW_STEPS};

/// CPU time of this process (user + sys), s.
fn cpu_seconds() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: a valid pointer to a timespec; CLOCK_PROCESS_CPUTIME_ID exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// One job: its name and a closure doing it once (returning a check value).
type Job<'a> = (&'static str, Box<dyn FnMut() -> f64 + 'a>);

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
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let pipe = McSpectral::new(n);
    let exact = McExact::new(n);
    let mut streamed = McStreamed::new(n);
    let mut streamed_floor = StreamedFloor::new(&streamed);
    let (f, hop, taps) = (streamed.fir.fft_len(), streamed.fir.hop(), streamed.fir.taps());

    let mut floor = OneFftFloor::new(n);
    // the exact route's floor draws as the route does: LANE_DRAW_STEPS steps' normals of every lane at a time
    let nz = exact.gm.n_states();
    let mut exact_normals = vec![[0.0; LANES]; LANE_DRAW_STEPS * nz];

    let mut jobs: Vec<Job> = vec![
        (
            "one FFT route",
            Box::new(|| pool.install(|| pipe.batch(r, true)).var.estimate),
        ),
        (
            "one FFT floor: N + 2 normals + 1 inverse real FFT",
            Box::new(|| floor.run(r)),
        ),
        ("exact route", Box::new(|| pool.install(|| exact.batch(r)).var.estimate)),
        (
            "exact floor: its normals (8 streams side by side)",
            Box::new(|| exact_floor(&mut exact_normals, nz * n, r)),
        ),
        (
            "streamed spectral route (FIR overlap-save + Σy, Σy²)",
            Box::new(|| streamed.run(r)),
        ),
        (
            "streamed floor: its normals + forward and inverse real FFT per segment",
            Box::new(|| streamed_floor.run(r)),
        ),
    ];
    let mut best = vec![(f64::INFINITY, f64::INFINITY, 0.0); jobs.len()];
    for _ in 0..rounds {
        for (b, (_, job)) in best.iter_mut().zip(&mut jobs) {
            let (c0, w0) = (cpu_seconds(), Instant::now());
            let check = black_box(job());
            let (c, w) = (cpu_seconds() - c0, w0.elapsed().as_secs_f64());
            *b = (b.0.min(c), b.1.min(w), check);
        }
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!("{r} realizations x {n} samples, 1 thread, best of {rounds} alternating rounds; FIR: {taps} taps, FFT {f}, hop {hop}; load {}", load.split(' ').next().unwrap_or("?"));
    println!();
    println!("| job | CPU | wall | route / floor (CPU) | route / floor (wall) |");
    println!("| --- | --- | --- | --- | --- |");
    for (k, ((name, _), b)) in jobs.iter().zip(&best).enumerate() {
        let ratio = if k % 2 == 0 {
            let fl = best[k + 1];
            format!("{:.3}x | {:.3}x", b.0 / fl.0, b.1 / fl.1)
        } else {
            "floor | floor".to_string()
        };
        println!("| {name} | {:.1} ms | {:.1} ms | {ratio} |", b.0 * 1e3, b.1 * 1e3);
    }
}
