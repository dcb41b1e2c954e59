//! Named spectral-density conventions and their exact conversions to and from the canonical two-sided
//! angular density S(ω).

use crate::error::{Error, Result};
use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

/// A convention for writing a spectral density.
///
/// # Formula
/// With S(ω) the canonical two-sided angular density (ω in rad/s or rad/m):
///
/// | variant | abscissa x | ordinate | inverse |
/// |---|---|---|---|
/// | `TwoSidedAngular` | ω | S(ω) | S = value |
/// | `OneSidedAngular` | ω ≥ 0 | G(ω) = 2 S(ω) | S = G/2 |
/// | `OneSidedCyclic` | f = ω/2π ≥ 0 (Hz or cycles/m) | G(f) = 4π S(2πf) | S(ω) = G(ω/2π)/(4π) |
/// | `Engineering` | ω | Ŝ(ω) = 2π S(ω) | S = Ŝ/(2π) |
///
/// Each row integrates to the same variance: ∫_{−∞}^{∞} S dω = ∫_0^∞ G(ω) dω = ∫_0^∞ G(f) df
/// = (1/2π) ∫_{−∞}^{∞} Ŝ dω.
///
/// # Examples
/// ```
/// use stochvib::spectrum::Convention;
/// // ISO 8608 class A geometric mean: G_d(0.1 cycles/m) = 16e-6 m^3 (one-sided, cycles/m)
/// let (omega, s) = Convention::OneSidedCyclic.to_canonical(0.1, 16e-6);
/// assert!((omega - 0.2 * std::f64::consts::PI).abs() < 1e-15);
/// assert!((s - 16e-6 / (4.0 * std::f64::consts::PI)).abs() < 1e-20);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Convention {
    /// Canonical: S(ω), two-sided, angular frequency.
    TwoSidedAngular,
    /// G(ω) = 2S(ω), ω ≥ 0 (textbook (8.19)).
    OneSidedAngular,
    /// G(f) = 4πS(2πf), f ≥ 0 in Hz (temporal) or cycles/m (spatial; ISO 8608 G_d(n)).
    OneSidedCyclic,
    /// Ŝ(ω) = 2πS(ω), two-sided, with σ² = (1/2π)∫Ŝ dω (textbook (8.66)–(8.69)).
    Engineering,
}

impl Convention {
    /// All conventions, in a fixed order.
    pub const ALL: [Convention; 4] = [
        Convention::TwoSidedAngular,
        Convention::OneSidedAngular,
        Convention::OneSidedCyclic,
        Convention::Engineering,
    ];

    /// Converts a canonical point (ω, S(ω)) into this convention's (x, value).
    pub fn from_canonical(self, omega: f64, s: f64) -> (f64, f64) {
        match self {
            Convention::TwoSidedAngular => (omega, s),
            Convention::OneSidedAngular => (omega, 2.0 * s),
            Convention::OneSidedCyclic => (omega / (2.0 * PI), 4.0 * PI * s),
            Convention::Engineering => (omega, 2.0 * PI * s),
        }
    }

    /// Converts this convention's point (x, value) into the canonical (ω, S(ω)).
    pub fn to_canonical(self, x: f64, value: f64) -> (f64, f64) {
        match self {
            Convention::TwoSidedAngular => (x, value),
            Convention::OneSidedAngular => (x, value / 2.0),
            Convention::OneSidedCyclic => (2.0 * PI * x, value / (4.0 * PI)),
            Convention::Engineering => (x, value / (2.0 * PI)),
        }
    }

    /// Whether the abscissa is cyclic (Hz, cycles/m) rather than angular.
    pub fn is_cyclic(self) -> bool {
        matches!(self, Convention::OneSidedCyclic)
    }

    /// Whether the convention is one-sided (defined for x ≥ 0 only).
    pub fn is_one_sided(self) -> bool {
        matches!(self, Convention::OneSidedAngular | Convention::OneSidedCyclic)
    }

    /// The name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Convention::TwoSidedAngular => "two-sided-angular",
            Convention::OneSidedAngular => "one-sided-angular",
            Convention::OneSidedCyclic => "one-sided-cyclic",
            Convention::Engineering => "engineering",
        }
    }
}

impl fmt::Display for Convention {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Convention {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Convention::ALL.into_iter().find(|c| c.name() == s).ok_or_else(|| {
            Error::invalid(
                "convention",
                s,
                "expected one of two-sided-angular, one-sided-angular, one-sided-cyclic, engineering",
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::ULPS;

    /// Round trip of every convention at a few points: exact up to rounding.
    #[test]
    fn round_trip() {
        for c in Convention::ALL {
            for &(w, s) in &[(0.0, 1.0), (0.3, 2.5e-3), (12.0, 7.0)] {
                let (x, v) = c.from_canonical(w, s);
                let (w2, s2) = c.to_canonical(x, v);
                assert!((w2 - w).abs() <= ULPS * w.abs().max(1.0));
                assert!((s2 - s).abs() <= ULPS * s.abs());
            }
            assert_eq!(c.name().parse::<Convention>().unwrap(), c);
        }
        assert!("two-sided".parse::<Convention>().is_err());
    }
}
