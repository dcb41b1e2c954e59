//! The accumulators a route-2 run stores per shard and the statistics it finishes from them — one code path
//! for a run, its shard files and their merge, so that the three give bit-identical numbers.
//!
//! # Layout (per simulated output, besides the standard `<output>:moments` and `<output>:welch`)
//! * `<output>:nonlinear`, length K·shard_size: K blocks of shard_size values (zero-padded), one value per
//!   realization: mean, variance, kurtosis, max |y|, the up-crossing rate of every level, the fraction and
//!   entry rate of every element regime the output carries, the Δt-halving differences of mean and σ (NaN
//!   for realizations without the check).
//! * `<output>:histogram`, length bins + 2: the shard's sample counts (underflow, bins, overflow).
//!
//! # Statistics
//! Per quantity the Student-t interval of the realizations' values (NaN values left out: the halving
//! differences exist for the checked realizations only); `sigma_response` is the square root of the
//! variance interval. The kurtosis is pooled, κ̂ = μ̄₄/σ̄⁴ (μ̄₄, σ̄² the means of the realizations' central
//! moments), with the delta-method interval of the ratio (Student-t on z_i = μ₄ᵢ/σ̄⁴ − 2κ̂σᵢ²/σ̄²): the
//! average of per-realization kurtoses is biased low by O(1/N_eff) for records of N_eff correlation times,
//! the pooled ratio only by O(1/N_eff²). The stored analytic value is route 1's (Gaussian equivalent: an approximation), and
//! where route 3 applies the statistic is repeated as `exact:<name>` with the exact value.

use crate::error::{Error, Result};
use crate::estimate::Interval;
use crate::simulate::finish_interval;
use crate::store::{ResponseHistogram, Statistic};

/// Name of the per-realization accumulator of `output`.
pub fn values_name(output: &str) -> String {
    format!("{output}:nonlinear")
}

/// Name of the histogram accumulator of `output`.
pub fn histogram_name(output: &str) -> String {
    format!("{output}:histogram")
}

/// Prefix of the statistics compared with route 3.
pub const EXACT: &str = "exact:";

/// The values of quantity k of every realization of a shard, from its accumulator.
pub(crate) fn encode(values: &[Vec<f64>], shard_size: usize) -> Vec<f64> {
    let k = values.first().map_or(0, Vec::len);
    let mut v = vec![0.0; k * shard_size];
    for (i, row) in values.iter().enumerate() {
        for (q, x) in row.iter().enumerate() {
            v[q * shard_size + i] = *x;
        }
    }
    v
}

/// Appends the `rows` realizations of a shard's accumulator to `per_quantity`.
///
/// # Errors
/// A vector whose length is not a multiple of the shard size (a damaged file).
pub(crate) fn decode_into(
    data: &[f64],
    rows: usize,
    shard_size: usize,
    per_quantity: &mut Vec<Vec<f64>>,
) -> Result<()> {
    if shard_size == 0 || !data.len().is_multiple_of(shard_size) || rows > shard_size {
        return Err(Error::Numerical {
            what: "reading a nonlinear accumulator".into(),
            reason: format!(
                "stored length {} is not a multiple of the shard size {shard_size}: the run file is damaged",
                data.len()
            ),
        });
    }
    let k = data.len() / shard_size;
    per_quantity.resize(k, Vec::new());
    for (q, out) in per_quantity.iter_mut().enumerate() {
        out.extend_from_slice(&data[q * shard_size..q * shard_size + rows]);
    }
    Ok(())
}

/// The interval of the finite values (Student-t; a single value with an unbounded interval; none: NaN).
fn interval(values: &[f64], confidence: f64) -> Result<Interval> {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return Ok(Interval {
            estimate: f64::NAN,
            lower: f64::NAN,
            upper: f64::NAN,
            confidence,
        });
    }
    finish_interval(&v, confidence)
}

/// Whether a statistic is a rate of events counted on each realization's record (level up-crossings,
/// entries into a regime): `<kind>_rate[…]` in 1/s.
fn is_count_rate(t: &Statistic) -> bool {
    t.unit == "1/s" && t.name.contains("_rate[")
}

