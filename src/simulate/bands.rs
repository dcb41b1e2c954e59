//! Octave and one-third-octave band r.m.s. from Monte Carlo (`[analysis] bands`): per realization the band
//! mean squares of every output from its own Welch estimate, accumulated per shard, finished with Student-t
//! intervals and stored beside the analytic band r.m.s.
//!
//! # Formula
//! Realization i's Welch estimate Ŝ_i(ω_j) (two-sided, rad/s; bins ω_j = jΔω, Δω = 2π/(MΔt), j = 0 … M/2)
//! is taken as constant on its bin [ω_j − Δω/2, ω_j + Δω/2] clipped to [0, ω_N] (half bins at 0 and at the
//! Nyquist frequency ω_N), so that the bins tile [0, ω_N]. The band mean square of band [f_1, f_2] (Hz) is
//! ```text
//! b_i = Σ_j c_j Ŝ_i(ω_j),    c_j = 2·|[ω_j − Δω/2, ω_j + Δω/2] ∩ [0, ω_N] ∩ [2πf_1, 2πf_2]|
//! ```
//! (one-sided: σ²_band = 2∫_{2πf_1}^{2πf_2} S(ω) dω; a bin cut by a band edge counts with the fraction of
//! it inside the band; a band above ω_N gets nothing and is left out, one across ω_N is cut there). Across
//! the bands covering [0, ω_N], Σ_k b_i,k = Σ_j w_j Ŝ_i(ω_j) Δω (w_j = 2, 1 at 0 and ω_N) is the estimate's
//! total variance.
//!
//! The b_i are independent across realizations, and E b_i = Σ_j c_j E Ŝ(ω_j) exactly, with E Ŝ the exact
//! mean of the Welch estimate of the *simulated* process ([`Welch::expected_all`] of its autocovariance: the
//! discretisation and the window's leakage across the band edges included). The Student-t interval of their
//! mean is an interval for that expected band mean square (independence and the central limit theorem), and
//! its square root one for the band r.m.s.; the statistics are
//! * `band_rms[<band>]`: analytic = √(∫_{f_1}^{f_2} G_y df) of the continuous response (the band table of
//!   `analyze`, [`crate::comfort::output_band_table`]);
//! * `band_rms_expected[<band>]`: the same interval, analytic = √(Σ_j c_j E Ŝ(ω_j)), what the Monte Carlo
//!   estimates without bias.
//!
//! The two analytic values differ by the discretisation (see `sigma_discrete`) and by the Welch window's
//! leakage across the band edges (largest for bands where the density falls steeply, and for bands a few
//! bins wide).
//!
//! # Layout
//! Per output the accumulator `<output>:bands`, length n_bands·shard_size: for each band (ascending) the
//! b_i of the shard's realizations, zero-padded to shard_size.

use crate::comfort::{output_band_table, Band, BandFraction};
use crate::error::{Error, Result};
use crate::estimate::{Interval, Welch, WelchSums};
use crate::store::{OutputStatistics, Statistic};
use std::f64::consts::PI;

/// What a run's band r.m.s. are asked for: the bandwidth and optionally the frequency range of the bands
/// (the scenario's `[analysis] bands` and `[analysis] band`).
///
/// # Formula
/// The bands of [`output_band_table`]: those covering `range_hz` when given, otherwise the fewest
/// contiguous bands around the peak of f·G_y(f) holding 99.9 % of the output's analytic σ².
///
/// # Errors
/// None (a band table that cannot be made for an output becomes a note of the run).
///
/// # Examples
/// ```
/// use stochvib::comfort::BandFraction;
/// use stochvib::simulate::RunBands;
/// let b = RunBands { fraction: BandFraction::ThirdOctave, range_hz: Some((1.0, 80.0)) };
/// assert_eq!(b.range_hz, Some((1.0, 80.0)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunBands {
    /// Octave or one-third octave (IEC 61260-1, base 10).
    pub fraction: BandFraction,
    /// [f_lo, f_hi] in Hz, if the bands must cover this range.
    pub range_hz: Option<(f64, f64)>,
}

/// The bands of one simulated output with their bin weights and reference values.
#[derive(Debug, Clone)]
pub(crate) struct OutputBands {
    /// Position of the output among the simulated outputs.
    pub output: usize,
    /// The bands kept (lower edge below the Nyquist frequency), ascending.
    pub bands: Vec<Band>,
    /// Per band: the bins it overlaps and their weights c_j (rad/s).
    pub weights: Vec<Vec<(usize, f64)>>,
    /// Per band: the analytic band mean square of the continuous response.
    pub analytic: Vec<f64>,
    /// Per band: Σ_j c_j E Ŝ(ω_j), the expected band mean square of the simulated process.
    pub expected: Vec<f64>,
}

/// Name of the band accumulator of `output`.
pub(crate) fn accumulator_name(output: &str) -> String {
    format!("{output}:bands")
}

