//! The realizations of route 2: the splitting integrator driven through burn-in and record, its samples fed
//! to the records of every output; and the Δt-halving check of a realization. On the spectral route
//! [`LANES`] realizations are stepped in lockstep, every state variable an array over them (structure of
//! arrays), so that the per-step arithmetic vectorises across realizations; each lane does exactly the
//! operations of a lone realization in the same order, so the results of a seed keep their bits.

use super::flow::{ExactFlow, FohFlow, HoldStep, NoisyStep};
use super::inputs::{refine, InputSamples};
use super::plan::{Flow, NlPlan};
use super::record::OutputRecords;
use super::sink::{records, LoneRecords, Sink};
use crate::error::Result;
use crate::estimate::{WelchScratch, WelchSums};
use crate::linalg::vmath;
use crate::nonlinear::integrator::{Lanes, Prepared};
use crate::simulate::lane_normals::{LaneNormals, StreamRng};
use crate::simulate::{fill_standard_normal, splitmix64, stream, Scratch, StreamNormals, LANE_DRAW_STEPS};
use rand::rngs::Xoshiro256PlusPlus;
use std::ops::Range;

/// One realization's results.
pub(crate) struct NlRealization {
    /// Time averages of y − c and (y − c)² per output (the standard moments accumulator).
    pub m: Vec<f64>,
    pub v: Vec<f64>,
    pub welch: Vec<WelchSums>,
    /// Per output: mean, variance, kurtosis, max |y|, rates per level, (fraction, rate) per regime, Δmean, Δσ.
    pub values: Vec<Vec<f64>>,
    pub hist: Vec<Vec<f64>>,
    pub raw: Vec<Vec<f64>>,
    pub raw_inputs: Vec<Vec<f64>>,
}

/// Realizations route 2 steps in lockstep (see [`realize_group`]).
pub(crate) const LANES: usize = 8;

/// A path of the linear flow for L realizations in lockstep: how to read the inputs and outputs from its
/// state and advance it (every quantity one [`Lanes`] value per state variable, input or output).
trait Path<const L: usize> {
    fn state(&mut self) -> &mut [Lanes<L>];
    fn mech(&self) -> usize;
    /// ũ of every input (base, then force; 0 where not needed) and u̇ of the base inputs at sample k.
    fn inputs(&self, k: usize, u: &mut [Lanes<L>], ud: &mut [Lanes<L>]);
    /// The linear part of every output at sample k.
    fn outputs(&self, k: usize, u: &[Lanes<L>], ud: &[Lanes<L>], y: &mut [Lanes<L>]);
    /// Advances the state from sample k to k + 1.
    fn step(&mut self, k: usize);
}

/// Where the exact flow's noise comes from.
enum Noise<'a> {
    /// Fresh normals from the realization's stream (the draws of a linear run).
    Stream(StreamNormals<Xoshiro256PlusPlus>),
    /// Stored normals, one vector of nz per fine step.
    Fine(&'a [f64]),
    /// The coarse steps of stored fine normals (η = Φ_f L_f w₁ + L_f w₂).
    Coarse(&'a [f64]),
}

/// The exact route's path: one realization (its noise is drawn in the order of a linear run).
struct ExactPath<'a> {
    flow: &'a ExactFlow,
    step: &'a NoisyStep,
    noise: Noise<'a>,
    z: Vec<Lanes<1>>,
    w: Vec<f64>,
    next: Vec<f64>,
}

impl Path<1> for ExactPath<'_> {
    fn state(&mut self) -> &mut [Lanes<1>] {
        &mut self.z
    }
    fn mech(&self) -> usize {
        self.flow.mech
    }
    fn inputs(&self, _k: usize, u: &mut [Lanes<1>], ud: &mut [Lanes<1>]) {
        let z = self.z.as_flattened();
        let dot = |r: &[f64]| r.iter().zip(z).map(|(a, b)| a * b).sum::<f64>();
        for (j, row) in self.flow.u_rows.iter().enumerate() {
            u[j] = [dot(row)];
            ud[j] = [self.flow.ud_rows[j].as_deref().map_or(0.0, dot)];
        }
    }
    fn outputs(&self, _k: usize, _u: &[Lanes<1>], _ud: &[Lanes<1>], y: &mut [Lanes<1>]) {
        for (o, row) in y.iter_mut().zip(&self.flow.out_rows) {
            let mut s = 0.0;
            for (a, b) in row.iter().zip(self.z.as_flattened()) {
                s += a * b;
            }
            *o = [s];
        }
    }
    fn step(&mut self, k: usize) {
        let n = self.flow.nz;
        let z = self.z.as_flattened_mut();
        match &mut self.noise {
            Noise::Stream(normals) => self.flow.step(self.step, z, &mut self.w, &mut self.next, normals),
            Noise::Fine(w) => self
                .flow
                .step_with(self.step, z, &w[k * n..(k + 1) * n], &mut self.next),
            Noise::Coarse(w) => {
                let (w1, w2) = (&w[2 * k * n..(2 * k + 1) * n], &w[(2 * k + 1) * n..(2 * k + 2) * n]);
                self.flow.coupled_noise(w1, w2, &mut self.w);
                self.flow.step_noise(self.step, z, &self.w, &mut self.next);
            }
        }
    }
}

