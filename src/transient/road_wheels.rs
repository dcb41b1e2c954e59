//! The road-grid Monte Carlo ([`super::road_grid`]) for vehicles with several wheels: wheels at positions
//! along the vehicle (a wheelbase) on one track, or on two parallel tracks with a coherence. Each track is
//! synthesised on the spatial grid with the coherence of the pair, and wheel j reads its track at
//! x(t) − ℓ_j, wherever the speed profile has taken the vehicle.

use super::road_grid::{accumulate, path, sample, Path, RoadGridOptions, RoadGridStatistics};
use super::SpeedProfile;
use crate::coherence::{Coherence, SpectralMatrix, TwoTracks};
use crate::error::{Error, Result};
use crate::simulate::{foh, stream, Amplitudes, FirstOrderHold, SpectralGenerator, SpectralScratch};
use crate::spectrum::{Domain, Spectrum};
use crate::system::StateSpace;
use nalgebra::{Complex, DVector};
use rand::rngs::Xoshiro256PlusPlus;
use std::sync::Arc;

/// A model input fed by the road: u_j(t) = g_j h_c(x(t) − ℓ_j).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wheel {
    /// c: the track (0 left, or the only one; 1 right).
    pub track: usize,
    /// ℓ_j, m behind the first contact (≥ 0).
    pub position: f64,
    /// g_j.
    pub gain: f64,
}

/// The road of a vehicle with wheels: one track, or two tracks of the same spatial density with a
/// coherence between them.
#[derive(Debug, Clone)]
pub struct WheelRoad {
    /// S_Ω (spatial, rad/m).
    pub spectrum: Arc<dyn Spectrum>,
    /// The coherence of the two tracks (`None`: one track).
    pub coherence: Option<Arc<dyn Coherence>>,
    /// One per model input.
    pub wheels: Vec<Wheel>,
}

/// The grid synthesis of a [`WheelRoad`]: the spectral generator of S_Ω and, for two tracks, the mixing
/// (ρ_j, √(1 − ρ_j²)) of the right track at every bin j; with `slope`, each track's slope dh/dx as well.
pub(crate) struct TrackGrid {
    generator: SpectralGenerator,
    mixing: Option<Vec<(Complex<f64>, Complex<f64>)>>,
    slope: bool,
}

/// The working memory of [`TrackGrid::generate`]: the generator's, and two coefficient vectors.
pub(crate) type TrackScratch = (SpectralScratch, Vec<Complex<f64>>, Vec<Complex<f64>>);

impl TrackGrid {
    /// The grid of step `dx` and `n` points (a power of two) of `road`, with the tracks' slopes when
    /// `slope` (for a model whose outputs contain u̇).
    ///
    /// # Formula
    /// The two tracks' spatial cross-spectral matrix is S_Ω(Ω)[[1, ρ], [ρ, 1]] (`TwoTracks` at 1 m/s: its
    /// time is the road coordinate). With C = LLᴴ the coherence matrix, the left track's grid coefficients
    /// are c_L,j, the right track's ρ_j c_L,j + √(1 − ρ_j²) c_R,j (L's second row), c_L and c_R independent
    /// draws of the one-track generator: each track has the density S_Ω and their cross-density is ρS_Ω.
    pub(crate) fn new(road: &WheelRoad, dx: f64, n: usize, slope: bool) -> Result<Self> {
        let generator = SpectralGenerator::new(road.spectrum.as_ref(), dx, n, Amplitudes::Rayleigh)?;
        let mixing = match &road.coherence {
            None => None,
            Some(c) => {
                let pair = TwoTracks::new(road.spectrum.clone(), c.clone(), 1.0)?;
                let dw = generator.d_omega();
                Some(
                    (0..=n / 2)
                        .map(|j| {
                            let l = crate::coherence::semidefinite_cholesky(&pair.coherence_matrix(j as f64 * dw));
                            (l[(1, 0)], l[(1, 1)])
                        })
                        .collect(),
                )
            }
        };
        Ok(TrackGrid {
            generator,
            mixing,
            slope,
        })
    }

