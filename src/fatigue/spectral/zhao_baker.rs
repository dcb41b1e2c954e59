//! Zhao–Baker (1992): rainflow amplitudes as a Weibull–Rayleigh mixture.

use super::gamma::{limit, ln_upper_gamma};
use super::{SpectralMethod, SpectralMoments};
use crate::error::{Error, Result};
use crate::fatigue::SnCurve;
use statrs::function::gamma::gamma;
use std::f64::consts::{PI, SQRT_2};

/// Which published parameter set of Zhao & Baker (1992).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ZhaoBakerVariant {
    /// The general fit (S–N slopes 2 ≤ k ≤ 6): α = 8 − 7α₂. The default.
    #[default]
    General,
    /// The variant fitted for k = 3: α from the cubic below, with the damage correction factor
    /// ρ(α₀.₇₅); needs the fractional moments m₀.₇₅ and m₁.₅.
    K3,
}

/// Zhao & Baker, "On the probability density function of rainflow stress range for stationary Gaussian
/// processes", Int. J. Fatigue 14(2), 121–135 (1992): a Weibull–Rayleigh mixture for the normalised
/// rainflow amplitude Z = S_a/√m₀, at the rate of peaks.
///
/// # Formula
/// ```text
/// p(S_a) = (1/√m₀)·[ w α β Z^{β−1} e^{−α Z^β} + (1 − w) Z e^{−Z²/2} ]
/// β = 1.1 (α₂ < 0.9),   β = 1.1 + 9(α₂ − 0.9) (α₂ ≥ 0.9)
/// w = (1 − α₂) / (1 − √(2/π) Γ(1 + 1/β) α^{−1/β})      (so that E[Z] = α₂√(π/2), the range-counting mean)
/// General: α = 8 − 7α₂
/// K3:      ρ = −0.4154 + 1.392 α₀.₇₅ (α₀.₇₅ ≥ 0.5), ρ = 0.28 otherwise; p = α^{−1/β} is the smaller
///          positive root of Γ(1+3/β)(1−α₂)p³ + 3Γ(1+1/β)(ρα₂ − 1)p + 3√(π/2)α₂(1 − ρ) = 0
/// D/T = (ν_p m₀^{k/2}/C)·[ w α^{−k/β} Γ(1 + k/β, α z_e^β) + (1 − w) 2^{k/2} Γ(1 + k/2, z_e²/2) ]
/// ```
/// ν_p = √(m₄/m₂), z_e = S_e/√m₀, Γ(a, x) the upper incomplete gamma function (Γ(a) without a limit).
/// The smaller root of the K3 cubic is the one continuous with the narrow-band limit: as α₂ → 1 the cubic
/// becomes linear with root p = √(π/2)/Γ(1 + 1/β) = √2 (β = 2), i.e. α = 1/2 and a Weibull term equal to
/// the Rayleigh one; the other root runs to infinity. In that limit (General) α → 1, β → 2, w → 0.
///
/// # Errors
/// [`Error::NotApplicable`] for [`ZhaoBakerVariant::K3`] when the moments lack m₀.₇₅, m₁.₅, or when the
/// cubic has no positive root.
///
/// # Examples
/// ```
/// use stochvib::fatigue::{SnCurve, SpectralMethod, SpectralMoments, ZhaoBaker, ZhaoBakerVariant};
/// // Bimodal: 0.125 unit²/Hz on [20, 60] Hz and 0.1 on [100, 120] Hz.
/// let g = |f: f64| if (20.0..=60.0).contains(&f) { 0.125 } else if (100.0..=120.0).contains(&f) { 0.1 } else { 0.0 };
/// let m = SpectralMoments::from_one_sided_hz_with_fractional(g, 0.0, 200.0, &[20.0, 60.0, 100.0, 120.0]).unwrap();
/// let sn = SnCurve { k: 3.0, c: 1e10, endurance_limit: None }.build().unwrap();
/// let general = ZhaoBaker::default().damage_rate(&m, &sn).unwrap();
/// let k3 = ZhaoBaker::new(ZhaoBakerVariant::K3).damage_rate(&m, &sn).unwrap();
/// assert!(general > 0.0 && k3 > 0.0);
/// // White noise on [50, 150] Hz: α₀.₇₅ = 0.977 gives ρ = 0.944 and the k = 3 cubic has no root.
/// let band = SpectralMoments::from_one_sided_hz_with_fractional(|_| 1.0, 50.0, 150.0, &[]).unwrap();
/// assert!(ZhaoBaker::new(ZhaoBakerVariant::K3).damage_rate(&band, &sn).is_err());
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ZhaoBaker {
    /// Which parameter set.
    pub variant: ZhaoBakerVariant,
}

/// The parameters of the Zhao–Baker mixture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZhaoBakerCoefficients {
    /// Weibull scale parameter α (of Z^β).
    pub alpha: f64,
    /// Weibull shape parameter β.
    pub beta: f64,
    /// Weight w of the Weibull term.
    pub w: f64,
}

impl ZhaoBaker {
    /// The method with parameter set `variant`.
    pub fn new(variant: ZhaoBakerVariant) -> Self {
        ZhaoBaker { variant }
    }

