//! The summary of a run file that `stochvib inspect` prints: root attributes, datasets with shapes, chunks
//! and units, the statistics table, the density estimates and the rainflow histograms.

use crate::error::Result;
use crate::store::layout as L;
use crate::store::{
    abbreviated_list, OutputStatistics, PsdEstimate, RainflowHistogram, RunFile, LISTED_FILES, RESOLVED_BIAS,
};
use std::fmt::Write as _;
use std::path::Path;

/// A human-readable summary of a run file (complete or interrupted): root attributes, datasets with
/// shapes, chunks and units, the statistics table and the density estimates.
///
/// # Errors
/// As [`RunFile::open_any`].
///
/// # Examples
/// ```
/// assert!(stochvib::report::summarize("no/such/run.h5").is_err());
/// ```
pub fn summarize(path: impl AsRef<Path>) -> Result<String> {
    let run = RunFile::open_any(path.as_ref())?;
    let mut s = String::new();
    write_header(&mut s, &run);
    write_signals(&mut s, &run);
    write_statistics(&mut s, &run.statistics()?);
    write_psd(&mut s, &run.psd()?);
    for h in run.rainflow()? {
        write_rainflow(&mut s, &h);
    }
    Ok(s)
}

/// The root attributes: status, versions, seed, grid, shards, provenance, storage and the scenario text.
fn write_header(s: &mut String, run: &RunFile) {
    let m = run.metadata();
    let p = run.path();
    let done = run.completed_shards().len();
    let status = if run.is_complete() {
        "complete".to_string()
    } else {
        format!("INCOMPLETE: {done} of {} shards written", m.n_shards())
    };
    let _ = writeln!(s, "run file {} ({status})", p.display());
    let _ = writeln!(s, "  format_version   {}", run.format_version());
    let _ = writeln!(s, "  toolkit_version  {}", run.toolkit_version());
    let _ = writeln!(s, "  seed             {}", m.seed);
    let _ = writeln!(s, "  generator        {}", m.generator);
    let _ = writeln!(s, "  dt               {} s", m.dt);
    let _ = writeln!(
        s,
        "  n_samples        {} (duration {} s)",
        m.n_samples,
        m.n_samples as f64 * m.dt
    );
    let _ = writeln!(s, "  n_realizations   {}", m.n_realizations);
    let _ = writeln!(
        s,
        "  shards           {} of up to {} realizations each ({done} complete)",
        m.n_shards(),
        m.shard_size
    );
    if let Some(part) = m.part {
        let (sh, r) = (m.local_shards(), m.local_realizations());
        let _ = writeln!(
            s,
            "  shard file       {} of {}: internal shards {}..{}, realizations {}..{} (merge the {} files with \
             `stochvib merge`)",
            part.index, part.count, sh.start, sh.end, r.start, r.end, part.count
        );
    }
    if let Some(from) = run.merged_from() {
        let _ = writeln!(
            s,
            "  merged from      {} shard files (raw data {}): {}",
            from.files.len(),
            from.raw.label(),
            abbreviated_list(&from.files, LISTED_FILES)
        );
    }
    let _ = writeln!(
        s,
        "  raw realizations {}",
        if m.store_raw { "stored" } else { "not stored" }
    );
    let _ = writeln!(s, "  compression      {}", m.compression.label());
    let _ = writeln!(s, "  scenario ({} lines):", m.scenario_text.lines().count());
    for line in m.scenario_text.lines() {
        let _ = writeln!(s, "    | {line}");
    }
}

