//! Verdict channels of a Monte Carlo run: per realization, the ISO 2631-1 metrics of a frequency-weighted
//! acceleration (VDV, MTVV, crest factor) and the rainflow count and Palmgren–Miner damage of a stress,
//! reduced to per-shard accumulators (so that a run resumes without raw data) and finished into
//! statistics with intervals.
//!
//! # Formula
//! A comfort channel is a run output that already *is* the weighted acceleration a_w(t) (the weighting
//! filter is part of the simulated system, discretised exactly with it: see
//! [`crate::comfort::weighted_output`]). Realization i of N samples at step Δt (T = NΔt) gives
//! ([`SignalMetrics`]): VDV_i = (Σ a_k⁴ Δt)^{1/4}, MTVV_i (1 s running r.m.s.), crest factor
//! CF_i = max|a_k| / a_w,i. Across realizations:
//! ```text
//! VDV:   E[VDV_i⁴] = 3 σ_w⁴ T exactly for a stationary Gaussian a_w(t) (E a⁴ = 3σ⁴), so the Student-t
//!        interval of the mean of VDV_i⁴, raised to the power 1/4, is an interval for (3T)^{1/4} σ_w
//!        (ISO 2631-1:1997 6.3.2; the Gaussian value is the "estimated VDV" (3T)^{1/4} a_w of its 6.3.2 note);
//!        for a non-Gaussian input (Laplace moving average) E[VDV_i⁴] = κ_w σ_w⁴ T with the weighted output's
//!        kurtosis κ_w, and the analytic value is (κ_w T)^{1/4} σ_w ([`set_non_gaussian_vdv`]);
//! MTVV, CF: Student-t interval of the mean over realizations (no closed form is claimed).
//! ```
//! A fatigue channel is a run output y(t) times a stress factor s (stress = s·y, in the S–N curve's unit).
//! Realization i is rainflow-counted (ASTM E1049-85 four-point method, residue as half cycles,
//! [`rainflow()`]) and its Miner damage D_i = Σ n_j S_a,j^k / C ([`SnCurve::damage`]) gives the damage rate
//! d_i = D_i/T (1/s); the Student-t interval of the mean of d_i is compared with the spectral methods. The
//! ranges are also binned ([`RangeHistogram`]) on [0, `max_range`] and summed over the realizations.
//!
//! # Accumulators (per shard)
//! * `verdict:<output>:comfort`, length 4·shard_size: a_w,i, VDV_i⁴, MTVV_i (NaN for a record shorter than
//!   1 s), CF_i, each block zero-padded to shard_size.
//! * `verdict:<output>:fatigue`, length shard_size + bins + 1: d_i (zero-padded), then the range histogram
//!   summed over the shard's realizations, then its overflow count.

use super::finish::interval;
use crate::comfort::SignalMetrics;
use crate::error::{Error, Result};
use crate::estimate::Interval;
use crate::fatigue::{rainflow, Dirlik, RangeHistogram, SnCurve, SpectralMethod, SpectralMoments};
use crate::store::Statistic;

/// A comfort channel: the run output `output` (a weighted acceleration).
#[derive(Debug, Clone, PartialEq)]
pub struct ComfortChannel {
    /// Name of the run output holding a_w(t).
    pub output: String,
}

/// A fatigue channel: stress = `stress_factor` · run output `output`, judged with `sn`.
#[derive(Debug, Clone, PartialEq)]
pub struct FatigueChannel {
    /// Name of the run output.
    pub output: String,
    /// Stress per unit of the output (S–N unit per output unit).
    pub stress_factor: f64,
    /// The S–N curve (amplitudes, in the stress unit).
    pub sn: SnCurve,
    /// Top of the range histogram, in the stress unit.
    pub max_range: f64,
    /// Number of histogram bins.
    pub bins: usize,
    /// Unit of the stress (the S–N curve's unit, e.g. `Pa`).
    pub sn_unit: String,
    /// One-sided Hz moments of the stress process (the analytic ones), for the expected damage rate and
    /// range histogram by Dirlik's method; `None` for no comparison.
    pub moments: Option<SpectralMoments>,
}

