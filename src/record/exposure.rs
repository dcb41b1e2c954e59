//! ISO 2631-1 evaluation of a measured acceleration record in the time domain, streamed block by block:
//! per axis the digitally weighted acceleration ([`DigitalWeighting`]), its a_w, running r.m.s. and MTVV,
//! VDV, crest factor and the basic-method criteria ([`SignalMetricsStream`]), its one-third-octave band
//! values ([`BandAnalyzer`]); over the axes the comfort vector sum, the daily exposure A(8) and VDV with the
//! health factors, the Directive 2002/44/EC and ISO 2631-1 Annex B verdict ([`ExposureVerdict`]); MSDV for
//! motion-sickness (Wf) channels. Memory is one block plus one Welch segment per axis, whatever the
//! record's length.

use super::bands::{segment_for, BandAnalyzer, BandValue};
use super::filter::{DigitalWeighting, FilterState};
use super::running::{Envelope, EnvelopeBin, ExponentialRms, RunningRms};
use super::source::{RecordInfo, RecordReader};
use crate::comfort::{
    axis_factor, daily_exposure_a8, directive_factor, vector_sum, Axis, AxisValue, ExposureVerdict, Location, Motion,
    Purpose, SignalMetrics, SignalMetricsStream, VectorSum, Weighting, MAX_DAILY_EXPOSURE_S, MIN_DAILY_EXPOSURE_S,
    MTVV_INTEGRATION_TIME_S,
};
use crate::error::{Error, Result};
use crate::units::Dim;
use rayon::prelude::*;

/// Samples per channel read at a time.
pub const BLOCK_SAMPLES: usize = 1 << 16;

/// Samples of one channel weighted and passed through the accumulators at a time: the weighted chunk and its
/// running r.m.s. stay in the processor's first-level cache between the passes.
const CHUNK_SAMPLES: usize = 2048;

/// The largest |value| (SI: m/s², rad/s²) of an evaluated channel. Above it the weighted signal's fourth
/// powers, summed for the VDV over up to 2⁶³ samples, could leave the range of f64 (1.8·10³⁰⁸): (1.2·10⁶⁰)⁴ ·
/// 9.2·10¹⁸ ≈ 2·10²⁵⁹, with 20 % for the weighting's gain and its filter's overshoot. No acceleration a
/// machine meets comes near it; such a value is a unit or scaling error, or a corrupt file.
pub const MAX_ABS_VALUE: f64 = 1e60;

/// Bins kept by the envelope of each weighted signal (for the time-history picture): between this and twice
/// this.
pub const ENVELOPE_BINS: usize = 300;

/// Which channel is which axis at which location.
///
/// # Examples
/// ```
/// use stochvib::comfort::{Axis, Location};
/// use stochvib::record::AxisAssignment;
/// let a = AxisAssignment::parse("seat_z=seat-surface:z").unwrap();
/// assert_eq!((a.channel.as_str(), a.location, a.axis), ("seat_z", Location::SeatSurface, Axis::Z));
/// assert!(AxisAssignment::parse("seat_z=seat:up").is_err());
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AxisAssignment {
    /// The record's channel.
    pub channel: String,
    /// Where it was measured.
    pub location: Location,
    /// Its axis.
    pub axis: Axis,
}

/// As written on the command line: `CHANNEL=LOCATION:AXIS` (what [`AxisAssignment::parse`] reads).
impl std::fmt::Display for AxisAssignment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}={}:{}", self.channel, self.location.label(), self.axis.label())
    }
}

