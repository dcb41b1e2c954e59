//! Numerical variance, band variance and correlation of any [`Spectrum`] by adaptive quadrature, with
//! divergence checks from the asymptotes. These are the "second way" that checks every closed form.

use super::{Asymptote, Spectrum};
use crate::error::{Error, Result};
use crate::quad::{integrate, QuadOptions, QuadResult};
use std::f64::consts::PI;

/// Relative tolerance used by the numerical spectrum routines.
pub const REL_TOL: f64 = 1e-10;

/// Variance D = ∫ S dω = 2∫₀^∞ S dω by adaptive quadrature (independent of any closed form).
///
/// # Errors
/// [`Error::Divergent`] when the asymptotes make the integral infinite; [`Error::Quadrature`] when the
/// quadrature does not converge.
pub fn variance<S: Spectrum + ?Sized>(s: &S) -> Result<QuadResult> {
    check_integrable(s, "variance")?;
    let (lo, hi) = s.support();
    band_integral(s, lo, hi)
}

/// Band-limited variance 2∫_{ω₁}^{ω₂} S dω over ω₁ ≤ |ω| ≤ ω₂ (rad/s or rad/m), both sides of the axis.
///
/// # Errors
/// [`Error::InvalidParameter`] unless 0 ≤ ω₁ < ω₂; [`Error::Divergent`] for a band reaching ω = 0 or ∞
/// where S is not integrable.
pub fn band_variance<S: Spectrum + ?Sized>(s: &S, w1: f64, w2: f64) -> Result<QuadResult> {
    if !(w1 >= 0.0 && w2 > w1) || w1.is_nan() || w2.is_nan() {
        return Err(Error::invalid("band", format!("[{w1}, {w2}]"), "need 0 <= w1 < w2"));
    }
    let (lo, hi) = s.support();
    let (a, b) = (w1.max(lo), w2.min(hi));
    if a >= b {
        return Ok(QuadResult {
            value: 0.0,
            abs_error: 0.0,
            evaluations: 0,
        });
    }
    if b.is_infinite() || a == 0.0 {
        check_integrable(s, "band variance")?;
    }
    band_integral(s, a, b)
}

fn band_integral<S: Spectrum + ?Sized>(s: &S, a: f64, b: f64) -> Result<QuadResult> {
    let opts = QuadOptions {
        rel_tol: REL_TOL,
        breakpoints: s.breakpoints(),
        ..QuadOptions::default()
    };
    let r = integrate(|w| s.density(w), a, b, &opts)?;
    Ok(QuadResult {
        value: 2.0 * r.value,
        abs_error: 2.0 * r.abs_error,
        ..r
    })
}

