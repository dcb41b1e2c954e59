//! The `stochvib` command-line tool: parses arguments, calls the library, prints.
#![warn(clippy::too_many_lines)] // no function of more than 100 lines of code (see the library's root)

#[path = "main/optimize_cli.rs"]
mod optimize_cli;
#[path = "main/record_cli.rs"]
mod record_cli;
#[path = "main/tailor_cli.rs"]
mod tailor_cli;
#[path = "main/transient_cli.rs"]
mod transient_cli;

use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use stochvib::nonlinear::monte_carlo::NonlinearRunOptions;
use stochvib::plot::{run_plots, scenario_plots_with, ScenarioPlotOptions};
use stochvib::report;
use stochvib::report::table::{ReportFormat, ToMarkdown};
use stochvib::scenario::{load_document, load_scenario, Catalogue, Document, Scenario};
use stochvib::simulate::{Route, RunOptions};
use stochvib::spectrum::Convention;
use stochvib::store::{Compression, RunFile};
use stochvib::study::{self, NonlinearAnswers, Sweep, SweepMode, SweepParam, SweepSpec};
use stochvib::study::{attach_monte_carlo, merge_runs, part_path, resolve_part, MergeOptions};

/// Stochastic vibration and random-road analysis of machines.
#[derive(Parser)]
#[command(name = "stochvib", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Where spectrum names are looked up.
#[derive(clap::Args)]
struct SpectraDir {
    /// Directory of spectrum files (default: $STOCHVIB_SPECTRA, else ./spectra, else the built-in catalogue).
    #[arg(long)]
    spectra_dir: Option<PathBuf>,
}

impl SpectraDir {
    /// The catalogue: `--spectra-dir`, else `$STOCHVIB_SPECTRA`, else `./spectra` if it exists, else the built-in
    /// catalogue embedded in the binary.
    fn catalogue(&self) -> Catalogue {
        Catalogue::chosen(self.spectra_dir.as_deref())
    }
}

/// How a report is printed: `--format`, with `--json` kept as `--format json`.
#[derive(clap::Args)]
struct Output {
    /// Print JSON; same as --format json.
    #[arg(long, conflicts_with = "format")]
    json: bool,
    /// Report format: text, markdown (tables to paste) or json.
    #[arg(long, value_enum)]
    format: Option<ReportFormat>,
}

impl Output {
    /// `--format`, or json with `--json`, else text.
    fn format(&self) -> ReportFormat {
        if self.json {
            ReportFormat::Json
        } else {
            self.format.unwrap_or_default()
        }
    }
}

/// Time step and duration of Monte Carlo realizations.
#[derive(clap::Args)]
struct Step {
    /// Time step, s (default: suggested from the system's eigenvalues).
    #[arg(long)]
    dt: Option<f64>,
    /// Duration of each realization, s (default: suggested from the slowest decay rate).
    #[arg(long)]
    duration: Option<f64>,
    /// Refuse a Monte Carlo run whose time estimate (a lower bound: one normal draw per sample) exceeds
    /// this many hours [default: 24].
    #[arg(long, value_name = "H")]
    max_hours: Option<f64>,
    /// Burn-in of a nonlinear run before its record, s (default: computed from the slowest decay rate of the
    /// Gaussian equivalent).
    #[arg(long)]
    burn_in: Option<f64>,
}

impl Step {
    /// `--max-hours`, or its default.
    fn max_hours(&self) -> f64 {
        self.max_hours
            .unwrap_or(stochvib::simulate::resources::DEFAULT_MAX_HOURS)
    }

    /// Refuses the flags of a Monte Carlo batch given without `--monte-carlo` (they would change nothing),
    /// and a batch of fewer than 2 realizations (`flag` names the count).
    fn check_batch(&self, flag: &str, realizations: Option<usize>) -> anyhow::Result<()> {
        if let Some(n) = realizations {
            if n < 2 {
                anyhow::bail!(
                    "{flag} {n}: a Monte Carlo batch needs at least 2 realizations (the interval of σ is taken across \
                     realizations)"
                );
            }
            return Ok(());
        }
        let given = [
            ("--dt", self.dt.is_some()),
            ("--duration", self.duration.is_some()),
            ("--max-hours", self.max_hours.is_some()),
        ];
        if let Some((flag, _)) = given.iter().find(|g| g.1) {
            anyhow::bail!(
                "{flag} sets the Monte Carlo batch, and there is none: give --monte-carlo N, or leave {flag} out"
            );
        }
        Ok(())
    }

    /// The given values, the missing ones suggested from what the scenario's run of `realizations` must
    /// resolve (said on stderr).
    fn resolve(&self, sc: &Scenario, realizations: usize) -> stochvib::Result<(f64, f64)> {
        if let (Some(dt), Some(d)) = (self.dt, self.duration) {
            return Ok((dt, d));
        }
        let s = sc.suggest_step(realizations)?;
        let (dt, d) = (self.dt.unwrap_or(s.dt_s), self.duration.unwrap_or(s.duration_s));
        eprintln!("time step {dt} s, duration {d} s (suggested: {})", s.reason);
        Ok((dt, d))
    }

    /// The options of a nonlinear run: the given step and duration, the missing ones suggested for route 2
    /// (said on stderr), the burn-in.
    fn nonlinear(
        &self,
        sc: &Scenario,
        answers: &NonlinearAnswers,
        run: RunOptions,
    ) -> stochvib::Result<NonlinearRunOptions> {
        let (dt, duration) = match (self.dt, self.duration) {
            (Some(dt), Some(d)) => (dt, d),
            _ => {
                let s = sc.suggest_nonlinear_step(answers)?;
                let (dt, d) = (self.dt.unwrap_or(s.dt_s), self.duration.unwrap_or(s.duration_s));
                eprintln!("time step {dt} s, duration {d} s (suggested for route 2: {})", s.reason);
                (dt, d)
            }
        };
        Ok(NonlinearRunOptions {
            run: RunOptions {
                dt_s: dt,
                duration_s: duration,
                ..run
            },
            burn_in_s: self.burn_in,
            halving_checks: None,
        })
    }
}

/// Effort of the quadratures (overrides `[analysis.quadrature]` of the scenario).
#[derive(clap::Args)]
struct Effort {
    /// Relative tolerance of the quadratures (default 1e-10).
    #[arg(long)]
    rel_tol: Option<f64>,
    /// Subintervals an adaptive quadrature may use (default 2000).
    #[arg(long)]
    max_subintervals: Option<usize>,
    /// Half-periods of an oscillatory tail resolved before extrapolation gives up (default 10000).
    #[arg(long)]
    max_half_periods: Option<usize>,
}

