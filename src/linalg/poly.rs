//! Real polynomials with **ascending** coefficients: `c[0] + c[1] x + c[2] x² + …`.
//!
//! Evaluation (Horner), products, roots (companion-matrix eigenvalues polished by Newton steps),
//! construction from a conjugate-closed root set, the Routh–Hurwitz stability test and the spectral
//! factorisation of a non-negative polynomial in ω² into a stable shaping-filter polynomial in s.

use crate::error::{Error, Result};
use nalgebra::{Complex, DMatrix};

/// Drops trailing (highest-degree) exact zeros.
///
/// # Formula
/// Returns `c[..=k]` with k the largest index with `c[k] != 0`; the zero polynomial gives `[]`.
///
/// # Examples
/// ```
/// use stochvib::linalg::poly::trim;
/// assert_eq!(trim(&[1.0, 2.0, 0.0, 0.0]), vec![1.0, 2.0]);
/// assert!(trim(&[0.0, 0.0]).is_empty());
/// ```
pub fn trim(coeffs: &[f64]) -> Vec<f64> {
    let len = coeffs.iter().rposition(|&c| c != 0.0).map_or(0, |k| k + 1);
    coeffs[..len].to_vec()
}

/// Evaluates the polynomial at a real point by Horner's rule.
///
/// # Formula
/// p(x) = c₀ + x(c₁ + x(c₂ + …)). The empty polynomial is 0.
///
/// # Examples
/// ```
/// use stochvib::linalg::poly::eval;
/// assert_eq!(eval(&[1.0, 2.0, 3.0], 2.0), 17.0);
/// ```
pub fn eval(coeffs: &[f64], x: f64) -> f64 {
    coeffs.iter().rev().fold(0.0, |acc, &c| acc * x + c)
}

/// Evaluates the polynomial at `L` real points at once by Horner's rule, one independent recurrence per
/// lane.
///
/// The lanes do exactly the operations of [`eval`] (same order, no fused multiply–add), so each result is
/// bit-identical to `eval(coeffs, x[j])`; the `L` independent chains let the compiler use SIMD registers
/// and hide the latency of the multiply–add chain, which a loop over points calling [`eval`] cannot.
///
/// # Formula
/// p(x_j) = c₀ + x_j(c₁ + x_j(c₂ + …)) for j = 0 … L−1. The empty polynomial is 0.
///
/// # Examples
/// ```
/// use stochvib::linalg::poly::{eval, eval_lanes};
/// let c = [1.0, 2.0, 3.0];
/// let x = [0.0, 2.0, -1.5, 1e3];
/// let p = eval_lanes(&c, &x);
/// assert_eq!(p[1], 17.0);
/// assert!(p.iter().zip(&x).all(|(v, &xj)| *v == eval(&c, xj)));
/// ```
pub fn eval_lanes<const L: usize>(coeffs: &[f64], x: &[f64; L]) -> [f64; L] {
    let mut acc = [0.0; L];
    for &c in coeffs.iter().rev() {
        for j in 0..L {
            acc[j] = acc[j] * x[j] + c;
        }
    }
    acc
}

/// Evaluates the polynomial at a complex point by Horner's rule.
///
/// # Formula
/// p(z) = c₀ + z(c₁ + z(c₂ + …)). With real coefficients p(z̄) = conj p(z) exactly in floating point.
///
/// # Examples
/// ```
/// use nalgebra::Complex;
/// use stochvib::linalg::poly::eval_complex;
/// // p(s) = s² + 1 vanishes at s = i
/// let v = eval_complex(&[1.0, 0.0, 1.0], Complex::new(0.0, 1.0));
/// assert_eq!(v, Complex::new(0.0, 0.0));
/// ```
pub fn eval_complex(coeffs: &[f64], z: Complex<f64>) -> Complex<f64> {
    coeffs.iter().rev().fold(Complex::new(0.0, 0.0), |acc, &c| acc * z + c)
}

/// Value and derivative at a complex point (Horner).
fn eval_with_derivative(coeffs: &[f64], z: Complex<f64>) -> (Complex<f64>, Complex<f64>) {
    let mut p = Complex::new(0.0, 0.0);
    let mut dp = Complex::new(0.0, 0.0);
    for &c in coeffs.iter().rev() {
        dp = dp * z + p;
        p = p * z + c;
    }
    (p, dp)
}

