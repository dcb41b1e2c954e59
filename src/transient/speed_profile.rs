//! Speed profiles v(t) of a vehicle over a spatial road.

use super::PiecewiseLinear;
use crate::error::{Error, Result};

/// A speed profile of constant acceleration: v₀ until t₀, then constant acceleration a (negative to brake)
/// until v₁, then v₁ ([`ConstantAcceleration::build`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConstantAcceleration {
    /// The speed v₀ before the manoeuvre, m/s.
    pub from_m_s: f64,
    /// The speed v₁ after it, m/s.
    pub to_m_s: f64,
    /// The acceleration a, m/s² (negative to brake).
    pub acceleration_m_s2: f64,
    /// The start t₀ of the manoeuvre, s.
    pub start_s: f64,
}

impl ConstantAcceleration {
    /// The profile v₀ until t₀, then v₀ + a(t − t₀) until v₁, then v₁.
    ///
    /// # Errors
    /// Negative speeds, a = 0 with v₀ ≠ v₁, an acceleration whose sign never reaches v₁, t₀ < 0 (named
    /// `speed[k]`, `acceleration`, `start`).
    pub fn build(self) -> Result<SpeedProfile> {
        let ConstantAcceleration {
            from_m_s: v0,
            to_m_s: v1,
            acceleration_m_s2: a,
            start_s: t0,
        } = self;
        if !(t0.is_finite() && t0 >= 0.0) {
            return Err(Error::invalid("start", t0, "the manoeuvre starts at a time >= 0"));
        }
        if !a.is_finite() {
            return Err(Error::invalid("acceleration", a, "must be finite"));
        }
        if v0 == v1 {
            return SpeedProfile::table(vec![0.0], vec![v0]);
        }
        if a == 0.0 || (v1 - v0).signum() != a.signum() {
            return Err(Error::invalid(
                "acceleration",
                a,
                format!("goes the wrong way from {v0} m/s to {v1} m/s (positive to speed up, negative to brake)"),
            ));
        }
        let t1 = t0 + (v1 - v0) / a;
        let (t, v) = if t0 > 0.0 {
            (vec![0.0, t0, t1], vec![v0, v0, v1])
        } else {
            (vec![t0, t1], vec![v0, v1])
        };
        SpeedProfile::table(t, v)
    }
}

/// A speed profile v(t) ≥ 0 (m/s) from the start of the manoeuvre t = 0, and the distance travelled
/// x(t) = ∫₀ᵗ v ds, which maps the spatial road onto time.
///
/// # Formula
/// Piecewise linear between the points of a table, or constant acceleration a from v₀ to v₁ starting at
/// t₀ ([`ConstantAcceleration`]):
/// ```text
/// v(t) = v₀ (t ≤ t₀),   v₀ + a(t − t₀) (t₀ ≤ t ≤ t₀ + (v₁ − v₀)/a),   v₁ afterwards
/// ```
///
/// # Errors
/// A negative or non-finite speed (named with its index), times that are not strictly increasing (a
/// profile that is not a function of time), an acceleration of zero or of the wrong sign.
///
/// # Examples
/// ```
/// use stochvib::transient::{ConstantAcceleration, SpeedProfile};
/// // braking from 60 km/h to rest at 4 m/s², from t = 1 s
/// let v = ConstantAcceleration { from_m_s: 60.0 / 3.6, to_m_s: 0.0, acceleration_m_s2: -4.0, start_s: 1.0 }
///     .build()
///     .unwrap();
/// assert_eq!(v.speed(0.5), 60.0 / 3.6);
/// assert!((v.stop_time().unwrap() - (1.0 + 60.0 / 3.6 / 4.0)).abs() < 1e-12);
/// assert!(SpeedProfile::table(vec![0.0, 1.0], vec![1.0, -1.0]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SpeedProfile {
    v: PiecewiseLinear,
}

impl SpeedProfile {
    /// The piecewise-linear profile through (t\[k\], v\[k\]).
    ///
    /// # Errors
    /// See the type's `# Errors` (`speed[k]` names a negative speed).
    pub fn table(times: Vec<f64>, speeds: Vec<f64>) -> Result<Self> {
        let v = PiecewiseLinear::new(times, speeds).map_err(|e| rename(e, "value", "speed"))?;
        if let Some((k, s)) = v.values().iter().enumerate().find(|(_, s)| **s < 0.0) {
            return Err(Error::invalid(
                &format!("speed[{k}]"),
                s,
                "a speed is >= 0: the road is traversed in one direction (x(t) must not decrease)",
            ));
        }
        Ok(SpeedProfile { v })
    }

    /// Constant speed v (m/s).
    ///
    /// # Errors
    /// v < 0 or not finite.
    pub fn constant(v: f64) -> Result<Self> {
        Self::table(vec![0.0], vec![v])
    }

    /// v(t), m/s.
    pub fn speed(&self, t: f64) -> f64 {
        self.v.value(t)
    }

    /// dv/dt, m/s².
    pub fn acceleration(&self, t: f64) -> f64 {
        self.v.slope(t)
    }

    /// x(t) = ∫₀ᵗ v ds, m.
    pub fn distance(&self, t: f64) -> f64 {
        self.v.integral(t)
    }

    /// The first time the vehicle stands (v = 0 from then on), if it comes to rest.
    pub fn stop_time(&self) -> Option<f64> {
        let (t, v) = (self.v.times(), self.v.values());
        if *v.last()? != 0.0 {
            return None;
        }
        let k = v.iter().rposition(|s| *s != 0.0).map_or(0, |k| k + 1);
        Some(t[k])
    }

    /// The table behind the profile.
    pub fn table_points(&self) -> &PiecewiseLinear {
        &self.v
    }

    /// Times where v(t) has a kink.
    pub fn knots(&self) -> &[f64] {
        self.v.times()
    }
}

/// Renames the `value[k]` of a [`PiecewiseLinear`] error to `<to>[k]`.
pub(crate) fn rename(e: Error, from: &str, to: &str) -> Error {
    match e {
        Error::InvalidParameter { name, value, reason } => Error::InvalidParameter {
            name: name.replacen(from, to, 1),
            value,
            reason,
        },
        other => other,
    }
}
