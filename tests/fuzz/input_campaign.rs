//! The input-file campaign: worker processes that evaluate cases in-process, a supervisor that restarts
//! them after a hang or a crash, CLI runs of a sample of cases, special files (FIFO, directory,
//! `/dev/zero`, ...), minimisation of one case per finding signature and the reproducer files.
//!
//! Protocol: a worker prints one line `@@fuzz <json>` per event ([`Msg`]) on stdout. It exits with 0 when
//! its range is done, and with [`EXIT_RESTART`] after a timeout (the hung thread cannot be stopped, so the
//! process is replaced). A worker that dies otherwise while a case is running has crashed on that case.

use super::commands::{self, Context, Fixtures};
use super::inputs::{self, Case, Corpus, DocKind, Finding, Outcome};
use super::mutate::{all_paths, normalize_path, remove, Seg};
use super::process::{self, Exit};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use stochvib::spectrum::Convention;

/// Exit code of a worker that must be restarted after a timeout.
pub const EXIT_RESTART: i32 = 75;
/// Prefix of protocol lines.
const TAG: &str = "@@fuzz ";

/// What a worker process does.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct WorkerConfig {
    /// Source tree (corpus and catalogue).
    pub root: PathBuf,
    /// Directory for the case files.
    pub scratch: PathBuf,
    /// Master seed.
    pub seed: u64,
    /// First case.
    pub from: u64,
    /// End of the range (exclusive).
    pub to: u64,
    /// Step between cases.
    pub stride: u64,
    /// Per-case time limit, ms.
    pub limit_ms: u64,
    /// Instead of a range: evaluate one file.
    pub check: Option<CheckSpec>,
}

/// One file to evaluate in a worker.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CheckSpec {
    /// The file.
    pub path: PathBuf,
    /// Its kind.
    pub kind: DocKind,
    /// Index into `Convention::ALL`.
    pub convention: usize,
    /// The arguments of a command case ([`Case::args`]).
    #[serde(default)]
    pub args: Vec<String>,
}

/// A protocol message.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum Msg {
    /// Case `index` starts.
    Start {
        /// Case.
        index: u64,
    },
    /// Case `index` finished.
    Done {
        /// Case.
        index: u64,
        /// Outcome.
        outcome: Outcome,
        /// Findings.
        findings: Vec<Finding>,
        /// Wall time, ms.
        ms: u64,
    },
    /// The outcome of a `check`.
    Checked {
        /// Outcome.
        outcome: Outcome,
    },
}

fn emit(m: &Msg) {
    let line = format!("{TAG}{}\n", serde_json::to_string(m).expect("serialisable message"));
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(line.as_bytes());
    let _ = out.flush();
}

fn conv_index(c: Convention) -> usize {
    Convention::ALL.iter().position(|x| *x == c).unwrap_or(0)
}

/// The context of the command cases of a campaign whose scratch directory is `scratch`.
pub fn context(root: &Path, scratch: &Path) -> Context {
    Context {
        root: root.to_path_buf(),
        fixtures: scratch.join("fixtures"),
    }
}

/// Evaluates a case of any kind in this process under `dir`.
pub fn run_any(
    corpus: &Corpus,
    case: &Case,
    dir: &Path,
    limit: Duration,
    ctx: &Context,
) -> (Outcome, Vec<Finding>, Duration) {
    if case.kind.is_command() {
        commands::run_case(case, dir, limit, ctx)
    } else {
        inputs::run_case(corpus, case, dir, limit)
    }
}

/// The body of a worker process; never returns.
pub fn worker_main(cfg: &WorkerConfig) -> ! {
    inputs::install_panic_hook();
    let corpus = Corpus::load(&cfg.root);
    let ctx = context(&cfg.root, &cfg.scratch);
    let limit = Duration::from_millis(cfg.limit_ms);
    if let Some(c) = &cfg.check {
        let o = if c.kind.is_command() {
            commands::run_limited(c.kind, &c.path, &c.args, &ctx, limit)
        } else {
            inputs::run_limited(
                c.kind,
                &c.path,
                &corpus.spectra_dir,
                Convention::ALL[c.convention],
                limit,
            )
        };
        let restart = matches!(o, Outcome::Timeout { .. });
        emit(&Msg::Checked { outcome: o });
        std::process::exit(if restart { EXIT_RESTART } else { 0 });
    }
    let dir = cfg.scratch.join(format!("worker-{}", cfg.from % cfg.stride.max(1)));
    let mut i = cfg.from;
    while i < cfg.to {
        emit(&Msg::Start { index: i });
        let case = inputs::generate(&corpus, cfg.seed, i);
        let (outcome, findings, el) = run_any(&corpus, &case, &dir, limit, &ctx);
        let timeout = matches!(outcome, Outcome::Timeout { .. });
        emit(&Msg::Done {
            index: i,
            outcome,
            findings,
            ms: el.as_millis() as u64,
        });
        if timeout {
            std::process::exit(EXIT_RESTART);
        }
        i += cfg.stride.max(1);
    }
    std::process::exit(0);
}

/// Builds the command that runs a worker with the given configuration (the example binary itself, or the
/// test binary's worker test).
pub type WorkerCommand = Arc<dyn Fn(&WorkerConfig) -> Command + Send + Sync>;

