//! Road profiles sampled along the track and felt in time by several wheels at speed v.

use super::{Amplitudes, GaussMarkov, SpectralGenerator, SpectralScratch};
use crate::error::{require_positive, Error, Result};
use crate::spectrum::{Domain, Spectrum};
use rand::rngs::Xoshiro256PlusPlus;

/// How the spatial profile is generated.
#[derive(Debug, Clone)]
enum Profile {
    Spectral(SpectralGenerator),
    Shaping(GaussMarkov),
}

/// Working memory of a [`RoadTrack`] (reused across realizations).
#[derive(Debug, Clone)]
pub struct RoadScratch {
    profile: Vec<f64>,
    spectral: Option<SpectralScratch>,
}

/// One random road profile q(x) (spatial spectrum S_Ω, Ω in rad/m) driven over at constant speed v by
/// several wheels: wheel j at distance ℓ_j behind the first reference point feels u_j(t) = q(vt − ℓ_j), the
/// delayed copy of [`Excitation::track`](crate::response::Excitation::track) with τ_j = ℓ_j/v.
///
/// # Formula
/// ```text
/// Δx = vΔt,   q_k = q(kΔx),   u_j(t_k) = q_{k − s_j},   s_j = ℓ_j/Δx  (an integer)
/// ```
/// The time series of each wheel has the temporal density S_t(ω) = S_Ω(ω/v)/v. The wheel offsets must
/// be integer multiples of Δx (checked to a relative 1e-9), so that the delays are exact index shifts and
/// no interpolation error enters the cross-covariances; otherwise the constructor fails and says which Δt
/// would work. Spectral profiles are periodic with period NΔx, so the shift wraps around (exact for the
/// periodic process, whose cross-covariances are K_N((s_j − s_l)Δx)); shaping-filter profiles are
/// generated N + max s_j samples long.
///
/// # Errors
/// A temporal spectrum (give the spatial one), v or Δt ≤ 0, negative offsets, offsets not on the grid,
/// and the errors of the profile generator.
///
/// # Examples
/// ```
/// use stochvib::simulate::{RoadTrack, RoadTrackGrid, stream};
/// use stochvib::spectrum::{Exponential, Domain};
/// // textbook road (8.45): D = 2.25e-4 m², α = 3.5 1/m; axles 2.5 m apart at 10 m/s, Δt = 0.005 s (Δx = 5 cm)
/// let q = Exponential::new(2.25e-4, 3.5, Domain::Spatial).unwrap();
/// let grid = RoadTrackGrid { speed: 10.0, dt: 0.005, n: 1000, offsets: &[0.0, 2.5] };
/// let road = RoadTrack::shaping(&q, grid).unwrap();
/// let mut scratch = road.scratch();
/// let mut u = vec![0.0; 2 * 1000];
/// road.generate(&mut stream(1, 0), &mut scratch, &mut u).unwrap();
/// // the rear wheel repeats the front wheel 50 samples later
/// assert_eq!(u[2 * 60 + 1], u[2 * 10]);
/// ```
#[derive(Debug, Clone)]
pub struct RoadTrack {
    profile: Profile,
    n: usize,
    dt: f64,
    speed: f64,
    shifts: Vec<usize>,
}

/// The sampling of a [`RoadTrack`]: the speed, the time step, the samples per wheel and the wheel offsets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoadTrackGrid<'a> {
    /// The speed v, m/s.
    pub speed: f64,
    /// The time step Δt, s (the distance step is Δx = vΔt).
    pub dt: f64,
    /// Samples N per wheel.
    pub n: usize,
    /// The distance ℓ_j of each wheel behind the first reference point, m (integer multiples of Δx).
    pub offsets: &'a [f64],
}