    /// Number of tracks.
    pub(crate) fn tracks(&self) -> usize {
        if self.mixing.is_some() {
            2
        } else {
            1
        }
    }

    /// Series [`generate`](Self::generate) writes: the tracks, then (with slopes) their slopes.
    pub(crate) fn series(&self) -> usize {
        self.tracks() * (1 + usize::from(self.slope))
    }

    /// Grid points per track.
    pub(crate) fn len(&self) -> usize {
        self.generator.len()
    }

    /// Fresh working memory.
    pub(crate) fn scratch(&self) -> TrackScratch {
        let bins = vec![Complex::new(0.0, 0.0); self.len() / 2 + 1];
        (self.generator.scratch(), bins.clone(), bins)
    }

    /// One realization of the tracks into `h` (one vector of `len()` points per series of
    /// [`series`](Self::series)), drawing from `rng`: the left track's coefficients, then (two tracks) the
    /// right track's innovations. The slopes use the same coefficients.
    ///
    /// # Formula
    /// The grid road is h(x) = Σ_j c_j e^{iΩ_j x} (the generator's inverse FFT, Ω_j = jΔΩ), so its slope
    /// is exactly dh/dx = Σ_j iΩ_j c_j e^{iΩ_j x}: every bin multiplied by iΩ_j, one more inverse FFT per
    /// track (the Nyquist bin, whose sine vanishes on the grid, gives 0).
    pub(crate) fn generate(
        &self,
        rng: &mut Xoshiro256PlusPlus,
        scratch: &mut TrackScratch,
        h: &mut [Vec<f64>],
    ) -> Result<()> {
        let (sc, left, keep) = scratch;
        self.generator.draw(rng, sc);
        let Some(mix) = &self.mixing else {
            let Some((h0, slope)) = h.split_first_mut() else {
                return Err(Error::invalid("tracks", 0, "one series per track and slope"));
            };
            return self.synthesize(sc, keep, h0, slope.first_mut());
        };
        left.copy_from_slice(sc.coefficients());
        self.generator.draw(rng, sc);
        for ((c, l), (m0, m1)) in sc.coefficients_mut().iter_mut().zip(left.iter()).zip(mix) {
            *c = m0 * l + m1 * *c;
        }
        let n = self.len();
        sc.coefficients_mut()[0].im = 0.0;
        sc.coefficients_mut()[n / 2].im = 0.0;
        let (h0, h1, s0, s1) = match h {
            [h0, h1] => (h0, h1, None, None),
            [h0, h1, s0, s1] => (h0, h1, Some(s0), Some(s1)),
            _ => return Err(Error::invalid("tracks", h.len(), "one series per track and slope")),
        };
        self.synthesize(sc, keep, h1, s1)?;
        sc.coefficients_mut().copy_from_slice(left);
        self.synthesize(sc, keep, h0, s0)
    }

    /// The track of the coefficients in `sc` into `h`, and its slope into `slope` when asked (`keep` holds
    /// the coefficients meanwhile; every inverse FFT overwrites its input).
    fn synthesize(
        &self,
        sc: &mut SpectralScratch,
        keep: &mut [Complex<f64>],
        h: &mut [f64],
        slope: Option<&mut Vec<f64>>,
    ) -> Result<()> {
        if let (true, Some(slope)) = (self.slope, slope) {
            keep.copy_from_slice(sc.coefficients());
            let dw = self.generator.d_omega();
            for (j, c) in sc.coefficients_mut().iter_mut().enumerate() {
                *c *= Complex::new(0.0, j as f64 * dw);
            }
            let n = self.len();
            sc.coefficients_mut()[n / 2] = Complex::new(0.0, 0.0);
            self.generator.synthesize(sc, slope)?;
            sc.coefficients_mut().copy_from_slice(keep);
        }
        self.generator.synthesize(sc, h)
    }
}

