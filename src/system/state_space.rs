//! State-space systems ẋ = Ax + Bu, y = Cx + Du + Eu̇.

use super::{FrequencyResponse, OutputInfo};
use crate::error::{Error, Result};
use crate::spectrum::Asymptote;
use nalgebra::{Complex, DMatrix};

/// A continuous-time state-space system with derivative feedthrough.
///
/// # Formula
/// ```text
/// ẋ = A x + B u,   y = C x + D u + E u̇,     H(s) = C (sI − A)⁻¹ B + D + s E
/// ```
/// As ω → ∞, H(iω) ≈ iω E + D + C B/(iω) + C A B/(iω)² + … (Markov parameters), which gives the exact
/// high-frequency slope of |H_ij|² used for divergence detection.
///
/// # Errors
/// [`StateSpace::new`] rejects inconsistent dimensions, non-finite entries and output lists of the wrong
/// length. Stability is not required here (modal analysis needs undamped systems); the response methods
/// that need it check it.
///
/// # Examples
/// ```
/// use stochvib::system::{StateSpace, OutputInfo, FrequencyResponse};
/// use nalgebra::DMatrix;
/// // SDOF oscillator ẍ + 2ζω ẋ + ω² x = u, output x
/// let (w, z) = (10.0, 0.05);
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * z * w]);
/// let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
/// let c = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
/// let ss = StateSpace::new(a, b, c, None, None, vec![OutputInfo::new("x", "m")]).unwrap();
/// let h0 = ss.static_gain().unwrap();
/// assert!((h0[(0, 0)] - 1.0 / (w * w)).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct StateSpace {
    /// State matrix (n × n).
    pub a: DMatrix<f64>,
    /// Input matrix (n × m).
    pub b: DMatrix<f64>,
    /// Output matrix (p × n).
    pub c: DMatrix<f64>,
    /// Direct feedthrough (p × m).
    pub d: DMatrix<f64>,
    /// Derivative feedthrough (p × m): y contains E u̇.
    pub e: DMatrix<f64>,
    outputs: Vec<OutputInfo>,
}

/// The relative resolution of [`StateSpace::require_stable`]: the largest real part of A's eigenvalues must
/// lie below −10⁻¹² max|Aᵢⱼ| (eigenvalues are computed to about ε‖A‖; a decay rate below this cannot be
/// told from zero).
pub const STABILITY_RESOLUTION: f64 = 1e-12;

