//! Operator seat under base motion, against the sanitary limits of Table 7.1 (Sukharev (2012) 7.6,
//! Example 7.2 (seat)).
//!
//! # Formula
//! Operator and seat reduced to one mass m_pr = (5/7) m_operator + m_seat (kg; the text introducing Fig. 7.10)
//! on the seat spring c (N/m) and damper b = 2 h m_pr (N s/m; the book gives h in s⁻¹). Base (cab floor)
//! motion u(t); seat motion z, relative motion y = z − u:
//! ```text
//! m_pr z̈ + b(ż − u̇) + c(z − u) = 0,   ω = √(c/m_pr),   β = h/ω,   ν = λ/ω          (7.37)–(7.41)
//! ÿ + 2h ẏ + ω² y = −ü = A_u λ² sin λt   for u = A_u sin λt                         (7.38)
//! η = A/A_u = √[(1 + 4β²ν²)/((1 − ν²)² + 4β²ν²)],   η_eff = 1/η                       (7.42), (7.43)
//! η_rel = A_y/A_u = ν² / √((1 − ν²)² + 4β²ν²)                                          (7.44)
//! d ≥ 2 A_y (free travel to the stops)                                                 (7.45)
//! σ_v = Aλ/√2,   σ_a = Aλ²/√2 (RMS of the seat's velocity and acceleration)             (7.46)–(7.49)
//! ```
//! **Octave bands**: the book (the text before Table 7.1) names the centres 1, 2, 4, 8, 16, 31.5, 63 Hz and
//! the edges f_c/√2 … f_c√2; with 31.5 ≠ 32 its 16 Hz band [11.31, 22.63] and 31.5 Hz band [22.27, 44.55]
//! overlap. The bands here are the base-10 octave bands of IEC 61260-1:2014 ([`crate::comfort::bands`]),
//! whose nominal centres are the book's seven: exact mid-band f_m = 1000·10^(3x/10) Hz for x = −10 … −4
//! (0.998, 1.995, 3.981, 7.943, 15.85, 31.62, 63.10 Hz), edges f_m·10^(∓3/20). They tile the axis
//! (0.7079 … 89.13 Hz, half-open [f_1, f_2)), so the book's overlap and the former non-overlap rule are gone.
//! **Size of the change**: the base-10 edges are f_c/√2, f_c√2 times 10^(3x/10)·1000/f_c · 10^(∓3/20)·√2^(±1):
//! the bands 1 … 63 Hz move by +0.12, −0.12, −0.36, −0.59, −0.83 % (lower edges of 1 … 16 Hz), −0.12,
//! −0.36, −0.59, −0.83, −1.06 % (their upper edges), and the 31.5 Hz and 63 Hz edges lie within +0.51 % of
//! the book's (the shared 16 | 31.5 Hz edge: 22.39 Hz instead of 16√2 = 22.63 Hz of the former rule,
//! −1.06 %; the book's own 31.5/√2 = 22.27 Hz, +0.51 %). A sinusoid's band changes only within these
//! slivers (Example 7.2's 3 Hz stays in the 4 Hz band); a random band value changes by the density
//! integrated over them.
//! **Random base motion** with two-sided displacement density S_u(ω): the band variance of an output with
//! frequency response H(iω) is σ² = 2∫_{2πf_lo}^{2πf_hi} |H(iω)|² S_u(ω) dω ([`band_variance`]); for a
//! **harmonic** base motion the band RMS is the sinusoid's RMS (amplitude/√2) in the band containing its
//! frequency and 0 in the others.
//!
//! # Examples
//! ```
//! use stochvib::models::operator_seat::OperatorSeat;
//! // Example 7.2: 80 kg operator, 26 kg seat, c = 6500 N/m, h = 4.22 1/s, u = 0.0035 sin 6πt
//! let seat = OperatorSeat { operator_mass: 80.0, seat_mass: 26.0, stiffness: 6500.0, damping: 0.0 }.with_damping_rate(4.22).unwrap();
//! let r = seat.harmonic(0.0035, 6.0 * std::f64::consts::PI).unwrap();
//! assert!((r.velocity_rms - 0.02588).abs() < 1e-4);
//! ```

