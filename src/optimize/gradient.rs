//! Gradients of σ quantities from the analytic sensitivity of the Lyapunov solution, and the
//! Karush–Kuhn–Tucker check of an answer with them.

use super::problem::{Goal, PointValues, Problem, Relation};
use crate::error::Result;
use crate::linalg::LyapunovSolver;
use crate::response::AugmentedSystem;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// The variances D_r = h_r P h_rᵀ of every row of `base.h` and their derivatives along each of `directions`
/// (each holding dF, dG, dH in the fields `a`, `g`, `h`; `f` is not used).
///
/// # Formula
/// ```text
/// F P + P Fᵀ + G Gᵀ = 0
/// F dP + dP Fᵀ + (dF P + P dFᵀ + dG Gᵀ + G dGᵀ) = 0,    dD_r = 2 dh_r P h_rᵀ + h_r dP h_rᵀ
/// ```
/// (the derivative of the Lyapunov equation; one more Lyapunov solve per direction with the same F, whose
/// Schur form is computed once, [`LyapunovSolver`]).
///
/// # Errors
/// The Lyapunov solver's (an unstable F).
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::optimize::gradient::variance_sensitivities;
/// use stochvib::response::AugmentedSystem;
/// // ẋ = −a x + w: D = 1/(2a), dD/da = −1/(2a²)
/// let a = 2.0;
/// let m = |v: f64| DMatrix::from_element(1, 1, v);
/// let base = AugmentedSystem { a: m(-a), g: m(1.0), h: m(1.0), f: m(0.0) };
/// let along_a = AugmentedSystem { a: m(-1.0), g: m(0.0), h: m(0.0), f: m(0.0) };
/// let (d, dd) = variance_sensitivities(&base, &[along_a]).unwrap();
/// assert!((d[0] - 0.25).abs() < 1e-15 && (dd[0][0] + 0.125).abs() < 1e-15);
/// ```
pub fn variance_sensitivities(
    base: &AugmentedSystem,
    directions: &[AugmentedSystem],
) -> Result<(Vec<f64>, Vec<Vec<f64>>)> {
    // one balancing and Schur form of F for P and every dP
    let solver = LyapunovSolver::new(&base.a)?;
    sensitivities_by(base, directions, |q| solver.solve(q))
}

/// [`variance_sensitivities`] with the Lyapunov equations F X + X Fᵀ + Q = 0 (F = `base.a`) solved by
/// `solve(Q)`: P first, then each dP.
pub(crate) fn sensitivities_by<E>(
    base: &AugmentedSystem,
    directions: &[AugmentedSystem],
    mut solve: impl FnMut(&DMatrix<f64>) -> std::result::Result<DMatrix<f64>, E>,
) -> std::result::Result<(Vec<f64>, Vec<Vec<f64>>), E> {
    let (n, rows) = (base.a.nrows(), base.h.nrows());
    // Q = G Gᵀ, then per direction Q = dF P + P dFᵀ + dG Gᵀ + G dGᵀ; one buffer each for Q and dF P
    let mut q = DMatrix::from_fn(n, n, |i, j| cross(&base.g, &base.g, i, j));
    let p = solve(&q)?;
    let variances = (0..rows).map(|r| quad(&base.h, r, &p, &base.h, r)).collect();
    let mut derivatives = Vec::with_capacity(directions.len());
    let mut fp = DMatrix::zeros(n, n);
    for d in directions {
        d.a.mul_to(&p, &mut fp);
        for j in 0..n {
            for i in 0..n {
                q[(i, j)] = fp[(i, j)] + fp[(j, i)] + cross(&d.g, &base.g, i, j) + cross(&d.g, &base.g, j, i);
            }
        }
        let dp = solve(&q)?;
        derivatives.push(
            (0..rows)
                .map(|r| 2.0 * quad(&d.h, r, &p, &base.h, r) + quad(&base.h, r, &dp, &base.h, r))
                .collect(),
        );
    }
    Ok((variances, derivatives))
}

/// (U Vᵀ)_ij = Σ_c u_ic v_jc.
fn cross(u: &DMatrix<f64>, v: &DMatrix<f64>, i: usize, j: usize) -> f64 {
    (0..u.ncols()).map(|c| u[(i, c)] * v[(j, c)]).sum()
}

/// u_r M v_sᵀ for row r of `u` and row s of `v`: Σ_j (Σ_i u_ri m_ij) v_sj.
fn quad(u: &DMatrix<f64>, r: usize, m: &DMatrix<f64>, v: &DMatrix<f64>, s: usize) -> f64 {
    (0..m.ncols())
        .map(|j| (0..m.nrows()).map(|i| u[(r, i)] * m[(i, j)]).sum::<f64>() * v[(s, j)])
        .sum()
}

/// The gradients of a problem's quantities at a point, SI per SI unit of each parameter.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointGradients {
    /// ∂(objective)/∂x_k.
    pub objective: Vec<f64>,
    /// Per constraint, ∂(its quantity)/∂x_k.
    pub constrained: Vec<Vec<f64>>,
}

