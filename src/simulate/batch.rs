//! Batches of realizations in parallel, each from its own random stream, mergeable shard by shard.

use super::normal_lanes::LANES;
use super::rng::stream;
use crate::error::{Error, Result};
use rand::rngs::Xoshiro256PlusPlus;
use rayon::prelude::*;
use std::ops::Range;

/// The per-realization results of realizations [start, start + len) of one seed, in realization order.
///
/// # Formula
/// Realization i uses only [`stream`]`(seed, i)`, so its result does not depend on which shard or thread
/// computed it. Shards of the same seed merge by concatenation in realization order; any statistic then
/// folded over [`Shard::results`] in that order (sums in a fixed order) is bit-identical for any number of
/// threads and any split into shards.
///
/// # Errors
/// [`Shard::merge`] rejects shards of different seeds or non-adjacent ranges.
///
/// # Examples
/// ```
/// use stochvib::simulate::{run_batch, Shard, standard_normal};
/// let f = |_: &mut (), _i: u64, rng: &mut _| standard_normal(rng);
/// let whole = run_batch(5, 0..8, || (), f);
/// let a = run_batch(5, 0..3, || (), f);
/// let b = run_batch(5, 3..8, || (), f);
/// assert_eq!(Shard::merge_all(vec![b, a]).unwrap().results(), whole.results());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Shard<T> {
    seed: u64,
    start: u64,
    results: Vec<T>,
}

impl<T> Shard<T> {
    /// Wraps per-realization results of realizations [start, start + results.len()) of `seed`.
    pub fn new(seed: u64, start: u64, results: Vec<T>) -> Self {
        Shard { seed, start, results }
    }
    /// The seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }
    /// Realization indices covered.
    pub fn range(&self) -> Range<u64> {
        self.start..self.start + self.results.len() as u64
    }
    /// Per-realization results in realization order.
    pub fn results(&self) -> &[T] {
        &self.results
    }
    /// Consumes the shard, returning the results.
    pub fn into_results(self) -> Vec<T> {
        self.results
    }

    /// Appends `next`, which must start where `self` ends (same seed).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn merge(mut self, next: Shard<T>) -> Result<Shard<T>> {
        if next.seed != self.seed {
            return Err(Error::invalid(
                "shard seed",
                next.seed,
                format!("cannot merge with a shard of seed {}", self.seed),
            ));
        }
        if next.start != self.range().end {
            return Err(Error::invalid(
                "shard range",
                format!("{:?}", next.range()),
                format!("must start where the previous shard {:?} ends", self.range()),
            ));
        }
        self.results.extend(next.results);
        Ok(self)
    }

    /// Merges shards given in any order into one (sorted by start; they must tile a range without gaps or
    /// overlaps).
    ///
    /// # Errors
    /// No shards; different seeds; gaps or overlaps.
    pub fn merge_all(mut shards: Vec<Shard<T>>) -> Result<Shard<T>> {
        shards.sort_by_key(|s| s.start);
        let mut it = shards.into_iter();
        let first = it
            .next()
            .ok_or_else(|| Error::invalid("shards", "[]", "need at least one shard"))?;
        it.try_fold(first, |acc, s| acc.merge(s))
    }
}

/// Runs realizations `range` of `seed` in parallel on the current rayon pool.
///
/// # Formula
/// result_i = f(state, i, stream(seed, i)) for i in `range`, collected in realization order. `init`
/// creates per-task working memory (FFT scratch, buffers) that `f` may reuse; `f` must overwrite whatever it
/// reads from it, so that results do not depend on which realizations shared a scratch.
///
/// Use `rayon::ThreadPoolBuilder::new().num_threads(k).build()?.install(|| run_batch(...))` to choose
/// the thread count.
///
/// # Examples
/// ```
/// use stochvib::simulate::{run_batch, standard_normal};
/// let s = run_batch(1, 10..20, || (), |_, _, rng| standard_normal(rng));
/// assert_eq!(s.range(), 10..20);
/// ```
pub fn run_batch<T, S, I, F>(seed: u64, range: Range<u64>, init: I, f: F) -> Shard<T>
where
    T: Send,
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, u64, &mut Xoshiro256PlusPlus) -> T + Sync + Send,
{
    let start = range.start;
    let len = range.end.saturating_sub(range.start) as usize;
    let results: Vec<T> = (0..len)
        .into_par_iter()
        .map_init(init, |state, k| {
            let i = start + k as u64;
            let mut rng = stream(seed, i);
            f(state, i, &mut rng)
        })
        .collect();
    Shard::new(seed, start, results)
}

/// Runs realizations `range` of `seed` in groups of [`LANES`] consecutive realizations, the groups in
/// parallel on the current rayon pool (for lockstep realizations, e.g. [`GaussMarkovLanes`]).
///
/// # Formula
/// The groups are `start + g·LANES .. min(start + (g + 1)·LANES, end)` (only the last one may be short);
/// `f(state, group)` returns the results of the group's realizations in realization order, each from its
/// own stream (seed, i) alone, so that, as for [`run_batch`], a result does not depend on the grouping, the
/// threads or the shards. `init` as for [`run_batch`].
///
/// # Errors
/// The first error of `f`, in group order.
///
/// # Panics
/// When `f` returns a number of results other than the size of its group (a programming error).
///
/// # Examples
/// ```
/// use stochvib::simulate::{run_batch, run_batch_groups, standard_normal, stream};
/// let g = run_batch_groups(5, 3..20, || (), |_, group| {
///     Ok::<_, ()>(group.map(|i| standard_normal(&mut stream(5, i))).collect())
/// })
/// .unwrap();
/// assert_eq!(g, run_batch(5, 3..20, || (), |_, _, rng| standard_normal(rng)));
/// ```
///
/// [`GaussMarkovLanes`]: super::GaussMarkovLanes
pub fn run_batch_groups<T, E, S, I, F>(seed: u64, range: Range<u64>, init: I, f: F) -> std::result::Result<Shard<T>, E>
where
    T: Send,
    E: Send,
    I: Fn() -> S + Sync + Send,
    F: Fn(&mut S, Range<u64>) -> std::result::Result<Vec<T>, E> + Sync + Send,
{
    let (start, end) = (range.start, range.end.max(range.start));
    let lanes = LANES as u64;
    let groups: Vec<Vec<T>> = (0..(end - start).div_ceil(lanes))
        .into_par_iter()
        .map_init(init, |state, g| {
            let first = start + g * lanes;
            let group = first..(first + lanes).min(end);
            let len = group.end - group.start;
            let results = f(state, group)?;
            assert_eq!(results.len() as u64, len, "one result per realization of the group");
            Ok(results)
        })
        .collect::<std::result::Result<_, E>>()?;
    Ok(Shard::new(seed, start, groups.into_iter().flatten().collect()))
}
