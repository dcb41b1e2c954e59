//! The variance of an output three independent ways, band variances and spectral moments.

use super::{Excitation, OutputDensity};
use crate::error::{Error, Result};
use crate::linalg::integral_table::h2_integral_conditioned;
use crate::linalg::transfer::scaled_transfer_polynomials;
use crate::linalg::{poly, solve_continuous_lyapunov};
use crate::quad::{integrate, QuadOptions, QuadResult};
use crate::quad_oscillatory::OscillatoryOptions;
use crate::spectrum::{Asymptote, ShapingFilter};
use crate::system::{FrequencyResponse, StateSpace, TransferFunction};
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// Two-sided density S_y(ω) of output `i`: the plain dense reference (the system's full H(iω), then
/// H S_u Hᴴ for row `i`). For many ω use [`OutputDensity`], which computes the same up to rounding
/// without allocating per ω (the quadrature routes here use it).
pub fn output_density(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize, omega: f64) -> f64 {
    let h = sys.response(omega);
    let row: Vec<_> = (0..h.ncols()).map(|j| h[(i, j)]).collect();
    exc.output_density(&row, omega)
}

fn combine(a: Asymptote, b: Asymptote) -> Asymptote {
    match (a, b) {
        (
            Asymptote::Power {
                exponent: e1,
                coefficient: c1,
            },
            Asymptote::Power {
                exponent: e2,
                coefficient: c2,
            },
        ) => Asymptote::Power {
            exponent: e1 + e2,
            coefficient: c1 * c2,
        },
        _ => Asymptote::Vanishing,
    }
}

fn dominant(list: impl IntoIterator<Item = Asymptote>, high: bool) -> Asymptote {
    // at high ω the largest exponent dominates; at low ω the smallest
    list.into_iter().fold(Asymptote::Vanishing, |acc, a| match (acc, a) {
        (Asymptote::Vanishing, x) | (x, Asymptote::Vanishing) => x,
        (Asymptote::Power { exponent: e1, .. }, Asymptote::Power { exponent: e2, .. }) => {
            if (high && e2 > e1) || (!high && e2 < e1) {
                a
            } else {
                acc
            }
        }
    })
}

/// Per-input asymptotes of |H_ij|² for output i, combining inputs that share a delay (their columns add
/// coherently and may cancel) when a state-space form is available.
fn column_asymptotes(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize, high: bool) -> Vec<(usize, Asymptote)> {
    let per_input = if high {
        sys.high_frequency()
    } else {
        sys.low_frequency()
    };
    match (exc, sys.state_space()) {
        (Excitation::Track { delays, gains, .. }, Some(ss)) => {
            let mut groups: Vec<f64> = delays.clone();
            groups.sort_by(f64::total_cmp);
            groups.dedup();
            groups
                .iter()
                .filter_map(|&t| {
                    let w: Vec<f64> = delays
                        .iter()
                        .zip(gains)
                        .map(|(d, g)| if *d == t { *g } else { 0.0 })
                        .collect();
                    let j = delays.iter().position(|d| *d == t)?;
                    let c = ss.combine_inputs(&w).ok()?;
                    let a = if high { c.high_frequency() } else { c.low_frequency() };
                    Some((j, a[i][0]))
                })
                .collect()
        }
        (Excitation::Track { gains, .. }, None) => gains
            .iter()
            .enumerate()
            .filter(|(_, g)| **g != 0.0)
            .map(|(j, g)| {
                (
                    j,
                    match per_input[i][j] {
                        Asymptote::Power { exponent, coefficient } => Asymptote::Power {
                            exponent,
                            coefficient: coefficient * g * g,
                        },
                        v => v,
                    },
                )
            })
            .collect(),
        (Excitation::Independent { .. }, _) => (0..sys.n_inputs()).map(|j| (j, per_input[i][j])).collect(),
        // each input's own column scaled by its gain²: the sum decays at least as fast as its slowest term
        (Excitation::Sources { inputs, .. }, _) => inputs
            .iter()
            .enumerate()
            .filter(|(_, m)| m.gain != 0.0)
            .map(|(j, m)| {
                (
                    j,
                    match per_input[i][j] {
                        Asymptote::Power { exponent, coefficient } => Asymptote::Power {
                            exponent,
                            coefficient: coefficient * m.gain * m.gain,
                        },
                        v => v,
                    },
                )
            })
            .collect(),
    }
}