/// Settings of a campaign.
#[derive(Clone)]
pub struct Campaign {
    /// Source tree.
    pub root: PathBuf,
    /// Master seed.
    pub seed: u64,
    /// Number of generated cases.
    pub cases: u64,
    /// Worker processes in parallel.
    pub jobs: u64,
    /// Run the CLI on every `cli_every`-th case (0: never).
    pub cli_every: u64,
    /// Per-case time limit in-process.
    pub limit: Duration,
    /// Time limit of a CLI run.
    pub cli_limit: Duration,
    /// Time limit (in-process and CLI) for the special files: a correct reader refuses a FIFO or a
    /// device at once, so this only bounds the cost of the hangs that are findings.
    pub special_limit: Duration,
    /// Scratch directory.
    pub scratch: PathBuf,
    /// Where to write reproducers (none: do not write).
    pub findings_dir: Option<PathBuf>,
    /// Minimise one case per signature.
    pub minimize: bool,
    /// Also run the special files.
    pub special: bool,
    /// The `stochvib` binary.
    pub bin: PathBuf,
    /// How to start a worker.
    pub worker: WorkerCommand,
    /// Print progress to stderr.
    pub progress: bool,
    /// Stop starting new cases after this long (the cases run so far are counted).
    pub budget: Option<Duration>,
}

/// Cases one worker process evaluates before the supervisor checks the time budget and starts the next.
const CASES_PER_WORKER: u64 = 20_000;

/// Where a finding came from.
#[derive(Debug, Clone)]
pub enum Source {
    /// Generated case `i`.
    Case(u64),
    /// A special file.
    Special(String),
}

impl std::fmt::Display for Source {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Source::Case(i) => write!(f, "case {i}"),
            Source::Special(n) => write!(f, "special file `{n}`"),
        }
    }
}

/// All occurrences of one signature.
#[derive(Debug, Clone)]
pub struct SigRecord {
    /// Invariant class.
    pub class: String,
    /// Signature.
    pub signature: String,
    /// Number of cases.
    pub count: usize,
    /// The first case.
    pub first: Source,
    /// Its detail.
    pub detail: String,
    /// The first case's mutations.
    pub describe: String,
    /// Reproducer written.
    pub reproducer: Option<PathBuf>,
    /// Its text, if small and UTF-8.
    pub reproducer_text: Option<String>,
    /// Command that shows it.
    pub command: String,
    /// For timeouts: what a longer limit showed.
    pub recheck: Option<String>,
}

/// Result of a campaign.
#[derive(Debug, Clone, Default)]
pub struct Summary {
    /// Seed.
    pub seed: u64,
    /// Generated cases evaluated.
    pub cases: u64,
    /// Special files evaluated.
    pub special: usize,
    /// CLI runs.
    pub cli_runs: u64,
    /// Worker restarts (after timeouts and crashes).
    pub restarts: u64,
    /// Outcome labels.
    pub outcomes: BTreeMap<String, usize>,
    /// Cases per class.
    pub by_class: BTreeMap<String, usize>,
    /// Per signature.
    pub signatures: BTreeMap<String, SigRecord>,
    /// Wall time.
    pub elapsed: Duration,
    /// Slowest in-process case, ms.
    pub slowest_ms: u64,
    /// Totals per format or command ([`DocKind::label`]; special files and output targets separately).
    pub formats: BTreeMap<String, FormatTotals>,
    /// Whether the time budget stopped the campaign before all its cases.
    pub stopped_by_budget: bool,
}

/// The totals of one format or command: cases evaluated in-process, CLI runs, and the cases that panicked,
/// died of a signal or hung (in-process or in the CLI), and that broke any asserted invariant.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct FormatTotals {
    /// Cases evaluated in-process.
    pub cases: u64,
    /// CLI runs.
    pub cli_runs: u64,
    /// Panics (in-process, or a CLI exit 101).
    pub panics: u64,
    /// Deaths by a signal (a worker process, or the CLI).
    pub signals: u64,
    /// Time limits passed (in-process, or the CLI).
    pub hangs: u64,
    /// Cases with a finding of an asserted class (panics, signals and hangs included).
    pub findings: u64,
    /// In-process time of the cases, ms.
    #[serde(default)]
    pub ms: u64,
}

impl FormatTotals {
    /// Adds one case: evaluated in-process or not, run through the CLI or not, with these findings.
    pub fn count(&mut self, in_process: bool, cli: bool, findings: &[Finding]) {
        let has = |classes: &[&str]| findings.iter().any(|f| classes.contains(&f.class.as_str()));
        self.cases += u64::from(in_process);
        self.cli_runs += u64::from(cli);
        self.panics += u64::from(has(&["panic", "cli-panic"]));
        self.signals += u64::from(has(&["crash", "cli-crash"]));
        self.hangs += u64::from(has(&["timeout", "cli-timeout"]));
        self.findings += u64::from(findings.iter().any(|f| !inputs::is_soft(&f.class)));
    }

    /// The sum of two totals.
    pub fn plus(self, o: FormatTotals) -> FormatTotals {
        FormatTotals {
            cases: self.cases + o.cases,
            cli_runs: self.cli_runs + o.cli_runs,
            panics: self.panics + o.panics,
            signals: self.signals + o.signals,
            hangs: self.hangs + o.hangs,
            findings: self.findings + o.findings,
            ms: self.ms + o.ms,
        }
    }
}