impl Effort {
    /// Applies the given flags to the scenario's quadrature options.
    fn apply(&self, sc: &mut Scenario) -> stochvib::Result<()> {
        let e = &mut sc.analysis.effort;
        if let Some(v) = self.rel_tol {
            e.rel_tol = v;
        }
        if let Some(v) = self.max_subintervals {
            e.max_subintervals = v;
        }
        if let Some(v) = self.max_half_periods {
            e.max_half_periods = v;
        }
        // a value of a flag is named by the flag (one of the file's [analysis.quadrature] is read and checked
        // with the file)
        let given = [
            ("rel_tol", "--rel-tol", self.rel_tol.is_some()),
            (
                "max_subintervals",
                "--max-subintervals",
                self.max_subintervals.is_some(),
            ),
            (
                "max_half_periods",
                "--max-half-periods",
                self.max_half_periods.is_some(),
            ),
        ];
        e.validate().map_err(|err| match err {
            stochvib::Error::InvalidParameter { name, value, reason } => {
                let flag = given.iter().find(|g| g.0 == name && g.2).map(|g| g.1.to_string());
                stochvib::Error::InvalidParameter {
                    name: flag.unwrap_or(name),
                    value,
                    reason,
                }
            }
            other => other,
        })
    }
}

#[derive(Subcommand)]
enum Command {
    /// List the spectrum catalogue with variance and sigma of each entry.
    Spectra {
        #[command(flatten)]
        spectra: SpectraDir,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
        /// Print the full report of every entry.
        #[arg(long, conflicts_with = "json")]
        full: bool,
    },
    /// Analyse a road profile (CSV: a distance column and one column per track, with units): the spatial
    /// density with its χ² intervals, the ISO 8608 fit (w = 2 and free) and class, the IRI, and the
    /// coherence of the first two tracks.
    Road {
        /// Profile file (CSV: a header `distance [m], left [mm], right [mm]`, every column `name [unit]`, then
        /// one row per sample; `#` starts a comment line).
        profile: PathBuf,
        /// Welch segment length in samples (even; default: the largest power of two giving at least 8
        /// half-overlapping segments).
        #[arg(long)]
        segment: Option<usize>,
        /// Trend removed before the density: `mean` or `linear`.
        #[arg(long, default_value = "linear")]
        detrend: String,
        /// Confidence of the intervals.
        #[arg(long, default_value_t = 0.95)]
        confidence: f64,
        #[command(flatten)]
        output: Output,
        /// Also write the pictures (per track the density with its χ² band, the ISO 8608 fits and class
        /// limits; the two-track coherence with its interval) as SVG and PNG into this directory.
        #[arg(long)]
        plots: Option<PathBuf>,
    },
    /// List the model kinds a scenario file may name in `[model] kind`.
    Models {
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Replay a road profile (CSV) through a scenario's model as a deterministic time-domain input: each
    /// wheel follows its track (delay = position/speed), the model is stepped exactly between samples; per
    /// reported output the mean, σ, min, max and crest factor beside the analytic σ from the profile's own
    /// measured density.
    Replay {
        /// Scenario file (TOML, see data/); its inputs must be roads.
        scenario: PathBuf,
        /// Profile file (CSV: a header `distance [m], left [mm], right [mm]`, every column `name [unit]`, then
        /// one row per sample; `#` starts a comment line).
        profile: PathBuf,
        /// Speed in m/s (default: the scenario's speed).
        #[arg(long)]
        speed: Option<f64>,
        /// Length in m skipped before the statistics (default: the settling length v·7/min|Re λ|).
        #[arg(long, value_name = "M")]
        skip: Option<f64>,
        /// Start from x = 0 instead of the static state under the first input sample.
        #[arg(long)]
        zero_start: bool,
        /// Profile column under a road of one track (default: the first; a road of two tracks uses `left`
        /// and `right`).
        #[arg(long)]
        track: Option<String>,
        /// Trend removed from every track (and before the measured density): `mean` or `linear`.
        #[arg(long, default_value = "linear")]
        detrend: String,
        /// Write the history of every output (after the skipped length) to this CSV file.
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
        /// Replace an existing history file.
        #[arg(long, requires = "output")]
        overwrite: bool,
        #[command(flatten)]
        spectra: SpectraDir,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Analyse a file of data/: for a model with a random input, per output the mean, σ, 3σ bounds, crossing
    /// rates and every variance method; for a deterministic model its results; a reference table as printed.
    Analyze {
        /// Scenario file (TOML, see data/).
        scenario: PathBuf,
        #[command(flatten)]
        spectra: SpectraDir,
        #[command(flatten)]
        output: Output,
        /// Also write the scenario's pictures (SVG and PNG) into this directory.
        #[arg(long)]
        plots: Option<PathBuf>,
        /// Add a Monte Carlo column: σ from N realizations with its 95 % interval and whether it covers
        /// the analytic σ (the run file goes to a temporary directory and is removed).
        #[arg(long, value_name = "N")]
        monte_carlo: Option<usize>,
        /// Master seed of the Monte Carlo column.
        #[arg(long, default_value_t = 1, requires = "monte_carlo")]
        seed: u64,
        #[command(flatten)]
        step: Step,
        #[command(flatten)]
        effort: Effort,
    },
    /// Write pictures of a scenario (`.toml`: input density, |H(iω)|² and output densities with the
    /// cumulative variance) or of a Monte Carlo run file (`.h5`), as SVG and PNG.
    Plot {
        /// Scenario file (TOML) or Monte Carlo run file (`.h5`: Welch estimate against the analytic density
        /// per output and, with raw data, realization excerpts, histogram and correlation).
        input: PathBuf,
        /// Output directory (created if missing).
        #[arg(short = 'o', long)]
        out: PathBuf,
        /// Convention of the densities of a scenario's pictures [default: one-sided-cyclic].
        #[arg(long, value_enum)]
        convention: Option<Convention>,
        #[command(flatten)]
        spectra: SpectraDir,
    },
    /// Write one report of a scenario to hand over (docs/report.md): provenance, the scenario file as written,
    /// the model and its poles, every output's statistics and variance methods, the verdicts and the
    /// pictures; a self-contained HTML file (inline SVG and CSS), or markdown with the pictures beside it. Of a
    /// Monte Carlo run file (RUN.h5), or with --run: the run's statistics, intervals, coverage and pictures.
    /// Of a scenario with [transient]: also σ(t), mean(t) and the mission extremes; with nonlinear elements:
    /// the three routes; of a workday file: the daily exposure.
    Report {
        /// Scenario file (TOML, see data/), workday file, or Monte Carlo run file (.h5).
        scenario: PathBuf,
        /// A Monte Carlo run of the scenario (RUN.h5): its section follows the scenario's.
        #[arg(long)]
        run: Option<PathBuf>,
        /// Output file (written under a temporary name and renamed when complete).
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
        /// html (one self-contained file) or markdown (pictures in the directory <stem>-pictures beside it).
        #[arg(long, value_enum, default_value_t = report::handover::HandoverFormat::Html)]
        format: report::handover::HandoverFormat,
        /// Replace an existing report of the same name.
        #[arg(long)]
        overwrite: bool,
        #[command(flatten)]
        spectra: SpectraDir,
    },
    /// Monte Carlo run of a scenario written to an HDF5 file (layout: docs/run-file-format.md).
    Simulate {
        /// Scenario file (TOML, see data/).
        scenario: PathBuf,
        /// Number of realizations.
        #[arg(long)]
        realizations: usize,
        #[command(flatten)]
        step: Step,
        /// Master seed; realization i uses stream (seed, i).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output file (written as FILE.tmp and renamed when complete; an interrupted run resumes); with
        /// --shard, the run directory that receives the shard file DIR/shard-<I>-of-<N>.h5.
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
        /// Compute only shard I of the run (0 <= I < N, N from --of), or `auto`: I from the scheduler
        /// (SLURM_ARRAY_TASK_ID of a job array, JOB_COMPLETION_INDEX of a Kubernetes Indexed Job). A shard
        /// holds whole internal shards of --shard-size realizations; merge the N files with `stochvib merge`
        /// (bit-identical to one process with the same --shard-size).
        #[arg(long, value_name = "I|auto")]
        shard: Option<String>,
        /// N, the number of shards of the run (with --shard; always give it: a resubmitted array index
        /// cannot tell N).
        #[arg(long, value_name = "N", requires = "shard")]
        of: Option<usize>,
        /// Realizations per shard.
        #[arg(long, default_value_t = 50)]
        shard_size: usize,
        /// Store every realization of every output.
        #[arg(long)]
        store_raw: bool,
        /// Compression of raw data: none, fast, best, deflate, deflate:N (N = 1-9) (with --store-raw).
        #[arg(long, default_value = "none", requires = "store_raw")]
        compression: Compression,
        /// Route of the realizations.
        #[arg(long, alias = "method", value_enum, default_value_t = Route::Auto)]
        route: Route,
        /// Confidence of the intervals.
        #[arg(long, default_value_t = 0.95)]
        confidence: f64,
        /// Streamed spectral route: fraction of each output's variance its kernels may leave outside their
        /// window (the variance is biased low by at most this) [default: 1e-4].
        #[arg(long)]
        stream_tail: Option<f64>,
        /// Replace an existing finished OUTPUT (a run file only; replaced when the new run is complete) and
        /// discard an interrupted run of different settings.
        #[arg(long)]
        overwrite: bool,
        #[command(flatten)]
        spectra: SpectraDir,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// After the run, write its pictures (as `stochvib plot OUTPUT -o DIR`) into this directory.
        #[arg(long)]
        plots: Option<PathBuf>,
    },
    /// Merge the shard files of a cluster run (`simulate --shard I --of N -o DIR/`) into one run file,
    /// bit-identical to a single-process run with the same scenario, seed, options and --shard-size. Refuses,
    /// naming the files and the indices to resubmit, files of other runs, duplicate, overlapping and missing
    /// shards. The raw realizations (--store-raw) stay in the shard files, read through HDF5 virtual
    /// datasets (paths relative to OUTPUT's directory: keep the shard files there), unless --copy.
    Merge {
        /// The merged run file (written as FILE.tmp and renamed when complete).
        output: PathBuf,
        /// Shard files, or directories whose *.h5 files are the shard files.
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
        /// Copy the raw realizations into the merged file (it then stands alone).
        #[arg(long)]
        copy: bool,
        /// Replace an existing finished OUTPUT (a run file only; replaced when the merge is complete).
        #[arg(long)]
        overwrite: bool,
        /// Confidence of the intervals (default: that of the shard files).
        #[arg(long)]
        confidence: Option<f64>,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Parameter study: the scenario's exact statistics (and optionally a Monte Carlo batch) at every point
    /// of a grid or list of scenario keys, as one table (CSV, JSON or HDF5 from -o's extension; CSV on
    /// stdout without -o). With --shard, one part of the points into DIR/sweep-shard-<I>-of-<N>.json;
    /// `stochvib merge TABLE DIR/` joins them.
    Sweep {
        /// Scenario file (TOML, see data/).
        scenario: PathBuf,
        /// KEY=VALUES: a scenario key (model.omega2, input.speed, model.element.0.stiffness) and a list
        /// `V1,V2,...` or a range `A..B:n` (`A..B:n:log`) of values with units, e.g. `model.omega2=1 Hz..2 Hz:5`.
        #[arg(long = "param", value_name = "KEY=VALUES", required = true)]
        params: Vec<String>,
        /// Zip the keys' values (the k-th values together) instead of the grid of every combination.
        #[arg(long)]
        zip: bool,
        /// The table (.csv, .json, .h5); with --shard, the directory of the shard files.
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
        /// Evaluate only part I of the points (or `auto`, from the scheduler, as for simulate).
        #[arg(long, value_name = "I|auto")]
        shard: Option<String>,
        /// N, the number of parts (with --shard).
        #[arg(long, value_name = "N", requires = "shard")]
        of: Option<usize>,
        /// Also run a Monte Carlo batch of N realizations at every point (same seed at every point).
        #[arg(long, value_name = "N")]
        monte_carlo: Option<usize>,
        #[command(flatten)]
        step: Step,
        /// Master seed of the Monte Carlo batches.
        #[arg(long, default_value_t = 1, requires = "monte_carlo")]
        seed: u64,
        /// Realizations per internal shard of the Monte Carlo batches.
        #[arg(long, default_value_t = 50, requires = "monte_carlo")]
        shard_size: usize,
        /// Confidence of the Monte Carlo intervals.
        #[arg(long, default_value_t = 0.95, requires = "monte_carlo")]
        confidence: f64,
        /// Replace an existing table or shard file.
        #[arg(long, requires = "output")]
        overwrite: bool,
        /// Print JSON instead of CSV (without -o: a table's format comes from -o's extension).
        #[arg(long, conflicts_with = "output")]
        json: bool,
        /// One row per point: the swept values as SI numbers (unit in the header) and what `analyze`
        /// reports as verdicts: σ of each output, a_w per comfort axis, a_v, A(8), VDV, damage rate, life
        /// (CSV; JSON with --json; -o FILE.csv or FILE.json; -o FILE.h5 holds them in its verdicts/ group
        /// beside the per-output statistics; shard files carry them and their merge keeps them).
        #[arg(long)]
        verdicts: bool,
        #[command(flatten)]
        spectra: SpectraDir,
    },
    /// Summarise a Monte Carlo run file.
    Inspect {
        /// Run file (HDF5).
        file: PathBuf,
        #[command(flatten)]
        output: Output,
    },
    /// Daily vibration exposure of a working day of several tasks (a workday file: [[task]] tables naming a
    /// scenario with [analysis.comfort], an optional speed and a duration): per task and axis k·a_w with the
    /// health factors, the day's A(8) = √(Σ (k a_w)² T / 8 h) and VDV = (Σ VDV⁴)^(1/4) per axis, against
    /// Directive 2002/44/EC and ISO 2631-1 Annex B (format: docs/comfort.md).
    Workday {
        /// Workday file (TOML).
        file: PathBuf,
        /// Draw the day's A(8) per axis against the limit value into DIR (SVG and PNG; docs/gallery.md).
        #[arg(long, value_name = "DIR")]
        plots: Option<PathBuf>,
        #[command(flatten)]
        spectra: SpectraDir,
        #[command(flatten)]
        output: Output,
    },
    /// Checks that a run file can be read (the parent process of `inspect` and `plot` runs this first, so that
    /// a damaged file that would crash the HDF5 library crashes only this child).
    #[command(hide = true)]
    CheckRun {
        /// Run file (HDF5).
        file: PathBuf,
        /// Also check the checksums of every shard's raw data and accumulators.
        #[arg(long)]
        full: bool,
    },
    /// Reproduce every worked example of the source documents: printed value, computed value, relative
    /// difference and an explanation for every difference over 2 %.
    Book {
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// Also write the catalogue-model pictures (seat octave bands against Table 7.1, mine-hoist
        /// frequencies and modes, balancer-bogie D_y/D_x, scraper σ over speed) as SVG and PNG into this
        /// directory.
        #[arg(long)]
        plots: Option<PathBuf>,
        #[command(flatten)]
        spectra: SpectraDir,
    },
    /// ISO 2631-1 evaluation of a measured acceleration record (CSV, HDF5, WAV): digital weighting per ISO 8041,
    /// a_w, running r.m.s., MTVV, VDV, crest factor, basic-method criteria per axis, one-third-octave bands,
    /// the comfort vector sum, A(8) and daily VDV against Directive 2002/44/EC and Annex B, MSDV for Wf
    /// channels (docs/records.md).
    Exposure(record_cli::ExposureArgs),
    /// Fatigue of a measured stress or strain record: rainflow (ASTM E1049), range–mean matrix, Miner damage
    /// with an S–N curve and a mean-stress correction, beside the five spectral methods from the record's
    /// own Welch density (docs/records.md).
    Fatigue(record_cli::FatigueArgs),
    /// A frequency weighting (ISO 2631-1, ISO 2631-4): magnitude and phase, and with --sample-rate its
    /// digital realisation and error.
    Weighting(record_cli::WeightingArgs),
    /// The coherence of two road tracks as numbers: a model (--model) and/or a measured profile (--profile).
    Coherence(record_cli::CoherenceArgs),
    /// The expected IRI of a road spectrum (golden car, 80 km/h, 250 mm moving average) beside the IRI of a
    /// measured profile.
    Iri(record_cli::IriArgs),
    /// Minimise or maximise a reported quantity (σ, 3σ, a_w, A(8), VDV, damage rate, life) over scenario
    /// values between bounds, subject to constraints on other quantities (docs/optimisation.md).
    Optimize(optimize_cli::OptimizeArgs),
    /// Non-stationary response of a scenario with [transient] (docs/transients.md): σ(t), mean(t), ν₀⁺(t),
    /// ν⁺(b, t) and a_w(t) by the exact route, the expected up-crossings and P(max |y| > b) of the mission;
    /// with --monte-carlo N -o FILE the same by simulation into a run file, σ(t) beside the exact curve.
    Transient(transient_cli::TransientArgs),
    /// Test tailoring (docs/transients.md): the extreme response spectrum and the fatigue damage spectrum
    /// (Lalanne) of a base acceleration, a spectrum file or a scenario output, over a family of
    /// base-excited oscillators of quality factor Q, for a duration T.
    Tailor(tailor_cli::TailorArgs),
    /// Report one spectrum: variance (model and quadrature), sigma, correlation, density.
    Spectrum {
        /// Catalogue name (e.g. `iso8608-c`) or path to a spectrum file.
        name: String,
        /// Convention of the printed density.
        #[arg(long, value_enum, default_value_t = Convention::TwoSidedAngular)]
        convention: Convention,
        /// Angular frequencies at which to print the density, comma-separated, in rad/s (rad/m for a
        /// spatial spectrum), e.g. `--omega 1,2,5`.
        #[arg(long, value_delimiter = ',', conflicts_with = "frequency")]
        omega: Option<Vec<f64>>,
        /// Cyclic frequencies at which to print the density, comma-separated, in Hz (cycles/m for a spatial
        /// spectrum), e.g. `--frequency 0.5,1,2`.
        #[arg(long, value_delimiter = ',')]
        frequency: Option<Vec<f64>>,
        #[command(flatten)]
        spectra: SpectraDir,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
}

fn main() {
    if let Err(e) = run(Cli::parse()) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn run(cli: Cli) -> anyhow::Result<()> {
    // a misspelt instruction-set cap is refused before any work (the library would ignore it)
    stochvib::linalg::vmath::Isa::cap_from_env()?;
    match cli.command {
        cmd @ Command::Spectra { .. } => spectra_command(cmd)?,
        Command::Models { json } => print(&report::models_report(), json)?,
        cmd @ Command::Road { .. } => road_command(cmd)?,
        cmd @ Command::Replay { .. } => replay_command(cmd)?,
        Command::Book { json, plots, spectra } => {
            print(
                &report::BookReport {
                    rows: stochvib::models::worked_example::book_rows(),
                },
                json,
            )?;
            if let Some(out) = plots {
                for f in stochvib::plot::book_plots(&out, spectra.catalogue().dir())? {
                    eprintln!("wrote {}", f.display());
                }
            }
        }
        cmd @ Command::Analyze { .. } => analyze_command(cmd)?,
        cmd @ Command::Report { .. } => report_command(cmd)?,
        cmd @ Command::Plot { .. } => plot_command(cmd)?,
        cmd @ Command::Simulate { .. } => simulate_command(cmd)?,
        cmd @ Command::Merge { .. } => merge_command(cmd)?,
        cmd @ Command::Sweep { .. } => sweep_command(cmd)?,
        cmd @ Command::CheckRun { .. } => check_run_command(cmd)?,
        Command::Inspect { file, output } => {
            check_in_child(&file, true)?;
            match output.format() {
                ReportFormat::Json => print_json(&RunFile::open(&file)?.info()?)?,
                ReportFormat::Markdown => emit(&report::inspect_markdown(&file)?),
                ReportFormat::Text => emit(&report::summarize(&file)?),
            }
        }
        cmd @ Command::Workday { .. } => workday_command(cmd)?,
        Command::Exposure(a) => record_cli::exposure(a)?,
        Command::Fatigue(a) => record_cli::fatigue(a)?,
        Command::Weighting(a) => record_cli::weighting(a)?,
        Command::Coherence(a) => record_cli::coherence(a)?,
        Command::Iri(a) => record_cli::iri(a)?,
        Command::Optimize(a) => optimize_cli::optimize(a)?,
        Command::Transient(args) => transient_cli::transient(
            args,
            &|d| SpectraDir { spectra_dir: d.clone() }.catalogue(),
            &progress_printer(),
            &shard_output,
        )?,
        Command::Tailor(a) => print_as(&tailor_cli::tailor(&a)?, a.output.format())?,
        cmd @ Command::Spectrum { .. } => spectrum_command(cmd)?,
    }
    Ok(())
}

/// `stochvib spectra`.
fn spectra_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Spectra { spectra, json, full } = cmd else {
        unreachable!("run passes only Command::Spectra")
    };
    let r = report::catalogue_report(&spectra.catalogue())?;
    for msg in &r.failures {
        eprintln!("error: {msg}");
    }
    if json {
        print_json(&r.spectra)?;
    } else if full {
        emit(&format!("{r:#}"));
    } else {
        emit(&format!("{r}"));
    }
    if !r.failures.is_empty() {
        anyhow::bail!("{} spectrum file(s) in {} are invalid", r.failures.len(), r.dir);
    }
    Ok(())
}

/// `stochvib report`.
fn report_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Report {
        scenario,
        run,
        output,
        format,
        overwrite,
        spectra,
    } = cmd
    else {
        unreachable!("run passes only Command::Report")
    };
    let catalogue = spectra.catalogue();
    let is_run = |p: &Path| {
        p.extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("h5") || e.eq_ignore_ascii_case("hdf5"))
    };
    // every checksum first, in a child process, as `plot` and `inspect`: a damaged file is an error
    for r in run.iter().chain(Some(&scenario).filter(|p| is_run(p))) {
        check_in_child(r, true)?;
    }
    let written = if is_run(&scenario) {
        anyhow::ensure!(
            run.is_none(),
            "--run: {} is already a run file; give a scenario file and --run RUN.h5, or the run file alone",
            scenario.display()
        );
        report::run_handover::write_run_handover(&scenario, &output, format, overwrite, catalogue.dir())?
    } else if report::workday_handover::is_workday_file(&scenario) {
        anyhow::ensure!(run.is_none(), "--run: a workday file has no Monte Carlo run");
        let dir = catalogue.dir();
        report::workday_handover::write_workday_handover(&scenario, &output, format, overwrite, dir)?
    } else {
        let doc = load_document(&scenario, catalogue.dir())?;
        let run = run.as_deref().map(|r| (r, catalogue.dir()));
        report::handover::write_handover(&doc, &scenario, &output, format, overwrite, run)?
    };
    eprintln!("wrote {}", written.display());
    Ok(())
}

/// `stochvib check-run` (hidden): reads a run file as `plot` and `inspect` do, in the child they start.
fn check_run_command(cmd: Command) -> anyhow::Result<()> {
    let Command::CheckRun { file, full } = cmd else {
        unreachable!("run passes only Command::CheckRun")
    };
    let run = RunFile::open_any(&file)?;
    run.statistics()?;
    run.psd()?;
    if full {
        run.verify()?;
    } else if run.metadata().store_raw && run.metadata().n_realizations > 0 {
        // what `plot` reads: the first realizations of every signal
        let rows = 0..run.metadata().n_realizations.min(3);
        for s in &run.metadata().outputs {
            run.read_signals(stochvib::store::SignalGroup::Outputs, &s.name, rows.clone())?;
        }
    }
    Ok(())
}

/// `stochvib workday`.
fn workday_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Workday {
        file,
        plots,
        spectra,
        output,
    } = cmd
    else {
        unreachable!("run passes only Command::Workday")
    };
    let day = stochvib::scenario::workday_file::load_workday(&file)?;
    let r = stochvib::study::workday::workday_exposure(&day, spectra.catalogue().dir())?;
    if let Some(dir) = plots {
        for f in stochvib::plot::comfort_plots::workday_chart(&r)?.render(&dir, "workday-a8")? {
            eprintln!("wrote {}", f.display());
        }
    }
    print_as(&report::WorkdayReport(r), output.format())?;
    Ok(())
}

/// `stochvib spectrum`.
fn spectrum_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Spectrum {
        name,
        convention,
        omega,
        frequency,
        spectra,
        json,
    } = cmd
    else {
        unreachable!("run passes only Command::Spectrum")
    };
    let file = spectra.catalogue().resolve(&name, None)?;
    let points = match (omega, frequency) {
        (Some(w), _) => study::DensityPoints::Angular(w),
        (None, Some(f)) => study::DensityPoints::Cyclic(f),
        (None, None) => study::DensityPoints::Characteristic,
    };
    points
        .check()
        .map_err(|e| e.renamed("omega", "--omega").renamed("frequency", "--frequency"))?;
    print(&study::spectrum_report_at(&file, convention, &points), json)?;
    Ok(())
}

