//! Across-realization moments with exact Gaussian confidence intervals (Student-t for the mean, χ² for
//! the variance and σ), and streaming moments (Welford).

use super::interval::Interval;
use crate::error::{Error, Result};
use statrs::distribution::{ChiSquared, ContinuousCDF, StudentsT};

fn check_confidence(confidence: f64) -> Result<()> {
    if !(confidence > 0.0 && confidence < 1.0) {
        return Err(Error::invalid("confidence", confidence, "must be in (0, 1)"));
    }
    Ok(())
}

fn check_samples(samples: &[f64], min: usize) -> Result<()> {
    if samples.len() < min {
        return Err(Error::invalid(
            "samples",
            samples.len(),
            format!("need at least {min} realizations"),
        ));
    }
    if samples.iter().any(|v| !v.is_finite()) {
        return Err(Error::invalid(
            "samples",
            "non-finite value",
            "all samples must be finite",
        ));
    }
    Ok(())
}

/// Solves F(x) = p for a continuous increasing CDF on (lo, ∞) by bracketing and bisection to full
/// precision, using the survival function for upper tails (accurate far in both tails, unlike a fixed
/// number of Newton steps).
fn quantile(cdf: impl Fn(f64) -> f64, sf: impl Fn(f64) -> f64, p: f64, lo: f64, start: f64) -> f64 {
    let upper = p > 0.5;
    let q = if upper { 1.0 - p } else { p };
    // g(x) < 0 left of the root, > 0 right of it
    let g = |x: f64| if upper { q - sf(x) } else { cdf(x) - q };
    let (mut a, mut b) = (start - 1.0, start + 1.0);
    if lo == 0.0 {
        a = start * 0.5;
        b = start * 2.0;
        while g(a) > 0.0 && a > 1e-300 {
            a *= 0.5;
        }
    } else {
        let mut step = 1.0;
        while g(a) > 0.0 {
            a -= step;
            step *= 2.0;
        }
    }
    let mut step = b - a;
    while g(b) < 0.0 {
        b += step;
        step *= 2.0;
    }
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if g(m) < 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// Quantile of the χ² distribution with ν degrees of freedom: x with P(χ²_ν ≤ x) = p.
///
/// # Errors
/// ν ≤ 0 or p ∉ (0, 1).
///
/// # Examples
/// ```
/// use stochvib::estimate::chi_squared_quantile;
/// // χ²₂ is exponential with mean 2: quantile −2 ln(1 − p)
/// let p = 1e-7;
/// assert!((chi_squared_quantile(2.0, p).unwrap() / (-2.0 * (-p).ln_1p()) - 1.0).abs() < 1e-9);
/// ```
pub fn chi_squared_quantile(nu: f64, p: f64) -> Result<f64> {
    let d = ChiSquared::new(nu).map_err(|e| Error::invalid("degrees of freedom", nu, e.to_string()))?;
    if !(p > 0.0 && p < 1.0) {
        return Err(Error::invalid("probability", p, "must be in (0, 1)"));
    }
    Ok(quantile(|x| d.cdf(x), |x| d.sf(x), p, 0.0, nu.max(1.0)))
}

/// The exact (Garwood) confidence interval of a Poisson rate from `k` events observed in `time` seconds:
/// (lower, upper) in 1/s.
///
/// # Formula
/// [χ²_{2k}(α/2)/2, χ²_{2k+2}(1 − α/2)/2]/time with α = 1 − confidence, the lower bound 0 for k = 0
/// (Garwood 1936, "Fiducial limits for the Poisson distribution", Biometrika 28, 437–442): for k = 0 the
/// upper bound is −ln(α/2)/time (χ²₂ is exponential with mean 2).
///
/// # Errors
/// k < 0 or not finite, time not finite and > 0, confidence ∉ (0, 1).
///
/// # Examples
/// ```
/// use stochvib::estimate::poisson_rate_interval;
/// // no event in 1200 s at 95 %: [0, −ln(0.025)/1200]
/// let (lo, hi) = poisson_rate_interval(0.0, 1200.0, 0.95).unwrap();
/// assert_eq!(lo, 0.0);
/// assert!((hi - (-(0.025f64).ln() / 1200.0)).abs() < 1e-12);
/// ```
pub fn poisson_rate_interval(k: f64, time: f64, confidence: f64) -> Result<(f64, f64)> {
    check_confidence(confidence)?;
    if !(k.is_finite() && k >= 0.0) {
        return Err(Error::invalid("events", k, "must be finite and >= 0"));
    }
    if !(time.is_finite() && time > 0.0) {
        return Err(Error::invalid("time", time, "must be finite and > 0 (s)"));
    }
    let alpha = 1.0 - confidence;
    let lower = if k > 0.0 {
        chi_squared_quantile(2.0 * k, alpha / 2.0)? / 2.0
    } else {
        0.0
    };
    let upper = chi_squared_quantile(2.0 * k + 2.0, 1.0 - alpha / 2.0)? / 2.0;
    Ok((lower / time, upper / time))
}

/// Quantile of Student's t distribution with ν degrees of freedom.
///
/// # Errors
/// ν ≤ 0 or p ∉ (0, 1).
///
/// # Examples
/// ```
/// use stochvib::estimate::student_t_quantile;
/// // t₁ is Cauchy: quantile tan(π(p − 1/2))
/// let p = 0.999;
/// let exact = (std::f64::consts::PI * (p - 0.5)).tan();
/// assert!((student_t_quantile(1.0, p).unwrap() / exact - 1.0).abs() < 1e-9);
/// ```
pub fn student_t_quantile(nu: f64, p: f64) -> Result<f64> {
    let d = StudentsT::new(0.0, 1.0, nu).map_err(|e| Error::invalid("degrees of freedom", nu, e.to_string()))?;
    if !(p > 0.0 && p < 1.0) {
        return Err(Error::invalid("probability", p, "must be in (0, 1)"));
    }
    Ok(quantile(|x| d.cdf(x), |x| d.sf(x), p, f64::NEG_INFINITY, 0.0))
}

/// Sample mean and unbiased sample variance (two passes, summed in the given order).
fn mean_var(samples: &[f64]) -> (f64, f64) {
    let n = samples.len() as f64;
    let mean = samples.iter().sum::<f64>() / n;
    let ss: f64 = samples.iter().map(|x| (x - mean) * (x - mean)).sum();
    (mean, if samples.len() > 1 { ss / (n - 1.0) } else { 0.0 })
}

/// Mean across N independent realizations with the Student-t interval (exact for Gaussian samples).
///
/// # Formula
/// ```text
/// m̂ = Σx_i/N,   s² = Σ(x_i − m̂)²/(N − 1),   m̂ ± t_{N−1, 1−p/2} s/√N
/// ```
///
/// # Errors
/// Fewer than 2 samples, non-finite samples, confidence ∉ (0, 1).
///
/// # Examples
/// ```
/// use stochvib::estimate::mean_interval;
/// let m = mean_interval(&[1.0, 2.0, 3.0], 0.95).unwrap();
/// assert_eq!(m.estimate, 2.0);
/// // t_{2, 0.975} = 4.302653 (tables); s = 1
/// assert!((m.upper - (2.0 + 4.302652729911275 / 3f64.sqrt())).abs() < 1e-9);
/// ```
pub fn mean_interval(samples: &[f64], confidence: f64) -> Result<Interval> {
    check_confidence(confidence)?;
    check_samples(samples, 2)?;
    let (m, v) = mean_var(samples);
    let n = samples.len() as f64;
    let t = student_t_quantile(n - 1.0, 0.5 + 0.5 * confidence)?;
    let h = t * (v / n).sqrt();
    Ok(Interval {
        estimate: m,
        lower: m - h,
        upper: m + h,
        confidence,
    })
}

/// Variance across N independent realizations about their sample mean, with the χ² interval (exact for
/// Gaussian samples).
///
/// # Formula
/// ```text
/// s² = Σ(x_i − m̂)²/(N − 1),   (N − 1)s²/σ² ~ χ²_{N−1}:   [(N−1)s²/χ²_{N−1, 1−p/2}, (N−1)s²/χ²_{N−1, p/2}]
/// ```
///
/// # Errors
/// As [`mean_interval`].
///
/// # Examples
/// ```
/// use stochvib::estimate::variance_interval;
/// let v = variance_interval(&[1.0, 2.0, 3.0, 4.0], 0.9).unwrap();
/// assert!((v.estimate - 5.0 / 3.0).abs() < 1e-15);
/// assert!(v.lower < v.estimate && v.estimate < v.upper);
/// ```
pub fn variance_interval(samples: &[f64], confidence: f64) -> Result<Interval> {
    check_confidence(confidence)?;
    check_samples(samples, 2)?;
    let (_, v) = mean_var(samples);
    VarianceEstimate {
        variance: v,
        dof: samples.len() as f64 - 1.0,
    }
    .interval(confidence)
}

/// Variance across N independent realizations about a known mean μ (e.g. 0 for a zero-mean fluctuation),
/// with the χ² interval on N degrees of freedom.
///
/// # Formula
/// ```text
/// σ̂² = Σ(x_i − μ)²/N,   N σ̂²/σ² ~ χ²_N
/// ```
///
/// # Errors
/// As [`mean_interval`] (at least 1 sample), and a non-finite μ.
///
/// # Examples
/// ```
/// use stochvib::estimate::variance_interval_known_mean;
/// let v = variance_interval_known_mean(&[1.0, -1.0, 2.0], 0.0, 0.95).unwrap();
/// assert_eq!(v.estimate, 2.0);
/// ```
pub fn variance_interval_known_mean(samples: &[f64], mean: f64, confidence: f64) -> Result<Interval> {
    check_confidence(confidence)?;
    check_samples(samples, 1)?;
    crate::error::require_finite("mean", mean)?;
    let n = samples.len() as f64;
    let v = samples.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
    VarianceEstimate { variance: v, dof: n }.interval(confidence)
}

/// A variance estimate v with ν degrees of freedom (ν v/σ² ~ χ²_ν for Gaussian samples). Named fields: the
/// estimate and ν are both positive numbers and cannot be swapped silently.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VarianceEstimate {
    /// v, the estimate of σ² (unit²).
    pub variance: f64,
    /// ν, its degrees of freedom (> 0; need not be an integer, e.g. Welch's equivalent ν).
    pub dof: f64,
}

