//! The Laplace moving average: a stationary non-Gaussian process with a prescribed spectrum and a
//! prescribed kurtosis (a road rougher in its extremes than a Gaussian one of the same spectrum).

use super::lane_normals::StreamNormals;
use super::rng::fill_standard_normal;
use super::spectral::{SpectralGenerator, SpectralScratch};
use super::Amplitudes;
use crate::error::{Error, Result};
use crate::spectrum::Spectrum;
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;
use rand_distr::Gamma;
use realfft::num_complex::Complex;
use realfft::{RealFftPlanner, RealToComplex};
use std::sync::Arc;

/// The draw order of a Laplace moving average, stored with a run as part of its generator's name.
pub const LAPLACE_DRAWS: &str = "Laplace increments ε_k = √Γ_k·Z_k, k = 0..N−1, each drawn as Γ_k by rand_distr 0.6 \
    `Gamma(1/ν, ν)` then Z_k by `StandardNormal` (no Gamma draw for ν = 0), forward real FFT, c_j = s_j·W_j";

/// Periodic realizations x_k = x(kΔt), k = 0..N, of a Laplace moving average (LMA): a process with the
/// two-sided density S(ω) of a [`SpectralGenerator`] (the same grid, the same autocovariance) whose marginal
/// kurtosis is a prescribed κ ≥ 3 instead of the Gaussian 3.
///
/// The model is the homogeneous Laplace moving average of K. Bogsjö, K. Podgórski and I. Rychlik, "Models
/// for road surface roughness", Vehicle System Dynamics 50(5), 2012, 725–747: X(t) = ∫ f(t − s) dΛ(s), with
/// Λ a symmetric Laplace motion (increments over Δ distributed as √Γ·Z, Γ ~ Gamma(shape Δ/ν, scale ν),
/// Z ~ N(0, 1)) and a kernel f with |𝓕f|² ∝ S; their continuous excess kurtosis is 3ν∫f⁴/(∫f²)². Here
/// it is written on the grid of the spectral representation, with a symmetric (zero-phase) kernel.
///
/// # Formula
/// Discrete, periodic form (the form simulated, exact on the grid):
/// ```text
/// ε_k = √Γ_k · Z_k,   Γ_k ~ Gamma(shape 1/ν̃, scale ν̃) (E Γ = 1, Var Γ = ν̃),  Z_k ~ N(0, 1),  all independent
/// W_j = N^{−1/2} Σ_k ε_k e^{−2πijk/N},   c_j = s_j W_j,   s_j = √(S(ω_j)Δω)   (j = 0 … N/2)
/// x_k = Σ_j c_j e^{iω_j kΔt}   (the inverse FFT of SpectralGenerator, Hermitian extension)
///     = Σ_m f_m ε_{(k−m) mod N},   f_l = N^{−1/2} Σ_{j=−N/2+1}^{N/2} s_j e^{2πijl/N}   (real, even)
/// ```
/// ν̃ = ν/Δt is the Laplace motion's ν in grid steps (ν in s, or m for a spatial profile).
/// * Spectrum: E ε = 0, E ε² = E Γ = 1, so E|W_j|² = 1 and E|c_j|² = S(ω_j)Δω exactly, as for the Rayleigh
///   draw: the autocovariance K_N(m) = Σ_j S(ω_j)Δω cos(ω_j mΔt) and the variance
///   D_N = Σ_l f_l² = Σ_j s_j² ([`SpectralGenerator::grid_variance`]) are unchanged by construction.
/// * Kurtosis: E ε⁴ = 3 E Γ² = 3(1 + ν̃), so the fourth cumulant of ε is 3ν̃, and cumulants add over the
///   independent terms of x_k = Σ_m f_m ε_{k−m}:
/// ```text
/// κ = E x⁴ / (E x²)² = 3 + 3ν̃ · r,   r = Σ_l f_l⁴ / (Σ_l f_l²)²         (r ∈ (0, 1])
/// ν̃ = (κ − 3) / (3r)                                                  (solved from the prescribed κ)
/// ```
///   With f_l ≈ Δt·f(lΔt) of a continuous kernel, r ≈ Δt∫f⁴/(∫f²)² and 3ν̃r → 3ν∫f⁴/(∫f²)², the continuous
///   formula above.
/// * Any linear filter with gains G_j on the grid gives again an LMA, with kernel g_l (transform s_jG_j), so its
///   output kurtosis is 3 + 3ν̃·Σg⁴/(Σg²)² ([`LaplaceMovingAverage::filtered_cumulants`]): a smoothing filter
///   (a longer kernel) brings it closer to 3.
/// * κ = 3 is ν̃ = 0: Γ ≡ 1, ε = Z is Gaussian white noise and W_j are exactly the complex Gaussian
///   coefficients of the Rayleigh draw (the same law, other draws).
/// * Largest kurtosis on the grid ([`max_kurtosis`]): the N increments of one realization are N numbers,
///   and N numbers have a kurtosis N·Σε⁴/(Σε²)² ≤ N (since Σε⁴ ≤ (Σε²)²), reached when one of them carries
///   everything. Increments of kurtosis E ε⁴/(E ε²)² = 3(1 + ν̃) > N cannot be represented by a realization:
///   its variance is then carried by fewer than about three increments (the Gamma draws of shape 1/ν̃ are
///   almost all zero: Σ_k Γ_k ~ Gamma(N/ν̃, ν̃), of shape N/ν̃ < 3), most realizations are nearly zero and
///   the Monte Carlo σ collapses (κ = 10⁹ gave σ = 0 where the process has σ = 1.9·10⁻²). So
/// ```text
/// 3(1 + ν̃) ≤ N   ⟺   κ ≤ κ_max = 3 + r·(N − 3)
/// ```
///   With f_l ≈ Δt·f(lΔt), r·N ≈ T·∫f⁴/(∫f²)² (T = NΔt): the bound grows with the duration of a realization
///   (the number of kernel lengths it holds), not with a finer step.
///
/// # Errors
/// [`LaplaceMovingAverage::new`]: the errors of [`SpectralGenerator::new`]; a kurtosis that is not finite or
/// below 3 (a Laplace moving average cannot be lighter-tailed than a Gaussian) or above [`max_kurtosis`] of
/// the grid; a spectrum that is zero on the whole grid. [`LaplaceMovingAverage::from_generator`]: the
/// kurtosis errors, and a phase-only generator.
///
/// # Examples
/// ```
/// use stochvib::simulate::{LaplaceGrid, LaplaceMovingAverage, stream};
/// use stochvib::spectrum::{Domain, Exponential};
/// // a type-1 road, D = 2.25e-4 m², α = 3.5 1/m, sampled every 5 cm, kurtosis 6
/// let q = Exponential::new(2.25e-4, 3.5, Domain::Spatial).unwrap();
/// let lma = LaplaceMovingAverage::new(&q, LaplaceGrid { dt: 0.05, n: 4096, kurtosis: 6.0 }).unwrap();
/// // the kurtosis of the generated process, from its kernel and ν
/// assert!((3.0 + 3.0 * lma.nu_steps() * lma.kernel_ratio() - 6.0).abs() < 1e-12);
/// let mut scratch = lma.scratch();
/// let mut x = vec![0.0; 4096];
/// lma.generate(&mut stream(7, 0), &mut scratch, &mut x).unwrap();
/// assert!(LaplaceMovingAverage::new(&q, LaplaceGrid { dt: 0.05, n: 4096, kurtosis: 2.5 }).is_err());
/// ```
#[derive(Clone)]
pub struct LaplaceMovingAverage {
    spectral: SpectralGenerator,
    kurtosis: f64,
    nu_steps: f64,
    kernel_ratio: f64,
    gamma: Option<Gamma<f64>>,
    forward: Arc<dyn RealToComplex<f64>>,
}

