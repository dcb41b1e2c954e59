//! The exact route: the mean and covariance of the states by the differential Lyapunov equation, integrated
//! by matrix exponentials on an adaptive grid with an error estimate.

use super::system::{Frozen, TimeVaryingSystem};
use crate::error::{Error, Result};
use crate::simulate::van_loan;
use nalgebra::{DMatrix, DVector};

/// Error control of [`propagate`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ExactOptions {
    /// Local relative error allowed per step (on every variance of the states and every mean, relative to
    /// the largest variance of that state seen so far, and to the standard deviation for the means).
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
    /// The largest accumulated error estimate (relative) at any stored time.
    pub max_error_estimate: f64,
}

/// One step's transition: P ← ΦPΦᵀ + Q_d, m ← Φm + Γ.
#[derive(Debug, Clone)]
struct Transition {
    phi: DMatrix<f64>,
    qd: DMatrix<f64>,
    gamma: DVector<f64>,
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
    let q = &tr.phi * p * tr.phi.transpose() + &tr.qd;
    ((&q + q.transpose()) * 0.5, &tr.phi * m + &tr.gamma)
}

/// The integrator's state between steps.
struct Integrator<'a> {
    sys: &'a TimeVaryingSystem,
    opts: ExactOptions,
    /// The largest variance of each state seen so far (error scale).
    scale: Vec<f64>,
    /// Accumulated local error estimates, relative to `scale`.
    error: f64,
    report: StepReport,
    /// The last constant-coefficient transition and its step.
    cache: Option<(Frozen, f64, Transition)>,
}

impl Integrator<'_> {
    /// Transition for constant coefficients `fr` over h, reused when the last one had the same coefficients
    /// and a step within 10⁻¹² relative (stored times k·Δt differ from their differences in the last bits;
    /// the reuse shifts the time grid by at most that fraction of a step).
    fn cached(&mut self, fr: Frozen, h: f64) -> Result<Transition> {
        if let Some((f, hh, tr)) = &self.cache
            && (hh - h).abs() <= 1e-12 * h
            && *f == fr
        {
            return Ok(tr.clone());
        }
        let tr = transition(&fr, h, &mut self.report.exponentials)?;
        self.cache = Some((fr, h, tr.clone()));
        Ok(tr)
    }

    /// One trial step from t over h: the new mean and covariance and the relative error estimate.
    ///
    /// # Formula
    /// The frozen coefficients at the midpoint make a second-order, time-symmetric scheme. When the
    /// coefficients are equal at t + h/4, t + h/2 and t + 3h/4 (piecewise-linear data with no knot inside
    /// the step: constant), the step is exact. Otherwise the step is taken once over h (P_h) and as two
    /// half steps (P_{h/2}); the local error of P_{h/2} is estimated by (P_{h/2} − P_h)/3 (Richardson, order
    /// 2) and the extrapolated P_{h/2} + (P_{h/2} − P_h)/3 is kept.
    fn trial(
        &mut self,
        t: f64,
        h: f64,
        p: &DMatrix<f64>,
        m: &DVector<f64>,
    ) -> Result<(DMatrix<f64>, DVector<f64>, f64, bool)> {
        let mid = self.sys.frozen(t + 0.5 * h)?;
        if self.sys.is_invariant() {
            let tr = self.cached(mid, h)?;
            let (p1, m1) = apply(&tr, p, m);
            return Ok((p1, m1, 0.0, true));
        }
        let (q1, q3) = (self.sys.frozen(t + 0.25 * h)?, self.sys.frozen(t + 0.75 * h)?);
        if q1 == mid && q3 == mid {
            let tr = self.cached(mid, h)?;
            let (p1, m1) = apply(&tr, p, m);
            return Ok((p1, m1, 0.0, true));
        }
        let c = &mut self.report.exponentials;
        let (pa, ma) = apply(&transition(&mid, h, c)?, p, m);
        let (ph, mh) = apply(&transition(&q1, 0.5 * h, c)?, p, m);
        let (pb, mb) = apply(&transition(&q3, 0.5 * h, c)?, &ph, &mh);
        let dp = (&pb - &pa) / 3.0;
        let dm = (&mb - &ma) / 3.0;
        let err = self.error_norm(&pb, &dp, &mb, &dm);
        Ok((pb + dp, mb + dm, err, false))
    }

    /// max over the states of |ΔP_ii|/scale_i and |Δm_i|/(√scale_i + |m_i|).
    fn error_norm(&self, p: &DMatrix<f64>, dp: &DMatrix<f64>, m: &DVector<f64>, dm: &DVector<f64>) -> f64 {
        (0..p.nrows())
            .map(|i| {
                let s = self.scale[i].max(p[(i, i)]).max(f64::MIN_POSITIVE);
                let ep = dp[(i, i)].abs() / s;
                let em = dm[i].abs() / (s.sqrt() + m[i].abs()).max(f64::MIN_POSITIVE);
                ep.max(em)
            })
            .fold(0.0, f64::max)
    }
}

/// What [`propagate`] calls at every stored time: (k, t_k, P, m, accumulated error estimate).
pub type Visit<'a> = dyn FnMut(usize, f64, &DMatrix<f64>, &DVector<f64>, f64) -> Result<()> + 'a;

/// Propagates the mean and covariance of `sys` from (P(0), m(0)) = (`p0`, `m0`) to every time of `times`
/// (increasing, ≥ 0), calling `visit(k, t_k, P, m, error)` at each, where `error` is the accumulated
/// relative error estimate of the variances up to t_k.
///
/// # Formula
/// ```text
/// Ṗ = F(t)P + PF(t)ᵀ + G(t)G(t)ᵀ,     ṁ = F(t)m + b(t)
/// ```
/// integrated step by step with the exact transition of the frozen coefficients ([`Integrator::trial`]:
/// exact where the coefficients are constant, else midpoint coefficients with step doubling). The step
/// adapts to keep the local error estimate below `rel_tol` (new step h·min(4, max(0.2, 0.9(tol/err)^{1/3}))),
/// and ends at every stored time and every knot of the coefficients. The error reported at t_k is the sum of
/// the local estimates so far (an upper estimate for a stable system, whose errors decay).
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
    let mut it = Integrator {
        sys,
        opts: *opts,
        scale: (0..p0.nrows()).map(|i| p0[(i, i)]).collect(),
        error: 0.0,
        report: StepReport::default(),
        cache: None,
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
            let (p1, m1, err, exact) = it.trial(t, step, &p, &m)?;
            if err > it.opts.rel_tol && step > 1e-12 * span.max(1.0) {
                it.report.rejected += 1;
                h = step * (0.9 * (it.opts.rel_tol / err).cbrt()).max(0.2);
                continue;
            }
            (p, m, t) = (p1, m1, if step == end - t { end } else { t + step });
            it.error += err;
            it.report.steps += 1;
            it.report.exact_steps += usize::from(exact);
            if it.report.steps > it.opts.max_steps {
                return Err(Error::invalid(
                    "max_steps",
                    it.opts.max_steps,
                    format!("the exact route needed more steps by t = {t} s: loosen rel_tol or raise max_steps"),
                ));
            }
            for (i, s) in it.scale.iter_mut().enumerate() {
                *s = s.max(p[(i, i)]);
            }
            h = if exact {
                h.max(step)
            } else {
                step * (0.9 * (it.opts.rel_tol / err.max(1e-300)).cbrt()).clamp(0.2, 4.0)
            };
        }
        it.report.max_error_estimate = it.report.max_error_estimate.max(it.error);
        visit(k, target, &p, &m, it.error)?;
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
