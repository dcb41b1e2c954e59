//! Exact discretisation of continuous linear systems: zero-order hold, first-order hold and Van Loan's
//! white-noise covariance, all by the matrix exponential of an augmented matrix.

use crate::error::{require_positive, Error, Result};
pub use crate::linalg::expm;
use crate::system::StateSpace;
use nalgebra::DMatrix;
use realfft::num_complex::Complex;

/// Zero-order-hold discretisation x_{k+1} = Φ x_k + Γ u_k (u constant over each step).
#[derive(Debug, Clone, PartialEq)]
pub struct ZeroOrderHold {
    /// Φ = e^{AΔt}.
    pub phi: DMatrix<f64>,
    /// Γ = ∫₀^Δt e^{As} ds B.
    pub gamma: DMatrix<f64>,
}

/// Exact zero-order-hold discretisation of ẋ = Ax + Bu with step `dt` (s).
///
/// # Formula
/// ```text
/// exp([[A, B], [0, 0]] Δt) = [[Φ, Γ], [0, I]],   Φ = e^{AΔt},   Γ = ∫₀^Δt e^{As} ds B
/// ```
///
/// # Errors
/// `dt` must be finite and > 0; `a` square and `b` with as many rows; the exponential must be finite.
///
/// # Examples
/// ```
/// use stochvib::simulate::zoh;
/// use nalgebra::DMatrix;
/// // ẋ = −a x + u: Φ = e^{−aΔt}, Γ = (1 − e^{−aΔt})/a
/// let (a, dt) = (2.0, 0.1);
/// let d = zoh(&DMatrix::from_element(1, 1, -a), &DMatrix::from_element(1, 1, 1.0), dt).unwrap();
/// assert!((d.phi[(0, 0)] - (-a * dt).exp()).abs() < 1e-15);
/// assert!((d.gamma[(0, 0)] - (1.0 - (-a * dt).exp()) / a).abs() < 1e-15);
/// ```
pub fn zoh(a: &DMatrix<f64>, b: &DMatrix<f64>, dt: f64) -> Result<ZeroOrderHold> {
    require_positive("dt", dt)?;
    check_ab(a, b)?;
    let (n, m) = (a.nrows(), b.ncols());
    let mut big = DMatrix::zeros(n + m, n + m);
    big.view_mut((0, 0), (n, n)).copy_from(&(a * dt));
    big.view_mut((0, n), (n, m)).copy_from(&(b * dt));
    let e = expm(&big)?;
    Ok(ZeroOrderHold {
        phi: e.view((0, 0), (n, n)).into_owned(),
        gamma: e.view((0, n), (n, m)).into_owned(),
    })
}

/// First-order-hold (piecewise-linear input) discretisation x_{k+1} = Φ x_k + Γ₀ u_k + Γ₁ u_{k+1}.
#[derive(Debug, Clone, PartialEq)]
pub struct FirstOrderHold {
    /// Φ = e^{AΔt}.
    pub phi: DMatrix<f64>,
    /// Γ₀ = P₀ − P₁ (weight of the sample at the start of the step).
    pub gamma0: DMatrix<f64>,
    /// Γ₁ = P₁ (weight of the sample at the end of the step).
    pub gamma1: DMatrix<f64>,
}

