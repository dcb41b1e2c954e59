//! An input continued above the top of its band by its own power law: what an output would receive if the
//! input's band did not stop where it does (an ISO 8608 road stops at 2.83 cycles/m, i.e. at 8.5 Hz at
//! 3 m/s, while a weighting, a band table or a fatigue moment may depend on higher frequencies).
//!
//! # Formula
//! For a source component of temporal density S, zero above ω_hi (its support's top) and continued to an
//! edge ω_e > ω_hi, the slope is fitted between ω_a = max(ω_hi/2, 1.01 ω_lo) and ω_b = 0.99 ω_hi:
//! ```text
//! w = −ln(S(ω_b)/S(ω_a)) / ln(ω_b/ω_a),
//! S_c(ω) = S(ω) for |ω| < ω_hi,    S(ω_b)(|ω|/ω_b)^(−w) for ω_hi ≤ |ω| ≤ ω_e,    0 above ω_e
//! ```
//! (w = 2 exactly for ISO 8608). A source seen through a moving average (a tyre's enveloping,
//! [`Spectrum::moving_average`]) is continued before the filter, which then applies to the continuation:
//! S_c = S_raw,c · sinc²(ωT/2). A source of several correlated components (two road tracks) keeps its
//! coherence: S_c,cd(ω) = C_cd(ω) √(S_c,c S_c,d) above the band, C the source's coherence matrix.

use super::{Excitation, Source};
use crate::coherence::SpectralMatrix;
use crate::error::Result;
use crate::spectrum::{sinc_squared, Asymptote, Domain, Spectrum};
use nalgebra::{Complex, DMatrix};
use std::sync::Arc;

/// A temporal density continued above its band's top by its power law (see the module docs).
#[derive(Debug)]
pub struct Continued {
    inner: Arc<dyn Spectrum>,
    /// The moving-average duration T of an enveloped source (the filter of the continuation), s.
    filter: Option<f64>,
    hi: f64,
    edge: f64,
    level: f64,
    at: f64,
    exponent: f64,
}

impl Continued {
    /// `spectrum` continued to `edge` (rad/s); `None` when its band reaches `edge` (or has no finite top)
    /// or no slope can be fitted (a zero density near the top).
    pub fn new(spectrum: Arc<dyn Spectrum>, edge: f64) -> Option<Continued> {
        let (raw, filter) = match spectrum.moving_average() {
            Some((raw, t)) => (raw, Some(t)),
            None => (spectrum.clone(), None),
        };
        let (lo, hi) = raw.support();
        if !(hi.is_finite() && hi < edge) {
            return None;
        }
        let (wa, wb) = ((0.5 * hi).max(1.01 * lo), 0.99 * hi);
        let (sa, sb) = (raw.density(wa), raw.density(wb));
        if !(sa > 0.0 && sb > 0.0 && wb > wa) {
            return None;
        }
        Some(Continued {
            inner: spectrum,
            filter,
            hi,
            edge,
            level: sb,
            at: wb,
            exponent: -(sb / sa).ln() / (wb / wa).ln(),
        })
    }

    /// The top of the band ω_hi, rad/s.
    pub fn band_top(&self) -> f64 {
        self.hi
    }

    /// The exponent w of the continued law S ∝ ω^(−w).
    pub fn exponent(&self) -> f64 {
        self.exponent
    }
}

impl Spectrum for Continued {
    fn describe(&self) -> String {
        format!(
            "{}, continued above {:.4e} rad/s by its power law (exponent {:.3}) to {:.4e} rad/s",
            self.inner.describe(),
            self.hi,
            self.exponent,
            self.edge
        )
    }
    fn domain(&self) -> Domain {
        Domain::Temporal
    }
    fn density(&self, omega: f64) -> f64 {
        let w = omega.abs();
        if w < self.hi {
            self.inner.density(w)
        } else if w <= self.edge {
            let law = self.level * (w / self.at).powf(-self.exponent);
            self.filter.map_or(law, |t| law * sinc_squared(w, t))
        } else {
            0.0
        }
    }
    fn high_frequency(&self) -> Asymptote {
        Asymptote::Vanishing
    }
    fn low_frequency(&self) -> Asymptote {
        self.inner.low_frequency()
    }
    fn support(&self) -> (f64, f64) {
        (self.inner.support().0, self.edge)
    }
    fn breakpoints(&self) -> Vec<f64> {
        let mut b = self.inner.breakpoints();
        b.extend([self.hi, self.edge]);
        if let Some(t) = self.filter {
            // the filter's zeros above the band (at most 256)
            let step = 2.0 * std::f64::consts::PI / t;
            let first = (self.hi / step).ceil() as usize;
            b.extend(
                (first.max(1)..first.max(1) + 256)
                    .map(|k| k as f64 * step)
                    .take_while(|w| *w < self.edge),
            );
        }
        b
    }
}