/// Statistic name of the band r.m.s. of `band` (`band_rms[31.5 Hz]`).
fn statistic_name(band_label: &str) -> String {
    format!("band_rms[{band_label}]")
}

/// Statistic name of the same interval against the expected value (`band_rms_expected[31.5 Hz]`).
fn expected_name(band_label: &str) -> String {
    format!("band_rms_expected[{band_label}]")
}

/// The weights c_j of the band [f_1, f_2] Hz on the bins of `welch` (see the module docs).
pub(crate) fn bin_weights(welch: &Welch, dt: f64, lower_hz: f64, upper_hz: f64) -> Vec<(usize, f64)> {
    let m = welch.segment_len();
    let dw = 2.0 * PI / (m as f64 * dt);
    let nyquist = (m / 2) as f64 * dw;
    let (w1, w2) = (2.0 * PI * lower_hz, 2.0 * PI * upper_hz);
    (0..=m / 2)
        .filter_map(|j| {
            let lo = (j as f64 - 0.5) * dw;
            let hi = (j as f64 + 0.5) * dw;
            let a = lo.max(0.0).max(w1);
            let b = hi.min(nyquist).min(w2);
            (b > a).then_some((j, 2.0 * (b - a)))
        })
        .collect()
}

/// Σ_j c_j v_j.
fn weighted(weights: &[(usize, f64)], v: &[f64]) -> f64 {
    weights.iter().map(|&(j, c)| c * v[j]).sum()
}

/// The bands of every simulated output (`outputs[r]` = (system index, analytic variance, name)) and the
/// notes of the outputs that get none or lose bands above the Nyquist frequency 1/(2Δt); `expected[r]` is
/// the expected Welch estimate E Ŝ(ω_j) of output r.
pub(crate) fn plan_bands(
    input: &super::RunInput,
    spec: &RunBands,
    outputs: &[(usize, f64, String)],
    expected: &[Vec<f64>],
    welch: &Welch,
    dt: f64,
) -> (Vec<OutputBands>, Vec<String>) {
    let mut out = Vec::new();
    let mut notes = Vec::new();
    let nyquist_hz = 0.5 / dt;
    for (r, ((index, variance, name), exp)) in outputs.iter().zip(expected).enumerate() {
        let table = output_band_table(
            input.system,
            input.excitation,
            *index,
            spec.fraction,
            Some(*variance),
            spec.range_hz,
        );
        let table = match table {
            Ok(t) => t,
            Err(e) => {
                notes.push(format!("no Monte Carlo band r.m.s. of `{name}`: {e}"));
                continue;
            }
        };
        let mut ob = OutputBands {
            output: r,
            bands: Vec::new(),
            weights: Vec::new(),
            analytic: Vec::new(),
            expected: Vec::new(),
        };
        let mut dropped = 0;
        for row in &table.rows {
            if row.band.lower_hz >= nyquist_hz {
                dropped += 1;
                continue;
            }
            let w = bin_weights(welch, dt, row.band.lower_hz, row.band.upper_hz);
            ob.expected.push(weighted(&w, exp));
            ob.weights.push(w);
            ob.analytic.push(row.mean_square);
            ob.bands.push(row.band);
        }
        if dropped > 0 {
            notes.push(format!(
                "`{name}`: {dropped} band(s) above the Nyquist frequency {nyquist_hz} Hz have no Monte Carlo band \
                 r.m.s."
            ));
        }
        if !ob.bands.is_empty() {
            out.push(ob);
        }
    }
    (out, notes)
}

/// The band accumulators of one shard: per output with bands, the b_i of every realization
/// (`welch_of(i, r)` = realization i's Welch sums of output r), encoded as in the module docs.
///
/// # Errors
/// A realization without Welch segments.
pub(crate) fn encode_shard<'a>(
    bands: &[OutputBands],
    rows: usize,
    welch_of: &dyn Fn(usize, usize) -> &'a WelchSums,
    shard_size: usize,
) -> Result<Vec<Vec<f64>>> {
    bands
        .iter()
        .map(|ob| {
            let mut v = vec![0.0; ob.bands.len() * shard_size];
            for i in 0..rows {
                let ws = welch_of(i, ob.output);
                if ws.segments == 0 {
                    return Err(Error::invalid("segments", 0, "a realization without Welch segments"));
                }
                let k = ws.segments as f64;
                for (b, w) in ob.weights.iter().enumerate() {
                    v[b * shard_size + i] = weighted(w, &ws.sum) / k;
                }
            }
            Ok(v)
        })
        .collect()
}

