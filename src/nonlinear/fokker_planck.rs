//! Route 3: the exact stationary (Fokker–Planck) density of a single-degree-of-freedom oscillator with
//! linear damping and any nonlinear restoring force under Gaussian white noise.
//!
//! # Formula
//! m q̈ + c q̇ + R(q) = f(t), E[f(t) f(t+τ)] = 2πS_f δ(τ) (S_f the two-sided density of the force in our
//! convention, N² s/rad), R = dV/dq with V(q) = k q²/2 + Σ_e V_e(d_e q). In Itô form dq = v dt,
//! dv = −(c v + R(q))/m dt + (√(2πS_f)/m) dW, whose Fokker–Planck equation
//! ```text
//! ∂p/∂t = −v ∂p/∂q + ∂/∂v[((c v + R)/m) p] + (πS_f/m²) ∂²p/∂v²
//! ```
//! has the stationary solution (substitute p = C e^{−β(mv²/2 + V)}: the residual is (c/m − πS_f β/m)(1 − β m v²)p)
//! ```text
//! p(q, v) = C exp(−β (m v²/2 + V(q))),     β = c/(π S_f)
//! ```
//! so v is Gaussian with σ_v² = πS_f/(c m), independent of q, and p(q) ∝ exp(−c V(q)/(π S_f)). The linear
//! spring alone gives σ_q² = πS_f/(c k) = πS₀/(2ζω₀³) with S₀ = S_f/m² the density of f/m (our convention's
//! linear oscillator). Rice's formula with q and q̇ independent gives the exact rate of up-crossings of a
//! level a, ν⁺(a) = p(a) E\[v⁺\] = p(a) σ_v/√(2π). Texts that write the noise as E\[ww\] = 2Dδ have
//! p ∝ exp(−(2ζω₀/D)H): D = πS₀ here ([`intensity_to_density`]). Caughey (1963), "Derivation and
//! application of the Fokker–Planck equation to discrete nonlinear dynamic systems subjected to white random
//! excitation", J. Acoust. Soc. Am. 35(11), 1683–1692; Lin (1967), *Probabilistic Theory of Structural
//! Dynamics*, ch. 10.
//!
//! The moments are adaptive quadratures of exp(−βV) with the elements' kinks as breakpoints. The result
//! does **not** apply to coloured inputs (a road through a shaping filter), to more than one degree of
//! freedom, to nonlinear damping or friction, or to a potential unbounded below (a softening spring):
//! [`WhiteNoiseOscillator::from_model`] says which condition fails.

use super::{ForceLaw, NonlinearModel};
use crate::error::{Error, Result};
use crate::quad::{integrate, QuadOptions};
use crate::response::Excitation;
use std::f64::consts::PI;
use std::sync::Arc;

/// The two-sided density S₀ of white noise given as an "intensity" D with E[w(t)w(t+τ)] = 2Dδ(τ):
/// S₀ = D/π (our convention: E[w w] = 2πS₀δ).
///
/// # Examples
/// ```
/// use stochvib::nonlinear::intensity_to_density;
/// assert!((intensity_to_density(std::f64::consts::PI) - 1.0).abs() < 1e-15);
/// ```
pub fn intensity_to_density(d: f64) -> f64 {
    d / PI
}

/// A white-noise-driven oscillator m q̈ + c q̇ + k q + Σ_e d_e F_e(d_e q) = f (see the module docs).
#[derive(Debug, Clone)]
pub struct WhiteNoiseOscillator {
    /// m, kg.
    pub mass: f64,
    /// c, N s/m.
    pub damping: f64,
    /// k, N/m (the linear spring; the elements' linear parts included).
    pub stiffness: f64,
    /// S_f, the two-sided density of the force, N² s/rad.
    pub force_density: f64,
    /// (d_e, F_e): the elements' remainders with their directions.
    pub springs: Vec<(f64, Arc<dyn ForceLaw>)>,
}

