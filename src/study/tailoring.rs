//! Test tailoring (`stochvib tailor`): the extreme response spectrum and the fatigue damage spectrum
//! ([`crate::extremes::ers_fds()`], Lalanne) of a base acceleration given as a spectrum file (a measured or
//! standard cab-floor or seat-base density) or as an output of a scenario (the computed cab floor), on a
//! logarithmic grid of natural frequencies; [`crate::report::tailoring_text`] prints it.

use crate::error::{Error, Result};
use crate::extremes::{ers_fds, ErsFdsOptions, ErsFdsPoint};
use crate::response::OutputDensity;
use crate::scenario::{Scenario, SpectrumFile};
use crate::spectrum::Domain;
use crate::units::{unit_dim, Dim};
use serde::Serialize;

/// The base acceleration whose spectra are wanted.
pub enum TailoringSource<'a> {
    /// A temporal spectrum of an acceleration (unit m/s²), e.g. a catalogue seat test input.
    Spectrum(&'a SpectrumFile),
    /// Output `output` of a scenario, an acceleration (unit m/s²), under the scenario's excitation.
    Output {
        /// The scenario.
        scenario: &'a Scenario,
        /// The output's index in the scenario's model.
        output: usize,
    },
}

/// The most natural frequencies of a grid: a table of 10⁶ rows (about 10 s of quadratures on one core) is
/// finer than any test specification reads; 10⁸ would run about 17 minutes (10 µs a point, measured at 10⁴
/// points) and hold gigabytes of text before printing a line.
pub const MAX_GRID_POINTS: usize = 1_000_000;

/// The logarithmic grid of natural frequencies of the oscillator family.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrequencyGrid {
    /// Lowest natural frequency, Hz.
    pub min_hz: f64,
    /// Highest natural frequency, Hz.
    pub max_hz: f64,
    /// Number of frequencies (2 to [`MAX_GRID_POINTS`]), evenly spaced in log f.
    pub points: usize,
}

impl FrequencyGrid {
    /// The frequencies min·(max/min)^{k/(points−1)}, k = 0 … points−1, Hz (the ends exact).
    ///
    /// # Errors
    /// A bound that is not finite and > 0, min ≥ max, fewer than 2 points or more than
    /// [`MAX_GRID_POINTS`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::study::tailoring::FrequencyGrid;
    /// let f = FrequencyGrid { min_hz: 1.0, max_hz: 100.0, points: 3 }.frequencies().unwrap();
    /// assert_eq!((f[0], f[2]), (1.0, 100.0));
    /// assert!((f[1] - 10.0).abs() < 1e-13);
    /// ```
    pub fn frequencies(&self) -> Result<Vec<f64>> {
        for (key, v) in [("f-min", self.min_hz), ("f-max", self.max_hz)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::invalid(key, v, "a natural frequency must be finite and > 0 Hz"));
            }
        }
        if self.min_hz >= self.max_hz {
            return Err(Error::invalid(
                "f-min",
                self.min_hz,
                format!("must be below f-max = {} Hz", self.max_hz),
            ));
        }
        if self.points < 2 {
            return Err(Error::invalid(
                "points",
                self.points,
                "a grid needs at least 2 frequencies",
            ));
        }
        if self.points > MAX_GRID_POINTS {
            return Err(Error::invalid(
                "points",
                self.points,
                format!("at most {MAX_GRID_POINTS} frequencies (a table finer than any specification reads)"),
            ));
        }
        let ratio = (self.max_hz / self.min_hz).ln();
        let last = self.points - 1;
        Ok((0..self.points)
            .map(|k| match k {
                0 => self.min_hz,
                k if k == last => self.max_hz,
                k => self.min_hz * (ratio * k as f64 / last as f64).exp(),
            })
            .collect())
    }
}

/// The spectra of one base acceleration.
#[derive(Debug, Clone, Serialize)]
pub struct TailoringTable {
    /// What the base acceleration is (spectrum name, or scenario title and output).
    pub source: String,
    /// The family, duration and material.
    pub options: ErsFdsOptions,
    /// ERS and FDS at each natural frequency.
    pub points: Vec<ErsFdsPoint>,
}

/// ERS and FDS of `source` for the oscillator family and duration of `opts`.
///
/// # Formula
/// The base acceleration's two-sided angular density S(ω) is the spectrum's density, or the scenario
/// output's S_y(ω) = H_y S_u H_yᴴ; the spectra are those of [`ers_fds()`] (Lalanne 2009, Vol. 5).
///
/// # Errors
/// A spectrum that is spatial or not of an acceleration, an output whose unit is not m/s², and the errors
/// of [`ers_fds()`] (the options) and of [`OutputDensity::new`].
pub fn tailoring_spectra(source: &TailoringSource, opts: &ErsFdsOptions) -> Result<TailoringTable> {
    match source {
        TailoringSource::Spectrum(file) => {
            let s = file.spectrum.as_ref();
            if s.domain() != Domain::Temporal {
                return Err(Error::invalid(
                    "spectrum",
                    &file.name,
                    "a spatial spectrum (a road) is not a base acceleration: give a temporal density in m/s^2, \
                     or a scenario output",
                ));
            }
            require_acceleration("spectrum", &file.name, &file.unit)?;
            Ok(TailoringTable {
                source: format!("spectrum {}", file.name),
                options: opts.clone(),
                points: ers_fds(&|w| s.density(w), &s.breakpoints(), opts)?,
            })
        }
        TailoringSource::Output { scenario, output } => {
            let sys = scenario.model.system.as_ref();
            let info = sys.outputs().get(*output).ok_or_else(|| {
                Error::invalid(
                    "output",
                    output,
                    format!("the model has {} outputs", sys.outputs().len()),
                )
            })?;
            require_acceleration("output", &info.name, &info.unit)?;
            let density = OutputDensity::new(sys, &scenario.excitation, *output)?;
            let breakpoints: Vec<f64> = sys
                .natural_frequencies()
                .into_iter()
                .chain(
                    scenario
                        .excitation
                        .spectra()
                        .iter()
                        .filter(|s| s.domain() == Domain::Temporal)
                        .flat_map(|s| s.breakpoints()),
                )
                .collect();
            Ok(TailoringTable {
                source: format!("{}, output {}", scenario.title, info.name),
                options: opts.clone(),
                points: ers_fds(&|w| density.density(w), &breakpoints, opts)?,
            })
        }
    }
}

fn require_acceleration(key: &str, name: &str, unit: &str) -> Result<()> {
    if unit_dim(unit) == Some(Dim::ACCELERATION) {
        return Ok(());
    }
    Err(Error::invalid(
        key,
        name,
        format!("its unit is {unit}: the spectra are those of a base acceleration (m/s^2)"),
    ))
}