/// Whether a statistic is a fraction of time (in a regime): `<kind>_fraction[…]`.
fn is_fraction(t: &Statistic) -> bool {
    t.name.contains("_fraction[")
}

/// The interval of an event rate: the Student-t interval across realizations (which sees the clustering
/// of the events, e.g. crossings in bursts), widened to hold the exact Poisson interval of the total count
/// over the total record time (which holds when the events are rare: a level never crossed in R·T seconds
/// has the rate interval [0, −ln(α/2)/(R·T)], not the zero-width [0, 0] of R zero rates), and never below 0.
/// The counts are the rates times the record time `record_s`, rounded.
fn rate_interval(iv: Interval, values: &[f64], record_s: f64, confidence: f64) -> Result<Interval> {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() || record_s.is_nan() || record_s <= 0.0 {
        return Ok(iv);
    }
    let k: f64 = v.iter().map(|r| (r * record_s).round()).sum();
    let (lo, hi) = crate::estimate::poisson_rate_interval(k, v.len() as f64 * record_s, confidence)?;
    Ok(Interval {
        lower: iv.lower.min(lo).max(0.0),
        upper: iv.upper.max(hi),
        ..iv
    })
}

/// The interval of a time fraction: within [0, 1]; when no realization spent any time in the regime the
/// samples bound nothing but the fraction itself (an episode's length is unknown), so [0, 1] rather than
/// the zero-width [0, 0] that R zero fractions give.
fn fraction_interval(iv: Interval, values: &[f64]) -> Interval {
    let none = values.iter().filter(|x| x.is_finite()).all(|x| *x == 0.0);
    Interval {
        lower: iv.lower.clamp(0.0, 1.0),
        upper: if none { 1.0 } else { iv.upper.clamp(0.0, 1.0) },
        ..iv
    }
}

/// The statistics from the per-quantity values and the templates (name, unit, method, analytic of each
/// quantity in order, then the `exact:` repetitions); `record_s` is each realization's record time (s),
/// which turns the rates back into counts ([`rate_interval`]).
///
/// # Errors
/// Fewer templates than quantities; a confidence outside (0, 1).
pub(crate) fn statistics(
    templates: &[Statistic],
    per_quantity: &[Vec<f64>],
    confidence: f64,
    record_s: f64,
) -> Result<Vec<Statistic>> {
    if templates.len() < per_quantity.len() {
        return Err(Error::Numerical {
            what: "nonlinear statistics".into(),
            reason: format!(
                "{} quantities stored but {} statistics described",
                per_quantity.len(),
                templates.len()
            ),
        });
    }
    let mut out: Vec<Statistic> = Vec::with_capacity(templates.len());
    for (k, (t, values)) in templates.iter().zip(per_quantity).enumerate() {
        let mut iv = if t.name == "kurtosis" && k == 2 {
            kurtosis_interval(&per_quantity[1], values, confidence)?
        } else {
            interval(values, confidence)?
        };
        if is_count_rate(t) {
            iv = rate_interval(iv, values, record_s, confidence)?;
        } else if is_fraction(t) {
            iv = fraction_interval(iv, values);
        }
        if t.name == "sigma_response" {
            iv = Interval {
                estimate: iv.estimate.max(0.0).sqrt(),
                lower: iv.lower.max(0.0).sqrt(),
                upper: iv.upper.max(0.0).sqrt(),
                confidence,
            };
        }
        out.push(with_interval(t, iv));
    }
    for t in &templates[per_quantity.len()..] {
        let base = t
            .name
            .strip_prefix(EXACT)
            .and_then(|b| out.iter().find(|s| s.name == b))
            .ok_or_else(|| Error::Numerical {
                what: "nonlinear statistics".into(),
                reason: format!("statistic `{}` repeats no stored quantity", t.name),
            })?;
        let iv = base.interval;
        out.push(with_interval(t, iv));
    }
    Ok(out)
}