/// Exact integration of ẋ = Ax + Bu over each step when u is linear between samples (first-order hold).
///
/// # Formula
/// With u(t_k + s) = u_k + (u_{k+1} − u_k) s/Δt:
/// ```text
/// x_{k+1} = Φ x_k + (P₀ − P₁) u_k + P₁ u_{k+1},
/// P₀ = ∫₀^Δt e^{A(Δt−s)} ds B,    P₁ = ∫₀^Δt e^{A(Δt−s)} (s/Δt) ds B,
/// exp([[A, B, 0], [0, 0, I/Δt], [0, 0, 0]] Δt) = [[Φ, P₀, P₁], [0, I, I], [0, 0, I]]
/// ```
/// (the (1,3) block is the response of the chain ż₁ = Az₁ + Bz₂, ż₂ = z₃/Δt, ż₃ = 0 from z₃ = I).
/// For sampled inputs this is exact whenever the input is piecewise linear, and second-order accurate in
/// Δt otherwise (the interpolation error of a smooth input).
///
/// # Errors
/// As [`zoh`].
///
/// # Examples
/// ```
/// use stochvib::simulate::foh;
/// use nalgebra::DMatrix;
/// // integrator ẋ = u: a ramp u = t is integrated exactly, x(Δt) = Δt²/2
/// let d = foh(&DMatrix::zeros(1, 1), &DMatrix::from_element(1, 1, 1.0), 0.5).unwrap();
/// let x1 = d.phi[(0, 0)] * 0.0 + d.gamma0[(0, 0)] * 0.0 + d.gamma1[(0, 0)] * 0.5;
/// assert!((x1 - 0.125).abs() < 1e-15);
/// ```
pub fn foh(a: &DMatrix<f64>, b: &DMatrix<f64>, dt: f64) -> Result<FirstOrderHold> {
    require_positive("dt", dt)?;
    check_ab(a, b)?;
    let (n, m) = (a.nrows(), b.ncols());
    let mut big = DMatrix::zeros(n + 2 * m, n + 2 * m);
    big.view_mut((0, 0), (n, n)).copy_from(&(a * dt));
    big.view_mut((0, n), (n, m)).copy_from(&(b * dt));
    big.view_mut((n, n + m), (m, m)).copy_from(&DMatrix::identity(m, m));
    let e = expm(&big)?;
    let p0 = e.view((0, n), (n, m)).into_owned();
    let p1 = e.view((0, n + m), (n, m)).into_owned();
    Ok(FirstOrderHold {
        phi: e.view((0, 0), (n, n)).into_owned(),
        gamma0: &p0 - &p1,
        gamma1: p1,
    })
}

/// Discretisation of ẋ = Ax + Gw driven by unit-intensity white noise (E[w(t)w(s)ᵀ] = I δ(t − s)).
#[derive(Debug, Clone, PartialEq)]
pub struct WhiteNoiseDiscretization {
    /// Φ = e^{AΔt}.
    pub phi: DMatrix<f64>,
    /// Q_d = ∫₀^Δt e^{As} G Gᵀ e^{Aᵀs} ds, the covariance of the noise accumulated over one step.
    pub qd: DMatrix<f64>,
}

/// Van Loan's method (Van Loan 1978, "Computing integrals involving the matrix exponential", IEEE TAC
/// 23(3)): the exact discrete system x_{k+1} = Φ x_k + v_k, v_k ~ N(0, Q_d) i.i.d., of ẋ = Ax + Gw.
///
/// # Formula
/// ```text
/// M = [[−A, GGᵀ], [0, Aᵀ]] Δt,   e^M = [[·, F₁₂], [0, F₂₂]],   Φ = F₂₂ᵀ,   Q_d = F₂₂ᵀ F₁₂
/// ```
/// Consequently, with P the stationary covariance (A P + P Aᵀ + GGᵀ = 0), Φ P Φᵀ + Q_d = P for every Δt:
/// the discrete recursion started from N(0, P) stays exactly stationary — no time-step bias. Q_d is
/// symmetrised ((Q + Qᵀ)/2) to remove rounding asymmetry.
///
/// # Errors
/// As [`zoh`] (with `g` in place of `b`).
///
/// # Examples
/// ```
/// use stochvib::simulate::van_loan;
/// use nalgebra::DMatrix;
/// // ẋ = −a x + g w: Q_d = g²(1 − e^{−2aΔt})/(2a)
/// let (a, g, dt) = (3.0, 2.0, 0.05);
/// let d = van_loan(&DMatrix::from_element(1, 1, -a), &DMatrix::from_element(1, 1, g), dt).unwrap();
/// let exact = g * g * (1.0 - (-2.0 * a * dt).exp()) / (2.0 * a);
/// assert!((d.qd[(0, 0)] - exact).abs() < 1e-14);
/// ```
pub fn van_loan(a: &DMatrix<f64>, g: &DMatrix<f64>, dt: f64) -> Result<WhiteNoiseDiscretization> {
    require_positive("dt", dt)?;
    check_ab(a, g)?;
    let n = a.nrows();
    let mut big = DMatrix::zeros(2 * n, 2 * n);
    big.view_mut((0, 0), (n, n)).copy_from(&(-a * dt));
    big.view_mut((0, n), (n, n)).copy_from(&(g * g.transpose() * dt));
    big.view_mut((n, n), (n, n)).copy_from(&(a.transpose() * dt));
    let e = expm(&big)?;
    let phi = e.view((n, n), (n, n)).transpose();
    let f12 = e.view((0, n), (n, n)).into_owned();
    let q = &phi * f12;
    let qd = (&q + q.transpose()) * 0.5;
    Ok(WhiteNoiseDiscretization { phi, qd })
}

