//! Independent input sources and the map from system inputs to them: the general form of an
//! [`Excitation`] (a road of two correlated tracks, a force, ... each felt by inputs with delays and
//! gains), and the exact variance per source.

use super::delayed::DelayedCovariance;
use super::variance::{variance_lyapunov, LyapunovMoments};
use super::Excitation;
use crate::coherence::SpectralMatrix;
use crate::error::{Error, Result};
use crate::spectrum::Spectrum;
use crate::system::FrequencyResponse;
use nalgebra::Complex;
use std::sync::Arc;

type C64 = Complex<f64>;

/// One independent random source: a single process or a process of several correlated components.
///
/// # Formula
/// `Process`: one component of two-sided density S(ω). `Matrix`: m components with the cross-spectral
/// matrix S(ω) ([`SpectralMatrix`]). Different sources are independent (their cross-spectra vanish).
///
/// # Errors
/// None here: [`Excitation::sources`] validates.
///
/// # Examples
/// ```
/// use stochvib::response::Source;
/// use stochvib::spectrum::{Domain, Exponential};
/// use std::sync::Arc;
/// let s = Source::Process(Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()));
/// assert_eq!(s.n_components(), 1);
/// ```
#[derive(Debug, Clone)]
pub enum Source {
    /// One process (temporal spectrum).
    Process(Arc<dyn Spectrum>),
    /// Several correlated components (e.g. two road tracks with a coherence).
    Matrix(Arc<dyn SpectralMatrix>),
}

impl Source {
    /// Number of components (1 for a process).
    pub fn n_components(&self) -> usize {
        match self {
            Source::Process(_) => 1,
            Source::Matrix(m) => m.n_components(),
        }
    }

    /// The auto-density of component c.
    pub fn component(&self, c: usize) -> Arc<dyn Spectrum> {
        match self {
            Source::Process(s) => s.clone(),
            Source::Matrix(m) => m.component(c),
        }
    }

    /// Short description.
    pub fn describe(&self) -> String {
        match self {
            Source::Process(s) => s.describe(),
            Source::Matrix(m) => m.describe(),
        }
    }

    /// S_cd(ω) (for a process, S(ω) for c = d = 0).
    pub fn entry(&self, omega: f64, c: usize, d: usize) -> C64 {
        match self {
            Source::Process(s) => C64::new(s.density(omega), 0.0),
            Source::Matrix(m) => m.matrix(omega)[(c, d)],
        }
    }
}

/// How system input j is driven: u_j(t) = gain · x_{source,component}(t − delay) + mean.
///
/// # Formula
/// u_j(t) = g_j x_{s_j c_j}(t − τ_j) + μ_j, τ_j in s (a wheel at ℓ m behind the first contact: τ = ℓ/v).
///
/// # Errors
/// None here: [`Excitation::sources`] validates.
///
/// # Examples
/// ```
/// use stochvib::response::InputMap;
/// let rear_left = InputMap { source: 0, component: 0, delay: 2.7 / 20.0, gain: 1.0, mean: 0.0 };
/// assert_eq!(rear_left.component, 0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputMap {
    /// Index of the source.
    pub source: usize,
    /// Component of that source (0 for a process).
    pub component: usize,
    /// Pure delay τ_j, s (≥ 0).
    pub delay: f64,
    /// Gain g_j.
    pub gain: f64,
    /// Mean μ_j added to the input.
    pub mean: f64,
}

