//! Helpers shared by the integration tests (each test file includes them with `mod common;`): the named
//! tolerances and the relative difference used in assertions.
#![allow(dead_code)] // each test binary uses a different subset

pub mod tolerance;

use std::path::PathBuf;

/// Relative difference |a − b| / max(|a|, |b|), 0 when both are 0 (the library's
/// [`stochvib::numbers::rel_diff`]).
pub fn rel(a: f64, b: f64) -> f64 {
    stochvib::numbers::rel_diff(a, b)
}

/// The source tree (for `data/` and `spectra/`).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}
