//! Rainflow cycle counting of a sampled signal (ASTM E1049-85 (reapproved 2017) §5.4.4), streaming in
//! chunks with O(residue) memory and O(n) time, and a range histogram of the counted cycles.
//!
//! # Algorithm
//! 1. **Turning points.** The first sample is a turning point (ASTM's starting point S); then each local
//!    extreme where the signal changes direction; the last extreme of the record is a turning point too
//!    (ASTM counts from the first to the last reversal). Repeated values are merged: a plateau (equal
//!    consecutive samples) is one point, at the index of its *first* sample; a plateau that continues in
//!    the same direction (a step) is not a turning point. A constant record has one turning point and
//!    no cycles.
//! 2. **Four-point rule** on the stack of turning points not yet counted (the *residue*): with the last
//!    four points a, b, c, d, if |c − b| ≤ |b − a| and |c − b| ≤ |d − c| the inner pair (b, c) is one full
//!    cycle of range |c − b|; b and c are removed and the test is repeated; otherwise the next turning
//!    point is read. Together with step 3 this gives the same cycles (range, mean, count) as the
//!    three-point algorithm of ASTM E1049-85 §5.4.4, which instead peels half cycles off the starting
//!    point as it goes: the integration tests check it against a plain transcription of §5.4.4 on
//!    random records, cycle by cycle (including the turning points' indices) for continuous values, and
//!    as totals per (range, mean) for integer values, where equal consecutive ranges let the two
//!    algorithms attribute a cycle to different, equal-valued turning points.
//! 3. **Residue.** At the end each pair of consecutive residue points is one half cycle (count 0.5), as
//!    in ASTM E1049-85 §5.4.4 step 6.
//!
//! Streaming: [`RainflowCounter::push`] takes the record in chunks of any size and carries the pending
//! extreme and the residue between chunks, so the cycles are exactly those of the one-shot count. Memory
//! is the residue, whose length is bounded by the number of distinct ranges it can hold (for a bounded
//! signal, a few dozen points in practice); time is O(n) (each turning point is pushed and removed at
//! most once).

use crate::error::{Error, Result};

/// One rainflow cycle (or half cycle) between two turning points.
///
/// # Formula
/// For turning points with values x_s (earlier) and x_e (later):
/// ```text
/// range ΔS = |x_e − x_s|,   amplitude S_a = ΔS/2,   mean S_m = (x_s + x_e)/2,   count ∈ {1, 0.5}
/// ```
/// in the unit of the signal.
///
/// # Errors
/// None (plain data).
///
/// # Examples
/// ```
/// use stochvib::fatigue::rainflow;
/// let c = rainflow(&[1.0, 4.0]).unwrap();
/// assert_eq!((c[0].range, c[0].amplitude, c[0].mean, c[0].count), (3.0, 1.5, 2.5, 0.5));
/// assert_eq!((c[0].start, c[0].end), (0, 1));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    /// Range ΔS = |x_e − x_s| (signal unit).
    pub range: f64,
    /// Amplitude S_a = ΔS/2 (signal unit).
    pub amplitude: f64,
    /// Mean (x_s + x_e)/2 (signal unit).
    pub mean: f64,
    /// 1.0 for a full cycle, 0.5 for a half cycle.
    pub count: f64,
    /// Sample index (in the whole stream) of the earlier turning point.
    pub start: usize,
    /// Sample index (in the whole stream) of the later turning point.
    pub end: usize,
}

impl Cycle {
    #[inline(always)]
    fn new(a: TurningPoint, b: TurningPoint, count: f64) -> Self {
        let range = (b.value - a.value).abs();
        Cycle {
            range,
            amplitude: 0.5 * range,
            mean: 0.5 * (a.value + b.value),
            count,
            start: a.index,
            end: b.index,
        }
    }

    /// Whether this is a half cycle (count 0.5).
    pub fn is_half(&self) -> bool {
        self.count == 0.5
    }
}

/// A turning point (peak or valley) of the record: its value and the index of its sample (the first
/// sample of a plateau).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurningPoint {
    /// Value (signal unit).
    pub value: f64,
    /// Sample index in the whole stream.
    pub index: usize,
}

