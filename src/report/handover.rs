//! `stochvib report SCENARIO.toml -o report.html`: one document an engineer hands over — the provenance
//! (toolkit version, size and CRC-32 of every file read), the scenario file as written, the model with its
//! poles, every output's statistics and variance methods, the verdicts, and the pictures of `stochvib plot`.
//!
//! The document is written once as markdown ([`handover_markdown`]); the HTML form is that markdown through
//! [`super::html::markdown_to_html`] with the pictures inlined as SVG, so both forms hold the same content.
//! The HTML file is self-contained (inline CSS and SVG, no script, no external address); the markdown file
//! links its pictures in a directory `<stem>-pictures` beside it. Both are written under the output rule
//! ([`crate::io_rules::Staged`]).

use super::table::{facts, Table, ToMarkdown};
use crate::error::{Error, Result};
use crate::scenario::{Document, Scenario};
use crate::study::poles::Pole;
use std::path::{Path, PathBuf};

/// The form of the report.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum HandoverFormat {
    /// One self-contained HTML file (inline SVG pictures and CSS).
    #[default]
    Html,
    /// Markdown, the pictures (SVG and PNG) in the directory `<stem>-pictures` beside it.
    Markdown,
}

/// The kind of file `stochvib report` writes, for the output rule: recognised by its first line.
pub const HANDOVER: crate::io_rules::OutputKind = crate::io_rules::OutputKind {
    what: "stochvib report",
    recognizes: is_handover,
    replaceable: false,
};

/// The first line of the markdown form.
const MARKDOWN_MARK: &str = "<!-- stochvib report -->";

fn is_handover(path: &Path) -> bool {
    crate::io_rules::starts_with(path, super::html::PAGE_MARK.as_bytes())
        || crate::io_rules::starts_with(path, MARKDOWN_MARK.as_bytes())
}

/// Writes the report of `doc` (loaded from `file`) to `out` in `format` and returns the path written; with
/// `run = Some((RUN.h5, spectra directory))` the Monte Carlo run's section follows
/// ([`super::run_handover::run_section`]).
///
/// The output is checked before any work: never one of the files the document was read from, a directory,
/// a device or a file of another kind; an existing report only with `overwrite`.
///
/// # Errors
/// The refusals of the output rule ([`crate::io_rules::check_output`]); [`Error::Io`] reading the inputs or
/// writing the report; the errors of the analysis and the pictures.
pub fn write_handover(
    doc: &Document,
    file: &Path,
    out: &Path,
    format: HandoverFormat,
    overwrite: bool,
    run: Option<(&Path, &Path)>,
) -> Result<PathBuf> {
    let sources = source_files(doc, file);
    let mut inputs = sources.clone();
    inputs.extend(run.map(|r| r.0.to_path_buf()));
    write_document(out, format, &inputs, overwrite, &|dir, link| {
        let mut s = handover_markdown(doc, file, &sources, dir, link)?;
        if let Some((run, spectra_dir)) = run {
            let text = crate::fields::read_text_file(file)?;
            s += &super::run_handover::run_section(run, Some(&text), spectra_dir, dir, link)?;
        }
        Ok(s)
    })
}

/// Writes a report whose markdown `build(dir, link)` makes (its pictures drawn into `dir`, linked as
/// `link/<name>.svg`) to `out` in `format`, under the output rule with `inputs` as the files it was read
/// from; returns the path written.
///
/// # Errors
/// The refusals of the output rule; [`Error::Io`] writing; the errors of `build`.
pub(super) fn write_document(
    out: &Path,
    format: HandoverFormat,
    inputs: &[PathBuf],
    overwrite: bool,
    build: &dyn Fn(&Path, &Path) -> Result<String>,
) -> Result<PathBuf> {
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let staged = crate::io_rules::Staged::begin(out, HANDOVER, &inputs, overwrite)?;
    let text = match format {
        HandoverFormat::Html => {
            let dir = TempDir::new()?;
            let md = build(&dir.0, &dir.0)?;
            let title = md
                .lines()
                .find_map(|l| l.strip_prefix("# "))
                .unwrap_or("stochvib report");
            super::html::page(
                title,
                &super::html::markdown_to_html(&md, &|p| inline_svg(Path::new(p))),
            )
        }
        HandoverFormat::Markdown => {
            let name = format!("{}-pictures", out.file_stem().unwrap_or_default().to_string_lossy());
            let dir = crate::io_rules::parent_dir(out).join(&name);
            build(&dir, Path::new(&name))?
        }
    };
    std::fs::write(staged.temporary(), text).map_err(|source| Error::Io {
        path: staged.temporary().to_path_buf(),
        source,
    })?;
    staged.commit()
}

