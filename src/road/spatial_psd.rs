//! Spatial spectral estimates of measured tracks: the one-sided ISO 8608 density G_d(n) of one track
//! (Welch, via [`crate::estimate::Welch`]), and the cross-spectrum and squared coherence of two tracks.

use crate::error::{require_positive, Error, Result};
use crate::estimate::{Interval, VarianceEstimate, Welch};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use statrs::distribution::{ContinuousCDF, Normal};
use std::f64::consts::PI;

/// A Welch estimate of the one-sided spatial density G_d(n) of one track, in m³ at n in cycles/m.
///
/// # Formula
/// [`Welch`] (periodic Hann window of M samples, 50 % overlap, K segments) applied with the distance step
/// Δx as its "time" step returns the canonical two-sided angular density Ŝ(Ω_j), Ω_j = 2πj/(MΔx) rad/m.
/// The exact conversion to ISO 8608's one-sided density in cycles/m is
/// ```text
/// n_j = j/(MΔx) cycles/m,    Ĝ_d(n_j) = 4π Ŝ(2π n_j)  m³,    j = 1 … M/2 − 1
/// ```
/// (the bins n = 0 and n = 1/(2Δx), where the periodogram is χ²₁ and the one-sided density is not
/// doubled, are left out). Ĝ_d/G_d is approximately χ²_ν/ν with Welch's equivalent ν = 2K²/(K + 2(K−1)/36)
/// ([`Welch`]); [`SpatialPsd::interval`] gives the χ² interval. The mean of the estimate is the density
/// smoothed by the window (about ±2 bins), which matters where G_d is steep: for a power law the lowest
/// bins (within ~3 bins of n = 0) are dominated by the window's main lobe at n = 0.
///
/// Remove the mean or a trend first ([`Detrend`](super::Detrend)): a trend leaks into the lowest bins.
///
/// # Errors
/// [`spatial_psd`] rejects Δx ≤ 0, M odd or < 4, a record shorter than M, non-finite elevations.
///
/// # Examples
/// ```
/// use stochvib::road::spatial_psd;
/// use stochvib::simulate::{standard_normal, stream};
/// // unit-variance white noise at step 0.1 m has G_d = 2Δx = 0.2 m³ at every n
/// let mut rng = stream(1, 0);
/// let x: Vec<f64> = (0..8192).map(|_| standard_normal(&mut rng)).collect();
/// let p = spatial_psd(&x, 0.1, 256).unwrap();
/// assert_eq!(p.n[0], 1.0 / (256.0 * 0.1));
/// let mean = p.g_d.iter().sum::<f64>() / p.g_d.len() as f64;
/// assert!((mean - 0.2).abs() < 0.02);         // about 6 standard errors
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialPsd {
    /// n_j = j/(MΔx), cycles/m, j = 1 … M/2 − 1.
    pub n: Vec<f64>,
    /// Ĝ_d(n_j), m³ (one-sided, per cycle/m).
    pub g_d: Vec<f64>,
    /// Number of averaged segments K.
    pub segments: u64,
    /// Welch's equivalent degrees of freedom ν of each bin.
    pub dof: f64,
    /// The nominal 2K.
    pub nominal_dof: f64,
    /// Distance step Δx, m.
    pub step_m: f64,
    /// Segment length M, samples.
    pub segment_len: usize,
}

impl SpatialPsd {
    /// Frequency resolution Δn = 1/(MΔx), cycles/m.
    pub fn resolution(&self) -> f64 {
        1.0 / (self.segment_len as f64 * self.step_m)
    }

    /// The χ² interval of bin i (index into [`SpatialPsd::n`]): [νĜ/χ²_{ν,1−p/2}, νĜ/χ²_{ν,p/2}].
    ///
    /// # Errors
    /// i out of range, confidence ∉ (0, 1).
    pub fn interval(&self, i: usize, confidence: f64) -> Result<Interval> {
        let g = *self
            .g_d
            .get(i)
            .ok_or_else(|| Error::invalid("bin", i, format!("have {} bins", self.g_d.len())))?;
        VarianceEstimate {
            variance: g,
            dof: self.dof,
        }
        .interval(confidence)
    }

