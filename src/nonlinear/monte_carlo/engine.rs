//! One realization of route 2: the splitting integrator driven through burn-in and record, its samples fed
//! to the records of every output; and the Δt-halving check of a realization.

use super::flow::{ExactFlow, FohFlow, HoldStep, NoisyStep};
use super::inputs::{refine, InputSamples};
use super::plan::{Flow, NlPlan};
use super::record::{OutputRecord, RegimeRecord};
use crate::error::Result;
use crate::estimate::{WelchScratch, WelchSums};
use crate::nonlinear::integrator::Prepared;
use crate::simulate::{standard_normal, Scratch};
use rand::rngs::Xoshiro256PlusPlus;

/// Samples per block fed to the Welch estimate.
const BLOCK: usize = 4096;

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

/// A path of the linear flow: how to read the inputs and outputs from its state and advance it.
trait Path {
    fn state(&mut self) -> &mut [f64];
    fn mech(&self) -> usize;
    /// ũ of every input (base, then force; 0 where not needed) and u̇ of the base inputs at sample k.
    fn inputs(&self, k: usize, u: &mut [f64], ud: &mut [f64]);
    /// The linear part of every output at sample k.
    fn outputs(&self, k: usize, u: &[f64], ud: &[f64], y: &mut [f64]);
    /// Advances the state from sample k to k + 1.
    fn step(&mut self, k: usize);
}

/// Where the exact flow's noise comes from.
enum Noise<'a> {
    /// Fresh normals from the realization's stream (the draws of a linear run).
    Stream(&'a mut Xoshiro256PlusPlus),
    /// Stored normals, one vector of nz per fine step.
    Fine(&'a [f64]),
    /// The coarse steps of stored fine normals (η = Φ_f L_f w₁ + L_f w₂).
    Coarse(&'a [f64]),
}

struct ExactPath<'a> {
    flow: &'a ExactFlow,
    step: &'a NoisyStep,
    noise: Noise<'a>,
    z: Vec<f64>,
    w: Vec<f64>,
    next: Vec<f64>,
}

impl Path for ExactPath<'_> {
    fn state(&mut self) -> &mut [f64] {
        &mut self.z
    }
    fn mech(&self) -> usize {
        self.flow.mech
    }
    fn inputs(&self, _k: usize, u: &mut [f64], ud: &mut [f64]) {
        let dot = |r: &[f64]| r.iter().zip(&self.z).map(|(a, b)| a * b).sum::<f64>();
        for (j, row) in self.flow.u_rows.iter().enumerate() {
            u[j] = dot(row);
            ud[j] = self.flow.ud_rows[j].as_deref().map_or(0.0, dot);
        }
    }
    fn outputs(&self, _k: usize, _u: &[f64], _ud: &[f64], y: &mut [f64]) {
        for (o, row) in y.iter_mut().zip(&self.flow.out_rows) {
            let mut s = 0.0;
            for (a, b) in row.iter().zip(&self.z) {
                s += a * b;
            }
            *o = s;
        }
    }
    fn step(&mut self, k: usize) {
        let n = self.flow.nz;
        match &mut self.noise {
            Noise::Stream(rng) => self.flow.step(self.step, &mut self.z, &mut self.w, &mut self.next, rng),
            Noise::Fine(w) => self
                .flow
                .step_with(self.step, &mut self.z, &w[k * n..(k + 1) * n], &mut self.next),
            Noise::Coarse(w) => {
                let (w1, w2) = (&w[2 * k * n..(2 * k + 1) * n], &w[(2 * k + 1) * n..(2 * k + 2) * n]);
                self.flow.coupled_noise(w1, w2, &mut self.w);
                self.flow.step_noise(self.step, &mut self.z, &self.w, &mut self.next);
            }
        }
    }
}

struct HoldPath<'a> {
    flow: &'a FohFlow,
    step: &'a HoldStep,
    u: &'a [Vec<f64>],
    rates: &'a [Vec<f64>],
    rate_inputs: &'a [usize],
    x: Vec<f64>,
    next: Vec<f64>,
    u0: Vec<f64>,
    u1: Vec<f64>,
}

