//! The random input of a system: one process felt by several inputs with delays and gains (a road track
//! under several wheels), or independent processes.

use crate::error::{require_finite, Error, Result};
use crate::spectrum::{Asymptote, AtSpeed, Domain, Spectrum};
use nalgebra::{Complex, DMatrix};
use std::sync::Arc;

/// The stationary random input of a system with m inputs.
///
/// # Formula
/// * `Track`: u_j(t) = g_j x(t − τ_j) + mean_j, one process x with two-sided density S(ω) felt by every
///   input with a pure delay τ_j = ℓ_j/v (s) and gain g_j:
///   S_jk(ω) = g_j g_k S(ω) e^{−iω(τ_j − τ_k)}.
/// * `Independent`: u_j independent processes, S_u = diag(S_j(ω)).
///
/// # Errors
/// Constructors reject non-temporal spectra, negative or non-finite delays, and mismatched lengths.
///
/// # Examples
/// ```
/// use stochvib::response::Excitation;
/// use stochvib::spectrum::{Exponential, Domain};
/// use std::sync::Arc;
/// let x = Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap());
/// // two wheels 0.6 m apart at 10 m/s: rear delayed by 0.06 s
/// let e = Excitation::track(x, vec![0.0, 0.06], vec![1.0, 1.0], 0.0).unwrap();
/// assert_eq!(e.n_inputs(), 2);
/// ```
#[derive(Debug, Clone)]
pub enum Excitation {
    /// One process felt by several inputs with delays and gains.
    Track {
        /// The process (temporal).
        spectrum: Arc<dyn Spectrum>,
        /// τ_j, s.
        delays: Vec<f64>,
        /// g_j.
        gains: Vec<f64>,
        /// Mean of the process x.
        mean: f64,
    },
    /// Independent processes, one per input, with their means.
    Independent {
        /// One spectrum per input.
        spectra: Vec<Arc<dyn Spectrum>>,
        /// One mean per input.
        means: Vec<f64>,
    },
}