/// Validates sources and inputs (see [`Excitation::sources`]).
pub(crate) fn validate(sources: &[Source], inputs: &[InputMap]) -> Result<()> {
    if sources.is_empty() || inputs.is_empty() {
        return Err(Error::invalid(
            "sources",
            format!("{} sources, {} inputs", sources.len(), inputs.len()),
            "need at least one source and one input",
        ));
    }
    for (s, src) in sources.iter().enumerate() {
        for c in 0..src.n_components() {
            let sp = src.component(c);
            if sp.domain() != crate::spectrum::Domain::Temporal {
                return Err(Error::invalid(
                    &format!("sources[{s}]"),
                    sp.describe(),
                    "the system is driven in time: turn a spatial road spectrum into time with a speed first",
                ));
            }
        }
        if let Source::Matrix(m) = src {
            // the matrix must be Hermitian and positive semi-definite: checked on a logarithmic grid of
            // 121 frequencies over [1e-3, 1e4] rad/s (and at the spectra's breakpoints)
            let mut grid: Vec<f64> = (0..=120).map(|k| 10f64.powf(-3.0 + 7.0 * k as f64 / 120.0)).collect();
            for c in 0..m.n_components() {
                grid.extend(m.component(c).breakpoints());
            }
            grid.retain(|w| w.is_finite() && *w > 0.0);
            crate::coherence::check_spectral_matrix(m.as_ref(), &grid)
                .map_err(|e| Error::invalid(&format!("sources[{s}]"), m.describe(), e.to_string()))?;
        }
    }
    for (j, inp) in inputs.iter().enumerate() {
        let Some(src) = sources.get(inp.source) else {
            return Err(Error::invalid(
                &format!("inputs[{j}].source"),
                inp.source,
                format!("there are {} sources", sources.len()),
            ));
        };
        if inp.component >= src.n_components() {
            return Err(Error::invalid(
                &format!("inputs[{j}].component"),
                inp.component,
                format!("source {} has {} component(s)", inp.source, src.n_components()),
            ));
        }
        if !(inp.delay.is_finite() && inp.delay >= 0.0) {
            return Err(Error::invalid(
                &format!("inputs[{j}].delay"),
                inp.delay,
                "must be finite and >= 0",
            ));
        }
        crate::error::require_finite(&format!("inputs[{j}].gain"), inp.gain)?;
        crate::error::require_finite(&format!("inputs[{j}].mean"), inp.mean)?;
    }
    Ok(())
}

/// The output density for row h (h_j = H_ij(iω), one per input) of a general excitation.
///
/// # Formula
/// S_y(ω) = Σ_s z_sᵀ S_s(ω) conj(z_s),  z_{s,c} = Σ_{j: s_j = s, c_j = c} h_j g_j e^{−iωτ_j}.
pub(crate) fn density(sources: &[Source], inputs: &[InputMap], h: &[C64], omega: f64) -> f64 {
    let mut total = 0.0;
    for (s, src) in sources.iter().enumerate() {
        let m = src.n_components();
        let mut z = vec![C64::new(0.0, 0.0); m];
        for (inp, hj) in inputs.iter().zip(h) {
            if inp.source == s {
                let ph = if inp.delay == 0.0 {
                    C64::new(1.0, 0.0)
                } else {
                    C64::from_polar(1.0, -omega * inp.delay)
                };
                z[inp.component] += hj * inp.gain * ph;
            }
        }
        total += match src {
            Source::Process(sp) => sp.density(omega) * z[0].norm_sqr(),
            Source::Matrix(mx) => {
                let sm = mx.matrix(omega);
                let mut acc = C64::new(0.0, 0.0);
                for c in 0..m {
                    for d in 0..m {
                        acc += z[c] * sm[(c, d)] * z[d].conj();
                    }
                }
                acc.re
            }
        };
    }
    total
}

/// The excitation that keeps only source `s` of a general excitation with single-process sources: a
/// [`Excitation::Track`] whose inputs of other sources have gain 0 (and the delay of the source's first
/// input, so that they add no delay group).
fn single_source(sources: &[Source], inputs: &[InputMap], s: usize) -> Result<Option<Excitation>> {
    let Source::Process(sp) = &sources[s] else {
        return Ok(None);
    };
    source_track(sp.clone(), inputs, s, |i| i.gain)
}

