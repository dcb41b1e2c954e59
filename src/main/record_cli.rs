//! The measured-record commands of the `stochvib` tool (`exposure`, `fatigue`, `weighting`, `coherence`,
//! `iri`): argument structs and their handlers, which parse, call the library and print.

use std::path::PathBuf;
use stochvib::comfort::Weighting;
use stochvib::fatigue::SnCurve;
use stochvib::record::{
    evaluate_exposure, evaluate_fatigue, open_record, AxisAssignment, ExposureOptions, FatigueOptions,
    MeanStressCorrection, RecordOptions, RunningRms, SnPoint,
};
use stochvib::report::record_report::{ExposureReport, FatigueReport};
use stochvib::study::weighting_table::WeightingReport;
use stochvib::units::Dim;

/// What a record file does not say: its rate, units, format details.
#[derive(clap::Args)]
pub struct RecordArgs {
    /// Sample rate in Hz (required without a time column or rate attribute; checked against them).
    #[arg(long, value_name = "HZ")]
    sample_rate: Option<f64>,
    /// Unit of a channel whose header or attribute gives none, e.g. `--unit seat_z=m/s^2` (repeatable).
    #[arg(long = "unit", value_name = "NAME=UNIT")]
    units: Vec<String>,
    /// CSV: the decimal separator is a comma (the fields then separated by `;` or tabs).
    #[arg(long)]
    decimal_comma: bool,
    /// HDF5: a dataset to read, e.g. `/seat/z` (repeatable; default: every 1-D dataset of the root group).
    #[arg(long = "dataset", value_name = "PATH")]
    datasets: Vec<String>,
    /// WAV: the channel names, comma-separated (default ch1, ch2, …).
    #[arg(long, value_delimiter = ',')]
    channels: Vec<String>,
    /// WAV: the physical value of full scale with its unit, e.g. `50 m/s^2`.
    #[arg(long, value_name = "VALUE UNIT")]
    full_scale: Option<String>,
}

