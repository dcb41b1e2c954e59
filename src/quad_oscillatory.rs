//! Integrals of oscillatory integrands over long or infinite ranges: adaptive quadrature over
//! half-periods of the oscillation, with Wynn's ε-algorithm on the partial sums of an infinite range.
//!
//! # Rule
//! An integrand f(x) = A(x) cos(Δx) + B(x) sin(Δx) with slowly varying amplitudes A, B changes sign about
//! every half-period h = π/Δ. Over an infinite range the mapped tails of [`crate::quad::integrate`] see
//! infinitely many oscillations of non-vanishing amplitude in the mapped variable (the map x = c + L t/(1−t)
//! compresses them towards t = 1 while its Jacobian keeps their amplitude) and stall. Here the range
//! [a, ∞) is cut into half-periods [a + nh, a + (n+1)h], each integrated by [`crate::quad::integrate`]
//! (smooth, at most one sign change: a handful of Gauss–Kronrod rules), and the partial sums Sₙ form an
//! asymptotically alternating sequence whose limit Wynn's ε-algorithm extrapolates — the method of
//! QUADPACK's `QAWF` (Piessens, de Doncker-Kapenga, Überhuber, Kahaner, *QUADPACK*, Springer 1983,
//! §3.3, routine `DQAWFE` with the extrapolation routine `DQELG`).
//!
//! The correlation quadrature [`crate::spectrum::numeric::correlation`] applies the same method to the
//! special case f = S(ω) cos ωτ with its own copy of the ε-algorithm; this module is the general form
//! (any integrand, finite or infinite range, options, a combined error estimate).

use crate::error::{Error, Result};
use crate::quad::{integrate, QuadOptions, QuadResult};

/// Effort and tolerances of [`integrate_oscillatory`] (and of the delayed-input moments built on it,
/// [`crate::response::spectral_moment_oscillatory`]).
///
/// # Formula
/// The result is accepted when its error estimate is at most `max(abs_tol, rel_tol·|value|)`.
///
/// # Errors
/// Checked by the functions that take it: `rel_tol`, `abs_tol` must be finite and ≥ 0 (not both 0 for
/// the response moments), `max_subintervals` and `max_half_periods` ≥ 1.
///
/// # Examples
/// ```
/// use stochvib::quad_oscillatory::OscillatoryOptions;
/// let more = OscillatoryOptions { max_subintervals: 20_000, ..OscillatoryOptions::default() };
/// assert_eq!(more.rel_tol, 1e-10);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct OscillatoryOptions {
    /// Relative tolerance on the value (default 1e-10, the crate's quadrature tolerance).
    pub rel_tol: f64,
    /// Absolute tolerance on the value (default 0).
    pub abs_tol: f64,
    /// Subintervals each adaptive integral may use beyond its initial partition at the breakpoints
    /// (default 2000, as [`QuadOptions`]). Raise it when a head integral does not converge.
    pub max_subintervals: usize,
    /// Half-periods resolved one by one (default 10 000): the pieces of an oscillatory integral (on a
    /// finite range the last piece takes the rest; on an infinite range the extrapolation gives up after
    /// this many), and for the delayed-input moments also the breakpoints of the head. Raise it when an
    /// oscillatory tail does not settle or the oscillations are very dense (long lags).
    pub max_half_periods: usize,
}

impl Default for OscillatoryOptions {
    fn default() -> Self {
        OscillatoryOptions {
            rel_tol: 1e-10,
            abs_tol: 0.0,
            max_subintervals: 2000,
            max_half_periods: 10_000,
        }
    }
}

impl OscillatoryOptions {
    /// Checks the fields.
    ///
    /// # Formula
    /// rel_tol, abs_tol finite and ≥ 0; max_subintervals, max_half_periods ≥ 1.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the offending field.
    ///
    /// # Examples
    /// ```
    /// use stochvib::quad_oscillatory::OscillatoryOptions;
    /// assert!(OscillatoryOptions::default().validate().is_ok());
    /// assert!(OscillatoryOptions { max_half_periods: 0, ..OscillatoryOptions::default() }.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        if !(self.rel_tol.is_finite() && self.rel_tol >= 0.0) {
            return Err(Error::invalid("rel_tol", self.rel_tol, "must be finite and >= 0"));
        }
        if !(self.abs_tol.is_finite() && self.abs_tol >= 0.0) {
            return Err(Error::invalid("abs_tol", self.abs_tol, "must be finite and >= 0"));
        }
        if self.max_subintervals == 0 {
            return Err(Error::invalid("max_subintervals", 0, "must be >= 1"));
        }
        if self.max_half_periods == 0 {
            return Err(Error::invalid("max_half_periods", 0, "must be >= 1"));
        }
        Ok(())
    }
}

