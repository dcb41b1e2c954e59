//! [`LANES`] realizations of a [`GaussMarkov`] process stepped side by side (in lockstep): lane l is
//! realization `first + l` of a seed, with the bits of that realization run alone.

use super::normal_lanes::{NormalLanes, LANES};
use super::GaussMarkov;
use crate::linalg::vmath;

/// Steps whose normals [`GaussMarkovLanes::fill`] draws at a time (one fill of every lane, then those steps).
pub const LANE_DRAW_STEPS: usize = 16;

/// Realizations `first .. first + LANES` of a seed of a [`GaussMarkov`] process, each state variable and
/// output one `[f64; LANES]` (one lane per realization).
///
/// # Formula
/// Lane l is the realization that [`GaussMarkov::stream`] gives from [`stream`](super::stream)`(seed,
/// first + l)`, bit for bit: its normals from its own stream in the same order (the n of z₀ first, then
/// n per step, [`NormalLanes`]), and per lane the same products added in the same order as
/// [`GaussMarkov::initial_state`] and [`GaussMarkov::advance`]:
/// ```text
/// z₀ = Σ_j L₀[i][j] ε[j]  (from −0.0),   y_k[r] = Σ_j H[r][j] z_k[j],   z_{k+1}[i] = Σ_j L[i][j] ε_k[j] + Σ_j Φ[i][j] z_k[j]
/// ```
/// (for n > 8 states the scalar path's other order, Φ terms first, and y from −0.0). The L chains of a
/// step are independent, so they overlap and go in vector registers, while each lane keeps the
/// dependency chain, and therefore the bits, of the realization alone.
///
/// # Examples
/// ```
/// use stochvib::simulate::{stream, GaussMarkov, LANES};
/// use nalgebra::DMatrix;
/// let (alpha, d) = (2.0, 0.5);
/// let gm = GaussMarkov::new(
///     DMatrix::from_element(1, 1, -alpha),
///     DMatrix::from_element(1, 1, (2.0 * alpha * d).sqrt()),
///     DMatrix::from_element(1, 1, 1.0),
///     0.01,
/// ).unwrap();
/// let mut lanes = gm.lanes(9, 40);
/// let mut y = vec![[0.0; LANES]; 300];
/// lanes.fill(&mut y);
/// let mut one = vec![0.0; 300];
/// gm.stream(stream(9, 45)).fill(&mut one);
/// assert!(y.iter().zip(&one).all(|(a, b)| a[5].to_bits() == b.to_bits()));
/// ```
pub struct GaussMarkovLanes<'a> {
    model: &'a GaussMarkov,
    z: Vec<[f64; LANES]>,
    normals: NormalLanes,
    eps: Vec<[f64; LANES]>,
}

impl GaussMarkov {
    /// Realizations `first .. first + LANES` of `seed` in lockstep, each started from its stationary state
    /// (see [`GaussMarkovLanes`]).
    pub fn lanes(&self, seed: u64, first: u64) -> GaussMarkovLanes<'_> {
        let n = self.n_states();
        let mut normals = NormalLanes::new(seed, first);
        let mut e = vec![[0.0; LANES]; n];
        normals.inner.fill(&mut e);
        let p0 = self.flat_matrices()[2];
        let z = (0..n)
            .map(|i| std::array::from_fn(|l| (0..n).map(|j| p0[i * n + j] * e[j][l]).sum()))
            .collect();
        GaussMarkovLanes {
            model: self,
            z,
            normals,
            eps: vec![[0.0; LANES]; LANE_DRAW_STEPS * n],
        }
    }
}

impl GaussMarkovLanes<'_> {
    /// The current state of every lane (`state()[i][l]`: state i of lane l).
    pub fn state(&self) -> &[[f64; LANES]] {
        &self.z
    }

    /// Writes the next `out.len() / p` output samples of every lane (sample-major: `out[k·p + r][l]` is
    /// output r of lane l at step k) and advances the lanes, as [`GaussMarkov::advance`] does for one
    /// realization; consecutive calls continue the same realizations. A trailing partial sample is left
    /// untouched.
    ///
    /// The normals of every lane are drawn [`LANE_DRAW_STEPS`] steps at a time, then those steps are stepped
    /// (compiled for the widest instruction set).
    pub fn fill(&mut self, out: &mut [[f64; LANES]]) {
        let (n, p) = (self.z.len(), self.model.n_outputs());
        let steps = out.len() / p;
        for chunk in out[..steps * p].chunks_mut(LANE_DRAW_STEPS * p) {
            let eps = &mut self.eps[..chunk.len() / p * n];
            self.normals.inner.fill(eps);
            let mut task = Advance {
                model: self.model,
                z: &mut self.z,
                eps,
                out: chunk,
            };
            vmath::run(&mut task);
        }
    }
}

