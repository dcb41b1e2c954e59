//! One-third-octave band r.m.s. values of a long sampled signal, from its streamed Welch density.
//!
//! # Realisation
//! The bands are those of IEC 61260-1:2014 (base 10: centres 1000·10^{x/10} Hz, edges f_m·10^{∓1/20};
//! [`Band`]). They are realised as **ideal band-pass filters** on the record's averaged periodogram (Welch,
//! Hann window, 50 % overlap, [`Welch`]): the band mean square is the integral of the one-sided density
//! G(f) = 4π S(2πf) over the exact band, each bin j taken as constant over [f_j − Δf/2, f_j + Δf/2] and
//! split in proportion at the band edges:
//! ```text
//! σ²_band = Σ_j G_j · |[f_j − Δf/2, f_j + Δf/2] ∩ [f₁, f₂]|,      band r.m.s. = √σ²_band.
//! ```
//! This is not an IEC 61260-1 filter bank: its bands have no skirts (a class 1 filter passes some energy of
//! the neighbouring bands, an ideal one none), and its resolution is the bin width Δf = f_s/M, so a band is
//! marked resolved only when it spans at least [`MIN_BINS_PER_BAND`] bins; the segment length M is chosen
//! for that ([`segment_for`]). The Hann window's main lobe spreads a bin over ±2 bins: a band of a steep
//! spectrum is accurate to about that leakage.

use crate::comfort::Band;
use crate::error::Result;
use crate::estimate::{Welch, WelchScratch, WelchStream, WelchSums};

/// Fewest Welch bins a band must span to be marked resolved.
pub const MIN_BINS_PER_BAND: f64 = 5.0;

/// Fewest Welch segments a record should hold for the bands ([`segment_for`] shortens the segments to keep
/// them).
pub const MIN_SEGMENTS: usize = 8;

/// The Welch segment length for bands down to `lowest`: the smallest power of two M with
/// f_s/M ≤ width/[`MIN_BINS_PER_BAND`], shortened (halved) until a record of `samples` samples holds
/// [`MIN_SEGMENTS`] half-overlapping segments, at least 16.
///
/// # Examples
/// ```
/// use stochvib::comfort::{Band, BandFraction};
/// use stochvib::record::segment_for;
/// let half_hz = Band::containing(BandFraction::ThirdOctave, 0.5).unwrap(); // 0.116 Hz wide
/// assert_eq!(segment_for(&half_hz, 1000.0, Some(100_000_000)), 65536);
/// assert_eq!(segment_for(&half_hz, 1000.0, Some(60_000)), 8192);
/// ```
pub fn segment_for(lowest: &Band, sample_rate_hz: f64, samples: Option<usize>) -> usize {
    let want = (MIN_BINS_PER_BAND * sample_rate_hz / lowest.width_hz()).max(16.0);
    let mut m = (want.log2().ceil().min(30.0).exp2() as usize).max(16);
    if let Some(n) = samples {
        while m > 16 && (n < m || (n - m) / (m / 2) + 1 < MIN_SEGMENTS) {
            m /= 2;
        }
    }
    m
}

/// One band's r.m.s. value.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BandValue {
    /// The band.
    pub band: Band,
    /// √(∫ G df) over the band, in the signal's unit.
    pub rms: f64,
    /// The band spans at least [`MIN_BINS_PER_BAND`] bins.
    pub resolved: bool,
}

/// The streamed Welch density of one signal, for its band values.
#[derive(Debug, Clone)]
pub struct BandAnalyzer {
    welch: Welch,
    stream: WelchStream,
    sums: WelchSums,
    scratch: WelchScratch,
    dt_s: f64,
}

impl BandAnalyzer {
    /// A density of segments of `segment_len` samples at step `dt_s`.
    ///
    /// # Errors
    /// As [`Welch::new`].
    pub fn new(segment_len: usize, dt_s: f64) -> Result<Self> {
        let welch = Welch::new(segment_len, dt_s)?;
        Ok(BandAnalyzer {
            stream: welch.stream(),
            sums: welch.sums(),
            scratch: welch.scratch(),
            welch,
            dt_s,
        })
    }

    /// Adds the next samples.
    ///
    /// # Errors
    /// As [`Welch::push`].
    pub fn push(&mut self, x: &[f64]) -> Result<()> {
        self.welch.push(&mut self.stream, x, &mut self.sums, &mut self.scratch)
    }

    /// The band values of `bands` (see the [module docs](self)); `None` when the record was shorter than one
    /// segment.
    ///
    /// # Errors
    /// As [`Welch::finish`].
    pub fn finish(mut self, bands: &[Band]) -> Result<Option<Vec<BandValue>>> {
        if self.welch.end_record(&mut self.stream, &mut self.sums).is_err() {
            return Ok(None);
        }
        let est = self.welch.finish(&self.sums)?;
        let (f, g) = est.one_sided_cyclic();
        let df = 1.0 / (self.welch.segment_len() as f64 * self.dt_s);
        Ok(Some(
            bands
                .iter()
                .map(|b| BandValue {
                    band: *b,
                    rms: band_mean_square(&f, &g, df, b.lower_hz, b.upper_hz).max(0.0).sqrt(),
                    resolved: b.width_hz() >= MIN_BINS_PER_BAND * df,
                })
                .collect(),
        ))
    }
}

/// Σ_j G_j·|[f_j − Δf/2, f_j + Δf/2] ∩ [lo, hi]| (the bins below 0 Hz and above the last clipped).
fn band_mean_square(f: &[f64], g: &[f64], df: f64, lo: f64, hi: f64) -> f64 {
    let first = ((lo / df - 0.5).floor().max(0.0)) as usize;
    let last = ((hi / df + 0.5).ceil() as usize).min(f.len().saturating_sub(1));
    let mut sum = 0.0;
    for j in first..=last {
        let a = (f[j] - 0.5 * df).max(0.0).max(lo);
        let b = (f[j] + 0.5 * df).min(hi);
        if b > a {
            sum += g[j] * (b - a);
        }
    }
    sum
}
