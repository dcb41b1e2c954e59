//! Statistics of a transient Monte Carlo run from its per-shard accumulators: the ensemble mean and σ at
//! every stored time with intervals, the empirical distributions of the per-realization maxima and their
//! verdicts against the analytic distributions. One code for a run and for a merge (bit-identical).

use crate::error::{Error, Result};
use crate::estimate::{chi_squared_quantile, student_t_quantile, Interval};
use crate::extremes::{BandVerdict, EmpiricalDistribution};
use crate::store::transient_series::{TransientOutput, TransientSeries};
use crate::store::{OutputStatistics, RunMetadata, Statistic};
use rayon::prelude::*;

/// Name of an output's per-shard series accumulator: per stored time the shard's mean, then its sum of
/// squared deviations M₂.
pub fn series_accumulator(output: &str) -> String {
    format!("{output}:transient")
}

/// Name of an output's per-shard maxima accumulator: max y of each realization, then max |y|, each
/// zero-padded to the shard size.
pub fn maxima_accumulator(output: &str) -> String {
    format!("{output}:maxima")
}

/// Whether a run's accumulators are those of a transient run.
pub fn is_transient_layout(accumulators: &[(String, usize)]) -> bool {
    accumulators.iter().any(|a| a.0.ends_with(":transient"))
}

/// The accumulator layout of a transient run of `outputs` with `n_stored` times.
pub fn layout(outputs: &[String], n_stored: usize, shard_size: usize) -> Vec<(String, usize)> {
    outputs
        .iter()
        .flat_map(|o| {
            [
                (series_accumulator(o), 2 * n_stored),
                (maxima_accumulator(o), 2 * shard_size),
            ]
        })
        .collect()
}

/// Per stored time: the count, mean and M₂ of the realizations folded so far.
#[derive(Debug, Clone)]
struct Fold {
    n: f64,
    mean: Vec<f64>,
    m2: Vec<f64>,
}

impl Fold {
    /// Adds a shard of `rows` realizations with means and M₂ from its accumulator (Chan, Golub & LeVeque
    /// 1979: δ = m_b − m_a, m = m_a + δ n_b/n, M₂ = M₂a + M₂b + δ² n_a n_b/n).
    fn add(&mut self, rows: usize, acc: &[f64]) {
        let k = self.mean.len();
        let nb = rows as f64;
        let n = self.n + nb;
        for j in 0..k {
            let (mb, m2b) = (acc[j], acc[k + j]);
            if self.n == 0.0 {
                self.mean[j] = mb;
                self.m2[j] = m2b;
            } else {
                let d = mb - self.mean[j];
                self.mean[j] += d * nb / n;
                self.m2[j] += m2b + d * d * self.n * nb / n;
            }
        }
        self.n = n;
    }
}

/// The analytic side of a run: the exact curves and the analytic distributions of the maxima, per output.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalyticSide {
    /// How the exact curves were computed.
    pub method: String,
    /// Per output: (exact mean, exact σ, levels, the four distributions as in [`TransientOutput`]).
    pub outputs: Vec<AnalyticOutput>,
}

/// One output's analytic side.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalyticOutput {
    /// Exact mean at the stored times.
    pub mean: Vec<f64>,
    /// Exact σ at the stored times.
    pub sigma: Vec<f64>,
    /// Levels of the distributions.
    pub levels: Vec<f64>,
    /// P(max y ≤ b), Poisson at the integrated Rice rate.
    pub cdf_y_rice: Vec<f64>,
    /// P(max |y| ≤ b), the same.
    pub cdf_abs_rice: Vec<f64>,
    /// P(max y ≤ b), Vanmarcke (NaN where not applicable).
    pub cdf_y_vanmarcke: Vec<f64>,
    /// P(max |y| ≤ b), Vanmarcke (NaN where not applicable).
    pub cdf_abs_vanmarcke: Vec<f64>,
}

impl AnalyticOutput {
    /// The analytic side as stored in a run file's series.
    pub fn from_stored(o: &TransientOutput) -> AnalyticOutput {
        AnalyticOutput {
            mean: o.exact_mean.clone(),
            sigma: o.exact_sigma.clone(),
            levels: o.levels.clone(),
            cdf_y_rice: o.cdf_max_y_rice.clone(),
            cdf_abs_rice: o.cdf_max_abs_y_rice.clone(),
            cdf_y_vanmarcke: o.cdf_max_y_vanmarcke.clone(),
            cdf_abs_vanmarcke: o.cdf_max_abs_y_vanmarcke.clone(),
        }
    }
}

/// The verdicts of the analytic distributions of one output's maxima against the DKW band.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MaximaVerdicts {
    /// Output.
    pub output: String,
    /// One per analytic distribution that exists.
    pub verdicts: Vec<BandVerdict>,
}

