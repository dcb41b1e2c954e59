//! Several searches (SLSQP with the analytic gradients, or COBYLA) from spread starts; the best feasible end
//! point with its active constraints, or the least infeasible one with what it misses by.

use super::gradient::{KktCheck, PointGradients};
use super::problem::{Goal, PointValues, Problem, Relation};
use super::small_point::PointScratch;
use crate::error::{Error, Result};
use serde::Serialize;
use std::cell::RefCell;

/// The search method of each start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// SLSQP where the problem has analytic gradients ([`Problem::has_gradients`]), else COBYLA.
    #[default]
    Auto,
    /// SLSQP (Kraft 1988; the `slsqp` crate's translation of NLopt's): sequential quadratic programming with
    /// the analytic gradients of the Lyapunov solution; quasi-Newton (BFGS) curvature, so it converges
    /// superlinearly in a few evaluations per start.
    Slsqp,
    /// COBYLA (Powell 1994): derivative-free, linear models from n + 1 points; for every quantity,
    /// including those without analytic gradients (a_w, A(8), VDV, damage, life, quadrature routes).
    Cobyla,
}

impl Method {
    /// `auto`, `slsqp` or `cobyla`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `--method` for another word.
    pub fn parse(text: &str) -> Result<Method> {
        match text.trim().to_ascii_lowercase().as_str() {
            "auto" => Ok(Method::Auto),
            "slsqp" => Ok(Method::Slsqp),
            "cobyla" => Ok(Method::Cobyla),
            _ => Err(Error::invalid("--method", text, "expected auto, slsqp or cobyla")),
        }
    }

    /// The method used on `problem`: `Auto` resolved.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `--method` for SLSQP on a problem without analytic gradients.
    pub fn for_problem(self, problem: &Problem) -> Result<Method> {
        match (self, problem.has_gradients()) {
            (Method::Auto, true) | (Method::Slsqp, true) => Ok(Method::Slsqp),
            (Method::Auto, false) | (Method::Cobyla, _) => Ok(Method::Cobyla),
            (Method::Slsqp, false) => Err(Error::invalid(
                "--method",
                "slsqp",
                "SLSQP needs the analytic gradients, which this problem has not (they exist when only `model.*` \
                 keys vary, every quantity is sigma or 3sigma and the input has an exact route); use --method cobyla",
            )),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Method::Auto => "auto",
            Method::Slsqp => "SLSQP",
            Method::Cobyla => "COBYLA",
        }
    }
}

/// How hard to search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveOptions {
    /// The search method ([`Method::Auto`]: SLSQP where the problem has analytic gradients, else COBYLA).
    pub method: Method,
    /// Number of starts (the centre of the box, then the Halton points 2, 3, … of the box).
    pub starts: usize,
    /// Most evaluations per start.
    pub max_evaluations: usize,
    /// Final trust-region radius of COBYLA, and the smallest step of SLSQP, as a fraction of each
    /// parameter's range.
    pub x_tolerance: f64,
    /// A constraint is active when its margin is within this fraction of its limit; a parameter is at a
    /// bound when within this fraction of its range.
    pub active_tolerance: f64,
    /// Refuse a search whose computing time's lower bound exceeds this many hours ([`check_budget`]).
    pub max_hours: f64,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            method: Method::Auto,
            starts: 4,
            max_evaluations: 2000,
            x_tolerance: 1e-9,
            active_tolerance: 1e-5,
            max_hours: crate::simulate::resources::DEFAULT_MAX_HOURS,
        }
    }
}

/// One start's end.
#[derive(Debug, Clone, Serialize)]
pub struct StartResult {
    /// Start point, SI.
    pub start: Vec<f64>,
    /// End point and its values; `None` when the end point could not be evaluated.
    pub end: Option<PointValues>,
    /// Evaluations used.
    pub evaluations: usize,
    /// The method's status.
    pub status: String,
}

/// A constraint at the answer.
#[derive(Debug, Clone, Serialize)]
pub struct ConstraintState {
    /// As given.
    pub text: String,
    /// The quantity's value, SI.
    pub value: f64,
    /// The limit, SI.
    pub limit: f64,
    /// Its unit.
    pub unit: String,
    /// limit − value (`<=`) or value − limit (`>=`): ≥ 0 when met, SI.
    pub margin: f64,
    /// Active: met with a margin within the tolerance (the optimum lies on it).
    pub active: bool,
    /// Met (margin ≥ −tolerance·|limit|).
    pub met: bool,
}

