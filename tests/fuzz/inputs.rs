//! Input-file cases: the corpus of shipped files, the generation of case `i` of seed `s`, its evaluation
//! through the library's public entry points, and the invariants.
//!
//! # Invariants (each violation is a finding of the named class)
//! * `panic` — no entry point panics (caught by `catch_unwind`; the location comes from a panic hook).
//! * `timeout` — every case finishes within the per-case time limit (`crash`, from the supervisor: the
//!   worker process must not die, e.g. by a stack overflow or a failed allocation).
//! * An error must name the file: [`Error::File`] with the case's file and a non-empty key, or
//!   [`Error::Parse`]/[`Error::Io`] with the case's file. Any other variant escaping an entry point is
//!   `error-without-file-key`; a different file is `error-wrong-file`.
//! * `phantom-key` — the key an [`Error::File`] names exists in the document, unless its value is
//!   `<missing>` (a required key that is absent). `missing-but-present` — the error says `<missing>` for a
//!   key that is there.
//! * A success prints no non-finite number as a result (`non-finite-result`). "A result" is every `f64`
//!   of the report the CLI prints (`AnalysisReport`, `TablesReport`, `SpectrumReport`: statistics,
//!   bounds, rates, method values, densities, correlation values, table cells, and the echoed inputs such
//!   as levels, band and duration): a quantity that does not exist must be a `None` / `NoValue` with its
//!   reason, never NaN or ±∞. The walk goes through serde (`floats::non_finite`), because the JSON shows
//!   NaN and `None` alike as `null`.
//! * `empty-result` — a success reports something: at least one output for a stochastic scenario, at
//!   least one table with a row for a deterministic model or a reference table.
//! * `duplicate-output` — the outputs of a report, and the outputs of a scenario's system, have distinct
//!   names.
//! * `must_reject` classes (`typo-accepted`, `unknown-key-accepted`, `wrong-unit-accepted`,
//!   `unknown-unit-accepted`, `non-finite-accepted`, `wrong-type-accepted`) — a document that contains a
//!   mutation no correct reader may accept is refused (any error counts).
//! * `unbounded-read` — an input is not read without bound: an error that only came because memory ran
//!   out (the harness runs everything under an address-space limit) is a finding, not a clean error.
//! * `unrelated-key` (soft, reported but not asserted) — for a single value mutation at path P that is
//!   refused, the key the error names is related to P (see [`related`]).
//!
//! The CLI run of a case (`stochvib analyze FILE`, `stochvib spectrum FILE`, as a child process with a
//! time limit) adds: `cli-timeout`, `cli-crash` (a signal), `cli-panic` (exit 101), `cli-exit-code` (not 0
//! or 1), `cli-error-message` (a failure without an `error:` line naming the file), `cli-empty-output`,
//! `cli-non-finite` (a printed `NaN`/`inf` token that is not in the input), `cli-unbounded-read`, and
//! `cli-inconsistent` (the CLI fails where the library succeeds, or the other way round).

use super::floats::non_finite;
use super::mutate::{self, all_paths, get, normalize_path, parse_path, path_str, Mutation, Rng, Seg};
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::{Arc, Mutex, Once};
use std::time::{Duration, Instant};
use stochvib::report;
use stochvib::scenario::{load_document, load_spectrum, Document};
use stochvib::simulate::splitmix64;
use stochvib::spectrum::Convention;
use stochvib::study;
use stochvib::Error;
use toml::{Table, Value};

/// Which entry points a file goes through.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum DocKind {
    /// A file of `data/` (scenario, deterministic model or reference table): `load_document` and the
    /// matching report; CLI `stochvib analyze FILE`.
    Data,
    /// A spectrum file: `load_spectrum` (`parse_spectrum`) and `spectrum_report`; CLI `stochvib spectrum
    /// FILE`.
    Spectrum,
    /// A road profile (CSV) with `road`'s options: `road_report`; CLI `stochvib road FILE …`
    /// ([`super::commands`]).
    Profile,
    /// A profile replayed through a road scenario with `replay`'s flags: `replay_scenario`; CLI `stochvib
    /// replay SCENARIO FILE …`.
    Replay,
    /// A shipped scenario with `sweep`'s `--param` grids and flags: `Sweep::new` and the first points; CLI
    /// `stochvib sweep SCENARIO --param …`.
    Sweep,
    /// A set of run or sweep shard files and a merged-file target: `merge_runs` / `merge_sweep`; CLI
    /// `stochvib merge OUT FILES…`.
    Merge,
    /// A workday file: `load_workday` and `workday_exposure`; CLI `stochvib workday FILE`.
    Workday,
    /// A measured record or profile through a record command (`exposure`, `fatigue`, `coherence`, `iri`,
    /// `weighting`) with its flags ([`super::records`]).
    Record,
    /// A scenario with `[[model.nonlinear]]` elements whose element tables are mutated (or an element
    /// added to a linear model of coordinates): as [`DocKind::Data`].
    Nonlinear,
    /// A scenario with a `[transient]` section whose non-stationary keys are mutated, through the exact
    /// route and sometimes a small Monte Carlo run ([`super::transient`]); CLI `stochvib transient FILE`.
    Transient,
    /// A shipped scenario with `optimize`'s flags (parameters and bounds, objective, constraints, starts)
    /// ([`super::optimize`]); CLI `stochvib optimize SCENARIO --param …`.
    Optimize,
    /// `stochvib simulate` with hostile flags and output targets, run through the CLI
    /// ([`super::cli_commands`]).
    Simulate,
    /// `stochvib plot` of a (mutated) scenario or a run file with hostile flags and targets, through the CLI.
    Plot,
    /// `stochvib report` of a (mutated) scenario, a workday or a run file with hostile flags and targets,
    /// through the CLI.
    Report,
    /// `stochvib inspect` and `stochvib check-run` of run files whole, damaged or of another kind, through
    /// the CLI.
    Inspect,
    /// `stochvib book`, `spectra` and `models` with their flags and hostile `--spectra-dir`/`--plots`,
    /// through the CLI.
    Catalogue,
}