impl Path for HoldPath<'_> {
    fn state(&mut self) -> &mut [f64] {
        &mut self.x
    }
    fn mech(&self) -> usize {
        0
    }
    fn inputs(&self, k: usize, u: &mut [f64], ud: &mut [f64]) {
        for (j, s) in self.u.iter().enumerate() {
            u[j] = s[k];
        }
        ud.iter_mut().for_each(|v| *v = 0.0);
        for (r, &j) in self.rate_inputs.iter().enumerate() {
            ud[j] = self.rates[r][k];
        }
    }
    fn outputs(&self, _k: usize, u: &[f64], ud: &[f64], y: &mut [f64]) {
        let f = self.flow;
        for (r, o) in y.iter_mut().enumerate() {
            let mut s = 0.0;
            for (a, b) in f.c_rows[r].iter().zip(&self.x) {
                s += a * b;
            }
            for j in 0..f.m {
                s += f.d_rows[r][j] * u[j] + f.e_rows[r][j] * ud[j];
            }
            *o = s;
        }
    }
    fn step(&mut self, k: usize) {
        for (j, s) in self.u.iter().enumerate() {
            self.u0[j] = s[k];
            self.u1[j] = s[k + 1];
        }
        self.flow
            .step(self.step, &mut self.x, &self.u0, &self.u1, &mut self.next);
    }
}

