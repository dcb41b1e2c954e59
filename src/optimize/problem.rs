//! The optimisation problem: named scenario parameters with bounds, an objective and constraints, read
//! from command-line text and checked against the scenario.

use super::affine::AffineModel;
use super::gradient::{variance_sensitivities, PointGradients};
use super::quantity::{Quantity, QuantityKind};
use super::small_point::{difference_step, small_point, PointScratch, SmallModel};
use crate::error::{Error, Result};
use crate::fields::Fields;
use crate::models::ModelInstance;
use crate::response::{ExactEvaluator, PointStatistics, VarianceMethod};
use crate::scenario::{build_model, parse_scenario, BuiltModel, ModelContext, Scenario};
use crate::system::{FrequencyResponse, StateSpace};
use crate::units::parse_quantity;
use serde::Serialize;
use std::sync::Arc;

/// A scenario key varied between bounds, e.g. `model.suspension_damping=200:5000 N*s/m`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Param {
    /// The dotted scenario key (as for `stochvib sweep --param`).
    pub key: String,
    /// Lower bound, SI.
    pub low: f64,
    /// Upper bound, SI.
    pub high: f64,
    /// The unit the values are written in when substituted (the upper bound's unit; empty: a number).
    pub unit: String,
    /// The SI value of one `unit`.
    #[serde(skip)]
    scale: f64,
}

impl Param {
    /// Parses `KEY=LOW:HIGH [UNIT]` or `KEY=LOW UNIT:HIGH UNIT`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `--param`: no `=` or `:`, a bound that is not a quantity, bounds
    /// of different dimensions, `LOW ≥ HIGH`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::optimize::Param;
    /// let p = Param::parse("model.suspension_damping=0.2:5 kN*s/m").unwrap();
    /// assert_eq!((p.low, p.high), (200.0, 5000.0));
    /// assert_eq!(p.value_text(1250.0), "1.25 kN*s/m");
    /// assert!(Param::parse("model.suspension_damping=5:0.2 kN*s/m").is_err()); // reversed
    /// ```
    pub fn parse(text: &str) -> Result<Param> {
        let bad = |why: &str| Error::invalid("--param", text, why.to_string());
        let (key, range) = text
            .split_once('=')
            .ok_or_else(|| bad("expected KEY=LOW:HIGH, e.g. model.suspension_damping=200:5000 N*s/m"))?;
        let key = key.trim();
        if key.is_empty() || key.split('.').any(|s| s.trim().is_empty()) {
            return Err(bad("the key must be a dotted path such as model.suspension_damping"));
        }
        let (lo, hi) = range
            .split_once(':')
            .ok_or_else(|| bad("expected LOW:HIGH after `=`, e.g. 200:5000 N*s/m"))?;
        let (hv, hdim) = parse_quantity(hi).map_err(|e| bad(&format!("upper bound: {e}")))?;
        let unit = hi
            .trim()
            .trim_start_matches(|c: char| c.is_ascii_digit() || "+-.eE".contains(c));
        let unit = unit.trim().to_string();
        let scale = if unit.is_empty() {
            1.0
        } else {
            parse_quantity(&format!("1 {unit}"))?.0
        };
        let lo_text = if lo.trim().parse::<f64>().is_ok() {
            format!("{lo} {unit}")
        } else {
            lo.to_string()
        };
        let (lv, ldim) = parse_quantity(&lo_text).map_err(|e| bad(&format!("lower bound: {e}")))?;
        if ldim != hdim {
            return Err(bad(&format!(
                "the bounds have different dimensions ({ldim} and {hdim})"
            )));
        }
        if lv >= hv {
            return Err(bad(&format!(
                "the lower bound ({lv:e}) must be below the upper bound ({hv:e}): bounds the wrong way round?"
            )));
        }
        Ok(Param {
            key: key.to_string(),
            low: lv,
            high: hv,
            unit,
            scale,
        })
    }

