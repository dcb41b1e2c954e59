//! `stochvib report SCENARIO -o report.html|md`: the report of every scenario of `data/` that `analyze`
//! accepts is written (with the three routes of a nonlinear model, the transient answers and mission
//! extremes of a scenario with `[transient]`; the working day of `data/workday/`), is well-formed (every
//! element closed, every `&` an entity: [`well_formed`]), is
//! self-contained (no address, no `src=`/`href=`, no script), and holds what it claims to hold.
//!
//! Provenance of the expected values: σ of each output from `stochvib analyze --json` (a separate command
//! and the full-precision JSON path; the report prints four significant figures, so they agree within
//! `PRINTED_4_DIGITS`); the pictures from the file names `stochvib plot` writes; the CRC-32 and size of the
//! scenario file computed here with `crc32fast` from the bytes on disk; the single isolator's pole from the
//! closed form ω₀ = √(k/m), ζ as written in its file; the scenario text escaped by this file's own
//! replacements; the transient mission table from `stochvib transient --json`, the nonlinear routes from
//! `analyze --json`, the day's A(8) from `stochvib workday --json` (separate commands, full precision).

use crate::common::tolerance::PRINTED_4_DIGITS;
use crate::common::{cli_within, rel, root};
use std::path::{Path, PathBuf};
use std::time::Duration;

const LIMIT: Duration = Duration::from_secs(600);

fn tmp(name: &str) -> PathBuf {
    crate::common::scratch_dir("html-report", name)
}

/// Runs the tool from the source tree; (success, stdout, stderr).
fn cli(args: &[&str]) -> (bool, String, String) {
    let o = cli_within(args, &root(), LIMIT);
    let text = |b: Vec<u8>| String::from_utf8(b).unwrap();
    (o.status.success(), text(o.stdout), text(o.stderr))
}

/// Tags that need no end tag in HTML; the report writes them `<x ... />` anyway.
const VOID: &[&str] = &["meta", "br", "img", "hr", "link", "input"];

/// Checks that every element of `html` is closed in order, every `<` begins a tag, a comment or the
/// doctype, and every `&` begins an entity; the error names the first fault and its byte offset.
fn well_formed(html: &str) -> Result<(), String> {
    let mut stack: Vec<String> = Vec::new();
    let mut i = 0;
    while let Some(k) = html[i..].find(['<', '&']) {
        let at = i + k;
        let rest = &html[at..];
        if let Some(after) = rest.strip_prefix('&') {
            let ent = after.split(';').next().unwrap_or("");
            let ok = ent.len() < 10
                && !ent.is_empty()
                && (ent.chars().all(|c| c.is_ascii_alphabetic())
                    || ent
                        .strip_prefix('#')
                        .is_some_and(|d| d.chars().all(|c| c.is_ascii_digit())));
            if !ok || !after.contains(';') {
                return Err(format!("bare & at {at}: {}", &rest[..rest.len().min(30)]));
            }
            i = at + 1;
            continue;
        }
        if let Some(r) = rest.strip_prefix("<!--") {
            i = at + 4 + r.find("-->").ok_or(format!("unclosed comment at {at}"))? + 3;
            continue;
        }
        let end = at + rest.find('>').ok_or(format!("unclosed tag at {at}"))?;
        let tag = &html[at + 1..end];
        i = end + 1;
        if tag.starts_with("!DOCTYPE") {
            continue;
        }
        let name: String = tag
            .trim_start_matches('/')
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
            .collect();
        if name.is_empty() || tag.contains('<') {
            return Err(format!("`<` that begins no tag at {at}"));
        }
        if tag.starts_with('/') {
            match stack.pop() {
                Some(open) if open == name => {}
                other => return Err(format!("</{name}> at {at} closes {other:?}")),
            }
        } else if !tag.ends_with('/') {
            if VOID.contains(&name.as_str()) {
                return Err(format!("<{name}> at {at} not written as <{name} ... />"));
            }
            stack.push(name);
        }
    }
    match stack.last() {
        None => Ok(()),
        Some(open) => Err(format!("<{open}> never closed")),
    }
}

