//! Command cases: the formats and commands beyond the TOML input files — road profiles (CSV) through
//! `road`, a profile through `replay` with its flags, `sweep` grids and flags, `merge` sets of run and sweep
//! shard files, `workday` files, and the record commands of [`super::records`] — their generation from
//! shipped files and fixtures, their evaluation through the library's entry points, and their invariants.
//!
//! # Invariants (besides `panic`, `timeout` and `crash`, as for the TOML cases)
//! * An error names what the user wrote: [`Error::File`], [`Error::Parse`], [`Error::Io`] or
//!   [`Error::Hdf5`] naming one of the case's files (the profile, the scenario or a spectrum it reads, a
//!   member or the target of a merge, a workday's scenario), or [`Error::InvalidParameter`] naming a flag
//!   (`--speed`, `--param`, …). Anything else is `error-without-file-key`; another file `error-wrong-file`;
//!   an `InvalidParameter` named like a library parameter `error-not-a-flag`.
//! * `long-message` — an error message of more than [`MAX_MESSAGE`] bytes (a value must be quoted as a
//!   bounded excerpt).
//! * `non-finite-result` — a success reports no NaN or infinity (through serde, as for the TOML cases).
//! * Merge sets: `merge-accepted-bad-set` — a set that is not exactly the shards of one run (a missing,
//!   duplicated, foreign, damaged or non-run member, a shard as the target, a finished run without
//!   `--overwrite`) is refused; `merge-refused-good-set` — the exact set into a new target is merged;
//!   `merge-wrong-result` — a merge gives the statistics of the single-process run bit for bit.
//! * Workday files carry the `must_reject` expectations of the TOML mutator.
//!
//! The CLI run of a case adds the checks of the TOML cases (exit 0 or 1, no signal, no panic, an `error:`
//! line naming a file or a flag, agreement with the library) and `cli-flood` (more than [`MAX_STDERR`]
//! bytes on stderr).

use super::inputs::{self, Case, Corpus, DocKind, Failure, Finding, Outcome, Success};
use super::mutate::{self, all_paths, Rng, Seg};
use rand::RngExt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU8, Ordering};
use std::time::Duration;
use stochvib::spectrum::{Convention, Domain};
use stochvib::Error;
use toml::{Table, Value};

/// Longest error message a case may give, bytes.
pub const MAX_MESSAGE: usize = 6000;
/// Longest stderr of a CLI run, bytes.
pub const MAX_STDERR: usize = 64 << 10;
/// Points of a sweep evaluated in-process (the study itself may be larger).
const SWEEP_POINTS: usize = 24;
/// Largest study the CLI runs whole (CSV on stdout has no size cap: it streams).
const SWEEP_CLI_POINTS: usize = 400;

/// The shipped material the command cases are made from.
#[derive(Debug, Clone, Default)]
pub struct CommandCorpus {
    /// Profile CSV seeds: (file name, bytes).
    pub profiles: Vec<(String, Vec<u8>)>,
    /// Road scenarios (`data/…`) a profile can replay.
    pub road_scenarios: Vec<String>,
    /// Stochastic scenarios and their sweepable keys with a template value each.
    pub sweep_scenarios: Vec<(String, Vec<(String, Value)>)>,
    /// Workday files with absolute scenario paths: (file name, table).
    pub workdays: Vec<(String, Table)>,
    /// The scenarios of [`super::optimize::SCENARIOS`]: (path, sweepable keys with a template value each,
    /// outputs (name, unit)).
    pub optimize_scenarios: Vec<OptimizeScenario>,
}

/// A scenario of the optimize cases: (path, sweepable keys with a template value each, outputs (name,
/// unit)).
pub type OptimizeScenario = (String, Vec<(String, Value)>, Vec<(String, String)>);

impl CommandCorpus {
    /// Reads the material under `root`.
    pub fn load(root: &Path, stochastic: &[(String, Table)]) -> CommandCorpus {
        let csv = std::fs::read_to_string(root.join("data/measured-profile.csv")).expect("the shipped profile");
        let (comments, rest): (Vec<&str>, Vec<&str>) = csv.lines().partition(|l| l.starts_with('#'));
        let two: String = comments
            .iter()
            .chain(rest.iter().take(2401))
            .map(|l| format!("{l}\n"))
            .collect();
        let one: String = std::iter::once("distance [m], z [mm]".to_string())
            .chain(rest.iter().skip(1).take(1200).map(|l| {
                let c: Vec<&str> = l.split(',').collect();
                format!("{},{}", c[0], c[1])
            }))
            .map(|l| format!("{l}\n"))
            .collect();
        let three: String = std::iter::once("distance [cm], left [mm], right [mm], middle [um]".to_string())
            .chain(rest.iter().skip(1).take(800).enumerate().map(|(k, l)| {
                let c: Vec<&str> = l.split(',').collect();
                format!(
                    "{},{},{},{}",
                    k * 5,
                    c[1],
                    c[2],
                    1000.0 * c[1].trim().parse::<f64>().unwrap_or(0.0)
                )
            }))
            .map(|l| format!("{l}\n"))
            .collect();
        let profiles = vec![
            ("profile.csv".to_string(), two.into_bytes()),
            ("one-track.csv".to_string(), one.into_bytes()),
            ("three-tracks.csv".to_string(), three.into_bytes()),
        ];
        let spectra = root.join("spectra");
        let mut road_scenarios = Vec::new();
        let mut optimize_scenarios = Vec::new();
        let mut sweep_scenarios = Vec::new();
        for (rel, table) in stochastic {
            let Ok(sc) = stochvib::scenario::load_scenario(&root.join(rel), &spectra) else {
                continue;
            };
            if sc.input.spectrum.domain() == Domain::Spatial {
                road_scenarios.push(rel.clone());
            }
            if super::optimize::SCENARIOS.contains(&rel.as_str()) {
                let outputs = sc.model.system.outputs().iter();
                let outputs = outputs.map(|o| (o.name.clone(), o.unit.clone())).collect();
                optimize_scenarios.push((rel.clone(), sweep_keys(table), outputs));
            }
            sweep_scenarios.push((rel.clone(), sweep_keys(table)));
        }
        let mut workdays = Vec::new();
        for e in std::fs::read_dir(root.join("data/workday"))
            .expect("data/workday")
            .flatten()
        {
            let p = e.path();
            let Ok(mut t) = std::fs::read_to_string(&p).unwrap().parse::<Table>() else {
                continue;
            };
            if let Some(Value::Array(tasks)) = t.get_mut("task") {
                for task in tasks.iter_mut().filter_map(Value::as_table_mut) {
                    if let Some(Value::String(s)) = task.get_mut("scenario") {
                        *s = p.parent().unwrap().join(&*s).display().to_string();
                    }
                }
            }
            workdays.push((p.file_name().unwrap().to_string_lossy().into_owned(), t));
        }
        workdays.sort_by(|a, b| a.0.cmp(&b.0));
        CommandCorpus {
            profiles,
            road_scenarios,
            sweep_scenarios,
            workdays,
            optimize_scenarios,
        }
    }
}

/// The numeric and quantity values of a scenario's `[model]` table and `input.speed`, as sweep keys
/// (`model.element.0.stiffness`) with their values.
fn sweep_keys(table: &Table) -> Vec<(String, Value)> {
    let mut keys = Vec::new();
    for p in all_paths(table) {
        let Some(v) = mutate::get(table, &p) else { continue };
        let numeric = matches!(v, Value::Integer(_) | Value::Float(_))
            || v.as_str().is_some_and(|s| stochvib::units::parse_quantity(s).is_ok());
        let key: Vec<String> = p
            .iter()
            .map(|s| match s {
                Seg::Key(k) => k.clone(),
                Seg::Index(i) => i.to_string(),
            })
            .collect();
        let key = key.join(".");
        if numeric && (key.starts_with("model.") || key == "input.speed") {
            keys.push((key, v.clone()));
        }
    }
    keys
}

