//! Monte Carlo of a vehicle under a speed profile on a road synthesised on a spatial grid and sampled along
//! the path x(t): the physically exact generator for any road spectrum (tabulated, measured, ISO 8608 with
//! its band edges), rational or not.

use super::SpeedProfile;
use crate::error::{Error, Result};
use crate::estimate::RunningMoments;
use crate::simulate::{foh, stream, Amplitudes, FirstOrderHold, SpectralGenerator};
use crate::spectrum::{Domain, Spectrum};
use crate::system::StateSpace;
use nalgebra::DVector;

/// Settings of [`road_grid_monte_carlo`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoadGridOptions {
    /// Spatial step Δx of the road grid, m (the grid holds the band |Ω| ≤ π/Δx).
    pub dx: f64,
    /// Integration steps per reported interval.
    pub substeps: usize,
    /// Realizations.
    pub realizations: usize,
    /// Master seed: realization i draws its road from stream (seed, i).
    pub seed: u64,
}

impl RoadGridOptions {
    /// At least two realizations and a positive grid step.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for R < 2, Δx ≤ 0 or NaN.
    pub fn check(&self) -> Result<()> {
        if self.realizations < 2 || self.dx.is_nan() || self.dx <= 0.0 {
            return Err(Error::invalid(
                "realizations/dx",
                self.realizations,
                "R >= 2 and dx > 0",
            ));
        }
        Ok(())
    }
}

/// The ensemble statistics at the reported times.
#[derive(Debug, Clone, PartialEq)]
pub struct RoadGridStatistics {
    /// Reported times, s.
    pub times: Vec<f64>,
    /// Per output, per time: the ensemble mean.
    pub mean: Vec<Vec<f64>>,
    /// Per output, per time: the ensemble variance (divisor R − 1).
    pub variance: Vec<Vec<f64>>,
    /// R.
    pub realizations: usize,
    /// The run-in before t = 0 at the speed v(0), m.
    pub run_in: f64,
}

/// Path positions on the road grid: the run-in at v(0) from −L_run to 0, then x(t) = ∫₀ᵗv ds.
pub(crate) struct Path {
    /// Road coordinate (from the grid's start) at every integration step.
    pub(crate) positions: Vec<f64>,
    /// The speed v at every integration step, m/s (v(0) over the run-in).
    pub(crate) speeds: Vec<f64>,
    /// The integration step index of every reported time.
    pub(crate) reported: Vec<usize>,
    /// Δt of the integration steps.
    pub(crate) dt: f64,
}

/// The integration grid: run-in steps at v(0), then `substeps` per reported interval (uniform times).
pub(crate) fn path(speed: &SpeedProfile, ss: &StateSpace, times: &[f64], substeps: usize) -> Result<(Path, f64)> {
    let uniform = times.len() >= 2
        && times[0] == 0.0
        && times
            .windows(2)
            .all(|w| ((w[1] - w[0]) - (times[1] - times[0])).abs() <= 1e-9 * times[1]);
    if !uniform || substeps == 0 {
        return Err(Error::invalid(
            "times",
            times.len(),
            "uniform reported times from 0 (at least two), with substeps >= 1",
        ));
    }
    let dt = (times[1] - times[0]) / substeps as f64;
    let v0 = speed.speed(0.0);
    let settle = crate::road::replay::settling_length(ss, v0)?;
    let run_steps = (settle / (v0 * dt)).ceil() as usize;
    let run_in = run_steps as f64 * v0 * dt;
    let mut positions: Vec<f64> = (0..=run_steps).map(|k| k as f64 * v0 * dt).collect();
    let steps = (times.len() - 1) * substeps;
    positions.extend((1..=steps).map(|k| run_in + speed.distance(k as f64 * dt)));
    let mut speeds = vec![v0; run_steps + 1];
    speeds.extend((1..=steps).map(|k| speed.speed(k as f64 * dt)));
    let reported = (0..times.len()).map(|j| run_steps + j * substeps).collect();
    Ok((
        Path {
            positions,
            speeds,
            reported,
            dt,
        },
        run_in,
    ))
}

/// The road at position p by linear interpolation of the grid samples h (step dx).
pub(crate) fn sample(h: &[f64], dx: f64, p: f64) -> f64 {
    let s = p / dx;
    let k = (s.floor() as usize).min(h.len() - 2);
    let f = s - k as f64;
    h[k] * (1.0 - f) + h[k + 1] * f
}

/// One realization through the discretised system: the outputs `rows` of y = Cx + Du at the reported steps
/// (time-major, `rows.len()` per time), and each one's largest y and |y| over every step from t = 0 on.
pub(crate) fn realization(
    ss: &StateSpace,
    d: &FirstOrderHold,
    h: &[f64],
    dx: f64,
    path: &Path,
    rows: &[usize],
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = ss.a.nrows();
    let mut x = DVector::zeros(n);
    let mut u0 = sample(h, dx, path.positions[0]);
    let mut next = path.reported.iter().peekable();
    let mut stored = Vec::with_capacity(path.reported.len() * rows.len());
    let (mut max_y, mut max_abs) = (vec![f64::NEG_INFINITY; rows.len()], vec![0.0_f64; rows.len()]);
    for (k, &p) in path.positions.iter().enumerate() {
        let u = sample(h, dx, p);
        if k > 0 {
            x = &d.phi * &x + d.gamma0.column(0) * u0 + d.gamma1.column(0) * u;
        }
        u0 = u;
        if k < path.reported[0] {
            continue;
        }
        let is_reported = next.peek() == Some(&&k);
        for (o, &i) in rows.iter().enumerate() {
            let y = (ss.c.row(i) * &x)[0] + ss.d[(i, 0)] * u;
            max_y[o] = max_y[o].max(y);
            max_abs[o] = max_abs[o].max(y.abs());
            if is_reported {
                stored.push(y);
            }
        }
        if is_reported {
            next.next();
        }
    }
    (stored, max_y, max_abs)
}