/// Everything finished from the accumulators.
#[derive(Debug, Clone, PartialEq)]
pub struct Finished {
    /// The `/transient` group.
    pub series: TransientSeries,
    /// The statistics group (the last stored time's mean and σ with their exact values).
    pub statistics: Vec<OutputStatistics>,
    /// The maxima verdicts.
    pub verdicts: Vec<MaximaVerdicts>,
}

/// Reads accumulator `name` of shard `b`.
pub type AccumulatorReader<'a> = dyn Fn(&str, usize) -> Result<Vec<f64>> + 'a;

/// The statistics of the shards `meta.local_shards()` of a run from their accumulators, in shard order.
///
/// # Formula
/// At every stored time, over the R realizations: m̂ ± t_{R−1}s/√R (Student-t) and σ̂ = s with the χ²_{R−1}
/// interval (both exact for the Gaussian response of a linear system to a Gaussian input); the
/// maxima's empirical distributions with the DKW band ε = √(ln(2/α)/(2R)); an analytic distribution is
/// "inside" when its largest distance from the empirical one at the samples is ≤ ε.
///
/// # Errors
/// Fewer than 2 realizations; a damaged accumulator.
pub fn finish(
    acc: &AccumulatorReader<'_>,
    meta: &RunMetadata,
    times: &[f64],
    analytic: &AnalyticSide,
    confidence: f64,
) -> Result<Finished> {
    let shards: Vec<(usize, usize)> = meta.local_shards().map(|b| (b, meta.shard_range(b).len())).collect();
    let r: usize = shards.iter().map(|s| s.1).sum();
    if r < 2 {
        return Err(Error::invalid(
            "realizations",
            r,
            "the ensemble statistics need at least 2 realizations",
        ));
    }
    let epsilon = crate::extremes::dkw_epsilon(r, 1.0 - confidence)?;
    // the file read output by output, then the outputs' series, verdicts and statistics in parallel
    let mut read = Vec::new();
    for sig in &meta.outputs {
        let fold = fold_series(acc, &sig.name, &shards, times.len())?;
        read.push((fold, read_maxima(acc, &sig.name, &shards, meta.shard_size)?));
    }
    let done: Vec<_> = read
        .into_par_iter()
        .zip(meta.outputs.par_iter().zip(&analytic.outputs))
        .map(|((fold, (max_y, max_abs_y)), (sig, an))| {
            let o = output_series(&sig.name, &sig.unit, &fold, an, max_y, max_abs_y, confidence)?;
            let v = maxima_verdicts(&o, confidence)?;
            let st = end_statistics(&o, r, confidence);
            Ok((o, v, st))
        })
        .collect::<Result<_>>()?;
    let mut outputs = Vec::new();
    let mut statistics = Vec::new();
    let mut verdicts = Vec::new();
    for (o, v, st) in done {
        verdicts.push(v);
        statistics.push(st);
        outputs.push(o);
    }
    Ok(Finished {
        series: TransientSeries {
            times: times.to_vec(),
            confidence,
            dkw_epsilon: epsilon,
            exact_method: analytic.method.clone(),
            outputs,
        },
        statistics,
        verdicts,
    })
}

fn fold_series(acc: &AccumulatorReader<'_>, output: &str, shards: &[(usize, usize)], k: usize) -> Result<Fold> {
    let mut fold = Fold {
        n: 0.0,
        mean: vec![0.0; k],
        m2: vec![0.0; k],
    };
    for &(b, rows) in shards {
        let a = acc(&series_accumulator(output), b)?;
        if a.len() != 2 * k {
            return Err(Error::invalid(
                "accumulator",
                series_accumulator(output),
                "wrong length: the file is damaged",
            ));
        }
        fold.add(rows, &a);
    }
    Ok(fold)
}

fn read_maxima(
    acc: &AccumulatorReader<'_>,
    output: &str,
    shards: &[(usize, usize)],
    shard_size: usize,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let (mut y, mut abs) = (Vec::new(), Vec::new());
    for &(b, rows) in shards {
        let a = acc(&maxima_accumulator(output), b)?;
        if a.len() != 2 * shard_size {
            return Err(Error::invalid(
                "accumulator",
                maxima_accumulator(output),
                "wrong length: the file is damaged",
            ));
        }
        y.extend_from_slice(&a[..rows]);
        abs.extend_from_slice(&a[shard_size..shard_size + rows]);
    }
    y.sort_by(f64::total_cmp);
    abs.sort_by(f64::total_cmp);
    Ok((y, abs))
}

