//! Removing the mean or the least-squares line from a uniformly sampled track.

use serde::{Deserialize, Serialize};

/// What to remove from a uniformly sampled record before spectral analysis.
///
/// # Formula
/// For samples y_k, k = 0..N (uniform step, so the abscissa is the index):
/// ```text
/// Mean:    y_k − ȳ,                      ȳ = Σ y_k / N
/// Linear:  y_k − (ȳ + β (k − k̄)),        k̄ = (N − 1)/2,  β = Σ (k − k̄)(y_k − ȳ) / Σ (k − k̄)²
/// ```
/// (β is the least-squares slope per sample; Σ(k − k̄)² = N(N² − 1)/12.) A record of one sample has
/// nothing to fit and is returned as zero.
///
/// # Examples
/// ```
/// use stochvib::road::Detrend;
/// let y = [1.0, 3.0, 5.0, 7.0];                  // a pure line: nothing left
/// assert!(Detrend::Linear.apply(&y).iter().all(|v| v.abs() < 1e-15));
/// assert_eq!(Detrend::Mean.apply(&y), vec![-3.0, -1.0, 1.0, 3.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Detrend {
    /// Remove the mean.
    Mean,
    /// Remove the least-squares straight line (mean and slope).
    Linear,
}

impl Detrend {
    /// The detrended copy of `y` (see the type's formula).
    pub fn apply(self, y: &[f64]) -> Vec<f64> {
        let mut out = y.to_vec();
        self.apply_in_place(&mut out);
        out
    }

    /// Detrends `y` in place (see the type's formula).
    pub fn apply_in_place(self, y: &mut [f64]) {
        let n = y.len();
        if n == 0 {
            return;
        }
        let mean = y.iter().sum::<f64>() / n as f64;
        match self {
            Detrend::Mean => y.iter_mut().for_each(|v| *v -= mean),
            Detrend::Linear => {
                let kbar = (n as f64 - 1.0) / 2.0;
                let sxx = n as f64 * ((n * n) as f64 - 1.0) / 12.0;
                let sxy: f64 = y.iter().enumerate().map(|(k, v)| (k as f64 - kbar) * (v - mean)).sum();
                let beta = if sxx > 0.0 { sxy / sxx } else { 0.0 };
                for (k, v) in y.iter_mut().enumerate() {
                    *v -= mean + beta * (k as f64 - kbar);
                }
            }
        }
    }
}