#[test]
fn the_checker_finds_faults() {
    assert!(well_formed("<!DOCTYPE html>\n<html><p>a &amp; b<br /></p><!-- <x> --></html>").is_ok());
    for bad in [
        "<p><b></p></b>",
        "<p>",
        "<p>a & b</p>",
        "<p>1 < 2</p>",
        "<meta charset=\"utf-8\">",
        "</p>",
    ] {
        assert!(well_formed(bad).is_err(), "{bad}");
    }
}

/// The report's text escaped as the HTML writes text.
fn escaped(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

/// The number in the `σ` row of output `name`'s table.
fn printed_sigma(html: &str, name: &str) -> f64 {
    let head = format!("<h3>Output <code>{}</code>", escaped(name));
    let at = html.find(&head).unwrap_or_else(|| panic!("no section {head}"));
    let row = "<tr><td>σ</td><td>";
    let s = &html[at..];
    let v = &s[s.find(row).unwrap() + row.len()..];
    v.split([' ', '<']).next().unwrap().parse().unwrap()
}

/// The stems of the SVG pictures `stochvib plot` writes for `scenario`.
fn plot_stems(scenario: &str, dir: &Path) -> Vec<String> {
    let (ok, _, err) = cli(&["plot", scenario, "-o", dir.to_str().unwrap()]);
    assert!(ok, "plot {scenario}: {err}");
    let mut v: Vec<String> = crate::common::listing(dir)
        .into_iter()
        .filter_map(|f| f.strip_suffix(".svg").map(str::to_string))
        .collect();
    v.sort();
    v
}

/// Checks the report of one stochastic scenario against its `analyze --json` and `plot` (and, with
/// `[transient]`, against `transient --json` and `transient --plots`); returns whether it is transient.
fn check_stochastic(html: &str, scenario: &str, json: &serde_json::Value, work: &Path) -> bool {
    for o in json["outputs"].as_array().unwrap() {
        let st = &o["statistics"];
        let name = st["name"].as_str().unwrap();
        assert!(html.contains(&escaped(name)), "{scenario}: output {name} missing");
        if let Some(sigma) = st["sigma"].as_f64() {
            let p = printed_sigma(html, name);
            assert!(rel(p, sigma) < PRINTED_4_DIGITS, "{scenario} {name}: σ {p} vs {sigma}");
        }
    }
    let mut stems = plot_stems(scenario, &work.join("plots"));
    let transient = std::fs::read_to_string(root().join(scenario))
        .unwrap()
        .lines()
        .any(|l| l.starts_with("[transient]"));
    if transient {
        stems.extend(check_transient(html, scenario, &work.join("transient")));
        stems.sort();
    }
    let mut figures: Vec<String> = html
        .split("<figcaption>")
        .skip(1)
        .map(|s| s.split('<').next().unwrap().to_string())
        .collect();
    figures.sort();
    assert_eq!(figures, stems, "{scenario}: the pictures of `stochvib plot`");
    assert_eq!(
        html.matches("<svg").count(),
        stems.len(),
        "{scenario}: every picture inline"
    );
    if json.get("verdicts").is_some() {
        assert!(html.contains("<h2>Verdicts</h2>"), "{scenario}: verdicts");
    }
    transient
}

/// The cells of the rows of the first table after `heading` (tags stripped).
fn table_after(html: &str, heading: &str) -> Vec<Vec<String>> {
    let at = html.find(heading).unwrap_or_else(|| panic!("no {heading}"));
    let t = &html[at..];
    let t = &t[t.find("<tbody>").unwrap()..t.find("</table>").unwrap()];
    t.split("<tr>")
        .skip(1)
        .map(|r| {
            r.split("<td")
                .skip(1)
                .map(|c| c.split_once('>').unwrap().1.split('<').next().unwrap().to_string())
                .collect()
        })
        .collect()
}

/// The transient section of a scenario with `[transient]`: the mission table's E N⁺(b) and P(max |y| > b)
/// by the integrated rate against `stochvib transient --json` (every digit; the report prints four), and
/// the stems of the pictures `stochvib transient --plots` draws.
fn check_transient(html: &str, scenario: &str, dir: &Path) -> Vec<String> {
    assert!(
        html.contains("<h2>Transient response and mission extremes</h2>"),
        "{scenario}"
    );
    let (ok, out, err) = cli(&["transient", scenario, "--json", "--plots", dir.to_str().unwrap()]);
    assert!(ok, "transient {scenario}: {err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    let mission = json["exact"]["mission"].as_array().unwrap();
    let rows = table_after(html, "<h3>Mission</h3>");
    assert_eq!(rows.len(), mission.len(), "{scenario}: mission rows");
    for (r, m) in rows.iter().zip(mission) {
        assert_eq!(r[0], m["output"].as_str().unwrap());
        for (cell, key) in [(2, "expected_upcrossings"), (3, "p_integrated_rate")] {
            let (p, want) = (r[cell].parse::<f64>().unwrap(), m[key].as_f64().unwrap());
            assert!(
                rel(p, want) < PRINTED_4_DIGITS || (p - want).abs() < 1e-300,
                "{scenario} {key}: {p} vs {want}"
            );
        }
    }
    for o in json["exact"]["outputs"].as_array().unwrap() {
        assert!(html.contains(&escaped(o["name"].as_str().unwrap())), "{scenario}");
    }
    let mut stems: Vec<String> = crate::common::listing(dir)
        .into_iter()
        .filter_map(|f| f.strip_suffix(".svg").map(str::to_string))
        .collect();
    assert!(
        stems.iter().all(|s| s.ends_with("-transient")) && !stems.is_empty(),
        "{stems:?}"
    );
    stems.sort();
    stems
}

/// The three routes of a model with nonlinear elements: every output's σ by route 1 and the exact route
/// (route 3) against `analyze --json` (the report prints six digits), and the input density picture.
fn check_nonlinear(html: &str, scenario: &str, json: &serde_json::Value) {
    assert!(html.contains("<h2>Nonlinear response: three routes</h2>"), "{scenario}");
    for o in json["outputs"].as_array().unwrap() {
        let name = o["name"].as_str().unwrap();
        let head = format!("<h3>{} [{}]</h3>", escaped(name), escaped(o["unit"].as_str().unwrap()));
        let rows = table_after(html, &head);
        let printed = rows.iter().find(|r| r[0] == "sigma_response").expect("a σ row");
        let row = o["rows"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["statistic"] == "sigma_response");
        for (cell, key) in [(1, "route1"), (2, "exact")] {
            if let Some(want) = row.and_then(|r| r[key].as_f64()) {
                let p: f64 = printed[cell].parse().unwrap();
                assert!(
                    rel(p, want) < PRINTED_4_DIGITS,
                    "{scenario} {name} {key}: {p} vs {want}"
                );
            }
        }
    }
    assert_eq!(html.matches("<svg").count(), 1, "{scenario}: the input density");
    assert!(html.contains("<figcaption>input-density<"), "{scenario}");
}

/// Deterministic models and reference tables: every table title of `analyze --json`.
fn check_tables(html: &str, scenario: &str, json: &serde_json::Value) {
    for t in json["tables"].as_array().unwrap() {
        let title = t["title"].as_str().unwrap();
        assert!(html.contains(&escaped(title)), "{scenario}: table {title} missing");
    }
}

/// What every report holds: self-contained, well-formed, the provenance and the scenario as written.
fn check_common(html: &str, scenario: &str) {
    if let Err(e) = well_formed(html) {
        panic!("{scenario}: not well-formed: {e}");
    }
    for no in ["http", "src=", "href=", "url(", "<script", "@import"] {
        assert!(!html.contains(no), "{scenario}: contains `{no}`");
    }
    let bytes = std::fs::read(root().join(scenario)).unwrap();
    let crc = format!("<td>{:08x}</td>", crc32fast::hash(&bytes));
    assert!(html.contains(&crc), "{scenario}: CRC-32 {crc}");
    assert!(
        html.contains(&format!("<td class=\"num\">{}</td>", bytes.len())),
        "{scenario}: size"
    );
    let text = String::from_utf8(bytes).unwrap();
    assert!(
        html.contains(&escaped(text.trim_end())),
        "{scenario}: the file as written"
    );
    assert!(html.contains(&format!("stochvib {}", env!("CARGO_PKG_VERSION"))));
}

/// Every `data/*.toml` that `analyze` accepts gets a report with every output's σ, the pictures of
/// `plot`, the verdicts, the provenance and the file as written; every report passes the HTML validator
/// of `report_browser` (html5lib).
#[test]
fn every_data_scenario_has_a_complete_self_contained_report() {
    let work = tmp("all");
    // every report also through the HTML validator (html5lib), when the browser test's tools are present
    let validate = crate::report_browser::tools_present();
    let (mut reported, mut nonlinear, mut transient) = (0, 0, 0);
    for f in crate::common::listing(&root().join("data")) {
        let Some(stem) = f.strip_suffix(".toml") else { continue };
        let scenario = format!("data/{f}");
        let (ok, out, _) = cli(&["analyze", &scenario, "--json"]);
        if !ok {
            continue;
        }
        let json: serde_json::Value = serde_json::from_str(&out).unwrap();
        let html_path = work.join(format!("{stem}.html"));
        let (ok, _, err) = cli(&["report", &scenario, "-o", html_path.to_str().unwrap()]);
        assert!(ok, "report {scenario}: {err}");
        let html = std::fs::read_to_string(&html_path).unwrap();
        check_common(&html, &scenario);
        if validate {
            crate::report_browser::validate(&html_path);
        }
        if json.get("route1").is_some() {
            check_nonlinear(&html, &scenario, &json);
            nonlinear += 1;
        } else if json.get("outputs").is_some() {
            let dir = work.join(stem);
            std::fs::create_dir_all(&dir).unwrap();
            transient += usize::from(check_stochastic(&html, &scenario, &json, &dir));
        } else {
            check_tables(&html, &scenario, &json);
        }
        reported += 1;
    }
    assert!(
        reported >= 19 && nonlinear >= 3 && transient >= 2,
        "{reported} reports, {nonlinear} nonlinear, {transient} transient"
    );
    std::fs::remove_dir_all(&work).unwrap();
}

/// The single isolator's one pole: ω₀ = √(k/m) = √(10⁴ N/m / 100 kg) = 10 rad/s, f = 10/(2π) = 1.592 Hz,
/// ζ = 0.2 as written in `data/isolator-single.toml`.
#[test]
fn the_pole_table_of_the_single_isolator() {
    let work = tmp("pole");
    let out = work.join("r.html");
    let (ok, _, err) = cli(&["report", "data/isolator-single.toml", "-o", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    let html = std::fs::read_to_string(&out).unwrap();
    let at = html
        .find("<th class=\"num\">damping ratio ζ</th>")
        .expect("a pole table");
    let body = &html[at..html[at..].find("</table>").unwrap() + at];
    let cells: Vec<f64> = body
        .split("<td class=\"num\">")
        .skip(1)
        .map(|c| c.split('<').next().unwrap().parse().unwrap())
        .collect();
    assert_eq!(cells.len(), 4, "one pole: {body}");
    let want = [1.0, 10.0, 10.0 / (2.0 * std::f64::consts::PI), 0.2];
    for (c, w) in cells.iter().zip(want) {
        assert!(rel(*c, w) < PRINTED_4_DIGITS, "{c} vs {w}");
    }
    std::fs::remove_dir_all(&work).unwrap();
}

/// `--format markdown`: the same sections, the scenario in a fence, every picture a file beside it.
#[test]
fn markdown_form_links_its_pictures_beside_it() {
    let work = tmp("md");
    let out = work.join("qc.md");
    let (ok, _, err) = cli(&[
        "report",
        "data/quarter-car.toml",
        "-o",
        out.to_str().unwrap(),
        "--format",
        "markdown",
    ]);
    assert!(ok, "{err}");
    let md = std::fs::read_to_string(&out).unwrap();
    let links: Vec<&str> = md
        .lines()
        .filter_map(|l| l.strip_prefix("![")?.split_once("](")?.1.strip_suffix(')'))
        .collect();
    assert_eq!(
        links.len(),
        9,
        "input density, transfer and output density of 4 outputs"
    );
    for l in &links {
        assert!(l.starts_with("qc-pictures/") && work.join(l).is_file(), "{l}");
    }
    for h in [
        "## Provenance",
        "## Model and input",
        "## Outputs",
        "## Pictures",
        "```toml",
    ] {
        assert!(md.contains(h), "{h}");
    }
    std::fs::remove_dir_all(&work).unwrap();
}

/// A bad `-o` is refused before any work, with the reason, and leaves nothing behind: the scenario itself,
/// a directory, an existing file of another kind; an existing report only with `--overwrite`.
#[test]
fn a_bad_output_is_refused_cleanly() {
    let work = tmp("bad");
    let scenario = work.join("s.toml");
    std::fs::copy(root().join("data/quarter-car.toml"), &scenario).unwrap();
    let before = std::fs::read(&scenario).unwrap();
    let s = scenario.to_str().unwrap();
    let other = work.join("notes.html");
    std::fs::write(&other, "my notes").unwrap();
    let dir = work.join("dir");
    std::fs::create_dir(&dir).unwrap();
    for (out, reason) in [
        (s, "is an input"),
        (dir.to_str().unwrap(), "is a directory"),
        (other.to_str().unwrap(), "is not a stochvib report"),
    ] {
        let (ok, _, err) = cli(&["report", s, "-o", out, "--overwrite"]);
        assert!(!ok && err.contains(out) && err.contains(reason), "{out}: {err}");
    }
    assert_eq!(std::fs::read(&scenario).unwrap(), before);
    assert_eq!(std::fs::read_to_string(&other).unwrap(), "my notes");
    let good = work.join("r.html");
    let g = good.to_str().unwrap();
    assert!(cli(&["report", s, "-o", g]).0);
    let (ok, _, err) = cli(&["report", s, "-o", g]);
    assert!(!ok && err.contains("--overwrite"), "{err}");
    assert!(cli(&["report", s, "-o", g, "--overwrite"]).0);
    assert_eq!(
        crate::common::listing(&work),
        ["dir", "notes.html", "r.html", "s.toml"],
        "no temporary file left"
    );
    std::fs::remove_dir_all(&work).unwrap();
}

/// `stochvib report WORKDAY.toml`: the working day of `data/workday/`: self-contained and well-formed, the
/// workday file and every task's scenario file with its CRC-32, the day's A(8) and VDV per axis against
/// `stochvib workday --json` (every digit; the report prints four), the verdict and the A(8) picture.
#[test]
fn the_workday_report_holds_the_day() {
    let work = tmp("workday");
    let day = "data/workday/scraper-operator.toml";
    let out = work.join("day.html");
    let (ok, _, err) = cli(&["report", day, "-o", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    let html = std::fs::read_to_string(&out).unwrap();
    check_common(&html, day);
    if crate::report_browser::tools_present() {
        crate::report_browser::validate(&out);
    }
    for task in ["data/scraper-cab-comfort.toml", "data/operator-seat-verdicts.toml"] {
        let crc = format!(
            "<td>{:08x}</td>",
            crc32fast::hash(&std::fs::read(root().join(task)).unwrap())
        );
        assert!(html.contains(&crc), "{task}: CRC-32");
    }
    let (ok, json, err) = cli(&["workday", day, "--json"]);
    assert!(ok, "{err}");
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    let rows = table_after(&html, "<h3>The day</h3>");
    let axes = json["axes"].as_array().unwrap();
    assert_eq!(rows.len(), axes.len());
    for (r, a) in rows.iter().zip(axes) {
        assert_eq!(r[0], a["axis"].as_str().unwrap());
        for (cell, key) in [(1, "a8"), (2, "vdv")] {
            let (p, want) = (r[cell].parse::<f64>().unwrap(), a[key].as_f64().unwrap());
            assert!(rel(p, want) < PRINTED_4_DIGITS, "{key}: {p} vs {want}");
        }
    }
    assert!(html.contains("Directive 2002/44/EC"), "the verdict");
    assert_eq!(html.matches("<svg").count(), 1);
    assert!(html.contains("<figcaption>workday-a8<"));
    std::fs::remove_dir_all(&work).unwrap();
}