impl std::fmt::Debug for LaplaceMovingAverage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LaplaceMovingAverage")
            .field("spectral", &self.spectral)
            .field("kurtosis", &self.kurtosis)
            .field("nu_steps", &self.nu_steps)
            .field("kernel_ratio", &self.kernel_ratio)
            .finish()
    }
}

/// Working memory of a [`LaplaceMovingAverage`] (the increments, the forward FFT's scratch and the
/// coefficients), reused across realizations.
#[derive(Debug, Clone)]
pub struct LaplaceScratch {
    increments: Vec<f64>,
    fft: Vec<Complex<f64>>,
    coef: SpectralScratch,
}

impl LaplaceScratch {
    /// The coefficients c₀..c_{N/2} of the last [`LaplaceMovingAverage::draw`].
    pub fn coefficients(&self) -> &[Complex<f64>] {
        self.coef.coefficients()
    }
    /// The increments ε₀..ε_{N−1} of the last draw (overwritten by the FFT: read them only before it; kept
    /// for tests of the draw order through [`LaplaceMovingAverage::draw_increments`]).
    pub fn increments(&self) -> &[f64] {
        &self.increments
    }
}

/// The largest kurtosis a Laplace moving average of `n` samples per realization with kernel ratio
/// `kernel_ratio` r = Σf⁴/(Σf²)² can represent: κ_max = 3 + r·(n − 3) (see [`LaplaceMovingAverage`],
/// "Largest kurtosis on the grid": the increments' kurtosis 3(1 + ν̃) must not exceed n).
///
/// # Examples
/// ```
/// use stochvib::simulate::laplace::max_kurtosis;
/// // a kernel of one tap (r = 1, white increments): the increments' own bound n
/// assert_eq!(max_kurtosis(1.0, 1000), 1000.0);
/// assert!((max_kurtosis(1.768e-2, 13536) - 242.2).abs() < 0.1);
/// ```
pub fn max_kurtosis(kernel_ratio: f64, n: usize) -> f64 {
    3.0 + kernel_ratio * (n as f64 - 3.0)
}