/// Number of partial sums the ε-table is built from (QUADPACK's `limexp` is 50).
const WYNN_DEPTH: usize = 50;

/// The extrapolated sequence starts where the half-period is at most this fraction of x (and a
/// slowly varying amplitude changes little over one): there the terms are smooth in n. Before that
/// point the half-periods are summed plainly.
const REGULAR_START: f64 = 8.0;

/// Extrapolated estimates that must agree before a tail is accepted.
const AGREEING_ESTIMATES: usize = 4;

/// Wynn's ε-algorithm on a sequence of partial sums: the extrapolated limit.
///
/// # Formula
/// With ε₋₁⁽ⁿ⁾ = 0 and ε₀⁽ⁿ⁾ = Sₙ (the last ≤ 50 sums),
/// ```text
/// ε_{k+1}⁽ⁿ⁾ = ε_{k−1}⁽ⁿ⁺¹⁾ + 1 / (ε_k⁽ⁿ⁺¹⁾ − ε_k⁽ⁿ⁾)
/// ```
/// (Wynn, "On a device for computing the e_m(S_n) transformation", MTAC 10, 1956, eq. (2)); the even
/// columns ε_{2m} are Shanks' transforms e_m(Sₙ), exact for a sum of m geometric sequences and highly
/// effective for alternating series with algebraically decaying terms. The estimate is the last entry of
/// the deepest even column; the table stops early at a column whose consecutive entries agree to rounding
/// (the sequence has converged there, or the next column would divide by zero).
///
/// # Errors
/// None; an empty slice gives 0.
///
/// # Examples
/// ```
/// use stochvib::quad_oscillatory::wynn_epsilon;
/// // partial sums of 1 − 1/2 + 1/3 − … → ln 2
/// let mut s = 0.0;
/// let sums: Vec<f64> = (1..=16).map(|k| { s += (-1f64).powi(k + 1) / k as f64; s }).collect();
/// assert!((sums[15] - 2f64.ln()).abs() > 1e-2);
/// assert!((wynn_epsilon(&sums) - 2f64.ln()).abs() < 1e-12);
/// ```
pub fn wynn_epsilon(sums: &[f64]) -> f64 {
    let start = sums.len().saturating_sub(WYNN_DEPTH);
    let sums = &sums[start..];
    let Some(&last) = sums.last() else {
        return 0.0;
    };
    let mut prev = vec![0.0; sums.len() + 1]; // ε₋₁
    let mut cur = sums.to_vec(); // ε₀
    let mut best = last;
    let mut k = 0usize;
    while cur.len() >= 2 {
        let mut next = Vec::with_capacity(cur.len() - 1);
        for i in 0..cur.len() - 1 {
            let d = cur[i + 1] - cur[i];
            if d.abs() <= 4.0 * f64::EPSILON * cur[i].abs().max(cur[i + 1].abs()) {
                // converged in this column (even k: its last entry is the limit) or about to divide by 0
                if k.is_multiple_of(2) {
                    best = *cur.last().unwrap_or(&best);
                }
                return best;
            }
            next.push(prev[i + 1] + 1.0 / d);
        }
        k += 1;
        if next.iter().any(|v| !v.is_finite()) {
            return best;
        }
        if k.is_multiple_of(2) {
            best = *next.last().unwrap_or(&best);
        }
        prev = cur;
        cur = next;
    }
    best
}