use crate::comfort::{Band, BandFraction};
use crate::error::{require_positive, Error, Result};
use crate::fields::Fields;
use crate::models::isolation::transmissibility;
use crate::models::worked_example::BookRow;
use crate::models::{InputLayout, ModelInstance};
use crate::response::{band_variance, Excitation};
use crate::spectrum::Spectrum;
use crate::system::{Drive, FrequencyResponse, MassSpringDamper, Mdof, Quantity};
use crate::units::Dim;
use std::f64::consts::{PI, SQRT_2};
use std::path::Path;
use std::sync::Arc;

/// Nominal octave-band centre frequencies, Hz (Sukharev (2012) 7.6, the text before Table 7.1; the
/// nominal mid-band frequencies of the IEC 61260-1 base-10 octave bands x = −10 … −4, see [`octave_bands`]).
pub const OCTAVE_CENTRES_HZ: [f64; 7] = [1.0, 2.0, 4.0, 8.0, 16.0, 31.5, 63.0];

/// IEC 61260-1 band index (relative to 1 kHz) of the first octave band of Table 7.1 (nominal 1 Hz).
pub const FIRST_OCTAVE_INDEX: i32 = -10;

/// The seven octave bands of Table 7.1 as IEC 61260-1:2014 base-10 octave bands (nominal 1 … 63 Hz).
///
/// # Formula
/// f_m = 1000·10^(3x/10) Hz, f_1 = f_m·10^(−3/20), f_2 = f_m·10^(3/20), x = −10 … −4
/// ([`crate::comfort::Band`]); contiguous: f_2 of one band is f_1 of the next.
///
/// # Errors
/// None (the indices are constants well inside the range of [`Band::new`]).
///
/// # Examples
/// ```
/// use stochvib::models::operator_seat::octave_bands;
/// let b = octave_bands();
/// assert_eq!(b[2].nominal_hz, 4.0);
/// assert!((b[2].centre_hz - 10f64.powf(0.6)).abs() < 1e-12);
/// assert!((b[5].lower_hz - b[4].upper_hz).abs() < 1e-12); // contiguous
/// ```
pub fn octave_bands() -> Vec<Band> {
    (0..OCTAVE_CENTRES_HZ.len() as i32)
        .map(|k| {
            Band::new(BandFraction::Octave, FIRST_OCTAVE_INDEX + k)
                .expect("constant band indices -10 ... -4 are far inside the accepted range")
        })
        .collect()
}

/// Index (0 … 6) of the octave band [f_1, f_2) of [`octave_bands`] containing frequency `f_hz` (Hz), if any.
///
/// # Formula
/// The k with f_1(k) ≤ f < f_2(k).
///
/// # Errors
/// None: `None` outside 0.7079 … 89.13 Hz or for a non-finite `f_hz`.
///
/// # Examples
/// ```
/// use stochvib::models::operator_seat::band_index;
/// assert_eq!(band_index(3.0), Some(2)); // the 4 Hz band
/// assert_eq!(band_index(100.0), None);
/// ```
pub fn band_index(f_hz: f64) -> Option<usize> {
    octave_bands()
        .iter()
        .position(|b| f_hz >= b.lower_hz && f_hz < b.upper_hz)
}

/// Octave-band RMS of a sinusoid of amplitude `amplitude` at `f_hz` (Hz): amplitude/√2 in its band, 0 elsewhere.
///
/// # Formula
/// RMS = |A|/√2 in the band [`band_index`]`(f)`, 0 in the others.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::models::operator_seat::harmonic_band_rms;
/// let v = harmonic_band_rms(2.0, 10.0); // 10 Hz: the 8 Hz band
/// assert!((v[3] - 2f64.sqrt()).abs() < 1e-15); // 2/√2 = √2 up to one rounding
/// ```
pub fn harmonic_band_rms(amplitude: f64, f_hz: f64) -> Vec<f64> {
    let mut out = vec![0.0; OCTAVE_CENTRES_HZ.len()];
    if let Some(i) = band_index(f_hz) {
        out[i] = amplitude.abs() / SQRT_2;
    }
    out
}

