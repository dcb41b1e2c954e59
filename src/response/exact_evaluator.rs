//! Exact response statistics of many systems under one excitation: the fast path of parameter sweeps.
//!
//! [`analyze_output`](super::analyze_output) computes every variance method and cross-checks them (three
//! methods, spectral moments by quadrature): right for one analysis, far too slow for 10⁶ points. An
//! [`ExactEvaluator`] prepares what depends on the excitation only once (the shaping filters of rational
//! inputs, whose spectral factorisation dominates a single call) and evaluates each system by one exact
//! route, with no cross-check:
//!
//! * [`VarianceMethod::IntegralTable`]: one delay-free rational input process (a track of wheels without
//!   delays, or one input) and a state-space system whose augmented order is ≤ 7. One Faddeev–LeVerrier
//!   pass gives the characteristic polynomial and the adjugate of the system matrix, hence the numerator of
//!   every output's transfer function; the integral table I_n gives the variance and λ₂ (the Hurwitz
//!   elimination of the common denominator done once per system, replayed on every output's right-hand
//!   side: the same numbers as one table call per value). Nothing is allocated on the heap per system.
//!   Each value passes the condition check of the table
//!   ([`INTEGRAL_TABLE_MAX_ERROR`]: pivot ratio of the Hurwitz elimination · n · ε ≤ 1e-9); an output whose
//!   variance or λ₂ fails it is computed by [`variance_lyapunov`](super::variance_lyapunov) instead and its
//!   method says [`VarianceMethod::Lyapunov`] — no unreliable table value is returned. The same fallback applies to
//!   every output of a system whose Faddeev–LeVerrier recurrence lost digits: its Cayley–Hamilton
//!   residual max|A M_n + δ₀ I|/|δ₀| (zero in exact arithmetic) exceeds [`INTEGRAL_TABLE_MAX_ERROR`].
//! * [`VarianceMethod::Lyapunov`]: other delay-free rational inputs (several independent processes)
//!   ([`variance_lyapunov`](super::variance_lyapunov)), every output of a system from one Lyapunov solve;
//!   and one delay-free *integrated white* process (a road of ISO waviness w = 2 without band limits: white road velocity),
//!   by the realization of H(s)/s given below (an output with H(0) ≠ 0, such as an absolute displacement,
//!   has an infinite variance under it, as the asymptote check of quadrature says).
//! * [`VarianceMethod::Quadrature`]: any other input (delays, non-rational or tabulated spectra)
//!   ([`variance_quadrature`], [`spectral_moment_quadrature`]).
//!
//! # Formula
//! With the inputs combined into one (u_j = g_j q), b = B g, d = D g, e = E g and Δ(s) = det(sI − A):
//! ```text
//! adj(sI − A) = Σ_{k=1}^{n} M_k s^{n−k},  M_1 = I,  M_k = A M_{k−1} + δ_{n−k+1} I,  δ_{n−k} = −tr(A M_k)/k
//! H_i(s) = N_i(s)/Δ(s),   N_i(s) = Σ_k (c_i M_k b) s^{n−k} + (d_i + e_i s) Δ(s)
//! D_y = (1/2π) ∫ |N_i F_num / (Δ F_den)|² dω = I_n/(2π),   λ₂ = (1/2π) ∫ ω² |…|² dω,   M_y = N_i(0)/Δ(0)·μ
//! ```
//! (F = F_num/F_den the shaping filter of the input process, driven by unit-intensity white noise.)
//!
//! Integrated white input u, S_u(ω) = S_v/ω² (u̇ = v white, E[v(t)v(t+τ)] = 2πS_v δ(τ)): with
//! x̃ = x + A⁻¹b u (the state about its quasi-static value), ẋ = A x + b u gives
//! ```text
//! dx̃/dt = A x̃ + (A⁻¹b) v,   y_i = c_i x̃ + H_i(0) u + e_i v,   H_i(0) = d_i − c_i A⁻¹ b
//! ```
//! so for H_i(0) = 0 (the quasi-static output vanishes) and e_i = 0, y_i = c_i x̃ is the output of the
//! stable, strictly proper realization (A, A⁻¹b, c_i) of H_i(s)/s driven by white v:
//! A P + P Aᵀ + 2πS_v (A⁻¹b)(A⁻¹b)ᵀ = 0, D_y = c_i P c_iᵀ; λ₂ = (c_i A) P (c_i A)ᵀ when d_i = 0 (else ẏ has
//! a white part and λ₂ = ∞). H_i(0) is tested with the tolerance of the low-frequency asymptote
//! ([`FrequencyResponse::low_frequency`] of a state space: 10⁻¹²(‖D‖ + ‖C‖‖A⁻¹b‖)).

