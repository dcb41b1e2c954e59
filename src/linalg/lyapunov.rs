//! Continuous and discrete Lyapunov equations.
//!
//! The continuous equation solved here is the **covariance equation**
//!
//! ```text
//! A X + X Aᵀ + Q = 0
//! ```
//!
//! of the linear system dx = A x dt + dW, where W is a Wiener process with incremental covariance
//! E[dW dWᵀ] = Q dt (white noise of intensity Q, i.e. E[w(t) w(t')ᵀ] = Q δ(t − t'), two-sided
//! angular spectral density Q/(2π)). If A is asymptotically stable, X is the stationary covariance
//! E[x xᵀ].
//!
//! **Sign relative to SciPy:** `scipy.linalg.solve_continuous_lyapunov(a, q)` solves
//! A X + X Aᴴ = Q. For real matrices our `solve_continuous_lyapunov(a, q)` equals SciPy's
//! `solve_continuous_lyapunov(a, -q)`.
//!
//! The discrete equation is X = A X Aᵀ + Q, the stationary covariance of x_{k+1} = A x_k + w_k with
//! E[w_k w_kᵀ] = Q (same sign as SciPy's `solve_discrete_lyapunov(a, q)`).
//!
//! The fast solvers use the Bartels–Stewart method on the real Schur form A = U T Uᵀ (T
//! quasi-upper-triangular with 1×1 and 2×2 diagonal blocks), O(n³). The `_dense` variants solve the
//! n²×n² Kronecker system with a fully pivoted LU, O(n⁶): they are independent oracles for tests and
//! small problems (n ≤ ~12).

use crate::error::{Error, Result};
use nalgebra::{Complex, DMatrix, DVector};

/// (U, T, eigenvalues, diagonal blocks (start, size) of T) from [`real_schur`].
pub(crate) type SchurParts = (DMatrix<f64>, DMatrix<f64>, Vec<Complex<f64>>, Vec<(usize, usize)>);

/// Real Schur decomposition A = U T Uᵀ with an iteration limit (nalgebra's default never gives up).
///
/// Returns (U, T, eigenvalues, blocks) where `blocks` lists (start, size) of the diagonal blocks of T
/// and T has been cleaned to be exactly zero below its block diagonal.
pub(crate) fn real_schur(a: &DMatrix<f64>, what: &str) -> Result<SchurParts> {
    let n = a.nrows();
    let max_iter = 200 * n + 200;
    let schur =
        nalgebra::linalg::Schur::try_new(a.clone(), f64::EPSILON, max_iter).ok_or_else(|| Error::Numerical {
            what: what.to_string(),
            reason: format!(
                "the real Schur decomposition (Francis QR) of the {n}x{n} matrix did not converge \
                     in {max_iter} iterations"
            ),
        })?;
    let eig: Vec<Complex<f64>> = schur.complex_eigenvalues().iter().copied().collect();
    let (u, mut t) = schur.unpack();
    if u.iter().chain(t.iter()).any(|v| !v.is_finite()) || eig.iter().any(|z| !z.re.is_finite() || !z.im.is_finite()) {
        return Err(Error::Numerical {
            what: what.to_string(),
            reason: "the real Schur decomposition produced non-finite values".to_string(),
        });
    }
    let mut blocks = Vec::new();
    let mut i = 0;
    while i < n {
        if i + 1 < n && t[(i + 1, i)] != 0.0 {
            if i + 2 < n && t[(i + 2, i + 1)] != 0.0 {
                return Err(Error::Numerical {
                    what: what.to_string(),
                    reason: format!(
                        "the Schur factor is not quasi-triangular (consecutive non-zero subdiagonal \
                         entries at rows {} and {})",
                        i + 1,
                        i + 2
                    ),
                });
            }
            blocks.push((i, 2));
            i += 2;
        } else {
            blocks.push((i, 1));
            i += 1;
        }
    }
    // Exact zeros below the block diagonal.
    for &(s, m) in &blocks {
        for c in s..s + m {
            for r in s + m..n {
                t[(r, c)] = 0.0;
            }
        }
    }
    Ok((u, t, eig, blocks))
}

fn check_square(name: &str, m: &DMatrix<f64>) -> Result<usize> {
    if m.nrows() != m.ncols() {
        return Err(Error::invalid(
            name,
            format!("{}x{} matrix", m.nrows(), m.ncols()),
            "must be square",
        ));
    }
    if m.nrows() == 0 {
        return Err(Error::invalid(name, "0x0 matrix", "must be non-empty"));
    }
    if let Some((k, v)) = m.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(Error::invalid(
            name,
            v,
            format!(
                "all entries must be finite (entry ({}, {}) is not)",
                k % m.nrows(),
                k / m.nrows()
            ),
        ));
    }
    Ok(m.nrows())
}

