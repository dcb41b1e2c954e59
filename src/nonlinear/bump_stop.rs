//! Bump stop: an elastic contact spring that engages beyond a clearance, on one side or both, each side
//! with its own clearance and contact stiffness.
//!
//! # Formula
//! With deflection x (positive when the element is stretched), upper clearance d_u, lower clearance d_l
//! and contact stiffnesses k_u, k_l:
//! ```text
//! F(x) = k_u (x − d_u)₊ − k_l (−d_l − x)₊,      V(x) = k_u (x − d_u)₊²/2 + k_l (−d_l − x)₊²/2
//! ```
//! For x ~ N(μ, σ²), with h_u = (μ − d_u)/σ and h_l = (−d_l − μ)/σ:
//! ```text
//! E[F] = k_u[(μ − d_u)Φ(h_u) + σφ(h_u)] + k_l[(μ + d_l)Φ(h_l) − σφ(h_l)],   k_eq = k_uΦ(h_u) + k_lΦ(h_l)
//! ```
//! (the positive-part moments of [`super::gauss`]). A very stiff stop approaches a rigid, perfectly
//! elastic wall; under white noise the exact variance then tends to that of the normal law truncated to
//! [−d_l, d_u], with an error of order k^{−1/2}.
//!
//! # Errors
//! [`BumpStop::new`] rejects a negative or non-finite clearance, a contact stiffness that is not finite and
//! > 0, and a stop with neither side.
//!
//! # Examples
//! ```
//! use stochvib::nonlinear::{BumpStop, ElementMoments, ForceLaw};
//! let s = BumpStop::new(Some((0.5, 10.0)), None).unwrap(); // upper side only
//! assert_eq!(s.force(0.75, 0.0), 10.0 * 0.25);
//! assert_eq!(s.force(-3.0, 0.0), 0.0);
//! ```

use super::gauss::{negative_part, positive_part, prob_positive};
use super::{ElementMoments, Equivalent, ForceLaw, Kernel, Regime};
use crate::error::{Error, Result};

/// One side of a stop: clearance (m) and contact stiffness (N/m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopSide {
    /// Clearance d ≥ 0 from the static equilibrium, m.
    pub clearance: f64,
    /// Contact stiffness k > 0, N/m.
    pub stiffness: f64,
}

/// A one- or two-sided elastic stop (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BumpStop {
    /// Engages when x > d_u.
    pub upper: Option<StopSide>,
    /// Engages when x < −d_l.
    pub lower: Option<StopSide>,
}

fn side(name: &str, s: Option<(f64, f64)>) -> Result<Option<StopSide>> {
    let Some((d, k)) = s else { return Ok(None) };
    if !(d.is_finite() && d >= 0.0) {
        return Err(Error::invalid(
            &format!("{name}_clearance"),
            d,
            "must be finite and >= 0 (a distance from the static equilibrium to the stop)",
        ));
    }
    if !(k.is_finite() && k > 0.0) {
        return Err(Error::invalid(
            &format!("{name}_stiffness"),
            k,
            "must be finite and > 0",
        ));
    }
    Ok(Some(StopSide {
        clearance: d,
        stiffness: k,
    }))
}

impl BumpStop {
    /// A stop with an upper side (clearance, stiffness) engaging for x > d_u and/or a lower side engaging
    /// for x < −d_l.
    ///
    /// # Errors
    /// See the module's `# Errors`.
    pub fn new(upper: Option<(f64, f64)>, lower: Option<(f64, f64)>) -> Result<Self> {
        if upper.is_none() && lower.is_none() {
            return Err(Error::invalid(
                "upper_clearance",
                "<missing>",
                "a bump stop needs an upper side, a lower side or both",
            ));
        }
        Ok(BumpStop {
            upper: side("upper", upper)?,
            lower: side("lower", lower)?,
        })
    }
}

impl ForceLaw for BumpStop {
    fn kind(&self) -> &'static str {
        "bump-stop"
    }
    fn describe(&self) -> String {
        let s = |name: &str, s: &Option<StopSide>| match s {
            Some(s) => format!(
                "{name} clearance {} m, contact stiffness {} N/m",
                s.clearance, s.stiffness
            ),
            None => format!("no {name} side"),
        };
        format!("bump stop: {}; {}", s("upper", &self.upper), s("lower", &self.lower))
    }
    fn force(&self, x: f64, _v: f64) -> f64 {
        let up = self.upper.map_or(0.0, |s| s.stiffness * (x - s.clearance).max(0.0));
        let lo = self.lower.map_or(0.0, |s| s.stiffness * (-s.clearance - x).max(0.0));
        up - lo
    }
    fn velocity_dependent(&self) -> bool {
        false
    }
    fn is_zero(&self) -> bool {
        false
    }
    fn gaussian(&self, m: &ElementMoments) -> Equivalent {
        let (mu, s) = (m.mean_x, m.sigma_x);
        let mut e = Equivalent::default();
        if let Some(u) = self.upper {
            e.mean_force += u.stiffness * positive_part(mu - u.clearance, s);
            e.stiffness += u.stiffness * prob_positive(mu - u.clearance, s);
        }
        if let Some(l) = self.lower {
            // −k (−d − x)₊ = k (x + d) 1{x + d < 0}
            e.mean_force += l.stiffness * negative_part(mu + l.clearance, s);
            e.stiffness += l.stiffness * prob_positive(-l.clearance - mu, s);
        }
        e
    }
    fn potential(&self, x: f64) -> Option<f64> {
        let up = self
            .upper
            .map_or(0.0, |s| 0.5 * s.stiffness * (x - s.clearance).max(0.0).powi(2));
        let lo = self
            .lower
            .map_or(0.0, |s| 0.5 * s.stiffness * (-s.clearance - x).max(0.0).powi(2));
        Some(up + lo)
    }
    fn kinks(&self) -> Vec<f64> {
        self.upper
            .map(|s| s.clearance)
            .into_iter()
            .chain(self.lower.map(|s| -s.clearance))
            .collect()
    }
    fn regime(&self) -> Option<Regime> {
        Some(Regime {
            fraction: "contact_fraction",
            rate: "impact_rate",
            levels: self
                .upper
                .map(|s| (s.clearance, true))
                .into_iter()
                .chain(self.lower.map(|s| (-s.clearance, false)))
                .collect(),
        })
    }
    fn engaged(&self, x: f64) -> bool {
        self.upper.is_some_and(|s| x > s.clearance) || self.lower.is_some_and(|s| x < -s.clearance)
    }
    fn kernel(&self, _kappa: f64, tau: f64) -> Option<Kernel> {
        let side = |s: Option<StopSide>| s.map(|s| (s.clearance, s.stiffness));
        Some(Kernel::Stop {
            upper: side(self.upper),
            lower: side(self.lower),
            tau,
        })
    }
    fn stiffness_bound(&self, _m: &ElementMoments) -> f64 {
        let k = |s: Option<StopSide>| s.map_or(0.0, |s| s.stiffness);
        k(self.upper).max(k(self.lower))
    }
}