/// Streaming rainflow counter: feed the record in chunks with [`RainflowCounter::push`], then call
/// [`RainflowCounter::finish`] to count the residue as half cycles.
///
/// # Formula
/// Turning points, four-point rule and residue as described in the [module docs](self) (ASTM E1049-85
/// (2017) §5.4.4). Every cycle is handed to the caller's sink as soon as it is counted, so counting
/// 10⁸ samples needs no storage beyond the residue.
///
/// # Errors
/// [`RainflowCounter::push`] rejects a chunk containing a non-finite sample (the chunk is then not
/// consumed at all, so the counter stays valid).
///
/// # Examples
/// ```
/// use stochvib::fatigue::{RainflowCounter, SnCurve};
/// // Streaming Miner damage of a long record read in chunks.
/// let sn = SnCurve { k: 3.0, c: 1e6, endurance_limit: None }.build().unwrap();
/// let mut damage = 0.0;
/// let mut counter = RainflowCounter::new();
/// let record = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0];
/// for chunk in record.chunks(4) {
///     counter.push(chunk, |c| damage += c.count * c.amplitude.powf(sn.k()) / sn.c()).unwrap();
/// }
/// counter.finish(|c| damage += c.count * c.amplitude.powf(sn.k()) / sn.c());
/// let all = stochvib::fatigue::rainflow(&record).unwrap();
/// assert!((damage - sn.damage_of_cycles(&all).unwrap()).abs() < 1e-18);
/// ```
#[derive(Debug, Clone, Default)]
pub struct RainflowCounter {
    /// Samples consumed so far (the stream index of the next sample).
    samples: usize,
    /// Direction of the current run: +1 rising, −1 falling, 0 not yet known.
    direction: i8,
    /// The extreme of the current run (the pending turning point), valid once `samples > 0`.
    pending: TurningPoint,
    /// Residue: turning points not yet counted.
    stack: Vec<TurningPoint>,
    turning_points: usize,
    full_cycles: usize,
}

impl Default for TurningPoint {
    fn default() -> Self {
        TurningPoint { value: 0.0, index: 0 }
    }
}

impl RainflowCounter {
    /// An empty counter.
    pub fn new() -> Self {
        Self::default()
    }

    /// Samples consumed so far.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Turning points found so far (not counting the pending extreme of the current run).
    pub fn turning_points(&self) -> usize {
        self.turning_points
    }

    /// Full cycles counted so far.
    pub fn full_cycles(&self) -> usize {
        self.full_cycles
    }

    /// The residue so far: turning points not yet closed into full cycles, in time order (without the
    /// pending extreme of the current run).
    pub fn residue(&self) -> &[TurningPoint] {
        &self.stack
    }

    /// Consumes the next chunk of the record, calling `sink` with every full cycle closed by it.
    ///
    /// # Formula
    /// See the [module docs](self): turning points, then the four-point rule
    /// |c − b| ≤ |b − a| ∧ |c − b| ≤ |d − c| ⇒ (b, c) is one full cycle.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `samples`, with the stream index and value of the first
    /// non-finite sample or one beyond [`MAX_ABS_SAMPLE`]; the chunk is then not consumed.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::RainflowCounter;
    /// let mut rc = RainflowCounter::new();
    /// let mut cycles = Vec::new();
    /// rc.push(&[0.0, 3.0, 1.0, 2.0, -1.0, 0.0], |c| cycles.push(c)).unwrap();
    /// // −1 becomes a turning point when the record turns up again: it closes the cycle 1 → 2.
    /// assert_eq!(cycles.len(), 1);
    /// assert_eq!((cycles[0].range, cycles[0].start, cycles[0].end), (1.0, 2, 3));
    /// assert!(rc.push(&[f64::NAN], |_| {}).is_err());
    /// ```
    pub fn push<F: FnMut(Cycle)>(&mut self, samples: &[f64], mut sink: F) -> Result<()> {
        check_finite(samples, self.samples)?;
        let base = self.samples;
        let mut rest = samples;
        let mut offset = 0usize;
        if self.samples == 0 {
            let Some((&x0, tail)) = rest.split_first() else {
                return Ok(());
            };
            // The first sample is ASTM's starting point: a turning point.
            let tp = TurningPoint { value: x0, index: 0 };
            self.push_turning_point(tp, &mut sink);
            self.pending = tp;
            self.direction = 0;
            rest = tail;
            offset = 1;
        }
        let mut cand = self.pending;
        let mut dir = self.direction;
        let mut j = 0usize;
        let n = rest.len();
        // Undetermined direction (only at the start, or on a constant record so far).
        while dir == 0 && j < n {
            let x = rest[j];
            if x > cand.value {
                dir = 1;
                cand = TurningPoint {
                    value: x,
                    index: base + offset + j,
                };
            } else if x < cand.value {
                dir = -1;
                cand = TurningPoint {
                    value: x,
                    index: base + offset + j,
                };
            }
            j += 1;
        }
        // Main loop: the pending extreme `cand` of a run in direction `dir`.
        while j < n {
            let x = rest[j];
            if dir > 0 {
                if x > cand.value {
                    cand = TurningPoint {
                        value: x,
                        index: base + offset + j,
                    };
                } else if x < cand.value {
                    self.push_turning_point(cand, &mut sink);
                    dir = -1;
                    cand = TurningPoint {
                        value: x,
                        index: base + offset + j,
                    };
                }
            } else if x < cand.value {
                cand = TurningPoint {
                    value: x,
                    index: base + offset + j,
                };
            } else if x > cand.value {
                self.push_turning_point(cand, &mut sink);
                dir = 1;
                cand = TurningPoint {
                    value: x,
                    index: base + offset + j,
                };
            }
            j += 1;
        }
        self.pending = cand;
        self.direction = dir;
        self.samples += samples.len();
        Ok(())
    }