impl DocKind {
    /// The format or command a case exercises, for the per-format totals.
    pub fn label(self) -> &'static str {
        match self {
            DocKind::Data => "scenario TOML (analyze)",
            DocKind::Spectrum => "spectrum TOML (spectrum)",
            DocKind::Profile => "road profile CSV (road)",
            DocKind::Replay => "replay (profile + flags)",
            DocKind::Sweep => "sweep (--param grids, flags)",
            DocKind::Merge => "merge (shard sets)",
            DocKind::Workday => "workday TOML (workday)",
            DocKind::Record => "record commands (exposure, fatigue, coherence, iri, weighting)",
            DocKind::Nonlinear => "nonlinear sections ([[model.nonlinear]], analyze)",
            DocKind::Transient => "transient sections ([transient], speed profile, envelope, schedule, mission)",
            DocKind::Optimize => "optimize (--param bounds, objective, constraints)",
            DocKind::Simulate => "simulate and analyze flags (counts, steps, shards, -o targets, .tmp)",
            DocKind::Plot => "plot (scenarios, run files, flags, targets)",
            DocKind::Report => "report (scenarios, workdays, run files, flags, targets)",
            DocKind::Inspect => "inspect and check-run (run files, flags)",
            DocKind::Catalogue => "book, spectra, models, spectrum (flags, names, --spectra-dir, --plots)",
        }
    }

    /// Whether the case is run through the CLI binary only ([`super::cli_commands`]).
    pub fn is_cli_only(self) -> bool {
        matches!(
            self,
            DocKind::Simulate | DocKind::Plot | DocKind::Report | DocKind::Inspect | DocKind::Catalogue
        )
    }

    /// Whether the case is one of [`super::commands`].
    pub fn is_command(self) -> bool {
        !matches!(
            self,
            DocKind::Data | DocKind::Spectrum | DocKind::Nonlinear | DocKind::Transient
        )
    }
}

/// One shipped file.
#[derive(Debug, Clone)]
pub struct SeedDoc {
    /// Path relative to the source tree, e.g. `data/quarter-car.toml`.
    pub rel: String,
    /// Its kind.
    pub kind: DocKind,
    /// Parsed.
    pub table: Table,
}

/// The shipped files and the key vocabulary.
#[derive(Debug, Clone)]
pub struct Corpus {
    /// The source tree.
    pub root: PathBuf,
    /// `root/spectra`, the catalogue.
    pub spectra_dir: PathBuf,
    /// Every `data/*.toml`, `data/reference/*.toml`, `spectra/*.toml`.
    pub seeds: Vec<SeedDoc>,
    /// Every key of every shipped file plus [`mutate::EXTRA_KEYS`] (typos avoid them).
    pub vocabulary: Vec<String>,
    /// For each stochastic scenario (by `rel`): the unit of its input process and the (name, unit) of its
    /// system's outputs, as the library reads the unmutated file.
    pub units: BTreeMap<String, (String, Vec<(String, String)>)>,
    /// The material of the command cases ([`super::commands`]).
    pub commands: super::commands::CommandCorpus,
}

fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    v.sort();
    v
}

impl Corpus {
    /// Reads the shipped files under `root`.
    ///
    /// # Panics
    /// If a shipped file does not parse as TOML (a broken source tree, not a finding).
    pub fn load(root: &Path) -> Corpus {
        let mut seeds = Vec::new();
        for (dir, kind) in [
            ("data", DocKind::Data),
            ("data/reference", DocKind::Data),
            ("spectra", DocKind::Spectrum),
        ] {
            for p in toml_files(&root.join(dir)) {
                let text = std::fs::read_to_string(&p).unwrap();
                let table: Table = toml::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
                let rel = p.strip_prefix(root).unwrap().to_string_lossy().into_owned();
                seeds.push(SeedDoc { rel, kind, table });
            }
        }
        let mut vocabulary: Vec<String> = mutate::EXTRA_KEYS.iter().map(|s| s.to_string()).collect();
        for s in &seeds {
            for p in all_paths(&s.table) {
                if let Some(Seg::Key(k)) = p.last() {
                    vocabulary.push(k.clone());
                }
            }
        }
        vocabulary.sort();
        vocabulary.dedup();
        let mut units = BTreeMap::new();
        let mut stochastic = Vec::new();
        for s in seeds.iter().filter(|s| s.kind == DocKind::Data) {
            if let Ok(Document::Stochastic(sc)) = load_document(&root.join(&s.rel), &root.join("spectra")) {
                stochastic.push((s.rel.clone(), s.table.clone()));
                let outs = sc
                    .model
                    .system
                    .outputs()
                    .iter()
                    .map(|o| (o.name.clone(), o.unit.clone()))
                    .collect();
                units.insert(s.rel.clone(), (sc.input.unit.clone(), outs));
            }
        }
        Corpus {
            spectra_dir: root.join("spectra"),
            root: root.to_path_buf(),
            seeds,
            vocabulary,
            units,
            commands: super::commands::CommandCorpus::load(root, &stochastic),
        }
    }

    fn spectrum_table(&self, name: &str) -> Option<&Table> {
        let rel = format!("spectra/{name}.toml");
        self.seeds.iter().find(|s| s.rel == rel).map(|s| &s.table)
    }
}

