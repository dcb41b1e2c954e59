//! A measured coherence table, interpolated linearly in the spatial frequency.

use super::{Coherence, CoherenceKind};
use crate::error::{Error, Result};

/// A coherence measured at spatial frequencies n_0 < n_1 < … (cycles/m), with values of a stated
/// [`CoherenceKind`] (ρ or γ²).
///
/// # Formula
/// The table's own quantity v (ρ or γ², as stated) is interpolated linearly in n, and ρ follows:
/// ```text
/// v(n) = v_k + (v_{k+1} − v_k)(n − n_k)/(n_{k+1} − n_k)   for n_k ≤ n ≤ n_{k+1}
/// v(n) = v_0 for n < n_0,    v(n) = v_last for n > n_last          (constant extrapolation)
/// ρ(n) = v(n) (amplitude table) or √v(n) (squared-coherence table);   ρ(−n) = ρ(n)
/// ```
/// Interpolating the tabulated quantity itself (not ρ from a γ² table) keeps the table exact at its nodes
/// and keeps v in [0, 1] between them.
///
/// **Extrapolation decision.** Outside the table the end values are held. Below n_0 the physical limit
/// is ρ → 1 as n → 0 (very long waves are common to both tracks), but the table does not say how fast:
/// holding v_0 invents nothing, whereas a ramp to 1 would invent a shape. Above n_last the measured
/// coherence is small and dominated by estimation noise and bias (E γ̂² ≈ 1/K for K averaged segments when
/// γ² = 0); a linear extrapolation could leave [0, 1]. Give a table that covers the band of interest.
///
/// # Errors
/// [`TabulatedCoherence::new`] names the offending index and value for: fewer than 2 points, different
/// lengths, non-finite or negative n, n not strictly ascending, values non-finite or outside [0, 1].
///
/// # Examples
/// ```
/// use stochvib::coherence::{Coherence, CoherenceKind, TabulatedCoherence};
/// let t = TabulatedCoherence::new(vec![0.0, 0.1, 0.5], vec![1.0, 0.64, 0.04],
///                                 CoherenceKind::SquaredCoherence).unwrap();
/// assert!((t.coherence_amplitude(0.1) - 0.8).abs() < 1e-15);      // √0.64
/// assert!((t.squared_coherence(0.3) - 0.34).abs() < 1e-15);       // midway in γ²
/// assert!((t.squared_coherence(9.0) - 0.04).abs() < 1e-15);       // held above the table
/// assert!(TabulatedCoherence::new(vec![0.0, 0.1], vec![1.0, 1.2],
///                                 CoherenceKind::SquaredCoherence).is_err());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedCoherence {
    n: Vec<f64>,
    values: Vec<f64>,
    kind: CoherenceKind,
}

impl TabulatedCoherence {
    /// Validates and stores the table: `n` in cycles/m (ascending), `values` of kind `kind`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(n: Vec<f64>, values: Vec<f64>, kind: CoherenceKind) -> Result<Self> {
        if n.len() != values.len() {
            return Err(Error::invalid(
                "coherence table",
                format!("{} frequencies, {} values", n.len(), values.len()),
                "need one value per frequency",
            ));
        }
        if n.len() < 2 {
            return Err(Error::invalid(
                "coherence table",
                format!("{} points", n.len()),
                "need at least 2 points to interpolate",
            ));
        }
        for (k, &nk) in n.iter().enumerate() {
            if !(nk.is_finite() && nk >= 0.0) {
                return Err(Error::invalid(
                    &format!("coherence table n[{k}]"),
                    nk,
                    "spatial frequency must be finite and >= 0 cycles/m",
                ));
            }
            if k > 0 && nk <= n[k - 1] {
                return Err(Error::invalid(
                    &format!("coherence table n[{k}]"),
                    nk,
                    format!("must be > n[{}] = {} (strictly ascending)", k - 1, n[k - 1]),
                ));
            }
        }
        for (k, &v) in values.iter().enumerate() {
            if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                return Err(Error::invalid(
                    &format!("coherence table {}[{k}]", kind.key()),
                    v,
                    "must be finite and in [0, 1]",
                ));
            }
        }
        Ok(TabulatedCoherence { n, values, kind })
    }

    /// The kind of the tabulated values.
    pub fn kind(&self) -> CoherenceKind {
        self.kind
    }

    /// The tabulated frequencies (cycles/m) and values.
    pub fn table(&self) -> (&[f64], &[f64]) {
        (&self.n, &self.values)
    }

    /// The interpolated table quantity v(n) (see the type's formula).
    pub fn value(&self, n: f64) -> f64 {
        if !n.is_finite() {
            return f64::NAN;
        }
        let n = n.abs();
        let last = self.n.len() - 1;
        if n <= self.n[0] {
            return self.values[0];
        }
        if n >= self.n[last] {
            return self.values[last];
        }
        // first index with n_k > n; 1 ≤ k ≤ last
        let k = self.n.partition_point(|&x| x <= n);
        let (n0, n1) = (self.n[k - 1], self.n[k]);
        let (v0, v1) = (self.values[k - 1], self.values[k]);
        v0 + (v1 - v0) * (n - n0) / (n1 - n0)
    }
}

impl Coherence for TabulatedCoherence {
    fn describe(&self) -> String {
        format!(
            "tabulated {} at {} frequencies {}..{} cycles/m (linear in n, ends held)",
            self.kind,
            self.n.len(),
            crate::numbers::num(self.n[0]),
            crate::numbers::num(self.n[self.n.len() - 1])
        )
    }

    fn coherence_amplitude(&self, n: f64) -> f64 {
        self.kind.to_amplitude(self.value(n))
    }

    fn squared_coherence(&self, n: f64) -> f64 {
        match self.kind {
            CoherenceKind::SquaredCoherence => self.value(n),
            CoherenceKind::CoherenceAmplitude => {
                let r = self.value(n);
                r * r
            }
        }
    }
}
