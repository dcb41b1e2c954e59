//! Transient cases: a scenario with a `[transient]` section (`data/quarter-car-accelerating.toml`,
//! `data/hoist-winding.toml`) whose non-stationary keys — `[transient]`, `[[transient.schedule]]`,
//! `[input.speed_profile]`, `[input.envelope]`, `[analysis.mission]` — are mutated by the TOML mutator and
//! evaluated as `stochvib transient` evaluates them (the exact route and its answers), sometimes with a small
//! Monte Carlo run (`--monte-carlo N -o FILE`). The invariants are those of the TOML cases
//! ([`super::inputs`]).
//!
//! The exact route's default local tolerance costs seconds per case on a loaded machine; every case sets
//! `[transient] rel_tol = 0.005` first (a mutation of its own, recorded; the mutator may change or drop it
//! again) so that a case stays well inside the per-case time limit.

use super::inputs::{Corpus, Outcome, Success};
use super::mutate::{self, Mutation, Rng};
use rand::RngExt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU8, Ordering};
use stochvib::study::transient_answers::answers;
use stochvib::study::transient_mc::{compare_sigma, simulate_transient, TransientMcOptions};
use stochvib::study::transient_run::{exact_solution, transient_setup};
use toml::{Table, Value};

/// The keys of a transient scenario the cases mutate: (table, key in it).
const PARTS: [(&str, &str); 4] = [
    ("", "transient"),
    ("input", "speed_profile"),
    ("input", "envelope"),
    ("analysis", "mission"),
];

/// Realizations of the occasional Monte Carlo run.
const MC_REALIZATIONS: [usize; 3] = [2, 4, 8];

/// The scenarios of the corpus with a `[transient]` section.
fn origins(corpus: &Corpus) -> Vec<(&str, &Table)> {
    corpus
        .seeds
        .iter()
        .filter(|s| s.table.contains_key("transient"))
        .map(|s| (s.rel.as_str(), &s.table))
        .collect()
}

/// A transient case (origin, document, mutations, file name): `rel_tol` set, then 1–3
/// mutations of the non-stationary keys; the file name is `mcN-<name>` for a case run with `--monte-carlo
/// N`. `None` when the corpus has no transient scenario.
pub fn mutated(corpus: &Corpus, rng: &mut Rng) -> Option<(String, Table, Vec<Mutation>, String)> {
    let all = origins(corpus);
    if all.is_empty() {
        return None;
    }
    let (rel, table) = all[rng.random_range(0..all.len())];
    let mut doc = table.clone();
    let mut mutations = Vec::new();
    if let Some(Value::Table(t)) = doc.get_mut("transient") {
        t.insert("rel_tol".into(), Value::Float(0.005));
        mutations.push(Mutation {
            op: "set-rel-tol".into(),
            path: "transient.rel_tol".into(),
            detail: "= 0.005 (a bounded time per case)".into(),
            must_reject: None,
            witness: None,
        });
    }
    let mut part = extract(&mut doc);
    let (n, mut done) = (rng.random_range(1..4), 0);
    for _ in 0..n * 5 {
        if done == n {
            break;
        }
        if let Some(m) = mutate::mutate_once(rng, &mut part, &corpus.vocabulary) {
            mutations.push(m);
            done += 1;
        }
    }
    put_back(&mut doc, part);
    let name = Path::new(rel).file_name()?.to_string_lossy().into_owned();
    let name = if rng.random_bool(0.08) {
        format!(
            "mc{}-{name}",
            MC_REALIZATIONS[rng.random_range(0..MC_REALIZATIONS.len())]
        )
    } else {
        name
    };
    Some((rel.to_string(), doc, mutations, name))
}

/// The non-stationary keys taken out of `doc`, as a document of the same shape (so that the mutations'
/// paths are the paths of `doc`).
fn extract(doc: &mut Table) -> Table {
    let mut part = Table::new();
    for (table, key) in PARTS {
        let from = if table.is_empty() {
            Some(&mut *doc)
        } else {
            doc.get_mut(table).and_then(Value::as_table_mut)
        };
        let Some(v) = from.and_then(|t| t.remove(key)) else {
            continue;
        };
        if table.is_empty() {
            part.insert(key.into(), v);
        } else if let Value::Table(t) = part.entry(table).or_insert_with(|| Value::Table(Table::new())) {
            t.insert(key.into(), v);
        }
    }
    part
}

