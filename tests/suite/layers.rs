//! The crate's layers are one-way: no module imports from a layer above its own (the table of `src/lib.rs`).
//!
//! The check reads every `src/**/*.rs` file, strips comments, and collects every `crate::<module>` path in
//! code (`use` lines and inline paths alike); a path to a module of a higher layer fails the test with the
//! file, the line and the two layers.

use std::path::{Path, PathBuf};

/// Bottom up; modules in one row may use each other.
const LAYERS: &[&[&str]] = &[
    &[
        "error",
        "numbers",
        "units",
        "fields",
        "io_rules",
        "quad",
        "quad_oscillatory",
        "linalg",
        "tolerance",
    ],
    &["spectrum", "coherence"],
    &["system"],
    &["response", "comfort", "extremes"],
    &["estimate", "store", "fatigue"],
    &["simulate", "road", "nonlinear", "record", "transient"],
    &["models"],
    &["scenario"],
    &["study", "optimize"],
    &["report", "plot"],
    &["prelude", "lib"],
];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|row| row.contains(&module))
}

pub(crate) fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The line without its `//` comment (string literals containing `//` are rare enough in this crate's
/// `crate::` lines not to matter: a false hit would show up as a failure to look at, never a silent pass).
fn code(line: &str) -> &str {
    match line.find("//") {
        Some(i) => &line[..i],
        None => line,
    }
}

/// Every `crate::<ident>` in `text`.
fn crate_paths(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("crate::") {
        let before = rest[..i].chars().last();
        rest = &rest[i + "crate::".len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue; // e.g. `stochvib_crate::`
        }
        let ident: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        if !ident.is_empty() {
            out.push(ident);
        }
    }
    out
}

/// `use crate::{a, b::c}` groups: every first segment inside the braces.
fn grouped(text: &str) -> Vec<String> {
    let Some(i) = text.find("crate::{") else { return vec![] };
    let body = &text[i + "crate::{".len()..];
    let mut depth = 0;
    let mut seg = String::new();
    let mut out = Vec::new();
    let mut at_start = true;
    for c in body.chars() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => break,
            '}' => depth -= 1,
            ',' if depth == 0 => at_start = true,
            c if at_start && (c.is_alphanumeric() || c == '_') => seg.push(c),
            _ => {
                if at_start && !seg.is_empty() {
                    out.push(std::mem::take(&mut seg));
                    at_start = false;
                }
            }
        }
    }
    if !seg.is_empty() {
        out.push(seg);
    }
    out
}

#[test]
fn no_module_imports_from_a_higher_layer() {
    let src = crate::common::root().join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut violations = Vec::new();
    let mut checked = 0;
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy()
            .into_owned();
        let module = first.trim_end_matches(".rs").to_string();
        if module == "main" {
            continue; // the binary uses the library through `stochvib::`
        }
        let own = layer_of(&module).unwrap_or_else(|| panic!("{}: module `{module}` is in no layer", rel.display()));
        let text = std::fs::read_to_string(f).unwrap();
        // multi-line `use crate::{...}` groups: join the file's code lines first
        let joined: String = text.lines().map(code).collect::<Vec<_>>().join(" ");
        let mut targets: Vec<(usize, String)> = Vec::new();
        for (n, line) in text.lines().enumerate() {
            for t in crate_paths(code(line)) {
                targets.push((n + 1, t));
            }
        }
        for t in grouped(&joined) {
            targets.push((0, t));
        }
        for (line, t) in targets {
            checked += 1;
            let Some(l) = layer_of(&t) else { continue }; // crate-root items such as `crate::Result`
            if l > own {
                violations.push(format!(
                    "{}:{line}: `{module}` (layer {own}) uses `crate::{t}` (layer {l})",
                    rel.display()
                ));
            }
        }
    }
    assert!(
        checked > 100,
        "the scan found only {checked} crate paths: is it reading the sources?"
    );
    assert!(violations.is_empty(), "upward imports:\n{}", violations.join("\n"));
}

/// Modules whose code evaluates a model or a density: frequency responses, output densities, variances,
/// quadrature. `plot/` draws curves that `study::scenario_curves` (and the other layers below) computed, so
/// it uses none of them, though the layer order would allow it.
const EVALUATION: &[&str] = &["response", "system", "quad", "quad_oscillatory", "linalg"];

/// `plot/` only draws: no file of it uses an evaluation module ([`EVALUATION`]), by `use` or inline path.
#[test]
fn plot_uses_no_evaluation_module() {
    let found = uses_of_under("plot", EVALUATION);
    assert!(
        found.is_empty(),
        "plot/ evaluates instead of drawing:\n{}",
        found.join("\n")
    );
}

/// Every use of a module of `modules` by a file under `src/<dir>`, as `file: uses crate::<module>`.
fn uses_of_under(dir: &str, modules: &[&str]) -> Vec<String> {
    paths_used_under(dir)
        .iter()
        .filter(|(_, t)| modules.contains(&t.as_str()))
        .map(|(f, t)| format!("{}: uses `crate::{t}`", f.display()))
        .collect()
}

/// Modules whose code computes what `report/` must not: models and numerics (the [`EVALUATION`] modules but
/// `response`, whose result types — `Outcome`, `VarianceValue` — the analysis text prints), nonlinear routes,
/// non-stationary responses, road profile estimates and coherence models. `report/` formats what `study/`
/// (and the layers below) computed; the plain results of these reach it through `study/`.
const COMPUTATION: &[&str] = &[
    "system",
    "quad",
    "quad_oscillatory",
    "linalg",
    "nonlinear",
    "transient",
    "road",
    "coherence",
];