impl RoadTrack {
    /// Spectral-representation profile (any spatial spectrum) on `grid`, periodic.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn spectral(spatial: &dyn Spectrum, grid: RoadTrackGrid, amplitudes: Amplitudes) -> Result<Self> {
        let RoadTrackGrid { speed, dt, n, offsets } = grid;
        let (dx, shifts) = Self::grid(spatial, speed, dt, offsets)?;
        let g = SpectralGenerator::new(spatial, dx, n, amplitudes)?;
        Ok(RoadTrack {
            profile: Profile::Spectral(g),
            n,
            dt,
            speed,
            shifts,
        })
    }

    /// Exact shaping-filter profile (rational spatial spectrum) on `grid`.
    ///
    /// # Errors
    /// See the type's `# Errors` and [`shaping_simulator`](super::shaping_simulator).
    pub fn shaping(spatial: &dyn Spectrum, grid: RoadTrackGrid) -> Result<Self> {
        let RoadTrackGrid { speed, dt, n, offsets } = grid;
        let (dx, shifts) = Self::grid(spatial, speed, dt, offsets)?;
        if n == 0 {
            return Err(Error::invalid("n", n, "need at least one sample"));
        }
        Ok(RoadTrack {
            profile: Profile::Shaping(super::shaping_simulator(spatial, dx)?),
            n,
            dt,
            speed,
            shifts,
        })
    }

    fn grid(spatial: &dyn Spectrum, speed: f64, dt: f64, offsets: &[f64]) -> Result<(f64, Vec<usize>)> {
        if spatial.domain() != Domain::Spatial {
            return Err(Error::invalid(
                "spectrum",
                spatial.describe(),
                "a road track needs the spatial spectrum (rad/m); it is turned into time by the speed",
            ));
        }
        require_positive("speed", speed)?;
        require_positive("dt", dt)?;
        if offsets.is_empty() {
            return Err(Error::invalid("offsets", "[]", "need one offset per wheel"));
        }
        let dx = speed * dt;
        let mut shifts = Vec::with_capacity(offsets.len());
        for (j, &l) in offsets.iter().enumerate() {
            if !(l.is_finite() && l >= 0.0) {
                return Err(Error::invalid(&format!("offsets[{j}]"), l, "must be finite and >= 0 m"));
            }
            let s = (l / dx).round();
            if (s * dx - l).abs() > 1e-9 * l.max(dx) {
                return Err(Error::invalid(
                    &format!("offsets[{j}]"),
                    format!("{l} m"),
                    format!(
                        "not an integer multiple of the distance step Δx = vΔt = {dx} m; exact delays need \
                         ℓ_j = s_j·Δx — choose Δt = ℓ/(v·k) for an integer k (e.g. Δt = {:e} s)",
                        l / (speed * (l / dx).ceil().max(1.0))
                    ),
                ));
            }
            shifts.push(s as usize);
        }
        Ok((dx, shifts))
    }

    /// Number of wheels m.
    pub fn n_wheels(&self) -> usize {
        self.shifts.len()
    }
    /// Samples per wheel N.
    pub fn len(&self) -> usize {
        self.n
    }
    /// Always false.
    pub fn is_empty(&self) -> bool {
        false
    }
    /// Time step Δt, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }
    /// Speed v, m/s.
    pub fn speed(&self) -> f64 {
        self.speed
    }
    /// Index shifts s_j = ℓ_j/Δx.
    pub fn shifts(&self) -> &[usize] {
        &self.shifts
    }

    /// Fresh working memory.
    pub fn scratch(&self) -> RoadScratch {
        match &self.profile {
            Profile::Spectral(g) => RoadScratch {
                profile: vec![0.0; self.n],
                spectral: Some(g.scratch()),
            },
            Profile::Shaping(_) => RoadScratch {
                profile: vec![0.0; self.n + self.shifts.iter().max().copied().unwrap_or(0)],
                spectral: None,
            },
        }
    }

    /// Writes the wheel inputs of one realization, sample-major: out[k·m + j] = u_j(t_k).
    ///
    /// # Errors
    /// `out.len()` ≠ N·m, or a scratch from another track.
    pub fn generate(&self, rng: &mut Xoshiro256PlusPlus, scratch: &mut RoadScratch, out: &mut [f64]) -> Result<()> {
        let (n, m) = (self.n, self.shifts.len());
        if out.len() != n * m {
            return Err(Error::invalid("out", out.len(), format!("need N·m = {}", n * m)));
        }
        match &self.profile {
            Profile::Spectral(g) => {
                let sc = scratch
                    .spectral
                    .as_mut()
                    .ok_or_else(|| Error::invalid("scratch", "shaping", "made by another track"))?;
                g.generate(rng, sc, &mut scratch.profile)?;
                for (j, &s) in self.shifts.iter().enumerate() {
                    let s = s % n;
                    for k in 0..n {
                        out[k * m + j] = scratch.profile[(k + n - s) % n];
                    }
                }
            }
            Profile::Shaping(gm) => {
                let smax = self.shifts.iter().max().copied().unwrap_or(0);
                if scratch.profile.len() != n + smax {
                    return Err(Error::invalid(
                        "scratch",
                        scratch.profile.len(),
                        "made by another track",
                    ));
                }
                let mut x = vec![0.0; gm.n_states()];
                gm.initial_state(rng, &mut x);
                gm.advance(&mut x, rng, &mut scratch.profile);
                for (j, &s) in self.shifts.iter().enumerate() {
                    for k in 0..n {
                        out[k * m + j] = scratch.profile[k + smax - s];
                    }
                }
            }
        }
        Ok(())
    }
}
