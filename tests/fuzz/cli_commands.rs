//! Cases of the commands whose work lives in the CLI's handlers: `simulate` (hostile `--realizations`,
//! `--duration`, `--dt`, `--seed`, shard flags, `-o` targets, `--overwrite`, an interrupted run's `.tmp`),
//! `plot` (a scenario mutated by the TOML mutator or a run file, hostile `-o`, `--convention`,
//! `--spectra-dir`), `report` (a scenario, a workday file or a run file, `--run`, `-o` targets, `--format`,
//! `--overwrite`), `inspect` and `check-run` (run files whole, damaged, truncated, of another kind, special
//! files; their flags), `analyze`'s flags (its Monte Carlo column, quadrature effort, format, pictures), and
//! the catalogue commands `book`, `spectra`, `models` and `spectrum` (their flags, hostile names,
//! `--spectra-dir` and `--plots`).
//!
//! A case is evaluated by running the CLI binary itself (the flags are parsed and checked in the handlers),
//! with the case's files made under a directory of its own (tokens `<…>` of the arguments, see
//! [`materialize`]). The invariants, besides those of every CLI run (exit 0, 1 or 2, no panic, no signal,
//! no hang, an `error:` line that names a flag or a file of the case, at most [`super::commands::MAX_STDERR`]
//! bytes of stderr, no NaN or infinity printed on success):
//! * `destroyed-input` — every input file of the case is left as it was;
//! * `output-rule` — a target that is an input, a FIFO, a device, a directory (of a file writer), a regular
//!   file (of a directory writer) or a file of another kind is refused and left as it was, with or without
//!   `--overwrite`;
//! * `half-written` — a command that fails leaves no new `.tmp` file and no new or changed target;
//! * `bad-output` — a command that succeeds wrote what it says: a run file that opens with finite statistics
//!   and verified checksums, a non-empty report, the pictures it lists;
//! * `hostile-accepted` — a value that must be refused (fewer than 2 realizations, a non-positive or
//!   non-finite step or duration, a confidence outside (0, 1), a shard outside `--of`, a damaged run file,
//!   an existing report without `--overwrite`) ends in exit 0.

use super::inputs::{Case, Corpus, DocKind, Failure, Finding, Outcome, Success};
use super::mutate::{self, Rng};
use rand::RngExt;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Mutex;
use std::time::Duration;
use toml::Table;

/// The commands of the family, each with the kind its cases are counted under.
pub const COMMANDS: [(&str, DocKind); 10] = [
    ("simulate", DocKind::Simulate),
    ("analyze", DocKind::Simulate),
    ("spectrum", DocKind::Catalogue),
    ("plot", DocKind::Plot),
    ("report", DocKind::Report),
    ("inspect", DocKind::Inspect),
    ("check-run", DocKind::Inspect),
    ("book", DocKind::Catalogue),
    ("spectra", DocKind::Catalogue),
    ("models", DocKind::Catalogue),
];

/// The cheap scenarios of `data/` the cases start from (a Monte Carlo run, a report or pictures of each
/// take well under a second on a quiet machine).
pub const SCENARIOS: [&str; 5] = [
    "data/conveyor-idler.toml",
    "data/quarter-car-model.toml",
    "data/isolator-single.toml",
    "data/quarter-car.toml",
    "data/operator-seat-verdicts.toml",
];

/// Findings of the file system made while a case ran, by case file, taken by [`check`].
static FS_FINDINGS: Mutex<BTreeMap<PathBuf, Vec<Finding>>> = Mutex::new(BTreeMap::new());

fn pick<'a>(rng: &mut Rng, v: &[&'a str]) -> &'a str {
    v[rng.random_range(0..v.len())]
}

/// Pushes `name value` with probability `p`.
fn maybe(rng: &mut Rng, a: &mut Vec<String>, p: f64, name: &str, values: &[&str]) {
    if rng.random_bool(p) {
        a.push(name.into());
        a.push(pick(rng, values).into());
    }
}

// ------------------------------------------------------------------------------------------------------
// Generation
// ------------------------------------------------------------------------------------------------------

/// A case of the family for case `index`: `args[0]` is the command, the rest its arguments with tokens.
pub fn case(corpus: &Corpus, rng: &mut Rng, index: u64, which: usize) -> Case {
    let (cmd, kind) = COMMANDS[which % COMMANDS.len()];
    let mut case = super::commands::blank(kind, index);
    case.origin = format!("cli {cmd}");
    case.file_name = "scenario.toml".into();
    let mut a = vec![cmd.to_string()];
    match cmd {
        "simulate" => simulate_args(corpus, rng, &mut case, &mut a),
        "analyze" => analyze_args(corpus, rng, &mut case, &mut a),
        "spectrum" => spectrum_args(rng, &mut a),
        "plot" => plot_args(corpus, rng, &mut case, &mut a),
        "report" => report_args(corpus, rng, &mut case, &mut a),
        "inspect" | "check-run" => inspect_args(rng, cmd, &mut a),
        _ => catalogue_args(rng, cmd, &mut a),
    }
    if rng.random_bool(0.03) {
        a.push(pick(rng, &["--bogus", "extra", "--json", "-o"]).into());
    }
    case.args = a;
    case
}

