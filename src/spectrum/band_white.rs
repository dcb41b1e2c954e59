//! Band-limited white noise.

use super::{Asymptote, Convention, Domain, Spectrum};
use crate::error::{require_non_negative, Error, Result};

/// White noise of constant two-sided density S₀ on the band ω₁ ≤ |ω| ≤ ω₂, zero outside.
///
/// # Formula
/// ```text
/// S(ω) = S₀ for ω₁ ≤ |ω| ≤ ω₂,     D = 2 S₀ (ω₂ − ω₁),
/// K(τ) = 2 S₀ (sin ω₂τ − sin ω₁τ) / τ
/// ```
///
/// # Errors
/// Constructors reject a negative level, non-finite values, ω₁ < 0 and ω₂ ≤ ω₁ (an infinite ω₂ is
/// rejected: ideal white noise has infinite variance).
///
/// # Examples
/// ```
/// use stochvib::spectrum::{BandWhiteParameters, Convention, Domain, Spectrum};
/// // A one-sided 1e-3 m²/Hz level from 1 Hz to 10 Hz: variance 9e-3 m².
/// let w = BandWhiteParameters {
///     convention: Convention::OneSidedCyclic,
///     level: 1e-3,
///     lo: 1.0,
///     hi: 10.0,
///     domain: Domain::Temporal,
/// }
/// .build()
/// .unwrap();
/// assert!((w.variance().unwrap() - 9e-3).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BandWhite {
    level: f64,
    lo: f64,
    hi: f64,
    domain: Domain,
}

/// The parameters of a [`BandWhite`] density (a level between two band edges, written in a `convention`) as
/// named fields.
///
/// # Errors
/// As [`BandWhite`]'s `# Errors`.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{BandWhiteParameters, Convention, Domain, Spectrum};
/// let w = BandWhiteParameters {
///     convention: Convention::TwoSidedAngular,
///     level: 1e-3,
///     lo: 0.0,
///     hi: 4.5,
///     domain: Domain::Temporal,
/// }
/// .build()
/// .unwrap();
/// assert!((w.variance().unwrap() - 9e-3).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandWhiteParameters {
    /// How `level`, `lo` and `hi` are written (band edges in Hz or cycles/m for `OneSidedCyclic`, in rad/s or
    /// rad/m otherwise).
    pub convention: Convention,
    /// The density level ≥ 0 in `convention`.
    pub level: f64,
    /// The lower band edge ≥ 0 in `convention`.
    pub lo: f64,
    /// The upper band edge > `lo` in `convention`.
    pub hi: f64,
    /// Temporal or spatial.
    pub domain: Domain,
}

impl BandWhiteParameters {
    /// The [`BandWhite`] of these parameters, checked.
    ///
    /// # Errors
    /// See [`BandWhite`]'s `# Errors`.
    pub fn build(self) -> Result<BandWhite> {
        let BandWhiteParameters {
            convention,
            level,
            lo,
            hi,
            domain,
        } = self;
        require_non_negative("level", level)?;
        require_non_negative("band.low", lo)?;
        if !(hi.is_finite() && hi > lo) {
            return Err(Error::invalid(
                "band.high",
                hi,
                format!("must be finite and > band.low = {lo}"),
            ));
        }
        let (w1, s0) = convention.to_canonical(lo, level);
        let (w2, _) = convention.to_canonical(hi, level);
        Ok(BandWhite {
            level: s0,
            lo: w1,
            hi: w2,
            domain,
        })
    }
}

impl Spectrum for BandWhite {
    fn describe(&self) -> String {
        format!(
            "band-limited white: S0 = {} (two-sided) on {} <= |w| <= {} {}",
            crate::numbers::num(self.level),
            crate::numbers::num(self.lo),
            crate::numbers::num(self.hi),
            self.domain.angular_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.domain
    }
    fn density(&self, omega: f64) -> f64 {
        let w = omega.abs();
        if w >= self.lo && w <= self.hi {
            self.level
        } else {
            0.0
        }
    }
    fn high_frequency(&self) -> Asymptote {
        Asymptote::Vanishing
    }
    fn low_frequency(&self) -> Asymptote {
        if self.lo > 0.0 {
            Asymptote::Vanishing
        } else {
            Asymptote::Power {
                exponent: 0.0,
                coefficient: self.level,
            }
        }
    }
    fn support(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }
    fn variance(&self) -> Result<f64> {
        Ok(2.0 * self.level * (self.hi - self.lo))
    }
    fn correlation(&self, tau: f64) -> Result<f64> {
        if tau == 0.0 {
            return self.variance();
        }
        Ok(2.0 * self.level * ((self.hi * tau).sin() - (self.lo * tau).sin()) / tau)
    }
}
