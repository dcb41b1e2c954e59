//! The Rust side of the Python call-overhead benchmark (`python/bench/overhead.py` runs this and times the
//! same calls through the Python package with `timeit`, in one run): a 10⁵-point density and a 10⁵-point
//! frequency response, exactly as the binding computes them, without Python.
//!
//! * `density/<spectrum>/reuse`: `Spectrum::density_into` into a reused buffer (Python: `density(w, out=buf)`).
//! * `density/<spectrum>/alloc`: a fresh zeroed `Vec` of 10⁵ values, then `density_into` (Python: `density(w)`,
//!   which returns a new array).
//! * `frequency_response/quarter_car/alloc`: `FrequencyResponse::response` at every ω, copied into a fresh
//!   `Vec<Complex<f64>>` laid out (output, input, ω) (Python: `frequency_response(w)`).
//!
//! Grid: 10⁵ points linearly spaced on [0.01, 100] rad/s.
//!
//! Flat sampling: every sample runs the same number of iterations, about 5 ms of work (one iteration of
//! the frequency response), as the `timeit` batches of the Python side do. With criterion's default linear
//! sampling the later samples last tens of milliseconds and, on a shared machine, none of them is
//! undisturbed: its minimum came out 1.4–2.5× the `timeit` minimum of the same call (measured at load
//! average 8 on 2 cores), which is the machine, not the binding.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use nalgebra::Complex;
use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;
use stochvib::prelude::*;
use stochvib::system::FrequencyResponse;

/// Number of grid points.
const N: usize = 100_000;

fn grid() -> Vec<f64> {
    (0..N)
        .map(|i| 0.01 + (100.0 - 0.01) * i as f64 / (N - 1) as f64)
        .collect()
}

fn spectra() -> Vec<(&'static str, Arc<dyn Spectrum>)> {
    vec![
        (
            "exponential",
            Arc::new(Exponential::new(2.0, 1.5, Domain::Temporal).unwrap()),
        ),
        (
            "gauss_cosine",
            Arc::new(
                GaussCosineParameters {
                    variance: 2.0,
                    alpha: 1.5,
                    beta: 6.0,
                    domain: Domain::Temporal,
                }
                .build()
                .unwrap(),
            ),
        ),
    ]
}

/// The quarter car of `data/quarter-car-model.toml` (300 kg, 40 kg, 20 kN/m, 1.5 kN s/m, 200 kN/m):
/// 4 outputs × 1 input.
pub fn quarter_car() -> Mdof {
    QuarterCar {
        sprung_mass: 300.0,
        unsprung_mass: 40.0,
        suspension_stiffness: 20e3,
        suspension_damping: 1.5e3,
        tyre_stiffness: 200e3,
        tyre_damping: 0.0,
    }
    .build()
    .unwrap()
    .system()
    .unwrap()
}

fn bench(c: &mut Criterion) {
    let w = grid();
    let mut g = c.benchmark_group("density");
    g.sampling_mode(SamplingMode::Flat);
    g.sample_size(200);
    g.measurement_time(Duration::from_secs(1)); // 200 samples of about 5 ms
    for (name, s) in spectra() {
        let mut out = vec![0.0; N];
        g.bench_function(format!("{name}/reuse"), |b| {
            b.iter(|| {
                s.density_into(black_box(&w), &mut out);
                black_box(out[N / 2])
            })
        });
        g.bench_function(format!("{name}/alloc"), |b| {
            b.iter(|| {
                let mut out = vec![0.0; N];
                s.density_into(black_box(&w), &mut out);
                out
            })
        });
    }
    g.finish();
    let sys = quarter_car();
    let (p, m) = (sys.outputs().len(), sys.n_inputs());
    let mut g = c.benchmark_group("frequency_response");
    g.sampling_mode(SamplingMode::Flat);
    g.sample_size(20); // one iteration (≥ 100 ms) per sample
    g.measurement_time(Duration::from_secs(2));
    g.bench_function("quarter_car/alloc", |b| {
        b.iter(|| {
            let mut out = vec![Complex::new(0.0, 0.0); p * m * N];
            for (k, &x) in black_box(&w).iter().enumerate() {
                let h = sys.response(x);
                for i in 0..p {
                    for j in 0..m {
                        out[(i * m + j) * N + k] = h[(i, j)];
                    }
                }
            }
            out
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
