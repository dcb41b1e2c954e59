//! The seeded signals and the density of the fatigue benchmarks, shared by `benches/fatigue.rs` and
//! `examples/fatigue_compare.rs` (included with `#[path]`), so both time exactly the same inputs.
#![allow(dead_code)] // each includer uses a subset

use std::f64::consts::PI;
use stochvib::simulate::{fill_standard_normal, stream};

/// Seed of the benchmark signals.
pub const SEED: u64 = 18;

/// Samples in the large rainflow benchmark.
pub const N_RAINFLOW: usize = 100_000_000;

/// A resonant AR(2) record: x_n = 2r cos θ x_{n−1} − r² x_{n−2} + e_n with r = 0.98, θ = 2π/20 (a
/// narrow-ish band process with ≈ 20 samples per cycle, as an oversampled stress record), e_n standard
/// normal from the crate's seeded stream `(SEED, 0)`.
pub fn resonant_signal(n: usize) -> Vec<f64> {
    let mut x = vec![0.0; n];
    fill_standard_normal(&mut stream(SEED, 0), &mut x);
    let (r, th) = (0.98f64, 2.0 * PI / 20.0);
    let (a1, a2) = (2.0 * r * th.cos(), -r * r);
    let (mut y1, mut y2) = (0.0, 0.0);
    for v in x.iter_mut() {
        let y = a1 * y1 + a2 * y2 + *v;
        y2 = y1;
        y1 = y;
        *v = y;
    }
    x
}

/// Plain standard normal white noise from stream `(SEED, 1)` (the worst case: two thirds of the samples are
/// turning points).
pub fn white_signal(n: usize) -> Vec<f64> {
    let mut x = vec![0.0; n];
    fill_standard_normal(&mut stream(SEED, 1), &mut x);
    x
}

/// Natural frequency (Hz), damping ratio and band (Hz) of the single-mode stress density of the Dirlik
/// benchmark.
pub const SDOF_FN: f64 = 50.0;
/// Damping ratio of the single-mode density.
pub const SDOF_ZETA: f64 = 0.05;
/// Upper band edge (Hz); the band starts at 0.
pub const SDOF_F_MAX: f64 = 500.0;

/// One-sided stress density in Hz (MPa²/Hz) of a lightly damped mode driven by a white base input
/// (|H|² shape), plus a flat 1 % floor: G(f) = 10 / ((1 − (f/fₙ)²)² + (2ζf/fₙ)²) + 0.1·[0 ≤ f ≤ 500].
pub fn sdof_density(f: f64) -> f64 {
    let u = f / SDOF_FN;
    10.0 / ((1.0 - u * u).powi(2) + (2.0 * SDOF_ZETA * u).powi(2)) + 0.1
}

/// S–N curve of the Dirlik benchmark: N·S_a^k = C with k = 5, C = 1e16 (MPa, amplitude).
pub const SN_K: f64 = 5.0;
/// Its intercept.
pub const SN_C: f64 = 1e16;
