//! The continuous Lyapunov equation of a small system (n ≤ [`SMALL_LYAPUNOV_MAX_STATES`]) with one LU
//! factorisation of its vectorised symmetric form, reused for many right-hand sides: the solution P and
//! every sensitivity dP of an optimisation point (each solves with the same A).
//!
//! The general solver ([`LyapunovSolver`](super::LyapunovSolver), Bartels–Stewart on a real Schur form)
//! stays the reference: [`SmallLyapunov::factor`] declines (returns `false`) where the small form is not
//! to be trusted, and the caller then takes the general path.

use nalgebra::{Cholesky, DMatrix, DVector, LU};

/// Largest number of states of the small path: n(n + 1)/2 = 36 unknowns.
pub const SMALL_LYAPUNOV_MAX_STATES: usize = 8;

/// Largest condition estimate κ (see [`SmallLyapunov::factor`]) the small path accepts: its solutions then
/// differ from the general solver's by at most about p(n)·κ·ε ≈ 10⁻⁹ relative; beyond it (nearly unstable
/// or badly scaled systems) the general solver is used.
pub const SMALL_LYAPUNOV_MAX_CONDITION: f64 = 1e6;

/// A P + P Aᵀ + Q = 0 for symmetric Q, by an LU factorisation of the n(n+1)/2 × n(n+1)/2 matrix of
/// X ↦ A X + X Aᵀ on symmetric X, with storage kept between factorisations.
///
/// # Formula
/// A is first balanced by a diagonal similarity of powers of two, A_b = D⁻¹ A D (exact; the general solver's
/// balancing), Q_b = D⁻¹ Q D⁻¹, P = D P_b D. The unknowns are the entries p_ij, i ≤ j, of P_b; equation
/// (i, j), i ≤ j, reads Σ_k a_ik p_kj + Σ_k p_ik a_jk = −q_ij. Each solve is followed by one step of
/// iterative refinement with the residual of the vectorised system (Skeel 1980, "Iterative refinement
/// implies numerical stability for Gaussian elimination", Math. Comp. 35, 817–832).
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::SmallLyapunov;
/// // SDOF oscillator, white force of intensity q: P = diag(q/(4ζω³), q/(4ζω))
/// let (w, z, q) = (2.0, 0.05, 3.0);
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * z * w]);
/// let qm = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, q]);
/// let mut s = SmallLyapunov::default();
/// assert!(s.factor(&a));
/// let mut p = DMatrix::zeros(2, 2);
/// assert!(s.solve(&qm, &mut p));
/// assert!((p[(0, 0)] - q / (4.0 * z * w.powi(3))).abs() < 1e-12 * p[(0, 0)]);
/// assert!((p[(1, 1)] - q / (4.0 * z * w)).abs() < 1e-12 * p[(1, 1)]);
/// ```
#[derive(Debug)]
pub struct SmallLyapunov {
    n: usize,
    /// The balancing D (its diagonal).
    d: Vec<f64>,
    /// The balanced A (storage kept between factorisations).
    ab: DMatrix<f64>,
    /// The vectorised operator, kept for the refinement's residual.
    m: DMatrix<f64>,
    lu: Option<LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    /// Right-hand side and correction of one solve.
    b: DVector<f64>,
    r: DVector<f64>,
    y: DVector<f64>,
    condition: f64,
}

impl Default for SmallLyapunov {
    fn default() -> Self {
        SmallLyapunov {
            n: 0,
            d: Vec::new(),
            ab: DMatrix::zeros(0, 0),
            m: DMatrix::zeros(0, 0),
            lu: None,
            b: DVector::zeros(0),
            r: DVector::zeros(0),
            y: DVector::zeros(0),
            condition: f64::INFINITY,
        }
    }
}

/// The index of p_ij (either order) among the n(n+1)/2 unknowns.
fn at(i: usize, j: usize) -> usize {
    let (i, j) = if i <= j { (i, j) } else { (j, i) };
    j * (j + 1) / 2 + i
}

