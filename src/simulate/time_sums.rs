//! The running time sums Σy and Σy² of one record, from which a run stores every realization's time
//! averages m_i and v_i, in one fixed order whatever the blocks the record arrives in.
//!
//! # Formula
//! Sample k of the record (k = 0, 1, …, counted from the record's start) goes to partial sum k mod
//! [`TIME_SUM_WAYS`]; each partial sum adds its samples in time order starting from −0.0 (as
//! `Iterator::sum` of f64 folds), and the totals are the partial sums added as a balanced tree:
//!
//! Σy = ((p₀ + p₁) + (p₂ + p₃)) + ((p₄ + p₅) + (p₆ + p₇)),   p_w = −0.0 + y_w + y_{w+8} + y_{w+16} + …
//!
//! and the same for Σy² with the squares y_k·y_k (rounded, no fused multiply-add). A record cut into blocks
//! of any lengths gives the same bits, and so does [`TimeSumLanes`], which keeps the sums of
//! [`LANES`] realizations stepped side by side.
//!
//! Eight chains instead of one: a single running sum is a chain of N dependent additions (3–4 cycles each
//! on current x86 processors), ≈ 15 % of a 2¹⁶-sample realization of the one-FFT route; eight independent
//! chains are added a vector at a time (one 512-bit addition per eight samples and sum, four 128-bit ones
//! on baseline x86-64), without waiting for each other.
//! The rounding error is also smaller: at most about (N/8 + 3)·ε·Σ|y| instead of N·ε·Σ|y|
//! (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., 2002, §4.2, eq. 4.4 for a recursive
//! sum; the tree adds log₂ 8 = 3 levels).

use super::LANES;

/// Partial sums of a record's time sums ([`TimeSums`]); sample k goes to partial sum k mod this.
pub const TIME_SUM_WAYS: usize = 8;

/// Σy and Σy² of one record, in the order of the module docs.
///
/// # Examples
/// ```
/// use stochvib::simulate::TimeSums;
/// let y: Vec<f64> = (0..21).map(|k| (k as f64 * 0.7).sin()).collect();
/// let mut whole = TimeSums::new();
/// whole.push(&y);
/// let mut blocks = TimeSums::new();
/// for b in y.chunks(5) {
///     blocks.push(b);
/// }
/// assert_eq!(whole.totals(), blocks.totals()); // the same bits for any cut into blocks
/// assert_eq!(whole.count(), 21);
/// let (s1, s2) = whole.totals();
/// assert!((s1 - y.iter().sum::<f64>()).abs() < 1e-13);
/// assert!((s2 - y.iter().map(|v| v * v).sum::<f64>()).abs() < 1e-13);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeSums {
    s1: [f64; TIME_SUM_WAYS],
    s2: [f64; TIME_SUM_WAYS],
    count: usize,
}

impl Default for TimeSums {
    fn default() -> Self {
        TimeSums::new()
    }
}

impl TimeSums {
    /// Empty sums (every partial sum −0.0).
    pub fn new() -> TimeSums {
        TimeSums {
            s1: [-0.0; TIME_SUM_WAYS],
            s2: [-0.0; TIME_SUM_WAYS],
            count: 0,
        }
    }

    /// The next samples of the record, in time order.
    #[inline]
    pub fn push(&mut self, ys: &[f64]) {
        let head = ((TIME_SUM_WAYS - self.count % TIME_SUM_WAYS) % TIME_SUM_WAYS).min(ys.len());
        let (first, rest) = ys.split_at(head);
        self.push_one_by_one(first);
        let mut rows = rest.chunks_exact(TIME_SUM_WAYS);
        // local copies: the compiler then keeps the partial sums in vector registers for the whole loop
        let (mut s1, mut s2) = (self.s1, self.s2);
        for row in &mut rows {
            for w in 0..TIME_SUM_WAYS {
                s1[w] += row[w];
                s2[w] += row[w] * row[w];
            }
        }
        (self.s1, self.s2) = (s1, s2);
        self.count += rest.len() - rows.remainder().len();
        self.push_one_by_one(rows.remainder());
    }

    fn push_one_by_one(&mut self, ys: &[f64]) {
        for &y in ys {
            let w = self.count % TIME_SUM_WAYS;
            self.s1[w] += y;
            self.s2[w] += y * y;
            self.count += 1;
        }
    }

    /// Samples pushed so far.
    pub fn count(&self) -> usize {
        self.count
    }

    /// (Σy, Σy²) over the samples pushed so far.
    pub fn totals(&self) -> (f64, f64) {
        (tree(&self.s1), tree(&self.s2))
    }

    /// The time averages (Σy/N, Σy²/N) over the N samples pushed so far (NaN for none).
    pub fn averages(&self) -> (f64, f64) {
        let (s1, s2) = self.totals();
        let n = self.count as f64;
        (s1 / n, s2 / n)
    }
}

/// The partial sums added as a balanced tree (see the module docs).
#[inline]
fn tree(p: &[f64; TIME_SUM_WAYS]) -> f64 {
    ((p[0] + p[1]) + (p[2] + p[3])) + ((p[4] + p[5]) + (p[6] + p[7]))
}

/// The [`TimeSums`] of [`LANES`] records sampled side by side (one `[f64; LANES]` per sample, lane l the
/// sample of record l): every lane's sums have the bits of that record's [`TimeSums`] alone.
#[derive(Debug, Clone)]
pub struct TimeSumLanes {
    s1: [[f64; LANES]; TIME_SUM_WAYS],
    s2: [[f64; LANES]; TIME_SUM_WAYS],
    count: usize,
}

