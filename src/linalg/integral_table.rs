//! The integral table Iₙ = ∫_{−∞}^{∞} |Hₙ(ω)|² dω for rational Hₙ (James, Nichols & Phillips 1947;
//! Newland, *An Introduction to Random Vibrations*, Appendix 1; Crandall & Mark; Gradshteyn & Ryzhik
//! 3.112).
//!
//! # Convention
//! With real coefficients A₀…Aₙ (Aₙ ≠ 0) and B₀…B_{n−1} (missing ones are zero),
//!
//! ```text
//!          B₀ + s B₁ + s² B₂ + … + s^{n−1} B_{n−1}
//! Hₙ  =  ─────────────────────────────────────────,      Iₙ = ∫_{−∞}^{∞} |Hₙ|² dω,
//!          A₀ + s A₁ + s² A₂ + … + sⁿ Aₙ
//! ```
//!
//! evaluated on the imaginary axis, **either** at s = iω (Newland; time factor e^{iωt}, so the
//! transfer function of Σ Aₖ x⁽ᵏ⁾ = Σ Bₖ f⁽ᵏ⁾ is exactly B(iω)/A(iω)) **or** at s = −iω (James,
//! Nichols & Phillips, Crandall; time factor e^{−iωt}). Because the coefficients are real,
//! |B(−iω)/A(−iω)| = |B(iω)/A(iω)|: the integral is the same in both conventions, and so are the
//! formulas. What the formulas require is that the polynomial A(s) = Σ Aₖ sᵏ be **Hurwitz** (all roots
//! in Re s < 0) — the stability of the system with Laplace transfer function B(s)/A(s). For Aₙ > 0
//! this implies Aₖ > 0 for all k (an all-negative A is also accepted: |H|² does not change under
//! A → −A). Example: m ẍ + c ẋ + k x = f has A = (k, c, m), B = (1), I₂ = π/(kc), so a white force of
//! two-sided density S₀ gives Var x = π S₀/(kc).
//!
//! # Closed forms (n ≤ 4)
//! ```text
//! I₁ = π B₀² / (A₀A₁)
//! I₂ = π (A₀B₁² + A₂B₀²) / (A₀A₁A₂)
//! I₃ = π [A₀A₃(2B₀B₂ − B₁²) − A₀A₁B₂² − A₂A₃B₀²] / [A₀A₃(A₀A₃ − A₁A₂)]
//! I₄ = π [A₀B₃²(A₀A₃ − A₁A₂) + A₀A₁A₄(2B₁B₃ − B₂²) − A₀A₃A₄(B₁² − 2B₀B₂)
//!         + A₄B₀²(A₁A₄ − A₂A₃)] / [A₀A₄(A₀A₃² + A₁²A₄ − A₁A₂A₃)]
//! ```
//!
//! # General order
//! [`integral_i_n`] evaluates the same quantity exactly for any n by solving the linear system that
//! the Hurwitz-determinant formula (Gradshteyn & Ryzhik 3.112) expresses by Cramer's rule; see its
//! documentation.

use super::poly::is_hurwitz;
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// Largest order n solved on the stack (fixed-size arrays, no heap allocation); higher orders use a
/// fully pivoted `nalgebra` LU.
const STACK_MAX: usize = 8;

/// `$f::<N>($args)` for the degree `$n` = N ≤ [`STACK_MAX`] (the caller has checked the range): each
/// degree gets its own copy of the loops with constant lengths, which the compiler unrolls and keeps in
/// registers. The operations and their order are those of the loops with a run-time length, so the
/// results are the same, bit for bit.
macro_rules! by_degree {
    ($n:expr, $f:ident, ($($arg:expr),*)) => {
        match $n {
            0 => $f::<0>($($arg),*),
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            6 => $f::<6>($($arg),*),
            7 => $f::<7>($($arg),*),
            _ => $f::<STACK_MAX>($($arg),*),
        }
    };
}

fn check_finite(name: &str, c: &[f64]) -> Result<()> {
    if let Some(v) = c.iter().find(|v| !v.is_finite()) {
        return Err(Error::invalid(name, v, "all coefficients must be finite"));
    }
    Ok(())
}

/// The slice without its trailing zeros (no allocation).
fn trimmed(c: &[f64]) -> &[f64] {
    &c[..c.iter().rposition(|&v| v != 0.0).map_or(0, |k| k + 1)]
}

/// Routh–Hurwitz test of a finite polynomial with non-zero leading coefficient; the same test as
/// [`is_hurwitz`] (all coefficients of one sign and every first-column Routh entry positive), on stack
/// arrays for degree ≤ [`STACK_MAX`].
fn hurwitz(p: &[f64]) -> bool {
    let n = p.len() - 1;
    if n > STACK_MAX {
        return is_hurwitz(p);
    }
    by_degree!(n, hurwitz_of, (p))
}

/// [`hurwitz`] of a polynomial of degree N ≤ [`STACK_MAX`] (`p.len()` = N + 1).
#[inline]
fn hurwitz_of<const N: usize>(p: &[f64]) -> bool {
    let (p, n) = (&p[..=N], N);
    let sg = p[n].signum();
    if !p.iter().all(|&c| c * sg > 0.0) {
        return false;
    }
    let (mut r0, mut r1) = ([0.0; STACK_MAX + 1], [0.0; STACK_MAX + 1]);
    let (mut l0, mut l1) = (0, 0);
    for k in (0..=n).rev().step_by(2) {
        r0[l0] = p[k] * sg;
        l0 += 1;
    }
    for k in (0..n).rev().step_by(2) {
        r1[l1] = p[k] * sg;
        l1 += 1;
    }
    while l1 > 0 {
        if !(r1[0] > 0.0 && r1[0].is_finite()) {
            return false;
        }
        let mut next = [0.0; STACK_MAX + 1];
        for j in 0..l0 - 1 {
            next[j] = r0[j + 1] - r0[0] * (if j + 1 < l1 { r1[j + 1] } else { 0.0 }) / r1[0];
        }
        r0 = r1;
        r1 = next;
        (l0, l1) = (l1, l0 - 1);
    }
    true
}

