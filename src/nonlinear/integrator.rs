//! Route 2's time integrator: a symmetric (Strang) splitting of the exact linear flow and the exact flows of
//! the element forces.
//!
//! # Formula
//! The state is the linear part's x = [q; p], p = M q̇ − B_u u (with the inputs' shaping-filter states on
//! the exact route). One step of Δt = h is
//! ```text
//! x_{k+1} = K_{h/2}(t_{k+1}) ∘ L_h ∘ K_{h/2}(t_k) x_k,      K_τ = K_τ^{(1)} ∘ … ∘ K_τ^{(E)} (reversed on the right)
//! ```
//! * L_h is the exact flow of the linear part over the step: on the exact route the Van Loan discretisation
//!   of the linear part augmented with the inputs' shaping filters (x ← Φx + Lε, no time-step error for the
//!   linear part, the same draws as a linear run), on the spectral route the first-order hold of the
//!   synthesised input samples (x ← Φx + Γ₀u_k + Γ₁u_{k+1}).
//! * K_τ^{(e)} is the exact flow of element e's force alone over τ with q and the inputs frozen: the
//!   momentum changes by −d_e J_e, J_e = ∫F_e dt ([`ForceLaw::impulse`](super::ForceLaw::impulse)): τF(x) for
//!   springs and stops, closed forms for the dampers, the Filippov flow of friction (sticking at v = 0).
//!
//! Every sub-flow is exact, so the composition is a symmetric splitting: second order for smooth forces
//! (Strang 1968, "On the construction and comparison of difference schemes", SIAM J. Numer. Anal. 5,
//! 506–517; for the stochastic case the noise is entirely in the exactly solved linear flow, as in the
//! BAOAB-type splittings of Leimkuhler & Matthews 2013, Appl. Math. Res. Express 2013(1), 34–56). A stop's
//! force is continuous with a jump in its slope: the one step that straddles each contact event makes an
//! O(h³) local error, which keeps the global order 2 (`tests/suite/nonlinear_routes.rs` measures it on
//! the free oscillation with a one-sided stop, whose period is known in closed form). A force jump
//! (friction reversing) makes it first order there. The kick of a stiff contact is explicit: the step must
//! resolve the contact frequency ω_c = √(κ k_c) (κ = dᵀM⁻¹d); route 2 takes h ≤ [`CONTACT_STEP`]/ω_c by
//! default and refuses h > 2/ω_c (unstable).

use super::{Kernel, NonlinearModel};
use crate::error::{Error, Result};
use crate::system::FrequencyResponse;
use nalgebra::DMatrix;
use std::sync::Arc;

/// Default resolution of the fastest contact: h·ω_c ≤ this (h·ω_c ≤ 0.3 keeps sampled contact rates
/// within 1 % on a stiff two-sided stop).
pub const CONTACT_STEP: f64 = 0.25;

/// Default resolution of dry friction: a step changes the element's relative velocity by at most this
/// fraction of its σ_v (κF_cΔt ≤ FRICTION_STEP·σ_v). The friction kick holds a sticking element's velocity
/// within κF_cΔt of zero (the linear flow moves it off zero by less than that in a step, the next kick
/// brings it back), so this is also the bound of the velocity's error while it sticks.
pub const FRICTION_STEP: f64 = 0.05;

/// One value per lane: realizations stepped in lockstep keep each state variable as an array over them
/// (structure of arrays); a lane does the scalar arithmetic of a lone realization, in the same order.
pub(crate) type Lanes<const L: usize> = [f64; L];

/// The element kicks of a model: directions, M⁻¹d, κ and the base input of every element.
#[derive(Debug, Clone)]
pub(crate) struct Kicks {
    n: usize,
    items: Vec<Kick>,
    /// M⁻¹ (n × n, row-major).
    minv: Vec<f64>,
    /// B_u (n × base inputs, row-major).
    bu: Vec<f64>,
    n_base: usize,
    /// The set-valued elements (dry friction), whose force is read from their impulses.
    set_valued: Vec<usize>,
}

#[derive(Debug, Clone)]
struct Kick {
    d: Vec<f64>,
    minv_d: Vec<f64>,
    kappa: f64,
    base: Option<usize>,
    law: Arc<dyn super::ForceLaw>,
    velocity: bool,
}

fn row_major(m: &DMatrix<f64>) -> Vec<f64> {
    let mut v = Vec::with_capacity(m.len());
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            v.push(m[(i, j)]);
        }
    }
    v
}