/// Octave-band RMS of output `output` of `sys` under `exc`: √(2∫_band S_y dω) per band of [`octave_bands`],
/// by [`band_variance`].
///
/// # Formula
/// σ²_band = 2∫_{2πf_1}^{2πf_2} S_y(ω) dω = ∫_{f_1}^{f_2} G_y(f) df, G_y(f) = 4π S_y(2πf).
///
/// # Errors
/// Those of [`band_variance`] (mismatched inputs, quadrature failure).
///
/// # Examples
/// ```
/// use stochvib::models::operator_seat::{example_7_2, random_band_rms};
/// use stochvib::response::Excitation;
/// use stochvib::spectrum::{BandWhiteParameters, Convention, Domain};
/// let (seat, _, _) = example_7_2();
/// let g = BandWhiteParameters {
///     convention: Convention::OneSidedCyclic,
///     level: 1e-6,
///     lo: 3.0,
///     hi: 5.0,
///     domain: Domain::Temporal,
/// }
/// .build()
/// .unwrap();
/// let exc = Excitation::single(std::sync::Arc::new(g), 0.0).unwrap();
/// let v = random_band_rms(&seat.mdof().unwrap(), &exc, 1).unwrap();
/// assert!(v[2] > 0.0 && v[0] == 0.0);
/// ```
pub fn random_band_rms(sys: &dyn FrequencyResponse, exc: &Excitation, output: usize) -> Result<Vec<f64>> {
    octave_bands()
        .iter()
        .map(|b| {
            Ok(
                band_variance(sys, exc, output, 2.0 * PI * b.lower_hz, 2.0 * PI * b.upper_hz)?
                    .value
                    .max(0.0)
                    .sqrt(),
            )
        })
        .collect()
}

/// One row of Table 7.1.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitBand {
    /// Octave centre, Hz.
    pub centre_hz: f64,
    /// RMS acceleration limit, m/s².
    pub acceleration: f64,
    /// Printed acceleration level, dB.
    pub acceleration_db: f64,
    /// RMS velocity limit, m/s.
    pub velocity: f64,
    /// Printed velocity level, dB.
    pub velocity_db: f64,
    /// Transcription note (e.g. an inconsistent printed value).
    pub comment: Option<String>,
}

/// Sanitary limits of vertical vibration on the seat (Table 7.1), read from `data/reference/table-7-1.toml`.
///
/// # Formula
/// Levels in dB: L = 20 log₁₀(x/x₀) with x₀ = `reference_acceleration` (1e-6 m/s²) or `reference_velocity`
/// (5e-8 m/s) (the book prints no references; these reproduce its dB column except the 4 Hz velocity).
///
/// # Errors
/// [`SanitaryLimits::parse`] fails with [`Error::File`] on a missing or invalid key, an unknown key, or band
/// centres that are not the seven octave centres in order.
///
/// # Examples
/// ```
/// use stochvib::models::operator_seat::SanitaryLimits;
/// let t = SanitaryLimits::table_7_1().unwrap();
/// assert_eq!(t.bands[2].velocity, 0.0251);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SanitaryLimits {
    /// Provenance.
    pub source: String,
    /// x₀ for acceleration levels, m/s².
    pub reference_acceleration: f64,
    /// x₀ for velocity levels, m/s.
    pub reference_velocity: f64,
    /// One entry per octave band, in the order of [`OCTAVE_CENTRES_HZ`].
    pub bands: Vec<LimitBand>,
}

impl SanitaryLimits {
    /// Table 7.1 from the `data/reference/table-7-1.toml` of the source tree (embedded at compile time).
    ///
    /// # Errors
    /// As [`SanitaryLimits::parse`].
    pub fn table_7_1() -> Result<Self> {
        Self::parse(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/data/reference/table-7-1.toml")),
            Path::new("data/reference/table-7-1.toml"),
        )
    }

    /// Reads a limits file.
    ///
    /// # Errors
    /// [`Error::Io`] if unreadable, otherwise as [`SanitaryLimits::parse`].
    pub fn load(path: &Path) -> Result<Self> {
        let text = crate::fields::read_text_file(path)?;
        Self::parse(&text, path)
    }

