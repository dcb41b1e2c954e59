//! The HTML report in a real browser (headless Chromium, the Debian package `chromium-headless-shell`) and
//! through an HTML validator (html5lib, the WHATWG parsing algorithm; `tests/browser/validate_html.py`).
//!
//! For each report: the page is opened and screenshot, printed to PDF and its first page rasterised with
//! `pdftoppm` (poppler-utils); both pictures must show something (not blank: more than 500 dark text pixels
//! and more than 0.2 % non-white pixels — a printed first page holds only the title and the provenance
//! tables, 0.7–0.9 % of its pixels at 60 dpi); the browser's console must stay silent (the report has no script, so
//! any console line is an error: a blocked or failed resource, a parse complaint); a copy of the page with a
//! probe script appended reports, after the load event, every `<img>` that did not load and every figure
//! whose inline SVG has no size or no drawing in it (expected: none of either, one SVG per figure); the
//! printed PDF has at least one page per section (the print style sheet starts each section on a new page).
//! The probe is checked against a page with a missing picture, which it must report.
//!
//! The tools are required: without them the test fails and says how to install them
//! (`bash scripts/ensure-deps.sh --with-browser`). A developer without them may set
//! `STOCHVIB_SKIP_BROWSER=1`: the test then passes with a warning on stderr that it did not run (CI never
//! sets it).

use crate::common::{cli_within, root};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const LIMIT: Duration = Duration::from_secs(600);
/// A browser run on a busy machine takes 0.3–5 s; a run still going after this has hung.
const BROWSER_LIMIT: Duration = Duration::from_secs(180);
const SKIP: &str = "STOCHVIB_SKIP_BROWSER";

fn tmp(name: &str) -> PathBuf {
    crate::common::scratch_dir("report-browser", name)
}

/// Whether the browser tests run: the tools are present, or the developer opted out (then `false`, with a
/// warning). Missing tools without the opt-out fail the test with the way to install them.
pub(crate) fn tools_present() -> bool {
    if std::env::var(SKIP).as_deref() == Ok("1") {
        eprintln!("WARNING: the browser test of the HTML report did NOT run: {SKIP}=1");
        return false;
    }
    let found = |tool: &str, arg: &str| {
        Command::new(tool)
            .arg(arg)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    let missing: Vec<&str> = [
        ("chromium-headless-shell", "--version", "chromium-headless-shell"),
        ("pdftoppm", "-v", "poppler-utils"),
        ("pdfinfo", "-v", "poppler-utils"),
    ]
    .into_iter()
    .filter(|(tool, arg, _)| !found(tool, arg))
    .map(|t| t.2)
    .collect();
    let html5lib = Command::new("python3")
        .args(["-c", "import html5lib"])
        .status()
        .is_ok_and(|s| s.success());
    assert!(
        missing.is_empty() && html5lib,
        "the browser test of the HTML report needs the Debian packages chromium-headless-shell and poppler-utils \
         and python3 with html5lib (missing: {missing:?}, html5lib present: {html5lib}); \
         `bash scripts/ensure-deps.sh --with-browser` installs them; a developer may set {SKIP}=1 to skip this test"
    );
    true
}

/// Runs `program args` with output to files in `dir`; fails the test on a hang. (status ok, stdout, stderr)
fn run(program: &str, args: &[String], dir: &Path) -> (bool, String, String) {
    let (out, err) = (dir.join("run.out"), dir.join("run.err"));
    let mut child = Command::new(program)
        .args(args)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out).unwrap())
        .stderr(std::fs::File::create(&err).unwrap())
        .spawn()
        .unwrap_or_else(|e| panic!("{program}: {e}"));
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > BROWSER_LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            panic!("`{program} {}` hung", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let read = |p: &Path| String::from_utf8_lossy(&std::fs::read(p).unwrap()).into_owned();
    (status.success(), read(&out), read(&err))
}