/// Validates (b, a) for the table (one pass, no allocation unless it fails) and returns (b without
/// trailing zeros, n).
fn validate<'b>(b: &'b [f64], a: &[f64]) -> Result<(&'b [f64], usize)> {
    check_finite("a", a)?;
    check_finite("b", b)?;
    if a.len() < 2 {
        return Err(Error::invalid(
            "a",
            format!("{a:?}"),
            "needs n + 1 ≥ 2 coefficients A₀..Aₙ (denominator of degree n ≥ 1)",
        ));
    }
    let n = a.len() - 1;
    if a[n] == 0.0 {
        return Err(Error::invalid(
            "a",
            format!("{a:?}"),
            "the last coefficient Aₙ must be non-zero (it fixes the order n)",
        ));
    }
    let bt = trimmed(b);
    if bt.len() > n {
        return Err(Error::Divergent {
            quantity: "integral of |N/D|^2".into(),
            reason: format!(
                "numerator degree {} >= denominator degree {n}: |H|^2 does not decay, the integral is \
                 infinite",
                bt.len() - 1
            ),
        });
    }
    if !hurwitz(a) {
        return Err(Error::invalid(
            "a",
            format!("{a:?}"),
            "denominator not stable: A(s) = Σ Aₖ sᵏ must be Hurwitz (all roots with Re s < 0); \
             with roots on the imaginary axis the integral diverges",
        ));
    }
    Ok((bt, n))
}

fn singular(ratio: f64) -> Error {
    Error::Numerical {
        what: "integral_i_n".into(),
        reason: format!(
            "the Hurwitz system is numerically singular (pivot ratio {ratio:e}): the denominator is too \
             close to having roots on the imaginary axis"
        ),
    }
}

/// Matrix entry (k, j) = 2(−1)ʲ A_{2k−j} and right-hand side dₖ = Σ_{i+j=2k} (−1)ʲ Bᵢ Bⱼ of the system
/// of [`integral_i_n`] (b trimmed, len ≤ n).
#[inline]
fn entry(a: &[f64], n: usize, k: usize, j: usize) -> f64 {
    let sgn = if j.is_multiple_of(2) { 1.0 } else { -1.0 };
    match (2 * k).checked_sub(j) {
        Some(i) if i <= n => 2.0 * sgn * a[i],
        _ => 0.0,
    }
}

#[inline]
fn rhs(b: &[f64], k: usize) -> f64 {
    // j ascending over the pairs with i = 2k − j < len (the terms outside contribute nothing)
    let mut d = 0.0;
    let lo = (2 * k + 1).saturating_sub(b.len());
    for j in lo..b.len().min(2 * k + 1) {
        let t = b[2 * k - j] * b[j];
        d += if j.is_multiple_of(2) { t } else { -t };
    }
    d
}

/// C_{n−1} of the validated system (b trimmed and non-zero): stack arrays and partial pivoting for
/// n ≤ [`STACK_MAX`], fully pivoted `nalgebra` LU above. Singular if the smallest |pivot| is at most
/// n ε times the largest.
fn solve_last(b: &[f64], a: &[f64], n: usize) -> Result<(f64, f64)> {
    if n <= STACK_MAX {
        let mut m = [[0.0; STACK_MAX + 1]; STACK_MAX];
        for (k, row) in m.iter_mut().enumerate().take(n) {
            for (j, v) in row.iter_mut().enumerate().take(n) {
                *v = entry(a, n, k, j);
            }
            row[n] = rhs(b, k);
        }
        let (mut umax, mut umin) = (0.0_f64, f64::INFINITY);
        for col in 0..n {
            let mut p = col;
            for r in col + 1..n {
                if m[r][col].abs() > m[p][col].abs() {
                    p = r;
                }
            }
            m.swap(col, p);
            let piv = m[col][col];
            umax = umax.max(piv.abs());
            umin = umin.min(piv.abs());
            if piv == 0.0 {
                return Err(singular(0.0));
            }
            for r in col + 1..n {
                let f = m[r][col] / piv;
                if f != 0.0 {
                    let (pivot_rows, rest) = m.split_at_mut(r);
                    for (x, y) in rest[0][col..=n].iter_mut().zip(&pivot_rows[col][col..=n]) {
                        *x -= f * y;
                    }
                }
            }
        }
        if umin <= n as f64 * f64::EPSILON * umax {
            return Err(singular(umin / umax));
        }
        let mut c = [0.0; STACK_MAX];
        for r in (0..n).rev() {
            let mut s = m[r][n];
            for k in r + 1..n {
                s -= m[r][k] * c[k];
            }
            c[r] = s / m[r][r];
        }
        return Ok((c[n - 1], umax / umin));
    }
    let m = DMatrix::<f64>::from_fn(n, n, |k, j| entry(a, n, k, j));
    let d = DVector::<f64>::from_fn(n, |k, _| rhs(b, k));
    let lu = nalgebra::linalg::FullPivLU::new(m);
    let u = lu.u();
    let (mut umax, mut umin) = (0.0_f64, f64::INFINITY);
    for i in 0..n {
        umax = umax.max(u[(i, i)].abs());
        umin = umin.min(u[(i, i)].abs());
    }
    let c = if umin > n as f64 * f64::EPSILON * umax {
        lu.solve(&d)
    } else {
        None
    };
    Ok((c.ok_or_else(|| singular(umin / umax))?[n - 1], umax / umin))
}

/// Iₙ = 2π C_{n−1}/Aₙ for validated input.
fn table_value(b: &[f64], a: &[f64], n: usize) -> Result<f64> {
    table_value_conditioned(b, a, n).map(|r| r.0)
}

/// Iₙ and the ratio of the largest to the smallest pivot of the Hurwitz elimination (a condition estimate:
/// the relative error of Iₙ is of the order of this ratio times n ε).
fn table_value_conditioned(b: &[f64], a: &[f64], n: usize) -> Result<(f64, f64)> {
    if b.is_empty() {
        return Ok((0.0, 1.0));
    }
    let (c, ratio) = solve_last(b, a, n)?;
    let value = 2.0 * PI * c / a[n];
    if !value.is_finite() {
        return Err(Error::Numerical {
            what: "integral_i_n".into(),
            reason: "the result overflowed".into(),
        });
    }
    // Rounding can only make a tiny result slightly negative.
    Ok((value.max(0.0), ratio))
}