    /// Parses limits-file text (`path` for messages).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn parse(text: &str, path: &Path) -> Result<Self> {
        let table: toml::Table = crate::fields::parse_toml(text, path)?;
        let f = Fields::new(path, "", &table);
        f.opt_string("title")?;
        f.opt_string("reference")?;
        let source = f.string("source")?.to_string();
        let reference_acceleration = f.quantity("reference_acceleration", Dim::ACCELERATION)?;
        let reference_velocity = f.quantity("reference_velocity", Dim::VELOCITY)?;
        let arr = f.require("band")?;
        let arr = arr
            .as_array()
            .ok_or_else(|| f.error("band", arr, "expected an array of tables [[band]]"))?;
        if arr.len() != OCTAVE_CENTRES_HZ.len() {
            return Err(f.error("band", arr.len(), "need the seven octave bands 1 ... 63 Hz"));
        }
        let mut bands = Vec::new();
        for (i, v) in arr.iter().enumerate() {
            let key = format!("band[{i}]");
            let t = v.as_table().ok_or_else(|| f.error(&key, v, "expected a table"))?;
            let b = Fields::new(path, &key, t);
            let cv = b.require("centre")?;
            let centre_hz = b.angular_frequency(cv, "centre", Dim::FREQUENCY)? / (2.0 * PI);
            if (centre_hz - OCTAVE_CENTRES_HZ[i]).abs() > 1e-9 * OCTAVE_CENTRES_HZ[i] {
                return Err(b.error("centre", cv, format!("expected {} Hz here", OCTAVE_CENTRES_HZ[i])));
            }
            let band = LimitBand {
                centre_hz: OCTAVE_CENTRES_HZ[i],
                acceleration: b.quantity("acceleration", Dim::ACCELERATION)?,
                acceleration_db: b.number("acceleration_db")?,
                velocity: b.quantity("velocity", Dim::VELOCITY)?,
                velocity_db: b.number("velocity_db")?,
                comment: b.opt_string("comment")?.map(str::to_string),
            };
            for (k, x) in [("acceleration", band.acceleration), ("velocity", band.velocity)] {
                if x <= 0.0 {
                    return Err(b.error(k, x, "a limit must be > 0"));
                }
            }
            b.finish()?;
            bands.push(band);
        }
        f.finish()?;
        Ok(SanitaryLimits {
            source,
            reference_acceleration,
            reference_velocity,
            bands,
        })
    }
}

/// Band-by-band comparison with the limits.
#[derive(Debug, Clone, PartialEq)]
pub struct BandCheck {
    /// Nominal octave centre, Hz.
    pub centre_hz: f64,
    /// IEC 61260-1 base-10 band edges [f_1, f_2), Hz.
    pub band_hz: (f64, f64),
    /// RMS seat velocity in the band, m/s.
    pub velocity_rms: f64,
    /// Limit, m/s.
    pub velocity_limit: f64,
    /// RMS seat acceleration in the band, m/s².
    pub acceleration_rms: f64,
    /// Limit, m/s².
    pub acceleration_limit: f64,
}

impl BandCheck {
    /// velocity_rms ≤ limit.
    pub fn velocity_ok(&self) -> bool {
        self.velocity_rms <= self.velocity_limit
    }
    /// acceleration_rms ≤ limit.
    pub fn acceleration_ok(&self) -> bool {
        self.acceleration_rms <= self.acceleration_limit
    }
}

/// Pairs band RMS values with the limits (pass/fail per band).
///
/// # Errors
/// Slices that do not have one value per octave band.
pub fn assess(velocity_rms: &[f64], acceleration_rms: &[f64], limits: &SanitaryLimits) -> Result<Vec<BandCheck>> {
    let n = OCTAVE_CENTRES_HZ.len();
    if velocity_rms.len() != n || acceleration_rms.len() != n || limits.bands.len() != n {
        return Err(Error::invalid(
            "band values",
            velocity_rms.len(),
            format!("need {n} octave bands"),
        ));
    }
    Ok(octave_bands()
        .iter()
        .enumerate()
        .map(|(i, b)| BandCheck {
            centre_hz: OCTAVE_CENTRES_HZ[i],
            band_hz: (b.lower_hz, b.upper_hz),
            velocity_rms: velocity_rms[i],
            velocity_limit: limits.bands[i].velocity,
            acceleration_rms: acceleration_rms[i],
            acceleration_limit: limits.bands[i].acceleration,
        })
        .collect())
}

/// Harmonic response of the seat (Example 7.2 quantities).
#[derive(Debug, Clone, PartialEq)]
pub struct HarmonicResponse {
    /// f = λ/2π, Hz.
    pub frequency_hz: f64,
    /// ν = λ/ω.
    pub nu: f64,
    /// η (7.42).
    pub eta: f64,
    /// η_rel (7.44).
    pub eta_rel: f64,
    /// η_eff = 1/η (7.43).
    pub eta_eff: f64,
    /// A = η A_u, m.
    pub amplitude: f64,
    /// A_y = η_rel A_u, m.
    pub relative_amplitude: f64,
    /// σ_v = Aλ/√2, m/s.
    pub velocity_rms: f64,
    /// σ_a = Aλ²/√2, m/s².
    pub acceleration_rms: f64,
    /// d = 2A_y, m (minimum free travel to the stops, (7.45)).
    pub free_travel: f64,
}