impl SmallLyapunov {
    /// Factors the equation of `a`; `false` (the caller takes the general solver) when `a` is not square,
    /// has more than [`SMALL_LYAPUNOV_MAX_STATES`] states or a non-finite entry, the factorisation is
    /// singular, A is not asymptotically stable or the condition estimate exceeds
    /// [`SMALL_LYAPUNOV_MAX_CONDITION`].
    ///
    /// # Formula
    /// With X_I the solution for Q_b = I, A_b is asymptotically stable if and only if X_I is positive definite
    /// (Lyapunov's theorem), tested by a Cholesky factorisation. ‖L⁻¹‖₂ = ‖X_I‖₂ for L(X) = A_b X + X A_bᵀ
    /// (Hewer & Kenney 1988, "The sensitivity of the stable Lyapunov equation", SIAM J. Control Optim. 26,
    /// 321–344, with A ↦ A_bᵀ), and ‖L‖₂ ≤ 2‖A_b‖₂, so κ = 2‖A_b‖_F·tr X_I bounds the condition
    /// number of the equation from above (tr X ≥ ‖X‖₂ for X > 0). κ grows without bound as A approaches
    /// instability (‖X_I‖₂ ≥ 1/(2|max Re λ|)).
    pub fn factor(&mut self, a: &DMatrix<f64>) -> bool {
        self.lu = None;
        let n = a.nrows();
        if n == 0 || n != a.ncols() || n > SMALL_LYAPUNOV_MAX_STATES || !a.iter().all(|v| v.is_finite()) {
            return false;
        }
        let k = n * (n + 1) / 2;
        self.n = n;
        self.d = super::lyapunov::balance_diagonal(a);
        let d = &self.d;
        self.ab.resize_mut(n, n, 0.0);
        for j in 0..n {
            for i in 0..n {
                self.ab[(i, j)] = a[(i, j)] * d[j] / d[i];
            }
        }
        let ab = &self.ab;
        self.m.resize_mut(k, k, 0.0);
        self.m.fill(0.0);
        // column-major storage: entry (row, col) of the k × k operator at row + k·col
        let m = self.m.as_mut_slice();
        for j in 0..n {
            for i in 0..=j {
                let row = at(i, j);
                for l in 0..n {
                    m[row + k * at(l, j)] += ab[(i, l)];
                    m[row + k * at(i, l)] += ab[(j, l)];
                }
            }
        }
        let lu = LU::new(self.m.clone());
        if !lu.is_invertible() {
            return false;
        }
        self.lu = Some(lu);
        let mut xi = DMatrix::zeros(n, n);
        if !self.solve_balanced(|i, j| if i == j { 1.0 } else { 0.0 }, &mut xi) {
            self.lu = None;
            return false;
        }
        let trace = xi.trace();
        self.condition = 2.0 * self.ab.norm() * trace;
        if Cholesky::new(xi).is_none() || self.condition.is_nan() || self.condition > SMALL_LYAPUNOV_MAX_CONDITION {
            self.lu = None;
            return false;
        }
        true
    }

    /// The condition estimate κ of the last successful [`factor`](Self::factor).
    pub fn condition(&self) -> f64 {
        self.condition
    }

    /// Writes the P of A P + P Aᵀ + Q = 0 (A the last factored, `q` n × n, its symmetric part used) into
    /// `p` (resized to n × n); `false` without a successful factorisation, for a `q` of another size or
    /// when P is not finite.
    pub fn solve(&mut self, q: &DMatrix<f64>, p: &mut DMatrix<f64>) -> bool {
        let n = self.n;
        if q.shape() != (n, n) {
            return false;
        }
        let d = std::mem::take(&mut self.d);
        let ok = self.solve_balanced(|i, j| 0.5 * (q[(i, j)] + q[(j, i)]) / (d[i] * d[j]), p);
        if ok {
            for j in 0..n {
                for i in 0..n {
                    p[(i, j)] *= d[i] * d[j];
                }
            }
        }
        self.d = d;
        ok
    }