/// Product of two polynomials.
///
/// # Formula
/// (p q)ₖ = Σᵢ pᵢ q_{k−i}. If either factor is empty (the zero polynomial) the result is empty.
///
/// # Examples
/// ```
/// use stochvib::linalg::poly::mul;
/// // (1 + s)(2 + s) = 2 + 3s + s²
/// assert_eq!(mul(&[1.0, 1.0], &[2.0, 1.0]), vec![2.0, 3.0, 1.0]);
/// ```
pub fn mul(p: &[f64], q: &[f64]) -> Vec<f64> {
    if p.is_empty() || q.is_empty() {
        return Vec::new();
    }
    let mut out = vec![0.0; p.len() + q.len() - 1];
    for (i, &a) in p.iter().enumerate() {
        for (j, &b) in q.iter().enumerate() {
            out[i + j] += a * b;
        }
    }
    out
}

/// Sum p + q (ascending coefficients; the result has the longer length).
///
/// # Examples
/// ```
/// use stochvib::linalg::poly::add;
/// assert_eq!(add(&[1.0, 2.0], &[3.0]), vec![4.0, 2.0]);
/// ```
pub fn add(p: &[f64], q: &[f64]) -> Vec<f64> {
    (0..p.len().max(q.len()))
        .map(|k| p.get(k).copied().unwrap_or(0.0) + q.get(k).copied().unwrap_or(0.0))
        .collect()
}

/// Difference p − q (ascending coefficients).
///
/// # Examples
/// ```
/// use stochvib::linalg::poly::sub;
/// assert_eq!(sub(&[1.0, 2.0, 3.0], &[1.0, 2.0]), vec![0.0, 0.0, 3.0]);
/// ```
pub fn sub(p: &[f64], q: &[f64]) -> Vec<f64> {
    let neg: Vec<f64> = q.iter().map(|v| -v).collect();
    add(p, &neg)
}

fn check_finite(name: &str, coeffs: &[f64]) -> Result<()> {
    if let Some(c) = coeffs.iter().find(|c| !c.is_finite()) {
        return Err(Error::invalid(name, c, "all polynomial coefficients must be finite"));
    }
    Ok(())
}

/// Monic real polynomial with the given roots.
///
/// # Formula
/// Π (s − rₖ), built from real linear factors (s − r) for real roots and real quadratics
/// s² − 2 Re(r) s + |r|² for conjugate pairs. A root counts as real if |Im r| ≤ 1e-14·|r|; otherwise it
/// must be matched by a root within 1e-8·|r| of its conjugate (the pair is averaged).
///
/// # Errors
/// [`Error::InvalidParameter`] if a root is not finite or the set is not closed under conjugation.
///
/// # Examples
/// ```
/// use nalgebra::Complex;
/// use stochvib::linalg::poly::from_roots;
/// let p = from_roots(&[Complex::new(-1.0, 2.0), Complex::new(-1.0, -2.0), Complex::new(-3.0, 0.0)])
///     .unwrap();
/// // (s² + 2s + 5)(s + 3) = 15 + 11s + 5s² + s³
/// let expect = [15.0, 11.0, 5.0, 1.0];
/// assert!(p.iter().zip(expect).all(|(a, b)| (a - b).abs() < 1e-12));
/// ```
pub fn from_roots(roots: &[Complex<f64>]) -> Result<Vec<f64>> {
    if let Some(z) = roots.iter().find(|z| !z.re.is_finite() || !z.im.is_finite()) {
        return Err(Error::invalid("roots", z, "all roots must be finite"));
    }
    let mut p = vec![1.0];
    let mut upper = Vec::new();
    let mut lower = Vec::new();
    for &z in roots {
        if z.im.abs() <= 1e-14 * z.norm() {
            p = mul(&p, &[-z.re, 1.0]);
        } else if z.im > 0.0 {
            upper.push(z);
        } else {
            lower.push(z);
        }
    }
    if upper.len() != lower.len() {
        return Err(Error::invalid(
            "roots",
            format!("{} roots above and {} below the real axis", upper.len(), lower.len()),
            "must be closed under complex conjugation (real polynomial)",
        ));
    }
    let mut used = vec![false; lower.len()];
    for z in upper {
        let mut best: Option<(usize, f64)> = None;
        for (k, w) in lower.iter().enumerate() {
            if !used[k] {
                let d = (z - w.conj()).norm();
                if best.is_none_or(|(_, bd)| d < bd) {
                    best = Some((k, d));
                }
            }
        }
        let (k, d) = best.expect("equal counts guarantee a partner");
        if d > 1e-8 * z.norm() {
            return Err(Error::invalid(
                "roots",
                z,
                format!(
                    "has no conjugate partner (nearest conjugate {} is {d:e} away); the root set must \
                     be closed under complex conjugation",
                    lower[k].conj()
                ),
            ));
        }
        used[k] = true;
        let r = (z + lower[k].conj()) * 0.5;
        p = mul(&p, &[r.norm_sqr(), -2.0 * r.re, 1.0]);
    }
    Ok(p)
}