/// Operator + seat on a base-excited spring–damper (book 7.6).
///
/// # Formula
/// See the module docs.
///
/// # Errors
/// Constructors reject non-positive masses, stiffness, negative damping and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::operator_seat::OperatorSeat;
/// let seat = OperatorSeat { operator_mass: 80.0, seat_mass: 26.0, stiffness: 6500.0, damping: 0.0 }.with_damping_rate(4.22).unwrap();
/// assert!((seat.reduced_mass() - (5.0 / 7.0 * 80.0 + 26.0)).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct OperatorSeat {
    /// Operator mass, kg.
    pub operator_mass: f64,
    /// Seat mass, kg.
    pub seat_mass: f64,
    /// c, N/m.
    pub stiffness: f64,
    /// b, N s/m.
    pub damping: f64,
}

impl OperatorSeat {
    /// The seat of these fields, checked: the operator's and the seat's masses (kg), c (N/m) and b (N s/m) as
    /// named fields instead of four bare numbers of different meaning.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        let OperatorSeat {
            operator_mass,
            seat_mass,
            stiffness,
            damping,
        } = self;
        require_positive("operator_mass", operator_mass)?;
        if !(seat_mass.is_finite() && seat_mass >= 0.0) {
            return Err(Error::invalid("seat_mass", seat_mass, "must be finite and >= 0"));
        }
        require_positive("stiffness", stiffness)?;
        if !(damping.is_finite() && damping >= 0.0) {
            return Err(Error::invalid("damping", damping, "must be finite and >= 0"));
        }
        Ok(OperatorSeat {
            operator_mass,
            seat_mass,
            stiffness,
            damping,
        })
    }

    /// The seat of these fields with the damping set from the book's damping rate h (s⁻¹): b = 2 h m_pr
    /// replaces `damping`; checked.
    ///
    /// # Errors
    /// h < 0 or non-finite; then as [`OperatorSeat::build`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::operator_seat::OperatorSeat;
    /// let unset = OperatorSeat { operator_mass: 70.0, seat_mass: 20.0, stiffness: 2.0e4, damping: 0.0 };
    /// let seat = unset.with_damping_rate(3.0).unwrap();
    /// assert!((seat.damping_rate() - 3.0).abs() < 1e-12);
    /// ```
    pub fn with_damping_rate(self, h: f64) -> Result<Self> {
        if !(h.is_finite() && h >= 0.0) {
            return Err(Error::invalid("damping_rate", h, "must be finite and >= 0"));
        }
        let m_pr = 5.0 / 7.0 * self.operator_mass + self.seat_mass;
        OperatorSeat {
            damping: 2.0 * h * m_pr,
            ..self
        }
        .build()
    }

    /// m_pr = (5/7) m_operator + m_seat, kg.
    pub fn reduced_mass(&self) -> f64 {
        5.0 / 7.0 * self.operator_mass + self.seat_mass
    }
    /// ω = √(c/m_pr), rad/s.
    pub fn natural_frequency(&self) -> f64 {
        (self.stiffness / self.reduced_mass()).sqrt()
    }
    /// h = b/(2 m_pr), s⁻¹.
    pub fn damping_rate(&self) -> f64 {
        self.damping / (2.0 * self.reduced_mass())
    }
    /// β = h/ω.
    pub fn damping_ratio(&self) -> f64 {
        self.damping_rate() / self.natural_frequency()
    }
    /// η(λ) (7.42), λ in rad/s.
    pub fn transmissibility(&self, lambda: f64) -> f64 {
        transmissibility(lambda / self.natural_frequency(), self.damping_ratio())
    }
    /// η_rel(λ) = ν²/√((1−ν²)² + 4β²ν²) (7.44).
    pub fn relative_transmissibility(&self, lambda: f64) -> f64 {
        let nu = lambda / self.natural_frequency();
        let b = self.damping_ratio();
        nu * nu / ((1.0 - nu * nu).powi(2) + 4.0 * b * b * nu * nu).sqrt()
    }

    /// Steady-state response to u = A_u sin λt (A_u in m, λ in rad/s).
    ///
    /// # Errors
    /// A_u < 0, λ ≤ 0, non-finite values.
    pub fn harmonic(&self, base_amplitude: f64, lambda: f64) -> Result<HarmonicResponse> {
        if !(base_amplitude.is_finite() && base_amplitude >= 0.0) {
            return Err(Error::invalid(
                "base_amplitude",
                base_amplitude,
                "must be finite and >= 0",
            ));
        }
        require_positive("lambda", lambda)?;
        let eta = self.transmissibility(lambda);
        let eta_rel = self.relative_transmissibility(lambda);
        let a = eta * base_amplitude;
        let ay = eta_rel * base_amplitude;
        Ok(HarmonicResponse {
            frequency_hz: lambda / (2.0 * PI),
            nu: lambda / self.natural_frequency(),
            eta,
            eta_rel,
            eta_eff: 1.0 / eta,
            amplitude: a,
            relative_amplitude: ay,
            velocity_rms: a * lambda / SQRT_2,
            acceleration_rms: a * lambda * lambda / SQRT_2,
            free_travel: 2.0 * ay,
        })
    }

    /// Base-excited model (input 0: base displacement u, m) with outputs `seat` (z, m), `seat_vel` (m/s),
    /// `seat_acc` (m/s²), `travel` (z − u, m).
    ///
    /// # Errors
    /// None for a validated model (the `Result` is the [`Mdof`] constructor's).
    pub fn mdof(&self) -> Result<Mdof> {
        MassSpringDamper {
            mass: self.reduced_mass(),
            stiffness: self.stiffness,
            damping: self.damping,
            drive: Drive::Base,
        }
        .build()?
        .with_output("seat", Quantity::Displacement(vec![1.0]))?
        .with_output("seat_vel", Quantity::Velocity(vec![1.0]))?
        .with_output("seat_acc", Quantity::Acceleration(vec![1.0]))?
        .with_output("travel", Quantity::Deflection(0))
    }

    /// The transfer function of the seat acceleration `seat_acc` (m/s²) from the base displacement u (m),
    /// as (numerator, denominator), ascending in s (rad/s): the closed form of [`OperatorSeat::mdof`]'s
    /// output, for parameter studies that need no state space per point (see
    /// [`WeightedEvaluator::a_w_rational`](crate::comfort::WeightedEvaluator::a_w_rational)).
    ///
    /// # Formula
    /// ```text
    /// m_pr z̈ + b(ż − u̇) + c(z − u) = 0   ⇒   H_z̈(s) = s²(b s + c)/(m_pr s² + b s + c)
    /// ```
    ///
    /// # Errors
    /// None (a validated model).
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::operator_seat::OperatorSeat;
    /// use stochvib::system::FrequencyResponse;
    /// let seat = OperatorSeat { operator_mass: 80.0, seat_mass: 26.0, stiffness: 6500.0, damping: 600.0 }.build().unwrap();
    /// let (num, den) = seat.seat_acc_transfer();
    /// let m = seat.instance().unwrap();
    /// let w = 9.0;
    /// let s = nalgebra::Complex::new(0.0, w);
    /// let h = (num[2] * s * s + num[3] * s * s * s) / (den[0] + den[1] * s + den[2] * s * s);
    /// let i = m.system.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
    /// assert!((m.system.response(w)[(i, 0)] - h).norm() < 1e-12 * h.norm());
    /// ```
    pub fn seat_acc_transfer(&self) -> ([f64; 4], [f64; 3]) {
        let (c, b) = (self.stiffness, self.damping);
        ([0.0, 0.0, c, b], [c, b, self.reduced_mass()])
    }

    /// The model with a single random base displacement ([`InputLayout::Single`]).
    ///
    /// # Errors
    /// As [`OperatorSeat::mdof`].
    pub fn instance(&self) -> Result<ModelInstance> {
        Ok(ModelInstance {
            system: Arc::new(self.mdof()?),
            layout: InputLayout::Single,
            description: format!(
                "operator seat (Sukharev 7.6): m_operator = {} kg, m_seat = {} kg (m_pr = {:.4} kg), c = {} N/m, \
                 b = {} N s/m, base displacement input",
                self.operator_mass,
                self.seat_mass,
                self.reduced_mass(),
                self.stiffness,
                self.damping
            ),
        })
    }

    /// Octave-band check of a harmonic base motion u = A_u sin λt: the seat's velocity and acceleration RMS in
    /// the band containing λ/2π, 0 elsewhere.
    ///
    /// # Errors
    /// As [`OperatorSeat::harmonic`].
    pub fn assess_harmonic(&self, base_amplitude: f64, lambda: f64, limits: &SanitaryLimits) -> Result<Vec<BandCheck>> {
        let r = self.harmonic(base_amplitude, lambda)?;
        let v = harmonic_band_rms(r.amplitude * lambda, r.frequency_hz);
        let a = harmonic_band_rms(r.amplitude * lambda * lambda, r.frequency_hz);
        assess(&v, &a, limits)
    }

    /// Octave-band check of a random base displacement with temporal two-sided density `base` (m²·s/rad).
    ///
    /// # Errors
    /// Non-temporal spectrum; quadrature failure.
    pub fn assess_random(&self, base: Arc<dyn Spectrum>, limits: &SanitaryLimits) -> Result<Vec<BandCheck>> {
        let sys = self.mdof()?;
        let exc = Excitation::single(base, 0.0)?;
        let v = random_band_rms(&sys, &exc, 1)?;
        let a = random_band_rms(&sys, &exc, 2)?;
        assess(&v, &a, limits)
    }
}