/// The steps of one draw of normals, compiled for the widest instruction set by [`vmath::run`].
struct Advance<'t> {
    model: &'t GaussMarkov,
    z: &'t mut [[f64; LANES]],
    /// n normals of every lane per step
    eps: &'t [[f64; LANES]],
    /// p outputs of every lane per step
    out: &'t mut [[f64; LANES]],
}

impl vmath::Task for Advance<'_> {
    #[inline(always)]
    fn run(&mut self) {
        // the state in a fixed-size array for the sizes the scalar path unrolls (its values in registers)
        match self.z.len() {
            1 => self.fixed::<1>(),
            2 => self.fixed::<2>(),
            3 => self.fixed::<3>(),
            4 => self.fixed::<4>(),
            5 => self.fixed::<5>(),
            6 => self.fixed::<6>(),
            7 => self.fixed::<7>(),
            8 => self.fixed::<8>(),
            _ => self.dynamic(),
        }
    }
}

/// One step of every lane from its normals `w` (n rows), its outputs written to `y` (p rows).
trait Step {
    fn step(&mut self, w: &[[f64; LANES]], y: &mut [[f64; LANES]]);
}

impl Advance<'_> {
    /// Every step of `out`: `stepper.step(normals of the step, outputs of the step)`.
    #[inline(always)]
    fn steps(&mut self, stepper: &mut impl Step) {
        let (n, p) = (self.z.len(), self.model.n_outputs());
        for (yk, w) in self.out.chunks_exact_mut(p).zip(self.eps.chunks_exact(n)) {
            stepper.step(w, yk);
        }
    }

    /// The steps with N states (the arithmetic of the scalar `kernel::<N>`).
    #[inline(always)]
    fn fixed<const N: usize>(&mut self) {
        let model = self.model;
        let [phi, lm, _, h] = model.flat_matrices();
        let mut st = Fixed::<N> {
            ph: std::array::from_fn(|i| std::array::from_fn(|j| phi[i * N + j])),
            lf: std::array::from_fn(|i| std::array::from_fn(|j| lm[i * N + j])),
            h,
            z: std::array::from_fn(|i| self.z[i]),
        };
        self.steps(&mut st);
        self.z.copy_from_slice(&st.z);
    }

    /// The steps with more than 8 states (the arithmetic of the scalar `kernel_dyn`).
    #[inline(always)]
    fn dynamic(&mut self) {
        let model = self.model;
        let [phi, l, _, h] = model.flat_matrices();
        let mut st = Dynamic {
            phi,
            l,
            h,
            z: self.z.to_vec(),
            nz: self.z.to_vec(),
        };
        self.steps(&mut st);
        self.z.copy_from_slice(&st.z);
    }
}

/// The step of N states: the state in registers, the loops unrolled.
struct Fixed<'m, const N: usize> {
    ph: [[f64; N]; N],
    lf: [[f64; N]; N],
    h: &'m [f64],
    z: [[f64; LANES]; N],
}

impl<const N: usize> Step for Fixed<'_, N> {
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lanes: several arrays indexed by the lane
    fn step(&mut self, w: &[[f64; LANES]], y: &mut [[f64; LANES]]) {
        let z = &self.z;
        for (r, yr) in y.iter_mut().enumerate() {
            let mut s = [0.0; LANES];
            for j in 0..N {
                let a = self.h[r * N + j];
                for l in 0..LANES {
                    s[l] += a * z[j][l];
                }
            }
            *yr = s;
        }
        let mut nz = [[0.0; LANES]; N];
        for i in 0..N {
            // the noise terms first, then the Φz terms (the step-to-step chain)
            let mut s = [0.0; LANES];
            for l in 0..LANES {
                s[l] = self.lf[i][0] * w[0][l];
            }
            for j in 1..N {
                for l in 0..LANES {
                    s[l] += self.lf[i][j] * w[j][l];
                }
            }
            for j in 0..N {
                for l in 0..LANES {
                    s[l] += self.ph[i][j] * z[j][l];
                }
            }
            nz[i] = s;
        }
        self.z = nz;
    }
}