impl AxisAssignment {
    /// Parses `CHANNEL=LOCATION:AXIS`, LOCATION one of `seat-surface`, `seat-back`, `feet`,
    /// `standing-floor`, AXIS one of `x`, `y`, `z`, `rx`, `ry`, `rz`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `--axis`, the text and what is accepted.
    pub fn parse(text: &str) -> Result<Self> {
        let bad = |why: &str| Error::invalid("--axis", text, why.to_string());
        let (channel, place) = text
            .split_once('=')
            .ok_or_else(|| bad("expected CHANNEL=LOCATION:AXIS, e.g. seat_z=seat-surface:z"))?;
        let (loc, axis) = place
            .split_once(':')
            .ok_or_else(|| bad("expected CHANNEL=LOCATION:AXIS, e.g. seat_z=seat-surface:z"))?;
        let location = [
            Location::SeatSurface,
            Location::SeatBack,
            Location::Feet,
            Location::StandingFloor,
        ]
        .into_iter()
        .find(|l| l.label() == loc.trim())
        .ok_or_else(|| bad("unknown location; expected seat-surface, seat-back, feet or standing-floor"))?;
        let axis = [Axis::X, Axis::Y, Axis::Z, Axis::Rx, Axis::Ry, Axis::Rz]
            .into_iter()
            .find(|a| a.label() == axis.trim())
            .ok_or_else(|| bad("unknown axis; expected x, y, z, rx, ry or rz"))?;
        if channel.trim().is_empty() {
            return Err(bad("empty channel name"));
        }
        Ok(AxisAssignment {
            channel: channel.trim().to_string(),
            location,
            axis,
        })
    }
}

/// What to evaluate and how.
#[derive(Debug, Clone, PartialEq)]
pub struct ExposureOptions {
    /// The axes; empty: channels named `x`, `y`, `z` (any case) as seat-surface axes.
    pub axes: Vec<AxisAssignment>,
    /// Channels evaluated for motion sickness (vertical, Wf, MSDV).
    pub motion_sickness: Vec<String>,
    /// Daily exposure duration T_exp, s (default: the record's duration).
    pub exposure_s: Option<f64>,
    /// Which running r.m.s. gives the MTVV.
    pub running: RunningRms,
    /// Integration time τ of the running r.m.s., s (1 s in ISO 2631-1).
    pub tau_s: f64,
}

impl Default for ExposureOptions {
    fn default() -> Self {
        ExposureOptions {
            axes: Vec::new(),
            motion_sickness: Vec::new(),
            exposure_s: None,
            running: RunningRms::Linear,
            tau_s: MTVV_INTEGRATION_TIME_S,
        }
    }
}

/// The largest error of a digital weighting over its evaluation range.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct RealisationError {
    /// Largest |20 log₁₀(|H|/|W|)| at a one-third-octave centre, dB.
    pub max_error_db: f64,
    /// Where, Hz.
    pub at_hz: f64,
    /// Largest |arg(H/W)| at a centre, degrees.
    pub max_phase_error_deg: f64,
}

/// The health values of an axis that enters the Directive's daily exposure.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HealthAxis {
    /// Health factor k (1.4 for x, y; 1 for z).
    pub k: f64,
    /// k·a_w, m/s².
    pub weighted_a_w: f64,
    /// A(8) = k·a_w·√(T_exp/8 h), m/s².
    pub a8: f64,
    /// Daily VDV = k·VDV·(T_exp/T)^(1/4), m/s^1.75.
    pub daily_vdv: f64,
}

/// One evaluated channel.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AxisEvaluation {
    /// The channel.
    pub channel: String,
    /// Location and axis (motion sickness: seat surface, z).
    pub location: Location,
    /// Axis.
    pub axis: Axis,
    /// The weighting applied.
    pub weighting: Weighting,
    /// The comfort factor k of ISO 2631-1 8.2 (`None` for motion sickness).
    pub comfort_k: Option<f64>,
    /// a_w, VDV, MSDV, MTVV (linear running r.m.s.), crest factor, the basic-method criteria.
    pub metrics: SignalMetrics,
    /// MTVV of the exponential running r.m.s. (τ), m/s².
    pub mtvv_exponential: f64,
    /// MTVV of the form chosen for the report ([`ExposureOptions::running`]).
    pub mtvv: Option<f64>,
    /// MSDV extrapolated to the exposure, a_w·√T_exp, m/s^1.5 (motion sickness only).
    pub msdv_exposure: Option<f64>,
    /// Health values, for the axes the Directive counts.
    pub health: Option<HealthAxis>,
    /// The digital weighting's largest error over the evaluation range.
    pub realisation: RealisationError,
    /// One-third-octave band values of the weighted signal (`None` for a record shorter than one segment).
    pub bands: Option<Vec<BandValue>>,
    /// Welch segment length of the bands, samples.
    pub segment_len: usize,
    /// The weighted signal's envelope with its running r.m.s. (for the time-history picture).
    #[serde(skip)]
    pub envelope: Vec<EnvelopeBin>,
}