/// Reads a `kind = "operator-seat"` `[model]` table: `operator_mass`, `seat_mass`, `stiffness`, and exactly
/// one of `damping` (N s/m) or `damping_rate` (the book's h, 1/s).
///
/// # Errors
/// [`Error::File`] naming the key for a missing or invalid value, or both / neither damping key.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    let mo = f.quantity("operator_mass", Dim::MASS)?;
    let ms = f.quantity("seat_mass", Dim::MASS)?;
    let c = f.quantity("stiffness", Dim::STIFFNESS)?;
    let seat = match (f.opt_quantity("damping", Dim::DAMPING)?, f.get("damping_rate")) {
        (Some(_), Some(v)) => {
            return Err(f.error("damping_rate", v, "give either `damping` or `damping_rate`, not both"))
        }
        (Some(b), None) => OperatorSeat {
            operator_mass: mo,
            seat_mass: ms,
            stiffness: c,
            damping: b,
        }
        .build(),
        (None, Some(_)) => OperatorSeat {
            operator_mass: mo,
            seat_mass: ms,
            stiffness: c,
            damping: 0.0,
        }
        .with_damping_rate(f.quantity("damping_rate", Dim::FREQUENCY)?),
        (None, None) => {
            return Err(f.error(
                "damping",
                "<missing>",
                "give `damping` (N s/m) or `damping_rate` (the book's h, 1/s)",
            ))
        }
    }
    .map_err(|e| f.wrap_param(e, "kind"))?;
    seat.instance()
}