impl Kicks {
    pub(crate) fn new(model: &NonlinearModel) -> Kicks {
        let lin = model.linear();
        let n = lin.n_coords();
        let minv = lin.mass_inverse();
        let items: Vec<Kick> = model
            .elements()
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let d = e.direction();
                let minv_d = (0..n).map(|r| (0..n).map(|c| minv[(r, c)] * d[c]).sum()).collect();
                Kick {
                    d,
                    minv_d,
                    kappa: model.kappa(i),
                    base: e.base(),
                    law: e.law.clone(),
                    velocity: e.law.velocity_dependent(),
                }
            })
            .collect();
        Kicks {
            n,
            set_valued: (0..items.len()).filter(|&e| items[e].law.set_valued()).collect(),
            items,
            minv: row_major(minv),
            bu: row_major(lin.base_damping()),
            n_base: lin.n_base(),
        }
    }

    /// Whether an element's force is set-valued (dry friction: see [`Prepared::set_valued_forces`]).
    pub(crate) fn has_set_valued(&self) -> bool {
        !self.set_valued.is_empty()
    }

    /// Number of elements.
    pub(crate) fn len(&self) -> usize {
        self.items.len()
    }

    /// q̇ = M⁻¹(p + B_u u) into `qdot` (u: the base inputs first), lane by lane (the rows as slices zipped
    /// with the vectors: no bounds check per term).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub(crate) fn velocities<const L: usize>(&self, p: &[Lanes<L>], u: &[Lanes<L>], qdot: &mut [Lanes<L>]) {
        let (n, nb) = (self.n, self.n_base);
        for (out, minv) in qdot.iter_mut().zip(self.minv.chunks_exact(n)) {
            let mut s = [0.0; L];
            for (c, (m, p)) in minv.iter().zip(p).enumerate() {
                let mut pc = *p;
                for (b, u) in self.bu[c * nb..(c + 1) * nb].iter().zip(u) {
                    for l in 0..L {
                        pc[l] += b * u[l];
                    }
                }
                for l in 0..L {
                    s[l] += m * pc[l];
                }
            }
            *out = s;
        }
    }

    /// Deflection x_e and rate v_e of element e, lane by lane.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub(crate) fn kinematics<const L: usize>(
        &self,
        e: usize,
        q: &[Lanes<L>],
        qdot: &[Lanes<L>],
        u: &[Lanes<L>],
        ud: &[Lanes<L>],
    ) -> (Lanes<L>, Lanes<L>) {
        let k = &self.items[e];
        let mut x = [0.0; L];
        let mut v = [0.0; L];
        for (i, d) in k.d.iter().enumerate() {
            for l in 0..L {
                x[l] += d * q[i][l];
            }
            if k.velocity {
                for l in 0..L {
                    v[l] += d * qdot[i][l];
                }
            }
        }
        if let Some(j) = k.base {
            for l in 0..L {
                x[l] -= u[j][l];
            }
            if k.velocity {
                for l in 0..L {
                    v[l] -= ud[j][l];
                }
            }
        }
        (x, v)
    }

    /// The kicks of duration τ, with every element's [`Kernel`] where its law has one.
    pub(crate) fn prepared(&self, tau: f64) -> Prepared<'_> {
        Prepared {
            kicks: self,
            tau,
            kernels: self.items.iter().map(|k| k.law.kernel(k.kappa, tau)).collect(),
        }
    }
}

/// The element kicks of one duration τ (see [`Kicks::prepared`]).
pub(crate) struct Prepared<'a> {
    kicks: &'a Kicks,
    tau: f64,
    kernels: Vec<Option<Kernel>>,
}