/// The exact stationary law of a [`WhiteNoiseOscillator`].
#[derive(Debug, Clone)]
pub struct Stationary {
    /// The oscillator.
    pub oscillator: WhiteNoiseOscillator,
    /// ∫ e^{−βV} dq.
    pub normalizer: f64,
    /// E\[q\].
    pub mean: f64,
    /// Var q.
    pub variance: f64,
    /// E[(q − μ)⁴]/σ⁴.
    pub kurtosis: f64,
    /// σ_v = √(πS_f/(c m)).
    pub sigma_v: f64,
    breakpoints: Vec<f64>,
}

impl WhiteNoiseOscillator {
    /// β = c/(πS_f), 1/J.
    pub fn beta(&self) -> f64 {
        self.damping / (PI * self.force_density)
    }

    /// V(q), J.
    pub fn potential(&self, q: f64) -> f64 {
        let nl: f64 = self
            .springs
            .iter()
            .map(|(d, f)| f.potential(d * q).unwrap_or(f64::NAN))
            .sum();
        0.5 * self.stiffness * q * q + nl
    }

    /// The oscillator of `model` under `exc`, or why route 3 does not apply.
    ///
    /// # Errors
    /// The reason (a text) when the model is not a white-noise-driven oscillator with linear damping and
    /// nonlinear springs only.
    pub fn from_model(model: &NonlinearModel, exc: &Excitation) -> std::result::Result<Self, String> {
        let lin = model.linear();
        if lin.n_coords() != 1 {
            return Err(format!(
                "{} degrees of freedom (the exact density is for one)",
                lin.n_coords()
            ));
        }
        if let Some(e) = model.elements().iter().find(|e| e.law.velocity_dependent()) {
            return Err(format!(
                "element `{}` ({}) dissipates nonlinearly: the exact density needs linear damping",
                e.name,
                e.law.kind()
            ));
        }
        if lin.n_base() > 0 || lin.force_distribution().ncols() != 1 {
            return Err("the input is not a single force (a base input is a coloured displacement)".into());
        }
        let s0 = white_level(exc)?;
        let f = lin.force_distribution()[(0, 0)];
        let springs = model
            .elements()
            .iter()
            .map(|e| (e.direction()[0], e.law.clone()))
            .collect();
        Ok(WhiteNoiseOscillator {
            mass: lin.mass()[(0, 0)],
            damping: lin.damping()[(0, 0)],
            stiffness: lin.stiffness()[(0, 0)],
            force_density: f * f * s0,
            springs,
        })
        .and_then(|o| {
            if o.damping > 0.0 {
                Ok(o)
            } else {
                Err("no linear damping".into())
            }
        })
    }

