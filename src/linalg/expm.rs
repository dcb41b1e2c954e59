//! The matrix exponential, checked.

use crate::error::{Error, Result};
use nalgebra::DMatrix;

/// Matrix exponential e^M (nalgebra's scaling-and-squaring Padé approximant, Higham 2005), with a check
/// that the result is finite.
///
/// # Formula
/// ```text
/// e^M = Σ_k M^k / k!
/// ```
///
/// # Errors
/// [`Error::Numerical`] when `m` is not square or the result overflows.
///
/// # Examples
/// ```
/// use stochvib::linalg::expm;
/// use nalgebra::DMatrix;
/// // rotation generator: e^{[[0, θ], [−θ, 0]]} = [[cos θ, sin θ], [−sin θ, cos θ]]
/// let t = 0.7;
/// let e = expm(&DMatrix::from_row_slice(2, 2, &[0.0, t, -t, 0.0])).unwrap();
/// assert!((e[(0, 0)] - t.cos()).abs() < 1e-14 && (e[(0, 1)] - t.sin()).abs() < 1e-14);
/// ```
pub fn expm(m: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    if m.nrows() != m.ncols() {
        return Err(Error::Numerical {
            what: "matrix exponential".into(),
            reason: format!("matrix is {}x{}, not square", m.nrows(), m.ncols()),
        });
    }
    if m.nrows() == 0 {
        return Ok(m.clone());
    }
    if m.iter().any(|v| !v.is_finite()) {
        return Err(Error::Numerical {
            what: "matrix exponential".into(),
            reason: "matrix has non-finite entries".into(),
        });
    }
    let e = m.exp();
    if e.iter().any(|v| !v.is_finite()) {
        return Err(Error::Numerical {
            what: "matrix exponential".into(),
            reason: format!("overflow (‖M‖ = {:e}): reduce the time step", m.norm()),
        });
    }
    Ok(e)
}
