//! Whether a weighted output depends on frequencies the input does not cover: an input band that stops
//! below the weighting's band (an ISO 8608 class spectrum stops at 2.83 cycles/m, i.e. at 8.5 Hz at 3 m/s,
//! while Wk weights up to its band-limiting corner f₂ = 100 Hz).
//!
//! # Formula
//! For one process x felt by every input (a road track), band-limited to |ω| ≤ ω_hi < ω₂ = 2πf₂ (f₂ the
//! weighting's upper band-limiting frequency, ISO 2631-1 Annex A), the input's own power law is continued
//! from its top: with the slope fitted between ω_a = ω_hi/2 and ω_b = 0.99 ω_hi,
//! ```text
//! w = −ln(S(ω_b)/S(ω_a)) / ln(ω_b/ω_a),        S_c(ω) = S(ω) for |ω| < ω_hi,   S(ω_b)(|ω|/ω_b)^(−w) for ω_hi ≤ |ω| ≤ ω₂,
//! a_w,c² = ∫ |W(iω)|² S_y,c(ω) dω  (quadrature),   covered fraction φ = a_w²/a_w,c²
//! ```
//! (w = 2 exactly for ISO 8608: S ∝ n⁻²). φ is the fraction of the weighted output's mean square, under the
//! continued power law, that the input's band delivers — the factor the reported a_w² is short by. It is
//! chosen over a fraction of the weighting band in log frequency because it is what the verdict depends on:
//! a band missing a decade where the weighted response is negligible costs nothing, one missing the
//! response's peak costs everything. The continuation stops at f₂: above it the weighting itself falls off
//! (its band limitation is part of the standard's weighting).
//!
//! The fix: an explicit spatial band on the spectrum (`band = ["0.011 cycles/m", "30 cycles/m"]` on an
//! `iso8608` or `power-law` spectrum); `docs/comfort.md` says when the road's law holds that far and when a
//! pneumatic tyre's enveloping (a contact-patch moving average) lowers it.

use crate::comfort::Weighting;
use crate::error::{Error, Result};
use crate::response::{analyze_output_with, Excitation};
use crate::spectrum::{Asymptote, Domain, Spectrum};
use crate::system::FrequencyResponse;
use serde::Serialize;
use std::f64::consts::PI;
use std::sync::Arc;

/// A weighted output that depends on frequencies the input does not cover.
#[derive(Debug, Clone, Serialize)]
pub struct InputCoverage {
    /// Upper edge of the input band (temporal), Hz.
    pub input_edge_hz: f64,
    /// The weighting's upper band-limiting frequency f₂, Hz.
    pub weighting_edge_hz: f64,
    /// Exponent w of the continued power law S ∝ ω^(−w).
    pub exponent: f64,
    /// a_w with the input's power law continued to f₂, m/s².
    pub a_w_continued: f64,
    /// φ = a_w²/a_w,continued²: the fraction of the continued mean square the input's band delivers.
    pub covered_fraction: f64,
}

impl InputCoverage {
    /// One line: where the input stops, the covered fraction, the continued value and the fixes.
    pub fn describe(&self, output: &str) -> String {
        format!(
            "the input stops at {:.3} Hz, below the weighting's band (to {} Hz): the band covers {:.1} % of the \
             weighted mean square of `{output}` under the input's power law (exponent {:.3}) continued to {} Hz, \
             where a_w = {:.4e} m/s² (√φ = {:.3} of it is reported). Fix: give the spectrum an explicit band, \
             e.g. band = [\"0.011 cycles/m\", \"30 cycles/m\"] (docs/comfort.md: when the road's law holds that far, \
             and when a tyre's enveloping lowers it)",
            self.input_edge_hz,
            self.weighting_edge_hz,
            100.0 * self.covered_fraction,
            self.exponent,
            self.weighting_edge_hz,
            self.a_w_continued,
            self.covered_fraction.sqrt()
        )
    }
}

/// The coverage of the weighted output 0 of `weighted` (W(s)·H(s)) with weighting `w` under `exc`, whose
/// reported a_w is `a_w`: `None` when the input reaches f₂ or is not one band-limited process felt by every
/// input (several independent processes, two coherent tracks: not assessed).
///
/// # Errors
/// The quadrature of the continued weighted output.
pub fn input_coverage(
    weighted: &dyn FrequencyResponse,
    exc: &Excitation,
    w: Weighting,
    a_w: f64,
    effort: &crate::quad_oscillatory::OscillatoryOptions,
) -> Result<Option<InputCoverage>> {
    let Excitation::Track {
        spectrum,
        delays,
        gains,
        mean,
    } = exc
    else {
        return Ok(None);
    };
    let (lo, hi) = spectrum.support();
    let edge = 2.0 * PI * w.parameters().f2_hz;
    if !(hi.is_finite() && hi < edge && a_w > 0.0) {
        return Ok(None);
    }
    let (wa, wb) = ((0.5 * hi).max(1.01 * lo), 0.99 * hi);
    let (sa, sb) = (spectrum.density(wa), spectrum.density(wb));
    if !(sa > 0.0 && sb > 0.0 && wb > wa) {
        return Ok(None);
    }
    let exponent = -(sb / sa).ln() / (wb / wa).ln();
    let continued = Arc::new(Continued {
        inner: spectrum.clone(),
        hi,
        edge,
        level: sb,
        at: wb,
        exponent,
    });
    let exc_c = Excitation::track(continued, delays.clone(), gains.clone(), *mean)?;
    let st = analyze_output_with(weighted, &exc_c, 0, effort)?;
    let a_c = st.sigma.ok_or_else(|| Error::Numerical {
        what: "the weighted r.m.s. with the input's power law continued".into(),
        reason: st.variance_outcome.describe(),
    })?;
    Ok(Some(InputCoverage {
        input_edge_hz: hi / (2.0 * PI),
        weighting_edge_hz: edge / (2.0 * PI),
        exponent,
        a_w_continued: a_c,
        covered_fraction: (a_w / a_c).powi(2),
    }))
}

/// A temporal density continued above its band's top ω_hi by the power law level·(|ω|/at)^(−exponent) up
/// to `edge`, zero above.
#[derive(Debug)]
struct Continued {
    inner: Arc<dyn Spectrum>,
    hi: f64,
    edge: f64,
    level: f64,
    at: f64,
    exponent: f64,
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
            self.level * (w / self.at).powf(-self.exponent)
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
        b
    }
}
