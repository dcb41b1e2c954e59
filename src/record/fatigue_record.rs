//! Fatigue of a measured stress (or strain) record, streamed block by block: rainflow counting (ASTM E1049,
//! residue as half cycles, optional hysteresis gate), the range–mean matrix, Palmgren–Miner damage with an
//! S–N curve and a named mean-stress correction, and beside it the five spectral methods from the record's
//! own Welch density — life by rainflow against life by each method, with the spread.

use super::source::{RecordInfo, RecordReader};
use crate::error::{Error, Result};
use crate::estimate::{Welch, WelchScratch, WelchStream, WelchSums};
use crate::fatigue::{
    compare_methods, Cycle, MethodComparison, RainflowCounter, SnCurve, SnReferencePoint, SpectralMoments,
};
use crate::units::Dim;

/// Samples per block.
pub const BLOCK_SAMPLES: usize = 1 << 16;

/// Range and mean bins of the range–mean matrix.
pub const MATRIX_BINS: usize = 32;

/// A mean-stress correction: the amplitude S_a,eq of a zero-mean cycle as damaging as a cycle of amplitude
/// S_a about the mean S_m; the S–N curve is then read at S_a,eq.
///
/// # Formula
/// ```text
/// none     S_a,eq = S_a
/// Goodman  S_a,eq = S_a / (1 − S_m/S_u)           S_m ≥ 0; compressive means not credited (S_m < 0 → 0)
/// Gerber   S_a,eq = S_a / (1 − (S_m/S_u)²)        S_m ≥ 0; compressive means not credited
/// SWT      S_a,eq = √(S_max·S_a), S_max = S_m + S_a;   no damage when S_max ≤ 0
/// ```
/// (Goodman 1899; Gerber 1874; Smith, Watson & Topper (1970), "A stress–strain function for the fatigue of
/// metals", J. Materials 5(4), 767–778.) A cycle with S_m ≥ S_u under Goodman or Gerber is refused (the
/// correction has no finite value there).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "name", rename_all = "lowercase")]
pub enum MeanStressCorrection {
    /// No correction.
    None,
    /// Goodman, with the ultimate strength S_u (SI).
    Goodman {
        /// S_u.
        ultimate: f64,
    },
    /// Gerber, with S_u.
    Gerber {
        /// S_u.
        ultimate: f64,
    },
    /// Smith–Watson–Topper.
    Swt,
}

impl MeanStressCorrection {
    /// The equivalent amplitude of a cycle (see the type's formula); `None` when the correction has no finite
    /// value (S_m ≥ S_u).
    pub fn equivalent(self, amplitude: f64, mean: f64) -> Option<f64> {
        match self {
            MeanStressCorrection::None => Some(amplitude),
            MeanStressCorrection::Goodman { ultimate } => {
                let r = mean.max(0.0) / ultimate;
                (r < 1.0).then(|| amplitude / (1.0 - r))
            }
            MeanStressCorrection::Gerber { ultimate } => {
                let r = mean.max(0.0) / ultimate;
                (r < 1.0).then(|| amplitude / (1.0 - r * r))
            }
            MeanStressCorrection::Swt => {
                let smax = mean + amplitude;
                Some(if smax > 0.0 { (smax * amplitude).sqrt() } else { 0.0 })
            }
        }
    }

    /// The name as printed: `none`, `Goodman`, `Gerber`, `SWT`.
    pub fn label(self) -> &'static str {
        match self {
            MeanStressCorrection::None => "none",
            MeanStressCorrection::Goodman { .. } => "Goodman",
            MeanStressCorrection::Gerber { .. } => "Gerber",
            MeanStressCorrection::Swt => "SWT",
        }
    }
}

