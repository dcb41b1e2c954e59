//! Exact discrete-time simulation of white-noise-driven linear systems (Gauss–Markov processes): rational
//! spectra through their shaping filters, and systems augmented with their input filters. Streaming, with
//! memory O(states), for any record length.

use super::discretize::{covariance_factor, van_loan, WhiteNoiseDiscretization};
use super::lane_normals::StreamNormals;
use super::rng::standard_normal;
use crate::error::{Error, Result};
use crate::linalg::solve_continuous_lyapunov;
use crate::spectrum::Spectrum;
use crate::system::{FrequencyResponse, OutputInfo, TransferFunction};
use nalgebra::DMatrix;
use rand::rngs::Xoshiro256PlusPlus;

/// The exact sampled version of a stationary Gauss–Markov process ż = A z + G w, y = H z, driven by
/// unit-intensity white noise (E[w(t)w(s)ᵀ] = I δ(t − s)), at step Δt.
///
/// # Formula
/// ```text
/// z₀ ~ N(0, P),   z_{k+1} = Φ z_k + L ε_k,   y_k = H z_k,   ε_k ~ N(0, I) i.i.d.
/// A P + P Aᵀ + G Gᵀ = 0,   Φ = e^{AΔt},   L Lᵀ = Q_d = ∫₀^Δt e^{As} G Gᵀ e^{Aᵀs} ds   (Van Loan)
/// ```
/// Since Φ P Φᵀ + Q_d = P, every z_k ~ N(0, P) exactly and (y_k) has exactly the autocovariance of the
/// continuous process at the lags kΔt: no time-step bias, for any Δt. Each step draws `n` normals
/// (n = number of states), in order ε_k\[0\], …, ε_k\[n−1\]; the initial state draws `n` normals first.
///
/// # Errors
/// [`GaussMarkov::new`] rejects inconsistent dimensions, an A that is not asymptotically stable (no
/// stationary state), Δt ≤ 0, and the numerical failures of the matrix exponential and Lyapunov solver.
///
/// # Examples
/// ```
/// use stochvib::simulate::{GaussMarkov, stream};
/// use nalgebra::DMatrix;
/// // type 1 (AR(1) when sampled): ż = −α z + √(2αD) w, K(τ) = D e^{−α|τ|}
/// let (alpha, d) = (2.0, 0.5);
/// let gm = GaussMarkov::new(
///     DMatrix::from_element(1, 1, -alpha),
///     DMatrix::from_element(1, 1, (2.0 * alpha * d).sqrt()),
///     DMatrix::from_element(1, 1, 1.0),
///     0.01,
/// ).unwrap();
/// assert!((gm.output_covariance()[(0, 0)] - d).abs() < 1e-12);
/// let mut s = gm.stream(stream(1, 0));
/// let mut y = vec![0.0; 1000];
/// s.fill(&mut y);
/// ```
#[derive(Debug, Clone)]
pub struct GaussMarkov {
    n: usize,
    p: usize,
    dt: f64,
    phi_flat: Vec<f64>,
    l_flat: Vec<f64>,
    p0_flat: Vec<f64>,
    h_flat: Vec<f64>,
    disc: WhiteNoiseDiscretization,
    cov: DMatrix<f64>,
    h: DMatrix<f64>,
}

fn flat(m: &DMatrix<f64>) -> Vec<f64> {
    let mut v = Vec::with_capacity(m.len());
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            v.push(m[(i, j)]);
        }
    }
    v
}