/// The case file: a cheap scenario with 0–2 mutations of the TOML mutator.
fn scenario_file(corpus: &Corpus, rng: &mut Rng, case: &mut Case) {
    let rel = pick(rng, &SCENARIOS);
    let Some(seed) = corpus.seeds.iter().find(|s| s.rel == rel) else {
        return;
    };
    let mut doc: Table = seed.table.clone();
    let n = match rng.random_range(0..10) {
        0..=4 => 0,
        5..=8 => 1,
        _ => 2,
    };
    for _ in 0..n * 5 {
        if case.mutations.len() == n {
            break;
        }
        if let Some(m) = mutate::mutate_once(rng, &mut doc, &corpus.vocabulary) {
            case.mutations.push(m);
        }
    }
    case.origin = format!("{} {rel}", case.origin);
    case.bytes = toml::to_string(&doc).unwrap_or_default().into_bytes();
}

/// A spectra directory: the catalogue mostly, else hostile.
fn spectra_dir(rng: &mut Rng, a: &mut Vec<String>, p_hostile: f64) {
    a.push("--spectra-dir".into());
    a.push(if rng.random_bool(p_hostile) {
        pick(
            rng,
            &[
                "<missing:spectra>",
                "<copy:spectra-file>",
                "<dir:empty-spectra>",
                "<spectra-bad>",
                "<fifo:spectra>",
            ],
        )
        .into()
    } else {
        "<spectra>".into()
    });
}

fn simulate_args(corpus: &Corpus, rng: &mut Rng, case: &mut Case, a: &mut Vec<String>) {
    scenario_file(corpus, rng, case);
    a.push("<file>".into());
    a.push("--realizations".into());
    a.push(
        pick(
            rng,
            &[
                "4",
                "4",
                "6",
                "2",
                "1",
                "0",
                "-1",
                "1e9",
                "1000000000",
                "18446744073709551615",
                "abc",
                "8",
            ],
        )
        .into(),
    );
    let durations = [
        "2", "2", "3", "0", "-1", "1e12", "NaN", "inf", "1e-300", "0.05", "abc", "1e308",
    ];
    let dts = [
        "0.01", "0.01", "0.02", "0", "-0.01", "1e-300", "NaN", "10", "1e308", "inf", "0.005",
    ];
    maybe(rng, a, 0.9, "--duration", &durations);
    maybe(rng, a, 0.9, "--dt", &dts);
    maybe(rng, a, 0.3, "--seed", &["0", "7", "18446744073709551615", "-1", "abc"]);
    if rng.random_bool(0.2) {
        a.push("--shard".into());
        a.push(pick(rng, &["0", "1", "2", "5", "auto", "-1", "x", "18446744073709551615"]).into());
        maybe(
            rng,
            a,
            0.85,
            "--of",
            &["2", "3", "1", "0", "18446744073709551615", "-2"],
        );
    }
    maybe(
        rng,
        a,
        0.2,
        "--shard-size",
        &["1", "2", "50", "0", "18446744073709551615"],
    );
    maybe(rng, a, 0.15, "--confidence", &["0.9", "0", "1", "NaN", "1.5", "-0.5"]);
    maybe(rng, a, 0.1, "--max-hours", &["1e-9", "0", "NaN", "-1", "1e308"]);
    maybe(
        rng,
        a,
        0.1,
        "--route",
        &["auto", "exact", "spectral", "spectral-stream", "bogus"],
    );
    maybe(rng, a, 0.08, "--stream-tail", &["1e-4", "0", "1", "NaN", "-1"]);
    if rng.random_bool(0.15) {
        a.push("--store-raw".into());
        maybe(
            rng,
            a,
            0.5,
            "--compression",
            &["none", "fast", "deflate:9", "deflate:0", "deflate:x", "zstd"],
        );
    }
    let targets = [
        "<new:run.h5>",
        "<new:run.h5>",
        "<new:run.h5>",
        "<run:run.h5>",
        "<file>",
        "<fifo:run.h5>",
        "<device:run.h5>",
        "<dir:run.h5>",
        "<copy:profile.csv>",
        "<missing:run.h5>",
        "<tmp-garbage:run.h5>",
        "<tmp-run:run.h5>",
        "<dir:shards>",
    ];
    a.push("-o".into());
    a.push(pick(rng, &targets).into());
    if rng.random_bool(0.35) {
        a.push("--overwrite".into());
    }
    if rng.random_bool(0.05) {
        a.push("--plots".into());
        a.push(pick(rng, &["<new:pictures>", "<copy:profile.csv>", "<fifo:pictures>"]).into());
    }
    if rng.random_bool(0.2) {
        a.push("--json".into());
    }
    spectra_dir(rng, a, 0.05);
}