/// A parameter at the answer.
#[derive(Debug, Clone, Serialize)]
pub struct ParamState {
    /// The key.
    pub key: String,
    /// The value, SI.
    pub value: f64,
    /// The value as scenario text (in the unit of the bound).
    pub text: String,
    /// `Some("lower")` or `Some("upper")` when at a bound.
    pub at_bound: Option<&'static str>,
}

/// The answer of [`solve`].
#[derive(Debug, Clone, Serialize)]
pub struct Solution {
    /// Minimise or maximise.
    pub goal: Goal,
    /// The objective's text and unit.
    pub objective: String,
    /// Its unit.
    pub unit: String,
    /// Its value at the answer, SI.
    pub value: f64,
    /// Every constraint is met at the answer.
    pub feasible: bool,
    /// The parameters at the answer.
    pub params: Vec<ParamState>,
    /// The constraints at the answer.
    pub constraints: Vec<ConstraintState>,
    /// Every start.
    pub starts: Vec<StartResult>,
    /// Evaluations in all (of the quantities; a gradient at a point counts apart, in `gradient_evaluations`).
    pub evaluations: usize,
    /// Gradient evaluations in all (SLSQP; 0 for COBYLA).
    pub gradient_evaluations: usize,
    /// The method used (`Auto` resolved).
    pub method: Method,
    /// The first-order optimality check at the answer with the analytic gradients ([`KktCheck`]); `None`
    /// where the problem has none ([`Problem::gradients`]) or they failed there. COBYLA itself uses no
    /// gradient.
    pub kkt: Option<KktCheck>,
}

impl Solution {
    /// The constraints that are not met, with the amount, as one sentence each.
    pub fn violations(&self) -> Vec<String> {
        self.constraints
            .iter()
            .filter(|c| !c.met)
            .map(|c| {
                format!(
                    "`{}` cannot be met: at the best point the value is {:.6e} {u}, beyond the limit {:.6e} {u} by \
                     {:.6e} {u} ({:.3} %)",
                    c.text,
                    c.value,
                    c.limit,
                    -c.margin,
                    -100.0 * c.margin / c.limit.abs(),
                    u = c.unit
                )
            })
            .collect()
    }
}

/// The k-th point of the Halton sequence in [0, 1]^n (bases 2, 3, 5, …; k ≥ 1).
fn halton(k: usize, n: usize) -> Vec<f64> {
    const PRIMES: [usize; 12] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37];
    (0..n)
        .map(|d| {
            let b = PRIMES[d % PRIMES.len()];
            let (mut f, mut r, mut i) = (1.0, 0.0, k);
            while i > 0 {
                f /= b as f64;
                r += f * (i % b) as f64;
                i /= b;
            }
            r
        })
        .collect()
}

/// The problem in unit coordinates u ∈ [0, 1]ⁿ, with the last evaluation and the last gradients kept (the
/// methods ask for the objective and then each constraint at one point). Points go by the small Lyapunov
/// path where it applies ([`Problem::small_point`], its storage kept for the whole search); the values it
/// computes with a gradient are kept for the evaluation that follows at the same point.
struct Scaled<'p, 'a> {
    problem: &'p Problem<'a>,
    f_scale: f64,
    last: RefCell<Option<(Vec<f64>, Option<PointValues>)>>,
    last_gradients: RefCell<Option<(Vec<f64>, Option<PointGradients>)>>,
    scratch: RefCell<PointScratch>,
    prefetched: RefCell<Option<PointValues>>,
    evaluations: RefCell<usize>,
    gradient_evaluations: RefCell<usize>,
}

/// What an evaluation that fails returns: far worse than any value of a scaled problem.
const FAILED: f64 = 1e30;

impl Scaled<'_, '_> {
    fn x_of(&self, u: &[f64]) -> Vec<f64> {
        let p = &self.problem.params;
        u.iter()
            .zip(p)
            .map(|(&u, p)| p.low + u.clamp(0.0, 1.0) * (p.high - p.low))
            .collect()
    }

    fn values(&self, u: &[f64]) -> Option<PointValues> {
        if let Some((lu, v)) = &*self.last.borrow()
            && lu == u
        {
            return v.clone();
        }
        *self.evaluations.borrow_mut() += 1;
        let x = self.x_of(u);
        let prefetched = self.prefetched.borrow_mut().take().filter(|v| v.x == x);
        let v = prefetched
            .or_else(|| {
                let small = self.problem.small_point(&x, &mut self.scratch.borrow_mut(), false);
                small.map(|(v, _)| v)
            })
            .or_else(|| self.problem.evaluate(&x).ok());
        *self.last.borrow_mut() = Some((u.to_vec(), v.clone()));
        v
    }