/// The verdict channels of one run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VerdictChannels {
    /// Comfort channels.
    pub comfort: Vec<ComfortChannel>,
    /// Fatigue channels.
    pub fatigue: Vec<FatigueChannel>,
}

/// Sets the analytic value of statistic `name` (and whether its interval covers it).
pub fn set_analytic(stats: &mut [Statistic], name: &str, analytic: f64) {
    if let Some(s) = stats.iter_mut().find(|s| s.name == name) {
        s.analytic = Some(analytic);
        s.covers = Some(s.interval.covers(analytic));
    }
}

/// The weighted acceleration a_w(t) of a run as [`set_non_gaussian_vdv`] needs it (named fields: three
/// numbers of different meaning cannot be swapped silently).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightedProcess {
    /// Kurtosis κ_w = E a⁴/σ_w⁴ (3 for a Gaussian process).
    pub kurtosis: f64,
    /// Variance σ_w², (m/s²)².
    pub variance: f64,
    /// Duration T of a realization, s.
    pub duration_s: f64,
}

/// Sets the analytic VDV of a weighted output of kurtosis `kurtosis` (a non-Gaussian input: a Laplace moving
/// average) and says so in the statistic's method: the Gaussian (3T)^{1/4}σ_w does not hold.
///
/// # Formula
/// For a stationary a_w(t) of variance σ_w² and kurtosis κ_w = E a⁴/σ_w⁴, sampled at N steps Δt (T = NΔt):
/// ```text
/// E[VDV⁴] = E[Σ_k a_k⁴ Δt] = T·E a⁴ = κ_w σ_w⁴ T,     analytic VDV = (κ_w T)^{1/4} σ_w
/// ```
/// (exact for the stationary simulated process, whatever its law; κ_w = 3 is the Gaussian value).
pub fn set_non_gaussian_vdv(stats: &mut [Statistic], w: &WeightedProcess) {
    let WeightedProcess {
        kurtosis,
        variance,
        duration_s,
    } = *w;
    set_analytic(stats, "vdv", (kurtosis * duration_s).powf(0.25) * variance.sqrt());
    if let Some(s) = stats.iter_mut().find(|s| s.name == "vdv") {
        s.method = non_gaussian_vdv_method(kurtosis);
    }
}

/// Withdraws the Gaussian (Dirlik) analytic value of a fatigue channel's `damage_rate` when its output is
/// non-Gaussian (kurtosis `kurtosis` ≠ 3 of a Laplace moving-average input): Dirlik's formula assumes a
/// Gaussian process, and a heavier-tailed output of the same spectrum has more large cycles (the damage
/// grows with E S^k), so the Monte Carlo rate is not compared with it. The method text keeps Dirlik's
/// value and says why it is not the analytic value.
pub fn unset_gaussian_damage(st: &mut Statistic, kurtosis: f64) {
    if let Some(d) = st.analytic.take() {
        st.covers = None;
        st.method = format!(
            "{}; NOT compared: the output is non-Gaussian (kurtosis {kurtosis:.4}, Laplace moving-average input) and \
             Dirlik's Gaussian rate {d:.6e} 1/s is no prediction for it",
            st.method
        );
    }
}

/// The method text of a non-Gaussian `vdv` statistic (see [`set_non_gaussian_vdv`]).
pub fn non_gaussian_vdv_method(kurtosis: f64) -> String {
    format!(
        "VDV_i = (Σ a_w⁴ Δt)^(1/4) per realization; Student-t interval of the mean of VDV_i⁴, raised to 1/4; \
         analytic = (κ_w T)^(1/4)·σ_w of the stationary non-Gaussian weighted output, κ_w = {kurtosis:.6} its \
         kurtosis (Laplace moving average input; E a⁴ = κ_w σ⁴, not the Gaussian 3σ⁴)"
    )
}

/// The rainflow histogram of a fatigue channel (the stored record).
pub use crate::store::RainflowHistogram as RainflowSummary;

impl VerdictChannels {
    /// True when there is nothing to evaluate.
    pub fn is_empty(&self) -> bool {
        self.comfort.is_empty() && self.fatigue.is_empty()
    }