/// Headless Chromium on `page` with `extra` arguments; returns (stdout, stderr).
fn chromium(page: &Path, extra: &[String], dir: &Path) -> (String, String) {
    let profile = dir.join("profile");
    let mut args: Vec<String> = [
        "--no-sandbox",
        "--disable-gpu",
        "--enable-logging=stderr",
        "--v=0",
        "--hide-scrollbars",
        "--window-size=1000,1300",
    ]
    .map(String::from)
    .into();
    args.push(format!("--user-data-dir={}", profile.display()));
    args.extend(extra.iter().cloned());
    args.push(format!("file://{}", page.canonicalize().unwrap().display()));
    let (ok, out, err) = run("chromium-headless-shell", &args, dir);
    assert!(ok, "chromium-headless-shell failed on {}:\n{err}", page.display());
    (out, err)
}

/// The browser's console lines in its log.
fn console(stderr: &str) -> Vec<&str> {
    stderr.lines().filter(|l| l.contains(":CONSOLE")).collect()
}

/// Fraction of non-white pixels and number of dark pixels (all channels < 100) of a PNG.
fn ink(path: &Path) -> (f64, usize) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks(channels).collect();
    let rgb = |p: &[u8]| if channels >= 3 { [p[0], p[1], p[2]] } else { [p[0]; 3] };
    let non_white = px.iter().filter(|p| rgb(p).iter().any(|c| *c < 245)).count();
    let dark = px.iter().filter(|p| rgb(p).iter().all(|c| *c < 100)).count();
    (non_white as f64 / px.len() as f64, dark)
}

fn assert_not_blank(png: &Path) {
    let (fraction, dark) = ink(png);
    assert!(
        fraction > 0.002 && dark > 500,
        "{} looks blank: {:.4} of the pixels are not white, {dark} are dark",
        png.display(),
        fraction
    );
}

/// The probe appended to a copy of the page: after the load event it logs the number of figures, of inline
/// SVGs in figures, of `<img>` elements, of images that did not load and of figures without a drawn SVG.
const PROBE: &str = "<script>window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  var broken = imgs.filter(function (i) { return !(i.complete && i.naturalWidth > 0); }).length;
  var figs = Array.prototype.slice.call(document.querySelectorAll('figure'));
  var svgs = document.querySelectorAll('figure svg').length;
  var empty = figs.filter(function (f) {
    var s = f.querySelector('svg'); if (!s) { return false; }
    var r = s.getBoundingClientRect();
    return !(r.width > 100 && r.height > 50 && s.querySelectorAll('polyline, polygon, path, rect').length > 0);
  }).length;
  console.log('PROBE figures=' + figs.length + ' svgs=' + svgs + ' imgs=' + imgs.length + ' broken=' + broken +
    ' empty=' + empty);
});</script>";

/// The probe's counts on `page`: (figures, svgs, imgs, broken, empty).
fn probe(page: &Path, dir: &Path) -> [usize; 5] {
    let html = std::fs::read_to_string(page).unwrap();
    let probed = dir.join("probed.html");
    std::fs::write(&probed, html.replace("</body>", &format!("{PROBE}</body>"))).unwrap();
    let (_, err) = chromium(
        &probed,
        &["--dump-dom".into(), "--virtual-time-budget=10000".into()],
        dir,
    );
    let line = console(&err)
        .into_iter()
        .find_map(|l| l.split("PROBE ").nth(1))
        .unwrap_or_else(|| panic!("the probe did not report on {}:\n{err}", page.display()))
        .to_string();
    let value = |key: &str| -> usize {
        line.split_whitespace()
            .find_map(|kv| kv.strip_prefix(&format!("{key}=")))
            .and_then(|v| v.trim_end_matches([',', '"']).parse().ok())
            .unwrap_or_else(|| panic!("no {key} in {line}"))
    };
    ["figures", "svgs", "imgs", "broken", "empty"].map(value)
}