/// `report/` only formats: no file of it uses a computation module ([`COMPUTATION`]), by `use` or inline
/// path.
#[test]
fn report_uses_no_computation_module() {
    let found = uses_of_under("report", COMPUTATION);
    assert!(
        found.is_empty(),
        "report/ computes instead of formatting:\n{}",
        found.join("\n")
    );
}

/// The items a `crate::models::…` path names on a code line: the braced list after the last `::`, or the
/// one identifier.
fn model_items(line: &str) -> Vec<String> {
    let Some(i) = line.find("crate::models::") else {
        return vec![];
    };
    let rest = &line[i..];
    let tail = match rest.find('{') {
        Some(b) => rest[b + 1..].split('}').next().unwrap_or(""),
        None => rest.rsplit("::").next().unwrap_or(""),
    };
    tail.split(',')
        .map(|t| {
            t.trim()
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect::<String>()
        })
        .filter(|t| !t.is_empty())
        .collect()
}

/// `report/` formats the models' results but never computes them: every item it names under
/// `crate::models` is a type or a constant (capitalised), never a function such as `book_rows` or a model
/// constructor. (The deterministic tables are computed by `study::deterministic_tables`, the book rows by
/// the caller.)
#[test]
fn report_names_only_types_of_the_models() {
    let mut files = Vec::new();
    rust_files(&crate::common::root().join("src/report"), &mut files);
    let mut named = 0;
    let mut found = Vec::new();
    for f in &files {
        for line in std::fs::read_to_string(f).unwrap().lines().map(code) {
            for item in model_items(line) {
                named += 1;
                if !item.starts_with(|c: char| c.is_uppercase()) {
                    found.push(format!("{}: `crate::models::…::{item}`", f.display()));
                }
            }
        }
    }
    assert!(named >= 3, "found only {named} model items in src/report");
    assert!(found.is_empty(), "report/ calls the models:\n{}", found.join("\n"));
    assert_eq!(
        model_items("use crate::models::results::{Cell, ResultTable};"),
        ["Cell", "ResultTable"]
    );
    assert_eq!(
        model_items("rows: crate::models::worked_example::book_rows(),"),
        ["book_rows"]
    );
}

/// What `store/` may use: the base layer's errors, numbers, units, file fields and file rules, and the
/// estimators' [`Interval`](stochvib::estimate::Interval) it stores. Not the numerics (`quad`, `linalg`),
/// not spectra, systems or response statistics: it stores and reads back what the layers above computed.
const STORE_USES: &[&str] = &["error", "numbers", "units", "fields", "io_rules", "estimate", "store"];

/// The crate paths the files under `src/<dir>` use (by `use` or inline path), with the file.
fn paths_used_under(dir: &str) -> Vec<(PathBuf, String)> {
    let mut files = Vec::new();
    rust_files(&crate::common::root().join("src").join(dir), &mut files);
    files.sort();
    assert!(files.len() > 5, "found only {} files in src/{dir}", files.len());
    let mut out = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let joined: String = text.lines().map(code).collect::<Vec<_>>().join(" ");
        let mut used: Vec<String> = text.lines().flat_map(|l| crate_paths(code(l))).collect();
        used.extend(grouped(&joined));
        out.extend(used.into_iter().map(|t| (f.clone(), t)));
    }
    out
}

/// `store/` only stores: every crate module it uses is one of [`STORE_USES`] (crate-root items such as
/// `crate::Result` aside).
#[test]
fn store_uses_only_files_and_intervals() {
    let used = paths_used_under("store");
    assert!(used.len() > 10, "found only {} crate paths in src/store", used.len());
    let found: Vec<String> = used
        .iter()
        .filter(|(_, t)| layer_of(t).is_some() && !STORE_USES.contains(&t.as_str()))
        .map(|(f, t)| format!("{}: uses `crate::{t}`", f.display()))
        .collect();
    assert!(found.is_empty(), "store/ does more than store:\n{}", found.join("\n"));
}

/// The scanner itself: a known upward import is found, comments are ignored.
#[test]
fn scanner_finds_paths_and_skips_comments() {
    assert_eq!(crate_paths("use crate::report::rel_diff;"), ["report"]);
    assert_eq!(
        crate_paths(code("let x = 1; // crate::report::x")),
        Vec::<String>::new()
    );
    assert_eq!(
        grouped("use crate::{report::a, simulate::{b, c}, error};"),
        ["report", "simulate", "error"]
    );
    assert_eq!(layer_of("report"), Some(9));
    assert!(layer_of("simulate") < layer_of("scenario"));
    assert!(layer_of("scenario") < layer_of("study") && layer_of("study") < layer_of("report"));
}

/// The binary target is built without a test harness (`test = false` in Cargo.toml: the suite tests the CLI
/// through the binary), so a unit test in `src/main.rs` or `src/main/` would never run: there must be none.
#[test]
fn the_cli_holds_no_unit_tests() {
    let root = crate::common::root().join("src");
    let mut files = vec![root.join("main.rs")];
    rust_files(&root.join("main"), &mut files);
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let tests = text.lines().filter(|l| code(l).contains("#[test]")).count();
        assert_eq!(
            tests,
            0,
            "{}: #[test] in the CLI, which has no test harness (Cargo.toml)",
            f.display()
        );
    }
}