/// ∫_a^b f(x) dx for an integrand that changes sign about every `half_period` (b may be +∞).
///
/// # Formula
/// With h = `half_period`, xₙ = a + n h and Tₙ = ∫_{xₙ}^{min(xₙ₊₁, b)} f dx (adaptive Gauss–Kronrod,
/// [`crate::quad::integrate`]; a half-period much longer than its start point is split geometrically
/// at xₙ·4^j so that an integrand concentrated near xₙ is resolved):
/// * b finite: the value is Σₙ Tₙ, the error estimate the sum of the pieces' estimates (no
///   extrapolation); beyond `max_half_periods` pieces the last piece takes the rest of the range.
/// * b = ∞: Sₙ = T₀ + … + Tₙ; the half-periods ending before x = 8h are only summed (there a slowly
///   varying amplitude may still change a lot over one half-period and the terms are irregular); from
///   there on Eₙ = [`wynn_epsilon`](S_{n₀}, …, Sₙ) and, in the manner of QUADPACK `DQAWFE`,
///   ```text
///   errₙ = |Eₙ − Eₙ₋₁| + |Eₙ − Eₙ₋₂| + |Eₙ − Eₙ₋₃| + Σ_{m≤n} err(Tₘ) + 5ε|Eₙ|
///   ```
///   (four agreeing estimates: three can agree by accident on a short table); the plain sum Sₙ with error
///   |Tₙ| + |Tₙ₋₁| + |Tₙ₋₂| + Σ err(Tₘ) is taken instead when that is smaller (terms that have died out).
///   The first n with at least four estimates and errₙ ≤ max(abs_tol, rel_tol·|Eₙ|) is returned.
///
/// Each piece is integrated with `rel_tol/10` and `abs_tol/100`, so that the sum of the pieces' errors
/// stays within the budget.
///
/// # Errors
/// * [`Error::InvalidParameter`] for NaN or infinite `a`, `b < a`, a `half_period` that is not finite and
///   > 0, or invalid options.
/// * [`Error::Quadrature`] when a piece does not converge in `max_subintervals` (reason says so) or
///   when `max_half_periods` pieces of an infinite range do not reach the tolerance (reason says so);
///   `estimate` and `abs_error` are the best reached.
///
/// # Examples
/// ```
/// use stochvib::quad_oscillatory::{integrate_oscillatory, OscillatoryOptions};
/// // ∫_0^∞ sin(x)/x dx = π/2 (only conditionally convergent)
/// let o = OscillatoryOptions { rel_tol: 1e-12, ..OscillatoryOptions::default() };
/// let sinc = |x: f64| if x == 0.0 { 1.0 } else { x.sin() / x };
/// let r = integrate_oscillatory(sinc, 0.0, f64::INFINITY, std::f64::consts::PI, &o)?;
/// assert!((r.value - std::f64::consts::FRAC_PI_2).abs() < 1e-11);
/// # Ok::<(), stochvib::Error>(())
/// ```
pub fn integrate_oscillatory(
    f: impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    half_period: f64,
    opts: &OscillatoryOptions,
) -> Result<QuadResult> {
    opts.validate()?;
    if !a.is_finite() {
        return Err(Error::invalid("a", a, "lower limit must be finite"));
    }
    if b.is_nan() || b < a {
        return Err(Error::invalid("b", b, format!("upper limit must be >= a = {a}")));
    }
    if !(half_period.is_finite() && half_period > 0.0) {
        return Err(Error::invalid("half_period", half_period, "must be finite and > 0"));
    }
    let tolerance = |v: f64| opts.abs_tol.max(opts.rel_tol * v.abs());
    let piece_opts = QuadOptions {
        rel_tol: opts.rel_tol / 10.0,
        abs_tol: opts.abs_tol / 100.0,
        max_subintervals: opts.max_subintervals,
        breakpoints: Vec::new(),
    };
    let (mut sum, mut comp) = (0.0f64, 0.0f64); // Neumaier-compensated partial sum
    let mut piece_err = 0.0;
    let mut evaluations = 0usize;
    let mut sums: Vec<f64> = Vec::new();
    let mut estimates: Vec<f64> = Vec::new();
    let mut last_terms = [f64::INFINITY; 3];
    let mut best = (f64::NAN, f64::INFINITY);
    for n in 0..opts.max_half_periods {
        let x0 = a + n as f64 * half_period;
        // on a finite range the last allowed piece takes the rest of it
        let x1 = if n + 1 == opts.max_half_periods && b.is_finite() {
            b
        } else {
            (a + (n + 1) as f64 * half_period).min(b)
        };
        let o = piece_options(&piece_opts, x0, x1);
        let r = integrate(&f, x0, x1, &o).map_err(|e| {
            let so_far = QuadResult {
                value: sum + comp,
                abs_error: piece_err,
                evaluations,
            };
            piece_failure(e, (n, x0, x1), &so_far, opts)
        })?;
        evaluations += r.evaluations;
        piece_err += r.abs_error;
        let t = sum + r.value;
        comp += if sum.abs() >= r.value.abs() {
            (sum - t) + r.value
        } else {
            (r.value - t) + sum
        };
        sum = t;
        last_terms = [last_terms[1], last_terms[2], r.value.abs()];
        if x1 >= b {
            return Ok(QuadResult {
                value: sum + comp,
                abs_error: piece_err,
                evaluations,
            });
        }
        if b.is_finite() {
            continue;
        }
        let s = sum + comp;
        if x1 >= REGULAR_START * half_period {
            sums.push(s);
            estimates.push(wynn_epsilon(&sums));
        }
        let m = estimates.len();
        let cand = candidate(s, &last_terms, &estimates, piece_err);
        if best.0.is_nan() || cand.1 < best.1 {
            best = cand;
        }
        if m >= AGREEING_ESTIMATES && cand.1 <= tolerance(cand.0) {
            return Ok(QuadResult {
                value: cand.0,
                abs_error: cand.1,
                evaluations,
            });
        }
    }
    Err(Error::Quadrature {
        what: "oscillatory integral".into(),
        estimate: best.0,
        abs_error: best.1,
        evaluations,
        reason: format!(
            "the extrapolated tail did not reach the tolerance in max_half_periods = {} half-periods of length \
             {half_period:e} (raise max_half_periods, or loosen the tolerance)",
            opts.max_half_periods
        ),
    })
}

