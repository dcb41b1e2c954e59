//! The check a run passes before it reports success: on the spectral route the variance of the simulated
//! process is known exactly (`sigma_discrete`), and so is the spread of one realization's mean square, so a
//! Monte Carlo variance far outside what R realizations can give is not a result but a failure of the
//! generator (a Laplace moving average whose variance is carried by too few increments gave σ = 0 where
//! the process has σ = 1.9·10⁻²). The bounds are distribution-free, so the check does not rely on the
//! central limit theorem that the reported interval uses.
//!
//! # Formula
//! The mean squares v_i ≥ 0 of R independent realizations have mean D (the exact discrete variance) and
//! standard deviation s (exact on the spectral route, from the power of the output in every bin and the
//! fourth cumulant of the increments); v̄ = (1/R)Σv_i.
//! * Lower tail, for independent non-negative variables (A. Maurer, "A bound on the deviation probability
//!   for sums of non-negative random variables", J. Inequalities in Pure and Applied Mathematics 4(1),
//!   2003, Theorem 1): P(v̄ ≤ D − t) ≤ exp(−R t² / (2 E v²)), E v² = s² + D². The run fails when
//!   v̄ < D − t_low, t_low = √(2 (s² + D²) ln(1/p) / R).
//! * Upper tail, Cantelli's inequality: P(v̄ − D ≥ k s/√R) ≤ 1/(1 + k²). The run fails when
//!   v̄ > D + k s/√R, k = √(1/p − 1).
//!
//! with p = [`FALSE_FAILURE`] per output and tail: a correct run fails with probability at most 2p per
//! output. (The lower bound says nothing while t_low ≥ D, i.e. for R < 2 ln(1/p)(1 + s²/D²); such a run is
//! too small to tell a collapse from chance.)

use super::plan::PlannedOutput;
use crate::error::{Error, Result};
use crate::numbers::num;

/// Probability that a correct run fails the check, per output and tail.
pub const FALSE_FAILURE: f64 = 1e-7;

/// The interval [lower, upper] outside which the mean v̄ of `realizations` mean squares with mean `d` and
/// standard deviation `sd` is a failure (see the module's formula).
///
/// # Examples
/// ```
/// use stochvib::simulate::agreement::agreement_bounds;
/// // 10⁴ realizations of a mean square with mean 1 and sd 0.1: lower 1 − √(2·1.01·ln 10⁷/10⁴) = 0.943,
/// // upper 1 + √(10⁷ − 1)·0.1/100 = 4.16 (Cantelli's bound is wide: it only catches an explosion)
/// let (lo, hi) = agreement_bounds(1.0, 0.1, 10_000);
/// assert!((lo - 0.9429).abs() < 1e-3 && (hi - 4.1623).abs() < 1e-3, "{lo} {hi}");
/// ```
pub fn agreement_bounds(d: f64, sd: f64, realizations: usize) -> (f64, f64) {
    let r = realizations.max(1) as f64;
    let t_low = (2.0 * (sd * sd + d * d) * (1.0 / FALSE_FAILURE).ln() / r).sqrt();
    let k = (1.0 / FALSE_FAILURE - 1.0).sqrt();
    (d - t_low, d + k * sd / r.sqrt())
}