/// The integral Iₙ = ∫_{−∞}^{∞} |B(iω)/A(iω)|² dω for any order n ≥ 1.
///
/// `a` holds A₀..Aₙ (ascending, Aₙ ≠ 0), `b` holds up to n coefficients B₀..B_{n−1} (ascending;
/// shorter is zero-padded, trailing zeros are ignored). See the [module docs](self) for the
/// convention (s = iω or s = −iω give the same value).
///
/// # Formula
/// Write |H(iω)|² = B(s)B(−s) / (A(s)A(−s)) at s = iω and find the polynomial C of degree ≤ n−1 with
///
/// ```text
/// A(s) C(−s) + A(−s) C(s) = B(s) B(−s).
/// ```
///
/// Matching the n even powers s^{2k} gives the linear system Σⱼ 2(−1)ʲ A_{2k−j} Cⱼ = dₖ,
/// dₖ = Σ_{i+j=2k} (−1)ʲ Bᵢ Bⱼ (k = 0..n−1; its matrix is the Hurwitz matrix up to signs, non-singular
/// when A is Hurwitz, and Cramer's rule on it is the Hurwitz-determinant formula). Then
/// |H|² = 2 Re[C(iω)/A(iω)], C/A is analytic in Re s ≥ 0 and ~ (C_{n−1}/Aₙ)/s at infinity, so closing
/// the contour in the right half plane gives
///
/// ```text
/// Iₙ = 2π C_{n−1} / Aₙ.
/// ```
///
/// For n ≤ 8 the system is built and solved on the stack by partially pivoted Gaussian elimination
/// (no heap allocation), above by fully pivoted LU. Exact in exact arithmetic for every n; in floating point
/// the accuracy degrades with the conditioning of the Hurwitz matrix (relative 1e-12 or better for
/// well-separated roots up to n ≈ 10).
///
/// # Errors
/// * [`Error::InvalidParameter`] for non-finite input, fewer than 2 `a` coefficients, Aₙ = 0, or A not
///   Hurwitz ("denominator not stable").
/// * [`Error::Divergent`] if `b` has a non-zero coefficient Bₖ with k ≥ n (|H|² does not decay).
/// * [`Error::Numerical`] if the linear system is numerically singular.
///
/// # Examples
/// ```
/// use stochvib::linalg::integral_i_n;
/// // ∫ dω / (1 + ω²) = π
/// assert!((integral_i_n(&[1.0], &[1.0, 1.0]).unwrap() - std::f64::consts::PI).abs() < 1e-15);
/// // m ẍ + c ẋ + k x = f: ∫|H|² dω = π/(kc)
/// let (m, c, k) = (2.0, 0.3, 50.0);
/// let i2 = integral_i_n(&[1.0], &[k, c, m]).unwrap();
/// assert!((i2 - std::f64::consts::PI / (k * c)).abs() < 1e-14 * i2);
/// ```
pub fn integral_i_n(b: &[f64], a: &[f64]) -> Result<f64> {
    let (b, n) = validate(b, a)?;
    table_value(b, a, n)
}

/// The tabulated closed forms I₁..I₄ (Newland, Appendix 1).
///
/// Same arguments and convention as [`integral_i_n`], which is the general-order algorithm; this
/// function exists as an independent check and for readers comparing with the textbook.
///
/// # Formula
/// See the [module docs](self): I₁ = π B₀²/(A₀A₁), I₂ = π(A₀B₁² + A₂B₀²)/(A₀A₁A₂), I₃, I₄.
///
/// # Errors
/// As [`integral_i_n`], plus [`Error::InvalidParameter`] for n > 4 (no closed form is tabulated here).
///
/// # Examples
/// ```
/// use stochvib::linalg::{integral_closed_form, integral_i_n};
/// // A(s) = (s + 1)³: ∫ dω / (1 + ω²)³ = 3π/8
/// let a = [1.0, 3.0, 3.0, 1.0];
/// let i3 = integral_closed_form(&[1.0], &a).unwrap();
/// assert!((i3 - 3.0 * std::f64::consts::PI / 8.0).abs() < 1e-14);
/// assert!((i3 - integral_i_n(&[1.0], &a).unwrap()).abs() < 1e-14);
/// ```
pub fn integral_closed_form(b: &[f64], a: &[f64]) -> Result<f64> {
    let (bt, n) = validate(b, a)?;
    let mut b = [0.0; 4];
    b[..bt.len().min(4)].copy_from_slice(&bt[..bt.len().min(4)]);
    let v = match n {
        1 => PI * b[0] * b[0] / (a[0] * a[1]),
        2 => PI * (a[0] * b[1] * b[1] + a[2] * b[0] * b[0]) / (a[0] * a[1] * a[2]),
        3 => {
            let (a0, a1, a2, a3) = (a[0], a[1], a[2], a[3]);
            let (b0, b1, b2) = (b[0], b[1], b[2]);
            PI * (a0 * a3 * (2.0 * b0 * b2 - b1 * b1) - a0 * a1 * b2 * b2 - a2 * a3 * b0 * b0)
                / (a0 * a3 * (a0 * a3 - a1 * a2))
        }
        4 => {
            let (a0, a1, a2, a3, a4) = (a[0], a[1], a[2], a[3], a[4]);
            let (b0, b1, b2, b3) = (b[0], b[1], b[2], b[3]);
            PI * (a0 * b3 * b3 * (a0 * a3 - a1 * a2) + a0 * a1 * a4 * (2.0 * b1 * b3 - b2 * b2)
                - a0 * a3 * a4 * (b1 * b1 - 2.0 * b0 * b2)
                + a4 * b0 * b0 * (a1 * a4 - a2 * a3))
                / (a0 * a4 * (a0 * a3 * a3 + a1 * a1 * a4 - a1 * a2 * a3))
        }
        _ => {
            return Err(Error::invalid(
                "a",
                format!("order n = {n}"),
                "closed forms are tabulated only for n ≤ 4; use integral_i_n for any order",
            ))
        }
    };
    Ok(v)
}