// ------------------------------------------------------------------------------------------------------
// Fixtures: the run and sweep shard files merge sets are made of
// ------------------------------------------------------------------------------------------------------

/// The merge fixtures under `dir`: run A (3 shard files and its single-process run `whole.h5`), run B (2
/// shard files, another seed), and the 2 shard files of a sweep.
#[derive(Debug, Clone)]
pub struct Fixtures {
    /// The directory.
    pub dir: PathBuf,
}

/// Names of the fixture files by token.
fn fixture_file(token: &str) -> Option<&'static str> {
    Some(match token {
        "A0" => "a/shard-0-of-3.h5",
        "A1" => "a/shard-1-of-3.h5",
        "A2" => "a/shard-2-of-3.h5",
        "B0" => "b/shard-0-of-2.h5",
        "B1" => "b/shard-1-of-2.h5",
        "whole" => "whole.h5",
        "S0" => "s/sweep-shard-0-of-2.json",
        "S1" => "s/sweep-shard-1-of-2.json",
        _ => return None,
    })
}

impl Fixtures {
    /// Creates the fixtures under `dir` unless a previous call did (`dir/READY`).
    ///
    /// # Panics
    /// If the shipped scenarios cannot be run (a broken source tree, not a finding).
    pub fn ensure(root: &Path, dir: &Path) -> Fixtures {
        let f = Fixtures { dir: dir.to_path_buf() };
        if dir.join("READY").is_file() {
            return f;
        }
        let _ = std::fs::remove_dir_all(dir);
        for sub in ["a", "b", "s"] {
            std::fs::create_dir_all(dir.join(sub)).unwrap();
        }
        let spectra = root.join("spectra");
        let sc = stochvib::scenario::load_scenario(&root.join("data/conveyor-idler.toml"), &spectra).unwrap();
        let opts = |seed, part| stochvib::simulate::RunOptions {
            shard_size: 2,
            part,
            realizations: 6,
            duration_s: 2.0,
            dt_s: 0.01,
            seed,
            ..Default::default()
        };
        let quiet = |_: usize, _: usize| {};
        for (sub, seed, count) in [("a", 3, 3), ("b", 4, 2)] {
            for i in 0..count {
                let p = stochvib::store::Part::new(i, count).unwrap();
                let out = stochvib::study::part_path(&dir.join(sub), p);
                sc.simulate(&opts(seed, Some(p)), &out, &quiet).unwrap();
            }
        }
        sc.simulate(&opts(3, None), &dir.join("whole.h5"), &quiet).unwrap();
        let qc = stochvib::scenario::load_scenario(&root.join("data/quarter-car-model.toml"), &spectra).unwrap();
        let param = stochvib::study::SweepParam::parse("model.sprung_mass=250 kg..350 kg:4").unwrap();
        let spec = stochvib::study::SweepSpec::new(vec![param], stochvib::study::SweepMode::Grid).unwrap();
        let sweep = stochvib::study::Sweep::new(&qc, spec).unwrap();
        for i in 0..2 {
            let p = stochvib::store::Part::new(i, 2).unwrap();
            stochvib::study::run_sweep_shard(&sweep, p, &dir.join("s"), false, None, false, &quiet).unwrap();
        }
        std::fs::write(dir.join("READY"), "").unwrap();
        f
    }

    /// The statistics of run A's single-process run, the result every good merge must give.
    pub fn whole_statistics(&self) -> Vec<stochvib::store::OutputStatistics> {
        stochvib::store::RunFile::open(self.dir.join("whole.h5"))
            .and_then(|r| r.statistics())
            .expect("the fixture run")
    }
}

// ------------------------------------------------------------------------------------------------------
// Generation
// ------------------------------------------------------------------------------------------------------

/// A command case for case `index` (drawn from `rng`), or `None` for a TOML case.
pub fn generate(corpus: &Corpus, rng: &mut Rng, index: u64) -> Option<Case> {
    let cc = &corpus.commands;
    let kind = match rng.random_range(0..100) {
        0..=14 => DocKind::Profile,
        15..=22 => DocKind::Replay,
        23..=32 => DocKind::Sweep,
        33..=40 => DocKind::Merge,
        41..=45 if !cc.workdays.is_empty() => DocKind::Workday,
        _ => return None,
    };
    let mut case = blank(kind, index);
    match kind {
        DocKind::Profile => profile_case(cc, rng, &mut case, 1..4),
        DocKind::Replay => replay_case(cc, rng, &mut case),
        DocKind::Sweep => sweep_case(cc, rng, &mut case),
        DocKind::Merge => merge_case(rng, &mut case),
        _ => workday_case(corpus, rng, &mut case),
    }
    Some(case)
}

/// A command case `index` of `kind` with nothing in it yet.
pub(super) fn blank(kind: DocKind, index: u64) -> Case {
    Case {
        index,
        origin: String::new(),
        kind,
        file_name: String::new(),
        bytes: Vec::new(),
        mutations: Vec::new(),
        raw: Vec::new(),
        convention: Convention::TwoSidedAngular,
        doc: None,
        must_reject: Vec::new(),
        args: Vec::new(),
    }
}

/// An optimize case `index` ([`super::optimize`]).
pub fn optimize(corpus: &Corpus, rng: &mut Rng, index: u64) -> Case {
    let mut case = blank(DocKind::Optimize, index);
    super::optimize::optimize_case(&corpus.commands, rng, &mut case);
    case
}

/// A record-command case `index` ([`super::records`]).
pub fn record(corpus: &Corpus, rng: &mut Rng, index: u64) -> Case {
    let mut case = blank(DocKind::Record, index);
    super::records::record_case(&corpus.commands, rng, &mut case);
    case
}

fn pick<'a, T>(rng: &mut Rng, v: &'a [T]) -> &'a T {
    &v[rng.random_range(0..v.len())]
}

/// Hostile cell texts of a CSV.
const CELLS: &[&str] = &[
    "NaN", "inf", "-inf", "1e308", "-1e308", "1e-320", "", "abc", "0x10", "1,5", "1e999", "   ", "-0", "+5", "1_000",
    "١٢٣", "\"3\"", "1e", "--1", "0.0.1",
];

/// Hostile units of a CSV header.
const UNITS: &[&str] = &["furlong", "", "M", "km", "um", "µm", "mm ", "m/s", "1", "[mm]", "mm]["];

/// A profile CSV from a seed with `n` structure-aware mutations (cells, header, rows, delimiters).
pub(super) fn profile_case(cc: &CommandCorpus, rng: &mut Rng, case: &mut Case, n: std::ops::Range<usize>) {
    let (name, bytes) = pick(rng, &cc.profiles).clone();
    case.origin = format!("profile {name}");
    case.file_name = name;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let k = if n.is_empty() { 0 } else { rng.random_range(n) };
    for _ in 0..k {
        let d = mutate_profile(rng, &mut lines);
        case.raw.push(d);
    }
    let mut out = lines.join("\n");
    out.push('\n');
    case.bytes = out.into_bytes();
    if rng.random_bool(0.08) {
        let d = mutate::mutate_bytes(rng, &mut case.bytes);
        case.raw.push(d);
    }
    if case.kind == DocKind::Profile {
        case.args = road_flags(rng);
    }
}

/// The index of the header line (the first line that is not a comment).
fn header_line(lines: &[String]) -> Option<usize> {
    lines.iter().position(|l| !l.trim_start().starts_with('#'))
}