/// `stochvib road`.
fn road_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Road {
        profile,
        segment,
        detrend,
        confidence,
        output,
        plots,
    } = cmd
    else {
        unreachable!("run passes only Command::Road")
    };
    let detrend = match detrend.as_str() {
        "mean" => stochvib::road::Detrend::Mean,
        "linear" => stochvib::road::Detrend::Linear,
        other => anyhow::bail!("--detrend {other}: expected `mean` or `linear`"),
    };
    if !(confidence > 0.0 && confidence < 1.0) {
        anyhow::bail!("--confidence {confidence}: expected a number in (0, 1)");
    }
    let opts = study::road_profile::RoadReportOptions {
        segment_len: segment,
        detrend,
        confidence,
    };
    let r = study::road_profile::road_report(&profile, &opts)?;
    print_as(&r, output.format())?;
    if let Some(out) = plots {
        let files = stochvib::plot::road_plots(&r, &out)?;
        eprintln!("wrote {} pictures to {}", files.len(), out.display());
    }
    Ok(())
}

/// `stochvib replay`.
fn replay_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Replay {
        scenario,
        profile,
        speed,
        skip,
        zero_start,
        track,
        detrend,
        output,
        overwrite,
        spectra,
        json,
    } = cmd
    else {
        unreachable!("run passes only Command::Replay")
    };
    let detrend = match detrend.as_str() {
        "mean" => stochvib::road::Detrend::Mean,
        "linear" => stochvib::road::Detrend::Linear,
        other => anyhow::bail!("--detrend {other}: expected `mean` or `linear`"),
    };
    let catalogue = spectra.catalogue();
    let sc = load_scenario(&scenario, catalogue.dir())?;
    let opts = stochvib::study::replay::ScenarioReplayOptions {
        speed_m_s: speed,
        skip_m: skip,
        start: if zero_start {
            stochvib::road::Start::Zero
        } else {
            stochvib::road::Start::Static
        },
        track,
        detrend,
    };
    let mut inputs = sc.source_files();
    inputs.push(profile.clone());
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    if let Some(out) = &output {
        // the output rule before the work
        stochvib::io_rules::check_output(out, &stochvib::road::replay::HISTORY_CSV, &inputs, overwrite)?;
    }
    let r = stochvib::study::replay::replay_scenario(&sc, &profile, &opts)?;
    if let Some(out) = output {
        r.replay.write_csv_from(&out, overwrite, &inputs)?;
        eprintln!("wrote {}", out.display());
    }
    print(&r, json)?;
    Ok(())
}

