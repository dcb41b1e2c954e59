//! The octave or one-third-octave band table of one output: which bands, and each band's r.m.s. by the band
//! integral of the output density.

use super::bands::{bands_covering, Band, BandFraction};
use crate::error::{Error, Result};
use crate::response::{band_variance, Excitation, OutputDensity};
use crate::system::FrequencyResponse;
use std::f64::consts::PI;

/// Fraction of σ² the automatically chosen bands must hold together (the rest is the tails outside them).
pub const BAND_COVERAGE: f64 = 0.999;

/// Largest number of bands of an automatically chosen table (90 one-third octaves = 30 octaves = 9 decades).
pub const MAX_TABLE_THIRD_OCTAVES: usize = 90;

/// Lowest and highest frequency (Hz) searched for the peak of f·G_y(f) that seeds the automatic choice.
const SEED_RANGE_HZ: (f64, f64) = (1.0e-4, 1.0e5);

/// One band of a [`BandTable`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BandRow {
    /// The band (label, exact centre, edges).
    pub band: Band,
    /// Band mean square σ²_band in the output's unit squared.
    pub mean_square: f64,
    /// The quadrature's error estimate of `mean_square`.
    pub error_estimate: f64,
    /// Band r.m.s. √σ²_band, in the output's unit.
    pub rms: f64,
}

/// The band table of one output.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BandTable {
    /// Octave or one-third octave.
    pub fraction: BandFraction,
    /// How the bands were chosen, in words.
    pub chosen_by: String,
    /// The bands, ascending and contiguous.
    pub rows: Vec<BandRow>,
    /// Σ σ²_band over the rows.
    pub sum_mean_square: f64,
    /// The output's total variance σ² (of the analysis), if finite.
    pub total_variance: Option<f64>,
}

impl BandTable {
    /// Σ σ²_band / σ², if σ² is known and > 0.
    ///
    /// # Formula
    /// Σ_k σ²_k / σ² (≤ 1 up to quadrature error, since the bands are disjoint).
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{BandFraction, BandTable};
    /// let t = BandTable { fraction: BandFraction::Octave, chosen_by: String::new(), rows: vec![],
    ///                     sum_mean_square: 0.5, total_variance: Some(2.0) };
    /// assert_eq!(t.coverage(), Some(0.25));
    /// ```
    pub fn coverage(&self) -> Option<f64> {
        self.total_variance
            .filter(|v| *v > 0.0)
            .map(|v| self.sum_mean_square / v)
    }
}

/// The mean square of output `i` in one band, σ²_band = 2∫_{2πf_1}^{2πf_2} S_y(ω) dω, by
/// [`band_variance`] (adaptive or oscillatory quadrature of the two-sided angular density).
///
/// # Formula
/// σ²_band = 2∫_{2πf_1}^{2πf_2} S_y(ω) dω = ∫_{f_1}^{f_2} G_y(f) df, G_y(f) = 4π S_y(2πf).
///
/// # Errors
/// Those of [`band_variance`].
///
/// # Examples
/// ```
/// use stochvib::comfort::{output_band_row, Band, BandFraction};
/// use stochvib::response::Excitation;
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::{OutputInfo, TransferFunction};
/// use std::sync::Arc;
/// let filter = TransferFunction::new(vec![3.0], vec![3.0, 1.0], OutputInfo::new("y", "m")).unwrap();
/// let exc = Excitation::single(Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()), 0.0).unwrap();
/// let r = output_band_row(&filter, &exc, 0, Band::new(BandFraction::Octave, -10).unwrap()).unwrap();
/// assert!(r.rms > 0.0 && r.rms < 1.0);
/// ```
pub fn output_band_row(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize, band: Band) -> Result<BandRow> {
    let q = band_variance(sys, exc, i, 2.0 * PI * band.lower_hz, 2.0 * PI * band.upper_hz)?;
    Ok(BandRow {
        band,
        mean_square: q.value,
        error_estimate: q.abs_error,
        rms: q.value.max(0.0).sqrt(),
    })
}