/// Runs html5lib over `page`; the test fails with every parse error it names.
pub(crate) fn validate(page: &Path) {
    let script = root().join("tests/browser/validate_html.py");
    let args = vec![script.display().to_string(), page.display().to_string()];
    let dir = page.parent().unwrap();
    let (ok, out, err) = run("python3", &args, dir);
    assert!(ok, "{} is not valid HTML:\n{out}{err}", page.display());
}

/// Opens, screenshots, prints and validates the HTML report `page` (with `sections` `<h2>` sections).
fn check_in_browser(page: &Path, dir: &Path) {
    validate(page);
    let html = std::fs::read_to_string(page).unwrap();
    let sections = html.matches("<h2").count();
    let shot = dir.join("screen.png");
    let (_, err) = chromium(page, &[format!("--screenshot={}", shot.display())], dir);
    assert!(
        console(&err).is_empty(),
        "console output on {}: {:?}",
        page.display(),
        console(&err)
    );
    assert_not_blank(&shot);
    let pdf = dir.join("printed.pdf");
    let (_, err) = chromium(
        page,
        &[
            format!("--print-to-pdf={}", pdf.display()),
            "--no-pdf-header-footer".into(),
        ],
        dir,
    );
    assert!(
        console(&err).is_empty(),
        "console output printing {}: {:?}",
        page.display(),
        console(&err)
    );
    let first = dir.join("printed-page-1");
    let args: Vec<String> = ["-f", "1", "-l", "1", "-singlefile", "-png", "-r", "60"]
        .map(String::from)
        .into_iter()
        .chain([pdf.display().to_string(), first.display().to_string()])
        .collect();
    let (ok, _, err) = run("pdftoppm", &args, dir);
    assert!(ok, "pdftoppm: {err}");
    assert_not_blank(&first.with_extension("png"));
    let (ok, info, _) = run("pdfinfo", &[pdf.display().to_string()], dir);
    assert!(ok);
    let pages: usize = info
        .lines()
        .find_map(|l| l.strip_prefix("Pages:"))
        .and_then(|v| v.trim().parse().ok())
        .unwrap();
    assert!(pages >= sections, "{pages} printed pages for {sections} sections");
    let [figures, svgs, imgs, broken, empty] = probe(page, dir);
    assert!(figures > 0, "no figure in {}", page.display());
    assert_eq!((svgs, imgs, broken, empty), (figures, 0, 0, 0), "{}", page.display());
}

