//! The confidence interval of an estimate, and its comparison with an analytic value.

/// A two-sided confidence interval around an estimate (the one interval type of the crate).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Interval {
    /// Point estimate.
    pub estimate: f64,
    /// Lower end.
    pub lower: f64,
    /// Upper end.
    pub upper: f64,
    /// Confidence level 1 − p (e.g. 0.95).
    pub confidence: f64,
}

impl Interval {
    /// Whether `value` lies in [lower, upper].
    pub fn covers(&self, value: f64) -> bool {
        self.lower <= value && value <= self.upper
    }
    /// The comparison of this interval with an analytic value.
    pub fn compare(&self, analytic: f64) -> Comparison {
        Comparison {
            analytic,
            interval: *self,
            covers: self.covers(analytic),
        }
    }
}

/// A Monte Carlo estimate compared with its analytic value.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Comparison {
    /// The analytic value.
    pub analytic: f64,
    /// The Monte Carlo interval.
    pub interval: Interval,
    /// Whether the interval covers the analytic value.
    pub covers: bool,
}