/// One generated case.
#[derive(Debug, Clone)]
pub struct Case {
    /// Case number within its seed.
    pub index: u64,
    /// The shipped file it was made from.
    pub origin: String,
    /// Its kind.
    pub kind: DocKind,
    /// File name to write it under (the origin's, so that messages look as they would for a user).
    pub file_name: String,
    /// The bytes of the file.
    pub bytes: Vec<u8>,
    /// The structured mutations, in order.
    pub mutations: Vec<Mutation>,
    /// The raw (byte-level) mutations applied after serialising.
    pub raw: Vec<String>,
    /// Density convention of the spectrum report.
    pub convention: Convention,
    /// The structured document before raw mutations (for minimisation), if it serialised.
    pub doc: Option<Table>,
    /// (class, key path, key for the signature) of each mutation that a correct reader must refuse and
    /// that is still in the final document. The signature key is the original key of a rename and
    /// `<table>.<new key>` for an added key, so that random key names do not split one root cause.
    pub must_reject: Vec<(String, String, String)>,
    /// The command's arguments besides the file ([`super::commands`]: flags, the scenario of a replay or
    /// a sweep, the members of a merge set); empty for the TOML cases.
    pub args: Vec<String>,
}

impl Case {
    /// One line describing the mutations.
    pub fn describe(&self) -> String {
        let mut parts: Vec<String> = self
            .mutations
            .iter()
            .map(|m| format!("{} {} {}", m.op, m.path, m.detail).trim().to_string())
            .collect();
        parts.extend(self.raw.iter().cloned());
        if !self.args.is_empty() {
            parts.push(format!("args {}", mutate::short_to(&self.args.join(" "), 200)));
        }
        format!("{} ← {}", self.origin, parts.join("; "))
    }
}

/// The generator of case `index` of `seed` (independent of every other case).
pub fn case_rng(seed: u64, index: u64) -> Rng {
    Rng::seed_from_u64(splitmix64(seed ^ splitmix64(index ^ 0x5eed_f00d)))
}

fn same_value(a: &Value, b: &Value) -> bool {
    a.to_string() == b.to_string()
}

/// Case `index` of `seed`: a shipped file, 0–3 structured mutations, sometimes a raw one.
pub fn generate(corpus: &Corpus, seed: u64, index: u64) -> Case {
    if let Some(c) = added_family(corpus, seed, index)
        .or_else(|| later_family(corpus, seed, index))
        .or_else(|| cli_family(corpus, seed, index))
    {
        return c;
    }
    let mut rng = case_rng(seed, index);
    if let Some(c) = super::commands::generate(corpus, &mut rng, index) {
        return c;
    }
    let data: Vec<&SeedDoc> = corpus.seeds.iter().filter(|s| s.kind == DocKind::Data).collect();
    let spectra: Vec<&SeedDoc> = corpus.seeds.iter().filter(|s| s.kind == DocKind::Spectrum).collect();
    let origin = if rng.random_bool(0.65) {
        data[rng.random_range(0..data.len())]
    } else {
        spectra[rng.random_range(0..spectra.len())]
    };
    let mut doc = origin.table.clone();
    let mut mutations = Vec::new();
    // Inline the catalogue spectrum of a scenario, so that inline spectra are mutated too.
    if origin.kind == DocKind::Data && rng.random_bool(0.15) {
        let name = get(&doc, &[Seg::Key("input".into()), Seg::Key("spectrum".into())])
            .and_then(|v| v.as_str())
            .map(str::to_string);
        if let Some(t) = name.as_deref().and_then(|n| corpus.spectrum_table(n))
            && let Some(Value::Table(input)) = doc.get_mut("input")
        {
            input.insert("spectrum".into(), Value::Table(t.clone()));
            mutations.push(Mutation {
                op: "inline-spectrum".into(),
                path: "input.spectrum".into(),
                detail: format!("the table of spectra/{}.toml", name.unwrap_or_default()),
                must_reject: None,
                witness: None,
            });
        }
    }
    // Optional keys of [input] and [analysis] with hostile values (the shipped files rarely have them).
    if let Some((unit, outs)) = corpus.units.get(&origin.rel)
        && rng.random_bool(0.25)
        && let Some(m) = add_optional(&mut rng, &mut doc, unit, outs)
    {
        mutations.push(m);
    }
    let pure_raw = rng.random_bool(0.05);
    let n = if pure_raw {
        0
    } else {
        match rng.random_range(0..100) {
            0..=59 => 1,
            60..=84 => 2,
            _ => 3,
        }
    };
    let mut done = 0;
    for _ in 0..n * 5 {
        if done == n {
            break;
        }
        if let Some(m) = mutate::mutate_once(&mut rng, &mut doc, &corpus.vocabulary) {
            mutations.push(m);
            done += 1;
        }
    }
    finish(&mut rng, index, &origin.rel, origin.kind, doc, mutations, pure_raw)
}

/// A case of the families added after the campaigns of seeds 2828–2833 (record commands 6 %, nonlinear
/// sections 6 %), drawn from a stream of its own: every other case of a seed is the case it was, so a
/// reproducer of those campaigns still regenerates from its seed and number.
fn added_family(corpus: &Corpus, seed: u64, index: u64) -> Option<Case> {
    let mut rng = case_rng(seed ^ 0xfa31_17e5_0000_0000, index);
    match rng.random_range(0..100) {
        0..=5 => Some(super::commands::record(corpus, &mut rng, index)),
        6..=11 => {
            let (origin, doc, mutations) = super::nonlinear::mutated(corpus, &mut rng)?;
            Some(finish(
                &mut rng,
                index,
                &origin,
                DocKind::Nonlinear,
                doc,
                mutations,
                false,
            ))
        }
        _ => None,
    }
}

