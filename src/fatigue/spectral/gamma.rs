//! Incomplete-gamma moments shared by the spectral methods (private).
//!
//! Every method's damage is a sum of terms ∫_{s_e}^∞ s^k p(s) ds over Rayleigh, Weibull or exponential
//! densities, each an upper incomplete gamma function Γ(a, x) = ∫_x^∞ t^{a−1} e^{−t} dt. They are formed
//! in logarithms so that large k (Γ(1+k) overflows near k = 170) and large stress units do not overflow.

use statrs::function::gamma::{gamma_ur, ln_gamma};

/// ln Γ(a, x) for a > 0, x ≥ 0 (ln Γ(a) at x = 0; −∞ when the regularised Q(a, x) underflows to 0).
pub(crate) fn ln_upper_gamma(a: f64, x: f64) -> f64 {
    let lg = ln_gamma(a);
    if x <= 0.0 {
        return lg;
    }
    let q = gamma_ur(a, x);
    if q > 0.0 {
        lg + q.ln()
    } else {
        f64::NEG_INFINITY
    }
}

/// ln of ∫_{s_e}^∞ s^k p(s) ds for the Rayleigh density p(s) = (s/σ²) e^{−s²/2σ²} of scale σ:
/// (√2 σ)^k Γ(1 + k/2, s_e²/(2σ²)).
pub(crate) fn ln_rayleigh_moment(sigma: f64, k: f64, s_e: f64) -> f64 {
    let x = if s_e > 0.0 {
        s_e * s_e / (2.0 * sigma * sigma)
    } else {
        0.0
    };
    k * (std::f64::consts::SQRT_2 * sigma).ln() + ln_upper_gamma(1.0 + 0.5 * k, x)
}

/// The Rayleigh density of scale σ at s ≥ 0.
pub(crate) fn rayleigh_pdf(sigma: f64, s: f64) -> f64 {
    if s < 0.0 {
        return 0.0;
    }
    let v = sigma * sigma;
    s / v * (-0.5 * s * s / v).exp()
}

/// The endurance limit of a curve as a number (0 without one).
pub(crate) fn limit(sn: &crate::fatigue::SnCurve) -> f64 {
    sn.endurance_limit().unwrap_or(0.0)
}