impl Prepared<'_> {
    /// The exact flow of every element over τ, in order (or in reverse order): p −= d J, q̇ −= M⁻¹d J, lane
    /// by lane (a lane whose impulse is 0 keeps its bits); every element's impulse J into `impulses` when
    /// given. `(u, ud)`: the base inputs and their rates.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub(crate) fn kick<const L: usize>(
        &self,
        q: &[Lanes<L>],
        p: &mut [Lanes<L>],
        qdot: &mut [Lanes<L>],
        (u, ud): (&[Lanes<L>], &[Lanes<L>]),
        reverse: bool,
        mut impulses: Option<&mut [Lanes<L>]>,
    ) {
        let items = &self.kicks.items;
        for step in 0..items.len() {
            let e = if reverse { items.len() - 1 - step } else { step };
            let (x, v) = self.kicks.kinematics(e, q, qdot, u, ud);
            let k = &items[e];
            let j = self.impulses(e, &x, &v);
            for ((pi, qi), (d, md)) in p.iter_mut().zip(qdot.iter_mut()).zip(k.d.iter().zip(&k.minv_d)) {
                sub_where_moved(pi, *d, &j);
                sub_where_moved(qi, *md, &j);
            }
            if let Some(out) = impulses.as_deref_mut() {
                out[e] = j;
            }
        }
    }

    /// Element e's impulse over τ at deflection x and rate v, lane by lane (its [`Kernel`] where it has one).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    fn impulses<const L: usize>(&self, e: usize, x: &Lanes<L>, v: &Lanes<L>) -> Lanes<L> {
        let mut j = [0.0; L];
        match &self.kernels[e] {
            Some(kernel) => kernel.impulses(x, v, &mut j),
            None => {
                let k = &self.kicks.items[e];
                for l in 0..L {
                    j[l] = k.law.impulse(x[l], v[l], k.kappa, self.tau);
                }
            }
        }
        j
    }

    /// The forces of the set-valued elements (dry friction, [`super::ForceLaw::set_valued`]) over the step
    /// around the state, into `out`: F = (J_b + J_f)/(2τ), J_b the impulse of the reverse half kick that
    /// ended the step before (`last`, from [`Prepared::kick`]) and J_f that of the forward half kick the
    /// state is about to get (the element's own flow at the state). While the element slides this is
    /// ±F_c, as F(x, v) is; while it sticks, v = 0 at the state and F(x, 0) = 0 says nothing, but the
    /// impulses that held v at zero over the step are the constraint force, |F| ≤ F_c: the force the
    /// element actually exerted, which an acceleration output must include.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub(crate) fn set_valued_forces<const L: usize>(
        &self,
        (q, qdot): (&[Lanes<L>], &[Lanes<L>]),
        (u, ud): (&[Lanes<L>], &[Lanes<L>]),
        last: &[Lanes<L>],
        out: &mut [Lanes<L>],
    ) {
        let h = 2.0 * self.tau;
        for &e in &self.kicks.set_valued {
            let (x, v) = self.kicks.kinematics(e, q, qdot, u, ud);
            let j = self.impulses(e, &x, &v);
            for l in 0..L {
                out[e][l] = (last[e][l] + j[l]) / h;
            }
        }
    }

    /// Every element's remainder force F_e and deflection x_e at the state (for acceleration outputs and
    /// statistics), lane by lane.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub(crate) fn forces<const L: usize>(
        &self,
        q: &[Lanes<L>],
        qdot: &[Lanes<L>],
        u: &[Lanes<L>],
        ud: &[Lanes<L>],
        out: &mut [Lanes<L>],
        xe: &mut [Lanes<L>],
    ) {
        for (e, (f, xo)) in out.iter_mut().zip(xe.iter_mut()).enumerate() {
            let (x, v) = self.kicks.kinematics(e, q, qdot, u, ud);
            *xo = x;
            match &self.kernels[e] {
                Some(kernel) => kernel.forces(&x, &v, f),
                None => {
                    for l in 0..L {
                        f[l] = self.kicks.items[e].law.force(x[l], v[l]);
                    }
                }
            }
        }
    }

    /// Whether element e is in its regime at deflection x, lane by lane.
    #[inline(always)]
    pub(crate) fn engaged<const L: usize>(&self, e: usize, x: &Lanes<L>) -> [bool; L] {
        match &self.kernels[e] {
            Some(kernel) => kernel.engaged_lanes(x),
            None => x.map(|x| self.kicks.items[e].law.engaged(x)),
        }
    }
}

/// x ← x − a·j in every lane whose impulse j is not 0, x unchanged where j = ±0: the kick's update of a
/// momentum or velocity, in a form that compiles to vector operations across the lanes (a select on
/// `j ≠ 0` compiled to a branch per lane).
///
/// # Formula
/// x − s with s = a·j where j ≠ 0 and s = +0 where j = ±0 ([`where_else_zero`], a bit mask): where the lane
/// moves, s is a·j itself; where it does not, x − (+0) = x for every non-NaN x (−0 − (+0) = −0 in
/// round-to-nearest; a·j = ±0 subtracted instead would turn x = −0 into +0 when a·j = −0). Each lane's
/// bits are those of `if j ≠ 0 { x − a·j } else { x }`.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
fn sub_where_moved<const L: usize>(x: &mut Lanes<L>, a: f64, j: &Lanes<L>) {
    for l in 0..L {
        x[l] -= where_else_zero(a * j[l], j[l] != 0.0);
    }
}

