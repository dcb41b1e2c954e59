//! Piecewise-linear functions of time: the one representation of speed profiles, envelopes and
//! parameter schedules.

use crate::error::{Error, Result};

/// A continuous piecewise-linear function of time through the points (t_k, y_k), constant before the
/// first and after the last point.
///
/// # Formula
/// ```text
/// y(t) = y_k + (y_{k+1} − y_k)(t − t_k)/(t_{k+1} − t_k)   for t_k ≤ t ≤ t_{k+1}
/// y(t) = y_0 for t < t_0,   y(t) = y_{K} for t > t_K
/// ```
///
/// # Errors
/// [`PiecewiseLinear::new`] refuses an empty table, tables of different lengths, non-finite values and
/// times that do not increase strictly (a repeated time gives two values at one time: not a function of
/// time), naming the element (`time[k]`, `value[k]`).
///
/// # Examples
/// ```
/// use stochvib::transient::PiecewiseLinear;
/// let v = PiecewiseLinear::new(vec![0.0, 10.0], vec![5.0, 15.0]).unwrap();
/// assert_eq!(v.value(5.0), 10.0);
/// assert_eq!(v.value(20.0), 15.0);
/// assert_eq!(v.integral(10.0), 100.0);
/// assert!(PiecewiseLinear::new(vec![0.0, 2.0, 1.0], vec![0.0; 3]).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PiecewiseLinear {
    t: Vec<f64>,
    y: Vec<f64>,
}

impl PiecewiseLinear {
    /// The function through the points (t\[k\], y\[k\]).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(t: Vec<f64>, y: Vec<f64>) -> Result<Self> {
        if t.is_empty() || t.len() != y.len() {
            return Err(Error::invalid(
                "time",
                format!("{} times, {} values", t.len(), y.len()),
                "a table needs at least one point and one value per time",
            ));
        }
        for (k, (&tk, &yk)) in t.iter().zip(&y).enumerate() {
            if !tk.is_finite() {
                return Err(Error::invalid(&format!("time[{k}]"), tk, "times must be finite"));
            }
            if !yk.is_finite() {
                return Err(Error::invalid(&format!("value[{k}]"), yk, "values must be finite"));
            }
            if k > 0 && tk <= t[k - 1] {
                return Err(Error::invalid(
                    &format!("time[{k}]"),
                    tk,
                    format!(
                        "not after time[{}] = {}: the table is not a function of time (times must increase \
                         strictly; a jump needs two distinct times)",
                        k - 1,
                        t[k - 1]
                    ),
                ));
            }
        }
        Ok(PiecewiseLinear { t, y })
    }

    /// The constant function y.
    ///
    /// # Errors
    /// Non-finite y.
    pub fn constant(y: f64) -> Result<Self> {
        Self::new(vec![0.0], vec![y])
    }

    /// The times of the table.
    pub fn times(&self) -> &[f64] {
        &self.t
    }

    /// The values of the table.
    pub fn values(&self) -> &[f64] {
        &self.y
    }

    /// Whether the function is constant.
    pub fn is_constant(&self) -> bool {
        self.y.iter().all(|v| *v == self.y[0])
    }

    /// The segment k with t_k ≤ t < t_{k+1}, clamped to the table.
    fn segment(&self, t: f64) -> usize {
        self.t
            .partition_point(|x| *x <= t)
            .saturating_sub(1)
            .min(self.t.len().saturating_sub(2))
    }

    /// y(t).
    pub fn value(&self, t: f64) -> f64 {
        let n = self.t.len();
        if n == 1 || t <= self.t[0] {
            return self.y[0];
        }
        if t >= self.t[n - 1] {
            return self.y[n - 1];
        }
        let k = self.segment(t);
        let w = (t - self.t[k]) / (self.t[k + 1] - self.t[k]);
        self.y[k] + w * (self.y[k + 1] - self.y[k])
    }

    /// dy/dt at t (the right derivative at a point of the table; 0 outside the table).
    pub fn slope(&self, t: f64) -> f64 {
        let n = self.t.len();
        if n == 1 || t < self.t[0] || t >= self.t[n - 1] {
            return 0.0;
        }
        let k = self.segment(t);
        (self.y[k + 1] - self.y[k]) / (self.t[k + 1] - self.t[k])
    }

    /// ∫₀ᵗ y(s) ds (t ≥ 0; negative t integrates backwards), exact for the piecewise-linear function.
    pub fn integral(&self, t: f64) -> f64 {
        self.antiderivative(t) - self.antiderivative(0.0)
    }

    /// An antiderivative Y with Y(t_0) = 0.
    fn antiderivative(&self, t: f64) -> f64 {
        let (t0, n) = (self.t[0], self.t.len());
        if t <= t0 {
            return self.y[0] * (t - t0);
        }
        let mut acc = 0.0;
        for k in 0..n - 1 {
            let (a, b) = (self.t[k], self.t[k + 1]);
            if t <= a {
                return acc;
            }
            let e = t.min(b);
            acc += 0.5 * (self.y[k] + self.value(e)) * (e - a);
            if t <= b {
                return acc;
            }
        }
        acc + self.y[n - 1] * (t - self.t[n - 1])
    }

    /// The smallest and largest value.
    pub fn range(&self) -> (f64, f64) {
        let lo = self.y.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = self.y.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    }
}