    /// The SI value `x` as scenario text in the parameter's unit.
    pub fn value_text(&self, x: f64) -> String {
        if self.unit.is_empty() {
            format!("{x}")
        } else {
            format!("{} {}", x / self.scale, self.unit)
        }
    }

    fn toml_value(&self, x: f64) -> toml::Value {
        if self.unit.is_empty() {
            toml::Value::Float(x)
        } else {
            toml::Value::String(self.value_text(x))
        }
    }
}

/// Which side of the limit is allowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Relation {
    /// `QUANTITY <= LIMIT`.
    #[serde(rename = "<=")]
    AtMost,
    /// `QUANTITY >= LIMIT`.
    #[serde(rename = ">=")]
    AtLeast,
}

/// A constraint `QUANTITY <= LIMIT` or `QUANTITY >= LIMIT`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Constraint {
    /// The constrained quantity.
    pub quantity: Quantity,
    /// Which side is allowed.
    pub relation: Relation,
    /// The limit, SI.
    pub limit: f64,
    /// The text as given.
    pub text: String,
}

impl Constraint {
    /// Parses `QUANTITY <= VALUE UNIT` (or `>=`), e.g. `3sigma(travel) <= 40 mm`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `--constraint`: no relation, an unknown quantity, a limit that is
    /// not a quantity of the quantity's dimension, a limit of 0 (the margin is relative to it).
    pub fn parse(text: &str, sc: &Scenario) -> Result<Constraint> {
        let bad = |why: String| Error::invalid("--constraint", text, why);
        let (q, relation, v) = if let Some((q, v)) = text.split_once("<=") {
            (q, Relation::AtMost, v)
        } else if let Some((q, v)) = text.split_once(">=") {
            (q, Relation::AtLeast, v)
        } else {
            return Err(bad("expected QUANTITY <= VALUE UNIT or QUANTITY >= VALUE UNIT".into()));
        };
        let quantity = Quantity::parse("--constraint", q, sc)?;
        let (limit, dim) = parse_quantity(v).map_err(|e| bad(e.to_string()))?;
        match quantity.dim {
            Some(d) if d != dim => {
                return Err(bad(format!(
                    "the limit has dimension {dim}; {} is in {}",
                    quantity.text, quantity.unit
                )));
            }
            None if dim != crate::units::Dim::DIMENSIONLESS => {
                return Err(bad(format!("write the limit as a number in {}", quantity.unit)));
            }
            _ => {}
        }
        if limit == 0.0 {
            return Err(bad(
                "a limit of 0 cannot be met by a variance; give a positive limit".into()
            ));
        }
        Ok(Constraint {
            quantity,
            relation,
            limit,
            text: text.trim().to_string(),
        })
    }

    /// The margin (limit − value for `<=`, value − limit for `>=`), ≥ 0 when met, SI.
    pub fn margin(&self, value: f64) -> f64 {
        match self.relation {
            Relation::AtMost => self.limit - value,
            Relation::AtLeast => value - self.limit,
        }
    }
}

/// Minimise or maximise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Goal {
    /// Smallest value.
    Minimize,
    /// Largest value.
    Maximize,
}

/// A whole problem over one scenario.
#[derive(Debug)]
pub struct Problem<'a> {
    base: &'a Scenario,
    root: toml::Table,
    /// Set when only `model.*` keys vary and every quantity is a σ: the base excitation's evaluator, and
    /// each point rebuilds the model from its `[model]` table alone (as `stochvib sweep` does).
    fast: Option<Fast>,
    /// The parameters.
    pub params: Vec<Param>,
    /// The objective.
    pub objective: Quantity,
    /// Minimise or maximise.
    pub goal: Goal,
    /// The constraints.
    pub constraints: Vec<Constraint>,
}

/// The values of the objective and of every constraint's quantity at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointValues {
    /// The parameters, SI.
    pub x: Vec<f64>,
    /// The objective, SI.
    pub objective: f64,
    /// Each constraint's quantity, SI.
    pub constrained: Vec<f64>,
}

