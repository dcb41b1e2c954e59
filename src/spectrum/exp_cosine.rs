//! Type 3: K(τ) = D e^{−α|τ|} cos βτ.

use super::{Asymptote, Domain, RationalSpectrum, Spectrum};
use crate::error::{require_non_negative, require_positive, Error, Result};
use std::f64::consts::PI;

/// Standard correlation type 3 (textbook (8.13), (8.24)): a damped-oscillation correlation.
///
/// # Formula
/// ```text
/// K(τ) = D e^{−α|τ|} cos βτ,
/// S(ω) = α D (ω² + α² + β²) / (π [(ω² − α² − β²)² + 4α²ω²])
/// ```
/// Derivation: S = (D/2π)·[α/(α² + (ω−β)²) + α/(α² + (ω+β)²)]; over a common denominator
/// (α² + (ω−β)²)(α² + (ω+β)²) = (ω² − α² − β²)² + 4α²ω². Rational, with a second-order shaping filter.
///
/// # Errors
/// [`ExpCosine::build`] rejects α ≤ 0, β < 0, D < 0 and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{ExpCosine, Domain, Spectrum};
/// let s = ExpCosine { variance: 1.0, alpha: 0.5, beta: 3.0, domain: Domain::Temporal }.build().unwrap();
/// assert!((s.correlation(0.2).unwrap() - (-0.1f64).exp() * 0.6f64.cos()).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExpCosine {
    /// D = K(0), the variance, (unit of the process)².
    pub variance: f64,
    /// α > 0, the decay rate, 1/s or 1/m (the lag unit of `domain`).
    pub alpha: f64,
    /// β ≥ 0, the frequency of the oscillation, rad/s or rad/m.
    pub beta: f64,
    /// Temporal or spatial.
    pub domain: Domain,
}

impl ExpCosine {
    /// The density of these fields, checked: K(τ) = D e^{−α|τ|} cos βτ.
    ///
    /// # Errors
    /// `variance` ≥ 0, `alpha` > 0, `beta` ≥ 0, all finite.
    pub fn build(self) -> Result<Self> {
        let ExpCosine {
            variance,
            alpha,
            beta,
            domain,
        } = self;
        if !(beta.is_finite() && beta >= 0.0) {
            return Err(Error::invalid("beta", beta, "must be finite and >= 0"));
        }
        Ok(ExpCosine {
            variance: require_non_negative("variance", variance)?,
            alpha: require_positive("alpha", alpha)?,
            beta,
            domain,
        })
    }
}

impl Spectrum for ExpCosine {
    fn describe(&self) -> String {
        format!(
            "type 3: K = D exp(-alpha |tau|) cos(beta tau), D = {}, alpha = {}, beta = {} 1/{}",
            crate::numbers::num(self.variance),
            crate::numbers::num(self.alpha),
            crate::numbers::num(self.beta),
            self.domain.lag_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        let (a, b, w2) = (self.alpha, self.beta, omega * omega);
        // product form of the denominator: no cancellation near the peak
        let d = (a * a + (omega - b).powi(2)) * (a * a + (omega + b).powi(2));
        a * self.variance * (w2 + a * a + b * b) / (PI * d)
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
            coefficient: self.density(0.0),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        vec![self.alpha, self.beta].into_iter().filter(|w| *w > 0.0).collect()
    }
    fn variance(&self) -> Result<f64> {
        Ok(self.variance)
    }
    fn correlation(&self, tau: f64) -> Result<f64> {
        Ok(self.variance * (-self.alpha * tau.abs()).exp() * (self.beta * tau).cos())
    }
    fn rational(&self) -> Option<RationalSpectrum> {
        let (a, b, d) = (self.alpha, self.beta, self.variance);
        let c = a * a + b * b;
        RationalSpectrum::new(
            vec![a * d * c / PI, a * d / PI],
            vec![c * c, 2.0 * (a * a - b * b), 1.0],
            self.domain,
        )
        .ok()
    }
}