/// `stochvib analyze`.
fn analyze_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Analyze {
        scenario,
        spectra,
        output,
        plots,
        monte_carlo,
        seed,
        step,
        effort,
    } = cmd
    else {
        unreachable!("run passes only Command::Analyze")
    };
    let catalogue = spectra.catalogue();
    step.check_batch("--monte-carlo", monte_carlo)?;
    let mut sc = match load_document(&scenario, catalogue.dir())? {
        Document::Stochastic(sc) => sc,
        Document::Deterministic(d) => {
            no_simulation(&scenario, monte_carlo, &plots)?;
            return print_as(
                &report::deterministic_report(&d, stochvib::study::deterministic_tables(&d)?),
                output.format(),
            );
        }
        Document::Reference(t) => {
            no_simulation(&scenario, monte_carlo, &plots)?;
            return print_as(&report::reference_report(&t), output.format());
        }
    };
    effort.apply(&mut sc)?;
    if let Some(answers) = sc.nonlinear_answers()? {
        return analyze_nonlinear(&sc, &answers, monte_carlo, seed, &step, &plots, &output, &catalogue);
    }
    let mut r = study::analysis_report(&sc)?;
    if let Some(n) = monte_carlo {
        let (dt, duration) = step.resolve(&sc, n)?;
        let opts = RunOptions {
            max_hours: step.max_hours(),
            realizations: n,
            duration_s: duration,
            dt_s: dt,
            seed,
            ..RunOptions::default()
        };
        let progress = progress_printer();
        let (summary, pictures) = stochvib::simulate::run_temporary_with(
            &std::env::temp_dir(),
            |path| sc.simulate(&opts, path, &progress),
            // the run's own pictures (Welch band vs analytic density) before the file goes
            |path| plots.as_ref().map(|out| run_plots(path, out, catalogue.dir())),
        )
        .map_err(|e| named_by_flag(sc.name_run_error(e), "--monte-carlo"))?;
        attach_monte_carlo(&mut r, &summary);
        if let (Some(files), Some(out)) = (pictures, &plots) {
            eprintln!("wrote {} Monte Carlo pictures to {}", files?.len(), out.display());
        }
    }
    print_as(&r, output.format())?;
    if let Some(out) = plots {
        let files = scenario_plots_with(&sc, &out, &ScenarioPlotOptions::default())?;
        eprintln!("wrote {} pictures to {}", files.len(), out.display());
    }
    Ok(())
}