/// One CSV mutation; returns its description.
pub(super) fn mutate_profile(rng: &mut Rng, lines: &mut Vec<String>) -> String {
    // earlier mutations may have deleted every line (the arms below index a line)
    if lines.is_empty() {
        return "no line left".into();
    }
    let h = header_line(lines).unwrap_or(0);
    let data = h + 1..lines.len().max(h + 1);
    let row = |rng: &mut Rng| {
        if data.is_empty() {
            h
        } else {
            rng.random_range(data.clone())
        }
    };
    match rng.random_range(0..16) {
        0..=2 => {
            let r = row(rng);
            let mut cells: Vec<String> = lines
                .get(r)
                .map_or(vec![], |l| l.split(',').map(str::to_string).collect());
            if cells.is_empty() {
                return "no cell".into();
            }
            let c = rng.random_range(0..cells.len());
            let v = if rng.random_bool(0.1) {
                "9".repeat([100, 5000, 70_000][rng.random_range(0..3)])
            } else {
                pick(rng, CELLS).to_string()
            };
            cells[c] = v.clone();
            lines[r] = cells.join(",");
            format!("line {} cell {c} -> {}", r + 1, mutate::short(&v))
        }
        3 => {
            let Some(l) = lines.get_mut(h) else {
                return "no header".into();
            };
            let u = pick(rng, UNITS);
            let cols: Vec<&str> = l.split(',').collect();
            let c = rng.random_range(0..cols.len());
            let name = cols[c].split('[').next().unwrap_or("").trim().to_string();
            let mut cols: Vec<String> = cols.iter().map(|s| s.to_string()).collect();
            cols[c] = format!("{name} [{u}]");
            *l = cols.join(",");
            format!("header column {c} unit -> {u}")
        }
        4 => {
            let Some(l) = lines.get_mut(h) else {
                return "no header".into();
            };
            let what = match rng.random_range(0..4) {
                0 => l.replacen("left", "", 1),
                1 => l.replacen("right", "left", 1),
                2 => format!("{l}, extra [mm]"),
                _ => l.split(',').next().unwrap_or("").to_string(),
            };
            *l = what.clone();
            format!("header -> {}", mutate::short(&what))
        }
        5 => {
            let keep = [0usize, 1, 2, 3, 15, 16, 17, 40, 100][rng.random_range(0..9)];
            lines.truncate((h + 1 + keep).min(lines.len()));
            format!("kept {keep} rows")
        }
        6 => {
            let (a, b) = (row(rng), row(rng));
            lines.swap(a, b);
            format!("swapped lines {} and {}", a + 1, b + 1)
        }
        7 => {
            let r = row(rng);
            let l = lines[r].clone();
            lines.insert(r, l);
            format!("duplicated line {}", r + 1)
        }
        8 => {
            let r = row(rng);
            lines.remove(r.min(lines.len() - 1));
            format!("deleted line {}", r + 1)
        }
        9 => {
            // a column made constant or a straight line: a flat track
            let ramp = rng.random_bool(0.5);
            for (k, l) in lines.iter_mut().enumerate().skip(h + 1) {
                let mut cells: Vec<String> = l.split(',').map(str::to_string).collect();
                if cells.len() > 1 {
                    cells[1] = if ramp {
                        format!("{:.3}", 1.0 + k as f64 * 0.001)
                    } else {
                        "5.000".into()
                    };
                }
                *l = cells.join(",");
            }
            format!("track 1 made {}", if ramp { "a straight line" } else { "constant" })
        }
        10 => {
            let sep = [";", "\t", " ", ",,"][rng.random_range(0..4)];
            for l in lines.iter_mut().skip(h) {
                *l = l.replace(',', sep);
            }
            format!("separator -> {sep:?}")
        }
        11 => {
            let r = row(rng);
            let l = &mut lines[r];
            let d: f64 = l.split(',').next().and_then(|x| x.trim().parse().ok()).unwrap_or(0.0);
            let nd = d + [0.01, 0.5, -1.0, 1e6, 0.0][rng.random_range(0..5)];
            let rest: Vec<&str> = l.split(',').skip(1).collect();
            *l = std::iter::once(format!("{nd}"))
                .chain(rest.iter().map(|s| s.to_string()))
                .collect::<Vec<_>>()
                .join(",");
            format!("line {} distance -> {nd}", r + 1)
        }
        12 => {
            let r = row(rng);
            lines.insert(
                r,
                ["# comment", "", "   ", "#", "\u{feff}"][rng.random_range(0..5)].to_string(),
            );
            format!("inserted a blank or comment line at {}", r + 1)
        }
        13 => {
            let r = row(rng);
            lines[r].push_str(&",1".repeat([1, 40_000][rng.random_range(0..2)]));
            format!("line {} got extra cells", r + 1)
        }
        14 => {
            lines.insert(0, "\u{feff}".into());
            "a byte-order mark line first".into()
        }
        _ => {
            let r = row(rng);
            lines[r] = lines[r].replace('.', "\0");
            format!("NUL bytes in line {}", r + 1)
        }
    }
}

/// `road`'s options: sometimes a segment (hostile ones too), a detrend, a confidence.
fn road_flags(rng: &mut Rng) -> Vec<String> {
    let mut a = Vec::new();
    if rng.random_bool(0.3) {
        a.push("--segment".into());
        a.push(
            ["0", "2", "3", "4", "16", "17", "64", "1048576", "18446744073709551615"][rng.random_range(0..9)].into(),
        );
    }
    if rng.random_bool(0.3) {
        a.push("--detrend".into());
        a.push(["mean", "linear", "quadratic"][rng.random_range(0..3)].into());
    }
    if rng.random_bool(0.15) {
        a.push("--confidence".into());
        a.push(["0.9", "0", "1", "1.5", "NaN"][rng.random_range(0..5)].into());
    }
    a
}

/// A profile (lightly mutated) replayed through a road scenario with random flags.
fn replay_case(cc: &CommandCorpus, rng: &mut Rng, case: &mut Case) {
    profile_case(cc, rng, case, 0..2);
    let scenario = pick(rng, &cc.road_scenarios).clone();
    case.origin = format!("{} on {}", case.origin, scenario);
    let mut a = vec![scenario];
    let mut flag = |rng: &mut Rng, p: f64, name: &str, values: &[&str]| {
        if rng.random_bool(p) {
            a.push(name.to_string());
            a.push(values[rng.random_range(0..values.len())].to_string());
        }
    };
    flag(
        rng,
        0.5,
        "--speed",
        &["20", "7.5", "0", "-3", "1e308", "1e-300", "NaN", "inf", "1e6"],
    );
    flag(rng, 0.25, "--skip", &["0", "3.5", "-1", "1e9", "NaN"]);
    flag(rng, 0.25, "--track", &["left", "right", "z", "nope", ""]);
    flag(rng, 0.2, "--detrend", &["mean", "linear", "cubic"]);
    if rng.random_bool(0.2) {
        a.push("--zero-start".into());
    }
    case.args = a;
}

/// A shipped scenario with 1–3 `--param` grids (hostile keys, values, ranges and counts), sometimes
/// `--zip`.
fn sweep_case(cc: &CommandCorpus, rng: &mut Rng, case: &mut Case) {
    let (rel, keys) = pick(rng, &cc.sweep_scenarios).clone();
    case.origin = rel.clone();
    case.file_name = Path::new(&rel).file_name().unwrap().to_string_lossy().into_owned();
    let mut a = vec![rel];
    for _ in 0..rng.random_range(1..4) {
        a.push("--param".into());
        a.push(sweep_param(rng, &keys));
    }
    if rng.random_bool(0.2) {
        a.push("--zip".into());
    }
    case.args = a;
}

/// The number and unit of a template value (`"20 kN/m"` → (20, "kN/m"); a number is SI; else 1).
pub(super) fn number_unit(v: &Value) -> (f64, String) {
    match v {
        Value::String(s) => {
            let mut it = s.splitn(2, ' ');
            let x = it.next().and_then(|n| n.parse::<f64>().ok()).unwrap_or(1.0);
            (x, it.next().unwrap_or("").to_string())
        }
        Value::Integer(i) => (*i as f64, String::new()),
        Value::Float(f) => (*f, String::new()),
        _ => (1.0, String::new()),
    }
}