/// Highest polynomial degree whose roots are computed ([`roots`], [`spectral_factor`]): the companion
/// matrix of degree n takes n² numbers and O(n³) operations, and in double precision the roots of a
/// polynomial of degree above a few dozen are already ill-conditioned (Wilkinson 1959, "The evaluation of
/// the zeros of ill-conditioned polynomials"); 256 is far beyond any spectrum or filter the toolkit meets.
pub const MAX_DEGREE: usize = 256;

/// Refuses a polynomial of degree above [`MAX_DEGREE`], naming `name` and what its roots would need.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `name`.
pub fn check_degree(name: &str, coeffs: &[f64]) -> Result<()> {
    let deg = coeffs.len().saturating_sub(1);
    if deg > MAX_DEGREE {
        return Err(Error::invalid(
            name,
            format!("{} coefficients", coeffs.len()),
            format!(
                "degree {deg} is above the {MAX_DEGREE} whose roots are computed (its companion matrix alone would \
                 take {} of memory, and roots of such degrees are not accurate in double precision): use a model \
                 of lower order",
                crate::io_rules::bytes_text(deg as u128 * deg as u128 * 8)
            ),
        ));
    }
    Ok(())
}

/// All complex roots of a real polynomial, with multiplicity.
///
/// # Formula
/// Trailing zeros are trimmed and exact zero roots (leading zero coefficients) split off. Degree 1 and
/// 2 use the closed forms (the quadratic in its cancellation-free form). Higher degrees use the
/// eigenvalues of the Parlett–Reinsch balanced companion matrix of the monic polynomial (real
/// Schur form, so conjugate pairs are exact), falling back to Aberth–Ehrlich iteration if the QR
/// iteration fails. Every root is then polished by up to 3 Newton steps on the original polynomial,
/// each accepted only if it decreases |p|. Multiple roots are found to accuracy ~ε^{1/m}.
///
/// # Errors
/// [`Error::InvalidParameter`] for non-finite coefficients or the zero polynomial;
/// [`Error::Numerical`] if no root finder converges.
///
/// # Examples
/// ```
/// use stochvib::linalg::poly::roots;
/// // s² + 2s + 5 = (s + 1 − 2i)(s + 1 + 2i)
/// let r = roots(&[5.0, 2.0, 1.0]).unwrap();
/// assert_eq!(r.len(), 2);
/// assert!(r.iter().all(|z| (z.re + 1.0).abs() < 1e-14 && (z.im.abs() - 2.0).abs() < 1e-14));
/// ```
pub fn roots(coeffs: &[f64]) -> Result<Vec<Complex<f64>>> {
    check_finite("coeffs", coeffs)?;
    let p = trim(coeffs);
    check_degree("coeffs", &p)?;
    if p.is_empty() {
        return Err(Error::invalid(
            "coeffs",
            "0",
            "the zero polynomial has no finite set of roots",
        ));
    }
    let nz = p.iter().take_while(|&&c| c == 0.0).count();
    let core = &p[nz..];
    let deg = core.len() - 1;
    let mut out = vec![Complex::new(0.0, 0.0); nz];
    let found: Vec<Complex<f64>> = match deg {
        0 => Vec::new(),
        1 => vec![Complex::new(-core[0] / core[1], 0.0)],
        2 => quadratic_roots(core[0], core[1], core[2]),
        _ => match companion_roots(core) {
            Ok(r) => r,
            Err(_) => aberth_roots(core)?,
        },
    };
    for z in found {
        out.push(polish(core, z));
    }
    Ok(out)
}

fn quadratic_roots(c: f64, b: f64, a: f64) -> Vec<Complex<f64>> {
    // a s² + b s + c with c ≠ 0
    let (bh, ch) = (b / a, c / a); // s² + bh s + ch
    let half = 0.5 * bh;
    let disc = half * half - ch;
    if disc >= 0.0 {
        let q = -(half + half.signum() * disc.sqrt());
        if q == 0.0 {
            // half = 0 and ch = 0 cannot happen (c ≠ 0); keep a safe branch anyway
            let r = (-ch).sqrt();
            return vec![Complex::new(r, 0.0), Complex::new(-r, 0.0)];
        }
        vec![Complex::new(q, 0.0), Complex::new(ch / q, 0.0)]
    } else {
        let im = (-disc).sqrt();
        vec![Complex::new(-half, im), Complex::new(-half, -im)]
    }
}

fn companion_roots(core: &[f64]) -> Result<Vec<Complex<f64>>> {
    let deg = core.len() - 1;
    let lead = core[deg];
    let mut m = DMatrix::<f64>::zeros(deg, deg);
    for j in 0..deg {
        m[(0, j)] = -core[deg - 1 - j] / lead;
    }
    for i in 1..deg {
        m[(i, i - 1)] = 1.0;
    }
    if m.iter().any(|v| !v.is_finite()) {
        return Err(Error::Numerical {
            what: "roots".to_string(),
            reason: "companion matrix overflowed".to_string(),
        });
    }
    nalgebra::linalg::balancing::balance_parlett_reinsch(&mut m);
    let (_, _, eig, _) = super::lyapunov::real_schur(&m, "roots (companion matrix eigenvalues)")?;
    Ok(eig)
}