/// The kernel ratio r = Σ f_l⁴ / (Σ f_l²)² of the kernel whose transform on the grid is `amp[j]` (j = 0..=N/2,
/// Hermitian extension; the imaginary parts of bins 0 and N/2 are ignored), f_l = N^{−1/2}·(inverse FFT)_l;
/// returns (Σ f⁴, Σ f²).
fn kernel_sums(amp: &[Complex<f64>], n: usize) -> Result<(f64, f64)> {
    let mut spec = amp.to_vec();
    spec[0].im = 0.0;
    spec[n / 2].im = 0.0;
    let mut f = vec![0.0; n];
    RealFftPlanner::<f64>::new()
        .plan_fft_inverse(n)
        .process(&mut spec, &mut f)
        .map_err(|e| Error::Numerical {
            what: "Laplace moving average kernel".into(),
            reason: e.to_string(),
        })?;
    let norm = 1.0 / n as f64;
    let (mut s2, mut s4) = (0.0, 0.0);
    for v in &f {
        let sq = v * v * norm;
        s2 += sq;
        s4 += sq * sq;
    }
    Ok((s4, s2))
}

/// Refuses a kurtosis above [`max_kurtosis`] of the grid of `spectral` (N samples, kernel ratio r).
fn check_representable(kurtosis: f64, kernel_ratio: f64, spectral: &SpectralGenerator) -> Result<()> {
    let n = spectral.len();
    let max = max_kurtosis(kernel_ratio, n);
    if kurtosis <= max {
        return Ok(());
    }
    let num = crate::numbers::num;
    Err(Error::invalid(
        "kurtosis",
        num(kurtosis),
        format!(
            "a Laplace moving average of N = {n} samples per realization (Δt = {} s, duration {} s) with this \
             spectrum's kernel ratio r = Σf⁴/(Σf²)² = {kernel_ratio:.4e} can have a kurtosis of at most \
             3 + r·(N − 3) = {:.4}: its increments would need a kurtosis 3(1 + ν) = {:.4e} above N, the largest \
             N numbers can have, so a realization would hold fewer than three increments that carry its \
             variance and the Monte Carlo σ would collapse; give a kurtosis of at most {:.4}, or longer \
             realizations (the bound grows in proportion to the duration)",
            num(spectral.dt()),
            num(n as f64 * spectral.dt()),
            max,
            3.0 * (1.0 + (kurtosis - 3.0) / (3.0 * kernel_ratio)),
            max,
        ),
    ))
}