/// `analyze` with the flags of its Monte Carlo column, its quadrature effort, its output format and pictures.
fn analyze_args(corpus: &Corpus, rng: &mut Rng, case: &mut Case, a: &mut Vec<String>) {
    scenario_file(corpus, rng, case);
    a.push("<file>".into());
    maybe(
        rng,
        a,
        0.6,
        "--monte-carlo",
        &["4", "8", "2", "1", "0", "1000000000000", "-1", "abc"],
    );
    maybe(
        rng,
        a,
        0.5,
        "--duration",
        &["2", "3", "0", "-1", "1e12", "NaN", "1e-300"],
    );
    maybe(
        rng,
        a,
        0.5,
        "--dt",
        &["0.01", "0.02", "0", "1e-300", "NaN", "-0.01", "1e308"],
    );
    maybe(rng, a, 0.2, "--seed", &["0", "18446744073709551615", "-1"]);
    maybe(rng, a, 0.1, "--max-hours", &["1e-9", "0", "NaN", "1e308"]);
    maybe(
        rng,
        a,
        0.2,
        "--rel-tol",
        &["1e-6", "0", "-1", "NaN", "1", "1e-300", "1e308"],
    );
    maybe(
        rng,
        a,
        0.15,
        "--max-subintervals",
        &["10", "0", "1", "18446744073709551615"],
    );
    maybe(rng, a, 0.1, "--max-half-periods", &["10", "0", "18446744073709551615"]);
    maybe(rng, a, 0.2, "--format", &["text", "markdown", "json", "bogus"]);
    if rng.random_bool(0.1) {
        a.push("--plots".into());
        a.push(
            pick(
                rng,
                &["<new:pictures>", "<copy:profile.csv>", "<fifo:pictures>", "<file>"],
            )
            .into(),
        );
    }
    spectra_dir(rng, a, 0.05);
}

/// `spectrum` of a catalogue name, a file or something hostile, with its density points and convention.
fn spectrum_args(rng: &mut Rng, a: &mut Vec<String>) {
    let names = [
        "iso8608-c",
        "book-8-45",
        "conveyor-lump-load",
        "nope",
        "",
        "<fifo:s.toml>",
        "<dir:s.toml>",
        "<copy:profile.csv>",
        "<junk:s.toml>",
        "../../etc/passwd",
    ];
    a.push(pick(rng, &names).into());
    let points = ["1,2,5", "0", "-1", "NaN", "inf", "1e308", "1e-300", "", "1,,2", "abc"];
    match rng.random_range(0..5) {
        0 => maybe(rng, a, 1.0, "--omega", &points),
        1 => maybe(rng, a, 1.0, "--frequency", &points),
        2 => a.extend(["--omega".into(), "1".into(), "--frequency".into(), "1".into()]),
        _ => {}
    }
    maybe(
        rng,
        a,
        0.3,
        "--convention",
        &["two-sided-angular", "one-sided-cyclic", "one-sided-angular", "bogus"],
    );
    if rng.random_bool(0.3) {
        a.push("--json".into());
    }
    spectra_dir(rng, a, 0.2);
}

/// A run file input: mostly whole, else damaged or of another kind.
const RUN_INPUTS: [&str; 10] = [
    "<run:in.h5>",
    "<run:in.h5>",
    "<run:in.h5>",
    "<run-damaged:in.h5>",
    "<run-truncated:in.h5>",
    "<junk:in.h5>",
    "<empty:in.h5>",
    "<fifo:in.h5>",
    "<dir:in.h5>",
    "<missing:in.h5>",
];

fn plot_args(corpus: &Corpus, rng: &mut Rng, case: &mut Case, a: &mut Vec<String>) {
    let input = if rng.random_bool(0.55) {
        scenario_file(corpus, rng, case);
        "<file>"
    } else if rng.random_bool(0.85) {
        pick(rng, &RUN_INPUTS)
    } else {
        pick(
            rng,
            &[
                "<copy:profile.csv>",
                "<fifo:in.toml>",
                "<dir:in.toml>",
                "<missing:in.toml>",
            ],
        )
    };
    a.push(input.into());
    a.push("-o".into());
    let outs = [
        "<new:pictures>",
        "<new:pictures>",
        "<dir:pictures>",
        "<copy:profile.csv>",
        "<fifo:pictures>",
        "<device:pictures>",
        "<missing:pictures/deeper>",
        "<file>",
        "<run:run.h5>",
    ];
    a.push(pick(rng, &outs).into());
    maybe(
        rng,
        a,
        0.3,
        "--convention",
        &[
            "one-sided-cyclic",
            "two-sided-angular",
            "one-sided-angular",
            "bogus",
            "",
        ],
    );
    spectra_dir(rng, a, 0.1);
}

fn report_args(corpus: &Corpus, rng: &mut Rng, case: &mut Case, a: &mut Vec<String>) {
    let input = match rng.random_range(0..10) {
        0..=5 => {
            scenario_file(corpus, rng, case);
            "<file>"
        }
        6 => "<workday>",
        _ => pick(rng, &RUN_INPUTS),
    };
    a.push(input.into());
    if rng.random_bool(0.2) {
        a.push("--run".into());
        a.push(
            pick(
                rng,
                &[
                    "<run:run.h5>",
                    "<run-damaged:run.h5>",
                    "<file>",
                    "<junk:run.h5>",
                    "<missing:run.h5>",
                ],
            )
            .into(),
        );
    }
    a.push("-o".into());
    let outs = [
        "<new:report.html>",
        "<new:report.html>",
        "<new:report.md>",
        "<report:report.html>",
        "<file>",
        "<run:out.h5>",
        "<fifo:report.html>",
        "<device:report.html>",
        "<dir:report.html>",
        "<copy:profile.csv>",
        "<missing:report.html>",
    ];
    a.push(pick(rng, &outs).into());
    maybe(rng, a, 0.4, "--format", &["html", "markdown", "markdown", "pdf", ""]);
    if rng.random_bool(0.35) {
        a.push("--overwrite".into());
    }
    spectra_dir(rng, a, 0.05);
}