/// The evaluation of a record.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ExposureEvaluation {
    /// The record.
    pub record: RecordInfo,
    /// Samples per channel.
    pub samples: usize,
    /// Duration T = N/f_s, s.
    pub duration_s: f64,
    /// Daily exposure T_exp, s.
    pub exposure_s: f64,
    /// Running r.m.s. form of the MTVV, and τ.
    pub running: RunningRms,
    /// τ, s.
    pub tau_s: f64,
    /// Health and comfort axes.
    pub axes: Vec<AxisEvaluation>,
    /// Motion-sickness channels (Wf).
    pub motion_sickness: Vec<AxisEvaluation>,
    /// The comfort vector sum over every axis (ISO 2631-1 8.2).
    pub comfort: Option<VectorSum>,
    /// The health vector sum of the seat-surface axes (ISO 2631-1 7.2.2, an additional indicator).
    pub health_vector: Option<VectorSum>,
    /// Directive and Annex B verdict from the dominant axes (`None` without a health axis).
    pub verdict: Option<ExposureVerdict>,
    /// The axis of the verdict's A(8).
    pub dominant_a8: Option<String>,
    /// The axis of the verdict's VDV.
    pub dominant_vdv: Option<String>,
}

/// One channel being evaluated.
struct Evaluator {
    index: usize,
    assignment: AxisAssignment,
    weighting: Weighting,
    filter: DigitalWeighting,
    state: Option<FilterState>,
    metrics: SignalMetricsStream,
    exponential: ExponentialRms,
    bands: BandAnalyzer,
    band_list: Vec<crate::comfort::Band>,
    envelope: Envelope,
    weighted: Vec<f64>,
    running: Vec<f64>,
    segment_len: usize,
}

impl Evaluator {
    fn new(info: &RecordInfo, assignment: AxisAssignment, weighting: Weighting, tau_s: f64) -> Result<Self> {
        let index = info.channel(&assignment.channel)?;
        let (dim, what) = match weighting.quantity().motion {
            Motion::Translational => (Dim::ACCELERATION, "an acceleration (m/s^2)"),
            Motion::Rotational => (Dim::new(0, 0, -2), "an angular acceleration (rad/s^2)"),
        };
        info.require_dim(index, dim, what)?;
        let fs = info.sample_rate_hz;
        let in_record = |e: Error| match e {
            Error::InvalidParameter { value, reason, .. } => Error::in_file(
                &info.source,
                format!("sample rate (channel `{}`, {weighting})", assignment.channel),
                value,
                reason,
            ),
            other => other,
        };
        let filter = DigitalWeighting::new(weighting, fs).map_err(in_record)?;
        let band_list = filter.check_bands().map_err(in_record)?;
        let dt = 1.0 / fs;
        let segment_len = segment_for(&band_list[0], fs, info.samples_hint);
        Ok(Evaluator {
            index,
            assignment,
            weighting,
            filter,
            state: None,
            metrics: SignalMetricsStream::new(dt, tau_s)?,
            exponential: ExponentialRms::new(dt, tau_s)?,
            bands: BandAnalyzer::new(segment_len, dt)?,
            band_list,
            envelope: Envelope::new(dt, ENVELOPE_BINS),
            weighted: Vec::new(),
            running: Vec::new(),
            segment_len,
        })
    }

    /// Weights the next samples and feeds every accumulator, [`CHUNK_SAMPLES`] at a time.
    fn push(&mut self, x: &[f64]) -> Result<()> {
        x.chunks(CHUNK_SAMPLES).try_for_each(|c| self.push_chunk(c))
    }

