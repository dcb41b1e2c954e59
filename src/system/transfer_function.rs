//! Single-input single-output rational transfer functions H(s) = N(s)/D(s).

use super::{FrequencyResponse, OutputInfo, StateSpace};
use crate::error::{Error, Result};
use crate::linalg::poly;
use crate::spectrum::Asymptote;
use nalgebra::{Complex, DMatrix};

/// A rational transfer function H(s) = N(s)/D(s), real coefficients in ascending powers of s.
///
/// # Formula
/// ```text
/// H(s) = (n₀ + n₁ s + … + n_q s^q) / (d₀ + d₁ s + … + d_n sⁿ),      q ≤ n + 1
/// ```
/// Realised in controllable canonical form; a numerator of degree n + 1 gives a derivative feedthrough E
/// (e.g. the base-velocity term of a damper).
///
/// # Errors
/// [`TransferFunction::new`] rejects empty or non-finite coefficients, a zero denominator and a numerator
/// more than one degree above the denominator.
///
/// # Examples
/// ```
/// use stochvib::system::{TransferFunction, FrequencyResponse, OutputInfo};
/// // wheel filter of the balancer bogie (textbook (8.46)): W(s) = 1/(1 + 4 r s), r = 0.11 m
/// let w = TransferFunction::new(vec![1.0], vec![1.0, 0.44], OutputInfo::new("z", "m")).unwrap();
/// let h = w.response(1.0 / 0.44)[(0, 0)];
/// assert!((h.norm_sqr() - 0.5).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TransferFunction {
    num: Vec<f64>,
    den: Vec<f64>,
    ss: StateSpace,
}

impl TransferFunction {
    /// Builds H(s) = N(s)/D(s).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(num: Vec<f64>, den: Vec<f64>, output: OutputInfo) -> Result<Self> {
        let num = poly::trim(&num);
        let den = poly::trim(&den);
        if den.is_empty() {
            return Err(Error::invalid("denominator", format!("{den:?}"), "must not be zero"));
        }
        crate::linalg::poly::check_degree("denominator", &den)?;
        crate::linalg::poly::check_degree("numerator", &num)?;
        if num.iter().chain(&den).any(|v| !v.is_finite()) {
            return Err(Error::invalid(
                "coefficients",
                format!("{num:?} / {den:?}"),
                "must be finite",
            ));
        }
        let n = den.len() - 1;
        if num.len() > n + 2 {
            return Err(Error::invalid(
                "numerator",
                format!("{num:?}"),
                format!(
                    "degree {} exceeds the denominator degree {n} by more than one",
                    num.len() - 1
                ),
            ));
        }
        let lead = den[n];
        let dn: Vec<f64> = den.iter().map(|v| v / lead).collect();
        let mut r: Vec<f64> = num.iter().map(|v| v / lead).collect();
        r.resize(n + 2, 0.0);
        // N/D = E s + D + R(s)/D(s): divide by the monic denominator
        let e = r[n + 1];
        for k in 0..=n {
            // subtract e·s·D(s)
            r[k + 1] -= e * dn[k];
        }
        let d = r[n];
        for k in 0..=n {
            r[k] -= d * dn[k];
        }
        let a = DMatrix::from_fn(n, n, |i, j| {
            if i + 1 < n {
                if j == i + 1 {
                    1.0
                } else {
                    0.0
                }
            } else {
                -dn[j]
            }
        });
        let b = DMatrix::from_fn(n, 1, |i, _| if i + 1 == n { 1.0 } else { 0.0 });
        let c = DMatrix::from_fn(1, n, |_, j| r[j]);
        let ss = StateSpace::new(
            a,
            b,
            c,
            Some(DMatrix::from_element(1, 1, d)),
            Some(DMatrix::from_element(1, 1, e)),
            vec![output],
        )?;
        Ok(TransferFunction { num, den, ss })
    }

    /// Numerator, ascending powers of s.
    pub fn numerator(&self) -> &[f64] {
        &self.num
    }
    /// Denominator, ascending powers of s.
    pub fn denominator(&self) -> &[f64] {
        &self.den
    }
}

impl FrequencyResponse for TransferFunction {
    fn n_inputs(&self) -> usize {
        1
    }
    fn outputs(&self) -> &[OutputInfo] {
        self.ss.outputs()
    }
    fn response(&self, omega: f64) -> DMatrix<Complex<f64>> {
        let s = Complex::new(0.0, omega);
        DMatrix::from_element(
            1,
            1,
            poly::eval_complex(&self.num, s) / poly::eval_complex(&self.den, s),
        )
    }
    fn static_gain(&self) -> Option<DMatrix<f64>> {
        (self.den[0] != 0.0)
            .then(|| DMatrix::from_element(1, 1, self.num.first().copied().unwrap_or(0.0) / self.den[0]))
    }
    fn high_frequency(&self) -> Vec<Vec<Asymptote>> {
        let (q, n) = (self.num.len() as f64 - 1.0, self.den.len() as f64 - 1.0);
        let lead = self.num.last().copied().unwrap_or(0.0) / self.den[self.den.len() - 1];
        if self.num.is_empty() {
            return vec![vec![Asymptote::Vanishing]];
        }
        vec![vec![Asymptote::Power {
            exponent: 2.0 * (q - n),
            coefficient: lead * lead,
        }]]
    }
    fn low_frequency(&self) -> Vec<Vec<Asymptote>> {
        let k = self.num.iter().position(|v| *v != 0.0);
        let j = self.den.iter().position(|v| *v != 0.0).unwrap_or(0);
        match k {
            None => vec![vec![Asymptote::Vanishing]],
            Some(k) => {
                let c = self.num[k] / self.den[j];
                vec![vec![Asymptote::Power {
                    exponent: 2.0 * (k as f64 - j as f64),
                    coefficient: c * c,
                }]]
            }
        }
    }
    fn natural_frequencies(&self) -> Vec<f64> {
        self.ss.natural_frequencies()
    }
    fn state_space(&self) -> Option<&StateSpace> {
        Some(&self.ss)
    }
}
