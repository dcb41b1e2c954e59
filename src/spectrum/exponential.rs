//! Type 1: exponentially correlated process, K(τ) = D e^{−α|τ|}.

use super::{Asymptote, Domain, RationalSpectrum, Spectrum};
use crate::error::{require_non_negative, require_positive, Result};
use std::f64::consts::PI;

/// Standard correlation type 1 (textbook (8.13), (8.24)); also the spatial road of (8.45) and (8.69).
///
/// # Formula
/// ```text
/// K(τ) = D e^{−α|τ|},        S(ω) = α D / (π (α² + ω²))        (two-sided, ω in rad/s or rad/m)
/// ```
/// Derivation: S(ω) = (1/2π)∫ D e^{−α|τ|} e^{−iωτ} dτ = (D/2π)·2α/(α² + ω²). The density is rational,
/// with shaping filter √(2αD)/(s + α) driven by unit white noise.
///
/// # Errors
/// [`Exponential::new`] rejects α ≤ 0, D < 0 and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Exponential, Domain, Spectrum};
/// // Textbook road (8.45): α = 0.035 1/cm = 3.5 1/m, D = 2.25 cm² = 2.25e-4 m², spatial.
/// let road = Exponential::new(2.25e-4, 3.5, Domain::Spatial).unwrap();
/// assert!((road.variance().unwrap() - 2.25e-4).abs() < 1e-18);
/// assert!((road.correlation(1.0).unwrap() - 2.25e-4 * (-3.5f64).exp()).abs() < 1e-18);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Exponential {
    variance: f64,
    alpha: f64,
    domain: Domain,
}

impl Exponential {
    /// Builds K(τ) = D e^{−α|τ|} with D = `variance` (unit²) and α = `alpha` (1/s or 1/m).
    ///
    /// # Errors
    /// `variance` must be finite and ≥ 0, `alpha` finite and > 0.
    pub fn new(variance: f64, alpha: f64, domain: Domain) -> Result<Self> {
        Ok(Exponential {
            variance: require_non_negative("variance", variance)?,
            alpha: require_positive("alpha", alpha)?,
            domain,
        })
    }
    /// The decay rate α.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
}

impl Spectrum for Exponential {
    fn describe(&self) -> String {
        format!(
            "type 1: K = D exp(-alpha |tau|), D = {}, alpha = {} 1/{}",
            crate::numbers::num(self.variance),
            crate::numbers::num(self.alpha),
            self.domain.lag_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        self.alpha * self.variance / (PI * (self.alpha * self.alpha + omega * omega))
    }
    fn high_frequency(&self) -> Asymptote {
        Asymptote::Power {
            exponent: -2.0,
            coefficient: self.alpha * self.variance / PI,
        }
    }
    fn low_frequency(&self) -> Asymptote {
        Asymptote::Power {
            exponent: 0.0,
            coefficient: self.variance / (PI * self.alpha),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        vec![self.alpha]
    }
    fn variance(&self) -> Result<f64> {
        Ok(self.variance)
    }
    fn correlation(&self, tau: f64) -> Result<f64> {
        Ok(self.variance * (-self.alpha * tau.abs()).exp())
    }
    fn rational(&self) -> Option<RationalSpectrum> {
        let a2 = self.alpha * self.alpha;
        RationalSpectrum::new(vec![self.alpha * self.variance / PI], vec![a2, 1.0], self.domain).ok()
    }
}