/// One `KEY=VALUES` text.
fn sweep_param(rng: &mut Rng, keys: &[(String, Value)]) -> String {
    let (key, v) = if keys.is_empty() || rng.random_bool(0.1) {
        let k = [
            "model.",
            "",
            "title",
            "input.spectrum",
            "model.element.99.stiffness",
            "model.nope",
            "a..b",
        ];
        (pick(rng, &k).to_string(), Value::Float(1.0))
    } else {
        pick(rng, keys).clone()
    };
    let key = if rng.random_bool(0.05) { format!("{key}x") } else { key };
    let (x, unit) = number_unit(&v);
    let unit = if rng.random_bool(0.05) { "furlong".into() } else { unit };
    let scaled = |rng: &mut Rng| -> String {
        match rng.random_range(0..12) {
            0 => "abc".into(),
            1 => "NaN".into(),
            2 => "1e308".into(),
            3 => "-1".into(),
            4 => String::new(),
            5 => "0".into(),
            _ => format!("{:e} {unit}", x * 10f64.powf(rng.random_range(-1.0..1.0)))
                .trim()
                .to_string(),
        }
    };
    let values = if rng.random_bool(0.5) {
        let n = rng.random_range(1..5);
        (0..n).map(|_| scaled(rng)).collect::<Vec<_>>().join(",")
    } else {
        let count = [
            "0",
            "1",
            "2",
            "5",
            "17",
            "1000000",
            "1000001",
            "18446744073709551615",
            "x",
            "-3",
        ][rng.random_range(0..10)];
        let log = if rng.random_bool(0.2) { ":log" } else { "" };
        let lo = if rng.random_bool(0.1) {
            format!("{:e}", -x)
        } else {
            format!("{:e}", x * 0.8)
        };
        format!("{lo}..{:e}:{count}{log} {unit}", x * 1.2).trim().to_string()
    };
    if rng.random_bool(0.03) {
        return key;
    }
    format!("{key}={values}")
}

/// A merge set: members (by fixture token), a target and flags.
fn merge_case(rng: &mut Rng, case: &mut Case) {
    case.file_name = "merged.h5".into();
    let sets: &[&[&str]] = &[
        &["A0", "A1", "A2"],
        &["A2", "A0", "A1"],
        &["dirA"],
        &["A0", "A1"],
        &["A0", "A0", "A1", "A2"],
        &["A0", "A1", "A2", "B0"],
        &["A0", "B1"],
        &["B0", "B1"],
        &["A0", "A1", "A2", "junk"],
        &["A0", "A1", "A2", "empty"],
        &["A0", "A1", "A2", "missing"],
        &["A0", "dmgA1", "A2"],
        &["A0", "truncA1", "A2"],
        &["A0", "A1", "A2", "whole"],
        &["S0", "S1"],
        &["S0", "S0", "S1"],
        &["S0"],
        &["S0", "mutS1"],
        &["S0", "S1", "A0"],
        &["dirS"],
    ];
    let set = *pick(rng, sets);
    let mut a: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let sweep = set.iter().any(|s| s.contains('S'));
    let targets: &[&str] = if sweep {
        &[
            "out=new.csv",
            "out=new.json",
            "out=new.h5",
            "out=S0",
            "out=junk",
            "out=dir",
            "out=new.txt",
        ]
    } else {
        &[
            "out=new",
            "out=new",
            "out=A0",
            "out=B0",
            "out=whole",
            "out=junk",
            "out=dir",
            "out=tmp",
        ]
    };
    a.push(pick(rng, targets).to_string());
    if rng.random_bool(0.3) {
        a.push("--overwrite".into());
    }
    if !sweep && rng.random_bool(0.2) {
        a.push("--copy".into());
    }
    // the damage of dmgA1 and the mutation of mutS1
    a.push(format!("seed={}", rng.random_range(0..u32::MAX)));
    case.origin = format!("merge {}", set.join(" "));
    case.args = a;
}

/// A shipped workday file with 1–3 mutations of the TOML mutator.
fn workday_case(corpus: &Corpus, rng: &mut Rng, case: &mut Case) {
    let (name, table) = pick(rng, &corpus.commands.workdays).clone();
    case.origin = format!("data/workday/{name}");
    case.file_name = name;
    let mut doc = table.clone();
    for _ in 0..rng.random_range(1..4) * 5 {
        if case.mutations.len() >= 3 {
            break;
        }
        if let Some(m) = mutate::mutate_once(rng, &mut doc, &corpus.vocabulary) {
            case.mutations.push(m);
        }
    }
    case.bytes = toml::to_string(&doc).unwrap_or_default().into_bytes();
    if rng.random_bool(0.1) {
        let d = mutate::mutate_bytes(rng, &mut case.bytes);
        case.raw.push(d);
    }
    if case.raw.is_empty() {
        for (i, m) in case.mutations.iter().enumerate() {
            // a key renamed back to its shipped name (`scenario` → `sscenario` → `scenario`: the vocabulary of
            // typos has no workday keys) is no typo
            let shipped = |p: &[Seg], v: &Value| mutate::get(&table, p).is_some_and(|x| x.to_string() == v.to_string());
            if let (Some(class), Some((p, v))) = (&m.must_reject, &m.witness)
                && mutate::get(&doc, p).is_some_and(|x| x.to_string() == v.to_string())
                && !shipped(p, v)
                && mutate::expectation_holds(&case.mutations, i)
            {
                case.must_reject
                    .push((class.clone(), mutate::path_str(p), mutate::path_str(p)));
            }
        }
        case.doc = Some(doc);
    }
}

// ------------------------------------------------------------------------------------------------------
// Evaluation
// ------------------------------------------------------------------------------------------------------

/// What a case needs besides its file.
#[derive(Debug, Clone)]
pub struct Context {
    /// The source tree.
    pub root: PathBuf,
    /// The merge fixtures.
    pub fixtures: PathBuf,
}

impl Context {
    fn spectra(&self) -> PathBuf {
        self.root.join("spectra")
    }
}

pub(super) fn fail(e: &Error, stage: &str) -> Outcome {
    let (variant, file, key, value) = match e {
        Error::File { file, key, value, .. } => ("File", Some(file.clone()), Some(key.clone()), Some(value.clone())),
        Error::Parse { file, .. } => ("Parse", Some(file.clone()), None, None),
        Error::Io { path, .. } => ("Io", Some(path.clone()), None, None),
        Error::Hdf5 { path, .. } => ("Hdf5", Some(path.clone()), None, None),
        Error::InvalidParameter { name, .. } => ("InvalidParameter", None, Some(name.clone()), None),
        Error::Divergent { .. } => ("Divergent", None, None, None),
        Error::Quadrature { .. } => ("Quadrature", None, None, None),
        Error::Unit { .. } => ("Unit", None, None, None),
        Error::Numerical { .. } => ("Numerical", None, None, None),
        Error::NotApplicable { .. } => ("NotApplicable", None, None, None),
        Error::Inaccurate { .. } => ("Inaccurate", None, None, None),
    };
    Outcome::Err(Failure {
        variant: variant.into(),
        message: e.to_string(),
        file,
        key,
        value,
        stage: stage.into(),
    })
}

pub(super) fn ok<T: serde::Serialize>(what: &str, r: &T) -> Outcome {
    Outcome::Ok(Success {
        what: what.into(),
        non_finite: super::floats::non_finite(r)
            .into_iter()
            .map(|(p, v)| (p, v.to_string()))
            .collect(),
        outputs: vec![],
        system_outputs: vec![],
        empty: false,
    })
}

/// The value after flag `name` in `args`.
fn flag<'a>(args: &'a [String], name: &str) -> Option<&'a str> {
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .map(String::as_str)
}

/// Parses a flag's value as the CLI would (`None`: absent; `Err`: clap refuses it).
fn parsed<T: std::str::FromStr>(args: &[String], name: &str) -> Result<Option<T>, String> {
    match flag(args, name) {
        None => Ok(None),
        Some(v) => v.parse().map(Some).map_err(|_| format!("{name} {v}")),
    }
}