    fn push_chunk(&mut self, x: &[f64]) -> Result<()> {
        let filter = &self.filter;
        let state = self.state.get_or_insert_with(|| filter.state_at_rest(x[0]));
        self.weighted.resize(x.len(), 0.0);
        filter.filter(state, x, &mut self.weighted);
        let running = &mut self.running;
        running.clear();
        self.metrics.push_each(&self.weighted, |ms| running.push(ms.sqrt()))?;
        self.exponential.push(&self.weighted);
        self.bands.push(&self.weighted)?;
        let missing = self.weighted.len() - self.running.len();
        for (i, &v) in self.weighted.iter().enumerate() {
            let r = if i < missing {
                f64::NAN
            } else {
                self.running[i - missing]
            };
            self.envelope.add(v, r);
        }
        Ok(())
    }

    fn finish(self, options: &ExposureOptions, exposure_s: f64, sickness: bool) -> Result<AxisEvaluation> {
        let metrics = self.metrics.finish()?;
        let (lo, hi) = self.weighting.evaluation_range_hz();
        let rows = self.filter.error_table(lo, hi)?;
        let worst = rows
            .iter()
            .max_by(|a, b| a.error_db.abs().total_cmp(&b.error_db.abs()))
            .copied();
        let realisation = RealisationError {
            max_error_db: worst.map_or(0.0, |r| r.error_db.abs()),
            at_hz: worst.map_or(f64::NAN, |r| r.frequency_hz),
            max_phase_error_deg: rows.iter().map(|r| r.phase_error_deg.abs()).fold(0.0, f64::max),
        };
        let a = &self.assignment;
        let health = if sickness {
            None
        } else {
            directive_factor(a.location, a.axis)
                .map(|f| health_axis(f.k, &metrics, exposure_s))
                .transpose()?
        };
        let comfort_k = if sickness {
            None
        } else {
            Some(axis_factor(Purpose::Comfort, a.location, a.axis)?.k)
        };
        let mtvv_exponential = self.exponential.mtvv();
        let mtvv = match options.running {
            RunningRms::Linear => metrics.mtvv,
            RunningRms::Exponential => Some(mtvv_exponential),
        };
        Ok(AxisEvaluation {
            channel: a.channel.clone(),
            location: a.location,
            axis: a.axis,
            weighting: self.weighting,
            comfort_k,
            mtvv_exponential,
            mtvv,
            msdv_exposure: sickness.then(|| metrics.a_w * exposure_s.sqrt()),
            health,
            realisation,
            bands: self.bands.finish(&self.band_list)?,
            segment_len: self.segment_len,
            envelope: self.envelope.bins(),
            metrics,
        })
    }
}

/// A(8) and daily VDV of one axis with health factor k.
fn health_axis(k: f64, m: &SignalMetrics, exposure_s: f64) -> Result<HealthAxis> {
    Ok(HealthAxis {
        k,
        weighted_a_w: k * m.a_w,
        a8: daily_exposure_a8(k * m.a_w, exposure_s)?,
        daily_vdv: k * m.vdv * (exposure_s / m.duration_s).powf(0.25),
    })
}