fn check_pair(a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<usize> {
    let n = check_square("a", a)?;
    let nq = check_square("q", q)?;
    if n != nq {
        return Err(Error::invalid(
            "q",
            format!("{nq}x{nq} matrix"),
            format!("must have the same size as `a` ({n}x{n})"),
        ));
    }
    Ok(n)
}

/// Checks that `q` is symmetric to rounding and returns its symmetric part.
fn symmetric_part(q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let asym = (q - q.transpose()).norm();
    let scale = q.norm();
    if asym > 1e-10 * scale {
        return Err(Error::invalid(
            "q",
            format!("matrix with ‖Q − Qᵀ‖_F/‖Q‖_F = {:e}", asym / scale),
            "must be symmetric (a noise intensity / covariance)",
        ));
    }
    Ok((q + q.transpose()) * 0.5)
}

/// Solves a dense system by fully pivoted LU, returning `None` if it is numerically singular
/// (smallest pivot ≤ ε × largest pivot) or the solution is not finite.
fn solve_small(m: DMatrix<f64>, rhs: DVector<f64>) -> Option<DVector<f64>> {
    let k = m.nrows();
    let lu = nalgebra::linalg::FullPivLU::new(m);
    let u = lu.u();
    let mut umax: f64 = 0.0;
    let mut umin = f64::INFINITY;
    for i in 0..k {
        umax = umax.max(u[(i, i)].abs());
        umin = umin.min(u[(i, i)].abs());
    }
    if umin.is_nan() || umin <= f64::EPSILON * umax {
        return None;
    }
    let x = lu.solve(&rhs)?;
    if x.iter().all(|v| v.is_finite()) {
        Some(x)
    } else {
        None
    }
}

/// The spectral abscissa α(A) = max Re λᵢ(A).
///
/// # Formula
/// α(A) = maxᵢ Re λᵢ, with the eigenvalues λᵢ from the real Schur form. The system ẋ = A x is
/// asymptotically stable iff α(A) < 0.
///
/// # Errors
/// [`Error::InvalidParameter`] if `a` is not square, empty or has non-finite entries;
/// [`Error::Numerical`] if the eigenvalue iteration does not converge.
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::spectral_abscissa;
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.4]); // ω = 2, ζ = 0.1
/// assert!((spectral_abscissa(&a).unwrap() + 0.2).abs() < 1e-12);
/// ```
pub fn spectral_abscissa(a: &DMatrix<f64>) -> Result<f64> {
    check_square("a", a)?;
    let (_, _, eig, _) = real_schur(a, "spectral_abscissa")?;
    Ok(eig.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max))
}

/// The spectral radius ρ(A) = max |λᵢ(A)|.
///
/// # Formula
/// ρ(A) = maxᵢ |λᵢ|. The discrete system x_{k+1} = A x_k is asymptotically stable iff ρ(A) < 1.
///
/// # Errors
/// As [`spectral_abscissa`].
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::spectral_radius;
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, -0.25, 1.0, 0.0]); // λ = ±0.5i
/// assert!((spectral_radius(&a).unwrap() - 0.5).abs() < 1e-12);
/// ```
pub fn spectral_radius(a: &DMatrix<f64>) -> Result<f64> {
    check_square("a", a)?;
    let (_, _, eig, _) = real_schur(a, "spectral_radius")?;
    Ok(eig.iter().map(|z| z.norm()).fold(0.0, f64::max))
}

/// Whether ẋ = A x is asymptotically stable (all eigenvalues with Re λ < 0).
///
/// # Formula
/// Returns `true` iff α(A) < −64·n·ε·‖A‖_F, i.e. the spectral abscissa is negative by more than the
/// rounding error of the computed eigenvalues. Returns `false` (never panics) for non-square, empty
/// or non-finite input and if the eigenvalue iteration fails.
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::is_stable;
/// assert!(is_stable(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -0.1])));
/// assert!(!is_stable(&DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0])));
/// ```
pub fn is_stable(a: &DMatrix<f64>) -> bool {
    match spectral_abscissa(a) {
        Ok(alpha) => alpha < -stability_margin(a),
        Err(_) => false,
    }
}

fn stability_margin(a: &DMatrix<f64>) -> f64 {
    64.0 * a.nrows() as f64 * f64::EPSILON * a.norm()
}

/// Solves the continuous Lyapunov (covariance) equation A X + X Aᵀ + Q = 0 by Bartels–Stewart.
///
/// # Formula
/// With the real Schur form A = U T Uᵀ, put C = Uᵀ Q U and Y = Uᵀ X U; then T Y + Y Tᵀ = −C is
/// solved block by block (diagonal blocks of T of size 1 or 2) from the bottom-right corner:
///
/// ```text
/// T_ii Y_ij + Y_ij T_jjᵀ = −C_ij − Σ_{k>i} T_ik Y_kj − Σ_{l>j} Y_il T_jlᵀ
/// ```
///
/// each a 1, 2 or 4 unknown linear system (I ⊗ T_ii + T_jj ⊗ I) vec Y_ij = vec RHS. Finally
/// X = U Y Uᵀ, symmetrised. For stable A, X = ∫₀^∞ e^{At} Q e^{Aᵀt} dt is the stationary covariance
/// of dx = A x dt + dW, E[dW dWᵀ] = Q dt. Relation to SciPy: this is
/// `scipy.linalg.solve_continuous_lyapunov(a, -q)`.
///
/// # Errors
/// * [`Error::InvalidParameter`] if `a` or `q` is not square, empty, non-finite, of different sizes,
///   or `q` is not symmetric (relative asymmetry above 1e-10).
/// * [`Error::Numerical`] if A is not asymptotically stable (some Re λ ≥ −64 n ε ‖A‖_F; for
///   λᵢ + λⱼ ≈ 0 the equation is singular, and for unstable A the solution is not a covariance), or
///   the Schur iteration fails.
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::solve_continuous_lyapunov;
/// // Single-degree-of-freedom oscillator driven by white noise of intensity q on the velocity:
/// // X = diag(q/(4ζω³), q/(4ζω)).
/// let (w, z, q) = (2.0, 0.05, 3.0);
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * z * w]);
/// let qm = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, q]);
/// let x = solve_continuous_lyapunov(&a, &qm).unwrap();
/// assert!((x[(0, 0)] - q / (4.0 * z * w.powi(3))).abs() < 1e-12 * x[(0, 0)]);
/// assert!((x[(1, 1)] - q / (4.0 * z * w)).abs() < 1e-12 * x[(1, 1)]);
/// assert!(x[(0, 1)].abs() < 1e-12);
/// ```
pub fn solve_continuous_lyapunov(a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    check_pair(a, q)?;
    BalancedLyapunov::new(a)?.solve(a, q)
}

