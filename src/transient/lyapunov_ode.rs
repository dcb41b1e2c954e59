//! The exact route: the mean and covariance of the states by the differential Lyapunov equation, integrated
//! by matrix exponentials on an adaptive grid with an error estimate.

use super::affine_step::{affine_transition, AffineNoise, AffineTransition};
use super::system::{Frozen, TimeVaryingSystem};
use crate::error::{Error, Result};
use crate::simulate::van_loan;
use nalgebra::{DMatrix, DVector};
use std::rc::Rc;

/// Error control of [`propagate`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ExactOptions {
    /// Local error allowed per step, relative to the scale of each state over the window: a variance error
    /// relative to the largest variance of that state over the window, a mean error relative to the largest
    /// standard deviation plus the largest |mean| (both from a pilot pass, raised by what the accurate pass
    /// finds). A state whose variance starts at 0 (a start from rest) is judged against the size it reaches,
    /// not against its own near-zero value.
    pub rel_tol: f64,
    /// Steps allowed in all (a refused run names it).
    pub max_steps: usize,
}

impl Default for ExactOptions {
    fn default() -> Self {
        ExactOptions {
            rel_tol: 1e-9,
            max_steps: 2_000_000,
        }
    }
}

/// What the integration did.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct StepReport {
    /// Accepted steps.
    pub steps: usize,
    /// Steps on which the coefficients were constant (exact, no error).
    pub exact_steps: usize,
    /// Rejected (halved) steps.
    pub rejected: usize,
    /// Matrix exponentials computed.
    pub exponentials: usize,
    /// The accumulated error estimate at the end of the window, relative to the largest variance of each
    /// state over the window (see [`propagate`]); the largest of the stored times' estimates.
    pub max_error_estimate: f64,
}

/// One step's transition: P ← ΦPΦᵀ + Q_d, m ← Φm + Γ.
#[derive(Debug, Clone)]
struct Transition {
    phi: DMatrix<f64>,
    /// Φᵀ, formed once for every step that applies the transition.
    phi_t: DMatrix<f64>,
    qd: DMatrix<f64>,
    gamma: DVector<f64>,
}

/// Multiple of ε·max|Q_d| (and ε·max|Γ|) below which a step's error estimate is rounding, not truncation
/// (see [`Transition::rounding_floor`]).
const ROUNDING_ULPS: f64 = 64.0;

impl Transition {
    /// The absolute rounding level of a step's variances and means: (`ROUNDING_ULPS`·ε·max_jk |Q_d,jk|,
    /// `ROUNDING_ULPS`·ε·max_j |Γ_j|).
    ///
    /// # Formula
    /// Q_d comes out of one matrix exponential of the 2n×2n Van Loan matrix, whose rounding error is
    /// normwise: every entry of the computed Q_d carries an absolute error of a few ε·max|Q_d|, whatever
    /// the entry's own size (Higham, *Functions of Matrices*, 2008, §10.3, the backward error of scaling and
    /// squaring). A state whose variance is zero by a cancellation (the roll of a symmetric body whose two
    /// wheels read one track) is therefore computed as rounding of that size, and so is the difference of
    /// its step-doubling estimates: an error estimate below this floor is not a truncation error a smaller
    /// step could reduce, and the error control ignores it (without the floor such a state refuses every
    /// step down to 10⁻¹¹ s).
    fn rounding_floor(&self) -> (f64, f64) {
        (
            ROUNDING_ULPS * f64::EPSILON * self.qd.amax(),
            ROUNDING_ULPS * f64::EPSILON * self.gamma.amax(),
        )
    }
}

/// The transition of the frozen form `fr` over h, exact for coefficients constant on the step.
///
/// # Formula
/// Van Loan (1978), "Computing integrals involving the matrix exponential", IEEE Trans. Autom. Control
/// 23(3), 395–404: e^{[[−F, GGᵀ], [0, Fᵀ]]h} gives Φ = e^{Fh} and Q_d = ∫₀ʰ e^{Fs}GGᵀe^{Fᵀs}ds; the mean's
/// Γ = ∫₀ʰ e^{Fs}ds·b is the last column of e^{[[F, b], [0, 0]]h}.
fn transition(fr: &Frozen, h: f64, count: &mut usize) -> Result<Transition> {
    let d = van_loan(&fr.f, &fr.g, h)?;
    *count += 1 + usize::from(fr.b.iter().any(|v| *v != 0.0));
    Ok(Transition {
        phi_t: d.phi.transpose(),
        phi: d.phi,
        qd: d.qd,
        gamma: mean_step(fr, h)?,
    })
}