impl VarianceEstimate {
    /// The χ² interval [ν v/χ²_{ν,1−p/2}, ν v/χ²_{ν,p/2}] at confidence 1 − p.
    ///
    /// # Errors
    /// ν ≤ 0, confidence ∉ (0, 1), v negative or non-finite.
    ///
    /// # Examples
    /// ```
    /// use stochvib::estimate::VarianceEstimate;
    /// // ν = 2: χ²₂ is exponential with mean 2, χ²_{2,q} = −2 ln(1 − q)
    /// let i = VarianceEstimate { variance: 1.0, dof: 2.0 }.interval(0.9).unwrap();
    /// assert!((i.lower - 2.0 / (-2.0 * 0.05f64.ln())).abs() < 1e-12);
    /// assert!((i.upper - 2.0 / (-2.0 * 0.95f64.ln())).abs() < 1e-9);
    /// ```
    pub fn interval(&self, confidence: f64) -> Result<Interval> {
        check_confidence(confidence)?;
        crate::error::require_non_negative("variance estimate", self.variance)?;
        ChiSquaredInterval::new(self.dof, confidence)?.interval(self.variance)
    }
}

/// The χ² interval of [`VarianceEstimate::interval`] for any number of estimates with the same ν and
/// confidence, its two quantiles found once (they cost far more than the interval itself).
///
/// # Examples
/// ```
/// use stochvib::estimate::ChiSquaredInterval;
/// // ν = 2: χ²₂ is exponential with mean 2, χ²_{2,q} = −2 ln(1 − q)
/// let chi = ChiSquaredInterval::new(2.0, 0.9).unwrap();
/// for v in [0.5, 1.0, 3.0] {
///     let i = chi.interval(v).unwrap();
///     assert!((i.lower - 2.0 * v / (-2.0 * 0.05f64.ln())).abs() < 1e-12 * v);
///     assert!((i.upper - 2.0 * v / (-2.0 * 0.95f64.ln())).abs() < 1e-9 * v);
/// }
/// assert!(chi.interval(-1.0).is_err());
/// assert!(ChiSquaredInterval::new(0.0, 0.9).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChiSquaredInterval {
    dof: f64,
    confidence: f64,
    /// χ²_{ν,1−p/2}.
    hi: f64,
    /// χ²_{ν,p/2}.
    lo: f64,
}