    /// Correlation between the estimates at two bins `d` apart, for a locally flat density (Gaussian data,
    /// the window's exact leakage; Percival & Walden 1993, §6.17, for the overlapped Welch average).
    ///
    /// # Formula
    /// With A_d = Σ_k w_k² e^{−2πidk/M}/Σw² (same segment) and B_d = Σ_{k<M/2} w_k w_{k+M/2} e^{−2πidk/M}/Σw²
    /// (half-overlapping segments):
    /// ```text
    /// r_d = (K|A_d|² + 2(K − 1)|B_d|²) / (K + 2(K − 1)|B_0|²)      (Hann: r_1 ≈ 0.46, r_2 ≈ 0.03 for large K)
    /// ```
    pub fn bin_correlation(&self, d: usize) -> f64 {
        bin_correlation(self.segment_len, self.segments as f64, d)
    }
}

/// r_d of [`SpatialPsd::bin_correlation`] for segment length m and k segments.
pub(crate) fn bin_correlation(m: usize, k: f64, d: usize) -> f64 {
    let w: Vec<f64> = (0..m)
        .map(|i| 0.5 * (1.0 - (2.0 * PI * i as f64 / m as f64).cos()))
        .collect();
    let norm: f64 = w.iter().map(|v| v * v).sum();
    let phase = |i: usize| {
        let a = -2.0 * PI * ((d * i) % m) as f64 / m as f64;
        Complex::new(a.cos(), a.sin())
    };
    let a: Complex<f64> = (0..m).map(|i| phase(i) * (w[i] * w[i])).sum::<Complex<f64>>() / norm;
    let b: Complex<f64> = (0..m / 2)
        .map(|i| phase(i) * (w[i] * w[i + m / 2]))
        .sum::<Complex<f64>>()
        / norm;
    let b0: f64 = (0..m / 2).map(|i| w[i] * w[i + m / 2]).sum::<f64>() / norm;
    (k * a.norm_sqr() + 2.0 * (k - 1.0) * b.norm_sqr()) / (k + 2.0 * (k - 1.0) * b0 * b0)
}

fn check_track(name: &str, x: &[f64]) -> Result<()> {
    if let Some(k) = x.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            &format!("{name}[{k}]"),
            x[k],
            "elevation must be finite",
        ));
    }
    Ok(())
}

/// The Welch estimate of the one-sided spatial density G_d(n) of a track (see [`SpatialPsd`]).
///
/// # Errors
/// See [`SpatialPsd`].
pub fn spatial_psd(elevation_m: &[f64], step_m: f64, segment_len: usize) -> Result<SpatialPsd> {
    require_positive("step", step_m)?;
    check_track("elevation", elevation_m)?;
    let welch = Welch::new(segment_len, step_m)?;
    let est = welch.estimate(elevation_m)?;
    let m = segment_len;
    Ok(SpatialPsd {
        n: (1..m / 2).map(|j| est.omega[j] / (2.0 * PI)).collect(),
        g_d: (1..m / 2).map(|j| 4.0 * PI * est.density[j]).collect(),
        segments: est.segments,
        dof: est.dof,
        nominal_dof: est.nominal_dof,
        step_m,
        segment_len,
    })
}