/// `stochvib plot`.
fn plot_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Plot {
        input,
        out,
        convention,
        spectra,
    } = cmd
    else {
        unreachable!("run passes only Command::Plot")
    };
    let catalogue = spectra.catalogue();
    let has = |ext: &[&str]| {
        input
            .extension()
            .is_some_and(|e| ext.iter().any(|x| e.eq_ignore_ascii_case(x)))
    };
    let files = if has(&["h5", "hdf5"]) {
        if let Some(c) = convention {
            anyhow::bail!(
                "--convention {c:?}: a run file's pictures are drawn in the convention the file stores; \
                 --convention applies to a scenario's pictures"
            );
        }
        // every checksum, as `inspect`: a damaged file is an error naming the damaged part
        check_in_child(&input, true)?;
        run_plots(&input, &out, catalogue.dir())?
    } else if has(&["toml"]) {
        let sc = load_scenario(&input, catalogue.dir())?;
        let opts = ScenarioPlotOptions {
            convention: convention.unwrap_or(Convention::OneSidedCyclic),
            ..ScenarioPlotOptions::default()
        };
        scenario_plots_with(&sc, &out, &opts)?
    } else {
        anyhow::bail!(
            "{}: can plot scenario files (.toml) and Monte Carlo run files (.h5)",
            input.display()
        );
    };
    for f in files {
        emit_line(&f.display().to_string());
    }
    Ok(())
}