/// [`Excitation::Track`] of `spectrum` felt by the inputs of source `s` with their delays and the gains
/// `gain(input)`, the other inputs with gain 0 and the delay of the source's first input; `None` when no
/// input is driven by source `s`.
fn source_track(
    spectrum: Arc<dyn Spectrum>,
    inputs: &[InputMap],
    s: usize,
    gain: impl Fn(&InputMap) -> f64,
) -> Result<Option<Excitation>> {
    let Some(first) = inputs.iter().find(|i| i.source == s) else {
        return Ok(None);
    };
    let delays = inputs
        .iter()
        .map(|i| if i.source == s { i.delay } else { first.delay })
        .collect();
    let gains = inputs
        .iter()
        .map(|i| if i.source == s { gain(i) } else { 0.0 })
        .collect();
    Excitation::track(spectrum, delays, gains, 0.0).map(Some)
}

/// The independent single-process excitations that multi-component source `s` is the sum of, when its
/// matrix factors with constant coefficients ([`SpectralMatrix::independent_parts`]) and its density is
/// rational.
///
/// # Formula
/// x_c = Σ_k a_ck w_k with independent w_k of density q_k S₀₀: part k is a track of density q_k S₀₀ felt
/// by input j of source s with gain g_j a_{c_j k} and delay τ_j (parts of zero density are left out).
///
/// # Errors
/// [`Error::NotApplicable`] when the matrix has no such factorisation (a coherence that depends on the
/// frequency) or the density is not rational.
fn matrix_parts(m: &dyn SpectralMatrix, inputs: &[InputMap], s: usize) -> Result<Vec<Excitation>> {
    let refuse = |why: String| Error::NotApplicable {
        method: "exact (Lyapunov) variance".into(),
        reason: format!("source {s} ({}) {why}; quadrature only", m.describe()),
    };
    let Some(parts) = m.independent_parts() else {
        return Err(refuse(
            "is a multi-component process whose cross-spectral matrix has no rational factorisation (a coherence \
             function of n)"
                .into(),
        ));
    };
    let density = m.component(0);
    let Some(rational) = density.rational() else {
        return Err(refuse(format!(
            "factors into independent parts of densities proportional to {}, which is not rational",
            density.describe()
        )));
    };
    let mut out = Vec::new();
    for (q, a) in parts.into_iter().filter(|(q, _)| *q > 0.0) {
        let spectrum: Arc<dyn Spectrum> = Arc::new(rational.scaled(q)?);
        out.extend(source_track(spectrum, inputs, s, |i| i.gain * a[i.component])?);
    }
    Ok(out)
}

/// The exact variance and moments λ₂, λ₄ of output i under a general excitation: the sum over the
/// independent sources of the exact (Lyapunov, or Lyapunov with delays) values for each source alone.
///
/// # Formula
/// Sources are independent, so S_y = Σ_s S_y^{(s)} and λ_k = Σ_s λ_k^{(s)}; each single-process source is
/// a track felt with delays and gains ([`variance_lyapunov`] or [`variance_lyapunov_delayed`](super::variance_lyapunov_delayed)), and a
/// multi-component source whose matrix factors into independent parts (two tracks of constant coherence:
/// sum and difference processes) is the sum of its parts, each such a track. A part that the output does
/// not feel (a symmetric machine's bounce under the difference process) is 0 and comes out of the delayed
/// route at the rounding of its cancelling pair terms, of either sign: a negative part within
/// [`PART_ROUNDING`] of the sum of the parts' magnitudes is taken as 0.
///
/// # Errors
/// [`Error::NotApplicable`] when a source is a multi-component process without a constant factorisation
/// (two tracks with a coherence function of n: quadrature only) or a source's spectrum is not rational;
/// [`Error::Inaccurate`] for a negative part beyond that rounding or a negative total; the errors of the
/// per-source methods otherwise.
pub(crate) fn variance_exact(
    sys: &dyn FrequencyResponse,
    sources: &[Source],
    inputs: &[InputMap],
    i: usize,
) -> Result<LyapunovMoments> {
    let mut total = LyapunovMoments {
        variance: 0.0,
        lambda2: Ok(0.0),
        lambda4: Ok(0.0),
    };
    let (mut scale, mut negative) = (PartSums::default(), PartSums::default());
    for (s, src) in sources.iter().enumerate() {
        let parts = match src {
            Source::Process(_) => single_source(sources, inputs, s)?.into_iter().collect(),
            Source::Matrix(m) => matrix_parts(m.as_ref(), inputs, s)?,
        };
        for exc in parts {
            // a delayed part unchecked: its sign is judged against the sum of all parts below
            let part = if exc.delay_free() {
                variance_lyapunov(sys, &exc, i)?
            } else {
                DelayedCovariance::new(sys, &exc, i)?.moments()?
            };
            scale = scale.add(&part);
            negative = negative.add(&part.negative_parts());
            total.variance += part.variance.max(0.0);
            total.lambda2 = add(total.lambda2, part.lambda2.map(|v| v.max(0.0)));
            total.lambda4 = add(total.lambda4, part.lambda4.map(|v| v.max(0.0)));
        }
    }
    negative.within_rounding_of(&scale, &total)?;
    total.checked("exact variance of the sources")
}