/// A factor L with L Lᵀ = Q of a symmetric positive semi-definite covariance: the Cholesky factor when Q
/// is numerically positive definite, otherwise V √max(Λ, 0) from the symmetric eigen-decomposition (Q_d
/// of a system with noise entering through few states is very ill-conditioned for small Δt).
///
/// # Errors
/// [`Error::Numerical`] when Q has a negative eigenvalue below −1e-10·‖Q‖ (not a covariance) or is not
/// square.
///
/// # Examples
/// ```
/// use stochvib::simulate::covariance_factor;
/// use nalgebra::DMatrix;
/// let q = DMatrix::from_row_slice(2, 2, &[4.0, 2.0, 2.0, 2.0]);
/// let l = covariance_factor(&q).unwrap();
/// assert!((&l * l.transpose() - &q).amax() < 1e-14);
/// ```
pub fn covariance_factor(q: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    if q.nrows() != q.ncols() {
        return Err(Error::Numerical {
            what: "covariance factor".into(),
            reason: "matrix is not square".into(),
        });
    }
    if q.nrows() == 0 {
        return Ok(q.clone());
    }
    if let Some(c) = q.clone().cholesky() {
        let l = c.l();
        if l.iter().all(|v| v.is_finite()) {
            return Ok(l);
        }
    }
    let eig = q.clone().symmetric_eigen();
    let scale = q.amax().max(1e-300);
    let worst = eig.eigenvalues.iter().cloned().fold(f64::INFINITY, f64::min);
    if worst < -1e-10 * scale {
        return Err(Error::Numerical {
            what: "covariance factor".into(),
            reason: format!("matrix has a negative eigenvalue {worst:e} (norm {scale:e}): not a covariance"),
        });
    }
    let mut v = eig.eigenvectors;
    for (j, lam) in eig.eigenvalues.iter().enumerate() {
        let s = lam.max(0.0).sqrt();
        v.column_mut(j).scale_mut(s);
    }
    Ok(v)
}

/// A linear system stepped exactly between samples of its inputs (first-order hold), for inputs that are
/// given as samples (spectral-representation realizations, road profiles, measured records).
///
/// # Formula
/// ```text
/// x_{k+1} = Φ x_k + Γ₀ u_k + Γ₁ u_{k+1},     y_k = C x_k + D u_k
/// ```
/// (see [`foh`]). A derivative feedthrough E u̇ is rejected: the derivative of a sampled input is not
/// defined at the samples.
///
/// # Errors
/// [`SampledSystem::new`]: `dt` > 0, E = 0, and the errors of [`foh`].
///
/// # Examples
/// ```
/// use stochvib::simulate::SampledSystem;
/// use stochvib::system::{StateSpace, OutputInfo};
/// use nalgebra::DMatrix;
/// // ẋ = −x + u with a constant input 1 from x₀ = 0: x(t) = 1 − e^{−t}
/// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0), DMatrix::from_element(1, 1, 1.0),
///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("x", "m")]).unwrap();
/// let sys = SampledSystem::new(&ss, 0.1).unwrap();
/// let u = vec![1.0; 11];
/// let mut y = vec![0.0; 11];
/// sys.respond(&u, &mut vec![0.0], &mut y).unwrap();
/// assert!((y[10] - (1.0 - (-1.0f64).exp())).abs() < 1e-14);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SampledSystem {
    n: usize,
    m: usize,
    p: usize,
    dt: f64,
    phi: Vec<f64>,
    g0: Vec<f64>,
    g1: Vec<f64>,
    c: Vec<f64>,
    d: Vec<f64>,
}