    /// The accumulator `(name, length)` pairs, in storage order (comfort channels, then fatigue channels).
    pub fn layout(&self, shard_size: usize) -> Vec<(String, usize)> {
        let mut v: Vec<(String, usize)> = self
            .comfort
            .iter()
            .map(|c| (comfort_name(&c.output), 4 * shard_size))
            .collect();
        v.extend(
            self.fatigue
                .iter()
                .map(|c| (fatigue_name(&c.output), shard_size + c.bins + 1)),
        );
        v
    }

    /// The channels of a stored run as its accumulator layout names them (`verdict:<output>:comfort`,
    /// `verdict:<output>:fatigue` of length shard_size + bins + 1), for finishing the stored accumulators
    /// without the scenario (a merge of shard files). Only what [`finish`](Self::finish) reads from the
    /// accumulators is known: a fatigue channel's S–N curve, stress factor and moments are placeholders
    /// (no analytic rate) and its histogram top is 1; the caller takes the analytic values, the edges and
    /// the Dirlik counts from a stored file.
    pub(crate) fn from_layout(accumulators: &[(String, usize)], shard_size: usize) -> Result<VerdictChannels> {
        let mut ch = VerdictChannels::default();
        for (name, len) in accumulators {
            let Some(rest) = name.strip_prefix("verdict:") else {
                continue;
            };
            if let Some(output) = rest.strip_suffix(":comfort") {
                ch.comfort.push(ComfortChannel { output: output.into() });
            } else if let Some(output) = rest.strip_suffix(":fatigue") {
                let bins = len.checked_sub(shard_size + 1).filter(|b| *b > 0).ok_or_else(|| {
                    Error::invalid(name, len, "too short for a fatigue accumulator of this shard size")
                })?;
                ch.fatigue.push(FatigueChannel {
                    output: output.into(),
                    stress_factor: 1.0,
                    sn: SnCurve {
                        k: 3.0,
                        c: 1.0,
                        endurance_limit: None,
                    }
                    .build()?,
                    max_range: 1.0,
                    bins,
                    sn_unit: String::new(),
                    moments: None,
                });
            }
        }
        Ok(ch)
    }

    /// Validates the channels against the simulated output names.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `verdicts` for a channel whose output is not simulated (e.g.
    /// skipped because its variance is infinite), or a histogram without bins or a non-positive top.
    pub fn check(&self, simulated: &[&str]) -> Result<()> {
        for name in self
            .comfort
            .iter()
            .map(|c| &c.output)
            .chain(self.fatigue.iter().map(|c| &c.output))
        {
            if !simulated.contains(&name.as_str()) {
                return Err(Error::invalid(
                    "verdicts",
                    name,
                    format!(
                        "this output is not simulated (simulated: {}); a verdict needs its realizations",
                        simulated.join(", ")
                    ),
                ));
            }
        }
        for c in &self.fatigue {
            RangeHistogram::new(c.max_range, c.bins)?;
        }
        Ok(())
    }