/// Every input and output signal with its dataset's shape and chunks, and the accumulators.
fn write_signals(s: &mut String, run: &RunFile) {
    let m = run.metadata();
    for (group, signals) in [(L::GROUP_INPUTS, &m.inputs), (L::GROUP_OUTPUTS, &m.outputs)] {
        let _ = writeln!(s, "  /{group}: {} signal(s)", signals.len());
        for sig in signals.iter() {
            let shape = if m.store_raw {
                match run.dataset_shape(&format!("{group}/{}", sig.name)) {
                    Ok((shape, chunks)) => format!("f64 {shape:?}, chunks {chunks:?}"),
                    Err(e) => format!("missing dataset ({e})"),
                }
            } else {
                "not stored".to_string()
            };
            let _ = writeln!(s, "    {:<16} [{}]  {shape}", sig.name, sig.unit);
        }
    }
    if !m.accumulators.is_empty() {
        let list: Vec<String> = m.accumulators.iter().map(|(n, l)| format!("{n}[{l}]")).collect();
        let _ = writeln!(s, "  /shards accumulators: {}", list.join(", "));
    }
}

/// The statistics table.
fn write_statistics(s: &mut String, stats: &[OutputStatistics]) {
    if !stats.is_empty() {
        let _ = writeln!(s, "  /statistics");
        let _ = writeln!(
            s,
            "    {:<12} {:<10} {:>14} {:>14} {:>14} {:>6} {:>14} {:>6}  unit",
            "signal", "statistic", "estimate", "lower", "upper", "conf", "analytic", "covers"
        );
        for st in stats {
            for x in &st.statistics {
                let analytic = x.analytic.map_or("-".to_string(), |a| format!("{a:.6e}"));
                let covers = x.covers.map_or("-", |c| if c { "yes" } else { "NO" });
                let _ = writeln!(
                    s,
                    "    {:<12} {:<10} {:>14.6e} {:>14.6e} {:>14.6e} {:>6.3} {:>14} {:>6}  {}",
                    st.output,
                    x.name,
                    x.interval.estimate,
                    x.interval.lower,
                    x.interval.upper,
                    x.interval.confidence,
                    analytic,
                    covers,
                    x.unit
                );
            }
        }
    }
}

/// The density estimates, with the coverage of the expected estimate.
fn write_psd(s: &mut String, psd: &[PsdEstimate]) {
    if !psd.is_empty() {
        let _ = writeln!(
            s,
            "  /psd (two-sided angular S(omega), variance = integral of S d omega)"
        );
        for e in psd {
            let lo = e.omega.first().copied().unwrap_or(f64::NAN);
            let hi = e.omega.last().copied().unwrap_or(f64::NAN);
            let _ = writeln!(
                s,
                "    {:<12} {} points, omega {lo:.4} .. {hi:.4} rad/s, dof {}, confidence {}, [{}]{}; {}",
                e.output,
                e.omega.len(),
                e.dof,
                e.confidence,
                e.unit,
                if e.analytic.is_some() { ", with analytic" } else { "" },
                e.method
            );
            if let Some(c) = e.coverage() {
                let pct = |a: usize, b: usize| 100.0 * a as f64 / b.max(1) as f64;
                let _ = writeln!(
                    s,
                    "    {:<12} the {} % band covers the expected estimate (window ⊛ sampled density) at {} of {} \
                     resolved bins ({:.1} %); {} of {} bins are leakage-, notch- or alias-dominated (expected \
                     estimate more than {} % from the density), covered at {} of them",
                    "",
                    100.0 * e.confidence,
                    c.covered_resolved,
                    c.resolved,
                    pct(c.covered_resolved, c.resolved),
                    c.bins - c.resolved,
                    c.bins,
                    100.0 * RESOLVED_BIAS,
                    c.covered - c.covered_resolved
                );
            }
        }
    }
}

/// One rainflow histogram's line.
fn write_rainflow(s: &mut String, h: &RainflowHistogram) {
    let total: f64 = h.counts.iter().sum();
    let (top, n) = (h.edges.last().copied().unwrap_or(0.0), h.counts.len());
    let _ = writeln!(
        s,
        "  /rainflow/{}  {n} range bins up to {top:.4e} {}; {total:.1} cycles per realization (+{:.2} above){}",
        h.output,
        h.unit,
        h.overflow,
        h.dirlik
            .as_ref()
            .map(|d| format!("; Dirlik expects {:.1}", d.iter().sum::<f64>()))
            .unwrap_or_default()
    );
}