    /// The displacement scale s with βV(±s) ≈ 1 on each side, found by bisection, after checking that the
    /// density can be normalised on that side ([`Self::check_confined`]).
    fn scales(&self) -> Result<(f64, f64)> {
        let beta = self.beta();
        let side = |sign: f64| -> Result<f64> {
            let mut hi = 1e-12f64;
            while beta * self.potential(sign * hi) < 1.0 {
                hi *= 2.0;
                if hi > 1e12 || self.potential(sign * hi).is_nan() {
                    return Err(not_confined(
                        "the potential does not grow on both sides (a softening spring: the density cannot be \
                         normalised, the response escapes)"
                            .into(),
                    ));
                }
            }
            self.check_confined(sign, hi)?;
            let mut lo = 0.5 * hi;
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if beta * self.potential(sign * mid) < 1.0 {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            Ok(hi)
        };
        Ok((side(-1.0)?, side(1.0)?))
    }

    /// Checks that e^{−βV} falls for good on the side `sign` beyond the scale `s` (βV(s) ≥ 1): along
    /// x = s·2^{k/8} up to 10¹² s, βV must reach [`CONFINED_BETA_V`] (a density below e^{−1000} of its peak,
    /// nothing left to integrate beyond). A softening spring's potential rises to a barrier and falls
    /// without bound beyond it, so βV never gets there: the density cannot be normalised and the response
    /// escapes over the barrier sooner or later; the error names the barrier (its place to 9 %, its βV).
    fn check_confined(&self, sign: f64, s: f64) -> Result<()> {
        let beta = self.beta();
        let (mut peak, mut at) = (f64::NEG_INFINITY, s);
        for k in 0..=8 * 40 {
            let x = s * 2f64.powf(f64::from(k) / 8.0);
            let bv = beta * self.potential(sign * x);
            if bv >= CONFINED_BETA_V {
                return Ok(());
            }
            if bv.is_nan() {
                return Err(not_confined(format!(
                    "the potential is not a number at x = {} m, so the density's tail cannot be checked",
                    crate::numbers::num(sign * x)
                )));
            }
            if bv > peak {
                (peak, at) = (bv, x);
            }
        }
        let at = self.barrier(sign, at / 2f64.powf(0.125), at * 2f64.powf(0.125));
        Err(not_confined(format!(
            "the potential rises to a barrier of βV = {} at x = {} m and falls beyond it (a softening \
             spring): exp(−βV) cannot be normalised, and the response escapes over the barrier sooner or \
             later (the rarer the higher βV); statistics of the motion inside the well (route 1, route 2 \
             over a finite time) hold only while it stays there",
            crate::numbers::num(beta * self.potential(sign * at)),
            crate::numbers::num(sign * at)
        )))
    }

    /// The top of the potential on the side `sign` between |x| = `lo` and `hi` (golden-section search;
    /// the potential has one maximum there).
    fn barrier(&self, sign: f64, mut lo: f64, mut hi: f64) -> f64 {
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let v = |x: f64| self.potential(sign * x);
        for _ in 0..100 {
            let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if v(a) < v(b) {
                lo = a;
            } else {
                hi = b;
            }
        }
        0.5 * (lo + hi)
    }

    /// The exact stationary law: normaliser, mean, variance and kurtosis by adaptive quadrature.
    ///
    /// # Errors
    /// A potential that does not grow on both sides; a quadrature that does not converge.
    pub fn stationary(&self) -> Result<Stationary> {
        let (sl, su) = self.scales()?;
        let mut bp: Vec<f64> = vec![-4.0 * sl, -sl, 0.0, su, 4.0 * su];
        let beta = self.beta();
        for (d, f) in &self.springs {
            // a stiff contact confines the density to a width w = 1/√(β k d²) beyond its kink: resolve it
            let k = f.stiffness_bound(&Default::default());
            let w = if k > 0.0 {
                1.0 / (beta * k * d * d).sqrt()
            } else {
                f64::INFINITY
            };
            for kink in f.kinks() {
                let q = kink / d;
                bp.push(q);
                bp.extend(
                    [-10.0, -3.0, -1.0, 1.0, 3.0, 10.0]
                        .iter()
                        .map(|s| q + s * w)
                        .filter(|x| x.is_finite()),
                );
            }
        }
        bp.retain(|x| x.is_finite());
        bp.sort_by(f64::total_cmp);
        bp.dedup();
        let mut st = Stationary {
            oscillator: self.clone(),
            normalizer: 1.0,
            mean: 0.0,
            variance: 0.0,
            kurtosis: 0.0,
            sigma_v: (PI * self.force_density / (self.damping * self.mass)).sqrt(),
            breakpoints: bp,
        };
        st.normalizer = st.integral(|_| 1.0)?;
        st.mean = st.integral(|q| q)?;
        let mu = st.mean;
        st.variance = st.integral(|q| (q - mu).powi(2))?;
        st.kurtosis = st.integral(|q| (q - mu).powi(4))? / (st.variance * st.variance);
        Ok(st)
    }
}

/// βV beyond which route 3 counts the density as fallen for good: e^{−1000} is below the smallest f64.
/// [`WhiteNoiseOscillator::stationary`] refuses a potential that never reaches it beyond its scale (a
/// softening spring's barrier).
pub const CONFINED_BETA_V: f64 = 1000.0;

/// Route 3 does not apply because the density cannot be normalised.
fn not_confined(reason: String) -> Error {
    Error::NotApplicable {
        method: "exact Fokker–Planck density".into(),
        reason,
    }
}

/// S₀ of a single white (constant) input spectrum of zero mean, or why not.
fn white_level(exc: &Excitation) -> std::result::Result<f64, String> {
    let spectra = exc.spectra();
    if spectra.len() != 1 || !exc.delay_free() {
        return Err("the excitation is not a single process".into());
    }
    if exc.means().iter().any(|m| *m != 0.0) {
        return Err("the input has a mean (the density is for zero-mean white noise)".into());
    }
    let r = spectra[0]
        .rational()
        .ok_or_else(|| format!("the input ({}) is not white noise", spectra[0].describe()))?;
    if r.numerator().len() != 1 || r.denominator().len() != 1 {
        return Err(format!(
            "the input ({}) is coloured, not white noise: the exact density needs white forcing",
            spectra[0].describe()
        ));
    }
    let gain = match exc {
        Excitation::Track { gains, .. } => gains[0],
        _ => 1.0,
    };
    Ok(gain * gain * r.numerator()[0] / r.denominator()[0])
}

impl Stationary {
    /// ∫ g(q) p(q) dq (with the normaliser of this law).
    fn integral(&self, g: impl Fn(f64) -> f64) -> Result<f64> {
        let beta = self.oscillator.beta();
        let opts = QuadOptions {
            rel_tol: 1e-12,
            abs_tol: 0.0,
            max_subintervals: 4000,
            breakpoints: self.breakpoints.clone(),
        };
        let f = |q: f64| {
            let e = (-beta * self.oscillator.potential(q)).exp();
            if e == 0.0 {
                0.0
            } else {
                g(q) * e
            }
        };
        let r = integrate(f, f64::NEG_INFINITY, f64::INFINITY, &opts)?;
        Ok(r.value / self.normalizer)
    }