impl Default for TimeSumLanes {
    fn default() -> Self {
        TimeSumLanes::new()
    }
}

impl TimeSumLanes {
    /// Empty sums.
    pub fn new() -> TimeSumLanes {
        TimeSumLanes {
            s1: [[-0.0; LANES]; TIME_SUM_WAYS],
            s2: [[-0.0; LANES]; TIME_SUM_WAYS],
            count: 0,
        }
    }

    /// The next samples of the records, in time order (one `[f64; LANES]` per time step).
    #[inline]
    pub fn push(&mut self, ys: impl IntoIterator<Item = [f64; LANES]>) {
        for y in ys {
            let w = self.count % TIME_SUM_WAYS;
            let (s1, s2) = (&mut self.s1[w], &mut self.s2[w]);
            for l in 0..LANES {
                s1[l] += y[l];
                s2[l] += y[l] * y[l];
            }
            self.count += 1;
        }
    }

    /// The sums of lane l.
    ///
    /// # Panics
    /// For l ≥ [`LANES`].
    pub fn lane(&self, l: usize) -> TimeSums {
        TimeSums {
            s1: std::array::from_fn(|w| self.s1[w][l]),
            s2: std::array::from_fn(|w| self.s2[w][l]),
            count: self.count,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The oracle: the formula of the module docs written out sample by sample.
    fn by_formula(y: &[f64]) -> (f64, f64) {
        let mut p1 = [-0.0f64; TIME_SUM_WAYS];
        let mut p2 = [-0.0f64; TIME_SUM_WAYS];
        for (k, &v) in y.iter().enumerate() {
            p1[k % TIME_SUM_WAYS] += v;
            p2[k % TIME_SUM_WAYS] += v * v;
        }
        let t = |p: [f64; 8]| ((p[0] + p[1]) + (p[2] + p[3])) + ((p[4] + p[5]) + (p[6] + p[7]));
        (t(p1), t(p2))
    }

    fn record(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = crate::simulate::stream(seed, 0);
        let mut y = vec![0.0; n];
        crate::simulate::fill_standard_normal(&mut rng, &mut y);
        // magnitudes over 12 decades so that the order of the additions shows in the bits
        y.iter()
            .enumerate()
            .map(|(k, v)| v * 10f64.powi((k % 13) as i32 - 6))
            .collect()
    }

    #[test]
    fn blocks_of_any_lengths_give_the_bits_of_the_formula() {
        for n in [0, 1, 7, 8, 9, 63, 1000, 4099] {
            let y = record(n, n as u64);
            let want = by_formula(&y);
            for cut in [1, 2, 3, 5, 8, 13, 64, 4096] {
                let mut s = TimeSums::new();
                for b in y.chunks(cut) {
                    s.push(b);
                }
                assert_eq!(s.count(), n);
                let got = s.totals();
                assert_eq!(got.0.to_bits(), want.0.to_bits(), "Σy, n {n}, blocks of {cut}");
                assert_eq!(got.1.to_bits(), want.1.to_bits(), "Σy², n {n}, blocks of {cut}");
            }
        }
    }

    #[test]
    fn lanes_give_the_bits_of_each_record_alone() {
        let n = 1003;
        let records: Vec<Vec<f64>> = (0..LANES as u64).map(|l| record(n, 100 + l)).collect();
        let mut lanes = TimeSumLanes::new();
        for cut in [5usize, 8, 990] {
            let done = lanes.count;
            let end = (done + cut).min(n);
            lanes.push((done..end).map(|k| std::array::from_fn(|l| records[l][k])));
        }
        lanes.push((lanes.count..n).map(|k| std::array::from_fn(|l| records[l][k])));
        for (l, y) in records.iter().enumerate() {
            let mut alone = TimeSums::new();
            alone.push(y);
            let bits = |s: TimeSums| (s.s1.map(f64::to_bits), s.s2.map(f64::to_bits), s.count);
            assert_eq!(bits(lanes.lane(l)), bits(alone), "lane {l}");
        }
    }

    #[test]
    fn empty_sums_are_negative_zero_and_averages_nan() {
        let s = TimeSums::new();
        let (a, b) = s.totals();
        assert!(a == 0.0 && a.is_sign_negative() && b.is_sign_negative());
        assert!(s.averages().0.is_nan());
    }

    #[test]
    fn averages_match_a_compensated_sum() {
        // independent reference: Kahan–Babuška (Neumaier) summation, error O(ε) independent of N
        let y = record(1 << 14, 7);
        let neumaier = |it: &mut dyn Iterator<Item = f64>| {
            let (mut s, mut c) = (0.0f64, 0.0f64);
            for v in it {
                let t = s + v;
                c += if s.abs() >= v.abs() { (s - t) + v } else { (v - t) + s };
                s = t;
            }
            s + c
        };
        let mut s = TimeSums::new();
        s.push(&y);
        let (s1, s2) = s.totals();
        let abs1: f64 = y.iter().map(|v| v.abs()).sum();
        let abs2: f64 = y.iter().map(|v| v * v).sum();
        // Higham's bound for 8 recursive chains of N/8 and a tree of 3 levels: (N/8 + 3 + 1)·ε·Σ|y|
        let bound = |a: f64| ((y.len() / 8 + 4) as f64) * f64::EPSILON * a;
        assert!((s1 - neumaier(&mut y.iter().copied())).abs() <= bound(abs1));
        assert!((s2 - neumaier(&mut y.iter().map(|v| v * v))).abs() <= bound(abs2));
    }
}