/// Drives a path through `burn` + `rec` samples of step h; `sink(y, x)` gets every recorded sample's outputs
/// and element deflections.
fn drive<P: Path>(plan: &NlPlan, path: &mut P, h: f64, burn: usize, rec: usize, mut sink: impl FnMut(&[f64], &[f64])) {
    let (n, nb, ne) = (plan.n_coords, plan.n_base, plan.kicks.len());
    let half = plan.kicks.prepared(0.5 * h);
    let m = plan.u_mean.len();
    let mut ut = vec![0.0; m];
    let mut ud = vec![0.0; nb.max(1)];
    let mut ua = vec![0.0; nb.max(1)];
    let mut q = vec![0.0; n];
    let mut qdot = vec![0.0; n];
    let mut y = vec![0.0; plan.outputs.len()];
    let mut xe = vec![0.0; ne];
    let mut fe = vec![0.0; ne];
    let mech = path.mech();
    let refresh =
        |path: &mut P, k: usize, ut: &mut [f64], ud: &mut [f64], ua: &mut [f64], q: &mut [f64], qdot: &mut [f64]| {
            path.inputs(k, ut, ud);
            for j in 0..nb {
                ua[j] = plan.u_mean[j] + ut[j];
            }
            let st = path.state();
            for i in 0..n {
                q[i] = plan.q_eq[i] + st[mech + i];
            }
            plan.kicks.velocities(&st[mech + n..mech + 2 * n], ut, qdot);
        };
    refresh(path, 0, &mut ut, &mut ud, &mut ua, &mut q, &mut qdot);
    for k in 0..burn + rec {
        if k >= burn {
            path.outputs(k, &ut, &ud, &mut y);
            half.forces(&q, &qdot, &ua, &ud, &mut fe, &mut xe);
            for (o, po) in y.iter_mut().zip(&plan.outputs) {
                *o += po.offset;
                for (w, f) in po.acc.iter().zip(&fe) {
                    *o -= w * f;
                }
            }
            sink(&y, &xe);
        }
        if k + 1 == burn + rec {
            break;
        }
        let st = path.state();
        let (_, rest) = st.split_at_mut(mech + n);
        half.kick(&q, &mut rest[..n], &mut qdot, &ua, &ud, false);
        path.step(k);
        refresh(path, k + 1, &mut ut, &mut ud, &mut ua, &mut q, &mut qdot);
        let st = path.state();
        let (_, rest) = st.split_at_mut(mech + n);
        half.kick(&q, &mut rest[..n], &mut qdot, &ua, &ud, true);
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

/// The records of one realization.
struct Sink<'a> {
    plan: &'a NlPlan,
    /// The element laws (for their regimes).
    regime: Prepared<'a>,
    records: Vec<OutputRecord>,
    regimes: Vec<RegimeRecord>,
    block: Vec<Vec<f64>>,
    filled: usize,
    streams: Vec<crate::estimate::WelchStream>,
    welch: Vec<WelchSums>,
    raw: Option<Vec<Vec<f64>>>,
    err: Option<crate::Error>,
}

fn records(plan: &NlPlan) -> Vec<OutputRecord> {
    plan.outputs
        .iter()
        .map(|o| {
            OutputRecord::new(
                o.centre,
                &o.levels,
                o.hist_lo,
                o.hist_width,
                super::plan::HISTOGRAM_BINS,
            )
        })
        .collect()
}

impl<'a> Sink<'a> {
    fn new(plan: &'a NlPlan, keep_raw: bool) -> Self {
        let p = plan.outputs.len();
        Sink {
            plan,
            regime: plan.kicks.prepared(0.5 * plan.h),
            records: records(plan),
            regimes: vec![RegimeRecord::default(); plan.kicks.len()],
            block: vec![vec![0.0; BLOCK]; p],
            filled: 0,
            streams: (0..p).map(|_| plan.welch.stream()).collect(),
            welch: (0..p).map(|_| plan.welch.sums()).collect(),
            raw: keep_raw.then(|| vec![Vec::with_capacity(plan.n); p]),
            err: None,
        }
    }

    fn push(&mut self, y: &[f64], x: &[f64], scratch: &mut WelchScratch) {
        for (r, &v) in y.iter().enumerate() {
            self.block[r][self.filled] = self.records[r].push(v);
            if let Some(raw) = &mut self.raw {
                raw[r].push(v);
            }
        }
        for (e, rg) in self.regimes.iter_mut().enumerate() {
            rg.push(self.regime.engaged(e, x[e]));
        }
        self.filled += 1;
        if self.filled == BLOCK {
            self.flush(scratch);
        }
    }

    fn flush(&mut self, scratch: &mut WelchScratch) {
        for r in 0..self.records.len() {
            let res = self.plan.welch.push(
                &mut self.streams[r],
                &self.block[r][..self.filled],
                &mut self.welch[r],
                scratch,
            );
            if let Err(e) = res {
                self.err.get_or_insert(e);
            }
        }
        self.filled = 0;
    }
}

/// Realization i: its inputs from `rng` (spectral route) or its noise (exact route), and, for i below the
/// plan's number of checks, the Δt-halving check from the stream `check`.
///
/// # Errors
/// An FFT or Welch failure.
pub(crate) fn realize(
    plan: &NlPlan,
    s: &mut NlScratch,
    rng: &mut Xoshiro256PlusPlus,
    check: Option<&mut Xoshiro256PlusPlus>,
    keep_raw: bool,
) -> Result<NlRealization> {
    let mut sink = Sink::new(plan, keep_raw);
    let mut raw_inputs = Vec::new();
    let mut samples = None;
    match &plan.flow {
        Flow::Exact(f) => {
            let mut path = exact_path(plan, f, &f.coarse, Noise::Stream(rng));
            let ws = &mut s.welch;
            drive(plan, &mut path, plan.h, plan.n_burn, plan.n, |y, x| sink.push(y, x, ws));
        }
        Flow::Hold { flow, inputs, rates } => {
            let sc = s.inputs.as_mut().expect("a spectral plan has an input scratch");
            let smp = inputs.draw(sc, rng, keep_raw)?;
            let mut path = hold_path(flow, &flow.coarse, &smp.u, &smp.rates, rates);
            let ws = &mut s.welch;
            drive(plan, &mut path, plan.h, plan.n_burn, plan.n, |y, x| sink.push(y, x, ws));
            if keep_raw {
                raw_inputs = smp.processes.iter().map(|p| p[plan.n_burn..].to_vec()).collect();
            }
            samples = Some(smp);
        }
    }
    sink.flush(&mut s.welch);
    for (st, ws) in sink.streams.iter_mut().zip(sink.welch.iter_mut()) {
        plan.welch.end_record(st, ws)?;
    }
    if let Some(e) = sink.err {
        return Err(e);
    }
    let halving = match check {
        Some(c) => Some(halving_check(plan, c, samples.as_ref())?),
        None => None,
    };
    finish(plan, sink, halving, raw_inputs)
}

fn exact_path<'a>(plan: &NlPlan, f: &'a ExactFlow, step: &'a NoisyStep, mut noise: Noise<'a>) -> ExactPath<'a> {
    let mut z = vec![0.0; f.nz];
    if let Noise::Stream(rng) = &mut noise {
        f.start.initial_state(rng, &mut z);
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
        z,
    }
}

