//! Cross-spectral density and coherence of two records by averaged periodograms, with intervals.

use super::interval::Interval;
use crate::error::{require_positive, Error, Result};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use statrs::distribution::{ContinuousCDF, Normal};
use std::f64::consts::PI;

/// Auto- and cross-spectral densities of two simultaneous records x, y (the canonical two-sided angular
/// convention), averaged over non-overlapping Hann-windowed segments, with the number of averages n_d.
///
/// # Formula
/// Segments s = 0..n_d of M samples, w_k = ½(1 − cos 2πk/M), X_s(ω_j) = Σ_k w_k x_{sM+k} e^{−iω_j kΔt},
/// ω_j = 2πj/(MΔt), j = 0..=M/2:
/// ```text
/// Ŝ_xy(ω_j) = (1/n_d) Σ_s Δt/(2π Σ_k w_k²) · X_s conj(Y_s),    S_xy(ω) = (1/2π)∫ E[x(t+τ) y(t)] e^{−iωτ} dτ
/// γ̂²(ω_j) = |Ŝ_xy|² / (Ŝ_xx Ŝ_yy)
/// ```
/// (Bendat & Piersol, *Random Data*, 4th ed., 2010, §9.2: the co-spectrum Ĉ = Re Ŝ_xy has variance
/// (S_xx S_yy + C² − Q²)/(2n_d), Q = Im S_xy, and tanh⁻¹|γ̂| is approximately normal with mean
/// tanh⁻¹|γ| + 1/(2(n_d − 1)) and variance 1/(2(n_d − 1)), §9.2.3.) Non-overlapping segments keep the
/// averages independent for segments much longer than the correlation time; records of independent
/// realizations add their segments ([`CrossSpectrum::merge`]).
///
/// # Errors
/// [`cross_spectrum`]: records of different lengths, M odd or < 4, a record shorter than M, Δt ≤ 0.
///
/// # Examples
/// ```
/// use stochvib::estimate::cross_spectrum;
/// let x: Vec<f64> = (0..4096).map(|k| ((k * 7919) % 101) as f64 - 50.0).collect();
/// let c = cross_spectrum(&x, &x, 128, 0.01).unwrap();
/// assert_eq!(c.segments, 32);
/// assert!((c.squared_coherence(5) - 1.0).abs() < 1e-12); // a record is fully coherent with itself
/// ```
#[derive(Debug, Clone)]
pub struct CrossSpectrum {
    /// ω_j, rad/s.
    pub omega: Vec<f64>,
    /// Ŝ_xx(ω_j), two-sided.
    pub s_xx: Vec<f64>,
    /// Ŝ_yy(ω_j), two-sided.
    pub s_yy: Vec<f64>,
    /// Ŝ_xy(ω_j), two-sided.
    pub s_xy: Vec<Complex<f64>>,
    /// Number of averaged segments n_d.
    pub segments: usize,
}

/// Estimates [`CrossSpectrum`] from records `x`, `y` sampled at `dt` s, segments of `segment_len` samples.
///
/// # Formula
/// See [`CrossSpectrum`].
///
/// # Errors
/// See [`CrossSpectrum`].
///
/// # Examples
/// See [`CrossSpectrum`].
pub fn cross_spectrum(x: &[f64], y: &[f64], segment_len: usize, dt: f64) -> Result<CrossSpectrum> {
    require_positive("dt", dt)?;
    let m = segment_len;
    if m < 4 || !m.is_multiple_of(2) {
        return Err(Error::invalid("segment_len", m, "must be even and >= 4"));
    }
    if x.len() != y.len() {
        return Err(Error::invalid(
            "y",
            format!("{} samples", y.len()),
            format!("x has {} samples: the records must be simultaneous", x.len()),
        ));
    }
    let nd = x.len() / m;
    if nd == 0 {
        return Err(Error::invalid(
            "x",
            format!("{} samples", x.len()),
            format!("shorter than one segment ({m})"),
        ));
    }
    let w: Vec<f64> = (0..m)
        .map(|k| 0.5 * (1.0 - (2.0 * PI * k as f64 / m as f64).cos()))
        .collect();
    let norm = dt / (2.0 * PI * w.iter().map(|v| v * v).sum::<f64>());
    let fft = RealFftPlanner::<f64>::new().plan_fft_forward(m);
    let half = m / 2 + 1;
    let (mut sxx, mut syy, mut sxy) = (vec![0.0; half], vec![0.0; half], vec![Complex::new(0.0, 0.0); half]);
    let (mut bx, mut by) = (vec![0.0; m], vec![0.0; m]);
    let (mut fx, mut fy) = (vec![Complex::new(0.0, 0.0); half], vec![Complex::new(0.0, 0.0); half]);
    let fft_err = |e: realfft::FftError| Error::Numerical {
        what: "cross-spectrum FFT".into(),
        reason: e.to_string(),
    };
    for s in 0..nd {
        for k in 0..m {
            bx[k] = w[k] * x[s * m + k];
            by[k] = w[k] * y[s * m + k];
        }
        fft.process(&mut bx, &mut fx).map_err(fft_err)?;
        fft.process(&mut by, &mut fy).map_err(fft_err)?;
        for j in 0..half {
            sxx[j] += fx[j].norm_sqr() * norm;
            syy[j] += fy[j].norm_sqr() * norm;
            sxy[j] += fx[j] * fy[j].conj() * norm;
        }
    }
    let f = 1.0 / nd as f64;
    Ok(CrossSpectrum {
        omega: (0..half).map(|j| 2.0 * PI * j as f64 / (m as f64 * dt)).collect(),
        s_xx: sxx.iter().map(|v| v * f).collect(),
        s_yy: syy.iter().map(|v| v * f).collect(),
        s_xy: sxy.iter().map(|v| v * f).collect(),
        segments: nd,
    })
}

