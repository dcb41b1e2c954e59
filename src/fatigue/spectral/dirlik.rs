//! Dirlik (1985): the empirical rainflow amplitude density (one exponential and two Rayleigh terms).

use super::gamma::{limit, ln_upper_gamma};
use super::narrow_band::narrow_band_rate;
use super::{SpectralMethod, SpectralMoments};
use crate::error::Result;
use crate::fatigue::SnCurve;
use std::f64::consts::SQRT_2;

/// Below this distance of α₂ from 1 the coefficients are formed from differences of numbers equal to 1
/// within a few ulps (R = 0/0 at α₂ = 1): the model is then replaced by its limit, the narrow-band
/// Rayleigh damage, from which it differs by O(k·(1 − α₂)) ≤ 1e-10·k relative (see the type's docs).
const NARROW_BAND_LIMIT: f64 = 1e-10;

/// Dirlik's rainflow amplitude model (T. Dirlik, "Application of computers in fatigue analysis", PhD
/// thesis, University of Warwick, 1985), written for amplitudes.
///
/// # Formula
/// With the moments of the one-sided density in Hz ([`SpectralMoments`]), Z = S_a/√m₀ (amplitude; the
/// thesis writes the range over 2√m₀, the same variable):
/// ```text
/// x_m = (m₁/m₀)√(m₂/m₄),   γ = α₂ = m₂/√(m₀m₄)
/// D₁ = 2(x_m − γ²)/(1 + γ²),   R = (γ − x_m − D₁²)/(1 − γ − D₁ + D₁²)
/// D₂ = (1 − γ − D₁ + D₁²)/(1 − R),   D₃ = 1 − D₁ − D₂,   Q = 1.25(γ − D₃ − D₂R)/D₁
/// p(S_a) = (1/√m₀)·[ (D₁/Q) e^{−Z/Q} + (D₂Z/R²) e^{−Z²/(2R²)} + D₃ Z e^{−Z²/2} ]
/// D/T = ν_p ∫_{S_e}^∞ S_a^k p(S_a) dS_a / C
///     = (ν_p m₀^{k/2}/C)·[ D₁Q^k Γ(1+k, z_e/Q) + D₂(√2|R|)^k Γ(1+k/2, z_e²/(2R²)) + D₃ √2^k Γ(1+k/2, z_e²/2) ]
/// ```
/// with ν_p = √(m₄/m₂) the rate of peaks, z_e = S_e/√m₀ and Γ(a, x) the upper incomplete gamma function
/// (Γ(a, 0) = Γ(a): without an endurance limit the bracket is D₁Q^kΓ(1+k) + √2^kΓ(1+k/2)(D₂|R|^k + D₃)).
/// Each term is ∫ z^k·(term) dz by the substitutions u = z/Q and u = z²/(2R²).
///
/// Narrow-band limit: as α₂ → 1 (with α₁ → 1), D₁ → 0, R → 1 and D₂ + D₃ → 1, so p → Rayleigh and
/// ν_p → ν₀⁺: the damage tends to the [`NarrowBand`](crate::fatigue::NarrowBand) one. For
/// 1 − α₂ < 1e-10 the coefficients are 0/0 in floating point and the narrow-band damage is returned.
///
/// # Errors
/// None beyond those of the inputs' constructors.
///
/// # Examples
/// ```
/// use stochvib::fatigue::{Dirlik, SnCurve, SpectralMethod, SpectralMoments};
/// // Band-limited white noise 1 unit²/Hz on [50, 150] Hz; k = 4.
/// let m = SpectralMoments::from_one_sided_hz(|_| 1.0, 50.0, 150.0, &[]).unwrap();
/// let sn = SnCurve { k: 4.0, c: 1e10, endurance_limit: None }.build().unwrap();
/// let c = Dirlik::coefficients(&m).unwrap();
/// assert!((c.d1 + c.d2 + c.d3 - 1.0).abs() < 1e-14);
/// let life = Dirlik.life(&m, &sn).unwrap();
/// assert!(life > 0.0 && life.is_finite());
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Dirlik;

/// Dirlik's coefficients (see [`Dirlik`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirlikCoefficients {
    /// x_m = (m₁/m₀)√(m₂/m₄).
    pub x_m: f64,
    /// γ = α₂.
    pub gamma: f64,
    /// Weight of the exponential term.
    pub d1: f64,
    /// Weight of the Rayleigh term of scale R.
    pub d2: f64,
    /// Weight of the unit Rayleigh term.
    pub d3: f64,
    /// Scale of the exponential term.
    pub q: f64,
    /// Scale of the second Rayleigh term.
    pub r: f64,
}

