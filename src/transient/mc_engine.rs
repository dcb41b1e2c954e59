//! The Monte Carlo engine of the transient route: realizations of a time-varying system stepped on a fixed
//! grid with the exact transition of its frozen coefficients, all realizations of a shard advanced block
//! by block (the step table of a block is computed once for all of them).

use super::system::{Frozen, Start, TimeVaryingSystem};
use crate::error::{Error, Result};
use crate::simulate::{covariance_factor, fill_standard_normal, stream, van_loan};
use nalgebra::{DMatrix, DVector};
use rand::rngs::Xoshiro256PlusPlus;
use rayon::prelude::*;
use std::sync::Arc;

/// Steps per block of the step table (memory O(block · n²) whatever the duration).
const BLOCK_STEPS: usize = 1024;

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

impl McGrid {
    /// The grid of `duration` in steps of `dt`, storing every `store_every`-th point.
    ///
    /// # Errors
    /// Non-positive or non-finite values; a duration that is not a whole number of stored intervals
    /// (within 10⁻⁹ relative).
    pub fn new(duration: f64, dt: f64, store_every: usize) -> Result<Self> {
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
}

/// The per-realization results of a block of a shard.
pub(crate) struct ShardBlock {
    /// stored\[r\]\[s·p + o\]: realization r, stored time s of the block, output o.
    pub stored: Vec<Vec<f64>>,
    /// The global index of the block's first stored time.
    pub first_stored: usize,
}

/// One realization's running state.
pub(crate) struct RealizationState {
    z: Vec<f64>,
    rng: Xoshiro256PlusPlus,
    eps: Vec<f64>,
    tmp: Vec<f64>,
    /// max y per output.
    pub max_y: Vec<f64>,
    /// max |y| per output.
    pub max_abs: Vec<f64>,
}

impl<'a> McPlan<'a> {
    /// The plan of `sys`'s outputs `outputs` started as `start` on `grid`.
    ///
    /// # Errors
    /// An output without a finite variance; the start's errors; a covariance that is not one.
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
        Ok(McPlan {
            sys,
            outputs,
            grid,
            m0,
            l0,
            n: sys.n_states(),
        })
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

    /// The transitions of steps `j0..j1` and the output maps of points `j0..=j1`, equal neighbours shared.
    fn block_tables(&self, j0: usize, j1: usize) -> Result<BlockTables> {
        let dt = self.grid.dt;
        let mut steps: Vec<Arc<StepDisc>> = Vec::with_capacity(j1 - j0);
        let mut last: Option<(Frozen, Arc<StepDisc>)> = None;
        for j in j0..j1 {
            let fr = self.sys.frozen((j as f64 + 0.5) * dt)?;
            let d = match &last {
                Some((f, d)) if *f == fr => d.clone(),
                _ => {
                    let tr = van_loan(&fr.f, &fr.g, dt)?;
                    let gamma = super::lyapunov_ode::mean_step(&fr, dt)?;
                    let d = Arc::new(StepDisc {
                        phi: flat(&tr.phi),
                        l: flat(&covariance_factor(&tr.qd)?),
                        gamma: gamma.iter().copied().collect(),
                    });
                    last = Some((fr, d.clone()));
                    d
                }
            };
            steps.push(d);
        }
        let mut maps: Vec<Arc<OutputMap>> = Vec::with_capacity(j1 - j0 + 1);
        for j in j0..=j1 {
            let m = self.output_map(&self.sys.frozen(j as f64 * dt)?);
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
            rng: stream(seed, i),
            eps: vec![0.0; n],
            tmp: vec![0.0; n],
            max_y: vec![f64::NEG_INFINITY; self.outputs.len()],
            max_abs: vec![0.0; self.outputs.len()],
        };
        fill_standard_normal(&mut s.rng, &mut s.eps);
        for r in 0..n {
            s.z[r] = self.m0[r] + (0..n).map(|c| self.l0[r * n + c] * s.eps[c]).sum::<f64>();
        }
        s
    }

    /// The outputs of state `s` at a point with map `m`, into `y`; the maxima updated.
    fn observe(&self, s: &mut RealizationState, m: &OutputMap, y: &mut [f64]) {
        let n = self.n;
        for (o, v) in y.iter_mut().enumerate() {
            let x = m.y0[o] + (0..n).map(|c| m.h[o * n + c] * s.z[c]).sum::<f64>();
            *v = x;
            s.max_y[o] = s.max_y[o].max(x);
            s.max_abs[o] = s.max_abs[o].max(x.abs());
        }
    }

    /// One step: z ← Φz + Γ + Lε with n fresh normals.
    fn step(&self, s: &mut RealizationState, d: &StepDisc) {
        let n = self.n;
        fill_standard_normal(&mut s.rng, &mut s.eps);
        for r in 0..n {
            let mut acc = d.gamma[r];
            for c in 0..n {
                acc += d.phi[r * n + c] * s.z[c];
            }
            for c in 0..n {
                acc += d.l[r * n + c] * s.eps[c];
            }
            s.tmp[r] = acc;
        }
        std::mem::swap(&mut s.z, &mut s.tmp);
    }

    /// Advances every realization of `states` over steps `j0..j1` (the point j0 already observed), and
    /// returns the outputs at the stored points of (j0, j1] (and at j0 = 0 itself).
    pub(crate) fn advance(&self, states: &mut [RealizationState], j0: usize, j1: usize) -> Result<ShardBlock> {
        let (steps, maps) = self.block_tables(j0, j1)?;
        let p = self.outputs.len();
        let k = self.grid.store_every;
        let first_stored = if j0 == 0 { 0 } else { j0 / k + 1 };
        let stored: Vec<Vec<f64>> = states
            .par_iter_mut()
            .map(|s| {
                let mut out = Vec::new();
                let mut y = vec![0.0; p];
                if j0 == 0 {
                    self.observe(s, &maps[0], &mut y);
                    out.extend_from_slice(&y);
                }
                for (j, d) in (j0..j1).zip(&steps) {
                    self.step(s, d);
                    self.observe(s, &maps[j + 1 - j0], &mut y);
                    if (j + 1) % k == 0 {
                        out.extend_from_slice(&y);
                    }
                }
                out
            })
            .collect();
        Ok(ShardBlock { stored, first_stored })
    }

    /// The blocks of the grid: (j0, j1) pairs covering 0..N.
    pub(crate) fn blocks(&self) -> Vec<(usize, usize)> {
        let n = self.grid.n_steps;
        (0..n.div_ceil(BLOCK_STEPS))
            .map(|b| (b * BLOCK_STEPS, ((b + 1) * BLOCK_STEPS).min(n)))
            .collect()
    }
}