impl ChiSquaredInterval {
    /// The quantiles of χ²_ν at (1 ± confidence)/2.
    ///
    /// # Errors
    /// ν ≤ 0, confidence ∉ (0, 1).
    pub fn new(dof: f64, confidence: f64) -> Result<Self> {
        check_confidence(confidence)?;
        let a = 1.0 - confidence;
        Ok(ChiSquaredInterval {
            dof,
            confidence,
            hi: chi_squared_quantile(dof, 1.0 - a / 2.0)?,
            lo: chi_squared_quantile(dof, a / 2.0)?,
        })
    }

    /// The interval [ν v/χ²_{ν,1−p/2}, ν v/χ²_{ν,p/2}] of the variance estimate v.
    ///
    /// # Errors
    /// v negative or non-finite.
    pub fn interval(&self, variance: f64) -> Result<Interval> {
        let (v, nu) = (
            crate::error::require_non_negative("variance estimate", variance)?,
            self.dof,
        );
        Ok(Interval {
            estimate: v,
            lower: nu * v / self.hi,
            upper: nu * v / self.lo,
            confidence: self.confidence,
        })
    }
}

/// Standard deviation σ across realizations: the square root of [`variance_interval`] (the χ² interval is
/// transformed, so its confidence is unchanged).
///
/// # Errors
/// As [`variance_interval`].
///
/// # Examples
/// ```
/// use stochvib::estimate::std_interval;
/// let s = std_interval(&[1.0, 2.0, 3.0, 4.0], 0.9).unwrap();
/// assert!((s.estimate - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
/// ```
pub fn std_interval(samples: &[f64], confidence: f64) -> Result<Interval> {
    let v = variance_interval(samples, confidence)?;
    Ok(Interval {
        estimate: v.estimate.sqrt(),
        lower: v.lower.sqrt(),
        upper: v.upper.sqrt(),
        confidence,
    })
}

