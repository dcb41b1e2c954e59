//! What a run did: the route, sizes, the statistics of every simulated output against the analytic values,
//! the outputs it skipped and why.

use super::{Route, SkippedOutput};
use crate::store::{OutputStatistics, Part, Statistic};
use serde::Serialize;
use std::path::PathBuf;

/// What [`run`](super::run()) did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSummary {
    /// The finished file.
    pub path: PathBuf,
    /// The route taken (never `Auto`).
    pub route: Route,
    /// Generator description (also the file's `@generator`).
    pub generator: String,
    /// Samples per realization.
    pub n_samples: usize,
    /// Time step, s.
    pub dt_s: f64,
    /// Realizations.
    pub n_realizations: usize,
    /// Shards (of a shard file: its own internal shards).
    pub n_shards: usize,
    /// Shards found complete in an interrupted run and not recomputed.
    pub resumed_shards: usize,
    /// The part of the run computed (`simulate --shard I --of N`), or `None` for the whole run.
    pub part: Option<Part>,
    /// The realizations computed (all of them but for a part).
    pub realizations: std::ops::Range<usize>,
    /// The statistics of every simulated output (`mean`, `variance`, `sigma`, `sigma_discrete`), as stored
    /// in the file.
    pub outputs: Vec<OutputStatistics>,
    /// Outputs not simulated, with reasons.
    pub skipped: Vec<SkippedOutput>,
    /// Remarks (route and why, bias).
    pub notes: Vec<String>,
    /// Rainflow range histograms of the fatigue verdict channels (empty without them).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rainflow: Vec<super::RainflowSummary>,
    /// ISO 2631-1's basic-method check of every weighted output (crest factor, MTVV/a_w, VDV/(a_w T^(1/4))
    /// of the simulated records and the governing metric; empty without comfort channels).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub basic_method: Vec<super::RunBasicMethod>,
}

impl RunSummary {
    /// Statistic `statistic` (e.g. `sigma`) of output `output`, if simulated.
    pub fn statistic(&self, output: &str, statistic: &str) -> Option<&Statistic> {
        self.outputs.iter().find(|o| o.output == output)?.get(statistic)
    }
}

impl std::fmt::Display for RunSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "run       {}", self.path.display())?;
        writeln!(f, "route     {}: {}", self.route.name(), self.generator)?;
        writeln!(
            f,
            "size      {} realizations × {} samples (Δt = {} s), {} shards ({} resumed)",
            self.n_realizations, self.n_samples, self.dt_s, self.n_shards, self.resumed_shards
        )?;
        if let Some(p) = self.part {
            writeln!(
                f,
                "shard     {} of {}: realizations {}..{} (statistics below: this shard's only; merge the {} shard \
                 files with `stochvib merge`)",
                p.index, p.count, self.realizations.start, self.realizations.end, p.count
            )?;
        }
        for n in &self.notes {
            writeln!(f, "note      {n}")?;
        }
        writeln!(
            f,
            "{:<14} {:>13} {:>13} {:>13} {:>27}  covers",
            "output", "analytic σ", "discrete σ", "MC σ", "interval"
        )?;
        for o in &self.outputs {
            let (Some(s), Some(d)) = (o.get("sigma"), o.get("sigma_discrete")) else {
                continue;
            };
            let iv = &s.interval;
            writeln!(
                f,
                "{:<14} {:>13.6e} {:>13.6e} {:>13.6e} [{:.6e}, {:.6e}]  {} ({} %)",
                o.output,
                s.analytic.unwrap_or(f64::NAN),
                d.analytic.unwrap_or(f64::NAN),
                iv.estimate,
                iv.lower,
                iv.upper,
                if s.covers == Some(true) { "yes" } else { "NO" },
                100.0 * iv.confidence
            )?;
        }
        // comfort verdicts: the predicted VDV (its law's fourth moment) beside the Monte Carlo VDV
        let t = self.n_samples as f64 * self.dt_s;
        let mut header = false;
        for o in &self.outputs {
            let (Some(v), Some(d)) = (o.get("vdv"), o.get("sigma_discrete")) else {
                continue;
            };
            if !header {
                writeln!(
                    f,
                    "{:<14} {:>13} {:>13} {:>27}  covers   (VDV in m/s^1.75 over T = {} s)",
                    "VDV of", "predicted", "MC VDV", "interval", t
                )?;
                header = true;
            }
            let iv = &v.interval;
            // the law of the prediction: κ_w = VDV⁴/(T σ_d⁴) (3 for a Gaussian output)
            let law = match (v.analytic, d.analytic) {
                (Some(a), Some(sd)) if sd > 0.0 && t > 0.0 => {
                    let k = a.powi(4) / (t * sd.powi(4));
                    if v.method.contains("non-Gaussian") {
                        format!("(κ_w T)^(1/4)·σ_w, κ_w = {k:.4} (non-Gaussian input)")
                    } else {
                        "(3T)^(1/4)·σ_w (Gaussian)".to_string()
                    }
                }
                _ => String::new(),
            };
            writeln!(
                f,
                "{:<14} {:>13.6e} {:>13.6e} [{:.6e}, {:.6e}]  {} ({} %)  {law}",
                o.output,
                v.analytic.unwrap_or(f64::NAN),
                iv.estimate,
                iv.lower,
                iv.upper,
                covers_word(v.covers),
                100.0 * iv.confidence
            )?;
        }
        for b in &self.basic_method {
            writeln!(f, "basic     {}: {}", b.output, b.describe())?;
        }
        write_coverage_notes(f, &self.outputs)?;
        write_band_tables(f, &self.outputs)?;
        for s in &self.skipped {
            writeln!(f, "skipped   {}: {}", s.name, s.reason)?;
        }
        Ok(())
    }
}

