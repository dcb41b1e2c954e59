//! The empirical distribution of Monte Carlo maxima with a distribution-free confidence band, and the
//! verdict of an analytic distribution against that band.

use crate::error::{Error, Result};

/// Half-width ε of the Dvoretzky–Kiefer–Wolfowitz band at confidence 1 − α for n independent samples.
///
/// # Formula
/// Dvoretzky, Kiefer & Wolfowitz (1956), "Asymptotic minimax character of the sample distribution
/// function and of the classical multinomial estimator", Ann. Math. Statist. 27(3), 642–669, with the
/// tight constant of Massart, P. (1990), "The tight constant in the Dvoretzky–Kiefer–Wolfowitz
/// inequality", Ann. Probab. 18(3), 1269–1283:
/// ```text
/// P(sup_b |F̂_n(b) − F(b)| > ε) ≤ 2 e^{−2nε²}   ⇒   ε = √(ln(2/α)/(2n))
/// ```
/// The band holds for every b at once, for any continuous F.
///
/// # Errors
/// n = 0 or α outside (0, 1).
///
/// # Examples
/// ```
/// use stochvib::extremes::dkw_epsilon;
/// assert!((dkw_epsilon(40_000, 0.05).unwrap() - (2.0f64 / 0.05).ln().sqrt() / 80_000f64.sqrt()).abs() < 1e-15);
/// ```
pub fn dkw_epsilon(n: usize, alpha: f64) -> Result<f64> {
    if n == 0 {
        return Err(Error::invalid("samples", n, "the empirical distribution needs samples"));
    }
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(Error::invalid("alpha", alpha, "must be in (0, 1)"));
    }
    Ok(((2.0 / alpha).ln() / (2.0 * n as f64)).sqrt())
}

/// An empirical distribution function F̂(b) = #{x_i ≤ b}/n with its DKW band.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct EmpiricalDistribution {
    /// The samples, ascending.
    pub sorted: Vec<f64>,
    /// Confidence 1 − α of the band.
    pub confidence: f64,
    /// The band's half-width ε.
    pub epsilon: f64,
}

/// The largest distance of an analytic distribution from the empirical one, and whether it stays in the band.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BandVerdict {
    /// Name of the analytic form.
    pub method: String,
    /// sup_b |F(b) − F̂(b)| over the samples (both sides of every jump).
    pub distance: f64,
    /// Where the largest distance is.
    pub at: f64,
    /// F(b) there.
    pub analytic: f64,
    /// F̂(b) there.
    pub empirical: f64,
    /// distance ≤ ε.
    pub inside: bool,
}

impl EmpiricalDistribution {
    /// The empirical distribution of `samples` with its band at `confidence`.
    ///
    /// # Errors
    /// No samples, a non-finite sample, confidence outside (0, 1).
    pub fn new(samples: &[f64], confidence: f64) -> Result<Self> {
        if let Some(x) = samples.iter().find(|x| !x.is_finite()) {
            return Err(Error::invalid("samples", x, "must be finite"));
        }
        let epsilon = dkw_epsilon(samples.len(), 1.0 - confidence)?;
        let mut sorted = samples.to_vec();
        sorted.sort_by(f64::total_cmp);
        Ok(EmpiricalDistribution {
            sorted,
            confidence,
            epsilon,
        })
    }

    /// F̂(b).
    pub fn value(&self, b: f64) -> f64 {
        self.sorted.partition_point(|x| *x <= b) as f64 / self.sorted.len() as f64
    }

    /// The Kolmogorov distance of the analytic distribution `cdf` from F̂ and the verdict against the band.
    ///
    /// # Formula
    /// F̂ is a step function: the supremum of |F − F̂| is attained at a sample, just before or at its jump,
    /// so D = max_i max(|F(x_(i)) − i/n|, |F(x_(i)) − (i−1)/n|) (for a continuous F).
    pub fn verdict(&self, method: &str, cdf: &dyn Fn(f64) -> f64) -> BandVerdict {
        let n = self.sorted.len() as f64;
        let mut best = BandVerdict {
            method: method.to_string(),
            distance: 0.0,
            at: f64::NAN,
            analytic: f64::NAN,
            empirical: f64::NAN,
            inside: true,
        };
        for (i, &x) in self.sorted.iter().enumerate() {
            let f = cdf(x);
            for e in [i as f64 / n, (i + 1) as f64 / n] {
                let d = (f - e).abs();
                if d > best.distance || best.at.is_nan() {
                    best.distance = d;
                    best.at = x;
                    best.analytic = f;
                    best.empirical = e;
                }
            }
        }
        best.inside = best.distance <= self.epsilon;
        best
    }
}
