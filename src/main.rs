//! The `stochvib` command-line tool: parses arguments, calls the library, prints.

use anyhow::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use stochvib::plot::{run_plots, scenario_plots_with, ScenarioPlotOptions};
use stochvib::report::{self, resolve_spectrum, spectrum_report};
use stochvib::scenario::{load_scenario, spectrum_catalogue};
use stochvib::simulate::{run_scenario, RunOptions};
use stochvib::spectrum::Convention;
use stochvib::store::{summarize, Compression, RunFile};

/// Stochastic vibration and random-road analysis of machines.
#[derive(Parser)]
#[command(name = "stochvib", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the spectrum catalogue with variance and sigma of each entry.
    Spectra {
        /// Directory of spectrum files (default: $STOCHVIB_SPECTRA, ./spectra, or the source tree's).
        #[arg(long)]
        spectra_dir: Option<PathBuf>,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
        /// Print the full report of every entry.
        #[arg(long)]
        full: bool,
    },
    /// Analyse a scenario: mean, σ, 3σ bounds, crossing rates, and every variance method per output.
    Analyze {
        /// Scenario file (TOML, see data/).
        scenario: PathBuf,
        /// Directory of spectrum files.
        #[arg(long)]
        spectra_dir: Option<PathBuf>,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// Also write the scenario's pictures (SVG and PNG) into this directory.
        #[arg(long)]
        plots: Option<PathBuf>,
        /// Add a Monte Carlo column: σ from N realizations with its 95 % interval and whether it covers
        /// the analytic σ (the run file goes to a temporary directory and is removed).
        #[arg(long, value_name = "N")]
        monte_carlo: Option<usize>,
        /// Master seed of the Monte Carlo column.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Time step, s (default: suggested from the system's eigenvalues).
        #[arg(long)]
        dt: Option<f64>,
        /// Duration of each realization, s (default: suggested from the slowest decay rate).
        #[arg(long)]
        duration: Option<f64>,
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
        /// Convention of the densities: one-sided-cyclic (Hz, default), one-sided-angular,
        /// two-sided-angular, engineering.
        #[arg(long, default_value = "one-sided-cyclic")]
        convention: Convention,
        /// Directory of spectrum files.
        #[arg(long)]
        spectra_dir: Option<PathBuf>,
    },
    /// Monte Carlo run of a scenario written to an HDF5 file (see the README's HDF5 section).
    Simulate {
        /// Scenario file (TOML, see data/).
        scenario: PathBuf,
        /// Number of realizations.
        #[arg(long)]
        realizations: usize,
        /// Duration of each realization, s.
        #[arg(long)]
        duration: f64,
        /// Time step, s.
        #[arg(long)]
        dt: f64,
        /// Master seed; realization i uses stream (seed, i).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output file (written as FILE.tmp and renamed when complete; an interrupted run resumes).
        #[arg(short = 'o', long = "output")]
        output: PathBuf,
        /// Realizations per shard.
        #[arg(long, default_value_t = 50)]
        shard_size: usize,
        /// Store every realization of every output.
        #[arg(long)]
        store_raw: bool,
        /// Compression of raw data: none, fast, deflate:N.
        #[arg(long, default_value = "none")]
        compression: String,
        /// Route: auto, exact, spectral.
        #[arg(long, default_value = "auto")]
        method: stochvib::simulate::Method,
        /// Confidence of the intervals.
        #[arg(long, default_value_t = 0.95)]
        confidence: f64,
        /// Remove an existing finished OUTPUT first (never needed for resuming a .tmp).
        #[arg(long)]
        overwrite: bool,
        /// Directory of spectrum files.
        #[arg(long)]
        spectra_dir: Option<PathBuf>,
        /// Print JSON.
        #[arg(long)]
        json: bool,
        /// After the run, write its pictures (as `stochvib plot OUTPUT -o DIR`) into this directory.
        #[arg(long)]
        plots: Option<PathBuf>,
    },
    /// Summarise a Monte Carlo run file.
    Inspect {
        /// Run file (HDF5).
        file: PathBuf,
        /// Print JSON.
        #[arg(long)]
        json: bool,
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
    },
    /// Report one spectrum: variance (model and quadrature), sigma, correlation, density.
    Spectrum {
        /// Catalogue name (e.g. `iso8608-c`) or path to a spectrum file.
        name: String,
        /// Convention of the printed density: two-sided-angular, one-sided-angular, one-sided-cyclic,
        /// engineering.
        #[arg(long, default_value = "two-sided-angular")]
        convention: Convention,
        /// Directory of spectrum files.
        #[arg(long)]
        spectra_dir: Option<PathBuf>,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> Result<()> {
    let cli = Cli::parse();
    match cli.command {
        Command::Spectra {
            spectra_dir,
            json,
            full,
        } => {
            let dir = spectra_dir.unwrap_or_else(report::default_spectra_dir);
            let entries = spectrum_catalogue(&dir)?;
            let mut reports = Vec::new();
            let mut failed = 0;
            if !json && !full {
                emit_line(&format!("catalogue {}", dir.display()));
                emit_line(&format!(
                    "{:<24} {:<9} {:>13} {:>13}  model",
                    "name", "domain", "variance", "sigma"
                ));
            }
            for e in &entries {
                match &e.spectrum {
                    Ok(s) => {
                        let r = spectrum_report(s, Convention::TwoSidedAngular);
                        if !json && !full {
                            let (v, sg) = match (&r.variance, &r.sigma) {
                                (
                                    report::spectrum_report::Outcome::Value(v),
                                    report::spectrum_report::Outcome::Value(s),
                                ) => (format!("{v:.4e}"), format!("{s:.4e}")),
                                _ => ("infinite".into(), "infinite".into()),
                            };
                            emit_line(&format!(
                                "{:<24} {:<9} {:>13} {:>13}  {}",
                                r.name, r.domain, v, sg, r.model
                            ));
                        } else if full && !json {
                            emit_line(&format!("{r}"));
                        }
                        reports.push(r);
                    }
                    Err(msg) => {
                        failed += 1;
                        eprintln!("error: {msg}");
                    }
                }
            }
            if json {
                emit_line(&serde_json::to_string_pretty(&reports)?);
            }
            if failed > 0 {
                anyhow::bail!("{failed} spectrum file(s) in {} are invalid", dir.display());
            }
        }
        Command::Book { json, plots } => {
            let r = report::book::book_report();
            if json {
                emit_line(&serde_json::to_string_pretty(&r)?);
            } else {
                emit(&format!("{r}"));
            }
            if let Some(out) = plots {
                for f in stochvib::plot::book_plots(&out)? {
                    eprintln!("wrote {}", f.display());
                }
            }
        }
        Command::Analyze {
            scenario,
            spectra_dir,
            json,
            plots,
            monte_carlo,
            seed,
            dt,
            duration,
        } => {
            let dir = spectra_dir.unwrap_or_else(report::default_spectra_dir);
            let sc = load_scenario(&scenario, &dir)?;
            let mut r = report::analysis_report(&sc)?;
            if let Some(n) = monte_carlo {
                let (sdt, sdur) = match (dt, duration) {
                    (Some(a), Some(b)) => (a, b),
                    _ => {
                        let (a, b) = stochvib::simulate::suggest_step(&sc)?;
                        (dt.unwrap_or(a), duration.unwrap_or(b))
                    }
                };
                let opts = RunOptions::new(n, sdur, sdt, seed);
                let tmp = std::env::temp_dir().join(format!("stochvib-analyze-{}.h5", std::process::id()));
                let _ = std::fs::remove_file(&tmp);
                let _ = std::fs::remove_file(stochvib::store::tmp_path(&tmp));
                let summary = run_scenario(&sc, &opts, &tmp, &progress_printer());
                // the run's own pictures (Welch band vs analytic density) before the file goes
                let mc_plots = match (&summary, &plots) {
                    (Ok(_), Some(out)) => Some(run_plots(&tmp, out)),
                    _ => None,
                };
                let _ = std::fs::remove_file(&tmp);
                let _ = std::fs::remove_file(stochvib::store::tmp_path(&tmp));
                report::analysis::attach_monte_carlo(&mut r, &summary?);
                if let (Some(files), Some(out)) = (mc_plots, &plots) {
                    eprintln!("wrote {} Monte Carlo pictures to {}", files?.len(), out.display());
                }
            }
            if json {
                emit_line(&serde_json::to_string_pretty(&r)?);
            } else {
                emit(&format!("{r}"));
            }
            if let Some(out) = plots {
                let files = write_scenario_plots(&sc, &dir, &out, Convention::OneSidedCyclic)?;
                eprintln!("wrote {} pictures to {}", files.len(), out.display());
            }
        }
        Command::Plot {
            input,
            out,
            convention,
            spectra_dir,
        } => {
            let is_h5 = input
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("h5") || e.eq_ignore_ascii_case("hdf5"));
            if is_h5 {
                for f in run_plots(&input, &out)? {
                    emit_line(&f.display().to_string());
                }
                return Ok(());
            }
            let is_toml = input.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"));
            if !is_toml {
                anyhow::bail!(
                    "{}: can plot scenario files (.toml) and Monte Carlo run files (.h5)",
                    input.display()
                );
            }
            let dir = spectra_dir.unwrap_or_else(report::default_spectra_dir);
            let sc = load_scenario(&input, &dir)?;
            for f in write_scenario_plots(&sc, &dir, &out, convention)? {
                emit_line(&f.display().to_string());
            }
        }
        Command::Simulate {
            scenario,
            realizations,
            duration,
            dt,
            seed,
            output,
            shard_size,
            store_raw,
            compression,
            method,
            confidence,
            overwrite,
            spectra_dir,
            json,
            plots,
        } => {
            let dir = spectra_dir.unwrap_or_else(report::default_spectra_dir);
            let sc = load_scenario(&scenario, &dir)?;
            let mut opts = RunOptions::new(realizations, duration, dt, seed);
            opts.shard_size = shard_size;
            opts.store_raw = store_raw;
            opts.compression = Compression::parse(&compression)?;
            opts.method = method;
            opts.confidence = confidence;
            if overwrite && output.exists() {
                std::fs::remove_file(&output)?;
            }
            let s = run_scenario(&sc, &opts, &output, &progress_printer())?;
            if json {
                emit_line(&serde_json::to_string_pretty(&s)?);
            } else {
                emit(&format!("{s}"));
            }
            if let Some(pdir) = plots {
                for f in run_plots(&s.path, &pdir)? {
                    if !json {
                        emit_line(&f.display().to_string());
                    }
                }
            }
        }
        Command::Inspect { file, json } => {
            if json {
                let run = RunFile::open(&file)?;
                let m = run.metadata();
                let stats: Vec<serde_json::Value> = run
                    .statistics()?
                    .iter()
                    .map(|o| {
                        serde_json::json!({
                            "output": o.output, "unit": o.unit, "n_used": o.n_used,
                            "statistics": o.statistics.iter().map(|s| serde_json::json!({
                                "name": s.name, "estimate": s.estimate, "lower": s.lower, "upper": s.upper,
                                "confidence": s.confidence, "unit": s.unit, "method": s.method,
                                "analytic": s.analytic, "covers": s.covers,
                            })).collect::<Vec<_>>(),
                        })
                    })
                    .collect();
                let v = serde_json::json!({
                    "path": file.display().to_string(),
                    "format_version": run.format_version(),
                    "toolkit_version": run.toolkit_version(),
                    "seed": m.seed, "generator": m.generator, "dt": m.dt, "n_samples": m.n_samples,
                    "n_realizations": m.n_realizations, "n_shards": m.n_shards(), "store_raw": m.store_raw,
                    "outputs": m.outputs.iter().map(|s| &s.name).collect::<Vec<_>>(),
                    "statistics": stats,
                });
                emit_line(&serde_json::to_string_pretty(&v)?);
            } else {
                emit(&summarize(&file)?);
            }
        }
        Command::Spectrum {
            name,
            convention,
            spectra_dir,
            json,
        } => {
            let dir = spectra_dir.unwrap_or_else(report::default_spectra_dir);
            let file = resolve_spectrum(&name, &dir)?;
            let r = spectrum_report(&file, convention);
            if json {
                emit_line(&serde_json::to_string_pretty(&r)?);
            } else {
                emit(&format!("{r}"));
            }
        }
    }
    Ok(())
}

/// Scenario pictures, with the input unit read from the spectrum file the scenario names.
fn write_scenario_plots(
    sc: &stochvib::scenario::Scenario,
    spectra_dir: &std::path::Path,
    out: &std::path::Path,
    convention: Convention,
) -> Result<Vec<PathBuf>> {
    let input_unit = resolve_spectrum(&sc.input_name, spectra_dir).ok().map(|f| f.unit);
    let opts = ScenarioPlotOptions {
        convention,
        input_unit,
        ..ScenarioPlotOptions::default()
    };
    Ok(scenario_plots_with(sc, out, &opts)?)
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
