//! General rational spectra S(ω) = N(ω²)/D(ω²) and their spectral factorisation into a stable,
//! minimum-phase shaping filter.

/// A rational two-sided density S(ω) = Σ nₖ ω^{2k} / Σ dₖ ω^{2k} (coefficients in ascending powers of ω²).
#[derive(Debug, Clone, PartialEq)]
pub struct RationalSpectrum {
    num: Vec<f64>,
    den: Vec<f64>,
}

impl RationalSpectrum {
    /// Numerator coefficients in ascending powers of ω².
    pub fn numerator(&self) -> &[f64] {
        &self.num
    }
    /// Denominator coefficients in ascending powers of ω².
    pub fn denominator(&self) -> &[f64] {
        &self.den
    }
}
