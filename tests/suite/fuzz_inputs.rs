//! Bounded structured fuzzing of the input files: a fixed seed, 300 mutated copies of the
//! shipped scenario, reference and spectrum files through the library's entry points (in worker
//! processes, with a per-case time limit) and every tenth through the CLI, plus the special files (FIFO,
//! directory, `/dev/zero`, `/dev/urandom`, empty, missing, symbolic-link loop, NUL bytes, a scenario whose
//! spectrum is a FIFO or `/dev/zero`, 20 MiB of comments).
//!
//! The invariants are listed in `tests/fuzz/inputs.rs`: no panic, no hang, no crash; an error names the
//! file and an existing key (or is a parse/I-O error naming the file); a success prints no non-finite
//! result, reports something, has distinct output names; a document with an unknown key, a wrong or
//! unknown unit, a non-finite number or an impossible type is refused; the CLI exits 0 or 1, with an
//! `error:` line naming the file, and agrees with the library. No expected value comes from the code
//! under test: the expectations are properties every correct reader has.
//!
//! The long campaign is `cargo run --release --features campaigns --example fuzz -- --cases 20000`.

use crate::fuzz;

use fuzz::input_campaign::{self, Campaign, WorkerConfig};
use std::path::PathBuf;
use std::process::Command;
use std::sync::Arc;
use std::time::Duration;

/// Fixed master seed of the bounded run (case i is generated from (seed, i) alone).
const SEED: u64 = 16;
/// Generated cases: about 3 ms each in-process, so the run is dominated by the special files' time limits.
const CASES: u64 = 300;
/// Run the CLI on every tenth case (30 runs).
const CLI_EVERY: u64 = 10;
/// Per-case time limit in-process. The slowest of 20,000 cases took under 0.3 s on this machine; 10 s
/// leaves room for a loaded machine and still catches a hang.
const CASE_LIMIT: Duration = Duration::from_secs(10);
/// Time limit of a CLI run (a hung one is killed).
const CLI_LIMIT: Duration = Duration::from_secs(20);
/// Time limit for the special files (FIFO, devices): a correct reader refuses them at once.
const SPECIAL_LIMIT: Duration = Duration::from_secs(3);

const WORKER_ENV: &str = "STOCHVIB_FUZZ_INPUTS_WORKER";

/// Worker half of `inputs_keep_the_invariants`: evaluates the cases its configuration names and exits.
/// Without the environment variable it does nothing.
#[test]
#[ignore = "worker process of inputs_keep_the_invariants"]
fn fuzz_inputs_worker() {
    let Ok(json) = std::env::var(WORKER_ENV) else { return };
    let cfg: WorkerConfig = serde_json::from_str(&json).expect("worker configuration");
    input_campaign::worker_main(&cfg);
}

/// The campaign of `scripts/fuzz-campaign.sh`: configured by `STOCHVIB_FUZZ_CAMPAIGN` (JSON: seed, cases,
/// budget_s, cli_every, timeout_ms, totals, findings, bin: the CLI to run), run with this binary as the worker and the CLI built
/// for the tests; the totals (cases, CLI runs, panics, signals, hangs per format and command) are written
/// to `totals` as JSON. Without the variable it does nothing.
#[test]
#[ignore = "the long campaign of scripts/fuzz-campaign.sh"]
fn fuzz_campaign() {
    let Ok(json) = std::env::var("STOCHVIB_FUZZ_CAMPAIGN") else {
        return;
    };
    let cfg: serde_json::Value = serde_json::from_str(&json).expect("campaign configuration");
    let num = |k: &str, d: u64| cfg.get(k).and_then(|v| v.as_u64()).unwrap_or(d);
    let text = |k: &str| cfg.get(k).and_then(|v| v.as_str()).map(PathBuf::from);
    let root = crate::common::root();
    let tmp = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let seed = num("seed", 1);
    let mut c = campaign(seed, num("cases", 1000), num("cli_every", 1000));
    c.limit = Duration::from_millis(num("timeout_ms", 10_000));
    c.budget = cfg.get("budget_s").and_then(|v| v.as_u64()).map(Duration::from_secs);
    c.scratch = crate::common::scratch_path("fuzz-campaign", &seed.to_string());
    c.findings_dir = Some(text("findings").unwrap_or_else(|| tmp.join(format!("fuzz-campaign-findings-{seed}"))));
    c.progress = true;
    // the CLI of the campaign's snapshot (scripts/fuzz-campaign.sh copies it), else the one built for the tests
    c.bin = text("bin").unwrap_or(c.bin);
    let s = input_campaign::run(&c);
    let _ = std::fs::remove_dir_all(&c.scratch);
    println!("{}", s.render());
    let mut totals = s.totals_json();
    totals["source"] = serde_json::json!(root.display().to_string());
    let out = text("totals").unwrap_or_else(|| tmp.join(format!("fuzz-campaign-{seed}.json")));
    std::fs::write(&out, serde_json::to_string_pretty(&totals).unwrap()).expect("write the totals");
    println!("totals: {}", out.display());
}

