//! The text of the `stochvib analyze` report ([`crate::study::analysis`] computes it): per output, the mean,
//! σ, 3σ bounds, crossing rates and every variance method with its value and its relative difference to the
//! reference.

use crate::response::{Outcome, VarianceValue};
use crate::study::analysis::{AnalysisReport, MonteCarloColumn, OutputReport};
use std::fmt;

fn opt(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.6e}")).unwrap_or_else(|| "—".into())
}

impl fmt::Display for AnalysisReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "scenario  {}  ({})", self.title, self.scenario)?;
        writeln!(f, "model     {}", self.model)?;
        writeln!(f, "input     {}", self.input)?;
        if let Some(sag) = &self.static_sag {
            let each: Vec<String> = sag
                .iter()
                .map(|s| format!("{} {} m", s.element, crate::numbers::sig4(s.deflection_m)))
                .collect();
            writeln!(f, "sag       static compression under gravity: {}", each.join(", "))?;
        }
        for o in &self.outputs {
            self.write_output(f, o)?;
        }
        if let Some(v) = &self.verdicts {
            write!(f, "{v}")?;
        }
        if let Some(v) = &self.monte_carlo_verdicts {
            write!(f, "{v}")?;
        }
        Ok(())
    }
}

impl AnalysisReport {
    /// One output's block: mean, σ (and the Monte Carlo σ), bounds, band σ, crossing rates, levels, every
    /// variance method and the band tables.
    fn write_output(&self, f: &mut fmt::Formatter<'_>, o: &OutputReport) -> fmt::Result {
        let s = &o.statistics;
        writeln!(f)?;
        writeln!(f, "output {} [{}]", s.name, s.unit)?;
        writeln!(f, "  mean          {}", opt(s.mean))?;
        match s.sigma {
            Some(sig) => writeln!(f, "  sigma         {sig:.6e}")?,
            None => writeln!(f, "  sigma         {}", s.variance_outcome.describe())?,
        }
        if let Some(mc) = &o.monte_carlo {
            monte_carlo_line(f, mc)?;
        }
        writeln!(f, "  3σ bounds     [{}, {}]", opt(o.lower_3sigma), opt(o.upper_3sigma))?;
        if let (Some((a, b)), true) = (self.band_rad_s, o.band_sigma.is_some() || o.band_note.is_some()) {
            let band = format!(
                "{:.3}–{:.3} Hz",
                a / (2.0 * std::f64::consts::PI),
                b / (2.0 * std::f64::consts::PI)
            );
            match (o.band_sigma, &o.band_note) {
                (Some(v), _) => writeln!(f, "  sigma {band}  {v:.6e}")?,
                (None, Some(n)) => writeln!(f, "  sigma {band}  — {n}")?,
                _ => {}
            }
        }
        match s.rate_note() {
            None => writeln!(
                f,
                "  ν0+ (zero up-crossings) {} /s   bandwidth ε {}",
                opt(s.zero_upcrossing_rate),
                opt(s.bandwidth)
            )?,
            Some(why) => writeln!(f, "  ν0+ (zero up-crossings) — ({why})")?,
        }
        writeln!(
            f,
            "  expected largest peak in {} s: {}",
            self.duration_s,
            opt(o.expected_largest_peak)
        )?;
        for l in &o.levels {
            writeln!(
                f,
                "  level {:.6e}: up-crossing rate {} /s, P(exceed in {} s) {}",
                l.level,
                opt(l.upcrossing_rate),
                self.duration_s,
                opt(l.exceedance_probability)
            )?;
        }
        writeln!(
            f,
            "  {:<17} {:>14} {:>11} {:>11}  note",
            "variance method", "value", "error est.", "rel. diff"
        )?;
        for m in &s.methods {
            method_line(f, m)?;
        }
        if let Some(b) = &o.bands {
            write!(f, "{b}")?;
        }
        Ok(())
    }
}

/// The Monte Carlo σ of an output with its interval, or why there is none.
fn monte_carlo_line(f: &mut fmt::Formatter<'_>, mc: &MonteCarloColumn) -> fmt::Result {
    match (&mc.sigma, mc.covered) {
        (Some(iv), Some(c)) => writeln!(
            f,
            "  sigma MC      {:.6e}  [{:.6e}, {:.6e}] ({} %, {} realizations, {})  covers analytic: {}{}",
            iv.estimate,
            iv.lower,
            iv.upper,
            100.0 * iv.confidence,
            mc.realizations,
            mc.method,
            if c { "yes" } else { "NO" },
            mc.discrete_sigma
                .map(|d| format!("  (discrete-process σ {d:.6e})"))
                .unwrap_or_default()
        )?,
        _ => writeln!(f, "  sigma MC      — {}", mc.note.as_deref().unwrap_or(""))?,
    }
    Ok(())
}

/// One variance method's row: value, error estimate, relative difference and note.
fn method_line(f: &mut fmt::Formatter<'_>, m: &VarianceValue) -> fmt::Result {
    let (value, error, note) = match &m.outcome {
        Outcome::Value { value, error_estimate } => (
            format!("{value:.6e}"),
            error_estimate.map(|e| format!("{e:.1e}")),
            String::new(),
        ),
        Outcome::Divergent { reason } => ("infinite".into(), None, reason.clone()),
        Outcome::NotConverged {
            estimate,
            error_estimate,
            reason,
            ..
        } => (
            format!("~{estimate:.6e}"),
            Some(format!("{error_estimate:.1e}")),
            format!("not converged: {reason}"),
        ),
        Outcome::Unreliable { value, reason } => (
            format!("({value:.6e})"),
            None,
            format!("unreliable, not used: {reason}"),
        ),
        Outcome::NotApplicable { reason } => ("—".into(), None, reason.clone()),
        Outcome::Failed { reason } => ("—".into(), None, format!("failed: {reason}")),
    };
    writeln!(
        f,
        "  {:<17} {:>14} {:>11} {:>11}  {}",
        m.method.name(),
        value,
        error.unwrap_or_else(|| "—".into()),
        m.rel_diff.map(|e| format!("{e:.1e}")).unwrap_or_else(|| "—".into()),
        note
    )?;
    Ok(())
}
