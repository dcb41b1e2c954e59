//! The Monte Carlo part of the hand-over report: `stochvib report RUN.h5 -o report.html` (the run alone)
//! and `stochvib report SCENARIO.toml --run RUN.h5 -o report.html` (the scenario's report followed by the
//! run's section).
//!
//! The run's section holds the run's identity and provenance (seed, generator, Δt, samples, realizations,
//! the writer's toolkit and format version, the stored metadata digest, the number of stored checksums
//! verified), every statistic's estimate with its confidence interval, the analytic value and whether the
//! interval covers it, the coverage count, the density estimates and rainflow histograms (the tables of
//! `stochvib inspect --format markdown`), and the pictures of `stochvib plot RUN.h5`.

use super::handover::{
    fence_for, mark, pictures_markdown, provenance, results_section, write_document, HandoverFormat,
};
use super::table::facts;
use crate::error::Result;
use crate::store::RunFile;
use std::path::{Path, PathBuf};

/// Writes the report of the run file `run` alone to `out` (see the module docs); `spectra_dir` is the
/// catalogue directory the run's analytic curves are drawn with.
///
/// # Errors
/// As [`super::handover::write_handover`]; [`crate::Error::Hdf5`] for a run file that cannot be read or whose
/// checksums do not match.
pub fn write_run_handover(
    run: &Path,
    out: &Path,
    format: HandoverFormat,
    overwrite: bool,
    spectra_dir: &Path,
) -> Result<PathBuf> {
    let inputs = [run.to_path_buf()];
    write_document(out, format, &inputs, overwrite, &|dir, link| {
        run_handover_markdown(run, spectra_dir, dir, link)
    })
}

/// The report of a run file alone as markdown: title, provenance, the scenario text stored in the run, the
/// run's section.
///
/// # Errors
/// As [`write_run_handover`].
pub fn run_handover_markdown(run: &Path, spectra_dir: &Path, dir: &Path, link: &Path) -> Result<String> {
    let file = RunFile::open_any(run)?;
    let text = file.metadata().scenario_text.clone();
    let title = toml::from_str::<toml::Table>(&text)
        .ok()
        .and_then(|t| t.get("title").and_then(|v| v.as_str()).map(str::to_string))
        .unwrap_or_else(|| "untitled scenario".into());
    let f = fence_for(&text);
    let mut s = format!("{}# Monte Carlo run: {title}\n\n", mark());
    s += &format!("## Provenance\n\n{}\n", provenance(&[run.to_path_buf()])?);
    s += &format!("## Scenario stored in the run\n\n{f}toml\n{}\n{f}\n\n", text.trim_end());
    drop(file);
    s += &run_section(run, None, spectra_dir, dir, link)?;
    Ok(s)
}

/// The run's section (see the module docs); `scenario_text`, when the report is of a scenario file, is that
/// file's text, compared with the text the run stores.
///
/// # Errors
/// As [`write_run_handover`].
pub fn run_section(
    run: &Path,
    scenario_text: Option<&str>,
    spectra_dir: &Path,
    dir: &Path,
    link: &Path,
) -> Result<String> {
    let file = RunFile::open_any(run)?;
    let checked = file.verify()?;
    let m = file.metadata();
    let mut identity = vec![
        ("run file", format!("`{}`", run.display())),
        (
            "written by",
            format!(
                "stochvib {} (run file format {})",
                file.toolkit_version(),
                file.format_version()
            ),
        ),
        (
            "metadata digest (CRC-32 of the canonical metadata)",
            format!("{:08x}", m.digest()),
        ),
        (
            "stored checksums verified",
            format!("{} of {}, all match", checked.checked, checked.checked),
        ),
    ];
    if let Some(t) = scenario_text {
        let same = t.trim_end() == m.scenario_text.trim_end();
        let verdict = if same {
            "yes: the run stores this scenario file's text"
        } else {
            "NO: the run stores a different scenario text (see `stochvib inspect RUN.h5`)"
        };
        identity.push(("made from this scenario", verdict.into()));
    }
    identity.push(("coverage", coverage(&file)?));
    drop(file);
    let tables = results_section(&super::inspect_markdown(run)?).replacen("## Results", "", 1);
    let pictures = pictures_markdown(&crate::plot::run_plots(run, dir, spectra_dir)?, link).replacen(
        "## Pictures",
        "## Pictures of the run",
        1,
    );
    Ok(format!("## Monte Carlo run\n\n{}{tables}{pictures}", facts(&identity)))
}

/// "k of n intervals cover the analytic value (confidence c)" over every statistic that has an analytic
/// value.
fn coverage(file: &RunFile) -> Result<String> {
    let stats = file.statistics()?;
    let judged: Vec<&crate::store::Statistic> = stats
        .iter()
        .flat_map(|o| o.statistics.iter())
        .filter(|x| x.covers.is_some())
        .collect();
    if judged.is_empty() {
        return Ok("no statistic has an analytic value to cover".into());
    }
    let covered = judged.iter().filter(|x| x.covers == Some(true)).count();
    let confidence: Vec<String> = {
        let mut c: Vec<String> = judged
            .iter()
            .map(|x| crate::numbers::num(100.0 * x.interval.confidence))
            .collect();
        c.dedup();
        c
    };
    Ok(format!(
        "{covered} of {} confidence intervals ({} %) cover the analytic value",
        judged.len(),
        confidence.join(", ")
    ))
}
