//! Route 1: statistical (Gaussian-equivalent) linearization with means, iterated on the linear machinery.
//!
//! # Formula
//! Every element's remainder is replaced by its Gaussian equivalent F₀ + k_eq (x − μ_x) + c_eq (v − μ_v)
//! ([`Equivalent`]) over the current Gaussian law of its deflection and rate. Given the equivalents:
//! * the fluctuation is the response of the linear model with the springs k_eq and dampers c_eq added,
//!   whose variances come from the linear machinery — Lyapunov for rational delay-free inputs, its delayed
//!   form for delayed rational inputs, adaptive quadrature otherwise (two tracks, non-rational spectra);
//! * the means solve the static equilibrium C μ_q + Σ_e d_e E\[F_e\] = K_u μ_u + F μ_f (exact in the mean;
//!   q̇ and q̈ have mean 0 in a stationary response), by one Newton step per iteration with the Jacobian
//!   C + Σ k_eq d dᵀ (∂E\[F\]/∂μ = E\[∂F/∂x\] for a Gaussian law).
//!
//! The iteration starts from the linear part (an element that adds no damping and leaves the linear part
//! without a stationary response gets a provisional 10 % of critical damping along its direction), and
//! under-relaxes the equivalents and the means by ω (default ½). It stops when no element's σ_x, σ_v (and
//! mean, relative to σ) changes by more than the tolerance between iterations. Caughey (1963), "Equivalent
//! linearization techniques", J. Acoust. Soc. Am. 35, 1706–1711; Roberts & Spanos (1990), *Random Vibration
//! and Statistical Linearization*, Wiley (means included: their ch. 5).
//!
//! Route 1 is an approximation: the response of a nonlinear system is not Gaussian. It is good for mild
//! nonlinearity (a Duffing spring: within 7 % in σ² at εσ₀² = 1) and poor for the tails of stiff contacts:
//! the Gaussian tail beyond a stop's clearance overestimates contact rates by orders of magnitude.
//!
//! Non-convergence is an outcome with its reason ([`Route1Outcome::NotConverged`]): an equivalent system
//! without a stationary response (a softening spring beyond its strength), friction that sticks (σ_v → 0,
//! c_eq → ∞), a velocity-dependent element on an input of infinite velocity variance, or no convergence in
//! the iteration limit.

use super::{ElementMoments, Equivalent, NonlinearElement, NonlinearModel};
use crate::error::{Error, Result};
use crate::quad_oscillatory::OscillatoryOptions;
use crate::response::{
    analyze_output_with, variance_lyapunov, variance_lyapunov_delayed, variance_oscillatory, Excitation,
    ResponseStatistics,
};
use crate::system::{FrequencyResponse, Mdof, STABILITY_RESOLUTION};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use serde::Serialize;

/// Friction whose Gaussian equivalent damping exceeds this multiple of the critical damping along its
/// direction (2√(k_d m_d), k_d = dᵀCd, m_d = 1/κ) locks its element: route 1 reports no meaningful answer.
pub const STICK_DAMPING_RATIO: f64 = 10.0;

/// Options of [`linearize`].
#[derive(Debug, Clone)]
pub struct Route1Options {
    /// Convergence tolerance on the relative change of every σ (and of every mean relative to its σ).
    pub tolerance: f64,
    /// Largest number of iterations.
    pub max_iterations: usize,
    /// Under-relaxation ω ∈ (0, 1]: new = (1 − ω)·old + ω·update.
    pub relaxation: f64,
    /// Effort of the quadratures (inputs without an exact route).
    pub effort: OscillatoryOptions,
}

impl Default for Route1Options {
    fn default() -> Self {
        Route1Options {
            tolerance: 1e-10,
            max_iterations: 400,
            relaxation: 0.5,
            effort: OscillatoryOptions::default(),
        }
    }
}

