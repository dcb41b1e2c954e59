//! Library errors and panics turned into the Python exceptions of `stochvib.errors`.
//!
//! Every [`stochvib::Error`] becomes an instance of one class of the `StochvibError` hierarchy (defined in
//! Python, `stochvib/errors.py`, so that a class can also derive from `ValueError`, `ArithmeticError` or
//! `OSError`) whose message is the error's `Display` text: the same text the command-line tool prints after
//! `error: `. The error's fields are attached as attributes (`quantity`, `reason`, `key`, ...).
//!
//! A panic inside the library (a bug: the library promises not to panic on user input) is caught by
//! [`catch`] and raised as `StochvibError("internal error: …")`; no panic reaches Python.

use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyModule};
use pyo3::IntoPyObjectExt;
use std::panic::{catch_unwind, AssertUnwindSafe};
use stochvib::Error;

/// Why a call failed: a library error, a Python exception (raised by a callback, or a KeyboardInterrupt),
/// or a panic. All three are `Send`, so they cross [`Python::detach`].
#[derive(Debug)]
pub enum Failure {
    /// An error of the library.
    Lib(Error),
    /// A Python exception to re-raise as it is.
    Py(PyErr),
    /// A panic message.
    Panic(String),
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        Failure::Lib(e)
    }
}

impl From<PyErr> for Failure {
    fn from(e: PyErr) -> Self {
        Failure::Py(e)
    }
}

/// Result of a guarded computation.
pub type Outcome<T> = std::result::Result<T, Failure>;

/// Runs `f`, turning a panic into [`Failure::Panic`].
pub fn catch<T>(f: impl FnOnce() -> Outcome<T>) -> Outcome<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => Err(Failure::Panic(panic_message(payload.as_ref()))),
    }
}

/// The text of a panic payload.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        s.to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic with a non-text payload".to_string()
    }
}

static ERRORS: PyOnceLock<Py<PyModule>> = PyOnceLock::new();

fn errors_module(py: Python<'_>) -> PyResult<&Bound<'_, PyModule>> {
    ERRORS
        .get_or_try_init(py, || Ok(py.import("stochvib.errors")?.unbind()))
        .map(|m| m.bind(py))
}

/// An instance of `stochvib.errors.<class>` with `message` and keyword attributes.
pub fn raise(py: Python<'_>, class: &str, message: &str, details: &[(&str, Py<PyAny>)]) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let cls = errors_module(py)?.getattr(class)?;
        let kw = PyDict::new(py);
        for (k, v) in details {
            kw.set_item(*k, v.bind(py))?;
        }
        Ok(PyErr::from_value(cls.call((message,), Some(&kw))?))
    };
    build().unwrap_or_else(|e| e)
}

/// `InvalidInputError(message)`: bad arguments found by the binding itself (dtype, shape, names).
pub fn invalid_input(py: Python<'_>, message: impl AsRef<str>) -> PyErr {
    raise(py, "InvalidInputError", message.as_ref(), &[])
}

/// `UnitError` for the quantity string `text` given as the parameter `name`: the library's
/// `InvalidParameter` message ("invalid parameter `speed` = \"10 kmh\": unknown unit …").
pub fn unit_error(py: Python<'_>, name: &str, text: &str, reason: &str) -> PyErr {
    let msg = Error::invalid(name, format!("{text:?}"), reason).to_string();
    raise(
        py,
        "UnitError",
        &msg,
        &[
            ("name", obj(py, name)),
            ("value", obj(py, text)),
            ("reason", obj(py, reason)),
        ],
    )
}

/// `NotApplicableError(message)`.
pub fn not_applicable(py: Python<'_>, message: impl AsRef<str>) -> PyErr {
    raise(py, "NotApplicableError", message.as_ref(), &[])
}

fn obj<'py, T: IntoPyObject<'py>>(py: Python<'py>, v: T) -> Py<PyAny> {
    v.into_py_any(py).unwrap_or_else(|_| py.None())
}