/// The campaign of this file's tests: `cases` cases of `seed`, every `cli_every`-th through the CLI.
fn campaign(seed: u64, cases: u64, cli_every: u64) -> Campaign {
    let root = crate::common::root();
    let tmp = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let exe = std::env::current_exe().expect("own path");
    Campaign {
        root,
        seed,
        cases,
        jobs: 1,
        cli_every,
        limit: CASE_LIMIT,
        cli_limit: CLI_LIMIT,
        special_limit: SPECIAL_LIMIT,
        scratch: crate::common::scratch_path("fuzz-inputs", &format!("seed-{seed}")),
        findings_dir: Some(tmp.join("fuzz-findings")),
        minimize: false,
        special: true,
        bin: PathBuf::from(crate::common::cli_bin()),
        worker: Arc::new(move |cfg: &WorkerConfig| {
            let mut cmd = Command::new(&exe);
            cmd.args([
                "--ignored",
                "--exact",
                "fuzz_inputs::fuzz_inputs_worker",
                "--nocapture",
                "--test-threads=1",
            ])
            .env(WORKER_ENV, serde_json::to_string(cfg).unwrap());
            cmd
        }),
        progress: false,
        budget: None,
    }
}

#[test]
fn inputs_keep_the_invariants() {
    let tmp = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let c = campaign(SEED, CASES, CLI_EVERY);
    let s = input_campaign::run(&c);
    let _ = std::fs::remove_dir_all(&c.scratch);
    assert_eq!(s.cases, CASES, "every case was evaluated");
    assert!(
        s.hard_not_slow().is_empty(),
        "broken invariants (reproducers in {}):\n{}",
        tmp.join("fuzz-findings/inputs").display(),
        s.render()
    );
}

/// The record commands (`exposure`, `fatigue`, `coherence`, `iri`, `weighting`) and the nonlinear sections are
/// case families of the harness, each in the 300 cases of the suite's run: 6 % of a seed's cases each, so
/// about 18 of 300, and every record command among the first 1000.
#[test]
fn the_record_commands_and_nonlinear_sections_are_case_families() {
    use fuzz::inputs::{generate, Corpus, DocKind};
    let corpus = Corpus::load(&crate::common::root());
    let cases: Vec<_> = (0..1000).map(|i| generate(&corpus, SEED, i)).collect();
    let in_suite = |k: DocKind| cases[..CASES as usize].iter().filter(|c| c.kind == k).count();
    assert!(
        in_suite(DocKind::Record) >= 5,
        "{} record cases",
        in_suite(DocKind::Record)
    );
    assert!(
        in_suite(DocKind::Nonlinear) >= 5,
        "{} nonlinear cases",
        in_suite(DocKind::Nonlinear)
    );
    for cmd in fuzz::records::COMMANDS {
        assert!(
            cases.iter().any(|c| c.kind == DocKind::Record && c.args[0] == cmd),
            "no `{cmd}` case"
        );
    }
    // the nonlinear cases mutate the element tables
    let nonlinear = cases.iter().filter(|c| c.kind == DocKind::Nonlinear);
    assert!(nonlinear
        .flat_map(|c| &c.mutations)
        .any(|m| m.path.starts_with("model.nonlinear") && m.op != "add-element"));
}