/// The per-format totals as a markdown table with a total row.
pub fn totals_table(formats: &BTreeMap<String, FormatTotals>) -> String {
    use std::fmt::Write as _;
    let mut s = String::from(
        "| format / command | in-process cases | CLI runs | panics | signals | hangs | cases with findings | ms per \
         case |\n|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut all = FormatTotals::default();
    for (k, t) in formats {
        all = all.plus(*t);
        let _ = writeln!(
            s,
            "| {k} | {} | {} | {} | {} | {} | {} | {:.1} |",
            t.cases,
            t.cli_runs,
            t.panics,
            t.signals,
            t.hangs,
            t.findings,
            t.ms as f64 / t.cases.max(1) as f64
        );
    }
    let _ = writeln!(
        s,
        "| **total** | **{}** | **{}** | **{}** | **{}** | **{}** | **{}** | {:.1} |",
        all.cases,
        all.cli_runs,
        all.panics,
        all.signals,
        all.hangs,
        all.findings,
        all.ms as f64 / all.cases.max(1) as f64
    );
    s
}

impl Summary {
    /// Counts one case of format `format` in [`Summary::formats`].
    fn tally(&mut self, format: &str, in_process: bool, cli: bool, findings: &[Finding]) {
        self.formats
            .entry(format.to_string())
            .or_default()
            .count(in_process, cli, findings);
    }

    fn add(&mut self, src: Source, findings: &[Finding], describe: &str, command: &str) {
        let mut classes: Vec<&str> = findings.iter().map(|f| f.class.as_str()).collect();
        classes.sort();
        classes.dedup();
        for c in classes {
            *self.by_class.entry(c.to_string()).or_default() += 1;
        }
        let mut seen = Vec::new();
        for f in findings {
            if seen.contains(&&f.signature) {
                continue;
            }
            seen.push(&f.signature);
            let r = self.signatures.entry(f.signature.clone()).or_insert_with(|| SigRecord {
                class: f.class.clone(),
                signature: f.signature.clone(),
                count: 0,
                first: src.clone(),
                detail: f.detail.clone(),
                describe: describe.to_string(),
                reproducer: None,
                reproducer_text: None,
                command: command.to_string(),
                recheck: None,
            });
            r.count += 1;
        }
    }

    /// The totals of a campaign as JSON (seed, cases, special files, CLI runs, seconds, whether the budget
    /// stopped it, hard findings by class, per-format totals).
    pub fn totals_json(&self) -> serde_json::Value {
        serde_json::json!({
            "seed": self.seed,
            "cases": self.cases,
            "special": self.special,
            "cli_runs": self.cli_runs,
            "seconds": self.elapsed.as_secs_f64(),
            "stopped_by_budget": self.stopped_by_budget,
            "hard_findings": self.hard(),
            "formats": self.formats,
        })
    }

    /// Cases with a hard (asserted) finding, by class.
    pub fn hard(&self) -> BTreeMap<String, usize> {
        self.by_class
            .iter()
            .filter(|(c, _)| !inputs::is_soft(c))
            .map(|(c, n)| (c.clone(), *n))
            .collect()
    }

    /// Hard findings that are findings of the code, not of the machine: [`Summary::hard`] without the
    /// time-outs whose every signature finished when evaluated again with the 15× limit ("slow, not hung").
    /// A loaded machine can push a case past its limit; a hang stays a hang under the longer limit.
    pub fn hard_not_slow(&self) -> BTreeMap<String, usize> {
        let slow_only = |class: &str| {
            let mut records = self.signatures.values().filter(|r| r.class == class).peekable();
            records.peek().is_some()
                && records.all(|r| r.recheck.as_deref().is_some_and(|x| x.ends_with("slow, not hung")))
        };
        let mut hard = self.hard();
        hard.retain(|class, _| !(class == "timeout" && slow_only(class)));
        hard
    }

    /// Text report.
    pub fn render(&self) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "input fuzzing: seed {}, {} generated cases + {} special files, {} CLI runs, {} worker restarts, {:.1} s (slowest finished case {} ms)",
            self.seed,
            self.cases,
            self.special,
            self.cli_runs,
            self.restarts,
            self.elapsed.as_secs_f64(),
            self.slowest_ms
        );
        let _ = writeln!(s, "outcomes: {}", fmt_counts(&self.outcomes));
        let _ = write!(s, "{}", totals_table(&self.formats));
        let _ = writeln!(s, "cases with findings, by class (hard): {}", fmt_counts(&self.hard()));
        let soft: BTreeMap<String, usize> = self
            .by_class
            .iter()
            .filter(|(c, _)| inputs::is_soft(c))
            .map(|(c, n)| (c.clone(), *n))
            .collect();
        let _ = writeln!(s, "soft (reported, not asserted): {}", fmt_counts(&soft));
        let mut recs: Vec<&SigRecord> = self.signatures.values().collect();
        recs.sort_by(|a, b| {
            (inputs::is_soft(&a.class), &a.class, &a.signature).cmp(&(
                inputs::is_soft(&b.class),
                &b.class,
                &b.signature,
            ))
        });
        let _ = writeln!(s, "{} signatures:", recs.len());
        for r in recs {
            let _ = writeln!(
                s,
                "- [{}] {} — {} case(s); first {}",
                r.class, r.signature, r.count, r.first
            );
            let _ = writeln!(s, "    mutations: {}", r.describe);
            if !r.detail.is_empty() {
                let _ = writeln!(s, "    detail: {}", r.detail);
            }
            if let Some(x) = &r.recheck {
                let _ = writeln!(s, "    recheck: {x}");
            }
            if let Some(p) = &r.reproducer {
                let _ = writeln!(s, "    reproducer: {}   ({})", p.display(), r.command);
            }
        }
        s
    }
}

/// `a 3, b 5`.
pub fn fmt_counts(c: &BTreeMap<String, usize>) -> String {
    if c.is_empty() {
        return "none".into();
    }
    c.iter().map(|(k, v)| format!("{k} {v}")).collect::<Vec<_>>().join(", ")
}