/// Largest negative part of a moment, relative to the sum of the parts' magnitudes, that is taken for the
/// rounding of a part whose true value is 0: a part that a symmetric machine does not feel at all (the
/// difference process under a bounce output, the sum process under roll), whose delayed covariance sums
/// pair terms 𝒞_g e^{𝒜Δ} P 𝒞_hᵀ that cancel exactly; they come out at ±10⁻¹⁶ of the terms.
const PART_ROUNDING: f64 = 1e-9;

/// Per moment, a sum over parts (of magnitudes, or of negative values).
#[derive(Debug, Clone, Copy, Default)]
struct PartSums([f64; 3]);

impl PartSums {
    fn add(self, m: &LyapunovMoments) -> PartSums {
        let v = [
            Some(m.variance),
            m.lambda2.as_ref().ok().copied(),
            m.lambda4.as_ref().ok().copied(),
        ];
        PartSums(std::array::from_fn(|k| self.0[k] + v[k].map_or(0.0, f64::abs)))
    }

    /// Errors when a negative part exceeds [`PART_ROUNDING`] of `scale` (then the solve lost its accuracy,
    /// as [`LyapunovMoments::checked`] says of a negative total), for each moment that `total` has (one that
    /// another part makes divergent is an error of its own, whatever the rounding of the other parts).
    fn within_rounding_of(&self, scale: &PartSums, total: &LyapunovMoments) -> Result<()> {
        let finite = [true, total.lambda2.is_ok(), total.lambda4.is_ok()];
        let moments = self.0.iter().zip(&scale.0).zip(finite).enumerate();
        for (k, ((&negative, &scale), finite)) in moments {
            if finite && negative > PART_ROUNDING * scale {
                return Err(Error::Inaccurate {
                    method: "Lyapunov variance with delays".into(),
                    value: -negative,
                    reason: format!(
                        "a part of moment λ{} came out negative ({:e}) beyond the rounding of the parts ({scale:e}): \
                         the solve lost its accuracy on this system",
                        2 * k,
                        -negative,
                    ),
                });
            }
        }
        Ok(())
    }
}

impl LyapunovMoments {
    /// The magnitudes of the negative moments (0 for the others and for an error).
    fn negative_parts(&self) -> LyapunovMoments {
        let neg = |v: f64| (-v).max(0.0);
        LyapunovMoments {
            variance: neg(self.variance),
            lambda2: Ok(self.lambda2.as_ref().map_or(0.0, |v| neg(*v))),
            lambda4: Ok(self.lambda4.as_ref().map_or(0.0, |v| neg(*v))),
        }
    }
}

fn add(a: Result<f64>, b: Result<f64>) -> Result<f64> {
    match (a, b) {
        (Ok(x), Ok(y)) => Ok(x + y),
        (Err(e), _) | (_, Err(e)) => Err(e),
    }
}