impl GaussMarkov {
    /// Discretises ż = A z + G w, y = H z exactly at step `dt`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(a: DMatrix<f64>, g: DMatrix<f64>, h: DMatrix<f64>, dt: f64) -> Result<Self> {
        let n = a.nrows();
        if n == 0 || a.ncols() != n || g.nrows() != n || h.ncols() != n || h.nrows() == 0 {
            return Err(Error::invalid(
                "A, G, H",
                format!(
                    "{}x{}, {}x{}, {}x{}",
                    a.nrows(),
                    a.ncols(),
                    g.nrows(),
                    g.ncols(),
                    h.nrows(),
                    h.ncols()
                ),
                "need A n×n (n ≥ 1), G n×q, H p×n (p ≥ 1)",
            ));
        }
        if !crate::linalg::is_stable(&a) {
            return Err(Error::invalid(
                "A",
                format!("{:?}", a.as_slice()),
                "not asymptotically stable: a stationary process needs all eigenvalues in Re < 0",
            ));
        }
        let disc = van_loan(&a, &g, dt)?;
        let cov = solve_continuous_lyapunov(&a, &(&g * g.transpose()))?;
        let cov = (&cov + cov.transpose()) * 0.5;
        let l = covariance_factor(&disc.qd)?;
        let p0 = covariance_factor(&cov)?;
        Ok(GaussMarkov {
            n,
            p: h.nrows(),
            dt,
            phi_flat: flat(&disc.phi),
            l_flat: flat(&l),
            p0_flat: flat(&p0),
            h_flat: flat(&h),
            disc,
            cov,
            h,
        })
    }

    /// Number of states n.
    pub fn n_states(&self) -> usize {
        self.n
    }
    /// Number of outputs p (rows of H).
    pub fn n_outputs(&self) -> usize {
        self.p
    }
    /// Time step Δt.
    pub fn dt(&self) -> f64 {
        self.dt
    }
    /// Φ and Q_d.
    pub fn discretization(&self) -> &WhiteNoiseDiscretization {
        &self.disc
    }
    /// The stationary state covariance P (A P + P Aᵀ + G Gᵀ = 0).
    pub fn state_covariance(&self) -> &DMatrix<f64> {
        &self.cov
    }
    /// The stationary output covariance H P Hᵀ (the exact variance of every sample y_k).
    pub fn output_covariance(&self) -> DMatrix<f64> {
        &self.h * &self.cov * self.h.transpose()
    }
    /// Exact output autocovariance at lag kΔt: E[y_{j+k} y_jᵀ] = H Φᵏ P Hᵀ.
    pub fn output_autocovariance(&self, k: usize) -> DMatrix<f64> {
        let mut m = self.cov.clone();
        for _ in 0..k {
            m = &self.disc.phi * m;
        }
        &self.h * m * self.h.transpose()
    }

    /// The exact autocovariance E[y_{j+k} y_j] of every output at lags k = 0..lags (one row per output):
    /// the diagonal of H Φᵏ P Hᵀ, with Φᵏ P built once by repeated multiplication.
    pub fn output_autocovariances(&self, lags: usize) -> Vec<Vec<f64>> {
        let mut out = vec![Vec::with_capacity(lags); self.p];
        let mut x = self.cov.clone();
        for _ in 0..lags {
            let m = &self.h * &x * self.h.transpose();
            for (r, row) in out.iter_mut().enumerate() {
                row.push(m[(r, r)]);
            }
            x = &self.disc.phi * x;
        }
        out
    }

    /// Draws a stationary initial state z₀ ~ N(0, P) into `state` (n normals).
    ///
    /// # Panics
    /// Never for `state.len() == n_states()`; other lengths are a programming error and panic.
    pub fn initial_state(&self, rng: &mut Xoshiro256PlusPlus, state: &mut [f64]) {
        let n = self.n;
        assert_eq!(state.len(), n, "state length must equal the number of states");
        let mut e = [0.0; 16];
        let mut ev = Vec::new();
        let e: &mut [f64] = if n <= 16 {
            &mut e[..n]
        } else {
            ev.resize(n, 0.0);
            &mut ev
        };
        for v in e.iter_mut() {
            *v = standard_normal(rng);
        }
        for (i, x) in state.iter_mut().enumerate() {
            *x = (0..n).map(|j| self.p0_flat[i * n + j] * e[j]).sum();
        }
    }

    /// Writes the next `out.len() / p` output samples from `state` (sample-major: out[k·p + r] is output r
    /// at step k) and advances `state`; consecutive calls continue the same realization. A trailing partial
    /// sample (length not a multiple of p) is left untouched.
    ///
    /// # Panics
    /// When `state.len() != n_states()` (a programming error).
    pub fn advance(&self, state: &mut [f64], rng: &mut Xoshiro256PlusPlus, out: &mut [f64]) {
        assert_eq!(state.len(), self.n, "state length must equal the number of states");
        macro_rules! dispatch {
            ($($n:literal)*) => {
                match self.n {
                    $($n => kernel::<$n>(&self.phi_flat, &self.l_flat, &self.h_flat, self.p, state, rng, out),)*
                    _ => kernel_dyn(self.n, &self.phi_flat, &self.l_flat, &self.h_flat, self.p, state, rng, out),
                }
            };
        }
        dispatch!(1 2 3 4 5 6 7 8);
    }

    /// Φ, L, the initial-state factor (L₀L₀ᵀ = P) and H, each row-major (for the lockstep realizations of
    /// [`GaussMarkovLanes`](super::GaussMarkovLanes)).
    pub(crate) fn flat_matrices(&self) -> [&[f64]; 4] {
        [&self.phi_flat, &self.l_flat, &self.p0_flat, &self.h_flat]
    }

    /// A stream owning its generator, started from a stationary state drawn from `rng`.
    pub fn stream(&self, mut rng: Xoshiro256PlusPlus) -> GaussMarkovStream<'_> {
        let mut x = vec![0.0; self.n];
        self.initial_state(&mut rng, &mut x);
        GaussMarkovStream { model: self, x, rng }
    }
}

