//! A row of rational transfer functions with one denominator: one output driven by several inputs, e.g.
//! a response that feels the road under two wheels, each through its own numerator.

use super::{FrequencyResponse, OutputInfo, StateSpace, TransferFunction};
use crate::error::{Error, Result};
use crate::spectrum::Asymptote;
use nalgebra::{Complex, DMatrix};

/// y(s) = Σ_k N_k(s)/D(s) · u_k(s): a multi-input single-output rational transfer function.
///
/// # Formula
/// ```text
/// H(s) = [N_1(s), …, N_m(s)] / D(s),   deg N_k ≤ deg D + 1   (ascending coefficients in s)
/// ```
/// Each N_k/D is divided by the monic denominator, N_k/D = e_k s + d_k + R_k(s)/D(s) with deg R_k < n, and
/// the row is realised in observable canonical form (the transpose of the controllable form of
/// [`TransferFunction`]): A has ones on the subdiagonal and −d̂_0 … −d̂_{n−1} in its last column, column k of
/// B holds the coefficients of R_k, C = [0 … 0 1], D = [d_1 … d_m], E = [e_1 … e_m]. Then
/// C (sI − A)⁻¹ B_k = R_k(s)/D(s) for every k with one state vector of order n = deg D (not m·n).
///
/// # Errors
/// [`TransferRow::new`] rejects an empty list of numerators and every case [`TransferFunction::new`]
/// rejects for one of the N_k/D (the error names the input).
///
/// # Examples
/// ```
/// use stochvib::system::{TransferRow, FrequencyResponse, OutputInfo};
/// // y = (u_1 + s u_2)/(1 + s): at ω = 1, H = [1/(1+i), i/(1+i)]
/// let t = TransferRow::new(vec![vec![1.0], vec![0.0, 1.0]], vec![1.0, 1.0], OutputInfo::new("y", "m")).unwrap();
/// let h = t.response(1.0);
/// assert!((h[(0, 0)].norm_sqr() - 0.5).abs() < 1e-15 && (h[(0, 1)].norm_sqr() - 0.5).abs() < 1e-15);
/// assert_eq!(t.state_space().unwrap().a.nrows(), 1);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TransferRow {
    parts: Vec<TransferFunction>,
    ss: StateSpace,
}

impl TransferRow {
    /// Builds the row N_1/D … N_m/D.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(numerators: Vec<Vec<f64>>, den: Vec<f64>, output: OutputInfo) -> Result<Self> {
        if numerators.is_empty() {
            return Err(Error::invalid("numerators", "[]", "need at least one input"));
        }
        let parts = numerators
            .into_iter()
            .enumerate()
            .map(|(k, num)| {
                TransferFunction::new(num, den.clone(), output.clone()).map_err(|e| match e {
                    Error::InvalidParameter { name, value, reason } => Error::InvalidParameter {
                        name: format!("input {k}: {name}"),
                        value,
                        reason,
                    },
                    other => other,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        // every part shares A and b = e_n of the controllable form; transpose to the observable form
        let first = parts[0].state_space().expect("a transfer function has a state space");
        let n = first.a.nrows();
        let m = parts.len();
        let a = first.a.transpose();
        let c = DMatrix::from_fn(1, n, |_, j| if j + 1 == n { 1.0 } else { 0.0 });
        let mut b = DMatrix::zeros(n, m);
        let mut d = DMatrix::zeros(1, m);
        let mut e = DMatrix::zeros(1, m);
        for (k, p) in parts.iter().enumerate() {
            let s = p.state_space().expect("a transfer function has a state space");
            for i in 0..n {
                b[(i, k)] = s.c[(0, i)];
            }
            d[(0, k)] = s.d[(0, 0)];
            e[(0, k)] = s.e[(0, 0)];
        }
        let ss = StateSpace::new(a, b, c, Some(d), Some(e), vec![output])?;
        Ok(TransferRow { parts, ss })
    }

    /// The single-input transfer functions N_k/D, one per input.
    pub fn parts(&self) -> &[TransferFunction] {
        &self.parts
    }
}

impl FrequencyResponse for TransferRow {
    fn n_inputs(&self) -> usize {
        self.parts.len()
    }
    fn outputs(&self) -> &[OutputInfo] {
        self.ss.outputs()
    }
    fn response(&self, omega: f64) -> DMatrix<Complex<f64>> {
        DMatrix::from_fn(1, self.parts.len(), |_, k| self.parts[k].response(omega)[(0, 0)])
    }
    fn static_gain(&self) -> Option<DMatrix<f64>> {
        let cols: Option<Vec<f64>> = self.parts.iter().map(|p| p.static_gain().map(|g| g[(0, 0)])).collect();
        cols.map(|c| DMatrix::from_row_slice(1, c.len(), &c))
    }
    fn high_frequency(&self) -> Vec<Vec<Asymptote>> {
        vec![self.parts.iter().map(|p| p.high_frequency()[0][0]).collect()]
    }
    fn low_frequency(&self) -> Vec<Vec<Asymptote>> {
        vec![self.parts.iter().map(|p| p.low_frequency()[0][0]).collect()]
    }
    fn natural_frequencies(&self) -> Vec<f64> {
        self.ss.natural_frequencies()
    }
    fn state_space(&self) -> Option<&StateSpace> {
        Some(&self.ss)
    }
}
