//! The random input of a system: one process felt by several inputs with delays and gains (a road track
//! under several wheels), independent processes, or in general independent sources (single processes or
//! correlated multi-component processes such as two road tracks) each felt by inputs with delays and gains.

use super::sources::{self, InputMap, Source};
use crate::coherence::SpectralMatrix;
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
/// * `Sources`: independent sources s (a process, or a process of several correlated components with the
///   cross-spectral matrix S_s(ω)), input j driven by u_j(t) = g_j x_{s_j c_j}(t − τ_j) + μ_j:
///   S_jk(ω) = g_j g_k S_{s, c_j c_k}(ω) e^{−iω(τ_j − τ_k)} when s_j = s_k = s, 0 otherwise.
///   `Track` and `Independent` are its one-source and one-input-per-source special cases, kept as their
///   own variants (with their own fast paths) so that their numbers stay bit-identical.
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
    /// Independent sources, each felt by inputs with delays, gains and means.
    Sources {
        /// The independent sources.
        sources: Vec<Source>,
        /// One entry per system input.
        inputs: Vec<InputMap>,
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

    /// Independent sources felt by the system inputs as `inputs` describes (one entry per system input).
    ///
    /// # Formula
    /// See the type's `Sources` variant.
    ///
    /// # Errors
    /// No source or no input; a non-temporal spectrum; a spectral matrix that is not Hermitian positive
    /// semi-definite on a logarithmic grid of 121 frequencies in [1e-3, 1e4] rad/s and at its breakpoints; an
    /// input naming a source or component that does not exist; a negative or non-finite delay; a non-finite
    /// gain or mean. Each error names the entry (`sources[s]`, `inputs[j].delay`, ...), the value and why.
    ///
    /// # Examples
    /// ```
    /// use stochvib::coherence::{ConstantCoherence, TwoTracks};
    /// use stochvib::response::{Excitation, InputMap, Source};
    /// use stochvib::spectrum::{IsoClass, PowerLaw};
    /// use std::sync::Arc;
    /// // four wheels on two tracks (wheelbase 2.7 m at 20 m/s)
    /// let road = Arc::new(PowerLaw::iso_class(IsoClass::C).unwrap());
    /// let tracks = Arc::new(TwoTracks::new(road, Arc::new(ConstantCoherence::new(0.3).unwrap()), 20.0).unwrap());
    /// let wheel = |c: usize, x: f64| InputMap { source: 0, component: c, delay: x / 20.0, gain: 1.0, mean: 0.0 };
    /// let e = Excitation::sources(vec![Source::Matrix(tracks)],
    ///     vec![wheel(0, 0.0), wheel(1, 0.0), wheel(0, 2.7), wheel(1, 2.7)]).unwrap();
    /// assert_eq!(e.n_inputs(), 4);
    /// ```
    pub fn sources(sources: Vec<Source>, inputs: Vec<InputMap>) -> Result<Self> {
        sources::validate(&sources, &inputs)?;
        Ok(Excitation::Sources { sources, inputs })
    }

    /// Two tracks driven over by wheels: wheel j on track `wheels[j].0` (0 = left, 1 = right) at
    /// `wheels[j].1` m behind the first contact, unit gains, zero means.
    ///
    /// # Formula
    /// u_j(t) = x_{c_j}(t − ℓ_j/v), S as in [`TwoTracks`](crate::coherence::TwoTracks).
    ///
    /// # Errors
    /// As [`Excitation::sources`]; a track other than 0 or 1, a negative position.
    ///
    /// # Examples
    /// ```
    /// use stochvib::coherence::{IsotropicCoherence, TwoTracks};
    /// use stochvib::response::Excitation;
    /// use stochvib::spectrum::{IsoClass, PowerLaw};
    /// use std::sync::Arc;
    /// let road = Arc::new(PowerLaw::iso_class(IsoClass::B).unwrap());
    /// let t = Arc::new(TwoTracks::new(road, Arc::new(IsotropicCoherence::new(1.6, 2.0).unwrap()), 15.0).unwrap());
    /// let e = Excitation::two_tracks(t, &[(0, 0.0), (1, 0.0), (0, 2.5), (1, 2.5)]).unwrap();
    /// assert!(!e.delay_free());
    /// ```
    pub fn two_tracks(tracks: Arc<crate::coherence::TwoTracks>, wheels: &[(usize, f64)]) -> Result<Self> {
        let v = tracks.speed();
        let inputs = wheels
            .iter()
            .enumerate()
            .map(|(j, &(c, x))| {
                if c > 1 {
                    return Err(Error::invalid(
                        &format!("wheels[{j}].track"),
                        c,
                        "0 (left) or 1 (right)",
                    ));
                }
                if !(x.is_finite() && x >= 0.0) {
                    return Err(Error::invalid(
                        &format!("wheels[{j}].position"),
                        x,
                        "must be finite and >= 0 m",
                    ));
                }
                Ok(InputMap {
                    source: 0,
                    component: c,
                    delay: x / v,
                    gain: 1.0,
                    mean: 0.0,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let m: Arc<dyn SpectralMatrix> = tracks;
        Excitation::sources(vec![Source::Matrix(m)], inputs)
    }

    /// The same excitation in the general `Sources` form (a track is one process source, independent
    /// processes one source each); a `Sources` excitation is returned as it is.
    ///
    /// # Formula
    /// Track: s_j = 0, c_j = 0, τ_j, g_j, μ_j = g_j μ. Independent: s_j = j, τ_j = 0, g_j = 1, μ_j.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::response::Excitation;
    /// use stochvib::spectrum::{Domain, Exponential};
    /// use std::sync::Arc;
    /// let x = Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap());
    /// let e = Excitation::track(x, vec![0.0, 0.06], vec![1.0, 1.0], 0.0).unwrap().to_sources();
    /// assert!(matches!(e, Excitation::Sources { .. }));
    /// ```
    pub fn to_sources(&self) -> Excitation {
        match self {
            Excitation::Track {
                spectrum,
                delays,
                gains,
                mean,
            } => Excitation::Sources {
                sources: vec![Source::Process(spectrum.clone())],
                inputs: delays
                    .iter()
                    .zip(gains)
                    .map(|(&delay, &gain)| InputMap {
                        source: 0,
                        component: 0,
                        delay,
                        gain,
                        mean: gain * mean,
                    })
                    .collect(),
            },
            Excitation::Independent { spectra, means } => Excitation::Sources {
                sources: spectra.iter().map(|s| Source::Process(s.clone())).collect(),
                inputs: means
                    .iter()
                    .enumerate()
                    .map(|(j, &mean)| InputMap {
                        source: j,
                        component: 0,
                        delay: 0.0,
                        gain: 1.0,
                        mean,
                    })
                    .collect(),
            },
            e @ Excitation::Sources { .. } => e.clone(),
        }
    }

    /// Number of system inputs this excitation drives.
    pub fn n_inputs(&self) -> usize {
        match self {
            Excitation::Track { gains, .. } => gains.len(),
            Excitation::Independent { spectra, .. } => spectra.len(),
            Excitation::Sources { inputs, .. } => inputs.len(),
        }
    }

    /// Mean of every input.
    pub fn means(&self) -> Vec<f64> {
        match self {
            Excitation::Track { gains, mean, .. } => gains.iter().map(|g| g * mean).collect(),
            Excitation::Independent { means, .. } => means.clone(),
            Excitation::Sources { inputs, .. } => inputs.iter().map(|i| i.mean).collect(),
        }
    }

    /// The input spectra involved: one per independent component (for `Sources`, each source's
    /// components in order; these are the generators of a spectral Monte Carlo run).
    pub fn spectra(&self) -> Vec<Arc<dyn Spectrum>> {
        match self {
            Excitation::Track { spectrum, .. } => vec![spectrum.clone()],
            Excitation::Independent { spectra, .. } => spectra.clone(),
            Excitation::Sources { sources, .. } => sources
                .iter()
                .flat_map(|s| (0..s.n_components()).map(move |c| s.component(c)))
                .collect(),
        }
    }

    /// Whether all delays are equal (then a common delay does not change any stationary statistic and the
    /// exact state-space methods apply).
    pub fn delay_free(&self) -> bool {
        match self {
            Excitation::Track { delays, .. } => delays.iter().all(|t| *t == delays[0]),
            Excitation::Independent { .. } => true,
            Excitation::Sources { inputs, .. } => inputs.iter().all(|i| i.delay == inputs[0].delay),
        }
    }

    /// What the inputs are, for a reason that mentions their delays: "the inputs are delayed copies of one
    /// process (wheels on a track)" for a track; for independent sources the sources themselves ("the inputs
    /// are delayed tracks of a road of two tracks with a coherence", "… of 2 independent sources: …").
    ///
    /// # Examples
    /// ```
    /// use stochvib::response::Excitation;
    /// use stochvib::spectrum::{Domain, Exponential};
    /// use std::sync::Arc;
    /// let x = Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap());
    /// let e = Excitation::track(x, vec![0.0, 0.1], vec![1.0, 1.0], 0.0).unwrap();
    /// assert!(e.inputs_described().contains("delayed copies of one process"));
    /// ```
    pub fn inputs_described(&self) -> String {
        match self {
            Excitation::Track { .. } => "the inputs are delayed copies of one process (wheels on a track)".into(),
            Excitation::Independent { spectra, .. } => {
                format!("the inputs are {} independent processes", spectra.len())
            }
            Excitation::Sources { sources, .. } => {
                let what = |s: &Source| match s.n_components() {
                    1 => "one process".to_string(),
                    2 => "a road of two tracks with a coherence".to_string(),
                    k => format!("{k} correlated components with a cross-spectral matrix"),
                };
                match sources.as_slice() {
                    [s] if s.n_components() > 1 => format!(
                        "the inputs are delayed tracks of {} (left and right wheels at their positions), not \
                         copies of one process",
                        what(s)
                    ),
                    [s] => format!("the inputs are delayed copies of {}", what(s)),
                    all => format!(
                        "the inputs are delayed components of {} independent sources: {}",
                        all.len(),
                        all.iter().map(what).collect::<Vec<_>>().join(", ")
                    ),
                }
            }
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
            Excitation::Sources { sources, inputs } => sources::density(sources, inputs, h_row, omega),
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
            Excitation::Sources { sources, inputs } => {
                let mats: Vec<_> = sources
                    .iter()
                    .map(|s| match s {
                        Source::Process(p) => DMatrix::from_element(1, 1, Complex::new(p.density(omega), 0.0)),
                        Source::Matrix(m) => m.matrix(omega),
                    })
                    .collect();
                DMatrix::from_fn(inputs.len(), inputs.len(), |j, k| {
                    let (a, b) = (&inputs[j], &inputs[k]);
                    if a.source != b.source {
                        return Complex::new(0.0, 0.0);
                    }
                    mats[a.source][(a.component, b.component)]
                        * (a.gain * b.gain)
                        * Complex::from_polar(1.0, -omega * (a.delay - b.delay))
                })
            }
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
            Excitation::Sources { sources, inputs } => inputs
                .iter()
                .map(|i| {
                    let s = sources[i.source].component(i.component);
                    (s.low_frequency(), s.high_frequency())
                })
                .collect(),
        }
    }
}
