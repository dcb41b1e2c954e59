//! The Monte Carlo engine of the transient route: realizations of a time-varying system stepped on a fixed
//! grid with the exact transition of its frozen coefficients, all realizations of a shard advanced block
//! by block (the step table of a block is computed once for all of them).

use super::system::{Frozen, Start, TimeVaryingSystem};
use crate::error::{Error, Result};
use crate::linalg::vmath;
use crate::simulate::lane_normals::{LaneNormals, StreamRng};
use crate::simulate::{covariance_factor, van_loan};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use std::sync::Arc;

/// Steps per block of the step table (memory O(block · n²) whatever the duration).
const BLOCK_STEPS: usize = 1024;

/// Grids of at most this many steps keep every step's tables for all shards (≈ 50 values a step for the
/// quarter car: 26 MB at 2¹⁶ steps).
const CACHED_STEPS: usize = 1 << 16;

/// Realizations stepped in lockstep (one AVX-512 register of f64).
const LANES: usize = 8;

/// Steps whose normals are drawn at once, before they are stepped (n·L·64 values: 16 KiB for 4 states).
const DRAW_STEPS: usize = 64;

/// The time grid of a Monte Carlo run: N steps of Δt, every k-th point stored.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct McGrid {
    /// Integration step Δt, s.
    pub dt: f64,
    /// Steps N (the duration is NΔt).
    pub n_steps: usize,
    /// Every `store_every`-th grid point is a stored time (t = 0 is the first).
    pub store_every: usize,
}

/// What a [`McGrid`] is built from: a duration in steps of Δt, every `store_every`-th point stored.
///
/// # Examples
/// ```
/// use stochvib::transient::McGridSpec;
/// let grid = McGridSpec { duration_s: 2.5, dt_s: 0.01, store_every: 5 }.build().unwrap();
/// assert_eq!((grid.n_steps, grid.n_stored()), (250, 51));
/// assert!(McGridSpec { duration_s: 2.5, dt_s: 0.01, store_every: 3 }.build().is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct McGridSpec {
    /// Duration of the run, s.
    pub duration_s: f64,
    /// Integration step Δt, s.
    pub dt_s: f64,
    /// Every `store_every`-th grid point is a stored time (t = 0 is the first).
    pub store_every: usize,
}

impl McGridSpec {
    /// The grid of `duration_s` in steps of `dt_s`, storing every `store_every`-th point.
    ///
    /// # Errors
    /// Non-positive or non-finite values (named `duration`, `dt`, `store_every`); a duration that is not a
    /// whole number of stored intervals (within 10⁻⁹ relative).
    pub fn build(self) -> Result<McGrid> {
        let McGridSpec {
            duration_s: duration,
            dt_s: dt,
            store_every,
        } = self;
        for (name, v) in [("duration", duration), ("dt", dt)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(name, v, "must be finite and > 0"));
            }
        }
        if store_every == 0 {
            return Err(Error::invalid("store_every", 0, "must be >= 1"));
        }
        let span = dt * store_every as f64;
        let k = (duration / span).round();
        if k < 1.0 || (k * span - duration).abs() > 1e-9 * duration {
            return Err(Error::invalid(
                "duration",
                duration,
                format!("must be a whole number of stored intervals of {span} s (dt = {dt} s × {store_every})"),
            ));
        }
        Ok(McGrid {
            dt,
            n_steps: k as usize * store_every,
            store_every,
        })
    }
}

impl McGrid {
    /// Number of stored times (t = 0 included).
    pub fn n_stored(&self) -> usize {
        self.n_steps / self.store_every + 1
    }

    /// The stored times k·(store_every·Δt).
    pub fn stored_times(&self) -> Vec<f64> {
        (0..self.n_stored())
            .map(|k| (k * self.store_every) as f64 * self.dt)
            .collect()
    }
}

/// One step's exact transition z ← Φz + Γ + Lε (row-major flat matrices; L L ᵀ = Q_d, a Cholesky or an
/// eigen factor, full).
#[derive(Debug, Clone, PartialEq)]
struct StepDisc {
    phi: Vec<f64>,
    l: Vec<f64>,
    gamma: Vec<f64>,
}