/// ∫_{−∞}^{∞} |N(iω)/D(iω)|² dω for real polynomials N, D in s (ascending coefficients).
///
/// # Formula
/// After trimming trailing zeros, requires deg N < deg D and D Hurwitz, and returns
/// `integral_i_n(N, D)` (the table Iₙ with n = deg D, Bₖ = Nₖ, Aₖ = Dₖ). For a stable filter H = N/D
/// driven by white noise of two-sided density S₀, the output variance is S₀ times this value. A zero
/// numerator gives 0.
///
/// # Errors
/// * [`Error::Divergent`] if deg N ≥ deg D (|H|² does not decay).
/// * [`Error::InvalidParameter`] if D is zero, has non-finite coefficients or is not Hurwitz
///   ("denominator not stable"), or N has non-finite coefficients.
/// * [`Error::Numerical`] as in [`integral_i_n`].
///
/// # Examples
/// ```
/// use stochvib::linalg::h2_integral;
/// // H(s) = 1/(s + 2): ∫ dω/(4 + ω²) = π/2
/// let v = h2_integral(&[1.0], &[2.0, 1.0]).unwrap();
/// assert!((v - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// // deg N ≥ deg D diverges
/// assert!(h2_integral(&[0.0, 1.0], &[2.0, 1.0]).is_err());
/// ```
pub fn h2_integral(num_s: &[f64], den_s: &[f64]) -> Result<f64> {
    check_finite("num_s", num_s)?;
    check_finite("den_s", den_s)?;
    let n = trimmed(num_s);
    let d = trimmed(den_s);
    if d.is_empty() {
        return Err(Error::invalid(
            "den_s",
            format!("{den_s:?}"),
            "the denominator must not be the zero polynomial",
        ));
    }
    if n.is_empty() {
        if !hurwitz(d) {
            return Err(Error::invalid(
                "den_s",
                format!("{den_s:?}"),
                "denominator not stable (not Hurwitz)",
            ));
        }
        return Ok(0.0);
    }
    if n.len() >= d.len() {
        return Err(Error::Divergent {
            quantity: "integral of |N/D|^2".into(),
            reason: "numerator degree >= denominator degree: |H|^2 does not decay, the integral is \
                     infinite"
                .into(),
        });
    }
    if !hurwitz(d) {
        return Err(Error::invalid(
            "den_s",
            format!("{den_s:?}"),
            "denominator not stable: D(s) must be Hurwitz (all roots with Re s < 0)",
        ));
    }
    // Validated above (finite, d trimmed with deg ≥ 1 > deg n, Hurwitz): no second pass.
    table_value(n, d, d.len() - 1)
}

/// [`h2_integral`] with a condition estimate of the Hurwitz elimination: `(value, ratio)`, where `ratio`
/// is the largest over the smallest pivot; the relative error of the value is of the order of
/// `ratio · n · ε` (ε = 2.2e-16).
///
/// # Errors
/// As [`h2_integral`].
///
/// # Examples
/// ```
/// use stochvib::linalg::integral_table::h2_integral_conditioned;
/// let (v, ratio) = h2_integral_conditioned(&[1.0], &[2.0, 1.0]).unwrap();
/// assert!((v - std::f64::consts::FRAC_PI_2).abs() < 1e-15 && ratio >= 1.0);
/// ```
pub fn h2_integral_conditioned(num_s: &[f64], den_s: &[f64]) -> Result<(f64, f64)> {
    let (n, d) = (trimmed(num_s), trimmed(den_s));
    if n.is_empty() || n.len() >= d.len() || !num_s.iter().chain(den_s).all(|v| v.is_finite()) || !hurwitz(d) {
        // zero numerator, divergence or invalid input: h2_integral's value or error
        return h2_integral(num_s, den_s).map(|v| (v, 1.0));
    }
    // validated as in h2_integral (one elimination: the same value as h2_integral, with its pivot ratio)
    table_value_conditioned(n, d, d.len() - 1)
}

/// One denominator D(s) of many [`h2_integral_conditioned`] calls (the outputs of one system share it):
/// the Routh–Hurwitz test and the Hurwitz elimination — which depend on D only — are done once, and each
/// numerator replays the recorded row swaps and multipliers on its right-hand side. Every operation on the
/// right-hand side is the one [`h2_integral_conditioned`] performs, in the same order, so the result is
/// the same, bit for bit (value, pivot ratio, or error). Numerators or denominators outside the stack
/// route (degree > 8, non-finite, not Hurwitz, zero or divergent numerator) go to
/// [`h2_integral_conditioned`] itself.
pub(crate) struct H2Denominator<'d> {
    den_s: &'d [f64],
    d: &'d [f64],
    elim: Option<Elimination>,
}

/// The recorded elimination of the Hurwitz matrix of a denominator of degree n ≤ [`STACK_MAX`].
struct Elimination {
    n: usize,
    /// The last diagonal entry of the upper triangle after elimination (the only one the table's
    /// C_{n−1} needs; 0 for n = 0).
    u_last: f64,
    /// Pivot row chosen at each column.
    swap: [u8; STACK_MAX],
    /// Multiplier of row r at column c (0: the row was skipped).
    /// (the strictly lower triangle, row by row: entry (r, c), c < r, at [`lower`]`(r, c)`).
    f: [f64; LOWER],
    /// The pivot ratio, or the error of a numerically singular system.
    ratio: std::result::Result<f64, f64>,
}

/// Entries of the strictly lower triangle of a STACK_MAX × STACK_MAX matrix.
const LOWER: usize = STACK_MAX * (STACK_MAX - 1) / 2;

/// The index of entry (r, c), c < r, of a strictly lower triangle stored row by row.
#[inline(always)]
fn lower(r: usize, c: usize) -> usize {
    r * (r - 1) / 2 + c
}