/// The converged Gaussian equivalent of a nonlinear model.
#[derive(Debug, Clone)]
pub struct Route1 {
    /// The linear part with the equivalents added (the model's outputs, then two per element: `<e>:x`,
    /// `<e>:v`).
    pub equivalent: Mdof,
    /// Number of the model's own outputs (the first outputs of `equivalent`).
    pub n_outputs: usize,
    /// The equivalent of every element's remainder.
    pub coefficients: Vec<Equivalent>,
    /// The Gaussian moments of every element's deflection and rate.
    pub moments: Vec<ElementMoments>,
    /// Mean of every coordinate, μ_q.
    pub mean_q: Vec<f64>,
    /// Mean of every output of the model (the static part: μ_q and the input means through the output's
    /// weights).
    pub output_means: Vec<f64>,
    /// Iterations used.
    pub iterations: usize,
    /// How the variances were computed (`lyapunov`, `lyapunov (delays)`, `quadrature`).
    pub method: &'static str,
}

/// The outcome of route 1.
#[derive(Debug, Clone)]
pub enum Route1Outcome {
    /// Converged to the tolerance.
    Converged(Box<Route1>),
    /// No Gaussian equivalent: why, and what to change.
    NotConverged {
        /// Why.
        reason: String,
        /// What to change.
        advice: String,
        /// Iterations done.
        iterations: usize,
    },
}

/// A failed route 1 as a report line.
#[derive(Debug, Clone, Serialize)]
pub struct NotConverged {
    /// Why.
    pub reason: String,
    /// What to change.
    pub advice: String,
}

impl Route1Outcome {
    /// The converged solution, if any.
    pub fn converged(&self) -> Option<&Route1> {
        match self {
            Route1Outcome::Converged(r) => Some(r),
            Route1Outcome::NotConverged { .. } => None,
        }
    }

    fn fail(reason: impl Into<String>, advice: impl Into<String>, iterations: usize) -> Route1Outcome {
        Route1Outcome::NotConverged {
            reason: reason.into(),
            advice: advice.into(),
            iterations,
        }
    }
}

/// The variance of output `i` of `sys` under `exc`: Lyapunov (delay-free rational inputs), its delayed form
/// (delayed rational inputs), else adaptive quadrature; with the method's name.
///
/// # Errors
/// [`Error::Divergent`] for an infinite variance; a quadrature that does not converge.
pub fn output_variance(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    effort: &OscillatoryOptions,
) -> Result<(f64, &'static str)> {
    let exact = if exc.delay_free() {
        variance_lyapunov(sys, exc, i).map(|m| (m.variance, "lyapunov"))
    } else {
        variance_lyapunov_delayed(sys, exc, i).map(|m| (m.variance, "lyapunov (delays)"))
    };
    match exact {
        Ok(v) => Ok(v),
        Err(e @ Error::Divergent { .. }) => Err(e),
        Err(_) => variance_oscillatory(sys, exc, i, effort).map(|q| (q.value, "quadrature")),
    }
}