/// Γ = ∫₀ʰ e^{Fs}ds·b, the last column of e^{[[F, b], [0, 0]]h} (zero without forcing).
///
/// # Errors
/// A failed matrix exponential.
pub(crate) fn mean_step(fr: &Frozen, h: f64) -> Result<DVector<f64>> {
    let n = fr.f.nrows();
    if fr.b.iter().all(|v| *v == 0.0) {
        return Ok(DVector::zeros(n));
    }
    let mut big = DMatrix::zeros(n + 1, n + 1);
    big.view_mut((0, 0), (n, n)).copy_from(&(&fr.f * h));
    big.view_mut((0, n), (n, 1)).copy_from(&(&fr.b * h));
    Ok(crate::linalg::expm(&big)?.column(n).rows(0, n).into_owned())
}

fn apply(tr: &Transition, p: &DMatrix<f64>, m: &DVector<f64>) -> (DMatrix<f64>, DVector<f64>) {
    let q = &tr.phi * p * &tr.phi_t + &tr.qd;
    ((&q + q.transpose()) * 0.5, &tr.phi * m + &tr.gamma)
}

/// Step lengths whose affine-intensity transitions are kept.
const AFFINE_CACHE: usize = 4;

/// The integrator's state between steps.
struct Integrator<'a> {
    sys: &'a TimeVaryingSystem,
    opts: ExactOptions,
    /// The largest variance of each state over the window (the pilot's, raised by the accurate pass).
    scale: Vec<f64>,
    /// The largest |mean| of each state over the window (likewise).
    mean_scale: Vec<f64>,
    /// Accumulated absolute local error estimates of each state's variance.
    error_p: Vec<f64>,
    /// Accumulated absolute local error estimates of each state's mean.
    error_m: Vec<f64>,
    report: StepReport,
    /// The last constant-coefficient transition and its step.
    cache: Option<(Frozen, f64, Rc<Transition>)>,
    /// The last affine-intensity transitions and their steps (at most [`AFFINE_CACHE`]).
    affine_cache: Vec<(f64, Rc<AffineTransition>)>,
}