impl<'d> H2Denominator<'d> {
    /// Prepares the denominator `den_s` (ascending in s).
    pub(crate) fn new(den_s: &'d [f64]) -> H2Denominator<'d> {
        let d = trimmed(den_s);
        let n = d.len().saturating_sub(1);
        let elim = if (1..=STACK_MAX).contains(&n) && den_s.iter().all(|v| v.is_finite()) && hurwitz(d) {
            Some(Elimination::new(d, n))
        } else {
            None
        };
        H2Denominator { den_s, d, elim }
    }

    /// [`h2_integral_conditioned`]`(num_s, den_s)`.
    pub(crate) fn h2_conditioned(&self, num_s: &[f64]) -> Result<(f64, f64)> {
        let b = trimmed(num_s);
        let Some(el) = &self.elim else {
            return h2_integral_conditioned(num_s, self.den_s);
        };
        if b.is_empty() || b.len() >= self.d.len() || !num_s.iter().all(|v| v.is_finite()) {
            return h2_integral_conditioned(num_s, self.den_s);
        }
        let n = el.n;
        let ratio = el.ratio.map_err(singular)?;
        let mut r = [0.0; STACK_MAX];
        for (k, v) in r.iter_mut().enumerate().take(n) {
            *v = rhs(b, k);
        }
        for col in 0..n {
            r.swap(col, usize::from(el.swap[col]));
            for row in col + 1..n {
                let f = el.f[lower(row, col)];
                if f != 0.0 {
                    r[row] -= f * r[col];
                }
            }
        }
        // back substitution yields C_{n−1} first, from the last row alone; the other Cⱼ do not enter Iₙ
        let c_last = r[n - 1] / el.u_last;
        let value = 2.0 * PI * c_last / self.d[n];
        if !value.is_finite() {
            return Err(Error::Numerical {
                what: "integral_i_n".into(),
                reason: "the result overflowed".into(),
            });
        }
        Ok((value.max(0.0), ratio))
    }
}

/// The table integrals of many numerators over one denominator as dot products (see
/// [`H2Denominator::weights`]): Iₙ(b) = 2π wᵀd(b)/Aₙ with dₖ(b) = Σ_{i+j=2k} (−1)ʲ BᵢBⱼ.
pub(crate) struct H2Weights {
    n: usize,
    /// w = M⁻ᵀ e_{n−1}, scaled by 2π/Aₙ.
    w: [f64; STACK_MAX],
    /// The pivot ratio of the elimination.
    ratio: f64,
}

impl H2Denominator<'_> {
    /// The linear functional of the table for this denominator: C_{n−1} = e_{n−1}ᵀM⁻¹d = wᵀd with
    /// Mᵀw = e_{n−1}, obtained by running the recorded elimination backwards on e_{n−1} (reverse mode of
    /// [`h2_conditioned`](Self::h2_conditioned)'s replay). Each numerator then costs its right-hand side
    /// and one dot product instead of a replay and a back substitution; the value equals
    /// [`h2_conditioned`](Self::h2_conditioned)'s within rounding (other order of operations), with the
    /// same pivot ratio. None where [`h2_conditioned`](Self::h2_conditioned) would not take the stack route
    /// (degree above 8, not finite, not Hurwitz) or the elimination is singular: ask it instead.
    pub(crate) fn weights(&self) -> Option<H2Weights> {
        let el = self.elim.as_ref()?;
        let ratio = el.ratio.ok()?;
        Some(by_degree!(el.n, weights_of, (el, self.d, ratio)))
    }
}

/// [`H2Denominator::weights`] of the elimination `el` of degree N of the denominator `d`.
#[inline]
fn weights_of<const N: usize>(el: &Elimination, d: &[f64], ratio: f64) -> H2Weights {
    let n = N;
    {
        let mut w = [0.0; STACK_MAX];
        w[n - 1] = 2.0 * PI / (el.u_last * d[n]);
        for col in (0..n).rev() {
            for row in (col + 1..n).rev() {
                let f = el.f[lower(row, col)];
                if f != 0.0 {
                    w[col] -= f * w[row];
                }
            }
            w.swap(col, usize::from(el.swap[col]));
        }
        H2Weights { n, w, ratio }
    }
}

impl H2Weights {
    /// Iₙ of the numerator `num_s` (ascending) over the denominator, with the pivot ratio; None where
    /// [`H2Denominator::h2_conditioned`] must decide (a zero, divergent or non-finite numerator).
    #[inline]
    pub(crate) fn h2(&self, num_s: &[f64]) -> Option<(f64, f64)> {
        let b = trimmed(num_s);
        if b.is_empty() || b.len() > self.n || !b.iter().all(|v| v.is_finite()) {
            return None;
        }
        let mut c = 0.0;
        for (k, wk) in self.w.iter().enumerate().take(self.n) {
            c += wk * rhs(b, k);
        }
        c.is_finite().then_some((c.max(0.0), self.ratio))
    }
}

impl H2Weights {
    /// Iₙ of `num_s` and of s·`num_s` (the second spectral moment's integral; None when it diverges, i.e.
    /// the numerator's degree is n − 1), with the pivot ratio, from one set of right-hand sides:
    /// dₖ(s·b) = −dₖ₋₁(b) (the substitution i → i + 1, j → j + 1 in Σ_{i+j=2k}(−1)ʲBᵢBⱼ flips the sign),
    /// d₀(s·b) = 0. None where [`h2`](Self::h2) is None.
    #[inline]
    pub(crate) fn h2_with_moment(&self, num_s: &[f64]) -> Option<(f64, Option<f64>, f64)> {
        let b = trimmed(num_s);
        let n = self.n;
        if b.is_empty() || b.len() > n || !b.iter().all(|v| v.is_finite()) {
            return None;
        }
        let (c0, c2) = by_degree!(n, sums_with_moment, (&self.w, b));
        if !c0.is_finite() {
            return None;
        }
        let moment = (b.len() < n && c2.is_finite()).then_some(c2.max(0.0));
        Some((c0.max(0.0), moment, self.ratio))
    }
}

/// (wᵀd(b), −Σₖ w_{k+1}dₖ(b)) for degree N: the two sums of [`H2Weights::h2_with_moment`], in its order.
#[inline]
fn sums_with_moment<const N: usize>(w: &[f64; STACK_MAX], b: &[f64]) -> (f64, f64) {
    // the numerator's length 1 ≤ B ≤ N (checked by the caller) as a constant too: rhs's loops unrolled
    match b.len() {
        1 => sums_of::<N, 1>(w, b),
        2 => sums_of::<N, 2>(w, b),
        3 => sums_of::<N, 3>(w, b),
        4 => sums_of::<N, 4>(w, b),
        5 => sums_of::<N, 5>(w, b),
        6 => sums_of::<N, 6>(w, b),
        7 => sums_of::<N, 7>(w, b),
        _ => sums_of::<N, STACK_MAX>(w, b),
    }
}

/// [`sums_with_moment`] for a numerator of B coefficients.
#[inline(always)]
fn sums_of<const N: usize, const B: usize>(w: &[f64; STACK_MAX], b: &[f64]) -> (f64, f64) {
    let b = &b[..B];
    let (mut c0, mut c2) = (0.0, 0.0);
    for k in 0..N {
        let d = rhs(b, k);
        c0 += w[k] * d;
        if k + 1 < N {
            c2 -= w[k + 1] * d;
        }
    }
    (c0, c2)
}

