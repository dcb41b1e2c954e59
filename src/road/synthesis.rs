//! Two parallel road tracks with a given auto-density and a given coherence, synthesised on an FFT grid
//! so that their cross-spectrum is exact in expectation.

use crate::coherence::Coherence;
use crate::error::{require_positive, Error, Result};
use crate::simulate::{Amplitudes, SpectralGenerator, SpectralScratch};
use crate::spectrum::{Domain, Spectrum};
use rand::rngs::Xoshiro256PlusPlus;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner};
use std::f64::consts::PI;
use std::sync::Arc;

/// A generator of pairs of periodic spatial tracks (left L, right R) with the same two-sided density
/// S(Ω) (Ω in rad/m, any spatial [`Spectrum`], e.g. an ISO 8608 [`PowerLaw`](crate::spectrum::PowerLaw)
/// with a band) and the cross-density S_LR = ρ S of a [`Coherence`] model.
///
/// # Formula
/// Grid and coefficients exactly as the single-track [`SpectralGenerator`] (its normalisation is reused:
/// the left track *is* the `SpectralGenerator` realization of the same stream):
/// ```text
/// N samples at step Δx (m),  ΔΩ = 2π/(NΔx),  Ω_j = jΔΩ,  n_j = j/(NΔx) cycles/m,  j = 0..=N/2
/// Z_j, W_j independent complex Gaussian, E Z_j = 0, E|Z_j|² = E|W_j|² = S(Ω_j)ΔΩ
///     (Re, Im ~ N(0, SΔΩ/2) for 0 < j < N/2;  real N(0, SΔΩ) at j = 0 and N/2: Rayleigh amplitudes)
/// c_L,j = Z_j,    c_R,j = ρ(n_j) Z_j + √(1 − ρ(n_j)²) W_j
/// x_k = Σ_{j=−N/2+1}^{N/2} c_j e^{iΩ_j kΔx}   (c_{−j} = conj c_j; one inverse real FFT per track)
/// ```
/// Second moments (W independent of Z): E[c_L,j conj c_R,j] = ρ_j S_j ΔΩ and E|c_R,j|² = (ρ_j² + 1 − ρ_j²)
/// S_j ΔΩ = S_j ΔΩ, so both tracks have the density S and their exact cross-covariance is
/// ```text
/// K_LR(mΔx) = E[x_L,k+m x_R,k] = Σ_{j two-sided} ρ_j S_j ΔΩ cos(Ω_j mΔx)   ([`TwoTrackGenerator::grid_cross_covariance`])
/// ```
/// **Cross-spectrum exact in expectation.** The DFT of one period is X_j = Σ_k x_k e^{−2πijk/N} = N c_j,
/// so the full-period cross-periodogram P_LR(Ω_j) = Δx/(2πN)·X_L,j conj X_R,j has
/// E P_LR(Ω_j) = (NΔx/2π)·ρ_j S_j ΔΩ = ρ_j S_j exactly, and E P_LL = E P_RR = S_j: the periodic
/// realization has no leakage, and the sample squared coherence estimates γ² = ρ². The coefficients carry
/// random (Rayleigh) amplitudes: each track is a Gaussian process; phase-only synthesis or mixing the
/// phases of two tracks (as some road generators do) gives neither ρ nor ρ² as the coherence.
///
/// ρ = 1 gives identical tracks (c_R = c_L bit for bit); ρ = 0 gives independent tracks (c_R = W).
/// The grid caveats of [`SpectralGenerator`] apply: the band |Ω| ≤ π/Δx only, resolution ΔΩ.
///
/// # Errors
/// [`TwoTrackGenerator::new`] rejects a temporal spectrum, Δx ≤ 0, N odd or < 2, a density that is
/// negative or not finite on the grid (e.g. a power law without a band: give the ISO band), and a
/// coherence outside [0, 1] on the grid, naming the frequency.
///
/// # Examples
/// ```
/// use stochvib::coherence::IsotropicCoherence;
/// use stochvib::road::TwoTrackGenerator;
/// use stochvib::simulate::stream;
/// use stochvib::spectrum::{IsoBound, IsoClass, PowerLaw};
/// let s = PowerLaw::iso8608(IsoClass::C, IsoBound::GeometricMean, Some((0.011, 10.0))).unwrap();
/// let rho = IsotropicCoherence::new(1.5, 2.0).unwrap();
/// let g = TwoTrackGenerator::new(&s, &rho, 0.05, 4096).unwrap();
/// let (mut left, mut right) = (vec![0.0; 4096], vec![0.0; 4096]);
/// g.generate(&mut stream(7, 0), &mut g.scratch(), &mut left, &mut right).unwrap();
/// // zero lag: K_LR(0) ≤ the variance of either track
/// assert!(g.grid_cross_covariance(0) < g.grid_variance());
/// ```
#[derive(Clone)]
pub struct TwoTrackGenerator {
    single: SpectralGenerator,
    /// ρ(n_j), j = 0..=N/2.
    rho: Vec<f64>,
    /// √(1 − ρ_j²).
    rho_c: Vec<f64>,
    /// S(Ω_j)ΔΩ, the same products the single-track generator takes the square root of.
    s_dw: Vec<f64>,
    plan: Arc<dyn ComplexToReal<f64>>,
    description: String,
}