/// The step of any number of states.
struct Dynamic<'m> {
    phi: &'m [f64],
    l: &'m [f64],
    h: &'m [f64],
    z: Vec<[f64; LANES]>,
    nz: Vec<[f64; LANES]>,
}

impl Step for Dynamic<'_> {
    #[inline(always)]
    fn step(&mut self, w: &[[f64; LANES]], y: &mut [[f64; LANES]]) {
        let (n, z) = (self.z.len(), &self.z);
        for (r, yr) in y.iter_mut().enumerate() {
            *yr = std::array::from_fn(|l| (0..n).map(|j| self.h[r * n + j] * z[j][l]).sum());
        }
        for (i, zi) in self.nz.iter_mut().enumerate() {
            let mut s = [0.0; LANES];
            for (a, zj) in self.phi[i * n..][..n].iter().zip(z) {
                (0..LANES).for_each(|l| s[l] += a * zj[l]);
            }
            for (a, wj) in self.l[i * n..][..n].iter().zip(w) {
                (0..LANES).for_each(|l| s[l] += a * wj[l]);
            }
            *zi = s;
        }
        std::mem::swap(&mut self.z, &mut self.nz);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::stream;
    use nalgebra::DMatrix;

    /// A stable n-state model with p outputs: A = −diag(1, …, n) + 0.3·(coupling to the next state), a
    /// lower-triangular A (its eigenvalues −1, …, −n), G a column of ones, H with distinct rows.
    fn model(n: usize, p: usize) -> GaussMarkov {
        let a = DMatrix::from_fn(n, n, |i, j| match (i, j) {
            _ if i == j => -(i as f64 + 1.0),
            _ if i == j + 1 => 0.3,
            _ => 0.0,
        });
        let g = DMatrix::from_element(n, 1, 1.0);
        let h = DMatrix::from_fn(p, n, |r, j| 1.0 / (1.0 + r as f64 + j as f64));
        GaussMarkov::new(a, g, h, 0.05).unwrap()
    }

    /// Lanes give, bit for bit, the states and outputs of every realization run alone
    /// (`GaussMarkov::stream`), for 1, 2, 3, 5 (the fixed-size kernels) and 9 states (the other order), one
    /// and two outputs, in fills of uneven lengths (one step, part of a draw chunk, a chunk of 64, more
    /// than a chunk, and a fill with a trailing partial sample, which is left untouched).
    #[test]
    fn lanes_give_the_bits_of_one_realization_at_a_time() {
        let steps = [1usize, 37, 64, 200, 3];
        for (n, p) in [(1, 1), (2, 1), (3, 2), (5, 1), (9, 2)] {
            let gm = model(n, p);
            let (seed, first) = (21, 13);
            let mut lanes = gm.lanes(seed, first);
            let mut alone: Vec<_> = (0..LANES as u64).map(|l| gm.stream(stream(seed, first + l))).collect();
            let bits = |v: &mut dyn Iterator<Item = f64>| v.map(f64::to_bits).collect::<Vec<_>>();
            for (k, &m) in steps.iter().enumerate() {
                // the last fill has one slot more than its samples
                let extra = usize::from(k == steps.len() - 1);
                let mut got = vec![[7.0; LANES]; m * p + extra];
                lanes.fill(&mut got);
                for (l, s) in alone.iter_mut().enumerate() {
                    let mut want = vec![7.0; m * p + extra];
                    s.fill(&mut want);
                    let tag = format!("n {n}, p {p}, fill {k}, lane {l}");
                    assert_eq!(
                        bits(&mut got.iter().map(|g| g[l])),
                        bits(&mut want.into_iter()),
                        "{tag}"
                    );
                    assert_eq!(
                        bits(&mut lanes.state().iter().map(|z| z[l])),
                        bits(&mut s.state().iter().copied()),
                        "{tag}: state"
                    );
                }
            }
        }
    }
}