fn aberth_roots(core: &[f64]) -> Result<Vec<Complex<f64>>> {
    let deg = core.len() - 1;
    // Cauchy-type radius bound for initial points.
    let lead = core[deg].abs();
    let radius = 1.0 + core[..deg].iter().map(|c| c.abs() / lead).fold(0.0, f64::max);
    let mut z: Vec<Complex<f64>> = (0..deg)
        .map(|k| {
            let th = 2.0 * std::f64::consts::PI * (k as f64 + 0.25) / deg as f64 + 0.4;
            Complex::from_polar(0.5 * radius, th)
        })
        .collect();
    for _ in 0..500 {
        let mut max_step: f64 = 0.0;
        for k in 0..deg {
            let (p, dp) = eval_with_derivative(core, z[k]);
            if p.norm() == 0.0 {
                continue;
            }
            let ratio = p / dp;
            let sum: Complex<f64> = (0..deg)
                .filter(|&j| j != k)
                .map(|j| Complex::new(1.0, 0.0) / (z[k] - z[j]))
                .sum();
            let step = ratio / (Complex::new(1.0, 0.0) - ratio * sum);
            if step.re.is_finite() && step.im.is_finite() {
                z[k] -= step;
                max_step = max_step.max(step.norm() / z[k].norm().max(1e-300));
            }
        }
        if max_step < 1e-15 {
            // Enforce conjugate symmetry: snap near-real roots to the real axis.
            return Ok(z
                .into_iter()
                .map(|w| {
                    if w.im.abs() <= 1e-10 * w.norm() {
                        Complex::new(w.re, 0.0)
                    } else {
                        w
                    }
                })
                .collect());
        }
    }
    Err(Error::Numerical {
        what: "roots".to_string(),
        reason: format!("neither the companion-matrix QR nor Aberth iteration converged (degree {deg})"),
    })
}

fn polish(coeffs: &[f64], mut z: Complex<f64>) -> Complex<f64> {
    let (mut p, mut dp) = eval_with_derivative(coeffs, z);
    for _ in 0..3 {
        if p.norm() == 0.0 || dp.norm() == 0.0 {
            break;
        }
        let cand = z - p / dp;
        if !(cand.re.is_finite() && cand.im.is_finite()) {
            break;
        }
        let (pc, dpc) = eval_with_derivative(coeffs, cand);
        if pc.norm() < p.norm() {
            z = cand;
            p = pc;
            dp = dpc;
        } else {
            break;
        }
    }
    z
}

/// Whether the polynomial is Hurwitz (all roots in the open left half plane Re s < 0).
///
/// # Formula
/// Routh's test: all coefficients non-zero with one sign, and all entries of the first column of the
/// Routh array of that same sign, where
///
/// ```text
/// r₀ = (aₙ, aₙ₋₂, …),  r₁ = (aₙ₋₁, aₙ₋₃, …),  r_{k+1}(j) = r_{k−1}(j+1) − r_{k−1}(0) r_k(j+1) / r_k(0).
/// ```
///
/// A zero in the first column (roots on or mirrored about the imaginary axis) gives `false`. A non-zero constant is Hurwitz (no roots); the zero
/// polynomial and non-finite input are not. No root finding, so no convergence issues; marginal cases
/// (roots within rounding of the axis) are decided by the rounded arithmetic.
///
/// # Examples
/// ```
/// use stochvib::linalg::is_hurwitz;
/// assert!(is_hurwitz(&[6.0, 11.0, 6.0, 1.0])); // (s+1)(s+2)(s+3)
/// assert!(!is_hurwitz(&[1.0, 0.0, 1.0])); // s² + 1: roots ±i
/// assert!(!is_hurwitz(&[10.0, 1.0, 1.0, 1.0])); // positive coefficients, RHP pair
/// ```
pub fn is_hurwitz(coeffs: &[f64]) -> bool {
    if coeffs.iter().any(|c| !c.is_finite()) {
        return false;
    }
    let p = trim(coeffs);
    if p.is_empty() {
        return false;
    }
    let n = p.len() - 1;
    let sgn = p[n].signum();
    if !p.iter().all(|&c| c * sgn > 0.0) {
        return false;
    }
    let mut r0: Vec<f64> = (0..=n).rev().step_by(2).map(|k| p[k] * sgn).collect();
    let mut r1: Vec<f64> = if n >= 1 {
        (0..n).rev().step_by(2).map(|k| p[k] * sgn).collect()
    } else {
        Vec::new()
    };
    while !r1.is_empty() {
        if r1[0].is_nan() || r1[0] <= 0.0 || !r1[0].is_finite() {
            return false;
        }
        let next: Vec<f64> = (0..r0.len() - 1)
            .map(|j| r0[j + 1] - r0[0] * r1.get(j + 1).copied().unwrap_or(0.0) / r1[0])
            .collect();
        r0 = r1;
        r1 = next;
    }
    true
}