/// The files `doc` was read from: the scenario file first.
fn source_files(doc: &Document, file: &Path) -> Vec<PathBuf> {
    match doc {
        Document::Stochastic(sc) => {
            let mut f = sc.source_files();
            f.retain(|p| p != file);
            f.insert(0, file.to_path_buf());
            f
        }
        _ => vec![file.to_path_buf()],
    }
}

/// The report as markdown: the pictures are drawn into `dir` and linked as `link/<name>.svg`.
///
/// # Errors
/// As [`write_handover`].
pub fn handover_markdown(doc: &Document, file: &Path, sources: &[PathBuf], dir: &Path, link: &Path) -> Result<String> {
    let text = crate::fields::read_text_file(file)?;
    let mut s = format!("{}# {}\n\n", mark(), title(doc));
    s += &format!("## Provenance\n\n{}\n", provenance(sources)?);
    let f = fence_for(&text);
    s += &format!(
        "## Scenario file `{}`\n\n{f}toml\n{}\n{f}\n\n",
        file.display(),
        text.trim_end()
    );
    match doc {
        Document::Stochastic(sc) => s += &stochastic_sections(sc, dir, link)?,
        Document::Deterministic(d) => {
            let tables = crate::study::deterministic_tables(d)?;
            s += &results_section(&super::deterministic_report(d, tables).markdown());
        }
        Document::Reference(t) => s += &results_section(&super::reference_report(t).markdown()),
    }
    Ok(s)
}

/// The first line of the markdown form, and the blank line after it.
pub(super) fn mark() -> String {
    format!("{MARKDOWN_MARK}\n\n")
}

fn title(doc: &Document) -> &str {
    match doc {
        Document::Stochastic(sc) => &sc.title,
        Document::Deterministic(d) => &d.title,
        Document::Reference(t) => &t.title,
    }
}

/// A fence longer than every run of backticks in `text` (at least three).
pub(super) fn fence_for(text: &str) -> String {
    let longest = text.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    "`".repeat(longest.max(2) + 1)
}

/// A report's markdown as one section: its own title dropped, its headings one level down.
pub(super) fn results_section(md: &str) -> String {
    let body: Vec<String> = md
        .lines()
        .skip_while(|l| l.trim().is_empty())
        .skip_while(|l| l.starts_with("# "))
        .map(|l| {
            if l.starts_with('#') {
                format!("#{l}")
            } else {
                l.to_string()
            }
        })
        .collect();
    format!("## Results\n\n{}\n", body.join("\n"))
}

/// The toolkit version, and the size and CRC-32 of every file read.
pub(super) fn provenance(sources: &[PathBuf]) -> Result<String> {
    let mut rows = (Vec::new(), Vec::new(), Vec::new());
    for p in sources {
        let (bytes, crc) = match checksum(p) {
            Ok((n, c)) => (n.to_string(), format!("{c:08x}")),
            Err(_) => ("—".into(), "— (built-in catalogue, not on disk)".into()),
        };
        rows.0.push(format!("`{}`", p.display()));
        rows.1.push(bytes);
        rows.2.push(crc);
    }
    let tool = facts(&[("toolkit", format!("stochvib {}", env!("CARGO_PKG_VERSION")))]);
    let t = Table::default()
        .text("file read", rows.0)
        .raw("size [bytes]", rows.1)
        .text("CRC-32 (ISO-HDLC)", rows.2);
    Ok(format!("{tool}\n{}", t.markdown()))
}

/// Size and CRC-32/ISO-HDLC of a file, read in pieces.
pub(super) fn checksum(path: &Path) -> std::io::Result<(u64, u32)> {
    use std::io::Read;
    let mut f = std::fs::File::open(path)?;
    let (mut h, mut n, mut buf) = (crc32fast::Hasher::new(), 0u64, vec![0u8; 1 << 16]);
    loop {
        let k = f.read(&mut buf)?;
        if k == 0 {
            return Ok((n, h.finalize()));
        }
        h.update(&buf[..k]);
        n += k as u64;
    }
}