impl SampledSystem {
    /// Discretises `ss` with step `dt` (s).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(ss: &StateSpace, dt: f64) -> Result<Self> {
        if ss.e.amax() != 0.0 {
            return Err(Error::invalid(
                "E",
                format!("{:?}", ss.e.as_slice()),
                "the output contains the input derivative E u̇, which is not defined at the samples of a \
                 sampled input; simulate the shaping-filter (augmented) system instead",
            ));
        }
        let f = foh(&ss.a, &ss.b, dt)?;
        let row = |m: &DMatrix<f64>| -> Vec<f64> {
            let mut v = Vec::with_capacity(m.len());
            for i in 0..m.nrows() {
                for j in 0..m.ncols() {
                    v.push(m[(i, j)]);
                }
            }
            v
        };
        Ok(SampledSystem {
            n: ss.n_states(),
            m: ss.b.ncols(),
            p: ss.c.nrows(),
            dt,
            phi: row(&f.phi),
            g0: row(&f.gamma0),
            g1: row(&f.gamma1),
            c: row(&ss.c),
            d: row(&ss.d),
        })
    }

    /// Number of states, inputs, outputs.
    pub fn dims(&self) -> (usize, usize, usize) {
        (self.n, self.m, self.p)
    }

    /// Time step, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The frequency response of the sampled system from input `input` to output `output` on the FFT grid
    /// of N = `n` samples: H_d(ω_j), j = 0..=N/2.
    ///
    /// # Formula
    /// ```text
    /// ω_j = 2πj/(NΔt),   z_j = e^{iω_jΔt} = e^{2πij/N},   H_d(ω_j) = C (z_j I − Φ)⁻¹ (Γ₀ + z_j Γ₁) + D
    /// ```
    /// The periodic steady state of [`respond`](Self::respond) under an N-periodic input
    /// u_k = Σ_j c_j e^{iω_j kΔt} (the output of [`SpectralGenerator`](super::SpectralGenerator)) is
    /// y_k = Σ_j H_d(ω_j) c_j e^{iω_j kΔt}: [`SpectralGenerator::generate_filtered`](super::SpectralGenerator)
    /// with this gain produces it with one inverse FFT, without time stepping or warm-up.
    ///
    /// # Errors
    /// `n` odd or < 2, indices out of range, z_j I − Φ singular (a pole of the sampled system on the unit
    /// circle: the system is not asymptotically stable).
    ///
    /// # Examples
    /// ```
    /// use stochvib::simulate::SampledSystem;
    /// use stochvib::system::{StateSpace, OutputInfo};
    /// use nalgebra::DMatrix;
    /// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0), DMatrix::from_element(1, 1, 1.0),
    ///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("x", "m")]).unwrap();
    /// let h = SampledSystem::new(&ss, 0.1).unwrap().grid_response(8, 0, 0).unwrap();
    /// // at ω = 0 the static gain 1/(s + 1) at s = 0 is exact for any hold
    /// assert!((h[0].re - 1.0).abs() < 1e-12 && h[0].im.abs() < 1e-12);
    /// ```
    pub fn grid_response(&self, n: usize, output: usize, input: usize) -> Result<Vec<Complex<f64>>> {
        if n < 2 || !n.is_multiple_of(2) {
            return Err(Error::invalid("n", n, "number of samples must be even and >= 2"));
        }
        if output >= self.p {
            return Err(Error::invalid(
                "output",
                output,
                format!("the system has {} outputs", self.p),
            ));
        }
        if input >= self.m {
            return Err(Error::invalid(
                "input",
                input,
                format!("the system has {} inputs", self.m),
            ));
        }
        let (ns, m) = (self.n, self.m);
        let c = |v: f64| Complex::new(v, 0.0);
        let phi = DMatrix::from_fn(ns, ns, |i, j| c(self.phi[i * ns + j]));
        let g0 = DMatrix::from_fn(ns, 1, |i, _| c(self.g0[i * m + input]));
        let g1 = DMatrix::from_fn(ns, 1, |i, _| c(self.g1[i * m + input]));
        let crow = DMatrix::from_fn(1, ns, |_, j| c(self.c[output * ns + j]));
        let d = self.d[output * m + input];
        let mut h = Vec::with_capacity(n / 2 + 1);
        for j in 0..=n / 2 {
            let z = Complex::from_polar(1.0, 2.0 * std::f64::consts::PI * j as f64 / n as f64);
            let zi = DMatrix::<Complex<f64>>::identity(ns, ns) * z - &phi;
            let rhs = &g0 + &g1 * z;
            let x = zi.lu().solve(&rhs).ok_or_else(|| Error::Numerical {
                what: "sampled frequency response".into(),
                reason: format!("zI − Φ singular at bin {j} of {n}"),
            })?;
            h.push((&crow * x)[(0, 0)] + d);
        }
        Ok(h)
    }

    /// Responds to the sampled inputs `u` (sample-major: u[k·m + j] is input j at t_k) from state `x`
    /// (updated to the state at the last sample), writing y[k·p + i].
    ///
    /// # Errors
    /// Length mismatches.
    #[allow(clippy::needless_range_loop)] // small dense loops over flat row-major matrices
    pub fn respond(&self, u: &[f64], x: &mut [f64], y: &mut [f64]) -> Result<()> {
        let (n, m, p) = (self.n, self.m, self.p);
        if m == 0 || !u.len().is_multiple_of(m) || x.len() != n || y.len() != (u.len() / m) * p {
            return Err(Error::invalid(
                "buffers",
                format!("u {}, x {}, y {}", u.len(), x.len(), y.len()),
                format!("need u = K·{m}, x = {n}, y = K·{p}"),
            ));
        }
        macro_rules! dispatch {
            ($($k:literal)*) => {
                match n {
                    $($k => respond_kernel::<$k>(self, u, x, y),)*
                    _ => respond_dyn(self, u, x, y),
                }
            };
        }
        dispatch!(1 2 3 4 5 6 7 8);
        Ok(())
    }
}