    fn objective(&self, u: &[f64]) -> f64 {
        let sign = if self.problem.goal == Goal::Maximize { -1.0 } else { 1.0 };
        self.values(u).map_or(FAILED, |v| sign * v.objective / self.f_scale)
    }

    /// The gradients at `u` (SI per SI unit), `None` where they fail.
    fn gradients(&self, u: &[f64]) -> Option<PointGradients> {
        if let Some((lu, g)) = &*self.last_gradients.borrow()
            && lu == u
        {
            return g.clone();
        }
        *self.gradient_evaluations.borrow_mut() += 1;
        let x = self.x_of(u);
        let small = self.problem.small_point(&x, &mut self.scratch.borrow_mut(), true);
        let g = match small {
            Some((v, g @ Some(_))) => {
                *self.prefetched.borrow_mut() = Some(v);
                g
            }
            _ => self.problem.gradients(&x).and_then(|r| r.ok()),
        };
        *self.last_gradients.borrow_mut() = Some((u.to_vec(), g.clone()));
        g
    }

    /// Writes `factor`·∂q/∂x_k·range_k into `out` (the gradient in unit coordinates), 0 where it fails.
    fn write_gradient(&self, out: &mut [f64], dq: Option<&[f64]>, factor: f64) {
        for (k, (o, p)) in out.iter_mut().zip(&self.problem.params).enumerate() {
            *o = dq.map_or(0.0, |g| factor * g[k] * (p.high - p.low));
        }
    }

    /// The scaled objective (SLSQP) with its gradient in unit coordinates when asked.
    fn objective_with_gradient(&self, u: &[f64], grad: Option<&mut [f64]>) -> f64 {
        let sign = if self.problem.goal == Goal::Maximize { -1.0 } else { 1.0 };
        if let Some(out) = grad {
            let g = self.gradients(u);
            self.write_gradient(out, g.as_ref().map(|g| g.objective.as_slice()), sign / self.f_scale);
        }
        self.objective(u)
    }

    /// Constraint j scaled by its limit, ≤ 0 when met (SLSQP's convention), with its gradient when asked.
    fn constraint_with_gradient(&self, j: usize, u: &[f64], grad: Option<&mut [f64]>) -> f64 {
        let c = &self.problem.constraints[j];
        if let Some(out) = grad {
            // −margin: +q for `<=`, −q for `>=`
            let s = if c.relation == Relation::AtMost { 1.0 } else { -1.0 };
            let g = self.gradients(u);
            let dq = g.as_ref().map(|g| g.constrained[j].as_slice());
            self.write_gradient(out, dq, s / c.limit.abs());
        }
        let violation = -self.constraint(j, u);
        if violation > 0.0 && violation <= SLSQP_FEASIBILITY {
            0.0
        } else {
            violation
        }
    }

    /// Constraint j scaled by its limit, ≥ 0 when met (COBYLA's convention).
    fn constraint(&self, j: usize, u: &[f64]) -> f64 {
        let c = &self.problem.constraints[j];
        self.values(u)
            .map_or(-FAILED, |v| c.margin(v.constrained[j]) / c.limit.abs())
    }
}

