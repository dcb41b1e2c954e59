//! The road-grid Monte Carlo ([`super::road_grid`]) as a run file: the realizations of a vehicle on roads
//! synthesised on a spatial grid and sampled along x(t), stored, resumed, sharded and merged exactly like
//! the other transient runs ([`super::monte_carlo`]; layout in `docs/transients.md`).

use super::mc_engine::ShardBlock;
use super::mc_finish::AnalyticSide;
use super::monte_carlo::{
    check_options, check_resources, metadata, run_batch, Maxima, RunIdentity, ShardSource, TransientRunOptions,
    TransientRunSummary,
};
use super::road_grid::{check_road, grid_generator, path, realization, Path};
use super::road_wheels::{check_wheels, wheels_grid, wheels_realization, TrackGrid, WheelRoad};
use super::SpeedProfile;
use crate::error::{Error, Result};
use crate::simulate::{foh, stream, FirstOrderHold, SpectralGenerator};
use crate::spectrum::Spectrum;
use crate::store::{Provenance, Signal};
use crate::system::{FrequencyResponse, StateSpace};
use rayon::prelude::*;

/// What a road-grid run is made of besides its options.
pub struct RoadGridRunInput<'a> {
    /// The vehicle: one input (the road elevation under the wheel) without a u̇ term, or one per wheel of
    /// `wheels` (a u̇ term reads the tracks' slopes).
    pub ss: &'a StateSpace,
    /// The wheels at positions or on two tracks ([`WheelRoad`]; its spectrum is `spectrum`'s), or `None`
    /// for one input.
    pub wheels: Option<&'a WheelRoad>,
    /// The road spectrum (spatial).
    pub spectrum: &'a dyn Spectrum,
    /// v(t); v(0) > 0.
    pub speed: &'a SpeedProfile,
    /// The simulated outputs (indices into the outputs of `ss`).
    pub outputs: Vec<usize>,
    /// Spatial step Δx of the road grid, m.
    pub dx: f64,
    /// The analytic curves at the grid's stored times (the exact route, or the evolutionary route with NaN
    /// where its error estimate exceeds its threshold) and the distributions of the maxima.
    pub analytic: AnalyticSide,
    /// The scenario text (identifies the run).
    pub scenario_text: String,
    /// What else identifies the run.
    pub provenance: Vec<Provenance>,
}

/// The road of a plan: one grid road under one input, or the tracks under several wheels.
enum GridRoad {
    One(SpectralGenerator),
    Wheels(TrackGrid, WheelRoad),
}

/// Everything a shard's realizations share.
struct GridPlan<'a> {
    ss: &'a StateSpace,
    d: FirstOrderHold,
    road: GridRoad,
    path: Path,
    dx: f64,
    rows: Vec<usize>,
}

impl ShardSource for GridPlan<'_> {
    fn n_outputs(&self) -> usize {
        self.rows.len()
    }

    fn realizations(
        &self,
        range: std::ops::Range<usize>,
        seed: u64,
        sink: &mut dyn FnMut(ShardBlock),
    ) -> Result<Vec<Maxima>> {
        let runs: Vec<(Vec<f64>, Maxima)> = match &self.road {
            GridRoad::One(generator) => range
                .into_par_iter()
                .map_init(
                    || (generator.scratch(), vec![0.0; generator.len()]),
                    |(scratch, h), i| {
                        generator.generate(&mut stream(seed, i as u64), scratch, h)?;
                        let (stored, max_y, max_abs) =
                            realization(self.ss, &self.d, h, self.dx, &self.path, &self.rows);
                        Ok((stored, (max_y, max_abs)))
                    },
                )
                .collect::<Result<_>>()?,
            GridRoad::Wheels(grid, road) => range
                .into_par_iter()
                .map_init(
                    || (grid.scratch(), vec![vec![0.0; grid.len()]; grid.series()]),
                    |(scratch, h), i| {
                        grid.generate(&mut stream(seed, i as u64), scratch, h)?;
                        let (stored, max_y, max_abs) =
                            wheels_realization(self.ss, &self.d, h, self.dx, &self.path, &road.wheels, &self.rows);
                        Ok((stored, (max_y, max_abs)))
                    },
                )
                .collect::<Result<_>>()?,
        };
        let (stored, maxima): (Vec<Vec<f64>>, _) = runs.into_iter().unzip();
        sink(ShardBlock {
            width: stored.first().map_or(0, Vec::len),
            stored: stored.concat(),
            first_stored: 0,
        });
        Ok(maxima)
    }
}

