//! Cubic (hardening or softening) spring: F = k₁ x + k₃ x³.
//!
//! # Formula
//! Linear part k₁ x; remainder k₃ x³. For x ~ N(μ, σ²):
//! ```text
//! E[k₃x³] = k₃(μ³ + 3μσ²),   k_eq = E[3k₃x²] = 3k₃(μ² + σ²),   V(x) = k₃x⁴/4
//! ```
//! With a zero-mean response the equivalent stiffness of the whole spring is k₁ + 3k₃σ² (Caughey 1963,
//! "Equivalent linearization techniques", J. Acoust. Soc. Am. 35(11), 1706–1711). A Duffing oscillator
//! x″ + 2ζω₀x′ + ω₀²(x + εx³) = w is this spring with k₁ = mω₀², k₃ = mω₀²ε.
//!
//! # Errors
//! [`CubicSpring::new`] rejects a negative or non-finite k₁ and a non-finite k₃ (k₃ < 0 is a softening
//! spring: allowed, but its potential is unbounded below and the response can escape).
//!
//! # Examples
//! ```
//! use stochvib::nonlinear::{CubicSpring, ElementMoments, ForceLaw};
//! let s = CubicSpring::new(2.0, 0.5).unwrap();
//! let m = ElementMoments { mean_x: 0.3, sigma_x: 0.8, ..Default::default() };
//! let e = s.gaussian(&m);
//! assert!((e.stiffness - 1.095).abs() < 1e-12); // 3·0.5·(0.09 + 0.64), the remainder only
//! ```

use super::{ElementMoments, Equivalent, ForceLaw};
use crate::error::{Error, Result};

/// A cubic spring (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubicSpring {
    /// k₁, N/m (the linear part).
    pub linear: f64,
    /// k₃, N/m³ (> 0 hardening, < 0 softening).
    pub cubic: f64,
}

impl CubicSpring {
    /// A spring k₁ x + k₃ x³.
    ///
    /// # Errors
    /// See the module's `# Errors`.
    pub fn new(linear: f64, cubic: f64) -> Result<Self> {
        if !(linear.is_finite() && linear >= 0.0) {
            return Err(Error::invalid("linear_stiffness", linear, "must be finite and >= 0"));
        }
        if !cubic.is_finite() {
            return Err(Error::invalid("cubic_stiffness", cubic, "must be finite"));
        }
        Ok(CubicSpring { linear, cubic })
    }
}

impl ForceLaw for CubicSpring {
    fn kind(&self) -> &'static str {
        "cubic-spring"
    }
    fn describe(&self) -> String {
        format!("cubic spring k₁ = {} N/m, k₃ = {} N/m³", self.linear, self.cubic)
    }
    fn linear_part(&self) -> (f64, f64) {
        (self.linear, 0.0)
    }
    fn force(&self, x: f64, _v: f64) -> f64 {
        self.cubic * x * x * x
    }
    fn velocity_dependent(&self) -> bool {
        false
    }
    fn is_zero(&self) -> bool {
        self.cubic == 0.0
    }
    fn softening(&self) -> bool {
        self.cubic < 0.0
    }
    fn gaussian(&self, m: &ElementMoments) -> Equivalent {
        let (mu, s2) = (m.mean_x, m.sigma_x * m.sigma_x);
        Equivalent {
            mean_force: self.cubic * (mu * mu * mu + 3.0 * mu * s2),
            stiffness: 3.0 * self.cubic * (mu * mu + s2),
            damping: 0.0,
        }
    }
    fn potential(&self, x: f64) -> Option<f64> {
        Some(0.25 * self.cubic * x.powi(4))
    }
    fn stiffness_bound(&self, m: &ElementMoments) -> f64 {
        let x = m.mean_x.abs() + 6.0 * m.sigma_x;
        3.0 * self.cubic.abs() * x * x
    }
}
