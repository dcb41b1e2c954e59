//! How many pending shards of a run file are realized at once: with one shard at a time the threads idle at
//! every shard's end (a shard of 50 realizations is 7 lockstep groups of at most 8, which 2 threads share
//! 4 : 3, and the shard's write runs alone), so the Monte Carlo runs realize a window of consecutive pending
//! shards together, their realizations shared out over the threads as one batch, and then write the shards
//! one by one in order. Every realization's result depends only on its own random stream, not on its group,
//! shard or thread, so the files are the same bit for bit; a killed run loses the window it was computing
//! (each shard is still written whole or not at all).

use std::ops::Range;

/// Lockstep groups each thread should get from one window ([`shard_window`]).
pub(crate) const GROUPS_PER_THREAD: usize = 16;

/// The most bytes of realized results one window holds before its shards are written.
pub(crate) const WINDOW_BYTES: usize = 64 << 20;

/// The number W of consecutive pending shards realized at once.
///
/// # Formula
/// W = max(1, min(⌈P·g·G / S⌉, ⌊B / (S·b)⌋)) for P ≥ 2 threads, shards of S realizations, lockstep groups of
/// g realizations, G = [`GROUPS_PER_THREAD`], B = [`WINDOW_BYTES`] and b the bytes of one realization's
/// results held until its shard is written: each thread gets about G groups and a window holds at most B.
/// W = 1 for one thread (nothing to balance, and a killed run then loses one shard's work at most).
pub(crate) fn shard_window(threads: usize, shard_size: usize, group: usize, bytes: usize) -> usize {
    if threads < 2 || shard_size == 0 {
        return 1;
    }
    let balanced = (threads * group.max(1) * GROUPS_PER_THREAD).div_ceil(shard_size);
    let affordable = WINDOW_BYTES / shard_size.saturating_mul(bytes.max(1));
    balanced.min(affordable).max(1)
}

/// The maximal runs of consecutive realizations of `ranges` (increasing, disjoint), in order: adjacent
/// ranges joined, empty ones dropped.
pub(crate) fn contiguous_runs(ranges: &[Range<u64>]) -> Vec<Range<u64>> {
    let mut runs: Vec<Range<u64>> = Vec::with_capacity(ranges.len());
    for r in ranges.iter().filter(|r| r.start < r.end) {
        match runs.last_mut() {
            Some(last) if last.end == r.start => last.end = r.end,
            _ => runs.push(r.clone()),
        }
    }
    runs
}

/// `results` (the realizations of `ranges` in order) cut into one vector per range.
///
/// # Panics
/// When `results` does not hold one result per realization of `ranges` (a programming error).
pub(crate) fn split_by_range<T>(results: Vec<T>, ranges: &[Range<u64>]) -> Vec<Vec<T>> {
    let total: u64 = ranges.iter().map(|r| r.end.saturating_sub(r.start)).sum();
    assert_eq!(results.len() as u64, total, "one result per realization of the ranges");
    let mut it = results.into_iter();
    ranges
        .iter()
        .map(|r| it.by_ref().take(r.end.saturating_sub(r.start) as usize).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{contiguous_runs, shard_window, split_by_range, GROUPS_PER_THREAD, WINDOW_BYTES};

    /// W = max(1, min(⌈P·g·G/S⌉, ⌊B/(S·b)⌋)) worked by hand for g = 8, G = 16, B = 64 MiB: one thread keeps
    /// one shard at a time; 2 threads and shards of 50 realizations of 15 KiB take ⌈256/50⌉ = 6 shards,
    /// 4 threads ⌈512/50⌉ = 11; shards of 1 take 256; raw samples of 4 signals × 11 064 steps (354 048 +
    /// 15 360 bytes a realization) cap shards of 50 at ⌊67 108 864/18 470 400⌋ = 3, and 10⁶-step records
    /// (32 MB a realization) at 1.
    #[test]
    fn the_window_balances_the_threads_within_its_memory() {
        assert_eq!((GROUPS_PER_THREAD, WINDOW_BYTES), (16, 64 << 20));
        let summary = 15 << 10;
        assert_eq!(shard_window(1, 50, 8, summary), 1);
        assert_eq!(shard_window(2, 0, 8, summary), 1);
        assert_eq!(shard_window(2, 50, 8, summary), 6);
        assert_eq!(shard_window(4, 50, 8, summary), 11);
        assert_eq!(shard_window(2, 1, 8, summary), 256);
        assert_eq!(shard_window(2, 50, 8, summary + 4 * 11_064 * 8), 3);
        assert_eq!(shard_window(2, 50, 8, summary + 4 * 1_000_000 * 8), 1);
        assert_eq!(shard_window(2, usize::MAX, 8, 1), 1);
    }

    /// Adjacent ranges join into one run (their realizations may share a lockstep group), a gap does not,
    /// an empty range disappears.
    #[test]
    fn contiguous_runs_join_adjacent_ranges_only() {
        assert_eq!(contiguous_runs(&[]), vec![]);
        assert_eq!(contiguous_runs(&[0..50, 50..100, 100..112]), vec![0..112]);
        assert_eq!(contiguous_runs(&[0..50, 100..150, 150..160]), vec![0..50, 100..160]);
        assert_eq!(contiguous_runs(&[3..3, 3..7, 7..7, 9..10]), vec![3..7, 9..10]);
    }

    /// The results of 0..3, 3..3, 10..14 in order are cut 3, 0, 4.
    #[test]
    fn results_are_cut_by_range_in_order() {
        let cut = split_by_range((0..7).collect(), &[0..3, 3..3, 10..14]);
        assert_eq!(cut, vec![vec![0, 1, 2], vec![], vec![3, 4, 5, 6]]);
    }
}