/// `stochvib transient` and `stochvib optimize` are case families of the harness (1.5 % of a seed's cases
/// each, drawn from a stream of their own): among 3000 cases of the suite's seed about 45 of each. The
/// transient cases mutate the non-stationary keys of both transient scenarios of `data/`; the optimize cases
/// give every flag; the first four of each keep the invariants in this process.
#[test]
fn transient_and_optimize_are_case_families() {
    use fuzz::inputs::{generate, Corpus, DocKind};
    let root = crate::common::root();
    let corpus = Corpus::load(&root);
    let cases: Vec<_> = (0..3000).map(|i| generate(&corpus, SEED, i)).collect();
    let of = |k: DocKind| cases.iter().filter(move |c| c.kind == k);
    assert!(
        of(DocKind::Transient).count() >= 20,
        "{}",
        of(DocKind::Transient).count()
    );
    assert!(of(DocKind::Optimize).count() >= 20, "{}", of(DocKind::Optimize).count());
    for origin in ["data/quarter-car-accelerating.toml", "data/hoist-winding.toml"] {
        assert!(
            of(DocKind::Transient).any(|c| c.origin == origin),
            "no case of {origin}"
        );
    }
    let keys = ["transient", "input.speed_profile", "input.envelope", "analysis.mission"];
    for k in keys {
        let mutated = of(DocKind::Transient)
            .flat_map(|c| &c.mutations)
            .any(|m| m.path.starts_with(k));
        assert!(mutated, "no mutation of {k}");
    }
    assert!(
        of(DocKind::Transient).any(|c| c.file_name.starts_with("mc")),
        "no Monte Carlo case"
    );
    for flag in [
        "--param",
        "--minimize",
        "--maximize",
        "--constraint",
        "--starts",
        "--max-evaluations",
    ] {
        assert!(
            of(DocKind::Optimize).any(|c| c.args.iter().any(|a| a == flag)),
            "no {flag}"
        );
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-families");
    let ctx = input_campaign::context(&root, &dir);
    let sample = of(DocKind::Transient).take(4).chain(of(DocKind::Optimize).take(4));
    for case in sample {
        let (o, f, _) = input_campaign::run_any(
            &corpus,
            case,
            &dir.join(format!("case-{}", case.index)),
            CASE_LIMIT,
            &ctx,
        );
        let hard: Vec<_> = f.iter().filter(|x| !fuzz::inputs::is_soft(&x.class)).collect();
        assert!(
            hard.is_empty(),
            "case {}: {}
{o:?}
{hard:?}",
            case.index,
            case.describe()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The commands whose work lives in the CLI's handlers — `simulate`, `plot`, `report`, `inspect`,
/// `check-run`, `book`, `spectra`, `models`, and `analyze`'s and `spectrum`'s flags — are case families of
/// the harness (4.3 % of a seed's cases, from a stream of their own): among 10,000 cases of the suite's seed
/// each command has at least 3 cases, the simulate cases give every hostile flag and output target kind, and
/// the first case of each command keeps the invariants (run through the CLI binary: no panic, no signal, no
/// hang, an error naming a flag or a file, inputs left as they were, no half-written file, an output that
/// verifies).
#[test]
fn the_cli_only_commands_are_case_families() {
    use fuzz::inputs::{generate, Corpus};
    let root = crate::common::root();
    let corpus = Corpus::load(&root);
    let cases: Vec<_> = (0..10_000).map(|i| generate(&corpus, SEED, i)).collect();
    let of = |cmd: &'static str| {
        cases
            .iter()
            .filter(move |c| c.kind.is_cli_only() && c.args.first().is_some_and(|a| a == cmd))
    };
    for (cmd, _) in fuzz::cli_commands::COMMANDS {
        assert!(of(cmd).count() >= 3, "{} `{cmd}` cases", of(cmd).count());
    }
    for flag in [
        "--realizations",
        "--duration",
        "--dt",
        "--seed",
        "--shard",
        "--of",
        "--overwrite",
        "-o",
    ] {
        assert!(
            of("simulate").any(|c| c.args.iter().any(|a| a == flag)),
            "no simulate {flag}"
        );
    }
    for target in [
        "<file>",
        "<fifo:run.h5>",
        "<dir:run.h5>",
        "<run:run.h5>",
        "<tmp-garbage:run.h5>",
    ] {
        assert!(
            of("simulate").any(|c| c.args.iter().any(|a| a == target)),
            "no simulate -o {target}"
        );
    }
    assert!(
        of("plot").any(|c| !c.mutations.is_empty()),
        "no plot of a mutated scenario"
    );
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz-cli-families");
    let ctx = input_campaign::context(&root, &dir);
    fuzz::commands::Fixtures::ensure(&root, &ctx.fixtures);
    for (cmd, _) in fuzz::cli_commands::COMMANDS {
        let case = of(cmd).next().unwrap();
        let (o, f, _) = input_campaign::run_any(
            &corpus,
            case,
            &dir.join(format!("case-{}", case.index)),
            CLI_LIMIT,
            &ctx,
        );
        let hard: Vec<_> = f.iter().filter(|x| !fuzz::inputs::is_soft(&x.class)).collect();
        assert!(
            hard.is_empty(),
            "case {}: {}\n{o:?}\n{hard:?}",
            case.index,
            case.describe()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The harness does not take free text for quantities (a finding of the 20,000-case campaign of seed 2027):
/// Table 8.1's transcription holds the print's text (`omega0 = "17...20 1/s"`, `sqrt_dq = "3.5 cm"` under
/// `printed_parameters`, `printed_symbol = "sigma_x1"`), which no reader interprets, so replacing it with a
/// wrong unit is not a "wrong unit accepted" finding; a quantity of a scenario still is one.
#[test]
fn free_text_of_the_reference_file_is_not_classified_as_quantities() {
    use fuzz::mutate::{all_paths, free_text, path_str};
    let root = crate::common::root();
    let read = |p: &str| -> toml::Table { std::fs::read_to_string(root.join(p)).unwrap().parse().unwrap() };
    let table = read("data/reference/table-8-1.toml");
    let paths: Vec<String> = all_paths(&table)
        .iter()
        .filter(|p| free_text(p))
        .map(|p| path_str(p))
        .collect();
    for must in [
        "printed_parameters.sqrt_dq",
        "printed_parameters.omega0",
        "row[0].printed_symbol",
        "status",
    ] {
        assert!(paths.iter().any(|p| p == must), "{must} not free text: {paths:?}");
    }
    // the numbers of the table and a scenario's quantities stay quantities
    assert!(
        !paths.iter().any(|p| p.starts_with("row[0].values") || p == "speeds[0]"),
        "{paths:?}"
    );
    let scenario = read("data/quarter-car.toml");
    let mass = all_paths(&scenario)
        .into_iter()
        .find(|p| path_str(p) == "model.coordinates[0].mass")
        .expect("the quarter car's body mass");
    assert!(!free_text(&mass));
}

/// Reproduces cases of a campaign in this process: `STOCHVIB_FUZZ_SCAN="SEED FROM TO [CLASS…]"` evaluates
/// cases FROM..TO of SEED (each regenerated from the seed and its number alone) and prints every case with
/// a finding of one of the classes (all classes when none is named): its description, outcome and
/// findings, and the case file under the target's temporary directory. Without the variable it does
/// nothing.
#[test]
#[ignore = "a tool: reproduces campaign cases by seed and number"]
fn fuzz_scan() {
    let Ok(spec) = std::env::var("STOCHVIB_FUZZ_SCAN") else {
        return;
    };
    let words: Vec<&str> = spec.split_whitespace().collect();
    let num = |i: usize| words.get(i).and_then(|w| w.parse::<u64>().ok()).expect("SEED FROM TO");
    let (seed, from, to) = (num(0), num(1), num(2));
    let classes = &words[3..];
    let root = crate::common::root();
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("fuzz-scan-{seed}"));
    let corpus = fuzz::inputs::Corpus::load(&root);
    let ctx = input_campaign::context(&root, &dir);
    fuzz::commands::Fixtures::ensure(&root, &ctx.fixtures);
    for i in from..to {
        let case = fuzz::inputs::generate(&corpus, seed, i);
        let case_dir = dir.join(format!("case-{i}"));
        let (o, f, _) = input_campaign::run_any(&corpus, &case, &case_dir, CASE_LIMIT, &ctx);
        let hits: Vec<_> = f
            .iter()
            .filter(|x| classes.is_empty() || classes.contains(&x.class.as_str()))
            .collect();
        if hits.is_empty() {
            let _ = std::fs::remove_dir_all(&case_dir);
            continue;
        }
        println!("case {i}: {}\n  outcome {}: {:?}", case.describe(), o.label(), o);
        for h in hits {
            println!("  {} | {} | {}", h.class, h.signature, h.detail);
        }
        println!("  file {}", case_dir.display());
    }
}

/// A name is a label, not a quantity (findings of seeds 2832 and 2833: a workday task renamed `"3 furlong"`
/// or `"4 s"` was counted as an accepted unit), and a wrong-unit judgment is relative to the shipped value
/// it replaced: a band edge set to `"3 kg m^2"` by one mutation and to `"1 Hz"` by the next is right.
#[test]
fn names_are_free_text_and_a_unit_is_judged_against_the_shipped_value() {
    use fuzz::mutate::{expectation_holds, free_text, Mutation, Seg};
    let path = |k: &[&str]| -> Vec<Seg> { k.iter().map(|s| Seg::Key(s.to_string())).collect() };
    assert!(free_text(&[
        Seg::Key("task".into()),
        Seg::Index(1),
        Seg::Key("name".into())
    ]));
    assert!(!free_text(&path(&["task", "duration"])));
    let m = |p: &str, segs: Vec<Seg>, must: Option<&str>| Mutation {
        op: "replace".into(),
        path: p.into(),
        detail: String::new(),
        must_reject: must.map(str::to_string),
        witness: Some((segs, toml::Value::String("1 Hz".into()))),
    };
    let mut edge = path(&["analysis", "band"]);
    edge.push(Seg::Index(1));
    let set = m(
        "analysis.band",
        path(&["analysis", "band"]),
        Some("wrong-unit-accepted"),
    );
    let replaced = m("analysis.band[1]", edge.clone(), Some("wrong-unit-accepted"));
    assert!(expectation_holds(std::slice::from_ref(&replaced), 0));
    assert!(!expectation_holds(&[set.clone(), replaced], 1));
    // an unknown unit stays an unknown unit whatever came before
    let unknown = m("analysis.band[1]", edge, Some("unknown-unit-accepted"));
    assert!(expectation_holds(&[set, unknown], 1));
}

/// The harness's panic hook records a panic of a fuzz-case thread silently and passes every other panic to
/// the hook it replaced: a test failing elsewhere in the suite process must still print why (a process-wide
/// silent hook once swallowed the message of a failing store test). A panic outside a case thread is never
/// what the hook records (other fuzz tests running at the same time may only clear the record or record
/// their own cases, never this message).
#[test]
fn the_panic_hook_is_silent_only_in_fuzz_case_threads() {
    let o = fuzz::inputs::limited(Duration::from_secs(60), |_| panic!("inside a fuzz case"));
    match o {
        fuzz::inputs::Outcome::Panic { message, .. } => assert_eq!(message, "inside a fuzz case"),
        _ => panic!("the case's panic was not caught"),
    }
    let outside = std::thread::spawn(|| panic!("outside a fuzz case")).join();
    assert!(outside.is_err());
    let recorded = fuzz::inputs::recorded_panic();
    assert!(
        recorded.as_ref().is_none_or(|(_, m)| m != "outside a fuzz case"),
        "{recorded:?}"
    );
}