/// A case of the families added after the campaigns of seeds 2834–2835 (`transient` 1.5 %, `optimize`
/// 1.5 %), drawn from a stream of its own and only where [`added_family`] has no case: every other case of a
/// seed is the case it was.
fn later_family(corpus: &Corpus, seed: u64, index: u64) -> Option<Case> {
    let mut rng = case_rng(seed ^ 0x7a45_1e47_0000_0000, index);
    match rng.random_range(0..1000) {
        0..=14 => {
            let (origin, doc, mutations, name) = super::transient::mutated(corpus, &mut rng)?;
            let mut c = finish(&mut rng, index, &origin, DocKind::Transient, doc, mutations, false);
            c.file_name = name;
            Some(c)
        }
        15..=29 => Some(super::commands::optimize(corpus, &mut rng, index)),
        _ => None,
    }
}

/// A case of the families added after the campaigns of seeds 2836–2837 (the CLI-only commands of
/// [`super::cli_commands`]: `simulate` 1 %, `analyze` with flags 0.5 %, `spectrum` with flags 0.3 %, `plot`
/// 0.6 %, `report` 0.5 %, `inspect` and `check-run` 0.4 % each, `book`, `spectra`, `models` 0.2 % each: 4.3 %
/// in all), drawn from a stream of its own and only where the
/// earlier families have no case: every other case of a seed is the case it was.
fn cli_family(corpus: &Corpus, seed: u64, index: u64) -> Option<Case> {
    let mut rng = case_rng(seed ^ 0xc11f_a317_0000_0000, index);
    // shares in ‰, in the order of super::cli_commands::COMMANDS
    const SHARES: [u32; 10] = [10, 5, 3, 6, 5, 4, 4, 2, 2, 2];
    let mut r = rng.random_range(0..1000u32);
    let which = SHARES.iter().position(|&s| {
        let hit = r < s;
        r = r.saturating_sub(s);
        hit
    })?;
    Some(super::cli_commands::case(corpus, &mut rng, index, which))
}

/// Case `index` from a mutated document: serialised, sometimes mutated byte-wise (always when
/// `pure_raw`), with the `must_reject` expectations that still hold in the final document.
fn finish(
    rng: &mut Rng,
    index: u64,
    origin: &str,
    kind: DocKind,
    doc: Table,
    mutations: Vec<Mutation>,
    pure_raw: bool,
) -> Case {
    let (mut bytes, doc) = match toml::to_string(&doc) {
        Ok(t) => (t.into_bytes(), Some(doc)),
        Err(e) => (
            format!("# toml could not serialise the mutated tree: {e}\n").into_bytes(),
            None,
        ),
    };
    let mut raw = Vec::new();
    if pure_raw || rng.random_bool(0.12) {
        raw.push(mutate::mutate_bytes(rng, &mut bytes));
    }
    // The expectations that still hold in the final document (a later mutation may have undone one).
    let mut must_reject = Vec::new();
    if raw.is_empty()
        && let Some(d) = &doc
    {
        for (i, m) in mutations.iter().enumerate() {
            if let (Some(class), Some((p, v))) = (&m.must_reject, &m.witness)
                && get(d, p).is_some_and(|x| same_value(x, v))
                && mutate::expectation_holds(&mutations, i)
            {
                let sig = match m.op.as_str() {
                    "rename" => m.path.clone(),
                    "add-key" => {
                        let parent = path_str(&p[..p.len() - 1]);
                        if parent.is_empty() {
                            "<new key>".to_string()
                        } else {
                            format!("{parent}.<new key>")
                        }
                    }
                    _ => path_str(p),
                };
                must_reject.push((class.clone(), path_str(p), sig));
            }
        }
    }
    let convention = Convention::ALL[rng.random_range(0..Convention::ALL.len())];
    let file_name = Path::new(origin).file_name().unwrap().to_string_lossy().into_owned();
    Case {
        index,
        origin: origin.to_string(),
        kind,
        file_name,
        bytes,
        mutations,
        raw,
        convention,
        doc,
        must_reject,
        args: Vec::new(),
    }
}

/// A quantity template `"1 <unit>"` if the library reads that unit, else the number 1 (SI).
fn template(unit: &str) -> Value {
    let q = format!("1 {unit}");
    if stochvib::units::parse_quantity(&q).is_ok() {
        Value::String(q)
    } else {
        Value::Float(1.0)
    }
}

/// Sets one optional key of `[input]` or `[analysis]`: `input.mean` (in the process's unit),
/// `analysis.levels.<output>` (in the output's unit), `analysis.band`, `analysis.duration` or
/// `analysis.outputs`, with a value from the mutator's replacement generator applied to a valid template.
fn add_optional(rng: &mut Rng, doc: &mut Table, unit: &str, outs: &[(String, String)]) -> Option<Mutation> {
    let (path, tmpl) = match rng.random_range(0..5) {
        0 => (vec!["input".to_string(), "mean".to_string()], template(unit)),
        1 if !outs.is_empty() => {
            let (n, u) = &outs[rng.random_range(0..outs.len())];
            (vec!["analysis".into(), "levels".into(), n.clone()], template(u))
        }
        2 => (vec!["analysis".into(), "band".into()], Value::String("80 Hz".into())),
        3 => (vec!["analysis".into(), "duration".into()], Value::String("1 h".into())),
        _ => {
            let names: Vec<Value> = match rng.random_range(0..3) {
                0 => vec![],
                1 if !outs.is_empty() => {
                    let n = &outs[rng.random_range(0..outs.len())].0;
                    vec![Value::String(n.clone()), Value::String(n.clone())]
                }
                _ => outs.iter().map(|(n, _)| Value::String(n.clone())).collect(),
            };
            doc.entry("analysis")
                .or_insert_with(|| Value::Table(Table::new()))
                .as_table_mut()?
                .insert("outputs".into(), Value::Array(names.clone()));
            return Some(Mutation {
                op: "set-optional".into(),
                path: "analysis.outputs".into(),
                detail: format!("= {}", Value::Array(names)),
                must_reject: None,
                witness: None,
            });
        }
    };
    let (v, class, must) = mutate::replacement(rng, &tmpl);
    // levels are arrays; band is [low, high] with the replaced value as the high edge
    let value = match path[1].as_str() {
        "levels" => Value::Array(vec![v.clone()]),
        "band" => Value::Array(vec![Value::String("0.5 Hz".into()), v.clone()]),
        _ => v.clone(),
    };
    let mut t: &mut Table = doc;
    for k in &path[..path.len() - 1] {
        t = t
            .entry(k.clone())
            .or_insert_with(|| Value::Table(Table::new()))
            .as_table_mut()?;
    }
    t.insert(path[path.len() - 1].clone(), value.clone());
    let segs: Vec<Seg> = path.iter().map(|k| Seg::Key(k.clone())).collect();
    Some(Mutation {
        op: format!("set-optional:{class}"),
        path: path.join("."),
        detail: format!("= {}", mutate::short(&value.to_string())),
        must_reject: must,
        witness: Some((segs, value)),
    })
}