/// Route 1 for `model` under `exc` (see the module docs).
///
/// # Errors
/// Only for an excitation that does not fit the model; every other failure is a
/// [`Route1Outcome::NotConverged`] with its reason.
///
/// # Examples
/// ```
/// use stochvib::nonlinear::{linearize, CubicSpring, NonlinearElement, NonlinearModel, Route1Options};
/// use stochvib::response::Excitation;
/// use stochvib::spectrum::{Domain, RationalSpectrum};
/// use stochvib::system::{Attach, Drive, MassSpringDamper, Mdof, Quantity};
/// use std::sync::Arc;
/// // Duffing, m = k = 1, c = 0.2, white force S₀ = 0.2/π: σ₀² = πS₀/(ck) = 1; ε = k₃/k = 1
/// let lin = MassSpringDamper { mass: 1.0, stiffness: 1.0, damping: 0.2, drive: Drive::Force }.build().unwrap().with_output("x", Quantity::Displacement(vec![1.0])).unwrap();
/// let e = NonlinearElement { name: "cubic".into(), law: Arc::new(CubicSpring::new(0.0, 1.0).unwrap()),
///     point: vec![1.0], to: Attach::Ground };
/// let model = NonlinearModel::new(&lin, vec![e]).unwrap();
/// let white = Arc::new(RationalSpectrum::new(vec![0.2 / std::f64::consts::PI], vec![1.0], Domain::Temporal).unwrap());
/// let r = linearize(&model, &Excitation::single(white, 0.0).unwrap(), &Route1Options::default()).unwrap();
/// let s2 = r.converged().unwrap().moments[0].sigma_x.powi(2);
/// assert!((s2 - ((13.0f64).sqrt() - 1.0) / 6.0).abs() < 1e-8); // root of 3σ⁴ + σ² − 1 = 0
/// ```
pub fn linearize(model: &NonlinearModel, exc: &Excitation, opts: &Route1Options) -> Result<Route1Outcome> {
    let probe = model.with_element_outputs()?;
    let p = model.linear().outputs().len();
    if exc.n_inputs() != probe.n_inputs() {
        return Err(Error::invalid(
            "excitation",
            exc.n_inputs(),
            format!("the model has {} inputs", probe.n_inputs()),
        ));
    }
    let mut it = Iteration::new(model, exc, &probe, p, opts);
    let mut eq = match it.start() {
        Ok(eq) => eq,
        Err(o) => return Ok(o),
    };
    let mut mean_q = match it.mean(&eq, &vec![ElementMoments::default(); eq.len()]) {
        Ok((m, _)) => m,
        Err(o) => return Ok(o),
    };
    let mut prev: Option<Vec<ElementMoments>> = None;
    for k in 1..=opts.max_iterations {
        let (sys, moments) = match it.moments(&eq, &mean_q, k) {
            Ok(x) => x,
            Err(o) => return Ok(o),
        };
        let new: Vec<Equivalent> = model
            .elements()
            .iter()
            .zip(&moments)
            .map(|(e, m)| e.law.gaussian(m))
            .collect();
        if let Some(o) = it.check_finite(&new, &moments, k) {
            return Ok(o);
        }
        let (mean_new, _) = match it.mean(&new, &moments) {
            Ok(m) => m,
            Err(o) => return Ok(o),
        };
        if prev.as_ref().is_some_and(|pm| change(pm, &moments) <= opts.tolerance) {
            if let Some(o) = it.check_sticking(&new, k) {
                return Ok(o);
            }
            return Ok(Route1Outcome::Converged(Box::new(
                it.finish(sys, new, moments, mean_new, k),
            )));
        }
        let w = if prev.is_none() { 1.0 } else { opts.relaxation };
        eq = relax(&eq, &new, w);
        mean_q = mean_q
            .iter()
            .zip(&mean_new)
            .map(|(a, b)| (1.0 - w) * a + w * b)
            .collect();
        prev = Some(moments);
    }
    Ok(Route1Outcome::fail(
        format!(
            "the equivalent stiffnesses and dampings did not settle within {} iterations (tolerance {:e})",
            opts.max_iterations, opts.tolerance
        ),
        "the Gaussian closure may have no or several fixed points here; use route 2 (--monte-carlo), or a stronger \
         under-relaxation",
        opts.max_iterations,
    ))
}

fn relax(old: &[Equivalent], new: &[Equivalent], w: f64) -> Vec<Equivalent> {
    old.iter()
        .zip(new)
        .map(|(a, b)| Equivalent {
            mean_force: (1.0 - w) * a.mean_force + w * b.mean_force,
            stiffness: (1.0 - w) * a.stiffness + w * b.stiffness,
            damping: (1.0 - w) * a.damping + w * b.damping,
        })
        .collect()
}

/// The largest relative change of a σ, or of a mean relative to its σ, between two iterations.
fn change(a: &[ElementMoments], b: &[ElementMoments]) -> f64 {
    let rel = |x: f64, y: f64, s: f64| if s > 0.0 { (x - y).abs() / s } else { (x - y).abs() };
    a.iter()
        .zip(b)
        .map(|(a, b)| {
            rel(a.sigma_x, b.sigma_x, b.sigma_x)
                .max(rel(a.sigma_v, b.sigma_v, b.sigma_v))
                .max(rel(a.mean_x, b.mean_x, b.sigma_x))
        })
        .fold(0.0, f64::max)
}