/// Model and poles, outputs, verdicts, the transient answers and mission extremes (`[transient]`) and
/// pictures of a scenario with a random input; the three routes of a model with nonlinear elements.
fn stochastic_sections(sc: &Scenario, dir: &Path, link: &Path) -> Result<String> {
    if let Some(answers) = sc.nonlinear_answers()? {
        return nonlinear_sections(sc, &answers, dir, link);
    }
    let mut r = crate::study::analysis_report(sc)?;
    let verdicts = r.verdicts.take();
    let outputs = std::mem::take(&mut r.outputs);
    let head = results_section(&r.markdown()).replacen("## Results", "## Model and input", 1);
    let mut s = format!("{head}\n{}", poles_markdown(sc));
    s += "\n## Outputs\n";
    for o in &outputs {
        s += &super::markdown::output_markdown(&r, o).replace("\n## ", "\n### ");
    }
    if let Some(v) = verdicts {
        s += &format!("\n## Verdicts\n{}", v.markdown().replace("\n## ", "\n### "));
    }
    let mut pictures = crate::plot::scenario_plots(sc, dir)?;
    if sc.transient.is_some() {
        let a = crate::study::transient_answers::transient_analysis(sc)?;
        s += &format!("\n{}", super::transient_report::transient_markdown(&a));
        pictures.extend(crate::plot::transient_plots::exact_plots(&a, dir)?);
    }
    s += &pictures_markdown(&pictures, link);
    Ok(s)
}

/// The three routes of a model with nonlinear elements (`stochvib analyze FILE --format markdown`), and the
/// input density (the linear-model pictures of `stochvib plot` do not describe its response).
fn nonlinear_sections(
    sc: &Scenario,
    answers: &crate::study::NonlinearAnswers,
    dir: &Path,
    link: &Path,
) -> Result<String> {
    let md = crate::study::nonlinear_report(sc, answers, None)?.markdown();
    let body: Vec<&str> = md.lines().skip_while(|l| l.starts_with("## ")).collect();
    let mut s = format!("## Nonlinear response: three routes\n{}\n", body.join("\n"));
    let opts = crate::plot::ScenarioPlotOptions::default();
    let pictures = crate::plot::scenario_plots::input_density_chart(sc, &opts)?.render(dir, "input-density")?;
    s += &pictures_markdown(&pictures, link);
    Ok(s)
}

/// The section of the pictures `files` (their SVG forms), linked as `link/<name>.svg`.
pub(super) fn pictures_markdown(files: &[PathBuf], link: &Path) -> String {
    let mut s = "\n## Pictures\n\n".to_string();
    for f in files {
        if f.extension().is_some_and(|e| e == "svg") {
            let name = f.file_name().unwrap_or_default();
            let stem = f.file_stem().unwrap_or_default().to_string_lossy();
            s += &format!("![{stem}]({})\n\n", link.join(name).display());
        }
    }
    s
}

/// The pole table of the model ([`crate::study::poles::model_poles`]): natural frequency ω_n and damping
/// ratio ζ of each pole with Im λ ≥ 0 (one of each complex pair), by increasing ω_n.
fn poles_markdown(sc: &Scenario) -> String {
    let Some(poles) = crate::study::poles::model_poles(sc) else {
        return "The model has no finite state space: no pole table.\n".into();
    };
    let col = |f: &dyn Fn(&Pole) -> f64| poles.iter().map(|p| Some(f(p))).collect::<Vec<_>>();
    let t = Table::default()
        .raw("pole", 1..=poles.len())
        .num("ω_n [rad/s]", &col(&|p| p.natural_frequency_rad_s))
        .num(
            "f_n [Hz]",
            &col(&|p| p.natural_frequency_rad_s / (2.0 * std::f64::consts::PI)),
        )
        .num("damping ratio ζ", &col(&|p| p.damping_ratio));
    format!(
        "\nPoles of the state space (one of each complex pair; ζ ≥ 1 for a real pole; poles at 0 left out):\n\n{}",
        t.markdown()
    )
}

/// The SVG of a picture file for inlining in HTML: from `<svg`, without the XML namespace attribute (HTML
/// puts `<svg>` in it; the report holds no address).
fn inline_svg(path: &Path) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    let start = text.find("<svg")?;
    Some(
        text[start..]
            .trim_end()
            .replacen(" xmlns=\"http://www.w3.org/2000/svg\"", "", 1),
    )
}

/// A directory of this process's own under the system's temporary directory, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new() -> Result<TempDir> {
        static COUNT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let n = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("stochvib-report-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir).map_err(|source| Error::Io {
            path: dir.clone(),
            source,
        })?;
        Ok(TempDir(dir))
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