/// [`solve_continuous_lyapunov`] for several right-hand sides with one A: A Xₖ + Xₖ Aᵀ + Qₖ = 0, the
/// balancing and the Schur form of A computed once (the sensitivities of a Lyapunov solution solve with
/// the same A as the solution itself, and their right-hand sides need the solution). Each Xₖ is the one
/// [`solve_continuous_lyapunov`] gives.
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::{solve_continuous_lyapunov, LyapunovSolver};
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.2]);
/// let q1 = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, 3.0]);
/// let q2 = DMatrix::from_row_slice(2, 2, &[1.0, 0.5, 0.5, 2.0]);
/// let solver = LyapunovSolver::new(&a).unwrap();
/// assert_eq!(solver.solve(&q1).unwrap(), solve_continuous_lyapunov(&a, &q1).unwrap());
/// assert_eq!(solver.solve(&q2).unwrap(), solve_continuous_lyapunov(&a, &q2).unwrap());
/// ```
#[derive(Debug)]
pub struct LyapunovSolver {
    a: DMatrix<f64>,
    inner: BalancedLyapunov,
}

impl LyapunovSolver {
    /// Balances `a` and computes its Schur form.
    ///
    /// # Errors
    /// As [`solve_continuous_lyapunov`] for A (not square, not finite, not asymptotically stable).
    pub fn new(a: &DMatrix<f64>) -> Result<Self> {
        check_square("a", a)?;
        Ok(LyapunovSolver {
            a: a.clone(),
            inner: BalancedLyapunov::new(a)?,
        })
    }

    /// X of A X + X Aᵀ + Q = 0.
    ///
    /// # Errors
    /// As [`solve_continuous_lyapunov`] for Q (shape, symmetry, finiteness).
    pub fn solve(&self, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
        check_pair(&self.a, q)?;
        self.inner.solve(&self.a, q)
    }
}

/// The balancing and Schur form of one A for [`solve_continuous_lyapunov`].
#[derive(Debug)]
struct BalancedLyapunov {
    d: Vec<f64>,
    schur: LyapunovSchur,
}

impl BalancedLyapunov {
    // Badly scaled models (positions in m next to momenta in kg m/s, filter poles at 1e3 rad/s) make the
    // backward-stable Bartels–Stewart solution inaccurate in its small entries. Balance A by a diagonal
    // similarity of powers of two (exact in floating point), solve, scale back, then refine once with the
    // residual: A E + E Aᵀ + R = 0, X ← X + E.
    fn new(a: &DMatrix<f64>) -> Result<Self> {
        let d = balance_diagonal(a);
        let n = a.nrows();
        let ab = DMatrix::from_fn(n, n, |i, j| a[(i, j)] * d[j] / d[i]);
        // The Schur form of the balanced A is computed once and reused by the refinement steps.
        Ok(BalancedLyapunov {
            schur: LyapunovSchur::new(&ab)?,
            d,
        })
    }

    /// X of A X + X Aᵀ + Q = 0 (`a` the matrix this was made of, `q` checked against it).
    fn solve(&self, a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
        let (d, schur, n) = (&self.d, &self.schur, a.nrows());
        let scale_q = |m: &DMatrix<f64>| DMatrix::from_fn(n, n, |i, j| m[(i, j)] / (d[i] * d[j]));
        let unscale = |m: &DMatrix<f64>| DMatrix::from_fn(n, n, |i, j| m[(i, j)] * d[i] * d[j]);
        let mut x = unscale(&schur.solve(&scale_q(q))?);
        let abs_a = a.abs();
        let abs_q = q.abs();
        for _ in 0..2 {
            let r = a * &x + &x * a.transpose() + q;
            let r = (&r + r.transpose()) * 0.5;
            // Skip the refinement when every residual entry is at the rounding level of its own computation
            // (|R| ≤ γ (|A||X| + |X||Aᵀ| + |Q|) entrywise, γ = (n + 2)·ε): a correction would be noise.
            let ax = &abs_a * x.abs();
            let gamma = (n + 2) as f64 * f64::EPSILON;
            let at_rounding =
                (0..n).all(|i| (0..n).all(|j| r[(i, j)].abs() <= gamma * (ax[(i, j)] + ax[(j, i)] + abs_q[(i, j)])));
            if at_rounding {
                break;
            }
            let e = unscale(&schur.solve(&scale_q(&r))?);
            x += e;
        }
        Ok((&x + x.transpose()) * 0.5)
    }
}