/// The state of one route-1 computation.
struct Iteration<'a> {
    model: &'a NonlinearModel,
    exc: &'a Excitation,
    probe: &'a Mdof,
    p: usize,
    opts: &'a Route1Options,
    method: &'static str,
    /// Per element, the first element with the same direction and base (itself if none): elements between
    /// the same two points (a damper and a bump stop across one suspension) have the same deflection and
    /// rate, i.e. the same output rows of the probe, so their variances are computed once.
    placement: Vec<usize>,
}

impl<'a> Iteration<'a> {
    fn new(model: &'a NonlinearModel, exc: &'a Excitation, probe: &'a Mdof, p: usize, opts: &'a Route1Options) -> Self {
        let els = model.elements();
        let placement = (0..els.len())
            .map(|i| {
                let same = |j: usize| els[j].direction() == els[i].direction() && els[j].base() == els[i].base();
                (0..i).find(|&j| same(j)).unwrap_or(i)
            })
            .collect();
        Iteration {
            model,
            exc,
            probe,
            p,
            opts,
            method: "lyapunov",
            placement,
        }
    }

    /// The probe's output rows whose variances an iteration needs: σ_x of every element's placement and σ_v
    /// of those whose law needs it, each row once, in the order the elements first read them.
    fn needed_rows(&self) -> Vec<usize> {
        let mut rows = Vec::new();
        for (i, e) in self.model.elements().iter().enumerate() {
            let x = self.p + 2 * self.placement[i];
            for r in [Some(x), reads_rate(e).then_some(x + 1)].into_iter().flatten() {
                if !rows.contains(&r) {
                    rows.push(r);
                }
            }
        }
        rows
    }

    /// The starting equivalents: zero, with provisional damping when the linear part is not asymptotically
    /// stable and an element can damp it.
    fn start(&self) -> std::result::Result<Vec<Equivalent>, Route1Outcome> {
        let n = self.model.elements().len();
        let mut eq = vec![Equivalent::default(); n];
        if stable(self.model.linear()) {
            return Ok(eq);
        }
        let (m_inv, c) = (self.model.linear().mass_inverse(), self.model.linear().stiffness());
        for (e, q) in self.model.elements().iter().zip(eq.iter_mut()) {
            if e.law.velocity_dependent() {
                let d = DVector::from_vec(e.direction());
                let kappa = (d.transpose() * m_inv * &d)[(0, 0)];
                let k = (d.transpose() * c * &d)[(0, 0)];
                q.damping = 0.2 * (k.max(f64::MIN_POSITIVE) / kappa).sqrt().max(0.2 / kappa.sqrt());
            }
        }
        Ok(eq)
    }