/// The (mutated) non-stationary keys back into `doc`, under whatever names the mutations gave them.
fn put_back(doc: &mut Table, part: Table) {
    for (k, v) in part {
        if let (Some(Value::Table(into)), Value::Table(t)) = (doc.get_mut(&k), &v) {
            into.extend(t.clone());
            continue;
        }
        doc.insert(k, v);
    }
}

/// The Monte Carlo realizations of a case file named `mcN-…`.
pub fn monte_carlo(path: &Path) -> Option<usize> {
    let name = path.file_name()?.to_str()?;
    name.strip_prefix("mc")?.split_once('-')?.0.parse().ok()
}

/// The run file of the in-process Monte Carlo run (`lib`) or of the CLI's (`cli`) of the case at `path`.
pub fn run_file(path: &Path, who: &str) -> PathBuf {
    path.with_extension(format!("{who}.h5"))
}

/// Evaluates the case at `path` as `stochvib transient` does (the stages as [`super::inputs::evaluate`]).
pub fn evaluate(path: &Path, spectra_dir: &Path, stage: &AtomicU8) -> Outcome {
    let set = |s: u8| stage.store(s, Ordering::SeqCst);
    let err =
        |e: &stochvib::Error, s: u8| Outcome::Err(super::inputs::reduce_error(e, super::inputs::STAGES[s as usize]));
    set(1);
    let sc = match stochvib::scenario::load_scenario(path, spectra_dir) {
        Ok(sc) => sc,
        Err(e) => return err(&e, 1),
    };
    set(2);
    let run = || -> stochvib::Result<_> {
        let setup = transient_setup(&sc)?;
        let sol = exact_solution(&sc, &setup)?;
        let r = answers(&sc, &setup, &sol);
        let mc = match monte_carlo(path) {
            Some(n) => Some(small_run(&sc, &setup, &sol, n, &run_file(path, "lib"))?),
            None => None,
        };
        Ok((r, mc))
    };
    let (r, mc) = match run() {
        Ok(x) => x,
        Err(e) => return err(&e, 2),
    };
    set(3);
    let _ = format!("{r}");
    set(4);
    let mut non_finite = super::inputs::nf(&r);
    non_finite.extend(mc.iter().flat_map(super::inputs::nf));
    Outcome::Ok(Success {
        what: "transient".into(),
        non_finite,
        outputs: r.outputs.iter().map(|o| o.name.clone()).collect(),
        system_outputs: Vec::new(),
        empty: r.outputs.is_empty(),
    })
}

/// A Monte Carlo run of `n` realizations into `out` (removed before and after) and its σ(t) comparison.
fn small_run(
    sc: &stochvib::scenario::Scenario,
    setup: &stochvib::study::transient_run::TransientSetup,
    sol: &stochvib::transient::TransientSolution,
    n: usize,
    out: &Path,
) -> stochvib::Result<Vec<stochvib::study::transient_mc::SigmaComparison>> {
    let _ = std::fs::remove_file(out);
    let opts = TransientMcOptions {
        realizations: n,
        substeps: 4,
        seed: 1,
        shard_size: 50,
        confidence: 0.95,
        store_raw: false,
        compression: stochvib::store::Compression::default(),
        part: None,
        overwrite: false,
        max_hours: stochvib::simulate::resources::DEFAULT_MAX_HOURS,
    };
    let r = simulate_transient(sc, setup, sol, &opts, out, &|_, _| {}).and_then(|(s, _)| {
        let series = stochvib::transient::monte_carlo::read_transient_run(&s.path)?.1;
        compare_sigma(&series, 1e-3)
    });
    let _ = std::fs::remove_file(out);
    r
}

/// The CLI arguments of a transient case at `path` after `stochvib transient FILE --spectra-dir DIR`: the
/// Monte Carlo flags of an `mcN-…` case (its run file removed first).
pub fn cli_tail(path: &Path) -> Vec<String> {
    let Some(n) = monte_carlo(path) else {
        return Vec::new();
    };
    let out = run_file(path, "cli");
    let _ = std::fs::remove_file(&out);
    vec![
        "--monte-carlo".into(),
        n.to_string(),
        "-o".into(),
        out.display().to_string(),
    ]
}