/// The exact route's path for L realizations in lockstep: lane l draws from its own stream in the order of
/// [`ExactPath`] alone (the initial state's normals, then nz a step; the L streams drawn side by side,
/// [`LANE_DRAW_STEPS`] steps ahead, each lane's k-th draw that of its stream alone) and does the additions
/// of [`ExactPath`], [`GaussMarkov::initial_state`](crate::simulate::GaussMarkov::initial_state) and
/// [`ExactFlow::step_with`] in the same order, so every lane has the bits of its realization alone.
struct ExactLanes<'a, const L: usize> {
    flow: &'a ExactFlow,
    step: &'a NoisyStep,
    normals: LaneNormals<L>,
    z: Vec<Lanes<L>>,
    /// The normals of the next [`LANE_DRAW_STEPS`] steps (nz a step) and how many of them are used.
    w: Vec<Lanes<L>>,
    used: usize,
    next: Vec<Lanes<L>>,
}

impl<const L: usize> ExactLanes<'_, L> {
    /// Σ row·z per lane, from −0 as `Iterator::sum` folds (the bits of [`ExactPath::inputs`]).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    fn dot(&self, row: &[f64]) -> Lanes<L> {
        let mut s = [-0.0; L];
        for (a, b) in row.iter().zip(&self.z) {
            for l in 0..L {
                s[l] += a * b[l];
            }
        }
        s
    }
}

impl<const L: usize> Path<L> for ExactLanes<'_, L> {
    #[inline(always)]
    fn state(&mut self) -> &mut [Lanes<L>] {
        &mut self.z
    }
    fn mech(&self) -> usize {
        self.flow.mech
    }
    #[inline(always)]
    fn inputs(&self, _k: usize, u: &mut [Lanes<L>], ud: &mut [Lanes<L>]) {
        for (j, row) in self.flow.u_rows.iter().enumerate() {
            u[j] = self.dot(row);
            ud[j] = self.flow.ud_rows[j].as_deref().map_or([0.0; L], |r| self.dot(r));
        }
    }
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    fn outputs(&self, _k: usize, _u: &[Lanes<L>], _ud: &[Lanes<L>], y: &mut [Lanes<L>]) {
        for (o, row) in y.iter_mut().zip(&self.flow.out_rows) {
            let mut s = [0.0; L];
            for (a, b) in row.iter().zip(&self.z) {
                for l in 0..L {
                    s[l] += a * b[l];
                }
            }
            *o = s;
        }
    }
    /// z ← Φz + Lw with each lane's nz fresh normals: for nz ≤ 8 the sum starts at L₀w₀ and adds the
    /// noise terms, then the state terms; above 8 it starts at 0 and adds the state terms first (the orders
    /// of [`ExactFlow::step_with`]).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    fn step(&mut self, _k: usize) {
        let n = self.flow.nz;
        if self.used == self.w.len() {
            self.normals.fill(&mut self.w);
            self.used = 0;
        }
        let w = &self.w[self.used..self.used + n];
        self.used += n;
        let s = self.step;
        for (i, o) in self.next.iter_mut().enumerate() {
            let (lr, ph) = (&s.l[i * n..(i + 1) * n], &s.phi[i * n..(i + 1) * n]);
            let mut acc = [0.0; L];
            if n <= 8 {
                for l in 0..L {
                    acc[l] = lr[0] * w[0][l];
                }
                for (a, w) in lr.iter().zip(w).skip(1) {
                    for l in 0..L {
                        acc[l] += a * w[l];
                    }
                }
                for (a, z) in ph.iter().zip(&self.z) {
                    for l in 0..L {
                        acc[l] += a * z[l];
                    }
                }
            } else {
                for (a, z) in ph.iter().zip(&self.z) {
                    for l in 0..L {
                        acc[l] += a * z[l];
                    }
                }
                for (a, w) in lr.iter().zip(w) {
                    for l in 0..L {
                        acc[l] += a * w[l];
                    }
                }
            }
            *o = acc;
        }
        self.z.copy_from_slice(&self.next);
    }
}