/// Osborne/Parlett–Reinsch balancing: diagonal D (powers of two) such that D⁻¹AD has rows and columns of
/// comparable norm.
pub(crate) fn balance_diagonal(a: &DMatrix<f64>) -> Vec<f64> {
    let n = a.nrows();
    let mut d = vec![1.0f64; n];
    for _ in 0..100 {
        let mut converged = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in 0..n {
                if j != i {
                    c += (a[(j, i)] * d[i] / d[j]).abs();
                    r += (a[(i, j)] * d[j] / d[i]).abs();
                }
            }
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let mut f = 1.0;
            let (mut cc, mut rr) = (c, r);
            while cc < rr / 2.0 {
                cc *= 2.0;
                rr /= 2.0;
                f *= 2.0;
            }
            while cc > rr * 2.0 {
                cc /= 2.0;
                rr *= 2.0;
                f /= 2.0;
            }
            if (cc + rr) < 0.95 * (c + r) {
                converged = false;
                d[i] *= f;
            }
        }
        if converged {
            break;
        }
    }
    d
}

/// The real Schur form of a stable A, factored once for [`LyapunovSchur::solve`].
#[derive(Debug)]
struct LyapunovSchur {
    u: DMatrix<f64>,
    t: DMatrix<f64>,
    blocks: Vec<(usize, usize)>,
}

const WHAT: &str = "solve_continuous_lyapunov";

impl LyapunovSchur {
    /// Schur form and stability check of `a` (square, finite).
    fn new(a: &DMatrix<f64>) -> Result<Self> {
        let (u, t, eig, blocks) = real_schur(a, WHAT)?;
        let alpha = eig.iter().map(|z| z.re).fold(f64::NEG_INFINITY, f64::max);
        let margin = stability_margin(a);
        if alpha >= -margin {
            return Err(Error::Numerical {
                what: WHAT.to_string(),
                reason: format!(
                    "A is not asymptotically stable: max Re λ = {alpha:e} (must be < {:e}); the \
                     covariance equation has no (positive semi-definite) solution, and it is singular \
                     when λᵢ + λⱼ = 0 for some eigenvalue pair",
                    -margin
                ),
            });
        }
        Ok(LyapunovSchur { u, t, blocks })
    }

    /// Solves A X + X Aᵀ + Q = 0 for a symmetric `q` (checked) with the stored Schur form.
    fn solve(&self, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
        let (u, t, blocks) = (&self.u, &self.t, &self.blocks);
        let n = t.nrows();
        let qs = symmetric_part(q)?;
        let c = u.transpose() * &qs * u;
        let mut y = DMatrix::<f64>::zeros(n, n);
        for &(i0, mi) in blocks.iter().rev() {
            let ie = i0 + mi;
            for &(j0, mj) in blocks.iter().rev() {
                let je = j0 + mj;
                // RHS = −C_ij − Σ_{k ≥ ie} T_ik Y_kj − Σ_{l ≥ je} Y_il T_jlᵀ, vec'd column-major (a + mi·b)
                let mut rhs = [0.0f64; 4];
                let mut k = [[0.0f64; 4]; 4];
                for b in 0..mj {
                    for a in 0..mi {
                        let (i, j) = (i0 + a, j0 + b);
                        let mut v = -c[(i, j)];
                        for kk in ie..n {
                            v -= t[(i, kk)] * y[(kk, j)];
                        }
                        for l in je..n {
                            v -= y[(i, l)] * t[(j, l)];
                        }
                        rhs[a + mi * b] = v;
                        // (I ⊗ T_ii + T_jj ⊗ I) vec Y_ij
                        for b2 in 0..mj {
                            for a2 in 0..mi {
                                let mut e = 0.0;
                                if b == b2 {
                                    e += t[(i0 + a, i0 + a2)];
                                }
                                if a == a2 {
                                    e += t[(j0 + b, j0 + b2)];
                                }
                                k[a + mi * b][a2 + mi * b2] = e;
                            }
                        }
                    }
                }
                if !solve_block(&mut k, &mut rhs, mi * mj) {
                    return Err(Error::Numerical {
                        what: WHAT.to_string(),
                        reason: format!(
                            "singular {}x{} block Sylvester system at Schur blocks ({i0}, {j0}): \
                         λᵢ + λⱼ ≈ 0",
                            mi * mj,
                            mi * mj
                        ),
                    });
                }
                for b in 0..mj {
                    for a in 0..mi {
                        y[(i0 + a, j0 + b)] = rhs[a + mi * b];
                    }
                }
            }
        }
        let x = u * y * u.transpose();
        let x = (&x + x.transpose()) * 0.5;
        finite_or_err(x, WHAT)
    }
}

/// Solves the m × m (m ≤ 4) system `k` x = `rhs` in place (x in `rhs`) by Gaussian elimination with
/// full pivoting on the stack; false when it is numerically singular (smallest pivot ≤ ε × largest
/// pivot, as [`solve_small`]) or the solution is not finite.
#[allow(clippy::needless_range_loop)] // index arithmetic on a small dense block
fn solve_block(k: &mut [[f64; 4]; 4], rhs: &mut [f64; 4], m: usize) -> bool {
    let mut col = [0usize, 1, 2, 3];
    let (mut umax, mut umin) = (0.0f64, f64::INFINITY);
    for p in 0..m {
        let (mut pr, mut pc, mut best) = (p, p, -1.0);
        for r in p..m {
            for c in p..m {
                if k[r][c].abs() > best {
                    (pr, pc, best) = (r, c, k[r][c].abs());
                }
            }
        }
        k.swap(p, pr);
        rhs.swap(p, pr);
        if pc != p {
            for row in k.iter_mut() {
                row.swap(p, pc);
            }
            col.swap(p, pc);
        }
        umax = umax.max(best);
        umin = umin.min(best);
        if best == 0.0 || best.is_nan() {
            return false;
        }
        for r in p + 1..m {
            let f = k[r][p] / k[p][p];
            for c in p + 1..m {
                k[r][c] -= f * k[p][c];
            }
            rhs[r] -= f * rhs[p];
        }
    }
    if umin <= f64::EPSILON * umax {
        return false;
    }
    let mut x = [0.0f64; 4];
    for p in (0..m).rev() {
        let mut v = rhs[p];
        for c in p + 1..m {
            v -= k[p][c] * x[c];
        }
        x[p] = v / k[p][p];
    }
    for p in 0..m {
        rhs[col[p]] = x[p];
    }
    rhs[..m].iter().all(|v| v.is_finite())
}