/// `stochvib simulate`.
fn simulate_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Simulate {
        scenario,
        realizations,
        step,
        seed,
        output,
        shard,
        of,
        shard_size,
        store_raw,
        compression,
        route,
        confidence,
        stream_tail,
        overwrite,
        spectra,
        json,
        plots,
    } = cmd
    else {
        unreachable!("run passes only Command::Simulate")
    };
    let catalogue = spectra.catalogue();
    step.check_batch("--realizations", Some(realizations))?;
    if let (Some(t), Route::Exact | Route::Spectral) = (stream_tail, route) {
        anyhow::bail!(
            "--stream-tail {t}: sets the streamed spectral route's kernels, and --route {} does not stream; \
             leave it out, or use --route spectral-stream (or auto)",
            format!("{route:?}").to_lowercase()
        );
    }
    // the shard before anything else: a task outside a scheduler fails at once
    let choice = match &shard {
        Some(spec) => {
            Some(resolve_part(spec, of, &|k| std::env::var(k).ok()).map_err(|e| named_by_flag(e, "--realizations"))?)
        }
        None => None,
    };
    if let Some(dir) = &plots {
        stochvib::plot::chart::check_picture_dir(dir)?; // before the run file is written
    }
    let sc = load_scenario(&scenario, catalogue.dir())?;
    let base = RunOptions {
        shard_size,
        store_raw,
        compression,
        route,
        confidence,
        overwrite,
        part: choice.as_ref().map(|c| c.part),
        max_hours: step.max_hours(),
        realizations,
        seed,
        ..RunOptions::default()
    };
    let path = match sc.nonlinear_answers()? {
        Some(answers) => {
            let base = RunOptions {
                duration_s: 1.0,
                dt_s: 1.0,
                ..base
            };
            let opts = step.nonlinear(&sc, &answers, base)?;
            let output = shard_output(output, &choice)?;
            let s = sc.simulate_nonlinear(&answers, &opts, &output, &progress_printer())?;
            print(&s, json)?;
            s.run.path
        }
        None => {
            let base = RunOptions {
                stream_tail: stream_tail.unwrap_or(stochvib::simulate::fir_stream::TAIL_FRACTION),
                ..base
            };
            simulate_linear(&sc, &step, base, output, &choice, json)?
        }
    };
    if let Some(pdir) = plots {
        for f in run_plots(&path, &pdir, catalogue.dir())? {
            if !json {
                emit_line(&f.display().to_string());
            }
        }
    }
    Ok(())
}

/// `stochvib simulate` of a linear scenario: Δt and the duration from `step`, the other options `base`; the
/// estimate of the run's size printed first; returns the run file's path.
fn simulate_linear(
    sc: &Scenario,
    step: &Step,
    base: RunOptions,
    output: PathBuf,
    choice: &Option<study::ShardChoice>,
    json: bool,
) -> anyhow::Result<PathBuf> {
    let (dt, duration) = step.resolve(sc, base.realizations)?;
    let opts = RunOptions {
        duration_s: duration,
        dt_s: dt,
        ..base
    };
    let flag = |e| named_by_flag(e, "--realizations");
    let estimate = stochvib::simulate::resources::estimate_text(
        &opts,
        sc.excitation.spectra().len(),
        sc.analysis.outputs.len(),
        sc.input_signals().len(),
    )
    .map_err(flag)?;
    eprintln!("{estimate}");
    // the run directory of a shard only once the options hold (a refused run creates nothing)
    let output = shard_output(output, choice)?;
    let s = sc.simulate(&opts, &output, &progress_printer()).map_err(flag)?;
    print(&s, json)?;
    Ok(s.path)
}

