//! A measured profile replayed as a deterministic time-domain input: every wheel of a model follows its
//! track of a [`Profile`] at a speed, the model is stepped exactly between samples
//! ([`SampledSystem`], first-order hold), and each output's time history and statistics are returned.

use super::Profile;
use crate::error::{Error, Result};
use crate::simulate::SampledSystem;
use crate::system::{FrequencyResponse as _, OutputInfo, StateSpace};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use std::io::Write as _;
use std::path::Path;

/// The kind of file `replay -o` writes, for the output rule ([`crate::io_rules::check_output`]): a history
/// CSV, recognised by its header `time [s], distance [m]`.
pub const HISTORY_CSV: crate::io_rules::OutputKind = crate::io_rules::OutputKind {
    what: "replay history CSV",
    recognizes: |p| crate::io_rules::starts_with(p, b"time [s], distance [m]"),
    replaceable: false,
};

/// One model input fed from a profile: u(t) = gain · z_track(x(t) − position) + offset.
#[derive(Debug, Clone, PartialEq)]
pub struct Wheel {
    /// Name of the profile column (track) under this input, e.g. `left`.
    pub track: String,
    /// Distance behind the first contact, m (≥ 0): the wheel sees its track `position_m / v` seconds after
    /// the foremost wheel.
    pub position_m: f64,
    /// Gain g (1 for a wheel on the road).
    pub gain: f64,
    /// Constant added to the input, in the input's unit (the scenario's `gain · mean`).
    pub offset: f64,
}

/// How the replay starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Start {
    /// From the static state under the first input sample: x₀ = −A⁻¹B u₀ (ẋ = 0), so the step from rest
    /// onto the profile is not replayed; what remains of the transient comes from the input's slope at
    /// the start, which the static state ignores.
    Static,
    /// From x₀ = 0.
    Zero,
}

/// Options of [`replay`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReplayOptions {
    /// Speed v, m/s (> 0).
    pub speed_m_s: f64,
    /// Length travelled before the statistics start, m (≥ 0); `None`: [`settling_length`].
    pub skip_m: Option<f64>,
    /// Initial state.
    pub start: Start,
}

/// The statistics of one output over the replayed (non-skipped) samples.
///
/// # Formula
/// Over the K samples y_k after the skipped length:
/// ```text
/// mean ȳ = Σ y_k / K,   σ = √(Σ (y_k − ȳ)² / K),   r.m.s. = √(Σ y_k² / K),
/// crest factor = max_k |y_k − ȳ| / σ
/// ```
/// (σ with divisor K: a time average, not an estimate from independent samples; the crest factor is taken
/// about the mean so that a static offset does not hide the peaks.)
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OutputStatistics {
    /// Output name.
    pub name: String,
    /// SI unit of the output.
    pub unit: String,
    /// ȳ.
    pub mean: f64,
    /// σ about the mean.
    pub sigma: f64,
    /// r.m.s. about zero.
    pub rms: f64,
    /// Smallest sample.
    pub min: f64,
    /// Largest sample.
    pub max: f64,
    /// max |y − ȳ| / σ (NaN for σ = 0).
    pub crest_factor: f64,
}

/// The result of [`replay`]: the time grid, the kept part of each output's history and its statistics.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Replay {
    /// Speed v, m/s.
    pub speed_m_s: f64,
    /// Time step Δt = Δx / v, s.
    pub dt_s: f64,
    /// Profile step Δx, m.
    pub step_m: f64,
    /// Skipped length, m (a whole number of steps: ⌈skip/Δx⌉ Δx).
    pub skip_m: f64,
    /// Number of skipped samples.
    pub skip_samples: usize,
    /// Initial state.
    pub start: Start,
    /// Samples replayed in all (skipped ones included).
    pub n_samples: usize,
    /// Distance of the foremost wheel along the profile (profile coordinates, m) at the first kept sample.
    pub first_distance_m: f64,
    /// Largest wheel position, m (the foremost wheel starts this far into the profile so that every wheel
    /// is on it).
    pub wheelbase_m: f64,
    /// True if some wheel falls between profile samples (its input is linearly interpolated).
    pub interpolated: bool,
    /// Statistics of each output, in the system's order.
    pub outputs: Vec<OutputStatistics>,
    /// The kept history of each output (output-major: `history[i][k]`), sample k at time
    /// (skip_samples + k)·Δt.
    #[serde(skip)]
    pub history: Vec<Vec<f64>>,
}

