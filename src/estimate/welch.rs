//! Welch's averaged-periodogram density estimate (Hann window, 50 % overlap) with χ² intervals.

use super::interval::Interval;
use super::moments::VarianceEstimate;
use crate::error::{require_positive, Error, Result};
use realfft::num_complex::Complex;
use realfft::{RealFftPlanner, RealToComplex};
use std::f64::consts::PI;
use std::sync::Arc;

/// Welch's method (Welch 1967, IEEE Trans. Audio Electroacoust. 15(2)) with a periodic Hann window of M
/// samples and 50 % overlap, giving the canonical two-sided angular density S(ω).
///
/// # Formula
/// Segments x^{(s)}_k = x_{sM/2 + k}, k = 0..M, s = 0..K with K = ⌊(L − M)/(M/2)⌋ + 1 for a record of L
/// samples; w_k = ½(1 − cos 2πk/M); ω_j = 2πj/(MΔt), j = 0..=M/2:
/// ```text
/// Ŝ(ω_j) = (1/K) Σ_s Δt/(2π Σ_k w_k²) · |Σ_k w_k x^{(s)}_k e^{−iω_j kΔt}|²
/// ```
/// Conversion: one-sided cyclic G(f_j) = 4π Ŝ(ω_j) at f_j = j/(MΔt) Hz (the "density" scaling of
/// scipy.signal.welch for 0 < f < f_N), one-sided angular G(ω) = 2Ŝ(ω).
///
/// Interval: Ŝ/S is approximately χ²_ν/ν. Without overlap ν = 2K (each periodogram ≈ χ²₂, K independent
/// segments). With 50 % overlap adjacent segments are correlated; the periodogram correlation is c² with
/// c = Σ_{k<M/2} w_k w_{k+M/2} / Σ w_k² (= 1/6 for Hann), and matching the variance gives Welch's equivalent degrees
/// of freedom
/// ```text
/// ν = 2K² / (K + 2(K − 1)c²)        (= 36K²/(19K − 1) ≈ 1.89 K for Hann, smaller than the nominal 2K)
/// ```
/// which is what the intervals use (both are reported). Records of independent realizations add their ν.
/// At ω = 0 and the Nyquist frequency the periodogram is χ²₁, so ν is halved there. The χ² law is an
/// approximation (Gaussian data, M much longer than the correlation time) and the estimate is biased by
/// the window's smoothing of S over about ±2 bins ([`Welch::expected`] gives its exact mean).
///
/// # Errors
/// [`Welch::new`] rejects M < 4 or odd and Δt ≤ 0; [`Welch::accumulate`] a record shorter than M.
///
/// # Examples
/// ```
/// use stochvib::estimate::Welch;
/// let w = Welch::new(256, 0.01).unwrap();
/// let x: Vec<f64> = (0..4096).map(|k| ((k * 7919) % 101) as f64 - 50.0).collect();
/// let est = w.estimate(&x).unwrap();
/// assert_eq!(est.segments, 31);
/// assert!(est.dof < est.nominal_dof);
/// ```
#[derive(Clone)]
pub struct Welch {
    m: usize,
    dt: f64,
    window: Vec<f64>,
    norm: f64,
    c2: f64,
    plan: Arc<dyn RealToComplex<f64>>,
    remove_mean: bool,
}

impl std::fmt::Debug for Welch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Welch")
            .field("m", &self.m)
            .field("dt", &self.dt)
            .field("remove_mean", &self.remove_mean)
            .finish()
    }
}

/// Accumulated periodograms (sums, in the order added) of one or more records.
#[derive(Debug, Clone, PartialEq)]
pub struct WelchSums {
    /// Σ over segments of the normalised periodogram at ω_j.
    pub sum: Vec<f64>,
    /// Number of segments K.
    pub segments: u64,
    /// Σ over records of Welch's equivalent ν (interior bins).
    pub dof: f64,
}

impl WelchSums {
    /// Adds another set of sums (for merging realizations or shards: add in realization order for
    /// bit-identical results).
    ///
    /// # Errors
    /// Different segment lengths.
    pub fn merge(&mut self, other: &WelchSums) -> Result<()> {
        if other.sum.len() != self.sum.len() {
            return Err(Error::invalid(
                "welch sums",
                other.sum.len(),
                "different segment length",
            ));
        }
        for (a, b) in self.sum.iter_mut().zip(&other.sum) {
            *a += b;
        }
        self.segments += other.segments;
        self.dof += other.dof;
        Ok(())
    }
}