/// [`SampledSystem::respond`] for N states: the state on the stack, no per-sample copies (a `memcpy` call
/// per step dominated the loop), and the input terms summed before the Φx terms, which shortens the
/// step-to-step dependency chain.
#[allow(clippy::needless_range_loop)]
fn respond_kernel<const N: usize>(s: &SampledSystem, u: &[f64], x: &mut [f64], y: &mut [f64]) {
    let (m, p) = (s.m, s.p);
    let k_total = u.len() / m;
    let mut ph = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            ph[i][j] = s.phi[i * N + j];
        }
    }
    let mut z = [0.0; N];
    z.copy_from_slice(x);
    for k in 0..k_total {
        let uk = &u[k * m..(k + 1) * m];
        let yk = &mut y[k * p..(k + 1) * p];
        for i in 0..p {
            let mut acc = 0.0;
            for j in 0..N {
                acc += s.c[i * N + j] * z[j];
            }
            for j in 0..m {
                acc += s.d[i * m + j] * uk[j];
            }
            yk[i] = acc;
        }
        if k + 1 == k_total {
            break;
        }
        let un = &u[(k + 1) * m..(k + 2) * m];
        let mut next = [0.0; N];
        for i in 0..N {
            // the input part first: it does not depend on z, so only the Φz terms lie on the step-to-step
            // dependency chain
            let mut acc = s.g0[i * m] * uk[0] + s.g1[i * m] * un[0];
            for j in 1..m {
                acc += s.g0[i * m + j] * uk[j] + s.g1[i * m + j] * un[j];
            }
            for j in 0..N {
                acc += ph[i][j] * z[j];
            }
            next[i] = acc;
        }
        z = next;
    }
    x.copy_from_slice(&z);
}