/// The default settling length: the distance travelled while the slowest mode decays by e⁻⁷ (< 10⁻³).
///
/// # Formula
/// ```text
/// L_settle = v · 7 / min_i |Re λ_i(A)|
/// ```
/// with λ_i the eigenvalues of A (all with Re λ < 0 for a stable system).
///
/// # Errors
/// A system that is not asymptotically stable (no settling); `speed_m_s` not finite and > 0.
///
/// # Examples
/// ```
/// use stochvib::road::replay::settling_length;
/// use stochvib::system::{OutputInfo, StateSpace};
/// use nalgebra::DMatrix;
/// // ẋ = −2x + u: settles in 3.5 s, i.e. 70 m at 20 m/s
/// let ss = StateSpace::new(DMatrix::from_element(1, 1, -2.0), DMatrix::from_element(1, 1, 2.0),
///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("x", "m")]).unwrap();
/// assert!((settling_length(&ss, 20.0).unwrap() - 70.0).abs() < 1e-9);
/// ```
pub fn settling_length(ss: &StateSpace, speed_m_s: f64) -> Result<f64> {
    crate::error::require_positive("speed", speed_m_s)?;
    ss.require_stable()?;
    if ss.n_states() == 0 {
        return Ok(0.0);
    }
    let slowest =
        ss.a.complex_eigenvalues()
            .iter()
            .map(|l| -l.re)
            .fold(f64::INFINITY, f64::min);
    Ok(speed_m_s * 7.0 / slowest)
}

/// Replays `profile` (read from `file`, named in messages) through `ss` at speed v, input j fed by
/// `wheels[j]`.
///
/// # Formula
/// With Δx the profile step, Δt = Δx / v and P = max_j p_j the largest wheel position, the foremost wheel
/// starts on sample b = ⌈P/Δx⌉ so that every wheel is on the profile; at t_k = kΔt wheel j is at profile
/// sample index s_j(k) = b − p_j/Δx + k and
/// ```text
/// u_j(t_k) = g_j [(1 − f) z[i] + f z[i + 1]] + offset_j,    i = ⌊s_j(k)⌋,  f = s_j(k) − i
/// ```
/// (linear interpolation between profile samples when p_j is not a whole number of steps, f fixed per
/// wheel; an offset within 10⁻⁹ of a whole step counts as whole). Linear interpolation of a sinusoid of
/// wavenumber n multiplies its amplitude by |1 − f + f e^{i2πnΔx}| ≤ 1 — at most 1 − 2f(1−f)(1 − cos 2πnΔx),
/// negligible for wavelengths of many steps. The model is stepped with [`SampledSystem`] (exact for inputs
/// linear between samples, [`crate::simulate::foh`]), from the static state x₀ = −A⁻¹B u₀ or from zero
/// ([`Start`]). An output with a derivative feedthrough, y = Cx + Du + Eu̇ (the acceleration of a mass
/// on a damper whose other end is the base: a cab on mounts, a scraper on its tyres), gets
/// u̇_k = (u_{k+1} − u_{k−1})/(2Δt) (one-sided at the ends of the replay): for a sinusoid of angular
/// frequency ω this is ω cos(ωt_k)·sin(ωΔt)/(ωΔt), an amplitude error below (ωΔt)²/6. The first ⌈skip/Δx⌉ samples are left out of the statistics ([`OutputStatistics`]) and the
/// history. The replay is K = min_j ⌊N − 1 − s_j(0)⌋ + 1 samples long (⌈·⌉ for a fractional s_j(0)) for a
/// profile of N samples.
///
/// # Errors
/// [`Error::File`] naming `file`: a track a wheel needs that the profile lacks (key `track`), a profile
/// shorter than the wheelbase P plus the skipped length plus one step (key `length`). [`Error::InvalidParameter`]:
/// speed not finite and > 0, skip negative or not finite, a position negative or not finite, a gain or
/// offset not finite, the number of wheels not the number of system inputs, an unstable system.
///
/// # Examples
/// ```
/// use stochvib::road::replay::{replay, ReplayOptions, Start, Wheel};
/// use stochvib::road::{Profile, Track};
/// use stochvib::system::{OutputInfo, StateSpace};
/// use nalgebra::DMatrix;
/// use std::path::Path;
/// // ẋ = −x + u, y = x, on a constant road 2 cm high: the static start is the steady state
/// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0), DMatrix::from_element(1, 1, 1.0),
///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("x", "m")]).unwrap();
/// let p = Profile::new(0.1, 0.0, vec![Track { name: "left".into(), elevation_m: vec![0.02; 50] }]).unwrap();
/// let wheel = Wheel { track: "left".into(), position_m: 0.0, gain: 1.0, offset: 0.0 };
/// let opts = ReplayOptions { speed_m_s: 1.0, skip_m: Some(0.0), start: Start::Static };
/// let r = replay(&ss, &[wheel], &p, Path::new("flat.csv"), &opts).unwrap();
/// assert!((r.outputs[0].mean - 0.02).abs() < 1e-15 && r.outputs[0].sigma < 1e-15);
/// assert_eq!(r.dt_s, 0.1);
/// ```
pub fn replay(
    ss: &StateSpace,
    wheels: &[Wheel],
    profile: &Profile,
    file: &Path,
    opts: &ReplayOptions,
) -> Result<Replay> {
    let v = opts.speed_m_s;
    if !(v.is_finite() && v > 0.0) {
        return Err(Error::invalid("speed", v, "must be a finite speed > 0 m/s"));
    }
    let m = ss.b.ncols();
    let columns = wheel_tracks(wheels, profile, file, m)?;
    let dx = profile.step_m;
    let dt = dx / v;
    let n = profile.len();
    let wheelbase = wheels.iter().map(|w| w.position_m).fold(0.0, f64::max);
    let offsets = wheel_offsets(wheels, wheelbase, dx);
    let interpolated = offsets.iter().any(|o| o.1 != 0.0);
    // last k with i₀ + k (+1 if f > 0) ≤ N − 1, for every wheel
    let last = offsets
        .iter()
        .map(|&(i0, f)| (n - 1) as i64 - i0 as i64 - i64::from(f > 0.0))
        .min()
        .unwrap_or((n - 1) as i64);
    let skip_samples = skip_samples(ss, opts, dx)?;
    let k_total = (last + 1).max(0) as usize;
    if k_total < skip_samples + 2 {
        return Err(too_short(file, profile, wheelbase, skip_samples, k_total));
    }
    let u = wheel_inputs(wheels, &columns, &offsets, k_total);
    let (y, p) = respond(ss, &u, k_total, dt, opts.start)?;
    let mut outputs = Vec::with_capacity(p);
    let mut history = Vec::with_capacity(p);
    for (i, info) in ss.outputs().iter().enumerate() {
        let h: Vec<f64> = (skip_samples..k_total).map(|k| y[k * p + i]).collect();
        outputs.push(history_statistics(info, &h));
        history.push(h);
    }
    Ok(Replay {
        speed_m_s: v,
        dt_s: dt,
        step_m: dx,
        skip_m: skip_samples as f64 * dx,
        skip_samples,
        start: opts.start,
        n_samples: k_total,
        first_distance_m: profile.distance_m(offsets.iter().map(|o| o.0).max().unwrap_or(0) + skip_samples),
        wheelbase_m: wheelbase,
        interpolated,
        outputs,
        history,
    })
}