/// The band table of output `i` of `sys` under `exc`.
///
/// # Formula
/// Each band's mean square by [`output_band_row`]. The bands are
/// * those covering `range_hz` = [f_lo, f_hi] ([`bands_covering`]) when it is given (the scenario's
///   `[analysis] band`);
/// * otherwise, when σ² = `total_variance` is finite and > 0, the shortest run of contiguous bands grown
///   from the band holding the maximum of f·G_y(f) (the variance per unit log-frequency, searched on a
///   grid of 10 points per one-third octave over 10⁻⁴ … 10⁵ Hz), adding at each step the neighbour band
///   with the larger mean square, until Σσ²_band ≥ [`BAND_COVERAGE`]·σ² (or
///   [`MAX_TABLE_THIRD_OCTAVES`] one-third octaves are reached; the table says so).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `bands` when neither a range nor a finite σ² > 0 is given (the
/// bands of a divergent variance need a range), or when the density is zero on the whole seed grid;
/// those of [`band_variance`] and [`bands_covering`].
///
/// # Examples
/// ```
/// use stochvib::comfort::{output_band_table, BandFraction};
/// use stochvib::response::Excitation;
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::{OutputInfo, TransferFunction};
/// use std::sync::Arc;
/// // 3/(s + 3) on an exponentially correlated input, D = 1, α = 2 rad/s: σ² = a/(a + α) = 0.6
/// let filter = TransferFunction::new(vec![3.0], vec![3.0, 1.0], OutputInfo::new("y", "m")).unwrap();
/// let exc = Excitation::single(Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()), 0.0).unwrap();
/// let t = output_band_table(&filter, &exc, 0, BandFraction::Octave, Some(0.6), None).unwrap();
/// assert!(t.coverage().unwrap() >= 0.999 && t.coverage().unwrap() < 1.0 + 1e-9);
/// ```
pub fn output_band_table(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    fraction: BandFraction,
    total_variance: Option<f64>,
    range_hz: Option<(f64, f64)>,
) -> Result<BandTable> {
    let total_variance = total_variance.filter(|v| v.is_finite() && *v > 0.0);
    let (rows, chosen_by) = match (range_hz, total_variance) {
        (Some((lo, hi)), _) => {
            let lo = lo.max(1e-12 * hi);
            let rows = bands_covering(fraction, lo, hi)?
                .into_iter()
                .map(|b| output_band_row(sys, exc, i, b))
                .collect::<Result<Vec<_>>>()?;
            (
                rows,
                format!("the bands covering the analysis band {lo:.4} … {hi:.4} Hz"),
            )
        }
        (None, Some(total)) => grow(sys, exc, i, fraction, total)?,
        (None, None) => {
            return Err(Error::invalid(
                "bands",
                "(no band)",
                "the output's variance is not finite: give [analysis] band = [f_lo, f_hi] to choose the bands",
            ))
        }
    };
    let sum_mean_square = rows.iter().map(|r| r.mean_square).sum();
    Ok(BandTable {
        fraction,
        chosen_by,
        rows,
        sum_mean_square,
        total_variance,
    })
}

/// The automatic choice of [`output_band_table`]: grow from the peak band until the coverage is reached.
fn grow(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    fraction: BandFraction,
    total: f64,
) -> Result<(Vec<BandRow>, String)> {
    let density = OutputDensity::new(sys, exc, i)?;
    let (lo, hi) = SEED_RANGE_HZ;
    let n = (300.0 * (hi / lo).log10()).ceil() as usize; // 10 per one-third octave
    let mut peak = (0.0, f64::NAN);
    for k in 0..=n {
        let f = lo * (hi / lo).powf(k as f64 / n as f64);
        let v = f * density.density(2.0 * PI * f);
        if v.is_finite() && v > peak.0 {
            peak = (v, f);
        }
    }
    if peak.0 <= 0.0 {
        return Err(Error::invalid(
            "bands",
            "(automatic)",
            format!("the output density is zero on {lo:e} … {hi:e} Hz: give [analysis] band"),
        ));
    }
    let seed = Band::containing(fraction, peak.1)?;
    let max_bands = MAX_TABLE_THIRD_OCTAVES / fraction_thirds(fraction);
    let mut rows = vec![output_band_row(sys, exc, i, seed)?];
    let mut sum = rows[0].mean_square;
    let mut below: Option<BandRow> = None;
    let mut above: Option<BandRow> = None;
    while sum < BAND_COVERAGE * total && rows.len() < max_bands {
        if below.is_none() {
            below = Some(output_band_row(
                sys,
                exc,
                i,
                Band::new(fraction, rows[0].band.index - 1)?,
            )?);
        }
        if above.is_none() {
            let last = rows[rows.len() - 1].band.index;
            above = Some(output_band_row(sys, exc, i, Band::new(fraction, last + 1)?)?);
        }
        let (b, a) = (below.as_ref().unwrap(), above.as_ref().unwrap());
        if b.mean_square > a.mean_square {
            sum += b.mean_square;
            rows.insert(0, below.take().unwrap());
        } else {
            sum += a.mean_square;
            rows.push(above.take().unwrap());
        }
    }
    let how = if sum >= BAND_COVERAGE * total {
        format!(
            "the fewest contiguous bands around the peak of f·G(f) ({:.4} Hz) holding ≥ {} % of σ²",
            peak.1,
            100.0 * BAND_COVERAGE
        )
    } else {
        format!(
            "grown around the peak of f·G(f) ({:.4} Hz) up to the limit of {max_bands} bands before holding {} % of σ²",
            peak.1,
            100.0 * BAND_COVERAGE
        )
    };
    Ok((rows, how))
}

/// One-third octaves per band.
fn fraction_thirds(fraction: BandFraction) -> usize {
    match fraction {
        BandFraction::Octave => 3,
        BandFraction::ThirdOctave => 1,
    }
}