/// Refuses to report a run whose Monte Carlo variance of output `o` (the mean of the realizations' mean
/// squares `v`) lies outside [`agreement_bounds`] of its exact discrete variance; outputs without a known
/// spread (`mean_square_sd` is `None`: the exact and the streamed routes) pass.
///
/// # Errors
/// [`Error::Inaccurate`] naming the output, the Monte Carlo and the exact σ, the bound and (a non-Gaussian
/// output) its kurtosis, and that the realizations are kept in the run's `.tmp` file.
pub(crate) fn check_mean_square(o: &PlannedOutput, v: &[f64]) -> Result<()> {
    let (Some(sd), false) = (o.mean_square_sd, v.is_empty()) else {
        return Ok(());
    };
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let d = o.discrete_variance;
    let (lo, hi) = agreement_bounds(d, sd, v.len());
    if mean >= lo && mean <= hi && mean.is_finite() {
        return Ok(());
    }
    let why = match o.kurtosis {
        Some(k) => format!(
            " The output is non-Gaussian (kurtosis {}): its variance is carried by rare large increments of the \
             Laplace moving average, and these realizations did not hold enough of them; a lower kurtosis or \
             longer realizations (--duration) make it representable.",
            num(k)
        ),
        None => String::new(),
    };
    Err(Error::Inaccurate {
        method: format!("the Monte Carlo σ of `{}`", o.signal.name),
        value: mean.max(0.0).sqrt(),
        reason: format!(
            "the simulated process has σ = {} exactly, and the mean of {} realizations' mean squares lies in \
             [{}, {}] (σ in [{}, {}]) but with probability {FALSE_FAILURE:e} per tail (Maurer's and Cantelli's \
             bounds, no normal approximation): the run is not reported as a success.{why} The realizations are \
             kept in the run's .tmp file.",
            num(d.sqrt()),
            v.len(),
            num(lo),
            num(hi),
            num(lo.max(0.0).sqrt()),
            num(hi.sqrt()),
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::Signal;

    fn output(kurtosis: Option<f64>) -> PlannedOutput {
        PlannedOutput {
            index: 0,
            signal: Signal::new("body", "m"),
            analytic_variance: 1.0,
            discrete_variance: 1.0,
            kurtosis,
            mean_square_sd: Some(1.0),
        }
    }

    /// The collapse of the issue (σ = 0, or 3e-33, where the process has σ = 1) fails the run, naming the
    /// output, the kurtosis and the kept realizations; a mean of 10³⁰⁰ fails too. The bounds are
    /// distribution-free: lower D − √(2(s² + D²) ln(10⁷)/R) = 1 − √(4·16.118/1000) = 0.746 for R = 1000.
    #[test]
    fn a_collapsed_or_exploded_variance_fails_the_run() {
        let (lo, hi) = agreement_bounds(1.0, 1.0, 1000);
        assert!((lo - (1.0 - (4.0 * 1e7f64.ln() / 1000.0).sqrt())).abs() < 1e-12, "{lo}");
        assert!(
            (hi - (1.0 + (1e7f64 - 1.0).sqrt() / 1000f64.sqrt())).abs() < 1e-9,
            "{hi}"
        );
        for v in [0.0, 1e-66, 1e300] {
            let e = check_mean_square(&output(Some(1e9)), &vec![v; 1000])
                .unwrap_err()
                .to_string();
            for part in ["`body`", "kurtosis 1e9", ".tmp", "not reported as a success"] {
                assert!(e.contains(part), "{part}: {e}");
            }
        }
        let e = check_mean_square(&output(None), &[f64::NAN; 10])
            .unwrap_err()
            .to_string();
        assert!(!e.contains("kurtosis"), "{e}");
    }

    /// Mean squares around their mean pass: 0 and 2 alternating have mean 1 and sd 1 exactly; so does a run
    /// too small to tell (R = 20: the lower bound is below 0, and no v̄ ≥ 0 fails it), and a route without a
    /// known spread.
    #[test]
    fn a_variance_within_the_bounds_passes() {
        let v: Vec<f64> = (0..1000).map(|i| if i % 2 == 0 { 0.0 } else { 2.0 }).collect();
        check_mean_square(&output(Some(6.0)), &v).unwrap();
        assert!(agreement_bounds(1.0, 1.0, 20).0 < 0.0);
        check_mean_square(&output(None), &[0.0; 20]).unwrap();
        let unknown = PlannedOutput {
            mean_square_sd: None,
            ..output(None)
        };
        check_mean_square(&unknown, &[0.0; 1000]).unwrap();
    }
}