/// The samples left out of the statistics: `opts.skip_m` (finite, ≥ 0), else the settling length, in whole
/// profile steps `dx`.
fn skip_samples(ss: &StateSpace, opts: &ReplayOptions, dx: f64) -> Result<usize> {
    let skip_m = match opts.skip_m {
        Some(s) if !(s.is_finite() && s >= 0.0) => {
            return Err(Error::invalid("skip", s, "must be a finite length >= 0 m"))
        }
        Some(s) => s,
        None => settling_length(ss, opts.speed_m_s)?,
    };
    Ok((skip_m / dx - 1e-9).ceil().max(0.0) as usize)
}

/// The refusal of a profile that leaves fewer than two samples after the wheelbase and the skipped length.
fn too_short(file: &Path, profile: &Profile, wheelbase: f64, skip_samples: usize, k_total: usize) -> Error {
    use crate::numbers::num;
    let dx = profile.step_m;
    Error::in_file(
        file,
        "length",
        format!("{} m", num(profile.length_m())),
        format!(
            "the profile is too short: the wheelbase {} m plus the skipped length {} m ({skip_samples} steps of \
             {} m) leave {} samples to replay; need at least 2 (a longer profile, or a smaller --skip)",
            num(wheelbase),
            num(skip_samples as f64 * dx),
            num(dx),
            k_total.saturating_sub(skip_samples)
        ),
    )
}