    /// Evaluates one realization: `signal(name)` gives the samples of a simulated output. Returns the
    /// per-channel values in [`VerdictChannels::layout`] order: per comfort channel \[a_w, VDV⁴, MTVV, CF\],
    /// per fatigue channel \[d, histogram counts…, overflow\].
    ///
    /// # Errors
    /// Non-finite samples; the errors of [`SignalMetrics::from_samples`], [`rainflow()`] and
    /// [`SnCurve::damage`].
    pub fn evaluate<'s>(&self, dt_s: f64, signal: &dyn Fn(&str) -> Option<&'s [f64]>) -> Result<Vec<Vec<f64>>> {
        let mut out = Vec::with_capacity(self.comfort.len() + self.fatigue.len());
        let missing = |n: &str| Error::invalid("verdicts", n, "no samples for this output");
        for c in &self.comfort {
            let x = signal(&c.output).ok_or_else(|| missing(&c.output))?;
            let m = SignalMetrics::from_samples(x, dt_s)?;
            out.push(vec![
                m.a_w,
                m.vdv.powi(4),
                m.mtvv.unwrap_or(f64::NAN),
                m.check.crest_factor.unwrap_or(f64::NAN),
            ]);
        }
        for c in &self.fatigue {
            let x = signal(&c.output).ok_or_else(|| missing(&c.output))?;
            let stress: Vec<f64> = x.iter().map(|v| v * c.stress_factor).collect();
            let cycles = rainflow(&stress)?;
            let damage = c.sn.damage_of_cycles(&cycles)?;
            let h = RangeHistogram::from_cycles(&cycles, c.max_range, c.bins)?;
            let mut v = Vec::with_capacity(c.bins + 2);
            v.push(damage / (x.len() as f64 * dt_s));
            v.extend_from_slice(h.counts());
            v.push(h.overflow());
            out.push(v);
        }
        Ok(out)
    }

    /// Encodes the per-realization values of one shard (`values[realization][channel]`, as returned by
    /// [`VerdictChannels::evaluate`]) into the accumulator vectors of [`VerdictChannels::layout`].
    pub fn encode(&self, values: &[Vec<Vec<f64>>], shard_size: usize) -> Vec<Vec<f64>> {
        let nc = self.comfort.len();
        let mut accs = Vec::with_capacity(nc + self.fatigue.len());
        for j in 0..nc {
            let mut a = vec![0.0; 4 * shard_size];
            for (i, r) in values.iter().enumerate() {
                for q in 0..4 {
                    a[q * shard_size + i] = r[j][q];
                }
            }
            accs.push(a);
        }
        for (jf, c) in self.fatigue.iter().enumerate() {
            let j = nc + jf;
            let mut a = vec![0.0; shard_size + c.bins + 1];
            for (i, r) in values.iter().enumerate() {
                a[i] = r[j][0];
                for (b, v) in r[j][1..].iter().enumerate() {
                    a[shard_size + b] += v;
                }
            }
            accs.push(a);
        }
        accs
    }

    /// Finishes the statistics from the accumulators of every shard: `read(name, k)` returns the stored
    /// vector of the k-th shard (in order), `rows[k]` its number of realizations. A single realization (a
    /// shard file of one) gets its value with an unbounded interval. Returns per comfort channel its statistics
    /// (`vdv`, `mtvv`, `crest_factor`), per fatigue channel its `damage_rate` statistic (with the
    /// `analytic` value `expected_rate[j]` if given) and its histogram.
    ///
    /// # Errors
    /// A damaged accumulator (wrong length); no realization; a confidence outside (0, 1).
    #[allow(clippy::type_complexity)]
    pub fn finish(
        &self,
        read: &dyn Fn(&str, usize) -> Result<Vec<f64>>,
        rows: &[usize],
        shard_size: usize,
        duration_s: f64,
        confidence: f64,
    ) -> Result<(Vec<(String, Vec<Statistic>)>, Vec<(String, Statistic, RainflowSummary)>)> {
        let shards = Shards {
            read,
            rows,
            size: shard_size,
        };
        let comfort = (self.comfort.iter())
            .map(|c| Ok((c.output.clone(), comfort_statistics(c, &shards, confidence)?)))
            .collect::<Result<_>>()?;
        let fatigue = (self.fatigue.iter())
            .map(|c| fatigue_statistics(c, &shards, duration_s, confidence))
            .collect::<Result<_>>()?;
        Ok((comfort, fatigue))
    }
}

/// The stored accumulators of every shard: `read(name, k)` the vector `name` of the k-th shard, `rows[k]` its
/// number of realizations, `size` the realizations a shard has room for.
struct Shards<'a> {
    read: &'a dyn Fn(&str, usize) -> Result<Vec<f64>>,
    rows: &'a [usize],
    size: usize,
}

/// The error of an accumulator whose stored length differs from the layout.
fn damaged(name: &str) -> Error {
    Error::Numerical {
        what: format!("reading the {name} accumulator"),
        reason: "stored length differs from the layout: the run file is damaged".into(),
    }
}