/// `stochvib merge`.
fn merge_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Merge {
        output,
        inputs,
        copy,
        overwrite,
        confidence,
        json,
    } = cmd
    else {
        unreachable!("run passes only Command::Merge")
    };
    let kind = study::merge_kind::merge_kind(&output, &inputs)?;
    if kind == study::merge_kind::MergeKind::Sweep {
        let sweeps = study::find_sweep_shards(&inputs)?;
        let run_only = [
            ("--copy", copy),
            ("--confidence", confidence.is_some()),
            ("--json", json),
        ];
        if let Some((flag, _)) = run_only.iter().find(|f| f.1) {
            anyhow::bail!(
                "{flag} applies to a merge of Monte Carlo run files; these are sweep shard files ({}), \
                 merged into one table as they are: leave {flag} out",
                sweeps[0].display()
            );
        }
        let t = study::merge_sweep(&output, &inputs, overwrite)?;
        eprintln!(
            "merged {} points ({} failed) into {}",
            t.n_points,
            t.errors.len(),
            output.display()
        );
        return Ok(());
    }
    let opts = MergeOptions {
        copy,
        overwrite,
        confidence,
    };
    if kind == study::merge_kind::MergeKind::Transient {
        let s = stochvib::study::merge_transient(&output, &inputs, &opts, &|_, _| {})?;
        eprintln!(
            "merged {} realizations of a transient run into {}",
            s.n_realizations,
            s.path.display()
        );
        return if json { print_json(&s) } else { Ok(()) };
    }
    let s = merge_runs(&output, &inputs, &opts, &|_, _| {})?;
    print(&s, json)?;
    Ok(())
}

/// `stochvib sweep`.
fn sweep_command(cmd: Command) -> anyhow::Result<()> {
    let Command::Sweep {
        scenario,
        params,
        zip,
        output,
        shard,
        of,
        monte_carlo,
        step,
        seed,
        shard_size,
        confidence,
        overwrite,
        json,
        verdicts,
        spectra,
    } = cmd
    else {
        unreachable!("run passes only Command::Sweep")
    };
    step.check_batch("--monte-carlo", monte_carlo)?;
    let flag = |e| named_by_flag(e, "--monte-carlo");
    let choice = match &shard {
        Some(spec) => Some(resolve_part(spec, of, &|k| std::env::var(k).ok()).map_err(flag)?),
        None => None,
    };
    let catalogue = spectra.catalogue();
    let sc = load_scenario(&scenario, catalogue.dir())?;
    let params = params
        .iter()
        .map(|p| SweepParam::parse(p))
        .collect::<Result<Vec<_>, _>>()?;
    let mode = if zip { SweepMode::Zip } else { SweepMode::Grid };
    let sweep = Sweep::new(&sc, SweepSpec::new(params, mode)?)?;
    let sweep = if verdicts { sweep.with_verdicts()? } else { sweep };
    eprintln!("sweep: {}", sweep.path());
    let mc = match monte_carlo {
        Some(n) => {
            let (dt, duration) = step.resolve(&sc, n)?;
            let m = study::SweepMonteCarlo {
                realizations: n,
                duration_s: duration,
                dt_s: dt,
                seed,
                shard_size,
                confidence,
            };
            study::check_monte_carlo_time(&sweep, &m, step.max_hours()).map_err(flag)?;
            Some(m)
        }
        None => None,
    };
    let progress = progress_printer();
    match choice {
        Some(c) => sweep_shard(&sweep, c, output, mc, overwrite, &progress),
        None => sweep_table(&sweep, output, json, mc, overwrite, &progress),
    }
}

/// `stochvib sweep --shard`: the shard file of part `c` in the directory `output`.
fn sweep_shard(
    sweep: &Sweep,
    c: study::ShardChoice,
    output: Option<PathBuf>,
    mc: Option<study::SweepMonteCarlo>,
    overwrite: bool,
    progress: &dyn Fn(usize, usize),
) -> anyhow::Result<()> {
    let dir = output.ok_or_else(|| anyhow::anyhow!("--shard needs -o DIR/ (the directory of the shard files)"))?;
    output_dir(&dir, "with --shard, -o names the directory of the shard files")?;
    eprintln!("sweep shard {} of {} ({})", c.part.index, c.part.count, c.source);
    for n in &c.notes {
        eprintln!("warning: {n}");
    }
    let (path, sh, fresh) = study::run_sweep_shard(sweep, c.part, &dir, true, mc, overwrite, progress)?;
    eprintln!(
        "{} {}: points {}..{} of {} ({} failed)",
        if fresh {
            "wrote"
        } else {
            "already complete (nothing to do):"
        },
        path.display(),
        sh.results.points.start,
        sh.results.points.end,
        sh.results.n_points,
        sh.results.errors.len()
    );
    Ok(())
}