/// The Python exception for a library error (class by variant, the `Display` text as message).
pub fn lib_error(py: Python<'_>, e: &Error) -> PyErr {
    let msg = e.to_string();
    let path = |p: &std::path::Path| obj(py, p.display().to_string());
    #[allow(unreachable_patterns)] // variants added to the library later fall back to the base class
    match e {
        Error::InvalidParameter { name, value, reason } => raise(
            py,
            "InvalidInputError",
            &msg,
            &[
                ("name", obj(py, name)),
                ("value", obj(py, value)),
                ("reason", obj(py, reason)),
            ],
        ),
        Error::Unit { text, reason } => raise(
            py,
            "UnitError",
            &msg,
            &[("value", obj(py, text)), ("reason", obj(py, reason))],
        ),
        Error::NotApplicable { method, reason } => raise(
            py,
            "NotApplicableError",
            &msg,
            &[("method", obj(py, method)), ("reason", obj(py, reason))],
        ),
        Error::Divergent { quantity, reason } => raise(
            py,
            "DivergentError",
            &msg,
            &[("quantity", obj(py, quantity)), ("reason", obj(py, reason))],
        ),
        Error::Quadrature {
            what,
            estimate,
            abs_error,
            evaluations,
            reason,
        } => raise(
            py,
            "NotConvergedError",
            &msg,
            &[
                ("what", obj(py, what)),
                ("estimate", obj(py, *estimate)),
                ("abs_error", obj(py, *abs_error)),
                ("evaluations", obj(py, *evaluations)),
                ("reason", obj(py, reason)),
            ],
        ),
        Error::Numerical { what, reason } => raise(
            py,
            "NumericalError",
            &msg,
            &[("what", obj(py, what)), ("reason", obj(py, reason))],
        ),
        Error::File {
            file,
            key,
            value,
            reason,
        } => raise(
            py,
            "FileError",
            &msg,
            &[
                ("path", path(file)),
                ("key", obj(py, key)),
                ("value", obj(py, value)),
                ("reason", obj(py, reason)),
            ],
        ),
        Error::Parse { file, reason } => raise(
            py,
            "FileError",
            &msg,
            &[("path", path(file)), ("reason", obj(py, reason))],
        ),
        Error::Hdf5 { path: p, reason } => {
            raise(py, "FileError", &msg, &[("path", path(p)), ("reason", obj(py, reason))])
        }
        Error::Io { path: p, source } => raise(
            py,
            "FileError",
            &msg,
            &[("path", path(p)), ("reason", obj(py, source.to_string()))],
        ),
        _ => raise(py, "StochvibError", &msg, &[]),
    }
}

/// The Python exception for a [`Failure`].
pub fn to_py(py: Python<'_>, f: Failure) -> PyErr {
    match f {
        Failure::Lib(e) => lib_error(py, &e),
        Failure::Py(e) => e,
        Failure::Panic(m) => raise(
            py,
            "StochvibError",
            &format!("internal error (a bug in stochvib, please report it): {m}"),
            &[],
        ),
    }
}

/// Runs a library call with the GIL held, catching panics, and converts its error.
pub fn call<T>(py: Python<'_>, f: impl FnOnce() -> stochvib::Result<T>) -> PyResult<T> {
    catch(|| f().map_err(Failure::Lib)).map_err(|e| to_py(py, e))
}

/// Converts a library result (for errors the binding builds itself).
pub fn lib<T>(py: Python<'_>, r: stochvib::Result<T>) -> PyResult<T> {
    r.map_err(|e| lib_error(py, &e))
}

/// Runs `f` without the GIL, catching panics, and converts its failure.
pub fn detached<T, F>(py: Python<'_>, f: F) -> PyResult<T>
where
    F: FnOnce() -> Outcome<T> + Send,
    T: Send,
{
    py.detach(|| catch(f)).map_err(|e| to_py(py, e))
}

/// As [`detached`] when `work` (points, evaluations) is at least `min_work`, else with the GIL held (releasing
/// and re-acquiring it costs more than a short computation); panics are caught either way.
pub fn detached_if<T, F>(py: Python<'_>, work: usize, min_work: usize, f: F) -> PyResult<T>
where
    F: FnOnce() -> Outcome<T> + Send,
    T: Send,
{
    if work >= min_work {
        detached(py, f)
    } else {
        catch(f).map_err(|e| to_py(py, e))
    }
}