impl<'a> Problem<'a> {
    /// Checks the parameters against `base` (every key is a value of the scenario file, given once) and
    /// evaluates the centre of the box (so that a value the scenario refuses fails at once).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `--param` for a key the scenario does not have or a repeated key;
    /// the scenario's errors at the centre.
    pub fn new(
        base: &'a Scenario,
        params: Vec<Param>,
        objective: Quantity,
        goal: Goal,
        constraints: Vec<Constraint>,
    ) -> Result<Problem<'a>> {
        let root = crate::fields::parse_toml(&base.text, &base.path)?;
        if params.is_empty() {
            return Err(Error::invalid(
                "--param",
                "<none>",
                "give at least one --param KEY=LOW:HIGH",
            ));
        }
        for (i, p) in params.iter().enumerate() {
            if lookup(&root, &p.key).is_none() {
                return Err(Error::invalid(
                    "--param",
                    &p.key,
                    "the scenario has no such value (a parameter must be a value written in the scenario file)",
                ));
            }
            if params[..i].iter().any(|q| q.key == p.key) {
                return Err(Error::invalid("--param", &p.key, "given twice"));
            }
        }
        let fast = Fast::new(base, &params, &objective, &constraints);
        let mut problem = Problem {
            base,
            root,
            fast,
            params,
            objective,
            goal,
            constraints,
        };
        let centre: Vec<f64> = problem.params.iter().map(|p| 0.5 * (p.low + p.high)).collect();
        // the reader's model at the centre, built once: its values, and the base of the affine model
        let built = problem
            .fast
            .as_ref()
            .and_then(|f| Some((f, f.model_at(&problem, &centre)?)));
        let affine = match built {
            Some((f, model)) => {
                let model = model.map_err(|e| problem.name_error(&centre, e))?;
                f.values(model.system.as_ref(), &problem, &centre)
                    .map_err(|e| problem.name_error(&centre, e))?;
                f.fit_affine(&problem, &centre, &model)
            }
            None => {
                problem.evaluate(&centre)?;
                None
            }
        };
        if let Some(f) = problem.fast.as_mut() {
            f.affine = affine;
        }
        Ok(problem)
    }

    /// How a point is computed: `"affine model"` (the state space written from a base and slopes, see
    /// `Fast::fit_affine`), `"model table"` (the model rebuilt from its substituted `[model]` table) or
    /// `"scenario"` (the whole substituted scenario read).
    pub fn path(&self) -> &'static str {
        match &self.fast {
            Some(f) if f.affine.is_some() => "affine model",
            Some(_) => "model table",
            None => "scenario",
        }
    }

    /// Whether [`gradients`](Self::gradients) applies: only `model.*` keys vary, every quantity is a σ or
    /// 3σ, and the input has an exact (Lyapunov or integral-table) route for the model.
    pub fn has_gradients(&self) -> bool {
        let sigma_like = |q: &Quantity| matches!(q.kind, QuantityKind::Sigma(_) | QuantityKind::ThreeSigma(_));
        let exact = self.fast.as_ref().is_some_and(|f| {
            let n = self.base.model.system.state_space().map(|s| s.n_states());
            n.is_some() && f.evaluator.method(n) != crate::response::VarianceMethod::Quadrature
        });
        exact && sigma_like(&self.objective) && self.constraints.iter().all(|c| sigma_like(&c.quantity))
    }

    /// Every quantity of the problem at `x` from the model the scenario reader builds there (never the
    /// affine model): what `stochvib analyze` of the substituted scenario reports. The answer of a search is
    /// reported with these values.
    ///
    /// # Errors
    /// As [`evaluate`](Self::evaluate).
    pub fn evaluate_by_reader(&self, x: &[f64]) -> Result<PointValues> {
        if let Some(fast) = &self.fast
            && let Some(v) = fast.evaluate_by_reader(self, x)
        {
            return v.map_err(|e| self.name_error(x, e));
        }
        self.evaluate_scenario(x)
    }

    /// The scenario with the parameters set to `x` (SI).
    ///
    /// # Errors
    /// The scenario reader's errors for the substituted values.
    pub fn scenario_at(&self, x: &[f64]) -> Result<Scenario> {
        let mut root = self.root.clone();
        for (p, &v) in self.params.iter().zip(x) {
            crate::study::sweep::set_key(&mut root, &p.key, p.toml_value(v))
                .map_err(|why| Error::invalid("--param", &p.key, why))?;
        }
        let text = toml::to_string(&root).map_err(|e| Error::Numerical {
            what: "writing the substituted scenario".into(),
            reason: e.to_string(),
        })?;
        parse_scenario(&text, &self.base.path, &self.base.spectra_dir).map_err(|e| self.name_error(x, e))
    }

    /// Every quantity of the problem at `x`.
    ///
    /// # Errors
    /// As [`scenario_at`](Self::scenario_at), and the quantities' errors.
    pub fn evaluate(&self, x: &[f64]) -> Result<PointValues> {
        if let Some(fast) = &self.fast
            && let Some(v) = fast.evaluate(self, x)
        {
            return v.map_err(|e| self.name_error(x, e));
        }
        self.evaluate_scenario(x)
    }

    /// Every quantity at `x` from the whole substituted scenario.
    fn evaluate_scenario(&self, x: &[f64]) -> Result<PointValues> {
        let sc = self.scenario_at(x)?;
        let all: Vec<&Quantity> = std::iter::once(&self.objective)
            .chain(self.constraints.iter().map(|c| &c.quantity))
            .collect();
        let mut v = Quantity::values(&all, &sc)?;
        let objective = v.remove(0);
        Ok(PointValues {
            x: x.to_vec(),
            objective,
            constrained: v,
        })
    }

    /// The gradients of the objective and of every constraint's quantity at `x` (SI per SI unit of each
    /// parameter) from the analytic sensitivity of the Lyapunov solution
    /// ([`variance_sensitivities`]), the model's matrices differenced
    /// centrally ([`ExactEvaluator::realization_derivative`]). `None` where that does not apply: a parameter
    /// outside `[model]`, a quantity other than σ or 3σ, an input with no exact route (quadrature), a model
    /// without a state space.
    ///
    /// # Errors
    /// The model's errors at `x` or at the difference points; the Lyapunov solver's.
    pub fn gradients(&self, x: &[f64]) -> Option<Result<PointGradients>> {
        self.fast.as_ref()?.gradients(self, x)
    }

    /// The values at `x` and, when `gradients`, the gradients there, by the small Lyapunov path with
    /// storage `scratch` kept across the evaluations of one search ([`small_point`]): the numbers of
    /// [`evaluate`](Self::evaluate) and [`gradients`](Self::gradients) to rounding (the Lyapunov equations
    /// solved by one LU of their vectorised form instead of a Schur form). `None` where the small path does
    /// not apply; the general path then gives the values or the error.
    pub(crate) fn small_point(
        &self,
        x: &[f64],
        scratch: &mut PointScratch,
        gradients: bool,
    ) -> Option<(PointValues, Option<PointGradients>)> {
        self.fast.as_ref()?.small_point(self, x, scratch, gradients)
    }

    /// A scenario error at `x` named by the parameters' values.
    fn name_error(&self, x: &[f64], e: Error) -> Error {
        let at: Vec<String> = self
            .params
            .iter()
            .zip(x)
            .map(|(p, &v)| format!("{}={}", p.key, p.value_text(v)))
            .collect();
        Error::invalid("--param", at.join(" "), e.to_string())
    }
}