    /// Ends the record: the last extreme becomes a turning point (possibly closing more full cycles),
    /// then every pair of consecutive residue points is counted as a half cycle, in time order. `sink`
    /// receives those cycles.
    ///
    /// # Formula
    /// Residue r₀, r₁, …, r_m ⇒ half cycles (r₀, r₁), (r₁, r₂), …, (r_{m−1}, r_m), count 0.5 each
    /// (ASTM E1049-85 §5.4.4 step 6).
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::RainflowCounter;
    /// let mut rc = RainflowCounter::new();
    /// rc.push(&[0.0, 1.0, 1.0, 3.0], |_| unreachable!()).unwrap();
    /// let mut halves = Vec::new();
    /// rc.finish(|c| halves.push(c));
    /// // The plateau at 1.0 continues upwards: one half cycle 0 → 3.
    /// assert_eq!(halves.len(), 1);
    /// assert_eq!((halves[0].range, halves[0].count, halves[0].end), (3.0, 0.5, 3));
    /// ```
    pub fn finish<F: FnMut(Cycle)>(mut self, mut sink: F) {
        if self.direction != 0 {
            let tp = self.pending;
            self.push_turning_point(tp, &mut sink);
        }
        for w in self.stack.windows(2) {
            sink(Cycle::new(w[0], w[1], 0.5));
        }
    }

    /// Adds a turning point to the residue and applies the four-point rule.
    #[inline(always)]
    fn push_turning_point<F: FnMut(Cycle)>(&mut self, tp: TurningPoint, sink: &mut F) {
        self.turning_points += 1;
        self.stack.push(tp);
        loop {
            let n = self.stack.len();
            if n < 4 {
                return;
            }
            let (a, b, c, d) = (
                self.stack[n - 4],
                self.stack[n - 3],
                self.stack[n - 2],
                self.stack[n - 1],
            );
            let inner = (c.value - b.value).abs();
            if inner <= (b.value - a.value).abs() && inner <= (d.value - c.value).abs() {
                sink(Cycle::new(b, c, 1.0));
                self.full_cycles += 1;
                self.stack[n - 3] = d;
                self.stack.truncate(n - 2);
            } else {
                return;
            }
        }
    }
}

/// The largest |sample| counted: half of f64's largest number, so that the range of any two samples,
/// |a − b| ≤ 2·(f64::MAX/2), is a finite number (1e308 and −1e308 gave a range of `inf`).
pub const MAX_ABS_SAMPLE: f64 = f64::MAX / 2.0;

/// Checks every sample is finite and at most [`MAX_ABS_SAMPLE`] in magnitude; the error names the first
/// offending stream index.
fn check_finite(samples: &[f64], base: usize) -> Result<()> {
    // Branch-free scan in blocks (vectorises), then locate the culprit only on failure.
    const BLOCK: usize = 256;
    let countable = |x: &f64| x.abs() <= MAX_ABS_SAMPLE;
    for (b, block) in samples.chunks(BLOCK).enumerate() {
        if !block.iter().fold(true, |ok, x| ok & countable(x)) {
            let p = block.iter().position(|x| !countable(x)).unwrap_or(0);
            let i = base + b * BLOCK + p;
            return Err(Error::invalid(
                "samples",
                block[p],
                format!(
                    "sample at index {i} is not finite, or beyond {MAX_ABS_SAMPLE:e} in magnitude (half the largest \
                     f64, so that every range is a number); rainflow counting needs finite values"
                ),
            ));
        }
    }
    Ok(())
}

/// Rainflow count of a whole record in one call: full cycles in the order they close, then the residue's
/// half cycles in time order.
///
/// # Formula
/// As [`RainflowCounter`] (ASTM E1049-85 (2017) §5.4.4).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `samples` for a non-finite sample or one beyond [`MAX_ABS_SAMPLE`]
/// (with its index).
///
/// # Examples
/// ```
/// use stochvib::fatigue::rainflow;
/// // ASTM E1049-85 (2017), Fig. 6: ranges 3 (½), 4 (1½), 6 (½), 8 (1), 9 (½).
/// let c = rainflow(&[-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]).unwrap();
/// let count = |r: f64| c.iter().filter(|c| c.range == r).map(|c| c.count).sum::<f64>();
/// assert_eq!([count(3.0), count(4.0), count(6.0), count(8.0), count(9.0)], [0.5, 1.5, 0.5, 1.0, 0.5]);
/// ```
pub fn rainflow(samples: &[f64]) -> Result<Vec<Cycle>> {
    let mut out = Vec::new();
    let mut rc = RainflowCounter::new();
    rc.push(samples, |c| out.push(c))?;
    rc.finish(|c| out.push(c));
    Ok(out)
}