/// The selected outputs at a grid point: y = Hz + y₀ (H row-major).
#[derive(Debug, Clone, PartialEq)]
struct OutputMap {
    h: Vec<f64>,
    y0: Vec<f64>,
}

fn flat(m: &DMatrix<f64>) -> Vec<f64> {
    (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| m[(i, j)]))
        .collect()
}

/// The exact transition of a step of `dt` with the coefficients `fr` (Van Loan; the mean step; a factor of
/// the noise covariance).
fn step_disc(fr: &Frozen, dt: f64) -> Result<StepDisc> {
    let tr = van_loan(&fr.f, &fr.g, dt)?;
    let gamma = super::lyapunov_ode::mean_step(fr, dt)?;
    Ok(StepDisc {
        phi: flat(&tr.phi),
        l: flat(&covariance_factor(&tr.qd)?),
        gamma: gamma.iter().copied().collect(),
    })
}

/// The step transitions and output maps of a block (equal neighbours shared).
type BlockTables = (Vec<Arc<StepDisc>>, Vec<Arc<OutputMap>>);

/// What every realization of a run shares: the system, the selected outputs, the start and the grid.
pub struct McPlan<'a> {
    sys: &'a TimeVaryingSystem,
    outputs: Vec<usize>,
    grid: McGrid,
    m0: DVector<f64>,
    l0: Vec<f64>,
    n: usize,
    /// The tables of every block, computed once for all shards when the grid has at most
    /// [`CACHED_STEPS`] steps (else each shard computes each block's tables again, in O(block) memory).
    tables: Option<Vec<BlockTables>>,
}

/// The per-realization results of a block of a shard.
pub(crate) struct ShardBlock {
    /// The stored outputs, one row of `width` values per realization (row-major): row r holds
    /// realization r's value at stored time s of the block and output o at s·p + o.
    pub stored: Vec<f64>,
    /// Values per realization: the block's stored times × the outputs.
    pub width: usize,
    /// The global index of the block's first stored time.
    pub first_stored: usize,
}

/// One realization's running state.
pub(crate) struct RealizationState {
    z: Vec<f64>,
    rng: StreamRng,
    /// max y per output.
    pub max_y: Vec<f64>,
    /// max |y| per output.
    pub max_abs: Vec<f64>,
}

impl<'a> McPlan<'a> {
    /// The plan of `sys`'s outputs `outputs` started as `start` on `grid`.
    ///
    /// # Errors
    /// An output without a finite variance; the start's errors; a covariance that is not one; the step
    /// tables' errors (a transition or noise covariance that cannot be computed).
    pub fn new(sys: &'a TimeVaryingSystem, outputs: Vec<usize>, start: &Start, grid: McGrid) -> Result<Self> {
        if let Some(&i) = outputs
            .iter()
            .find(|&&i| i >= sys.outputs().len() || sys.unavailable(i).is_some())
        {
            return Err(Error::invalid(
                "output",
                i,
                sys.unavailable(i).unwrap_or("no such output").to_string(),
            ));
        }
        let (p0, m0) = sys.start(start)?;
        let l0 = flat(&covariance_factor(&p0)?);
        let mut plan = McPlan {
            sys,
            outputs,
            grid,
            m0,
            l0,
            n: sys.n_states(),
            tables: None,
        };
        if grid.n_steps <= CACHED_STEPS {
            let all = plan.blocks().into_iter().map(|(j0, j1)| plan.block_tables(j0, j1));
            plan.tables = Some(all.collect::<Result<_>>()?);
        }
        Ok(plan)
    }

    /// The grid.
    pub fn grid(&self) -> &McGrid {
        &self.grid
    }

    /// The selected outputs.
    pub fn outputs(&self) -> &[usize] {
        &self.outputs
    }

    /// The output map at grid time t.
    fn output_map(&self, fr: &Frozen) -> OutputMap {
        let rows: Vec<usize> = self.outputs.clone();
        let h = DMatrix::from_fn(rows.len(), self.n, |i, j| fr.h[(rows[i], j)]);
        OutputMap {
            h: flat(&h),
            y0: rows.iter().map(|&i| fr.y0[i]).collect(),
        }
    }

