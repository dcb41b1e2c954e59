//! Time-varying systems: a linear model whose parameters follow a schedule (frozen coefficients).

use super::PiecewiseLinear;
use crate::error::{Error, Result};
use crate::system::StateSpace;
use nalgebra::DVector;
use std::sync::Arc;

/// A linear system ẋ = A(t)x + B(t)u + f(t), y = C(t)x + D(t)u + E(t)u̇ whose matrices are those of a model
/// evaluated at the parameter values of time t ("frozen coefficients": the model's equations are taken at
/// every instant with the current parameters; the time derivatives of the parameters do not enter, which is
/// the source articles' assumption of a slowly varying rope length, valid when the parameters change little
/// over one period of the slowest mode).
pub trait SystemFamily: Send + Sync + std::fmt::Debug {
    /// The state space at time t (s), with the deterministic forcing f(t) of the states if the model has
    /// one (a start-up torque).
    ///
    /// # Errors
    /// A parameter value the model refuses at t.
    fn at(&self, t: f64) -> Result<ModelAt>;
    /// Times where the parameters have kinks or jumps (the exact route ends its steps there).
    fn knots(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Whether the matrices do not depend on t.
    fn is_constant(&self) -> bool;
    /// One line: the model and its schedules.
    fn describe(&self) -> String;
}

/// A family's model at one time.
#[derive(Debug, Clone)]
pub struct ModelAt {
    /// ẋ = Ax + Bu, y = Cx + Du + Eu̇.
    pub ss: StateSpace,
    /// f(t), added to ẋ (n entries), if any.
    pub forcing: Option<DVector<f64>>,
}

/// A time-invariant system (the stationary case as a family).
#[derive(Debug, Clone)]
pub struct FixedSystem {
    ss: StateSpace,
    forcing: Option<DVector<f64>>,
    description: String,
}

impl FixedSystem {
    /// The constant family of `ss`, with an optional constant forcing of the states.
    ///
    /// # Errors
    /// A forcing of the wrong length or not finite.
    pub fn new(ss: StateSpace, forcing: Option<DVector<f64>>, description: &str) -> Result<Self> {
        if let Some(f) = &forcing
            && (f.len() != ss.n_states() || f.iter().any(|v| !v.is_finite()))
        {
            return Err(Error::invalid(
                "forcing",
                f.len(),
                format!("needs {} finite entries, one per state", ss.n_states()),
            ));
        }
        Ok(FixedSystem {
            ss,
            forcing,
            description: description.to_string(),
        })
    }
}

impl SystemFamily for FixedSystem {
    fn at(&self, _t: f64) -> Result<ModelAt> {
        Ok(ModelAt {
            ss: self.ss.clone(),
            forcing: self.forcing.clone(),
        })
    }
    fn is_constant(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        self.description.clone()
    }
}

/// One scheduled parameter: its name (a scenario key or a model's variable), unit and values over time.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Schedule {
    /// The parameter, e.g. `model.suspension_damping` or `hanging_length`.
    pub name: String,
    /// Its SI unit.
    pub unit: String,
    /// Its values over time.
    pub profile: PiecewiseLinear,
}

/// A builder of the model's state space (and forcing) from the values of its scheduled parameters.
pub type FamilyBuilder = dyn Fn(&[f64]) -> Result<(StateSpace, Option<DVector<f64>>)> + Send + Sync;

/// A model whose parameters follow schedules: at time t the builder gets the scheduled values.
#[derive(Clone)]
pub struct ScheduledSystem {
    schedules: Vec<Schedule>,
    build: Arc<FamilyBuilder>,
    description: String,
}

impl std::fmt::Debug for ScheduledSystem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ScheduledSystem")
            .field("schedules", &self.schedules)
            .field("description", &self.description)
            .finish()
    }
}

impl ScheduledSystem {
    /// The family built by `build` from the values of `schedules` at each time.
    pub fn new(schedules: Vec<Schedule>, build: Arc<FamilyBuilder>, description: &str) -> Self {
        ScheduledSystem {
            schedules,
            build,
            description: description.to_string(),
        }
    }

    /// The schedules.
    pub fn schedules(&self) -> &[Schedule] {
        &self.schedules
    }

    fn values(&self, t: f64) -> Vec<f64> {
        self.schedules.iter().map(|s| s.profile.value(t)).collect()
    }
}

impl SystemFamily for ScheduledSystem {
    fn at(&self, t: f64) -> Result<ModelAt> {
        (self.build)(&self.values(t)).map(|(ss, forcing)| ModelAt { ss, forcing })
    }
    fn knots(&self) -> Vec<f64> {
        let mut k: Vec<f64> = self.schedules.iter().flat_map(|s| s.profile.times().to_vec()).collect();
        k.sort_by(f64::total_cmp);
        k.dedup();
        k
    }
    fn is_constant(&self) -> bool {
        self.schedules.iter().all(|s| s.profile.is_constant())
    }
    fn describe(&self) -> String {
        let s: Vec<String> = self
            .schedules
            .iter()
            .map(|s| format!("{} scheduled over {} points", s.name, s.profile.times().len()))
            .collect();
        format!("{} ({})", self.description, s.join(", "))
    }
}

/// The largest real part of the eigenvalues of A(t) at `times`, refused at the first time where the
/// system grows exponentially.
///
/// # Formula
/// The frozen system at t is unstable when max Re λ(A(t)) > 10⁻⁹·max|A_ij| (a growth rate beyond the
/// rounding of the eigensolver). Eigenvalues on the imaginary axis (a rigid-body mode of a hoist, an
/// undamped mode) are accepted: the response of such a mode to noise grows like a random walk, not
/// exponentially; its absolute coordinates have no stationary state.
///
/// # Errors
/// [`Error::InvalidParameter`] naming the time (`schedule at t = … s`) and the eigenvalue; a model that
/// cannot be built at some time (its error, with the time).
pub fn check_stability(family: &dyn SystemFamily, times: &[f64]) -> Result<f64> {
    let mut worst = f64::NEG_INFINITY;
    for &t in times {
        let ss = family.at(t).map_err(|e| at_time(e, t))?.ss;
        let s = ss.spectral_abscissa();
        let scale = ss.a.amax().max(1e-300);
        if s > 1e-9 * scale {
            return Err(Error::invalid(
                &format!("schedule at t = {t} s"),
                format!("max Re(eigenvalue) = {s:e} 1/s"),
                format!(
                    "the system is unstable at t = {t} s ({}): its response grows like e^({s:.3e} t); check the \
                     scheduled values at that time",
                    family.describe()
                ),
            ));
        }
        worst = worst.max(s);
    }
    Ok(worst)
}

/// `e` with the time t added to its name.
pub(crate) fn at_time(e: Error, t: f64) -> Error {
    match e {
        Error::InvalidParameter { name, value, reason } => Error::InvalidParameter {
            name: format!("{name} at t = {t} s"),
            value,
            reason,
        },
        other => other,
    }
}
