//! The `stochvib` command-line tool: parses arguments, calls the library, prints.

use anyhow::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use stochvib::plot::{scenario_plots_with, ScenarioPlotOptions};
use stochvib::report::{self, resolve_spectrum, spectrum_report};
use stochvib::scenario::{load_scenario, spectrum_catalogue};
use stochvib::spectrum::Convention;

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
    },
    /// Write pictures of a scenario (`.toml`): input density, |H(iω)|² and output densities with the
    /// cumulative variance, as SVG and PNG.
    Plot {
        /// Scenario file (TOML). Monte Carlo run files (`.h5`) are not handled yet.
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
                emit_line(&format!("{}", serde_json::to_string_pretty(&reports)?));
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
        } => {
            let dir = spectra_dir.unwrap_or_else(report::default_spectra_dir);
            let sc = load_scenario(&scenario, &dir)?;
            let r = report::analysis_report(&sc)?;
            if json {
                emit_line(&format!("{}", serde_json::to_string_pretty(&r)?));
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
            let is_toml = input.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"));
            if !is_toml {
                anyhow::bail!(
                    "{}: only scenario files (.toml) can be plotted; pictures of Monte Carlo run files (.h5) are not \
                     implemented",
                    input.display()
                );
            }
            let dir = spectra_dir.unwrap_or_else(report::default_spectra_dir);
            let sc = load_scenario(&input, &dir)?;
            for f in write_scenario_plots(&sc, &dir, &out, convention)? {
                emit_line(&f.display().to_string());
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
                emit_line(&format!("{}", serde_json::to_string_pretty(&r)?));
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
