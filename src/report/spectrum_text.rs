//! The text of the `stochvib spectrum` report ([`crate::study::spectrum_report()`] computes it): variance two
//! ways, correlation at a few lags, density at a few frequencies in a chosen convention.

use crate::study::spectrum_report::{Outcome, SpectrumReport};
use std::fmt;

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Outcome::Value(v) => write!(f, "{v:.6e}"),
            Outcome::NoValue { error } => write!(f, "none: {error}"),
        }
    }
}

impl fmt::Display for SpectrumReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let lag = if self.domain == "spatial" { "m" } else { "s" };
        writeln!(f, "spectrum  {}", self.name)?;
        writeln!(f, "model     {}", self.model)?;
        if !self.source.is_empty() {
            writeln!(f, "source    {}", self.source)?;
        }
        writeln!(f, "domain    {} (process unit {})", self.domain, self.unit)?;
        writeln!(f, "variance  {}  [{}^2]", self.variance, self.unit)?;
        write!(f, "  by quadrature {}", self.variance_quadrature)?;
        if let Some(e) = self.variance_quadrature_error {
            write!(f, " ± {e:.1e}")?;
        }
        if let Some(r) = self.variance_rel_diff {
            write!(f, "   (relative difference {r:.1e})")?;
        }
        writeln!(f)?;
        writeln!(f, "sigma     {}  [{}]", self.sigma, self.unit)?;
        writeln!(f, "correlation K(tau) [{}^2]:", self.unit)?;
        writeln!(
            f,
            "  {:>12}  {:>14}  {:>14}",
            format!("tau [{lag}]"),
            "model",
            "quadrature"
        )?;
        for (t, a, b) in &self.correlation {
            writeln!(f, "  {t:>12.4e}  {:>14}  {:>14}", short(a), short(b))?;
        }
        writeln!(f, "density ({}):", self.convention)?;
        writeln!(f, "  {:>14}  {:>14}", format!("[{}]", self.abscissa_unit), "value")?;
        for (x, v) in &self.density {
            writeln!(f, "  {x:>14.4e}  {v:>14.6e}")?;
        }
        Ok(())
    }
}

fn short(o: &Outcome) -> String {
    match o {
        Outcome::Value(v) => format!("{v:.6e}"),
        Outcome::NoValue { .. } => "infinite/none".to_string(),
    }
}