/// What to evaluate and how.
#[derive(Debug, Clone, PartialEq)]
pub struct FatigueOptions {
    /// The channel; `None`: the record's only channel.
    pub channel: Option<String>,
    /// The S–N curve, amplitudes in SI.
    pub sn: SnCurve,
    /// The SI dimension of the S–N curve's amplitudes (Pa for stress, dimensionless for strain).
    pub sn_dim: Dim,
    /// Mean-stress correction of the rainflow damage.
    pub mean_stress: MeanStressCorrection,
    /// Hysteresis gate (SI): reversals of a smaller range are removed before counting.
    pub gate: Option<f64>,
    /// Welch segment length (default: the largest power of two ≤ N/8, at most 2¹⁶).
    pub segment_len: Option<usize>,
}

/// The point of an S–N curve as `stochvib fatigue` takes it: an amplitude (`--sn-amplitude`) or a range
/// (`--sn-range`, halved), each a number with its unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SnPoint<'a> {
    /// `--sn-amplitude`.
    Amplitude(&'a str),
    /// `--sn-range`.
    Range(&'a str),
}

/// A quantity given by `flag` (a number and a unit) in SI, which must have the dimension `dim`.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `flag`: not a number with a unit, or another dimension.
pub fn quantity_of_dim(flag: &str, text: &str, dim: Dim) -> Result<f64> {
    let (v, d) = super::source::parse_quantity(text, flag)?;
    if d != dim {
        return Err(Error::invalid(
            flag,
            text,
            format!("its unit has dimension {d}, the S–N curve's {dim}"),
        ));
    }
    Ok(v)
}

/// The S–N curve N·S_a^k = C of `stochvib fatigue`'s flags: slope k (`--sn-slope`), a point (amplitude or
/// range with its unit) endured for `cycles` (`--sn-cycles`), an optional endurance limit (`--endurance`,
/// the point's dimension); returns the curve and the dimension of its amplitudes.
///
/// # Errors
/// [`Error::InvalidParameter`] naming the flag whose value [`SnReferencePoint::build`](crate::fatigue::SnReferencePoint::build) refuses.
pub fn sn_curve_from_flags(
    slope: f64,
    point: SnPoint<'_>,
    cycles: f64,
    endurance: Option<&str>,
) -> Result<(SnCurve, Dim)> {
    let (flag, text) = match point {
        SnPoint::Amplitude(t) => ("--sn-amplitude", t),
        SnPoint::Range(t) => ("--sn-range", t),
    };
    let (v, dim) = super::source::parse_quantity(text, flag)?;
    let amplitude = if matches!(point, SnPoint::Range(_)) { v / 2.0 } else { v };
    let endurance_limit = endurance.map(|t| quantity_of_dim("--endurance", t, dim)).transpose()?;
    let sn = SnReferencePoint {
        k: slope,
        amplitude,
        cycles,
        endurance_limit,
    }
    .build()
    .map_err(|e| match e {
        Error::InvalidParameter { name, value, reason } => {
            let flag = match name.as_str() {
                "amplitude" => flag,
                "cycles" => "--sn-cycles",
                "endurance_limit" => "--endurance",
                "k" | "slope" => "--sn-slope",
                _ => flag, // C, from the point, its cycles and the slope
            };
            Error::InvalidParameter {
                name: flag.to_string(),
                value,
                reason: format!("{reason} (the S–N curve's `{name}`)"),
            }
        }
        other => other,
    })?;
    Ok((sn, dim))
}

/// A histogram of cycles over range × mean whose bins widen (pairs merge) when a cycle falls outside, so it
/// holds any record in fixed memory.
///
/// # Formula
/// Range bins [iΔ_r, (i+1)Δ_r), i < n; mean bins [m₀ + jΔ_m, m₀ + (j+1)Δ_m), j < n; a cycle beyond the
/// range doubles Δ_r, one beyond the mean span doubles Δ_m (extending the span on the side of the cycle).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RangeMeanMatrix {
    /// Range bin width Δ_r (SI).
    pub range_width: f64,
    /// Lowest mean m₀ (SI).
    pub mean_origin: f64,
    /// Mean bin width Δ_m (SI).
    pub mean_width: f64,
    /// Counts (full cycles 1, half cycles 0.5), `counts[i][j]` for range bin i, mean bin j.
    pub counts: Vec<Vec<f64>>,
}