fn inspect_args(rng: &mut Rng, cmd: &str, a: &mut Vec<String>) {
    let extra = ["<copy:profile.csv>", "<run-raw:in.h5>", "<run-raw-damaged:in.h5>"];
    a.push(
        if rng.random_bool(0.8) {
            pick(rng, &RUN_INPUTS)
        } else {
            pick(rng, &extra)
        }
        .into(),
    );
    if cmd == "check-run" {
        if rng.random_bool(0.5) {
            a.push("--full".into());
        }
    } else {
        match rng.random_range(0..6) {
            0 => a.push("--json".into()),
            1 => a.extend([
                "--format".into(),
                pick(rng, &["text", "markdown", "json", "bogus"]).into(),
            ]),
            2 => a.extend(["--json".into(), "--format".into(), "markdown".into()]),
            _ => {}
        }
    }
}

fn catalogue_args(rng: &mut Rng, cmd: &str, a: &mut Vec<String>) {
    match cmd {
        "book" => {
            if rng.random_bool(0.5) {
                a.push("--json".into());
            }
            if rng.random_bool(0.3) {
                a.push("--plots".into());
                let t = [
                    "<new:pictures>",
                    "<dir:pictures>",
                    "<copy:profile.csv>",
                    "<fifo:pictures>",
                    "<missing:a/b>",
                ];
                a.push(pick(rng, &t).into());
                spectra_dir(rng, a, 0.4);
            }
        }
        "spectra" => {
            match rng.random_range(0..5) {
                0 => a.push("--json".into()),
                1 => a.push("--full".into()),
                2 => a.extend(["--json".into(), "--full".into()]),
                _ => {}
            }
            spectra_dir(rng, a, 0.5);
        }
        _ => {
            if rng.random_bool(0.5) {
                a.push("--json".into());
            }
        }
    }
}

// ------------------------------------------------------------------------------------------------------
// The case's files
// ------------------------------------------------------------------------------------------------------

/// One file or directory a case made.
#[derive(Debug, Clone)]
struct Made {
    /// The token's kind (`new`, `run`, `fifo`, …).
    kind: String,
    path: PathBuf,
    /// Whether it is an output target (after `-o`, `--plots`).
    target: bool,
}

/// The case's arguments with their tokens made into files under `dir`.
struct Materialized {
    args: Vec<String>,
    made: Vec<Made>,
}

/// A type and (for a regular file) the bytes of `p`.
fn snapshot(p: &Path) -> (String, Vec<u8>) {
    match std::fs::symlink_metadata(p) {
        Err(_) => ("absent".into(), vec![]),
        Ok(m) if m.is_file() => ("file".into(), std::fs::read(p).unwrap_or_default()),
        Ok(m) if m.is_dir() => ("dir".into(), {
            let mut names: Vec<String> = std::fs::read_dir(p)
                .map(|d| {
                    d.flatten()
                        .map(|e| e.file_name().to_string_lossy().into_owned())
                        .collect()
                })
                .unwrap_or_default();
            names.sort();
            names.join("\n").into_bytes()
        }),
        Ok(m) => (format!("{:?}", m.file_type()), vec![]),
    }
}