/// The pooled kurtosis μ̄₄/σ̄⁴ with its delta-method interval (see the module docs).
fn kurtosis_interval(var: &[f64], mu4: &[f64], confidence: f64) -> Result<Interval> {
    let n = var.len() as f64;
    let (v, m4) = (var.iter().sum::<f64>() / n, mu4.iter().sum::<f64>() / n);
    let k = m4 / (v * v);
    let z: Vec<f64> = var
        .iter()
        .zip(mu4)
        .map(|(s, m)| m / (v * v) - 2.0 * k * s / v)
        .collect();
    let iv = interval(&z, confidence)?;
    let half = 0.5 * (iv.upper - iv.lower);
    Ok(Interval {
        estimate: k,
        lower: k - half,
        upper: k + half,
        confidence,
    })
}

fn with_interval(t: &Statistic, iv: Interval) -> Statistic {
    Statistic {
        interval: iv,
        covers: t.analytic.map(|a| iv.covers(a)),
        ..t.clone()
    }
}

/// The histogram of summed counts (underflow, bins, overflow) on `edges`, with the reference densities.
pub(crate) fn histogram(
    output: &str,
    unit: &str,
    edges: Vec<f64>,
    counts: &[f64],
    gaussian: Option<Vec<f64>>,
    exact: Option<Vec<f64>>,
) -> ResponseHistogram {
    let total: f64 = counts.iter().sum();
    let bins = counts.len() - 2;
    let width = (edges[bins] - edges[0]) / bins as f64;
    let norm = if total > 0.0 { total } else { 1.0 };
    ResponseHistogram {
        output: output.to_string(),
        unit: unit.to_string(),
        density: counts[1..=bins].iter().map(|c| c / (norm * width)).collect(),
        edges,
        below: counts[0] / norm,
        above: counts[bins + 1] / norm,
        samples: total,
        gaussian,
        exact,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn template(name: &str, unit: &str) -> Statistic {
        Statistic {
            name: name.into(),
            unit: unit.into(),
            method: String::new(),
            analytic: Some(1e-5),
            interval: Interval {
                estimate: f64::NAN,
                lower: f64::NAN,
                upper: f64::NAN,
                confidence: 0.95,
            },
            covers: None,
        }
    }

    /// Eight realizations of 150 s without a crossing: the rate's interval is Garwood's for 0 events in
    /// 1200 s, [0, −ln(0.025)/1200] = [0, 3.0741e-3] at 95 % (its closed form for k = 0), so a route-1 rate
    /// of 10⁻⁵ lies inside (the zero-width [0, 0] of eight zero rates said it did not); the fraction of
    /// time in a regime never entered is [0, 1]. With 2 and 1 crossings in two 100-s records the interval
    /// holds Garwood's [χ²₆(0.025)/2, χ²₈(0.975)/2]/200 (χ²₆(0.025) = 1.2373, χ²₈(0.975) = 17.5345, tables)
    /// and never goes below 0.
    #[test]
    fn rare_event_rates_and_fractions_have_honest_intervals() {
        let t = [
            template("upcrossing_rate[0.04 m]", "1/s"),
            template("contact_fraction[stop]", "-"),
        ];
        let zeros = vec![vec![0.0; 8], vec![0.0; 8]];
        let st = statistics(&t, &zeros, 0.95, 150.0).unwrap();
        let r = st[0].interval;
        assert_eq!((r.estimate, r.lower), (0.0, 0.0));
        assert!((r.upper - (-(0.025f64).ln() / 1200.0)).abs() < 1e-12, "{r:?}");
        assert_eq!(st[0].covers, Some(true));
        assert_eq!((st[1].interval.lower, st[1].interval.upper), (0.0, 1.0));
        let st = statistics(&t[..1], &[vec![0.02, 0.01]], 0.95, 100.0).unwrap();
        let r = st[0].interval;
        assert!(r.lower >= 0.0 && r.lower <= 1.2373 / 2.0 / 200.0 + 1e-6, "{r:?}");
        assert!(r.upper >= 17.5345 / 2.0 / 200.0 - 1e-6, "{r:?}");
    }
}