/// `x` where `keep`, +0 otherwise: the bits of `if keep { x } else { 0.0 }` for every x (NaN included), as
/// a bit mask (x's bits ANDed with all ones, or with zero), which compiles to one vector `and` across lanes where
/// the select compiled to a branch per lane.
#[inline(always)]
fn where_else_zero(x: f64, keep: bool) -> f64 {
    f64::from_bits(x.to_bits() & u64::from(keep).wrapping_neg())
}

/// The deterministic free response of `model` (no input) from q(0) = `q0`, q̇(0) = `v0` after `steps` steps
/// of `h` by the splitting integrator: returns (q, q̇) at the end. This is route 2's scheme with the noise
/// switched off, for order checks on problems with a known answer.
///
/// # Errors
/// Lengths that do not match the model; h ≤ 0; the matrix exponential's failures.
///
/// # Examples
/// ```
/// use stochvib::nonlinear::{integrator::free_response, BumpStop, NonlinearElement, NonlinearModel};
/// use stochvib::system::{Attach, Drive, MassSpringDamper, Mdof};
/// use std::sync::Arc;
/// // x″ + x = 0 with a stop that is never reached: the exact linear flow, to rounding
/// let lin = MassSpringDamper { mass: 1.0, stiffness: 1.0, damping: 0.0, drive: Drive::Force }.build().unwrap();
/// let stop = NonlinearElement { name: "stop".into(), law: Arc::new(BumpStop::new(Some((5.0, 100.0)), None).unwrap()),
///     point: vec![1.0], to: Attach::Ground };
/// let m = NonlinearModel::new(&lin, vec![stop]).unwrap();
/// let (q, _) = free_response(&m, &[0.0], &[1.0], 0.1, 10).unwrap();
/// assert!((q[0] - 1.0f64.sin()).abs() < 1e-12);
/// ```
pub fn free_response(
    model: &NonlinearModel,
    q0: &[f64],
    v0: &[f64],
    h: f64,
    steps: usize,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let lin = model.linear();
    let n = lin.n_coords();
    if q0.len() != n || v0.len() != n || !(h > 0.0 && h.is_finite()) {
        return Err(Error::invalid(
            "free_response",
            format!("{} coordinates, h = {h}", q0.len()),
            format!("need {n} coordinates and h > 0"),
        ));
    }
    let ss = lin.state_space().ok_or_else(|| Error::Numerical {
        what: "free response".into(),
        reason: "no state space".into(),
    })?;
    let phi = row_major(&crate::linalg::expm(&(&ss.a * h))?);
    let kicks = Kicks::new(model);
    let mv = lin.mass() * nalgebra::DVector::from_column_slice(v0);
    let mut x: Vec<Lanes<1>> = q0.iter().chain(mv.iter()).map(|v| [*v]).collect();
    let mut qdot: Vec<Lanes<1>> = v0.iter().map(|v| [*v]).collect();
    let mut next = vec![0.0; 2 * n];
    let nb = lin.n_inputs();
    let zeros = vec![[0.0]; nb.max(1)];
    let half = kicks.prepared(0.5 * h);
    for _ in 0..steps {
        let (q, p) = x.split_at_mut(n);
        half.kick(q, p, &mut qdot, (&zeros, &zeros), false, None);
        for (i, o) in next.iter_mut().enumerate() {
            *o = (0..2 * n).map(|j| phi[i * 2 * n + j] * x[j][0]).sum();
        }
        x.iter_mut().zip(&next).for_each(|(a, b)| *a = [*b]);
        let (q, p) = x.split_at_mut(n);
        kicks.velocities(p, &zeros, &mut qdot);
        half.kick(q, p, &mut qdot, (&zeros, &zeros), true, None);
    }
    let (q, p) = x.split_at(n);
    kicks.velocities(p, &zeros, &mut qdot);
    let q = q.iter().map(|v| v[0]).collect();
    Ok((q, qdot.iter().map(|v| v[0]).collect()))
}

#[cfg(test)]
mod tests {
    use super::{sub_where_moved, where_else_zero};