/// The options of the piece [x0, x1]: `base` with breakpoints at 4x0, 16x0, … when the piece reaches far
/// beyond x0 > 0 (the last piece of a finite range), and as many more subintervals allowed.
fn piece_options(base: &QuadOptions, x0: f64, x1: f64) -> QuadOptions {
    let mut o = base.clone();
    if x0 > 0.0 && x1 > 8.0 * x0 {
        let mut p = 4.0 * x0;
        while p < x1 {
            o.breakpoints.push(p);
            p *= 4.0;
        }
        o.max_subintervals += o.breakpoints.len();
    }
    o
}

/// The error of the oscillatory integral when the quadrature of half-period `n` = [x0, x1] failed with `e`:
/// its estimate and error added to the sum `so_far` of the pieces before, the piece named.
fn piece_failure(e: Error, (n, x0, x1): (usize, f64, f64), so_far: &QuadResult, opts: &OscillatoryOptions) -> Error {
    match e {
        Error::Quadrature {
            estimate,
            abs_error,
            evaluations,
            reason,
            ..
        } => Error::Quadrature {
            what: "oscillatory integral".into(),
            estimate: so_far.value + estimate,
            abs_error: so_far.abs_error + abs_error,
            evaluations: so_far.evaluations + evaluations,
            reason: format!(
                "half-period {n} [{x0:e}, {x1:e}]: {reason} (raise max_subintervals, now {}, or \
                 max_half_periods, now {}, if this piece holds many oscillations)",
                opts.max_subintervals, opts.max_half_periods
            ),
        },
        e => e,
    }
}

/// The best estimate of the infinite sum after the partial sum `s` and its error: the plain partial sum, with
/// the last three terms as its error (terms that have died out), or the last of the Wynn `estimates` once
/// [`AGREEING_ESTIMATES`] exist, its error the spread of the last four (plus rounding), where smaller;
/// `piece_err` (the pieces' quadrature errors) is added to either.
fn candidate(s: f64, last_terms: &[f64; 3], estimates: &[f64], piece_err: f64) -> (f64, f64) {
    let plain = (s, last_terms.iter().sum::<f64>() + piece_err);
    let m = estimates.len();
    if m < AGREEING_ESTIMATES {
        return plain;
    }
    let e = estimates[m - 1];
    let ext_err = (e - estimates[m - 2]).abs()
        + (e - estimates[m - 3]).abs()
        + (e - estimates[m - 4]).abs()
        + 5.0 * f64::EPSILON * e.abs();
    if ext_err + piece_err < plain.1 {
        (e, ext_err + piece_err)
    } else {
        plain
    }
}
