//! Reports: the tables the command-line tool prints, as plain data (serialisable to JSON) plus a text
//! rendering. The CLI only parses arguments, calls these and prints.

pub mod analysis;
pub mod book;
pub mod spectrum_report;

pub use analysis::{analysis_report, AnalysisReport};
pub use spectrum_report::{resolve_spectrum, spectrum_report, SpectrumReport};

/// Directory of the spectrum catalogue: `$STOCHVIB_SPECTRA`, else `./spectra` if it exists, else the
/// `spectra/` directory of the source tree this binary was built from.
pub fn default_spectra_dir() -> std::path::PathBuf {
    if let Ok(d) = std::env::var("STOCHVIB_SPECTRA") {
        return d.into();
    }
    let local = std::path::PathBuf::from("spectra");
    if local.is_dir() {
        return local;
    }
    std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/spectra"))
}

/// Relative difference |a − b| / max(|a|, |b|), 0 when both are 0.
pub fn rel_diff(a: f64, b: f64) -> f64 {
    let m = a.abs().max(b.abs());
    if m == 0.0 {
        0.0
    } else {
        (a - b).abs() / m
    }
}