/// A character device node like `/dev/null` (major 1, minor 3) at `p` (we run as root; otherwise a FIFO).
fn mknod(p: &Path) {
    let c = std::ffi::CString::new(p.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    let r = unsafe { libc::mknod(c.as_ptr(), libc::S_IFCHR | 0o600, libc::makedev(1, 3)) };
    if r != 0 {
        super::input_campaign::mkfifo(p);
    }
}

/// A run file with raw data (`store_raw`) of the conveyor idler under the fixtures, made once.
fn raw_fixture(ctx: &super::commands::Context) -> PathBuf {
    let p = ctx.fixtures.join("cli-raw.h5");
    if p.is_file() {
        return p;
    }
    let sc = stochvib::scenario::load_scenario(&ctx.root.join("data/conveyor-idler.toml"), &ctx.root.join("spectra"))
        .expect("the shipped conveyor idler");
    let opts = stochvib::simulate::RunOptions {
        realizations: 4,
        duration_s: 2.0,
        dt_s: 0.01,
        store_raw: true,
        ..Default::default()
    };
    let tmp = ctx.fixtures.join(format!("cli-raw-{}.h5", std::process::id()));
    let _ = std::fs::remove_file(&tmp);
    sc.simulate(&opts, &tmp, &|_, _| {}).expect("the raw fixture run");
    std::fs::rename(&tmp, &p).unwrap();
    p
}

/// Makes the file of one token under `dir`.
fn make(kind: &str, name: &str, dir: &Path, case_file: &Path, ctx: &super::commands::Context) -> PathBuf {
    let p = dir.join(name);
    let whole = ctx.fixtures.join("whole.h5");
    let copy = |from: &Path| {
        std::fs::copy(from, &p).unwrap_or_else(|e| panic!("{}: {e}", from.display()));
    };
    match kind {
        "new" => {}
        "missing" => return dir.join("no-such-dir").join(name),
        "run" => copy(&whole),
        "run-damaged" => {
            copy(&whole);
            super::commands::damage_accumulator(&p, 5);
        }
        "run-truncated" => {
            copy(&whole);
            let len = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
            std::fs::OpenOptions::new()
                .write(true)
                .open(&p)
                .and_then(|f| f.set_len(len / 2))
                .unwrap();
        }
        "run-raw" | "run-raw-damaged" => {
            copy(&raw_fixture(ctx));
            if kind == "run-raw-damaged" {
                damage_raw(&p);
            }
        }
        "junk" => std::fs::write(&p, b"not a run file\n").unwrap(),
        "empty" => std::fs::write(&p, b"").unwrap(),
        "fifo" => super::input_campaign::mkfifo(&p),
        "device" => mknod(&p),
        "dir" => std::fs::create_dir_all(&p).unwrap(),
        "copy" if name == "profile.csv" => copy(&ctx.root.join("data/measured-profile.csv")),
        "copy" => std::fs::write(&p, b"# a file that is no spectrum directory\n").unwrap(),
        "tmp-garbage" => std::fs::write(stochvib::store::tmp_path(&p), b"garbage of an interrupted run\n").unwrap(),
        "tmp-run" => std::fs::copy(&whole, stochvib::store::tmp_path(&p))
            .map(|_| ())
            .unwrap(),
        "report" => std::fs::write(&p, b"<html><body>an earlier report</body></html>\n").unwrap(),
        "spectra" => return ctx.root.join("spectra"),
        "spectra-bad" => {
            std::fs::create_dir_all(&p).unwrap();
            for f in ["iso8608-c.toml", "book-8-45.toml"] {
                let _ = std::fs::copy(ctx.root.join("spectra").join(f), p.join(f));
            }
            std::fs::write(p.join("broken.toml"), b"kind = \"rational\"\nnumerator = [1.0\n").unwrap();
        }
        "workday" => {
            let w = std::fs::read_to_string(ctx.root.join("data/workday/scraper-operator.toml")).unwrap_or_default();
            let abs = ctx.root.join("data/workday").display().to_string();
            std::fs::write(&p, w.replace("scenario = \"", &format!("scenario = \"{abs}/"))).unwrap();
        }
        "file" => return case_file.to_path_buf(),
        _ => panic!("unknown token kind {kind}"),
    }
    p
}

/// Flips a bit of a sample of the first realization of the first raw output of `file` whose 8 bytes occur
/// once in the file (the raw datasets are chunked: found by value, not by offset; a checksum must find it).
fn damage_raw(file: &Path) {
    let values = stochvib::store::RunFile::open(file).ok().and_then(|run| {
        let name = run.metadata().outputs.first()?.name.clone();
        run.read_signal(stochvib::store::SignalGroup::Outputs, &name, 0).ok()
    });
    let mut b = std::fs::read(file).unwrap();
    let at = values.iter().flatten().find_map(|v| {
        let k = v.to_le_bytes();
        let mut hits = b.windows(8).enumerate().filter(|(_, w)| *w == k).map(|(i, _)| i);
        let first = hits.next()?;
        hits.next().is_none().then_some(first)
    });
    if let Some(at) = at {
        b[at + 3] ^= 0x10;
        std::fs::write(file, b).unwrap();
    }
}

/// The case's tokens made into files under `dir` (emptied first).
fn materialize(dir: &Path, case_file: &Path, args: &[String], ctx: &super::commands::Context) -> Materialized {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).unwrap();
    let mut out = Materialized {
        args: Vec::new(),
        made: Vec::new(),
    };
    for (k, a) in args.iter().enumerate() {
        let Some(tok) = a.strip_prefix('<').and_then(|t| t.strip_suffix('>')) else {
            out.args.push(a.clone());
            continue;
        };
        let (kind, name) = tok.split_once(':').unwrap_or((tok, tok));
        let target = k > 0 && matches!(args[k - 1].as_str(), "-o" | "--plots");
        let existing = out
            .made
            .iter()
            .find(|m| m.kind == kind && m.path.ends_with(name) && kind != "file");
        let path = match existing {
            Some(m) => m.path.clone(),
            None => make(kind, name, dir, case_file, ctx),
        };
        out.args.push(path.display().to_string());
        out.made.push(Made {
            kind: kind.into(),
            path,
            target,
        });
    }
    out
}

/// The CLI binary: `STOCHVIB_FUZZ_BIN`, else the one Cargo built beside the executable that runs the cases
/// (`<target>/<profile>/stochvib` for `<target>/<profile>/deps/<test or example>`).
fn bin() -> PathBuf {
    std::env::var_os("STOCHVIB_FUZZ_BIN")
        .map(PathBuf::from)
        .or_else(|| {
            let exe = std::env::current_exe().ok()?;
            Some(exe.parent()?.parent()?.join("stochvib"))
        })
        .expect("no CLI binary: set STOCHVIB_FUZZ_BIN")
}

// ------------------------------------------------------------------------------------------------------
// Evaluation and invariants
// ------------------------------------------------------------------------------------------------------

