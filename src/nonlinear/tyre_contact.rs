//! Unilateral tyre contact: the tyre's linear spring k_t cannot pull, so the wheel lifts off the road when
//! its dynamic deflection exceeds the static one.
//!
//! # Formula
//! The element sits across a linear spring k_t (the tyre of the linear model) that carries the static load
//! P at equilibrium, a static compression s₀ = P/k_t. With x the spring's deflection from equilibrium
//! (positive when stretched, i.e. the wheel above its static position relative to the road), the tyre's
//! compression is s₀ − x and its force k_t (s₀ − x)₊ can only push. Relative to the static load the element
//! force is k_t x in contact and P off the ground, so the remainder beyond the linear spring is
//! ```text
//! F(x) = −k_t (x − s₀)₊,     V(x) = −k_t (x − s₀)₊²/2
//! E[F] = −k_t[(μ − s₀)Φ(h) + σφ(h)],   k_eq = −k_t Φ(h),   h = (μ − s₀)/σ
//! ```
//! so the total equivalent stiffness is k_t(1 − Φ(h)) = k_t P(contact). The Gaussian closure is meaningful
//! only while lift-off is rare (P(lift-off) = Φ(h) ≲ 10⁻²); the classical rule σ(dynamic tyre force) ≤ P/3
//! is P(lift-off) ≤ Φ(−3) = 1.35·10⁻³ for a Gaussian response.
//!
//! # Errors
//! [`TyreContact::new`] rejects a tyre stiffness or static load that is not finite and > 0.
//!
//! # Examples
//! ```
//! use stochvib::nonlinear::{ForceLaw, TyreContact};
//! let t = TyreContact::new(200e3, 4000.0).unwrap(); // s₀ = 2 cm
//! assert_eq!(t.force(0.01, 0.0), 0.0); // still in contact: the linear spring is the whole force
//! assert!((200e3 * 0.03 + t.force(0.03, 0.0) - 4000.0).abs() < 1e-9); // off the ground: the static load
//! ```

use super::gauss::{positive_part, prob_positive};
use super::{ElementMoments, Equivalent, ForceLaw, Kernel, Regime};
use crate::error::{Error, Result};

/// Unilateral contact of a tyre spring (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TyreContact {
    /// k_t, N/m (the stiffness of the linear spring it sits across).
    pub stiffness: f64,
    /// P, N: the static load the tyre carries.
    pub static_load: f64,
}

impl TyreContact {
    /// Contact of a tyre spring of stiffness k_t (N/m) carrying the static load P (N).
    ///
    /// # Errors
    /// See the module's `# Errors`.
    pub fn new(stiffness: f64, static_load: f64) -> Result<Self> {
        if !(stiffness.is_finite() && stiffness > 0.0) {
            return Err(Error::invalid(
                "stiffness",
                stiffness,
                "the tyre spring must have a finite stiffness > 0",
            ));
        }
        if !(static_load.is_finite() && static_load > 0.0) {
            return Err(Error::invalid("static_load", static_load, "must be finite and > 0"));
        }
        Ok(TyreContact { stiffness, static_load })
    }

    /// s₀ = P/k_t, m: the deflection at which the wheel leaves the road.
    pub fn static_deflection(&self) -> f64 {
        self.static_load / self.stiffness
    }
}

impl ForceLaw for TyreContact {
    fn kind(&self) -> &'static str {
        "tyre-contact"
    }
    fn describe(&self) -> String {
        format!(
            "unilateral tyre contact: k_t = {} N/m, static load {} N (lift-off at a deflection of {} m)",
            self.stiffness,
            self.static_load,
            self.static_deflection()
        )
    }
    fn force(&self, x: f64, _v: f64) -> f64 {
        -self.stiffness * (x - self.static_deflection()).max(0.0)
    }
    fn velocity_dependent(&self) -> bool {
        false
    }
    fn is_zero(&self) -> bool {
        false
    }
    fn gaussian(&self, m: &ElementMoments) -> Equivalent {
        let z = m.mean_x - self.static_deflection();
        Equivalent {
            mean_force: -self.stiffness * positive_part(z, m.sigma_x),
            stiffness: -self.stiffness * prob_positive(z, m.sigma_x),
            damping: 0.0,
        }
    }
    fn potential(&self, x: f64) -> Option<f64> {
        Some(-0.5 * self.stiffness * (x - self.static_deflection()).max(0.0).powi(2))
    }
    fn kinks(&self) -> Vec<f64> {
        vec![self.static_deflection()]
    }
    fn regime(&self) -> Option<Regime> {
        Some(Regime {
            fraction: "lift_off_fraction",
            rate: "lift_off_rate",
            levels: vec![(self.static_deflection(), true)],
        })
    }
    fn engaged(&self, x: f64) -> bool {
        x > self.static_deflection()
    }
    fn kernel(&self, _kappa: f64, tau: f64) -> Option<Kernel> {
        Some(Kernel::Lift {
            stiffness: self.stiffness,
            deflection: self.static_deflection(),
            tau,
        })
    }
    fn stiffness_bound(&self, _m: &ElementMoments) -> f64 {
        self.stiffness
    }
}
