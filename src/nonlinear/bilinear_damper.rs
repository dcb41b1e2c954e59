//! Asymmetric (bilinear) damper: rebound coefficient c_r for extension (v > 0), compression coefficient
//! c_c for v < 0.
//!
//! # Formula
//! v is the element's relative velocity, positive when it extends (rebound). With c̄ = (c_r + c_c)/2 and
//! Δ = (c_r − c_c)/2:
//! ```text
//! F(v) = c_r v (v > 0),  c_c v (v < 0)  =  c̄ v + Δ|v|          (linear part c̄ v, remainder Δ|v|)
//! ```
//! For v ~ N(μ, σ²), h = μ/σ: E[Δ|v|] = Δ[μ(2Φ(h) − 1) + 2σφ(h)], c_eq = E[Δ sgn v] = Δ(2Φ(h) − 1); for the
//! whole damper E[F] = c_cμ + (c_r − c_c)[μΦ(h) + σφ(h)] and c_eq = c_c + (c_r − c_c)Φ(h). A stationary
//! response has μ = 0, so E[F] = (c_r − c_c)σ/√(2π): a rebound-stiffer damper pulls the body down
//! (jacking), the mean deflection is −E[F]/k of the spring in parallel.
//!
//! The remainder's own flow v′ = −κΔ|v| keeps the sign of v: v(τ) = v₀ e^{−κΔτ sgn v₀} (exact), so route 2
//! applies it without a step-size limit.
//!
//! # Errors
//! [`BilinearDamper::new`] rejects negative or non-finite coefficients.
//!
//! # Examples
//! ```
//! use stochvib::nonlinear::{BilinearDamper, ForceLaw};
//! let d = BilinearDamper::new(3.0, 1.0).unwrap();
//! assert_eq!(d.linear_part(), (0.0, 2.0));
//! assert_eq!(2.0 * 0.5 + d.force(0.0, 0.5), 3.0 * 0.5);
//! assert_eq!(2.0 * -0.5 + d.force(0.0, -0.5), 1.0 * -0.5);
//! ```

use super::gauss::{pdf, prob_positive, standardized};
use super::{ElementMoments, Equivalent, ForceLaw, Kernel};
use crate::error::{Error, Result};

/// A bilinear damper (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BilinearDamper {
    /// c_r, N s/m, for v > 0 (extension, rebound).
    pub rebound: f64,
    /// c_c, N s/m, for v < 0 (compression).
    pub compression: f64,
}

impl BilinearDamper {
    /// A damper of rebound coefficient c_r and compression coefficient c_c (N s/m).
    ///
    /// # Errors
    /// See the module's `# Errors`.
    pub fn new(rebound: f64, compression: f64) -> Result<Self> {
        for (name, c) in [("rebound_damping", rebound), ("compression_damping", compression)] {
            if !(c.is_finite() && c >= 0.0) {
                return Err(Error::invalid(name, c, "must be finite and >= 0"));
            }
        }
        Ok(BilinearDamper { rebound, compression })
    }

    fn half_difference(&self) -> f64 {
        0.5 * (self.rebound - self.compression)
    }
}

impl ForceLaw for BilinearDamper {
    fn kind(&self) -> &'static str {
        "bilinear-damper"
    }
    fn describe(&self) -> String {
        format!(
            "bilinear damper: rebound (extension) {} N s/m, compression {} N s/m",
            self.rebound, self.compression
        )
    }
    fn linear_part(&self) -> (f64, f64) {
        (0.0, 0.5 * (self.rebound + self.compression))
    }
    fn force(&self, _x: f64, v: f64) -> f64 {
        self.half_difference() * v.abs()
    }
    fn velocity_dependent(&self) -> bool {
        true
    }
    fn is_zero(&self) -> bool {
        self.rebound == self.compression
    }
    fn gaussian(&self, m: &ElementMoments) -> Equivalent {
        let (mu, s, dl) = (m.mean_v, m.sigma_v, self.half_difference());
        let h = standardized(mu, s);
        let two_phi = 2.0 * prob_positive(mu, s) - 1.0;
        let spdf = if s > 0.0 { s * pdf(h) } else { 0.0 };
        Equivalent {
            mean_force: dl * (mu * two_phi + 2.0 * spdf),
            stiffness: 0.0,
            damping: dl * two_phi,
        }
    }
    fn impulse(&self, _x: f64, v: f64, kappa: f64, tau: f64) -> f64 {
        let rate = kappa * self.half_difference() * tau;
        if rate == 0.0 || v == 0.0 {
            return 0.0;
        }
        // v(τ) = v e^{−rate sgn v}; impulse = (v − v(τ))/κ
        -v * (-rate * v.signum()).exp_m1() / kappa
    }
    fn kernel(&self, kappa: f64, tau: f64) -> Option<Kernel> {
        Some(Kernel::bilinear(self.half_difference(), kappa, tau))
    }
    fn potential(&self, _x: f64) -> Option<f64> {
        None
    }
    fn stiffness_bound(&self, _m: &ElementMoments) -> f64 {
        0.0
    }
}