impl Elimination {
    /// The elimination of `solve_last`'s stack route on the Hurwitz matrix of `a` (degree n), recorded.
    fn new(a: &[f64], n: usize) -> Elimination {
        debug_assert!(n <= STACK_MAX, "the stack route");
        by_degree!(n, elimination_of, (a))
    }
}

/// [`Elimination::new`] of degree N ≤ [`STACK_MAX`].
#[inline]
fn elimination_of<const N: usize>(a: &[f64]) -> Elimination {
    let n = N;
    {
        let mut m = [[0.0; N]; N];
        for (k, row) in m.iter_mut().enumerate().take(n) {
            for (j, v) in row.iter_mut().enumerate().take(n) {
                *v = entry(a, n, k, j);
            }
        }
        let mut swap = [0; STACK_MAX];
        let mut f = [0.0; LOWER];
        let (mut umax, mut umin) = (0.0_f64, f64::INFINITY);
        let mut ratio = Ok(0.0);
        for col in 0..n {
            let mut p = col;
            for r in col + 1..n {
                if m[r][col].abs() > m[p][col].abs() {
                    p = r;
                }
            }
            m.swap(col, p);
            swap[col] = p as u8; // p < N ≤ STACK_MAX
            let piv = m[col][col];
            umax = umax.max(piv.abs());
            umin = umin.min(piv.abs());
            if piv == 0.0 {
                ratio = Err(0.0);
                break;
            }
            for r in col + 1..n {
                let fr = m[r][col] / piv;
                f[lower(r, col)] = fr;
                if fr != 0.0 {
                    let (pivot_rows, rest) = m.split_at_mut(r);
                    for (x, y) in rest[0][col..n].iter_mut().zip(&pivot_rows[col][col..n]) {
                        *x -= fr * y;
                    }
                }
            }
        }
        if ratio.is_ok() {
            ratio = if umin <= n as f64 * f64::EPSILON * umax {
                Err(umin / umax)
            } else {
                Ok(umax / umin)
            };
        }
        Elimination {
            n,
            u_last: m.last().and_then(|row| row.last()).copied().unwrap_or(0.0),
            swap,
            f,
            ratio,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::lyapunov::solve_continuous_lyapunov;
    use crate::linalg::poly::test_rng::{hurwitz, Rng};
    use crate::linalg::poly::{eval_complex, mul};
    use crate::tolerance::{CONDITION_SCALED, EXACT, FACTORISATION, QUADRATURE, ROUNDING, ULPS};
    use nalgebra::Complex;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(1e-300)
    }

    /// Lyapunov route: controllable canonical form of N/D (D normalised to monic),
    /// ẋᵢ = xᵢ₊₁ (i < n), ẋₙ = −Σ dₖ xₖ₊₁ + u, y = Σ nₖ xₖ₊₁, so H(s) = N(s)/D(s).
    /// With unit white noise u (E[u(t)u(t')] = δ(t − t'), two-sided density 1/(2π)),
    /// Var y = C X Cᵀ with A X + X Aᵀ + B Bᵀ = 0, and also Var y = (1/2π) ∫|H|² dω, hence
    /// ∫|H(iω)|² dω = 2π C X Cᵀ.
    fn lyapunov_route(num: &[f64], den: &[f64]) -> f64 {
        let n = den.len() - 1;
        let lead = den[n];
        let mut a = DMatrix::<f64>::zeros(n, n);
        for i in 0..n - 1 {
            a[(i, i + 1)] = 1.0;
        }
        for k in 0..n {
            a[(n - 1, k)] = -den[k] / lead;
        }
        let mut bbt = DMatrix::<f64>::zeros(n, n);
        bbt[(n - 1, n - 1)] = 1.0;
        let mut c = DVector::<f64>::zeros(n);
        for (k, v) in num.iter().enumerate() {
            c[k] = v / lead;
        }
        let x = solve_continuous_lyapunov(&a, &bbt).unwrap();
        2.0 * PI * (c.transpose() * x * c)[(0, 0)]
    }

    /// ∫|H|² dω by the substitution ω = tan θ (smooth on [−π/2, π/2] since deg N < deg D) and
    /// composite Simpson — an independent, weak check.
    fn brute(num: &[f64], den: &[f64], m: usize) -> f64 {
        let f = |th: f64| {
            let w = th.tan();
            let sec2 = 1.0 + w * w;
            if !sec2.is_finite() {
                // limit at ±π/2: |H|²(1 + ω²) → (N_{n−1}/D_n)² if deg N = deg D − 1, else 0
                let n = den.len() - 1;
                return if num.len() == n {
                    (num[n - 1] / den[n]).powi(2)
                } else {
                    0.0
                };
            }
            let s = Complex::new(0.0, w);
            (eval_complex(num, s) / eval_complex(den, s)).norm_sqr() * sec2
        };
        let (lo, hi) = (-PI / 2.0, PI / 2.0);
        let h = (hi - lo) / m as f64;
        let mut sum = f(lo) + f(hi);
        for k in 1..m {
            let w = if k % 2 == 1 { 4.0 } else { 2.0 };
            sum += w * f(lo + k as f64 * h);
        }
        sum * h / 3.0
    }

    #[test]
    fn hand_cases() {
        assert!(rel(integral_i_n(&[1.0], &[1.0, 1.0]).unwrap(), PI) < ULPS);
        // n = 1: π B₀²/(A₀A₁)
        let v = integral_i_n(&[3.0], &[2.0, 5.0]).unwrap();
        assert!(rel(v, PI * 9.0 / 10.0) < ULPS);
        // n = 2: π(A₀B₁² + A₂B₀²)/(A₀A₁A₂)
        let (a, b) = ([4.0, 0.5, 2.0], [1.5, -0.7]);
        let expect = PI * (a[0] * b[1] * b[1] + a[2] * b[0] * b[0]) / (a[0] * a[1] * a[2]);
        assert!(rel(integral_i_n(&b, &a).unwrap(), expect) < ROUNDING);
        // (s+1)^n with B = 1: ∫(1+ω²)^{−n} dω = π (2n−2)!/(2^{2n−2} ((n−1)!)²)
        let mut a = vec![1.0];
        let mut expect = PI;
        for n in 1..=7 {
            a = mul(&a, &[1.0, 1.0]);
            if n > 1 {
                expect *= (2 * n - 3) as f64 / (2 * n - 2) as f64;
            }
            assert!(rel(integral_i_n(&[1.0], &a).unwrap(), expect) < ROUNDING, "n = {n}");
            if n <= 4 {
                assert!(rel(integral_closed_form(&[1.0], &a).unwrap(), expect) < ROUNDING);
            }
        }
        // All-negative Hurwitz denominator: same value.
        assert!(rel(integral_i_n(&[1.0], &[-1.0, -1.0]).unwrap(), PI) < ULPS);
        assert_eq!(integral_i_n(&[], &[1.0, 1.0]).unwrap(), 0.0);
        assert_eq!(h2_integral(&[0.0], &[1.0, 1.0]).unwrap(), 0.0);
    }

    #[test]
    fn closed_form_matches_general() {
        let mut rng = Rng::new(31);
        for trial in 0..400 {
            let n = 1 + trial % 4;
            let a = hurwitz(&mut rng, n);
            let b: Vec<f64> = (0..n).map(|_| rng.range(-2.0, 2.0)).collect();
            let g = integral_i_n(&b, &a).unwrap();
            let c = integral_closed_form(&b, &a).unwrap();
            assert!(rel(c, g) < EXACT, "n={n} a={a:?} b={b:?}: {c} vs {g}");
        }
    }

    /// The shared-denominator route replays h2_integral_conditioned's elimination: the same value and
    /// pivot ratio bit for bit, or the same error, for stable denominators of degree 1..10 (10 > 8: the
    /// delegated route), numerators of every degree up to divergent, zero numerators, unstable and
    /// non-finite denominators, and stiff denominators (roots spread over 8 decades) whose elimination is
    /// ill-conditioned.
    #[test]
    fn shared_denominator_equals_one_call() {
        let mut rng = Rng::new(2026);
        let same = |num: &[f64], den: &[f64]| {
            let one = h2_integral_conditioned(num, den).map_err(|e| e.to_string());
            let shared = H2Denominator::new(den).h2_conditioned(num).map_err(|e| e.to_string());
            match (&one, &shared) {
                (Ok((v1, r1)), Ok((v2, r2))) => {
                    assert_eq!(
                        (v1.to_bits(), r1.to_bits()),
                        (v2.to_bits(), r2.to_bits()),
                        "{num:?} / {den:?}"
                    )
                }
                _ => assert_eq!(one, shared, "{num:?} / {den:?}"),
            }
        };
        for trial in 0..600 {
            let n = 1 + trial % 10;
            let mut a = hurwitz(&mut rng, n);
            if trial % 7 == 3 {
                // stiff: scale the roots' spread by multiplying with (s + 1e-4)(s + 1e4)
                a = mul(&a, &[1.0, 1e4 + 1e-4, 1.0]);
            }
            if trial % 11 == 5 {
                a[0] = -a[0]; // not Hurwitz
            }
            let den = a.clone();
            let nb = (rng.next_u64() as usize) % (den.len() + 1);
            let b: Vec<f64> = (0..nb).map(|_| rng.range(-2.0, 2.0)).collect();
            same(&b, &den);
            same(&[], &den);
            same(&[0.0, 0.0], &den);
            let mut bad = b.clone();
            bad.push(f64::NAN);
            same(&bad, &den);
            let mut padded = den.clone();
            padded.push(0.0);
            same(&b, &padded);
        }
        same(&[1.0], &[1.0, f64::INFINITY, 1.0]);
        same(&[1.0], &[1.0]);
    }

    /// The adjoint form (`H2Denominator::weights`, a dot product per numerator) against the replayed
    /// elimination (`h2_conditioned`, itself bit-identical to one `h2_integral_conditioned` call): both
    /// solve the same factored Hurwitz system, forwards or transposed, so they agree within the rounding of
    /// that solve, κ·p(n)·ε with κ the pivot ratio: CONDITION_SCALED · ratio (plus a floor of ROUNDING).
    /// Where `weights` or `h2` declines, `h2_conditioned` is the answer by construction.
    /// The Routh test of every degree 0…8 (one copy per degree, [`by_degree!`]) against
    /// [`is_hurwitz`], an independent implementation (heap arrays, its own loop): random Hurwitz
    /// polynomials, the same with one coefficient's sign flipped or set to zero, and random coefficients.
    #[test]
    fn routh_test_of_every_degree_equals_is_hurwitz() {
        let mut rng = Rng::new(7);
        let (mut yes, mut no) = (0, 0);
        for trial in 0..2700 {
            let n = trial % (STACK_MAX + 1);
            let mut a = match trial % 3 {
                0 => hurwitz(&mut rng, n),
                _ => (0..=n).map(|_| rng.range(-1.0, 3.0)).collect(),
            };
            if trial % 3 == 1 && n > 0 {
                let k = (rng.next_u64() as usize) % n;
                a[k] = if trial % 2 == 0 { -a[k] } else { 0.0 };
            }
            let want = is_hurwitz(&a);
            assert_eq!(super::hurwitz(&a), want, "{a:?}");
            if want {
                yes += 1;
            } else {
                no += 1;
            }
        }
        assert!(yes > 900 && no > 900, "{yes} Hurwitz, {no} not");
    }

    /// The loops of one copy per degree N and numerator length B ([`sums_with_moment`], [`weights_of`])
    /// give the bits of the same loops with run-time lengths (written out here as the oracle), for every
    /// N ≤ 8 and B ≤ N.
    #[test]
    fn constant_length_loops_give_the_bits_of_run_time_ones() {
        let mut rng = Rng::new(11);
        for trial in 0..800 {
            let n = 1 + trial % STACK_MAX;
            let a = hurwitz(&mut rng, n);
            let table = H2Denominator::new(&a);
            let (Some(el), Some(w)) = (table.elim.as_ref(), table.weights()) else {
                continue;
            };
            // weights: the recorded elimination run backwards, lengths at run time
            let mut w0 = [0.0; STACK_MAX];
            w0[n - 1] = 2.0 * PI / (el.u_last * a[n]);
            for col in (0..n).rev() {
                for row in (col + 1..n).rev() {
                    let f = el.f[lower(row, col)];
                    if f != 0.0 {
                        w0[col] -= f * w0[row];
                    }
                }
                w0.swap(col, usize::from(el.swap[col]));
            }
            assert_eq!(w.w.map(f64::to_bits), w0.map(f64::to_bits), "{a:?}");
            for nb in 1..=n {
                let b: Vec<f64> = (0..nb).map(|_| rng.range(-2.0, 2.0)).collect();
                let (mut c0, mut c2) = (0.0, 0.0);
                for k in 0..n {
                    let d = rhs(&b, k);
                    c0 += w.w[k] * d;
                    if k + 1 < n {
                        c2 -= w.w[k + 1] * d;
                    }
                }
                let got = by_degree!(n, sums_with_moment, (&w.w, &b));
                assert_eq!(
                    (got.0.to_bits(), got.1.to_bits()),
                    (c0.to_bits(), c2.to_bits()),
                    "{b:?} / {a:?}"
                );
            }
        }
    }

    #[test]
    fn weights_equal_the_replayed_elimination() {
        let mut rng = Rng::new(2025);
        let (mut compared, mut declined) = (0, 0);
        for trial in 0..600 {
            let n = 1 + trial % 8;
            let mut a = hurwitz(&mut rng, n);
            if trial % 7 == 3 {
                a = mul(&a, &[1.0, 1e4 + 1e-4, 1.0]);
            }
            if trial % 11 == 5 {
                a[0] = -a[0];
            }
            let table = H2Denominator::new(&a);
            let nb = (rng.next_u64() as usize) % (a.len() + 1);
            let b: Vec<f64> = (0..nb).map(|_| rng.range(-2.0, 2.0)).collect();
            match (table.weights().and_then(|w| w.h2(&b)), table.h2_conditioned(&b)) {
                (Some((v, r)), Ok((v0, r0))) => {
                    compared += 1;
                    assert_eq!(r.to_bits(), r0.to_bits(), "{b:?} / {a:?}");
                    let tol = CONDITION_SCALED * r0 + ROUNDING;
                    assert!(
                        (v - v0).abs() <= tol * v0.abs().max(f64::MIN_POSITIVE),
                        "{b:?} / {a:?}: {v} vs {v0}"
                    );
                }
                (Some(_), Err(e)) => panic!("weights answered where the table fails: {e}"),
                (None, _) => declined += 1,
            }
            // the pair (Iₙ(b), Iₙ(s·b)) against two replayed calls
            if let Some((v, m, r)) = table.weights().and_then(|w| w.h2_with_moment(&b)) {
                let tol = CONDITION_SCALED * r + ROUNDING;
                let (v0, _) = table.h2_conditioned(&b).unwrap();
                assert!((v - v0).abs() <= tol * v0.abs().max(f64::MIN_POSITIVE), "{b:?} / {a:?}");
                let mut sb = vec![0.0];
                sb.extend(&b);
                match (m, table.h2_conditioned(&sb)) {
                    (Some(m), Ok((m0, _))) => {
                        assert!(
                            (m - m0).abs() <= tol * m0.abs().max(f64::MIN_POSITIVE),
                            "s·{b:?} / {a:?}: {m} vs {m0}"
                        )
                    }
                    (None, Err(Error::Divergent { .. })) => {}
                    (m, other) => panic!("s·{b:?} / {a:?}: {m:?} vs {other:?}"),
                }
            }
        }
        assert!(
            compared > 300 && declined > 20,
            "compared {compared}, declined {declined}"
        );
    }

    #[test]
    fn general_matches_lyapunov_route() {
        let mut rng = Rng::new(99);
        for trial in 0..300 {
            let n = 1 + trial % 10;
            let a = hurwitz(&mut rng, n);
            let nb = 1 + (rng.next_u64() as usize) % n;
            let b: Vec<f64> = (0..nb).map(|_| rng.range(-2.0, 2.0)).collect();
            let g = integral_i_n(&b, &a).unwrap();
            let l = lyapunov_route(&b, &a);
            let h = h2_integral(&b, &a).unwrap();
            assert_eq!(g, h);
            assert!(rel(g, l) < FACTORISATION, "n={n} a={a:?} b={b:?}: {g} vs {l}");
        }
    }

    #[test]
    fn general_matches_brute_force_quadrature() {
        // SDOF-like resonance plus a real pole, numerator with s term.
        let den = mul(&[1.0, 0.4, 1.0], &[2.0, 1.0]);
        let num = [1.0, 0.5];
        let v = integral_i_n(&num, &den).unwrap();
        assert!(rel(brute(&num, &den, 200_000), v) < QUADRATURE);
        // Order 5 with a non-decaying-as-fast numerator (deg N = deg D − 1).
        let den = mul(&mul(&[4.0, 0.8, 1.0], &[1.0, 1.0, 1.0]), &[0.5, 1.0]);
        let num = [0.3, -1.0, 0.2, 0.0, 1.0];
        let v = integral_i_n(&num, &den).unwrap();
        assert!(rel(brute(&num, &den, 200_000), v) < QUADRATURE);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(matches!(
            integral_i_n(&[1.0], &[-1.0, 1.0]),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(integral_i_n(&[1.0], &[1.0, 0.0, 1.0]).is_err()); // roots ±i
        assert!(integral_i_n(&[1.0], &[10.0, 1.0, 1.0, 1.0]).is_err()); // RHP pair
        assert!(integral_i_n(&[1.0], &[1.0]).is_err()); // n = 0
        assert!(integral_i_n(&[1.0], &[1.0, 0.0]).is_err()); // Aₙ = 0
        assert!(integral_i_n(&[1.0, f64::NAN], &[1.0, 1.0, 1.0]).is_err());
        assert!(matches!(
            integral_i_n(&[1.0, 1.0], &[1.0, 1.0]),
            Err(Error::Divergent { .. })
        ));
        assert!(integral_i_n(&[1.0, 0.0], &[1.0, 1.0]).is_ok()); // trailing zero ignored
        assert!(integral_closed_form(&[1.0], &[1.0, 5.0, 10.0, 10.0, 5.0, 1.0]).is_err());
        assert!(matches!(
            h2_integral(&[1.0, 2.0, 3.0], &[1.0, 1.0]),
            Err(Error::Divergent { .. })
        ));
        assert!(matches!(h2_integral(&[1.0], &[5.0]), Err(Error::Divergent { .. })));
        assert!(matches!(
            h2_integral(&[1.0], &[1.0, -1.0, 1.0]),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(h2_integral(&[1.0], &[0.0, 0.0]).is_err());
    }
}