    /// The transitions of steps `j0..j1` and the output maps of points `j0..=j1`, equal neighbours shared
    /// (the frozen coefficients and each distinct transition computed in parallel).
    fn block_tables(&self, j0: usize, j1: usize) -> Result<BlockTables> {
        let dt = self.grid.dt;
        // the coefficients at (j + offset)Δt (j + 0 is j exactly)
        let frozen = |offset: f64, js: std::ops::Range<usize>| -> Result<Vec<Frozen>> {
            js.into_par_iter()
                .map(|j| self.sys.frozen((j as f64 + offset) * dt))
                .collect()
        };
        let mid = frozen(0.5, j0..j1)?;
        // a step starts a run of equal coefficients, whose steps share its transition
        let starts = |m: usize| m == 0 || mid[m] != mid[m - 1];
        let distinct: Vec<&Frozen> = (0..mid.len()).filter(|&m| starts(m)).map(|m| &mid[m]).collect();
        let discs: Vec<StepDisc> = distinct.par_iter().map(|fr| step_disc(fr, dt)).collect::<Result<_>>()?;
        let mut discs = discs.into_iter().map(Arc::new);
        let mut steps: Vec<Arc<StepDisc>> = Vec::with_capacity(mid.len());
        for m in 0..mid.len() {
            let d = if starts(m) { discs.next() } else { steps.last().cloned() };
            steps.extend(d);
        }
        let mut maps: Vec<Arc<OutputMap>> = Vec::with_capacity(j1 - j0 + 1);
        for fr in frozen(0.0, j0..j1 + 1)? {
            let m = self.output_map(&fr);
            match maps.last() {
                Some(prev) if **prev == m => maps.push(prev.clone()),
                _ => maps.push(Arc::new(m)),
            }
        }
        Ok((steps, maps))
    }

    /// Realization i's initial state z₀ = m₀ + L₀ε (n normals drawn first from its stream (seed, i)).
    pub(crate) fn initial(&self, seed: u64, i: u64) -> RealizationState {
        let n = self.n;
        let mut s = RealizationState {
            z: vec![0.0; n],
            rng: StreamRng::new(seed, i),
            max_y: vec![f64::NEG_INFINITY; self.outputs.len()],
            max_abs: vec![0.0; self.outputs.len()],
        };
        let eps: Vec<f64> = (0..n).map(|_| s.rng.normal()).collect();
        for r in 0..n {
            s.z[r] = self.m0[r] + (0..n).map(|c| self.l0[r * n + c] * eps[c]).sum::<f64>();
        }
        s
    }

    /// Advances every realization of `states` over steps `j0..j1` (the point j0 already observed), and
    /// returns the outputs at the stored points of (j0, j1] (and at j0 = 0 itself).
    ///
    /// The realizations go [`LANES`] at a time in lockstep ([`Lockstep`]), the rest one at a time: a
    /// lane's arithmetic and its order are those of a lone realization, so the bits do not depend on the
    /// grouping (`tests::lockstep_gives_the_bits_of_one_realization_at_a_time`).
    pub(crate) fn advance(&self, states: &mut [RealizationState], j0: usize, j1: usize) -> Result<ShardBlock> {
        let computed;
        let (steps, maps) = match &self.tables {
            Some(t) => &t[j0 / BLOCK_STEPS],
            None => {
                computed = self.block_tables(j0, j1)?;
                &computed
            }
        };
        let k = self.grid.store_every;
        let first_stored = if j0 == 0 { 0 } else { j0 / k + 1 };
        let width = (j1 / k + 1 - first_stored) * self.outputs.len();
        let block = Block {
            plan: self,
            steps,
            maps,
            j0,
            j1,
            width,
        };
        // rows of at least one value, so that every realization gets one (a block may store no time)
        let w = width.max(1);
        let mut stored = vec![0.0; states.len() * w];
        states
            .par_chunks_mut(LANES)
            .zip(stored.par_chunks_mut(LANES * w))
            .for_each(
                |(chunk, out)| match <&mut [RealizationState; LANES]>::try_from(&mut *chunk) {
                    Ok(lanes) => block.lockstep(lanes, out),
                    Err(_) => chunk
                        .iter_mut()
                        .zip(out.chunks_exact_mut(w))
                        .for_each(|(s, row)| block.lockstep(std::array::from_mut(s), row)),
                },
            );
        stored.truncate(states.len() * width);
        Ok(ShardBlock {
            stored,
            width,
            first_stored,
        })
    }