    /// The density p(q).
    pub fn density(&self, q: f64) -> f64 {
        (-self.oscillator.beta() * self.oscillator.potential(q)).exp() / self.normalizer
    }

    /// The exact rate of up-crossings of level a (per second): ν⁺(a) = p(a) σ_v/√(2π). Down-crossings of a
    /// level have the same rate.
    pub fn upcrossing_rate(&self, a: f64) -> f64 {
        self.density(a) * self.sigma_v / (2.0 * PI).sqrt()
    }

    /// P(q > a).
    ///
    /// # Errors
    /// A quadrature that does not converge.
    pub fn prob_above(&self, a: f64) -> Result<f64> {
        let beta = self.oscillator.beta();
        let mut bp: Vec<f64> = self.breakpoints.iter().copied().filter(|x| *x > a).collect();
        bp.insert(0, a);
        let opts = QuadOptions {
            rel_tol: 1e-12,
            abs_tol: 0.0,
            max_subintervals: 4000,
            breakpoints: bp[1..].to_vec(),
        };
        let r = integrate(
            |q| (-beta * self.oscillator.potential(q)).exp(),
            a,
            f64::INFINITY,
            &opts,
        )?;
        Ok(r.value / self.normalizer)
    }

    /// P(q < a).
    ///
    /// # Errors
    /// As [`Stationary::prob_above`].
    pub fn prob_below(&self, a: f64) -> Result<f64> {
        Ok((1.0 - self.prob_above(a)?).max(0.0))
    }

    /// The fraction of time element e of the oscillator spends engaged (in contact, lifted off) and its rate
    /// of entries into that regime (per second): the probabilities beyond its kinks and the crossing rates
    /// at them.
    ///
    /// # Errors
    /// As [`Stationary::prob_above`].
    pub fn regime(&self, e: usize) -> Result<Option<(f64, f64)>> {
        let (d, law) = &self.oscillator.springs[e];
        let Some(reg) = law.regime() else { return Ok(None) };
        let mut fraction = 0.0;
        let mut rate = 0.0;
        for &(lv, above) in &reg.levels {
            let q = lv / d;
            // x = d q: above the level in x is above q/d in q for d > 0, below it for d < 0
            fraction += if above == (*d > 0.0) {
                self.prob_above(q)?
            } else {
                self.prob_below(q)?
            };
            rate += self.upcrossing_rate(q);
        }
        Ok(Some((fraction, rate)))
    }
}
