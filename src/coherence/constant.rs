//! A coherence amplitude that does not depend on the spatial frequency.

use super::Coherence;
use crate::error::{Error, Result};

/// ρ(n) = ρ₀ for every n: ρ₀ = 1 makes the two tracks identical, ρ₀ = 0 makes them independent.
///
/// # Formula
/// ```text
/// ρ(n) = ρ₀,   γ²(n) = ρ₀²,   S_LR = ρ₀ S
/// ```
///
/// # Errors
/// [`ConstantCoherence::new`] rejects ρ₀ outside [0, 1] or non-finite.
///
/// # Examples
/// ```
/// use stochvib::coherence::{Coherence, ConstantCoherence};
/// let c = ConstantCoherence::new(0.5).unwrap();
/// assert_eq!(c.coherence_amplitude(3.0), 0.5);
/// assert_eq!(c.squared_coherence(3.0), 0.25);
/// assert!(ConstantCoherence::new(1.2).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstantCoherence {
    rho: f64,
}

impl ConstantCoherence {
    /// ρ(n) = `rho` (the coherence amplitude, not its square).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(rho: f64) -> Result<Self> {
        if !(rho.is_finite() && (0.0..=1.0).contains(&rho)) {
            return Err(Error::invalid(
                "coherence_amplitude",
                rho,
                "must be finite and in [0, 1]",
            ));
        }
        Ok(ConstantCoherence { rho })
    }
}

impl Coherence for ConstantCoherence {
    fn describe(&self) -> String {
        format!("constant coherence amplitude ρ = {}", crate::numbers::num(self.rho))
    }
    fn coherence_amplitude(&self, n: f64) -> f64 {
        if n.is_finite() {
            self.rho
        } else {
            f64::NAN
        }
    }
    fn constant_amplitude(&self) -> Option<f64> {
        Some(self.rho)
    }
}
