//! The discrete first-order-hold transfer function on many frequencies at once, through one complex Schur
//! decomposition of the transition matrix: O(n²m + pnm) per frequency without a factorisation or an
//! allocation, for the kernel design of the streamed spectral route on grids of millions of points.

use super::foh;
use crate::error::Result;
use crate::system::StateSpace;
use nalgebra::DMatrix;
use realfft::num_complex::Complex;

type C64 = Complex<f64>;

/// H_d(ω) = C (zI − Φ)⁻¹ (Γ₀ + Γ₁ z) + D (+ iω E), z = e^{iωΔt}, of a first-order-hold discretisation
/// (Φ, Γ₀, Γ₁ from [`foh`]), evaluated with the complex Schur form Φ = Q T Qᴴ.
///
/// # Formula
/// ```text
/// (zI − Φ)⁻¹ = Q (zI − T)⁻¹ Qᴴ,   H_d(ω) = (CQ) y + D,   (zI − T) y = QᴴΓ₀ + z QᴴΓ₁
/// ```
/// with T upper triangular, so y comes by back substitution: y_i = (r_i + Σ_{j>i} T_ij y_j)/(z − T_ii).
/// The decomposition is accepted only when T is triangular to 1e-13‖Φ‖ and ‖QTQᴴ − Φ‖ ≤ 1e-12‖Φ‖
/// (Q is unitary, so the evaluation is then as accurate as an LU solve per frequency).
///
/// # Errors
/// [`foh`]'s errors. A decomposition that fails the checks gives `Ok(None)` (the caller solves per
/// frequency instead).
///
/// # Examples
/// ```
/// use stochvib::simulate::transfer_grid::SchurTransfer;
/// use stochvib::system::{StateSpace, OutputInfo};
/// use nalgebra::DMatrix;
/// // ẋ = −x + u, y = x: at ω = 0 the discrete gain of the first-order hold is the static gain 1
/// let ss = StateSpace::new(
///     DMatrix::from_element(1, 1, -1.0), DMatrix::from_element(1, 1, 1.0),
///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("x", "m")],
/// ).unwrap();
/// let t = SchurTransfer::new(&ss, 0.01).unwrap().unwrap();
/// let mut h = vec![Default::default(); 1];
/// let mut work = t.work();
/// t.eval(0.0, false, &mut work, &mut h);
/// assert!((h[0].re - 1.0).abs() < 1e-12 && h[0].im.abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct SchurTransfer {
    n: usize,
    m: usize,
    p: usize,
    dt: f64,
    /// T, row-major n × n
    t: Vec<C64>,
    /// QᴴΓ₀ and QᴴΓ₁, row-major n × m
    r0: Vec<C64>,
    r1: Vec<C64>,
    /// CQ, row-major p × n
    cq: Vec<C64>,
    /// D and E, row-major p × m
    d: Vec<f64>,
    e: Vec<f64>,
}

impl SchurTransfer {
    /// The evaluator of `sub` sampled at `dt` s, or `None` when the Schur form fails its checks.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(sub: &StateSpace, dt: f64) -> Result<Option<SchurTransfer>> {
        let f = foh(&sub.a, &sub.b, dt)?;
        let (n, m, p) = (sub.n_states(), sub.b.ncols(), sub.c.nrows());
        let to_c = |x: &DMatrix<f64>| x.map(|v| C64::new(v, 0.0));
        let phi = to_c(&f.phi);
        let norm = phi.norm().max(f64::MIN_POSITIVE);
        let Some(schur) = nalgebra::linalg::Schur::try_new(phi.clone(), 1e-15, 10_000) else {
            return Ok(None);
        };
        let (q, t) = schur.unpack();
        let lower = (0..n)
            .flat_map(|i| (0..i).map(move |j| (i, j)))
            .map(|(i, j)| t[(i, j)].norm())
            .fold(0.0, f64::max);
        let back = &q * &t * q.adjoint() - &phi;
        if !(lower <= 1e-13 * norm && back.norm() <= 1e-12 * norm) {
            return Ok(None);
        }
        let qh = q.adjoint();
        let (r0, r1, cq) = (&qh * to_c(&f.gamma0), &qh * to_c(&f.gamma1), to_c(&sub.c) * &q);
        let rows = |x: &DMatrix<C64>| -> Vec<C64> {
            (0..x.nrows())
                .flat_map(|i| (0..x.ncols()).map(move |j| (i, j)))
                .map(|(i, j)| x[(i, j)])
                .collect()
        };
        let rows_r = |x: &DMatrix<f64>| -> Vec<f64> {
            (0..x.nrows())
                .flat_map(|i| (0..x.ncols()).map(move |j| (i, j)))
                .map(|(i, j)| x[(i, j)])
                .collect()
        };
        Ok(Some(SchurTransfer {
            n,
            m,
            p,
            dt,
            t: rows(&t),
            r0: rows(&r0),
            r1: rows(&r1),
            cq: rows(&cq),
            d: rows_r(&sub.d),
            e: rows_r(&sub.e),
        }))
    }

    /// Working memory of [`eval`](Self::eval) (n·m values).
    pub fn work(&self) -> Vec<C64> {
        vec![C64::new(0.0, 0.0); self.n * self.m]
    }

    /// Writes H_d(ω) (row-major p × m) into `h`; `nyquist` leaves out the iωE term (as the spectral route
    /// does at the Nyquist bin). `work` comes from [`work`](Self::work), `h` has p·m values.
    ///
    /// # Panics
    /// `work` or `h` of the wrong length (a programming error).
    pub fn eval(&self, w: f64, nyquist: bool, work: &mut [C64], h: &mut [C64]) {
        let (n, m, p) = (self.n, self.m, self.p);
        let z = C64::new(0.0, w * self.dt).exp();
        for k in 0..m {
            for i in (0..n).rev() {
                let mut acc = self.r0[i * m + k] + self.r1[i * m + k] * z;
                for j in i + 1..n {
                    acc += self.t[i * n + j] * work[j * m + k];
                }
                work[i * m + k] = acc / (z - self.t[i * n + i]);
            }
        }
        for r in 0..p {
            for k in 0..m {
                let mut acc = C64::new(self.d[r * m + k], 0.0);
                if !nyquist {
                    acc += C64::new(0.0, w * self.e[r * m + k]);
                }
                for i in 0..n {
                    acc += self.cq[r * n + i] * work[i * m + k];
                }
                h[r * m + k] = acc;
            }
        }
    }
}