/// Correlation K(τ) = 2∫₀^∞ S(ω) cos ωτ dω by quadrature.
///
/// # Formula
/// The head [0, W] (W a whole number of half-periods π/|τ| beyond the last breakpoint) is integrated with
/// the half-periods as breakpoints; the oscillatory tail is summed half-period by half-period and the
/// partial sums are extrapolated with Wynn's ε-algorithm (as QUADPACK's QAWF does).
///
/// # Errors
/// As [`variance`]; [`Error::Quadrature`] when the tail does not converge.
pub fn correlation<S: Spectrum + ?Sized>(s: &S, tau: f64) -> Result<QuadResult> {
    if !tau.is_finite() {
        return Err(Error::invalid("tau", tau, "must be finite"));
    }
    if tau == 0.0 {
        return variance(s);
    }
    check_integrable(s, "correlation")?;
    let t = tau.abs();
    let h = PI / t;
    let (lo, hi) = s.support();
    let bmax = s.breakpoints().into_iter().fold(lo.max(h), f64::max);
    let head_end = if hi.is_finite() {
        hi
    } else {
        (4.0 * bmax / h).ceil() * h
    };
    let mut bps = s.breakpoints();
    let first = (lo / h).ceil() as usize;
    let last = (head_end / h).floor() as usize;
    if last.saturating_sub(first) <= 4000 {
        bps.extend((first..=last).map(|k| k as f64 * h));
    }
    let f = |w: f64| s.density(w) * (w * t).cos();
    let opts = QuadOptions {
        rel_tol: REL_TOL,
        abs_tol: 0.0,
        max_subintervals: 20_000,
        breakpoints: bps,
    };
    let head = integrate(f, lo, head_end, &opts)?;
    let mut evaluations = head.evaluations;
    if hi.is_finite() {
        return Ok(QuadResult {
            value: 2.0 * head.value,
            abs_error: 2.0 * head.abs_error,
            evaluations,
        });
    }
    // Scale for absolute tolerances: the head's |S| integral.
    let scale = integrate(
        |w| s.density(w),
        lo,
        head_end,
        &QuadOptions {
            rel_tol: 1e-6,
            ..QuadOptions::default()
        },
    )?
    .value
    .abs()
    .max(f64::MIN_POSITIVE);
    let term_opts = QuadOptions {
        rel_tol: 1e-12,
        abs_tol: 1e-15 * scale,
        ..QuadOptions::default()
    };
    let mut sum = 0.0;
    let mut sums = Vec::new();
    let mut last_est = f64::NAN;
    let mut tail_err = f64::INFINITY;
    for k in 0..5000 {
        let a = head_end + k as f64 * h;
        let r = integrate(f, a, a + h, &term_opts)?;
        evaluations += r.evaluations;
        sum += r.value;
        if r.value.abs() < 1e-15 * scale {
            tail_err = r.value.abs() + r.abs_error;
            last_est = sum;
            break;
        }
        sums.push(sum);
        let est = wynn_epsilon(&sums);
        if k >= 3 {
            let diff = (est - last_est).abs();
            if diff < 1e-12 * scale {
                tail_err = diff;
                last_est = est;
                break;
            }
        }
        last_est = est;
    }
    if !tail_err.is_finite() {
        return Err(Error::Quadrature {
            what: format!("correlation at tau = {tau}"),
            estimate: 2.0 * (head.value + last_est),
            abs_error: f64::INFINITY,
            evaluations,
            reason: "oscillatory tail did not converge in 5000 half-periods".into(),
        });
    }
    Ok(QuadResult {
        value: 2.0 * (head.value + last_est),
        abs_error: 2.0 * (head.abs_error + tail_err),
        evaluations,
    })
}

/// Checks, from the asymptotes, that ∫ S dω is finite over the support.
///
/// # Errors
/// [`Error::Divergent`] with the reason and a suggestion.
pub fn check_integrable<S: Spectrum + ?Sized>(s: &S, what: &str) -> Result<()> {
    let (lo, hi) = s.support();
    if let Asymptote::Power { exponent, .. } = s.high_frequency()
        && hi.is_infinite()
        && exponent >= -1.0
    {
        return Err(Error::Divergent {
            quantity: what.to_string(),
            reason: format!(
                "S(ω) ~ |ω|^{exponent} as |ω| → ∞ does not decay faster than 1/|ω|; ask for a band-limited \
                     value"
            ),
        });
    }
    if let Asymptote::Power { exponent, .. } = s.low_frequency()
        && lo == 0.0
        && exponent <= -1.0
    {
        return Err(Error::Divergent {
            quantity: what.to_string(),
            reason: format!("S(ω) ~ |ω|^{exponent} as ω → 0 is not integrable; give a band or a low-frequency cut-off"),
        });
    }
    Ok(())
}

/// Wynn's ε-algorithm on (the last ≤ 24 of) a sequence of partial sums: the best extrapolated limit.
///
/// ε₋₁ = 0, ε₀ = Sₙ, ε_{k+1}⁽ⁿ⁾ = ε_{k−1}⁽ⁿ⁺¹⁾ + 1/(ε_k⁽ⁿ⁺¹⁾ − ε_k⁽ⁿ⁾); the even columns estimate the limit.
fn wynn_epsilon(sums: &[f64]) -> f64 {
    let start = sums.len().saturating_sub(24);
    let mut prev: Vec<f64> = vec![0.0; sums.len() - start + 1];
    let mut cur: Vec<f64> = sums[start..].to_vec();
    let mut best = *sums.last().unwrap_or(&0.0);
    let mut k = 0;
    while cur.len() >= 2 {
        let next: Vec<f64> = (0..cur.len() - 1)
            .map(|i| prev[i + 1] + 1.0 / (cur[i + 1] - cur[i]))
            .collect();
        k += 1;
        if next.iter().any(|v| !v.is_finite()) {
            break;
        }
        if k % 2 == 0 {
            best = *next.last().unwrap();
        }
        prev = cur;
        cur = next;
    }
    best
}