/// Evaluates a command case whose file is at `path` (no time limit; panics propagate).
pub fn evaluate(kind: DocKind, path: &Path, args: &[String], ctx: &Context, stage: &AtomicU8) -> Outcome {
    stage.store(1, Ordering::SeqCst);
    let o = match kind {
        DocKind::Profile => eval_road(path, args),
        DocKind::Replay => eval_replay(path, args, ctx),
        DocKind::Sweep => eval_sweep(args, ctx),
        DocKind::Merge => eval_merge(path, args, ctx),
        DocKind::Record => super::records::evaluate(path, args, &ctx.spectra()),
        DocKind::Optimize => super::optimize::evaluate(args, ctx),
        _ => eval_workday(path, ctx),
    };
    stage.store(4, Ordering::SeqCst);
    o
}

/// Flags clap refuses before the command runs: the case is then only a CLI case.
pub(super) fn clap_refusal(what: String) -> Outcome {
    Outcome::Err(Failure {
        variant: "Clap".into(),
        message: format!("the command line refuses {what}"),
        file: None,
        key: None,
        value: None,
        stage: "start".into(),
    })
}

fn eval_road(path: &Path, args: &[String]) -> Outcome {
    use stochvib::study::road_profile::{road_report, RoadReportOptions};
    let (segment, confidence) = match (parsed::<usize>(args, "--segment"), parsed::<f64>(args, "--confidence")) {
        (Ok(s), Ok(c)) => (s, c.unwrap_or(0.95)),
        (Err(w), _) | (_, Err(w)) => return clap_refusal(w),
    };
    let detrend = match flag(args, "--detrend") {
        None | Some("linear") => stochvib::road::Detrend::Linear,
        Some("mean") => stochvib::road::Detrend::Mean,
        Some(other) => return clap_refusal(format!("--detrend {other}")),
    };
    if !(confidence > 0.0 && confidence < 1.0) {
        return clap_refusal(format!("--confidence {confidence} (the CLI checks it)"));
    }
    let opts = RoadReportOptions {
        segment_len: segment,
        detrend,
        confidence,
    };
    match road_report(path, &opts) {
        Ok(r) => {
            let _ = format!("{r}");
            ok("profile", &r)
        }
        Err(e) => fail(&e, "report"),
    }
}

fn eval_replay(path: &Path, args: &[String], ctx: &Context) -> Outcome {
    use stochvib::study::replay::{replay_scenario, ScenarioReplayOptions};
    let (speed, skip) = match (parsed::<f64>(args, "--speed"), parsed::<f64>(args, "--skip")) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(w), _) | (_, Err(w)) => return clap_refusal(w),
    };
    let detrend = match flag(args, "--detrend") {
        None | Some("linear") => stochvib::road::Detrend::Linear,
        Some("mean") => stochvib::road::Detrend::Mean,
        Some(other) => return clap_refusal(format!("--detrend {other}")),
    };
    let sc = match stochvib::scenario::load_scenario(&ctx.root.join(&args[0]), &ctx.spectra()) {
        Ok(sc) => sc,
        Err(e) => return fail(&e, "load"),
    };
    let opts = ScenarioReplayOptions {
        speed_m_s: speed,
        skip_m: skip,
        start: if args.iter().any(|a| a == "--zero-start") {
            stochvib::road::Start::Zero
        } else {
            stochvib::road::Start::Static
        },
        track: flag(args, "--track").map(str::to_string),
        detrend,
    };
    match replay_scenario(&sc, path, &opts) {
        Ok(r) => {
            let _ = format!("{r}");
            ok("replay", &r)
        }
        Err(e) => fail(&e, "report"),
    }
}

fn eval_sweep(args: &[String], ctx: &Context) -> Outcome {
    use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec};
    let sc = match stochvib::scenario::load_scenario(&ctx.root.join(&args[0]), &ctx.spectra()) {
        Ok(sc) => sc,
        Err(e) => return fail(&e, "load"),
    };
    let params: Vec<&String> = args.windows(2).filter(|w| w[0] == "--param").map(|w| &w[1]).collect();
    let params = match params
        .iter()
        .map(|p| SweepParam::parse(p))
        .collect::<Result<Vec<_>, _>>()
    {
        Ok(p) => p,
        Err(e) => return fail(&e, "load"),
    };
    let mode = if args.iter().any(|a| a == "--zip") {
        SweepMode::Zip
    } else {
        SweepMode::Grid
    };
    let sweep = match SweepSpec::new(params, mode).and_then(|spec| Sweep::new(&sc, spec)) {
        Ok(s) => s,
        Err(e) => return fail(&e, "load"),
    };
    let n = sweep.spec().n_points().min(SWEEP_POINTS);
    let rows = sweep.evaluate_range(0..n, false);
    if let Some(m) = rows
        .iter()
        .filter_map(|r| r.as_ref().err())
        .find(|m| m.len() > MAX_MESSAGE)
    {
        return fail(
            &Error::invalid("--param", "a point's message", mutate::short_to(m, 300)),
            "report",
        );
    }
    let values: Vec<Vec<stochvib::response::PointStatistics>> = rows.into_iter().filter_map(Result::ok).collect();
    ok("sweep", &values)
}

/// The members of a merge case materialised under `dir`: the input paths, the target, `--overwrite`,
/// `--copy`.
struct MergeSet {
    inputs: Vec<PathBuf>,
    out: PathBuf,
    overwrite: bool,
    copy: bool,
    /// Exactly the shards of run A or of run B into a new target (or, with --overwrite, over a finished run or
    /// past a garbage `.tmp`).
    good: bool,
    /// The shards of run A, whose merge must equal the single-process run `whole.h5`.
    run_a: bool,
}

/// Copies fixture `token` to `dir/name`.
fn copy_fixture(ctx: &Context, token: &str, to: &Path) {
    if let Some(f) = fixture_file(token) {
        std::fs::copy(ctx.fixtures.join(f), to).unwrap_or_else(|e| panic!("fixture {f}: {e}"));
    }
}

/// Flips a bit in the data of an accumulator of `file` (not in HDF5's metadata: a checksum must find it).
pub fn damage_accumulator(file: &Path, seed: u64) {
    let offset = hdf5::File::open(file)
        .and_then(|f| f.dataset("shards/y:moments"))
        .ok()
        .and_then(|d| d.offset());
    let Some(off) = offset else { return };
    let mut b = std::fs::read(file).unwrap();
    let at = off as usize + (seed as usize % 48);
    if at < b.len() {
        b[at] ^= 1 << (seed % 8);
        std::fs::write(file, b).unwrap();
    }
}