/// The road generator of a path: a power-of-two grid of step Δx longer than the path.
pub(crate) fn grid_generator(spectrum: &dyn Spectrum, path: &Path, dx: f64) -> Result<SpectralGenerator> {
    let length = path.positions.iter().copied().fold(0.0, f64::max) + 2.0 * dx;
    let n = ((length / dx).ceil() as usize).next_power_of_two().max(2);
    SpectralGenerator::new(spectrum, dx, n, Amplitudes::Rayleigh)
}

/// Refuses a temporal spectrum, several inputs or a u̇ term, v(0) = 0.
pub(crate) fn check_road(ss: &StateSpace, spectrum: &dyn Spectrum, speed: &SpeedProfile) -> Result<()> {
    if spectrum.domain() != Domain::Spatial {
        return Err(Error::invalid(
            "spectrum",
            spectrum.describe(),
            "a road (spatial) spectrum",
        ));
    }
    if ss.b.ncols() != 1 || ss.e.iter().any(|v| *v != 0.0) {
        return Err(Error::NotApplicable {
            method: "road-grid Monte Carlo".into(),
            reason: "one input (the road elevation) without a u̇ term: combine the inputs first".into(),
        });
    }
    if speed.speed(0.0) <= 0.0 {
        return Err(Error::invalid(
            "speed",
            0.0,
            "v(0) > 0: the run-in starts the vehicle in its stationary state",
        ));
    }
    Ok(())
}

/// Ensemble mean and variance of every output of `ss` (one input, the road elevation, felt with `gains`)
/// at `times` while the vehicle follows `speed`, by Monte Carlo on roads synthesised on a spatial grid.
///
/// # Formula
/// Realization i draws a periodic Gaussian road h on the grid x_k = kΔx (the spectral generator of the
/// crate: complex Gaussian coefficients of variance S(Ω_j)ΔΩ, one inverse FFT; N a power of two with NΔx
/// longer than the path, so the road does not repeat along it). The vehicle starts from rest a run-in
/// L_run = 7v(0)/min|Re λ(A)| before x = 0 at the constant speed v(0), so that at t = 0 it is in its
/// stationary state at v(0) (to e^{−7} of the initial amplitude), then follows x(t) = ∫₀ᵗv ds. The input
/// u(t) = h(x(t)) is the grid road interpolated linearly; the states are stepped exactly for an input linear
/// over each step (first-order hold, Δt = reported interval / `substeps`); y = Cx + Du.
///
/// This generator needs no rational form: the road is a function of x, and the vehicle samples it where it
/// is. Its approximations are the grid's: the band |Ω| ≤ π/Δx, the linear interpolation (it attenuates the
/// power at wavenumber Ω by about (ΩΔx)²/6 relative) and the step Δt of the hold.
///
/// # Errors
/// A temporal spectrum; a system with an E·u̇ term (the road slope is not generated) or several inputs;
/// v(0) = 0 (no run-in: the stationary state at rest is not defined); a density not finite on the grid (a
/// power law without its band); non-uniform times; Δx ≤ 0; R < 2.
pub fn road_grid_monte_carlo(
    ss: &StateSpace,
    spectrum: &dyn Spectrum,
    speed: &SpeedProfile,
    times: &[f64],
    opts: &RoadGridOptions,
) -> Result<RoadGridStatistics> {
    check_road(ss, spectrum, speed)?;
    opts.check()?;
    let (path, run_in) = path(speed, ss, times, opts.substeps)?;
    let generator = grid_generator(spectrum, &path, opts.dx)?;
    let d = foh(&ss.a, &ss.b, path.dt)?;
    let rows: Vec<usize> = (0..ss.c.nrows()).collect();
    let mut scratch = generator.scratch();
    let mut h = vec![0.0; generator.len()];
    accumulate(times, rows.len(), opts.realizations, run_in, |i| {
        generator.generate(&mut stream(opts.seed, i as u64), &mut scratch, &mut h)?;
        Ok(realization(ss, &d, &h, opts.dx, &path, &rows).0)
    })
}

/// The ensemble statistics of `realizations` runs of `run` (realization i → its `p` outputs at each of the
/// `times`, time-major), accumulated in realization order.
pub(crate) fn accumulate(
    times: &[f64],
    p: usize,
    realizations: usize,
    run_in: f64,
    mut run: impl FnMut(usize) -> Result<Vec<f64>>,
) -> Result<RoadGridStatistics> {
    let mut acc = vec![vec![RunningMoments::default(); times.len()]; p];
    for i in 0..realizations {
        let stored = run(i)?;
        for (j, y) in stored.chunks(p).enumerate() {
            for (i, a) in acc.iter_mut().enumerate() {
                a[j].push(y[i]);
            }
        }
    }
    Ok(RoadGridStatistics {
        times: times.to_vec(),
        mean: acc.iter().map(|a| a.iter().map(|w| w.mean()).collect()).collect(),
        variance: acc.iter().map(|a| a.iter().map(|w| w.variance()).collect()).collect(),
        realizations,
        run_in,
    })
}