impl RangeMeanMatrix {
    fn new(n: usize, range_width: f64, mean_origin: f64, mean_width: f64) -> Self {
        RangeMeanMatrix {
            range_width,
            mean_origin,
            mean_width,
            counts: vec![vec![0.0; n]; n],
        }
    }

    fn add(&mut self, c: &Cycle) {
        let n = self.counts.len();
        while c.range >= n as f64 * self.range_width {
            self.range_width *= 2.0;
            for i in 0..n / 2 {
                let merged: Vec<f64> = (0..n)
                    .map(|j| self.counts[2 * i][j] + self.counts[2 * i + 1][j])
                    .collect();
                self.counts[i] = merged;
            }
            for row in self.counts.iter_mut().skip(n / 2) {
                row.iter_mut().for_each(|v| *v = 0.0);
            }
        }
        while c.mean < self.mean_origin || c.mean >= self.mean_origin + n as f64 * self.mean_width {
            let left = c.mean < self.mean_origin;
            for row in self.counts.iter_mut() {
                let old = row.clone();
                row.iter_mut().for_each(|v| *v = 0.0);
                for (j, v) in old.into_iter().enumerate() {
                    let k = if left { (j + n) / 2 } else { j / 2 };
                    row[k] += v;
                }
            }
            if left {
                self.mean_origin -= n as f64 * self.mean_width;
            }
            self.mean_width *= 2.0;
        }
        let i = ((c.range / self.range_width) as usize).min(n - 1);
        let j = (((c.mean - self.mean_origin) / self.mean_width) as usize).min(n - 1);
        self.counts[i][j] += c.count;
    }

    /// Counts per range bin (summed over the means), with the bins' lower edges.
    pub fn range_histogram(&self) -> Vec<(f64, f64)> {
        self.counts
            .iter()
            .enumerate()
            .map(|(i, row)| (i as f64 * self.range_width, row.iter().sum()))
            .collect()
    }
}

/// Rainflow against one spectral method.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MethodLife {
    /// The method and its reference.
    pub method: String,
    /// Damage per second, 1/s.
    pub damage_rate: f64,
    /// Life 1/rate, s.
    pub life_s: f64,
    /// Life by this method / life by rainflow (without mean-stress correction).
    pub life_ratio: f64,
}

/// Spectral moments and the parameters the methods use.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MomentsSummary {
    /// m₀ = σ² (SI²).
    pub m0: f64,
    /// m₁, Hz·SI².
    pub m1: f64,
    /// m₂, Hz²·SI².
    pub m2: f64,
    /// m₄, Hz⁴·SI².
    pub m4: f64,
    /// ν₀⁺ = √(m₂/m₀), Hz.
    pub nu0_plus_hz: f64,
    /// ν_p = √(m₄/m₂), Hz.
    pub nu_peak_hz: f64,
    /// α₁ = m₁/√(m₀m₂).
    pub alpha1: f64,
    /// α₂ = m₂/√(m₀m₄).
    pub alpha2: f64,
}

impl MomentsSummary {
    fn of(m: &SpectralMoments) -> Self {
        MomentsSummary {
            m0: m.m0(),
            m1: m.m1(),
            m2: m.m2(),
            m4: m.m4(),
            nu0_plus_hz: m.nu0_plus(),
            nu_peak_hz: m.nu_peak(),
            alpha1: m.alpha1(),
            alpha2: m.alpha2(),
        }
    }
}