fn finite_or_err(x: DMatrix<f64>, what: &str) -> Result<DMatrix<f64>> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(x)
    } else {
        Err(Error::Numerical {
            what: what.to_string(),
            reason: "the solution overflowed (the equation is too ill-conditioned)".to_string(),
        })
    }
}

/// Dense Kronecker-product oracle for A X + X Aᵀ + Q = 0 (any size, intended for n ≤ ~12).
///
/// # Formula
/// With column-major vec, vec(A X) = (I ⊗ A) vec X and vec(X Aᵀ) = (A ⊗ I) vec X, so
///
/// ```text
/// (I ⊗ A + A ⊗ I) vec X = −vec Q,
/// ```
///
/// solved with a fully pivoted LU (O(n⁶) work, n⁴ memory). No stability check and no symmetry
/// requirement on Q: it solves the linear equation whenever it is uniquely solvable (λᵢ + λⱼ ≠ 0).
///
/// # Errors
/// [`Error::InvalidParameter`] for non-square, empty, non-finite or mismatched input;
/// [`Error::Numerical`] if the Kronecker matrix is numerically singular.
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::{solve_continuous_lyapunov, solve_continuous_lyapunov_dense};
/// let a = DMatrix::from_row_slice(3, 3, &[-3.0, -2.0, 0.0, -1.0, -1.0, 0.0, 0.0, -5.0, -1.0]);
/// let q = DMatrix::identity(3, 3);
/// let x1 = solve_continuous_lyapunov(&a, &q).unwrap();
/// let x2 = solve_continuous_lyapunov_dense(&a, &q).unwrap();
/// assert!((x1 - x2).norm() < 1e-12);
/// ```
pub fn solve_continuous_lyapunov_dense(a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let n = check_pair(a, q)?;
    let id = DMatrix::<f64>::identity(n, n);
    let k = id.kronecker(a) + a.kronecker(&id);
    let rhs = -DVector::from_column_slice(q.as_slice());
    let sol = solve_small(k, rhs).ok_or_else(|| Error::Numerical {
        what: "solve_continuous_lyapunov_dense".to_string(),
        reason: "the Kronecker matrix I⊗A + A⊗I is singular (λᵢ + λⱼ ≈ 0 for some eigenvalues of A)".to_string(),
    })?;
    finite_or_err(
        DMatrix::from_column_slice(n, n, sol.as_slice()),
        "solve_continuous_lyapunov_dense",
    )
}

/// Solves the discrete Lyapunov (Stein) equation X = A X Aᵀ + Q by a Schur method.
///
/// # Formula
/// X is the stationary covariance of x_{k+1} = A x_k + w_k, E[w_k w_kᵀ] = Q:
/// X = Σ_{k≥0} Aᵏ Q (Aᵀ)ᵏ. With A = U T Uᵀ, C = Uᵀ Q U, Y = Uᵀ X U the equation becomes
/// Y = T Y Tᵀ + C and is solved block by block from the bottom-right corner (Barraud's method):
///
/// ```text
/// Y_ij − T_ii Y_ij T_jjᵀ = C_ij + Σ_{k>i} T_ik W_kj + T_ii Σ_{l>j} Y_il T_jlᵀ,   W = Y Tᵀ,
/// ```
///
/// each a system (I − T_jj ⊗ T_ii) vec Y_ij = vec RHS of size 1, 2 or 4; O(n³) in total. Then
/// X = U Y Uᵀ, symmetrised. Same sign convention as SciPy's `solve_discrete_lyapunov(a, q)`.
///
/// # Errors
/// * [`Error::InvalidParameter`] as for [`solve_continuous_lyapunov`].
/// * [`Error::Numerical`] if A is not Schur-stable (ρ(A) ≥ 1 − 64 n ε ‖A‖_F; the equation is
///   singular when λᵢ λⱼ = 1) or the Schur iteration fails.
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::solve_discrete_lyapunov;
/// // AR(1): x_{k+1} = φ x_k + w_k, Var w = s² → Var x = s²/(1 − φ²).
/// let a = DMatrix::from_element(1, 1, 0.9);
/// let q = DMatrix::from_element(1, 1, 2.0);
/// let x = solve_discrete_lyapunov(&a, &q).unwrap();
/// assert!((x[(0, 0)] - 2.0 / (1.0 - 0.81)).abs() < 1e-12);
/// ```
pub fn solve_discrete_lyapunov(a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    const WHAT: &str = "solve_discrete_lyapunov";
    let n = check_pair(a, q)?;
    let qs = symmetric_part(q)?;
    let (u, t, eig, blocks) = real_schur(a, WHAT)?;
    let rho = eig.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let margin = stability_margin(a);
    if rho >= 1.0 - margin {
        return Err(Error::Numerical {
            what: WHAT.to_string(),
            reason: format!(
                "A is not Schur-stable: spectral radius {rho} (must be < 1 − {margin:e}); the \
                 stationary covariance does not exist, and the equation is singular when λᵢ λⱼ = 1"
            ),
        });
    }
    let c = u.transpose() * &qs * &u;
    let mut y = DMatrix::<f64>::zeros(n, n);
    let mut w = DMatrix::<f64>::zeros(n, n); // rows filled as block rows of Y are completed
    for &(i0, mi) in blocks.iter().rev() {
        let ie = i0 + mi;
        let tii = t.view((i0, i0), (mi, mi)).clone_owned();
        for &(j0, mj) in blocks.iter().rev() {
            let je = j0 + mj;
            let mut rhs = c.view((i0, j0), (mi, mj)).clone_owned();
            if ie < n {
                rhs += t.view((i0, ie), (mi, n - ie)) * w.view((ie, j0), (n - ie, mj));
            }
            if je < n {
                let s = y.view((i0, je), (mi, n - je)) * t.view((j0, je), (mj, n - je)).transpose();
                rhs += &tii * s;
            }
            let tjj = t.view((j0, j0), (mj, mj)).clone_owned();
            let k = DMatrix::<f64>::identity(mi * mj, mi * mj) - tjj.kronecker(&tii);
            let v = DVector::from_column_slice(rhs.as_slice());
            let sol = solve_small(k, v).ok_or_else(|| Error::Numerical {
                what: WHAT.to_string(),
                reason: format!(
                    "singular {}x{} block Stein system at Schur blocks ({i0}, {j0}): λᵢ λⱼ ≈ 1",
                    mi * mj,
                    mi * mj
                ),
            })?;
            y.view_mut((i0, j0), (mi, mj)).copy_from_slice(sol.as_slice());
        }
        let wrow = y.view((i0, 0), (mi, n)) * t.transpose();
        w.view_mut((i0, 0), (mi, n)).copy_from(&wrow);
    }
    let x = &u * y * u.transpose();
    let x = (&x + x.transpose()) * 0.5;
    finite_or_err(x, WHAT)
}