/// A model's system, shared.
type SystemRef = Arc<dyn FrequencyResponse>;

/// The model-table path: the outputs of every quantity and the base excitation's evaluator.
struct Fast {
    evaluator: ExactEvaluator,
    /// Per quantity (objective first, then the constraints), its index in `outputs`.
    slots: Vec<usize>,
    /// The output names evaluated.
    outputs: Vec<String>,
    /// The model's state space as an affine function of the parameters, where it is one.
    affine: Option<AffineModel>,
}

impl std::fmt::Debug for Fast {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Fast").field("outputs", &self.outputs).finish()
    }
}

impl Fast {
    fn new(base: &Scenario, params: &[Param], objective: &Quantity, constraints: &[Constraint]) -> Option<Fast> {
        let quantities = std::iter::once(objective).chain(constraints.iter().map(|c| &c.quantity));
        let mut outputs: Vec<String> = Vec::new();
        let mut slots = Vec::new();
        for q in quantities {
            let o = q.output()?;
            slots.push(outputs.iter().position(|x| x == o).unwrap_or_else(|| {
                outputs.push(o.to_string());
                outputs.len() - 1
            }));
        }
        let model_only = params.iter().all(|p| p.key.starts_with("model."));
        (model_only && base.inputs.len() <= 1 && base.nonlinear.is_none()).then(|| Fast {
            evaluator: ExactEvaluator::new(&base.excitation).variances_only(),
            slots,
            outputs,
            affine: None,
        })
    }