/// The profile column of every wheel, after checking the wheels: one per system input (`m`), each with a
/// finite position ≥ 0, a finite gain and offset, and a track the profile has (else an error naming
/// `file`).
fn wheel_tracks<'a>(wheels: &[Wheel], profile: &'a Profile, file: &Path, m: usize) -> Result<Vec<&'a [f64]>> {
    if wheels.len() != m {
        return Err(Error::invalid(
            "wheels",
            wheels.len(),
            format!("the system has {m} inputs: need one wheel per input"),
        ));
    }
    let mut columns = Vec::with_capacity(m);
    for (j, w) in wheels.iter().enumerate() {
        if !(w.position_m.is_finite() && w.position_m >= 0.0) {
            return Err(Error::invalid(
                &format!("wheels[{j}].position"),
                w.position_m,
                "must be a finite distance >= 0 behind the first contact",
            ));
        }
        crate::error::require_finite(&format!("wheels[{j}].gain"), w.gain)?;
        crate::error::require_finite(&format!("wheels[{j}].offset"), w.offset)?;
        let track = profile.track(&w.track).map_err(|e| {
            let reason = match e {
                Error::InvalidParameter { reason, .. } => reason,
                other => other.to_string(),
            };
            Error::in_file(
                file,
                "track",
                &w.track,
                format!("model input {j} runs on track `{}`: {reason}", w.track),
            )
        })?;
        columns.push(track.elevation_m.as_slice());
    }
    Ok(columns)
}

/// Per wheel, the whole offset i₀ and the fraction f of its sample index at k = 0: the foremost wheel
/// starts on the first whole sample with every wheel (behind it by up to `wheelbase`) on the profile.
fn wheel_offsets(wheels: &[Wheel], wheelbase: f64, dx: f64) -> Vec<(usize, f64)> {
    let base = (wheelbase / dx - 1e-9).ceil().max(0.0);
    wheels
        .iter()
        .map(|w| {
            let s = (base - w.position_m / dx).max(0.0);
            let r = s.round();
            if (s - r).abs() < 1e-9 {
                (r as usize, 0.0)
            } else {
                (s.floor() as usize, s - s.floor())
            }
        })
        .collect()
}

/// The inputs u\[k·m + j\] = g_j z_j(s_j(k)) + offset_j of `k_total` samples (see [`replay`]'s formula).
fn wheel_inputs(wheels: &[Wheel], columns: &[&[f64]], offsets: &[(usize, f64)], k_total: usize) -> Vec<f64> {
    let m = wheels.len();
    let mut u = vec![0.0; k_total * m];
    for (j, (w, &(i0, f))) in wheels.iter().zip(offsets).enumerate() {
        let z = columns[j];
        for k in 0..k_total {
            let i = i0 + k;
            let zi = if f == 0.0 {
                z[i]
            } else {
                (1.0 - f) * z[i] + f * z[i + 1]
            };
            u[k * m + j] = w.gain * zi + w.offset;
        }
    }
    u
}

/// The outputs y\[k·p + i\] of `ss` stepped exactly under the `k_total` samples of inputs `u` at Δt = `dt`
/// from `start`, and p; a derivative feedthrough E u̇ (a damper between the base and a reported mass: its
/// acceleration) is added after the stepping, from the central difference of the replayed input (see
/// [`replay`]'s formula).
fn respond(ss: &StateSpace, u: &[f64], k_total: usize, dt: f64, start: Start) -> Result<(Vec<f64>, usize)> {
    let m = ss.b.ncols();
    let derivative = ss.e.amax() != 0.0;
    let stepped = if derivative {
        StateSpace::new(
            ss.a.clone(),
            ss.b.clone(),
            ss.c.clone(),
            Some(ss.d.clone()),
            None,
            ss.outputs().to_vec(),
        )?
    } else {
        ss.clone()
    };
    let sys = SampledSystem::new(&stepped, dt)?;
    let (ns, _, p) = sys.dims();
    let mut x = match start {
        Start::Zero => vec![0.0; ns],
        Start::Static => {
            if ns == 0 {
                Vec::new()
            } else {
                let u0 = DVector::from_column_slice(&u[..m]);
                let rhs: DVector<f64> = -(&ss.b * u0);
                let lu = DMatrix::clone(&ss.a).lu();
                let x0 = lu.solve(&rhs).ok_or_else(|| {
                    Error::invalid("A", "singular", "no static state (A is singular): use the zero start")
                })?;
                x0.iter().copied().collect()
            }
        }
    };
    let mut y = vec![0.0; k_total * p];
    sys.respond(u, &mut x, &mut y)?;
    if derivative {
        add_derivative_feedthrough(ss, u, dt, &mut y);
    }
    Ok((y, p))
}