impl StateSpace {
    /// Builds a state-space system; `d` and `e` default to zero.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(
        a: DMatrix<f64>,
        b: DMatrix<f64>,
        c: DMatrix<f64>,
        d: Option<DMatrix<f64>>,
        e: Option<DMatrix<f64>>,
        outputs: Vec<OutputInfo>,
    ) -> Result<Self> {
        let n = a.nrows();
        let (m, p) = (b.ncols(), c.nrows());
        let d = d.unwrap_or_else(|| DMatrix::zeros(p, m));
        let e = e.unwrap_or_else(|| DMatrix::zeros(p, m));
        let dims = |name: &str, mat: &DMatrix<f64>, r: usize, c: usize| -> Result<()> {
            if mat.nrows() != r || mat.ncols() != c {
                return Err(Error::invalid(
                    name,
                    format!("{}x{}", mat.nrows(), mat.ncols()),
                    format!("must be {r}x{c} (states n = {n}, inputs m = {m}, outputs p = {p})"),
                ));
            }
            if mat.iter().any(|v| !v.is_finite()) {
                return Err(Error::invalid(name, "matrix", "entries must be finite"));
            }
            Ok(())
        };
        dims("A", &a, n, n)?;
        dims("B", &b, n, m)?;
        dims("C", &c, p, n)?;
        dims("D", &d, p, m)?;
        dims("E", &e, p, m)?;
        if outputs.len() != p {
            return Err(Error::invalid(
                "outputs",
                outputs.len(),
                format!("need one name per output row ({p})"),
            ));
        }
        Ok(StateSpace { a, b, c, d, e, outputs })
    }

    /// Number of states.
    pub fn n_states(&self) -> usize {
        self.a.nrows()
    }

    /// Largest real part of the eigenvalues of A (< 0 for an asymptotically stable system).
    pub fn spectral_abscissa(&self) -> f64 {
        if self.n_states() == 0 {
            return f64::NEG_INFINITY;
        }
        self.a
            .complex_eigenvalues()
            .iter()
            .map(|l| l.re)
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Checks asymptotic stability.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the largest real part of an eigenvalue.
    pub fn require_stable(&self) -> Result<()> {
        let s = self.spectral_abscissa();
        let scale = self.a.amax().max(1e-300);
        if s >= -STABILITY_RESOLUTION * scale {
            return Err(Error::invalid(
                "A",
                format!("max Re(eigenvalue) = {s:e}"),
                "the system is not asymptotically stable: no stationary response exists",
            ));
        }
        Ok(())
    }

    /// Keeps only the outputs with the given row indices.
    ///
    /// # Errors
    /// An index out of range.
    pub fn select_outputs(&self, rows: &[usize]) -> Result<StateSpace> {
        let p = self.c.nrows();
        if let Some(&r) = rows.iter().find(|&&r| r >= p) {
            return Err(Error::invalid("output index", r, format!("system has {p} outputs")));
        }
        let pick = |m: &DMatrix<f64>| DMatrix::from_fn(rows.len(), m.ncols(), |i, j| m[(rows[i], j)]);
        Ok(StateSpace {
            a: self.a.clone(),
            b: self.b.clone(),
            c: pick(&self.c),
            d: pick(&self.d),
            e: pick(&self.e),
            outputs: rows.iter().map(|&r| self.outputs[r].clone()).collect(),
        })
    }

    /// Sums the input columns with the given weights into a single input (e.g. one road felt by several
    /// inputs with no delay).
    ///
    /// # Errors
    /// Wrong weight count.
    pub fn combine_inputs(&self, weights: &[f64]) -> Result<StateSpace> {
        let m = self.b.ncols();
        if weights.len() != m {
            return Err(Error::invalid(
                "weights",
                weights.len(),
                format!("system has {m} inputs"),
            ));
        }
        let w = DMatrix::from_column_slice(m, 1, weights);
        Ok(StateSpace {
            a: self.a.clone(),
            b: &self.b * &w,
            c: self.c.clone(),
            d: &self.d * &w,
            e: &self.e * &w,
            outputs: self.outputs.clone(),
        })
    }
}