/// Why an interval of σ does not cover the analytic σ: the discretisation bias of the chosen Δt (the
/// interval covers the exact σ of the simulated discrete process, [`coverage_cause`]) or chance.
fn write_coverage_notes(f: &mut std::fmt::Formatter<'_>, outputs: &[OutputStatistics]) -> std::fmt::Result {
    for o in outputs {
        if let Some(why) = coverage_cause(o) {
            writeln!(f, "covers    {}: {why}", o.output)?;
        }
    }
    Ok(())
}

/// For an output whose `sigma` interval misses the analytic σ: which it is. The discretisation bias
/// b = σ_d/σ − 1 of the chosen Δt and duration (σ_d the exact σ of the simulated discrete process,
/// `sigma_discrete`) is the cause when the interval covers σ_d; otherwise the miss is statistical (an
/// interval at confidence c misses with probability 1 − c). `None` when the interval covers.
///
/// # Examples
/// ```
/// use stochvib::estimate::Interval;
/// use stochvib::store::{OutputStatistics, Statistic};
/// let st = |name: &str, analytic: f64| Statistic {
///     name: name.into(),
///     interval: Interval { estimate: 0.94, lower: 0.93, upper: 0.95, confidence: 0.95 },
///     unit: "m".into(),
///     method: String::new(),
///     analytic: Some(analytic),
///     covers: Some((0.93..=0.95).contains(&analytic)),
/// };
/// let o = OutputStatistics {
///     output: "a".into(),
///     unit: "m".into(),
///     n_used: 10,
///     statistics: vec![st("sigma", 1.0), st("sigma_discrete", 0.94)],
/// };
/// assert!(stochvib::simulate::coverage_cause(&o).unwrap().contains("discretisation bias"));
/// ```
pub fn coverage_cause(o: &OutputStatistics) -> Option<String> {
    let s = o.get("sigma")?;
    if s.covers != Some(false) {
        return None;
    }
    let (a, iv) = (s.analytic?, &s.interval);
    let half = 0.5 * (iv.upper - iv.lower) / a;
    let Some(d) = o.get("sigma_discrete").and_then(|d| d.analytic) else {
        return Some("the interval misses the analytic σ (no discrete-process σ to compare)".into());
    };
    let bias = d / a - 1.0;
    Some(if iv.covers(d) {
        format!(
            "NOT covered because of the discretisation bias of Δt and the duration: the simulated discrete process \
             has σ_d/σ − 1 = {:+.3} %, more than the interval's half-width ±{:.3} %; the interval covers σ_d (a \
             smaller --dt or a longer --duration reduces the bias)",
            100.0 * bias,
            100.0 * half
        )
    } else {
        format!(
            "NOT covered by chance (statistical: the interval misses the discrete-process σ_d too, which happens in \
             {:.1} % of runs); the discretisation bias σ_d/σ − 1 = {:+.3} % is not the cause",
            100.0 * (1.0 - iv.confidence),
            100.0 * bias
        )
    })
}

/// The Monte Carlo band r.m.s. of every output that has them (`band_rms[…]` statistics, [`super::bands`]):
/// per band the analytic band r.m.s., the expected one of the simulated process, the estimate and its
/// interval, and whether the interval covers the expected value.
pub(crate) fn write_band_tables(f: &mut std::fmt::Formatter<'_>, outputs: &[OutputStatistics]) -> std::fmt::Result {
    for o in outputs {
        let rows: Vec<(&str, &Statistic)> = o
            .statistics
            .iter()
            .filter_map(|s| {
                s.name
                    .strip_prefix("band_rms[")
                    .and_then(|x| x.strip_suffix(']'))
                    .map(|label| (label, s))
            })
            .collect();
        if rows.is_empty() {
            continue;
        }
        writeln!(
            f,
            "bands     {} [{}]: band r.m.s. from the realizations' Welch estimates (IEC 61260-1 base 10)",
            o.output, o.unit
        )?;
        writeln!(
            f,
            "  {:>9} {:>13} {:>13} {:>13} {:>27}  covers expected",
            "band", "analytic", "expected", "MC", "interval"
        )?;
        for (label, s) in rows {
            let e = o.get(&format!("band_rms_expected[{label}]"));
            let iv = &s.interval;
            writeln!(
                f,
                "  {:>9} {:>13.6e} {:>13.6e} {:>13.6e} [{:.6e}, {:.6e}]  {}",
                label,
                s.analytic.unwrap_or(f64::NAN),
                e.and_then(|e| e.analytic).unwrap_or(f64::NAN),
                iv.estimate,
                iv.lower,
                iv.upper,
                covers_word(e.and_then(|e| e.covers))
            )?;
        }
    }
    Ok(())
}

/// `yes`, `NO` or `-` (not compared): whether an interval covers its analytic value, as printed.
pub fn covers_word(covers: Option<bool>) -> &'static str {
    match covers {
        Some(true) => "yes",
        Some(false) => "NO",
        None => "-",
    }
}