    /// The equivalent system and the Gaussian moments of every element under it.
    fn moments(
        &mut self,
        eq: &[Equivalent],
        mean_q: &[f64],
        k: usize,
    ) -> std::result::Result<(Mdof, Vec<ElementMoments>), Route1Outcome> {
        let sys = self
            .model
            .with_equivalents(self.probe, eq)
            .map_err(|e| Route1Outcome::fail(e.to_string(), "check the element parameters", k))?;
        if !stable(&sys) {
            return Err(Route1Outcome::fail(
                instability_reason(&sys),
                "the Gaussian equivalent does not exist; route 2 (--monte-carlo) shows whether the response escapes",
                k,
            ));
        }
        // the variances of the distinct rows side by side (each one deterministic: the same bits on any
        // number of threads), then read in element order, so the first failure reported is the same
        let rows = self.needed_rows();
        let variances: Vec<Result<(f64, &'static str)>> = rows
            .par_iter()
            .map(|&r| output_variance(&sys, self.exc, r, &self.opts.effort))
            .collect();
        let mut out = Vec::with_capacity(eq.len());
        for (i, e) in self.model.elements().iter().enumerate() {
            let mut m = ElementMoments {
                mean_x: self.mean_x(i, mean_q),
                ..Default::default()
            };
            let (x, own) = (self.p + 2 * self.placement[i], self.p + 2 * i);
            let of = |r: usize| &variances[rows.iter().position(|&q| q == r).expect("a needed row")];
            m.sigma_x = self.sigma(&sys, of(x), own, k)?;
            if reads_rate(e) {
                m.sigma_v = self.sigma(&sys, of(x + 1), own + 1, k)?;
            }
            out.push(m);
        }
        Ok((sys, out))
    }

    /// σ from the variance of output `i` of `sys` (`variance`, computed for `i` or for an identical row of an
    /// earlier element), or the outcome that reports its failure.
    fn sigma(
        &mut self,
        sys: &Mdof,
        variance: &Result<(f64, &'static str)>,
        i: usize,
        k: usize,
    ) -> std::result::Result<f64, Route1Outcome> {
        let computed = match variance {
            Ok(v) => Ok(*v),
            // a failure names the row it was computed for: computed again for row i, it names this element's
            // own output, as when every element computed its own rows
            Err(_) => output_variance(sys, self.exc, i, &self.opts.effort),
        };
        match computed {
            Ok((v, method)) => {
                self.method = method;
                Ok(v.max(0.0).sqrt())
            }
            Err(e) => {
                let advice = match e {
                    Error::Divergent { .. } => "a velocity-dependent element needs a relative velocity of finite \
                                                variance: attach it between masses, or give the input a spectrum \
                                                that decays faster than ω⁻²"
                        .to_string(),
                    _ => quadrature_advice(sys),
                };
                Err(Route1Outcome::fail(
                    format!("`{}`: {e}", sys.outputs()[i].name),
                    advice,
                    k,
                ))
            }
        }
    }

    /// μ_x of element i for the coordinate means `mean_q`.
    fn mean_x(&self, i: usize, mean_q: &[f64]) -> f64 {
        let e = &self.model.elements()[i];
        let mu_u = self.exc.means();
        let x: f64 = e.direction().iter().zip(mean_q).map(|(d, q)| d * q).sum();
        x - e.base().map_or(0.0, |j| mu_u[j])
    }

    /// One Newton step of the static equilibrium C μ_q + Σ d E[F] = K_u μ_u + F μ_f from the moments'
    /// means, with the Jacobian C + Σ k_eq d dᵀ; returns the new means and the Jacobian.
    fn mean(
        &self,
        eq: &[Equivalent],
        moments: &[ElementMoments],
    ) -> std::result::Result<(Vec<f64>, DMatrix<f64>), Route1Outcome> {
        let lin = self.model.linear();
        let mu_u = self.exc.means();
        let nb = lin.n_base();
        let mut rhs = lin.base_stiffness() * DVector::from_column_slice(&mu_u[..nb])
            + lin.force_distribution() * DVector::from_column_slice(&mu_u[nb..]);
        let mut jac = lin.stiffness().clone();
        for ((e, q), m) in self.model.elements().iter().zip(eq).zip(moments) {
            let d = DVector::from_vec(e.direction());
            jac += q.stiffness * &d * d.transpose();
            rhs -= (q.mean_force - q.stiffness * m.mean_x) * &d;
            if let Some(j) = e.base() {
                rhs += q.stiffness * mu_u[j] * &d;
            }
        }
        match jac.clone().lu().solve(&rhs) {
            Some(x) if x.iter().all(|v| v.is_finite()) => Ok((x.as_slice().to_vec(), jac)),
            _ => Err(Route1Outcome::fail(
                "the static equilibrium has no unique solution (the stiffness matrix with the equivalent \
                 stiffnesses is singular: a free rigid-body mode)",
                "the means of a free body are undefined; support the model or ask for relative outputs",
                0,
            )),
        }
    }

    fn check_finite(&self, new: &[Equivalent], moments: &[ElementMoments], k: usize) -> Option<Route1Outcome> {
        let bad = new
            .iter()
            .zip(self.model.elements())
            .zip(moments)
            .find(|((q, _), _)| !(q.mean_force.is_finite() && q.stiffness.is_finite() && q.damping.is_finite()))?;
        let ((_, e), m) = bad;
        Some(Route1Outcome::fail(
            format!(
                "element `{}` ({}): its Gaussian equivalent is infinite (σ_v = {:e}: the element sticks, a friction \
                 force the excitation cannot overcome)",
                e.name,
                e.law.kind(),
                m.sigma_v
            ),
            "route 1 is not meaningful for a sticking element; use route 2 (--monte-carlo)",
            k,
        ))
    }

    /// A friction element whose equivalent damping locks it (see [`STICK_DAMPING_RATIO`]).
    fn check_sticking(&self, eq: &[Equivalent], k: usize) -> Option<Route1Outcome> {
        let lin = self.model.linear();
        let (m_inv, c) = (lin.mass_inverse(), lin.stiffness());
        self.model.elements().iter().zip(eq).find_map(|(e, q)| {
            if !e.law.can_stick() {
                return None;
            }
            let d = DVector::from_vec(e.direction());
            let kappa = (d.transpose() * m_inv * &d)[(0, 0)];
            let kd = (d.transpose() * c * &d)[(0, 0)];
            let critical = 2.0 * (kd / kappa).sqrt();
            (q.damping > STICK_DAMPING_RATIO * critical).then(|| {
                Route1Outcome::fail(
                    format!(
                        "element `{}` sticks: its Gaussian equivalent damping {:.4e} N s/m is {:.1} times the critical \
                         damping along it — the friction force exceeds what the excitation can overcome, so the \
                         linearized element is locked and route 1 is not meaningful",
                        e.name,
                        q.damping,
                        q.damping / critical
                    ),
                    "use route 2 (--monte-carlo), which follows stick and slip",
                    k,
                )
            })
        })
    }

    fn finish(
        &self,
        sys: Mdof,
        coefficients: Vec<Equivalent>,
        moments: Vec<ElementMoments>,
        mean_q: Vec<f64>,
        k: usize,
    ) -> Route1 {
        let mu_u = self.exc.means();
        let lin = self.model.linear();
        let output_means = (0..self.p)
            .map(|r| {
                let w = lin.output_weights(r).expect("an output of the model");
                let q: f64 = w.q.iter().zip(&mean_q).map(|(a, b)| a * b).sum();
                q + w.u.iter().zip(&mu_u).map(|(a, b)| a * b).sum::<f64>()
            })
            .collect();
        Route1 {
            equivalent: sys,
            n_outputs: self.p,
            coefficients,
            moments,
            mean_q,
            output_means,
            iterations: k,
            method: self.method,
        }
    }
}

impl Route1 {
    /// The statistics of the model's outputs under route 1: those of the equivalent linear system by
    /// every applicable method ([`analyze_output_with`]), with the mean replaced by route 1's mean. The
    /// outputs are computed side by side (each the same on any number of threads).
    ///
    /// # Errors
    /// As [`analyze_output_with`]: the first failing output's.
    pub fn output_statistics(&self, exc: &Excitation, effort: &OscillatoryOptions) -> Result<Vec<ResponseStatistics>> {
        let each: Vec<Result<ResponseStatistics>> = (0..self.n_outputs)
            .into_par_iter()
            .map(|r| {
                let mut st = analyze_output_with(&self.equivalent, exc, r, effort)?;
                st.values.mean = Some(self.output_means[r]);
                Ok(st)
            })
            .collect();
        each.into_iter().collect()
    }

    /// Route 1's fraction of time in element e's regime and its rate of entries (per second): the Gaussian
    /// probability beyond each level and Rice's rate (σ_v/(2πσ_x)) e^{−(a−μ)²/(2σ_x²)} there; `None` for an
    /// element without a regime.
    pub fn regime(&self, model: &NonlinearModel, e: usize) -> Option<(f64, f64)> {
        let reg = model.elements()[e].law.regime()?;
        let m = &self.moments[e];
        let mut fraction = 0.0;
        let mut rate = 0.0;
        for &(a, above) in &reg.levels {
            let z = if above { m.mean_x - a } else { a - m.mean_x };
            fraction += super::gauss::prob_positive(z, m.sigma_x);
            if m.sigma_x > 0.0 {
                let u = (a - m.mean_x) / m.sigma_x;
                rate += m.sigma_v / (2.0 * std::f64::consts::PI * m.sigma_x) * (-0.5 * u * u).exp();
            }
        }
        Some((fraction, rate))
    }
}

/// Whether route 1 needs the σ of element e's rate: its law depends on the velocity, or it has a regime
/// (whose entry rate is Rice's, from σ_v).
fn reads_rate(e: &NonlinearElement) -> bool {
    e.law.velocity_dependent() || e.law.regime().is_some()
}

/// Damping ratios below which a mode of the equivalent system counts as almost undamped: its resonance
/// peak, of relative width 2ζ, is then narrower than the variance quadrature's tolerance lets it resolve.
pub const UNDAMPED_MODE_ZETA: f64 = 1e-4;

/// What to change when the equivalent system's variance quadrature fails: its least damped mode if that is
/// almost undamped ([`UNDAMPED_MODE_ZETA`]; a stiff element can lock the coordinates the dampers act on,
/// leaving a mode nothing damps), else the quadrature's effort.
fn quadrature_advice(sys: &Mdof) -> String {
    let least = sys.state_space().map(|ss| {
        ss.a.complex_eigenvalues()
            .iter()
            .filter(|l| l.im > 0.0)
            .map(|l| (-l.re / l.norm(), l.norm()))
            .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a })
    });
    match least {
        Some((zeta, w)) if zeta < UNDAMPED_MODE_ZETA => format!(
            "the equivalent system's mode at {} rad/s is almost undamped (ζ = {}): its resonance is a peak \
             narrower than the quadrature resolves. A very stiff element (a stop's contact, a cubic spring far \
             beyond its clearance) can lock the coordinates the dampers act on; route 2 (--monte-carlo) needs no \
             Gaussian equivalent, or give the element a contact stiffness nearer the suspension's",
            crate::numbers::num(w),
            crate::numbers::num(zeta)
        ),
        _ => "raise the quadrature effort (its subintervals), or use route 2 (--monte-carlo)".to_string(),
    }
}