/// The spectral route's path: L realizations, each with its own synthesised inputs.
struct HoldPath<'a, const L: usize> {
    flow: &'a FohFlow,
    step: &'a HoldStep,
    /// Per lane: the input samples u\[j\]\[k\] and the rates u̇\[r\]\[k\].
    u: [&'a [Vec<f64>]; L],
    rates: [&'a [Vec<f64>]; L],
    rate_inputs: &'a [usize],
    x: Vec<Lanes<L>>,
    next: Vec<Lanes<L>>,
    u0: Vec<Lanes<L>>,
    u1: Vec<Lanes<L>>,
    /// The sample whose inputs `u1` holds (gathered by the last step): the next step's u₀ and the inputs
    /// of that sample are copied from it instead of gathered again from every lane's samples.
    held: Option<usize>,
}

impl<const L: usize> HoldPath<'_, L> {
    /// Every input's sample k into `out`.
    #[inline(always)]
    fn gather(&self, k: usize, out: &mut [Lanes<L>]) {
        for (j, o) in out.iter_mut().enumerate().take(self.u[0].len()) {
            *o = std::array::from_fn(|l| self.u[l][j][k]);
        }
    }
}

impl<const L: usize> Path<L> for HoldPath<'_, L> {
    #[inline(always)]
    fn state(&mut self) -> &mut [Lanes<L>] {
        &mut self.x
    }
    fn mech(&self) -> usize {
        0
    }
    #[inline(always)]
    fn inputs(&self, k: usize, u: &mut [Lanes<L>], ud: &mut [Lanes<L>]) {
        let m = self.u[0].len().min(u.len());
        if self.held == Some(k) && m <= self.u1.len() {
            u[..m].copy_from_slice(&self.u1[..m]);
        } else {
            self.gather(k, u);
        }
        ud.iter_mut().for_each(|v| *v = [0.0; L]);
        for (r, &j) in self.rate_inputs.iter().enumerate() {
            ud[j] = std::array::from_fn(|l| self.rates[l][r][k]);
        }
    }
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    fn outputs(&self, _k: usize, u: &[Lanes<L>], ud: &[Lanes<L>], y: &mut [Lanes<L>]) {
        let f = self.flow;
        for (r, o) in y.iter_mut().enumerate() {
            let mut s = [0.0; L];
            for (a, b) in f.c_rows[r].iter().zip(&self.x) {
                for l in 0..L {
                    s[l] += a * b[l];
                }
            }
            for j in 0..f.m {
                let (d, e) = (f.d_rows[r][j], f.e_rows[r][j]);
                for l in 0..L {
                    s[l] += d * u[j][l] + e * ud[j][l];
                }
            }
            *o = s;
        }
    }
    #[inline(always)]
    fn step(&mut self, k: usize) {
        if self.held == Some(k) {
            std::mem::swap(&mut self.u0, &mut self.u1);
        } else {
            let mut u0 = std::mem::take(&mut self.u0);
            self.gather(k, &mut u0);
            self.u0 = u0;
        }
        let mut u1 = std::mem::take(&mut self.u1);
        self.gather(k + 1, &mut u1);
        self.u1 = u1;
        self.held = Some(k + 1);
        self.flow
            .step(self.step, &mut self.x, &self.u0, &self.u1, &mut self.next);
    }
}

/// What takes every recorded sample of [`drive`]: the outputs y and the element deflections x (one
/// [`Lanes`] value each). Always inlined into the drive loop (a closure's call is not, and its body would
/// then miss the instruction set of [`Drive`]: the histogram's bin was a libm `floor` call).
trait Records<const L: usize> {
    fn record(&mut self, y: &[Lanes<L>], x: &[Lanes<L>]);
}

impl<const L: usize, F: FnMut(&[Lanes<L>], &[Lanes<L>])> Records<L> for F {
    #[inline(always)]
    fn record(&mut self, y: &[Lanes<L>], x: &[Lanes<L>]) {
        self(y, x)
    }
}

/// The records of L realizations stepped in lockstep with the Welch scratch of the thread.
struct Recorder<'s, 'p, 'w, const L: usize> {
    sink: &'s mut Sink<'p, L>,
    welch: &'w mut WelchScratch,
}

impl<const L: usize> Records<L> for Recorder<'_, '_, '_, L> {
    #[inline(always)]
    fn record(&mut self, y: &[Lanes<L>], x: &[Lanes<L>]) {
        self.sink.push(y, x, self.welch);
    }
}

