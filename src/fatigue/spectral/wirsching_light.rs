//! Wirsching–Light (1980) empirical correction of the narrow-band damage.

use super::narrow_band::narrow_band_rate;
use super::{SpectralMethod, SpectralMoments};
use crate::error::Result;
use crate::fatigue::SnCurve;

/// Wirsching & Light, "Fatigue under wide band random stresses", J. Struct. Div. ASCE 106(7), 1593–1607
/// (1980): the narrow-band damage times an empirical rainflow correction factor λ(ε, k) fitted to
/// simulations.
///
/// # Formula
/// ```text
/// D/T = λ(ε, k) · D_NB/T,      λ = a(k) + (1 − a(k)) (1 − ε)^{b(k)}
/// a(k) = 0.926 − 0.033 k,      b(k) = 1.587 k − 2.323,      ε = √(1 − α₂²)
/// ```
/// with D_NB the [`NarrowBand`](crate::fatigue::NarrowBand) rate. The slope k is that of the S–N curve
/// (the same in amplitudes and ranges). With an endurance limit, λ multiplies the cut-off narrow-band
/// damage: an approximation, since λ was fitted without a limit.
///
/// # Errors
/// None beyond those of the inputs' constructors.
///
/// # Examples
/// ```
/// use stochvib::fatigue::{NarrowBand, SnCurve, SpectralMethod, OneSidedHzMoments, WirschingLight};
/// // A pure tone (ε = 0): λ = 1, the narrow-band damage.
/// let m = OneSidedHzMoments { m0: 1.0, m1: 10.0, m2: 100.0, m4: 1e4 }.build().unwrap();
/// let sn = SnCurve { k: 3.0, c: 1e6, endurance_limit: None }.build().unwrap();
/// let wl = WirschingLight.damage_rate(&m, &sn).unwrap();
/// assert!((wl / NarrowBand.damage_rate(&m, &sn).unwrap() - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct WirschingLight;

impl WirschingLight {
    /// The correction factor λ(ε, k).
    ///
    /// # Formula
    /// λ = a(k) + (1 − a(k))(1 − ε)^{b(k)}, a(k) = 0.926 − 0.033k, b(k) = 1.587k − 2.323.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::WirschingLight;
    /// // ε = 1 (α₂ → 0), k = 3: λ = a(3) = 0.827.
    /// assert!((WirschingLight::correction(1.0, 3.0) - 0.827).abs() < 1e-12);
    /// ```
    pub fn correction(epsilon: f64, k: f64) -> f64 {
        let a = 0.926 - 0.033 * k;
        let b = 1.587 * k - 2.323;
        a + (1.0 - a) * (1.0 - epsilon).powf(b)
    }
}

impl SpectralMethod for WirschingLight {
    fn name(&self) -> &'static str {
        "Wirsching-Light (1980)"
    }

    fn damage_rate(&self, moments: &SpectralMoments, sn: &SnCurve) -> Result<f64> {
        Ok(WirschingLight::correction(moments.epsilon(), sn.k()) * narrow_band_rate(moments, sn))
    }
}