/// Reads a worker's protocol lines until it exits; returns its exit, the index of a case that started
/// and did not finish, and its stderr tail.
fn drive_worker(mut cmd: Command, mut on: impl FnMut(Msg)) -> (Exit, Option<u64>, String) {
    process::limit_memory(&mut cmd, process::DEFAULT_MEMORY_LIMIT);
    cmd.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
    let mut child =
        stochvib::store::spawn_child(&mut cmd).unwrap_or_else(|e| panic!("cannot start worker {cmd:?}: {e}"));
    let stderr = child.stderr.take().unwrap();
    let err_thread = std::thread::spawn(move || {
        let mut keep = String::new();
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            keep.push_str(&line);
            keep.push('\n');
            if keep.len() > 1 << 16 {
                keep = process::tail(&keep, 1 << 15);
            }
        }
        keep
    });
    let mut running = None;
    for line in BufReader::new(child.stdout.take().unwrap())
        .lines()
        .map_while(Result::ok)
    {
        // (libtest may print `test name ... ` without a newline before the first message)
        let Some(json) = line.find(TAG).map(|i| &line[i + TAG.len()..]) else {
            continue;
        };
        let m: Msg = match serde_json::from_str(json) {
            Ok(m) => m,
            Err(e) => panic!("bad worker line {json}: {e}"),
        };
        match &m {
            Msg::Start { index } => running = Some(*index),
            Msg::Done { .. } | Msg::Checked { .. } => running = None,
        }
        on(m);
    }
    let st = child.wait().expect("wait for the worker");
    use std::os::unix::process::ExitStatusExt;
    let exit = match (st.code(), st.signal()) {
        (Some(c), _) => Exit::Code(c),
        (None, Some(s)) => Exit::Signal(s),
        _ => Exit::Code(-1),
    };
    (exit, running, err_thread.join().unwrap_or_default())
}

/// The finding of a worker that died while a case was running.
fn crash_finding(exit: Exit, stderr: &str) -> Finding {
    let last = stderr
        .lines()
        .rev()
        .find(|l| !l.trim().is_empty())
        .unwrap_or("")
        .to_string();
    // the first frame of the crate in a printed backtrace
    let frame = stderr
        .lines()
        .map(str::trim)
        .filter_map(|l| l.split_once(": ").map(|x| x.1))
        .find(|f| f.starts_with("stochvib::"))
        .map(|f| format!(" in {f}"))
        .unwrap_or_default();
    let what = if stderr.contains("overflowed its stack") {
        "stack overflow".to_string()
    } else if stderr.contains("memory allocation of") {
        format!("allocation failure{frame}")
    } else if let Some(l) = stderr.lines().find(|l| l.contains("panicked at")) {
        format!("panic while unwinding is impossible: {}", inputs::normalize_message(l))
    } else {
        inputs::normalize_message(&last)
    };
    Finding {
        class: "crash".into(),
        signature: format!("worker process {exit}: {what}"),
        detail: process::tail(stderr, 300),
    }
}

/// Evaluates one file in a fresh worker process; returns the outcome, or the finding of a crash.
pub fn check_in_worker(c: &Campaign, spec: CheckSpec, limit: Duration) -> std::result::Result<Outcome, Finding> {
    let cfg = WorkerConfig {
        root: c.root.clone(),
        scratch: c.scratch.clone(),
        seed: c.seed,
        from: 0,
        to: 0,
        stride: 1,
        limit_ms: limit.as_millis() as u64,
        check: Some(spec.clone()),
    };
    let mut cmd = (c.worker)(&cfg);
    cmd.env("STOCHVIB_FUZZ_BIN", &c.bin);
    if let Some(d) = spec.path.parent().filter(|d| d.is_dir()) {
        cmd.current_dir(d);
    }
    let mut got = None;
    let (exit, _, stderr) = drive_worker(cmd, |m| {
        if let Msg::Checked { outcome } = m {
            got = Some(outcome)
        }
    });
    match got {
        Some(o) => Ok(o),
        None => Err(crash_finding(exit, &stderr)),
    }
}

/// Runs the CLI on a case written under `dir` (given the library's outcome label `lib`); its findings,
/// or `None` when the case is not run through the CLI (a sweep too large to run whole).
fn run_cli(c: &Campaign, case: &Case, dir: &Path, lib: &str) -> Option<Vec<Finding>> {
    let json = case.index % 2 == 1;
    let ctx = context(&c.root, &c.scratch);
    let (path, args) = if case.kind.is_command() {
        let path = commands::write_case(case, dir, &ctx);
        let args = commands::cli_args(case, &path, &ctx, json)?;
        (path, args)
    } else {
        let path = inputs::write_case(case, dir);
        let args = inputs::cli_args(case.kind, &path, &c.root.join("spectra"), json);
        (path, args)
    };
    let mut cmd = Command::new(&c.bin);
    cmd.args(&args);
    if let Some(d) = path.parent().filter(|d| d.is_dir()) {
        cmd.current_dir(d);
    }
    let out = process::run(cmd, c.cli_limit, process::DEFAULT_MEMORY_LIMIT);
    Some(if case.kind.is_command() {
        commands::check_cli(case, &args, lib, &out)
    } else {
        inputs::check_cli(case, &path, &args, lib, &out)
    })
}

fn cli_command_line(case: &Case, file: &str) -> String {
    match case.kind {
        DocKind::Data | DocKind::Nonlinear => format!("stochvib analyze {file} --spectra-dir spectra"),
        DocKind::Transient => format!(
            "stochvib transient {file} --spectra-dir spectra {}",
            super::transient::cli_tail(Path::new(file)).join(" ")
        ),
        DocKind::Spectrum => format!("stochvib spectrum {file}"),
        _ => commands::command_line(case, file),
    }
}