fn materialize(dir: &Path, args: &[String], ctx: &Context) -> MergeSet {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).unwrap();
    let seed: u64 = args
        .iter()
        .find_map(|a| a.strip_prefix("seed=")?.parse().ok())
        .unwrap_or(1);
    let mut inputs = Vec::new();
    let mut members = Vec::new();
    for (k, t) in args
        .iter()
        .filter(|a| !a.contains('=') && !a.starts_with("--"))
        .enumerate()
    {
        let p = dir.join(format!("m{k}-{}", t.replace('/', "_")));
        match t.as_str() {
            "dirA" | "dirS" => {
                std::fs::create_dir_all(&p).unwrap();
                let toks = if t == "dirA" {
                    ["A0", "A1", "A2"].as_slice()
                } else {
                    ["S0", "S1"].as_slice()
                };
                for tok in toks {
                    let name = Path::new(fixture_file(tok).unwrap()).file_name().unwrap().to_owned();
                    copy_fixture(ctx, tok, &p.join(name));
                    members.push(tok.to_string());
                }
                inputs.push(p);
                continue;
            }
            "junk" => std::fs::write(p.with_extension("h5"), b"not a run file\n").unwrap(),
            "empty" => std::fs::write(p.with_extension("h5"), b"").unwrap(),
            "missing" => {}
            "fifo" => super::input_campaign::mkfifo(&p.with_extension("h5")),
            "devnull" => {
                inputs.push(PathBuf::from("/dev/null"));
                members.push(t.clone());
                continue;
            }
            "dmgA1" => {
                copy_fixture(ctx, "A1", &p.with_extension("h5"));
                damage_accumulator(&p.with_extension("h5"), seed);
            }
            "truncA1" => {
                copy_fixture(ctx, "A1", &p.with_extension("h5"));
                let f = std::fs::OpenOptions::new()
                    .write(true)
                    .open(p.with_extension("h5"))
                    .unwrap();
                let len = f.metadata().unwrap().len();
                f.set_len(len * (seed % 90 + 5) / 100).unwrap();
            }
            "mutS1" => {
                let mut b = std::fs::read(ctx.fixtures.join(fixture_file("S1").unwrap())).unwrap();
                let mut rng = inputs::case_rng(seed, 7);
                mutate::mutate_bytes(&mut rng, &mut b);
                std::fs::write(p.with_extension("json"), b).unwrap();
            }
            tok => {
                let ext = if tok.starts_with('S') { "json" } else { "h5" };
                copy_fixture(ctx, tok, &p.with_extension(ext));
            }
        }
        let ext = if t.starts_with('S') || t == "mutS1" {
            "json"
        } else {
            "h5"
        };
        inputs.push(p.with_extension(ext));
        members.push(t.clone());
    }
    let target = args.iter().find_map(|a| a.strip_prefix("out=")).unwrap_or("new");
    let overwrite = args.iter().any(|a| a == "--overwrite");
    let out = match target {
        "A0" | "B0" | "S0" => {
            let ext = if target == "S0" { "json" } else { "h5" };
            // the first member when it is that shard (then the target is an input), else a copy of it
            match inputs.iter().zip(&members).find(|(_, m)| *m == target) {
                Some((p, _)) if !p.is_dir() => p.clone(),
                _ => {
                    let p = dir.join(format!("target-{target}.{ext}"));
                    copy_fixture(ctx, target, &p);
                    p
                }
            }
        }
        "whole" => {
            let p = dir.join("whole-target.h5");
            copy_fixture(ctx, "whole", &p);
            p
        }
        "junk" => {
            let p = dir.join("junk-target.h5");
            std::fs::write(&p, b"keep me\n").unwrap();
            p
        }
        "dir" => {
            let p = dir.join("dir-target.h5");
            std::fs::create_dir_all(&p).unwrap();
            p
        }
        "tmp" => {
            let p = dir.join("merged.h5");
            std::fs::write(dir.join("merged.h5.tmp"), b"garbage\n").unwrap();
            p
        }
        t => dir.join(
            t.strip_prefix("new")
                .map_or("merged.h5".to_string(), |e| format!("merged{e}")),
        ),
    };
    let out = if out.extension().is_none() {
        out.with_extension("h5")
    } else {
        out
    };
    let mut sorted = members.clone();
    sorted.sort();
    // run B's two shards are a complete run too (another seed: no single-process run to compare with)
    let run_a = sorted == ["A0", "A1", "A2"];
    let complete = run_a || sorted == ["B0", "B1"];
    // --overwrite replaces a finished run, and a garbage .tmp in the way (not an interrupted run)
    let good = complete && (target == "new" || (matches!(target, "whole" | "tmp") && overwrite));
    MergeSet {
        inputs,
        out,
        overwrite,
        copy: args.iter().any(|a| a == "--copy"),
        good,
        run_a,
    }
}

/// The directory of a merge case's files: next to the case file `path`.
fn merge_dir(path: &Path) -> PathBuf {
    path.parent().unwrap_or(Path::new(".")).join("merge-set")
}

fn eval_merge(path: &Path, args: &[String], ctx: &Context) -> Outcome {
    let set = materialize(&merge_dir(path), args, ctx);
    let sweeps = match stochvib::study::find_sweep_shards(&set.inputs) {
        Ok(s) => s,
        Err(e) => return fail(&e, "load"),
    };
    if !sweeps.is_empty() {
        return match stochvib::study::merge_sweep(&set.out, &set.inputs, set.overwrite) {
            Ok(t) => ok("merge-sweep", &t.errors),
            Err(e) => fail(&e, "report"),
        };
    }
    let opts = stochvib::study::MergeOptions {
        copy: set.copy,
        overwrite: set.overwrite,
        confidence: None,
    };
    match stochvib::study::merge_runs(&set.out, &set.inputs, &opts, &|_, _| {}) {
        Ok(s) => {
            let same = !set.run_a
                || s.outputs
                    == Fixtures {
                        dir: ctx.fixtures.clone(),
                    }
                    .whole_statistics();
            Outcome::Ok(Success {
                what: format!(
                    "merge:{}:{}",
                    if set.good { "good" } else { "bad" },
                    if same { "same" } else { "differs" }
                ),
                non_finite: vec![],
                outputs: vec![],
                system_outputs: vec![],
                empty: false,
            })
        }
        Err(e) => {
            let mut o = fail(&e, "report");
            if set.good
                && let Outcome::Err(f) = &mut o
            {
                f.stage = "refused-good-set".into();
            }
            o
        }
    }
}

fn eval_workday(path: &Path, ctx: &Context) -> Outcome {
    use stochvib::scenario::workday_file::load_workday;
    use stochvib::study::workday::workday_exposure;
    let day = match load_workday(path) {
        Ok(d) => d,
        Err(e) => return fail(&e, "load"),
    };
    match workday_exposure(&day, &ctx.spectra()) {
        Ok(r) => {
            let rep = stochvib::report::WorkdayReport(r);
            let _ = format!("{rep}");
            ok("workday", &rep)
        }
        Err(e) => fail(&e, "report"),
    }
}

/// Runs a command case in this process (written under `dir`) with a time limit; its outcome, findings and
/// time.
pub fn run_case(case: &Case, dir: &Path, limit: Duration, ctx: &Context) -> (Outcome, Vec<Finding>, Duration) {
    let path = write_case(case, dir, ctx);
    let t = std::time::Instant::now();
    let o = run_limited(case.kind, &path, &case.args, ctx, limit);
    let el = t.elapsed();
    let f = check(case, &path, &o, ctx);
    (o, f, el)
}

/// [`evaluate`] with a time limit.
pub fn run_limited(kind: DocKind, path: &Path, args: &[String], ctx: &Context, limit: Duration) -> Outcome {
    let (p, a, c) = (path.to_path_buf(), args.to_vec(), ctx.clone());
    if kind.is_cli_only() {
        // the child process has the limit; the thread waits a little longer for its report
        let f = move |st: &AtomicU8| super::cli_commands::evaluate(&p, &a, &c, limit, st);
        return inputs::limited(limit + Duration::from_secs(5), f);
    }
    inputs::limited(limit, move |st| evaluate(kind, &p, &a, &c, st))
}

/// Writes a command case's file (a merge case has none of its own: its members are made by
/// [`evaluate`]); returns its path.
pub fn write_case(case: &Case, dir: &Path, ctx: &Context) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    match case.kind {
        DocKind::Sweep | DocKind::Optimize => ctx.root.join(&case.args[0]),
        DocKind::Merge => dir.join(&case.file_name),
        _ => inputs::write_case(case, dir),
    }
}

// ------------------------------------------------------------------------------------------------------
// Invariants
// ------------------------------------------------------------------------------------------------------

/// Whether an error naming `named` names one of the case's files.
fn names_a_case_file(case: &Case, path: &Path, named: &Path, ctx: &Context) -> bool {
    let n = named.display().to_string();
    let root = ctx.root.display().to_string();
    named == path
        || n.starts_with(&root)
        || n.contains("merge-set")
        || String::from_utf8_lossy(&case.bytes).contains(&n)
        || case.args.iter().any(|a| n.ends_with(a.as_str()))
}