/// [`SampledSystem::respond`] for any number of states (heap state).
#[allow(clippy::needless_range_loop)]
fn respond_dyn(s: &SampledSystem, u: &[f64], x: &mut [f64], y: &mut [f64]) {
    let (n, m, p) = (s.n, s.m, s.p);
    let k_total = u.len() / m;
    // double buffer swapped by pointer: no per-step copy
    let mut z = x.to_vec();
    let mut next = vec![0.0; n];
    for k in 0..k_total {
        let uk = &u[k * m..(k + 1) * m];
        let yk = &mut y[k * p..(k + 1) * p];
        for i in 0..p {
            let mut acc = 0.0;
            for j in 0..n {
                acc += s.c[i * n + j] * z[j];
            }
            for j in 0..m {
                acc += s.d[i * m + j] * uk[j];
            }
            yk[i] = acc;
        }
        if k + 1 == k_total {
            break;
        }
        let un = &u[(k + 1) * m..(k + 2) * m];
        for i in 0..n {
            let mut acc = 0.0;
            for j in 0..n {
                acc += s.phi[i * n + j] * z[j];
            }
            for j in 0..m {
                acc += s.g0[i * m + j] * uk[j] + s.g1[i * m + j] * un[j];
            }
            next[i] = acc;
        }
        std::mem::swap(&mut z, &mut next);
    }
    x.copy_from_slice(&z);
}

/// The exact sampled joint simulation of a system's outputs under rational, delay-free random inputs: the
/// system augmented with the shaping filters of its inputs
/// ([`augmented_system`](crate::response::augmented_system)), discretised by Van Loan's method
/// ([`GaussMarkov`](crate::simulate::shaping::GaussMarkov)).
///
/// # Formula
/// ```text
/// ż = F z + G w,   y_i = h_i z   (one row per requested output),   z₀ ~ N(0, P),  F P + P Fᵀ + G Gᵀ = 0
/// ```
/// The samples y_k are exactly those of the stationary response (zero-mean fluctuation: add the mean
/// H(0)·M_u separately), so sample variances converge to the Lyapunov variance with no time-step bias.
///
/// # Errors
/// [`Error::Numerical`] when the system has no state space, the inputs are delayed copies or not rational;
/// [`Error::Divergent`] when a requested output has a white-noise component (infinite variance); the
/// errors of [`GaussMarkov::new`](crate::simulate::shaping::GaussMarkov::new) (unstable system, bad `dt`).
///
/// # Examples
/// ```
/// use stochvib::simulate::augmented_response;
/// use stochvib::response::{Excitation, variance_lyapunov};
/// use stochvib::system::StateSpace;
/// use stochvib::spectrum::{Exponential, Domain};
/// use std::sync::Arc;
/// let ss = StateSpace::oscillator(10.0, 0.05).unwrap();
/// let exc = Excitation::single(Arc::new(Exponential::new(1.0, 3.0, Domain::Temporal).unwrap()), 0.0).unwrap();
/// let gm = augmented_response(&ss, &exc, &[0], 0.005).unwrap();
/// let d = variance_lyapunov(&ss, &exc, 0).unwrap().variance;
/// assert!((gm.output_covariance()[(0, 0)] - d).abs() < 1e-9 * d);
/// ```
pub fn augmented_response(
    sys: &dyn crate::system::FrequencyResponse,
    exc: &crate::response::Excitation,
    outputs: &[usize],
    dt: f64,
) -> Result<super::GaussMarkov> {
    let ss = sys.state_space().ok_or_else(|| Error::Numerical {
        what: "exact time-domain simulation".into(),
        reason: "the system has no finite state-space form".into(),
    })?;
    if outputs.is_empty() {
        return Err(Error::invalid("outputs", "[]", "need at least one output index"));
    }
    let mut first: Option<crate::response::AugmentedSystem> = None;
    let mut rows: Vec<DMatrix<f64>> = Vec::new();
    for &i in outputs {
        if i >= ss.c.nrows() {
            return Err(Error::invalid(
                "output",
                i,
                format!("the system has {} outputs", ss.c.nrows()),
            ));
        }
        let aug = crate::response::augmented_system(ss, exc, i)?;
        if aug.f.amax() > 0.0 {
            return Err(Error::Divergent {
                quantity: format!("samples of `{}`", sys.outputs()[i].name),
                reason: "the output contains the driving white noise directly (infinite variance); its samples \
                         are not defined"
                    .into(),
            });
        }
        rows.push(aug.h.clone());
        if first.is_none() {
            first = Some(aug);
        }
    }
    let aug = first.expect("outputs is not empty");
    let nz = aug.a.nrows();
    let h = DMatrix::from_fn(rows.len(), nz, |r, j| rows[r][(0, j)]);
    super::GaussMarkov::new(aug.a, aug.g, h, dt)
}