/// Minimises (or maximises) the problem's objective subject to its constraints and bounds from
/// `opts.starts` starts by SLSQP with the analytic gradients or by COBYLA (`opts.method`; [`Method::Auto`]
/// takes SLSQP where the problem has the gradients), and returns the best end point: the feasible one with
/// the best objective, or, when no start ends feasible, the one with the smallest largest relative
/// violation. The answer's values are those of the scenario reader's model there.
///
/// # Formula
/// In unit coordinates u = (x − low)/(high − low) ∈ [0, 1]ⁿ, minimise s·f(x)/|f(x_c)| (s = −1 to
/// maximise, x_c the centre) subject to g_j(x) = m_j(x)/|L_j| ≥ 0, m_j the margin of constraint j
/// (L_j − q_j for `<=`, q_j − L_j for `>=`). COBYLA builds linear models of f and every g_j from n + 1
/// points and takes trust-region steps; ρ shrinks from 0.25 to `x_tolerance`. SLSQP solves a quadratic
/// model of the Lagrangian (BFGS curvature from the gradients) with the constraints linearised by their
/// gradients ∂q/∂x_k·(high_k − low_k)/|L_j| (from [`Problem::gradients`]), then searches along the step.
///
/// # Errors
/// When no start's end point can be evaluated (the scenario's error at the centre); `--method slsqp` on a
/// problem without analytic gradients ([`Method::for_problem`]).
pub fn solve(problem: &Problem, opts: &SolveOptions) -> Result<Solution> {
    let n = problem.params.len();
    let clock = std::time::Instant::now();
    let centre = problem.evaluate(
        &problem
            .params
            .iter()
            .map(|p| 0.5 * (p.low + p.high))
            .collect::<Vec<_>>(),
    )?;
    check_budget(problem, opts, clock.elapsed().as_secs_f64())?;
    let scaled = Scaled {
        problem,
        f_scale: if centre.objective != 0.0 {
            centre.objective.abs()
        } else {
            1.0
        },
        last: RefCell::new(None),
        last_gradients: RefCell::new(None),
        scratch: RefCell::new(PointScratch::default()),
        prefetched: RefCell::new(None),
        evaluations: RefCell::new(0),
        gradient_evaluations: RefCell::new(0),
    };
    let method = opts.method.for_problem(problem)?;
    let mut starts = Vec::new();
    for k in 0..opts.starts.max(1) {
        let u0 = if k == 0 { vec![0.5; n] } else { halton(k + 1, n) }; // halton(1) is the centre
        starts.push(match method {
            Method::Slsqp => run_slsqp(&scaled, &u0, opts),
            _ => run_start(&scaled, &u0, opts),
        });
    }
    let best = pick(problem, &starts, opts.active_tolerance).ok_or_else(|| Error::Numerical {
        what: "optimisation".into(),
        reason: "no start ended at a point the scenario accepts".into(),
    })?;
    // the answer as the scenario reader's model gives it (the search may have used the affine model)
    let best = problem.evaluate_by_reader(&best.x)?;
    let mut answer = describe(problem, &best, starts, *scaled.evaluations.borrow(), opts);
    answer.method = method;
    answer.gradient_evaluations = *scaled.gradient_evaluations.borrow();
    Ok(answer)
}

/// Refuses, before the search, a number of starts whose results do not fit in memory or whose computing time's
/// lower bound exceeds `opts.max_hours`.
///
/// # Formula
/// COBYLA evaluates at least n + 1 points per start (its first simplex), so the search takes at least
/// S·(n + 1)·t_c, with S starts, n parameters and t_c the measured time of the centre's evaluation. Every
/// start's result is kept (the answer lists them): S·(b + 8·(3n + m + 8)) bytes, b the size of a
/// [`StartResult`], m the constraints. `--max-evaluations` only caps a start that does not converge.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `starts` with the estimate and what to change.
pub fn check_budget(problem: &Problem, opts: &SolveOptions, centre_s: f64) -> Result<()> {
    let (n, m) = (problem.params.len() as u128, problem.constraints.len() as u128);
    let starts = opts.starts.max(1);
    let per_start = std::mem::size_of::<StartResult>() as u128 + 8 * (3 * n + m + 8);
    crate::io_rules::check_memory(
        starts as u128 * per_start,
        "starts",
        starts,
        "keeping every start's result",
        "fewer --starts",
    )?;
    if opts.max_hours.is_nan() || opts.max_hours <= 0.0 {
        return Err(Error::invalid("max hours", opts.max_hours, "must be > 0"));
    }
    crate::io_rules::check_time(
        starts as f64 * (n + 1) as f64 * centre_s,
        opts.max_hours,
        "starts",
        starts,
        &format!(
            "{starts} starts × at least {} evaluations of {} s (the centre's)",
            n + 1,
            crate::numbers::short(centre_s)
        ),
        "fewer --starts",
    )
}

fn run_start(s: &Scaled, u0: &[f64], opts: &SolveOptions) -> StartResult {
    let before = *s.evaluations.borrow();
    let f = |u: &[f64], _: &mut ()| s.objective(u);
    // one closure type for every constraint (COBYLA's slice of constraints has one element type)
    let cons: Vec<_> = (0..s.problem.constraints.len())
        .map(|j| move |u: &[f64], _: &mut ()| s.constraint(j, u))
        .collect();
    let tols = cobyla::StopTols {
        xtol_abs: vec![opts.x_tolerance; u0.len()],
        ..Default::default()
    };
    let bounds = vec![(0.0, 1.0); u0.len()];
    let out = cobyla::minimize(
        f,
        u0,
        &bounds,
        &cons,
        (),
        opts.max_evaluations,
        cobyla::RhoBeg::All(0.25),
        Some(tols),
    );
    let end = match out {
        Ok((st, u, _)) => (format!("{st:?}"), u),
        Err((st, u, _)) => (format!("{st:?}"), u),
    };
    start_result(s, u0, before, end)
}