fn output_series(
    name: &str,
    unit: &str,
    fold: &Fold,
    an: &AnalyticOutput,
    max_y: Vec<f64>,
    max_abs_y: Vec<f64>,
    confidence: f64,
) -> Result<TransientOutput> {
    let n = fold.n;
    let t = student_t_quantile(n - 1.0, 0.5 + 0.5 * confidence)?;
    // the χ² interval of `VarianceEstimate::interval` with its two quantiles found once for every time
    let (nu, a) = (n - 1.0, 1.0 - confidence);
    let (hi, lo) = (
        chi_squared_quantile(nu, 1.0 - a / 2.0)?,
        chi_squared_quantile(nu, a / 2.0)?,
    );
    let mut o = TransientOutput {
        output: name.to_string(),
        unit: unit.to_string(),
        mean: fold.mean.clone(),
        mean_lower: Vec::new(),
        mean_upper: Vec::new(),
        sigma: Vec::new(),
        sigma_lower: Vec::new(),
        sigma_upper: Vec::new(),
        exact_mean: an.mean.clone(),
        exact_sigma: an.sigma.clone(),
        max_y,
        max_abs_y,
        levels: an.levels.clone(),
        cdf_max_y_rice: an.cdf_y_rice.clone(),
        cdf_max_abs_y_rice: an.cdf_abs_rice.clone(),
        cdf_max_y_vanmarcke: an.cdf_y_vanmarcke.clone(),
        cdf_max_abs_y_vanmarcke: an.cdf_abs_vanmarcke.clone(),
    };
    for (j, &m) in fold.mean.iter().enumerate() {
        let var = fold.m2[j].max(0.0) / (n - 1.0);
        let h = t * (var / n).sqrt();
        o.mean_lower.push(m - h);
        o.mean_upper.push(m + h);
        o.sigma.push(var.sqrt());
        o.sigma_lower.push((nu * var / hi).sqrt());
        o.sigma_upper.push((nu * var / lo).sqrt());
    }
    Ok(o)
}

/// The verdicts of the analytic distributions of `o`'s maxima that exist (not NaN).
fn maxima_verdicts(o: &TransientOutput, confidence: f64) -> Result<MaximaVerdicts> {
    let mut verdicts = Vec::new();
    for (samples, label, curves) in [
        (
            &o.max_y,
            "max y",
            [
                (&o.cdf_max_y_rice, "Poisson (Rice)"),
                (&o.cdf_max_y_vanmarcke, "Vanmarcke (1975)"),
            ],
        ),
        (
            &o.max_abs_y,
            "max |y|",
            [
                (&o.cdf_max_abs_y_rice, "Poisson (Rice)"),
                (&o.cdf_max_abs_y_vanmarcke, "Vanmarcke (1975)"),
            ],
        ),
    ] {
        let emp = EmpiricalDistribution::new(samples, confidence)?;
        for (cdf, method) in curves {
            if o.levels.len() < 2 || cdf.iter().any(|v| v.is_nan()) {
                continue;
            }
            let f = |b: f64| interpolate(&o.levels, cdf, b);
            verdicts.push(emp.verdict(&format!("{label}: {method}"), &f));
        }
    }
    Ok(MaximaVerdicts {
        output: o.output.clone(),
        verdicts,
    })
}

/// Linear interpolation of a distribution tabulated at ascending `x`, constant beyond the table (its
/// levels span the maxima with a margin of several σ).
pub fn interpolate(x: &[f64], y: &[f64], v: f64) -> f64 {
    let k = x.partition_point(|a| *a <= v);
    if k == 0 {
        return y[0];
    }
    if k == x.len() {
        return y[x.len() - 1];
    }
    let w = (v - x[k - 1]) / (x[k] - x[k - 1]);
    y[k - 1] + w * (y[k] - y[k - 1])
}

/// The statistics of the last stored time: `mean_end`, `sigma_end` with the exact values.
fn end_statistics(o: &TransientOutput, r: usize, confidence: f64) -> OutputStatistics {
    let last = o.mean.len() - 1;
    let stat = |name: &str, est: f64, lo: f64, hi: f64, analytic: f64, method: &str| {
        let interval = Interval {
            estimate: est,
            lower: lo,
            upper: hi,
            confidence,
        };
        Statistic {
            name: name.to_string(),
            interval,
            unit: o.unit.clone(),
            method: method.to_string(),
            analytic: Some(analytic),
            covers: Some(interval.covers(analytic)),
        }
    };
    OutputStatistics {
        output: o.output.clone(),
        unit: o.unit.clone(),
        n_used: r as u64,
        statistics: vec![
            stat(
                "mean_end",
                o.mean[last],
                o.mean_lower[last],
                o.mean_upper[last],
                o.exact_mean[last],
                "Student-t at the last stored time; analytic: exact route",
            ),
            stat(
                "sigma_end",
                o.sigma[last],
                o.sigma_lower[last],
                o.sigma_upper[last],
                o.exact_sigma[last],
                "chi-square at the last stored time; analytic: exact route",
            ),
        ],
    }
}
