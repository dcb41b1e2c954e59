//! Two parallel road tracks (left and right wheel paths) with the same spatial density and a coherence
//! between them, driven over at a constant speed: a two-component [`SpectralMatrix`] in time.

use super::{Coherence, SpectralMatrix};
use crate::error::Result;
use crate::spectrum::{AtSpeed, Spectrum};
use nalgebra::{Complex, DMatrix};
use std::f64::consts::PI;
use std::sync::Arc;

/// Left and right tracks with the same spatial density S_Ω (Ω in rad/m) and coherence amplitude ρ(n)
/// (n in cycles/m), seen in time at speed v (m/s).
///
/// # Formula
/// ```text
/// S_t(ω) = S_Ω(ω/v)/v,      n = ω/(2πv) cycles/m,
/// S(ω) = S_t(ω) [[1, ρ(n)], [ρ(n), 1]]        (component 0 = left, 1 = right; two-sided, rad/s)
/// ```
/// The bounce combination (L + R)/2 has the density S_t(1 + ρ)/2, the roll combination (L − R)/2 the
/// density S_t(1 − ρ)/2 (Dodds & Robson, "The description of road surface roughness", J. Sound Vib. 31,
/// 1973).
///
/// # Errors
/// [`TwoTracks::new`]: a spectrum that is not spatial, a speed that is not positive (from [`AtSpeed`]).
///
/// # Examples
/// ```
/// use stochvib::coherence::{IsotropicCoherence, SpectralMatrix, TwoTracks};
/// use stochvib::spectrum::{IsoClass, PowerLaw};
/// use std::sync::Arc;
/// let road = Arc::new(PowerLaw::iso_class(IsoClass::C).unwrap());
/// let t = TwoTracks::new(road, Arc::new(IsotropicCoherence::new(1.5, 2.0).unwrap()), 20.0).unwrap();
/// let s = t.matrix(2.0 * std::f64::consts::PI * 20.0 * 0.1); // n = 0.1 cycles/m
/// assert!(s[(0, 1)].re < s[(0, 0)].re && s[(0, 1)].re > 0.0);
/// ```
#[derive(Debug, Clone)]
pub struct TwoTracks {
    temporal: Arc<dyn Spectrum>,
    coherence: Arc<dyn Coherence>,
    speed: f64,
}

impl TwoTracks {
    /// Two tracks of the spatial density `road` with coherence `coherence`, at `speed_m_s`.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(road: Arc<dyn Spectrum>, coherence: Arc<dyn Coherence>, speed_m_s: f64) -> Result<Self> {
        let temporal: Arc<dyn Spectrum> = Arc::new(AtSpeed::new(road, speed_m_s)?);
        Ok(TwoTracks {
            temporal,
            coherence,
            speed: speed_m_s,
        })
    }

    /// The speed v in m/s.
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// The coherence model.
    pub fn coherence(&self) -> &Arc<dyn Coherence> {
        &self.coherence
    }

    /// The coherence amplitude ρ at ω (rad/s): ρ(n), n = |ω|/(2πv).
    pub fn rho(&self, omega: f64) -> f64 {
        self.coherence
            .coherence_amplitude(omega.abs() / (2.0 * PI * self.speed))
    }
}

impl SpectralMatrix for TwoTracks {
    fn describe(&self) -> String {
        format!(
            "two tracks of {} with coherence {}",
            self.temporal.describe(),
            self.coherence.describe()
        )
    }

    fn n_components(&self) -> usize {
        2
    }

    fn component_name(&self, c: usize) -> String {
        match c {
            0 => "left".into(),
            1 => "right".into(),
            _ => format!("component {c}"),
        }
    }

    fn component(&self, _c: usize) -> Arc<dyn Spectrum> {
        self.temporal.clone()
    }

    fn matrix(&self, omega: f64) -> DMatrix<Complex<f64>> {
        let s = self.temporal.density(omega);
        let x = Complex::new(self.rho(omega) * s, 0.0);
        DMatrix::from_row_slice(2, 2, &[Complex::new(s, 0.0), x, x, Complex::new(s, 0.0)])
    }

    /// For a constant coherence ρ₀ the sum and difference processes s = (L + R)/2, d = (L − R)/2 are
    /// uncorrelated with densities S(1 + ρ₀)/2 and S(1 − ρ₀)/2, and L = s + d, R = s − d (see the type's
    /// formula; derivation in `docs/models.md`).
    fn independent_parts(&self) -> Option<Vec<(f64, Vec<f64>)>> {
        let rho = self.coherence.constant_amplitude()?;
        Some(vec![
            ((1.0 + rho) / 2.0, vec![1.0, 1.0]),
            ((1.0 - rho) / 2.0, vec![1.0, -1.0]),
        ])
    }

    fn coherence_matrix(&self, omega: f64) -> DMatrix<Complex<f64>> {
        let r = Complex::new(self.rho(omega), 0.0);
        let one = Complex::new(1.0, 0.0);
        DMatrix::from_row_slice(2, 2, &[one, r, r, one])
    }
}