/// The result of a start from `u0` that ended at `u` with `status`, `before` the evaluations before it.
fn start_result(s: &Scaled, u0: &[f64], before: usize, (status, u): (String, Vec<f64>)) -> StartResult {
    StartResult {
        start: s.x_of(u0),
        end: s.values(&u),
        evaluations: *s.evaluations.borrow() - before,
        status,
    }
}

/// One SLSQP run from `u0` in unit coordinates, the gradients analytic.
fn run_slsqp(s: &Scaled, u0: &[f64], opts: &SolveOptions) -> StartResult {
    let before = *s.evaluations.borrow();
    let f = |u: &[f64], g: Option<&mut [f64]>, _: &mut ()| s.objective_with_gradient(u, g);
    let cons: Vec<_> = (0..s.problem.constraints.len())
        .map(|j| move |u: &[f64], g: Option<&mut [f64]>, _: &mut ()| s.constraint_with_gradient(j, u, g))
        .collect();
    let tols = slsqp::StopTols {
        xtol_abs: vec![opts.x_tolerance; u0.len()],
        ftol_rel: SLSQP_FTOL_REL,
        ..Default::default()
    };
    let bounds = vec![(0.0, 1.0); u0.len()];
    let out = slsqp::minimize(f, u0, &bounds, &cons, (), opts.max_evaluations, Some(tols));
    let end = match out {
        Ok((st, u, _)) => (format!("{st:?}"), u),
        Err((st, u, _)) => (format!("{st:?}"), u),
    };
    start_result(s, u0, before, end)
}

/// SLSQP stops when the scaled objective changes by less than this fraction between iterations (a few
/// roundings: the objective is a square root of a Lyapunov solution, known to ≈ 10⁻¹⁵ relative), or when
/// its step is below `x_tolerance` of every range.
const SLSQP_FTOL_REL: f64 = 1e-14;

/// A constraint violated by at most this fraction of its limit is met for SLSQP. At an active constraint
/// the search's last steps are a few units in the last place of u, and the constrained quantity there (a
/// square root of a Lyapunov solution) is known to a few roundings, so its sign against the limit is
/// rounding noise. The `slsqp` crate judges feasibility with no tolerance and tests its stopping criteria
/// (`ftol_rel`, `x_tolerance`) only at feasible points, so without this tolerance a start that reached the
/// optimum can alternate between points a rounding above and below the limit until it ends
/// `RoundoffLimited`.
const SLSQP_FEASIBILITY: f64 = 1e-14;

/// The largest relative violation of a point (0 when feasible).
fn violation(problem: &Problem, v: &PointValues) -> f64 {
    problem
        .constraints
        .iter()
        .zip(&v.constrained)
        .map(|(c, &q)| (-c.margin(q) / c.limit.abs()).max(0.0))
        .fold(0.0, f64::max)
}

fn pick<'s>(problem: &Problem, starts: &'s [StartResult], tol: f64) -> Option<&'s PointValues> {
    let sign = if problem.goal == Goal::Maximize { -1.0 } else { 1.0 };
    let ends: Vec<&PointValues> = starts.iter().filter_map(|s| s.end.as_ref()).collect();
    let feasible = ends.iter().filter(|v| violation(problem, v) <= tol);
    feasible
        .min_by(|a, b| (sign * a.objective).total_cmp(&(sign * b.objective)))
        .or_else(|| {
            ends.iter()
                .min_by(|a, b| violation(problem, a).total_cmp(&violation(problem, b)))
        })
        .copied()
}