/// Streaming mean and variance (Welford 1962), O(1) memory; merge by Chan, Golub & LeVeque (1979).
///
/// # Formula
/// ```text
/// n ← n + 1,  δ = x − m,  m ← m + δ/n,  M₂ ← M₂ + δ (x − m);    variance = M₂/(n − 1)
/// ```
///
/// # Examples
/// ```
/// use stochvib::estimate::RunningMoments;
/// let mut r = RunningMoments::default();
/// r.extend(&[1.0, 2.0, 3.0, 4.0]);
/// assert_eq!(r.mean(), 2.5);
/// assert!((r.variance() - 5.0 / 3.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunningMoments {
    count: u64,
    mean: f64,
    m2: f64,
}

impl RunningMoments {
    /// Adds one sample.
    #[inline]
    pub fn push(&mut self, x: f64) {
        self.count += 1;
        let d = x - self.mean;
        self.mean += d / self.count as f64;
        self.m2 += d * (x - self.mean);
    }
    /// Adds samples in order.
    pub fn extend(&mut self, xs: &[f64]) {
        for &x in xs {
            self.push(x);
        }
    }
    /// Combines with the moments of another, disjoint set of samples.
    pub fn merge(&mut self, other: &RunningMoments) {
        if other.count == 0 {
            return;
        }
        let n = (self.count + other.count) as f64;
        let d = other.mean - self.mean;
        self.m2 += other.m2 + d * d * self.count as f64 * other.count as f64 / n;
        self.mean += d * other.count as f64 / n;
        self.count += other.count;
    }
    /// Number of samples.
    pub fn count(&self) -> u64 {
        self.count
    }
    /// Mean (0 with no samples).
    pub fn mean(&self) -> f64 {
        self.mean
    }
    /// Unbiased variance M₂/(n − 1) (0 with fewer than 2 samples).
    pub fn variance(&self) -> f64 {
        if self.count < 2 {
            0.0
        } else {
            self.m2 / (self.count - 1) as f64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::{LARGE_MEAN_VARIANCE, QUANTILE, ULPS};

    #[test]
    fn quantiles_against_closed_forms() {
        // χ²₁ quantile = z² with z the normal quantile at (1+p)/2; z_{0.975} = 1.959963984540054 (tables).
        let q = chi_squared_quantile(1.0, 0.95).unwrap();
        assert!((q - 1.959963984540054f64.powi(2)).abs() < QUANTILE);
        // χ²₂ far lower tail: −2 ln(1 − p) ≈ 2p
        let p = 1e-9;
        assert!((chi_squared_quantile(2.0, p).unwrap() / (-2.0 * (-p).ln_1p()) - 1.0).abs() < QUANTILE);
        // t₂ has the closed-form quantile t = (2p − 1)/√(2p(1 − p))
        for p in [0.6f64, 0.99, 1.0 - 1e-8] {
            let exact = (2.0 * p - 1.0) / (2.0 * p * (1.0 - p)).sqrt();
            assert!(
                (student_t_quantile(2.0, p).unwrap() / exact - 1.0).abs() < QUANTILE,
                "{p}"
            );
        }
    }

    #[test]
    fn welford_matches_two_pass_and_merge() {
        let xs: Vec<f64> = (0..100).map(|k| ((k * 37) % 101) as f64 * 0.1 + 1e6).collect();
        let (m, v) = mean_var(&xs);
        let mut r = RunningMoments::default();
        r.extend(&xs);
        assert!((r.mean() - m).abs() < ULPS * m && (r.variance() / v - 1.0).abs() < LARGE_MEAN_VARIANCE);
        let (mut a, mut b) = (RunningMoments::default(), RunningMoments::default());
        a.extend(&xs[..30]);
        b.extend(&xs[30..]);
        a.merge(&b);
        assert_eq!(a.count(), 100);
        assert!((a.mean() - m).abs() < ULPS * m && (a.variance() / v - 1.0).abs() < LARGE_MEAN_VARIANCE);
    }
}
