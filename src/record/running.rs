//! The running r.m.s. of ISO 2631-1 6.3.1 in its exponential form, and a decimated envelope of a long
//! signal for pictures (memory bounded whatever the record's length). The linear form (the standard's
//! first form, used for the MTVV unless the exponential one is asked for) is part of
//! [`SignalMetricsStream`](crate::comfort::SignalMetricsStream).

use crate::error::{Error, Result};

/// Which running r.m.s. defines the MTVV.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum RunningRms {
    /// Linear integration over the last τ (ISO 2631-1:1997 6.3.1, first form).
    #[default]
    Linear,
    /// Exponential averaging with time constant τ (ISO 2631-1:1997 6.3.1, second form; ISO 8041 "slow" for
    /// τ = 1 s).
    Exponential,
}

/// The exponential running mean square of a sampled signal.
///
/// # Formula
/// ISO 2631-1:1997 6.3.1: a_w(t₀) = [(1/τ)∫_{−∞}^{t₀} a_w²(t) e^{(t−t₀)/τ} dt]^{1/2}. With each sample held over
/// one step dt (as the other metrics take it), the integral is exact step by step:
/// ```text
/// m_k = α m_{k−1} + (1 − α) a_k²,   α = e^{−dt/τ},   a_w(t_k) = √m_k,   m_{−1} = 0,
/// ```
/// and the MTVV of this form is max_k √m_k. (HVLab's `hvrunrms` uses a bilinear first-order filter instead;
/// the two agree to O((dt/τ)²).)
///
/// # Errors
/// [`ExponentialRms::new`] refuses dt or τ not finite and > 0.
///
/// # Examples
/// ```
/// use stochvib::record::ExponentialRms;
/// let mut r = ExponentialRms::new(0.001, 1.0).unwrap();
/// r.push(&vec![2.0; 20_000]); // 20 s of a constant 2: the mean square approaches 4
/// assert!((r.mtvv() - 2.0).abs() < 1e-6);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ExponentialRms {
    alpha: f64,
    mean_square: f64,
    max_mean_square: f64,
}

impl ExponentialRms {
    /// A running r.m.s. at step `dt_s` with time constant `tau_s`, starting from rest.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(dt_s: f64, tau_s: f64) -> Result<Self> {
        for (name, v) in [("dt", dt_s), ("tau", tau_s)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(name, v, "must be finite and > 0 s"));
            }
        }
        Ok(ExponentialRms {
            alpha: (-dt_s / tau_s).exp(),
            mean_square: 0.0,
            max_mean_square: 0.0,
        })
    }

    /// Adds samples.
    pub fn push(&mut self, x: &[f64]) {
        let (a, b) = (self.alpha, 1.0 - self.alpha);
        let mut m = self.mean_square;
        let mut top = self.max_mean_square;
        for v in x {
            m = a * m + b * (v * v);
            top = top.max(m);
        }
        self.mean_square = m;
        self.max_mean_square = top;
    }

    /// The running r.m.s. now.
    pub fn value(&self) -> f64 {
        self.mean_square.sqrt()
    }

    /// The largest running r.m.s. so far (the MTVV of this form).
    pub fn mtvv(&self) -> f64 {
        self.max_mean_square.sqrt()
    }
}

/// One bin of an [`Envelope`]: the extremes of the signal and the largest running r.m.s. in it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct EnvelopeBin {
    /// Start of the bin, s from the start of the record.
    pub time_s: f64,
    /// Smallest sample.
    pub min: f64,
    /// Largest sample.
    pub max: f64,
    /// Largest running r.m.s. (NaN before the first full window).
    pub running_rms: f64,
}

/// A decimated picture of a long signal: at most `2·capacity` bins of equal length, each with the signal's
/// extremes and the largest running r.m.s.; when full, neighbouring bins merge and the bin length doubles,
/// so memory is bounded whatever the length.
///
/// # Formula
/// Bin i covers samples [i·L, (i+1)·L), L = 2^j samples for the smallest j that keeps the bins within the
/// capacity.
///
/// # Examples
/// ```
/// use stochvib::record::Envelope;
/// let mut e = Envelope::new(0.01, 4);
/// for k in 0..100 {
///     e.add(k as f64, f64::NAN);
/// }
/// let bins = e.bins();
/// assert!(bins.len() <= 8);
/// assert_eq!(bins[0].min, 0.0);
/// assert_eq!(bins.last().unwrap().max, 99.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Envelope {
    dt_s: f64,
    capacity: usize,
    per_bin: usize,
    bins: Vec<EnvelopeBin>,
    current: Option<EnvelopeBin>,
    in_current: usize,
}

impl Envelope {
    /// An empty envelope of a signal sampled at `dt_s`, keeping between `capacity` and `2·capacity` bins.
    pub fn new(dt_s: f64, capacity: usize) -> Self {
        Envelope {
            dt_s,
            capacity: capacity.max(1),
            per_bin: 1,
            bins: Vec::new(),
            current: None,
            in_current: 0,
        }
    }

    /// Adds one sample and the running r.m.s. at it (NaN when not available).
    #[inline]
    pub fn add(&mut self, value: f64, running_rms: f64) {
        let start = (self.bins.len() * self.per_bin) as f64 * self.dt_s;
        let c = self.current.get_or_insert(EnvelopeBin {
            time_s: start,
            min: value,
            max: value,
            running_rms,
        });
        c.min = c.min.min(value);
        c.max = c.max.max(value);
        c.running_rms = c.running_rms.max(running_rms);
        self.in_current += 1;
        if self.in_current == self.per_bin {
            self.bins.push(*c);
            self.current = None;
            self.in_current = 0;
            if self.bins.len() == 2 * self.capacity {
                self.halve();
            }
        }
    }

    /// Merges neighbouring bins (the bin length doubles).
    fn halve(&mut self) {
        let merged: Vec<EnvelopeBin> = self
            .bins
            .chunks(2)
            .map(|p| {
                let mut b = p[0];
                if let Some(q) = p.get(1) {
                    b.min = b.min.min(q.min);
                    b.max = b.max.max(q.max);
                    b.running_rms = b.running_rms.max(q.running_rms);
                }
                b
            })
            .collect();
        self.bins = merged;
        self.per_bin *= 2;
    }

    /// The bins so far (the last, partial bin included).
    pub fn bins(&self) -> Vec<EnvelopeBin> {
        let mut out = self.bins.clone();
        out.extend(self.current);
        out
    }
}
