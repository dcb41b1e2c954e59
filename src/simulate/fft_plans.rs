//! The real FFT plans of the Monte Carlo routes, made in this crate.
//!
//! rustfft and realfft are generic: their butterflies are compiled into every crate that makes a plan (in a
//! release build each crate carries its own copy). A plan made here runs the machine code the spectral
//! routes run ([`SpectralGenerator`](super::SpectralGenerator), the one-FFT engine,
//! [`FirSynthesis`](super::FirSynthesis)); a plan made in another crate runs another copy, placed elsewhere
//! in the binary. The benchmarks' floors ("the same normals and the same real FFT alone",
//! `benches/RESULTS.md`) take their plans from here, so that a route and its floor share one copy and one
//! placement: with two copies in `examples/compare_rust` the one-FFT route (the library's copy) took
//! 66.6–66.9 ms against its floor's 56.8–57.2 ms (the benchmark crate's copy), 1.17×, and with one copy
//! 60.3–60.6 ms against 58.1–58.5 ms, 1.04× — the same library code in both builds (2-core AMD EPYC VM,
//! 200 × 2¹⁶ samples, alternated processes).

use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use std::sync::Arc;

/// The inverse real FFT of length `n` (N/2 + 1 complex bins in, N real samples out, unnormalised:
/// x_k = Σ_j c_j e^{+2πijk/N} over the full Hermitian spectrum), as the spectral routes plan it.
///
/// # Examples
/// ```
/// use realfft::num_complex::Complex;
/// let plan = stochvib::simulate::fft_plans::inverse_real_fft(8);
/// let mut bins = vec![Complex::new(0.0, 0.0); 5];
/// bins[0] = Complex::new(1.0, 0.0);
/// let mut x = vec![0.0; 8];
/// plan.process(&mut bins, &mut x).unwrap();
/// assert!(x.iter().all(|v| (v - 1.0).abs() < 1e-15));
/// ```
pub fn inverse_real_fft(n: usize) -> Arc<dyn ComplexToReal<f64>> {
    RealFftPlanner::<f64>::new().plan_fft_inverse(n)
}

/// The forward and the inverse real FFT of length `n` from one planner (their twiddles shared), as the
/// streamed route plans its overlap-save pair.
pub fn real_fft_pair(n: usize) -> (Arc<dyn RealToComplex<f64>>, Arc<dyn ComplexToReal<f64>>) {
    let mut planner = RealFftPlanner::<f64>::new();
    (planner.plan_fft_forward(n), planner.plan_fft_inverse(n))
}

#[cfg(test)]
mod tests {
    use super::*;
    use realfft::num_complex::Complex;

    /// The pair inverts itself: inverse(forward(x)) = N·x (realfft's transforms are unnormalised), at an
    /// even length with odd factors (the spectral routes' lengths are 2^a·3^b·5^c).
    #[test]
    fn the_pair_inverts_itself() {
        let n = 90;
        let (fwd, inv) = real_fft_pair(n);
        let x: Vec<f64> = (0..n).map(|k| ((k * 7 % 13) as f64 - 6.0) / 3.0).collect();
        let mut xin = x.clone();
        let mut bins = vec![Complex::new(0.0, 0.0); n / 2 + 1];
        fwd.process(&mut xin, &mut bins).unwrap();
        let mut back = vec![0.0; n];
        inv.process(&mut bins, &mut back).unwrap();
        let worst = x
            .iter()
            .zip(&back)
            .map(|(a, b)| (b / n as f64 - a).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-13, "round trip error {worst:e}");
        assert_eq!(inverse_real_fft(n).len(), n);
    }
}