/// Runs the case whose file is at `path` through the CLI with the time limit `limit`: its outcome; the
/// file system's findings go to [`FS_FINDINGS`] for [`check`].
pub fn evaluate(
    path: &Path,
    args: &[String],
    ctx: &super::commands::Context,
    limit: Duration,
    stage: &AtomicU8,
) -> Outcome {
    stage.store(1, Ordering::SeqCst);
    let dir = path.parent().unwrap_or(Path::new(".")).join("cli-set");
    let m = materialize(&dir, path, args, ctx);
    let watched: Vec<(Made, (String, Vec<u8>))> = m.made.iter().map(|x| (x.clone(), snapshot(&x.path))).collect();
    let before_tmp = tmp_files(&dir);
    let mut cmd = std::process::Command::new(bin());
    cmd.args(&m.args).current_dir(&dir).env("NO_COLOR", "1");
    stage.store(2, Ordering::SeqCst);
    let out = super::process::run(cmd, limit, super::process::DEFAULT_MEMORY_LIMIT);
    stage.store(3, Ordering::SeqCst);
    let mut f = fs_findings(args, &m, &watched, &before_tmp, &dir, &out);
    f.extend(message_findings(args, &m, &out));
    if let Ok(mut g) = FS_FINDINGS.lock() {
        g.insert(path.to_path_buf(), f);
    }
    stage.store(4, Ordering::SeqCst);
    outcome(&out, limit)
}

/// The outcome of a CLI run in the harness's terms.
fn outcome(out: &super::process::Output, limit: Duration) -> Outcome {
    use super::process::Exit;
    let first_err = out
        .stderr
        .lines()
        .find(|l| l.starts_with("error"))
        .unwrap_or("")
        .to_string();
    let failure = |variant: &str| {
        Outcome::Err(Failure {
            variant: variant.into(),
            message: first_err.clone(),
            file: None,
            key: None,
            value: None,
            stage: "cli".into(),
        })
    };
    match out.exit {
        Exit::Timeout => Outcome::Timeout {
            stage: "cli".into(),
            limit_ms: limit.as_millis() as u64,
        },
        Exit::Code(101) => {
            let at = out.stderr.split("panicked at ").nth(1).unwrap_or("");
            Outcome::Panic {
                location: at.split([':', '\n']).take(3).collect::<Vec<_>>().join(":"),
                message: super::process::tail(&out.stderr, 300),
                stage: "cli".into(),
            }
        }
        Exit::Signal(s) => failure(&format!("Signal {}", super::process::signal_name(s))),
        Exit::Code(0) => Outcome::Ok(Success {
            what: "cli".into(),
            non_finite: super::inputs::non_finite_tokens(&out.stdout, b"")
                .into_iter()
                .map(|t| ("stdout".to_string(), t))
                .collect(),
            outputs: vec![],
            system_outputs: vec![],
            empty: false,
        }),
        Exit::Code(2) => failure("Clap"),
        Exit::Code(1) => failure("Cli"),
        Exit::Code(c) => failure(&format!("Exit {c}")),
    }
}

/// The `.tmp` files under `dir` (one level of subdirectories).
fn tmp_files(dir: &Path) -> Vec<PathBuf> {
    let mut v = Vec::new();
    let mut walk = vec![dir.to_path_buf()];
    while let Some(d) = walk.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if e.file_type().is_ok_and(|t| t.is_dir()) && d == dir {
                walk.push(p);
            } else if p.to_string_lossy().ends_with(".tmp") {
                v.push(p);
            }
        }
    }
    v.sort();
    v
}

fn finding(class: &str, signature: String, detail: String) -> Finding {
    Finding {
        class: class.into(),
        signature,
        detail,
    }
}

/// Whether the target `m` of command `cmd` is of the kind the command writes: a new path or (with
/// `--overwrite`) an earlier output of its kind.
fn legit_target(cmd: &str, m: &Made, overwrite: bool) -> bool {
    let dir_writer = cmd == "plot" || cmd == "book" || m.path.ends_with("pictures");
    match m.kind.as_str() {
        "new" | "tmp-garbage" | "tmp-run" => true,
        "dir" | "missing" if dir_writer => true, // a picture directory is created with its parents
        "dir" => cmd == "simulate" && m.path.ends_with("shards"),
        "run" => cmd == "simulate" && overwrite,
        "report" => cmd == "report" && overwrite,
        _ => false,
    }
}