/// The fatigue evaluation of a record.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FatigueEvaluation {
    /// The record.
    pub record: RecordInfo,
    /// The channel and its unit.
    pub channel: String,
    /// Samples.
    pub samples: usize,
    /// Duration T, s.
    pub duration_s: f64,
    /// The S–N curve (k, C in SI amplitude, endurance limit).
    pub sn: String,
    /// Mean-stress correction.
    pub mean_stress: MeanStressCorrection,
    /// Hysteresis gate (SI).
    pub gate: Option<f64>,
    /// Mean, min, max of the record (SI).
    pub mean: f64,
    /// Smallest sample.
    pub min: f64,
    /// Largest sample.
    pub max: f64,
    /// Full cycles counted.
    pub full_cycles: usize,
    /// Half cycles of the residue.
    pub half_cycles: usize,
    /// Miner damage of the record with the mean-stress correction.
    pub damage: f64,
    /// Miner damage without a correction (what the spectral methods estimate).
    pub damage_uncorrected: f64,
    /// Life T/D with the correction, s; infinite (`null` in JSON, "unlimited" in text) when the corrected
    /// damage is 0 (SWT with every cycle's peak in compression).
    pub life_s: f64,
    /// Life T/D without a correction, s.
    pub life_uncorrected_s: f64,
    /// The range–mean matrix.
    pub matrix: RangeMeanMatrix,
    /// Spectral moments of the Welch density (mean removed per segment), m_j = ∫ f^j G df.
    #[serde(skip)]
    pub moments: Option<SpectralMoments>,
    /// The same moments and their bandwidth parameters, as numbers.
    pub spectral: Option<MomentsSummary>,
    /// Welch segment length, samples, and the number of segments.
    pub segment_len: usize,
    /// Segments averaged.
    pub segments: u64,
    /// Each spectral method against rainflow.
    pub methods: Vec<MethodLife>,
    /// Longest / shortest life over the spectral methods.
    pub spread: Option<f64>,
    /// Samples per peak f_s/ν_p (rainflow underestimates peaks when it is small).
    pub samples_per_peak: Option<f64>,
}

/// The streaming hysteresis gate: keeps the first sample and every extreme from which the signal then moves
/// back by at least the gate.
struct Gate {
    gate: f64,
    last: f64,
    candidate: f64,
    direction: i8,
    started: bool,
}

impl Gate {
    fn new(gate: f64) -> Self {
        Gate {
            gate,
            last: 0.0,
            candidate: 0.0,
            direction: 0,
            started: false,
        }
    }

    fn push(&mut self, x: &[f64], out: &mut Vec<f64>) {
        for &v in x {
            if !self.started {
                self.started = true;
                self.last = v;
                out.push(v);
                continue;
            }
            match self.direction {
                0 => {
                    if (v - self.last).abs() >= self.gate {
                        self.direction = if v > self.last { 1 } else { -1 };
                        self.candidate = v;
                    }
                }
                d => {
                    let further = if d > 0 { v > self.candidate } else { v < self.candidate };
                    if further {
                        self.candidate = v;
                    } else if (self.candidate - v).abs() >= self.gate {
                        out.push(self.candidate);
                        self.last = self.candidate;
                        self.direction = -d;
                        self.candidate = v;
                    }
                }
            }
        }
    }

    fn finish(&self, out: &mut Vec<f64>) {
        if self.direction != 0 {
            out.push(self.candidate);
        }
    }
}

/// Running sums of the damage and the counts.
struct Tally {
    sn: SnCurve,
    correction: MeanStressCorrection,
    damage: f64,
    damage_plain: f64,
    full: usize,
    half: usize,
    matrix: Option<RangeMeanMatrix>,
    refused: Option<Cycle>,
}

impl Tally {
    #[inline]
    fn add(&mut self, c: Cycle) {
        let k = self.sn.k();
        if self.sn.damages(c.amplitude) {
            self.damage_plain += c.count * c.amplitude.powf(k);
        }
        match self.correction.equivalent(c.amplitude, c.mean) {
            Some(a) if self.sn.damages(a) => self.damage += c.count * a.powf(k),
            Some(_) => {}
            None => {
                self.refused.get_or_insert(c);
            }
        }
        if c.is_half() {
            self.half += 1;
        } else {
            self.full += 1;
        }
        if let Some(m) = &mut self.matrix {
            m.add(&c);
        }
    }
}