/// The statistics (`vdv`, `mtvv`, `crest_factor`) of the comfort channel `c` from every shard's accumulator.
///
/// # Errors
/// A damaged accumulator; no realization; a confidence outside (0, 1).
fn comfort_statistics(c: &ComfortChannel, shards: &Shards, confidence: f64) -> Result<Vec<Statistic>> {
    let name = comfort_name(&c.output);
    let mut cols: [Vec<f64>; 4] = Default::default();
    for (s, &r) in shards.rows.iter().enumerate() {
        let a = (shards.read)(&name, s)?;
        if a.len() != 4 * shards.size {
            return Err(damaged(&name));
        }
        for (q, col) in cols.iter_mut().enumerate() {
            col.extend_from_slice(&a[q * shards.size..q * shards.size + r]);
        }
    }
    let v4 = interval(&cols[1], confidence)?;
    let root = |x: f64| x.max(0.0).powf(0.25);
    let vdv = Interval {
        estimate: root(v4.estimate),
        lower: root(v4.lower),
        upper: root(v4.upper),
        confidence,
    };
    let mut stats = vec![stat(
        "vdv",
        vdv,
        "m/s^1.75",
        "VDV_i = (Σ a_w⁴ Δt)^(1/4) per realization; Student-t interval of the mean of VDV_i⁴, raised to \
         1/4; analytic = (3T)^(1/4)·σ_w of the stationary Gaussian weighted output (E a⁴ = 3σ⁴)",
        None,
    )];
    // the analytic VDV needs the analytic σ_w: the caller sets it ([`set_analytic`])
    let mtvv: Vec<f64> = cols[2].iter().copied().filter(|v| v.is_finite()).collect();
    if !mtvv.is_empty() {
        stats.push(stat(
            "mtvv",
            interval(&mtvv, confidence)?,
            "m/s^2",
            "maximum 1 s running r.m.s. per realization (ISO 2631-1 6.3.1); Student-t across realizations",
            None,
        ));
    }
    let cf: Vec<f64> = cols[3].iter().copied().filter(|v| v.is_finite()).collect();
    if !cf.is_empty() {
        stats.push(stat(
            "crest_factor",
            interval(&cf, confidence)?,
            "1",
            "max|a_w(t)|/a_w per realization (ISO 2631-1 6.2.1); Student-t across realizations",
            None,
        ));
    }
    Ok(stats)
}

/// The `damage_rate` statistic and the histogram of the fatigue channel `c` from every shard's accumulator.
///
/// # Errors
/// A damaged accumulator; no realization; a confidence outside (0, 1).
fn fatigue_statistics(
    c: &FatigueChannel,
    shards: &Shards,
    duration_s: f64,
    confidence: f64,
) -> Result<(String, Statistic, RainflowSummary)> {
    let name = fatigue_name(&c.output);
    let mut d = Vec::new();
    let mut hist = vec![0.0; c.bins + 1];
    for (s, &r) in shards.rows.iter().enumerate() {
        let a = (shards.read)(&name, s)?;
        if a.len() != shards.size + c.bins + 1 {
            return Err(damaged(&name));
        }
        d.extend_from_slice(&a[..r]);
        for (h, v) in hist.iter_mut().zip(&a[shards.size..]) {
            *h += v;
        }
    }
    let n = d.len() as f64;
    let iv = interval(&d, confidence)?;
    let mut st = stat(
        "damage_rate",
        iv,
        "1/s",
        "rainflow (ASTM E1049-85, residue as half cycles) and Palmgren–Miner per realization, divided by \
         its duration; Student-t across realizations; analytic = Dirlik (1985) from the analytic moments",
        match &c.moments {
            Some(m) => Some(Dirlik.damage_rate(m, &c.sn)?),
            None => None,
        },
    );
    // no damaging cycle in any realization (all below an endurance limit): R zero damages give the
    // zero-width interval [0, 0], which bounds the rate of damaging cycles but not their damage (a cycle's
    // damage has no upper bound), so it is not compared with the analytic value (it would read "NO")
    if d.iter().all(|x| *x == 0.0) {
        st.covers = None;
    }
    let edges = RangeHistogram::new(c.max_range, c.bins)?.bin_edges();
    let overflow = hist[c.bins] / n;
    let counts = hist[..c.bins].iter().map(|v| v / n).collect();
    Ok((
        c.output.clone(),
        st,
        RainflowSummary {
            output: c.output.clone(),
            unit: String::new(),
            edges,
            counts,
            overflow,
            dirlik: c.moments.as_ref().map(|m| dirlik_counts(m, &edges_of(c), duration_s)),
        },
    ))
}

fn edges_of(c: &FatigueChannel) -> Vec<f64> {
    RangeHistogram::new(c.max_range, c.bins)
        .map(|h| h.bin_edges())
        .unwrap_or_default()
}