/// The findings of one evaluation of a command case.
pub fn check(case: &Case, path: &Path, outcome: &Outcome, ctx: &Context) -> Vec<Finding> {
    if case.kind.is_cli_only() {
        return super::cli_commands::check(case, path, outcome);
    }
    let mut f = Vec::new();
    let what = case.kind.label();
    let mut add = |class: &str, signature: String, detail: String| {
        f.push(Finding {
            class: class.into(),
            signature,
            detail,
        })
    };
    match outcome {
        Outcome::Panic {
            location,
            message,
            stage,
        } => add(
            "panic",
            format!("panic at {location}"),
            format!("{what}, stage {stage}: {}", mutate::short_to(message, 240)),
        ),
        Outcome::Timeout { stage, limit_ms } => add(
            "timeout",
            format!("timeout in stage {stage} ({what})"),
            format!("no result after {limit_ms} ms"),
        ),
        Outcome::Err(e) if e.variant == "Clap" => {}
        Outcome::Err(e) => {
            if e.message.len() > MAX_MESSAGE {
                add(
                    "long-message",
                    format!("{what}: a {} message of more than {MAX_MESSAGE} bytes", e.variant),
                    mutate::short_to(&e.message, 240),
                );
            }
            if case.kind == DocKind::Merge && e.stage == "refused-good-set" {
                add(
                    "merge-refused-good-set",
                    format!(
                        "merge refuses the shards of one run: {}",
                        inputs::normalize_message(&e.message)
                    ),
                    case.describe(),
                );
            }
            match (e.variant.as_str(), &e.file, &e.key) {
                ("File" | "Parse" | "Io" | "Hdf5", Some(named), _) => {
                    if !names_a_case_file(case, path, named, ctx) {
                        add(
                            "error-wrong-file",
                            format!("{what}: {} error names another file", e.variant),
                            format!("names {}: {}", named.display(), mutate::short_to(&e.message, 240)),
                        );
                    }
                }
                ("InvalidParameter", _, Some(name)) if name.starts_with("--") => {}
                ("InvalidParameter", _, Some(name)) if super::records::names_a_positional(case, name, &e.message) => {}
                ("InvalidParameter", _, Some(name)) => add(
                    "error-not-a-flag",
                    format!("{what}: parameter `{name}` is not what the user wrote"),
                    mutate::short_to(&e.message, 240),
                ),
                (v, _, _) => add(
                    "error-without-file-key",
                    format!(
                        "{what}: {v} error from stage {}: {}",
                        e.stage,
                        inputs::normalize_message(&e.message)
                    ),
                    mutate::short_to(&e.message, 240),
                ),
            }
        }
        Outcome::Ok(s) => {
            for (p, v) in &s.non_finite {
                add(
                    "non-finite-result",
                    format!("{v} in the {what} report at {}", mutate::normalize_path(p)),
                    format!("{p} = {v}"),
                );
            }
            if s.what.starts_with("merge:bad") {
                add(
                    "merge-accepted-bad-set",
                    format!("merge accepts {}", case.origin),
                    case.describe(),
                );
            }
            if s.what == "merge:good:differs" {
                add(
                    "merge-wrong-result",
                    "a merge differs from the single-process run".into(),
                    case.describe(),
                );
            }
            for (class, _, p) in &case.must_reject {
                add(
                    class,
                    format!("{class}: `{}` ({what})", mutate::normalize_path(p)),
                    case.describe(),
                );
            }
        }
    }
    f
}

// ------------------------------------------------------------------------------------------------------
// The CLI
// ------------------------------------------------------------------------------------------------------

/// The CLI arguments of a command case whose file is at `path`, or `None` when the CLI is not run (a
/// sweep too large to run whole).
pub fn cli_args(case: &Case, path: &Path, ctx: &Context, json: bool) -> Option<Vec<String>> {
    if case.kind.is_cli_only() {
        return None; // each case is a CLI run already
    }
    let file = path.display().to_string();
    let spectra = ["--spectra-dir".to_string(), ctx.spectra().display().to_string()];
    let mut a: Vec<String> = match case.kind {
        DocKind::Profile => {
            let mut a = vec!["road".into(), file];
            a.extend(case.args.iter().cloned());
            a
        }
        DocKind::Replay => {
            let mut a = vec![
                "replay".into(),
                ctx.root.join(&case.args[0]).display().to_string(),
                file,
            ];
            a.extend(case.args[1..].iter().cloned());
            a.extend(spectra);
            a
        }
        DocKind::Sweep => {
            let mut a = vec!["sweep".into(), file];
            a.extend(case.args[1..].iter().cloned());
            a.extend(spectra);
            if sweep_points(case) > SWEEP_CLI_POINTS {
                return None;
            }
            a
        }
        DocKind::Record => return Some(super::records::cli_args(case, path, &ctx.spectra())),
        DocKind::Optimize => return Some(super::optimize::cli_args(case, ctx, json)),
        DocKind::Merge => {
            let set = materialize(&merge_dir(path), &case.args, ctx);
            let mut a = vec!["merge".into(), set.out.display().to_string()];
            a.extend(set.inputs.iter().map(|p| p.display().to_string()));
            a.extend(case.args.iter().filter(|x| x.starts_with("--")).cloned());
            return Some(a);
        }
        _ => {
            let mut a = vec!["workday".into(), file];
            a.extend(spectra);
            a
        }
    };
    if json && matches!(case.kind, DocKind::Profile | DocKind::Replay) {
        a.push("--json".into());
    }
    Some(a)
}

/// The number of points of a sweep case's study as the CLI would see it (0 when its flags do not parse).
fn sweep_points(case: &Case) -> usize {
    let params: Option<Vec<_>> = case
        .args
        .windows(2)
        .filter(|w| w[0] == "--param")
        .map(|w| stochvib::study::SweepParam::parse(&w[1]).ok())
        .collect();
    let mode = if case.args.iter().any(|a| a == "--zip") {
        stochvib::study::SweepMode::Zip
    } else {
        stochvib::study::SweepMode::Grid
    };
    params
        .and_then(|p| stochvib::study::SweepSpec::new(p, mode).ok())
        .map_or(0, |s| s.n_points())
}

/// The findings of a CLI run of a command case, given the library's outcome label `lib`.
pub fn check_cli(case: &Case, args: &[String], lib: &str, out: &super::process::Output) -> Vec<Finding> {
    use super::process::Exit;
    let mut f = Vec::new();
    let cmd = format!("stochvib {}", args[0]);
    let mut add = |class: &str, signature: String, detail: String| {
        f.push(Finding {
            class: class.into(),
            signature,
            detail,
        })
    };
    if out.stderr.len() > MAX_STDERR {
        add(
            "cli-flood",
            format!("{cmd} writes more than {MAX_STDERR} bytes of stderr"),
            String::new(),
        );
    }
    let first_err = out
        .stderr
        .lines()
        .find(|l| l.starts_with("error"))
        .unwrap_or("")
        .to_string();
    if let Some(expected) = super::optimize::infeasible_as_expected(lib, out) {
        if !expected {
            add(
                "cli-inconsistent",
                format!("{cmd} does not fail with \"infeasible\" after printing an infeasible answer"),
                mutate::short(&first_err),
            );
        }
        return f;
    }
    match out.exit {
        Exit::Timeout => add(
            "cli-timeout",
            format!("{cmd} timed out"),
            format!("after {:?}", out.elapsed),
        ),
        Exit::Signal(s) => add(
            "cli-crash",
            format!("{cmd} killed by signal {s}"),
            super::process::tail(&out.stderr, 300),
        ),
        Exit::Code(101) => add(
            "cli-panic",
            format!("{cmd} panicked"),
            super::process::tail(&out.stderr, 300),
        ),
        Exit::Code(0) => {
            let toks = inputs::non_finite_tokens(&out.stdout, &case.bytes);
            if !toks.is_empty() && case.kind != DocKind::Sweep {
                add("cli-non-finite", format!("{cmd} prints {}", toks[0]), String::new());
            }
            if lib.starts_with("err") && !lib.contains("Clap") {
                add(
                    "cli-inconsistent",
                    format!("{cmd} succeeds where the library returns {lib}"),
                    case.describe(),
                );
            }
        }
        // clap's own refusals (exit 2) name the flag
        Exit::Code(2) if lib.contains("Clap") || out.stderr.contains("--") => {}
        Exit::Code(c) => {
            if c != 1 {
                add(
                    "cli-exit-code",
                    format!("{cmd} exit code {c}"),
                    mutate::short(&first_err),
                );
            }
            let named = args[1..]
                .iter()
                .any(|a| a.starts_with('/') && out.stderr.contains(a.as_str()))
                || out.stderr.contains("--")
                || out.stderr.contains(&case.file_name)
                || (case.kind == DocKind::Record && super::records::cli_names_a_positional(case, &out.stderr));
            if !first_err.starts_with("error") || !named {
                add(
                    "cli-error-message",
                    format!("{cmd} fails without naming a file or a flag"),
                    mutate::short(&first_err),
                );
            }
            if lib.starts_with("ok") {
                add(
                    "cli-inconsistent",
                    format!("{cmd} fails where the library succeeds ({lib})"),
                    mutate::short(&first_err),
                );
            }
        }
    }
    f
}