/// The per-step quantities of [`drive`], one [`Lanes`] value each, allocated once per run.
struct StepState<const L: usize> {
    /// Input fluctuations ũ and rates u̇ of every model input, absolute base inputs u = ū + ũ.
    ut: Vec<Lanes<L>>,
    ud: Vec<Lanes<L>>,
    ua: Vec<Lanes<L>>,
    /// Absolute coordinates q = q_eq + q̃ and their velocities.
    q: Vec<Lanes<L>>,
    qdot: Vec<Lanes<L>>,
    /// Outputs, element deflections and element forces.
    y: Vec<Lanes<L>>,
    xe: Vec<Lanes<L>>,
    fe: Vec<Lanes<L>>,
    /// The impulses of the last reverse half kick (read for the set-valued elements' forces).
    jb: Vec<Lanes<L>>,
}

impl<const L: usize> StepState<L> {
    fn new(plan: &NlPlan) -> Self {
        let (n, nb, ne) = (plan.n_coords, plan.n_base, plan.kicks.len());
        StepState {
            ut: vec![[0.0; L]; plan.u_mean.len()],
            // every model input's rate: an output row may use a force input's too (D and E of all inputs)
            ud: vec![[0.0; L]; plan.u_mean.len().max(1)],
            ua: vec![[0.0; L]; nb.max(1)],
            q: vec![[0.0; L]; n],
            qdot: vec![[0.0; L]; n],
            y: vec![[0.0; L]; plan.outputs.len()],
            xe: vec![[0.0; L]; ne],
            fe: vec![[0.0; L]; ne],
            jb: vec![[0.0; L]; ne],
        }
    }

    /// The inputs of sample k and the absolute coordinates and velocities of the path's state.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    fn refresh<P: Path<L>>(&mut self, plan: &NlPlan, path: &mut P, k: usize) {
        let (n, nb, mech) = (plan.n_coords, plan.n_base, path.mech());
        path.inputs(k, &mut self.ut, &mut self.ud);
        // local lane arrays: the compiler cannot tell the heap arrays apart, and computed in place these
        // sums were scalar, lane by lane
        for j in 0..nb {
            let (mean, ut, mut a) = (plan.u_mean[j], self.ut[j], [0.0; L]);
            for l in 0..L {
                a[l] = mean + ut[l];
            }
            self.ua[j] = a;
        }
        let st = path.state();
        for i in 0..n {
            let (eq, qt, mut a) = (plan.q_eq[i], st[mech + i], [0.0; L]);
            for l in 0..L {
                a[l] = eq + qt[l];
            }
            self.q[i] = a;
        }
        plan.kicks
            .velocities(&st[mech + n..mech + 2 * n], &self.ut, &mut self.qdot);
    }

    /// The outputs of sample k (the linear part's, the offsets, minus the element forces' accelerations)
    /// into `y`, the element deflections into `xe`.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    fn outputs<P: Path<L>>(&mut self, plan: &NlPlan, half: &Prepared, path: &P, k: usize) {
        path.outputs(k, &self.ut, &self.ud, &mut self.y);
        half.forces(&self.q, &self.qdot, &self.ua, &self.ud, &mut self.fe, &mut self.xe);
        if plan.kicks.has_set_valued() {
            half.set_valued_forces((&self.q, &self.qdot), (&self.ua, &self.ud), &self.jb, &mut self.fe);
        }
        // a local lane array per output: `y` and `fe` are separate heap arrays the compiler cannot tell
        // apart, and updating `y` in place kept it from vectorising across the lanes
        for (o, po) in self.y.iter_mut().zip(&plan.outputs) {
            let mut s = *o;
            for l in 0..L {
                s[l] += po.offset;
            }
            for (w, f) in po.acc.iter().zip(&self.fe) {
                for l in 0..L {
                    s[l] -= w * f[l];
                }
            }
            *o = s;
        }
    }

    /// The half kick of every element on the path's momenta (in reverse order after the linear flow).
    #[inline(always)]
    fn kick<P: Path<L>>(&mut self, plan: &NlPlan, half: &Prepared, path: &mut P, reverse: bool) {
        let (n, mech) = (plan.n_coords, path.mech());
        let (_, rest) = path.state().split_at_mut(mech + n);
        let record = (reverse && plan.kicks.has_set_valued()).then_some(&mut self.jb[..]);
        half.kick(
            &self.q,
            &mut rest[..n],
            &mut self.qdot,
            (&self.ua, &self.ud),
            reverse,
            record,
        );
    }
}