    /// The balanced solution for the balanced right-hand side `qb(i, j)` (i ≤ j), refined once.
    fn solve_balanced(&mut self, qb: impl Fn(usize, usize) -> f64, p: &mut DMatrix<f64>) -> bool {
        let Some(lu) = &self.lu else {
            return false;
        };
        let n = self.n;
        let k = n * (n + 1) / 2;
        self.b.resize_vertically_mut(k, 0.0);
        for j in 0..n {
            for i in 0..=j {
                self.b[at(i, j)] = -qb(i, j);
            }
        }
        self.y.clone_from(&self.b);
        if !lu.solve_mut(&mut self.y) {
            return false;
        }
        // r = b − M y, then y += M⁻¹ r
        self.r.clone_from(&self.b);
        self.r.gemv(-1.0, &self.m, &self.y, 1.0);
        if !lu.solve_mut(&mut self.r) {
            return false;
        }
        self.y += &self.r;
        p.resize_mut(n, n, 0.0);
        for j in 0..n {
            for i in 0..n {
                p[(i, j)] = self.y[at(i, j)];
            }
        }
        p.iter().all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::poly::test_rng::Rng;
    use crate::linalg::LyapunovSolver;
    use crate::tolerance::{CONDITION_SCALED, SMALL_DECOMPOSITION};

    /// A random stable A of order n: a random matrix shifted left of its spectral radius by `margin`,
    /// with its rows and columns scaled by 2^s, s uniform in [−`spread`, `spread`] (a badly scaled model).
    fn random_stable(rng: &mut Rng, n: usize, margin: f64, spread: f64) -> DMatrix<f64> {
        let m = DMatrix::from_fn(n, n, |_, _| rng.range(-1.0, 1.0));
        let rho = m.complex_eigenvalues().iter().map(|z| z.norm()).fold(0.0, f64::max);
        let a = m - DMatrix::identity(n, n) * (rho + margin);
        let s: Vec<f64> = (0..n).map(|_| 2f64.powf(rng.range(-spread, spread).round())).collect();
        DMatrix::from_fn(n, n, |i, j| a[(i, j)] * s[i] / s[j])
    }

    /// Over many random stable systems of order 1 to 8 (margins from 10⁻³ to 1, scalings up to 2¹⁰) and
    /// random symmetric right-hand sides, the small path equals the general Bartels–Stewart solver within
    /// CONDITION_SCALED·κ of ‖P‖ (two backward-stable solves of one equation differ by about p(n)·κ·ε;
    /// κ the estimate, an upper bound of the condition number) wherever it accepts the system, and it
    /// accepts every well-conditioned one.
    #[test]
    fn equals_the_general_solver() {
        let mut rng = Rng::new(2024);
        let mut s = SmallLyapunov::default();
        let (mut accepted, mut p, mut declined) = (0, DMatrix::zeros(1, 1), 0);
        for case in 0..2000 {
            let n = 1 + case % SMALL_LYAPUNOV_MAX_STATES;
            let margin = 10f64.powf(rng.range(-3.0, 0.0));
            let a = random_stable(&mut rng, n, margin, 10.0);
            let g = DMatrix::from_fn(n, n, |_, _| rng.range(-1.0, 1.0));
            let q = &g * g.transpose() - DMatrix::identity(n, n) * rng.range(0.0, 0.5);
            if !s.factor(&a) {
                declined += 1;
                continue;
            }
            assert!(s.condition() <= SMALL_LYAPUNOV_MAX_CONDITION);
            assert!(s.solve(&q, &mut p));
            let reference = LyapunovSolver::new(&a).unwrap().solve(&q).unwrap();
            let err = (&p - &reference).norm();
            assert!(
                err <= CONDITION_SCALED * s.condition() * reference.norm(),
                "case {case}: n = {n}, κ = {:e}, relative difference {:e}",
                s.condition(),
                err / reference.norm()
            );
            accepted += 1;
        }
        // most cases are well conditioned (margin ≥ 10⁻³ of a spectrum of radius ≈ n)
        assert!(
            accepted > 1500 && declined < 500,
            "accepted {accepted}, declined {declined}"
        );
    }

    /// Closed form: the scalar equation −2a p + q = 0 ⇒ p = q/(2a); κ = 2a·1/(2a) = 1.
    #[test]
    fn scalar_closed_form() {
        let mut s = SmallLyapunov::default();
        let mut p = DMatrix::zeros(1, 1);
        assert!(s.factor(&DMatrix::from_element(1, 1, -4.0)));
        assert!(s.solve(&DMatrix::from_element(1, 1, 3.0), &mut p));
        assert!((p[(0, 0)] - 3.0 / 8.0).abs() <= SMALL_DECOMPOSITION * 3.0 / 8.0);
        assert!((s.condition() - 1.0).abs() <= SMALL_DECOMPOSITION);
    }

    /// Unstable, marginal, nearly unstable (κ ≈ 2·‖A‖/(2·10⁻⁹)), too large and non-finite systems are
    /// declined, and a declined factorisation solves nothing.
    #[test]
    fn declines_what_the_general_solver_must_judge() {
        let mut s = SmallLyapunov::default();
        let mut p = DMatrix::zeros(2, 2);
        let q = DMatrix::identity(2, 2);
        let unstable = DMatrix::from_row_slice(2, 2, &[0.1, 1.0, -1.0, 0.1]);
        let saddle = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, 2.0]); // λ₁ + λ₂ ≠ 0: solvable, indefinite
        let marginal = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, 0.0]);
        let nearly = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0, -2e-9]);
        let mut nan = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 0.0, -1.0]);
        nan[(0, 1)] = f64::NAN;
        for a in [&unstable, &saddle, &marginal, &nearly, &nan] {
            assert!(!s.factor(a), "{a}");
            assert!(!s.solve(&q, &mut p));
        }
        let big = DMatrix::identity(9, 9) * -1.0;
        assert!(!s.factor(&big));
        assert!(s.factor(&(DMatrix::identity(8, 8) * -1.0)));
        assert!(!s.solve(&q, &mut p)); // q of another size
    }
}