/// Example 7.2 of Sukharev (2012) 7.6 (seat): m_operator = 80 kg, m_seat = 26 kg, c = 6500 N/m, h = 4.22 s⁻¹;
/// returns the model, A_u = 0.0035 m and λ = 6π rad/s.
pub fn example_7_2() -> (OperatorSeat, f64, f64) {
    (
        OperatorSeat {
            operator_mass: 80.0,
            seat_mass: 26.0,
            stiffness: 6500.0,
            damping: 0.0,
        }
        .with_damping_rate(4.22)
        .expect("valid book parameters"),
        0.0035,
        6.0 * PI,
    )
}

/// The example of the book rows of this model.
const EXAMPLE_7_2: &str = "Sukharev (2012) 7.6, Example 7.2 (operator seat)";

/// One book row of Example 7.2.
fn seat_row(q: &str, unit: &str, printed: Option<f64>, computed: Option<f64>, why: &str) -> BookRow {
    BookRow {
        example: EXAMPLE_7_2.into(),
        quantity: q.into(),
        unit: unit.into(),
        printed,
        computed,
        explanation: why.into(),
    }
}

/// Book rows of Example 7.2 (seat): every printed number, and the verdict in the conclusion of the example.
pub fn book_rows() -> Vec<BookRow> {
    let (seat, au, lambda) = example_7_2();
    let r = seat.harmonic(au, lambda).ok();
    let mut rows = response_rows(&seat, r.as_ref());
    rows.extend(limit_rows(r.as_ref(), lambda));
    rows
}

