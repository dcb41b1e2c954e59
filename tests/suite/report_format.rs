//! Reports a person pastes: numbers with four significant figures and one notation per column, markdown
//! tables for `analyze`, `road`, `inspect` and `workday` (`--format markdown`; `--json` is `--format json`),
//! inputs echoed as the user wrote them (`seat-surface`, `z`; a measured profile's file name), and `--help`
//! texts without source-code paths.
//!
//! Provenance: the formatter's expected strings are written by hand from the rule (correct rounding to four
//! significant figures; fixed notation for 10⁻³ ≤ |x| < 10⁴, scientific otherwise), and checked against the
//! value they stand for within half a unit of the fourth figure (`PRINTED_4_DIGITS`).

use crate::common;
use crate::common::SpawnSerial;
use common::root;
use common::tolerance::PRINTED_4_DIGITS;
use proptest::prelude::*;
use std::process::Command;
use stochvib::numbers::{column_notation, sig, sig_column, Notation, REPORT_SIGNIFICANT};

fn run(args: &[&str]) -> String {
    let o = Command::new(crate::common::cli_bin())
        .args(args)
        .current_dir(root())
        .output_serial()
        .unwrap();
    assert!(o.status.success(), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

#[test]
fn four_significant_figures_in_one_notation_per_column() {
    use Notation::*;
    for (x, n, s) in [
        (0.43301270189, Fixed, "0.4330"),
        (1.15, Fixed, "1.150"),
        (9.99996, Fixed, "10.00"),
        (1234.56, Fixed, "1235"),
        (0.00123456, Fixed, "0.001235"),
        (-0.5, Fixed, "-0.5000"),
        (6.433716e-6, Scientific, "6.434e-6"),
        (1.29313e10, Scientific, "1.293e10"),
        (0.5, Scientific, "5.000e-1"),
        (0.0, Fixed, "0"),
        (f64::INFINITY, Fixed, "inf"),
    ] {
        assert_eq!(sig(x, REPORT_SIGNIFICANT, n), s, "{x}");
    }
    assert_eq!(column_notation(&[0.001, 9999.4]), Fixed);
    assert_eq!(
        column_notation(&[0.001, 9999.6]),
        Scientific,
        "9999.6 rounds to 1.000e4"
    );
    assert_eq!(column_notation(&[0.00099996]), Fixed, "rounds to 0.001000");
    assert_eq!(column_notation(&[0.0009999]), Scientific);
    assert_eq!(sig_column(&[Some(3.0), None, Some(2e5)]), ["3.000e0", "—", "2.000e5"]);
}

/// The significant digits of a written number: its digits without sign, exponent and leading zeros.
fn significant_digits(s: &str) -> usize {
    let mantissa = s.split('e').next().unwrap();
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    digits.trim_start_matches('0').len().max(1)
}

proptest! {
    #![proptest_config(crate::common::proptest_config(256))]
    #[test]
    fn every_written_number_has_four_figures_and_stands_for_its_value(
        m in 1.0f64..10.0, e in -12i32..12, neg in any::<bool>()
    ) {
        let x = if neg { -m } else { m } * 10f64.powi(e);
        let n = column_notation(&[x]);
        let s = sig(x, REPORT_SIGNIFICANT, n);
        let back: f64 = s.parse().unwrap();
        prop_assert!((back - x).abs() <= PRINTED_4_DIGITS * x.abs(), "{x} written {s}");
        prop_assert_eq!(significant_digits(&s), 4, "{} written {}", x, s);
        prop_assert_eq!(s.contains('e'), n == Notation::Scientific);
    }
}

/// A pipe table: header cells, alignment row cells, body rows.
type PipeTable = (Vec<String>, Vec<String>, Vec<Vec<String>>);

/// Every pipe table of a markdown text.
fn pipe_tables(md: &str) -> Vec<PipeTable> {
    let cells = |l: &str| {
        let inner = l.trim().trim_start_matches('|').trim_end_matches('|');
        // `\|` is an escaped bar inside a cell
        inner
            .replace("\\|", "\u{0}")
            .split('|')
            .map(|c| c.trim().replace('\u{0}', "|"))
            .collect::<Vec<_>>()
    };
    let lines: Vec<&str> = md.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i + 1 < lines.len() {
        if lines[i].starts_with('|') && lines[i + 1].starts_with("|---") {
            let (head, rule) = (cells(lines[i]), cells(lines[i + 1]));
            let mut rows = Vec::new();
            let mut j = i + 2;
            while j < lines.len() && lines[j].starts_with('|') {
                rows.push(cells(lines[j]));
                j += 1;
            }
            out.push((head, rule, rows));
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

/// Every right-aligned (numeric) column of every table: one notation, four significant figures per number.
fn check_columns(md: &str, what: &str) -> usize {
    let tables = pipe_tables(md);
    assert!(!tables.is_empty(), "{what}: no table in\n{md}");
    let mut checked = 0;
    for (head, rule, rows) in &tables {
        assert_eq!(head.len(), rule.len(), "{what}: {head:?}");
        for r in rows {
            assert_eq!(r.len(), head.len(), "{what}: row {r:?} under {head:?}");
        }
        for (j, _) in rule.iter().enumerate().filter(|(_, r)| r.as_str() == "---:") {
            let nums: Vec<&str> = rows
                .iter()
                .map(|r| {
                    r[j].trim_start_matches('~')
                        .trim_start_matches('(')
                        .trim_end_matches(')')
                })
                .filter(|c| c.parse::<f64>().is_ok_and(|x| x != 0.0 && x.is_finite()) && c.contains('.'))
                .collect();
            let sci = nums.iter().filter(|c| c.contains('e')).count();
            assert!(
                sci == 0 || sci == nums.len(),
                "{what}: column `{}` mixes notations: {nums:?}",
                head[j]
            );
            for c in &nums {
                assert_eq!(significant_digits(c), 4, "{what}: `{c}` in column `{}`", head[j]);
            }
            checked += nums.len();
        }
    }
    checked
}

#[test]
fn markdown_reports_are_tables_with_one_notation_per_column() {
    let md = run(&["analyze", "data/operator-seat-verdicts.toml", "--format", "markdown"]);
    assert!(check_columns(&md, "analyze") > 20);
    for part in [
        "# Operator seat",
        "## Output `seat` [m]",
        "| variance method |",
        "health factors",
        "| method |",
    ] {
        assert!(md.contains(part), "`{part}` not in:\n{md}");
    }
    let md = run(&["road", "data/measured-profile.csv", "--format", "markdown"]);
    assert!(check_columns(&md, "road") > 1000, "every density bin");
    let md = run(&["analyze", "data/reference/table-8-1.toml", "--format", "markdown"]);
    check_columns(&md, "reference table");
    // a run file
    let dir = crate::common::scratch_path("report-format", "md-inspect");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.h5");
    let o = out.to_str().unwrap();
    run(&[
        "simulate",
        "data/quarter-car.toml",
        "--realizations",
        "4",
        "--dt",
        "0.01",
        "--duration",
        "5",
        "-o",
        o,
    ]);
    let md = run(&["inspect", o, "--format", "markdown"]);
    assert!(check_columns(&md, "inspect") > 10);
    assert!(md.contains("| signal | statistic | estimate |"), "{md}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn json_flag_is_format_json_and_conflicts_with_another_format() {
    let f = "data/operator-seat-verdicts.toml";
    let a: serde_json::Value = serde_json::from_str(&run(&["analyze", f, "--json"])).unwrap();
    let b: serde_json::Value = serde_json::from_str(&run(&["analyze", f, "--format", "json"])).unwrap();
    assert_eq!(a, b);
    assert_eq!(run(&["analyze", f]), run(&["analyze", f, "--format", "text"]));
    let o = Command::new(crate::common::cli_bin())
        .args(["analyze", f, "--json", "--format", "markdown"])
        .current_dir(root())
        .output_serial()
        .unwrap();
    assert!(!o.status.success() && o.stdout.is_empty());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--format"));
}

#[test]
fn inputs_are_echoed_as_written() {
    let f = "data/operator-seat-verdicts.toml";
    let text = run(&["analyze", f]);
    assert!(text.contains("seat-surface  z"), "{text}");
    assert!(!text.contains("SeatSurface") && !text.contains("Health"), "{text}");
    let j: serde_json::Value = serde_json::from_str(&run(&["analyze", f, "--json"])).unwrap();
    let axis = &j["verdicts"]["comfort"]["axes"][0];
    assert_eq!(
        (axis["location"].as_str(), axis["axis"].as_str()),
        (Some("seat-surface"), Some("z"))
    );
    assert_eq!(j["verdicts"]["comfort"]["purpose"], "health");
    // a measured profile is named by its file, not by the tabulated density built from it
    let car = std::fs::read_to_string(root().join("data/quarter-car.toml")).unwrap();
    assert!(car.contains("spectrum = \"iso8608-c\""));
    let scenario = car.replace(
        "spectrum = \"iso8608-c\"",
        "spectrum = { kind = \"measured-profile\", file = \"measured-profile.csv\", track = \"right\" }",
    );
    let sc =
        stochvib::scenario::parse_scenario(&scenario, &root().join("data/p.toml"), &root().join("spectra")).unwrap();
    let r = stochvib::study::analysis_report(&sc).unwrap();
    assert_eq!(
        r.input,
        "measured-profile.csv (measured profile, track right) at 20 m/s"
    );
}

#[test]
fn help_texts_name_no_source_files() {
    let top = run(&["--help"]);
    let subcommands: Vec<String> = top
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect();
    assert!(subcommands.len() >= 12, "{subcommands:?}");
    for c in subcommands.iter().map(String::as_str).chain([""]) {
        let help = if c.is_empty() { top.clone() } else { run(&[c, "--help"]) };
        assert!(
            !help.contains("src/") && !help.contains(".rs"),
            "`stochvib {c} --help` names a source file:\n{help}"
        );
    }
}