/// Evaluates a stress record (see the [module docs](self)).
///
/// # Formula
/// Rainflow per ASTM E1049-85 (2017) §5.4.4 ([`RainflowCounter`]), streamed; the residue counted as half
/// cycles. Miner: D = Σ n_i/N(S_a,eq,i), N = C·S_a^{−k} (no damage below the endurance limit); life T/D.
/// Spectral: the one-sided Welch density G(f) (Hann, 50 % overlap, each segment's mean removed) gives
/// m_j = Σ ∫ f^j Ĝ df (piecewise linear, [`SpectralMoments::from_tabulated_one_sided_hz`]) up to the Nyquist
/// frequency, and [`compare_methods`] the damage rate of each method; life ratio = life_method/life_rainflow
/// (rainflow without a mean-stress correction: the spectral methods take a zero-mean Gaussian process).
///
/// # Errors
/// A missing channel; a channel whose unit's dimension differs from the S–N curve's; a gate that is not
/// finite and > 0; a cycle beyond the correction's validity (S_m ≥ S_u, naming it); a `--segment` longer
/// than the record; the reader's errors.
pub fn evaluate_fatigue(reader: &mut dyn RecordReader, options: &FatigueOptions) -> Result<FatigueEvaluation> {
    let info = reader.info().clone();
    let index = stress_channel(&info, options)?;
    let dt = 1.0 / info.sample_rate_hz;
    let m = options
        .segment_len
        .unwrap_or_else(|| default_segment(info.samples_hint));
    let welch = Welch::new(m, dt)
        .map_err(|e| e.renamed("segment length", "--segment"))?
        .with_segment_mean_removed();
    let mut spectral = SpectralSums::new(&welch);
    let mut counter = RainflowCounter::new();
    let mut gate = options.gate.map(Gate::new);
    let mut tally = Tally {
        sn: options.sn,
        correction: options.mean_stress,
        damage: 0.0,
        damage_plain: 0.0,
        full: 0,
        half: 0,
        matrix: None,
        refused: None,
    };
    let passes = Passes {
        welch: &welch,
        spectral: &mut spectral,
        gate: &mut gate,
        counter: &mut counter,
        tally: &mut tally,
    };
    let Extent { n, sum, lo, hi } = read_stress(reader, index, passes)?;
    if n == 0 {
        return Err(Error::in_file(&info.source, "samples", 0, "the record is empty"));
    }
    if let Some(g) = &gate {
        let mut gated = Vec::new();
        g.finish(&mut gated);
        counter.push(&gated, |c| tally.add(c))?;
    }
    counter.finish(|c| tally.add(c));
    refuse_mean_stress(&tally, options)?;
    let duration_s = n as f64 / info.sample_rate_hz;
    let channel = format!("{} [{}]", info.channels[index].name, info.channels[index].unit);
    let (moments, segments) = spectral.moments(&welch)?;
    refuse_long_segment(options, segments, n)?;
    let damage = tally.damage / options.sn.c();
    let damage_plain = tally.damage_plain / options.sn.c();
    // a corrected damage of exactly 0 is an answer (SWT: a cycle whose peak stays in compression does no
    // damage; its life is unlimited and printed so); the uncorrected damage must be a number
    if damage != 0.0 {
        require_damage(&info, &channel, "rainflow (Miner)", damage)?;
    }
    require_damage(
        &info,
        &channel,
        "rainflow (Miner) without the mean-stress correction",
        damage_plain,
    )?;
    let life_plain = duration_s / damage_plain;
    let (methods, spread) = match &moments {
        Some(mo) => {
            let cmp = compare_methods(mo, &options.sn)?;
            for e in &cmp.estimates {
                require_damage(&info, &channel, e.name, e.damage_rate)?;
            }
            method_lives(&cmp, life_plain)
        }
        None => (Vec::new(), None),
    };
    Ok(FatigueEvaluation {
        channel,
        samples: n,
        duration_s,
        sn: options.sn.describe(),
        mean_stress: options.mean_stress,
        gate: options.gate,
        mean: sum / n as f64,
        min: lo,
        max: hi,
        full_cycles: tally.full,
        half_cycles: tally.half,
        damage,
        damage_uncorrected: damage_plain,
        life_s: duration_s / damage,
        life_uncorrected_s: life_plain,
        matrix: tally
            .matrix
            .unwrap_or_else(|| RangeMeanMatrix::new(MATRIX_BINS, 1.0, 0.0, 1.0)),
        samples_per_peak: moments.as_ref().map(|m| info.sample_rate_hz / m.nu_peak()),
        spectral: moments.as_ref().map(MomentsSummary::of),
        moments,
        segment_len: m,
        segments,
        methods,
        spread,
        record: info,
    })
}

