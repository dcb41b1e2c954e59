//! The native module `stochvib._stochvib` of the Python package `stochvib` (PyO3).
//!
//! A thin layer over the library's public API: every computation is a library call; this crate converts
//! arrays (`arrays`), names (`names`), errors (`errors`) and reports (`convert`), releases the GIL around
//! long calls and stops Monte Carlo runs on Ctrl-C (`interrupt`). The Python package (`stochvib/`) adds
//! the result classes, the progress bar and the module-level functions.
#![warn(clippy::too_many_lines)] // no function of more than 100 lines of code (see the library's root)

use pyo3::prelude::*;

mod analysis;
mod arrays;
mod convert;
mod errors;
mod interrupt;
mod linalg;
mod merges;
mod names;
mod nonlinear_run;
mod optimize;
mod quantity;
mod reports;
mod scenario;
mod spectrum;
mod spectrum_units;
mod system;
mod toolkit;
mod transient;
mod two_tracks;

/// Native part of the stochvib Python package (import `stochvib`, not this module).
#[pymodule]
fn _stochvib(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<spectrum::PySpectrum>()?;
    m.add_class::<system::PySystem>()?;
    m.add_class::<scenario::PyScenario>()?;
    m.add_function(wrap_pyfunction!(linalg::h2_integral, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::weighting_response, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::weighting_filter, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::rainflow, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::spectral_fatigue, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::sn_curve, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::exposure, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::welch, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::iri, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::expected_iri, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::iso8608_class, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::road_profile, m)?)?;
    m.add_function(wrap_pyfunction!(merges::merge, m)?)?;
    m.add_function(wrap_pyfunction!(merges::merge_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::coherence_amplitude, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::daily_exposure_a8, m)?)?;
    m.add_function(wrap_pyfunction!(toolkit::vdv_gaussian, m)?)?;
    m.add_function(wrap_pyfunction!(reports::replay, m)?)?;
    m.add_function(wrap_pyfunction!(reports::workday, m)?)?;
    m.add_function(wrap_pyfunction!(reports::inspect, m)?)?;
    m.add_function(wrap_pyfunction!(_check_panic_guard, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ISO_BAND", stochvib::spectrum::ISO_BAND)?;
    Ok(())
}

/// Test hook (not API): panics inside the binding's guards — ``"gil"`` with the GIL held, ``"detached"``
/// without it, ``"callback"`` inside the progress callback of an interruptible call — to show that a panic
/// becomes ``StochvibError("internal error …")`` and never reaches Python as a crash.
#[pyfunction]
fn _check_panic_guard(py: Python<'_>, r#where: &str) -> PyResult<()> {
    let boom = || -> ! { panic!("panic guard check ({where})") };
    match r#where {
        "gil" => errors::call(py, || -> stochvib::Result<()> { boom() }),
        "detached" => errors::detached(py, || -> errors::Outcome<()> { boom() }),
        "callback" => interrupt::run_interruptible(py, None, |cb| -> stochvib::Result<()> {
            cb(0, 1);
            boom()
        }),
        _ => Err(errors::invalid_input(py, format!("unknown place {where:?}"))),
    }
}
