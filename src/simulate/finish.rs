//! Finishing a run from its per-shard accumulators: the statistics of every output and its Welch density.
//! One code path for a run of one process ([`run()`](super::run())), a shard file of a cluster run, and a
//! merge of shard files ([`merge_runs`](crate::study::merge_runs)), so that the three give bit-identical numbers
//! for the same realizations.
//!
//! # Formula
//! The per-realization time averages m_i, v_i are concatenated in realization order (internal shard by
//! internal shard) and reduced by [`mean_interval`]; the Welch sums of every internal shard are added, in
//! internal-shard order, to zero sums. Floating-point addition is not associative, so the numbers depend on
//! this order and on the grouping into internal shards (`shard_size`), and on nothing else.

use super::accumulators::{Moments, WelchAccumulator};
use crate::error::Result;
use crate::estimate::{mean_interval, Interval, Welch, WelchSums};
use crate::store::{OutputStatistics, PsdEstimate, RunMetadata, Signal, Statistic};

/// The analytic values stored with the four statistics of an output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Analytic {
    /// Of `mean` (the fluctuation's mean, 0).
    pub mean: f64,
    /// Of `variance`: the analytic variance.
    pub variance: f64,
    /// Of `sigma`: the analytic σ.
    pub sigma: f64,
    /// Of `sigma_discrete`: the exact σ of the simulated discretised process.
    pub sigma_discrete: f64,
}

impl Analytic {
    /// From the analytic and the discrete variance of a planned output.
    pub fn from_variances(analytic_variance: f64, discrete_variance: f64) -> Analytic {
        Analytic {
            mean: 0.0,
            variance: analytic_variance,
            sigma: analytic_variance.sqrt(),
            sigma_discrete: discrete_variance.sqrt(),
        }
    }

    /// As stored in `stats` (the statistics a run wrote), if all four are there.
    pub fn from_statistics(stats: &OutputStatistics) -> Option<Analytic> {
        let a = |name: &str| stats.get(name).and_then(|s| s.analytic);
        Some(Analytic {
            mean: a("mean")?,
            variance: a("variance")?,
            sigma: a("sigma")?,
            sigma_discrete: a("sigma_discrete")?,
        })
    }
}

/// The accumulators of one output folded shard by shard, in internal-shard order: the time averages m_i
/// and v_i of every realization (in realization order) and the Welch sums added shard by shard.
pub(crate) struct OutputFold {
    /// m_i of every realization folded so far.
    pub mean: Vec<f64>,
    /// v_i of every realization folded so far.
    pub mean_square: Vec<f64>,
    /// The Welch sums of every shard folded so far.
    pub welch: WelchSums,
    bins: usize,
}

impl OutputFold {
    /// Nothing folded yet.
    pub fn new(welch: &Welch) -> OutputFold {
        OutputFold {
            mean: Vec::new(),
            mean_square: Vec::new(),
            welch: welch.sums(),
            bins: welch.segment_len() / 2 + 1,
        }
    }

    /// Folds the next shard: its `rows` realizations' moments accumulator and its Welch accumulator.
    ///
    /// # Errors
    /// A damaged accumulator (wrong length).
    pub fn add(&mut self, rows: usize, shard_size: usize, moments: &[f64], welch: &[f64]) -> Result<()> {
        let mom = Moments::decode(moments, rows, shard_size)?;
        self.mean.extend_from_slice(&mom.mean);
        self.mean_square.extend_from_slice(&mom.mean_square);
        let wa = WelchAccumulator::decode(welch, self.bins)?;
        self.welch.merge(&wa.0)
    }
}

/// Reads `accumulator(name, shard)` of every internal shard the file holds, in order, and returns the
/// time averages m_i and v_i of every realization of output `output` (in realization order) and the Welch
/// sums added shard by shard ([`OutputFold`]).
///
/// # Errors
/// What `accumulator` returns; a damaged accumulator (wrong length).
pub(crate) fn read_output(
    accumulator: &dyn Fn(&str, usize) -> Result<Vec<f64>>,
    meta: &RunMetadata,
    output: &str,
    welch: &Welch,
) -> Result<(Vec<f64>, Vec<f64>, WelchSums)> {
    let mut fold = OutputFold::new(welch);
    let (mn, wn) = (Moments::name(output), WelchAccumulator::name(output));
    for shard in meta.local_shards() {
        let rows = meta.shard_range(shard).len();
        fold.add(
            rows,
            meta.shard_size,
            &accumulator(&mn, shard)?,
            &accumulator(&wn, shard)?,
        )?;
    }
    Ok((fold.mean, fold.mean_square, fold.welch))
}