/// Writes the report of `scenario` into `dir` and returns its path.
fn report(scenario: &str, dir: &Path) -> PathBuf {
    let out = dir.join("report.html");
    let o = cli_within(&["report", scenario, "-o", out.to_str().unwrap()], &root(), LIMIT);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

#[test]
fn the_probe_reports_a_missing_picture_and_an_empty_figure() {
    if !tools_present() {
        return;
    }
    let dir = tmp("probe");
    let page = dir.join("broken.html");
    std::fs::write(
        &page,
        "<!DOCTYPE html><html><head><title>t</title></head><body><figure><img src=\"missing.png\" alt=\"m\" />\
         </figure><figure><svg width=\"10\" height=\"10\"></svg></figure></body></html>",
    )
    .unwrap();
    assert_eq!(probe(&page, &dir), [2, 1, 1, 1, 1]);
}

#[test]
fn scenario_reports_render_print_and_validate() {
    if !tools_present() {
        return;
    }
    let scenarios = [
        "data/quarter-car.toml",
        "data/operator-seat-verdicts.toml",
        "data/quarter-car-accelerating.toml",
        "data/duffing-white-noise.toml",
        "data/workday/scraper-operator.toml",
    ];
    for (k, scenario) in scenarios.iter().enumerate() {
        let dir = tmp(&format!("scenario-{k}"));
        check_in_browser(&report(scenario, &dir), &dir);
    }
}

/// A small stored run of the conveyor idler (8 realizations of 5 s, seed 7) in `dir`.
fn idler_run(dir: &Path) -> PathBuf {
    let run = dir.join("idler.h5");
    let args = [
        "simulate",
        "data/conveyor-idler.toml",
        "--realizations",
        "8",
        "--duration",
        "5",
        "--dt",
        "0.01",
        "--seed",
        "7",
        "--store-raw",
        "-o",
        run.to_str().unwrap(),
    ];
    let o = cli_within(&args, &root(), LIMIT);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    run
}

/// The report of a run file holds the seed, the file's CRC-32 and size (computed here with crc32fast from
/// the bytes on disk), the verified checksums, every row of the statistics table of `stochvib inspect
/// --format markdown` (estimate, interval, analytic value, covers) and the coverage count recomputed from
/// the `covers` fields of `inspect --json`; with
/// `--run`, the scenario's report gains the run's section and says the run stores this scenario's text.
/// Then the browser checks of the run's report.
#[test]
fn run_file_reports_hold_the_run() {
    let dir = tmp("run");
    let run = idler_run(&dir);
    let out = dir.join("run.html");
    let o = cli_within(
        &["report", run.to_str().unwrap(), "-o", out.to_str().unwrap()],
        &root(),
        LIMIT,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let html = std::fs::read_to_string(&out).unwrap();
    let bytes = std::fs::read(&run).unwrap();
    for needle in [
        format!("{:08x}", crc32fast::hash(&bytes)),
        format!(">{}</td>", bytes.len()),
        "<td>seed</td><td>7</td>".into(),
        "stored checksums verified".into(),
        "Conveyor idler".into(),
        "y-welch".into(),
    ] {
        assert!(html.contains(&needle), "run report lacks {needle}");
    }
    let o = cli_within(&["inspect", run.to_str().unwrap(), "--json"], &root(), LIMIT);
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let stats: Vec<&serde_json::Value> = json["statistics"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|o| o["statistics"].as_array().unwrap())
        .collect();
    assert!(!stats.is_empty());
    let judged = stats.iter().filter(|s| s["covers"].is_boolean()).count();
    let covered = stats
        .iter()
        .filter(|s| s["covers"] == serde_json::Value::Bool(true))
        .count();
    assert!(
        html.contains(&format!("{covered} of {judged} confidence intervals")),
        "coverage {covered}/{judged} not in the report"
    );
    // the statistics table of `inspect --format markdown`, row by row, in the markdown form of the report
    let md = dir.join("run.md");
    let o = cli_within(
        &[
            "report",
            run.to_str().unwrap(),
            "-o",
            md.to_str().unwrap(),
            "--format",
            "markdown",
        ],
        &root(),
        LIMIT,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report_md = std::fs::read_to_string(&md).unwrap();
    let o = cli_within(
        &["inspect", run.to_str().unwrap(), "--format", "markdown"],
        &root(),
        LIMIT,
    );
    let inspect = String::from_utf8(o.stdout).unwrap();
    let rows: Vec<&str> = inspect.lines().filter(|l| l.starts_with("| y")).collect();
    assert!(rows.len() >= 4, "{inspect}");
    for r in rows {
        assert!(report_md.contains(r), "the report lacks the row {r}");
    }
    if tools_present() {
        check_in_browser(&out, &dir);
    }

    // the scenario with its run
    let both = dir.join("both.html");
    let args = [
        "report",
        "data/conveyor-idler.toml",
        "--run",
        run.to_str().unwrap(),
        "-o",
        both.to_str().unwrap(),
    ];
    let o = cli_within(&args, &root(), LIMIT);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let html = std::fs::read_to_string(&both).unwrap();
    assert!(html.contains("yes: the run stores this scenario file"));
    assert!(html.contains("Monte Carlo run") && html.contains("output-density-y") && html.contains("y-welch"));
    // the run of another scenario is named as such
    let other = dir.join("other.html");
    let args = [
        "report",
        "data/quarter-car.toml",
        "--run",
        run.to_str().unwrap(),
        "-o",
        other.to_str().unwrap(),
    ];
    let o = cli_within(&args, &root(), LIMIT);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(std::fs::read_to_string(&other)
        .unwrap()
        .contains("NO: the run stores a different scenario text"));
}