/// Runs the campaign.
pub fn run(c: &Campaign) -> Summary {
    let start = Instant::now();
    let corpus = Arc::new(Corpus::load(&c.root));
    let _ = std::fs::remove_dir_all(&c.scratch);
    std::fs::create_dir_all(&c.scratch).unwrap();
    Fixtures::ensure(&c.root, &context(&c.root, &c.scratch).fixtures);
    let summary = Arc::new(Mutex::new(Summary {
        seed: c.seed,
        ..Summary::default()
    }));
    if c.special {
        run_special(c, &mut summary.lock().unwrap());
    }
    let jobs = c.jobs.max(1);
    let mut handles = Vec::new();
    for j in 0..jobs {
        let (c, corpus, summary) = (c.clone(), corpus.clone(), summary.clone());
        handles.push(std::thread::spawn(move || {
            let cli_dir = c.scratch.join(format!("cli-{j}"));
            let mut next = j;
            while next < c.cases {
                if c.budget.is_some_and(|b| start.elapsed() > b) {
                    summary.lock().unwrap().stopped_by_budget = true;
                    break;
                }
                let cfg = WorkerConfig {
                    root: c.root.clone(),
                    scratch: c.scratch.clone(),
                    seed: c.seed,
                    from: next,
                    to: c.cases.min(next + CASES_PER_WORKER * jobs),
                    stride: jobs,
                    limit_ms: c.limit.as_millis() as u64,
                    check: None,
                };
                let mut cmd = (c.worker)(&cfg);
                cmd.env("STOCHVIB_FUZZ_BIN", &c.bin);
                let wdir = c.scratch.join(format!("worker-{j}"));
                std::fs::create_dir_all(&wdir).unwrap();
                cmd.current_dir(&wdir);
                let mut last_done = None;
                let (exit, running, stderr) = drive_worker(cmd, |m| {
                    let Msg::Done {
                        index,
                        outcome,
                        findings,
                        ms,
                    } = m
                    else {
                        return;
                    };
                    last_done = Some(index);
                    let case = inputs::generate(&corpus, c.seed, index);
                    let label = outcome.label();
                    let mut all = findings;
                    let mut do_cli = c.cli_every > 0 && index % c.cli_every == 0;
                    if do_cli {
                        match run_cli(&c, &case, &cli_dir, &label) {
                            Some(f) => all.extend(f),
                            None => do_cli = false,
                        }
                    }
                    let mut s = summary.lock().unwrap();
                    s.cases += 1;
                    s.cli_runs += u64::from(do_cli);
                    s.tally(case.kind.label(), true, do_cli, &all);
                    if let Some(t) = s.formats.get_mut(case.kind.label()) {
                        t.ms += ms;
                    }
                    if !label.starts_with("timeout") {
                        s.slowest_ms = s.slowest_ms.max(ms);
                    }
                    *s.outcomes.entry(label).or_default() += 1;
                    let cmdline = cli_command_line(&case, &case.file_name);
                    s.add(Source::Case(index), &all, &case.describe(), &cmdline);
                    if c.progress && s.cases % 500 == 0 {
                        eprintln!(
                            "[fuzz] {} cases, {:.0} s, findings: {}",
                            s.cases,
                            start.elapsed().as_secs_f64(),
                            fmt_counts(&s.by_class)
                        );
                    }
                });
                match (exit, running) {
                    (Exit::Code(0), None) => next = last_done.map(|i| i + jobs).unwrap_or(next + jobs),
                    (Exit::Code(EXIT_RESTART), None) => {
                        summary.lock().unwrap().restarts += 1;
                        next = last_done.map(|i| i + jobs).unwrap_or(next + jobs);
                    }
                    (_, Some(i)) => {
                        let case = inputs::generate(&corpus, c.seed, i);
                        let f = crash_finding(exit, &stderr);
                        let mut s = summary.lock().unwrap();
                        s.cases += 1;
                        s.restarts += 1;
                        *s.outcomes.entry("crash".into()).or_default() += 1;
                        let cmdline = cli_command_line(&case, &case.file_name);
                        s.tally(case.kind.label(), true, false, std::slice::from_ref(&f));
                        s.add(Source::Case(i), &[f], &case.describe(), &cmdline);
                        next = i + jobs;
                    }
                    (e, None) => panic!("worker exited with {e} between cases: {stderr}"),
                }
            }
        }));
    }
    for h in handles {
        h.join().expect("campaign thread");
    }
    let mut s = Arc::try_unwrap(summary).unwrap().into_inner().unwrap();
    recheck_timeouts(c, &corpus, &mut s);
    if let Some(dir) = &c.findings_dir {
        write_reproducers(c, &corpus, &mut s, dir);
    }
    s.elapsed = start.elapsed();
    s
}

/// Writes `case` under `dir` and describes it for a worker's check; also returns its path.
fn spec_of(c: &Campaign, case: &Case, dir: &Path) -> (CheckSpec, PathBuf) {
    let path = if case.kind.is_command() {
        commands::write_case(case, dir, &context(&c.root, &c.scratch))
    } else {
        inputs::write_case(case, dir)
    };
    let spec = CheckSpec {
        path: path.clone(),
        kind: case.kind,
        convention: conv_index(case.convention),
        args: case.args.clone(),
    };
    (spec, path)
}

/// The findings of an outcome of `case` at `path`, by its kind.
fn check_any(c: &Campaign, case: &Case, path: &Path, o: &Outcome) -> Vec<Finding> {
    if case.kind.is_command() {
        commands::check(case, path, o, &context(&c.root, &c.scratch))
    } else {
        inputs::check(case, path, o)
    }
}

