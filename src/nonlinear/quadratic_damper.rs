//! Quadratic (orifice) damper, possibly asymmetric: F = q_r v² for v > 0 (rebound), −q_c v² for v < 0.
//!
//! # Formula
//! No linear part. For v ~ N(μ, σ²), with E₊ₙ = E[vⁿ 1{v>0}] and E₋ₙ = E[vⁿ 1{v<0}] ([`super::gauss`]):
//! ```text
//! E[F] = q_r E₊₂ − q_c E₋₂,      c_eq = E[∂F/∂v] = 2q_r E₊₁ − 2q_c E₋₁
//! ```
//! For a symmetric damper (q_r = q_c = q) at μ = 0: c_eq = 2qσ√(2/π). The force alone has the exact flow
//! v′ = −κ q v|v|: v(τ) = v₀/(1 + κ q |v₀| τ), q the coefficient of v₀'s sign.
//!
//! # Errors
//! [`QuadraticDamper::new`] rejects negative or non-finite coefficients and a damper with both zero.
//!
//! # Examples
//! ```
//! use stochvib::nonlinear::{ElementMoments, ForceLaw, QuadraticDamper};
//! let d = QuadraticDamper::new(2.0, 2.0).unwrap();
//! let m = ElementMoments { sigma_v: 0.5, ..Default::default() };
//! let ceq = 2.0 * 2.0 * 0.5 * (2.0 / std::f64::consts::PI).sqrt();
//! assert!((d.gaussian(&m).damping - ceq).abs() < 1e-14);
//! ```

use super::gauss::{negative_part, negative_square, positive_part, positive_square};
use super::{ElementMoments, Equivalent, ForceLaw};
use crate::error::{Error, Result};

/// A quadratic damper (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadraticDamper {
    /// q_r, N s²/m², for v > 0.
    pub rebound: f64,
    /// q_c, N s²/m², for v < 0.
    pub compression: f64,
}

impl QuadraticDamper {
    /// A damper with coefficients q_r (extension) and q_c (compression), N s²/m².
    ///
    /// # Errors
    /// See the module's `# Errors`.
    pub fn new(rebound: f64, compression: f64) -> Result<Self> {
        for (name, c) in [
            ("rebound_coefficient", rebound),
            ("compression_coefficient", compression),
        ] {
            if !(c.is_finite() && c >= 0.0) {
                return Err(Error::invalid(name, c, "must be finite and >= 0"));
            }
        }
        if rebound == 0.0 && compression == 0.0 {
            return Err(Error::invalid(
                "coefficient",
                0,
                "a quadratic damper needs a coefficient > 0 on at least one side",
            ));
        }
        Ok(QuadraticDamper { rebound, compression })
    }

    fn coefficient(&self, v: f64) -> f64 {
        if v > 0.0 {
            self.rebound
        } else {
            self.compression
        }
    }
}

impl ForceLaw for QuadraticDamper {
    fn kind(&self) -> &'static str {
        "quadratic-damper"
    }
    fn describe(&self) -> String {
        format!(
            "quadratic damper: {} N s²/m² in rebound (extension), {} N s²/m² in compression",
            self.rebound, self.compression
        )
    }
    fn force(&self, _x: f64, v: f64) -> f64 {
        self.coefficient(v) * v * v.abs()
    }
    fn velocity_dependent(&self) -> bool {
        true
    }
    fn is_zero(&self) -> bool {
        false
    }
    fn gaussian(&self, m: &ElementMoments) -> Equivalent {
        let (mu, s) = (m.mean_v, m.sigma_v);
        Equivalent {
            mean_force: self.rebound * positive_square(mu, s) - self.compression * negative_square(mu, s),
            stiffness: 0.0,
            damping: 2.0 * self.rebound * positive_part(mu, s) - 2.0 * self.compression * negative_part(mu, s),
        }
    }
    fn impulse(&self, _x: f64, v: f64, kappa: f64, tau: f64) -> f64 {
        // v − v(τ) = v · r/(1 + r), r = κ q |v| τ
        let r = kappa * self.coefficient(v) * v.abs() * tau;
        v * r / (1.0 + r) / kappa
    }
    fn potential(&self, _x: f64) -> Option<f64> {
        None
    }
    fn stiffness_bound(&self, _m: &ElementMoments) -> f64 {
        0.0
    }
}