fn fs_findings(
    args: &[String],
    m: &Materialized,
    watched: &[(Made, (String, Vec<u8>))],
    before_tmp: &[PathBuf],
    dir: &Path,
    out: &super::process::Output,
) -> Vec<Finding> {
    let cmd = args[0].as_str();
    let ok = matches!(out.exit, super::process::Exit::Code(0));
    if matches!(out.exit, super::process::Exit::Timeout) {
        // killed by the harness: what it leaves is the kill's, and the timeout is the finding
        return Vec::new();
    }
    let overwrite = args.iter().any(|a| a == "--overwrite");
    let mut f = Vec::new();
    for (made, before) in watched {
        if made.kind == "spectra" {
            continue;
        }
        let changed = snapshot(&made.path) != *before;
        let is_input = m.made.iter().any(|x| x.path == made.path && !x.target);
        if is_input && changed {
            f.push(finding(
                "destroyed-input",
                format!("{cmd} changes its input ({})", made.kind),
                format!("{} {}", made.path.display(), mutate::short(&out.stderr)),
            ));
        } else if made.target && !legit_target(cmd, made, overwrite) && (ok || changed) {
            f.push(finding(
                "output-rule",
                format!(
                    "{cmd} {} a target of kind {}",
                    if ok { "accepts" } else { "changes" },
                    made.kind
                ),
                format!("{} {}", made.path.display(), mutate::short(&out.stderr)),
            ));
        } else if made.target && !ok && changed && !matches!(made.kind.as_str(), "tmp-garbage" | "tmp-run") {
            f.push(finding(
                "half-written",
                format!("{cmd} fails and leaves its target {} changed", made.kind),
                format!("{} {}", made.path.display(), mutate::short(&out.stderr)),
            ));
        }
    }
    if !ok {
        let new_tmp: Vec<_> = tmp_files(dir).into_iter().filter(|p| !before_tmp.contains(p)).collect();
        if let Some(p) = new_tmp.first() {
            f.push(finding(
                "half-written",
                format!("{cmd} fails and leaves a new .tmp"),
                format!("{} {}", p.display(), mutate::short(&out.stderr)),
            ));
        }
    } else {
        f.extend(output_findings(cmd, m, out));
        if let Some(why) = hostile(args, m) {
            f.push(finding(
                "hostile-accepted",
                format!("{cmd} accepts {why}"),
                mutate::short_to(&args.join(" "), 300),
            ));
        }
    }
    f
}

/// What a successful command wrote, checked.
fn output_findings(cmd: &str, m: &Materialized, out: &super::process::Output) -> Vec<Finding> {
    let mut f = Vec::new();
    let target = m.made.iter().find(|x| x.target && !x.path.ends_with("pictures"));
    let bad = |what: String| {
        finding(
            "bad-output",
            format!("{cmd} succeeds and {what}"),
            mutate::short(&out.stderr),
        )
    };
    match (cmd, target) {
        ("simulate", Some(t)) if !m.args.iter().any(|a| a == "--shard") => {
            let r = stochvib::store::RunFile::open(&t.path).and_then(|r| {
                r.verify()?;
                r.statistics()
            });
            match r {
                Err(e) => f.push(bad(format!(
                    "its run file does not verify: {}",
                    super::inputs::normalize_message(&e.to_string())
                ))),
                Ok(s) if super::floats::non_finite(&s).is_empty() => {}
                Ok(_) => f.push(bad("its run file holds a non-finite statistic".into())),
            }
        }
        ("report", Some(t)) if std::fs::metadata(&t.path).map_or(true, |x| x.len() == 0) => {
            f.push(bad("its report is missing or empty".into()))
        }
        _ => {}
    }
    if cmd == "plot" {
        let missing = out
            .stdout
            .lines()
            .filter(|l| !l.trim().is_empty())
            .find(|l| !Path::new(l.trim()).is_file());
        if let Some(l) = missing {
            f.push(bad(format!("lists a picture that is not there ({})", mutate::short(l))));
        }
    }
    f
}

/// Why the arguments must be refused, if they must.
fn hostile(args: &[String], m: &Materialized) -> Option<String> {
    let val = |name: &str| args.windows(2).rev().find(|w| w[0] == name).map(|w| w[1].as_str());
    let num = |name: &str| val(name).and_then(|v| v.parse::<f64>().ok());
    let cmd = args[0].as_str();
    let run_value = val("--run").map(str::to_string);
    let damaged = m.made.iter().any(|x| {
        let p = x.path.display().to_string();
        (m.args.get(1) == Some(&p) || run_value.is_some() && m.args.windows(2).any(|w| w[0] == "--run" && w[1] == p))
            && matches!(
                x.kind.as_str(),
                "run-damaged" | "run-truncated" | "junk" | "empty" | "fifo" | "dir" | "missing" | "run-raw-damaged"
            )
    });
    // `check-run` without `--full` checks that the file reads, not its checksums (inspect, plot and report
    // run it with `--full`)
    let checksums_only = m
        .made
        .iter()
        .any(|x| matches!(x.kind.as_str(), "run-damaged" | "run-raw-damaged"))
        && cmd == "check-run"
        && !args.iter().any(|a| a == "--full");
    if damaged && matches!(cmd, "plot" | "report" | "inspect" | "check-run") && !checksums_only {
        return Some("a damaged or special input".into());
    }
    if cmd == "report"
        && m.made.iter().any(|x| x.target && x.kind == "report")
        && !args.iter().any(|a| a == "--overwrite")
    {
        return Some("an existing report without --overwrite".into());
    }
    if cmd == "spectrum"
        && ["--omega", "--frequency"].iter().any(|f| {
            val(f).is_some_and(|v| {
                v.split(',')
                    .any(|x| x.parse::<f64>().map_or(true, |x| !(x.is_finite() && x >= 0.0)))
            })
        })
    {
        return Some("a density point that is no finite frequency >= 0".into());
    }
    if cmd == "analyze" && num("--monte-carlo").is_some_and(|n| n < 2.0) {
        return Some("a Monte Carlo batch of fewer than 2 realizations".into());
    }
    if cmd == "analyze" && num("--rel-tol").is_some_and(|x| !(x.is_finite() && x > 0.0)) {
        return Some("a non-positive --rel-tol".into());
    }
    if cmd == "analyze" && val("--monte-carlo").is_some() {
        for flag in ["--dt", "--duration", "--max-hours"] {
            if num(flag).is_some_and(|x| !(x.is_finite() && x > 0.0)) {
                return Some(format!("{flag} {}", val(flag).unwrap_or("")));
            }
        }
    }
    if cmd != "simulate" {
        return None;
    }
    if num("--realizations").is_some_and(|n| n < 2.0) {
        return Some("fewer than 2 realizations".into());
    }
    for flag in ["--dt", "--duration", "--max-hours"] {
        if num(flag).is_some_and(|x| !(x.is_finite() && x > 0.0)) {
            return Some(format!("{flag} {}", val(flag).unwrap_or("")));
        }
    }
    if num("--confidence").is_some_and(|c| !(c > 0.0 && c < 1.0)) {
        return Some("a confidence outside (0, 1)".into());
    }
    if num("--shard-size") == Some(0.0) || num("--of") == Some(0.0) {
        return Some("a count of 0".into());
    }
    if let (Some(i), Some(n)) = (num("--shard"), num("--of"))
        && i >= n
    {
        return Some("a shard outside --of".into());
    }
    None
}

