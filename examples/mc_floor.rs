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

use common::{exact_floor, McExact, McSpectral, OneFftFloor, MC_SEED};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use std::hint::black_box;
use std::time::Instant;
use stochvib::simulate::{fill_standard_normal, stream, FirSynthesis, TimeSums, LANES, LANE_DRAW_STEPS};

/// CPU time of this process (user + sys), s.
fn cpu_seconds() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: a valid pointer to a timespec; CLOCK_PROCESS_CPUTIME_ID exists on Linux.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// One job: its name and a closure doing it once (returning a check value).
type Job<'a> = (&'static str, Box<dyn FnMut() -> f64 + 'a>);

/// The SDOF's impulse response h(kΔt) = e^{−ζωt} sin(ω_d t)/ω_d (ω = 10 rad/s, ζ = 0.05, Δt = 0.01 s) up
/// to where its envelope falls below 10⁻⁴ of its start: the streamed route's kernel.
fn sdof_kernel() -> Vec<f64> {
    let (w, z, dt) = (10.0f64, 0.05f64, 0.01f64);
    let wd = w * (1.0 - z * z).sqrt();
    let taps = ((1e4f64).ln() / (z * w) / dt).ceil() as usize;
    (0..taps)
        .map(|k| {
            let t = k as f64 * dt;
            (-z * w * t).exp() * (wd * t).sin() / wd * dt.sqrt()
        })
        .collect()
}

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
    let fir = FirSynthesis::from_taps(vec![vec![sdof_kernel()]]).unwrap();
    let (f, hop, taps) = (fir.fft_len(), fir.hop(), fir.taps());

    let mut floor = OneFftFloor::new(n);
    // the exact route's floor draws as the route does: LANE_DRAW_STEPS steps' normals of every lane at a time
    let nz = exact.gm.n_states();
    let mut exact_normals = vec![[0.0; LANES]; LANE_DRAW_STEPS * nz];
    let mut planner = RealFftPlanner::<f64>::new();
    let (fwd, inv) = (planner.plan_fft_forward(f), planner.plan_fft_inverse(f));
    let (mut buf, mut spec, mut back) = (fwd.make_input_vec(), fwd.make_output_vec(), inv.make_output_vec());
    let mut fscr = vec![Complex::new(0.0, 0.0); fwd.get_scratch_len().max(inv.get_scratch_len())];
    let mut fs = fir.scratch();
    let segments = n.div_ceil(hop);

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
            Box::new(|| {
                let mut acc = 0.0;
                for i in 0..r as u64 {
                    let mut rng = stream(MC_SEED, i);
                    fir.start(&mut rng, &mut fs);
                    let mut sums = TimeSums::new();
                    for _ in 0..segments {
                        fir.next_segment(&mut rng, &mut fs).unwrap();
                        sums.push(fir.output(&fs, 0));
                    }
                    let (s1, s2) = sums.totals();
                    acc += s2 - s1 * s1 / (segments * hop) as f64;
                }
                acc
            }),
        ),
        (
            "streamed floor: its normals + forward and inverse real FFT per segment",
            Box::new(|| {
                let mut acc = 0.0;
                for i in 0..r as u64 {
                    let mut rng = stream(MC_SEED, i);
                    fill_standard_normal(&mut rng, &mut buf[..taps - 1]);
                    for _ in 0..segments {
                        fill_standard_normal(&mut rng, &mut buf[taps - 1..]);
                        fwd.process_with_scratch(&mut buf, &mut spec, &mut fscr).unwrap();
                        spec[0].im = 0.0;
                        spec[f / 2].im = 0.0;
                        inv.process_with_scratch(&mut spec, &mut back, &mut fscr).unwrap();
                        acc += back[taps];
                    }
                }
                acc
            }),
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