/// A running realization of a [`GaussMarkov`] process: produces samples in chunks of any size with
/// memory O(states); consecutive `fill` calls continue the same realization.
#[derive(Debug, Clone)]
pub struct GaussMarkovStream<'a> {
    model: &'a GaussMarkov,
    x: Vec<f64>,
    rng: Xoshiro256PlusPlus,
}

impl GaussMarkovStream<'_> {
    /// The current state z_k.
    pub fn state(&self) -> &[f64] {
        &self.x
    }

    /// Writes the next `out.len() / p` output samples (see [`GaussMarkov::advance`]).
    pub fn fill(&mut self, out: &mut [f64]) {
        self.model.advance(&mut self.x, &mut self.rng, out);
    }
}

#[inline(always)]
fn kernel<const N: usize>(
    phi: &[f64],
    l: &[f64],
    h: &[f64],
    p: usize,
    x: &mut [f64],
    rng: &mut Xoshiro256PlusPlus,
    out: &mut [f64],
) {
    let mut ph = [[0.0; N]; N];
    let mut lf = [[0.0; N]; N];
    for i in 0..N {
        for j in 0..N {
            ph[i][j] = phi[i * N + j];
            lf[i][j] = l[i * N + j];
        }
    }
    let mut z = [0.0; N];
    z.copy_from_slice(x);
    let mut normals = StreamNormals::new(rng);
    for yk in out.chunks_exact_mut(p) {
        for (r, y) in yk.iter_mut().enumerate() {
            let hr = &h[r * N..(r + 1) * N];
            let mut s = 0.0;
            for j in 0..N {
                s += hr[j] * z[j];
            }
            *y = s;
        }
        let mut w = [0.0; N];
        normals.fill(&mut w);
        let mut nz = [0.0; N];
        for i in 0..N {
            // the noise part first: it does not depend on z, so only the Φz terms lie on the step-to-step
            // dependency chain
            let mut s = lf[i][0] * w[0];
            for j in 1..N {
                s += lf[i][j] * w[j];
            }
            for j in 0..N {
                s += ph[i][j] * z[j];
            }
            nz[i] = s;
        }
        z = nz;
    }
    *rng = normals.into_rng();
    x.copy_from_slice(&z);
}

#[allow(clippy::too_many_arguments)]
fn kernel_dyn(
    n: usize,
    phi: &[f64],
    l: &[f64],
    h: &[f64],
    p: usize,
    x: &mut [f64],
    rng: &mut Xoshiro256PlusPlus,
    out: &mut [f64],
) {
    let mut w = vec![0.0; n];
    let mut nz = vec![0.0; n];
    let mut normals = StreamNormals::new(rng);
    for yk in out.chunks_exact_mut(p) {
        for (r, y) in yk.iter_mut().enumerate() {
            *y = (0..n).map(|j| h[r * n + j] * x[j]).sum();
        }
        normals.fill(&mut w);
        for i in 0..n {
            let mut s = 0.0;
            for j in 0..n {
                s += phi[i * n + j] * x[j];
            }
            for j in 0..n {
                s += l[i * n + j] * w[j];
            }
            nz[i] = s;
        }
        x.copy_from_slice(&nz);
    }
    *rng = normals.into_rng();
}

