//! rustfft chooses its code at run time: AVX with FMA, else SSE4.1, else scalar (`docs/cluster.md`, "Which
//! numbers are identical on which machines"). This forces every path the CPU has on the same inputs, at sizes
//! the simulation routes use (powers of two, even sizes with large prime factors), and checks what that page
//! says: the paths agree to rounding ([`tolerance::FFT_PATHS`], normwise), and they do not agree to the bit,
//! which is why the numbers computed through an FFT depend on the CPU. The library's own FFTs go through
//! `FftPlanner::new()` (via realfft), which takes the first path of that list the CPU runs.

use crate::common::tolerance;
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftDirection, FftPlannerAvx, FftPlannerScalar, FftPlannerSse};
use std::sync::Arc;

/// Powers of two, and even sizes N = round(T/Δt) of the spectral routes with large prime factors
/// (1112 = 8·139, 5000 = 2³·5⁴, 65 538 = 2·3·10 923).
const SIZES: [usize; 7] = [512, 1024, 1112, 4096, 5000, 16_384, 65_538];

/// A deterministic test signal with no structure an FFT could compute exactly.
fn signal(n: usize) -> Vec<Complex64> {
    (0..n)
        .map(|k| {
            let t = k as f64;
            Complex64::new((0.37 * t).sin() + (1e-3 * t * t).cos(), (0.11 * t).cos() - 0.5)
        })
        .collect()
}

fn transform(plan: &Arc<dyn Fft<f64>>, x: &[Complex64]) -> Vec<Complex64> {
    let mut y = x.to_vec();
    plan.process(&mut y);
    y
}

/// The paths this CPU runs, by name (scalar always).
fn paths(n: usize) -> Vec<(&'static str, Arc<dyn Fft<f64>>)> {
    let mut out = vec![("scalar", FftPlannerScalar::new().plan_fft(n, FftDirection::Inverse))];
    if let Ok(mut p) = FftPlannerSse::new() {
        out.push(("sse4.1", p.plan_fft(n, FftDirection::Inverse)));
    }
    if let Ok(mut p) = FftPlannerAvx::new() {
        out.push(("avx+fma", p.plan_fft(n, FftDirection::Inverse)));
    }
    out
}

fn norm(v: impl Iterator<Item = Complex64>) -> f64 {
    v.map(|c| c.norm_sqr()).sum::<f64>().sqrt()
}

#[test]
fn every_fft_path_agrees_with_the_scalar_one_to_rounding_but_not_to_the_bit() {
    for n in SIZES {
        let x = signal(n);
        let results: Vec<(&str, Vec<Complex64>)> = paths(n).iter().map(|(name, p)| (*name, transform(p, &x))).collect();
        let (_, reference) = &results[0];
        let scale = norm(reference.iter().copied());
        for (name, y) in &results[1..] {
            let diff = norm(y.iter().zip(reference).map(|(a, b)| a - b));
            assert!(
                diff <= tolerance::FFT_PATHS * scale,
                "n = {n}: {name} differs from scalar by {:.3e} (relative, normwise)",
                diff / scale
            );
            let same_bits = y
                .iter()
                .zip(reference)
                .all(|(a, b)| a.re.to_bits() == b.re.to_bits() && a.im.to_bits() == b.im.to_bits());
            assert!(
                !same_bits,
                "n = {n}: {name} gives the scalar path's bits: docs/cluster.md says the paths differ in the last bits"
            );
        }
        if results.len() == 1 {
            eprintln!("fft_paths: this CPU runs only rustfft's scalar path (n = {n}): nothing to compare");
        }
    }
}
