//! The `stochvib spectra` report: every spectrum of a catalogue directory with its variance and σ, and the
//! files that failed to load with their errors; and the `stochvib models` list of model kinds.

use crate::error::Result;
use crate::scenario::{Catalogue, ModelKind, MODEL_KINDS};
use crate::spectrum::Convention;
use crate::study::spectrum_report::{spectrum_report, Outcome, SpectrumReport};
use serde::Serialize;
use std::fmt;

/// Every entry of a spectrum catalogue.
#[derive(Debug, Clone, Serialize)]
pub struct CatalogueReport {
    /// The catalogue directory.
    pub dir: String,
    /// One report per valid spectrum file, sorted by file name.
    pub spectra: Vec<SpectrumReport>,
    /// The invalid files with the error that names what is wrong.
    pub failures: Vec<String>,
}

/// Reports every spectrum of `catalogue` (densities in the canonical two-sided angular convention).
///
/// # Errors
/// [`Error::Io`](crate::Error::Io) if the directory cannot be read; invalid files are listed in
/// [`CatalogueReport::failures`], not errors.
pub fn catalogue_report(catalogue: &Catalogue) -> Result<CatalogueReport> {
    let mut spectra = Vec::new();
    let mut failures = Vec::new();
    for e in catalogue.entries()? {
        match &e.spectrum {
            Ok(s) => spectra.push(spectrum_report(s, Convention::TwoSidedAngular)),
            Err(msg) => failures.push(msg.clone()),
        }
    }
    Ok(CatalogueReport {
        dir: catalogue.dir().display().to_string(),
        spectra,
        failures,
    })
}

impl fmt::Display for CatalogueReport {
    /// The table `name, domain, variance, sigma, model`; `{:#}` prints the full report of every entry.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if f.alternate() {
            for r in &self.spectra {
                writeln!(f, "{r}")?;
            }
            return Ok(());
        }
        writeln!(f, "catalogue {}", self.dir)?;
        writeln!(
            f,
            "{:<24} {:<9} {:>13} {:>13}  model",
            "name", "domain", "variance", "sigma"
        )?;
        for r in &self.spectra {
            let (v, sg) = match (&r.variance, &r.sigma) {
                (Outcome::Value(v), Outcome::Value(s)) => (format!("{v:.4e}"), format!("{s:.4e}")),
                _ => ("infinite".into(), "infinite".into()),
            };
            writeln!(f, "{:<24} {:<9} {:>13} {:>13}  {}", r.name, r.domain, v, sg, r.model)?;
        }
        Ok(())
    }
}

/// The model kinds of the registry ([`MODEL_KINDS`]), for `stochvib models`.
#[derive(Debug, Clone, Serialize)]
pub struct ModelsReport {
    /// Every kind.
    pub kinds: Vec<ModelKind>,
}

/// The list of model kinds.
pub fn models_report() -> ModelsReport {
    ModelsReport {
        kinds: MODEL_KINDS.to_vec(),
    }
}

impl fmt::Display for ModelsReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{:<24} {:<10} {:<13} {:<32}  summary",
            "kind", "family", "input", "example"
        )?;
        for k in &self.kinds {
            writeln!(
                f,
                "{:<24} {:<10} {:<13} {:<32}  {}",
                k.name,
                format!("{:?}", k.family).to_lowercase(),
                if k.stochastic { "random" } else { "deterministic" },
                if k.example.is_empty() { "-" } else { k.example },
                k.summary
            )?;
        }
        Ok(())
    }
}
