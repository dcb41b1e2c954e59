//! `stochvib transient SCENARIO [--monte-carlo N -o run.h5]` and the merge of transient shard files: parse
//! the arguments, call the library, print.

use std::path::PathBuf;
use stochvib::report::transient_report::SigmaComparisons;
use stochvib::scenario::{load_scenario, Catalogue};
use stochvib::store::Compression;
use stochvib::study::transient_answers::{answers, evolutionary_analysis};
use stochvib::study::transient_mc::{
    check_run_size, check_run_size_of, compare_sigma, simulate_road_grid, simulate_transient, TransientMcOptions,
};
use stochvib::study::transient_run::{exact_solution, has_exact_route, transient_setup};
use stochvib::transient::monte_carlo::read_transient_run;
use stochvib::transient::TransientRunSummary;

/// False-alarm probability of the σ(t) verdict over all reported times together.
pub const VERDICT_ALPHA: f64 = 1e-3;

/// `stochvib transient`.
#[derive(clap::Args)]
pub struct TransientArgs {
    /// Scenario file with a [transient] section (docs/transients.md).
    scenario: PathBuf,
    /// Monte Carlo realizations of the same transient (written to -o).
    #[arg(long, value_name = "N", requires = "output")]
    monte_carlo: Option<usize>,
    /// The run file of --monte-carlo (written as FILE.tmp and renamed when complete; an interrupted run
    /// resumes); with --shard, the run directory that receives DIR/shard-<I>-of-<N>.h5.
    #[arg(short = 'o', long = "output", requires = "monte_carlo")]
    output: Option<PathBuf>,
    /// Master seed; realization i uses stream (seed, i).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Integration steps per reported interval of the Monte Carlo realizations.
    #[arg(long, default_value_t = 4)]
    substeps: usize,
    /// Realizations per shard.
    #[arg(long, default_value_t = 50)]
    shard_size: usize,
    /// Compute only shard I of N of the run (merge the files with `stochvib merge`).
    #[arg(long, value_name = "I|auto", requires = "monte_carlo")]
    shard: Option<String>,
    /// N, the number of shards (with --shard).
    #[arg(long, value_name = "N", requires = "shard")]
    of: Option<usize>,
    /// Store every realization at the reported times.
    #[arg(long)]
    store_raw: bool,
    /// Confidence of the per-time intervals and of the DKW band of the maxima.
    #[arg(long, default_value_t = 0.95)]
    confidence: f64,
    /// Replace an existing finished run file.
    #[arg(long)]
    overwrite: bool,
    /// Refuse a Monte Carlo batch whose time estimate (a lower bound: one normal draw per state and step)
    /// exceeds this many hours.
    #[arg(long, value_name = "H", default_value_t = stochvib::simulate::resources::DEFAULT_MAX_HOURS, requires = "monte_carlo")]
    max_hours: f64,
    /// Directory of spectrum files (default: $STOCHVIB_SPECTRA, else ./spectra, else the built-in catalogue).
    #[arg(long)]
    spectra_dir: Option<PathBuf>,
    /// Print JSON (every reported time).
    #[arg(long)]
    json: bool,
    /// Monte Carlo on roads synthesised on a spatial grid and sampled along x(t) (for a road under a speed
    /// profile; taken by itself for a road without an exact route).
    #[arg(long, requires = "monte_carlo")]
    road_grid: bool,
    /// The grid step Δx of --road-grid, m (default: 0.1·v_min/ω_max of the vehicle).
    #[arg(long, value_name = "M", requires = "monte_carlo")]
    road_step: Option<f64>,
    /// Draw σ(t) and mean(t) of every output by the exact route into DIR (SVG and PNG; docs/gallery.md).
    #[arg(long, value_name = "DIR")]
    plots: Option<PathBuf>,
}

