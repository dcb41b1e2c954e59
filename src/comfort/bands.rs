//! Base-10 octave and one-third-octave bands of IEC 61260-1:2014 and band mean squares of a density.

use crate::error::{Error, Result};
use crate::quad::{integrate, QuadOptions, QuadResult};

/// Preferred numbers of the R10 series (ISO 3, ISO 266) times 100: the nominal mid-band mantissas
/// 1, 1.25, 1.6, 2, 2.5, 3.15, 4, 5, 6.3, 8.
const R10_CENTI: [u32; 10] = [100, 125, 160, 200, 250, 315, 400, 500, 630, 800];

/// Largest |band index| accepted (third-octave index ±3000 spans 10^±300 around 1 kHz).
const MAX_THIRD_OCTAVE_INDEX: i64 = 3000;

/// Bandwidth designator: octave (b = 1) or one-third octave (b = 3).
///
/// # Formula
/// IEC 61260-1:2014: mid-band ratio G^(1/b) between adjacent bands, G = 10^(3/10).
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::{Band, BandFraction};
/// let o = Band::new(BandFraction::Octave, 1).unwrap();
/// assert!((o.centre_hz - 1000.0 * 10f64.powf(0.3)).abs() < 1e-9);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum BandFraction {
    /// Octave bands, b = 1.
    Octave,
    /// One-third-octave bands, b = 3.
    ThirdOctave,
}

impl BandFraction {
    /// The bandwidth designator b (1 or 3) of IEC 61260-1.
    ///
    /// # Formula
    /// b = 1 for octaves, b = 3 for one-third octaves.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::BandFraction;
    /// assert_eq!(BandFraction::ThirdOctave.designator(), 3);
    /// ```
    pub fn designator(self) -> i32 {
        match self {
            BandFraction::Octave => 1,
            BandFraction::ThirdOctave => 3,
        }
    }

    /// Number of one-third-octave steps per band: 3 for octaves, 1 for one-third octaves.
    fn thirds(self) -> i64 {
        match self {
            BandFraction::Octave => 3,
            BandFraction::ThirdOctave => 1,
        }
    }
}

/// One band: its index, exact mid-band and edge frequencies, and nominal (labelled) mid-band frequency.
///
/// # Formula
/// IEC 61260-1:2014, base-10 system: octave frequency ratio G = 10^(3/10), reference frequency
/// f_r = 1000 Hz, bandwidth designator b (1 or 3), band index x (integer):
///
/// ```text
/// f_m = f_r · G^(x/b)        (one-third octave: 1000·10^(x/10) Hz;  octave: 1000·10^(3x/10) Hz)
/// f_1 = f_m · G^(−1/(2b)),  f_2 = f_m · G^(1/(2b))   (one-third: f_m·10^(∓1/20);  octave: f_m·10^(∓3/20))
/// ```
/// Adjacent bands share their edges, so the bands tile the frequency axis. The nominal mid-band frequency
/// is the R10 preferred number (ISO 266) that the exact one rounds to: 1, 1.25, 1.6, 2, 2.5, 3.15, 4, 5,
/// 6.3, 8 times a power of ten (0.1, 0.125, … 0.8 for the motion-sickness range of Wf); the octave band
/// of index x has the nominal frequency of the one-third-octave band 3x (…, 1, 2, 4, 8, 16, 31.5, 63, …).
/// The index x here is relative to 1 kHz as in IEC 61260-1 (ISO 2631-1 numbers bands relative to 1 Hz:
/// its band number is x + 30).
///
/// # Errors
/// [`Band::new`] and [`Band::containing`] reject indices or frequencies whose band frequencies would
/// overflow.
///
/// # Examples
/// ```
/// use stochvib::comfort::{Band, BandFraction};
/// let b = Band::new(BandFraction::ThirdOctave, -25).unwrap(); // 10^0.5 Hz
/// assert_eq!(b.nominal_hz, 3.15);
/// assert!((b.centre_hz - 3.16227766).abs() < 1e-8);
/// assert_eq!(b.label(), "3.15 Hz");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Band {
    /// Octave or one-third octave.
    pub fraction: BandFraction,
    /// Band index x relative to 1 kHz (IEC 61260-1).
    pub index: i32,
    /// Exact mid-band frequency f_m, Hz.
    pub centre_hz: f64,
    /// Lower edge f_1, Hz.
    pub lower_hz: f64,
    /// Upper edge f_2, Hz.
    pub upper_hz: f64,
    /// Nominal mid-band frequency (the label), Hz.
    pub nominal_hz: f64,
}

