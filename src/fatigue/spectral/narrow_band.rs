//! Narrow-band (Rayleigh) approximation: every up-crossing is one cycle with a Rayleigh amplitude.

use super::gamma::{limit, ln_rayleigh_moment, rayleigh_pdf};
use super::{SpectralMethod, SpectralMoments};
use crate::error::Result;
use crate::fatigue::SnCurve;

/// Narrow-band damage (Bendat 1964; Miles 1954): cycles at the rate of zero up-crossings with Rayleigh
/// amplitudes, exact for an ideally narrow-band Gaussian process and conservative for wide-band ones.
///
/// # Formula
/// ```text
/// p(S_a) = (S_a/m₀) exp(−S_a²/(2m₀))                                   (Rayleigh, σ = √m₀)
/// D/T = ν₀⁺ ∫_{S_e}^∞ S_a^k p(S_a) dS_a / C = ν₀⁺ (√(2m₀))^k Γ(1 + k/2, S_e²/(2m₀)) / C
///     = ν₀⁺ (√(2m₀))^k Γ(1 + k/2) / C                                    (no endurance limit)
/// ```
/// ν₀⁺ = √(m₂/m₀) (1/s), Γ(a, x) the upper incomplete gamma function, moments of the one-sided density in
/// Hz ([`SpectralMoments`]), S–N curve N·S_a^k = C in amplitudes.
///
/// # Errors
/// None beyond those of the inputs' constructors.
///
/// # Examples
/// ```
/// use stochvib::fatigue::{NarrowBand, SnCurve, SpectralMethod, OneSidedHzMoments};
/// // m0 = 1, ν₀⁺ = 10 Hz, k = 2: D/T = 10 · 2 · Γ(2) / C.
/// let m = OneSidedHzMoments { m0: 1.0, m1: 10.0, m2: 100.0, m4: 1e4 }.build().unwrap();
/// let sn = SnCurve { k: 2.0, c: 1e6, endurance_limit: None }.build().unwrap();
/// assert!((NarrowBand.damage_rate(&m, &sn).unwrap() - 20.0 / 1e6).abs() < 1e-18);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NarrowBand;

impl NarrowBand {
    /// The Rayleigh amplitude density p(S_a) of the model (1/unit).
    ///
    /// # Formula
    /// p(S_a) = (S_a/m₀) exp(−S_a²/(2m₀)), S_a ≥ 0.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{NarrowBand, OneSidedHzMoments};
    /// let m = OneSidedHzMoments { m0: 1.0, m1: 10.0, m2: 100.0, m4: 1e4 }.build().unwrap();
    /// assert!((NarrowBand.amplitude_pdf(&m, 1.0) - (-0.5f64).exp()).abs() < 1e-15);
    /// ```
    pub fn amplitude_pdf(&self, moments: &SpectralMoments, amplitude: f64) -> f64 {
        rayleigh_pdf(moments.m0().sqrt(), amplitude)
    }
}

impl SpectralMethod for NarrowBand {
    fn name(&self) -> &'static str {
        "narrow-band Rayleigh"
    }

    fn damage_rate(&self, moments: &SpectralMoments, sn: &SnCurve) -> Result<f64> {
        Ok(narrow_band_rate(moments, sn))
    }
}

/// D_NB/T of the narrow-band model (used by the corrected methods).
pub(crate) fn narrow_band_rate(moments: &SpectralMoments, sn: &SnCurve) -> f64 {
    let k = sn.k();
    (moments.nu0_plus().ln() - sn.c().ln() + ln_rayleigh_moment(moments.m0().sqrt(), k, limit(sn))).exp()
}