/// A command line for a case, for the reproducers.
pub fn command_line(case: &Case, file: &str) -> String {
    match case.kind {
        DocKind::Profile => format!("stochvib road {file} {}", case.args.join(" ")),
        DocKind::Replay => format!("stochvib replay {} {file} {}", case.args[0], case.args[1..].join(" ")),
        DocKind::Sweep => format!("stochvib sweep {}", case.args.join(" ")),
        DocKind::Merge => format!("stochvib merge <target> <members> ({})", case.args.join(" ")),
        DocKind::Record => super::records::command_line(case, file),
        DocKind::Optimize => format!("stochvib optimize {}", case.args.join(" ")),
        k if k.is_cli_only() => super::cli_commands::command_line(case, file),
        _ => format!("stochvib workday {file}"),
    }
}

// ------------------------------------------------------------------------------------------------------
// The output rule through the CLI
// ------------------------------------------------------------------------------------------------------

/// A CLI command whose output target must be refused (with or without `--overwrite`) and left as it was.
#[derive(Debug, Clone)]
pub struct OutputProbe {
    /// What the probe is.
    pub name: &'static str,
    /// The arguments.
    pub args: Vec<String>,
    /// The target that must not change.
    pub target: PathBuf,
}

/// A target's type and (for a regular file) its bytes.
fn snapshot(p: &Path) -> (String, Vec<u8>) {
    match std::fs::symlink_metadata(p) {
        Err(_) => ("absent".into(), vec![]),
        Ok(m) if m.is_file() => ("file".into(), std::fs::read(p).unwrap_or_default()),
        Ok(m) => (format!("{:?}", m.file_type()), vec![]),
    }
}

/// The probes of the output rule under `dir`: `replay -o` onto its profile, its scenario, `/dev/null`, a
/// FIFO, a directory; `sweep -o` onto a run file and onto a profile; `merge` onto one of its shard files
/// and onto a FIFO; `simulate -o` onto its scenario and onto a profile; `plot -o` onto a regular file.
pub fn output_probes(ctx: &Context, dir: &Path) -> Vec<OutputProbe> {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).unwrap();
    let copy = |from: &Path, name: &str| {
        let p = dir.join(name);
        std::fs::copy(from, &p).unwrap();
        p
    };
    let sc = copy(&ctx.root.join("data/quarter-car.toml"), "scenario.toml");
    let profile = copy(&ctx.root.join("data/measured-profile.csv"), "profile.csv");
    let run = copy(&ctx.fixtures.join("whole.h5"), "run.h5");
    let fifo = dir.join("fifo.out");
    super::input_campaign::mkfifo(&fifo);
    let folder = dir.join("folder.csv");
    std::fs::create_dir_all(&folder).unwrap();
    let shards: Vec<PathBuf> = ["A0", "A1", "A2"]
        .iter()
        .map(|t| copy(&ctx.fixtures.join(fixture_file(t).unwrap()), &format!("{t}.h5")))
        .collect();
    let s = |p: &Path| p.display().to_string();
    let spectra = ["--spectra-dir".to_string(), s(&ctx.spectra())];
    let replay = |target: &Path| {
        let mut a = vec![
            "replay".into(),
            s(&sc),
            s(&profile),
            "-o".into(),
            s(target),
            "--overwrite".into(),
        ];
        a.extend(spectra.clone());
        a
    };
    let sweep = |target: &Path| {
        let mut a = vec![
            "sweep".into(),
            s(&sc),
            "--param".into(),
            "model.element.0.stiffness=15 kN/m,20 kN/m".into(),
            "-o".into(),
            s(target),
            "--overwrite".into(),
        ];
        a.extend(spectra.clone());
        a
    };
    let simulate = |target: &Path| {
        let mut a = vec!["simulate".into(), s(&sc), "--realizations".into(), "4".into()];
        a.extend([
            "--duration".into(),
            "5".into(),
            "--dt".into(),
            "0.01".into(),
            "-o".into(),
            s(target),
        ]);
        a.push("--overwrite".into());
        a.extend(spectra.clone());
        a
    };
    let merge = |target: &Path| {
        let mut a = vec!["merge".into(), s(target)];
        a.extend(shards.iter().map(|p| s(p)));
        a.push("--overwrite".into());
        a
    };
    let probe = |name, args, target: &Path| OutputProbe {
        name,
        args,
        target: target.to_path_buf(),
    };
    vec![
        probe("replay -o its profile", replay(&profile), &profile),
        probe("replay -o its scenario", replay(&sc), &sc),
        probe(
            "replay -o /dev/null",
            replay(Path::new("/dev/null")),
            Path::new("/dev/null"),
        ),
        probe("replay -o a FIFO", replay(&fifo), &fifo),
        probe("replay -o a directory", replay(&folder), &folder),
        probe("sweep -o a run file", sweep(&run), &run),
        probe("sweep -o a profile (.csv)", sweep(&profile), &profile),
        probe("merge onto one of its shard files", merge(&shards[0]), &shards[0]),
        probe("merge onto a FIFO", merge(&fifo), &fifo),
        probe("simulate -o its scenario", simulate(&sc), &sc),
        probe("simulate -o a profile", simulate(&profile), &profile),
        probe(
            "plot -o a regular file",
            vec!["plot".into(), s(&run), "-o".into(), s(&profile)],
            &profile,
        ),
    ]
}

/// Runs one probe with `bin` and returns its findings: the command must exit 1 with an `error:` line that
/// names the target, and leave the target as it was.
pub fn run_output_probe(bin: &Path, p: &OutputProbe, limit: Duration) -> Vec<Finding> {
    let before = snapshot(&p.target);
    let mut cmd = std::process::Command::new(bin);
    cmd.args(&p.args);
    let out = super::process::run(cmd, limit, super::process::DEFAULT_MEMORY_LIMIT);
    let mut f = Vec::new();
    let mut add = |class: &str, what: &str| {
        f.push(Finding {
            class: class.into(),
            signature: format!("output rule: {}: {what}", p.name),
            detail: mutate::short_to(&out.stderr, 300),
        })
    };
    match out.exit {
        super::process::Exit::Signal(_) => add("cli-crash", "killed by a signal"),
        super::process::Exit::Timeout => add("cli-timeout", "timed out"),
        super::process::Exit::Code(101) => add("cli-panic", "panicked"),
        super::process::Exit::Code(1) => {
            if !out.stderr.contains(&p.target.display().to_string()) {
                add("cli-error-message", "the error does not name the target");
            }
        }
        super::process::Exit::Code(c) => add("output-rule", &format!("exit {c} instead of a refusal")),
    }
    if snapshot(&p.target) != before {
        add("output-rule", "the target changed");
    }
    f
}