/// Evaluates a timed-out case again with a 15× limit: a slow case finishes, a hang does not.
fn recheck_timeouts(c: &Campaign, corpus: &Corpus, s: &mut Summary) {
    let long = c.limit * 15;
    for r in s.signatures.values_mut() {
        if r.class != "timeout" {
            continue;
        }
        let Source::Case(i) = r.first else { continue };
        let case = inputs::generate(corpus, c.seed, i);
        let (spec, _) = spec_of(c, &case, &c.scratch.join("recheck"));
        let t = Instant::now();
        r.recheck = Some(match check_in_worker(c, spec, long) {
            Ok(Outcome::Timeout { .. }) => format!("still running after {:.0} s: a hang", long.as_secs_f64()),
            Ok(o) => format!(
                "finished in {:.1} s ({}): slow, not hung",
                t.elapsed().as_secs_f64(),
                o.label()
            ),
            Err(f) => format!("crashed: {}", f.signature),
        });
    }
}

// ------------------------------------------------------------------------------------------------------
// Special files
// ------------------------------------------------------------------------------------------------------

struct Special {
    name: &'static str,
    kind: DocKind,
    path: PathBuf,
    note: &'static str,
    text: Vec<u8>,
    /// The command's arguments ([`Case::args`]).
    args: Vec<String>,
}

