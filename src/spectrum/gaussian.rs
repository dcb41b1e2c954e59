//! Type 2: Gaussian-correlated process, K(τ) = D e^{−ατ²}.

use super::{Asymptote, Domain, Spectrum};
use crate::error::{require_non_negative, require_positive, Result};
use std::f64::consts::PI;

/// Standard correlation type 2 (textbook (8.13), (8.24)).
///
/// # Formula
/// ```text
/// K(τ) = D e^{−ατ²},        S(ω) = D / (2√(πα)) · e^{−ω²/(4α)}
/// ```
/// Derivation: (1/2π)∫ e^{−ατ²} e^{−iωτ} dτ = (1/2π) √(π/α) e^{−ω²/(4α)} = e^{−ω²/(4α)} / (2√(πα)).
/// The textbook's printed prefactor is garbled; this one integrates to D exactly. Not rational: no exact
/// finite-dimensional shaping filter exists.
///
/// # Errors
/// [`Gaussian::new`] rejects α ≤ 0, D < 0 and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Gaussian, Domain, Spectrum};
/// let g = Gaussian::new(2.0, 0.5, Domain::Temporal).unwrap();
/// // S(0) = D / (2 √(π α))
/// assert!((g.density(0.0) - 2.0 / (2.0 * (std::f64::consts::PI * 0.5).sqrt())).abs() < 1e-15);
/// assert_eq!(g.variance().unwrap(), 2.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Gaussian {
    variance: f64,
    alpha: f64,
    domain: Domain,
    /// D/(2√(πα)), precomputed for `density`.
    prefactor: f64,
}

impl Gaussian {
    /// Builds K(τ) = D e^{−ατ²} with D = `variance` and α = `alpha` (1/s² or 1/m²).
    ///
    /// # Errors
    /// `variance` must be finite and ≥ 0, `alpha` finite and > 0.
    pub fn new(variance: f64, alpha: f64, domain: Domain) -> Result<Self> {
        let variance = require_non_negative("variance", variance)?;
        let alpha = require_positive("alpha", alpha)?;
        Ok(Gaussian {
            variance,
            alpha,
            domain,
            prefactor: variance / (2.0 * (PI * alpha).sqrt()),
        })
    }
}

impl Spectrum for Gaussian {
    fn describe(&self) -> String {
        format!(
            "type 2: K = D exp(-alpha tau^2), D = {}, alpha = {} 1/{}^2",
            crate::numbers::num(self.variance),
            crate::numbers::num(self.alpha),
            self.domain.lag_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        self.prefactor * (-omega * omega / (4.0 * self.alpha)).exp()
    }
    /// The formula of `density` with the vectorised [`vmath::exp`](crate::linalg::vmath::exp) on the CPU's
    /// widest SIMD unit: within `vmath::EXP_ULP_BOUND` + 1 ulp of `density`.
    fn density_into(&self, omega: &[f64], out: &mut [f64]) {
        use crate::linalg::vmath;
        vmath::map(omega, out, |w: f64| {
            self.prefactor * vmath::exp(-w * w / (4.0 * self.alpha))
        });
    }
    fn high_frequency(&self) -> Asymptote {
        Asymptote::Vanishing
    }
    fn low_frequency(&self) -> Asymptote {
        Asymptote::Power {
            exponent: 0.0,
            coefficient: self.density(0.0),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        // e-folding scale of the density: ω = 2√α
        vec![2.0 * self.alpha.sqrt()]
    }
    fn variance(&self) -> Result<f64> {
        Ok(self.variance)
    }
    fn correlation(&self, tau: f64) -> Result<f64> {
        Ok(self.variance * (-self.alpha * tau * tau).exp())
    }
}