impl Dirlik {
    /// Dirlik's coefficients for these moments, or `None` in the narrow-band limit 1 − α₂ < 1e-10 (where
    /// they are 0/0 and the model is the Rayleigh density).
    ///
    /// # Formula
    /// See [`Dirlik`].
    ///
    /// # Errors
    /// None (`None` as above).
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{Dirlik, OneSidedHzMoments};
    /// let tone = OneSidedHzMoments { m0: 1.0, m1: 10.0, m2: 100.0, m4: 1e4 }.build().unwrap();
    /// assert!(Dirlik::coefficients(&tone).is_none());
    /// ```
    pub fn coefficients(moments: &SpectralMoments) -> Option<DirlikCoefficients> {
        let g = moments.alpha2();
        if 1.0 - g < NARROW_BAND_LIMIT {
            return None;
        }
        let xm = moments.x_m();
        let d1 = 2.0 * (xm - g * g) / (1.0 + g * g);
        let den = 1.0 - g - d1 + d1 * d1;
        let r = (g - xm - d1 * d1) / den;
        let d2 = den / (1.0 - r);
        let d3 = 1.0 - d1 - d2;
        let q = 1.25 * (g - d3 - d2 * r) / d1;
        let c = DirlikCoefficients {
            x_m: xm,
            gamma: g,
            d1,
            d2,
            d3,
            q,
            r,
        };
        if [d1, d2, d3, q, r].iter().all(|v| v.is_finite()) {
            Some(c)
        } else {
            None
        }
    }

    /// Dirlik's amplitude density p(S_a) (1/unit) at `amplitude` S_a ≥ 0 (0 for S_a < 0; the Rayleigh
    /// density in the narrow-band limit).
    ///
    /// # Formula
    /// p(S_a) = (1/√m₀)[(D₁/Q)e^{−Z/Q} + (D₂Z/R²)e^{−Z²/(2R²)} + D₃Ze^{−Z²/2}], Z = S_a/√m₀.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{Dirlik, SpectralMoments};
    /// let m = SpectralMoments::from_one_sided_hz(|_| 1.0, 50.0, 150.0, &[]).unwrap();
    /// // Crude midpoint sum of the density over [0, 20σ]: close to 1.
    /// let s = m.m0().sqrt();
    /// let h = 1e-3 * s;
    /// let total: f64 = (0..20_000).map(|i| Dirlik::amplitude_pdf(&m, (i as f64 + 0.5) * h) * h).sum();
    /// assert!((total - 1.0).abs() < 1e-4);
    /// ```
    pub fn amplitude_pdf(moments: &SpectralMoments, amplitude: f64) -> f64 {
        if amplitude < 0.0 {
            return 0.0;
        }
        let s0 = moments.m0().sqrt();
        let z = amplitude / s0;
        match Dirlik::coefficients(moments) {
            None => z * (-0.5 * z * z).exp() / s0,
            Some(c) => {
                let t1 = if c.d1 > 0.0 && c.q > 0.0 {
                    c.d1 / c.q * (-z / c.q).exp()
                } else {
                    0.0
                };
                let t2 = if c.r != 0.0 {
                    c.d2 * z / (c.r * c.r) * (-z * z / (2.0 * c.r * c.r)).exp()
                } else {
                    0.0
                };
                let t3 = c.d3 * z * (-0.5 * z * z).exp();
                (t1 + t2 + t3) / s0
            }
        }
    }
}

impl SpectralMethod for Dirlik {
    fn name(&self) -> &'static str {
        "Dirlik (1985)"
    }

    fn damage_rate(&self, moments: &SpectralMoments, sn: &SnCurve) -> Result<f64> {
        let Some(c) = Dirlik::coefficients(moments) else {
            return Ok(narrow_band_rate(moments, sn));
        };
        let k = sn.k();
        let s0 = moments.m0().sqrt();
        let ze = limit(sn) / s0;
        let pre = moments.nu_peak().ln() - sn.c().ln() + k * s0.ln();
        let mut d = 0.0;
        if c.d1 > 0.0 && c.q > 0.0 {
            d += c.d1 * (pre + k * c.q.ln() + ln_upper_gamma(1.0 + k, ze / c.q)).exp();
        }
        if c.r != 0.0 {
            let r = c.r.abs();
            d += c.d2 * (pre + k * (SQRT_2 * r).ln() + ln_upper_gamma(1.0 + 0.5 * k, ze * ze / (2.0 * r * r))).exp();
        }
        d += c.d3 * (pre + k * SQRT_2.ln() + ln_upper_gamma(1.0 + 0.5 * k, 0.5 * ze * ze)).exp();
        Ok(d)
    }
}