use super::statistics::{PointStatistics, VarianceMethod};
use super::variance::{
    lyapunov_outputs, moments_of, spectral_moment_quadrature, variance_quadrature, AugmentedSystem, LyapunovMoments,
    INTEGRAL_TABLE_MAX_ERROR,
};
use super::Excitation;
use crate::error::{Error, Result};
use crate::linalg::integral_table::H2Denominator;
use crate::spectrum::{Asymptote, ShapingFilter, Spectrum};
use crate::system::FrequencyResponse;
use std::f64::consts::PI;

/// Largest state count of the stack-based integral-table route (the table's order n + filter order ≤ 7).
pub(crate) const MAX_STATES: usize = 7;

/// The route an [`ExactEvaluator`] takes, decided from the excitation.
#[derive(Debug, Clone)]
enum Route {
    /// One delay-free rational process: its shaping filter, the input gains and the process mean.
    Table {
        filter: ShapingFilter,
        gains: Vec<f64>,
        mean: f64,
    },
    Lyapunov,
    /// One delay-free integrated white process (S_u = level/ω²): the input gains.
    IntegratedWhite {
        level: f64,
        gains: Vec<f64>,
    },
    Quadrature,
}

/// Evaluates the exact statistics of many systems under one excitation (see the module docs).
///
/// # Examples
/// ```
/// use stochvib::response::{analyze_output, Excitation, ExactEvaluator};
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::StateSpace;
/// use std::sync::Arc;
/// let exc = Excitation::single(Arc::new(Exponential::new(2.0, 3.0, Domain::Temporal).unwrap()), 0.5).unwrap();
/// let ev = ExactEvaluator::new(&exc);
/// for w in [5.0, 10.0, 20.0] {
///     let sys = StateSpace::oscillator(w, 0.1).unwrap();
///     let st = ev.evaluate(&sys, &exc, &[0]).unwrap()[0];
///     let full = analyze_output(&sys, &exc, 0).unwrap();
///     assert!((st.variance.unwrap() / full.variance.unwrap() - 1.0).abs() < 1e-9);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct ExactEvaluator {
    route: Route,
    /// Compute λ₂ (for ν₀⁺) where it costs a quadrature or a quadratic form ([`variances_only`](Self::variances_only)).
    lambda2: bool,
}

impl ExactEvaluator {
    /// Prepares the evaluation of systems driven by `exc`: the integral-table route when `exc` is one
    /// delay-free rational process, else Lyapunov when every input is rational and delay-free, else
    /// quadrature.
    pub fn new(exc: &Excitation) -> ExactEvaluator {
        let route = match exc {
            Excitation::Track {
                spectrum, gains, mean, ..
            } if exc.delay_free() => match spectrum.rational().map(|r| r.shaping_filter()) {
                Some(Ok(filter)) => Route::Table {
                    filter,
                    gains: gains.clone(),
                    mean: *mean,
                },
                _ => match integrated_white_level(spectrum.as_ref()) {
                    Some(level) => Route::IntegratedWhite {
                        level,
                        gains: gains.clone(),
                    },
                    None => Route::Quadrature,
                },
            },
            Excitation::Independent { spectra, .. }
                if spectra
                    .iter()
                    .all(|s| s.rational().is_some_and(|r| r.shaping_filter().is_ok())) =>
            {
                Route::Lyapunov
            }
            _ => Route::Quadrature,
        };
        ExactEvaluator { route, lambda2: true }
    }

    /// The same evaluator computing variances (and means) only: λ₂ is left out where it would cost a
    /// quadrature or a quadratic form of its own (the integral table's λ₂, nearly free, is still given), so
    /// [`PointStatistics::lambda2`] may be `None`. For callers that need σ alone (optimisation).
    pub fn variances_only(mut self) -> ExactEvaluator {
        self.lambda2 = false;
        self
    }

    /// The method the evaluator uses for a system of `n_states` states (state-space form) or `None` (no
    /// state-space form).
    pub fn method(&self, n_states: Option<usize>) -> VarianceMethod {
        match (&self.route, n_states) {
            (Route::Table { filter, .. }, Some(n)) if n + filter.den.len() - 1 <= MAX_STATES => {
                VarianceMethod::IntegralTable
            }
            (Route::Table { .. } | Route::Lyapunov | Route::IntegratedWhite { .. }, Some(_)) => {
                VarianceMethod::Lyapunov
            }
            _ => VarianceMethod::Quadrature,
        }
    }