/// A finding: the class of invariant broken, a signature grouping findings of one probable root cause,
/// and the details of this occurrence.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Finding {
    /// Invariant class, e.g. `panic`, `non-finite-result`.
    pub class: String,
    /// Grouping key, e.g. `panic at src/x.rs:10:5`.
    pub signature: String,
    /// This occurrence.
    pub detail: String,
}

/// Classes reported but not asserted (heuristic).
pub fn is_soft(class: &str) -> bool {
    class == "unrelated-key"
}

/// What a successful evaluation produced, reduced to what the invariants look at.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Success {
    /// `stochastic`, `deterministic`, `reference` or `spectrum`.
    pub what: String,
    /// Paths and values (as text: JSON has no NaN) of non-finite numbers in the report.
    pub non_finite: Vec<(String, String)>,
    /// Output names of the report (stochastic scenarios).
    pub outputs: Vec<String>,
    /// Output names of the scenario's system (stochastic scenarios).
    pub system_outputs: Vec<String>,
    /// Whether the report has nothing in it.
    pub empty: bool,
}

/// An error returned by an entry point, reduced.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Failure {
    /// Variant name.
    pub variant: String,
    /// `to_string()`.
    pub message: String,
    /// File named by the error, if any.
    pub file: Option<PathBuf>,
    /// Key of an `Error::File`.
    pub key: Option<String>,
    /// Value of an `Error::File`.
    pub value: Option<String>,
    /// Stage that returned it.
    pub stage: String,
}

/// How an evaluation ended.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Outcome {
    /// Every entry point succeeded.
    Ok(Success),
    /// An entry point returned an error.
    Err(Failure),
    /// An entry point panicked.
    Panic {
        /// `file:line:col` of the panic.
        location: String,
        /// Panic message.
        message: String,
        /// Stage.
        stage: String,
    },
    /// The time limit passed.
    Timeout {
        /// Stage that was running.
        stage: String,
        /// The limit.
        limit_ms: u64,
    },
}

impl Outcome {
    /// Short label: `ok:stochastic`, `err:File`, `panic`, `timeout`.
    pub fn label(&self) -> String {
        match self {
            Outcome::Ok(s) => format!("ok:{}", s.what),
            Outcome::Err(f) => format!("err:{}", f.variant),
            Outcome::Panic { .. } => "panic".into(),
            Outcome::Timeout { .. } => "timeout".into(),
        }
    }
}

pub(super) const STAGES: [&str; 5] = ["start", "load", "report", "render", "done"];

pub(super) fn reduce_error(e: &Error, stage: &str) -> Failure {
    let (variant, file, key, value) = match e {
        Error::File { file, key, value, .. } => ("File", Some(file.clone()), Some(key.clone()), Some(value.clone())),
        Error::Parse { file, .. } => ("Parse", Some(file.clone()), None, None),
        Error::Io { path, .. } => ("Io", Some(path.clone()), None, None),
        Error::Hdf5 { path, .. } => ("Hdf5", Some(path.clone()), None, None),
        Error::InvalidParameter { .. } => ("InvalidParameter", None, None, None),
        Error::Divergent { .. } => ("Divergent", None, None, None),
        Error::Quadrature { .. } => ("Quadrature", None, None, None),
        Error::Unit { .. } => ("Unit", None, None, None),
        Error::Numerical { .. } => ("Numerical", None, None, None),
        Error::NotApplicable { .. } => ("NotApplicable", None, None, None),
        Error::Inaccurate { .. } => ("Inaccurate", None, None, None),
    };
    Failure {
        variant: variant.into(),
        message: e.to_string(),
        file,
        key,
        value,
        stage: stage.into(),
    }
}

pub(super) fn nf<T: Serialize>(r: &T) -> Vec<(String, String)> {
    non_finite(r).into_iter().map(|(p, v)| (p, v.to_string())).collect()
}

fn names_unique(v: &[String]) -> bool {
    let mut s = v.to_vec();
    s.sort();
    s.windows(2).all(|w| w[0] != w[1])
}

