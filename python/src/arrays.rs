//! numpy arrays in and out: every array argument is converted to a C-contiguous float64 array when it is
//! not one already (lists, integer arrays, strided views, Fortran order, big-endian data), and refused with
//! an `InvalidInputError` naming the argument when it cannot be (complex, bool, strings, objects, the wrong
//! number of dimensions). Results are new float64 (or complex128) arrays, or an `out=` array the caller
//! provides, which must already be float64, C-contiguous, writeable and of the right shape (outputs are never
//! converted: a converted copy would silently not be the caller's array).

use crate::errors::invalid_input;
use nalgebra::DMatrix;
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyModule};

static NUMPY: PyOnceLock<Py<PyModule>> = PyOnceLock::new();

/// The `numpy` module.
pub fn numpy(py: Python<'_>) -> PyResult<&Bound<'_, PyModule>> {
    NUMPY
        .get_or_try_init(py, || Ok(py.import("numpy")?.unbind()))
        .map(|m| m.bind(py))
}

/// `obj` as a C-contiguous float64 array: the array itself when it is one, else a converted copy.
///
/// # Errors
/// `InvalidInputError` naming `name` for complex, boolean, string or object data, or anything numpy cannot
/// read as an array.
pub fn real_array<'py>(py: Python<'py>, obj: &Bound<'py, PyAny>, name: &str) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        if a.is_c_contiguous() {
            return Ok(a.clone());
        }
    }
    let np = numpy(py)?;
    let arr = np
        .call_method1("asarray", (obj,))
        .map_err(|e| invalid_input(py, format!("`{name}` cannot be read as an array of numbers: {e}")))?;
    let dtype = arr.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    match kind.as_str() {
        "i" | "u" | "f" => {}
        "c" => {
            return Err(invalid_input(
                py,
                format!(
                    "`{name}` has complex dtype {}: expected real numbers (pass .real or abs() explicitly)",
                    dtype.str()?
                ),
            ))
        }
        _ => {
            return Err(invalid_input(
                py,
                format!(
                    "`{name}` has dtype {}: expected real numbers (float or integer)",
                    dtype.str()?
                ),
            ))
        }
    }
    let kw = PyDict::new(py);
    kw.set_item("dtype", np.getattr("float64")?)?;
    kw.set_item("order", "C")?;
    // (not ascontiguousarray, which turns a 0-d array into a 1-d one)
    let c = np.call_method("asarray", (arr,), Some(&kw))?;
    Ok(c.cast_into::<PyArrayDyn<f64>>()?)
}

/// A 1-D real vector argument.
///
/// # Errors
/// As [`real_array`], plus an array that is not 1-D.
pub fn vector(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<f64>> {
    let a = real_array(py, obj, name)?;
    if a.ndim() != 1 {
        return Err(invalid_input(
            py,
            format!("`{name}` must be 1-D, got shape {:?}", a.shape()),
        ));
    }
    Ok(a.readonly().as_slice()?.to_vec())
}

/// A 2-D real matrix argument (row-major input, any memory order accepted).
///
/// # Errors
/// As [`real_array`], plus an array that is not 2-D (a 1-D vector is ambiguous between a row and a column).
pub fn matrix(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> PyResult<DMatrix<f64>> {
    let a = real_array(py, obj, name)?;
    let shape = a.shape().to_vec();
    if shape.len() != 2 {
        return Err(invalid_input(
            py,
            format!(
                "`{name}` must be a 2-D matrix, got shape {shape:?} (a column is x.reshape(-1, 1), a row \
                 x.reshape(1, -1))"
            ),
        ));
    }
    let ro = a.readonly();
    Ok(DMatrix::from_row_slice(shape[0], shape[1], ro.as_slice()?))
}

/// A matrix as a new 2-D float64 numpy array.
pub fn matrix_to_py<'py>(py: Python<'py>, m: &DMatrix<f64>) -> PyResult<Bound<'py, PyAny>> {
    let rows: Vec<Vec<f64>> = (0..m.nrows()).map(|i| m.row(i).iter().copied().collect()).collect();
    if m.nrows() == 0 || m.ncols() == 0 {
        let kw = PyDict::new(py);
        kw.set_item("dtype", numpy(py)?.getattr("float64")?)?;
        return numpy(py)?.call_method("zeros", ((m.nrows(), m.ncols()),), Some(&kw));
    }
    Ok(numpy::PyArray2::from_vec2(py, &rows)
        .map_err(|e| invalid_input(py, e.to_string()))?
        .into_any())
}