impl Integrator<'_> {
    /// Transition for constant coefficients `fr` over h, reused when the last one had the same coefficients
    /// and a step within 10⁻¹² relative (stored times k·Δt differ from their differences in the last bits;
    /// the reuse shifts the time grid by at most that fraction of a step).
    fn cached(&mut self, fr: Frozen, h: f64) -> Result<Rc<Transition>> {
        if let Some((f, hh, tr)) = &self.cache
            && (hh - h).abs() <= 1e-12 * h
            && *f == fr
        {
            return Ok(Rc::clone(tr));
        }
        let tr = Rc::new(transition(&fr, h, &mut self.report.exponentials)?);
        self.cache = Some((fr, h, Rc::clone(&tr)));
        Ok(tr)
    }

    /// Affine-intensity transition of `aff` over h, reused for any step within 10⁻¹² relative of one of the
    /// last [`AFFINE_CACHE`] step lengths (as [`Integrator::cached`]; F and ḠḠᵀ do not change, κ enters only
    /// when the transition is applied). Several lengths alternate where the stored times are not multiples
    /// of the step cap or a knot cuts an interval.
    fn affine_cached(&mut self, aff: &AffineNoise, h: f64) -> Result<Rc<AffineTransition>> {
        if let Some((_, tr)) = self.affine_cache.iter().find(|(hh, _)| (hh - h).abs() <= 1e-12 * h) {
            return Ok(Rc::clone(tr));
        }
        let tr = Rc::new(affine_transition(aff, h, &mut self.report.exponentials)?);
        if self.affine_cache.len() == AFFINE_CACHE {
            self.affine_cache.remove(0);
        }
        self.affine_cache.push((h, Rc::clone(&tr)));
        Ok(tr)
    }

    /// One trial step from t over h: the new mean and covariance and the relative error estimate.
    ///
    /// # Formula
    /// A system of affine intensity ([`AffineNoise`]: F, b, H constant, GGᵀ = κ(t)ḠḠᵀ with κ linear on the
    /// step, which never crosses a knot) takes the exact step of [`affine_transition`]. Otherwise the frozen
    /// coefficients at the midpoint make a second-order, time-symmetric scheme. When the
    /// coefficients are equal at t + h/4, t + h/2 and t + 3h/4 (piecewise-linear data with no knot inside
    /// the step: constant), the step is exact. Otherwise the step is taken once over h (P_h) and as two
    /// half steps (P_{h/2}); the local error of P_{h/2} is estimated by (P_{h/2} − P_h)/3 (Richardson, order
    /// 2) and the extrapolated P_{h/2} + (P_{h/2} − P_h)/3 is kept.
    fn trial(&mut self, t: f64, h: f64, p: &DMatrix<f64>, m: &DVector<f64>) -> Result<Trial> {
        if let Some(aff) = self.sys.affine_noise() {
            let tr = self.affine_cached(aff, h)?;
            let (p, m) = tr.apply(aff.factor(t), aff.factor(t + h), p, m);
            return Ok(Trial::exact(p, m));
        }
        let mid = self.sys.frozen(t + 0.5 * h)?;
        let exact = |tr: &Transition| {
            let (p, m) = apply(tr, p, m);
            Trial::exact(p, m)
        };
        if self.sys.is_invariant() {
            return Ok(exact(&*self.cached(mid, h)?));
        }
        let (q1, q3) = (self.sys.frozen(t + 0.25 * h)?, self.sys.frozen(t + 0.75 * h)?);
        if q1 == mid && q3 == mid {
            return Ok(exact(&*self.cached(mid, h)?));
        }
        let c = &mut self.report.exponentials;
        let (whole, first, second) = (
            transition(&mid, h, c)?,
            transition(&q1, 0.5 * h, c)?,
            transition(&q3, 0.5 * h, c)?,
        );
        let (pa, ma) = apply(&whole, p, m);
        let (ph, mh) = apply(&first, p, m);
        let (pb, mb) = apply(&second, &ph, &mh);
        let dp = (&pb - &pa) / 3.0;
        let dm = (&mb - &ma) / 3.0;
        // the rounding of the three transitions, each entering the difference once
        let (floor_p, floor_m) = [whole, first, second]
            .iter()
            .map(Transition::rounding_floor)
            .fold((0.0, 0.0), |(a, b), (fp, fm)| (a + fp, b + fm));
        Ok(Trial {
            p: pb + &dp,
            m: mb + &dm,
            dp: dp.diagonal().map(|e| (e.abs() - floor_p).max(0.0)),
            dm: dm.map(|e| (e.abs() - floor_m).max(0.0)),
            exact: false,
        })
    }

    /// max over the states of ΔP_i/scale_i and Δm_i/(√scale_i + mean_scale_i), with the scales raised to
    /// the state's current variance and |mean| (errors of the variances `dp` and means `dm`, absolute).
    fn error_norm(&self, p: &DMatrix<f64>, m: &DVector<f64>, dp: &[f64], dm: &[f64]) -> f64 {
        (0..p.nrows())
            .map(|i| {
                let s = self.scale[i].max(p[(i, i)]).max(f64::MIN_POSITIVE);
                let ms = self.mean_scale[i].max(m[i].abs());
                (dp[i] / s).max(dm[i] / (s.sqrt() + ms).max(f64::MIN_POSITIVE))
            })
            .fold(0.0, f64::max)
    }

    /// The accumulated error estimate relative to the scales (see [`Integrator::error_norm`]).
    fn accumulated(&self, p: &DMatrix<f64>, m: &DVector<f64>) -> f64 {
        self.error_norm(p, m, &self.error_p, &self.error_m)
    }

    /// Raises the scales to the state's variances and |means| after an accepted step.
    fn raise_scales(&mut self, p: &DMatrix<f64>, m: &DVector<f64>) {
        for i in 0..p.nrows() {
            self.scale[i] = self.scale[i].max(p[(i, i)]);
            self.mean_scale[i] = self.mean_scale[i].max(m[i].abs());
        }
    }
}