/// The band statistics of one output from the band mean squares b_i of every realization (`per_band[k]`,
/// realization order), the band labels, and the analytic and expected band **r.m.s.** values (`None` when
/// not known).
pub(crate) fn band_statistics(
    unit: &str,
    labels: &[String],
    per_band: &[Vec<f64>],
    analytic: &[Option<f64>],
    expected: &[Option<f64>],
    confidence: f64,
) -> Result<Vec<Statistic>> {
    let mut out = Vec::with_capacity(2 * labels.len());
    for (k, label) in labels.iter().enumerate() {
        let ms = super::finish::interval(&per_band[k], confidence)?;
        let iv = Interval {
            estimate: ms.estimate.max(0.0).sqrt(),
            lower: ms.lower.max(0.0).sqrt(),
            upper: ms.upper.max(0.0).sqrt(),
            confidence,
        };
        let stat = |name: String, a: Option<f64>, method: &str| Statistic {
            name,
            interval: iv,
            unit: unit.to_string(),
            method: method.to_string(),
            analytic: a,
            covers: a.map(|a| iv.covers(a)),
        };
        out.push(stat(
            statistic_name(label),
            analytic[k],
            "band r.m.s. (IEC 61260-1 base 10): per realization the band integral of its one-sided Welch \
             estimate (bins cut by a band edge weighted by their overlap), Student-t across realizations on the \
             mean square, square root of its bounds; analytic = band integral of the analytic output density",
        ));
        out.push(stat(
            expected_name(label),
            expected[k],
            "as band_rms, compared with the band integral of the exact mean of the Welch estimate of the \
             simulated process (discretisation and window leakage included)",
        ));
    }
    Ok(out)
}

/// Band k's b_i of every realization folded shard by shard from the accumulator `<output>:bands`.
///
/// # Errors
/// A damaged accumulator (length not a multiple of shard_size); what `accumulator` returns.
pub(crate) fn read_bands(
    accumulator: &dyn Fn(&str, usize) -> Result<Vec<f64>>,
    output: &str,
    shards: &[(usize, usize)],
    shard_size: usize,
) -> Result<Vec<Vec<f64>>> {
    let name = accumulator_name(output);
    let mut per_band: Vec<Vec<f64>> = Vec::new();
    for &(shard, rows) in shards {
        let v = accumulator(&name, shard)?;
        if shard_size == 0 || !v.len().is_multiple_of(shard_size) || rows > shard_size {
            return Err(Error::Numerical {
                what: "reading the bands accumulator".into(),
                reason: format!(
                    "stored length {} is not a multiple of the shard size {shard_size}: the run file is damaged",
                    v.len()
                ),
            });
        }
        let n = v.len() / shard_size;
        if per_band.is_empty() {
            per_band = vec![Vec::new(); n];
        }
        for (k, b) in per_band.iter_mut().enumerate() {
            b.extend_from_slice(&v[k * shard_size..k * shard_size + rows]);
        }
    }
    Ok(per_band)
}

/// The band labels and stored (analytic, expected) band r.m.s. of an output from its statistics (a shard
/// file's, for a merge): the pairs `band_rms[…]`, `band_rms_expected[…]` in stored order.
pub(crate) fn stored_bands(stats: &OutputStatistics) -> (Vec<String>, Vec<Option<f64>>, Vec<Option<f64>>) {
    let mut labels = Vec::new();
    let mut analytic = Vec::new();
    let mut expected = Vec::new();
    for s in &stats.statistics {
        if let Some(label) = s.name.strip_prefix("band_rms[").and_then(|x| x.strip_suffix(']')) {
            labels.push(label.to_string());
            analytic.push(s.analytic);
            expected.push(stats.get(&expected_name(label)).and_then(|e| e.analytic));
        }
    }
    (labels, analytic, expected)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_tile_the_bins_and_cut_partial_bins_by_overlap() {
        // M = 8, Δt = 0.125 s: Δω = 2π rad/s (1 Hz), bins 0..=4, Nyquist 4 Hz.
        let w = Welch::new(8, 0.125).unwrap();
        let all = bin_weights(&w, 0.125, 0.0, 100.0);
        // half bins at 0 and Nyquist: c = 2·(π, 2π, 2π, 2π, π)
        let two_pi = 2.0 * PI;
        let expect = [two_pi * 0.5, two_pi, two_pi, two_pi, two_pi * 0.5].map(|x| 2.0 * x);
        assert_eq!(all.len(), 5);
        for ((j, c), e) in all.iter().zip(expect) {
            assert!((c - e).abs() < 1e-12 * e, "bin {j}");
        }
        // [1.25, 2.0] Hz: a quarter of bin 1 ([0.5, 1.5]) and half of bin 2 ([1.5, 2.5]).
        let part = bin_weights(&w, 0.125, 1.25, 2.0);
        assert_eq!(part.len(), 2);
        assert!((part[0].1 - 2.0 * two_pi * 0.25).abs() < 1e-12);
        assert!((part[1].1 - 2.0 * two_pi * 0.5).abs() < 1e-12);
    }
}