/// The `out=` argument checked against the result shape: float64, C-contiguous, writeable.
///
/// # Errors
/// `InvalidInputError` saying what is wrong; outputs are never converted.
pub fn check_out<'py>(
    py: Python<'py>,
    out: &Bound<'py, PyAny>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let a = out.cast::<PyArrayDyn<f64>>().map_err(|_| {
        invalid_input(
            py,
            "`out` must be a numpy array of dtype float64 (outputs are never converted)",
        )
    })?;
    if a.shape() != shape {
        return Err(invalid_input(
            py,
            format!("`out` has shape {:?}; the result has shape {shape:?}", a.shape()),
        ));
    }
    if !a.is_c_contiguous() {
        return Err(invalid_input(py, "`out` must be C-contiguous"));
    }
    if let Err(e) = a.try_readwrite() {
        return Err(invalid_input(py, format!("`out` cannot be written: {e}")));
    }
    Ok(a.clone())
}

/// Polynomial coefficients in ASCENDING powers (the library's order), from coefficients given in `order`:
/// "descending" (highest power first, scipy.signal's and python-control's order) or "ascending".
///
/// # Errors
/// As [`vector`], plus an `order` that is neither.
pub fn polynomial(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, order: &str) -> PyResult<Vec<f64>> {
    let mut v = vector(py, obj, name)?;
    if descending(py, order)? {
        v.reverse();
    }
    Ok(v)
}

/// Whether `order` is "descending" (true) or "ascending" (false).
///
/// # Errors
/// `InvalidInputError` for anything else.
pub fn descending(py: Python<'_>, order: &str) -> PyResult<bool> {
    match order {
        "descending" => Ok(true),
        "ascending" => Ok(false),
        other => crate::errors::lib(
            py,
            Err(stochvib::Error::invalid(
                "order",
                other,
                "expected \"descending\" (highest power first, as scipy.signal) or \"ascending\"",
            )),
        ),
    }
}

/// A vector of coefficients in ascending powers as a new 1-D array in `order`.
pub fn polynomial_to_py<'py>(py: Python<'py>, coeffs: &[f64], descending: bool) -> Bound<'py, PyArray1<f64>> {
    let mut v = coeffs.to_vec();
    if descending {
        v.reverse();
    }
    PyArray1::from_vec(py, v)
}

/// The angular frequencies of an `omega=` (rad/s) or `f=` (Hz, converted: ω = 2πf) argument, exactly one
/// of which must be given.
///
/// # Errors
/// `InvalidInputError` when both or neither are given, or as [`real_array`].
pub fn angular<'py>(
    py: Python<'py>,
    omega: Option<&Bound<'py, PyAny>>,
    f: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    match (omega, f) {
        (Some(w), None) => real_array(py, w, "omega"),
        (None, Some(f)) => {
            let f = real_array(py, f, "f")?;
            // SAFETY: every element is written below before the array is used.
            let w = unsafe { PyArrayDyn::<f64>::new(py, f.shape().to_vec(), false) };
            {
                let fr = f.readonly();
                let mut wr = w.readwrite();
                for (o, &x) in wr.as_slice_mut()?.iter_mut().zip(fr.as_slice()?) {
                    *o = 2.0 * std::f64::consts::PI * x;
                }
            }
            Ok(w)
        }
        _ => Err(invalid_input(
            py,
            "give exactly one of `omega` (angular frequency, rad/s) and `f` (frequency, Hz)",
        )),
    }
}