    /// The mixture parameters α, β, w for these moments.
    ///
    /// # Formula
    /// See [`ZhaoBaker`].
    ///
    /// # Errors
    /// As [`ZhaoBaker`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{SpectralMoments, ZhaoBaker};
    /// let m = SpectralMoments::from_one_sided_hz(|_| 1.0, 0.0, 100.0, &[]).unwrap();
    /// let c = ZhaoBaker::default().coefficients(&m).unwrap();
    /// // α₂ = √5/3 ≈ 0.745 < 0.9: β = 1.1, α = 8 − 7α₂.
    /// assert_eq!(c.beta, 1.1);
    /// assert!((c.alpha - (8.0 - 7.0 * 5f64.sqrt() / 3.0)).abs() < 1e-9);
    /// ```
    pub fn coefficients(&self, moments: &SpectralMoments) -> Result<ZhaoBakerCoefficients> {
        let a2 = moments.alpha2();
        let beta = if a2 < 0.9 { 1.1 } else { 1.1 + 9.0 * (a2 - 0.9) };
        let g1 = gamma(1.0 + 1.0 / beta);
        let alpha = match self.variant {
            ZhaoBakerVariant::General => 8.0 - 7.0 * a2,
            ZhaoBakerVariant::K3 => {
                let a075 = moments.alpha_0_75().ok_or_else(|| Error::NotApplicable {
                    method: "Zhao-Baker (k = 3 variant)".into(),
                    reason: "needs the fractional moments m0.75 and m1.5 (SpectralMoments::with_fractional, \
                             from_one_sided_hz_with_fractional or from_spectrum_with_fractional)"
                        .into(),
                })?;
                let rho = if a075 >= 0.5 { -0.4154 + 1.392 * a075 } else { 0.28 };
                let a = gamma(1.0 + 3.0 / beta) * (1.0 - a2);
                let b = 3.0 * g1 * (rho * a2 - 1.0);
                let c = 3.0 * (PI / 2.0).sqrt() * a2 * (1.0 - rho);
                let p = smaller_positive_root(a, b, c).ok_or_else(|| Error::NotApplicable {
                    method: "Zhao-Baker (k = 3 variant)".into(),
                    reason: format!(
                        "the cubic for alpha has no positive root (alpha2 = {a2}, alpha0.75 = {a075}, rho = {rho})"
                    ),
                })?;
                p.powf(-beta)
            }
        };
        // At α₂ = 1 the K3 Weibull term is the Rayleigh one (α = 1/2, β = 2) and w is 0/0: take w = 0.
        let w = if a2 >= 1.0 {
            0.0
        } else {
            (1.0 - a2) / (1.0 - (2.0 / PI).sqrt() * g1 * alpha.powf(-1.0 / beta))
        };
        Ok(ZhaoBakerCoefficients { alpha, beta, w })
    }

    /// The mixture's amplitude density p(S_a) (1/unit) at `amplitude` S_a ≥ 0 (0 for S_a < 0).
    ///
    /// # Formula
    /// p(S_a) = (1/√m₀)[wαβZ^{β−1}e^{−αZ^β} + (1 − w)Ze^{−Z²/2}], Z = S_a/√m₀.
    ///
    /// # Errors
    /// As [`ZhaoBaker::coefficients`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{SpectralMoments, ZhaoBaker};
    /// let m = SpectralMoments::from_one_sided_hz(|_| 1.0, 50.0, 150.0, &[]).unwrap();
    /// assert_eq!(ZhaoBaker::default().amplitude_pdf(&m, -1.0).unwrap(), 0.0);
    /// ```
    pub fn amplitude_pdf(&self, moments: &SpectralMoments, amplitude: f64) -> Result<f64> {
        if amplitude < 0.0 {
            return Ok(0.0);
        }
        let c = self.coefficients(moments)?;
        let s0 = moments.m0().sqrt();
        let z = amplitude / s0;
        let weibull = if z > 0.0 || c.beta <= 1.0 {
            c.alpha * c.beta * z.powf(c.beta - 1.0) * (-c.alpha * z.powf(c.beta)).exp()
        } else {
            0.0
        };
        Ok((c.w * weibull + (1.0 - c.w) * z * (-0.5 * z * z).exp()) / s0)
    }
}

/// The smaller positive root of a p³ + b p + c = 0 with a ≥ 0, b < 0 < c (bisection on [0, p*], p* the
/// minimum of the cubic); `None` when the minimum is above zero.
fn smaller_positive_root(a: f64, b: f64, c: f64) -> Option<f64> {
    if !(b < 0.0 && c > 0.0 && a >= 0.0) {
        return None;
    }
    let f = |p: f64| (a * p * p + b) * p + c;
    let hi = if a > 0.0 {
        (-b / (3.0 * a)).sqrt()
    } else {
        return Some(-c / b);
    };
    if f(hi) > 0.0 {
        return None;
    }
    let (mut lo, mut hi) = (0.0f64, hi);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
    }
    Some(0.5 * (lo + hi))
}

impl SpectralMethod for ZhaoBaker {
    fn name(&self) -> &'static str {
        match self.variant {
            ZhaoBakerVariant::General => "Zhao-Baker (1992)",
            ZhaoBakerVariant::K3 => "Zhao-Baker (1992, k = 3 variant)",
        }
    }

    fn damage_rate(&self, moments: &SpectralMoments, sn: &SnCurve) -> Result<f64> {
        let c = self.coefficients(moments)?;
        let k = sn.k();
        let s0 = moments.m0().sqrt();
        let ze = limit(sn) / s0;
        let pre = moments.nu_peak().ln() - sn.c().ln() + k * s0.ln();
        let weibull =
            (pre - (k / c.beta) * c.alpha.ln() + ln_upper_gamma(1.0 + k / c.beta, c.alpha * ze.powf(c.beta))).exp();
        let rayleigh = (pre + k * SQRT_2.ln() + ln_upper_gamma(1.0 + 0.5 * k, 0.5 * ze * ze)).exp();
        Ok(c.w * weibull + (1.0 - c.w) * rayleigh)
    }
}