fn check_ab(a: &DMatrix<f64>, b: &DMatrix<f64>) -> Result<()> {
    if a.nrows() != a.ncols() || b.nrows() != a.nrows() {
        return Err(Error::invalid(
            "A, B",
            format!("{}x{}, {}x{}", a.nrows(), a.ncols(), b.nrows(), b.ncols()),
            "A must be square and B must have as many rows as A",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::EXACT;

    #[test]
    fn expm_damped_oscillator_closed_form() {
        // ẍ + 2ζω ẋ + ω² x = 0: with ω_d = ω√(1−ζ²), σ = ζω,
        // e^{At} = e^{−σt} [[cos + (σ/ω_d) sin, sin/ω_d], [−ω² sin/ω_d, cos − (σ/ω_d) sin]] (ω_d t arguments)
        let (w, z, t) = (7.0f64, 0.1f64, 0.37f64);
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -w * w, -2.0 * z * w]);
        let e = expm(&(a * t)).unwrap();
        let (s, wd) = (z * w, w * (1.0 - z * z).sqrt());
        let (c, sn, ex) = ((wd * t).cos(), (wd * t).sin(), (-s * t).exp());
        let exact = [
            ex * (c + s / wd * sn),
            ex * sn / wd,
            -ex * w * w * sn / wd,
            ex * (c - s / wd * sn),
        ];
        for (k, v) in exact.iter().enumerate() {
            assert!(
                (e[(k / 2, k % 2)] - v).abs() < EXACT,
                "{k}: {} vs {v}",
                e[(k / 2, k % 2)]
            );
        }
    }

    #[test]
    fn van_loan_stationary_identity_and_foh_consistency() {
        // ZOH and FOH share Φ; for a constant input FOH reduces to ZOH: Γ₀ + Γ₁ = Γ.
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -25.0, -1.0]);
        let b = DMatrix::from_row_slice(2, 1, &[0.0, 1.0]);
        let z = zoh(&a, &b, 0.01).unwrap();
        let f = foh(&a, &b, 0.01).unwrap();
        assert!((&z.phi - &f.phi).amax() < EXACT);
        assert!((&z.gamma - (&f.gamma0 + &f.gamma1)).amax() < EXACT);
        // Van Loan: Φ P Φᵀ + Q_d = P with P from the continuous Lyapunov equation
        let v = van_loan(&a, &b, 0.01).unwrap();
        let p = crate::linalg::solve_continuous_lyapunov(&a, &(&b * b.transpose())).unwrap();
        let resid = &v.phi * &p * v.phi.transpose() + &v.qd - &p;
        assert!(resid.amax() < EXACT * p.amax(), "{resid}");
    }
}