fn describe(
    problem: &Problem,
    best: &PointValues,
    starts: Vec<StartResult>,
    evals: usize,
    o: &SolveOptions,
) -> Solution {
    let constraints: Vec<ConstraintState> = problem
        .constraints
        .iter()
        .zip(&best.constrained)
        .map(|(c, &q)| {
            let m = c.margin(q);
            let tol = o.active_tolerance * c.limit.abs();
            ConstraintState {
                text: c.text.clone(),
                value: q,
                limit: c.limit,
                unit: c.quantity.unit.clone(),
                margin: m,
                active: m.abs() <= tol,
                met: m >= -tol,
            }
        })
        .collect();
    let params: Vec<ParamState> = problem
        .params
        .iter()
        .zip(&best.x)
        .map(|(p, &x)| {
            let tol = o.active_tolerance * (p.high - p.low);
            ParamState {
                key: p.key.clone(),
                value: x,
                text: p.value_text(x),
                at_bound: if x - p.low <= tol {
                    Some("lower")
                } else if p.high - x <= tol {
                    Some("upper")
                } else {
                    None
                },
            }
        })
        .collect();
    let active: Vec<bool> = constraints.iter().map(|c| c.active).collect();
    let at_bound: Vec<i8> = params
        .iter()
        .map(|p| match p.at_bound {
            Some("lower") => -1,
            Some(_) => 1,
            None => 0,
        })
        .collect();
    let kkt = KktCheck::of(problem, best, &active, &at_bound).and_then(|r| r.ok());
    Solution {
        method: o.method,
        gradient_evaluations: 0,
        kkt,
        goal: problem.goal,
        objective: problem.objective.text.clone(),
        unit: problem.objective.unit.clone(),
        value: best.objective,
        feasible: constraints.iter().all(|c| c.met),
        params,
        constraints,
        starts,
        evaluations: evals,
    }
}

impl std::fmt::Display for Solution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let goal = if self.goal == Goal::Maximize {
            "maximum"
        } else {
            "minimum"
        };
        let state = if self.feasible {
            ""
        } else {
            " (INFEASIBLE: the least violating point)"
        };
        writeln!(
            f,
            "{goal} of {}{state}: {:.6e} {}",
            self.objective, self.value, self.unit
        )?;
        for p in &self.params {
            let b = p.at_bound.map(|b| format!("  (at the {b} bound)")).unwrap_or_default();
            writeln!(f, "  {} = {}  ({:.9e} SI){b}", p.key, p.text, p.value)?;
        }
        for c in &self.constraints {
            let state = match (c.met, c.active) {
                (true, true) => "ACTIVE",
                (true, false) => "inactive",
                _ => "VIOLATED",
            };
            writeln!(
                f,
                "  constraint {}: value {:.6e} {u}, margin {:.6e} {u} ({:.3} % of the limit)  {state}",
                c.text,
                c.value,
                c.margin,
                100.0 * c.margin / c.limit.abs(),
                u = c.unit
            )?;
        }
        for v in self.violations() {
            writeln!(f, "  {v}")?;
        }
        if let Some(k) = &self.kkt {
            write_kkt(f, self, k)?;
        }
        let ends = self.starts.iter().filter(|s| s.end.is_some()).count();
        writeln!(
            f,
            "  {} starts ({ends} ended at an evaluable point), {} evaluations and {} gradients, {}",
            self.starts.len(),
            self.evaluations,
            self.gradient_evaluations,
            self.method.name()
        )
    }
}

/// The KKT lines of an answer: the gradients, the active multipliers and the residual.
fn write_kkt(f: &mut std::fmt::Formatter<'_>, s: &Solution, k: &KktCheck) -> std::fmt::Result {
    let fmt = |g: &[f64]| {
        let parts: Vec<String> = s
            .params
            .iter()
            .zip(g)
            .map(|(p, v)| format!("d/d {} = {v:.6e}", p.key))
            .collect();
        parts.join(", ")
    };
    writeln!(
        f,
        "  gradient (analytic Lyapunov sensitivities, SI): {}: {}",
        s.objective,
        fmt(&k.gradients.objective)
    )?;
    for ((c, g), mu) in s.constraints.iter().zip(&k.gradients.constrained).zip(&k.multipliers) {
        let m = if c.active {
            format!("  (multiplier {mu:.4e})")
        } else {
            String::new()
        };
        writeln!(f, "    {}: {}{m}", c.text, fmt(g))?;
    }
    writeln!(
        f,
        "  KKT: stationarity residual {:.3e} in unit coordinates (tolerance {:.0e}), multipliers {}: {}",
        k.residual,
        super::gradient::KKT_TOLERANCE,
        if k.multipliers
            .iter()
            .chain(&k.bound_multipliers)
            .all(|&m| m >= -super::gradient::KKT_TOLERANCE)
        {
            "≥ 0"
        } else {
            "NEGATIVE"
        },
        if k.satisfied { "satisfied" } else { "NOT satisfied" }
    )
}

/// `Relation` as text.
impl std::fmt::Display for Relation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Relation::AtMost => "<=",
            Relation::AtLeast => ">=",
        })
    }
}
