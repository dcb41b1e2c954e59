//! The statistics of one realization of route 2, accumulated sample by sample in time order.
//!
//! # Formula
//! For output y with reference c (route 1's mean), over the N recorded samples of duration T = NΔt:
//! * the sums S_p = Σ (y_k − c)^p, p = 1…4, in time order from −0.0 (S₁, S₂ are the standard moments
//!   accumulator of a linear run: the time averages m = S₁/N, v = S₂/N);
//! * mean μ̂ = c + S₁/N; variance σ̂² = S₂/N − (S₁/N)²; the central fourth moment
//!   μ̂₄ = S₄/N − 4 m S₃/N + 6 m² S₂/N − 3 m⁴ (m = S₁/N), for the pooled kurtosis ([`super::stats`]);
//! * max |y|; the up-crossings of every level a (y_{k−1} < a ≤ y_k) per second, count/T;
//! * a histogram of y on fixed bins (with an underflow and an overflow count);
//! * for an element with a regime (a stop in contact, a tyre off the road): the fraction of samples in the
//!   regime and the entries into it per second.

use crate::linalg::vmath::SHIFT;

/// The statistics of one output over one realization, as the records leave them (see [`OutputRecords`]).
#[derive(Debug, Clone)]
pub(crate) struct OutputRecord {
    centre: f64,
    pub(crate) s: [f64; 4],
    max_abs: f64,
    counts: Vec<u64>,
    /// bins + 2: underflow, the bins, overflow.
    pub(crate) hist: Vec<f64>,
    n: usize,
}

impl OutputRecord {
    /// The realization's values: [mean, variance, central fourth moment, max |y|, rate of each level...]
    /// (T = recorded duration, s).
    pub(crate) fn values(&self, duration: f64) -> Vec<f64> {
        let (m, n) = (self.s[0] / self.n as f64, self.n as f64);
        let var = self.s[1] / n - m * m;
        let mu4 = self.s[3] / n - 4.0 * m * self.s[2] / n + 6.0 * m * m * self.s[1] / n - 3.0 * m.powi(4);
        let mut v = vec![self.centre + m, var, mu4, self.max_abs];
        v.extend(self.counts.iter().map(|c| *c as f64 / duration));
        v
    }

    /// (time average of y − c, of (y − c)²): the standard moments accumulator.
    pub(crate) fn moments(&self) -> (f64, f64) {
        (self.s[0] / self.n as f64, self.s[1] / self.n as f64)
    }

    /// (mean, σ) of the record.
    pub(crate) fn mean_sigma(&self) -> (f64, f64) {
        let v = self.values(1.0);
        (v[0], v[1].max(0.0).sqrt())
    }
}

/// The running statistics of one output of L realizations stepped in lockstep, every accumulator an
/// array over the lanes (structure of arrays): the sums, the maximum and the level crossings of all lanes
/// update in vector operations without branches, and so do the histogram's t = (y − lo)/w (a division
/// per lane, as a lone realization divides: a precomputed reciprocal would move samples at the bin
/// edges) and its slot ([`slots`]); only the histogram's increment is a store per lane. Lane l does
/// exactly the arithmetic of a lone realization, in the same order.
#[derive(Debug, Clone)]
pub(crate) struct OutputRecords<const L: usize> {
    centre: f64,
    s: [[f64; L]; 4],
    max_abs: [f64; L],
    levels: Vec<f64>,
    counts: Vec<[u64; L]>,
    /// The previous sample of every lane (from the second sample on).
    prev: [f64; L],
    started: bool,
    hist_lo: f64,
    hist_width: f64,
    /// The number of bins B, as f64 (exact).
    bins: f64,
    /// The counts of every lane, lane after lane, B + 2 slots each (underflow, the bins, overflow).
    hist: Vec<u64>,
    /// The slot of every lane's last sample: [`slots`] stores them as one lane array, which the compiler
    /// then computes in vector operations (it does not vectorise values that only feed addresses).
    slot: [usize; L],
    n: usize,
}