impl Band {
    /// The band of index `index` (relative to 1 kHz).
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `index` when the band lies beyond 10^±300 Hz.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{Band, BandFraction};
    /// let b = Band::new(BandFraction::Octave, 0).unwrap();
    /// assert_eq!(b.centre_hz, 1000.0);
    /// assert!((b.lower_hz - 1000.0 * 10f64.powf(-0.15)).abs() < 1e-9);
    /// ```
    pub fn new(fraction: BandFraction, index: i32) -> Result<Band> {
        let thirds = index as i64 * fraction.thirds();
        if thirds.abs() > MAX_THIRD_OCTAVE_INDEX {
            return Err(Error::invalid(
                "index",
                index,
                format!(
                    "band too far from 1 kHz (its frequencies would overflow): need |index| <= {}",
                    MAX_THIRD_OCTAVE_INDEX / fraction.thirds()
                ),
            ));
        }
        let exponent = thirds as f64 / 10.0;
        let half = fraction.thirds() as f64 / 20.0;
        let centre_hz = 1000.0 * 10f64.powf(exponent);
        Ok(Band {
            fraction,
            index,
            centre_hz,
            lower_hz: 1000.0 * 10f64.powf(exponent - half),
            upper_hz: 1000.0 * 10f64.powf(exponent + half),
            nominal_hz: nominal_third_octave(thirds),
        })
    }

    /// The band that contains the frequency `f_hz` (bands are taken as half-open [f_1, f_2), so an edge
    /// belongs to the band above it, up to rounding of the logarithm).
    ///
    /// # Formula
    /// x = ⌊b·10·log₁₀(f/1000 Hz)/3 + 1/2⌋.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `f_hz` when it is not finite and > 0, or beyond 10^±300 Hz.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{Band, BandFraction};
    /// let b = Band::containing(BandFraction::ThirdOctave, 7.0).unwrap();
    /// assert_eq!(b.nominal_hz, 6.3);
    /// ```
    pub fn containing(fraction: BandFraction, f_hz: f64) -> Result<Band> {
        let x = band_coordinate(fraction, f_hz, "f_hz")?;
        Band::new(fraction, (x + 0.5).floor() as i32)
    }

    /// The label "`<nominal>` Hz", e.g. "0.315 Hz", "31.5 Hz".
    ///
    /// # Formula
    /// The shortest decimal representation of the nominal mid-band frequency.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{Band, BandFraction};
    /// assert_eq!(Band::new(BandFraction::ThirdOctave, -35).unwrap().label(), "0.315 Hz");
    /// ```
    pub fn label(&self) -> String {
        format!("{} Hz", self.nominal_hz)
    }

    /// Bandwidth f_2 − f_1, Hz.
    ///
    /// # Formula
    /// f_2 − f_1 = f_m (G^(1/(2b)) − G^(−1/(2b))): 0.23077·f_m for one-third octaves, 0.70459·f_m for
    /// octaves.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{Band, BandFraction};
    /// let b = Band::new(BandFraction::ThirdOctave, 0).unwrap();
    /// assert!((b.width_hz() / b.centre_hz - 0.230768).abs() < 1e-6);
    /// ```
    pub fn width_hz(&self) -> f64 {
        self.upper_hz - self.lower_hz
    }
}

/// The R10 nominal frequency of the one-third-octave band with index `thirds` relative to 1 kHz, computed
/// as integer mantissa × or ÷ an exact power of ten so that it equals the decimal literal (0.315, 6.3).
fn nominal_third_octave(thirds: i64) -> f64 {
    let n = thirds + 30; // relative to 1 Hz
    let decade = n.div_euclid(10);
    let mantissa = R10_CENTI[n.rem_euclid(10) as usize] as f64; // nominal = mantissa · 10^(decade − 2)
    let e = decade - 2;
    if e >= 0 {
        mantissa * 10f64.powi(e as i32)
    } else {
        mantissa / 10f64.powi((-e) as i32)
    }
}

/// b·10·log₁₀(f/1000)/3: the band coordinate of f, whose nearest integer is the band index.
fn band_coordinate(fraction: BandFraction, f_hz: f64, name: &str) -> Result<f64> {
    if !(f_hz.is_finite() && f_hz > 0.0) {
        return Err(Error::invalid(name, f_hz, "must be a finite frequency > 0 Hz"));
    }
    let x = 10.0 * (f_hz / 1000.0).log10() / fraction.thirds() as f64;
    if x.abs() > (MAX_THIRD_OCTAVE_INDEX / fraction.thirds()) as f64 {
        return Err(Error::invalid(name, f_hz, "frequency too far from 1 kHz for a band"));
    }
    Ok(x)
}