/// Spectral factorisation of a non-negative polynomial in ω².
///
/// # Formula
/// Given P(x) = Σ pₖ xᵏ (ascending, x = ω²) with P(ω²) ≥ 0 for all real ω and pₘ > 0, returns
/// F(s) = √pₘ Π (s − sᵣ) with real coefficients, positive leading coefficient and all roots in the
/// closed left half plane, such that
///
/// ```text
/// |F(iω)|² = F(iω) F(−iω) = P(ω²)   for all real ω.
/// ```
///
/// Since F(s)F(−s) must equal Q(s) = P(−s²) = pₘ(−1)ᵐ Π (s² + xᵣ) over the roots xᵣ of P, each root
/// xᵣ contributes one factor s − sᵣ with sᵣ = −√(−xᵣ) (principal square root, so Re sᵣ ≤ 0):
/// * complex xᵣ: Re sᵣ < 0 (conjugate xᵣ give conjugate sᵣ);
/// * real xᵣ < 0: sᵣ = −√|xᵣ| (real, stable);
/// * xᵣ = 0: sᵣ = 0 (P = x gives F = s);
/// * real xᵣ > 0 (a zero of P at ω = √xᵣ): must have even multiplicity; consecutive positive roots
///   are paired, provided P does not go negative between them (relative to Σ|pₖ|xᵏ, beyond 1e-9),
///   and each pair contributes s² + x̄ (roots ±i√x̄ on the axis).
///
/// The second element of the result is the maximal relative residual
/// max |  |F(iω)|² − P(ω²) | / Σ|pₖ|ω^{2k} over a logarithmic grid of ω spanning two decades beyond
/// the root magnitudes, plus ω = 0 and the resonance frequencies.
///
/// Accuracy: a root of P of multiplicity μ is located only to ~ε^{1/μ}. Double zeros on the ω axis
/// are refined by Newton steps on P′ (full accuracy), but higher even multiplicities (e.g.
/// P = (x − 4)⁴) leave a residual of order 1e-5, which the returned residual reports.
///
/// # Errors
/// [`Error::InvalidParameter`] if a coefficient is non-finite, P is zero, the leading coefficient is
/// ≤ 0, or P changes sign (a positive root of odd multiplicity): P(ω²) < 0 somewhere.
/// [`Error::Numerical`] if root finding fails.
///
/// # Examples
/// ```
/// use stochvib::linalg::spectral_factor;
/// // |(iω)² + 0.2(iω) + 4|² = (4 − ω²)² + 0.04ω² = 16 − 7.96ω² + ω⁴
/// let (f, resid) = spectral_factor(&[16.0, -7.96, 1.0]).unwrap();
/// assert!((f[0] - 4.0).abs() < 1e-12 && (f[1] - 0.2).abs() < 1e-12 && (f[2] - 1.0).abs() < 1e-12);
/// assert!(resid < 1e-13);
/// ```
pub fn spectral_factor(p_of_w2: &[f64]) -> Result<(Vec<f64>, f64)> {
    check_finite("p_of_w2", p_of_w2)?;
    let p = trim(p_of_w2);
    if p.is_empty() {
        return Err(Error::invalid(
            "p_of_w2",
            "0",
            "the zero polynomial has no spectral factor (spectral density identically zero)",
        ));
    }
    let m = p.len() - 1;
    // a polynomial of degree m in ω² has degree 2m in s
    check_degree("p_of_w2", &vec![0.0; 2 * m + 1])?;
    let lead = p[m];
    if lead <= 0.0 {
        return Err(Error::invalid(
            "p_of_w2",
            format!("leading coefficient {lead}"),
            "must be > 0 (otherwise P(ω²) < 0 for large ω)",
        ));
    }
    let abs_p: Vec<f64> = p.iter().map(|c| c.abs()).collect();
    let xroots = roots(&p)?;
    let mut s_roots: Vec<Complex<f64>> = Vec::with_capacity(m);
    let mut positive: Vec<f64> = Vec::new();
    for x in xroots {
        if x.im == 0.0 {
            if x.re > 0.0 {
                positive.push(x.re);
            } else {
                s_roots.push(Complex::new(-(-x.re).sqrt(), 0.0));
            }
        } else {
            s_roots.push(-(-x).sqrt());
        }
    }
    positive.sort_by(|a, b| a.total_cmp(b));
    if positive.len() % 2 == 1 {
        let x = positive[positive.len() / 2];
        return Err(Error::invalid(
            "p_of_w2",
            format!("{p:?}"),
            format!(
                "P(ω²) changes sign at ω² ≈ {x} (a positive root of odd multiplicity): not a \
                 non-negative spectral density"
            ),
        ));
    }
    for pair in positive.chunks(2) {
        let (x1, x2) = (pair[0], pair[1]);
        let mid = 0.5 * (x1 + x2);
        let val = eval(&p, mid);
        if val < -1e-9 * eval(&abs_p, mid) {
            return Err(Error::invalid(
                "p_of_w2",
                format!("{p:?}"),
                format!("P(ω²) = {val:e} < 0 at ω² = {mid}: not a non-negative spectral density"),
            ));
        }
        let w = refine_double_root(&p, x1, x2).sqrt();
        s_roots.push(Complex::new(0.0, w));
        s_roots.push(Complex::new(0.0, -w));
    }
    let monic = from_roots(&s_roots)?;
    let scale = lead.sqrt();
    let f: Vec<f64> = monic.iter().map(|c| c * scale).collect();

    // Residual on a grid.
    let mags: Vec<f64> = s_roots.iter().map(|z| z.norm()).filter(|&r| r > 0.0).collect();
    let (lo, hi) = if mags.is_empty() {
        (1e-2, 1e2)
    } else {
        (
            mags.iter().copied().fold(f64::INFINITY, f64::min) * 1e-2,
            mags.iter().copied().fold(0.0, f64::max) * 1e2,
        )
    };
    let npts = 400;
    let mut grid: Vec<f64> = (0..npts)
        .map(|k| lo * (hi / lo).powf(k as f64 / (npts - 1) as f64))
        .collect();
    grid.push(0.0);
    grid.extend(s_roots.iter().map(|z| z.im.abs()));
    let mut resid: f64 = 0.0;
    for w in grid {
        let x = w * w;
        let fv = eval_complex(&f, Complex::new(0.0, w)).norm_sqr();
        let denom = eval(&abs_p, x);
        if denom > 0.0 {
            resid = resid.max((fv - eval(&p, x)).abs() / denom);
        }
    }
    Ok((f, resid))
}