/// One trial step: the new covariance and mean, the absolute local error estimates of each state's
/// variance and mean above the step's rounding level ([`Transition::rounding_floor`]; zero for an exact
/// step), and whether it was exact.
struct Trial {
    p: DMatrix<f64>,
    m: DVector<f64>,
    dp: DVector<f64>,
    dm: DVector<f64>,
    exact: bool,
}

impl Trial {
    /// An exact step to (P, m): no error estimate.
    fn exact(p: DMatrix<f64>, m: DVector<f64>) -> Self {
        Trial {
            dp: DVector::zeros(p.nrows()),
            dm: DVector::zeros(m.len()),
            p,
            m,
            exact: true,
        }
    }
}

/// Number of pilot steps over the window at least (the pilot's scale is sampled at their ends).
const PILOT_STEPS: usize = 256;

/// The largest variance and |mean| of each state over the window by a pilot pass: midpoint-frozen
/// transitions without error control on the stored times and knots, each interval cut into pieces of at
/// most 1/[`PILOT_STEPS`] of the window. A scale for the error control, within a few per cent of the accurate
/// pass's (the accurate pass raises it where it is larger).
fn pilot_scales(
    sys: &TimeVaryingSystem,
    p0: &DMatrix<f64>,
    m0: &DVector<f64>,
    times: &[f64],
) -> Result<(Vec<f64>, Vec<f64>)> {
    let span = times.last().copied().unwrap_or(0.0);
    let mut ends: Vec<f64> = times
        .iter()
        .chain(sys.knots())
        .copied()
        .filter(|t| *t > 0.0 && *t <= span)
        .collect();
    ends.sort_by(f64::total_cmp);
    ends.dedup();
    let (mut p, mut m, mut t) = (p0.clone(), m0.clone(), 0.0);
    let mut var: Vec<f64> = p.diagonal().iter().copied().collect();
    let mut mean: Vec<f64> = m.iter().map(|x| x.abs()).collect();
    let mut count = 0;
    for end in ends {
        let pieces = ((end - t) * PILOT_STEPS as f64 / span).ceil().max(1.0) as usize;
        let h = (end - t) / pieces as f64;
        for j in 0..pieces {
            let fr = sys.frozen(t + (j as f64 + 0.5) * h)?;
            (p, m) = apply(&transition(&fr, h, &mut count)?, &p, &m);
            for i in 0..p.nrows() {
                var[i] = var[i].max(p[(i, i)]);
                mean[i] = mean[i].max(m[i].abs());
            }
        }
        t = end;
    }
    Ok((var, mean))
}

/// What [`propagate`] calls at every stored time: (k, t_k, P, m, accumulated error estimate).
pub type Visit<'a> = dyn FnMut(usize, f64, &DMatrix<f64>, &DVector<f64>, f64) -> Result<()> + 'a;