/// Histogram of rainflow cycle counts over equal **range** bins [iΔ, (i+1)Δ), Δ = max_range/n_bins, the
/// last bin closed at max_range; half cycles add 0.5. Ranges above max_range are kept in an overflow
/// count (never dropped silently).
///
/// # Formula
/// bin(ΔS) = ⌊ΔS/Δ⌋ for ΔS < max_range, n_bins − 1 for ΔS = max_range; counts_i = Σ_{cycles in bin i} n.
///
/// # Errors
/// [`RangeHistogram::new`] rejects a `max_range` that is not finite and > 0, and `n_bins` = 0.
///
/// # Examples
/// ```
/// use stochvib::fatigue::{rainflow, RangeHistogram};
/// let c = rainflow(&[-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]).unwrap();
/// let h = RangeHistogram::from_cycles(&c, 10.0, 5).unwrap(); // bins of width 2
/// assert_eq!(h.counts(), &[0.0, 0.5, 1.5, 0.5, 1.5]);
/// assert_eq!(h.total(), 4.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RangeHistogram {
    max_range: f64,
    width: f64,
    counts: Vec<f64>,
    overflow: f64,
}

impl RangeHistogram {
    /// An empty histogram of `n_bins` equal range bins on [0, `max_range`].
    ///
    /// # Formula
    /// Δ = max_range / n_bins.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `max_range` (finite, > 0) or `n_bins` (≥ 1).
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::RangeHistogram;
    /// let h = RangeHistogram::new(8.0, 4).unwrap();
    /// assert_eq!(h.bin_edges(), vec![0.0, 2.0, 4.0, 6.0, 8.0]);
    /// assert!(RangeHistogram::new(0.0, 4).is_err());
    /// ```
    pub fn new(max_range: f64, n_bins: usize) -> Result<Self> {
        if !(max_range.is_finite() && max_range > 0.0) {
            return Err(Error::invalid(
                "max_range",
                max_range,
                "the histogram's top range must be finite and > 0",
            ));
        }
        if n_bins == 0 {
            return Err(Error::invalid("n_bins", n_bins, "need at least one bin"));
        }
        Ok(RangeHistogram {
            max_range,
            width: max_range / n_bins as f64,
            counts: vec![0.0; n_bins],
            overflow: 0.0,
        })
    }

    /// Histogram of `cycles` on [0, `max_range`] with `n_bins` bins.
    ///
    /// # Formula
    /// As the type.
    ///
    /// # Errors
    /// As [`RangeHistogram::new`].
    ///
    /// # Examples
    /// See the type.
    pub fn from_cycles(cycles: &[Cycle], max_range: f64, n_bins: usize) -> Result<Self> {
        let mut h = RangeHistogram::new(max_range, n_bins)?;
        for c in cycles {
            h.add(c);
        }
        Ok(h)
    }

    /// Adds one cycle (its count, 1 or 0.5) to the bin of its range, or to the overflow.
    ///
    /// # Formula
    /// bin = ⌊ΔS/Δ⌋ (the last bin also takes ΔS = max_range); ΔS > max_range → overflow.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::fatigue::{rainflow, RangeHistogram};
    /// let mut h = RangeHistogram::new(1.0, 2).unwrap();
    /// for c in rainflow(&[0.0, 3.0]).unwrap() { h.add(&c); }
    /// assert_eq!(h.overflow(), 0.5);
    /// ```
    #[inline]
    pub fn add(&mut self, cycle: &Cycle) {
        let r = cycle.range;
        if r > self.max_range || r.is_nan() {
            self.overflow += cycle.count;
            return;
        }
        let n = self.counts.len();
        let i = ((r / self.width) as usize).min(n - 1);
        self.counts[i] += cycle.count;
    }

    /// Counts per bin (half cycles count 0.5).
    pub fn counts(&self) -> &[f64] {
        &self.counts
    }

    /// Count of cycles whose range exceeds `max_range`.
    pub fn overflow(&self) -> f64 {
        self.overflow
    }

    /// The n_bins + 1 bin edges 0, Δ, …, max_range.
    pub fn bin_edges(&self) -> Vec<f64> {
        let n = self.counts.len();
        (0..=n)
            .map(|i| if i == n { self.max_range } else { i as f64 * self.width })
            .collect()
    }

    /// Total count in the bins (without the overflow).
    pub fn total(&self) -> f64 {
        self.counts.iter().sum()
    }
}
