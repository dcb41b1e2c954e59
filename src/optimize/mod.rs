//! Design by optimisation: minimise or maximise any quantity `stochvib analyze` reports for a scenario
//! (σ or 3σ of an output, a_w, a_v, A(8), VDV, damage rate, life) over named scenario values between
//! bounds, subject to constraints on other quantities (`3sigma(travel) <= 40 mm`).
//!
//! * [`Param`]: a scenario key (the dotted path of `stochvib sweep --param`) and its bounds;
//! * [`Quantity`]: what is computed at a point ([`QUANTITY_FORMS`]);
//! * [`Constraint`]: `QUANTITY <= LIMIT` or `>=`;
//! * [`Problem`]: the scenario with the values substituted at each point (the substituted text is read by
//!   the scenario reader, so each point is the scenario `stochvib analyze` would read);
//! * [`solve()`]: SLSQP (Kraft 1988, the `slsqp` crate's translation of NLopt's) with the analytic gradients
//!   where the problem has them, else COBYLA (Powell 1994, the `cobyla` crate's), from several starts;
//! * [`pareto()`]: the Pareto front of two quantities by the ε-constraint method.
//!
//! SLSQP takes the gradients of the σ quantities from the analytic sensitivity of the Lyapunov solution
//! ([`gradient`]), so it converges in a few evaluations per start; COBYLA is derivative-free (linear
//! models built from n + 1 points) and serves every other quantity. Where the reader's model is affine in
//! the parameters (stiffnesses and dampings), each point's state space is written from a base and slopes
//! instead of being rebuilt from the `[model]` table. The method, the formulas and the command are in
//! `docs/optimisation.md`.
//!
//! # Examples
//! ```
//! use stochvib::optimize::{solve, Constraint, Goal, Param, Problem, Quantity, SolveOptions};
//! use stochvib::scenario::load_scenario;
//! use std::path::Path;
//! let sc = load_scenario(Path::new("data/quarter-car-model.toml"), Path::new("spectra")).unwrap();
//! let params = vec![Param::parse("model.suspension_damping=0.2:6 kN*s/m").unwrap()];
//! let objective = Quantity::parse("--minimize", "sigma(body_acc)", &sc).unwrap();
//! let travel = Constraint::parse("3sigma(travel) <= 40 mm", &sc).unwrap();
//! let problem = Problem::new(&sc, params, objective, Goal::Minimize, vec![travel]).unwrap();
//! let answer = solve(&problem, &SolveOptions::default()).unwrap();
//! assert!(answer.feasible);
//! assert!(answer.constraints[0].margin >= -1e-9);
//! ```

mod affine;
pub mod gradient;
pub mod pareto;
pub mod problem;
pub mod quantity;
mod small_point;
pub mod solve;

pub use gradient::{KktCheck, PointGradients, KKT_TOLERANCE};
pub use pareto::{pareto, ParetoFront, ParetoPoint, ParetoProblem};
pub use problem::{Constraint, Goal, Param, PointValues, Problem, Relation};
pub use quantity::{Quantity, QuantityKind, QUANTITY_FORMS};
pub use solve::{solve, ConstraintState, Method, ParamState, Solution, SolveOptions, StartResult};