impl RecordArgs {
    fn options(&self) -> anyhow::Result<RecordOptions> {
        let units = self
            .units
            .iter()
            .map(|u| {
                u.split_once('=')
                    .map(|(n, v)| (n.trim().to_string(), v.trim().to_string()))
                    .ok_or_else(|| anyhow::anyhow!("--unit {u}: expected NAME=UNIT, e.g. seat_z=m/s^2"))
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        Ok(RecordOptions {
            sample_rate_hz: self.sample_rate,
            units,
            decimal_comma: self.decimal_comma,
            datasets: self.datasets.clone(),
            channel_names: self.channels.clone(),
            full_scale: self.full_scale.clone(),
        })
    }
}

/// `stochvib exposure RECORD`.
#[derive(clap::Args)]
pub struct ExposureArgs {
    /// Acceleration record: CSV (`time [s], seat_z [m/s^2], …`), HDF5 datasets or WAV (docs/records.md).
    record: PathBuf,
    /// Which channel is which axis: CHANNEL=LOCATION:AXIS, LOCATION seat-surface, seat-back, feet or
    /// standing-floor, AXIS x, y, z, rx, ry, rz (repeatable; default: channels named x, y, z on the seat).
    #[arg(long = "axis", value_name = "CHANNEL=LOCATION:AXIS")]
    axes: Vec<String>,
    /// A vertical channel also evaluated for motion sickness (Wf, MSDV) (repeatable).
    #[arg(long = "motion-sickness", value_name = "CHANNEL")]
    motion_sickness: Vec<String>,
    /// Daily exposure duration, e.g. `8 h`, `150 min` (default: the record's duration).
    #[arg(long, value_name = "DURATION")]
    exposure: Option<String>,
    /// Running r.m.s. of the MTVV: linear (ISO 2631-1 6.3.1 first form) or exponential.
    #[arg(long, value_enum, default_value_t = RunningRms::Linear)]
    running: RunningRms,
    #[command(flatten)]
    record_args: RecordArgs,
    #[command(flatten)]
    output: super::Output,
    /// Also write the pictures (weighted time history with the running r.m.s.; band spectrum against the
    /// comfort scale) as SVG and PNG into this directory.
    #[arg(long)]
    plots: Option<PathBuf>,
}

/// `stochvib exposure`.
pub fn exposure(a: ExposureArgs) -> anyhow::Result<()> {
    let options = ExposureOptions {
        axes: a
            .axes
            .iter()
            .map(|s| AxisAssignment::parse(s))
            .collect::<stochvib::Result<Vec<_>>>()?,
        motion_sickness: a.motion_sickness.clone(),
        exposure_s: a
            .exposure
            .as_deref()
            .map(|t| stochvib::units::parse_as(t, Dim::TIME).map_err(|e| anyhow::anyhow!("--exposure {t}: {e}")))
            .transpose()?,
        running: a.running,
        ..ExposureOptions::default()
    };
    check_plots(a.plots.as_deref())?;
    let mut reader = open_record(&a.record, &a.record_args.options()?)?;
    let report = ExposureReport(evaluate_exposure(reader.as_mut(), &options)?);
    print_and_draw(&report, &a.output, a.plots, |r, dir| {
        stochvib::plot::record_plots::exposure_plots(&r.0, dir)
    })
}

/// What `--plots` names: refused before the record is read when it exists and is not a directory. The directory
/// itself is made only after the record was evaluated ([`print_and_draw`]), so a refused record leaves nothing.
fn check_plots(dir: Option<&std::path::Path>) -> anyhow::Result<()> {
    if let Some(dir) = dir
        && std::fs::metadata(dir).is_ok_and(|m| !m.is_dir())
    {
        anyhow::bail!(
            "{}: is not a directory: --plots names the directory of the pictures; nothing was written",
            dir.display()
        );
    }
    Ok(())
}

/// Prints `report`, then makes the directory `plots` (when given) and draws its pictures into it with `draw`.
fn print_and_draw<T: std::fmt::Display + serde::Serialize + stochvib::report::table::ToMarkdown>(
    report: &T,
    output: &super::Output,
    plots: Option<PathBuf>,
    draw: impl FnOnce(&T, &std::path::Path) -> stochvib::Result<Vec<PathBuf>>,
) -> anyhow::Result<()> {
    if let Some(dir) = &plots {
        super::output_dir(dir, "--plots names the directory of the pictures")?;
    }
    super::print_as(report, output.format())?;
    if let Some(dir) = plots {
        let files = draw(report, &dir)?;
        eprintln!("wrote {} pictures to {}", files.len(), dir.display());
    }
    Ok(())
}

/// `stochvib fatigue RECORD`.
#[derive(clap::Args)]
pub struct FatigueArgs {
    /// Stress or strain record: CSV, HDF5 or WAV (docs/records.md).
    record: PathBuf,
    /// The channel to count (default: the record's only channel).
    #[arg(long)]
    channel: Option<String>,
    /// Slope k of the S–N curve N·S_a^k = C.
    #[arg(long, value_name = "K")]
    sn_slope: f64,
    /// A point of the S–N curve as an amplitude with its unit, e.g. `80 MPa` (with --sn-cycles).
    #[arg(long, value_name = "VALUE UNIT", conflicts_with = "sn_range")]
    sn_amplitude: Option<String>,
    /// A point of the S–N curve as a range with its unit, e.g. `160 MPa` (a detail category; with --sn-cycles).
    #[arg(long, value_name = "VALUE UNIT")]
    sn_range: Option<String>,
    /// Cycles to failure at that point.
    #[arg(long, value_name = "N", default_value_t = 2e6)]
    sn_cycles: f64,
    /// Endurance limit as an amplitude with its unit (cycles below it do no damage).
    #[arg(long, value_name = "VALUE UNIT")]
    endurance: Option<String>,
    /// Mean-stress correction of the rainflow damage: none, goodman, gerber, swt.
    #[arg(long, default_value = "none")]
    mean_stress: String,
    /// Ultimate strength for Goodman and Gerber, with its unit.
    #[arg(long, value_name = "VALUE UNIT")]
    ultimate: Option<String>,
    /// Hysteresis gate with its unit: reversals of a smaller range are removed before counting.
    #[arg(long, value_name = "VALUE UNIT")]
    gate: Option<String>,
    /// Welch segment length in samples (default: the largest power of two ≤ N/8, at most 65536).
    #[arg(long)]
    segment: Option<usize>,
    #[command(flatten)]
    record_args: RecordArgs,
    #[command(flatten)]
    output: super::Output,
    /// Also write the pictures (range histogram against Dirlik's density, the rainflow matrix).
    #[arg(long)]
    plots: Option<PathBuf>,
}

/// An amplitude-like flag in SI with the dimension it must share with the S–N point.
fn same_dim(flag: &str, text: &str, dim: Dim) -> anyhow::Result<f64> {
    Ok(stochvib::record::quantity_of_dim(flag, text, dim)?)
}

/// The S–N curve and its dimension from the flags.
fn sn_curve(a: &FatigueArgs) -> anyhow::Result<(SnCurve, Dim)> {
    let point = match (&a.sn_amplitude, &a.sn_range) {
        (Some(p), None) => SnPoint::Amplitude(p),
        (None, Some(p)) => SnPoint::Range(p),
        _ => anyhow::bail!("give the S–N curve's point: --sn-amplitude VALUE UNIT or --sn-range VALUE UNIT"),
    };
    Ok(stochvib::record::sn_curve_from_flags(
        a.sn_slope,
        point,
        a.sn_cycles,
        a.endurance.as_deref(),
    )?)
}

/// `stochvib fatigue`.
pub fn fatigue(a: FatigueArgs) -> anyhow::Result<()> {
    let (sn, sn_dim) = sn_curve(&a)?;
    let ultimate = || -> anyhow::Result<f64> {
        let t = a
            .ultimate
            .as_deref()
            .ok_or_else(|| anyhow::anyhow!("--mean-stress {}: needs --ultimate VALUE UNIT", a.mean_stress))?;
        same_dim("--ultimate", t, sn_dim)
    };
    let mean_stress = match a.mean_stress.as_str() {
        "none" => MeanStressCorrection::None,
        "goodman" => MeanStressCorrection::Goodman { ultimate: ultimate()? },
        "gerber" => MeanStressCorrection::Gerber { ultimate: ultimate()? },
        "swt" => MeanStressCorrection::Swt,
        other => anyhow::bail!("--mean-stress {other}: expected none, goodman, gerber or swt"),
    };
    let options = FatigueOptions {
        channel: a.channel.clone(),
        sn,
        sn_dim,
        mean_stress,
        gate: a.gate.as_deref().map(|t| same_dim("--gate", t, sn_dim)).transpose()?,
        segment_len: a.segment,
    };
    check_plots(a.plots.as_deref())?;
    let mut reader = open_record(&a.record, &a.record_args.options()?)?;
    let report = FatigueReport(evaluate_fatigue(reader.as_mut(), &options)?);
    print_and_draw(&report, &a.output, a.plots, |r, dir| {
        stochvib::plot::record_plots::fatigue_plots(&r.0, dir)
    })
}

/// `stochvib weighting NAME`.
#[derive(clap::Args)]
pub struct WeightingArgs {
    /// Wk, Wd, Wc, We, Wj, Wb or Wf.
    name: String,
    /// Frequencies in Hz, comma-separated (default: the one-third-octave centres of the evaluation range).
    #[arg(long, value_delimiter = ',')]
    frequency: Vec<f64>,
    /// Also the digital realisation at this sample rate (Hz), with its error.
    #[arg(long, value_name = "HZ")]
    sample_rate: Option<f64>,
    #[command(flatten)]
    output: super::Output,
}

/// `stochvib weighting`.
pub fn weighting(a: WeightingArgs) -> anyhow::Result<()> {
    let w = Weighting::parse(&a.name)?;
    super::print_as(
        &WeightingReport::new(w, &a.frequency, a.sample_rate)?,
        a.output.format(),
    )
}

/// `stochvib coherence`.
#[derive(clap::Args)]
pub struct CoherenceArgs {
    /// A coherence model as a TOML inline table, e.g. `{ kind = "dodds-robson", waviness = 2 }` (the
    /// `coherence` of a scenario's road; kinds dodds-robson, ammon-bormann, tabulated, constant).
    #[arg(long, value_name = "TOML")]
    model: Option<String>,
    /// Track width of the model, with its unit.
    #[arg(long, value_name = "VALUE UNIT", default_value = "1.5 m")]
    track_width: String,
    /// Spatial frequencies in cycles/m, comma-separated (model only; default 0.01 to 10, 4 per decade).
    #[arg(long, value_delimiter = ',')]
    frequency: Vec<f64>,
    /// A measured profile of two tracks (CSV as for `stochvib road`): its squared coherence per bin, with the
    /// model's beside it when --model is given.
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Welch segment length of the profile, samples.
    #[arg(long)]
    segment: Option<usize>,
    /// Confidence of the profile's intervals.
    #[arg(long, default_value_t = 0.95)]
    confidence: f64,
    #[command(flatten)]
    output: super::Output,
}

/// `stochvib coherence`.
pub fn coherence(a: CoherenceArgs) -> anyhow::Result<()> {
    let width = stochvib::units::parse_as(&a.track_width, Dim::LENGTH)
        .map_err(|e| anyhow::anyhow!("--track-width {}: {e}", a.track_width))?;
    let model = a
        .model
        .as_deref()
        .map(|t| stochvib::scenario::coherence_from_toml(t, width))
        .transpose()?;
    let r = stochvib::study::road_numbers::coherence_report(
        model,
        a.profile.as_deref(),
        &a.frequency,
        a.segment,
        a.confidence,
    )?;
    super::print_as(&r, a.output.format())
}

/// `stochvib iri`.
#[derive(clap::Args)]
pub struct IriArgs {
    /// A road spectrum: catalogue name (e.g. `iso8608-c`) or spectrum file (spatial).
    spectrum: String,
    /// A measured profile (CSV as for `stochvib road`) whose IRI is printed beside the expectation.
    #[arg(long)]
    profile: Option<PathBuf>,
    #[command(flatten)]
    spectra: super::SpectraDir,
    #[command(flatten)]
    output: super::Output,
}

/// `stochvib iri`.
pub fn iri(a: IriArgs) -> anyhow::Result<()> {
    let spectrum = a.spectra.catalogue().resolve(&a.spectrum, None)?;
    let r = stochvib::study::road_numbers::iri_report(&spectrum, a.profile.as_deref())?;
    super::print_as(&r, a.output.format())
}