/// Why the equivalent system `sys` has no stationary response: an eigenvalue with Re λ ≥ 0, or a decay
/// rate so small beside the stiffest term of its state matrix that its eigenvalues cannot tell it from
/// zero (the stability test's resolution; a very stiff element that locks the damped coordinates).
fn instability_reason(sys: &Mdof) -> String {
    let worst = sys.state_space().and_then(|ss| {
        let top =
            ss.a.complex_eigenvalues()
                .iter()
                .copied()
                .reduce(|a, b| if b.re > a.re { b } else { a })?;
        Some((top, ss.a.amax()))
    });
    match worst {
        Some((l, scale)) if l.re.abs() <= STABILITY_RESOLUTION * scale => format!(
            "the equivalent linear system's mode at {} rad/s has Re λ = {} 1/s, which its eigenvalues cannot \
             tell from zero beside its stiffest term ({}): nothing damps that mode within rounding. A very stiff \
             element (a stop's contact, a cubic spring far beyond its clearance) can lock the coordinates the \
             dampers act on; give it a contact stiffness nearer the suspension's",
            crate::numbers::num(l.im.abs()),
            crate::numbers::num(l.re),
            crate::numbers::num(scale)
        ),
        _ => "the equivalent linear system has no stationary response (an eigenvalue with Re λ ≥ 0): a softening \
              element has lost its stiffness at this excitation level, or nothing damps a coordinate"
            .to_string(),
    }
}

fn stable(m: &Mdof) -> bool {
    m.state_space().is_some_and(|ss| ss.require_stable().is_ok())
}
