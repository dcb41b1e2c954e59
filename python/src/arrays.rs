//! numpy arrays in and out: every array argument is converted to a C-contiguous float64 array when it is
//! not one already (lists, integer arrays, strided views, Fortran order, big-endian data), and refused with
//! an `InvalidInputError` naming the argument when it cannot be (complex, bool, strings, objects, the wrong
//! number of dimensions). Results are new float64 (or complex128) arrays, or an `out=` array the caller
//! provides, which must already be float64, C-contiguous, writeable and of the right shape (outputs are never
//! converted: a converted copy would silently not be the caller's array).

use crate::errors::invalid_input;
use nalgebra::DMatrix;
use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
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