/// Propagates the mean and covariance of `sys` from (P(0), m(0)) = (`p0`, `m0`) to every time of `times`
/// (increasing, ≥ 0), calling `visit(k, t_k, P, m, error)` at each, where `error` is the accumulated error
/// estimate up to t_k relative to the scale of each state over the window (below).
///
/// # Formula
/// ```text
/// Ṗ = F(t)P + PF(t)ᵀ + G(t)G(t)ᵀ,     ṁ = F(t)m + b(t)
/// ```
/// integrated step by step with the exact transition of the frozen coefficients (`Integrator::trial`:
/// exact where the coefficients are constant or only the noise intensity varies, linearly between knots
/// ([`super::affine_step`]), else midpoint coefficients with step doubling). The step
/// adapts to keep the local error estimate below `rel_tol` (new step h·min(4, max(0.2, 0.9(tol/err)^{1/3}))),
/// and ends at every stored time and every knot of the coefficients.
///
/// Errors are measured against the scale of each state over the whole window: a variance error against
/// the state's largest variance s_i, a mean error against √s_i plus its largest |mean|. Time-varying
/// systems with inexact steps take these scales from a pilot pass (`pilot_scales`); the accurate pass
/// raises them where it
/// finds more. The estimate reported at t_k is max_i of the accumulated absolute local estimates so far over
/// those scales: an upper estimate for a stable system, whose errors decay. (An error relative to each
/// step's own variance would be meaningless where the variance is near 0, at a start from rest, and would
/// force the steps there down to nothing.) Local estimates are counted above the step's rounding level only
/// (`Transition::rounding_floor`): a state whose variance is zero by a cancellation is rounding noise, and
/// so is its estimate.
///
/// # Errors
/// Times that are negative, not finite or not increasing; more than `max_steps` steps; the model's errors;
/// a failed matrix exponential.
pub fn propagate(
    sys: &TimeVaryingSystem,
    p0: DMatrix<f64>,
    m0: DVector<f64>,
    times: &[f64],
    opts: &ExactOptions,
    visit: &mut Visit<'_>,
) -> Result<StepReport> {
    check_times(times)?;
    if !(opts.rel_tol > 0.0 && opts.rel_tol < 1.0) {
        return Err(Error::invalid("rel_tol", opts.rel_tol, "must be in (0, 1)"));
    }
    let n = p0.nrows();
    let (scale, mean_scale) = if sys.is_invariant() || sys.affine_noise().is_some() {
        (
            p0.diagonal().iter().copied().collect(),
            m0.iter().map(|x| x.abs()).collect(),
        )
    } else {
        pilot_scales(sys, &p0, &m0, times)?
    };
    let mut it = Integrator {
        sys,
        opts: *opts,
        scale,
        mean_scale,
        error_p: vec![0.0; n],
        error_m: vec![0.0; n],
        report: StepReport::default(),
        cache: None,
        affine_cache: Vec::new(),
    };
    let (mut p, mut m, mut t) = (p0, m0, 0.0);
    let span = times.last().copied().unwrap_or(0.0);
    let mut h = (span / 100.0).max(f64::MIN_POSITIVE);
    for (k, &target) in times.iter().enumerate() {
        while t < target {
            let end = sys
                .knots()
                .iter()
                .copied()
                .find(|x| *x > t)
                .map_or(target, |x| x.min(target));
            let step = if h >= end - t || end - t - h < 1e-12 * end.abs().max(1.0) {
                end - t
            } else {
                h
            };
            let tr = it.trial(t, step, &p, &m)?;
            let err = it.error_norm(&tr.p, &tr.m, tr.dp.as_slice(), tr.dm.as_slice());
            if err > it.opts.rel_tol && step > 1e-12 * span.max(1.0) {
                it.report.rejected += 1;
                h = step * (0.9 * (it.opts.rel_tol / err).cbrt()).max(0.2);
                continue;
            }
            (p, m, t) = (tr.p, tr.m, if step == end - t { end } else { t + step });
            for i in 0..n {
                it.error_p[i] += tr.dp[i];
                it.error_m[i] += tr.dm[i];
            }
            it.raise_scales(&p, &m);
            it.report.steps += 1;
            it.report.exact_steps += usize::from(tr.exact);
            if it.report.steps > it.opts.max_steps {
                return Err(Error::invalid(
                    "max_steps",
                    it.opts.max_steps,
                    format!("the exact route needed more steps by t = {t} s: loosen rel_tol or raise max_steps"),
                ));
            }
            h = if tr.exact {
                h.max(step)
            } else {
                step * (0.9 * (it.opts.rel_tol / err.max(1e-300)).cbrt()).clamp(0.2, 4.0)
            };
        }
        let error = it.accumulated(&p, &m);
        it.report.max_error_estimate = it.report.max_error_estimate.max(error);
        visit(k, target, &p, &m, error)?;
    }
    Ok(it.report)
}

fn check_times(times: &[f64]) -> Result<()> {
    for (k, &t) in times.iter().enumerate() {
        if !(t.is_finite() && t >= 0.0) || (k > 0 && t <= times[k - 1]) {
            return Err(Error::invalid(
                &format!("times[{k}]"),
                t,
                "stored times are finite, >= 0 and strictly increasing",
            ));
        }
    }
    Ok(())
}