/// Dense Kronecker-product oracle for X = A X Aᵀ + Q (intended for n ≤ ~12).
///
/// # Formula
/// vec(A X Aᵀ) = (A ⊗ A) vec X, so (I − A ⊗ A) vec X = vec Q, solved with a fully pivoted LU.
/// No stability check and no symmetry requirement on Q.
///
/// # Errors
/// [`Error::InvalidParameter`] for non-square, empty, non-finite or mismatched input;
/// [`Error::Numerical`] if I − A ⊗ A is numerically singular (λᵢ λⱼ ≈ 1).
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::{solve_discrete_lyapunov, solve_discrete_lyapunov_dense};
/// let a = DMatrix::from_row_slice(2, 2, &[0.5, 0.4, -0.3, 0.2]);
/// let q = DMatrix::from_row_slice(2, 2, &[1.0, 0.2, 0.2, 2.0]);
/// let x1 = solve_discrete_lyapunov(&a, &q).unwrap();
/// let x2 = solve_discrete_lyapunov_dense(&a, &q).unwrap();
/// assert!((x1 - x2).norm() < 1e-12);
/// ```
pub fn solve_discrete_lyapunov_dense(a: &DMatrix<f64>, q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let n = check_pair(a, q)?;
    let k = DMatrix::<f64>::identity(n * n, n * n) - a.kronecker(a);
    let rhs = DVector::from_column_slice(q.as_slice());
    let sol = solve_small(k, rhs).ok_or_else(|| Error::Numerical {
        what: "solve_discrete_lyapunov_dense".to_string(),
        reason: "the Kronecker matrix I − A⊗A is singular (λᵢ λⱼ ≈ 1 for some eigenvalues of A)".to_string(),
    })?;
    finite_or_err(
        DMatrix::from_column_slice(n, n, sol.as_slice()),
        "solve_discrete_lyapunov_dense",
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::poly::test_rng::Rng;
    use crate::tolerance::{FACTORISATION, RESIDUAL, ROUNDING, SMALL_DECOMPOSITION};

    fn residual_c(a: &DMatrix<f64>, q: &DMatrix<f64>, x: &DMatrix<f64>) -> f64 {
        let r = a * x + x * a.transpose() + q;
        r.norm() / (2.0 * a.norm() * x.norm() + q.norm())
    }

    fn residual_d(a: &DMatrix<f64>, q: &DMatrix<f64>, x: &DMatrix<f64>) -> f64 {
        let r = a * x * a.transpose() + q - x;
        r.norm() / (a.norm().powi(2) * x.norm() + q.norm() + x.norm())
    }

    fn random_matrix(rng: &mut Rng, n: usize) -> DMatrix<f64> {
        DMatrix::from_fn(n, n, |_, _| rng.range(-1.0, 1.0))
    }

    fn random_spd(rng: &mut Rng, n: usize) -> DMatrix<f64> {
        let g = random_matrix(rng, n);
        &g * g.transpose() + DMatrix::identity(n, n) * 0.1
    }

    /// A = M − (ρ(M) + 1) I: stable with spectral abscissa ≤ −1 (ρ from nalgebra's eigenvalues).
    fn random_stable(rng: &mut Rng, n: usize) -> DMatrix<f64> {
        let m = random_matrix(rng, n);
        let rho = m.complex_eigenvalues().iter().map(|z| z.norm()).fold(0.0, f64::max);
        m - DMatrix::identity(n, n) * (rho + 1.0)
    }

    #[test]
    fn scipy_example() {
        // scipy.linalg.solve_continuous_lyapunov docs: a = [[-3,-2,0],[-1,-1,0],[0,-5,-1]],
        // b = eye(3), checks a @ x + x @ a.H == b. Ours solves A X + X Aᵀ + Q = 0, so with Q = I the
        // solution is minus SciPy's; verified by the Kronecker oracle and the residual.
        let a = DMatrix::from_row_slice(3, 3, &[-3.0, -2.0, 0.0, -1.0, -1.0, 0.0, 0.0, -5.0, -1.0]);
        let q = DMatrix::<f64>::identity(3, 3);
        let x = solve_continuous_lyapunov(&a, &q).unwrap();
        let xd = solve_continuous_lyapunov_dense(&a, &q).unwrap();
        assert!((&x - &xd).norm() <= SMALL_DECOMPOSITION * xd.norm());
        assert!((&a * &x + &x * a.transpose() + &q).norm() < RESIDUAL);
        // SciPy's solution of A X + X Aᵀ = Q is −X.
        let xs = -&x;
        assert!((&a * &xs + &xs * a.transpose() - &q).norm() < RESIDUAL);
        // covariance: symmetric positive definite
        assert!(x.clone().symmetric_eigenvalues().iter().all(|&l| l > 0.0));
    }

    #[test]
    fn scalar_and_sdof_closed_forms() {
        // 1×1: −a x − x a + q = 0 ⇒ x = q/(2a)
        for &(aa, qq) in &[(1.0, 1.0), (0.01, 3.0), (250.0, 0.5)] {
            let x =
                solve_continuous_lyapunov(&DMatrix::from_element(1, 1, -aa), &DMatrix::from_element(1, 1, qq)).unwrap();
            assert!((x[(0, 0)] - qq / (2.0 * aa)).abs() <= ROUNDING * qq / (2.0 * aa));
        }
        // SDOF oscillator A = [[0,1],[−ω²,−2ζω]], Q = diag(0, q): the (0,1) entry of the equation
        // gives x22 = ω² x11, the (1,1) entry −4ζω x22 + q = 0, so X = diag(q/(4ζω³), q/(4ζω)).
        // For ζ < 1 the eigenvalues are complex: a 2×2 Schur block.
        for &(w, z, q) in &[(2.0, 0.05, 3.0), (10.0, 0.3, 1.0), (0.5, 0.01, 2.0), (3.0, 1.5, 1.0)] {
            let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * z * w]);
            let qm = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, q]);
            let x = solve_continuous_lyapunov(&a, &qm).unwrap();
            let x11 = q / (4.0 * z * w * w * w);
            let x22 = q / (4.0 * z * w);
            assert!((x[(0, 0)] - x11).abs() <= SMALL_DECOMPOSITION * x11);
            assert!((x[(1, 1)] - x22).abs() <= SMALL_DECOMPOSITION * x22);
            assert!(x[(0, 1)].abs() <= SMALL_DECOMPOSITION * x22 && x[(1, 0)] == x[(0, 1)]);
        }
    }

    #[test]
    fn complex_blocks_explicit() {
        // Block-diagonal rotations (pure 2×2 blocks) mixed by a random similarity.
        let mut rng = Rng::new(5);
        for n in [2usize, 4, 6, 7, 9] {
            let mut d = DMatrix::<f64>::zeros(n, n);
            let mut i = 0;
            while i < n {
                if i + 1 < n {
                    let (s, w) = (rng.range(0.05, 1.0), rng.range(0.5, 5.0));
                    d[(i, i)] = -s;
                    d[(i + 1, i + 1)] = -s;
                    d[(i, i + 1)] = w;
                    d[(i + 1, i)] = -w;
                    i += 2;
                } else {
                    d[(i, i)] = -rng.range(0.1, 2.0);
                    i += 1;
                }
            }
            let s = random_matrix(&mut rng, n) + DMatrix::identity(n, n) * 2.0;
            let a = &s * d * s.clone().try_inverse().unwrap();
            let (_, _, eig, blocks) = real_schur(&a, "test").unwrap();
            assert!(eig.iter().filter(|z| z.im != 0.0).count() >= 2 * (n / 2));
            assert!(blocks.iter().filter(|b| b.1 == 2).count() == n / 2);
            let q = random_spd(&mut rng, n);
            let x = solve_continuous_lyapunov(&a, &q).unwrap();
            assert!(residual_c(&a, &q, &x) < RESIDUAL, "n={n}");
            let xd = solve_continuous_lyapunov_dense(&a, &q).unwrap();
            assert!((&x - &xd).norm() <= FACTORISATION * xd.norm(), "n={n}");
        }
    }

    #[test]
    fn random_stable_up_to_30() {
        let mut rng = Rng::new(42);
        for n in 1..=30 {
            for _ in 0..3 {
                let a = random_stable(&mut rng, n);
                let q = random_spd(&mut rng, n);
                let x = solve_continuous_lyapunov(&a, &q).unwrap();
                let r = residual_c(&a, &q, &x);
                assert!(r <= RESIDUAL, "n={n} residual {r:e}");
                assert_eq!(x, x.transpose());
                if n <= 10 {
                    let xd = solve_continuous_lyapunov_dense(&a, &q).unwrap();
                    assert!((&x - &xd).norm() <= SMALL_DECOMPOSITION * xd.norm(), "n={n}");
                }
                // covariance of a stable system with Q > 0 is positive definite
                let lmin = x.clone().symmetric_eigenvalues().min();
                assert!(lmin > 0.0, "n={n}");
            }
        }
    }

    #[test]
    fn rejects_unstable_singular_and_bad_shapes() {
        let q = DMatrix::<f64>::identity(2, 2);
        let unstable = DMatrix::from_row_slice(2, 2, &[0.1, 1.0, -1.0, 0.1]);
        let marginal = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]); // λ = ±i, λ₁+λ₂ = 0
        let zero = DMatrix::<f64>::zeros(2, 2);
        let mixed = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, 1.0]); // λ₁ + λ₂ = 0
        for a in [&unstable, &marginal, &zero, &mixed] {
            assert!(matches!(solve_continuous_lyapunov(a, &q), Err(Error::Numerical { .. })));
            assert!(!is_stable(a));
        }
        assert!(solve_continuous_lyapunov_dense(&marginal, &q).is_err());
        assert!(solve_continuous_lyapunov_dense(&mixed, &q).is_err());
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -2.0]);
        assert!(is_stable(&a));
        assert!(solve_continuous_lyapunov(&a, &DMatrix::identity(3, 3)).is_err());
        assert!(solve_continuous_lyapunov(&DMatrix::zeros(2, 3), &q).is_err());
        assert!(solve_continuous_lyapunov(&DMatrix::zeros(0, 0), &DMatrix::zeros(0, 0)).is_err());
        let mut bad = a.clone();
        bad[(0, 1)] = f64::NAN;
        assert!(solve_continuous_lyapunov(&bad, &q).is_err());
        assert!(!is_stable(&bad));
        let nonsym = DMatrix::from_row_slice(2, 2, &[1.0, 0.5, 0.0, 1.0]);
        assert!(matches!(
            solve_continuous_lyapunov(&a, &nonsym),
            Err(Error::InvalidParameter { .. })
        ));
        assert!(solve_discrete_lyapunov(&DMatrix::identity(2, 2), &q).is_err());
        assert!(solve_discrete_lyapunov(&(DMatrix::identity(2, 2) * 1.5), &q).is_err());
        assert!(solve_discrete_lyapunov_dense(&DMatrix::identity(2, 2), &q).is_err());
        assert!(spectral_abscissa(&DMatrix::zeros(2, 3)).is_err());
    }

    #[test]
    fn discrete_lyapunov() {
        // AR(1)
        let x =
            solve_discrete_lyapunov(&DMatrix::from_element(1, 1, -0.95), &DMatrix::from_element(1, 1, 1.0)).unwrap();
        assert!((x[(0, 0)] - 1.0 / (1.0 - 0.9025)).abs() < SMALL_DECOMPOSITION * x[(0, 0)]);
        // rotation-contraction (2×2 complex block): A = r R(θ) ⇒ A X Aᵀ = r² X for X = c I,
        // so X = q/(1 − r²) I.
        let (r, th) = (0.9_f64, 0.7_f64);
        let a = DMatrix::from_row_slice(2, 2, &[r * th.cos(), -r * th.sin(), r * th.sin(), r * th.cos()]);
        let x = solve_discrete_lyapunov(&a, &(DMatrix::identity(2, 2) * 2.0)).unwrap();
        let expect = DMatrix::<f64>::identity(2, 2) * (2.0 / (1.0 - r * r));
        assert!((x - &expect).norm() < SMALL_DECOMPOSITION * expect.norm());
        // random Schur-stable matrices
        let mut rng = Rng::new(77);
        for n in 1..=25 {
            let m = random_matrix(&mut rng, n);
            let rho = m.complex_eigenvalues().iter().map(|z| z.norm()).fold(0.0, f64::max);
            let a = m * (rng.range(0.3, 0.97) / rho);
            let q = random_spd(&mut rng, n);
            let x = solve_discrete_lyapunov(&a, &q).unwrap();
            let res = residual_d(&a, &q, &x);
            assert!(res <= RESIDUAL, "n={n} residual {res:e}");
            if n <= 10 {
                let xd = solve_discrete_lyapunov_dense(&a, &q).unwrap();
                assert!((&x - &xd).norm() <= FACTORISATION * xd.norm(), "n={n}");
            }
            assert!(x.clone().symmetric_eigenvalues().min() > 0.0);
        }
    }

    #[test]
    fn discretisation_consistency() {
        // The exact discretisation of dx = A x dt + dW over step h has Φ = e^{Ah} and
        // Q_d = ∫₀ʰ e^{As} Q e^{Aᵀs} ds = X − Φ X Φᵀ (X the continuous covariance); the discrete
        // Lyapunov solution with (Φ, Q_d) must reproduce X.
        let mut rng = Rng::new(3);
        for n in [2usize, 5, 8] {
            let a = random_stable(&mut rng, n);
            let q = random_spd(&mut rng, n);
            let x = solve_continuous_lyapunov(&a, &q).unwrap();
            let phi = (&a * 0.1).exp();
            let qd = &x - &phi * &x * phi.transpose();
            let xd = solve_discrete_lyapunov(&phi, &qd).unwrap();
            assert!((&xd - &x).norm() <= FACTORISATION * x.norm(), "n={n}");
        }
    }

    #[test]
    fn spectral_helpers() {
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -4.0, -0.4]);
        assert!((spectral_abscissa(&a).unwrap() + 0.2).abs() < SMALL_DECOMPOSITION);
        assert!((spectral_radius(&a).unwrap() - 2.0).abs() < SMALL_DECOMPOSITION);
    }
}