/// Asymptote of S_y(ω) for output `i` as ω → ∞.
pub fn output_high_frequency(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Asymptote {
    let inputs = exc.asymptotes();
    dominant(
        column_asymptotes(sys, exc, i, true)
            .into_iter()
            .map(|(j, h)| combine(h, inputs[j].1)),
        true,
    )
}

/// Asymptote of S_y(ω) for output `i` as ω → 0.
pub fn output_low_frequency(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Asymptote {
    let inputs = exc.asymptotes();
    dominant(
        column_asymptotes(sys, exc, i, false)
            .into_iter()
            .map(|(j, h)| combine(h, inputs[j].0)),
        false,
    )
}

/// Checks that the k-th spectral moment ∫|ω|^k S_y dω of output `i` is finite.
///
/// # Errors
/// [`Error::Divergent`] explaining which end diverges and why.
pub fn check_moment(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize, k: u32) -> Result<()> {
    let name = &sys.outputs()[i].name;
    let what = if k == 0 {
        format!("variance of `{name}`")
    } else {
        format!("spectral moment λ{k} of `{name}`")
    };
    let (lo, hi) = exc.support();
    if hi.is_infinite()
        && let Asymptote::Power { exponent, .. } = output_high_frequency(sys, exc, i)
        && exponent + k as f64 >= -1.0
    {
        return Err(Error::Divergent {
                    quantity: what,
                    reason: format!(
                        "the output density decays only like ω^{exponent} as ω → ∞ (|H|² times the input \
                         density){}, so ∫ω^{k}·S_y dω diverges. This happens e.g. for the \
                         acceleration of a damped base-excited mass under a first-order (type 1) road, whose \
                         density tends to a constant. Ask for a band-limited value (scenario `[analysis] band = [\"0.5 Hz\", \"80 Hz\"]`, or `band_variance`) \
                         or use a smoother input spectrum",
                        if k > 0 {
                            format!(" and ω^{k} multiplies it")
                        } else {
                            String::new()
                        }
                    ),
                });
    }
    if lo == 0.0
        && let Asymptote::Power { exponent, .. } = output_low_frequency(sys, exc, i)
        && exponent + k as f64 <= -1.0
    {
        return Err(Error::Divergent {
            quantity: what,
            reason: format!(
                "the output density grows like ω^{exponent} as ω → 0 (an unbounded road spectrum or a \
                         free rigid-body mode), so the integral diverges at low frequency; give the input a band \
                         or a low-frequency cut-off"
            ),
        });
    }
    Ok(())
}

fn breakpoints(sys: &dyn FrequencyResponse, exc: &Excitation) -> Vec<f64> {
    let mut b = sys.natural_frequencies();
    b.extend(exc.breakpoints());
    b.retain(|w| w.is_finite() && *w > 0.0);
    b
}

/// ∫|ω|^k S_y dω over ω₁ ≤ |ω| ≤ ω₂ (both sides), by adaptive quadrature.
fn moment_integral(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    k: u32,
    w1: f64,
    w2: f64,
    effort: &OscillatoryOptions,
) -> Result<QuadResult> {
    let (lo, hi) = exc.support();
    let (a, b) = (w1.max(lo), w2.min(hi));
    if a >= b {
        return Ok(QuadResult {
            value: 0.0,
            abs_error: 0.0,
            evaluations: 0,
        });
    }
    let opts = QuadOptions {
        rel_tol: effort.rel_tol,
        abs_tol: effort.abs_tol,
        max_subintervals: effort.max_subintervals,
        breakpoints: breakpoints(sys, exc),
    };
    let density = OutputDensity::new(sys, exc, i)?;
    let r = integrate(|w| w.powi(k as i32) * density.density(w), a, b, &opts).map_err(|e| match e {
        Error::Quadrature {
            estimate,
            abs_error,
            evaluations,
            reason,
            ..
        } => Error::Quadrature {
            what: format!("∫ω^{k} S_y dω of `{}`", sys.outputs()[i].name),
            estimate: 2.0 * estimate,
            abs_error: 2.0 * abs_error,
            evaluations,
            reason,
        },
        e => e,
    })?;
    Ok(QuadResult {
        value: 2.0 * r.value,
        abs_error: 2.0 * r.abs_error,
        evaluations: r.evaluations,
    })
}

/// Variance of output `i` by adaptive quadrature of S_y (any spectrum, delays, tabulated data).
///
/// # Errors
/// [`Error::Divergent`] (checked from the asymptotes before integrating), [`Error::Quadrature`].
pub fn variance_quadrature(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<QuadResult> {
    spectral_moment_quadrature(sys, exc, i, 0)
}

/// Spectral moment λ_k = ∫|ω|^k S_y dω of output `i` by quadrature.
///
/// # Errors
/// As [`variance_quadrature`].
pub fn spectral_moment_quadrature(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    k: u32,
) -> Result<QuadResult> {
    spectral_moment_quadrature_with(sys, exc, i, k, &OscillatoryOptions::default())
}

/// [`spectral_moment_quadrature`] with the tolerance and the subinterval limit of `effort`.
///
/// # Errors
/// As [`variance_quadrature`]; [`Error::Quadrature`] names the options that raise the effort.
pub fn spectral_moment_quadrature_with(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    k: u32,
    effort: &OscillatoryOptions,
) -> Result<QuadResult> {
    check_io(sys, exc, i)?;
    check_moment(sys, exc, i, k)?;
    moment_integral(sys, exc, i, k, 0.0, f64::INFINITY, effort)
}

/// Band-limited variance 2∫_{ω₁}^{ω₂} S_y dω of output `i` (rad/s), finite whenever the band is finite.
///
/// # Errors
/// [`Error::InvalidParameter`] unless 0 ≤ ω₁ < ω₂ < ∞.
pub fn band_variance(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize, w1: f64, w2: f64) -> Result<QuadResult> {
    band_variance_with(sys, exc, i, (w1, w2), &OscillatoryOptions::default())
}

/// [`band_variance`] with the tolerances of `opts`: e.g. an absolute tolerance that is a fraction of the
/// whole-axis variance, for one band of many whose sum is what matters (a band holding a negligible share
/// of the variance then does not need `opts.rel_tol` of its own tiny value).
///
/// # Errors
/// As [`band_variance`].
pub fn band_variance_with(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    (w1, w2): (f64, f64),
    opts: &OscillatoryOptions,
) -> Result<QuadResult> {
    check_io(sys, exc, i)?;
    if !(w1 >= 0.0 && w2 > w1 && w2.is_finite()) {
        return Err(Error::invalid(
            "band",
            format!("[{w1}, {w2}] rad/s"),
            "need 0 <= w1 < w2 < inf",
        ));
    }
    if w1 == 0.0
        && let Asymptote::Power { exponent, .. } = output_low_frequency(sys, exc, i)
        && exponent <= -1.0
        && exc.support().0 == 0.0
    {
        return Err(Error::Divergent {
            quantity: format!("band variance of `{}`", sys.outputs()[i].name),
            reason: "the band starts at ω = 0 where the output density is not integrable".into(),
        });
    }
    moment_integral(sys, exc, i, 0, w1, w2, opts)
}

/// Checks that `exc` drives every input of `sys`, that output `i` exists and that the system is stable.
fn check_io(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<()> {
    check_shapes(sys, exc, i)?;
    // |H(iω)|² of an unstable system is finite, but no stationary response exists: never integrate it
    if let Some(ss) = sys.state_space() {
        ss.require_stable()?;
    }
    Ok(())
}

/// Checks that `exc` drives every input of `sys` and that output `i` exists.
pub(crate) fn check_shapes(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<()> {
    if exc.n_inputs() != sys.n_inputs() {
        return Err(Error::invalid(
            "excitation",
            format!("{} inputs", exc.n_inputs()),
            format!("the system has {} inputs", sys.n_inputs()),
        ));
    }
    if i >= sys.outputs().len() {
        return Err(Error::invalid(
            "output",
            i,
            format!("the system has {} outputs", sys.outputs().len()),
        ));
    }
    Ok(())
}

/// Largest relative error the integral table may carry before its value is reported as unreliable
/// (estimated from the pivots of its Hurwitz elimination).
pub const INTEGRAL_TABLE_MAX_ERROR: f64 = 1e-9;

/// Exact variance and higher moments from the Lyapunov equation of the system augmented with the input
/// shaping filters.
#[derive(Debug)]
pub struct LyapunovMoments {
    /// λ₀ = D_y.
    pub variance: f64,
    /// λ₂ = Var(ẏ), or why it is infinite.
    pub lambda2: Result<f64>,
    /// λ₄ = Var(ÿ), or why it is infinite.
    pub lambda4: Result<f64>,
}

impl LyapunovMoments {
    /// Refuses values no covariance can have: a negative or non-finite variance (or moment) means the solve
    /// lost its accuracy (time scales too far apart for double precision), and is reported as
    /// [`Error::Inaccurate`] instead of a number (a moment alone becomes that error, the variance stays).
    pub(crate) fn checked(self, method: &str) -> Result<Self> {
        let bad = |what: &str, v: f64| Error::Inaccurate {
            method: method.to_string(),
            value: v,
            reason: format!(
                "the solve gave a {} {what} ({v:e}): it lost its accuracy on this system (time scales or masses \
                 too far apart for double precision; check the units)",
                if v.is_finite() { "negative" } else { "non-finite" }
            ),
        };
        let ok = |v: f64| v.is_finite() && v >= 0.0;
        if !ok(self.variance) {
            return Err(bad("variance", self.variance));
        }
        let moment = |r: Result<f64>, what: &str| match r {
            Ok(v) if !ok(v) => Err(bad(what, v)),
            other => other,
        };
        Ok(LyapunovMoments {
            variance: self.variance,
            lambda2: moment(self.lambda2, "λ₂"),
            lambda4: moment(self.lambda4, "λ₄"),
        })
    }
}

/// Shaping filters (state space with unit-intensity white noise) of every input process.
fn filters(exc: &Excitation) -> Result<Vec<ShapingFilter>> {
    exc.spectra()
        .iter()
        .map(|s| {
            let r = s.rational().ok_or_else(|| Error::NotApplicable {
                method: "exact (Lyapunov / integral-table) variance".into(),
                reason: format!(
                    "the input spectrum ({}) is not rational (no finite shaping filter); quadrature applies",
                    s.describe()
                ),
            })?;
            r.shaping_filter()
        })
        .collect()
}

/// The augmented system z = [filter states; system states] driven by unit-intensity white noise w, with
/// output row h and white-noise feedthrough f: y = h z + f w.
///
/// # Formula
/// ```text
/// ż = A z + G w,   y_i = h z + f w,   E[w(t) w(s)ᵀ] = I δ(t − s)
/// ```
#[derive(Debug, Clone)]
pub struct AugmentedSystem {
    /// State matrix of z = [filter states; system states].
    pub a: DMatrix<f64>,
    /// Noise input matrix (one column per independent input process).
    pub g: DMatrix<f64>,
    /// Output row (1 × states) of the selected output.
    pub h: DMatrix<f64>,
    /// White-noise feedthrough (1 × processes); non-zero means the output has infinite variance.
    pub f: DMatrix<f64>,
}

/// The system augmented with the shaping filters of its (rational, delay-free) inputs, for output `i`: the
/// white-noise-driven state-space form used by [`variance_lyapunov`] and by exact time-domain simulation.
///
/// # Errors
/// [`Error::NotApplicable`] for delayed inputs or non-rational input spectra; [`Error::Divergent`] for
/// an input with a white-noise component that cannot be shaped; dimension errors from the system.
pub fn augmented_system(ss: &StateSpace, exc: &Excitation, i: usize) -> Result<AugmentedSystem> {
    augmented_rows(ss, exc, &[i])
}

/// As [`augmented_system`] for several outputs at once: `h` and `f` have one row per entry of `rows` (A and
/// G do not depend on the outputs).
pub(crate) fn augmented_rows(ss: &StateSpace, exc: &Excitation, rows: &[usize]) -> Result<AugmentedSystem> {
    if !exc.delay_free() {
        return Err(Error::NotApplicable {
            method: "exact (Lyapunov / integral-table) variance".into(),
            reason: format!(
                "{}: pure delays have no finite state-space form; use quadrature",
                exc.inputs_described()
            ),
        });
    }
    if let Excitation::Sources { sources, .. } = exc
        && let Some(m) = sources.iter().find_map(|s| match s {
            super::Source::Matrix(m) => Some(m),
            super::Source::Process(_) => None,
        })
    {
        return Err(Error::NotApplicable {
            method: "exact (Lyapunov / integral-table) variance".into(),
            reason: format!(
                "{} is a multi-component process whose cross-spectral matrix has no rational factorisation; \
                     quadrature only",
                m.describe()
            ),
        });
    }
    let fl = filters(exc)?;
    // Reduce the system to one input per independent process.
    let (sys, nproc) = match exc {
        Excitation::Track { gains, .. } => (ss.combine_inputs(gains)?, 1),
        Excitation::Independent { spectra, .. } => (ss.clone(), spectra.len()),
        Excitation::Sources { sources, inputs } => (combine_per_source(ss, sources.len(), inputs)?, sources.len()),
    };
    let sys = sys.select_outputs(rows)?;
    let k = rows.len();
    // Block-diagonal filter bank: ẋ_F = A_F x_F + B_F w, u = C_F x_F (strictly proper filters)
    let parts: Vec<StateSpace> = fl
        .iter()
        .map(|f| {
            TransferFunction::new(f.num.clone(), f.den.clone(), crate::system::OutputInfo::new("u", "-"))
                .map(|t| t.state_space().cloned().expect("transfer functions have a state space"))
        })
        .collect::<Result<_>>()?;
    let nf: usize = parts.iter().map(|p| p.n_states()).sum();
    let n = sys.n_states();
    // Filter bank: ẋ_F = A_F x_F + B_F w, u = C_F x_F + D_F w (block diagonal, one block per process)
    let mut af = DMatrix::zeros(nf, nf);
    let mut bf = DMatrix::zeros(nf, nproc);
    let mut cf = DMatrix::zeros(nproc, nf);
    let mut df = DMatrix::zeros(nproc, nproc);
    let mut off = 0;
    for (k, p) in parts.iter().enumerate() {
        let q = p.n_states();
        af.view_mut((off, off), (q, q)).copy_from(&p.a);
        bf.view_mut((off, k), (q, 1)).copy_from(&p.b);
        cf.view_mut((k, off), (1, q)).copy_from(&p.c);
        df[(k, k)] = p.d[(0, 0)];
        off += q;
    }
    // z = [x_F; x]:  ż = [[A_F, 0], [B C_F, A]] z + [[B_F], [B D_F]] w
    // y = (D C_F + E C_F A_F) x_F + C x + (D D_F + E C_F B_F) w + E D_F ẇ
    let mut a = DMatrix::zeros(nf + n, nf + n);
    a.view_mut((0, 0), (nf, nf)).copy_from(&af);
    a.view_mut((nf, 0), (n, nf)).copy_from(&(&sys.b * &cf));
    a.view_mut((nf, nf), (n, n)).copy_from(&sys.a);
    let mut g = DMatrix::zeros(nf + n, nproc);
    g.view_mut((0, 0), (nf, nproc)).copy_from(&bf);
    g.view_mut((nf, 0), (n, nproc)).copy_from(&(&sys.b * &df));
    let mut h = DMatrix::zeros(k, nf + n);
    h.view_mut((0, 0), (k, nf))
        .copy_from(&(&sys.d * &cf + &sys.e * &cf * &af));
    h.view_mut((0, nf), (k, n)).copy_from(&sys.c);
    // white-noise feedthrough: exactly zero unless the system passes u (or u̇) and the filter has relative
    // degree zero (or one)
    let f = &sys.d * &df + &sys.e * &cf * &bf + (&sys.e * &df).abs();
    Ok(AugmentedSystem { a, g, h, f })
}

/// The system with one input per source: column s of B (D, E) is Σ_{j: s_j = s} g_j times column j.
fn combine_per_source(ss: &StateSpace, n_sources: usize, inputs: &[super::InputMap]) -> Result<StateSpace> {
    let w = DMatrix::from_fn(inputs.len(), n_sources, |j, s| {
        if inputs[j].source == s {
            inputs[j].gain
        } else {
            0.0
        }
    });
    StateSpace::new(
        ss.a.clone(),
        &ss.b * &w,
        ss.c.clone(),
        Some(&ss.d * &w),
        Some(&ss.e * &w),
        ss.outputs().to_vec(),
    )
}

/// Exact variance (and λ₂, λ₄) of output `i` by the Lyapunov equation of the system augmented with the
/// shaping filters of the (rational, delay-free) inputs.
///
/// # Formula
/// ```text
/// ż = F z + G w,  y = h z + f w,   F P + P Fᵀ + G Gᵀ = 0,   D_y = h P hᵀ   (f = 0; else D_y = ∞)
/// λ₂ = Var(ẏ) = (hF) P (hF)ᵀ if hG = 0;    λ₄ = (hF²) P (hF²)ᵀ if hFG = 0 as well
/// ```
///
/// # Errors
/// [`Error::Numerical`] when the method does not apply (non-rational input, delays, no state space),
/// [`Error::InvalidParameter`] for an unstable system, [`Error::Divergent`] for a white-noise component.
pub fn variance_lyapunov(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<LyapunovMoments> {
    let mut all = lyapunov_outputs(sys, exc, &[i], 4)?;
    all.pop()
        .unwrap_or_else(|| Err(white_divergence(&sys.outputs()[i].name, 0)))
}

/// [`variance_lyapunov`] of several outputs from one augmented system and one Lyapunov solve, the spectral
/// moments up to λ_`upto` (0, 2 or 4; a moment above it is [`Error::NotApplicable`]). Each entry is that
/// output's result ([`Error::Divergent`] for a white-noise component); the outer error is the system's
/// (unstable, not applicable, a failed solve).
///
/// # Errors
/// As [`variance_lyapunov`].
pub(crate) fn lyapunov_outputs(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    outputs: &[usize],
    upto: u32,
) -> Result<Vec<Result<LyapunovMoments>>> {
    for &i in outputs {
        check_shapes(sys, exc, i)?;
    }
    let ss = sys.state_space().ok_or_else(|| Error::NotApplicable {
        method: "Lyapunov variance".into(),
        reason: "the system has no finite state-space form".into(),
    })?;
    // |H(iω)|² of an unstable system is finite, but no stationary response exists (A's eigenvalues once)
    ss.require_stable()?;
    let aug = augmented_rows(ss, exc, outputs)?;
    let names: Vec<&str> = outputs.iter().map(|&i| sys.outputs()[i].name.as_str()).collect();
    moments_of(&aug, &names, upto)
}

/// The moments of every output row of `aug` (named `names`) from one solve of F P + P Fᵀ + G Gᵀ = 0 (see
/// [`variance_lyapunov`]'s formula), up to λ_`upto`.
pub(crate) fn moments_of(aug: &AugmentedSystem, names: &[&str], upto: u32) -> Result<Vec<Result<LyapunovMoments>>> {
    let tiny = |m: &DMatrix<f64>, scale: f64| m.amax() <= 1e-12 * scale.max(1e-300);
    let not_asked = |k: u32| Error::NotApplicable {
        method: format!("spectral moment λ{k}"),
        reason: "not requested".into(),
    };
    if (0..names.len()).all(|r| aug.f.row(r).amax() > 0.0) {
        // every output has a white-noise component: no solve needed to say so
        return Ok(names.iter().map(|name| Err(white_divergence(name, 0))).collect());
    }
    let p = solve_continuous_lyapunov(&aug.a, &(&aug.g * aug.g.transpose()))?;
    let quad = |row: &DMatrix<f64>| (row * &p * row.transpose())[(0, 0)];
    let one = |r: usize, name: &str| -> Result<LyapunovMoments> {
        let h = aug.h.rows(r, 1).into_owned();
        if aug.f.row(r).amax() > 0.0 {
            return Err(white_divergence(name, 0));
        }
        let ha = &h * &aug.a;
        let lambda2 = if upto < 2 {
            Err(not_asked(2))
        } else if tiny(&(&h * &aug.g), h.norm() * aug.g.norm()) {
            Ok(quad(&ha))
        } else {
            Err(white_divergence(name, 2))
        };
        let lambda4 = match &lambda2 {
            _ if upto < 4 => Err(not_asked(4)),
            Ok(_) if tiny(&(&ha * &aug.g), ha.norm() * aug.g.norm()) => Ok(quad(&(&ha * &aug.a))),
            _ => Err(white_divergence(name, 4)),
        };
        LyapunovMoments {
            variance: quad(&h),
            lambda2,
            lambda4,
        }
        .checked("Lyapunov variance")
    };
    Ok(names.iter().enumerate().map(|(r, name)| one(r, name)).collect())
}

fn white_divergence(name: &str, k: u32) -> Error {
    Error::Divergent {
        quantity: if k == 0 {
            format!("variance of `{name}`")
        } else {
            format!("spectral moment λ{k} of `{name}`")
        },
        reason: format!(
            "{} contains a white-noise component (the augmented system feeds the driving noise \
             straight through), so its density does not decay; ask for a band-limited value",
            match k {
                0 => "the output",
                2 => "the derivative of the output",
                _ => "the second derivative of the output",
            }
        ),
    }
}

/// Variance (k = 0) or spectral moment λ_k (k = 2, 4) of output `i` by the closed-form integral table
/// I_n applied to the rational integrand |s^{k/2} H(s) F(s)|²/(2π) of a single delay-free rational input.
///
/// # Formula
/// H(s) = N(s)/Δ(s) with Δ = det(sI − A), N = det(sI − A + b c) − Δ + (d + e s) Δ for the SISO path;
/// D_y = (1/2π) ∫ |N B_F / (Δ A_F)|² dω evaluated by the table (Gradshteyn–Ryzhik 3.112).
///
/// # Errors
/// [`Error::Numerical`] when not applicable (not SISO after combining, order > 7, non-rational input);
/// [`Error::Divergent`] when the integrand does not decay.
pub fn variance_integral_table(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize, k: u32) -> Result<f64> {
    check_io(sys, exc, i)?;
    let not_applicable = |reason: String| Error::NotApplicable {
        method: "integral-table variance".into(),
        reason,
    };
    if matches!(exc, Excitation::Sources { .. }) {
        return Err(not_applicable(
            "several sources or inputs mapped to sources: the table handles one rational input".into(),
        ));
    }
    if !matches!(exc, Excitation::Track { .. }) {
        return Err(not_applicable(
            "several independent inputs: the table handles one rational input".into(),
        ));
    }
    if !exc.delay_free() {
        return Err(not_applicable(
            "pure delays make the integrand non-rational; use quadrature".into(),
        ));
    }
    let ss = sys
        .state_space()
        .ok_or_else(|| not_applicable("the system has no finite state-space form".into()))?;
    // stability was checked by check_io (A's eigenvalues once per call)
    let aug = augmented_system(ss, exc, i)?;
    let name = &sys.outputs()[i].name;
    if aug.f.amax() > 0.0 {
        return Err(white_divergence(name, 0));
    }
    let n = aug.a.nrows();
    if n > 7 {
        return Err(not_applicable(format!("order {n} exceeds the table's n ≤ 7")));
    }
    if aug.g.ncols() != 1 {
        return Err(not_applicable("one input process is needed".into()));
    }
    let (num, den, ws) = scaled_transfer_polynomials(&aug.a, &aug.g, &aug.h, 0.0)?;
    let mut num = num;
    for _ in 0..k / 2 {
        num.insert(0, 0.0);
    }
    let num = poly::trim(&num);
    if num.is_empty() {
        return Ok(0.0);
    }
    let (v, ratio) = h2_integral_conditioned(&num, &den).map_err(|e| match e {
        Error::Divergent { .. } => white_divergence(name, k),
        e => e,
    })?;
    let value = v * ws.powi(k as i32 + 1) / (2.0 * PI);
    let err = ratio * n as f64 * f64::EPSILON;
    if err > INTEGRAL_TABLE_MAX_ERROR {
        return Err(Error::Inaccurate {
            method: "integral-table variance".into(),
            value,
            reason: format!(
                "its Hurwitz elimination is ill-conditioned here (pivot ratio {ratio:.1e}, relative error up to \
                 ~{err:.0e}); trust the Lyapunov or quadrature value"
            ),
        });
    }
    Ok(value)
}