impl Excitation {
    /// One process x felt by every input j as g_j x(t − τ_j).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn track(spectrum: Arc<dyn Spectrum>, delays: Vec<f64>, gains: Vec<f64>, mean: f64) -> Result<Self> {
        if spectrum.domain() != Domain::Temporal {
            return Err(Error::invalid(
                "spectrum",
                spectrum.describe(),
                "the system is driven in time: turn a spatial road spectrum into time with a speed first",
            ));
        }
        if delays.len() != gains.len() || delays.is_empty() {
            return Err(Error::invalid(
                "delays",
                delays.len(),
                format!("need one delay per gain ({})", gains.len()),
            ));
        }
        for (j, &t) in delays.iter().enumerate() {
            if !(t.is_finite() && t >= 0.0) {
                return Err(Error::invalid(&format!("delays[{j}]"), t, "must be finite and >= 0"));
            }
        }
        for (j, &g) in gains.iter().enumerate() {
            require_finite(&format!("gains[{j}]"), g)?;
        }
        require_finite("mean", mean)?;
        Ok(Excitation::Track {
            spectrum,
            delays,
            gains,
            mean,
        })
    }

    /// A single process driving a single-input system.
    ///
    /// # Errors
    /// As [`Excitation::track`].
    pub fn single(spectrum: Arc<dyn Spectrum>, mean: f64) -> Result<Self> {
        Excitation::track(spectrum, vec![0.0], vec![1.0], mean)
    }

    /// A road profile (a spatial spectrum, Ω in rad/m) driven over at `speed` (m/s), felt by the wheels at
    /// `positions` (m behind the first contact, e.g. `[0.0]` for one wheel, `[0.0, 2.7]` for two axles):
    /// the temporal spectrum [`AtSpeed`] with delays ℓ_j/v, unit gains, zero mean.
    ///
    /// # Errors
    /// A spectrum that is not spatial, a speed that is not positive, negative positions.
    ///
    /// # Examples
    /// ```
    /// use stochvib::response::Excitation;
    /// use stochvib::spectrum::{IsoClass, PowerLaw};
    /// use std::sync::Arc;
    /// let road = Arc::new(PowerLaw::iso_class(IsoClass::C).unwrap());
    /// let e = Excitation::road(road, 20.0, &[0.0, 2.7]).unwrap();
    /// assert_eq!(e.n_inputs(), 2);
    /// ```
    pub fn road(spectrum: Arc<dyn Spectrum>, speed: f64, positions: &[f64]) -> Result<Self> {
        let temporal = Arc::new(AtSpeed::new(spectrum, speed)?);
        for (j, &p) in positions.iter().enumerate() {
            if !(p.is_finite() && p >= 0.0) {
                return Err(Error::invalid(&format!("positions[{j}]"), p, "must be finite and >= 0"));
            }
        }
        let delays = positions.iter().map(|p| p / speed).collect();
        Excitation::track(temporal, delays, vec![1.0; positions.len()], 0.0)
    }

    /// Independent processes, one per input.
    ///
    /// # Errors
    /// Non-temporal spectra, mismatched lengths, non-finite means.
    pub fn independent(spectra: Vec<Arc<dyn Spectrum>>, means: Vec<f64>) -> Result<Self> {
        if spectra.len() != means.len() || spectra.is_empty() {
            return Err(Error::invalid(
                "means",
                means.len(),
                format!("need one mean per spectrum ({})", spectra.len()),
            ));
        }
        for (j, s) in spectra.iter().enumerate() {
            if s.domain() != Domain::Temporal {
                return Err(Error::invalid(
                    &format!("spectra[{j}]"),
                    s.describe(),
                    "must be temporal",
                ));
            }
            require_finite(&format!("means[{j}]"), means[j])?;
        }
        Ok(Excitation::Independent { spectra, means })
    }

    /// Number of system inputs this excitation drives.
    pub fn n_inputs(&self) -> usize {
        match self {
            Excitation::Track { gains, .. } => gains.len(),
            Excitation::Independent { spectra, .. } => spectra.len(),
        }
    }

    /// Mean of every input.
    pub fn means(&self) -> Vec<f64> {
        match self {
            Excitation::Track { gains, mean, .. } => gains.iter().map(|g| g * mean).collect(),
            Excitation::Independent { means, .. } => means.clone(),
        }
    }

    /// The input spectra involved.
    pub fn spectra(&self) -> Vec<Arc<dyn Spectrum>> {
        match self {
            Excitation::Track { spectrum, .. } => vec![spectrum.clone()],
            Excitation::Independent { spectra, .. } => spectra.clone(),
        }
    }

    /// Whether all delays are equal (then a common delay does not change any stationary statistic and the
    /// exact state-space methods apply).
    pub fn delay_free(&self) -> bool {
        match self {
            Excitation::Track { delays, .. } => delays.iter().all(|t| *t == delays[0]),
            Excitation::Independent { .. } => true,
        }
    }

    /// Two-sided density of output row `h_row` (1 × m row of H(iω)) at ω: (H S_u Hᴴ).
    pub fn output_density(&self, h_row: &[Complex<f64>], omega: f64) -> f64 {
        match self {
            Excitation::Track {
                spectrum,
                delays,
                gains,
                ..
            } => {
                let mut z = Complex::new(0.0, 0.0);
                for ((h, g), t) in h_row.iter().zip(gains).zip(delays) {
                    z += h * *g * Complex::from_polar(1.0, -omega * t);
                }
                spectrum.density(omega) * z.norm_sqr()
            }
            Excitation::Independent { spectra, .. } => h_row
                .iter()
                .zip(spectra)
                .map(|(h, s)| h.norm_sqr() * s.density(omega))
                .sum(),
        }
    }

    /// The cross-spectral matrix S_u(ω), m × m, Hermitian.
    pub fn matrix(&self, omega: f64) -> DMatrix<Complex<f64>> {
        match self {
            Excitation::Track {
                spectrum,
                delays,
                gains,
                ..
            } => {
                let s = spectrum.density(omega);
                DMatrix::from_fn(gains.len(), gains.len(), |j, k| {
                    Complex::from_polar(s * gains[j] * gains[k], -omega * (delays[j] - delays[k]))
                })
            }
            Excitation::Independent { spectra, .. } => DMatrix::from_fn(spectra.len(), spectra.len(), |j, k| {
                if j == k {
                    Complex::new(spectra[j].density(omega), 0.0)
                } else {
                    Complex::new(0.0, 0.0)
                }
            }),
        }
    }

    /// Breakpoints of the input spectra.
    pub fn breakpoints(&self) -> Vec<f64> {
        self.spectra().iter().flat_map(|s| s.breakpoints()).collect()
    }

    /// (low, high) of the union of supports.
    pub fn support(&self) -> (f64, f64) {
        self.spectra()
            .iter()
            .map(|s| s.support())
            .fold((f64::INFINITY, 0.0), |(a, b), (c, d)| (a.min(c), b.max(d)))
    }

    /// Per-input high- and low-frequency asymptotes of the input densities (input j's own process).
    pub fn asymptotes(&self) -> Vec<(Asymptote, Asymptote)> {
        match self {
            Excitation::Track { spectrum, gains, .. } => gains
                .iter()
                .map(|_| (spectrum.low_frequency(), spectrum.high_frequency()))
                .collect(),
            Excitation::Independent { spectra, .. } => spectra
                .iter()
                .map(|s| (s.low_frequency(), s.high_frequency()))
                .collect(),
        }
    }
}