/// The stress channel of the record: the one `--channel` names, or the only one; its unit must have the
/// dimension of the S–N curve's amplitudes, and a `--gate` must be finite and > 0.
///
/// # Errors
/// A missing channel, several channels and none named, a unit of another dimension, a bad gate.
fn stress_channel(info: &RecordInfo, options: &FatigueOptions) -> Result<usize> {
    let index = match &options.channel {
        Some(c) => info.channel(c)?,
        None if info.channels.len() == 1 => 0,
        None => {
            return Err(Error::in_file(
                &info.source,
                "channels",
                info.channels
                    .iter()
                    .map(|c| c.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
                "the record has several channels: name the stress with --channel",
            ))
        }
    };
    info.require_dim(index, options.sn_dim, "the unit of the S–N curve's amplitudes")?;
    if let Some(g) = options.gate
        && !(g.is_finite() && g > 0.0)
    {
        return Err(Error::invalid("--gate", g, "a hysteresis gate must be finite and > 0"));
    }
    Ok(index)
}

/// What one reading of the record feeds: the Welch sums, and the rainflow counter (behind the gate, if any)
/// whose cycles the tally adds up.
struct Passes<'a> {
    welch: &'a Welch,
    spectral: &'a mut SpectralSums,
    gate: &'a mut Option<Gate>,
    counter: &'a mut RainflowCounter,
    tally: &'a mut Tally,
}

/// The samples of the stress channel: how many, their sum, their least and greatest.
struct Extent {
    n: usize,
    sum: f64,
    lo: f64,
    hi: f64,
}

/// Reads the record to its end in blocks of [`BLOCK_SAMPLES`]; each block of channel `index` goes into
/// `passes` (the first block also sizes the range–mean matrix).
///
/// # Errors
/// The reader's errors; a cycle the counter refuses.
fn read_stress(reader: &mut dyn RecordReader, index: usize, p: Passes) -> Result<Extent> {
    let mut block = vec![Vec::with_capacity(BLOCK_SAMPLES); reader.info().channels.len()];
    let mut gated = Vec::new();
    let (mut n, mut sum, mut lo, mut hi) = (0usize, 0.0f64, f64::INFINITY, f64::NEG_INFINITY);
    loop {
        let got = reader.read_block(&mut block, BLOCK_SAMPLES)?;
        if got == 0 {
            break;
        }
        let x = &block[index];
        if p.tally.matrix.is_none() {
            p.tally.matrix = Some(first_matrix(x));
        }
        n += got;
        sum += x.iter().sum::<f64>();
        (lo, hi) = x.iter().fold((lo, hi), |(a, b), &v| (a.min(v), b.max(v)));
        p.spectral.push(p.welch, x)?;
        let samples: &[f64] = match p.gate.as_mut() {
            Some(g) => {
                gated.clear();
                g.push(x, &mut gated);
                &gated
            }
            None => x,
        };
        p.counter.push(samples, |c| p.tally.add(c))?;
    }
    Ok(Extent { n, sum, lo, hi })
}

/// Refuses a `--segment` the user gave that left no Welch segment in the record's `n` samples (`segments`
/// = 0): the spectral methods would vanish from the table without a word. The default segment of a short
/// record is not refused; the report says why it has no spectral methods.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `--segment`.
fn refuse_long_segment(options: &FatigueOptions, segments: u64, n: usize) -> Result<()> {
    match options.segment_len {
        Some(asked) if segments == 0 => Err(Error::invalid(
            "--segment",
            asked,
            format!(
                "longer than the record's {n} samples: the spectral methods need at least one Welch segment (give \
                 an even length of at most {n}, or none for the default)"
            ),
        )),
        _ => Ok(()),
    }
}