/// Welch estimates of the auto- and cross-densities of two parallel tracks (one-sided, m³, n in
/// cycles/m) and their squared coherence.
///
/// # Formula
/// Same segments, Hann window and normalisation as [`Welch`] (which has no cross-spectrum; the auto
/// densities are Welch's own, the cross term repeats its window and scaling, and a test checks that the
/// cross term of a track with itself equals Welch's auto density):
/// ```text
/// Ĝ_LR(n_j) = (2Δx/(K Σw²)) Σ_s X_L^{(s)}(j) conj X_R^{(s)}(j),   X^{(s)}(j) = Σ_k w_k x_{sM/2+k} e^{−2πijk/M}
/// γ̂²(n_j) = |Ĝ_LR|² / (Ĝ_LL Ĝ_RR)
/// ```
/// This is the estimate of G_LR with K_LR(τ) = E[x_L(s + τ) x_R(s)], so that S_LR = ρS for the
/// two-track model (real when ρ is).
///
/// **Bias and interval of γ̂².** For K independent segments and Gaussian data γ̂² is biased upward:
/// E γ̂² ≈ γ² + (1 − γ²)²/K (Carter, Knapp & Nuttall 1973, "Estimation of the magnitude-squared coherence
/// function via overlapped FFT processing", IEEE Trans. Audio Electroacoust. AU-21(4)); at γ² = 0 exactly
/// 1/K. With 50 % overlap the segments are correlated; K is replaced by K_e = ν/2 (ν Welch's equivalent
/// degrees of freedom), an approximation that Carter et al. found adequate for Hann windows.
/// [`SpatialCrossSpectrum::squared_coherence_interval`] uses the Fisher z-transform of |γ̂|
/// (Enochson & Goodman 1965; Bendat & Piersol, "Random Data", 4th ed. 2010, ch. 9):
/// ```text
/// z = atanh|γ̂| ≈ N(atanh|γ| + 1/(2(K_e − 1)), 1/(2(K_e − 1)))
/// |γ| ∈ [tanh(z − b − q σ), tanh(z − b + q σ)]  (lower end clipped at 0),  squared for γ²
/// ```
/// with b = 1/(2(K_e − 1)), σ = 1/√(2(K_e − 1)), q the normal quantile; approximate, best for K_e ≳ 10.
///
/// # Errors
/// [`spatial_cross_spectrum`]: tracks of different lengths, non-finite values, and the errors of
/// [`spatial_psd`].
///
/// # Examples
/// ```
/// use stochvib::road::spatial_cross_spectrum;
/// let x: Vec<f64> = (0..4096u64).map(|k| ((k.wrapping_mul(2654435761) % 1000) as f64 - 499.5)).collect();
/// let c = spatial_cross_spectrum(&x, &x, 0.05, 256).unwrap();
/// // a track with itself: G_LR = G_LL, γ̂² = 1
/// assert!(c.squared_coherence().iter().all(|g| (g - 1.0).abs() < 1e-12));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialCrossSpectrum {
    /// n_j = j/(MΔx), cycles/m, j = 1 … M/2 − 1.
    pub n: Vec<f64>,
    /// Ĝ_LL(n_j), m³.
    pub g_ll: Vec<f64>,
    /// Ĝ_RR(n_j), m³.
    pub g_rr: Vec<f64>,
    /// Ĝ_LR(n_j), m³ (complex).
    pub g_lr: Vec<Complex<f64>>,
    /// Number of averaged segments K.
    pub segments: u64,
    /// Welch's equivalent degrees of freedom ν.
    pub dof: f64,
    /// Distance step Δx, m.
    pub step_m: f64,
    /// Segment length M, samples.
    pub segment_len: usize,
}

impl SpatialCrossSpectrum {
    /// γ̂²(n_j) = |Ĝ_LR|²/(Ĝ_LL Ĝ_RR) at every bin (see the type's formula for its bias).
    pub fn squared_coherence(&self) -> Vec<f64> {
        self.g_lr
            .iter()
            .zip(self.g_ll.iter().zip(&self.g_rr))
            .map(|(lr, (ll, rr))| (lr.norm_sqr() / (ll * rr)).min(1.0))
            .collect()
    }

    /// The equivalent number of independent segments K_e = ν/2.
    pub fn effective_segments(&self) -> f64 {
        self.dof / 2.0
    }

    /// The Fisher-z interval of γ² at bin i (see the type's formula).
    ///
    /// # Errors
    /// i out of range, confidence ∉ (0, 1), K_e ≤ 1.5 (with one segment γ̂² ≡ 1).
    pub fn squared_coherence_interval(&self, i: usize, confidence: f64) -> Result<Interval> {
        if !(confidence > 0.0 && confidence < 1.0) {
            return Err(Error::invalid("confidence", confidence, "must be in (0, 1)"));
        }
        let lr = self
            .g_lr
            .get(i)
            .ok_or_else(|| Error::invalid("bin", i, format!("have {} bins", self.g_lr.len())))?;
        let ke = self.effective_segments();
        if ke <= 1.5 {
            return Err(Error::invalid(
                "segments",
                self.segments,
                "the coherence of fewer than two segments is identically 1; use a shorter segment",
            ));
        }
        let g2 = (lr.norm_sqr() / (self.g_ll[i] * self.g_rr[i])).min(1.0);
        let z = g2.sqrt().atanh();
        let var = 1.0 / (2.0 * (ke - 1.0));
        let q = Normal::new(0.0, 1.0)
            .map_err(|e| Error::Numerical {
                what: "normal quantile".into(),
                reason: e.to_string(),
            })?
            .inverse_cdf(0.5 + 0.5 * confidence);
        let centre = z - var;
        let lo = (centre - q * var.sqrt()).max(0.0).tanh();
        let hi = (centre + q * var.sqrt()).max(0.0).tanh();
        Ok(Interval {
            estimate: g2,
            lower: lo * lo,
            upper: if z.is_infinite() { 1.0 } else { hi * hi },
            confidence,
        })
    }
}

