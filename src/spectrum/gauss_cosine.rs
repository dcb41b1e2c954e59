//! Type 4: K(τ) = D e^{−ατ²} cos βτ.

use super::{Asymptote, Domain, Spectrum};
use crate::error::{require_non_negative, require_positive, Error, Result};
use std::f64::consts::PI;

/// Standard correlation type 4 (textbook (8.13), (8.24)).
///
/// # Formula
/// ```text
/// K(τ) = D e^{−ατ²} cos βτ,
/// S(ω) = D / (4√(πα)) · [e^{−(ω−β)²/(4α)} + e^{−(ω+β)²/(4α)}]
/// ```
/// Derivation: cos βτ shifts the type-2 density by ±β with weight ½ each. The printed prefactor is garbled;
/// this one integrates to D. Not rational.
///
/// # Errors
/// [`GaussCosineParameters::build`] rejects α ≤ 0, β < 0, D < 0 and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Domain, GaussCosineParameters, Spectrum};
/// let s = GaussCosineParameters { variance: 1.0, alpha: 0.5, beta: 3.0, domain: Domain::Temporal }.build().unwrap();
/// assert!((s.correlation(1.0).unwrap() - (-0.5f64).exp() * 3.0f64.cos()).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GaussCosine {
    variance: f64,
    alpha: f64,
    beta: f64,
    domain: Domain,
    /// D/(4√(πα)), precomputed for `density`.
    prefactor: f64,
}

/// The parameters of a [`GaussCosine`] density (type 4, K(τ) = D e^{−ατ²} cos βτ) as named fields.
///
/// # Errors
/// As [`GaussCosine`]'s `# Errors`.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{Domain, GaussCosineParameters, Spectrum};
/// let s = GaussCosineParameters { variance: 2.0, alpha: 0.5, beta: 3.0, domain: Domain::Temporal };
/// let s = s.build().unwrap();
/// assert!((s.variance().unwrap() - 2.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussCosineParameters {
    /// D = K(0) ≥ 0, the variance, (unit of the process)².
    pub variance: f64,
    /// α > 0, 1/s² or 1/m² (the lag unit of `domain`, squared).
    pub alpha: f64,
    /// β ≥ 0, rad/s or rad/m.
    pub beta: f64,
    /// Temporal or spatial.
    pub domain: Domain,
}

impl GaussCosineParameters {
    /// The [`GaussCosine`] of these parameters, checked.
    ///
    /// # Errors
    /// `variance` ≥ 0, `alpha` > 0, `beta` ≥ 0, all finite.
    pub fn build(self) -> Result<GaussCosine> {
        let GaussCosineParameters {
            variance,
            alpha,
            beta,
            domain,
        } = self;
        if !(beta.is_finite() && beta >= 0.0) {
            return Err(Error::invalid("beta", beta, "must be finite and >= 0"));
        }
        let variance = require_non_negative("variance", variance)?;
        let alpha = require_positive("alpha", alpha)?;
        Ok(GaussCosine {
            variance,
            alpha,
            beta,
            domain,
            prefactor: variance / (4.0 * (PI * alpha).sqrt()),
        })
    }
}

/// `density` with [`vmath::exp`](crate::linalg::vmath::exp), as a [`Kernel`](crate::linalg::vmath::Kernel)
/// always inlined into the SIMD loop of `density_into`.
struct Simd<'a>(&'a GaussCosine);

impl crate::linalg::vmath::Kernel for Simd<'_> {
    #[inline(always)]
    fn at(&self, omega: f64) -> f64 {
        use crate::linalg::vmath::exp;
        let s = self.0;
        let four_alpha = 4.0 * s.alpha;
        let (a, b) = (omega - s.beta, omega + s.beta);
        s.prefactor * (exp(-a * a / four_alpha) + exp(-b * b / four_alpha))
    }
}

impl Spectrum for GaussCosine {
    fn describe(&self) -> String {
        format!(
            "type 4: K = D exp(-alpha tau^2) cos(beta tau), D = {}, alpha = {} 1/{lag}^2, beta = {} 1/{lag}",
            crate::numbers::num(self.variance),
            crate::numbers::num(self.alpha),
            crate::numbers::num(self.beta),
            lag = self.domain.lag_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        let four_alpha = 4.0 * self.alpha;
        let f = |x: f64| (-x * x / four_alpha).exp();
        self.prefactor * (f(omega - self.beta) + f(omega + self.beta))
    }
    /// The formula of `density` with the vectorised [`vmath::exp`](crate::linalg::vmath::exp) on the CPU's
    /// widest SIMD unit: within `vmath::EXP_ULP_BOUND` + 2 ulp of `density`.
    fn density_into(&self, omega: &[f64], out: &mut [f64]) {
        use crate::linalg::vmath;
        vmath::map(omega, out, Simd(self));
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
        let w = 2.0 * self.alpha.sqrt();
        let mut v = vec![self.beta, self.beta + 3.0 * w];
        if self.beta > 3.0 * w {
            v.push(self.beta - 3.0 * w);
        }
        v.retain(|x| *x > 0.0);
        v
    }
    fn variance(&self) -> Result<f64> {
        Ok(self.variance)
    }
    fn correlation(&self, tau: f64) -> Result<f64> {
        Ok(self.variance * (-self.alpha * tau * tau).exp() * (self.beta * tau).cos())
    }
}