/// The first-order optimality (KKT) check of an answer with the analytic gradients.
#[derive(Debug, Clone, Serialize)]
pub struct KktCheck {
    /// The gradients at the answer.
    pub gradients: PointGradients,
    /// Per constraint, its Lagrange multiplier in unit coordinates (0 for an inactive one): the rate at which
    /// the scaled objective would improve per unit of relative slack.
    pub multipliers: Vec<f64>,
    /// Per parameter, the multiplier of the bound it sits at (0 when inside).
    pub bound_multipliers: Vec<f64>,
    /// |∇f − Σ μ_j ∇c_j − Σ ν_i ∇b_i| in unit coordinates (f scaled by its value, c_j by its limit, x by its
    /// range): 0 at a KKT point.
    pub residual: f64,
    /// The residual is at most [`KKT_TOLERANCE`] and every multiplier is ≥ −[`KKT_TOLERANCE`].
    pub satisfied: bool,
}

/// Largest stationarity residual and most negative multiplier of a point called a KKT point, in unit
/// coordinates (a relative change of the objective per unit of the parameters' ranges). COBYLA stops when
/// its trust region is 10⁻⁹ of the ranges, so at a smooth optimum the residual is of the order of the
/// curvature times that.
pub const KKT_TOLERANCE: f64 = 1e-5;

impl KktCheck {
    /// The check of `best` (a point of `problem` whose constraints' activity is `active` and whose
    /// parameters sit at bounds `at_bound`, −1 lower, +1 upper, 0 inside), `None` where the problem has no
    /// analytic gradients ([`Problem::gradients`]).
    ///
    /// # Formula
    /// In unit coordinates u = (x − low)/(high − low), with f̃ = s f/|f| (s = −1 to maximise) and
    /// c̃_j = m_j/|L_j| ≥ 0 (m_j the margin), the multipliers μ (active constraints) and ν (bounds, ∇b = ±e_i)
    /// solve min |∇f̃ − Σ μ_j ∇c̃_j − Σ ν_i ∇b_i| by least squares; a KKT point has residual 0 and μ, ν ≥ 0.
    pub fn of(problem: &Problem, best: &PointValues, active: &[bool], at_bound: &[i8]) -> Option<Result<KktCheck>> {
        let grads = match problem.gradients(&best.x)? {
            Ok(g) => g,
            Err(e) => return Some(Err(e)),
        };
        let n = problem.params.len();
        let range: Vec<f64> = problem.params.iter().map(|p| p.high - p.low).collect();
        let sign = if problem.goal == Goal::Maximize { -1.0 } else { 1.0 };
        let f_scale = if best.objective != 0.0 {
            best.objective.abs()
        } else {
            1.0
        };
        let grad_f = DVector::from_fn(n, |k, _| sign * grads.objective[k] * range[k] / f_scale);
        // the columns of the active set: constraints, then bounds
        let mut cols: Vec<DVector<f64>> = Vec::new();
        let mut owners: Vec<(bool, usize)> = Vec::new();
        for (j, c) in problem.constraints.iter().enumerate() {
            if active[j] {
                let s = if c.relation == Relation::AtMost { -1.0 } else { 1.0 };
                cols.push(DVector::from_fn(n, |k, _| {
                    s * grads.constrained[j][k] * range[k] / c.limit.abs()
                }));
                owners.push((true, j));
            }
        }
        for (i, &b) in at_bound.iter().enumerate() {
            if b != 0 {
                cols.push(DVector::from_fn(n, |k, _| if k == i { -f64::from(b) } else { 0.0 }));
                owners.push((false, i));
            }
        }
        let mu = least_squares(&cols, &grad_f);
        let fitted = cols.iter().zip(&mu).fold(DVector::zeros(n), |acc, (c, m)| acc + c * *m);
        let residual = (&grad_f - fitted).norm();
        let mut multipliers = vec![0.0; problem.constraints.len()];
        let mut bound_multipliers = vec![0.0; n];
        for (&(is_constraint, k), &m) in owners.iter().zip(&mu) {
            if is_constraint {
                multipliers[k] = m;
            } else {
                bound_multipliers[k] = m;
            }
        }
        let satisfied = residual <= KKT_TOLERANCE && mu.iter().all(|&m| m >= -KKT_TOLERANCE);
        Some(Ok(KktCheck {
            gradients: grads,
            multipliers,
            bound_multipliers,
            residual,
            satisfied,
        }))
    }
}

/// The coefficients μ minimising |b − Σ μ_j a_j| (the SVD's least-squares solution; empty for no columns).
fn least_squares(cols: &[DVector<f64>], b: &DVector<f64>) -> Vec<f64> {
    if cols.is_empty() {
        return Vec::new();
    }
    let a = DMatrix::from_columns(cols);
    a.svd(true, true)
        .solve(b, 1e-12)
        .map(|m| m.iter().copied().collect())
        .unwrap_or_else(|_| vec![f64::NAN; cols.len()])
}