/// Expected rainflow cycles per range bin in a record of `duration_s` seconds by Dirlik's amplitude
/// density: ν_p·T·∫ p(S_a) dS_a over the bin's amplitudes [ΔS₁/2, ΔS₂/2] (Simpson's rule on 16
/// sub-intervals of the bin; Dirlik's density is smooth).
///
/// # Formula
/// n_bin = ν_p T ∫_{ΔS₁/2}^{ΔS₂/2} p_D(a) da, ν_p = √(m₄/m₂) (peaks per second).
pub fn dirlik_counts(m: &SpectralMoments, edges: &[f64], duration_s: f64) -> Vec<f64> {
    let rate = m.nu_peak() * duration_s;
    edges
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0] / 2.0, w[1] / 2.0);
            let n = 16;
            let h = (b - a) / n as f64;
            let mut s = Dirlik::amplitude_pdf(m, a) + Dirlik::amplitude_pdf(m, b);
            for i in 1..n {
                s += if i % 2 == 1 { 4.0 } else { 2.0 } * Dirlik::amplitude_pdf(m, a + i as f64 * h);
            }
            rate * s * h / 3.0
        })
        .collect()
}

/// Accumulator name of a comfort channel.
pub fn comfort_name(output: &str) -> String {
    format!("verdict:{output}:comfort")
}

/// Accumulator name of a fatigue channel.
pub fn fatigue_name(output: &str) -> String {
    format!("verdict:{output}:fatigue")
}

fn stat(name: &str, interval: Interval, unit: &str, method: &str, analytic: Option<f64>) -> Statistic {
    Statistic {
        name: name.into(),
        interval,
        unit: unit.into(),
        method: method.into(),
        analytic,
        covers: analytic.map(|a| interval.covers(a)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_then_finish_round_trips() {
        // two realizations of a sinusoid of amplitude 2 (a_w = √2, CF = √2) and of a square wave ±1
        let sn = SnCurve {
            k: 3.0,
            c: 1.0,
            endurance_limit: None,
        }
        .build()
        .unwrap();
        let ch = VerdictChannels {
            comfort: vec![ComfortChannel { output: "a".into() }],
            fatigue: vec![FatigueChannel {
                output: "s".into(),
                stress_factor: 1.0,
                sn,
                max_range: 4.0,
                bins: 2,
                sn_unit: "Pa".into(),
                moments: None,
            }],
        };
        let dt = 0.25;
        let a: Vec<f64> = (0..64)
            .map(|k| 2.0 * (std::f64::consts::PI * k as f64 / 4.0).sin())
            .collect();
        let s: Vec<f64> = (0..64).map(|k| if k % 2 == 0 { 1.0 } else { -1.0 }).collect();
        let sig = |n: &str| if n == "a" { Some(&a[..]) } else { Some(&s[..]) };
        let v = ch.evaluate(dt, &sig).unwrap();
        // square wave ±1 of 64 samples: 63 ranges of 2 between turning points. Rainflow removes two ranges
        // per full cycle and counts the r − 1 ranges of the residue as halves, so the total count is
        // always 63/2 = 31.5 cycles of amplitude 1: damage Σ n·1³/1 = 31.5 over T = 64·0.25 = 16 s
        assert!((v[1][0] - 31.5 / 16.0).abs() < 1e-12);
        let accs = ch.encode(&[v.clone(), v.clone()], 3);
        let read = |name: &str, _s: usize| -> Result<Vec<f64>> {
            Ok(if name.ends_with("comfort") {
                accs[0].clone()
            } else {
                accs[1].clone()
            })
        };
        let (c, f) = ch.finish(&read, &[2], 3, 16.0, 0.95).unwrap();
        // identical realizations: zero-width intervals at the per-realization values
        let cf = c[0].1.iter().find(|s| s.name == "crest_factor").unwrap();
        assert!((cf.interval.estimate - 2f64.sqrt()).abs() < 1e-12);
        assert_eq!(f[0].1.interval.estimate, 31.5 / 16.0);
        // per realization: every range 2 falls in the bin [2, 4]
        assert_eq!(f[0].2.counts, vec![0.0, 31.5]);
    }
}
