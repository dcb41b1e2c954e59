//! A spectrum restricted to a band: an explicit band given to a spectrum that has none of its own.

use super::{Asymptote, Domain, Spectrum};
use crate::error::{Error, Result};
use std::sync::Arc;

/// The spectrum S restricted to the band ω₁ ≤ |ω| ≤ ω₂ (zero outside).
///
/// # Formula
/// ```text
/// S_b(ω) = S(ω) for ω₁ ≤ |ω| ≤ ω₂,  0 otherwise;        D_b = 2 ∫_{ω₁}^{ω₂} S(ω) dω
/// ```
/// (ω in rad/s, or rad/m for a spatial spectrum). A restriction is not rational: the Lyapunov route does
/// not apply, variances come from quadrature. For spectra with a band of their own (ISO 8608 and other
/// power laws, band-limited white noise) the scenario's `band` key changes that band instead, continuing
/// the law to the new edges.
///
/// # Errors
/// [`BandLimited::new`] rejects ω₁ < 0, ω₂ ≤ ω₁ and non-finite edges.
///
/// # Examples
/// ```
/// use stochvib::spectrum::{BandLimited, Domain, Exponential, Spectrum};
/// use std::sync::Arc;
/// // type 1 (D = 1, α = 2 rad/s) on 0 ≤ |ω| ≤ 2 rad/s: D_b = (2/π) atan(ω₂/α) = 1/2
/// let s = Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap());
/// let b = BandLimited::new(s, 0.0, 2.0).unwrap();
/// assert!((b.variance().unwrap() - 0.5).abs() < 1e-10);
/// assert_eq!(b.density(2.5), 0.0);
/// ```
#[derive(Debug, Clone)]
pub struct BandLimited {
    inner: Arc<dyn Spectrum>,
    lo: f64,
    hi: f64,
}

impl BandLimited {
    /// `inner` restricted to `lo` ≤ |ω| ≤ `hi` (rad/s or rad/m).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(inner: Arc<dyn Spectrum>, lo: f64, hi: f64) -> Result<Self> {
        if !(lo.is_finite() && lo >= 0.0 && hi.is_finite() && hi > lo) {
            return Err(Error::invalid(
                "band",
                format!("[{lo}, {hi}]"),
                "need finite edges with 0 <= low < high",
            ));
        }
        Ok(BandLimited { inner, lo, hi })
    }
}

impl Spectrum for BandLimited {
    fn describe(&self) -> String {
        format!(
            "{} restricted to {} <= |w| <= {} {}",
            self.inner.describe(),
            crate::numbers::num(self.lo),
            crate::numbers::num(self.hi),
            self.domain().angular_unit()
        )
    }
    fn domain(&self) -> Domain {
        self.inner.domain()
    }
    fn density(&self, omega: f64) -> f64 {
        let w = omega.abs();
        if w >= self.lo && w <= self.hi {
            self.inner.density(omega)
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
            self.inner.low_frequency()
        }
    }
    fn support(&self) -> (f64, f64) {
        let (a, b) = self.inner.support();
        (a.max(self.lo), b.min(self.hi))
    }
    fn breakpoints(&self) -> Vec<f64> {
        let mut b: Vec<f64> = self
            .inner
            .breakpoints()
            .into_iter()
            .filter(|w| *w > self.lo && *w < self.hi)
            .collect();
        if self.lo > 0.0 {
            b.push(self.lo);
        }
        b.push(self.hi);
        b
    }
}