    /// The blocks of the grid: (j0, j1) pairs covering 0..N.
    pub(crate) fn blocks(&self) -> Vec<(usize, usize)> {
        let n = self.grid.n_steps;
        (0..n.div_ceil(BLOCK_STEPS))
            .map(|b| (b * BLOCK_STEPS, ((b + 1) * BLOCK_STEPS).min(n)))
            .collect()
    }
}

/// The tables of one block of steps, shared by every realization of a shard.
struct Block<'b, 'a> {
    plan: &'b McPlan<'a>,
    steps: &'b [Arc<StepDisc>],
    maps: &'b [Arc<OutputMap>],
    j0: usize,
    j1: usize,
    /// Stored values per realization in the block.
    width: usize,
}

impl Block<'_, '_> {
    /// The L realizations `lanes` advanced over the block in lockstep, their stored outputs written to
    /// `out` (L rows of the block's width).
    fn lockstep<const L: usize>(&self, lanes: &mut [RealizationState; L], out: &mut [f64]) {
        let mut task = Lockstep {
            block: self,
            lanes,
            out,
            kept: 0,
        };
        vmath::run(&mut task);
    }
}

/// L realizations advanced over a block: each state variable, noise value and output one `[f64; L]` (one
/// lane per realization), compiled for the widest instruction set by [`vmath::run`]. Every lane draws its
/// normals from its own stream in the order of a lone realization (n per step), all lanes at once
/// ([`LaneNormals`]: the bits of `rand_distr`'s `StandardNormal`).
struct Lockstep<'t, 'b, 'a, const L: usize> {
    block: &'t Block<'b, 'a>,
    lanes: &'t mut [RealizationState; L],
    /// L rows of the block's width.
    out: &'t mut [f64],
    /// Values kept so far in each row.
    kept: usize,
}

impl<const L: usize> vmath::Task for Lockstep<'_, '_, '_, L> {
    #[inline(always)]
    fn run(&mut self) {
        // the state in a fixed-size array for the common sizes (the loops over it unrolled, its values in
        // registers), else in a vector; the same arithmetic in the same order either way
        let zero = [0.0; L];
        match self.block.plan.n {
            2 => self.run_with([zero; 2], [zero; 2]),
            3 => self.run_with([zero; 3], [zero; 3]),
            4 => self.run_with([zero; 4], [zero; 4]),
            5 => self.run_with([zero; 5], [zero; 5]),
            6 => self.run_with([zero; 6], [zero; 6]),
            7 => self.run_with([zero; 7], [zero; 7]),
            8 => self.run_with([zero; 8], [zero; 8]),
            n => self.run_with(vec![zero; n], vec![zero; n]),
        }
    }
}

impl<const L: usize> Lockstep<'_, '_, '_, L> {
    /// The block stepped with the state held in `z` and `tmp` (n states each, zeros).
    #[inline(always)]
    fn run_with<S: AsRef<[[f64; L]]> + AsMut<[[f64; L]]>>(&mut self, mut z: S, mut tmp: S) {
        let b = self.block;
        let (n, p, k) = (b.plan.n, b.plan.outputs.len(), b.plan.grid.store_every);
        for (c, zc) in z.as_mut().iter_mut().enumerate() {
            *zc = std::array::from_fn(|l| self.lanes[l].z[c]);
        }
        let mut y = vec![[0.0; L]; p];
        let mut max_y: Vec<[f64; L]> = (0..p)
            .map(|o| std::array::from_fn(|l| self.lanes[l].max_y[o]))
            .collect();
        let mut max_abs: Vec<[f64; L]> = (0..p)
            .map(|o| std::array::from_fn(|l| self.lanes[l].max_abs[o]))
            .collect();
        let mut eps = vec![[0.0; L]; DRAW_STEPS * n];
        let mut normals = LaneNormals::new(std::array::from_fn(|l| self.lanes[l].rng));
        if b.j0 == 0 {
            observe(&b.maps[0], z.as_ref(), &mut y, &mut max_y, &mut max_abs);
            self.keep(&y);
        }
        for j0 in (b.j0..b.j1).step_by(DRAW_STEPS) {
            let eps = &mut eps[..(b.j1 - j0).min(DRAW_STEPS) * n];
            normals.fill(eps);
            for (j, eps) in (j0..).zip(eps.chunks_exact(n)) {
                step(&b.steps[j - b.j0], z.as_ref(), eps, tmp.as_mut());
                std::mem::swap(&mut z, &mut tmp);
                observe(&b.maps[j + 1 - b.j0], z.as_ref(), &mut y, &mut max_y, &mut max_abs);
                if (j + 1) % k == 0 {
                    self.keep(&y);
                }
            }
        }
        for (l, s) in self.lanes.iter_mut().enumerate() {
            s.rng = normals.stream(l);
            s.z.iter_mut().zip(z.as_ref()).for_each(|(v, zc)| *v = zc[l]);
            s.max_y.iter_mut().zip(&max_y).for_each(|(v, m)| *v = m[l]);
            s.max_abs.iter_mut().zip(&max_abs).for_each(|(v, m)| *v = m[l]);
        }
    }

    /// Writes every lane's outputs `y` after its stored values so far.
    #[inline(always)]
    fn keep(&mut self, y: &[[f64; L]]) {
        let (w, at) = (self.block.width, self.kept);
        for (l, row) in self.out.chunks_exact_mut(w).enumerate() {
            row[at..at + y.len()].iter_mut().zip(y).for_each(|(v, yo)| *v = yo[l]);
        }
        self.kept += y.len();
    }
}