    /// The affine model of the problem (module `affine`) when the reader's models are affine in the
    /// parameters over the box and the evaluator has an exact route: slopes from the reader's model
    /// `at_centre` and those at each parameter's upper bound, checked at each lower bound and at the two
    /// corners of the box (a point met twice, as the corners of a one-parameter box, is built once). The
    /// reader accepts every one of these points, so every value of the box is one it accepts (each key's
    /// valid values are an interval).
    fn fit_affine(&self, pb: &Problem, centre: &[f64], at_centre: &ModelInstance) -> Option<AffineModel> {
        let n = pb.base.model.system.state_space().map(|s| s.n_states());
        if n.is_none() || self.evaluator.method(n) == crate::response::VarianceMethod::Quadrature {
            return None;
        }
        let base = at_centre.system.state_space()?.clone();
        let mut built: Vec<(Vec<f64>, StateSpace)> = Vec::new();
        let mut ss_at = |x: Vec<f64>| -> Option<(Vec<f64>, StateSpace)> {
            if let Some(known) = built.iter().find(|(y, _)| *y == x) {
                return Some(known.clone());
            }
            let ss = self.model_at(pb, &x)?.ok()?.system.state_space().cloned()?;
            built.push((x.clone(), ss.clone()));
            Some((x, ss))
        };
        let mut up = Vec::with_capacity(centre.len());
        let mut checks = Vec::with_capacity(centre.len() + 2);
        for (k, p) in pb.params.iter().enumerate() {
            let mut x = centre.to_vec();
            x[k] = p.high;
            up.push((p.high - centre[k], ss_at(x.clone())?.1));
            x[k] = p.low;
            checks.push(ss_at(x)?);
        }
        checks.push(ss_at(pb.params.iter().map(|p| p.low).collect())?);
        checks.push(ss_at(pb.params.iter().map(|p| p.high).collect())?);
        AffineModel::fit(centre, &base, &up, &checks)
    }

    /// The state space of the affine model at `x`, or `None` without one (or with a non-finite entry).
    fn affine_at(&self, x: &[f64]) -> Option<StateSpace> {
        let af = self.affine.as_ref()?;
        let mut ss = af.base().clone();
        af.write(x, &mut ss).then_some(ss)
    }

    /// The values at `x` by the rebuilt model, or `None` when the model's input layout changed (then the
    /// whole scenario is read).
    fn evaluate(&self, pb: &Problem, x: &[f64]) -> Option<Result<PointValues>> {
        if let Some(ss) = self.affine_at(x) {
            return Some(self.values(&ss, pb, x));
        }
        self.evaluate_by_reader(pb, x)
    }

    /// As [`evaluate`](Self::evaluate) with the reader's model.
    fn evaluate_by_reader(&self, pb: &Problem, x: &[f64]) -> Option<Result<PointValues>> {
        Some(
            self.model_at(pb, x)?
                .and_then(|model| self.values(model.system.as_ref(), pb, x)),
        )
    }