impl FrequencyResponse for StateSpace {
    fn n_inputs(&self) -> usize {
        self.b.ncols()
    }
    fn outputs(&self) -> &[OutputInfo] {
        &self.outputs
    }
    fn response(&self, omega: f64) -> DMatrix<Complex<f64>> {
        let n = self.n_states();
        let s = Complex::new(0.0, omega);
        let cplx = |m: &DMatrix<f64>| m.map(|v| Complex::new(v, 0.0));
        let mut h = cplx(&self.d) + cplx(&self.e) * s;
        if n > 0 {
            let si_a = DMatrix::from_fn(n, n, |i, j| {
                let v = Complex::new(-self.a[(i, j)], 0.0);
                if i == j {
                    v + s
                } else {
                    v
                }
            });
            match si_a.lu().solve(&cplx(&self.b)) {
                Some(x) => h += cplx(&self.c) * x,
                None => h.fill(Complex::new(f64::INFINITY, 0.0)),
            }
        }
        h
    }
    fn static_gain(&self) -> Option<DMatrix<f64>> {
        let n = self.n_states();
        if n == 0 {
            return Some(self.d.clone());
        }
        let x = self.a.clone().lu().solve(&self.b)?;
        let g = &self.d - &self.c * x;
        g.iter().all(|v| v.is_finite()).then_some(g)
    }
    fn high_frequency(&self) -> Vec<Vec<Asymptote>> {
        let (p, m) = (self.c.nrows(), self.b.ncols());
        // Markov parameters M₀ = E (|H|² ~ ω²), M₁ = D (ω⁰), M₂ = CB (ω⁻²), M₃ = CAB (ω⁻⁴), ...
        // E and D are taken as given; C Aᵏ B entries below 1e-12 ‖C‖‖A‖ᵏ‖B‖ are roundoff zeros.
        let mut markov: Vec<(DMatrix<f64>, f64)> = vec![(self.e.clone(), 0.0), (self.d.clone(), 0.0)];
        let (na, nb, nc) = (self.a.norm(), self.b.norm(), self.c.norm());
        let mut ak_b = self.b.clone();
        for k in 0..=self.n_states() {
            markov.push((&self.c * &ak_b, 1e-12 * nc * nb * na.powi(k as i32)));
            ak_b = &self.a * ak_b;
        }
        let mut out = vec![vec![Asymptote::Vanishing; m]; p];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, slot) in row.iter_mut().enumerate() {
                if let Some((k, (mk, _))) = markov.iter().enumerate().find(|(_, (mk, tol))| mk[(i, j)].abs() > *tol) {
                    let v = mk[(i, j)];
                    *slot = Asymptote::Power {
                        exponent: 2.0 * (1.0 - k as f64),
                        coefficient: v * v,
                    };
                }
            }
        }
        out
    }
    fn low_frequency(&self) -> Vec<Vec<Asymptote>> {
        let (p, m, n) = (self.c.nrows(), self.b.ncols(), self.n_states());
        // Taylor series at s = 0: H(s) = h₀ + h₁ s + h₂ s² + …, h₀ = D − CA⁻¹B, h₁ = E − CA⁻²B,
        // h_k = −CA^{−(k+1)}B; a singular A (rigid-body mode, integrator) makes |H|² blow up like ω^{−2}.
        let lu = self.a.clone().lu();
        let Some(mut x) = (if n == 0 {
            Some(DMatrix::zeros(0, m))
        } else {
            lu.solve(&self.b)
        }) else {
            let inf = Asymptote::Power {
                exponent: -2.0,
                coefficient: f64::INFINITY,
            };
            return vec![vec![inf; m]; p];
        };
        let mut terms: Vec<(DMatrix<f64>, f64)> = Vec::new();
        let scale = |x: &DMatrix<f64>| 1e-12 * self.c.norm() * x.norm();
        terms.push((&self.d - &self.c * &x, 1e-12 * self.d.norm() + scale(&x)));
        for k in 1..=n.max(1) + 1 {
            x = if n == 0 { x } else { lu.solve(&x).unwrap_or(x) };
            let mut h = -(&self.c * &x);
            if k == 1 {
                h += &self.e;
            }
            terms.push((h, scale(&x) + if k == 1 { 1e-12 * self.e.norm() } else { 0.0 }));
        }
        let mut out = vec![vec![Asymptote::Vanishing; m]; p];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, slot) in row.iter_mut().enumerate() {
                if let Some((k, (h, _))) = terms.iter().enumerate().find(|(_, (h, tol))| h[(i, j)].abs() > *tol) {
                    *slot = Asymptote::Power {
                        exponent: 2.0 * k as f64,
                        coefficient: h[(i, j)].powi(2),
                    };
                }
            }
        }
        out
    }
    fn natural_frequencies(&self) -> Vec<f64> {
        if self.n_states() == 0 {
            return Vec::new();
        }
        let mut w: Vec<f64> = self
            .a
            .complex_eigenvalues()
            .iter()
            .map(|l| l.norm())
            .filter(|x| *x > 0.0 && x.is_finite())
            .collect();
        w.sort_by(f64::total_cmp);
        w.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * b.abs());
        w
    }
    fn state_space(&self) -> Option<&StateSpace> {
        Some(self)
    }
}