fn hold_path<'a>(
    f: &'a FohFlow,
    step: &'a HoldStep,
    u: &'a [Vec<f64>],
    rates: &'a [Vec<f64>],
    rate_inputs: &'a [usize],
) -> HoldPath<'a> {
    HoldPath {
        flow: f,
        step,
        u,
        rates,
        rate_inputs,
        x: vec![0.0; f.nx],
        next: vec![0.0; f.nx],
        u0: vec![0.0; f.m],
        u1: vec![0.0; f.m],
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
    let mut coarse = records(plan);
    let mut fine = records(plan);
    let total = plan.n_burn + plan.n;
    match (&plan.flow, samples) {
        (Flow::Exact(f), _) => {
            let mut z0 = vec![0.0; f.nz];
            f.start.initial_state(rng, &mut z0);
            let w: Vec<f64> = (0..2 * total * f.nz).map(|_| standard_normal(rng)).collect();
            let mut pc = exact_path(plan, f, &f.coarse, Noise::Coarse(&w));
            pc.z.iter_mut().zip(&z0).for_each(|(a, b)| *a += b);
            drive(plan, &mut pc, plan.h, plan.n_burn, plan.n, |y, _| {
                push_all(&mut coarse, y)
            });
            let mut pf = exact_path(plan, f, &f.fine, Noise::Fine(&w));
            pf.z.iter_mut().zip(&z0).for_each(|(a, b)| *a += b);
            drive(plan, &mut pf, 0.5 * plan.h, 2 * plan.n_burn, 2 * plan.n, |y, _| {
                push_all(&mut fine, y)
            });
        }
        (Flow::Hold { flow, rates, .. }, Some(smp)) => {
            let mut pc = hold_path(flow, &flow.coarse, &smp.u, &smp.rates, rates);
            drive(plan, &mut pc, plan.h, plan.n_burn, plan.n, |y, _| {
                push_all(&mut coarse, y)
            });
            let u2 = smp.u.iter().map(|x| refine(x)).collect::<Result<Vec<_>>>()?;
            let r2 = smp.rates.iter().map(|x| refine(x)).collect::<Result<Vec<_>>>()?;
            let mut pf = hold_path(flow, &flow.fine, &u2, &r2, rates);
            drive(plan, &mut pf, 0.5 * plan.h, 2 * plan.n_burn, 2 * plan.n, |y, _| {
                push_all(&mut fine, y)
            });
        }
        (Flow::Hold { .. }, None) => unreachable!("a spectral realization has its samples"),
    }
    Ok(coarse
        .iter()
        .zip(&fine)
        .map(|(c, f)| {
            let ((mc, sc), (mf, sf)) = (c.mean_sigma(), f.mean_sigma());
            (mc - mf, sc - sf)
        })
        .collect())
}

fn push_all(r: &mut [OutputRecord], y: &[f64]) {
    for (rec, &v) in r.iter_mut().zip(y) {
        rec.push(v);
    }
}

fn finish(
    plan: &NlPlan,
    sink: Sink,
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