    /// The model rebuilt at `x`, or `None` when its input layout changed.
    fn model_at(&self, pb: &Problem, x: &[f64]) -> Option<Result<ModelInstance>> {
        let mut table = pb.root.get("model")?.as_table()?.clone();
        for (p, &v) in pb.params.iter().zip(x) {
            let rest = p.key.strip_prefix("model.")?;
            crate::study::sweep::set_key(&mut table, rest, p.toml_value(v)).ok()?;
        }
        let f = Fields::new(&pb.base.path, "model", &table);
        let _ = f.get("kind"); // read by the scenario reader, not by the model
        let ctx = ModelContext {
            speed: pb.base.input.speed,
            several_inputs: false,
        };
        let model = match build_model(&pb.base.kind, &f, ctx).and_then(|m| f.finish().map(|()| m)) {
            Ok(BuiltModel::Stochastic(m)) => m,
            Ok(BuiltModel::Deterministic(_)) => return None,
            Err(e) => return Some(Err(e)),
        };
        if model.layout != pb.base.model.layout {
            return None;
        }
        Some(Ok(model))
    }

    /// The analytic gradients at `x` (see [`Problem::gradients`]).
    fn gradients(&self, pb: &Problem, x: &[f64]) -> Option<Result<PointGradients>> {
        let quantities = sigma_quantities(pb)?;
        if let Some(ss) = self.affine_at(x) {
            let at = |y: &[f64]| self.affine_at(y).map(|s| Ok(Arc::new(s) as SystemRef));
            return self.gradients_of(pb, x, &ss, &quantities, at);
        }
        let model = match self.model_at(pb, x)? {
            Ok(m) => m,
            Err(e) => return Some(Err(e)),
        };
        let at = |y: &[f64]| self.model_at(pb, y).map(|r| r.map(|m| m.system));
        self.gradients_of(pb, x, model.system.as_ref(), &quantities, at)
    }

    /// The gradients at `x` of the system `sys` there, the systems at other points given by `at`.
    fn gradients_of<F>(
        &self,
        pb: &Problem,
        x: &[f64],
        sys: &dyn FrequencyResponse,
        quantities: &[&Quantity],
        at: F,
    ) -> Option<Result<PointGradients>>
    where
        F: Fn(&[f64]) -> Option<Result<SystemRef>>,
    {
        let idx = match self
            .outputs
            .iter()
            .map(|o| sys.output_index(o))
            .collect::<Result<Vec<_>>>()
        {
            Ok(i) => i,
            Err(e) => return Some(Err(e)),
        };
        let exc = &pb.base.excitation;
        let base = self.evaluator.realization(sys, exc, &idx)?;
        let mut directions = Vec::with_capacity(x.len());
        for (k, (p, &xk)) in pb.params.iter().zip(x).enumerate() {
            // a step small against x_k (and against the range where x_k is 0): the matrices' central difference
            let delta = difference_step(p, xk);
            let step = |s: f64| {
                let mut y = x.to_vec();
                y[k] += s * delta;
                at(&y)
            };
            let (plus, minus) = match (step(1.0)?, step(-1.0)?) {
                (Ok(p), Ok(m)) => (p, m),
                (Err(e), _) | (_, Err(e)) => return Some(Err(e)),
            };
            let d = self
                .evaluator
                .realization_derivative(sys, plus.as_ref(), minus.as_ref(), delta, exc, &idx)?;
            directions.push(d);
        }
        let result = (|| -> Result<PointGradients> {
            let base = base?;
            let directions = directions.into_iter().collect::<Result<Vec<_>>>()?;
            let (var, dvar) = variance_sensitivities(&base, &directions)?;
            Ok(self.sigma_gradients(quantities, &var, &dvar))
        })();
        Some(result)
    }