/// Runs the entry points on the file at `path` (no time limit, panics propagate). `stage` records how far
/// it got (an index into the stage names).
pub fn evaluate(kind: DocKind, path: &Path, spectra_dir: &Path, conv: Convention, stage: &AtomicU8) -> Outcome {
    let set = |s: u8| stage.store(s, Ordering::SeqCst);
    let err = |e: &Error, s: u8| Outcome::Err(reduce_error(e, STAGES[s as usize]));
    set(1);
    match kind {
        DocKind::Transient => super::transient::evaluate(path, spectra_dir, stage),
        DocKind::Spectrum => {
            let f = match load_spectrum(path) {
                Ok(f) => f,
                Err(e) => return err(&e, 1),
            };
            set(2);
            let r = study::spectrum_report(&f, conv);
            set(3);
            let _ = format!("{r}");
            set(4);
            Outcome::Ok(Success {
                what: "spectrum".into(),
                non_finite: nf(&r),
                outputs: vec![],
                system_outputs: vec![],
                empty: false,
            })
        }
        _ => {
            let doc = match load_document(path, spectra_dir) {
                Ok(d) => d,
                Err(e) => return err(&e, 1),
            };
            set(2);
            let s = match doc {
                Document::Stochastic(sc) => {
                    // as `stochvib analyze`: a model with nonlinear elements gets the report of its three routes
                    match sc.nonlinear_answers() {
                        Err(e) => return err(&e, 2),
                        Ok(Some(answers)) => {
                            let r = match study::nonlinear_report(&sc, &answers, None) {
                                Ok(r) => r,
                                Err(e) => return err(&e, 2),
                            };
                            set(3);
                            let _ = format!("{r}");
                            set(4);
                            return Outcome::Ok(Success {
                                what: "nonlinear".into(),
                                non_finite: Vec::new(), // a route that does not apply reports NaN by design
                                outputs: r.outputs.iter().map(|o| o.name.clone()).collect(),
                                system_outputs: sc.model.system.outputs().iter().map(|o| o.name.clone()).collect(),
                                empty: r.outputs.is_empty() && r.skipped.is_empty(),
                            });
                        }
                        Ok(None) => {}
                    }
                    let r = match study::analysis_report(&sc) {
                        Ok(r) => r,
                        Err(e) => return err(&e, 2),
                    };
                    set(3);
                    let _ = format!("{r}");
                    Success {
                        what: "stochastic".into(),
                        non_finite: nf(&r),
                        outputs: r.outputs.iter().map(|o| o.statistics.name.clone()).collect(),
                        system_outputs: sc.model.system.outputs().iter().map(|o| o.name.clone()).collect(),
                        empty: r.outputs.is_empty(),
                    }
                }
                Document::Deterministic(d) => {
                    let r = match stochvib::study::deterministic_tables(&d) {
                        Ok(t) => report::deterministic_report(&d, t),
                        Err(e) => return err(&e, 2),
                    };
                    set(3);
                    let _ = format!("{r}");
                    Success {
                        what: "deterministic".into(),
                        non_finite: nf(&r),
                        outputs: vec![],
                        system_outputs: vec![],
                        empty: r.tables.is_empty() || r.tables.iter().all(|t| t.rows.is_empty()),
                    }
                }
                Document::Reference(t) => {
                    let r = report::reference_report(&t);
                    set(3);
                    let _ = format!("{r}");
                    Success {
                        what: "reference".into(),
                        non_finite: nf(&r),
                        outputs: vec![],
                        system_outputs: vec![],
                        empty: r.tables.is_empty() || r.tables.iter().all(|t| t.rows.is_empty()),
                    }
                }
            };
            set(4);
            Outcome::Ok(s)
        }
    }
}

/// The most recent panic's (location, message), recorded by the hook.
static LAST_PANIC: Mutex<Option<(String, String)>> = Mutex::new(None);
static HOOK: Once = Once::new();

thread_local! {
    /// Set in the threads that evaluate a fuzz case ([`limited`]): their panics are findings, recorded
    /// silently; a panic anywhere else (another test of the suite failing) goes to the previous hook.
    static CASE_THREAD: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Installs a panic hook that records the location and message of a panic in a fuzz-case thread silently and
/// passes every other panic to the hook it replaces, so a test that fails beside the fuzz tests in the same
/// process still prints why.
pub fn install_panic_hook() {
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !CASE_THREAD.with(|c| c.get()) {
                return previous(info);
            }
            let loc = info
                .location()
                .map(|l| format!("{}:{}:{}", l.file(), l.line(), l.column()))
                .unwrap_or_else(|| "<unknown>".into());
            let msg = if let Some(s) = info.payload().downcast_ref::<&str>() {
                s.to_string()
            } else if let Some(s) = info.payload().downcast_ref::<String>() {
                s.clone()
            } else {
                "<non-string payload>".into()
            };
            if let Ok(mut g) = LAST_PANIC.lock() {
                *g = Some((loc, msg));
            }
        }));
    });
}

/// The (location, message) the hook recorded last, if any.
pub fn recorded_panic() -> Option<(String, String)> {
    LAST_PANIC.lock().ok().and_then(|g| g.clone())
}

/// Runs [`evaluate`] in a fresh thread with `catch_unwind`, giving up after `limit`. A thread that does not
/// finish is left running (the caller decides whether to restart the process).
pub fn run_limited(kind: DocKind, path: &Path, spectra_dir: &Path, conv: Convention, limit: Duration) -> Outcome {
    let (p, sd) = (path.to_path_buf(), spectra_dir.to_path_buf());
    limited(limit, move |st| evaluate(kind, &p, &sd, conv, st))
}

/// Runs `eval` (given the stage counter it advances) in a fresh thread with `catch_unwind`, giving up after
/// `limit`; the outcome, a panic with its location, or a timeout naming the stage. A thread that does not
/// finish is left running (the caller decides whether to restart the process).
pub fn limited(limit: Duration, eval: impl FnOnce(&AtomicU8) -> Outcome + Send + 'static) -> Outcome {
    install_panic_hook();
    let stage = Arc::new(AtomicU8::new(0));
    let (tx, rx) = std::sync::mpsc::channel();
    let st = stage.clone();
    if let Ok(mut g) = LAST_PANIC.lock() {
        *g = None;
    }
    std::thread::Builder::new()
        .name("fuzz-case".into())
        .spawn(move || {
            CASE_THREAD.with(|c| c.set(true));
            let r = std::panic::catch_unwind(AssertUnwindSafe(|| eval(&st)));
            let _ = tx.send(r);
        })
        .expect("spawn a case thread");
    match rx.recv_timeout(limit) {
        Ok(Ok(o)) => o,
        Ok(Err(payload)) => {
            let (location, message) = LAST_PANIC.lock().ok().and_then(|g| g.clone()).unwrap_or_else(|| {
                let m = payload
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                ("<unknown>".into(), m)
            });
            Outcome::Panic {
                location,
                message,
                stage: STAGES[stage.load(Ordering::SeqCst) as usize].into(),
            }
        }
        Err(_) => Outcome::Timeout {
            stage: STAGES[stage.load(Ordering::SeqCst) as usize].into(),
            limit_ms: limit.as_millis() as u64,
        },
    }
}