/// Drives a path through `burn` + `rec` samples of step h; `sink` gets every recorded sample's outputs
/// and element deflections (one [`Lanes`] value each). Always inlined, with the per-step work it calls, so
/// that [`Drive`] compiles all of it for the instruction set it runs on (a closure or a function that is
/// not inlined would be compiled for the baseline instruction set).
///
/// # The hot loop
/// Per step, for the L lanes at once: the outputs and element forces at the state (recorded after the
/// burn-in: the records update every lane's sums, maximum, crossings, regimes and histogram slot as
/// arrays over the lanes), the forward half kicks, the linear flow over h, the new inputs, absolute
/// coordinates and velocities, the reverse half kicks. Every quantity is a [`Lanes`] array, so each
/// operation is one vector operation over the lanes, in a lone realization's order (no fused
/// multiply-add): the bits of a lane are those of the realization run alone.
#[inline(always)]
fn drive<const L: usize, P: Path<L>>(
    plan: &NlPlan,
    path: &mut P,
    h: f64,
    burn: usize,
    rec: usize,
    sink: &mut impl Records<L>,
) {
    let half = plan.kicks.prepared(0.5 * h);
    let mut st = StepState::<L>::new(plan);
    st.refresh(plan, path, 0);
    for k in 0..burn + rec {
        if k >= burn {
            st.outputs(plan, &half, path, k);
            sink.record(&st.y, &st.xe);
        }
        if k + 1 == burn + rec {
            break;
        }
        st.kick(plan, &half, path, false);
        path.step(k);
        st.refresh(plan, path, k + 1);
        st.kick(plan, &half, path, true);
    }
}

/// [`drive`] over a run's burn-in and record as a [`vmath::Task`]: compiled for the widest instruction set
/// of the processor, whose vectors hold more lanes at once; the same operations (no fused multiply-add),
/// so the same bits on every instruction set.
struct Drive<'a, const L: usize, P, S> {
    plan: &'a NlPlan,
    path: &'a mut P,
    sink: S,
}

impl<const L: usize, P: Path<L>, S: Records<L>> vmath::Task for Drive<'_, L, P, S> {
    #[inline(always)]
    fn run(&mut self) {
        let plan = self.plan;
        drive::<L, P>(plan, self.path, plan.h, plan.n_burn, plan.n, &mut self.sink);
    }
}

/// Working memory of one thread.
pub(crate) struct NlScratch {
    inputs: Option<Scratch>,
    welch: WelchScratch,
}

impl NlScratch {
    pub(crate) fn new(plan: &NlPlan) -> NlScratch {
        NlScratch {
            inputs: match &plan.flow {
                Flow::Hold { inputs, .. } => Some(inputs.scratch()),
                Flow::Exact(_) => None,
            },
            welch: plan.welch.scratch(),
        }
    }
}

/// The stream of the Δt-halving check of realization i (independent of the realization's own stream).
fn check_stream(seed: u64, i: u64) -> Xoshiro256PlusPlus {
    stream(splitmix64(seed ^ 0x5851_f42d_4c95_7f2d), i)
}

/// Realizations `first .. first + width` of the run of `seed`, one group of [`lockstep_groups`], stepped in
/// lockstep (a lane's arithmetic is that of a lone realization, so every sample has the same bits whatever
/// the grouping): on the spectral route by [`realize_hold`], on the exact route by [`realize_exact_lanes`]
/// (a group of 1 through [`realize_exact`], the lone path). `s` is the working memory of the thread.
///
/// # Errors
/// An FFT or Welch failure.
pub(crate) fn realize_group(
    plan: &NlPlan,
    s: &mut NlScratch,
    seed: u64,
    first: u64,
    width: usize,
    keep_raw: bool,
) -> Result<Vec<NlRealization>> {
    match (&plan.flow, width) {
        (Flow::Exact(_), LANES) => realize_exact_lanes::<LANES>(plan, s, seed, first, keep_raw),
        (Flow::Exact(_), 4) => realize_exact_lanes::<4>(plan, s, seed, first, keep_raw),
        (Flow::Exact(_), 2) => realize_exact_lanes::<2>(plan, s, seed, first, keep_raw),
        (Flow::Exact(_), _) => Ok(vec![realize_exact(plan, s, seed, first, keep_raw)?]),
        (_, LANES) => realize_hold::<LANES>(plan, s, seed, first, keep_raw),
        (_, 4) => realize_hold::<4>(plan, s, seed, first, keep_raw),
        (_, 2) => realize_hold::<2>(plan, s, seed, first, keep_raw),
        _ => realize_hold::<1>(plan, s, seed, first, keep_raw),
    }
}