/// The generator text of a road-grid run.
fn generator(plan: &GridPlan<'_>, run_in: f64) -> String {
    let (points, wheels) = match &plan.road {
        GridRoad::One(g) => (g.len(), String::new()),
        GridRoad::Wheels(grid, road) => (
            grid.len(),
            format!(
                ", {} track(s){}, wheel j read at x(t) - l_j (l = {:?} m)",
                grid.tracks(),
                road.coherence
                    .as_ref()
                    .map_or(String::new(), |c| format!(" of {}", c.describe())),
                road.wheels.iter().map(|w| w.position).collect::<Vec<_>>()
            ),
        ),
    };
    format!(
        "{}; transient on a road synthesised on a spatial grid: dx = {} m, {points} points (periodic, longer than \
         the path){wheels}, linear interpolation along x(t), run-in {run_in:.3} m at v(0), first-order hold dt = {} s",
        crate::simulate::GENERATOR,
        plan.dx,
        plan.path.dt
    )
}

/// Runs the road-grid Monte Carlo batch into `out` (resuming an interrupted run of the same settings).
///
/// # Formula
/// Realization i draws its road from stream (seed, i) ([`super::road_grid_monte_carlo`]: a periodic Gaussian
/// road on the grid x_k = kΔx, a run-in at v(0) from rest, then x(t) = ∫₀ᵗv ds, stepped exactly for an
/// input linear over each step of `opts.grid`); with `wheels`, the tracks of
/// [`super::road_wheels_monte_carlo`], wheel j read at x(t) − ℓ_j. Every stored time of the grid is a
/// reported time; the maxima are taken over every step from t = 0 on. The shards' accumulators and their statistics are those
/// of [`super::run_transient`], so runs, shards and merges are handled alike.
///
/// # Errors
/// A temporal spectrum; several inputs or a u̇ term without `wheels`; v(0) = 0; wheels that do not match
/// the inputs; Δx ≤ 0; a density not finite on the grid; an output index out of range; the errors of [`super::run_transient`] (options, resources, store).
pub fn run_road_grid(
    input: &RoadGridRunInput<'_>,
    opts: &TransientRunOptions,
    out: &std::path::Path,
    progress: &dyn Fn(usize, usize),
) -> Result<TransientRunSummary> {
    match input.wheels {
        Some(w) => check_wheels(input.ss, w, input.speed)?,
        None => check_road(input.ss, input.spectrum, input.speed)?,
    }
    let times = opts.grid.stored_times();
    check_options(opts, &times)?;
    if !(input.dx.is_finite() && input.dx > 0.0) {
        return Err(Error::invalid(
            "road step",
            input.dx,
            "the grid step Δx must be finite and > 0 m",
        ));
    }
    let infos = input.ss.outputs();
    if let Some(&i) = input.outputs.iter().find(|&&i| i >= infos.len()) {
        return Err(Error::invalid("output", i, "no such output"));
    }
    let (path, run_in) = path(input.speed, input.ss, &times, opts.grid.store_every)?;
    let road = match input.wheels {
        Some(w) => GridRoad::Wheels(wheels_grid(input.ss, w, &path, input.dx)?, w.clone()),
        None => GridRoad::One(grid_generator(input.spectrum, &path, input.dx)?),
    };
    let plan = GridPlan {
        ss: input.ss,
        d: foh(&input.ss.a, &input.ss.b, path.dt)?,
        road,
        path,
        dx: input.dx,
        rows: input.outputs.clone(),
    };
    let id = RunIdentity {
        outputs: input
            .outputs
            .iter()
            .map(|&i| Signal::new(&infos[i].name, &infos[i].unit))
            .collect(),
        scenario_text: input.scenario_text.clone(),
        provenance: input.provenance.clone(),
        generator: generator(&plan, run_in),
    };
    let meta = metadata(id, opts)?;
    check_resources(&meta, opts, input.ss.n_states(), out)?;
    run_batch(&plan, &meta, &input.analytic, opts, out, progress)
}