/// `stochvib sweep` without `--shard`: the table to the file `output` (its format by its extension), as
/// JSON or CSV to standard output.
fn sweep_table(
    sweep: &Sweep,
    output: Option<PathBuf>,
    json: bool,
    mc: Option<study::SweepMonteCarlo>,
    overwrite: bool,
    progress: &dyn Fn(usize, usize),
) -> anyhow::Result<()> {
    let opts = study::StreamOptions::default();
    match output {
        Some(path) => {
            let t = study::write_sweep_table(sweep, &path, overwrite, mc, opts, progress)?;
            eprintln!(
                "wrote {} points ({} failed) to {}",
                t.n_points,
                t.errors.len(),
                path.display()
            );
        }
        None if json => {
            let n = sweep.spec().n_points();
            emit_line(&study::compute_sweep(sweep, 0..n, true, mc, progress)?.to_json()?)
        }
        None => {
            let out = std::io::stdout();
            match study::stream_sweep_csv(sweep, out, Path::new("<stdout>"), mc, opts, progress) {
                // a closed pipe (`stochvib sweep ... | head`): the evaluation has stopped and
                // the writer thread has ended; end quietly, as `emit` does
                Err(stochvib::Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::BrokenPipe => {
                    std::process::exit(0)
                }
                r => {
                    r?;
                }
            }
        }
    }
    Ok(())
}

/// Reads a run file in a child process first (`stochvib check-run`): libhdf5 can crash on a damaged file,
/// and a crash must not take this process with it. A child killed by a signal means a damaged file; a
/// child's error is this command's error.
fn check_in_child(file: &Path, full: bool) -> anyhow::Result<()> {
    let exe = std::env::current_exe()?;
    let mut cmd = std::process::Command::new(exe);
    cmd.arg("check-run").arg(file);
    if full {
        cmd.arg("--full");
    }
    let out = cmd.stdin(std::process::Stdio::null()).output()?;
    if out.status.success() {
        return Ok(());
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    let msg = stderr
        .lines()
        .find(|l| l.starts_with("error: "))
        .map(|l| l.trim_start_matches("error: "));
    match (out.status.code(), msg) {
        (Some(_), Some(m)) => anyhow::bail!("{m}"),
        _ => {
            #[cfg(unix)]
            let how = {
                use std::os::unix::process::ExitStatusExt;
                out.status
                    .signal()
                    .map_or("abnormally".to_string(), |s| format!("with signal {s}"))
            };
            #[cfg(not(unix))]
            let how = "abnormally".to_string();
            anyhow::bail!(
                "{}: the file is damaged: reading it made the HDF5 library fail {how}",
                file.display()
            )
        }
    }
}

/// Creates the output directory `dir` if missing; refuses a `dir` that exists and is not a directory
/// (`what` says what the directory is for).
fn output_dir(dir: &Path, what: &str) -> anyhow::Result<()> {
    if let Ok(m) = std::fs::metadata(dir)
        && !m.is_dir()
    {
        anyhow::bail!("{}: is not a directory: {what}; nothing was written", dir.display());
    }
    std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{}: {e}", dir.display()))
}

/// The flags that set the fields of [`RunOptions`], by the names the library's errors give them.
const RUN_FLAGS: [(&str, &str); 11] = [
    ("realizations", "--realizations"),
    ("shard size", "--shard-size"),
    ("dt", "--dt"),
    ("duration", "--duration"),
    ("confidence", "--confidence"),
    ("stream tail", "--stream-tail"),
    ("max hours", "--max-hours"),
    ("of", "--of"),
    ("shard", "--shard"),
    ("road step", "--road-step"),
    ("substeps", "--substeps"),
];

/// A library error about a value the user gave as a flag, named by that flag: `flags` maps the library's
/// parameter names to the flags (`count` names the flag of the number of realizations, which is
/// `--realizations` for `simulate` and `--monte-carlo` for `analyze` and `sweep`).
fn named_by_flag(e: stochvib::Error, count: &str) -> stochvib::Error {
    match e {
        stochvib::Error::InvalidParameter { name, value, reason } => {
            let flag = match name.as_str() {
                "realizations" => Some(count),
                n => RUN_FLAGS.iter().find(|(k, _)| *k == n).map(|(_, f)| *f),
            };
            stochvib::Error::InvalidParameter {
                name: flag.map_or(name, str::to_string),
                value,
                reason,
            }
        }
        other => other,
    }
}

/// The run file of `simulate`: `-o` itself, or with `--shard` the shard file in the run directory `-o`.
fn shard_output(output: PathBuf, choice: &Option<stochvib::study::ShardChoice>) -> anyhow::Result<PathBuf> {
    let Some(c) = choice else { return Ok(output) };
    output_dir(
        &output,
        "with --shard, -o names the run directory that receives shard-<I>-of-<N>.h5 files",
    )?;
    eprintln!("shard {} of {} ({})", c.part.index, c.part.count, c.source);
    for n in &c.notes {
        eprintln!("warning: {n}");
    }
    Ok(part_path(&output, c.part))
}

/// `analyze` of a scenario with nonlinear elements: routes 1 and 3, and route 2 with `--monte-carlo N`.
#[allow(clippy::too_many_arguments)]
fn analyze_nonlinear(
    sc: &Scenario,
    answers: &NonlinearAnswers,
    monte_carlo: Option<usize>,
    seed: u64,
    step: &Step,
    plots: &Option<PathBuf>,
    output: &Output,
    catalogue: &Catalogue,
) -> anyhow::Result<()> {
    let mc = match monte_carlo {
        Some(n) => {
            let opts = step.nonlinear(
                sc,
                answers,
                RunOptions {
                    realizations: n,
                    duration_s: 1.0,
                    dt_s: 1.0,
                    seed,
                    ..RunOptions::default()
                },
            )?;
            let run =
                sc.simulate_nonlinear_temporary(answers, &opts, &std::env::temp_dir(), &progress_printer(), |path| {
                    plots.as_ref().map(|out| run_plots(path, out, catalogue.dir()))
                });
            let (s, pictures) = match run {
                Ok(r) => r,
                Err(e) => match study::escaped(&e) {
                    Some(reason) => {
                        return print_as(&study::nonlinear_report_escaped(sc, answers, &reason)?, output.format())
                    }
                    None => return Err(e.into()),
                },
            };
            if let (Some(files), Some(out)) = (pictures, plots) {
                eprintln!("wrote {} Monte Carlo pictures to {}", files?.len(), out.display());
            }
            Some(s)
        }
        None => None,
    };
    print_as(&study::nonlinear_report(sc, answers, mc.as_ref())?, output.format())
}

/// Refuses Monte Carlo and pictures for a file without a random input.
fn no_simulation(file: &Path, monte_carlo: Option<usize>, plots: &Option<PathBuf>) -> anyhow::Result<()> {
    if monte_carlo.is_some() || plots.is_some() {
        anyhow::bail!(
            "{}: --monte-carlo and --plots need a model with a random input; this file has none",
            file.display()
        );
    }
    Ok(())
}

/// Prints a report as text, or as JSON with `json`.
fn print<T: std::fmt::Display + serde::Serialize>(r: &T, json: bool) -> anyhow::Result<()> {
    if json {
        print_json(r)
    } else {
        emit(&format!("{r}"));
        Ok(())
    }
}

/// Prints a report in `format`.
fn print_as<T: std::fmt::Display + serde::Serialize + ToMarkdown>(r: &T, format: ReportFormat) -> anyhow::Result<()> {
    match format {
        ReportFormat::Json => print_json(r),
        ReportFormat::Markdown => {
            emit(&r.markdown());
            Ok(())
        }
        ReportFormat::Text => {
            emit(&format!("{r}"));
            Ok(())
        }
    }
}

fn print_json<T: serde::Serialize + ?Sized>(r: &T) -> anyhow::Result<()> {
    emit_line(&serde_json::to_string_pretty(r)?);
    Ok(())
}

/// Progress on stderr: a `\r` percentage on a terminal, one "shard k/n" line per shard otherwise.
fn progress_printer() -> impl Fn(usize, usize) {
    use std::io::IsTerminal;
    let tty = std::io::stderr().is_terminal();
    move |done, total| {
        if tty {
            eprint!(
                "\rshard {done}/{total} ({:.0} %)",
                100.0 * done as f64 / total.max(1) as f64
            );
            if done == total {
                eprintln!();
            }
        } else {
            eprintln!("shard {done}/{total}");
        }
    }
}

/// Writes to stdout; a closed pipe (`stochvib spectra | head`) ends the program quietly.
fn emit(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
        eprintln!("error writing output: {e}");
        std::process::exit(1);
    }
}

fn emit_line(text: &str) {
    emit(&format!("{text}\n"));
}