    /// The statistics of outputs `outputs` of `sys` under `exc` (the excitation the evaluator was made
    /// for). A variance that is infinite is `None` in the result; the reason is given by
    /// [`analyze_output`](super::analyze_output).
    ///
    /// # Errors
    /// An output index out of range, an excitation that does not match the system, an unstable system
    /// (no stationary response), a numerical failure of the route.
    pub fn evaluate(
        &self,
        sys: &dyn FrequencyResponse,
        exc: &Excitation,
        outputs: &[usize],
    ) -> Result<Vec<PointStatistics>> {
        super::variance::check_shapes(sys, exc, outputs.iter().copied().max().unwrap_or(0))?;
        let ss = sys.state_space();
        match (self.method(ss.map(|s| s.n_states())), &self.route, ss) {
            (VarianceMethod::IntegralTable, Route::Table { filter, gains, mean }, Some(ss)) => {
                let mut out = Vec::with_capacity(outputs.len());
                table_route(ss, filter, gains, *mean, outputs, &mut out)?;
                // an ill-conditioned table value is not printed: that output goes by Lyapunov
                for (st, &i) in out.iter_mut().zip(outputs) {
                    if st.method == VarianceMethod::Lyapunov {
                        *st = lyapunov_point(sys, exc, i)?;
                    }
                }
                Ok(out)
            }
            (VarianceMethod::Lyapunov, Route::IntegratedWhite { level, gains }, Some(ss)) => {
                integrated_white_points(sys, ss, exc, *level, gains, outputs, self.upto())
            }
            (VarianceMethod::Lyapunov, _, _) => {
                let moments = lyapunov_outputs(sys, exc, outputs, self.upto())?;
                outputs
                    .iter()
                    .zip(moments)
                    .map(|(&i, m)| lyapunov_statistics(static_mean(sys, exc, i), m))
                    .collect()
            }
            _ => outputs
                .iter()
                .map(|&i| {
                    let mean = static_mean(sys, exc, i);
                    let variance = match variance_quadrature(sys, exc, i) {
                        Ok(q) => Some(q.value),
                        Err(Error::Divergent { .. }) => None,
                        Err(e) => return Err(e),
                    };
                    let lambda2 = if self.lambda2 {
                        variance.and(spectral_moment_quadrature(sys, exc, i, 2).ok().map(|q| q.value))
                    } else {
                        None
                    };
                    Ok(PointStatistics {
                        mean,
                        variance,
                        lambda2,
                        method: VarianceMethod::Quadrature,
                    })
                })
                .collect(),
        }
    }
}

impl ExactEvaluator {
    /// The highest spectral moment the Lyapunov routes compute.
    fn upto(&self) -> u32 {
        if self.lambda2 {
            2
        } else {
            0
        }
    }
}

