//! The verdict channels of a realization evaluated block by block, in time order, with memory independent
//! of the record length: the same per-realization values as [`VerdictChannels::evaluate`] on the whole
//! record, bit for bit, for any block size.

use super::VerdictChannels;
use crate::comfort::{SignalMetricsStream, MTVV_INTEGRATION_TIME_S};
use crate::error::{Error, Result};
use crate::fatigue::{Cycle, RainflowCounter, RangeHistogram};

/// The running state of one comfort channel.
#[derive(Debug, Clone)]
struct ComfortState {
    output: usize,
    metrics: SignalMetricsStream,
}

/// The running state of one fatigue channel.
#[derive(Debug, Clone)]
struct FatigueState {
    output: usize,
    counter: RainflowCounter,
    /// Σ n·S_a^k over the damaging cycles so far (divided by C at the end, as [`crate::fatigue::SnCurve::damage`])
    damage_sum: f64,
    histogram: RangeHistogram,
    samples: usize,
    stress: Vec<f64>,
}

/// Verdict channels fed block by block (see the module docs).
///
/// # Formula
/// Comfort: a_w = √(Σa²/N), VDV⁴ = (Σa⁴·Δt)^{1/4} raised to 4, MTVV = max_j √((1/n)Σ_{k=j−n+1}^{j} a_k²) with
/// n = round(1 s/Δt) (the sliding sum recomputed every n samples, from the last n samples kept), CF =
/// max|a|/a_w; the sums are compensated and carried across blocks. Fatigue: the rainflow counter
/// (ASTM E1049-85) keeps its stack of unmatched turning points across blocks, each closed cycle adds
/// n·S_a^k to the damage sum and n to its range bin; the residue is counted as half cycles at the end.
///
/// # Errors
/// [`VerdictStream::new`]: a channel whose output is not simulated. [`VerdictStream::push`]: non-finite
/// samples. [`VerdictStream::finish`]: the errors of
/// [`BasicMethodInputs::check`](crate::comfort::BasicMethodInputs::check).
///
/// # Examples
/// ```
/// use stochvib::simulate::{verdict_stream::VerdictStream, ComfortChannel, VerdictChannels};
/// let ch = VerdictChannels { comfort: vec![ComfortChannel { output: "a".into() }], fatigue: vec![] };
/// let a: Vec<f64> = (0..400).map(|k| (0.1 * k as f64).sin()).collect();
/// let whole = ch.evaluate(0.01, &|_| Some(&a[..])).unwrap();
/// let mut s = VerdictStream::new(&ch, 0.01, &["a"]).unwrap();
/// for block in a.chunks(7) {
///     s.push(0, block).unwrap();
/// }
/// assert_eq!(s.finish().unwrap(), whole);
/// ```
#[derive(Debug, Clone)]
pub struct VerdictStream {
    dt_s: f64,
    comfort: Vec<ComfortState>,
    fatigue: Vec<(FatigueState, f64)>,
    channels: VerdictChannels,
}

impl VerdictStream {
    /// A fresh state for one realization of the channels `channels`; `outputs` are the simulated output
    /// names in row order.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(channels: &VerdictChannels, dt_s: f64, outputs: &[&str]) -> Result<VerdictStream> {
        let find = |name: &str| {
            outputs
                .iter()
                .position(|o| *o == name)
                .ok_or_else(|| Error::invalid("verdicts", name, "no samples for this output"))
        };
        // as SignalMetrics::from_samples: n = round(τ/Δt) samples per MTVV window
        let n_win = (MTVV_INTEGRATION_TIME_S / dt_s).round();
        if !(dt_s.is_finite() && dt_s > 0.0 && n_win >= 1.0) {
            return Err(Error::invalid(
                "dt",
                dt_s,
                "the time step must be finite, > 0 s and at most 2 s",
            ));
        }
        let comfort = channels
            .comfort
            .iter()
            .map(|c| {
                Ok(ComfortState {
                    output: find(&c.output)?,
                    metrics: SignalMetricsStream::new(dt_s, MTVV_INTEGRATION_TIME_S)?,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let fatigue = channels
            .fatigue
            .iter()
            .map(|c| {
                Ok((
                    FatigueState {
                        output: find(&c.output)?,
                        counter: RainflowCounter::new(),
                        damage_sum: 0.0,
                        histogram: RangeHistogram::new(c.max_range, c.bins)?,
                        samples: 0,
                        stress: Vec::new(),
                    },
                    c.stress_factor,
                ))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(VerdictStream {
            dt_s,
            comfort,
            fatigue,
            channels: channels.clone(),
        })
    }

    /// Feeds the next samples `x` of output row `output` (blocks of every output in time order).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn push(&mut self, output: usize, x: &[f64]) -> Result<()> {
        for c in self.comfort.iter_mut().filter(|c| c.output == output) {
            c.metrics.push(x)?;
        }
        for (f, ch) in self.fatigue.iter_mut().zip(&self.channels.fatigue) {
            if f.0.output != output {
                continue;
            }
            let (state, factor) = f;
            state.stress.clear();
            state.stress.extend(x.iter().map(|v| v * *factor));
            let (sn, hist, sum) = (&ch.sn, &mut state.histogram, &mut state.damage_sum);
            state.counter.push(&state.stress, |c: Cycle| {
                if sn.damages(c.amplitude) {
                    *sum += c.count * c.amplitude.powf(sn.k());
                }
                hist.add(&c);
            })?;
            state.samples += x.len();
        }
        Ok(())
    }

    /// The per-channel values of the realization, in [`VerdictChannels::evaluate`]'s layout.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn finish(self) -> Result<Vec<Vec<f64>>> {
        let mut out = Vec::with_capacity(self.comfort.len() + self.fatigue.len());
        for c in &self.comfort {
            let m = c.metrics.finish()?;
            out.push(vec![
                m.a_w,
                m.vdv.powi(4),
                m.mtvv.unwrap_or(f64::NAN),
                m.check.crest_factor.unwrap_or(f64::NAN),
            ]);
        }
        for ((mut state, _), ch) in self.fatigue.into_iter().zip(&self.channels.fatigue) {
            let (sn, hist, sum) = (&ch.sn, &mut state.histogram, &mut state.damage_sum);
            state.counter.finish(|c: Cycle| {
                if sn.damages(c.amplitude) {
                    *sum += c.count * c.amplitude.powf(sn.k());
                }
                hist.add(&c);
            });
            let damage = state.damage_sum / sn.c();
            let mut v = Vec::with_capacity(ch.bins + 2);
            v.push(damage / (state.samples as f64 * self.dt_s));
            v.extend_from_slice(state.histogram.counts());
            v.push(state.histogram.overflow());
            out.push(v);
        }
        Ok(out)
    }
}