/// The lockstep groups (first realization, width) of `range`, in order: [`LANES`] realizations each, then
/// the remainder (fewer than [`LANES`]) in groups of 4, 2 and 1, largest first. A run's shards rarely hold a
/// multiple of [`LANES`] realizations (50 by default: 6 × 8 + 2), and a lone realization costs several
/// times a lane of a group (its steps are scalar, its per-step overhead is not shared).
pub(crate) fn lockstep_groups(range: Range<u64>) -> Vec<(u64, usize)> {
    let mut groups = Vec::with_capacity(range.clone().count().div_ceil(LANES) + 2);
    let mut a = range.start;
    for width in [LANES, 4, 2, 1] {
        while a + width as u64 <= range.end {
            groups.push((a, width));
            a += width as u64;
        }
    }
    groups
}

/// Realization i on the exact route: its noise from its stream, and the Δt-halving check for i below the
/// plan's number of checks.
fn realize_exact(plan: &NlPlan, s: &mut NlScratch, seed: u64, i: u64, keep_raw: bool) -> Result<NlRealization> {
    let Flow::Exact(f) = &plan.flow else {
        unreachable!("an exact-route plan")
    };
    let mut sink = Sink::<1>::new(plan, keep_raw);
    let normals = StreamNormals::new(&stream(seed, i));
    let mut path = exact_path(plan, f, &f.coarse, Noise::Stream(normals));
    let mut rec = Recorder {
        sink: &mut sink,
        welch: &mut s.welch,
    };
    drive::<1, _>(plan, &mut path, plan.h, plan.n_burn, plan.n, &mut rec);
    let lone = sink.close(&mut s.welch).remove(0)?;
    conclude(plan, lone, seed, i, None, Vec::new())
}

/// Realizations first..first + L on the exact route stepped in lockstep ([`ExactLanes`]), each then
/// concluded as a lone realization (its Δt-halving check included).
fn realize_exact_lanes<const L: usize>(
    plan: &NlPlan,
    s: &mut NlScratch,
    seed: u64,
    first: u64,
    keep_raw: bool,
) -> Result<Vec<NlRealization>> {
    let Flow::Exact(f) = &plan.flow else {
        unreachable!("an exact-route plan")
    };
    let mut path = exact_lanes::<L>(plan, f, &f.coarse, seed, first);
    let mut out = Vec::with_capacity(L);
    for (l, lone) in drive_lanes(plan, &mut path, &mut s.welch, keep_raw)
        .into_iter()
        .enumerate()
    {
        out.push(conclude(plan, lone?, seed, first + l as u64, None, Vec::new())?);
    }
    Ok(out)
}

/// The L realizations of `path` driven in lockstep through the burn-in and the record ([`Drive`], compiled
/// for the widest instruction set), their records closed lane by lane.
fn drive_lanes<const L: usize, P: Path<L>>(
    plan: &NlPlan,
    path: &mut P,
    welch: &mut WelchScratch,
    keep_raw: bool,
) -> Vec<Result<LoneRecords>> {
    let mut sink = Sink::<L>::new(plan, keep_raw);
    vmath::run(&mut Drive {
        plan,
        path,
        sink: Recorder {
            sink: &mut sink,
            welch: &mut *welch,
        },
    });
    sink.close(welch)
}

/// Realizations first..first + L on the spectral route: every lane's inputs synthesised from its stream,
/// the L stepped in lockstep, then each concluded as a lone realization.
fn realize_hold<const L: usize>(
    plan: &NlPlan,
    s: &mut NlScratch,
    seed: u64,
    first: u64,
    keep_raw: bool,
) -> Result<Vec<NlRealization>> {
    let Flow::Hold { flow, inputs, rates } = &plan.flow else {
        unreachable!("a spectral-route plan")
    };
    let sc = s.inputs.as_mut().expect("a spectral plan has an input scratch");
    let smp = (0..L as u64)
        .map(|l| inputs.draw(sc, &mut stream(seed, first + l), keep_raw))
        .collect::<Result<Vec<_>>>()?;
    let mut path = hold_path::<L>(
        flow,
        &flow.coarse,
        std::array::from_fn(|l| &smp[l].u[..]),
        std::array::from_fn(|l| &smp[l].rates[..]),
        rates,
    );
    let mut out = Vec::with_capacity(L);
    let closed = drive_lanes(plan, &mut path, &mut s.welch, keep_raw);
    for ((l, lone), smp) in closed.into_iter().enumerate().zip(&smp) {
        let raw_inputs = if keep_raw {
            smp.processes.iter().map(|p| p[plan.n_burn..].to_vec()).collect()
        } else {
            Vec::new()
        };
        out.push(conclude(plan, lone?, seed, first + l as u64, Some(smp), raw_inputs)?);
    }
    Ok(out)
}