/// Welch auto- and cross-spectra of two tracks (see [`SpatialCrossSpectrum`]).
///
/// # Errors
/// See [`SpatialCrossSpectrum`].
pub fn spatial_cross_spectrum(
    left_m: &[f64],
    right_m: &[f64],
    step_m: f64,
    segment_len: usize,
) -> Result<SpatialCrossSpectrum> {
    if left_m.len() != right_m.len() {
        return Err(Error::invalid(
            "tracks",
            format!("{} and {} samples", left_m.len(), right_m.len()),
            "the two tracks must have the same length",
        ));
    }
    check_track("right", right_m)?;
    let ll = spatial_psd(left_m, step_m, segment_len)?;
    let rr = spatial_psd(right_m, step_m, segment_len)?;
    let m = segment_len;
    let window: Vec<f64> = (0..m)
        .map(|k| 0.5 * (1.0 - (2.0 * PI * k as f64 / m as f64).cos()))
        .collect();
    let norm: f64 = window.iter().map(|w| w * w).sum();
    let plan = RealFftPlanner::<f64>::new().plan_fft_forward(m);
    let mut input = vec![0.0; m];
    let mut xl = vec![Complex::new(0.0, 0.0); m / 2 + 1];
    let mut xr = xl.clone();
    let mut scratch = vec![Complex::new(0.0, 0.0); plan.get_scratch_len()];
    let mut sum = vec![Complex::new(0.0, 0.0); m / 2 + 1];
    let k = Welch::new(m, step_m)?.segments_in(left_m.len());
    let fft_err = |e: realfft::FftError| Error::Numerical {
        what: "forward real FFT".into(),
        reason: e.to_string(),
    };
    for s in 0..k {
        let off = s * m / 2;
        for ((d, v), w) in input.iter_mut().zip(&left_m[off..off + m]).zip(&window) {
            *d = v * w;
        }
        plan.process_with_scratch(&mut input, &mut xl, &mut scratch)
            .map_err(fft_err)?;
        for ((d, v), w) in input.iter_mut().zip(&right_m[off..off + m]).zip(&window) {
            *d = v * w;
        }
        plan.process_with_scratch(&mut input, &mut xr, &mut scratch)
            .map_err(fft_err)?;
        for ((a, l), r) in sum.iter_mut().zip(&xl).zip(&xr) {
            *a += l * r.conj();
        }
    }
    // two-sided Ŝ = Δx/(2π Σw²)·avg, one-sided G = 4π Ŝ = 2Δx/Σw²·avg
    let scale = 2.0 * step_m / (norm * k as f64);
    Ok(SpatialCrossSpectrum {
        n: ll.n,
        g_ll: ll.g_d,
        g_rr: rr.g_d,
        g_lr: (1..m / 2).map(|j| sum[j] * scale).collect(),
        segments: ll.segments,
        dof: ll.dof,
        step_m,
        segment_len,
    })
}

/// Fewest samples of a track whose density is estimated: one Welch segment of 16 samples (the smallest
/// default segment, [`default_segment`]), whose bins n = 1/(16Δx) … 7/(16Δx) are the least an ISO 8608 fit
/// can be tried on.
pub const MIN_DENSITY_SAMPLES: usize = 16;

/// A track is flat when, after its trend is removed, its σ is at most this fraction of its largest
/// elevation: what is left is the rounding noise of the numbers (a double resolves about 10⁻¹⁶ of a value,
/// the detrending adds a few roundings), four decades below this, not a roughness.
pub const FLAT_FRACTION: f64 = 1e-12;

