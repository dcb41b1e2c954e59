//! `Scenario.transient`: the non-stationary response of a scenario with a `[transient]` section (`stochvib
//! transient`): σ(t), crossing rates and mission extremes by the exact route, and optionally a Monte Carlo
//! batch of the same transient with σ(t) compared against the exact one.

use std::path::{Path, PathBuf};
use stochvib::report::transient_report::SigmaComparisons;
use stochvib::scenario::Scenario;
use stochvib::study::transient_answers::{answers, TransientAnalysis};
use stochvib::study::transient_mc::{compare_sigma, simulate_transient, TransientMcOptions};
use stochvib::study::transient_run::{exact_solution, transient_setup};
use stochvib::transient::monte_carlo::read_transient_run;
use stochvib::transient::TransientRunSummary;

/// False-alarm probability of the σ(t) verdict over all reported times together (the command-line tool's).
pub const VERDICT_ALPHA: f64 = 1e-3;

/// Where a batch's run file goes: the given path, or the shard file in that directory.
pub type Place<'a> = &'a dyn Fn(PathBuf) -> stochvib::Result<PathBuf>;

/// A Monte Carlo batch: its options and the run file (None: a temporary file, removed afterwards).
pub struct Batch {
    pub opts: TransientMcOptions,
    pub path: Option<PathBuf>,
}

/// The exact answers, and with a batch its run summary, the σ(t) comparisons and the run's notes.
pub struct Answer {
    pub exact: TransientAnalysis,
    pub monte_carlo: Option<(TransientRunSummary, SigmaComparisons, Vec<String>)>,
}

/// Removes a temporary run file (and its `.tmp`) when dropped.
struct Remove(Option<PathBuf>);

impl Drop for Remove {
    fn drop(&mut self) {
        if let Some(p) = &self.0 {
            let _ = std::fs::remove_file(p);
            let _ = std::fs::remove_file(stochvib::store::tmp_path(p));
        }
    }
}

/// A fresh temporary run file name in the system's temporary directory.
fn temporary_path() -> PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    std::env::temp_dir().join(format!("stochvib-transient-{}-{nanos}.h5", std::process::id()))
}

/// The exact route of the scenario's transient and, with `batch`, its Monte Carlo run (into `out`, the run
/// file or a shard file) with σ(t) compared at the simultaneous level 1 − [`VERDICT_ALPHA`].
pub fn transient(
    sc: &Scenario,
    batch: Option<(Batch, Place<'_>)>,
    progress: &dyn Fn(usize, usize),
) -> stochvib::Result<Answer> {
    let setup = transient_setup(sc)?;
    let sol = exact_solution(sc, &setup)?;
    let exact = answers(sc, &setup, &sol);
    let Some((b, place)) = batch else {
        return Ok(Answer {
            exact,
            monte_carlo: None,
        });
    };
    let (out, _guard) = match b.path {
        Some(p) => (place(p)?, Remove(None)),
        None => {
            let p = temporary_path();
            (p.clone(), Remove(Some(p)))
        }
    };
    let (summary, notes) = simulate_transient(sc, &setup, &sol, &b.opts, &out, progress)?;
    let comparison = SigmaComparisons(compare_sigma(&read_run(&summary.path)?, VERDICT_ALPHA)?);
    Ok(Answer {
        exact,
        monte_carlo: Some((summary, comparison, notes)),
    })
}

fn read_run(path: &Path) -> stochvib::Result<stochvib::store::transient_series::TransientSeries> {
    Ok(read_transient_run(path)?.1)
}