/// A record being fed to [`Welch::push`] in pieces: the last samples not yet in a full segment.
#[derive(Debug, Clone)]
pub struct WelchStream {
    pending: Vec<f64>,
    segments: usize,
}

/// Working memory of [`Welch::accumulate`].
#[derive(Debug, Clone)]
pub struct WelchScratch {
    input: Vec<f64>,
    spectrum: Vec<Complex<f64>>,
    fft: Vec<Complex<f64>>,
}

/// A Welch density estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct WelchEstimate {
    /// ω_j = 2πj/(MΔt), rad/s (rad/m for spatial records).
    pub omega: Vec<f64>,
    /// Two-sided angular density Ŝ(ω_j).
    pub density: Vec<f64>,
    /// Number of averaged segments K.
    pub segments: u64,
    /// Welch's equivalent degrees of freedom ν (interior bins), used by [`WelchEstimate::interval`].
    pub dof: f64,
    /// The nominal 2K.
    pub nominal_dof: f64,
}

impl WelchEstimate {
    /// The χ² interval at bin j: [ν Ŝ/χ²_{ν,1−p/2}, ν Ŝ/χ²_{ν,p/2}] (ν halved at j = 0 and the Nyquist bin).
    ///
    /// # Errors
    /// j out of range, confidence ∉ (0, 1).
    pub fn interval(&self, j: usize, confidence: f64) -> Result<Interval> {
        if j >= self.density.len() {
            return Err(Error::invalid("bin", j, format!("have {} bins", self.density.len())));
        }
        let nu = if j == 0 || j + 1 == self.density.len() {
            self.dof / 2.0
        } else {
            self.dof
        };
        VarianceEstimate {
            variance: self.density[j],
            dof: nu,
        }
        .interval(confidence)
    }

    /// The χ² intervals of every bin, as [`WelchEstimate::interval`] gives them bin by bin (the same
    /// floating-point operations, bit for bit), with the two pairs of χ² quantiles (ν inside, ν/2 at the end
    /// bins) computed once instead of at every bin: (lower bounds, upper bounds).
    ///
    /// # Formula
    /// As [`WelchEstimate::interval`]: [ν Ŝ_j/χ²_{ν,1−p/2}, ν Ŝ_j/χ²_{ν,p/2}], p = 1 − confidence.
    ///
    /// # Errors
    /// confidence ∉ (0, 1); a negative density.
    ///
    /// # Examples
    /// ```
    /// use stochvib::estimate::Welch;
    /// let w = Welch::new(8, 0.1).unwrap();
    /// let mut sums = w.sums();
    /// let x = [1.0, -2.0, 0.5, 0.3, -1.1, 0.7, 0.2, -0.4, 0.9, -0.6, 0.1, 0.8];
    /// w.accumulate(&x, &mut sums, &mut w.scratch()).unwrap();
    /// let est = w.finish(&sums).unwrap();
    /// let (lo, hi) = est.intervals(0.9).unwrap();
    /// for j in 0..est.density.len() {
    ///     let iv = est.interval(j, 0.9).unwrap();
    ///     assert_eq!((lo[j].to_bits(), hi[j].to_bits()), (iv.lower.to_bits(), iv.upper.to_bits()));
    /// }
    /// ```
    pub fn intervals(&self, confidence: f64) -> Result<(Vec<f64>, Vec<f64>)> {
        let n = self.density.len();
        let (mut lower, mut upper) = (Vec::with_capacity(n), Vec::with_capacity(n));
        if n == 0 {
            return Ok((lower, upper));
        }
        // the confidence checked (and refused) as the bin's interval does; its quantiles, once per ν
        VarianceEstimate {
            variance: 0.0,
            dof: self.dof,
        }
        .interval(confidence)?;
        let a = 1.0 - confidence;
        let q = |nu: f64| -> Result<(f64, f64)> {
            Ok((
                super::moments::chi_squared_quantile(nu, 1.0 - a / 2.0)?,
                super::moments::chi_squared_quantile(nu, a / 2.0)?,
            ))
        };
        let (qi, qe) = (q(self.dof)?, q(self.dof / 2.0)?);
        for (j, &v) in self.density.iter().enumerate() {
            if !(v.is_finite() && v >= 0.0) {
                return Err(crate::Error::invalid(
                    &format!("density at bin {j}"),
                    v,
                    "not a finite number >= 0: the record holds NaN, or its squares leave the range of f64 \
                     (values beyond about 1e150 in magnitude)",
                ));
            }
            let (nu, (hi, lo)) = if j == 0 || j + 1 == n {
                (self.dof / 2.0, qe)
            } else {
                (self.dof, qi)
            };
            lower.push(nu * v / hi);
            upper.push(nu * v / lo);
        }
        Ok((lower, upper))
    }

