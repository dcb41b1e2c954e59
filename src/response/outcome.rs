//! What a method gave for one quantity (a variance, a spectral moment): a value, or exactly why there is
//! none — infinite, not converged (with the estimate and what to raise), not applicable, or computed but
//! unreliable. The four are different answers and are never printed alike.

use crate::error::Error;
use crate::quad_oscillatory::OscillatoryOptions;
use serde::Serialize;

/// The outcome of one method for one quantity.
///
/// # Examples
/// ```
/// use stochvib::response::Outcome;
/// let o = Outcome::Value { value: 2.0, error_estimate: None };
/// assert_eq!(o.value(), Some(2.0));
/// assert!(Outcome::Divergent { reason: "S ~ ω⁻¹".into() }.value().is_none());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "kebab-case")]
pub enum Outcome {
    /// A finite value, with an absolute error estimate where the method has one (quadrature).
    Value {
        /// The value.
        value: f64,
        /// Absolute error estimate.
        error_estimate: Option<f64>,
    },
    /// The quantity is infinite; the diagnosis (from the asymptotic slopes or a white-noise feedthrough)
    /// and what finite question could be asked instead.
    Divergent {
        /// Why it diverges.
        reason: String,
    },
    /// A finite quantity the method did not resolve to its tolerance.
    NotConverged {
        /// Best estimate reached.
        estimate: f64,
        /// Its absolute error estimate.
        error_estimate: f64,
        /// Integrand evaluations used.
        evaluations: usize,
        /// Why it stopped, and which option raises the effort.
        reason: String,
    },
    /// The method does not apply to this problem.
    NotApplicable {
        /// Why.
        reason: String,
    },
    /// The method computed a value it cannot vouch for (ill-conditioned, or in disagreement with an
    /// exact route); never used as a result.
    Unreliable {
        /// The value computed.
        value: f64,
        /// Why it is not trusted.
        reason: String,
    },
    /// Any other failure of the method.
    Failed {
        /// What went wrong.
        reason: String,
    },
}

impl Outcome {
    /// The value, when there is one to use (not for [`Outcome::Unreliable`]).
    pub fn value(&self) -> Option<f64> {
        match self {
            Outcome::Value { value, .. } => Some(*value),
            _ => None,
        }
    }

    /// Whether the quantity is infinite.
    pub fn is_divergent(&self) -> bool {
        matches!(self, Outcome::Divergent { .. })
    }

    /// From a method's result; `effort` names the options that raise the effort of a quadrature that did
    /// not converge.
    pub fn from_result(r: &crate::Result<f64>, error_estimate: Option<f64>, effort: &OscillatoryOptions) -> Outcome {
        match r {
            Ok(v) => Outcome::Value {
                value: *v,
                error_estimate,
            },
            Err(e) => Outcome::from_error(e, effort),
        }
    }

    /// The outcome of a method that failed with `e`.
    pub fn from_error(e: &Error, effort: &OscillatoryOptions) -> Outcome {
        match e {
            Error::Divergent { .. } => Outcome::Divergent { reason: e.to_string() },
            Error::Quadrature {
                what,
                estimate,
                abs_error,
                evaluations,
                reason,
            } => Outcome::NotConverged {
                estimate: *estimate,
                error_estimate: *abs_error,
                evaluations: *evaluations,
                reason: format!(
                    "quadrature of {what} stopped: {reason}; raise [analysis.quadrature] max_subintervals (now {}) \
                     or max_half_periods (now {}), or --max-subintervals / --max-half-periods, or loosen rel_tol \
                     (now {:e})",
                    effort.max_subintervals, effort.max_half_periods, effort.rel_tol
                ),
            },
            Error::NotApplicable { reason, .. } => Outcome::NotApplicable { reason: reason.clone() },
            Error::Inaccurate { value, reason, .. } => Outcome::Unreliable {
                value: *value,
                reason: reason.clone(),
            },
            other => Outcome::Failed {
                reason: other.to_string(),
            },
        }
    }

    /// One line for a report: the value, or the kind of non-answer and its reason.
    pub fn describe(&self) -> String {
        match self {
            Outcome::Value { value, .. } => format!("{value:.6e}"),
            Outcome::Divergent { reason } => format!("infinite: {reason}"),
            Outcome::NotConverged {
                estimate,
                error_estimate,
                evaluations,
                reason,
            } => format!(
                "not converged (estimate {estimate:.6e} ± {error_estimate:.1e} after {evaluations} evaluations): {reason}"
            ),
            Outcome::NotApplicable { reason } => format!("not available: {reason}"),
            Outcome::Unreliable { value, reason } => format!("unreliable ({value:.6e}): {reason}"),
            Outcome::Failed { reason } => format!("failed: {reason}"),
        }
    }
}