/// A realization's closed records, its Δt-halving check if i is below the plan's number of checks, and
/// its results.
fn conclude(
    plan: &NlPlan,
    sink: LoneRecords,
    seed: u64,
    i: u64,
    samples: Option<&InputSamples>,
    raw_inputs: Vec<Vec<f64>>,
) -> Result<NlRealization> {
    let halving = if (i as usize) < plan.checks {
        Some(halving_check(plan, &mut check_stream(seed, i), samples)?)
    } else {
        None
    };
    finish(plan, sink, halving, raw_inputs)
}

fn exact_path<'a>(plan: &NlPlan, f: &'a ExactFlow, step: &'a NoisyStep, mut noise: Noise<'a>) -> ExactPath<'a> {
    let mut z = vec![0.0; f.nz];
    if let Noise::Stream(normals) = &mut noise {
        f.start.initial_state(normals.rng_mut(), &mut z);
    }
    for (i, d) in plan.start_shift.iter().enumerate() {
        z[f.mech + i] += d;
    }
    ExactPath {
        flow: f,
        step,
        noise,
        w: vec![0.0; f.nz],
        next: vec![0.0; f.nz],
        z: z.into_iter().map(|v| [v]).collect(),
    }
}

/// The lockstep path of realizations first..first + L: lane l's initial state from the first nz draws of
/// its stream, z = P₀e summed as [`GaussMarkov::initial_state`](crate::simulate::GaussMarkov::initial_state)
/// sums it, and shifted as [`exact_path`] does it.
fn exact_lanes<'a, const L: usize>(
    plan: &NlPlan,
    f: &'a ExactFlow,
    step: &'a NoisyStep,
    seed: u64,
    first: u64,
) -> ExactLanes<'a, L> {
    let n = f.nz;
    let mut normals = LaneNormals::new(std::array::from_fn(|l| StreamRng::new(seed, first + l as u64)));
    let mut e = vec![[0.0; L]; n];
    normals.fill(&mut e);
    let p0 = f.start.flat_matrices()[2];
    let mut z: Vec<Lanes<L>> = (0..n)
        .map(|i| std::array::from_fn(|l| (0..n).map(|j| p0[i * n + j] * e[j][l]).sum()))
        .collect();
    for (i, d) in plan.start_shift.iter().enumerate() {
        for v in z[f.mech + i].iter_mut() {
            *v += d;
        }
    }
    ExactLanes {
        flow: f,
        step,
        normals,
        z,
        w: vec![[0.0; L]; LANE_DRAW_STEPS * n],
        used: LANE_DRAW_STEPS * n,
        next: vec![[0.0; L]; n],
    }
}

fn hold_path<'a, const L: usize>(
    f: &'a FohFlow,
    step: &'a HoldStep,
    u: [&'a [Vec<f64>]; L],
    rates: [&'a [Vec<f64>]; L],
    rate_inputs: &'a [usize],
) -> HoldPath<'a, L> {
    HoldPath {
        flow: f,
        step,
        u,
        rates,
        rate_inputs,
        x: vec![[0.0; L]; f.nx],
        next: vec![[0.0; L]; f.nx],
        u0: vec![[0.0; L]; f.m],
        u1: vec![[0.0; L]; f.m],
        held: None,
    }
}