/// A track whose largest |elevation| (m) is below this, and not 0, is refused: the squares in its density
/// (10⁻²⁰⁰ and below) approach the smallest normal f64 (2.2·10⁻³⁰⁸) once a window and a segment's sums
/// scale them. No road comes near it; such a track is a unit error.
pub const MIN_PEAK_ELEVATION_M: f64 = 1e-100;

/// Refuses a track of a profile file `file` whose density cannot be estimated or fitted: fewer than
/// [`MIN_DENSITY_SAMPLES`] samples, all its elevations below [`MIN_PEAK_ELEVATION_M`] in magnitude, or flat (`detrended` — the track after its trend is removed — has
/// σ ≤ [`FLAT_FRACTION`]·max|`raw`|: a constant or a straight line, whose "density" would be rounding
/// noise fitted as a road of class A).
///
/// # Errors
/// [`Error::File`] naming the file and the track, with the number of rows or the σ and the largest
/// elevation.
///
/// # Examples
/// ```
/// use stochvib::road::spatial_psd::check_density_input;
/// let f = std::path::Path::new("p.csv");
/// let ramp: Vec<f64> = (0..1000).map(|k| 1e-3 + 1e-6 * k as f64).collect();
/// let detrended = stochvib::road::Detrend::Linear.apply(&ramp);
/// let e = check_density_input(f, "left", &ramp, &detrended).unwrap_err().to_string();
/// assert!(e.contains("flat"), "{e}");
/// let e = check_density_input(f, "left", &ramp[..2], &detrended[..2]).unwrap_err().to_string();
/// assert!(e.contains("2 rows"), "{e}");
/// ```
pub fn check_density_input(file: &std::path::Path, track: &str, raw: &[f64], detrended: &[f64]) -> Result<()> {
    let key = format!("column {track}");
    if raw.len() < MIN_DENSITY_SAMPLES {
        return Err(Error::in_file(
            file,
            key,
            format!("{} rows", raw.len()),
            format!(
                "too few rows: a density needs at least {MIN_DENSITY_SAMPLES} samples (one Welch segment of \
                 {MIN_DENSITY_SAMPLES}); give a longer profile"
            ),
        ));
    }
    let peak = raw.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if peak > 0.0 && peak < MIN_PEAK_ELEVATION_M {
        return Err(Error::in_file(
            file,
            key,
            format!("largest |elevation| {peak:e} m"),
            format!(
                "every elevation is below {MIN_PEAK_ELEVATION_M:e} m in magnitude: their squares approach the \
                 smallest numbers of f64, so the density would be rounding; check the column's unit"
            ),
        ));
    }
    let sigma = (detrended.iter().map(|v| v * v).sum::<f64>() / detrended.len() as f64).sqrt();
    if sigma <= FLAT_FRACTION * peak || peak == 0.0 {
        return Err(Error::in_file(
            file,
            key,
            format!("σ = {sigma:e} m after the trend, largest |elevation| {peak:e} m"),
            format!(
                "the track is flat (a constant or a straight line): what is left after its trend is removed is \
                 at most {FLAT_FRACTION:e} of its elevations, the rounding noise of its numbers; it has no \
                 roughness whose density could be estimated or fitted (a flat track is not a road of ISO 8608 \
                 class A)"
            ),
        ));
    }
    Ok(())
}

/// The default Welch segment for `samples` samples: the largest power of two M ≥ 16 with
/// M ≤ 2·samples/9, i.e. at least 8 half-overlapping segments (for fewer than 72 samples: 16, or the
/// largest even number ≤ samples).
///
/// # Formula
/// K = ⌊(N − M)/(M/2)⌋ + 1 ≥ 8 ⇔ M ≤ 2N/9.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// assert_eq!(stochvib::road::default_segment(10_000), 2048);
/// ```
pub fn default_segment(samples: usize) -> usize {
    let cap = 2 * samples / 9;
    let mut m = 16;
    while m * 2 <= cap {
        m *= 2;
    }
    if m > samples {
        samples - samples % 2
    } else {
        m
    }
}