/// [`mean_interval`], or for a single value (a shard file of one realization) that value with an unbounded
/// interval.
pub(crate) fn interval(values: &[f64], confidence: f64) -> Result<Interval> {
    if values.len() == 1 {
        return Ok(Interval {
            estimate: values[0],
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
            confidence,
        });
    }
    mean_interval(values, confidence)
}

/// The statistics of one output: `mean` (of the fluctuation, analytic 0), `variance`, `sigma` (analytic σ)
/// and `sigma_discrete` (analytic = the exact σ of the simulated discretised process).
///
/// # Errors
/// No values; a confidence outside (0, 1).
pub(crate) fn output_statistics(
    signal: &Signal,
    analytic: &Analytic,
    m: &[f64],
    v: &[f64],
    confidence: f64,
) -> Result<OutputStatistics> {
    let conf = confidence;
    let mi = interval(m, conf)?;
    let vi = interval(v, conf)?;
    let si = Interval {
        estimate: vi.estimate.max(0.0).sqrt(),
        lower: vi.lower.max(0.0).sqrt(),
        upper: vi.upper.max(0.0).sqrt(),
        confidence: conf,
    };
    let unit = &signal.unit;
    let var_unit = format!("({unit})^2");
    let stat = |sname: &str, iv: &Interval, u: &str, method: &str, a: f64| Statistic {
        name: sname.into(),
        interval: Interval {
            confidence: conf,
            ..*iv
        },
        unit: u.into(),
        method: method.into(),
        analytic: Some(a),
        covers: Some(iv.covers(a)),
    };
    Ok(OutputStatistics {
        output: signal.name.clone(),
        unit: unit.clone(),
        n_used: m.len() as u64,
        statistics: vec![
            stat(
                "mean",
                &mi,
                unit,
                "time average of the zero-mean fluctuation per realization; Student-t across realizations \
                 (the deterministic mean H(0)·M_u is not simulated)",
                analytic.mean,
            ),
            stat(
                "variance",
                &vi,
                &var_unit,
                "time average of y² per realization (known zero mean, unbiased); Student-t across \
                 independent realizations (CLT); analytic = reference analytic variance",
                analytic.variance,
            ),
            stat(
                "sigma",
                &si,
                unit,
                "square root of the variance interval; analytic σ",
                analytic.sigma,
            ),
            stat(
                "sigma_discrete",
                &si,
                unit,
                "as sigma, compared with the exact σ of the simulated discretised process",
                analytic.sigma_discrete,
            ),
        ],
    })
}

/// The Welch density of one output with its χ² intervals; `analytic(ω)` gives the analytic density at the
/// estimate's frequencies. The expected estimate (`expected`) is left `None`: the caller sets it (a run from
/// its plan, a merge from the shard files).
///
/// # Errors
/// No segments; a confidence outside (0, 1).
pub(crate) fn density_estimate(
    signal: &Signal,
    welch: &Welch,
    ws: &WelchSums,
    conf: f64,
    analytic: impl FnOnce(&[f64]) -> Result<Option<Vec<f64>>>,
) -> Result<PsdEstimate> {
    let est = welch.finish(ws)?;
    // every bin's interval as est.interval(j, conf) gives it, with the χ² quantiles computed once (they were
    // a third of a small shard's time and most of a merge's)
    let (lower, upper) = est.intervals(conf)?;
    let analytic = analytic(&est.omega)?;
    Ok(PsdEstimate {
        output: signal.name.clone(),
        unit: format!("({})^2 s/rad", signal.unit),
        omega: est.omega.clone(),
        density: est.density.clone(),
        lower,
        upper,
        analytic,
        expected: None,
        dof: est.dof,
        confidence: conf,
        method: format!(
            "Welch, Hann window of {} samples, 50 % overlap, averaged over realizations; χ² interval with \
             Welch's equivalent ν",
            welch.segment_len()
        ),
    })
}