/// The exact sampled simulation of a process with a rational spectrum, through its shaping filter.
///
/// # Formula
/// S(ω) = |B(iω)/A(iω)|²/(2π) ([`ShapingFilter`](crate::spectrum::ShapingFilter)); B/A is realised in
/// controllable canonical form (`TransferFunction::new(B, A).state_space()`), ż = A_c z + b w, x = c z, and
/// discretised by [`GaussMarkov`]. Type 1 gives the AR(1) recursion x_{k+1} = e^{−αΔt} x_k + ε_k with
/// Var ε = D(1 − e^{−2αΔt}). Works for temporal (Δt in s) and spatial (Δx in m) spectra alike.
///
/// # Errors
/// [`Error::InvalidParameter`] when the spectrum is not rational, or when deg N = deg D (the process has
/// a white-noise component, i.e. infinite variance: its samples are not defined — white noise sampled at
/// Δt is a modelling choice of bandwidth, not a property of the process; drive a system with it through
/// [`augmented_response`](super::augmented_response) instead); [`Error::Divergent`] when S grows without
/// bound; the errors of [`GaussMarkov::new`].
///
/// # Examples
/// ```
/// use stochvib::simulate::shaping_simulator;
/// use stochvib::spectrum::{ExpCosine, Domain, Spectrum};
/// let s = ExpCosine { variance: 2.0, alpha: 0.5, beta: 3.0, domain: Domain::Temporal }.build().unwrap();
/// let gm = shaping_simulator(&s, 0.01).unwrap();
/// assert!((gm.output_covariance()[(0, 0)] - 2.0).abs() < 1e-9);
/// // lag-one autocovariance is K(Δt) exactly
/// let k1 = gm.output_autocovariance(1)[(0, 0)];
/// assert!((k1 - s.correlation(0.01).unwrap()).abs() < 1e-9);
/// ```
pub fn shaping_simulator(spectrum: &dyn Spectrum, dt: f64) -> Result<GaussMarkov> {
    let r = spectrum.rational().ok_or_else(|| {
        Error::invalid(
            "spectrum",
            spectrum.describe(),
            "not rational: exact shaping-filter simulation needs S = N(ω²)/D(ω²); use the spectral \
             representation generator",
        )
    })?;
    let f = r.shaping_filter()?;
    let tf = TransferFunction::new(f.num.clone(), f.den.clone(), OutputInfo::new("x", "-"))?;
    let ss = tf.state_space().ok_or_else(|| Error::Numerical {
        what: "shaping filter".into(),
        reason: "transfer function without state space".into(),
    })?;
    if ss.d.amax() != 0.0 || ss.e.amax() != 0.0 || ss.n_states() == 0 {
        return Err(Error::invalid(
            "spectrum",
            spectrum.describe(),
            "S(ω) tends to a non-zero constant as ω → ∞: the process contains white noise and has infinite \
             variance, so its samples are not meaningful; let it drive a system (augmented_response) instead",
        ));
    }
    GaussMarkov::new(ss.a.clone(), ss.b.clone(), ss.c.clone(), dt)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::stream;
    use rand::Rng;

    /// The recursion written out with `rand_distr`'s draws one at a time, in the kernels' order of
    /// operations (up to 8 states: the noise terms, then Φz; beyond: Φz, then the noise terms).
    fn oracle(gm: &GaussMarkov, z: &mut [f64], rng: &mut Xoshiro256PlusPlus, steps: usize) -> Vec<f64> {
        let (n, p) = (gm.n, gm.p);
        let (phi, l, h) = (&gm.phi_flat, &gm.l_flat, &gm.h_flat);
        let mut out = Vec::new();
        for _ in 0..steps {
            for r in 0..p {
                let mut s = 0.0;
                for j in 0..n {
                    s += h[r * n + j] * z[j];
                }
                out.push(s);
            }
            let w: Vec<f64> = (0..n).map(|_| standard_normal(rng)).collect();
            let next: Vec<f64> = (0..n)
                .map(|i| {
                    let (li, pi) = (&l[i * n..(i + 1) * n], &phi[i * n..(i + 1) * n]);
                    let noise = |s: f64| (1..n).fold(s, |s, j| s + li[j] * w[j]);
                    let drift = |s: f64| (0..n).fold(s, |s, j| s + pi[j] * z[j]);
                    if n <= 8 {
                        drift(noise(li[0] * w[0]))
                    } else {
                        noise(drift(0.0) + li[0] * w[0])
                    }
                })
                .collect();
            z.copy_from_slice(&next);
        }
        out
    }

    /// A stable chain of n states (poles −1 … −n, a coupling above the diagonal) driven by one white noise,
    /// with two outputs.
    fn chain(n: usize) -> GaussMarkov {
        let a = DMatrix::from_fn(n, n, |i, j| match j as i64 - i as i64 {
            0 => -(i as f64 + 1.0),
            1 => 0.3,
            _ => 0.0,
        });
        let h = DMatrix::from_fn(2, n, |r, j| if r == 0 { f64::from(j == 0) } else { 1.0 });
        GaussMarkov::new(a, DMatrix::from_element(n, 1, 1.0), h, 0.05).unwrap()
    }

    /// `advance` in pieces of uneven lengths gives the bits of the recursion with `rand_distr`'s draws one
    /// at a time and leaves the generator where those draws leave it (3 states: the fixed-size kernel; 10:
    /// the general one).
    #[test]
    fn advance_gives_the_bits_of_the_draws_one_at_a_time() {
        for n in [3, 10] {
            let gm = chain(n);
            let (mut rng, mut want_rng) = (stream(5, n as u64), stream(5, n as u64));
            let (mut x, mut z) = (vec![0.0; n], vec![0.0; n]);
            gm.initial_state(&mut rng, &mut x);
            gm.initial_state(&mut want_rng, &mut z);
            let mut got = Vec::new();
            for steps in [1, 7, 1000, 24] {
                let mut buf = vec![0.0; steps * gm.p];
                gm.advance(&mut x, &mut rng, &mut buf);
                got.extend(buf);
            }
            let want = oracle(&gm, &mut z, &mut want_rng, 1032);
            assert!(
                got.iter().zip(&want).all(|(a, b)| a.to_bits() == b.to_bits()),
                "{n} states"
            );
            assert_eq!(got.len(), want.len());
            assert_eq!(x, z, "{n} states: the state");
            assert_eq!(rng.next_u64(), want_rng.next_u64(), "{n} states: the generator");
        }
    }
}
