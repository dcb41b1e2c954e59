//! Amplitude envelopes a(t) of modulated inputs: u(t) = a(t)·s(t) with s stationary.

use super::speed_profile::rename;
use super::PiecewiseLinear;
use crate::error::{Error, Result};

/// A deterministic envelope a(t) (dimensionless) multiplying a stationary input process s(t): u(t) =
/// a(t)·s(t) is a uniformly modulated process (Priestley's evolutionary process with a
/// frequency-independent modulation), e.g. a load that builds up on start-up.
///
/// # Formula
/// Given as the amplitude a(t) or as the intensity e(t) = a(t)² (the factor on the variance, or on the
/// white-noise density: S₀(t) = e(t)S₀), each piecewise linear through its table and constant outside it
/// (see [`PiecewiseLinear`]):
/// ```text
/// amplitude table:  a(t) = table(t),          ȧ = slope
/// intensity table:  a(t) = √table(t) (≥ 0),   ȧ = slope/(2a)
/// ```
///
/// # Errors
/// A non-finite value or time, times that do not increase strictly (named `envelope[k]` / `time[k]`), a
/// negative intensity.
///
/// # Examples
/// ```
/// use stochvib::transient::Envelope;
/// let a = Envelope::ramp(2.0).unwrap(); // 0 at t = 0, 1 from t = 2 s on
/// assert_eq!(a.value(1.0), 0.5);
/// let e = Envelope::intensity(vec![0.0, 4.0], vec![0.0, 1.0]).unwrap(); // S₀ ramps linearly
/// assert_eq!(e.value(1.0), 0.5);
/// assert!(Envelope::table(vec![0.0, 1.0], vec![0.0, f64::NAN]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Envelope {
    table: PiecewiseLinear,
    intensity: bool,
}

impl Envelope {
    /// The amplitude envelope through (t\[k\], a\[k\]).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn table(times: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        let table = PiecewiseLinear::new(times, values).map_err(|e| rename(e, "value", "envelope"))?;
        Ok(Envelope {
            table,
            intensity: false,
        })
    }

    /// The intensity envelope e(t) = a(t)² through (t\[k\], e\[k\]), e ≥ 0.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn intensity(times: Vec<f64>, values: Vec<f64>) -> Result<Self> {
        let table = PiecewiseLinear::new(times, values).map_err(|e| rename(e, "value", "envelope"))?;
        if let Some((k, v)) = table.values().iter().enumerate().find(|(_, v)| **v < 0.0) {
            return Err(Error::invalid(
                &format!("envelope[{k}]"),
                v,
                "an intensity (the factor on the variance) is >= 0",
            ));
        }
        Ok(Envelope { table, intensity: true })
    }

    /// a = 1 everywhere (a stationary input).
    pub fn unit() -> Self {
        Envelope {
            table: PiecewiseLinear::constant(1.0).expect("1 is finite"),
            intensity: false,
        }
    }

    /// A linear rise of the amplitude from 0 at t = 0 to 1 at `rise_time` (s), then 1.
    ///
    /// # Errors
    /// A rise time that is not finite and > 0.
    pub fn ramp(rise_time: f64) -> Result<Self> {
        Self::table(vec![0.0, rise_time], vec![0.0, 1.0])
    }

    /// a(t).
    pub fn value(&self, t: f64) -> f64 {
        let v = self.table.value(t);
        if self.intensity {
            v.sqrt()
        } else {
            v
        }
    }

    /// da/dt (for an intensity table: ė/(2a); 0 where a = 0 and e is flat).
    pub fn slope(&self, t: f64) -> f64 {
        let s = self.table.slope(t);
        if !self.intensity {
            return s;
        }
        let a = self.value(t);
        if s == 0.0 {
            0.0
        } else {
            s / (2.0 * a)
        }
    }

    /// Whether a ≡ 1.
    pub fn is_unit(&self) -> bool {
        self.table.is_constant() && self.table.values()[0] == 1.0
    }

    /// Whether the table is an intensity e = a².
    pub fn is_intensity(&self) -> bool {
        self.intensity
    }

    /// The table.
    pub fn points(&self) -> &PiecewiseLinear {
        &self.table
    }

    /// Times where the table has a kink.
    pub fn knots(&self) -> &[f64] {
        self.table.times()
    }
}