/// (mean, σ) of every output at Δt minus those at Δt/2 on the same path (exact route: the same Brownian
/// path, the coarse noise built from the fine normals; spectral route: the same synthesised input, refined
/// to half steps by its trigonometric interpolant).
fn halving_check(
    plan: &NlPlan,
    rng: &mut Xoshiro256PlusPlus,
    samples: Option<&InputSamples>,
) -> Result<Vec<(f64, f64)>> {
    let mut coarse = records::<1>(plan);
    let mut fine = records::<1>(plan);
    let total = plan.n_burn + plan.n;
    match (&plan.flow, samples) {
        (Flow::Exact(f), _) => {
            let mut z0 = vec![0.0; f.nz];
            f.start.initial_state(rng, &mut z0);
            let mut w = vec![0.0; 2 * total * f.nz];
            fill_standard_normal(rng, &mut w);
            let mut pc = exact_path(plan, f, &f.coarse, Noise::Coarse(&w));
            pc.z.iter_mut().zip(&z0).for_each(|(a, b)| a[0] += b);
            drive::<1, _>(
                plan,
                &mut pc,
                plan.h,
                plan.n_burn,
                plan.n,
                &mut |y: &[Lanes<1>], _: &[Lanes<1>]| push_all(&mut coarse, y),
            );
            let mut pf = exact_path(plan, f, &f.fine, Noise::Fine(&w));
            pf.z.iter_mut().zip(&z0).for_each(|(a, b)| a[0] += b);
            drive::<1, _>(
                plan,
                &mut pf,
                0.5 * plan.h,
                2 * plan.n_burn,
                2 * plan.n,
                &mut |y: &[Lanes<1>], _: &[Lanes<1>]| push_all(&mut fine, y),
            );
        }
        (Flow::Hold { flow, rates, .. }, Some(smp)) => {
            let mut pc = hold_path(flow, &flow.coarse, [&smp.u[..]], [&smp.rates[..]], rates);
            drive::<1, _>(
                plan,
                &mut pc,
                plan.h,
                plan.n_burn,
                plan.n,
                &mut |y: &[Lanes<1>], _: &[Lanes<1>]| push_all(&mut coarse, y),
            );
            let u2 = smp.u.iter().map(|x| refine(x)).collect::<Result<Vec<_>>>()?;
            let r2 = smp.rates.iter().map(|x| refine(x)).collect::<Result<Vec<_>>>()?;
            let mut pf = hold_path(flow, &flow.fine, [&u2[..]], [&r2[..]], rates);
            drive::<1, _>(
                plan,
                &mut pf,
                0.5 * plan.h,
                2 * plan.n_burn,
                2 * plan.n,
                &mut |y: &[Lanes<1>], _: &[Lanes<1>]| push_all(&mut fine, y),
            );
        }
        (Flow::Hold { .. }, None) => unreachable!("a spectral realization has its samples"),
    }
    Ok(coarse
        .iter()
        .zip(&fine)
        .map(|(c, f)| {
            let ((mc, sc), (mf, sf)) = (c.lane(0).mean_sigma(), f.lane(0).mean_sigma());
            (mc - mf, sc - sf)
        })
        .collect())
}

fn push_all(r: &mut [OutputRecords<1>], y: &[Lanes<1>]) {
    for (rec, v) in r.iter_mut().zip(y) {
        rec.push(v);
    }
}

fn finish(
    plan: &NlPlan,
    sink: LoneRecords,
    halving: Option<Vec<(f64, f64)>>,
    raw_inputs: Vec<Vec<f64>>,
) -> Result<NlRealization> {
    let t = plan.duration();
    let mut out = NlRealization {
        m: Vec::new(),
        v: Vec::new(),
        welch: sink.welch,
        values: Vec::new(),
        hist: Vec::new(),
        raw: sink.raw.unwrap_or_default(),
        raw_inputs,
    };
    for (r, (rec, po)) in sink.records.iter().zip(&plan.outputs).enumerate() {
        let (m, v) = rec.moments();
        out.m.push(m);
        out.v.push(v);
        let mut vals = rec.values(t);
        for &e in &po.regimes {
            let (f, rate) = sink.regimes[e].values(t);
            vals.push(f);
            vals.push(rate);
        }
        let (dm, ds) = halving.as_ref().map_or((f64::NAN, f64::NAN), |h| h[r]);
        vals.push(dm);
        vals.push(ds);
        out.values.push(vals);
        out.hist.push(rec.hist.clone());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::{lockstep_groups, LANES};

    /// The groups cover the range once, in order, [`LANES`] wide while [`LANES`] realizations remain, then
    /// the remainder as its binary digits (4, 2, 1), largest first.
    #[test]
    fn lockstep_groups_cover_the_range_in_order() {
        for (start, len) in [(0u64, 0u64), (0, 1), (3, 7), (50, 50), (100, 64), (7, 15), (0, 23)] {
            let groups = lockstep_groups(start..start + len);
            let mut next = start;
            for &(a, w) in &groups {
                assert_eq!(a, next, "{start}+{len}: {groups:?}");
                next += w as u64;
            }
            assert_eq!(next, start + len, "{start}+{len}: {groups:?}");
            let full = (len / LANES as u64) as usize;
            let rest = (len % LANES as u64) as usize;
            assert!(groups[..full].iter().all(|g| g.1 == LANES), "{groups:?}");
            let tail: Vec<usize> = groups[full..].iter().map(|g| g.1).collect();
            let want: Vec<usize> = [4, 2, 1].into_iter().filter(|w| rest & w != 0).collect();
            assert_eq!(tail, want, "{start}+{len}");
        }
    }
}
