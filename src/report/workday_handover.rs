//! `stochvib report WORKDAY.toml -o report.html`: the hand-over report of a working day (a workday file of
//! `[[task]]` tables, `stochvib workday`): the provenance (the workday file, every task's scenario file and
//! the files those read), the workday file as written, the tables and verdict of `stochvib workday`, and
//! the day's A(8) per axis as a picture. Written as [`super::handover::write_handover`] writes a scenario's.

use super::handover::{
    fence_for, mark, pictures_markdown, provenance, results_section, write_document, HandoverFormat,
};
use super::table::ToMarkdown;
use super::WorkdayReport;
use crate::error::Result;
use crate::scenario::workday_file::load_workday;
use crate::study::workday::workday_exposure;
use std::path::{Path, PathBuf};

/// Whether `path` is a workday file: a TOML table with `[[task]]` tables and no `[model]`.
pub fn is_workday_file(path: &Path) -> bool {
    let Ok(text) = crate::fields::read_text_file(path) else {
        return false;
    };
    toml::from_str::<toml::Table>(&text)
        .is_ok_and(|t| t.get("task").is_some_and(toml::Value::is_array) && !t.contains_key("model"))
}

/// Writes the report of the workday file `file` to `out` in `format` and returns the path written.
///
/// # Errors
/// The refusals of the output rule; the errors of [`load_workday`] and [`workday_exposure`] (a task's
/// scenario that cannot be read or has no comfort axis); [`crate::Error::Io`] writing.
pub fn write_workday_handover(
    file: &Path,
    out: &Path,
    format: HandoverFormat,
    overwrite: bool,
    spectra_dir: &Path,
) -> Result<PathBuf> {
    let day = load_workday(file)?;
    let exposure = workday_exposure(&day, spectra_dir)?;
    let mut sources = vec![file.to_path_buf()];
    for t in &day.tasks {
        let sc = crate::scenario::load_scenario(&t.scenario_path, spectra_dir)?;
        for p in std::iter::once(t.scenario_path.clone()).chain(sc.source_files()) {
            if !sources.contains(&p) {
                sources.push(p);
            }
        }
    }
    let text = crate::fields::read_text_file(file)?;
    let f = fence_for(&text);
    let mut head = format!("{}# {}\n\n", mark(), day.title);
    head += &format!("## Provenance\n\n{}\n", provenance(&sources)?);
    head += &format!(
        "## Workday file `{}`\n\n{f}toml\n{}\n{f}\n\n",
        file.display(),
        text.trim_end()
    );
    head +=
        &results_section(&WorkdayReport(exposure.clone()).markdown()).replacen("## Results", "## Daily exposure", 1);
    write_document(out, format, &sources, overwrite, &|dir, link| {
        let files = crate::plot::comfort_plots::workday_chart(&exposure)?.render(dir, "workday-a8")?;
        Ok(format!("{head}{}", pictures_markdown(&files, link)))
    })
}