/// Refines a double root of `p` approximated by the close pair (x1, x2) with guarded Newton steps
/// on p′ (a double root of p is a simple root of p′; the two individually polished roots of p carry
/// O(√ε) errors that need not be symmetric, so their mean is only O(√ε) accurate).
fn refine_double_root(p: &[f64], x1: f64, x2: f64) -> f64 {
    let d1: Vec<f64> = p.iter().enumerate().skip(1).map(|(k, c)| k as f64 * c).collect();
    let d2: Vec<f64> = d1.iter().enumerate().skip(1).map(|(k, c)| k as f64 * c).collect();
    let spread = (x2 - x1).abs().max(1e-8 * x1.abs().max(x2.abs()));
    let (lo, hi) = (x1.min(x2) - spread, x1.max(x2) + spread);
    let mut x = 0.5 * (x1 + x2);
    let mut g = eval(&d1, x);
    for _ in 0..8 {
        let h = eval(&d2, x);
        if g == 0.0 || h == 0.0 {
            break;
        }
        let cand = x - g / h;
        let gc = eval(&d1, cand);
        if cand.is_finite() && cand >= lo && cand <= hi && gc.abs() < g.abs() {
            x = cand;
            g = gc;
        } else {
            break;
        }
    }
    x
}

/// Small deterministic random generator for tests (SplitMix64).
#[cfg(test)]
pub(crate) mod test_rng {
    /// SplitMix64 generator.
    pub struct Rng(u64);
    impl Rng {
        pub fn new(seed: u64) -> Self {
            Rng(seed)
        }
        pub fn next_u64(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^ (z >> 31)
        }
        /// Uniform in [0, 1).
        pub fn uniform(&mut self) -> f64 {
            (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
        }
        /// Uniform in [a, b).
        pub fn range(&mut self, a: f64, b: f64) -> f64 {
            a + (b - a) * self.uniform()
        }
    }