/// Makes a FIFO at `p` (replacing what is there).
pub fn mkfifo(p: &Path) {
    let _ = std::fs::remove_file(p);
    let c = std::ffi::CString::new(p.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    let r = unsafe { libc::mkfifo(c.as_ptr(), 0o600) };
    assert_eq!(r, 0, "mkfifo {}", p.display());
}

fn specials(c: &Campaign) -> Vec<Special> {
    let d = c.scratch.join("special");
    std::fs::create_dir_all(&d).unwrap();
    let fifo = d.join("fifo.toml");
    mkfifo(&fifo);
    let dir = d.join("directory.toml");
    std::fs::create_dir_all(&dir).unwrap();
    let empty = d.join("empty.toml");
    std::fs::write(&empty, b"").unwrap();
    let nul = d.join("nul.toml");
    std::fs::write(&nul, b"\0\0\0title = 1\n").unwrap();
    let lp = d.join("loop.toml");
    let _ = std::fs::remove_file(&lp);
    std::os::unix::fs::symlink("loop.toml", &lp).unwrap();
    let qc = std::fs::read_to_string(c.root.join("data/quarter-car-model.toml")).unwrap();
    let with_spec = |name: &str, target: &Path| {
        let p = d.join(name);
        let t = qc.replace(
            "spectrum = \"iso8608-c\"",
            &format!("spectrum = {:?}", target.display().to_string()),
        );
        std::fs::write(&p, &t).unwrap();
        (p, t.into_bytes())
    };
    let (sf, sft) = with_spec("spectrum-fifo.toml", &fifo);
    let (sz, szt) = with_spec("spectrum-dev-zero.toml", Path::new("/dev/zero"));
    let big = d.join("big-comment.toml");
    let mut bt = Vec::with_capacity(21 << 20);
    for _ in 0..(20 << 20) / 64 {
        bt.extend_from_slice(b"# 345678901234567890123456789012345678901234567890123456789012\n");
    }
    bt.extend_from_slice(qc.as_bytes());
    std::fs::write(&big, &bt).unwrap();
    vec![
        Special {
            name: "fifo-as-scenario",
            kind: DocKind::Data,
            path: fifo.clone(),
            note: "a FIFO nobody writes to, given as the scenario file",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "fifo-as-spectrum",
            kind: DocKind::Spectrum,
            path: fifo,
            note: "the same FIFO given as a spectrum file",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "directory",
            kind: DocKind::Data,
            path: dir,
            note: "a directory named like a scenario file",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "dev-zero",
            kind: DocKind::Data,
            path: "/dev/zero".into(),
            note: "/dev/zero as the scenario file (endless NUL bytes)",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "dev-urandom",
            kind: DocKind::Spectrum,
            path: "/dev/urandom".into(),
            note: "/dev/urandom as the spectrum file (endless random bytes)",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "empty",
            kind: DocKind::Data,
            path: empty,
            note: "an empty scenario file",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "missing",
            kind: DocKind::Data,
            path: d.join("no-such-file.toml"),
            note: "a path that does not exist",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "symlink-loop",
            kind: DocKind::Data,
            path: lp,
            note: "a symbolic link to itself",
            text: vec![],
            args: vec![],
        },
        Special {
            name: "nul-bytes",
            kind: DocKind::Data,
            path: nul,
            note: "NUL bytes before a key",
            text: b"\0\0\0title = 1\n".to_vec(),
            args: vec![],
        },
        Special {
            name: "spectrum-is-fifo",
            kind: DocKind::Data,
            path: sf,
            note: "a scenario whose [input] spectrum is the path of a FIFO",
            text: sft,
            args: vec![],
        },
        Special {
            name: "spectrum-is-dev-zero",
            kind: DocKind::Data,
            path: sz,
            note: "a scenario whose [input] spectrum is /dev/zero",
            text: szt,
            args: vec![],
        },
        Special {
            name: "big-comment",
            kind: DocKind::Data,
            path: big,
            note: "20 MiB of comment lines before a valid scenario (must succeed, quickly)",
            text: vec![],
            args: vec![],
        },
    ]
    .into_iter()
    .chain(command_specials(c, &d))
    .collect()
}

/// The special files of the command cases: a FIFO, `/dev/zero`, a directory and a 2 GiB (sparse) file as
/// a road profile, a FIFO as a replayed profile and as a workday file, a workday whose scenario is
/// `/dev/zero`, a 1 MiB line in a profile, a FIFO and `/dev/null` in a merge set.
fn command_specials(c: &Campaign, d: &Path) -> Vec<Special> {
    let fifo = d.join("fifo.csv");
    mkfifo(&fifo);
    let dir = d.join("directory.csv");
    std::fs::create_dir_all(&dir).unwrap();
    let big = d.join("huge-sparse.csv");
    std::fs::File::create(&big).unwrap().set_len(2 << 30).unwrap();
    let long = d.join("long-line.csv");
    let mut t = b"distance [m], left [mm]\n0.0,".to_vec();
    t.extend(std::iter::repeat_n(b'1', 1 << 20));
    std::fs::write(&long, &t).unwrap();
    let zero_day = d.join("dev-zero-day.toml");
    std::fs::write(
        &zero_day,
        "title = \"x\"\n[[task]]\nname = \"a\"\nscenario = \"/dev/zero\"\nduration = \"1 h\"\n",
    )
    .unwrap();
    let road = Corpus::load(&c.root)
        .commands
        .road_scenarios
        .first()
        .cloned()
        .unwrap_or_default();
    let sp = |name, kind, path: &Path, note, args: Vec<String>| Special {
        name,
        kind,
        path: path.to_path_buf(),
        note,
        text: vec![],
        args,
    };
    vec![
        sp(
            "profile-fifo",
            DocKind::Profile,
            &fifo,
            "a FIFO nobody writes to as the road profile",
            vec![],
        ),
        sp(
            "profile-dev-zero",
            DocKind::Profile,
            Path::new("/dev/zero"),
            "/dev/zero as the road profile",
            vec![],
        ),
        sp(
            "profile-directory",
            DocKind::Profile,
            &dir,
            "a directory named like a profile",
            vec![],
        ),
        sp(
            "profile-2-gib",
            DocKind::Profile,
            &big,
            "a 2 GiB (sparse) profile: refused by its size, unread",
            vec![],
        ),
        sp(
            "profile-long-line",
            DocKind::Profile,
            &long,
            "a profile whose second line is 1 MiB long",
            vec![],
        ),
        sp(
            "replay-fifo",
            DocKind::Replay,
            &fifo,
            "a FIFO as the replayed profile",
            vec![road],
        ),
        sp(
            "workday-fifo",
            DocKind::Workday,
            &fifo,
            "a FIFO as the workday file",
            vec![],
        ),
        sp(
            "workday-dev-zero",
            DocKind::Workday,
            &zero_day,
            "a workday whose scenario is /dev/zero",
            vec![],
        ),
        sp(
            "merge-fifo",
            DocKind::Merge,
            &d.join("merged.h5"),
            "a FIFO among the shard files",
            merge_args(&["A0", "fifo", "A1", "A2"]),
        ),
        sp(
            "merge-dev-null",
            DocKind::Merge,
            &d.join("merged.h5"),
            "/dev/null among the shard files",
            merge_args(&["A0", "devnull", "A1", "A2"]),
        ),
    ]
}

fn merge_args(members: &[&str]) -> Vec<String> {
    members
        .iter()
        .map(|m| m.to_string())
        .chain(["out=new".to_string(), "seed=1".into()])
        .collect()
}

fn special_case(sp: &Special) -> Case {
    Case {
        index: u64::MAX,
        origin: sp.name.into(),
        kind: sp.kind,
        file_name: sp
            .path
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default(),
        bytes: sp.text.clone(),
        mutations: vec![],
        raw: vec![sp.note.to_string()],
        convention: Convention::TwoSidedAngular,
        doc: None,
        must_reject: vec![],
        args: sp.args.clone(),
    }
}

fn run_special(c: &Campaign, s: &mut Summary) {
    for sp in specials(c) {
        let case = special_case(&sp);
        let spec = CheckSpec {
            path: sp.path.clone(),
            kind: sp.kind,
            convention: 0,
            args: sp.args.clone(),
        };
        let (label, mut f) = match check_in_worker(c, spec, c.special_limit) {
            Ok(o) => (o.label(), check_any(c, &case, &sp.path, &o)),
            Err(f) => ("crash".to_string(), vec![f]),
        };
        let ctx = context(&c.root, &c.scratch);
        let args = if sp.kind.is_command() {
            commands::cli_args(&case, &sp.path, &ctx, false).unwrap_or_default()
        } else {
            inputs::cli_args(sp.kind, &sp.path, &c.root.join("spectra"), false)
        };
        let mut cmd = Command::new(&c.bin);
        cmd.args(&args);
        let out = process::run(cmd, c.special_limit, process::DEFAULT_MEMORY_LIMIT);
        f.extend(if sp.kind.is_command() {
            commands::check_cli(&case, &args, &label, &out)
        } else {
            inputs::check_cli(&case, &sp.path, &args, &label, &out)
        });
        s.special += 1;
        s.cli_runs += 1;
        s.tally("special files (input rule)", true, true, &f);
        *s.outcomes.entry(format!("special:{label}")).or_default() += 1;
        let cmdline = format!(
            "{} ({})",
            cli_command_line(&case, &sp.path.display().to_string()),
            sp.note
        );
        if c.progress {
            eprintln!("[fuzz] special {}: library {label}, CLI {}", sp.name, out.exit);
        }
        s.add(Source::Special(sp.name.into()), &f, sp.note, &cmdline);
    }
    let ctx = context(&c.root, &c.scratch);
    for p in commands::output_probes(&ctx, &c.scratch.join("output-rule")) {
        let f = commands::run_output_probe(&c.bin, &p, c.cli_limit);
        s.special += 1;
        s.cli_runs += 1;
        s.tally("output targets (output rule, CLI)", false, true, &f);
        if c.progress {
            eprintln!("[fuzz] output rule {}: {} findings", p.name, f.len());
        }
        s.add(Source::Special(p.name.into()), &f, p.name, &p.args.join(" "));
    }
}

// ------------------------------------------------------------------------------------------------------
// Minimisation and reproducers
// ------------------------------------------------------------------------------------------------------

/// Whether `cand` (written under `dir`) still shows signature `sig` of class `class`.
fn reproduces(c: &Campaign, cand: &Case, class: &str, sig: &str, dir: &Path) -> bool {
    let (spec, path) = spec_of(c, cand, dir);
    let outcome = check_in_worker(c, spec, c.limit);
    if class == "crash" {
        return matches!(outcome, Err(f) if f.signature == sig);
    }
    let Ok(o) = outcome else { return false };
    let mut found = check_any(c, cand, &path, &o);
    if class.starts_with("cli-") {
        found.extend(run_cli(c, cand, dir, &o.label()).unwrap_or_default());
    }
    found.iter().any(|f| f.signature == sig)
}

/// A smaller case that still shows the signature: keys deleted one at a time (structured cases), else
/// lines deleted one at a time; the paths a `must_reject` expectation is about are kept.
fn minimize(c: &Campaign, case: &Case, class: &str, sig: &str) -> Case {
    let dir = c.scratch.join("minimize");
    let t0 = Instant::now();
    let budget = if class == "timeout" || class == "cli-timeout" {
        Duration::from_secs(60)
    } else {
        Duration::from_secs(40)
    };
    let mut best = case.clone();
    let mut evals = 0;
    let over = |evals: usize| evals >= 400 || t0.elapsed() > budget;
    if let (true, Some(doc)) = (case.raw.is_empty(), &case.doc) {
        let protected: Vec<Vec<Seg>> = case
            .must_reject
            .iter()
            .map(|(_, p, _)| super::mutate::parse_path(p))
            .collect();
        let mut doc = doc.clone();
        for _pass in 0..2 {
            let mut i = 0;
            loop {
                let paths = all_paths(&doc);
                if i >= paths.len() || over(evals) {
                    break;
                }
                let p = &paths[i];
                // keep the protected values, their containers and their elements
                if protected.iter().any(|q| q.starts_with(p) || p.starts_with(q)) {
                    i += 1;
                    continue;
                }
                let mut cand_doc = doc.clone();
                remove(&mut cand_doc, p);
                let Ok(text) = toml::to_string(&cand_doc) else {
                    i += 1;
                    continue;
                };
                let mut cand = case.clone();
                cand.bytes = text.into_bytes();
                cand.doc = Some(cand_doc.clone());
                evals += 1;
                if reproduces(c, &cand, class, sig, &dir) {
                    doc = cand_doc;
                    best = cand;
                } else {
                    i += 1;
                }
            }
        }
    } else {
        let mut lines: Vec<Vec<u8>> = case.bytes.split(|b| *b == b'\n').map(<[u8]>::to_vec).collect();
        let mut i = lines.len();
        while i > 0 && !over(evals) {
            i -= 1;
            let mut cand_lines = lines.clone();
            cand_lines.remove(i);
            let mut cand = case.clone();
            cand.bytes = cand_lines.join(&b'\n');
            evals += 1;
            if reproduces(c, &cand, class, sig, &dir) {
                lines = cand_lines;
                best = cand;
            }
        }
    }
    best
}

fn slug(s: &str) -> String {
    let mut out: String = s
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    while out.contains("--") {
        out = out.replace("--", "-");
    }
    out.trim_matches('-').chars().take(60).collect()
}

fn write_reproducers(c: &Campaign, corpus: &Corpus, s: &mut Summary, dir: &Path) {
    let dir = dir.join("inputs");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let keys: Vec<String> = s.signatures.keys().cloned().collect();
    for (n, k) in keys.iter().enumerate() {
        let r = s.signatures.get_mut(k).unwrap();
        let Source::Case(i) = r.first else { continue };
        let case = inputs::generate(corpus, c.seed, i);
        let case = if c.minimize && !inputs::is_soft(&r.class) && !case.kind.is_command() {
            if c.progress {
                eprintln!("[fuzz] minimising {} ({} of {})", r.signature, n + 1, keys.len());
            }
            minimize(c, &case, &r.class, &r.signature)
        } else {
            case
        };
        let name = format!(
            "{:03}-{}-{}",
            n + 1,
            slug(&r.class),
            slug(&normalize_path(&r.signature))
        );
        let sub = dir.join(&name);
        std::fs::create_dir_all(&sub).unwrap();
        let p = sub.join(&case.file_name);
        std::fs::write(&p, &case.bytes).unwrap();
        r.command = cli_command_line(&case, &p.display().to_string());
        r.reproducer_text = std::str::from_utf8(&case.bytes)
            .ok()
            .filter(|t| t.len() <= 3000)
            .map(str::to_string);
        r.reproducer = Some(p);
    }
    let _ = std::fs::write(dir.join("SUMMARY.txt"), s.render());
    let mut md = String::from("# Reproducers\n\n");
    for r in s.signatures.values() {
        md.push_str(&format!(
            "## [{}] {}\n\n{} case(s); first {}: {}\n\n",
            r.class, r.signature, r.count, r.first, r.describe
        ));
        if !r.detail.is_empty() {
            md.push_str(&format!("detail: {}\n\n", r.detail));
        }
        if let Some(x) = &r.recheck {
            md.push_str(&format!("recheck: {x}\n\n"));
        }
        md.push_str(&format!("`{}`\n\n", r.command));
        if let Some(t) = &r.reproducer_text {
            md.push_str(&format!("```toml\n{t}\n```\n\n"));
        }
    }
    let _ = std::fs::write(dir.join("REPRODUCERS.md"), md);
}