/// Digits and quoted parts of a message replaced, for grouping.
pub fn normalize_message(m: &str) -> String {
    let mut out = String::new();
    let mut in_number = false;
    let mut in_tick = false;
    for c in m.chars() {
        if c == '`' {
            in_tick = !in_tick;
            if in_tick {
                out.push_str("`…`");
            }
            continue;
        }
        if in_tick {
            continue;
        }
        // a number: a digit, then digits, `.`, `e`, `E`, `+`, `-` (and `NaN`/`inf` spelled out)
        if c.is_ascii_digit() || (in_number && ".eE+-".contains(c)) {
            if !in_number {
                out.push('N');
            }
            in_number = true;
            continue;
        }
        in_number = false;
        out.push(c);
    }
    let out = out.replace("-N", "N").replace("NaN", "N").replace("inf", "N");
    out.chars().take(120).collect()
}

fn top(p: &str) -> &str {
    p.split(['.', '[']).next().unwrap_or("")
}

fn parent(p: &str) -> &str {
    let p = p.trim_end_matches("[]");
    match p.rfind(['.', '[']) {
        Some(i) => &p[..i],
        None => "",
    }
}

fn last_key(p: &str) -> &str {
    let p = p.trim_end_matches("[]");
    p.rsplit('.').next().unwrap_or(p)
}

fn is_prefix(a: &str, b: &str) -> bool {
    b.strip_prefix(a)
        .is_some_and(|rest| rest.is_empty() || rest.starts_with('.') || rest.starts_with('['))
}

/// Whether an error naming key `k` is a plausible consequence of mutating path `p` (both as written by the
/// library): the same key, one inside the other, siblings (constraints between keys of one table), a
/// meaning-changing key (`kind`, `domain`, `unit`, `form`, `convention`, `frequency_unit`, `reference`,
/// `class`, `bound`) anywhere, two keys of `[model]` (elements, coordinates and outputs refer to each
/// other), a model key and an `[analysis]` key (output names), `input.speed` and a model key (delays).
pub fn related(p: &str, k: &str) -> bool {
    let (p, k) = (normalize_path(p), normalize_path(k));
    if p == k || is_prefix(&p, &k) || is_prefix(&k, &p) || parent(&p) == parent(&k) {
        return true;
    }
    const MEANING: [&str; 9] = [
        "kind",
        "domain",
        "unit",
        "form",
        "convention",
        "frequency_unit",
        "reference",
        "class",
        "bound",
    ];
    if MEANING.contains(&last_key(&p)) {
        return true;
    }
    match (top(&p), top(&k)) {
        ("model", "model") | ("model", "analysis") => true,
        _ => p == "input.speed" && top(&k) == "model",
    }
}

/// The findings of one evaluation of `case` (written at `path`).
pub fn check(case: &Case, path: &Path, outcome: &Outcome) -> Vec<Finding> {
    let mut f = Vec::new();
    let mut add = |class: &str, signature: String, detail: String| {
        f.push(Finding {
            class: class.into(),
            signature,
            detail,
        })
    };
    let doc_kind = match case.kind {
        DocKind::Spectrum => "spectrum",
        _ => "data",
    };
    let shown = |m: &str| mutate::short_to(&m.replace(&path.display().to_string(), &case.file_name), 240);
    let parsed: Option<Table> = std::str::from_utf8(&case.bytes)
        .ok()
        .and_then(|t| toml::from_str(t).ok());
    match outcome {
        Outcome::Panic {
            location,
            message,
            stage,
        } => add(
            "panic",
            format!("panic at {location}"),
            format!("stage {stage}: {}", mutate::short_to(message, 240)),
        ),
        Outcome::Timeout { stage, limit_ms } => add(
            "timeout",
            format!("timeout in stage {stage} ({doc_kind} file)"),
            format!("no result after {limit_ms} ms"),
        ),
        Outcome::Err(e) => {
            let named = e.file.as_deref();
            if e.message.contains("out of memory") {
                add(
                    "unbounded-read",
                    format!(
                        "{} error after reading until memory ran out (stage {})",
                        e.variant, e.stage
                    ),
                    format!("{} (stopped by the harness' address-space limit)", shown(&e.message)),
                );
            }
            match e.variant.as_str() {
                "File" | "Parse" | "Io" => {
                    if named != Some(path) {
                        add(
                            "error-wrong-file",
                            format!("{} error names another file (stage {})", e.variant, e.stage),
                            format!("names {:?}: {}", named, shown(&e.message)),
                        );
                    }
                }
                v => add(
                    "error-without-file-key",
                    format!("{v} error from stage {}: {}", e.stage, normalize_message(&e.message)),
                    shown(&e.message),
                ),
            }
            if let (Some(key), Some(value)) = (&e.key, &e.value) {
                if key.is_empty() {
                    add("error-no-key", "File error with an empty key".into(), e.message.clone());
                } else if let Some(doc) = &parsed {
                    let present = get(doc, &parse_path(key)).is_some();
                    if !present && value != "<missing>" {
                        add(
                            "phantom-key",
                            format!("error names key `{}`, which is not in the file", normalize_path(key)),
                            shown(&e.message),
                        );
                    }
                    if present && value == "<missing>" {
                        add(
                            "missing-but-present",
                            format!("error says `{}` is missing but it is there", normalize_path(key)),
                            shown(&e.message),
                        );
                    }
                }
                // soft: attribution of a single structured mutation
                let single = case.raw.is_empty()
                    && case.mutations.len() == 1
                    && !["swap", "dup-element", "remove-element"].contains(&case.mutations[0].op.as_str());
                if single {
                    let m = &case.mutations[0];
                    let p = match &m.witness {
                        Some((wp, _)) => path_str(wp),
                        None => m.path.clone(),
                    };
                    if !related(&p, key) {
                        add(
                            "unrelated-key",
                            format!(
                                "{} at `{}` reported at `{}`",
                                m.op,
                                normalize_path(&p),
                                normalize_path(key)
                            ),
                            shown(&e.message),
                        );
                    }
                }
            }
        }
        Outcome::Ok(s) => {
            for (p, v) in &s.non_finite {
                add(
                    "non-finite-result",
                    format!("{v} in {} report at {}", s.what, normalize_path(p)),
                    format!("{p} = {v}"),
                );
            }
            if s.empty {
                add(
                    "empty-result",
                    format!("{} report with nothing in it", s.what),
                    String::new(),
                );
            }
            if !names_unique(&s.outputs) {
                add(
                    "duplicate-output",
                    "report lists an output name twice".into(),
                    s.outputs.join(", "),
                );
            }
            if !names_unique(&s.system_outputs) {
                add(
                    "duplicate-output",
                    "system has two outputs of the same name".into(),
                    s.system_outputs.join(", "),
                );
            }
            for (class, _, p) in &case.must_reject {
                add(
                    class,
                    format!("{class}: `{}` ({})", normalize_path(p), s.what),
                    case.describe(),
                );
            }
        }
    }
    f
}

