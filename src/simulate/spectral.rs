//! Spectral representation: stationary Gaussian realizations of any spectrum as a sum of cosines on an FFT
//! grid, synthesised by one inverse real FFT per realization.

use super::rng::{fill_standard_normal, uniform01};
use crate::error::{require_positive, Error, Result};
use crate::spectrum::Spectrum;
use rand::rngs::Xoshiro256PlusPlus;
use realfft::num_complex::Complex;
use realfft::ComplexToReal;
use std::f64::consts::PI;
use std::sync::Arc;

/// How the Fourier coefficients of a realization are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Amplitudes {
    /// Complex Gaussian coefficients (Rayleigh amplitudes, uniform phases): every realization is a
    /// Gaussian process with the target covariance. The default.
    Rayleigh,
    /// Deterministic amplitudes √(S(ω_j)Δω), uniform random phases ("phase-only" synthesis, Shinozuka).
    /// Every realization has the same time-average variance; the process is only asymptotically Gaussian
    /// (many cosines) and across-realization statistics differ from the Gaussian ones. Use only knowingly.
    PhaseOnly,
}

/// A generator of periodic, stationary realizations x_k = x(kΔt), k = 0..N, of a process with two-sided
/// density S(ω): any [`Spectrum`], including non-rational and tabulated ones (spatial spectra: Δt is a
/// distance step Δx in m and ω is in rad/m).
///
/// # Formula
/// ```text
/// Δω = 2π/(NΔt),   ω_j = jΔω,   x_k = Σ_{j=−N/2+1}^{N/2} c_j e^{iω_j kΔt}  (c_{−j} = conj c_j)
///     = c₀ + 2 Σ_{j=1}^{N/2−1} |c_j| cos(ω_j t_k + φ_j) + c_{N/2} (−1)^k
/// Rayleigh:  Re c_j, Im c_j ~ N(0, S(ω_j)Δω/2) (0 < j < N/2);  c₀, c_{N/2} ~ N(0, S(ω_j)Δω) real
/// PhaseOnly: |c_j| = √(S(ω_j)Δω), φ_j uniform;  c₀, c_{N/2} = ±√(S(ω_j)Δω)
/// ```
/// i.e. the amplitude of the cosine at ω_j is A_j = 2|c_j| with E\[A_j²\]/2 = 2S(ω_j)Δω. The realization is
/// one inverse real FFT of length N of the coefficients c₀..c_{N/2}.
///
/// Exact statistics of the generated (discretised) process: its autocovariance is
/// K_N(mΔt) = Σ_j S(ω_j)Δω cos(ω_j mΔt) (over the two-sided grid), periodic in m with period N, and its
/// variance is
/// ```text
/// D_N = S(0)Δω + Σ_{j=1}^{N/2−1} 2S(ω_j)Δω + S(ω_{N/2})Δω        ([`SpectralGenerator::grid_variance`])
/// ```
/// Caveats: D_N differs from D = ∫S dω by truncation (|ω| > π/Δt is omitted, not folded back: the
/// generated samples are not the aliased samples of the continuous process) and by the rectangle-rule error
/// of the grid (resolution Δω must resolve the peaks of S); K_N(τ) ≈ K(τ) only for τ ≪ NΔt. The c₀ term
/// makes each realization's time average random with variance S(0)Δω, as for a finite record.
///
/// # Errors
/// [`SpectralGenerator::new`] rejects N < 2 or odd, Δt ≤ 0, and a spectrum with a negative or non-finite
/// density on the grid.
///
/// # Examples
/// ```
/// use stochvib::simulate::{SpectralGenerator, Amplitudes, SpectralScratch, stream};
/// use stochvib::spectrum::{Gaussian, Domain, Spectrum};
/// let s = Gaussian::new(1.0, 4.0, Domain::Temporal).unwrap();   // type 2, non-rational
/// let g = SpectralGenerator::new(&s, 0.05, 4096, Amplitudes::Rayleigh).unwrap();
/// assert!((g.grid_variance() - 1.0).abs() < 1e-9);
/// let mut scratch = g.scratch();
/// let mut x = vec![0.0; 4096];
/// g.generate(&mut stream(7, 0), &mut scratch, &mut x).unwrap();
/// ```
#[derive(Clone)]
pub struct SpectralGenerator {
    n: usize,
    dt: f64,
    amplitudes: Amplitudes,
    /// √(S(ω_j)Δω), j = 0..=N/2.
    scale: Vec<f64>,
    grid_variance: f64,
    plan: Arc<dyn ComplexToReal<f64>>,
    description: String,
}