/// The findings of the messages of a CLI run: a failure names a flag or a file of the case, in a bounded
/// message; a success prints no NaN or infinity.
fn message_findings(args: &[String], m: &Materialized, out: &super::process::Output) -> Vec<Finding> {
    use super::process::Exit;
    let cmd = args[0].as_str();
    let mut f = Vec::new();
    if out.stderr.len() > super::commands::MAX_STDERR {
        f.push(finding(
            "cli-flood",
            format!("{cmd} writes more than 64 KiB of stderr"),
            String::new(),
        ));
    }
    let first_err = out.stderr.lines().find(|l| l.starts_with("error")).unwrap_or("");
    if first_err.len() > super::commands::MAX_MESSAGE {
        f.push(finding(
            "long-message",
            format!("{cmd}: an error line of {} bytes", first_err.len()),
            String::new(),
        ));
    }
    match out.exit {
        Exit::Code(1) => {
            let names_file = m.made.iter().any(|x| {
                out.stderr.contains(&x.path.display().to_string())
                    || x.path
                        .file_name()
                        .is_some_and(|n| out.stderr.contains(&*n.to_string_lossy()))
            });
            let names_flag = out.stderr.contains("--");
            // a positional argument typed by the user (a catalogue name), quoted as typed
            // (an empty one is named by its role: "`spectrum` = :")
            let names_positional = args.get(1).is_some_and(|a| {
                (!a.is_empty() && !a.starts_with('<') && !a.starts_with('-') && first_err.contains(a.as_str()))
                    || (a.is_empty() && first_err.contains("` = :"))
            });
            if first_err.is_empty() || !(names_file || names_flag || names_positional) {
                f.push(finding(
                    "cli-error-message",
                    format!(
                        "{cmd} fails without naming a file or a flag: {}",
                        super::inputs::normalize_message(first_err)
                    ),
                    mutate::short(first_err),
                ));
            }
        }
        Exit::Code(0 | 2 | 101) | Exit::Timeout | Exit::Signal(_) => {}
        Exit::Code(c) => f.push(finding(
            "cli-exit-code",
            format!("{cmd} exit code {c}"),
            mutate::short(first_err),
        )),
    }
    f
}

/// The findings of a case's evaluation at `path`.
pub fn check(case: &Case, path: &Path, outcome: &Outcome) -> Vec<Finding> {
    let cmd = case.args[0].as_str();
    let mut f = FS_FINDINGS
        .lock()
        .ok()
        .and_then(|mut g| g.remove(path))
        .unwrap_or_default();
    match outcome {
        Outcome::Panic { location, message, .. } => f.push(finding(
            "cli-panic",
            format!("{cmd} panicked at {location}"),
            mutate::short_to(message, 240),
        )),
        Outcome::Timeout { limit_ms, .. } => f.push(finding(
            "timeout",
            format!("timeout of {cmd}"),
            format!("no result after {limit_ms} ms"),
        )),
        Outcome::Err(e) if e.variant.starts_with("Signal") => f.push(finding(
            "cli-crash",
            format!("{cmd} killed by {}", e.variant),
            mutate::short(&e.message),
        )),
        Outcome::Ok(s) => {
            for (_, v) in &s.non_finite {
                f.push(finding("cli-non-finite", format!("{cmd} prints {v}"), case.describe()));
            }
        }
        Outcome::Err(_) => {}
    }
    f
}

/// A command line for the reproducers.
pub fn command_line(case: &Case, file: &str) -> String {
    let a: Vec<String> = case
        .args
        .iter()
        .map(|a| if a == "<file>" { file.to_string() } else { a.clone() })
        .collect();
    format!(
        "stochvib {} (tokens <kind:name> are files the harness makes)",
        a.join(" ")
    )
}