    /// The gradients of σ and 3σ `quantities` from the variances `var` of the outputs and their derivatives
    /// `dvar` (per parameter, per output): dσ/dx = dD/dx / (2σ); 3σ: three times that.
    fn sigma_gradients(&self, quantities: &[&Quantity], var: &[f64], dvar: &[Vec<f64>]) -> PointGradients {
        let grad = |q: &Quantity, slot: usize| -> Vec<f64> {
            let factor = if matches!(q.kind, QuantityKind::ThreeSigma(_)) {
                3.0
            } else {
                1.0
            };
            dvar.iter()
                .map(|d| factor * d[slot] / (2.0 * var[slot].sqrt()))
                .collect()
        };
        let mut all = quantities.iter().zip(&self.slots).map(|(q, &s)| grad(q, s));
        PointGradients {
            objective: all.next().unwrap_or_default(),
            constrained: all.collect(),
        }
    }

    /// The values at `x` and, when `gradients`, the gradients there by the small path
    /// ([`small_point`]); `None` where it does not apply (no affine model, a quantity other than σ or 3σ,
    /// see also [`small_point`]).
    fn small_point(
        &self,
        pb: &Problem,
        x: &[f64],
        scratch: &mut PointScratch,
        gradients: bool,
    ) -> Option<(PointValues, Option<PointGradients>)> {
        let quantities = sigma_quantities(pb)?;
        let model = SmallModel {
            evaluator: &self.evaluator,
            excitation: &pb.base.excitation,
            affine: self.affine.as_ref()?,
            outputs: &self.outputs,
        };
        let (var, dvar) = small_point(&model, &pb.params, x, gradients, scratch)?;
        let value = |q: &Quantity, slot: usize| {
            let st = PointStatistics {
                mean: None,
                variance: Some(var[slot]),
                lambda2: None,
                method: VarianceMethod::Lyapunov,
            };
            q.of_statistics(&st).ok()
        };
        let mut values = quantities.iter().zip(&self.slots).map(|(q, &s)| value(q, s));
        let objective = values.next()??;
        let values = PointValues {
            x: x.to_vec(),
            objective,
            constrained: values.collect::<Option<Vec<f64>>>()?,
        };
        let grads = gradients.then(|| self.sigma_gradients(&quantities, &var, &dvar));
        Some((values, grads))
    }

    fn values(&self, sys: &dyn FrequencyResponse, pb: &Problem, x: &[f64]) -> Result<PointValues> {
        let idx = self
            .outputs
            .iter()
            .map(|o| sys.output_index(o))
            .collect::<Result<Vec<_>>>()?;
        let st = self.evaluator.evaluate(sys, &pb.base.excitation, &idx)?;
        let mut q = std::iter::once(&pb.objective)
            .chain(pb.constraints.iter().map(|c| &c.quantity))
            .zip(&self.slots)
            .map(|(q, &k)| q.of_statistics(&st[k]));
        Ok(PointValues {
            x: x.to_vec(),
            objective: q.next().unwrap_or(Ok(f64::NAN))?,
            constrained: q.collect::<Result<Vec<_>>>()?,
        })
    }
}

/// The objective's and the constraints' quantities when every one is a σ or 3σ.
fn sigma_quantities<'p>(pb: &'p Problem) -> Option<Vec<&'p Quantity>> {
    let quantities: Vec<&Quantity> = std::iter::once(&pb.objective)
        .chain(pb.constraints.iter().map(|c| &c.quantity))
        .collect();
    let sigma_like = |q: &Quantity| matches!(q.kind, QuantityKind::Sigma(_) | QuantityKind::ThreeSigma(_));
    quantities.iter().all(|q| sigma_like(q)).then_some(quantities)
}

/// The value at dotted `key` of `root` (an array element by its index).
fn lookup<'t>(root: &'t toml::Table, key: &str) -> Option<&'t toml::Value> {
    let mut segs = key.split('.').map(str::trim);
    let mut v = root.get(segs.next()?)?;
    for s in segs {
        v = match v {
            toml::Value::Table(t) => t.get(s)?,
            toml::Value::Array(a) => a.get(s.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(v)
}
