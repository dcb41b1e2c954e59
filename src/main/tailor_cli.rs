//! `stochvib tailor`: the extreme response spectrum and the fatigue damage spectrum of a base
//! acceleration (a spectrum file or a scenario output) over a family of oscillators; parses, calls the
//! library, returns the table for printing.

use std::path::PathBuf;
use stochvib::extremes::{ErsFdsOptions, FdsMaterial};
use stochvib::scenario::load_scenario;
use stochvib::study::tailoring::{tailoring_spectra, FrequencyGrid, TailoringSource, TailoringTable};
use stochvib::units::{parse_as, Dim};

/// `stochvib tailor SPECTRUM --duration T` or `stochvib tailor --scenario FILE --output-name NAME --duration T`.
#[derive(clap::Args)]
pub struct TailorArgs {
    /// The base acceleration: a catalogue name (e.g. `iso7096-em6`) or a spectrum file, temporal, in m/s^2.
    #[arg(required_unless_present = "scenario", conflicts_with = "scenario")]
    spectrum: Option<String>,
    /// A scenario whose output --output-name is the base acceleration (e.g. a cab floor).
    #[arg(long, requires = "output_name")]
    scenario: Option<PathBuf>,
    /// The scenario's output (unit m/s^2).
    #[arg(long, value_name = "NAME", requires = "scenario")]
    output_name: Option<String>,
    /// Duration T of the vibration, with a unit (e.g. "8 h", "600 s").
    #[arg(long, value_name = "T")]
    duration: String,
    /// Lowest natural frequency of the family, with a unit.
    #[arg(long, value_name = "F", default_value = "1 Hz")]
    f_min: String,
    /// Highest natural frequency of the family, with a unit.
    #[arg(long, value_name = "F", default_value = "100 Hz")]
    f_max: String,
    /// Natural frequencies, evenly spaced in log f, the ends included.
    #[arg(long, default_value_t = 41)]
    points: usize,
    /// Quality factor Q = 1/(2ζ) of the oscillators.
    #[arg(long, default_value_t = 10.0)]
    q: f64,
    /// Basquin exponent b of N·σ^b = C.
    #[arg(long, default_value_t = 8.0)]
    b: f64,
    /// K, stress per metre of relative displacement, Pa/m (1: the FDS in m^b).
    #[arg(long, default_value_t = 1.0)]
    k: f64,
    /// C of N·σ^b = C, Pa^b (1: unscaled).
    #[arg(long, default_value_t = 1.0)]
    c: f64,
    #[command(flatten)]
    spectra: super::SpectraDir,
    #[command(flatten)]
    pub(crate) output: super::Output,
}

/// Runs `stochvib tailor`: the table to print.
pub fn tailor(a: &TailorArgs) -> anyhow::Result<TailoringTable> {
    let quantity =
        |flag: &str, text: &str, dim: Dim| parse_as(text, dim).map_err(|e| anyhow::anyhow!("--{flag} {text}: {e}"));
    // a frequency's SI value is angular (rad/s; "1 Hz" reads as 2π): the grid is in Hz
    let hz = |flag: &str, text: &str| quantity(flag, text, Dim::FREQUENCY).map(|w| w / (2.0 * std::f64::consts::PI));
    let grid = FrequencyGrid {
        min_hz: hz("f-min", &a.f_min)?,
        max_hz: hz("f-max", &a.f_max)?,
        points: a.points,
    };
    let opts = ErsFdsOptions {
        frequencies_hz: grid.frequencies()?,
        q: a.q,
        duration_s: quantity("duration", &a.duration, Dim::TIME)?,
        material: FdsMaterial { b: a.b, k: a.k, c: a.c },
        rel_tol: 1e-8,
    };
    let catalogue = a.spectra.catalogue();
    let table = match (&a.spectrum, &a.scenario, &a.output_name) {
        (Some(name), _, _) => {
            let file = catalogue.resolve(name, None)?;
            tailoring_spectra(&TailoringSource::Spectrum(&file), &opts)?
        }
        (None, Some(path), Some(name)) => {
            let sc = load_scenario(path, catalogue.dir())?;
            let output = sc.model.system.output_index(name)?;
            tailoring_spectra(&TailoringSource::Output { scenario: &sc, output }, &opts)?
        }
        _ => anyhow::bail!("give a spectrum, or --scenario FILE with --output-name NAME"),
    };
    Ok(table)
}