    /// A random Hurwitz polynomial of exact degree `n` with positive leading coefficient, built from
    /// factors (s + p) and (s² + 2ζω s + ω²).
    pub fn hurwitz(rng: &mut Rng, n: usize) -> Vec<f64> {
        let mut p = vec![rng.range(0.5, 2.0)];
        let mut d = 0;
        while d < n {
            if n - d >= 2 && rng.uniform() < 0.6 {
                let w = rng.range(0.3, 3.0);
                let z = rng.range(0.05, 0.9);
                p = super::mul(&p, &[w * w, 2.0 * z * w, 1.0]);
                d += 2;
            } else {
                p = super::mul(&p, &[rng.range(0.2, 3.0), 1.0]);
                d += 1;
            }
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::test_rng::{hurwitz, Rng};
    use super::*;
    use crate::tolerance::{DOUBLE_ROOT, FACTORISATION, RESIDUAL, ROUNDING, SMALL_DECOMPOSITION, ULPS};

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * a.abs().max(b.abs()).max(1e-300)
    }

    #[test]
    fn eval_mul_trim() {
        assert_eq!(eval(&[], 3.0), 0.0);
        assert_eq!(eval(&[1.0, -3.0, 2.0], 2.0), 3.0);
        assert_eq!(mul(&[1.0, 1.0], &[2.0, 1.0]), vec![2.0, 3.0, 1.0]);
        assert!(mul(&[], &[1.0]).is_empty());
        assert_eq!(trim(&[0.0, 1.0, 0.0]), vec![0.0, 1.0]);
        let z = Complex::new(0.3, -1.2);
        let c = [1.5, -2.0, 0.5, 3.0];
        let direct = c[0] + z * c[1] + z * z * c[2] + z * z * z * c[3];
        assert!((eval_complex(&c, z) - direct).norm() < ROUNDING);
    }

    #[test]
    fn roots_round_trip_products() {
        // (s+1)(s+2) and friends
        let r = roots(&[2.0, 3.0, 1.0]).unwrap();
        let mut re: Vec<f64> = r.iter().map(|z| z.re).collect();
        re.sort_by(|a, b| a.total_cmp(b));
        assert!(close(re[0], -2.0, ULPS) && close(re[1], -1.0, ULPS));
        let p = mul(&mul(&[1.0, 1.0], &[2.0, 1.0]), &[5.0, 2.0, 1.0]);
        let r = roots(&p).unwrap();
        assert_eq!(r.len(), 4);
        let back = from_roots(&r).unwrap();
        for (a, b) in back.iter().zip(&p) {
            assert!((a - b).abs() < SMALL_DECOMPOSITION, "{back:?} vs {p:?}");
        }
        // zero roots and scaling
        let r = roots(&[0.0, 0.0, -6.0, 3.0]).unwrap(); // 3 s²(s − 2)
        assert_eq!(r.iter().filter(|z| z.norm() == 0.0).count(), 2);
        assert!(r.iter().any(|z| (z - Complex::new(2.0, 0.0)).norm() < ROUNDING));
        assert!(roots(&[5.0]).unwrap().is_empty());
        assert!(roots(&[0.0, 0.0]).is_err());
        assert!(roots(&[1.0, f64::NAN]).is_err());
    }

    #[test]
    fn roots_random_high_degree() {
        let mut rng = Rng::new(7);
        for n in 3..=12 {
            let p = hurwitz(&mut rng, n);
            let r = roots(&p).unwrap();
            assert_eq!(r.len(), n);
            let back = from_roots(&r).unwrap();
            let lead = p[n];
            for (a, b) in back.iter().zip(&p) {
                assert!((a * lead - b).abs() < FACTORISATION * p.iter().map(|c| c.abs()).fold(0.0, f64::max));
            }
        }
        // x^n − 1: roots of unity (a stalling case for unshifted QR)
        for n in 3..=8 {
            let mut p = vec![0.0; n + 1];
            p[0] = -1.0;
            p[n] = 1.0;
            let r = roots(&p).unwrap();
            assert_eq!(r.len(), n);
            for z in r {
                assert!(
                    (z.norm() - 1.0).abs() < SMALL_DECOMPOSITION && eval_complex(&p, z).norm() < SMALL_DECOMPOSITION
                );
            }
        }
    }

    #[test]
    fn from_roots_rejects_non_conjugate_sets() {
        assert!(from_roots(&[Complex::new(1.0, 1.0)]).is_err());
        assert!(from_roots(&[Complex::new(1.0, 1.0), Complex::new(1.0, -1.1)]).is_err());
        assert!(from_roots(&[Complex::new(f64::NAN, 0.0)]).is_err());
        assert_eq!(from_roots(&[]).unwrap(), vec![1.0]);
    }

    #[test]
    fn hurwitz_routh_agrees_with_roots() {
        assert!(is_hurwitz(&[1.0, 1.0]));
        assert!(is_hurwitz(&[-1.0, -1.0, -1.0])); // negated Hurwitz is Hurwitz
        assert!(!is_hurwitz(&[-1.0, 1.0]));
        assert!(!is_hurwitz(&[0.0, 1.0])); // root at 0
        assert!(!is_hurwitz(&[1.0, 0.0, 1.0]));
        assert!(!is_hurwitz(&[]));
        assert!(is_hurwitz(&[3.0]));
        assert!(!is_hurwitz(&[1.0, f64::INFINITY]));
        let mut rng = Rng::new(11);
        let mut n_stable = 0;
        for _ in 0..400 {
            let n = 1 + (rng.next_u64() % 7) as usize;
            let p: Vec<f64> = if rng.uniform() < 0.5 {
                hurwitz(&mut rng, n)
            } else {
                // random positive coefficients: sometimes stable, often not for n ≥ 3
                (0..=n).map(|_| rng.range(0.1, 3.0)).collect()
            };
            let by_roots = roots(&p).unwrap().iter().all(|z| z.re < 0.0);
            let margin = roots(&p)
                .unwrap()
                .iter()
                .map(|z| z.re.abs())
                .fold(f64::INFINITY, f64::min);
            if margin > 1e-6 {
                assert_eq!(is_hurwitz(&p), by_roots, "{p:?}");
            }
            n_stable += by_roots as usize;
        }
        assert!(n_stable > 100 && n_stable < 400);
    }

    #[test]
    fn spectral_factor_hand_cases() {
        let (f, r) = spectral_factor(&[1.0, 1.0]).unwrap();
        assert!(close(f[0], 1.0, ROUNDING) && close(f[1], 1.0, ROUNDING) && r < ROUNDING);
        let (f, r) = spectral_factor(&[0.0, 1.0]).unwrap();
        assert_eq!(f.len(), 2);
        assert!(f[0].abs() < ULPS && close(f[1], 1.0, ROUNDING) && r < ROUNDING);
        let (f, _) = spectral_factor(&[4.0]).unwrap();
        assert_eq!(f, vec![2.0]);
        // (x − 4)² + 4·x·0.01 ⇒ F = s² + 0.2 s + 4 (ω₀ = 2, ζ = 0.05)
        let p = [16.0, -8.0 + 0.04, 1.0];
        let (f, r) = spectral_factor(&p).unwrap();
        assert!(
            close(f[0], 4.0, SMALL_DECOMPOSITION)
                && close(f[1], 0.2, SMALL_DECOMPOSITION)
                && close(f[2], 1.0, ROUNDING)
        );
        assert!(r < ROUNDING);
        // double positive root: (x − 4)² ⇒ F = s² + 4 (undamped)
        let (f, r) = spectral_factor(&[16.0, -8.0, 1.0]).unwrap();
        assert!(close(f[0], 4.0, DOUBLE_ROOT) && f[1].abs() < DOUBLE_ROOT && close(f[2], 1.0, ROUNDING));
        assert!(r < RESIDUAL);
        // 3 (1 + x)(x − 1)² x  (mixed: negative root, double positive root, zero root)
        let p = mul(&mul(&[3.0, 3.0], &[1.0, -2.0, 1.0]), &[0.0, 1.0]);
        let (f, r) = spectral_factor(&p).unwrap();
        assert!(r < RESIDUAL, "{r}");
        assert!(f.len() == 5 && f[0].abs() < SMALL_DECOMPOSITION);
    }

    #[test]
    fn spectral_factor_rejects_negative() {
        assert!(spectral_factor(&[1.0, -1.0]).is_err()); // 1 − ω²
        assert!(spectral_factor(&[-1.0, 0.0, 1.0]).is_err()); // ω⁴ − 1
        assert!(spectral_factor(&[1.0, -3.0, 1.0]).is_err()); // two simple positive roots
        assert!(spectral_factor(&[]).is_err());
        assert!(spectral_factor(&[0.0]).is_err());
        assert!(spectral_factor(&[1.0, f64::NAN]).is_err());
    }

    #[test]
    fn spectral_factor_random_round_trip() {
        let mut rng = Rng::new(2024);
        for trial in 0..200 {
            let deg = 1 + trial % 4;
            let fz = hurwitz(&mut rng, deg);
            // P(ω²) = F(iω)F(−iω): G(s) = F(s)F(−s) is even; pₖ = (−1)ᵏ g₂ₖ
            let fneg: Vec<f64> = fz
                .iter()
                .enumerate()
                .map(|(k, c)| if k % 2 == 0 { *c } else { -c })
                .collect();
            let g = mul(&fz, &fneg);
            let p: Vec<f64> = (0..=deg)
                .map(|k| if k % 2 == 0 { g[2 * k] } else { -g[2 * k] })
                .collect();
            let (f, resid) = spectral_factor(&p).unwrap();
            assert!(resid <= RESIDUAL, "resid {resid} for {fz:?}");
            assert!(is_hurwitz(&f));
            let scale = fz.iter().map(|c| c.abs()).fold(0.0, f64::max);
            for (a, b) in f.iter().zip(&fz) {
                assert!((a - b).abs() <= FACTORISATION * scale, "{f:?} vs {fz:?}");
            }
        }
    }
}