    /// One-sided cyclic density G(f) = 4π S(2πf) (f in Hz): (f_j, G_j); at f = 0 and the Nyquist frequency
    /// the one-sided value is conventionally 2πS (not doubled), as in scipy.
    pub fn one_sided_cyclic(&self) -> (Vec<f64>, Vec<f64>) {
        let last = self.density.len() - 1;
        let f = self.omega.iter().map(|w| w / (2.0 * PI)).collect();
        let g = self
            .density
            .iter()
            .enumerate()
            .map(|(j, s)| {
                if j == 0 || j == last {
                    2.0 * PI * s
                } else {
                    4.0 * PI * s
                }
            })
            .collect();
        (f, g)
    }
}

impl Welch {
    /// Plans segments of M = `segment_len` samples at step `dt`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(segment_len: usize, dt: f64) -> Result<Self> {
        require_positive("dt", dt)?;
        let m = segment_len;
        if m < 4 || !m.is_multiple_of(2) {
            return Err(Error::invalid("segment length", m, "must be even and >= 4"));
        }
        let window: Vec<f64> = (0..m)
            .map(|k| 0.5 * (1.0 - (2.0 * PI * k as f64 / m as f64).cos()))
            .collect();
        let norm: f64 = window.iter().map(|w| w * w).sum();
        let c: f64 = (0..m / 2).map(|k| window[k] * window[k + m / 2]).sum::<f64>() / norm;
        Ok(Welch {
            m,
            dt,
            window,
            norm,
            c2: c * c,
            plan: RealFftPlanner::<f64>::new().plan_fft_forward(m),
            remove_mean: false,
        })
    }

    /// The same estimator with each segment's mean subtracted before the window (scipy's
    /// `detrend="constant"`): a constant offset of the record (a static stress, gravity) then leaks no power
    /// into the lowest bins.
    ///
    /// # Formula
    /// x^{(s)}_k − (1/M)Σ_k x^{(s)}_k in place of x^{(s)}_k in the type's formula.
    ///
    /// # Examples
    /// ```
    /// use stochvib::estimate::Welch;
    /// let w = Welch::new(64, 0.01).unwrap().with_segment_mean_removed();
    /// let est = w.estimate(&vec![5.0; 256]).unwrap();
    /// assert!(est.density.iter().all(|d| *d < 1e-25));
    /// ```
    pub fn with_segment_mean_removed(mut self) -> Self {
        self.remove_mean = true;
        self
    }

    /// Segment length M.
    pub fn segment_len(&self) -> usize {
        self.m
    }

    /// Number of segments in a record of `len` samples.
    pub fn segments_in(&self, len: usize) -> usize {
        if len < self.m {
            0
        } else {
            (len - self.m) / (self.m / 2) + 1
        }
    }

    /// Welch's equivalent degrees of freedom of one record of K segments (see the type docs).
    pub fn record_dof(&self, k: usize) -> f64 {
        let k = k as f64;
        2.0 * k * k / (k + 2.0 * (k - 1.0) * self.c2)
    }

    /// Empty sums.
    pub fn sums(&self) -> WelchSums {
        WelchSums {
            sum: vec![0.0; self.m / 2 + 1],
            segments: 0,
            dof: 0.0,
        }
    }

    /// Fresh working memory.
    pub fn scratch(&self) -> WelchScratch {
        WelchScratch {
            input: vec![0.0; self.m],
            spectrum: vec![Complex::new(0.0, 0.0); self.m / 2 + 1],
            fft: vec![Complex::new(0.0, 0.0); self.plan.get_scratch_len()],
        }
    }

    /// Adds the segments of one record (one realization) to `sums`.
    ///
    /// # Errors
    /// Record shorter than M; sums or scratch of another segment length.
    pub fn accumulate(&self, x: &[f64], sums: &mut WelchSums, scratch: &mut WelchScratch) -> Result<()> {
        let k = self.segments_in(x.len());
        if k == 0 {
            return Err(Error::invalid(
                "record length",
                x.len(),
                format!("shorter than the segment length {}", self.m),
            ));
        }
        if sums.sum.len() != self.m / 2 + 1 || scratch.input.len() != self.m {
            return Err(Error::invalid(
                "sums",
                sums.sum.len(),
                "made for another segment length",
            ));
        }
        for s in 0..k {
            self.segment(&x[s * self.m / 2..s * self.m / 2 + self.m], sums, scratch)?;
        }
        sums.segments += k as u64;
        sums.dof += self.record_dof(k);
        Ok(())
    }

    /// Adds one windowed segment's periodogram to `sums.sum` (segment count and ν are the caller's).
    fn segment(&self, seg: &[f64], sums: &mut WelchSums, scratch: &mut WelchScratch) -> Result<()> {
        let scale = self.dt / (2.0 * PI * self.norm);
        let mean = if self.remove_mean {
            seg.iter().sum::<f64>() / seg.len() as f64
        } else {
            0.0
        };
        for ((d, v), w) in scratch.input.iter_mut().zip(seg).zip(&self.window) {
            *d = (v - mean) * w;
        }
        self.plan
            .process_with_scratch(&mut scratch.input, &mut scratch.spectrum, &mut scratch.fft)
            .map_err(|e| Error::Numerical {
                what: "forward real FFT".into(),
                reason: e.to_string(),
            })?;
        for (a, c) in sums.sum.iter_mut().zip(&scratch.spectrum) {
            *a += scale * c.norm_sqr();
        }
        Ok(())
    }

    /// A record fed in pieces ([`Welch::push`], [`Welch::end_record`]) with memory O(M): the same segments,
    /// in the same order and with the same arithmetic as [`Welch::accumulate`] on the whole record, so the
    /// sums are bit-identical for any split of the record.
    pub fn stream(&self) -> WelchStream {
        WelchStream {
            pending: Vec::with_capacity(self.m),
            segments: 0,
        }
    }

    /// Adds the next samples of the record of `stream`.
    ///
    /// # Errors
    /// Sums or scratch of another segment length.
    pub fn push(
        &self,
        stream: &mut WelchStream,
        mut x: &[f64],
        sums: &mut WelchSums,
        scratch: &mut WelchScratch,
    ) -> Result<()> {
        if sums.sum.len() != self.m / 2 + 1 || scratch.input.len() != self.m {
            return Err(Error::invalid(
                "sums",
                sums.sum.len(),
                "made for another segment length",
            ));
        }
        while !x.is_empty() {
            let take = (self.m - stream.pending.len()).min(x.len());
            stream.pending.extend_from_slice(&x[..take]);
            x = &x[take..];
            if stream.pending.len() == self.m {
                self.segment(&stream.pending, sums, scratch)?;
                stream.segments += 1;
                stream.pending.drain(..self.m / 2);
            }
        }
        Ok(())
    }

    /// Ends the record of `stream`: counts its segments and adds its equivalent ν (as
    /// [`Welch::accumulate`] does for a whole record).
    ///
    /// # Errors
    /// A record shorter than M.
    pub fn end_record(&self, stream: &mut WelchStream, sums: &mut WelchSums) -> Result<()> {
        let k = stream.segments;
        if k == 0 {
            return Err(Error::invalid(
                "record length",
                stream.pending.len(),
                format!("shorter than the segment length {}", self.m),
            ));
        }
        sums.segments += k as u64;
        sums.dof += self.record_dof(k);
        stream.pending.clear();
        stream.segments = 0;
        Ok(())
    }

    /// The estimate from accumulated sums.
    ///
    /// # Errors
    /// No segments.
    pub fn finish(&self, sums: &WelchSums) -> Result<WelchEstimate> {
        if sums.segments == 0 {
            return Err(Error::invalid("segments", 0, "no data accumulated"));
        }
        let k = sums.segments as f64;
        let dw = 2.0 * PI / (self.m as f64 * self.dt);
        Ok(WelchEstimate {
            omega: (0..=self.m / 2).map(|j| j as f64 * dw).collect(),
            density: sums.sum.iter().map(|v| v / k).collect(),
            segments: sums.segments,
            dof: sums.dof,
            nominal_dof: 2.0 * k,
        })
    }

    /// Welch estimate of one record.
    ///
    /// # Errors
    /// As [`Welch::accumulate`].
    pub fn estimate(&self, x: &[f64]) -> Result<WelchEstimate> {
        let mut sums = self.sums();
        self.accumulate(x, &mut sums, &mut self.scratch())?;
        self.finish(&sums)
    }

    /// The exact mean of the estimate at bin j for a zero-mean stationary sequence with autocovariance
    /// `autocov(m)` = E[x_{k+m} x_k] (m ≥ 0): the window-smoothed, aliased density actually estimated.
    ///
    /// # Formula
    /// ```text
    /// E Ŝ(ω_j) = Δt/(2π Σw²) Σ_{|m|<M} K(|m|) r_w(|m|) cos(ω_j mΔt),   r_w(m) = Σ_k w_k w_{k+m}
    /// ```
    pub fn expected(&self, autocov: impl Fn(usize) -> f64, j: usize) -> f64 {
        let m = self.m;
        let mut total = 0.0;
        for lag in 0..m {
            let r: f64 = (0..m - lag).map(|k| self.window[k] * self.window[k + lag]).sum();
            let w = if lag == 0 { 1.0 } else { 2.0 };
            let arg = 2.0 * PI * ((j * lag) % m) as f64 / m as f64;
            total += w * autocov(lag) * r * arg.cos();
        }
        self.dt / (2.0 * PI * self.norm) * total
    }

    /// [`Welch::expected`] at every bin j = 0..=M/2, from the autocovariance at lags 0..M (`autocov[m]`,
    /// missing lags taken as 0), with the window's lag products computed once: O(M²) in all.
    ///
    /// # Formula
    /// As [`Welch::expected`].
    pub fn expected_all(&self, autocov: &[f64]) -> Vec<f64> {
        let m = self.m;
        let weighted: Vec<f64> = (0..m)
            .map(|lag| {
                let r: f64 = (0..m - lag).map(|k| self.window[k] * self.window[k + lag]).sum();
                let w = if lag == 0 { 1.0 } else { 2.0 };
                w * autocov.get(lag).copied().unwrap_or(0.0) * r
            })
            .collect();
        let cos: Vec<f64> = (0..m).map(|q| (2.0 * PI * q as f64 / m as f64).cos()).collect();
        (0..=m / 2)
            .map(|j| {
                let total: f64 = weighted.iter().enumerate().map(|(lag, v)| v * cos[(j * lag) % m]).sum();
                self.dt / (2.0 * PI * self.norm) * total
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::{EXACT, ROUNDING, ULPS};

    #[test]
    fn hann_overlap_correlation_is_one_sixth() {
        // Periodic Hann: over the half-segment overlap w_k w_{k+M/2} = sin²(πk/M) cos²(πk/M) = ¼ sin²(2πk/M),
        // summing to M/16 over k < M/2; Σ w² = Σ sin⁴ = 3M/8; so c = 1/6 and c² = 1/36, which gives Percival &
        // Walden's (1993, eq. 292b) ν = 36K²/(19K − 1) for Hanning with 50 % overlap.
        let w = Welch::new(64, 1.0).unwrap();
        assert!((w.c2 - 1.0 / 36.0).abs() < ROUNDING);
        let k = 10.0;
        assert!((w.record_dof(10) - 36.0 * k * k / (19.0 * k - 1.0)).abs() < EXACT);
    }

    /// `expected_all` is `expected` at every bin (same sums, table of cosines instead of calls).
    #[test]
    fn expected_all_equals_expected_per_bin() {
        let w = Welch::new(32, 0.1).unwrap();
        let k: Vec<f64> = (0..32)
            .map(|m| (-0.2 * m as f64).exp() * (0.7 * m as f64).cos())
            .collect();
        let all = w.expected_all(&k);
        for (j, v) in all.iter().enumerate() {
            let one = w.expected(|m| k[m], j);
            assert!(
                (v - one).abs() <= 1e-12 * one.abs().max(1e-300),
                "bin {j}: {v} vs {one}"
            );
        }
    }

    #[test]
    fn white_noise_expectation_is_flat() {
        // unit-variance white sequence: E Ŝ = Δt/(2π) at every bin (K(m) = δ_m)
        let w = Welch::new(32, 0.5).unwrap();
        for j in [0, 5, 16] {
            let e = w.expected(|m| if m == 0 { 1.0 } else { 0.0 }, j);
            assert!((e - 0.5 / (2.0 * PI)).abs() < ULPS);
        }
    }
}
