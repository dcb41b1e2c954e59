//! `stochvib.linalg`: the closed-form integral table, vectorised over rows (parameter sweeps).

use crate::arrays::real_array;
use crate::errors::{detached, invalid_input, Failure};
use numpy::{PyArray1, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyFloat;
use stochvib::linalg::h2_integral as lib_h2_integral;

/// ∫_{−∞}^{∞} |N(iω)/D(iω)|² dω for real polynomials N, D in s, coefficients in DESCENDING powers of s
/// (highest first, as scipy.signal; ``order="ascending"`` for lowest first) — the table Iₙ of James,
/// Nichols & Phillips; Newland, Appendix 1. Exact; requires deg N < deg D and D Hurwitz (all roots in
/// Re s < 0).
///
/// For a stable filter H = N/D driven by white noise of two-sided density S₀ the output variance is
/// S₀ · h2_integral(N, D); with the shaping filter (B, A) of a rational input spectrum
/// (:meth:`Spectrum.shaping_filter`, S = |B/A|²/(2π)) the variance of the response H·input is
/// h2_integral(N·B, D·A) / (2π).
///
/// Parameters
/// ----------
/// numerator, denominator : array_like
///     1-D (one integral) or 2-D with one row per integral; SI coefficients of s (s in rad/s); zero padding
///     on the high-power side (leading zeros in descending order) is trimmed.
/// order : {"descending", "ascending"}, keyword-only
///     The order of the coefficients.
///
/// Returns
/// -------
/// float or numpy.ndarray
///     The integral (a float for 1-D arguments, one per row for 2-D), in the units of |N/D|² times rad/s.
///
/// Raises
/// ------
/// DivergentError
///     deg N ≥ deg D.
/// InvalidInputError
///     An unstable denominator, naming the row.
///
/// The GIL is released.
///
/// Examples
/// --------
/// ∫ dω/|iω + 2|² = π/2:
///
/// >>> import math
/// >>> from stochvib.linalg import h2_integral
/// >>> round(h2_integral([1.0], [1.0, 2.0]) / (math.pi / 2), 12)
/// 1.0
#[pyfunction]
#[pyo3(signature = (numerator, denominator, *, order="descending"))]
pub fn h2_integral<'py>(
    py: Python<'py>,
    numerator: &Bound<'py, PyAny>,
    denominator: &Bound<'py, PyAny>,
    order: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let desc = crate::arrays::descending(py, order)?;
    let n = real_array(py, numerator, "numerator")?;
    let d = real_array(py, denominator, "denominator")?;
    let (ns, ds) = (n.shape().to_vec(), d.shape().to_vec());
    let rows_of = |s: &[usize], name: &str| -> PyResult<(usize, usize, bool)> {
        match s.len() {
            1 => Ok((1, s[0], true)),
            2 => Ok((s[0], s[1], false)),
            _ => Err(invalid_input(
                py,
                format!("`{name}` must be 1-D or 2-D, got shape {s:?}"),
            )),
        }
    };
    let (rn, kn, one_n) = rows_of(&ns, "numerator")?;
    let (rd, kd, one_d) = rows_of(&ds, "denominator")?;
    if one_n != one_d || rn != rd {
        return Err(invalid_input(
            py,
            format!("`numerator` {ns:?} and `denominator` {ds:?} must both be 1-D or have as many rows"),
        ));
    }
    let nr = n.readonly();
    let dr = d.readonly();
    let (nsl, dsl) = (nr.as_slice()?, dr.as_slice()?);
    // the library's order (ascending): every row reversed, in one copy
    let flipped =
        |x: &[f64], k: usize| -> Vec<f64> { x.chunks(k.max(1)).flat_map(|r| r.iter().rev().copied()).collect() };
    let (nf, df);
    let (nsl, dsl) = if desc {
        (nf, df) = (flipped(nsl, kn), flipped(dsl, kd));
        (&nf[..], &df[..])
    } else {
        (nsl, dsl)
    };
    let values = detached(py, || {
        let mut out = Vec::with_capacity(rn);
        for r in 0..rn {
            let v = lib_h2_integral(&nsl[r * kn..(r + 1) * kn], &dsl[r * kd..(r + 1) * kd]).map_err(|e| {
                if one_n {
                    Failure::Lib(e)
                } else {
                    Failure::Lib(row_error(e, r))
                }
            })?;
            out.push(v);
        }
        Ok(out)
    })?;
    if one_n {
        Ok(PyFloat::new(py, values[0]).into_any())
    } else {
        Ok(PyArray1::from_vec(py, values).into_any())
    }
}

/// The library error with the row named in its reason.
fn row_error(e: stochvib::Error, row: usize) -> stochvib::Error {
    use stochvib::Error;
    match e {
        Error::InvalidParameter { name, value, reason } => Error::InvalidParameter {
            name: format!("{name} (row {row})"),
            value,
            reason,
        },
        Error::Divergent { quantity, reason } => Error::Divergent {
            quantity: format!("{quantity} (row {row})"),
            reason,
        },
        Error::Numerical { what, reason } => Error::Numerical {
            what: format!("{what} (row {row})"),
            reason,
        },
        other => other,
    }
}