/// The axes to evaluate: the options', or the channels named x, y, z as seat-surface axes.
fn resolve_axes(info: &RecordInfo, options: &ExposureOptions) -> Result<Vec<AxisAssignment>> {
    if !options.axes.is_empty() || !options.motion_sickness.is_empty() {
        for (i, a) in options.axes.iter().enumerate() {
            if let Some(b) = options.axes[..i]
                .iter()
                .find(|b| (b.location, b.axis) == (a.location, a.axis))
            {
                return Err(Error::invalid(
                    "--axis",
                    a,
                    format!(
                        "{}:{} is already given to channel `{}`: each location and axis is one channel",
                        a.location.label(),
                        a.axis.label(),
                        b.channel
                    ),
                ));
            }
        }
        return Ok(options.axes.clone());
    }
    let by_name: Vec<AxisAssignment> = info
        .channels
        .iter()
        .filter_map(|c| {
            let axis = match c.name.to_ascii_lowercase().as_str() {
                "x" => Axis::X,
                "y" => Axis::Y,
                "z" => Axis::Z,
                _ => return None,
            };
            Some(AxisAssignment {
                channel: c.name.clone(),
                location: Location::SeatSurface,
                axis,
            })
        })
        .collect();
    if by_name.is_empty() {
        return Err(Error::in_file(
            &info.source,
            "channels",
            info.channels
                .iter()
                .map(|c| c.name.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            "which channel is which axis? name them with --axis CHANNEL=LOCATION:AXIS (e.g. seat_z=seat-surface:z), \
             or name the columns x, y, z for the seat surface",
        ));
    }
    Ok(by_name)
}

/// Evaluates a record (see the [module docs](self)).
///
/// # Formula
/// Per axis, the digital weighting (started at rest with the first sample, [`DigitalWeighting::state_at_rest`])
/// gives a_w(t); then [`SignalMetrics`] (a_w, VDV, MSDV, MTVV, crest factor, basic-method criteria), the
/// exponential running r.m.s. ([`ExponentialRms`]) and the band values. With T the record's duration and
/// T_exp the exposure:
/// ```text
/// A(8) = k·a_w·√(T_exp/8 h),    VDV_day = k·VDV·(T_exp/T)^(1/4),    MSDV_exp = a_w·√T_exp (Wf)
/// ```
/// with the health factors k = 1.4 (x, y), 1 (z) of Directive 2002/44/EC Annex B on the seat surface and the
/// standing floor; the verdict uses the largest A(8) and the largest daily VDV over the axes, and the comfort
/// vector sum a_v = √(Σ k²a_w²) with the comfort factors of ISO 2631-1 8.2.
///
/// # Errors
/// Channels that are missing or not accelerations; a sample rate that loses a band
/// ([`DigitalWeighting::check_bands`]); the reader's errors (naming the line, dataset or frame); an axis the
/// standard does not define, or given twice; an exposure duration outside 1 min … 24 h.
pub fn evaluate_exposure(reader: &mut dyn RecordReader, options: &ExposureOptions) -> Result<ExposureEvaluation> {
    let info = reader.info().clone();
    let axes = resolve_axes(&info, options)?;
    let mut evaluators = Vec::new();
    for a in axes {
        let w = axis_factor(Purpose::Comfort, a.location, a.axis)
            .map_err(|e| Error::invalid("--axis", &a, e.to_string()))?
            .weighting;
        evaluators.push((Evaluator::new(&info, a, w, options.tau_s)?, false));
    }
    for c in &options.motion_sickness {
        let a = AxisAssignment {
            channel: c.clone(),
            location: Location::SeatSurface,
            axis: Axis::Z,
        };
        evaluators.push((Evaluator::new(&info, a, Weighting::Wf, options.tau_s)?, true));
    }
    if let Some(t) = options.exposure_s {
        check_exposure(t)?;
    }
    let mut block: Vec<Vec<f64>> = vec![Vec::with_capacity(BLOCK_SAMPLES); info.channels.len()];
    let mut samples = 0usize;
    loop {
        let n = reader.read_block(&mut block, BLOCK_SAMPLES)?;
        if n == 0 {
            break;
        }
        for (e, _) in &evaluators {
            check_magnitudes(&info, e.index, &block[e.index][..n], samples)?;
        }
        samples += n;
        evaluators
            .par_iter_mut()
            .try_for_each(|(e, _)| e.push(&block[e.index]))?;
    }
    if samples == 0 {
        return Err(Error::in_file(&info.source, "samples", 0, "the record is empty"));
    }
    let duration_s = samples as f64 / info.sample_rate_hz;
    let exposure_s = options.exposure_s.unwrap_or(duration_s);
    let mut axes = Vec::new();
    let mut sickness = Vec::new();
    for (e, is_sickness) in evaluators {
        let ev = e.finish(options, exposure_s, is_sickness)?;
        if is_sickness {
            sickness.push(ev);
        } else {
            axes.push(ev);
        }
    }
    summarise(info, samples, duration_s, exposure_s, options, axes, sickness)
}

/// Refuses a daily exposure (s) outside 1 min … 24 h, the range a scenario's `[analysis.comfort] exposure`
/// accepts ([`MIN_DAILY_EXPOSURE_S`], [`MAX_DAILY_EXPOSURE_S`]): shorter is almost surely a unit slip
/// (`7 s` for 7 h), longer is more than a day.
fn check_exposure(t: f64) -> Result<()> {
    let shown = || {
        if t < 3600.0 {
            format!("{} s", crate::numbers::num(t))
        } else {
            format!("{} h", crate::numbers::num(t / 3600.0))
        }
    };
    if !(t.is_finite() && t > 0.0) {
        return Err(Error::invalid(
            "--exposure",
            shown(),
            "an exposure duration must be finite and > 0 s",
        ));
    }
    if t < MIN_DAILY_EXPOSURE_S {
        return Err(Error::invalid(
            "--exposure",
            shown(),
            "implausible: less than 1 min; a daily exposure is minutes to hours (ISO 2631-1 Annex B guides 10 min \
             to 24 h): write e.g. --exposure \"7 h\"",
        ));
    }
    if t > MAX_DAILY_EXPOSURE_S {
        return Err(Error::invalid(
            "--exposure",
            shown(),
            "a daily exposure is at most 24 h",
        ));
    }
    Ok(())
}

/// Refuses a value of channel `index` whose magnitude exceeds [`MAX_ABS_VALUE`], naming the channel, the
/// sample (counted from 0 over the record; `first` is the index of `x[0]`), its time and its value.
fn check_magnitudes(info: &RecordInfo, index: usize, x: &[f64], first: usize) -> Result<()> {
    let Some(i) = x.iter().position(|v| v.abs() > MAX_ABS_VALUE) else {
        return Ok(());
    };
    let at = first + i;
    Err(Error::in_file(
        &info.source,
        format!(
            "channel `{}`, sample {at} (t = {} s)",
            info.channels[index].name,
            crate::numbers::num(at as f64 / info.sample_rate_hz)
        ),
        format!("{:e} (SI)", x[i]),
        format!(
            "larger in magnitude than {MAX_ABS_VALUE:e}: the fourth powers of the VDV would leave the range of \
             f64; check the channel's unit and scaling"
        ),
    ))
}

/// The vector sums and the verdict over the evaluated axes.
fn summarise(
    record: RecordInfo,
    samples: usize,
    duration_s: f64,
    exposure_s: f64,
    options: &ExposureOptions,
    axes: Vec<AxisEvaluation>,
    motion_sickness: Vec<AxisEvaluation>,
) -> Result<ExposureEvaluation> {
    let values = |filter: &dyn Fn(&AxisEvaluation) -> bool| -> Vec<AxisValue> {
        axes.iter()
            .filter(|a| filter(a))
            .map(|a| AxisValue {
                location: a.location,
                axis: a.axis,
                a_w: a.metrics.a_w,
            })
            .collect()
    };
    let comfort_values = values(&|_| true);
    let comfort = (!comfort_values.is_empty())
        .then(|| vector_sum(Purpose::Comfort, &comfort_values))
        .transpose()?;
    let seat = values(&|a| a.location == Location::SeatSurface && a.health.is_some());
    let health_vector = (!seat.is_empty())
        .then(|| vector_sum(Purpose::Health, &seat))
        .transpose()?;
    let top = |f: fn(&HealthAxis) -> f64| {
        axes.iter()
            .filter_map(|a| a.health.map(|h| (a.channel.clone(), f(&h))))
            .max_by(|x, y| x.1.total_cmp(&y.1))
    };
    let (a8, vdv) = (top(|h| h.a8), top(|h| h.daily_vdv));
    let verdict = match (&a8, &vdv) {
        (Some((_, a8)), Some((_, vdv))) => Some(ExposureVerdict::assess(
            *a8,
            Some(*vdv),
            comfort.as_ref().map(|c| c.a_v),
        )?),
        _ => None,
    };
    Ok(ExposureEvaluation {
        record,
        samples,
        duration_s,
        exposure_s,
        running: options.running,
        tau_s: options.tau_s,
        axes,
        motion_sickness,
        comfort,
        health_vector,
        verdict,
        dominant_a8: a8.map(|x| x.0),
        dominant_vdv: vdv.map(|x| x.0),
    })
}