/// The rows of the seat's reduced mass, natural frequency, damping and harmonic response `r`.
fn response_rows(seat: &OperatorSeat, r: Option<&HarmonicResponse>) -> Vec<BookRow> {
    let row = seat_row;
    let g = |f: fn(&HarmonicResponse) -> f64| r.map(f);
    vec![
        row(
            "m_pr",
            "kg",
            Some(83.0),
            Some(seat.reduced_mass()),
            "5/7*80 + 26 = 83.14, printed rounded",
        ),
        row(
            "omega",
            "rad/s",
            Some(8.85),
            Some(seat.natural_frequency()),
            "sqrt(c/m_pr)",
        ),
        row(
            "beta = h/omega",
            "1",
            Some(0.477),
            Some(seat.damping_ratio()),
            "h = 4.22 1/s",
        ),
        row("nu = lambda/omega", "1", Some(2.13), g(|r| r.nu), "lambda = 6 pi rad/s"),
        row(
            "eta (7.42)",
            "1",
            Some(0.56),
            g(|r| r.eta),
            "rounding (the book's rounded beta, nu give 0.5552)",
        ),
        row("eta_rel (7.44)", "1", Some(1.11), g(|r| r.eta_rel), ""),
        row(
            "eta_eff = 1/eta",
            "1",
            Some(1.78),
            g(|r| r.eta_eff),
            "book: 1/0.56 (= 1.786) printed 1.78",
        ),
        row("A = A_u eta", "m", Some(0.00196), g(|r| r.amplitude), ""),
        row("A_y = A_u eta_rel", "m", Some(0.0039), g(|r| r.relative_amplitude), ""),
        row(
            "sigma_v = A lambda/sqrt 2",
            "m/s",
            Some(0.026),
            g(|r| r.velocity_rms),
            "",
        ),
        row(
            "sigma_a = A lambda^2/sqrt 2",
            "m/s^2",
            Some(0.49),
            g(|r| r.acceleration_rms),
            "",
        ),
        row(
            "f = lambda/(2 pi)",
            "Hz",
            Some(3.0),
            g(|r| r.frequency_hz),
            "in the 4 Hz octave band",
        ),
    ]
}

/// The rows of the sanitary limits of the 4 Hz octave band (Table 7.1) and the example's verdict against
/// them, for the harmonic response `r` at the forcing frequency λ (rad/s).
fn limit_rows(r: Option<&HarmonicResponse>, lambda: f64) -> Vec<BookRow> {
    let row = seat_row;
    let g = |f: fn(&HarmonicResponse) -> f64| r.map(f);
    let limits = SanitaryLimits::table_7_1().ok();
    let band = band_index(lambda / (2.0 * PI));
    let lim = |f: fn(&LimitBand) -> f64| -> Option<f64> {
        let l = limits.as_ref()?;
        Some(f(&l.bands[band?]))
    };
    let vel_ratio = g(|r| r.velocity_rms).zip(lim(|b| b.velocity)).map(|(a, b)| a / b);
    let acc_ratio = g(|r| r.acceleration_rms)
        .zip(lim(|b| b.acceleration))
        .map(|(a, b)| a / b);
    vec![
        row(
            "velocity limit, 4 Hz band",
            "m/s",
            Some(0.025),
            lim(|b| b.velocity),
            "Table 7.1: 2.51e-2 m/s; the text rounds to 0.025",
        ),
        row(
            "acceleration limit, 4 Hz band",
            "m/s^2",
            Some(0.57),
            lim(|b| b.acceleration),
            "Table 7.1",
        ),
        row(
            "d = 2 A_y",
            "m",
            Some(0.008),
            g(|r| r.free_travel),
            "the book states the bound d >= 0.008 m, i.e. 2 A_y = 0.00778 m rounded up",
        ),
        row(
            "sigma_v / velocity limit (4 Hz)",
            "1",
            None,
            vel_ratio,
            "the book (conclusion of Example 7.2) says the seat meets the norm; it does not: \
             sigma_v = 0.0259 m/s exceeds 0.0251 m/s (ratio > 1; with the printed 0.026 > 0.025 too)",
        ),
        row(
            "sigma_a / acceleration limit (4 Hz)",
            "1",
            None,
            acc_ratio,
            "acceleration criterion met (ratio < 1)",
        ),
    ]
}