/// Runs `stochvib transient`; `catalogue` resolves `--spectra-dir`, `progress` prints the shards.
pub fn transient(
    a: TransientArgs,
    catalogue: &dyn Fn(&Option<PathBuf>) -> Catalogue,
    progress: &dyn Fn(usize, usize),
    shard_output: &dyn Fn(PathBuf, &Option<stochvib::study::ShardChoice>) -> anyhow::Result<PathBuf>,
) -> anyhow::Result<()> {
    let choice = match &a.shard {
        Some(spec) => Some(stochvib::study::resolve_part(spec, a.of, &|k| std::env::var(k).ok())?),
        None => None,
    };
    if let Some(dir) = &a.plots {
        stochvib::plot::chart::check_picture_dir(dir)?; // before any work
    }
    if let (Some(_), Some(out), None) = (a.monte_carlo, &a.output, &choice) {
        // the run file's target before the exact route and its pictures (the writer checks it again)
        stochvib::io_rules::check_output(out, &stochvib::store::RUN_FILE, &[&a.scenario], a.overwrite)?;
    }
    let sc = load_scenario(&a.scenario, catalogue(&a.spectra_dir).dir())?;
    let exact = has_exact_route(&sc)?;
    let opts = mc_options(&a, &choice);
    // the set-up of the exact route's run, read once for the size check and the route
    let setup = if exact && !a.road_grid {
        Some(transient_setup(&sc)?)
    } else {
        None
    };
    if a.monte_carlo.is_some() && a.output.is_some() {
        // the run's size before the exact route and the analytic curves (the run checks it again)
        match &setup {
            Some(s) => check_run_size_of(s, &opts),
            None => check_run_size(&sc, &opts, a.road_grid || !exact, a.road_step),
        }
        .map_err(|e| super::named_by_flag(e, "--monte-carlo"))?;
    }
    let answers = if exact {
        let setup = match setup {
            Some(s) => s,
            None => transient_setup(&sc)?,
        };
        let sol = exact_solution(&sc, &setup)?;
        let r = answers(&sc, &setup, &sol);
        if let Some(dir) = &a.plots {
            for f in stochvib::plot::transient_plots::exact_plots(&r, dir)? {
                eprintln!("wrote {}", f.display());
            }
        }
        Some((setup, sol, r))
    } else {
        None
    };
    let evolutionary = match (&answers, a.monte_carlo) {
        (Some(_), _) => None,
        // with a road-grid run, a road on which the evolutionary route holds at no time still gets its run
        (None, Some(_)) => evolutionary_analysis(&sc).map_err(|e| eprintln!("note: {e}")).ok(),
        (None, None) => Some(evolutionary_analysis(&sc)?),
    };
    let mc = match (a.monte_carlo, &a.output) {
        (Some(_), Some(out)) => {
            let out = shard_output(out.clone(), &choice)?;
            let ran = match &answers {
                Some((setup, sol, _)) if !a.road_grid => simulate_transient(&sc, setup, sol, &opts, &out, progress),
                _ => simulate_road_grid(&sc, &opts, a.road_step, &out, progress),
            };
            let (summary, notes) = ran.map_err(|e| super::named_by_flag(e, "--monte-carlo"))?;
            for n in notes {
                eprintln!("note: {n}");
            }
            Some(summary)
        }
        _ => None,
    };
    let comparison = match &mc {
        Some(s) => Some(SigmaComparisons(compare_sigma(
            &read_transient_run(&s.path)?.1,
            VERDICT_ALPHA,
        )?)),
        None => None,
    };
    let r = answers.map(|a| a.2);
    if a.json {
        let all =
            serde_json::json!({ "exact": r, "evolutionary": evolutionary, "monte_carlo": mc, "sigma": comparison });
        println!("{}", serde_json::to_string_pretty(&all)?);
        return Ok(());
    }
    if let Some(r) = r.as_ref().or(evolutionary.as_ref()) {
        print!("{r}");
    }
    if let (Some(s), Some(c)) = (&mc, &comparison) {
        print!("{c}");
        print_summary(s);
    }
    Ok(())
}

/// The Monte Carlo options of the arguments (`realizations` 0 without `--monte-carlo`).
fn mc_options(a: &TransientArgs, choice: &Option<stochvib::study::ShardChoice>) -> TransientMcOptions {
    TransientMcOptions {
        realizations: a.monte_carlo.unwrap_or(0),
        substeps: a.substeps,
        seed: a.seed,
        shard_size: a.shard_size,
        confidence: a.confidence,
        store_raw: a.store_raw,
        compression: Compression::default(),
        part: choice.as_ref().map(|c| c.part),
        overwrite: a.overwrite,
        max_hours: a.max_hours,
    }
}

/// The run file and the verdicts of the maxima against their DKW band.
fn print_summary(s: &TransientRunSummary) {
    println!(
        "\nrun file {} ({} realizations, {} shards, {} resumed); DKW band ε = {:.4}",
        s.path.display(),
        s.n_realizations,
        s.n_shards,
        s.resumed_shards,
        s.dkw_epsilon
    );
    for v in &s.verdicts {
        for b in &v.verdicts {
            println!(
                "  {} {}: largest distance {:.4} at {:.4e} ({})",
                v.output,
                b.method,
                b.distance,
                b.at,
                if b.inside {
                    "inside the band"
                } else {
                    "OUTSIDE the band"
                }
            );
        }
    }
    for n in &s.notes {
        println!("note: {n}");
    }
}
