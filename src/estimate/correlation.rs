//! Correlation-function estimates: across realizations (textbook (8.11)) and by time averaging.

use super::interval::Interval;
use super::moments::chi_squared_quantile;
use crate::error::{Error, Result};

/// The across-realization estimate (textbook (8.11)) of the correlation function K(t₁, t₂) from the values
/// x_i(t₁), x_i(t₂) of N independent realizations, with an exact interval for Gaussian data.
///
/// # Formula
/// ```text
/// K̂(t₁, t₂) = 1/(N − 1) Σ_i (x_i(t₁) − m̂(t₁)) (x_i(t₂) − m̂(t₂))
/// ```
/// Interval: with U = x(t₁) + x(t₂), V = x(t₁) − x(t₂), K̂ = (s_U² − s_V²)/4 exactly, and
/// (N − 1)s_U²/σ_U² ~ χ²_{N−1}, (N − 1)s_V²/σ_V² ~ χ²_{N−1} (Gaussian data). Each variance gets a χ² interval
/// at confidence 1 − p/2, so [(U_lo − V_hi)/4, (U_hi − V_lo)/4] covers K = (σ_U² − σ_V²)/4 with probability
/// ≥ 1 − p (union bound) — no large-sample approximation.
///
/// # Errors
/// Fewer than 2 realizations, different lengths, non-finite values, confidence ∉ (0, 1).
///
/// # Examples
/// ```
/// use stochvib::estimate::ensemble_correlation;
/// let a = [1.0, 2.0, 3.0, 4.0];
/// let b = [2.0, 1.0, 4.0, 3.0];
/// let k = ensemble_correlation(&a, &b, 0.95).unwrap();
/// // Σ(a − 2.5)(b − 2.5)/3 = (−1.5·(−0.5) + (−0.5)(−1.5) + 0.5·1.5 + 1.5·0.5)/3 = 1
/// assert!((k.estimate - 1.0).abs() < 1e-15);
/// assert!(k.lower < 1.0 && 1.0 < k.upper);
/// ```
pub fn ensemble_correlation(x1: &[f64], x2: &[f64], confidence: f64) -> Result<Interval> {
    if x1.len() != x2.len() || x1.len() < 2 {
        return Err(Error::invalid(
            "realizations",
            format!("{} and {}", x1.len(), x2.len()),
            "need the same number (>= 2) of values at t1 and t2",
        ));
    }
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(Error::invalid("confidence", confidence, "must be in (0, 1)"));
    }
    if x1.iter().chain(x2).any(|v| !v.is_finite()) {
        return Err(Error::invalid(
            "realizations",
            "non-finite value",
            "all values must be finite",
        ));
    }
    let n = x1.len() as f64;
    let m1 = x1.iter().sum::<f64>() / n;
    let m2 = x2.iter().sum::<f64>() / n;
    let (mut k, mut su, mut sv) = (0.0, 0.0, 0.0);
    for (a, b) in x1.iter().zip(x2) {
        let (da, db) = (a - m1, b - m2);
        k += da * db;
        su += (da + db) * (da + db);
        sv += (da - db) * (da - db);
    }
    let nu = n - 1.0;
    let a = (1.0 - confidence) / 2.0; // split between U and V
    let (qlo, qhi) = (
        chi_squared_quantile(nu, a / 2.0)?,
        chi_squared_quantile(nu, 1.0 - a / 2.0)?,
    );
    let (u_lo, u_hi) = (su / qhi, su / qlo);
    let (v_lo, v_hi) = (sv / qhi, sv / qlo);
    Ok(Interval {
        estimate: k / nu,
        lower: (u_lo - v_hi) / 4.0,
        upper: (u_hi - v_lo) / 4.0,
        confidence,
    })
}

/// Time-average estimate of the autocovariance of one stationary record, K̂(mΔt), m = 0..=max_lag.
///
/// # Formula
/// ```text
/// K̂(m) = 1/(L − m) Σ_{k=0}^{L−m−1} (x_k − μ)(x_{k+m} − μ)
/// ```
/// with μ the known mean if given (unbiased for every m), else the record mean (then biased by
/// O(correlation time / record length)). Direct O(L·max_lag) sums in index order.
///
/// # Errors
/// `max_lag` ≥ L, non-finite values.
///
/// # Examples
/// ```
/// use stochvib::estimate::time_correlation;
/// let k = time_correlation(&[1.0, -1.0, 1.0, -1.0], 1, Some(0.0)).unwrap();
/// assert_eq!(k, vec![1.0, -1.0]);
/// ```
pub fn time_correlation(x: &[f64], max_lag: usize, mean: Option<f64>) -> Result<Vec<f64>> {
    if max_lag >= x.len() {
        return Err(Error::invalid(
            "max_lag",
            max_lag,
            format!("must be < record length {}", x.len()),
        ));
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Err(Error::invalid(
            "record",
            "non-finite value",
            "all values must be finite",
        ));
    }
    let mu = match mean {
        Some(m) => crate::error::require_finite("mean", m)?,
        None => x.iter().sum::<f64>() / x.len() as f64,
    };
    let d: Vec<f64> = x.iter().map(|v| v - mu).collect();
    Ok((0..=max_lag)
        .map(|m| {
            let s: f64 = d[..d.len() - m].iter().zip(&d[m..]).map(|(a, b)| a * b).sum();
            s / (d.len() - m) as f64
        })
        .collect())
}
