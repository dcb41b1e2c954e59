//! Monte Carlo throughput (`cargo bench --bench montecarlo`), in samples per second: generation per sample
//! for each generator, response stepping, and a full batch with statistics.
//!
//! * Generators (one realization of N = 2¹⁶ samples per iteration, from `stream(seed, i)`): spectral
//!   representation of K(τ) = e^{−3|τ|} with Rayleigh amplitudes (the default) and phase-only; the exact
//!   shaping-filter stream (AR(1)) of the same process; the road (8.69) at 10 m/s felt by 2 wheels 2.5 m
//!   apart (Δt = 5 ms, Δx = 5 cm), spectral and shaping-filter profiles (elements = N·wheels).
//! * Response stepping: the SDOF of the pipeline (ω = 10 rad/s, ζ = 0.05) discretised by the exact
//!   first-order hold, `SampledSystem::respond` over N input samples; the SDOF augmented with the input's
//!   shaping filter (3 states, Van Loan), `GaussMarkov::advance` over N samples (noise drawn inside).
//! * Full batch: `run_batch` of 64 realizations × 2¹⁴ samples, generate → respond → statistics
//!   (Student-t intervals of mean and σ²), on the global rayon pool: spectral route with time stepping
//!   (`respond`, one warm-up period), spectral route in one FFT (`generate_filtered` with
//!   `SampledSystem::grid_response`, the same periodic steady state), exact route.
//!
//! `benches/common/mod.rs` holds the model and the pipeline (`McSpectral`, `McExact`), shared with
//! `examples/compare_rust.rs`.

mod common;

use common::*;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use stochvib::models::scraper::book_road_8_69;
use stochvib::simulate::{
    shaping_simulator, stream, Amplitudes, RoadTrack, RoadTrackGrid, SampledSystem, SpectralGenerator,
};

const N: usize = 1 << 16;

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

fn generators(c: &mut Criterion) {
    let input = mc_input();
    let mut g = c.benchmark_group("mc_generate");
    g.throughput(Throughput::Elements(N as u64));
    let mut out = vec![0.0; N];
    for (name, amp) in [
        ("spectral_rayleigh", Amplitudes::Rayleigh),
        ("spectral_phase_only", Amplitudes::PhaseOnly),
    ] {
        let generator = SpectralGenerator::new(input.as_ref(), MC_DT, N, amp).unwrap();
        let mut sc = generator.scratch();
        let mut i = 0;
        g.bench_function(name, |b| {
            b.iter(|| {
                i += 1;
                generator.generate(&mut stream(MC_SEED, i), &mut sc, &mut out).unwrap();
                black_box(out[N / 2])
            })
        });
    }
    let gm = shaping_simulator(input.as_ref(), MC_DT).unwrap();
    let mut i = 0;
    g.bench_function("shaping_stream_ar1", |b| {
        b.iter(|| {
            i += 1;
            gm.stream(stream(MC_SEED, i)).fill(&mut out);
            black_box(out[N / 2])
        })
    });
    // the road (8.69) at 10 m/s, two wheels 2.5 m apart
    let spatial = book_road_8_69();
    let dt = 0.005;
    let grid = RoadTrackGrid {
        speed: SPEED,
        dt,
        n: N,
        offsets: &[0.0, 2.5],
    };
    let tracks = [
        (
            "road_spectral_2_wheels",
            RoadTrack::spectral(spatial.as_ref(), grid, Amplitudes::Rayleigh).unwrap(),
        ),
        (
            "road_shaping_2_wheels",
            RoadTrack::shaping(spatial.as_ref(), grid).unwrap(),
        ),
    ];
    g.throughput(Throughput::Elements(2 * N as u64));
    let mut u = vec![0.0; 2 * N];
    for (name, track) in &tracks {
        let mut sc = track.scratch();
        let mut i = 0;
        g.bench_function(*name, |b| {
            b.iter(|| {
                i += 1;
                track.generate(&mut stream(MC_SEED, i), &mut sc, &mut u).unwrap();
                black_box(u[N])
            })
        });
    }
    g.finish();
}

fn response(c: &mut Criterion) {
    let (ss, exc) = mc_sdof();
    let sys = SampledSystem::new(&ss, MC_DT).unwrap();
    let generator = SpectralGenerator::new(mc_input().as_ref(), MC_DT, N, Amplitudes::Rayleigh).unwrap();
    let mut u = vec![0.0; N];
    generator
        .generate(&mut stream(MC_SEED, 0), &mut generator.scratch(), &mut u)
        .unwrap();
    let mut y = vec![0.0; N];
    let mut x = vec![0.0; 2];
    let mut g = c.benchmark_group("mc_respond");
    g.throughput(Throughput::Elements(N as u64));
    g.bench_function("sdof_foh_respond", |b| {
        b.iter(|| {
            sys.respond(black_box(&u), &mut x, &mut y).unwrap();
            black_box(y[N - 1])
        })
    });
    let gm = stochvib::simulate::augmented_response(&ss, &exc, &[0], MC_DT).unwrap();
    let mut z = vec![0.0; gm.n_states()];
    let mut rng = stream(MC_SEED, 1);
    gm.initial_state(&mut rng, &mut z);
    let gain = sys.grid_response(N, 0, 0).unwrap();
    let mut sc = generator.scratch();
    let mut i = 0;
    g.bench_function("sdof_generate_filtered_one_fft", |b| {
        b.iter(|| {
            i += 1;
            generator
                .generate_filtered(&mut stream(MC_SEED, i), &mut sc, &gain, &mut y)
                .unwrap();
            black_box(y[N - 1])
        })
    });
    g.bench_function("augmented_gauss_markov_3_states", |b| {
        b.iter(|| {
            gm.advance(&mut z, &mut rng, &mut y);
            black_box(y[N - 1])
        })
    });
    g.finish();
}

fn batch(c: &mut Criterion) {
    const R: usize = 64;
    const NB: usize = 1 << 14;
    let spectral = McSpectral::new(NB);
    let exact = McExact::new(NB);
    let mut g = c.benchmark_group("mc_batch_64x2^14");
    g.throughput(Throughput::Elements((R * NB) as u64));
    g.bench_function("spectral_generate_respond_stats", |b| {
        b.iter(|| spectral.batch(black_box(R), false).var.estimate)
    });
    g.bench_function("spectral_generate_filtered_fft_stats", |b| {
        b.iter(|| spectral.batch(black_box(R), true).var.estimate)
    });
    g.bench_function("exact_stream_stats", |b| {
        b.iter(|| exact.batch(black_box(R)).var.estimate)
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = generators, response, batch
}
criterion_main!(benches);