/// Refuses a record in which the mean-stress correction met a cycle it has no finite value for.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `--mean-stress` and the cycle.
fn refuse_mean_stress(tally: &Tally, options: &FatigueOptions) -> Result<()> {
    match tally.refused {
        Some(c) => Err(Error::invalid(
            "--mean-stress",
            options.mean_stress.label(),
            format!(
                "a cycle of mean {} and amplitude {} (SI) has a mean at or above the ultimate strength (--ultimate): \
                 the correction has no finite value",
                crate::numbers::sig4(c.mean),
                crate::numbers::sig4(c.amplitude)
            ),
        )),
        None => Ok(()),
    }
}

/// Refuses a damage (or damage rate) of `method` that is 0 — no cycle does damage within the range of f64
/// (all below the endurance limit, or amplitudes so small that S^k underflows): the life would be
/// infinite — or not finite (amplitudes whose S^k overflows), naming the record and the channel.
///
/// # Errors
/// [`Error::File`] naming the record's channel.
fn require_damage(info: &RecordInfo, channel: &str, method: &str, damage: f64) -> Result<()> {
    if damage.is_finite() && damage > 0.0 {
        return Ok(());
    }
    let why = if damage == 0.0 {
        "no damage within the range of f64 (every cycle below the endurance limit, or S^k below the smallest \
         number): the life is not a finite number; check the S–N curve's point and the channel's unit"
    } else {
        "a damage that is not a finite number (S^k overflows): check the S–N curve's point and the channel's unit"
    };
    Err(Error::in_file(
        &info.source,
        "channel",
        channel,
        format!("{method} gives {why}"),
    ))
}

/// The methods' lives against the rainflow life, and their spread.
fn method_lives(cmp: &MethodComparison, rainflow_life: f64) -> (Vec<MethodLife>, Option<f64>) {
    let rows = cmp
        .estimates
        .iter()
        .map(|e| MethodLife {
            method: e.name.to_string(),
            damage_rate: e.damage_rate,
            life_s: e.life,
            life_ratio: e.life / rainflow_life,
        })
        .collect();
    (rows, Some(cmp.spread()))
}

/// A matrix sized from the first block: ranges up to twice its span, means over twice its span.
fn first_matrix(x: &[f64]) -> RangeMeanMatrix {
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let span = if hi > lo { hi - lo } else { hi.abs().max(1.0) };
    let n = MATRIX_BINS as f64;
    RangeMeanMatrix::new(MATRIX_BINS, 2.0 * span / n, 0.5 * (lo + hi) - span, 2.0 * span / n)
}

/// The default Welch segment: the largest power of two ≤ N/8, between 256 and 2¹⁶.
fn default_segment(samples: Option<usize>) -> usize {
    let n = samples.unwrap_or(1 << 19);
    let mut m = 1usize << 16;
    while m > 256 && m * 8 > n {
        m /= 2;
    }
    m
}

/// The streamed Welch sums of the stress.
struct SpectralSums {
    stream: WelchStream,
    sums: WelchSums,
    scratch: WelchScratch,
}

impl SpectralSums {
    fn new(w: &Welch) -> Self {
        SpectralSums {
            stream: w.stream(),
            sums: w.sums(),
            scratch: w.scratch(),
        }
    }

    fn push(&mut self, w: &Welch, x: &[f64]) -> Result<()> {
        w.push(&mut self.stream, x, &mut self.sums, &mut self.scratch)
    }

    /// The moments of the one-sided density (`None` for a record shorter than one segment or without
    /// fluctuation) and the segments.
    fn moments(mut self, w: &Welch) -> Result<(Option<SpectralMoments>, u64)> {
        if w.end_record(&mut self.stream, &mut self.sums).is_err() {
            return Ok((None, 0));
        }
        let est = w.finish(&self.sums)?;
        let (f, g) = est.one_sided_cyclic();
        // a record without fluctuation has no moments (m₀ = 0): no spectral estimate then
        Ok((
            SpectralMoments::from_tabulated_one_sided_hz(&f, &g, false).ok(),
            est.segments,
        ))
    }
}