/// A source of several correlated components continued component by component, keeping its coherence.
#[derive(Debug)]
struct ContinuedMatrix {
    inner: Arc<dyn SpectralMatrix>,
    components: Vec<Arc<dyn Spectrum>>,
    /// Below this |ω| (the lowest top of the continued components) the matrix is the inner one.
    below: f64,
}

impl SpectralMatrix for ContinuedMatrix {
    fn describe(&self) -> String {
        format!("{}, continued by its power law", self.inner.describe())
    }
    fn n_components(&self) -> usize {
        self.inner.n_components()
    }
    fn component_name(&self, c: usize) -> String {
        self.inner.component_name(c)
    }
    fn component(&self, c: usize) -> Arc<dyn Spectrum> {
        self.components[c].clone()
    }
    fn matrix(&self, omega: f64) -> DMatrix<Complex<f64>> {
        if omega.abs() < self.below {
            return self.inner.matrix(omega);
        }
        let s: Vec<f64> = self.components.iter().map(|c| c.density(omega)).collect();
        let coh = self.inner.coherence_matrix(omega);
        DMatrix::from_fn(s.len(), s.len(), |c, d| coh[(c, d)] * (s[c] * s[d]).sqrt())
    }
    fn coherence_matrix(&self, omega: f64) -> DMatrix<Complex<f64>> {
        self.inner.coherence_matrix(omega)
    }
}

/// A source that was continued: its index in the excitation's sources ([`Excitation::to_sources`] order:
/// the one process of a track, one per independent process), the top of its band and the exponent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContinuedSource {
    /// Index of the source.
    pub source: usize,
    /// Top of its band ω_hi, rad/s.
    pub band_top: f64,
    /// Exponent w of the continued law.
    pub exponent: f64,
}

/// `exc` with every source whose band stops below `edge` (rad/s) continued to it by its power law (only
/// source `only` when given), and the continued sources; `None` when no source stops below `edge`.
///
/// # Errors
/// Those of rebuilding the excitation (none for an excitation that was valid).
pub fn continue_excitation(
    exc: &Excitation,
    edge: f64,
    only: Option<usize>,
) -> Result<Option<(Excitation, Vec<ContinuedSource>)>> {
    let wanted = |k: usize| only.is_none_or(|o| o == k);
    if let Excitation::Track {
        spectrum,
        delays,
        gains,
        mean,
    } = exc
    {
        // one process: kept in its own form (its fast paths)
        let Some(c) = Continued::new(spectrum.clone(), edge).filter(|_| wanted(0)) else {
            return Ok(None);
        };
        let info = vec![source_info(0, &c)];
        let exc = Excitation::track(Arc::new(c), delays.clone(), gains.clone(), *mean)?;
        return Ok(Some((exc, info)));
    }
    let Excitation::Sources { sources, inputs } = exc.to_sources() else {
        return Ok(None);
    };
    let mut info = Vec::new();
    let mut out = Vec::with_capacity(sources.len());
    for (k, src) in sources.into_iter().enumerate() {
        out.push(match (&src, wanted(k)) {
            (Source::Process(s), true) => match Continued::new(s.clone(), edge) {
                Some(c) => {
                    info.push(source_info(k, &c));
                    Source::Process(Arc::new(c))
                }
                None => src,
            },
            (Source::Matrix(m), true) => match continue_matrix(m, edge) {
                Some((cm, c)) => {
                    info.push(ContinuedSource { source: k, ..c });
                    Source::Matrix(Arc::new(cm))
                }
                None => src,
            },
            _ => src,
        });
    }
    if info.is_empty() {
        return Ok(None);
    }
    Ok(Some((Excitation::sources(out, inputs)?, info)))
}

fn source_info(source: usize, c: &Continued) -> ContinuedSource {
    ContinuedSource {
        source,
        band_top: c.band_top(),
        exponent: c.exponent(),
    }
}

/// A matrix source continued (every component that stops below `edge`), with the continuation of its
/// lowest-topped component.
fn continue_matrix(m: &Arc<dyn SpectralMatrix>, edge: f64) -> Option<(ContinuedMatrix, ContinuedSource)> {
    let mut first: Option<ContinuedSource> = None;
    let components: Vec<Arc<dyn Spectrum>> = (0..m.n_components())
        .map(|c| {
            let s = m.component(c);
            match Continued::new(s.clone(), edge) {
                Some(cont) => {
                    if first.is_none_or(|f| cont.band_top() < f.band_top) {
                        first = Some(source_info(0, &cont));
                    }
                    Arc::new(cont) as Arc<dyn Spectrum>
                }
                None => s,
            }
        })
        .collect();
    let first = first?;
    let cm = ContinuedMatrix {
        inner: m.clone(),
        components,
        below: first.band_top,
    };
    Some((cm, first))
}