/// Arguments of the CLI run of a case file.
pub fn cli_args(kind: DocKind, path: &Path, spectra_dir: &Path, json: bool) -> Vec<String> {
    let mut a: Vec<String> = match kind {
        DocKind::Spectrum => vec!["spectrum".into(), path.display().to_string()],
        DocKind::Transient => vec!["transient".into(), path.display().to_string()],
        _ => vec!["analyze".into(), path.display().to_string()],
    };
    a.push("--spectra-dir".into());
    a.push(spectra_dir.display().to_string());
    if kind == DocKind::Transient {
        a.extend(super::transient::cli_tail(path));
    }
    if json {
        a.push("--json".into());
    }
    a
}

/// Tokens of `stdout` that are a printed non-finite number (`NaN`, `inf`, `-inf`) and do not occur in the
/// input text itself (a title may contain the word).
pub fn non_finite_tokens(stdout: &str, input: &[u8]) -> Vec<String> {
    let input = String::from_utf8_lossy(input);
    stdout
        .split(|c: char| c.is_whitespace() || "[](),;:=\"".contains(c))
        .filter(|t| matches!(*t, "NaN" | "-NaN" | "inf" | "-inf" | "+inf"))
        .filter(|t| !input.contains(*t))
        .map(str::to_string)
        .collect()
}

/// The findings of a CLI run of a case, given the in-process outcome of the same file.
pub fn check_cli(case: &Case, path: &Path, args: &[String], lib: &str, out: &super::process::Output) -> Vec<Finding> {
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
    let first_err = out
        .stderr
        .lines()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("")
        .to_string();
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
        Exit::Code(101) => {
            let loc = out
                .stderr
                .lines()
                .find(|l| l.contains("panicked at"))
                .map(|l| l.split("panicked at").nth(1).unwrap_or("").trim().to_string())
                .unwrap_or_default();
            add(
                "cli-panic",
                format!("{cmd} panicked at {loc}"),
                super::process::tail(&out.stderr, 300),
            )
        }
        Exit::Code(0) => {
            if out.stdout.trim().is_empty() {
                add(
                    "cli-empty-output",
                    format!("{cmd} exit 0 with no output"),
                    String::new(),
                );
            }
            let toks = non_finite_tokens(&out.stdout, &case.bytes);
            if !toks.is_empty() {
                add(
                    "cli-non-finite",
                    format!("{cmd} prints {}", toks[0]),
                    format!("{} non-finite tokens", toks.len()),
                );
            }
            if lib.starts_with("err") {
                add(
                    "cli-inconsistent",
                    format!("{cmd} succeeds where the library returns {lib}"),
                    String::new(),
                );
            }
        }
        Exit::Code(c) => {
            let p = path.display().to_string();
            if c != 1 {
                add("cli-exit-code", format!("{cmd} exit code {c}"), first_err.clone());
            }
            if out.stderr.contains("out of memory") {
                add(
                    "cli-unbounded-read",
                    format!("{cmd} reads until memory runs out"),
                    format!(
                        "{} (stopped by the harness' address-space limit)",
                        mutate::short(&first_err)
                    ),
                );
            }
            if !first_err.starts_with("error:") || !out.stderr.contains(&p) {
                add(
                    "cli-error-message",
                    format!("{cmd} fails without a message naming the file"),
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

/// Counts by label, for summaries.
pub type Counts = BTreeMap<String, usize>;

/// Writes `case` as `dir/<file name>` and returns the path.
pub fn write_case(case: &Case, dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let p = dir.join(&case.file_name);
    std::fs::write(&p, &case.bytes).unwrap();
    p
}

/// Evaluates case `case` in this process (written under `dir`) and returns its outcome and findings.
pub fn run_case(corpus: &Corpus, case: &Case, dir: &Path, limit: Duration) -> (Outcome, Vec<Finding>, Duration) {
    let path = write_case(case, dir);
    let t = Instant::now();
    let o = run_limited(case.kind, &path, &corpus.spectra_dir, case.convention, limit);
    let el = t.elapsed();
    let f = check(case, &path, &o);
    (o, f, el)
}