/// One step of every lane: z' = Φz + Γ + Lε (per lane: Γ_r, then the Φ terms, then the L terms, in column
/// order).
#[inline(always)]
fn step<const L: usize>(d: &StepDisc, z: &[[f64; L]], eps: &[[f64; L]], out: &mut [[f64; L]]) {
    let n = z.len();
    for (r, o) in out.iter_mut().enumerate() {
        // a local accumulator (registers, one vector), stored once
        let mut acc = [d.gamma[r]; L];
        for (a, zc) in d.phi[r * n..][..n].iter().zip(z) {
            (0..L).for_each(|l| acc[l] += a * zc[l]);
        }
        for (a, ec) in d.l[r * n..][..n].iter().zip(eps) {
            (0..L).for_each(|l| acc[l] += a * ec[l]);
        }
        *o = acc;
    }
}

/// Every lane's outputs y = y₀ + Σ_c h_c z_c (the sum from −0.0 in column order, as `Iterator::sum`), and
/// the running max y and max |y| updated.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // lanes: several arrays indexed by the lane
fn observe<const L: usize>(
    m: &OutputMap,
    z: &[[f64; L]],
    y: &mut [[f64; L]],
    max_y: &mut [[f64; L]],
    max_abs: &mut [[f64; L]],
) {
    let n = z.len();
    for (o, yo) in y.iter_mut().enumerate() {
        let mut sum = [-0.0; L];
        for (h, zc) in m.h[o * n..][..n].iter().zip(z) {
            (0..L).for_each(|l| sum[l] += h * zc[l]);
        }
        let (mut v, mut hi, mut hi_abs) = (*yo, max_y[o], max_abs[o]);
        for l in 0..L {
            v[l] = m.y0[o] + sum[l];
            hi[l] = hi[l].max(v[l]);
            hi_abs[l] = hi_abs[l].max(v[l].abs());
        }
        (*yo, max_y[o], max_abs[o]) = (v, hi, hi_abs);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::{IsoBound, IsoClass, PowerLaw};
    use crate::system::{Attach, Element, FrequencyResponse, Mdof, Quantity};
    use crate::transient::schedule::FixedSystem;
    use crate::transient::{input_model, ConstantAcceleration, Envelope, TransientInput};

    /// The quarter car accelerating from 5 to 15 m/s on a w = 2 road (every step's table differs).
    fn accelerating_car() -> TimeVaryingSystem {
        // the catalogue quarter car's equations, built on the system layer (models sit above transient)
        let element = |name: &str, point: Vec<f64>, to: Attach, stiffness: f64, damping: f64| Element {
            name: name.into(),
            point,
            to,
            stiffness,
            damping,
        };
        let els = vec![
            element("suspension", vec![1.0, 0.0], Attach::Point(vec![0.0, 1.0]), 20e3, 1.5e3),
            element("tyre", vec![0.0, 1.0], Attach::Base(0), 200e3, 0.0),
        ];
        let mdof = Mdof::from_elements(&[("body", "m"), ("wheel", "m")], &[400.0, 40.0], els, 1, &[])
            .unwrap()
            .with_output("body_acc", Quantity::Acceleration(vec![1.0, 0.0]))
            .unwrap()
            .with_output("travel", Quantity::Deflection(0))
            .unwrap();
        let road = PowerLaw::iso8608(IsoClass::D, IsoBound::GeometricMean, None).unwrap();
        let v = ConstantAcceleration {
            from_m_s: 5.0,
            to_m_s: 15.0,
            acceleration_m_s2: 1.0,
            start_s: 0.0,
        }
        .build()
        .unwrap();
        let ss = mdof.state_space().unwrap().clone();
        let gains = vec![1.0; ss.b.ncols()];
        let input = TransientInput {
            model: input_model(&road, Some(&v)).unwrap(),
            envelope: Envelope::unit(),
            mean: 0.0,
            gains,
        };
        TimeVaryingSystem::new(Arc::new(FixedSystem::new(ss, None, "test").unwrap()), input).unwrap()
    }

    /// The oracle: one realization stepped alone with scalar loops (the engine's arithmetic before the
    /// lanes), its stored outputs at every stored time and its maxima.
    fn alone(plan: &McPlan, (steps, maps): &BlockTables, seed: u64, i: u64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let (n, g) = (plan.n, plan.grid);
        let mut s = plan.initial(seed, i);
        let mut eps = vec![0.0; n];
        let mut stored = Vec::new();
        for j in 0..=g.n_steps {
            if j > 0 {
                let d = &steps[j - 1];
                eps.iter_mut().for_each(|e| *e = s.rng.normal());
                s.z = (0..n)
                    .map(|r| {
                        let mut acc = d.gamma[r];
                        (0..n).for_each(|c| acc += d.phi[r * n + c] * s.z[c]);
                        (0..n).for_each(|c| acc += d.l[r * n + c] * eps[c]);
                        acc
                    })
                    .collect();
            }
            let m = &maps[j];
            for o in 0..plan.outputs.len() {
                let x = m.y0[o] + (0..n).map(|c| m.h[o * n + c] * s.z[c]).sum::<f64>();
                s.max_y[o] = s.max_y[o].max(x);
                s.max_abs[o] = s.max_abs[o].max(x.abs());
                if j % g.store_every == 0 {
                    stored.push(x);
                }
            }
        }
        (stored, s.max_y, s.max_abs)
    }

    /// 11 realizations (one group of 8 lanes, three alone) over three blocks of the step table (the last
    /// one short) and several draw-ahead spans: every stored output and maximum has the bits of the
    /// realization stepped alone.
    #[test]
    fn lockstep_gives_the_bits_of_one_realization_at_a_time() {
        let sys = accelerating_car();
        let index = |name: &str| sys.outputs().iter().position(|o| o.name == name).unwrap();
        let outputs = vec![index("body_acc"), index("travel")];
        let grid = McGridSpec {
            duration_s: 2.25,
            dt_s: 1e-3,
            store_every: 5,
        }
        .build()
        .unwrap(); // 2250 steps: blocks of 1024, 1024 and 202
        let plan = McPlan::new(&sys, outputs, &Start::Stationary, grid).unwrap();
        let (seed, r) = (7, 11);
        let mut states: Vec<RealizationState> = (0..r).map(|i| plan.initial(seed, i)).collect();
        let mut stored = vec![Vec::new(); r as usize];
        for (j0, j1) in plan.blocks() {
            let b = plan.advance(&mut states, j0, j1).unwrap();
            let rows = b.stored.chunks_exact(b.width);
            stored.iter_mut().zip(rows).for_each(|(s, v)| s.extend_from_slice(v));
        }
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let tables = plan.block_tables(0, grid.n_steps).unwrap();
        for (i, (s, st)) in stored.iter().zip(&states).enumerate() {
            let (want, max_y, max_abs) = alone(&plan, &tables, seed, i as u64);
            assert_eq!(s.len(), grid.n_stored() * 2);
            assert_eq!(bits(s), bits(&want), "realization {i}");
            assert_eq!(bits(&st.max_y), bits(&max_y), "realization {i}");
            assert_eq!(bits(&st.max_abs), bits(&max_abs), "realization {i}");
        }
    }
}
