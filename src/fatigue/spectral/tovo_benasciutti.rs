//! Tovo–Benasciutti: rainflow damage as a weighted mean of the narrow-band and range-counting damages.

use super::gamma::{limit, ln_rayleigh_moment};
use super::narrow_band::narrow_band_rate;
use super::{SpectralMethod, SpectralMoments};
use crate::error::Result;
use crate::fatigue::SnCurve;

/// Which published weighting factor b to use.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum TovoBenasciuttiVariant {
    /// R. Tovo, "Cycle distribution and fatigue damage under broadband random loading", Int. J. Fatigue
    /// 24(11), 1137–1147 (2002): b = min((α₁ − α₂)/(1 − α₁), 1).
    Tovo2002,
    /// D. Benasciutti, R. Tovo, "Spectral methods for lifetime prediction under wide-band stationary
    /// random processes", Int. J. Fatigue 27(8), 867–877 (2005): the best-fit approximation
    /// b_app = (α₁ − α₂)[1.112(1 + α₁α₂ − (α₁ + α₂)) e^{2.11α₂} + (α₁ − α₂)] / (α₂ − 1)²
    /// (the "TB" method of the 2005 paper; FLife's "method 2"). The default.
    #[default]
    BenasciuttiTovo2005,
}

/// Tovo–Benasciutti damage: a convex combination of the narrow-band damage D_NB (an upper bound of the
/// rainflow damage) and the range-counting damage D_RC (a lower bound).
///
/// # Formula
/// ```text
/// D/T = b·D_NB/T + (1 − b)·D_RC/T,       b ∈ [0, 1] (the published expression, clamped to [0, 1])
/// D_NB/T = ν₀⁺ (√(2m₀))^k Γ(1 + k/2, S_e²/(2m₀)) / C                      (Rayleigh amplitudes, σ = √m₀)
/// D_RC/T = ν_p (√(2m₀)α₂)^k Γ(1 + k/2, S_e²/(2α₂²m₀)) / C                 (Rayleigh amplitudes, σ = α₂√m₀)
///        = α₂^{k−1} D_NB/T                                                 (no endurance limit; ν_p α₂ = ν₀⁺)
/// ```
/// so that without an endurance limit D = D_NB·[b + (1 − b)α₂^{k−1}] (Benasciutti & Tovo 2005). b is that
/// of the chosen [`TovoBenasciuttiVariant`]. The 2005 b_app grows without bound as α₂ → 1 (the numerator is
/// O(1 − α₂), the denominator O((1 − α₂)²)); clamping it to 1 gives the narrow-band damage there, the
/// correct limit. At α₂ = 1 (a pure tone) D_NB = D_RC and b is irrelevant.
///
/// # Errors
/// None beyond those of the inputs' constructors.
///
/// # Examples
/// ```
/// use stochvib::fatigue::{NarrowBand, SnCurve, SpectralMethod, SpectralMoments, TovoBenasciutti};
/// let m = SpectralMoments::from_one_sided_hz(|_| 1.0, 50.0, 150.0, &[]).unwrap();
/// let sn = SnCurve { k: 4.0, c: 1e10, endurance_limit: None }.build().unwrap();
/// let tb = TovoBenasciutti::default();
/// let b = tb.weight(&m);
/// let expected = NarrowBand.damage_rate(&m, &sn).unwrap() * (b + (1.0 - b) * m.alpha2().powi(3));
/// assert!((tb.damage_rate(&m, &sn).unwrap() / expected - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TovoBenasciutti {
    /// Which weighting factor b.
    pub variant: TovoBenasciuttiVariant,
}

impl TovoBenasciutti {
    /// The method with weighting factor `variant`.
    pub fn new(variant: TovoBenasciuttiVariant) -> Self {
        TovoBenasciutti { variant }
    }

    /// The weighting factor b ∈ [0, 1].
    ///
    /// # Formula
    /// Tovo2002: b = (α₁ − α₂)/(1 − α₁); BenasciuttiTovo2005: b_app (see [`TovoBenasciuttiVariant`]); both
    /// clamped to [0, 1]; b = 1 at α₂ = 1.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{SpectralMoments, TovoBenasciutti, TovoBenasciuttiVariant};
    /// let m = SpectralMoments::from_one_sided_hz(|_| 1.0, 0.0, 100.0, &[]).unwrap();
    /// // White noise on [0, F]: α₁ = √3/2, α₂ = √5/3.
    /// let (a1, a2) = (3f64.sqrt() / 2.0, 5f64.sqrt() / 3.0);
    /// let b = TovoBenasciutti::new(TovoBenasciuttiVariant::Tovo2002).weight(&m);
    /// assert!((b - (a1 - a2) / (1.0 - a1)).abs() < 1e-9);
    /// ```
    pub fn weight(&self, moments: &SpectralMoments) -> f64 {
        let a1 = moments.alpha1();
        let a2 = moments.alpha2();
        if a2 >= 1.0 || a1 >= 1.0 {
            return 1.0;
        }
        let b = match self.variant {
            TovoBenasciuttiVariant::Tovo2002 => (a1 - a2) / (1.0 - a1),
            TovoBenasciuttiVariant::BenasciuttiTovo2005 => {
                (a1 - a2) * (1.112 * (1.0 + a1 * a2 - (a1 + a2)) * (2.11 * a2).exp() + (a1 - a2))
                    / ((a2 - 1.0) * (a2 - 1.0))
            }
        };
        if b.is_nan() {
            1.0
        } else {
            b.clamp(0.0, 1.0)
        }
    }
}

impl SpectralMethod for TovoBenasciutti {
    fn name(&self) -> &'static str {
        match self.variant {
            TovoBenasciuttiVariant::Tovo2002 => "Tovo (2002)",
            TovoBenasciuttiVariant::BenasciuttiTovo2005 => "Benasciutti-Tovo (2005)",
        }
    }

    fn damage_rate(&self, moments: &SpectralMoments, sn: &SnCurve) -> Result<f64> {
        let b = self.weight(moments);
        let nb = narrow_band_rate(moments, sn);
        let k = sn.k();
        let a2 = moments.alpha2();
        let rc =
            (moments.nu_peak().ln() - sn.c().ln() + ln_rayleigh_moment(a2 * moments.m0().sqrt(), k, limit(sn))).exp();
        Ok(b * nb + (1.0 - b) * rc)
    }
}
