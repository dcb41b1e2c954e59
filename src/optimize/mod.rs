//! Design by optimisation: minimise or maximise any quantity `stochvib analyze` reports for a scenario
//! (σ or 3σ of an output, a_w, a_v, A(8), VDV, damage rate, life) over named scenario values between
//! bounds, subject to constraints on other quantities (`3sigma(travel) <= 40 mm`).
//!
//! * [`Param`]: a scenario key (the dotted path of `stochvib sweep --param`) and its bounds;
//! * [`Quantity`]: what is computed at a point ([`QUANTITY_FORMS`]);
//! * [`Constraint`]: `QUANTITY <= LIMIT` or `>=`;
//! * [`Problem`]: the scenario with the values substituted at each point (the substituted text is read by
//!   the scenario reader, so each point is the scenario `stochvib analyze` would read);
//! * [`solve`]: COBYLA (Powell 1994, the `cobyla` crate's translation of NLopt's) from several starts;
//! * [`pareto`]: the Pareto front of two quantities by the ε-constraint method.
//!
//! COBYLA is derivative-free: it handles the bounds and every inequality constraint by linear models
//! built from n + 1 points, so no gradient of a quantity is needed (the analytic Lyapunov sensitivities
//! are not used). The method, the formulas and the command are in `docs/optimisation.md`.
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

pub mod gradient;
pub mod pareto;
pub mod problem;
pub mod quantity;
pub mod solve;

pub use gradient::{KktCheck, PointGradients, KKT_TOLERANCE};
pub use pareto::{pareto, ParetoFront, ParetoPoint, ParetoProblem};
pub use problem::{Constraint, Goal, Param, PointValues, Problem, Relation};
pub use quantity::{Quantity, QuantityKind, QUANTITY_FORMS};
pub use solve::{solve, ConstraintState, ParamState, Solution, SolveOptions, StartResult};
