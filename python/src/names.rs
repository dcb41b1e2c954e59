//! Names written in Python arguments turned into library values: conventions, domains, the spectrum
//! catalogue directory. Bad names raise the library's own `InvalidParameter` message.

use crate::errors::{call, lib};
use pyo3::prelude::*;
use std::path::PathBuf;
use stochvib::scenario::Catalogue;
use stochvib::spectrum::{Convention, Domain};
use stochvib::Error;

/// A [`Convention`] by its file/command-line name (`two-sided-angular`, `one-sided-angular`,
/// `one-sided-cyclic`, `engineering`).
pub fn convention(py: Python<'_>, name: &str) -> PyResult<Convention> {
    call(py, || name.parse::<Convention>())
}

/// A [`Domain`] by its file name (`temporal`, `spatial`).
pub fn domain(py: Python<'_>, name: &str) -> PyResult<Domain> {
    match name {
        "temporal" => Ok(Domain::Temporal),
        "spatial" => Ok(Domain::Spatial),
        other => lib(
            py,
            Err(Error::invalid("domain", other, "expected \"temporal\" or \"spatial\"")),
        ),
    }
}

/// The file name of a [`Domain`].
pub fn domain_name(d: Domain) -> &'static str {
    match d {
        Domain::Temporal => "temporal",
        Domain::Spatial => "spatial",
    }
}

/// The spectrum catalogue, chosen as the command-line tool chooses it: `spectra_dir` if given, else
/// `$STOCHVIB_SPECTRA`, else `./spectra` if it exists, else the built-in catalogue (the `spectra/` files
/// embedded when the package was built).
pub fn catalogue(spectra_dir: Option<PathBuf>) -> Catalogue {
    Catalogue::chosen(spectra_dir.as_deref())
}

/// A [`stochvib::road::Detrend`] by its name (`mean`, `linear`), as the command-line tool's `--detrend`.
pub fn detrend(py: Python<'_>, name: &str) -> PyResult<stochvib::road::Detrend> {
    match name {
        "mean" => Ok(stochvib::road::Detrend::Mean),
        "linear" => Ok(stochvib::road::Detrend::Linear),
        other => Err(crate::errors::invalid_input(
            py,
            format!("detrend={other:?}: expected \"mean\" or \"linear\""),
        )),
    }
}
