//! The per-shard accumulators of a run, typed: what each shard stores per output so that the statistics can
//! be finished (and an interrupted run resumed) without raw data. The layout of every accumulator vector
//! lives here, in one `encode` and one `decode`.
//!
//! # Layout (per simulated output)
//! * `<output>:moments`, length 2·shard_size: the per-realization time averages m_i of the zero-mean
//!   fluctuation, zero-padded to shard_size, then the time averages v_i of its square, zero-padded.
//! * `<output>:welch`, length bins + 2: Welch's periodogram sums per bin, then the number of segments and
//!   Welch's equivalent degrees of freedom ν.

use crate::error::{Error, Result};
use crate::estimate::WelchSums;

/// Per-realization time averages of one output over one shard.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Moments {
    /// m_i = (1/N) Σ_k y_k, one per realization of the shard.
    pub mean: Vec<f64>,
    /// v_i = (1/N) Σ_k y_k², one per realization of the shard.
    pub mean_square: Vec<f64>,
}

impl Moments {
    /// Name of the accumulator of `output`.
    pub fn name(output: &str) -> String {
        format!("{output}:moments")
    }

    /// Length of the stored vector for shards of up to `shard_size` realizations.
    pub fn len(shard_size: usize) -> usize {
        2 * shard_size
    }

    /// The stored vector (see the module docs).
    pub fn encode(&self, shard_size: usize) -> Vec<f64> {
        let mut v = vec![0.0; Moments::len(shard_size)];
        v[..self.mean.len()].copy_from_slice(&self.mean);
        v[shard_size..shard_size + self.mean_square.len()].copy_from_slice(&self.mean_square);
        v
    }

    /// Reads back the `rows` realizations of a shard.
    ///
    /// # Errors
    /// [`Error::Numerical`] for a vector of the wrong length (a damaged file).
    pub fn decode(data: &[f64], rows: usize, shard_size: usize) -> Result<Moments> {
        if data.len() != Moments::len(shard_size) || rows > shard_size {
            return Err(bad("moments", data.len(), Moments::len(shard_size)));
        }
        Ok(Moments {
            mean: data[..rows].to_vec(),
            mean_square: data[shard_size..shard_size + rows].to_vec(),
        })
    }
}

/// Welch sums of one output over one shard.
#[derive(Debug, Clone, PartialEq)]
pub struct WelchAccumulator(pub WelchSums);

impl WelchAccumulator {
    /// Name of the accumulator of `output`.
    pub fn name(output: &str) -> String {
        format!("{output}:welch")
    }

    /// Length of the stored vector for `bins` frequency bins.
    pub fn len(bins: usize) -> usize {
        bins + 2
    }

    /// The stored vector (see the module docs).
    pub fn encode(&self) -> Vec<f64> {
        let mut v = self.0.sum.clone();
        v.push(self.0.segments as f64);
        v.push(self.0.dof);
        v
    }

    /// Reads back a stored vector of `bins` bins.
    ///
    /// # Errors
    /// [`Error::Numerical`] for a vector of the wrong length (a damaged file).
    pub fn decode(data: &[f64], bins: usize) -> Result<WelchAccumulator> {
        if data.len() != WelchAccumulator::len(bins) {
            return Err(bad("welch", data.len(), WelchAccumulator::len(bins)));
        }
        Ok(WelchAccumulator(WelchSums {
            sum: data[..bins].to_vec(),
            segments: data[bins] as u64,
            dof: data[bins + 1],
        }))
    }
}

fn bad(what: &str, got: usize, want: usize) -> Error {
    Error::Numerical {
        what: format!("reading the {what} accumulator"),
        reason: format!("stored length {got}, expected {want}: the run file is damaged"),
    }
}

/// The `(name, length)` of every accumulator of a run, in storage order: per output its moments, then its
/// Welch sums.
pub fn layout(outputs: &[&str], shard_size: usize, bins: usize) -> Vec<(String, usize)> {
    outputs
        .iter()
        .flat_map(|o| {
            [
                (Moments::name(o), Moments::len(shard_size)),
                (WelchAccumulator::name(o), WelchAccumulator::len(bins)),
            ]
        })
        .collect()
}