impl CrossSpectrum {
    /// γ̂²(ω_j) (0 where an auto-density vanishes).
    pub fn squared_coherence(&self, j: usize) -> f64 {
        let d = self.s_xx[j] * self.s_yy[j];
        if d > 0.0 {
            (self.s_xy[j].norm_sqr() / d).min(1.0)
        } else {
            0.0
        }
    }

    /// Pools the averages of another estimate on the same grid (an independent realization).
    ///
    /// # Errors
    /// Different grids.
    pub fn merge(&mut self, other: &CrossSpectrum) -> Result<()> {
        if self.omega != other.omega {
            return Err(Error::invalid(
                "cross spectrum",
                "other grid",
                "can only merge estimates on the same grid",
            ));
        }
        let (a, b) = (self.segments as f64, other.segments as f64);
        let t = a + b;
        for j in 0..self.omega.len() {
            self.s_xx[j] = (a * self.s_xx[j] + b * other.s_xx[j]) / t;
            self.s_yy[j] = (a * self.s_yy[j] + b * other.s_yy[j]) / t;
            self.s_xy[j] = (self.s_xy[j] * a + other.s_xy[j] * b) / t;
        }
        self.segments += other.segments;
        Ok(())
    }

    /// Interval for the squared coherence γ²(ω_j) by Fisher's z (Bendat & Piersol 2010, §9.2.3).
    ///
    /// # Formula
    /// z = tanh⁻¹|γ̂| − 1/(2(n_d − 1)), σ_z = 1/√(2(n_d − 1)), interval tanh²(z ∓ q σ_z) with q the
    /// normal quantile of (1 + confidence)/2 (ends clamped to [0, 1]). The approximation needs n_d ≳ 20 and
    /// γ² not near 0 (for γ = 0, E γ̂² ≈ 1/n_d).
    ///
    /// # Errors
    /// Fewer than 3 segments; confidence outside (0, 1); j out of range.
    pub fn coherence_interval(&self, j: usize, confidence: f64) -> Result<Interval> {
        let q = self.quantile(j, confidence)?;
        let g2 = self.squared_coherence(j);
        let nd = self.segments as f64;
        let sz = 1.0 / (2.0 * (nd - 1.0)).sqrt();
        let z = g2.sqrt().min(1.0 - f64::EPSILON).atanh() - 1.0 / (2.0 * (nd - 1.0));
        let end = |v: f64| {
            let t = v.max(0.0).tanh();
            t * t
        };
        Ok(Interval {
            estimate: g2,
            lower: end(z - q * sz),
            upper: end(z + q * sz),
            confidence,
        })
    }

    /// Interval for the co-spectrum Re S_xy(ω_j) (normal approximation, Bendat & Piersol 2010, §9.2).
    ///
    /// # Formula
    /// Ĉ ± q √((Ŝ_xx Ŝ_yy + Ĉ² − Q̂²)/(2 n_d)), Q̂ = Im Ŝ_xy.
    ///
    /// # Errors
    /// As [`CrossSpectrum::coherence_interval`].
    pub fn co_spectrum_interval(&self, j: usize, confidence: f64) -> Result<Interval> {
        let q = self.quantile(j, confidence)?;
        let (c, qq) = (self.s_xy[j].re, self.s_xy[j].im);
        let sd = ((self.s_xx[j] * self.s_yy[j] + c * c - qq * qq).max(0.0) / (2.0 * self.segments as f64)).sqrt();
        Ok(Interval {
            estimate: c,
            lower: c - q * sd,
            upper: c + q * sd,
            confidence,
        })
    }

    fn quantile(&self, j: usize, confidence: f64) -> Result<f64> {
        if j >= self.omega.len() {
            return Err(Error::invalid("bin", j, format!("there are {} bins", self.omega.len())));
        }
        if self.segments < 3 {
            return Err(Error::invalid(
                "segments",
                self.segments,
                "need at least 3 averages for an interval",
            ));
        }
        if !(confidence > 0.0 && confidence < 1.0) {
            return Err(Error::invalid("confidence", confidence, "must lie in (0, 1)"));
        }
        let n = Normal::new(0.0, 1.0).map_err(|e| Error::Numerical {
            what: "normal quantile".into(),
            reason: e.to_string(),
        })?;
        Ok(n.inverse_cdf(0.5 + confidence / 2.0))
    }
}
