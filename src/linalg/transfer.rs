//! The numerator and denominator polynomials of a single-input single-output state-space transfer function,
//! computed in a frequency-scaled variable so that stiff systems (natural frequencies spanning decades) keep
//! their digits.
//!
//! # Formula
//! For H(s) = h (sI − A)⁻¹ g + f with A of order n and eigenvalues λ_j, let ω_s = (Π|λ_j|)^{1/n} (the
//! geometric mean of the natural frequencies) and z = s/ω_s. Then H(ω_s z) = N(z)/D(z) with
//! ```text
//! D(z) = Π_j (z − λ_j/ω_s)                          (monic, from the eigenvalues)
//! N(z) = D(z) · H(ω_s z)                            (degree ≤ n)
//! ```
//! N is recovered from its values at the M = n + 1 roots of unity z_k = e^{2πik/M} by the inverse discrete
//! Fourier transform, N_m = (1/M) Σ_k N(z_k) z_k^{−m}, where each H(ω_s z_k) is one complex LU solve. On
//! the unit circle of the scaled variable every factor (z − μ_j) has a modulus of order one, so no
//! coefficient is the small difference of large ones (as it is when N is taken from
//! det(sI − A + g h) − det(sI − A) in the variable s). A is balanced first (Osborne/Parlett–Reinsch,
//! powers of two) so that the eigenvalues of a stiff system keep their relative accuracy.

use crate::error::{Error, Result};
use nalgebra::{Complex, DMatrix};
use std::f64::consts::PI;

/// N(z), D(z) (ascending coefficients in z = s/ω_s) and ω_s of h (sI − A)⁻¹ g + f (see the module docs).
///
/// # Errors
/// [`Error::InvalidParameter`] for mismatched shapes or a zero eigenvalue (no scale: an integrator);
/// [`Error::Numerical`] for a singular solve on the circle (an eigenvalue on it to rounding).
///
/// # Examples
/// ```
/// use nalgebra::DMatrix;
/// use stochvib::linalg::transfer::scaled_transfer_polynomials;
/// // H(s) = 1/(s² + 0.2 s + 100): ω_s = 10, H(10 z) = 0.01/(z² + 0.02 z + 1)
/// let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -100.0, -0.2]);
/// let g = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
/// let h = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
/// let (n, d, w) = scaled_transfer_polynomials(&a, &g, &h, 0.0).unwrap();
/// assert!((w - 10.0).abs() < 1e-12);
/// assert!((d[1] - 0.02).abs() < 1e-14 && (d[0] - 1.0).abs() < 1e-14);
/// assert!((n[0] - 0.01).abs() < 1e-15 && n[1].abs() < 1e-15);
/// ```
pub fn scaled_transfer_polynomials(
    a: &DMatrix<f64>,
    g: &DMatrix<f64>,
    h: &DMatrix<f64>,
    f: f64,
) -> Result<(Vec<f64>, Vec<f64>, f64)> {
    let n = a.nrows();
    if a.ncols() != n || g.shape() != (n, 1) || h.shape() != (1, n) {
        return Err(Error::invalid(
            "state space",
            format!("A {:?}, g {:?}, h {:?}", a.shape(), g.shape(), h.shape()),
            "need A n×n, g n×1, h 1×n",
        ));
    }
    if n == 0 {
        return Ok((vec![f], vec![1.0], 1.0));
    }
    // balanced (D⁻¹AD, D⁻¹g, hD with D powers of two: exact) so that the eigenvalues of a stiff system keep
    // their relative accuracy
    let dg = super::lyapunov::balance_diagonal(a);
    let a = DMatrix::from_fn(n, n, |i, j| a[(i, j)] * dg[j] / dg[i]);
    let g = DMatrix::from_fn(n, 1, |i, _| g[(i, 0)] / dg[i]);
    let h = DMatrix::from_fn(1, n, |_, j| h[(0, j)] * dg[j]);
    let (a, g, h) = (&a, &g, &h);
    let ev = a.complex_eigenvalues();
    let log_mean = ev.iter().map(|l| l.norm().ln()).sum::<f64>() / n as f64;
    let ws = log_mean.exp();
    if !(ws.is_finite() && ws > 0.0) || ev.iter().any(|l| l.norm() == 0.0) {
        return Err(Error::invalid(
            "A",
            "eigenvalue 0",
            "a zero eigenvalue (an integrator) has no frequency scale",
        ));
    }
    let mu: Vec<Complex<f64>> = ev.iter().map(|l| l / ws).collect();
    // D(z) = Π (z − μ_j), built by repeated multiplication (complex, then the real parts)
    let mut d = vec![Complex::new(1.0, 0.0)];
    for m in &mu {
        let mut next = vec![Complex::new(0.0, 0.0); d.len() + 1];
        for (k, c) in d.iter().enumerate() {
            next[k + 1] += c;
            next[k] -= c * m;
        }
        d = next;
    }
    let den: Vec<f64> = d.iter().map(|c| c.re).collect();
    let ac = a.map(|v| Complex::new(v, 0.0));
    let gc = g.map(|v| Complex::new(v, 0.0));
    let hc = h.map(|v| Complex::new(v, 0.0));
    let m_pts = n + 1;
    let mut values = Vec::with_capacity(m_pts);
    for k in 0..m_pts {
        let z = Complex::from_polar(1.0, 2.0 * PI * k as f64 / m_pts as f64);
        let s = z * ws;
        let lhs = DMatrix::<Complex<f64>>::identity(n, n) * s - &ac;
        let x = lhs.lu().solve(&gc).ok_or_else(|| Error::Numerical {
            what: "transfer polynomials".into(),
            reason: format!("sI − A singular at s = {s}"),
        })?;
        let hv = (&hc * x)[(0, 0)] + f;
        let dv = mu.iter().fold(Complex::new(1.0, 0.0), |acc, m| acc * (z - m));
        values.push(hv * dv);
    }
    let mut num: Vec<f64> = (0..m_pts)
        .map(|mdeg| {
            let sum: Complex<f64> = values
                .iter()
                .enumerate()
                .map(|(k, v)| v * Complex::from_polar(1.0, -2.0 * PI * (k * mdeg) as f64 / m_pts as f64))
                .sum();
            sum.re / m_pts as f64
        })
        .collect();
    // the leading coefficient of D·H is f exactly (D is monic): no rounding noise in degree n
    num[n] = f;
    Ok((num, den, ws))
}