impl<const L: usize> OutputRecords<L> {
    pub(crate) fn new(centre: f64, levels: &[f64], hist_lo: f64, hist_width: f64, bins: usize) -> Self {
        OutputRecords {
            centre,
            s: [[-0.0; L]; 4],
            max_abs: [0.0; L],
            levels: levels.to_vec(),
            counts: vec![[0; L]; levels.len()],
            prev: [0.0; L],
            started: false,
            hist_lo,
            hist_width,
            bins: bins as f64,
            hist: vec![0; L * (bins + 2)],
            slot: [0; L],
            n: 0,
        }
    }

    /// Adds sample y of every lane; returns y − c (the values for the Welch estimate and the moments).
    /// Every update works on local lane arrays (the record's own heap arrays could alias each other as
    /// far as the compiler knows, which kept it from vectorising across the lanes).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub(crate) fn push(&mut self, y: &[f64; L]) -> [f64; L] {
        let y = *y;
        let mut d = [0.0; L];
        for l in 0..L {
            d[l] = y[l] - self.centre;
            let d2 = d[l] * d[l];
            self.s[0][l] += d[l];
            self.s[1][l] += d2;
            self.s[2][l] += d2 * d[l];
            self.s[3][l] += d2 * d2;
            self.max_abs[l] = self.max_abs[l].max(y[l].abs());
        }
        if self.started {
            let prev = self.prev;
            for (&a, c) in self.levels.iter().zip(self.counts.iter_mut()) {
                let mut up = *c;
                for l in 0..L {
                    up[l] += u64::from((prev[l] < a) & (y[l] >= a));
                }
                *c = up;
            }
        }
        self.prev = y;
        self.started = true;
        let mut t = [0.0; L];
        for l in 0..L {
            t[l] = (y[l] - self.hist_lo) / self.hist_width;
        }
        slots(&t, self.bins, &mut self.slot);
        let stride = self.hist.len() / L;
        for (l, s) in self.slot.iter().enumerate() {
            self.hist[l * stride + s] += 1;
        }
        self.n += 1;
        d
    }

    /// The statistics of lane l.
    pub(crate) fn lane(&self, l: usize) -> OutputRecord {
        let stride = self.hist.len() / L;
        OutputRecord {
            centre: self.centre,
            s: self.s.map(|s| s[l]),
            max_abs: self.max_abs[l],
            counts: self.counts.iter().map(|c| c[l]).collect(),
            // counts below 2⁵³: exactly the sums of 1.0 that a lone realization's histogram holds
            hist: self.hist[l * stride..(l + 1) * stride]
                .iter()
                .map(|&c| c as f64)
                .collect(),
            n: self.n,
        }
    }
}

/// The slot of t = (y − lo)/w in a histogram of `bins` bins with an underflow (slot 0) and an overflow
/// (slot bins + 1): ⌊t⌋ + 1, clamped. Without a floor (a libm call on baseline x86-64): ⌊t⌋ < 0 ⇔ t < 0,
/// ⌊t⌋ ≥ B ⇔ t ≥ B for the integer B = bins, and for 0 ≤ t < B the truncation `t as usize` is ⌊t⌋; NaN
/// goes to the underflow. The scalar form of [`slots`], and the tests' oracle for it.
#[cfg(test)]
fn bin(t: f64, bins: usize) -> usize {
    if t.is_nan() || t < 0.0 {
        0
    } else if t >= bins as f64 {
        bins + 1
    } else {
        t as usize + 1
    }
}

/// [`bin`] of every lane into `s`, as lane arrays (no branch and no float-to-integer conversion, neither of
/// which vectorises across the lanes on AVX2): with B = `bins` (an integer, as f64), c = max(t, −1) then
/// min(c, B) (NaN → −1, as `f64::max` ignores NaN) has ⌊c⌋ = −1 for t < 0 (−0 included: ⌊−0⌋ = 0 as for
/// +0), ⌊c⌋ = ⌊t⌋ for 0 ≤ t < B and ⌊c⌋ = B for t ≥ B, so ⌊c⌋ + 1 = `bin(t, B)`; the sum c + S with
/// S = 1.5·2⁵² ([`SHIFT`]) holds the integer n nearest to c in its low mantissa bits (exact for
/// |c| < 2⁵¹), and ⌊c⌋ = n − 1 where n > c, n otherwise.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
fn slots<const L: usize>(t: &[f64; L], bins: f64, s: &mut [usize; L]) {
    for l in 0..L {
        let c = t[l].max(-1.0).min(bins);
        let k = c + SHIFT;
        let up = u64::from(k - SHIFT > c);
        s[l] = k
            .to_bits()
            .wrapping_sub(SHIFT.to_bits())
            .wrapping_add(1)
            .wrapping_sub(up) as usize;
    }
}