impl std::fmt::Debug for TwoTrackGenerator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TwoTrackGenerator")
            .field("single", &self.single)
            .field("coherence", &self.description)
            .finish()
    }
}

/// Working memory of a [`TwoTrackGenerator`] (reused across realizations).
#[derive(Debug, Clone)]
pub struct TwoTrackScratch {
    spectral: SpectralScratch,
    left: Vec<Complex<f64>>,
    right: Vec<Complex<f64>>,
    buf: Vec<Complex<f64>>,
    fft: Vec<Complex<f64>>,
}

impl TwoTrackScratch {
    /// The coefficients c_L,j and c_R,j (j = 0..=N/2) of the last [`TwoTrackGenerator::draw`].
    pub fn coefficients(&self) -> (&[Complex<f64>], &[Complex<f64>]) {
        (&self.left, &self.right)
    }
}

impl TwoTrackGenerator {
    /// Prepares the grid of N = `n` samples at step `dx_m` (m) for the spatial spectrum `spectrum` and the
    /// coherence model `coherence`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(spectrum: &dyn Spectrum, coherence: &dyn Coherence, dx_m: f64, n: usize) -> Result<Self> {
        if spectrum.domain() != Domain::Spatial {
            return Err(Error::invalid(
                "spectrum",
                spectrum.describe(),
                "two road tracks need a spatial spectrum (Ω in rad/m)",
            ));
        }
        require_positive("dx", dx_m)?;
        let single = SpectralGenerator::new(spectrum, dx_m, n, Amplitudes::Rayleigh)?;
        let dn = 1.0 / (n as f64 * dx_m);
        let dw = single.d_omega();
        let s_dw = (0..=n / 2).map(|j| spectrum.density(j as f64 * dw) * dw).collect();
        let mut rho = Vec::with_capacity(n / 2 + 1);
        let mut rho_c = Vec::with_capacity(n / 2 + 1);
        for j in 0..=n / 2 {
            let nj = j as f64 * dn;
            let r = coherence.coherence_amplitude(nj);
            if !(r.is_finite() && (0.0..=1.0).contains(&r)) {
                return Err(Error::invalid(
                    "coherence",
                    coherence.describe(),
                    format!("coherence amplitude at n = {nj:e} cycles/m is {r}; need a value in [0, 1]"),
                ));
            }
            rho.push(r);
            rho_c.push((1.0 - r * r).max(0.0).sqrt());
        }
        Ok(TwoTrackGenerator {
            single,
            rho,
            rho_c,
            s_dw,
            plan: RealFftPlanner::<f64>::new().plan_fft_inverse(n),
            description: coherence.describe(),
        })
    }

    /// Number of samples N per track.
    pub fn len(&self) -> usize {
        self.single.len()
    }
    /// Always false (N ≥ 2).
    pub fn is_empty(&self) -> bool {
        false
    }
    /// Distance step Δx in m.
    pub fn dx(&self) -> f64 {
        self.single.dt()
    }
    /// Grid spacing ΔΩ = 2π/(NΔx) in rad/m.
    pub fn d_omega(&self) -> f64 {
        self.single.d_omega()
    }
    /// The coherence amplitudes ρ(n_j) used on the grid, n_j = j/(NΔx), j = 0..=N/2.
    pub fn coherence_on_grid(&self) -> &[f64] {
        &self.rho
    }
    /// The single-track generator (same grid, same normalisation; the left track's generator).
    pub fn single_track(&self) -> &SpectralGenerator {
        &self.single
    }
    /// Exact variance of each track, D_N (see [`SpectralGenerator::grid_variance`]).
    pub fn grid_variance(&self) -> f64 {
        self.single.grid_variance()
    }
    /// Exact autocovariance of each track at lag mΔx (see [`SpectralGenerator::grid_autocovariance`]).
    pub fn grid_autocovariance(&self, m: i64) -> f64 {
        self.single.grid_autocovariance(m)
    }
    /// Exact cross-covariance K_LR(mΔx) = E[x_L,k+m x_R,k] = Σ_j w_j ρ_j S_j ΔΩ cos(2πjm/N), w_j = 1 at j = 0
    /// and N/2, 2 otherwise. Even in m because ρ is real.
    pub fn grid_cross_covariance(&self, m: i64) -> f64 {
        let n = self.len();
        let mut k = 0.0;
        for (j, (r, s)) in self.rho.iter().zip(&self.s_dw).enumerate() {
            let weight = if j == 0 || j == n / 2 { 1.0 } else { 2.0 };
            let arg = 2.0 * PI * ((j as i64 * m).rem_euclid(n as i64)) as f64 / n as f64;
            k += weight * r * s * arg.cos();
        }
        k
    }

    /// Fresh working memory.
    pub fn scratch(&self) -> TwoTrackScratch {
        let h = self.len() / 2 + 1;
        TwoTrackScratch {
            spectral: self.single.scratch(),
            left: vec![Complex::new(0.0, 0.0); h],
            right: vec![Complex::new(0.0, 0.0); h],
            buf: vec![Complex::new(0.0, 0.0); h],
            fft: vec![Complex::new(0.0, 0.0); self.plan.get_scratch_len()],
        }
    }

    /// Draws the coefficients c_L and c_R of one realization into `scratch` (see the type's formula): the
    /// draws of [`SpectralGenerator::draw`] for Z (left), then for W, from `rng`.
    ///
    /// # Errors
    /// A scratch made by another generator.
    pub fn draw(&self, rng: &mut Xoshiro256PlusPlus, scratch: &mut TwoTrackScratch) -> Result<()> {
        let h = self.len() / 2 + 1;
        if scratch.left.len() != h || scratch.buf.len() != h || scratch.spectral.coefficients().len() != h {
            return Err(Error::invalid(
                "scratch",
                scratch.left.len(),
                "made by a generator of another length",
            ));
        }
        self.single.draw(rng, &mut scratch.spectral);
        scratch.left.copy_from_slice(scratch.spectral.coefficients());
        self.single.draw(rng, &mut scratch.spectral);
        for (j, ((r, z), w)) in scratch
            .right
            .iter_mut()
            .zip(&scratch.left)
            .zip(scratch.spectral.coefficients())
            .enumerate()
        {
            *r = z * self.rho[j] + w * self.rho_c[j];
        }
        Ok(())
    }

    /// Writes one realization of both tracks (N samples each, elevations in the unit of the spectrum,
    /// e.g. m) into `left` and `right`.
    ///
    /// # Errors
    /// `left` or `right` not of length N; a scratch made by another generator.
    pub fn generate(
        &self,
        rng: &mut Xoshiro256PlusPlus,
        scratch: &mut TwoTrackScratch,
        left: &mut [f64],
        right: &mut [f64],
    ) -> Result<()> {
        let n = self.len();
        if left.len() != n || right.len() != n {
            return Err(Error::invalid(
                "tracks",
                format!("{} and {} samples", left.len(), right.len()),
                format!("need N = {n} samples per track"),
            ));
        }
        if scratch.fft.len() != self.plan.get_scratch_len() {
            return Err(Error::invalid(
                "scratch",
                scratch.fft.len(),
                "made by another generator",
            ));
        }
        self.draw(rng, scratch)?;
        let fft_err = |e: realfft::FftError| Error::Numerical {
            what: "inverse real FFT".into(),
            reason: e.to_string(),
        };
        // the FFT consumes its input: transform copies so that `coefficients()` stays readable
        scratch.buf.copy_from_slice(&scratch.left);
        self.plan
            .process_with_scratch(&mut scratch.buf, left, &mut scratch.fft)
            .map_err(fft_err)?;
        scratch.buf.copy_from_slice(&scratch.right);
        self.plan
            .process_with_scratch(&mut scratch.buf, right, &mut scratch.fft)
            .map_err(fft_err)
    }
}
