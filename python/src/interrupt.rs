//! Long library calls with a progress callback, the GIL released, and a clean stop on Ctrl-C.
//!
//! The library's [`stochvib::simulate::run`] reports progress through `&dyn Fn(usize, usize)` after every
//! shard written, and offers no way for the callback to ask it to stop. The callback here re-attaches to the
//! interpreter, calls the Python progress callable and `Python::check_signals` (which raises
//! `KeyboardInterrupt` after Ctrl-C); on an exception it stores it and unwinds out of the library with
//! [`std::panic::resume_unwind`] (a payload of its own type, which runs no panic hook and prints nothing).
//! The unwinding drops the library's run writer between two shards, which closes the HDF5 file and leaves
//! `<path>.tmp` with every shard written so far: a rerun with the same options resumes it. The stored
//! exception is then raised in Python. Any other panic becomes `StochvibError("internal error: …")`.
//!
//! A library API for this — the callback returning `ControlFlow`/`Result`, or a cancellation flag in
//! `RunOptions` — would make the unwinding unnecessary.

use crate::errors::{lib_error, panic_message, raise};
use pyo3::prelude::*;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::Mutex;

/// The unwinding payload of a stop requested from Python.
struct StopRequested;

/// Runs `f` without the GIL, handing it a progress callback that calls `progress(done, total)` (if any) and
/// checks for Ctrl-C; an exception in either stops `f` (see the module docs) and is raised here.
pub fn run_interruptible<T, F>(py: Python<'_>, progress: Option<Py<PyAny>>, f: F) -> PyResult<T>
where
    F: FnOnce(&(dyn Fn(usize, usize) + Sync)) -> stochvib::Result<T> + Send,
    T: Send,
{
    let stored: Mutex<Option<PyErr>> = Mutex::new(None);
    let callback = |done: usize, total: usize| {
        let r = Python::attach(|py| -> PyResult<()> {
            if let Some(cb) = &progress {
                cb.call1(py, (done, total))?;
            }
            py.check_signals()
        });
        if let Err(e) = r {
            *stored.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
            resume_unwind(Box::new(StopRequested));
        }
    };
    let outcome = py.detach(|| catch_unwind(AssertUnwindSafe(|| f(&callback))));
    match outcome {
        Ok(Ok(v)) => Ok(v),
        Ok(Err(e)) => Err(lib_error(py, &e)),
        Err(payload) if payload.is::<StopRequested>() => Err(stored
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .take()
            .unwrap_or_else(|| pyo3::exceptions::PyKeyboardInterrupt::new_err("stopped"))),
        Err(payload) => Err(raise(
            py,
            "StochvibError",
            &format!(
                "internal error (a bug in stochvib, please report it): {}",
                panic_message(payload.as_ref())
            ),
            &[],
        )),
    }
}