/// The statistics of output `i` by [`variance_lyapunov`](super::variance_lyapunov).
pub(crate) fn lyapunov_point(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<PointStatistics> {
    let m = lyapunov_outputs(sys, exc, &[i], 2)?.pop();
    lyapunov_statistics(static_mean(sys, exc, i), m.unwrap_or_else(|| Err(unreachable_entry())))
}

/// An output's Lyapunov moments as point statistics: a divergent variance is `None`, other errors pass.
fn lyapunov_statistics(mean: Option<f64>, m: Result<LyapunovMoments>) -> Result<PointStatistics> {
    match m {
        Ok(m) => Ok(PointStatistics {
            mean,
            variance: Some(m.variance),
            lambda2: m.lambda2.ok(),
            method: VarianceMethod::Lyapunov,
        }),
        Err(Error::Divergent { .. }) => Ok(PointStatistics {
            mean,
            variance: None,
            lambda2: None,
            method: VarianceMethod::Lyapunov,
        }),
        Err(e) => Err(e),
    }
}

/// The error of a per-output list that came back shorter than the outputs asked (not expected).
fn unreachable_entry() -> Error {
    Error::Numerical {
        what: "Lyapunov moments".into(),
        reason: "no entry for the output".into(),
    }
}

/// S(ω) = S_v/ω² on the whole axis (an integrated white process, u̇ white of density S_v): its S_v, from
/// the two power-law asymptotes (exponent −2 at both ends with one coefficient, no band), confirmed on the
/// density itself at 81 log-spaced ω from 10⁻¹⁰ to 10¹⁰ and at its breakpoints (within 10⁻⁹ relative);
/// `None` for any other spectrum.
fn integrated_white_level(s: &dyn Spectrum) -> Option<f64> {
    let (
        Asymptote::Power {
            exponent: e0,
            coefficient: c0,
        },
        Asymptote::Power {
            exponent: e1,
            coefficient: c1,
        },
    ) = (s.low_frequency(), s.high_frequency())
    else {
        return None;
    };
    let level_ok = c0 > 0.0 && c0.is_finite() && (c0 - c1).abs() <= 1e-12 * c0;
    if e0 != -2.0 || e1 != -2.0 || !level_ok || s.support() != (0.0, f64::INFINITY) {
        return None;
    }
    let mut grid = (-40..=40)
        .map(|k| 10f64.powf(f64::from(k) / 4.0))
        .chain(s.breakpoints());
    grid.all(|w| w.is_nan() || w <= 0.0 || (s.density(w) * w * w / c0 - 1.0).abs() <= 1e-9)
        .then_some(c0)
}

/// The integrated-white route (module docs) for outputs `outputs` of `ss` driven through `gains` by a
/// process of density `level`/ω², every output from one Lyapunov solve, moments up to λ_`upto`.
#[allow(clippy::too_many_arguments)]
fn integrated_white_points(
    sys: &dyn FrequencyResponse,
    ss: &crate::system::StateSpace,
    exc: &Excitation,
    level: f64,
    gains: &[f64],
    outputs: &[usize],
    upto: u32,
) -> Result<Vec<PointStatistics>> {
    ss.require_stable()?;
    let (aug, finite) = integrated_white_realization(ss, level, gains, outputs)?;
    let names: Vec<&str> = outputs.iter().map(|&i| sys.outputs()[i].name.as_str()).collect();
    let moments = moments_of(&aug, &names, upto)?;
    outputs
        .iter()
        .zip(moments)
        .zip(finite)
        .map(|((&i, m), finite)| {
            let mean = static_mean(sys, exc, i);
            if !finite {
                // the quasi-static part H(0)·u of a Wiener process: infinite variance
                return lyapunov_statistics(mean, Err(divergent_at_zero(&sys.outputs()[i].name)));
            }
            lyapunov_statistics(mean, m)
        })
        .collect()
}

/// The realization (A, √(2πS_v)·A⁻¹b, C, √(2πS_v)·|e|) of H(s)/s for `outputs` (module docs), and per output
/// whether H(0) = 0 (within the low-frequency asymptote's tolerance), i.e. whether its variance is finite.
fn integrated_white_realization(
    ss: &crate::system::StateSpace,
    level: f64,
    gains: &[f64],
    outputs: &[usize],
) -> Result<(AugmentedSystem, Vec<bool>)> {
    let combined = ss.combine_inputs(gains)?;
    let x = solve_a(&combined.a, &combined.b)?;
    let h0 = &combined.d - &combined.c * &x;
    let tol = 1e-12 * combined.d.norm() + 1e-12 * combined.c.norm() * x.norm();
    let rows = combined.select_outputs(outputs)?;
    let q = (2.0 * PI * level).sqrt();
    let aug = AugmentedSystem {
        a: rows.a.clone(),
        g: x * q,
        h: rows.c.clone(),
        f: rows.e.abs() * q,
    };
    Ok((aug, outputs.iter().map(|&i| h0[(i, 0)].abs() <= tol).collect()))
}

/// A⁻¹ b.
fn solve_a(a: &nalgebra::DMatrix<f64>, b: &nalgebra::DMatrix<f64>) -> Result<nalgebra::DMatrix<f64>> {
    a.clone()
        .lu()
        .solve(b)
        .ok_or_else(|| Error::invalid("A", "singular", "the system matrix is singular"))
}

impl ExactEvaluator {
    /// The white-noise-driven realization ż = F z + G w, y = H z (one row of H per entry of `outputs`) whose
    /// Lyapunov equation F P + P Fᵀ + G Gᵀ = 0 gives the variances D_y = diag(H P Hᵀ) on this evaluator's
    /// exact routes: the system augmented with the input's shaping filter ([`augmented_system`](super::augmented_system))
    /// or, for an integrated white input, the realization of H(s)/s (module docs). `None` on the quadrature
    /// route or without a state space.
    ///
    /// # Errors
    /// As [`augmented_system`](super::augmented_system); a singular A.
    pub fn realization(
        &self,
        sys: &dyn FrequencyResponse,
        exc: &Excitation,
        outputs: &[usize],
    ) -> Option<Result<AugmentedSystem>> {
        self.realization_with_finite(sys, exc, outputs)
            .map(|r| r.map(|(aug, _)| aug))
    }

    /// [`realization`](Self::realization) and, per output, whether its variance is finite: no white-noise
    /// feedthrough (its row of `f` is zero) and, for an integrated white input, H(0) = 0 (module docs).
    pub(crate) fn realization_with_finite(
        &self,
        sys: &dyn FrequencyResponse,
        exc: &Excitation,
        outputs: &[usize],
    ) -> Option<Result<(AugmentedSystem, Vec<bool>)>> {
        let ss = sys.state_space()?;
        let made = match &self.route {
            Route::Table { .. } | Route::Lyapunov => {
                super::variance::augmented_rows(ss, exc, outputs).map(|aug| (aug, vec![true; outputs.len()]))
            }
            Route::IntegratedWhite { level, gains } => integrated_white_realization(ss, *level, gains, outputs),
            Route::Quadrature => return None,
        };
        Some(made.map(|(aug, finite)| {
            let finite = finite
                .iter()
                .enumerate()
                .map(|(r, &f)| f && aug.f.row(r).amax() == 0.0)
                .collect();
            (aug, finite)
        }))
    }

    /// The derivative (dF, dG, dH) of [`realization`](Self::realization) along a parameter θ, from the systems
    /// `plus` and `minus` built at θ ± δ and `sys` at θ: the model's matrices are differenced centrally,
    /// (M(θ+δ) − M(θ−δ))/(2δ) (exact for entries affine in θ, as stiffness and damping are; O(δ²) else), and
    /// carried through the realization analytically: the augmentation is affine in them, and the
    /// integrated-white input column G = √(2πS_v) A⁻¹b has dG = √(2πS_v) A⁻¹(db − dA A⁻¹b).
    /// `None` as [`realization`](Self::realization).
    ///
    /// # Errors
    /// As [`realization`](Self::realization).
    pub fn realization_derivative(
        &self,
        sys: &dyn FrequencyResponse,
        plus: &dyn FrequencyResponse,
        minus: &dyn FrequencyResponse,
        delta: f64,
        exc: &Excitation,
        outputs: &[usize],
    ) -> Option<Result<AugmentedSystem>> {
        let diff = |p: &nalgebra::DMatrix<f64>, m: &nalgebra::DMatrix<f64>| (p - m) / (2.0 * delta);
        if let Route::IntegratedWhite { level, gains } = &self.route {
            let (ss, sp, sm) = (sys.state_space()?, plus.state_space()?, minus.state_space()?);
            let derivative = || -> Result<AugmentedSystem> {
                let [c0, cp, cm] =
                    [ss, sp, sm].map(|s| s.combine_inputs(gains).and_then(|c| c.select_outputs(outputs)));
                let (c0, cp, cm) = (c0?, cp?, cm?);
                let da = diff(&cp.a, &cm.a);
                let db = diff(&cp.b, &cm.b);
                let x = solve_a(&c0.a, &c0.b)?;
                let q = (2.0 * PI * level).sqrt();
                Ok(AugmentedSystem {
                    g: solve_a(&c0.a, &(db - &da * x))? * q,
                    a: da,
                    h: diff(&cp.c, &cm.c),
                    f: diff(&cp.e, &cm.e) * q,
                })
            };
            return Some(derivative());
        }
        let (p, m) = (
            self.realization(plus, exc, outputs)?,
            self.realization(minus, exc, outputs)?,
        );
        Some(p.and_then(|p| {
            m.map(|m| AugmentedSystem {
                a: diff(&p.a, &m.a),
                g: diff(&p.g, &m.g),
                h: diff(&p.h, &m.h),
                f: diff(&p.f, &m.f),
            })
        }))
    }
}

fn divergent_at_zero(name: &str) -> Error {
    Error::Divergent {
        quantity: format!("variance of `{name}`"),
        reason: "H(0) ≠ 0 under an integrated white input (an unbounded road): the density grows like ω⁻² as \
                 ω → 0"
            .into(),
    }
}

/// M_y = H(0)·M_u from the system's static gain (None when infinite).
fn static_mean(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Option<f64> {
    sys.static_gain().map(|g| {
        let mu = exc.means();
        (0..g.ncols()).map(|j| g[(i, j)] * mu[j]).sum::<f64>()
    })
}

/// Faddeev–LeVerrier on the stack for a state-space system of at most [`MAX_STATES`] states driven by
/// one combined input (module docs): Δ(s) = det(sI − A) and the vectors M_k b.
pub(crate) struct Leverrier {
    /// Number of states n.
    pub(crate) n: usize,
    /// Δ, ascending, monic (length n + 1 used).
    pub(crate) delta: [f64; MAX_STATES + 1],
    /// M_k b for k = 1..n (row k − 1).
    mb: [[f64; MAX_STATES]; MAX_STATES],
    /// max |A M_n + δ₀ I| / |δ₀|: the Cayley–Hamilton residual of the recurrence, relative (NaN or ∞ when
    /// δ₀ = 0).
    pub(crate) residual: f64,
}

impl Leverrier {
    /// Δ and M_k b of `ss` with the inputs combined by `gains` (b = B g). `ss` has ≤ [`MAX_STATES`] states.
    pub(crate) fn new(ss: &crate::system::StateSpace, gains: &[f64]) -> Leverrier {
        const N: usize = MAX_STATES;
        let n = ss.n_states();
        let m = ss.b.ncols();
        // combined input column b = B g
        let mut a = [[0.0; N]; N];
        let mut b = [0.0; N];
        for r in 0..n {
            for (c, v) in a[r].iter_mut().enumerate().take(n) {
                *v = ss.a[(r, c)];
            }
            b[r] = (0..m).map(|j| ss.b[(r, j)] * gains[j]).sum();
        }
        // Faddeev–LeVerrier: delta (ascending, monic) and M_k b
        let mut delta = [0.0; N + 1];
        delta[n] = 1.0;
        let mut mk = [[0.0; N]; N];
        let mut am = [[0.0; N]; N];
        let mut mb = [[0.0; N]; N];
        for k in 1..=n {
            // M_k = A M_{k-1} + delta[n+1-k] I  (M_0 = 0)
            for r in 0..n {
                for c in 0..n {
                    mk[r][c] = am[r][c] + if r == c { delta[n + 1 - k] } else { 0.0 };
                }
            }
            for r in 0..n {
                mb[k - 1][r] = (0..n).map(|c| mk[r][c] * b[c]).sum();
            }
            // A M_k, its trace gives delta[n-k]
            let mut tr = 0.0;
            for r in 0..n {
                for c in 0..n {
                    let mut s = 0.0;
                    for j in 0..n {
                        s += a[r][j] * mk[j][c];
                    }
                    am[r][c] = s;
                }
                tr += am[r][r];
            }
            delta[n - k] = -tr / k as f64;
        }
        // Cayley–Hamilton: M_{n+1} = A M_n + δ₀ I vanishes in exact arithmetic; its size relative to |δ₀|
        // measures the rounding the recurrence accumulated (stiff systems lose digits here)
        let mut residual: f64 = 0.0;
        for (r, row) in am.iter().enumerate().take(n) {
            for (c, v) in row.iter().enumerate().take(n) {
                residual = residual.max((v + if r == c { delta[0] } else { 0.0 }).abs());
            }
        }
        let residual = if n == 0 { 0.0 } else { residual / delta[0].abs() };
        Leverrier { n, delta, mb, residual }
    }

    /// N_i(s) = Σ_k (c_i M_k b) s^{n−k} + (d_i + e_i s) Δ(s), ascending (length n + 2 used), with
    /// d = D g, e = E g.
    pub(crate) fn numerator(&self, ss: &crate::system::StateSpace, gains: &[f64], i: usize) -> [f64; MAX_STATES + 2] {
        let (n, m) = (self.n, ss.b.ncols());
        let di: f64 = (0..m).map(|j| ss.d[(i, j)] * gains[j]).sum();
        let ei: f64 = (0..m).map(|j| ss.e[(i, j)] * gains[j]).sum();
        let mut ni = [0.0; MAX_STATES + 2];
        for k in 1..=n {
            ni[n - k] = (0..n).map(|c| ss.c[(i, c)] * self.mb[k - 1][c]).sum();
        }
        for (p, &dp) in self.delta[..=n].iter().enumerate() {
            ni[p] += di * dp;
            ni[p + 1] += ei * dp;
        }
        ni
    }
}

/// The integral-table route (module docs), on the stack, appending one entry per output to `out`. An
/// output whose Hurwitz elimination (variance or λ₂) is ill-conditioned (pivot ratio · n · ε above
/// [`INTEGRAL_TABLE_MAX_ERROR`]) gets an entry with method [`VarianceMethod::Lyapunov`] and no numbers: the
/// caller computes it by Lyapunov.
pub(crate) fn table_route(
    ss: &crate::system::StateSpace,
    filter: &ShapingFilter,
    gains: &[f64],
    mean: f64,
    outputs: &[usize],
    out: &mut Vec<PointStatistics>,
) -> Result<()> {
    let lv = Leverrier::new(ss, gains);
    if lv.residual.is_nan() || lv.residual > INTEGRAL_TABLE_MAX_ERROR {
        // the characteristic and numerator polynomials themselves lost digits: every output by Lyapunov
        for _ in outputs {
            out.push(UNRELIABLE);
        }
        return Ok(());
    }
    table_outputs(
        &lv.delta[..=lv.n],
        |i| lv.numerator(ss, gains, i),
        filter,
        mean,
        outputs,
        false,
        out,
    )
}

/// An entry of [`table_route`] whose table value failed its check: the caller computes it by Lyapunov.
const UNRELIABLE: PointStatistics = PointStatistics {
    mean: None,
    variance: None,
    lambda2: None,
    method: VarianceMethod::Lyapunov,
};

/// The table statistics of outputs `outputs` of a system with characteristic polynomial `delta`
/// (ascending, degree n ≤ [`MAX_STATES`]) and numerators `numerator(i)` (ascending, n + 2 coefficients used)
/// for the combined input, under the process of shaping filter `filter` and mean `mean`: one Hurwitz
/// elimination of Δ·F_den, a back substitution per value, the pivot-ratio check on each (see
/// [`table_route`]). With `adjoint`, each value is instead the dot product of its right-hand side with
/// the table's linear functional, computed once from the elimination (`H2Denominator::weights`; the same
/// pivot ratio, equal within rounding); otherwise the numbers are those of one table call per value, bit
/// for bit.
#[allow(clippy::too_many_arguments)]
fn table_outputs(
    delta: &[f64],
    numerator: impl Fn(usize) -> [f64; MAX_STATES + 2],
    filter: &ShapingFilter,
    mean: f64,
    outputs: &[usize],
    adjoint: bool,
    out: &mut Vec<PointStatistics>,
) -> Result<()> {
    const N: usize = MAX_STATES;
    let n = delta.len() - 1;
    let fnum = &filter.num;
    let fden = &filter.den;
    let den_len = n + fden.len();
    let mut den = [0.0; 2 * N + 2];
    mul_into(delta, fden, &mut den);
    let reliable = |ratio: f64| ratio * (den_len - 1) as f64 * f64::EPSILON <= INTEGRAL_TABLE_MAX_ERROR;
    // one Hurwitz elimination of the common denominator for every output's variance and λ₂
    let table = H2Denominator::new(&den[..den_len]);
    let weights = if adjoint { table.weights() } else { None };
    let h2 = |num: &[f64]| match weights.as_ref().and_then(|w| w.h2(num)) {
        Some(v) => Ok(v),
        None => table.h2_conditioned(num),
    };
    for &i in outputs {
        let ni = numerator(i);
        let ni_len = n + 2;
        let mut num = [0.0; 2 * N + 4];
        let num_len = mul_into(&ni[..ni_len], fnum, &mut num);
        let static_mean = if delta[0] != 0.0 {
            Some(ni[0] / delta[0] * mean)
        } else {
            None
        };
        if let Some((v, l2, ratio)) = weights.as_ref().and_then(|w| w.h2_with_moment(&num[..num_len])) {
            // variance and λ₂ from one set of right-hand sides (one pivot ratio for both)
            out.push(if reliable(ratio) {
                PointStatistics {
                    mean: static_mean,
                    variance: Some(v / (2.0 * PI)),
                    lambda2: l2.map(|l| l / (2.0 * PI)),
                    method: VarianceMethod::IntegralTable,
                }
            } else {
                UNRELIABLE
            });
            continue;
        }
        let variance = match h2(&num[..num_len]) {
            Ok((v, ratio)) if reliable(ratio) => Some(v / (2.0 * PI)),
            Ok(_) => {
                out.push(UNRELIABLE);
                continue;
            }
            Err(Error::Divergent { .. }) => None,
            Err(e) => return Err(unstable_or(e, delta)),
        };
        let mut lambda2 = None;
        if variance.is_some() {
            let mut s_num = [0.0; 2 * N + 5];
            s_num[1..=num_len].copy_from_slice(&num[..num_len]);
            match h2(&s_num[..=num_len]) {
                Ok((v, ratio)) if reliable(ratio) => lambda2 = Some(v / (2.0 * PI)),
                Ok(_) => {
                    out.push(UNRELIABLE);
                    continue;
                }
                Err(_) => {}
            }
        }
        out.push(PointStatistics {
            mean: static_mean,
            variance,
            lambda2,
            method: VarianceMethod::IntegralTable,
        });
    }
    Ok(())
}

/// Largest number of outputs of a [`TransferPolynomials`].
pub(crate) const MAX_TRANSFER_OUTPUTS: usize = 8;

/// The transfer functions H_i(s) = N_i(s)/Δ(s) from the single input of a system to each of its outputs,
/// with one common denominator, ascending in s, on the stack: what a model kind's closed-form builder
/// writes per point of a parameter study (see [`NumericModel`](crate::scenario::NumericModel)), in place of
/// the state space and its Faddeev–LeVerrier pass.
///
/// Δ has degree n ≤ [`MAX_STATES`] (`den[..=n]`, any non-zero leading coefficient); each N_i has degree
/// ≤ n + 1 (`num[i][..n + 2]`, a degree n + 1 meaning an output with a direct term in u̇, as E ≠ 0 of a
/// state space). Coefficients beyond those are zero.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TransferPolynomials {
    /// Δ(s), ascending.
    pub(crate) den: [f64; MAX_STATES + 1],
    /// The degree n of Δ.
    pub(crate) n: usize,
    /// N_i(s), ascending, one row per output of the model (in the model's output order).
    pub(crate) num: [[f64; MAX_STATES + 2]; MAX_TRANSFER_OUTPUTS],
}

/// A model kind's closed-form transfer-polynomial builder: writes [`TransferPolynomials`] for one value per
/// key of the kind's numeric builder (None: absent), or returns false where the model cannot be built. The
/// polynomials arrive as [`TransferPolynomials::zero`] gives them (the builder writes only its non-zero
/// coefficients).
pub(crate) type TransferBuilder = fn(&[Option<f64>], &mut TransferPolynomials) -> bool;

impl TransferPolynomials {
    /// All coefficients zero, degree 0.
    pub(crate) fn zero() -> TransferPolynomials {
        TransferPolynomials {
            den: [0.0; MAX_STATES + 1],
            n: 0,
            num: [[0.0; MAX_STATES + 2]; MAX_TRANSFER_OUTPUTS],
        }
    }
}

impl ExactEvaluator {
    /// The integral-table statistics of outputs `outputs` (rows of `tp.num`) of the single-input system
    /// whose transfer functions are `tp`, under the excitation the evaluator was made for: as
    /// [`evaluate`](Self::evaluate)'s table route, with Δ and N_i given instead of computed from a state
    /// space, and every value a dot product with the table's linear functional of Δ·F_den (one Hurwitz
    /// elimination per system; equal to one table call per value within rounding, same pivot-ratio check). An output whose table value fails its check comes back with method
    /// [`VarianceMethod::Lyapunov`] and no numbers (the caller computes it by Lyapunov on a state space).
    /// None when the table route does not apply: the excitation is not one delay-free rational process on
    /// one input, or the augmented order exceeds [`MAX_STATES`].
    ///
    /// # Errors
    /// An unstable system (Δ·F_den not Hurwitz), a numerical failure of the table (inside the `Some`).
    pub(crate) fn evaluate_transfer(
        &self,
        tp: &TransferPolynomials,
        outputs: &[usize],
        out: &mut Vec<PointStatistics>,
    ) -> Option<Result<()>> {
        let Route::Table { filter, gains, mean } = &self.route else {
            return None;
        };
        let n = tp.n;
        if gains.len() != 1 || n == 0 || n + filter.den.len() - 1 > MAX_STATES || tp.den[n] == 0.0 {
            return None;
        }
        if outputs.iter().any(|&i| i >= MAX_TRANSFER_OUTPUTS) {
            return None;
        }
        // monic, as Faddeev–LeVerrier's Δ (the table's value does not depend on the scaling)
        let lead = tp.den[n];
        let mut delta = [0.0; MAX_STATES + 1];
        for (d, v) in delta.iter_mut().zip(&tp.den[..=n]) {
            *d = v / lead;
        }
        let g = gains[0] / lead;
        Some(table_outputs(
            &delta[..=n],
            |i| tp.num[i].map(|v| v * g),
            filter,
            *mean,
            outputs,
            true,
            out,
        ))
    }
}

/// A failure of the table for a characteristic polynomial that is not Hurwitz is an unstable system.
fn unstable_or(e: Error, delta: &[f64]) -> Error {
    match e {
        Error::InvalidParameter { reason, .. } if reason.contains("not stable") => Error::invalid(
            "A",
            format!("det(sI - A) = {delta:?} (ascending)"),
            "the system is not asymptotically stable: no stationary response exists",
        ),
        e => e,
    }
}

/// p·q (ascending) into `out`; returns the length used. Each coefficient Σᵢ pᵢq_{k−i} is summed in a
/// register in ascending i (the order, and so the rounding, of accumulating pᵢ·q row by row into a zeroed
/// `out`), so no sum waits on a store of the previous product.
#[inline]
pub(crate) fn mul_into(p: &[f64], q: &[f64], out: &mut [f64]) -> usize {
    debug_assert!(
        !p.is_empty() && !q.is_empty(),
        "polynomials have at least one coefficient"
    );
    // a shaping filter's polynomials have a few coefficients: a copy of the loop per length, whose inner
    // loop the compiler unrolls (the same operations in the same order)
    match q.len() {
        1 => mul_into_q::<1>(p, q, out),
        2 => mul_into_q::<2>(p, q, out),
        3 => mul_into_q::<3>(p, q, out),
        4 => mul_into_q::<4>(p, q, out),
        _ => mul_into_any(p, q, out),
    }
}

/// [`mul_into`] for `q.len()` = Q: the coefficients with all Q terms (Q − 1 ≤ k < p.len()) as one
/// unrolled sum each, the others by [`mul_into_any`]'s loop (every sum from 0 in ascending i, as there).
#[inline(always)]
fn mul_into_q<const Q: usize>(p: &[f64], q: &[f64], out: &mut [f64]) -> usize {
    let q: &[f64; Q] = q.try_into().unwrap_or_else(|_| unreachable!("q has Q coefficients"));
    let len = p.len() + Q - 1;
    for (k, o) in out[..len].iter_mut().enumerate() {
        if k + 1 >= Q && k < p.len() {
            let window = &p[k + 1 - Q..=k];
            let mut acc = 0.0;
            for t in 0..Q {
                acc += window[t] * q[Q - 1 - t];
            }
            *o = acc;
        } else {
            *o = coefficient(p, q, k);
        }
    }
    len
}

/// Σᵢ pᵢq_{k−i} over the valid i, ascending, from 0.
#[inline(always)]
fn coefficient(p: &[f64], q: &[f64], k: usize) -> f64 {
    let lo = (k + 1).saturating_sub(q.len());
    let hi = k.min(p.len() - 1);
    let mut acc = 0.0;
    for i in lo..=hi {
        acc += p[i] * q[k - i];
    }
    acc
}

/// [`mul_into`] for any lengths.
#[inline(always)]
fn mul_into_any(p: &[f64], q: &[f64], out: &mut [f64]) -> usize {
    let len = p.len() + q.len() - 1;
    for (k, o) in out[..len].iter_mut().enumerate() {
        *o = coefficient(p, q, k);
    }
    len
}