/// The consecutive bands that cover [f_lo, f_hi]: from the band containing f_lo to the band containing
/// f_hi, omitting a band that would only touch the interval at an edge.
///
/// # Formula
/// x_lo = ⌊c(f_lo) + 1/2⌋, x_hi = ⌈c(f_hi) − 1/2⌉ with c(f) = b·10·log₁₀(f/1000 Hz)/3; every band
/// x_lo ≤ x ≤ x_hi. (Exact edges are subject to rounding of the logarithm.)
///
/// # Errors
/// [`Error::InvalidParameter`] naming `f_lo_hz` or `f_hi_hz` when not finite and > 0, or when
/// f_hi < f_lo.
///
/// # Examples
/// ```
/// use stochvib::comfort::{bands_covering, BandFraction};
/// // the ISO 2631-1 range for health and comfort, 0.5 Hz to 80 Hz: 23 one-third octaves
/// let b = bands_covering(BandFraction::ThirdOctave, 0.5, 80.0).unwrap();
/// assert_eq!(b.len(), 23);
/// assert_eq!((b[0].nominal_hz, b[22].nominal_hz), (0.5, 80.0));
/// ```
pub fn bands_covering(fraction: BandFraction, f_lo_hz: f64, f_hi_hz: f64) -> Result<Vec<Band>> {
    let lo = band_coordinate(fraction, f_lo_hz, "f_lo_hz")?;
    let hi = band_coordinate(fraction, f_hi_hz, "f_hi_hz")?;
    if f_hi_hz < f_lo_hz {
        return Err(Error::invalid(
            "f_hi_hz",
            f_hi_hz,
            format!("must be >= f_lo_hz = {f_lo_hz}"),
        ));
    }
    let x_lo = (lo + 0.5).floor() as i32;
    let x_hi = ((hi - 0.5).ceil() as i32).max(x_lo);
    (x_lo..=x_hi).map(|x| Band::new(fraction, x)).collect()
}

/// The mean square in a band of a one-sided density in Hz, ∫_{f_1}^{f_2} G(f) df, by adaptive quadrature
/// ([`crate::quad::integrate`], relative tolerance 1e-10).
///
/// # Formula
/// ```text
/// σ²_band = ∫_{f_1}^{f_2} G(f) df,       band r.m.s. = √σ²_band,
/// ```
/// with G(f) the **one-sided density in Hz** (units²/Hz); from the crate's canonical two-sided angular
/// density S(ω), G(f) = 4π S(2πf) (see [`crate::spectrum`]). For a weighted response use
/// G(f) = |W(i2πf)|²·G_y(f).
///
/// # Errors
/// [`Error::Quadrature`] when the quadrature does not converge (including non-finite density values);
/// [`Error::InvalidParameter`] naming `density_one_sided_hz` when the integral is negative (a density is
/// ≥ 0).
///
/// # Examples
/// ```
/// use stochvib::comfort::{band_mean_square, Band, BandFraction};
/// let band = Band::new(BandFraction::ThirdOctave, -21).unwrap(); // 8 Hz
/// let flat = |_f: f64| 2.0e-3; // (m/s²)²/Hz
/// let ms = band_mean_square(&flat, &band).unwrap();
/// assert!((ms.value - 2.0e-3 * band.width_hz()).abs() < 1e-15);
/// ```
pub fn band_mean_square(density_one_sided_hz: &dyn Fn(f64) -> f64, band: &Band) -> Result<QuadResult> {
    let r = integrate(
        density_one_sided_hz,
        band.lower_hz,
        band.upper_hz,
        &QuadOptions::default(),
    )?;
    if r.value < -r.abs_error {
        return Err(Error::invalid(
            "density_one_sided_hz",
            format!("integral {:e} over the {} band", r.value, band.label()),
            "is negative; a one-sided density must be >= 0",
        ));
    }
    Ok(r)
}

/// The band r.m.s. √(∫_{f_1}^{f_2} G(f) df) of a one-sided density in Hz (see [`band_mean_square`]).
///
/// # Formula
/// √σ²_band, clamped at 0 for a roundoff-negative mean square.
///
/// # Errors
/// Those of [`band_mean_square`].
///
/// # Examples
/// ```
/// use stochvib::comfort::{band_rms, Band, BandFraction};
/// let band = Band::new(BandFraction::Octave, -3).unwrap(); // nominal 1 Hz
/// let rms = band_rms(&|_f| 1.0, &band).unwrap();
/// assert!((rms * rms - band.width_hz()).abs() < 1e-12);
/// ```
pub fn band_rms(density_one_sided_hz: &dyn Fn(f64) -> f64, band: &Band) -> Result<f64> {
    Ok(band_mean_square(density_one_sided_hz, band)?.value.max(0.0).sqrt())
}