/// Mean, σ, r.m.s., extremes and crest factor of one output's replayed history.
fn history_statistics(info: &OutputInfo, h: &[f64]) -> OutputStatistics {
    let kf = h.len() as f64;
    let mean = h.iter().sum::<f64>() / kf;
    let sigma = (h.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / kf).sqrt();
    let rms = (h.iter().map(|v| v * v).sum::<f64>() / kf).sqrt();
    let min = h.iter().copied().fold(f64::INFINITY, f64::min);
    let max = h.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let peak = (max - mean).max(mean - min);
    let crest_factor = if sigma > 0.0 { peak / sigma } else { f64::NAN };
    OutputStatistics {
        name: info.name.clone(),
        unit: info.unit.clone(),
        mean,
        sigma,
        rms,
        min,
        max,
        crest_factor,
    }
}

/// Adds E u̇_k to every output sample y_k (row-major `y[k·p + i]`, inputs `u[k·m + j]`), with u̇_k the
/// central difference (u_{k+1} − u_{k−1})/(2Δt) of the replayed input — the mean of the slopes of the
/// linear interpolation on either side of the sample — and the one-sided slope at the first and last
/// sample.
fn add_derivative_feedthrough(ss: &StateSpace, u: &[f64], dt: f64, y: &mut [f64]) {
    let (m, p) = (ss.b.ncols(), ss.c.nrows());
    let k_total = u.len() / m.max(1);
    if k_total < 2 {
        return;
    }
    for k in 0..k_total {
        let (lo, hi) = (k.saturating_sub(1), (k + 1).min(k_total - 1));
        let span = (hi - lo) as f64 * dt;
        for j in 0..m {
            let du = (u[hi * m + j] - u[lo * m + j]) / span;
            for i in 0..p {
                y[k * p + i] += ss.e[(i, j)] * du;
            }
        }
    }
}

impl Replay {
    /// The kept history as CSV: `time [s], distance [m], <output> [<unit>], …`, time from the start of the
    /// replay and distance of the foremost wheel along the profile; numbers in the shortest text that reads
    /// back to the same f64.
    pub fn to_csv_string(&self) -> String {
        let mut buf = Vec::new();
        // writing into memory cannot fail
        let _ = self.write_csv_to(&mut buf);
        String::from_utf8(buf).unwrap_or_default()
    }

    /// Writes [`Replay::to_csv_string`]'s text to `w`, line by line (no copy of the whole text in memory).
    ///
    /// # Errors
    /// The I/O errors of `w`.
    pub fn write_csv_to(&self, w: impl std::io::Write) -> std::io::Result<()> {
        let mut w = std::io::BufWriter::with_capacity(1 << 16, w);
        write!(w, "time [s], distance [m]")?;
        for o in &self.outputs {
            write!(w, ", {} [{}]", o.name, o.unit)?;
        }
        writeln!(w)?;
        let kept = self.history.first().map_or(0, Vec::len);
        for k in 0..kept {
            let t = (self.skip_samples + k) as f64 * self.dt_s;
            let d = self.first_distance_m + k as f64 * self.step_m;
            write!(w, "{t},{d}")?;
            for h in &self.history {
                write!(w, ",{}", h[k])?;
            }
            writeln!(w)?;
        }
        w.flush()
    }

    /// Writes the history CSV to `path` under the output rule ([`crate::io_rules::Staged`]): through a
    /// temporary file renamed when complete (never a half-written file); an existing history is only
    /// replaced with `overwrite`; a directory, link, FIFO, device or a file that is not a history is never.
    ///
    /// # Errors
    /// The refusals of [`crate::io_rules::check_output`]; I/O errors.
    pub fn write_csv(&self, path: &Path, overwrite: bool) -> Result<()> {
        self.write_csv_from(path, overwrite, &[])
    }

    /// [`write_csv`](Self::write_csv), refusing also a `path` that is one of `inputs` (the scenario, the
    /// profile: the files the replay was read from).
    ///
    /// # Errors
    /// As [`write_csv`](Self::write_csv).
    pub fn write_csv_from(&self, path: &Path, overwrite: bool, inputs: &[&Path]) -> Result<()> {
        let staged = crate::io_rules::Staged::begin(path, HISTORY_CSV, inputs, overwrite)?;
        let tmp = staged.temporary().to_path_buf();
        std::fs::File::create(&tmp)
            .and_then(|f| self.write_csv_to(f))
            .map_err(|source| Error::Io { path: tmp, source })?;
        staged.commit().map(|_| ())
    }
}