/// The grid and the kurtosis of a [`LaplaceMovingAverage`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaplaceGrid {
    /// The step Δt of the samples (s, or m for a spatial spectrum).
    pub dt: f64,
    /// The number N of samples of a realization.
    pub n: usize,
    /// The marginal kurtosis κ = E x⁴/(E x²)² (3 for a Gaussian; the excess kurtosis is κ − 3).
    pub kurtosis: f64,
}

impl LaplaceMovingAverage {
    /// The LMA of two-sided density `spectrum` on the grid and with the kurtosis of `grid`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(spectrum: &dyn Spectrum, grid: LaplaceGrid) -> Result<Self> {
        let LaplaceGrid { dt, n, kurtosis } = grid;
        Self::check_kurtosis(kurtosis)?;
        let g = SpectralGenerator::new(spectrum, dt, n, Amplitudes::Rayleigh)?;
        Self::from_generator(g, kurtosis)
    }

    /// The LMA on the grid of an existing (Rayleigh) spectral generator: same N, Δt and s_j.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn from_generator(spectral: SpectralGenerator, kurtosis: f64) -> Result<Self> {
        Self::check_kurtosis(kurtosis)?;
        if spectral.amplitudes() != Amplitudes::Rayleigh {
            return Err(Error::invalid(
                "amplitudes",
                format!("{:?}", spectral.amplitudes()),
                "a Laplace moving average draws its own amplitudes: give a Rayleigh spectral generator",
            ));
        }
        let n = spectral.len();
        let amp: Vec<Complex<f64>> = spectral.scales().iter().map(|s| Complex::new(*s, 0.0)).collect();
        let (s4, s2) = kernel_sums(&amp, n)?;
        if s2.is_nan() || s2 <= 0.0 {
            return Err(Error::invalid(
                "spectrum",
                format!("grid variance {s2:e}"),
                "the density is zero on the whole grid: no process to shape",
            ));
        }
        let kernel_ratio = s4 / (s2 * s2);
        check_representable(kurtosis, kernel_ratio, &spectral)?;
        let nu_steps = (kurtosis - 3.0) / (3.0 * kernel_ratio);
        let gamma = if nu_steps > 0.0 {
            Some(Gamma::new(1.0 / nu_steps, nu_steps).map_err(|e| {
                Error::invalid(
                    "kurtosis",
                    kurtosis,
                    format!("Gamma(1/ν, ν) with ν = {nu_steps:e} steps is not a distribution: {e}"),
                )
            })?)
        } else {
            None
        };
        Ok(LaplaceMovingAverage {
            forward: RealFftPlanner::<f64>::new().plan_fft_forward(n),
            spectral,
            kurtosis,
            nu_steps,
            kernel_ratio,
            gamma,
        })
    }

    fn check_kurtosis(kurtosis: f64) -> Result<()> {
        if !(kurtosis.is_finite() && kurtosis >= 3.0) {
            return Err(Error::invalid(
                "kurtosis",
                kurtosis,
                "the kurtosis E x⁴/(E x²)² of a Laplace moving average is finite and >= 3 (3 is the Gaussian \
                 process; a lighter tail than Gaussian is not a Laplace moving average)",
            ));
        }
        Ok(())
    }

    /// The prescribed marginal kurtosis κ.
    pub fn kurtosis(&self) -> f64 {
        self.kurtosis
    }
    /// ν̃ = ν/Δt, the Laplace motion's ν in grid steps (0 for κ = 3).
    pub fn nu_steps(&self) -> f64 {
        self.nu_steps
    }
    /// ν = ν̃·Δt, in the unit of Δt (s, or m for a spatial profile).
    pub fn nu(&self) -> f64 {
        self.nu_steps * self.spectral.dt()
    }
    /// r = Σf_l⁴/(Σf_l²)² of the grid kernel (see the type's formula).
    pub fn kernel_ratio(&self) -> f64 {
        self.kernel_ratio
    }
    /// The spectral generator whose grid and spectrum this LMA shares.
    pub fn spectral(&self) -> &SpectralGenerator {
        &self.spectral
    }
    /// Number of samples N.
    pub fn len(&self) -> usize {
        self.spectral.len()
    }
    /// Always false (N ≥ 2).
    pub fn is_empty(&self) -> bool {
        false
    }
    /// Exact variance D_N of the generated process (that of [`SpectralGenerator::grid_variance`]).
    pub fn grid_variance(&self) -> f64 {
        self.spectral.grid_variance()
    }

    /// (fourth cumulant, variance) of the stationary output of a linear filter with gains `gain[j]` on the
    /// grid (j = 0..=N/2) driven by this process: for y_k = Σ_j G_j c_j e^{iω_j kΔt},
    ///
    /// # Formula
    /// ```text
    /// y_k = Σ_m g_m ε_{k−m},   g_l = N^{−1/2} Σ_j s_j G_j e^{2πijl/N}
    /// Var y = Σ_l g_l²,   κ₄(y) = 3ν̃ Σ_l g_l⁴,   kurtosis(y) = 3 + κ₄/Var²
    /// ```
    /// (the imaginary parts of G₀ and G_{N/2} are ignored, as by the synthesis). Cumulants of independent
    /// LMA inputs add: sum the pairs over the generators feeding one output.
    ///
    /// # Errors
    /// `gain.len()` ≠ N/2 + 1.
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::{LaplaceGrid, LaplaceMovingAverage};
    /// use stochvib::spectrum::{Domain, Exponential};
    /// use realfft::num_complex::Complex;
    /// let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
    /// let lma = LaplaceMovingAverage::new(&s, LaplaceGrid { dt: 0.05, n: 256, kurtosis: 5.0 }).unwrap();
    /// // the identity filter gives the process itself
    /// let (k4, var) = lma.filtered_cumulants(&vec![Complex::new(1.0, 0.0); 129]).unwrap();
    /// assert!((3.0 + k4 / (var * var) - 5.0).abs() < 1e-12);
    /// ```
    pub fn filtered_cumulants(&self, gain: &[Complex<f64>]) -> Result<(f64, f64)> {
        let n = self.len();
        if gain.len() != n / 2 + 1 {
            return Err(Error::invalid(
                "gain",
                gain.len(),
                format!("need N/2 + 1 = {} bins", n / 2 + 1),
            ));
        }
        let amp: Vec<Complex<f64>> = self.spectral.scales().iter().zip(gain).map(|(s, g)| g * *s).collect();
        let (s4, s2) = kernel_sums(&amp, n)?;
        Ok((3.0 * self.nu_steps * s4, s2))
    }

    /// Fresh working memory.
    pub fn scratch(&self) -> LaplaceScratch {
        LaplaceScratch {
            increments: vec![0.0; self.len()],
            fft: vec![Complex::new(0.0, 0.0); self.forward.get_scratch_len()],
            coef: self.spectral.scratch(),
        }
    }

    /// Draws the N increments ε_k = √Γ_k·Z_k of one realization into `scratch` (see [`LAPLACE_DRAWS`]),
    /// without transforming them.
    pub fn draw_increments(&self, rng: &mut Xoshiro256PlusPlus, scratch: &mut LaplaceScratch) {
        self.fill_increments(rng, &mut scratch.increments);
    }

    fn fill_increments(&self, rng: &mut Xoshiro256PlusPlus, eps: &mut [f64]) {
        match &self.gamma {
            Some(gamma) => {
                // the generator held for the loop (the same draws in the same order: Γ_k, then Z_k)
                let mut normals = StreamNormals::new(rng);
                for e in eps.iter_mut() {
                    let g: f64 = normals.rng_mut().sample(gamma);
                    *e = g.sqrt() * normals.next();
                }
                *rng = normals.into_rng();
            }
            None => {
                fill_standard_normal(rng, eps);
            }
        }
    }

    /// Draws the coefficients c₀..c_{N/2} of one realization into `scratch` (read them with
    /// [`LaplaceScratch::coefficients`]).
    ///
    /// # Errors
    /// A scratch from another generator; an FFT failure.
    pub fn draw(&self, rng: &mut Xoshiro256PlusPlus, scratch: &mut LaplaceScratch) -> Result<()> {
        let LaplaceScratch { increments, fft, coef } = scratch;
        self.draw_into(rng, increments, fft, coef)
    }

    /// The draw of [`draw`](Self::draw) with the coefficients written into a spectral generator's scratch
    /// (the spectral route of a run keeps one per generator); `increments` and `fft` from a
    /// [`LaplaceScratch`] of this generator.
    pub(crate) fn draw_with(
        &self,
        rng: &mut Xoshiro256PlusPlus,
        work: &mut LaplaceScratch,
        out: &mut SpectralScratch,
    ) -> Result<()> {
        self.draw_into(rng, &mut work.increments, &mut work.fft, out)
    }

    fn draw_into(
        &self,
        rng: &mut Xoshiro256PlusPlus,
        increments: &mut [f64],
        fft: &mut [Complex<f64>],
        coef: &mut SpectralScratch,
    ) -> Result<()> {
        let n = self.len();
        if increments.len() != n || fft.len() != self.forward.get_scratch_len() {
            return Err(Error::invalid(
                "scratch",
                increments.len(),
                format!("need {n} increments: a scratch made by this generator"),
            ));
        }
        self.fill_increments(rng, increments);
        let c = coef.coefficients_mut();
        if c.len() != n / 2 + 1 {
            return Err(Error::invalid("scratch", c.len(), "made by another generator"));
        }
        self.forward
            .process_with_scratch(increments, c, fft)
            .map_err(|e| Error::Numerical {
                what: "forward real FFT".into(),
                reason: e.to_string(),
            })?;
        let norm = 1.0 / (n as f64).sqrt();
        for (cj, s) in c.iter_mut().zip(self.spectral.scales()) {
            *cj *= s * norm;
        }
        c[0].im = 0.0;
        c[n / 2].im = 0.0;
        Ok(())
    }

    /// Writes one realization of N samples into `out`.
    ///
    /// # Errors
    /// `out.len()` ≠ N; a scratch from another generator.
    pub fn generate(&self, rng: &mut Xoshiro256PlusPlus, scratch: &mut LaplaceScratch, out: &mut [f64]) -> Result<()> {
        self.draw(rng, scratch)?;
        self.spectral.synthesize(&mut scratch.coef, out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::{standard_normal, stream};
    use crate::spectrum::{Domain, Exponential};
    use crate::tolerance::{EXACT, ROUNDING};

    #[test]
    fn realization_is_the_circular_convolution_of_kernel_and_increments() {
        // Independent evaluation of the defining sum x_k = Σ_m f_m ε_{(k−m) mod N} with
        // f_l = N^{−1/2}[s_0 + 2Σ_{j=1}^{N/2−1} s_j cos(2πjl/N) + s_{N/2}(−1)^l] by direct cosine sums (no FFT),
        // from the same increments (same stream, same draw order).
        let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
        let n = 32;
        let lma = LaplaceMovingAverage::new(
            &s,
            LaplaceGrid {
                dt: 0.1,
                n,
                kurtosis: 7.0,
            },
        )
        .unwrap();
        let mut sc = lma.scratch();
        let mut x = vec![0.0; n];
        lma.generate(&mut stream(3, 1), &mut sc, &mut x).unwrap();
        lma.draw_increments(&mut stream(3, 1), &mut sc);
        let eps = sc.increments().to_vec();
        let sj = lma.spectral().scales().to_vec();
        let f: Vec<f64> = (0..n)
            .map(|l| {
                let mut v = sj[0] + sj[n / 2] * if l % 2 == 0 { 1.0 } else { -1.0 };
                for (j, s) in sj.iter().enumerate().take(n / 2).skip(1) {
                    v += 2.0 * s * (2.0 * std::f64::consts::PI * (j * l) as f64 / n as f64).cos();
                }
                v / (n as f64).sqrt()
            })
            .collect();
        let scale = x.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for k in 0..n {
            let direct: f64 = (0..n).map(|m| f[m] * eps[(k + n - m) % n]).sum();
            assert!((direct - x[k]).abs() < EXACT * scale, "{k}: {direct} vs {}", x[k]);
        }
        // Parseval: Σ f_l² is the grid variance; the kernel ratio is Σf⁴/(Σf²)² of the same kernel
        let s2: f64 = f.iter().map(|v| v * v).sum();
        let s4: f64 = f.iter().map(|v| v.powi(4)).sum();
        assert!((s2 - lma.grid_variance()).abs() < ROUNDING * s2);
        assert!((s4 / (s2 * s2) - lma.kernel_ratio()).abs() < EXACT);
    }

    /// Above kurtosis 3 every increment is Γ_k by `rand_distr`'s Gamma, then Z_k by its standard normal,
    /// k in order ([`LAPLACE_DRAWS`]): 4096 increments have the bits of those draws one call at a time and
    /// leave the stream where they leave it.
    #[test]
    fn increments_draw_gamma_then_normal_in_order() {
        use rand::Rng;
        let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
        let grid = LaplaceGrid {
            dt: 0.05,
            n: 4096,
            kurtosis: 6.0,
        };
        let lma = LaplaceMovingAverage::new(&s, grid).unwrap();
        let gamma = lma.gamma.expect("a Gamma law above kurtosis 3");
        let mut sc = lma.scratch();
        let mut got_rng = stream(9, 2);
        lma.draw_increments(&mut got_rng, &mut sc);
        let mut rng = stream(9, 2);
        for (k, e) in sc.increments().iter().enumerate() {
            let g: f64 = rng.sample(gamma);
            assert_eq!(
                e.to_bits(),
                (g.sqrt() * standard_normal(&mut rng)).to_bits(),
                "increment {k}"
            );
        }
        assert_eq!(got_rng.next_u64(), rng.next_u64(), "the stream after the draws");
    }

    #[test]
    fn kurtosis_three_draws_no_gamma_and_rejects_below_three() {
        // ν = 0: the increments are the stream's standard normals themselves
        let s = Exponential::new(1.0, 2.0, Domain::Temporal).unwrap();
        let lma = LaplaceMovingAverage::new(
            &s,
            LaplaceGrid {
                dt: 0.1,
                n: 16,
                kurtosis: 3.0,
            },
        )
        .unwrap();
        assert_eq!(lma.nu_steps(), 0.0);
        let mut sc = lma.scratch();
        lma.draw_increments(&mut stream(5, 0), &mut sc);
        let mut rng = stream(5, 0);
        for e in sc.increments() {
            assert_eq!(*e, standard_normal(&mut rng));
        }
        for bad in [2.999, f64::NAN, f64::INFINITY, -1.0] {
            assert!(
                LaplaceMovingAverage::new(
                    &s,
                    LaplaceGrid {
                        dt: 0.1,
                        n: 16,
                        kurtosis: bad
                    }
                )
                .is_err(),
                "{bad}"
            );
        }
    }
}