/// One realization of the vehicle on the tracks `h`: wheel j reads h_{c_j} at the path position plus
/// ℓ_max − ℓ_j (the rearmost wheel starts at the grid's origin); outputs as [`super::road_grid`]'s, plus
/// E·u̇ with u̇_j = g_j·v(t)·h′_{c_j} when `ss` has a u̇ term (`h` then holds the tracks' slopes after the
/// tracks, [`TrackGrid::series`]).
pub(crate) fn wheels_realization(
    ss: &StateSpace,
    d: &FirstOrderHold,
    h: &[Vec<f64>],
    dx: f64,
    path: &Path,
    wheels: &[Wheel],
    rows: &[usize],
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = ss.a.nrows();
    let back = wheels.iter().map(|w| w.position).fold(0.0, f64::max);
    let inputs = |p: f64| {
        DVector::from_iterator(
            wheels.len(),
            wheels
                .iter()
                .map(|w| w.gain * sample(&h[w.track], dx, p + back - w.position)),
        )
    };
    let slopes = ss.e.iter().any(|v| *v != 0.0);
    let tracks = h.len() / (1 + usize::from(slopes));
    let rates = |p: f64, v: f64| {
        DVector::from_iterator(
            wheels.len(),
            wheels
                .iter()
                .map(|w| w.gain * v * sample(&h[tracks + w.track], dx, p + back - w.position)),
        )
    };
    let mut x = DVector::zeros(n);
    let mut u0 = inputs(path.positions[0]);
    let mut next = path.reported.iter().peekable();
    let mut stored = Vec::with_capacity(path.reported.len() * rows.len());
    let (mut max_y, mut max_abs) = (vec![f64::NEG_INFINITY; rows.len()], vec![0.0_f64; rows.len()]);
    for (k, &p) in path.positions.iter().enumerate() {
        let u = inputs(p);
        let du = slopes.then(|| rates(p, path.speeds[k]));
        if k > 0 {
            x = &d.phi * &x + &d.gamma0 * &u0 + &d.gamma1 * &u;
        }
        if k >= path.reported[0] {
            let is_reported = next.peek() == Some(&&k);
            for (o, &i) in rows.iter().enumerate() {
                let mut y = (ss.c.row(i) * &x)[0] + (ss.d.row(i) * &u)[0];
                if let Some(du) = &du {
                    y += (ss.e.row(i) * du)[0];
                }
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
        u0 = u;
    }
    (stored, max_y, max_abs)
}

/// Refuses what the wheels' grid cannot take: a temporal spectrum, a wheel per input missing,
/// a track other than 0 (one track) or 0/1 (two), a negative or non-finite position, v(0) = 0.
pub(crate) fn check_wheels(ss: &StateSpace, road: &WheelRoad, speed: &SpeedProfile) -> Result<()> {
    let refuse = |reason: String| Error::NotApplicable {
        method: "road-grid Monte Carlo".into(),
        reason,
    };
    if road.spectrum.domain() != Domain::Spatial {
        return Err(refuse("it takes a road (spatial) spectrum".into()));
    }
    if road.wheels.len() != ss.b.ncols() {
        return Err(refuse(format!(
            "{} wheels for {} model inputs",
            road.wheels.len(),
            ss.b.ncols()
        )));
    }
    let tracks = if road.coherence.is_some() { 2 } else { 1 };
    if let Some(w) = road
        .wheels
        .iter()
        .find(|w| w.track >= tracks || !(w.position.is_finite() && w.position >= 0.0) || !w.gain.is_finite())
    {
        return Err(refuse(format!(
            "a wheel on track {} at {} m with gain {}: tracks 0..{tracks}, positions finite and >= 0, finite gains",
            w.track, w.position, w.gain
        )));
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

/// The track grid of a path: a power of two of points of step Δx, longer than the path and the wheelbase;
/// with the tracks' slopes when `ss` has a u̇ term.
pub(crate) fn wheels_grid(ss: &StateSpace, road: &WheelRoad, path: &Path, dx: f64) -> Result<TrackGrid> {
    let back = road.wheels.iter().map(|w| w.position).fold(0.0, f64::max);
    let length = path.positions.iter().copied().fold(0.0, f64::max) + back + 2.0 * dx;
    let n = ((length / dx).ceil() as usize).next_power_of_two().max(2);
    TrackGrid::new(road, dx, n, ss.e.iter().any(|v| *v != 0.0))
}

/// Ensemble mean and variance of every output of `ss` (its inputs fed by the wheels of `road`) at `times`
/// while the vehicle follows `speed`, by Monte Carlo on tracks synthesised on a spatial grid.
///
/// # Formula
/// As [`super::road_grid_monte_carlo`], with the tracks of [`WheelRoad`] (two tracks: the left track's grid
/// coefficients c_L, the right's ρc_L + √(1 − ρ²)c_R at each bin) and u_j(t) = g_j h_{c_j}(x(t) − ℓ_j): the
/// wheelbase delay is the distance ℓ_j on the road, whatever v(t) does.
///
/// # Errors
/// The refusals of `check_wheels` (a temporal spectrum, wheels that do not match the inputs, a
/// bad track or position, v(0) = 0); a density not finite on the grid; non-uniform times; Δx ≤ 0; R < 2.
pub fn road_wheels_monte_carlo(
    ss: &StateSpace,
    road: &WheelRoad,
    speed: &SpeedProfile,
    times: &[f64],
    opts: &RoadGridOptions,
) -> Result<RoadGridStatistics> {
    check_wheels(ss, road, speed)?;
    opts.check()?;
    let (path, run_in) = path(speed, ss, times, opts.substeps)?;
    let grid = wheels_grid(ss, road, &path, opts.dx)?;
    let d = foh(&ss.a, &ss.b, path.dt)?;
    let rows: Vec<usize> = (0..ss.c.nrows()).collect();
    let mut scratch = grid.scratch();
    let mut h = vec![vec![0.0; grid.len()]; grid.series()];
    accumulate(times, rows.len(), opts.realizations, run_in, |i| {
        grid.generate(&mut stream(opts.seed, i as u64), &mut scratch, &mut h)?;
        Ok(wheels_realization(ss, &d, &h, opts.dx, &path, &road.wheels, &rows).0)
    })
}

/// The coherence of a two-component temporal spectral matrix formed at a speed (the two tracks of a
/// scenario's stationary excitation), as a function of the wavenumber: ρ(n) = Re C₀₁(2πnv).
#[derive(Debug, Clone)]
pub struct MatrixCoherence {
    matrix: Arc<dyn SpectralMatrix>,
    speed: f64,
}

impl MatrixCoherence {
    /// The coherence of `matrix` (two components, formed at `speed_m_s`).
    ///
    /// # Errors
    /// A matrix of other than two components; a speed that is not finite and > 0.
    pub fn new(matrix: Arc<dyn SpectralMatrix>, speed_m_s: f64) -> Result<Self> {
        if matrix.n_components() != 2 || !(speed_m_s.is_finite() && speed_m_s > 0.0) {
            return Err(Error::invalid(
                "matrix",
                matrix.describe(),
                format!(
                    "two tracks at a speed > 0 (got {} components at {speed_m_s} m/s)",
                    matrix.n_components()
                ),
            ));
        }
        Ok(MatrixCoherence {
            matrix,
            speed: speed_m_s,
        })
    }
}

impl Coherence for MatrixCoherence {
    fn describe(&self) -> String {
        format!("the coherence of {}", self.matrix.describe())
    }

    fn coherence_amplitude(&self, n: f64) -> f64 {
        self.matrix
            .coherence_matrix(2.0 * std::f64::consts::PI * n.abs() * self.speed)[(0, 1)]
            .re
    }
}