impl std::fmt::Debug for SpectralGenerator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpectralGenerator")
            .field("n", &self.n)
            .field("dt", &self.dt)
            .field("amplitudes", &self.amplitudes)
            .field("grid_variance", &self.grid_variance)
            .field("spectrum", &self.description)
            .finish()
    }
}

/// Per-thread working memory of a [`SpectralGenerator`] (coefficients and FFT scratch), reused across
/// realizations so that generation does not allocate.
#[derive(Debug, Clone)]
pub struct SpectralScratch {
    coef: Vec<Complex<f64>>,
    fft: Vec<Complex<f64>>,
}

impl SpectralScratch {
    /// The coefficients c₀..c_{N/2} of the last [`SpectralGenerator::draw`].
    pub fn coefficients(&self) -> &[Complex<f64>] {
        &self.coef
    }
    /// The coefficients, for a generator that draws them its own way ([`super::LaplaceMovingAverage`]).
    pub(crate) fn coefficients_mut(&mut self) -> &mut [Complex<f64>] {
        &mut self.coef
    }
}

impl SpectralGenerator {
    /// Prepares the grid and the FFT plan for N = `n` samples at step `dt`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(spectrum: &dyn Spectrum, dt: f64, n: usize, amplitudes: Amplitudes) -> Result<Self> {
        require_positive("dt", dt)?;
        if n < 2 || !n.is_multiple_of(2) {
            return Err(Error::invalid("n", n, "number of samples must be even and >= 2"));
        }
        let dw = 2.0 * PI / (n as f64 * dt);
        let mut scale = Vec::with_capacity(n / 2 + 1);
        let mut var = 0.0;
        for j in 0..=n / 2 {
            let w = j as f64 * dw;
            let s = spectrum.density(w);
            if !(s.is_finite() && s >= 0.0) {
                return Err(Error::invalid(
                    "spectrum",
                    spectrum.describe(),
                    format!("density at ω = {w:e} is {s:e}; need finite and >= 0 on the whole grid (give a band)"),
                ));
            }
            var += if j == 0 || j == n / 2 { s * dw } else { 2.0 * s * dw };
            scale.push((s * dw).sqrt());
        }
        let plan = super::fft_plans::inverse_real_fft(n);
        Ok(SpectralGenerator {
            n,
            dt,
            amplitudes,
            scale,
            grid_variance: var,
            plan,
            description: spectrum.describe(),
        })
    }

    /// Number of samples N of a realization.
    pub fn len(&self) -> usize {
        self.n
    }
    /// Always false (N ≥ 2).
    pub fn is_empty(&self) -> bool {
        false
    }
    /// Sample step Δt (s, or m for spatial spectra).
    pub fn dt(&self) -> f64 {
        self.dt
    }
    /// Grid spacing Δω = 2π/(NΔt).
    pub fn d_omega(&self) -> f64 {
        2.0 * PI / (self.n as f64 * self.dt)
    }
    /// The amplitude law.
    pub fn amplitudes(&self) -> Amplitudes {
        self.amplitudes
    }
    /// Exact variance D_N of the generated process (see the type's formula).
    pub fn grid_variance(&self) -> f64 {
        self.grid_variance
    }
    /// The amplitude scales s_j = √(S(ω_j)Δω), j = 0..=N/2.
    pub fn scales(&self) -> &[f64] {
        &self.scale
    }
    /// Exact autocovariance of the generated process at lag mΔt: K_N(m) = Σ_j S(ω_j)Δω cos(ω_j mΔt).
    pub fn grid_autocovariance(&self, m: i64) -> f64 {
        let n = self.n;
        let mut k = 0.0;
        for (j, s) in self.scale.iter().enumerate() {
            let weight = if j == 0 || j == n / 2 { 1.0 } else { 2.0 };
            let arg = 2.0 * PI * ((j as i64 * m).rem_euclid(n as i64)) as f64 / n as f64;
            k += weight * s * s * arg.cos();
        }
        k
    }
    /// Fresh working memory for [`generate`](Self::generate).
    pub fn scratch(&self) -> SpectralScratch {
        SpectralScratch {
            coef: vec![Complex::new(0.0, 0.0); self.n / 2 + 1],
            fft: vec![Complex::new(0.0, 0.0); self.plan.get_scratch_len()],
        }
    }

    /// Writes one realization of N samples into `out`, drawing from `rng`: Rayleigh draws N/2 + 1 … two
    /// normals per interior bin (real, imaginary) and one for bins 0 and N/2, in bin order; PhaseOnly draws
    /// one uniform per bin.
    ///
    /// # Errors
    /// `out.len()` ≠ N; a scratch from another generator.
    pub fn generate(&self, rng: &mut Xoshiro256PlusPlus, scratch: &mut SpectralScratch, out: &mut [f64]) -> Result<()> {
        let n = self.n;
        if out.len() != n || scratch.coef.len() != n / 2 + 1 || scratch.fft.len() != self.plan.get_scratch_len() {
            return Err(Error::invalid(
                "out",
                out.len(),
                format!("need {n} samples and a scratch made by this generator"),
            ));
        }
        self.draw(rng, scratch);
        self.synthesize(scratch, out)
    }

    /// The inverse real FFT of the coefficients in `scratch` into `out` (N samples; the coefficients are
    /// overwritten).
    pub(crate) fn synthesize(&self, scratch: &mut SpectralScratch, out: &mut [f64]) -> Result<()> {
        if out.len() != self.n {
            return Err(Error::invalid("out", out.len(), format!("need {} samples", self.n)));
        }
        self.plan
            .process_with_scratch(&mut scratch.coef, out, &mut scratch.fft)
            .map_err(|e| Error::Numerical {
                what: "inverse real FFT".into(),
                reason: e.to_string(),
            })
    }

    /// Writes one realization of the response of a linear filter to the generated process: the same
    /// coefficients as [`generate`](Self::generate) (same draws from `rng`), each multiplied by the filter's
    /// gain on the grid before the one inverse FFT.
    ///
    /// # Formula
    /// ```text
    /// y_k = Σ_j G_j c_j e^{iω_j kΔt}   (G_{−j} = conj G_j;  only Re G_0 and Re G_{N/2} are used)
    /// ```
    /// With G = [`SampledSystem::grid_response`](super::SampledSystem::grid_response) this is exactly the
    /// periodic steady state that [`SampledSystem::respond`](super::SampledSystem::respond) reaches after
    /// warm-up periods of the periodic input (what the spectral route of
    /// [`run`](super::run()) records), in one FFT; with G = H(iω_j) of the continuous system
    /// it is the spectral representation of the continuous response.
    ///
    /// # Errors
    /// As [`generate`](Self::generate); `gain.len()` ≠ N/2 + 1.
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::{SpectralGenerator, Amplitudes, stream};
    /// use stochvib::spectrum::{Exponential, Domain};
    /// use realfft::num_complex::Complex;
    /// let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
    /// let g = SpectralGenerator::new(&s, 0.05, 64, Amplitudes::Rayleigh).unwrap();
    /// let (mut sc, mut x, mut y) = (g.scratch(), vec![0.0; 64], vec![0.0; 64]);
    /// g.generate(&mut stream(1, 0), &mut sc, &mut x).unwrap();
    /// // a gain of 2 on every bin doubles the realization
    /// g.generate_filtered(&mut stream(1, 0), &mut sc, &vec![Complex::new(2.0, 0.0); 33], &mut y).unwrap();
    /// assert!(x.iter().zip(&y).all(|(a, b)| (2.0 * a - b).abs() < 1e-12));
    /// ```
    pub fn generate_filtered(
        &self,
        rng: &mut Xoshiro256PlusPlus,
        scratch: &mut SpectralScratch,
        gain: &[Complex<f64>],
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.n;
        if gain.len() != n / 2 + 1 {
            return Err(Error::invalid(
                "gain",
                gain.len(),
                format!("need N/2 + 1 = {} bins", n / 2 + 1),
            ));
        }
        if out.len() != n || scratch.coef.len() != n / 2 + 1 || scratch.fft.len() != self.plan.get_scratch_len() {
            return Err(Error::invalid(
                "out",
                out.len(),
                format!("need {n} samples and a scratch made by this generator"),
            ));
        }
        self.draw(rng, scratch);
        for (c, g) in scratch.coef.iter_mut().zip(gain) {
            *c *= g;
        }
        scratch.coef[0].im = 0.0;
        scratch.coef[n / 2].im = 0.0;
        self.plan
            .process_with_scratch(&mut scratch.coef, out, &mut scratch.fft)
            .map_err(|e| Error::Numerical {
                what: "inverse real FFT".into(),
                reason: e.to_string(),
            })
    }

    /// Draws the coefficients c₀..c_{N/2} of one realization into `scratch` (see the type's formula), in
    /// the order [`generate`](Self::generate) draws them; read them with [`SpectralScratch::coefficients`].
    /// For combining several generators or filters before one's own inverse FFT.
    ///
    /// # Panics
    /// When `scratch` was made by a generator of another N (a programming error).
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::{SpectralGenerator, Amplitudes, stream};
    /// use stochvib::spectrum::{Exponential, Domain};
    /// let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
    /// let g = SpectralGenerator::new(&s, 0.05, 64, Amplitudes::Rayleigh).unwrap();
    /// let mut sc = g.scratch();
    /// g.draw(&mut stream(1, 0), &mut sc);
    /// assert_eq!(sc.coefficients().len(), 33);
    /// assert_eq!(sc.coefficients()[0].im, 0.0);
    /// ```
    pub fn draw(&self, rng: &mut Xoshiro256PlusPlus, scratch: &mut SpectralScratch) {
        assert_eq!(scratch.coef.len(), self.n / 2 + 1, "scratch made by another generator");
        let n = self.n;
        let half = n / 2;
        match self.amplitudes {
            Amplitudes::Rayleigh => {
                // the 2·(N/2) draws in bin order in one run (z for c₀, Re and Im of c₁ … c_{N/2−1}, z for
                // c_{N/2}) into the coefficients viewed as numbers, from the second on; then z₀ moved to
                // Re c₀, the imaginary parts of c₀ and c_{N/2} cleared, every bin scaled as it was drawn
                // (s·z at the ends, (s·r)·z inside: the bits of drawing and scaling bin by bin)
                let r = std::f64::consts::FRAC_1_SQRT_2;
                let draws = 2 * half;
                let flat: &mut [f64] = bytemuck::cast_slice_mut(&mut scratch.coef);
                fill_standard_normal(rng, &mut flat[1..=draws]);
                flat[0] = flat[1];
                flat[1] = 0.0;
                flat[draws + 1] = 0.0;
                let (first, last) = (self.scale[0], self.scale[half]);
                for (c, s) in scratch.coef[1..half].iter_mut().zip(&self.scale[1..half]) {
                    let sr = s * r;
                    *c = Complex::new(sr * c.re, sr * c.im);
                }
                scratch.coef[0].re *= first;
                scratch.coef[half].re *= last;
            }
            Amplitudes::PhaseOnly => {
                for (j, (c, s)) in scratch.coef.iter_mut().zip(&self.scale).enumerate() {
                    let u = uniform01(rng);
                    if j == 0 || j == half {
                        *c = Complex::new(if u < 0.5 { -*s } else { *s }, 0.0);
                    } else {
                        let (sn, cs) = (2.0 * PI * u).sin_cos();
                        *c = Complex::new(s * cs, s * sn);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::{standard_normal, stream};
    use crate::spectrum::{Domain, Exponential};
    use crate::tolerance::{EXACT, ROUNDING};

    #[test]
    fn synthesis_matches_cosine_sum() {
        // The FFT output must equal the defining sum c₀ + 2Σ Re(c_j e^{iω_j t_k}) + c_{N/2}(−1)^k, evaluated
        // directly from the same coefficients (independent of the FFT).
        let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
        let n = 16;
        let g = SpectralGenerator::new(&s, 0.1, n, Amplitudes::Rayleigh).unwrap();
        let mut sc = g.scratch();
        let mut x = vec![0.0; n];
        g.generate(&mut stream(3, 1), &mut sc, &mut x).unwrap();
        // regenerate the coefficients with the same stream
        let mut rng = stream(3, 1);
        let mut c = Vec::new();
        for j in 0..=n / 2 {
            let sj = g.scale[j];
            if j == 0 || j == n / 2 {
                c.push(Complex::new(sj * standard_normal(&mut rng), 0.0));
            } else {
                let (a, b) = (standard_normal(&mut rng), standard_normal(&mut rng));
                c.push(Complex::new(sj * a, sj * b) * std::f64::consts::FRAC_1_SQRT_2);
            }
        }
        for (k, xk) in x.iter().enumerate() {
            let mut v = c[0].re + c[n / 2].re * if k % 2 == 0 { 1.0 } else { -1.0 };
            for (j, cj) in c.iter().enumerate().take(n / 2).skip(1) {
                let ph = 2.0 * PI * (j * k) as f64 / n as f64;
                v += 2.0 * (cj * Complex::new(ph.cos(), ph.sin())).re;
            }
            assert!((v - xk).abs() < EXACT, "{k}: {v} vs {xk}");
        }
        // K_N(0) equals the grid variance
        assert!((g.grid_autocovariance(0) - g.grid_variance()).abs() < ROUNDING);
    }

    #[test]
    fn phase_only_time_variance_is_deterministic() {
        // Parseval: the time-average of x² over one period is c₀² + 2Σ|c_j|² + c_{N/2}² = D_N for every
        // phase-only realization (that is what the label warns about).
        let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
        let g = SpectralGenerator::new(&s, 0.05, 256, Amplitudes::PhaseOnly).unwrap();
        let mut sc = g.scratch();
        let mut x = vec![0.0; 256];
        for i in 0..3 {
            g.generate(&mut stream(1, i), &mut sc, &mut x).unwrap();
            let ms = x.iter().map(|v| v * v).sum::<f64>() / 256.0;
            assert!((ms - g.grid_variance()).abs() < EXACT);
        }
    }

    #[test]
    fn filtered_generation_is_the_periodic_steady_state_of_respond() {
        // Independent method: time-step the FOH-sampled SDOF (ω = 10, ζ = 0.05) through the same periodic
        // input for 12 periods from rest (transient factor e^{−0.5·12·12.8} ≈ 5e-34) and compare the last
        // period with the one-FFT product G_j c_j. Agreement to rounding (EXACT relative to max |y|).
        use crate::simulate::SampledSystem;
        use crate::system::StateSpace;
        let (n, dt) = (256, 0.05);
        let ss = StateSpace::oscillator(10.0, 0.05).unwrap();
        let sys = SampledSystem::new(&ss, dt).unwrap();
        let s = Exponential::new(1.0, 3.0, Domain::Temporal).unwrap();
        let g = SpectralGenerator::new(&s, dt, n, Amplitudes::Rayleigh).unwrap();
        let mut sc = g.scratch();
        let mut u = vec![0.0; n + 1];
        g.generate(&mut stream(5, 2), &mut sc, &mut u[..n]).unwrap();
        u[n] = u[0];
        let (mut x, mut y) = (vec![0.0; 2], vec![0.0; n + 1]);
        for _ in 0..12 {
            sys.respond(&u, &mut x, &mut y).unwrap();
        }
        let gain = sys.grid_response(n, 0, 0).unwrap();
        let mut yf = vec![0.0; n];
        g.generate_filtered(&mut stream(5, 2), &mut sc, &gain, &mut yf).unwrap();
        let scale = y.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for k in 0..n {
            assert!((y[k] - yf[k]).abs() < EXACT * scale, "{k}: {} vs {}", y[k], yf[k]);
        }
    }
}