/// The regime of one element over a realization.
#[derive(Debug, Clone, Default)]
pub(crate) struct RegimeRecord {
    engaged: u64,
    entries: u64,
    n: u64,
}

impl RegimeRecord {
    /// (fraction of samples engaged, entries per second).
    pub(crate) fn values(&self, duration: f64) -> (f64, f64) {
        (self.engaged as f64 / self.n as f64, self.entries as f64 / duration)
    }
}

/// The regime of one element over L realizations in lockstep: counts per lane, updated without branches.
#[derive(Debug, Clone)]
pub(crate) struct RegimeRecords<const L: usize> {
    engaged: [u64; L],
    entries: [u64; L],
    /// 1 where the lane was engaged at the previous sample, else 0.
    prev: [u64; L],
    started: bool,
    n: u64,
}

impl<const L: usize> Default for RegimeRecords<L> {
    fn default() -> Self {
        RegimeRecords {
            engaged: [0; L],
            entries: [0; L],
            prev: [0; L],
            started: false,
            n: 0,
        }
    }
}

impl<const L: usize> RegimeRecords<L> {
    /// Adds whether every lane is in the regime (an entry: engaged after a sample that was not), as
    /// integer lane arrays (0 or 1 per lane).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub(crate) fn push(&mut self, engaged: &[bool; L]) {
        let on = engaged.map(u64::from);
        for l in 0..L {
            self.engaged[l] += on[l];
        }
        if self.started {
            for l in 0..L {
                self.entries[l] += on[l] & !self.prev[l];
            }
        }
        self.prev = on;
        self.started = true;
        self.n += 1;
    }

    /// The regime of lane l.
    pub(crate) fn lane(&self, l: usize) -> RegimeRecord {
        RegimeRecord {
            engaged: self.engaged[l],
            entries: self.entries[l],
            n: self.n,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{bin, slots, OutputRecords, RegimeRecords};

    /// The slot by the floor, as the histogram counted before [`bin`] (the reference).
    fn by_floor(t: f64, bins: usize) -> usize {
        let b = t.floor();
        if b < 0.0 || b.is_nan() {
            0
        } else if b >= bins as f64 {
            bins + 1
        } else {
            b as usize + 1
        }
    }

    /// Arguments t of a histogram of `bins` bins: NaN, ±∞, ±0, the smallest normal, ±10³⁰⁰, every integer
    /// from −3 to bins + 3 with its neighbours and midpoint, and 10⁵ values in [−10, 130).
    fn slot_arguments(bins: usize) -> Vec<f64> {
        let mut ts = vec![
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            1e300,
            -1e300,
        ];
        for k in -3..=bins as i64 + 3 {
            let x = k as f64;
            ts.extend([x, x.next_up(), x.next_down(), x + 0.5]);
        }
        let mut u = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..100_000 {
            u = u
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ts.push((u >> 11) as f64 / (1u64 << 53) as f64 * 140.0 - 10.0);
        }
        ts
    }

    #[test]
    fn bin_is_the_floor_slot_at_every_edge() {
        let bins = 120;
        for t in slot_arguments(bins) {
            assert_eq!(bin(t, bins), by_floor(t, bins), "t = {t:e}");
        }
    }

    /// Every window of 8 consecutive arguments of `ts` (cyclically): each argument in every lane.
    fn windows8(ts: &[f64]) -> impl Iterator<Item = [f64; 8]> + '_ {
        (0..ts.len()).map(|k| std::array::from_fn(|l| ts[(k + l) % ts.len()]))
    }

    /// [`slots`] of 8 lanes and of 1 over every window of [`slot_arguments`], as compiled by `vmath::run`
    /// for the widest instruction set of the CPU (the code of the drive loop).
    struct Slots<'a> {
        ts: &'a [f64],
        eight: Vec<[usize; 8]>,
        one: Vec<usize>,
    }

    impl crate::linalg::vmath::Task for Slots<'_> {
        #[inline(always)]
        fn run(&mut self) {
            for t in windows8(self.ts) {
                let (mut s8, mut s1) = ([0; 8], [0; 1]);
                slots(&t, 120.0, &mut s8);
                slots(&[t[0]], 120.0, &mut s1);
                self.eight.push(s8);
                self.one.push(s1[0]);
            }
        }
    }

    /// The lane arrays of [`slots`] are the slots of [`bin`] lane by lane, at every argument of
    /// [`slot_arguments`] in every lane, for 8 lanes and for 1, compiled for the baseline and (through
    /// `vmath::run`) for the widest instruction set of the CPU.
    #[test]
    fn slots_of_the_lanes_are_the_bins() {
        let bins = 120;
        let ts = slot_arguments(bins);
        let mut wide = Slots {
            ts: &ts,
            eight: Vec::new(),
            one: Vec::new(),
        };
        crate::linalg::vmath::run(&mut wide);
        for (k, t) in windows8(&ts).enumerate() {
            let want = t.map(|t| bin(t, bins));
            let mut s8 = [0; 8];
            slots(&t, bins as f64, &mut s8);
            assert_eq!((s8, wide.eight[k]), (want, want), "{t:?}");
            assert_eq!(wide.one[k], want[0], "t = {:e}", t[0]);
        }
    }

    /// Deterministic samples in [−3, 3) (a linear congruential generator).
    fn samples(seed: u64, n: usize) -> Vec<f64> {
        let mut u = seed;
        (0..n)
            .map(|_| {
                u = u
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (u >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
            })
            .collect()
    }

    /// Every lane of the records of 4 realizations in lockstep against the definitions evaluated for one
    /// realization alone (sums in time order from −0, up-crossings p < a ≤ y, the slot by the floor,
    /// entries into y > 1): equal to the bit.
    #[test]
    #[allow(clippy::needless_range_loop)] // sample k of every lane at once
    fn lanes_give_the_bits_of_lone_realizations() {
        let (levels, lo, w, bins, c) = ([-0.5, 0.0, 0.7], -2.0, 0.05, 80, 0.1);
        let ys: Vec<Vec<f64>> = (0..4).map(|l| samples(11 + l, 2000)).collect();
        let mut rec = OutputRecords::<4>::new(c, &levels, lo, w, bins);
        let mut reg = RegimeRecords::<4>::default();
        for k in 0..2000 {
            let y: [f64; 4] = std::array::from_fn(|l| ys[l][k]);
            rec.push(&y);
            reg.push(&y.map(|v| v > 1.0));
        }
        for (l, y) in ys.iter().enumerate() {
            let mut s = [-0.0f64; 4];
            let mut hist = vec![0.0; bins + 2];
            for v in y {
                let d = v - c;
                (s[0], s[1], s[2], s[3]) = (s[0] + d, s[1] + d * d, s[2] + d * d * d, s[3] + d * d * (d * d));
                hist[by_floor((v - lo) / w, bins)] += 1.0;
            }
            let got = rec.lane(l);
            assert_eq!(got.s.map(f64::to_bits), s.map(f64::to_bits), "lane {l}");
            assert_eq!(got.hist, hist, "lane {l}");
            let up = |a: f64| y.windows(2).filter(|p| p[0] < a && p[1] >= a).count() as f64;
            let max = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let v = got.values(1.0);
            assert_eq!(v[3].to_bits(), max.to_bits());
            assert_eq!(&v[4..], &levels.map(up)[..]);
            let on: Vec<bool> = y.iter().map(|v| *v > 1.0).collect();
            let entries = on.windows(2).filter(|p| p[1] && !p[0]).count() as f64;
            let frac = on.iter().filter(|b| **b).count() as f64 / 2000.0;
            assert_eq!(reg.lane(l).values(1.0), (frac, entries));
        }
    }
}
