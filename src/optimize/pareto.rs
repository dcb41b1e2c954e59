//! The Pareto front of two quantities (comfort against travel, say) by the ε-constraint method: the first
//! quantity minimised with the second held below a ladder of limits between its values at the two
//! single-objective optima.
//!
//! # Formula
//! With A = argmin f₁ and B = argmin f₂ (both under the problem's own constraints and bounds), and
//! ε_k = f₂(A) − (f₂(A) − f₂(B))·k/(n − 1), k = 1 … n − 2, point k minimises f₁ subject to f₂ ≤ ε_k
//! (Haimes, Lasdon & Wismer 1971). Every such minimiser is weakly Pareto optimal, and where the limit is
//! active it is on the front with f₂ = ε_k; the front's two ends are A and B.

use super::problem::{Constraint, Goal, Param, Problem, Relation};
use super::quantity::Quantity;
use super::solve::{solve, Solution, SolveOptions};
use crate::error::{Error, Result};
use crate::scenario::Scenario;
use serde::Serialize;

/// One point of the front.
#[derive(Debug, Clone, Serialize)]
pub struct ParetoPoint {
    /// The parameters, SI.
    pub params: Vec<f64>,
    /// The two quantities there, SI.
    pub values: [f64; 2],
    /// The limit ε_k on the second quantity (`None` at the two ends).
    pub limit: Option<f64>,
    /// Every constraint is met (the problem's and the limit).
    pub feasible: bool,
}

/// The front: the points in order of increasing first quantity.
#[derive(Debug, Clone, Serialize)]
pub struct ParetoFront {
    /// The parameters' keys.
    pub keys: Vec<String>,
    /// The two quantities as given.
    pub quantities: [String; 2],
    /// Their SI units.
    pub units: [String; 2],
    /// The points.
    pub points: Vec<ParetoPoint>,
    /// Evaluations in all.
    pub evaluations: usize,
}

/// The two-objective problem: `first` and `second` both minimised over `params` subject to `constraints`.
pub struct ParetoProblem<'a> {
    /// The scenario.
    pub base: &'a Scenario,
    /// The parameters with their bounds.
    pub params: Vec<Param>,
    /// The quantities (both minimised).
    pub quantities: [Quantity; 2],
    /// The constraints every point meets.
    pub constraints: Vec<Constraint>,
}

impl ParetoProblem<'_> {
    fn minimise(&self, which: usize, limit: Option<f64>, opts: &SolveOptions) -> Result<Solution> {
        let mut constraints = self.constraints.clone();
        if let Some(eps) = limit {
            let q = &self.quantities[1];
            constraints.push(Constraint {
                quantity: q.clone(),
                relation: Relation::AtMost,
                limit: eps,
                text: format!("{} <= {eps:e} {}", q.text, q.unit),
            });
        }
        let q = self.quantities[which].clone();
        let problem = Problem::new(self.base, self.params.clone(), q, Goal::Minimize, constraints)?;
        solve(&problem, opts)
    }

    /// Both quantities at `x`.
    fn both(&self, x: &[f64]) -> Result<[f64; 2]> {
        let [a, b] = self.quantities.clone();
        let problem = Problem::new(
            self.base,
            self.params.clone(),
            a,
            Goal::Minimize,
            vec![Constraint {
                quantity: b,
                relation: Relation::AtMost,
                limit: 1.0,
                text: String::new(),
            }],
        )?;
        let v = problem.evaluate(x)?;
        Ok([v.objective, v.constrained[0]])
    }
}

/// Refuses, after the two ends, a front of `n` points whose list does not fit in memory or whose inner
/// points, each a search like an end's (`per_point_s` measured), would take longer than `max_hours`.
fn check_front_budget(n: usize, per_point_s: f64, max_hours: f64) -> Result<()> {
    let what = format!("a front of {n} points");
    crate::io_rules::check_memory(
        n as u128 * std::mem::size_of::<ParetoPoint>() as u128,
        "--points",
        n,
        &what,
        "fewer --points",
    )?;
    let estimate = (n - 2) as f64 * per_point_s;
    let what = format!(
        "{what}: {} inner searches of about {} s (an end's)",
        n - 2,
        crate::numbers::short(per_point_s)
    );
    crate::io_rules::check_time(estimate, max_hours, "--points", n, &what, "fewer --points")
}

/// The front of `problem` with `n` ≥ 2 points (see the module docs), each optimum found by [`solve`] with
/// `opts`.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `--points` for n < 2 or for a front whose estimate (after its two ends)
/// exceeds `opts.max_hours` or the memory; an end point that meets not every constraint
/// (the problem is infeasible: its violations); the errors of [`Problem::new`] and [`solve`].
pub fn pareto(problem: &ParetoProblem, n: usize, opts: &SolveOptions) -> Result<ParetoFront> {
    if n < 2 {
        return Err(Error::invalid(
            "--points",
            n,
            "a front needs at least its two ends: give 2 or more",
        ));
    }
    let mut evaluations = 0;
    let mut end = |which: usize| -> Result<ParetoPoint> {
        let s = problem.minimise(which, None, opts)?;
        evaluations += s.evaluations;
        if !s.feasible {
            return Err(Error::invalid(
                "--constraint",
                s.violations().join("; "),
                "no point meets every constraint",
            ));
        }
        let x: Vec<f64> = s.params.iter().map(|p| p.value).collect();
        Ok(ParetoPoint {
            values: problem.both(&x)?,
            params: x,
            limit: None,
            feasible: true,
        })
    };
    let clock = std::time::Instant::now();
    let (a, b) = (end(0)?, end(1)?);
    check_front_budget(n, clock.elapsed().as_secs_f64() / 2.0, opts.max_hours)?;
    let (hi, lo) = (a.values[1], b.values[1]);
    let mut points = vec![a];
    for k in 1..n - 1 {
        let eps = hi - (hi - lo) * k as f64 / (n - 1) as f64;
        let s = problem.minimise(0, Some(eps), opts)?;
        evaluations += s.evaluations;
        let x: Vec<f64> = s.params.iter().map(|p| p.value).collect();
        points.push(ParetoPoint {
            values: problem.both(&x)?,
            params: x,
            limit: Some(eps),
            feasible: s.feasible,
        });
    }
    points.push(b);
    points.sort_by(|p, q| p.values[0].total_cmp(&q.values[0]));
    let [q1, q2] = &problem.quantities;
    Ok(ParetoFront {
        keys: problem.params.iter().map(|p| p.key.clone()).collect(),
        quantities: [q1.text.clone(), q2.text.clone()],
        units: [q1.unit.clone(), q2.unit.clone()],
        points,
        evaluations,
    })
}

impl ParetoFront {
    /// The front as CSV: the parameters (SI), the two quantities with their units, the limit, feasibility.
    pub fn to_csv(&self) -> String {
        let mut s = String::from("point");
        for k in &self.keys {
            s.push_str(&format!(",{k} [SI]"));
        }
        for (q, u) in self.quantities.iter().zip(&self.units) {
            s.push_str(&format!(",{q} [{u}]"));
        }
        s.push_str(",limit,feasible\n");
        for (i, p) in self.points.iter().enumerate() {
            s.push_str(&i.to_string());
            for x in p.params.iter().chain(&p.values) {
                s.push_str(&format!(",{x:e}"));
            }
            let limit = p.limit.map(|e| format!("{e:e}")).unwrap_or_default();
            s.push_str(&format!(",{limit},{}\n", if p.feasible { "yes" } else { "no" }));
        }
        s
    }
}