    /// [`where_else_zero`] has the bits of the select `if keep { x } else { 0.0 }` for every kind of x: ±0,
    /// the smallest subnormal, ±1, the largest finite values, ±∞ and a NaN with a payload.
    #[test]
    fn the_mask_gives_the_bits_of_the_select() {
        let nan = f64::from_bits(0x7ff8_0000_0000_1234);
        for x in [
            0.0,
            -0.0,
            5e-324,
            -5e-324,
            1.0,
            -1.0,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            nan,
        ] {
            for keep in [false, true] {
                let want = if keep { x } else { 0.0 };
                assert_eq!(
                    where_else_zero(x, keep).to_bits(),
                    want.to_bits(),
                    "x = {x:e}, keep = {keep}"
                );
            }
        }
    }

    /// The kick's update in its scalar form (the oracle of [`sub_where_moved`]).
    fn scalar(x: f64, a: f64, j: f64) -> f64 {
        if j != 0.0 {
            x - a * j
        } else {
            x
        }
    }

    /// States, factors and impulses: ±0, the smallest subnormal, ±1, the largest finite values, 0.1, −3.7
    /// and 200 magnitudes from 10⁻³⁰⁰ to 10³⁰⁰ of either sign (no NaN; a·j may overflow to ±∞).
    fn values() -> Vec<f64> {
        let mut v = vec![0.0, -0.0, 5e-324, -5e-324, 1.0, -1.0, f64::MAX, f64::MIN, 0.1, -3.7];
        let mut u = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200 {
            u = u
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let m = (u >> 11) as f64 / (1u64 << 53) as f64;
            v.push((if u & 1 == 0 { 1.0 } else { -1.0 }) * 10f64.powf(600.0 * m - 300.0));
        }
        v
    }

    /// Case (ia, k) of the test: every window of 8 consecutive values as x, and as j with a quarter of the
    /// lanes +0 and a quarter −0 (lanes that do not move).
    fn case(v: &[f64], ia: usize, k: usize) -> ([f64; 8], [f64; 8]) {
        let n = v.len();
        let x = std::array::from_fn(|l| v[(k + l) % n]);
        let j = std::array::from_fn(|l| match (k + l + ia) % 4 {
            0 => 0.0,
            1 => -0.0,
            _ => v[(3 * k + l) % n],
        });
        (x, j)
    }

    /// [`sub_where_moved`] of 8 lanes and of 1 over every case, as compiled by `vmath::run` for the widest
    /// instruction set of the CPU (the code of the drive loop).
    struct Updates<'a> {
        v: &'a [f64],
        eight: Vec<[f64; 8]>,
        one: Vec<f64>,
    }

    impl crate::linalg::vmath::Task for Updates<'_> {
        #[inline(always)]
        fn run(&mut self) {
            for (ia, &a) in self.v.iter().enumerate() {
                for k in 0..self.v.len() {
                    let (mut x, j) = case(self.v, ia, k);
                    let mut one = [x[0]];
                    sub_where_moved(&mut x, a, &j);
                    sub_where_moved(&mut one, a, &[j[0]]);
                    self.eight.push(x);
                    self.one.push(one[0]);
                }
            }
        }
    }

    /// [`sub_where_moved`] gives the bits of the scalar select in every lane, 8 lanes and 1, compiled for
    /// the baseline and (through `vmath::run`) for the widest instruction set of the CPU, over states,
    /// factors and impulses that include ±0 (lanes that do not move, and x = −0 that must stay −0).
    #[test]
    fn lanes_give_the_bits_of_the_scalar_select() {
        let v = values();
        let mut wide = Updates {
            v: &v,
            eight: Vec::new(),
            one: Vec::new(),
        };
        crate::linalg::vmath::run(&mut wide);
        let mut c = 0;
        for (ia, &a) in v.iter().enumerate() {
            for k in 0..v.len() {
                let (x, j) = case(&v, ia, k);
                let want: [f64; 8] = std::array::from_fn(|l| scalar(x[l], a, j[l]));
                let mut got = x;
                sub_where_moved(&mut got, a, &j);
                let bits = |y: [f64; 8]| y.map(f64::to_bits);
                assert_eq!(bits(got), bits(want), "a = {a:e}, x = {x:?}, j = {j:?}");
                assert_eq!(bits(wide.eight[c]), bits(want), "a = {a:e}, x = {x:?}, j = {j:?}");
                assert_eq!(
                    wide.one[c].to_bits(),
                    want[0].to_bits(),
                    "a = {a:e}, x = {}, j = {}",
                    x[0],
                    j[0]
                );
                c += 1;
            }
        }
    }
}
