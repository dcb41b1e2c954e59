//! Every spectral method on one problem, and the spread of their lives.

use super::{
    Dirlik, NarrowBand, SpectralMethod, SpectralMoments, TovoBenasciutti, TovoBenasciuttiVariant, WirschingLight,
    ZhaoBaker, ZhaoBakerVariant,
};
use crate::error::Result;
use crate::fatigue::SnCurve;

/// The spectral methods of this crate, by name (each variant with its default parameter set).
///
/// # Formula
/// See each method's type: [`NarrowBand`], [`WirschingLight`], [`Dirlik`], [`TovoBenasciutti`]
/// (2005 b_app), [`ZhaoBaker`] (general fit).
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::fatigue::SpectralMethodKind;
/// assert_eq!(SpectralMethodKind::ALL.len(), 5);
/// assert_eq!(SpectralMethodKind::Dirlik.method().name(), "Dirlik (1985)");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SpectralMethodKind {
    /// [`NarrowBand`].
    NarrowBand,
    /// [`WirschingLight`].
    WirschingLight,
    /// [`Dirlik`].
    Dirlik,
    /// [`TovoBenasciutti`] with the 2005 weighting factor.
    TovoBenasciutti,
    /// [`ZhaoBaker`], general parameter set.
    ZhaoBaker,
}

impl SpectralMethodKind {
    /// Every method, in the order above.
    pub const ALL: [SpectralMethodKind; 5] = [
        SpectralMethodKind::NarrowBand,
        SpectralMethodKind::WirschingLight,
        SpectralMethodKind::Dirlik,
        SpectralMethodKind::TovoBenasciutti,
        SpectralMethodKind::ZhaoBaker,
    ];

    /// The method object.
    pub fn method(self) -> Box<dyn SpectralMethod> {
        match self {
            SpectralMethodKind::NarrowBand => Box::new(NarrowBand),
            SpectralMethodKind::WirschingLight => Box::new(WirschingLight),
            SpectralMethodKind::Dirlik => Box::new(Dirlik),
            SpectralMethodKind::TovoBenasciutti => {
                Box::new(TovoBenasciutti::new(TovoBenasciuttiVariant::BenasciuttiTovo2005))
            }
            SpectralMethodKind::ZhaoBaker => Box::new(ZhaoBaker::new(ZhaoBakerVariant::General)),
        }
    }
}

/// One method's estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodEstimate {
    /// Which method.
    pub kind: SpectralMethodKind,
    /// Its name with the reference.
    pub name: &'static str,
    /// Expected damage per second (1/s).
    pub damage_rate: f64,
    /// Expected life 1/damage_rate (s).
    pub life: f64,
}

/// The estimates of every method on one problem.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodComparison {
    /// One estimate per method, in [`SpectralMethodKind::ALL`] order.
    pub estimates: Vec<MethodEstimate>,
}

impl MethodComparison {
    /// The estimate of one method, if present.
    pub fn get(&self, kind: SpectralMethodKind) -> Option<&MethodEstimate> {
        self.estimates.iter().find(|e| e.kind == kind)
    }

    /// Shortest and longest life (s).
    pub fn life_range(&self) -> (f64, f64) {
        let lo = self.estimates.iter().map(|e| e.life).fold(f64::INFINITY, f64::min);
        let hi = self.estimates.iter().map(|e| e.life).fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    }

    /// Spread: longest life / shortest life (≥ 1).
    pub fn spread(&self) -> f64 {
        let (lo, hi) = self.life_range();
        hi / lo
    }
}

/// Runs every method of [`SpectralMethodKind::ALL`] on the same moments and S–N curve.
///
/// # Formula
/// life_i = 1/(D/T)_i; spread = max_i life_i / min_i life_i.
///
/// # Errors
/// The first error of a method (none of the default methods fails on valid inputs).
///
/// # Examples
/// ```
/// use stochvib::fatigue::{compare_methods, SnCurve, SpectralMethodKind, SpectralMoments};
/// let m = SpectralMoments::from_one_sided_hz(|_| 1.0, 50.0, 150.0, &[]).unwrap();
/// let sn = SnCurve { k: 4.0, c: 1e10, endurance_limit: None }.build().unwrap();
/// let cmp = compare_methods(&m, &sn).unwrap();
/// // The narrow-band life is the shortest (it is conservative).
/// let nb = cmp.get(SpectralMethodKind::NarrowBand).unwrap().life;
/// assert_eq!(cmp.life_range().0, nb);
/// assert!(cmp.spread() >= 1.0);
/// ```
pub fn compare_methods(moments: &SpectralMoments, sn: &SnCurve) -> Result<MethodComparison> {
    let mut estimates = Vec::with_capacity(SpectralMethodKind::ALL.len());
    for kind in SpectralMethodKind::ALL {
        let m = kind.method();
        let damage_rate = m.damage_rate(moments, sn)?;
        estimates.push(MethodEstimate {
            kind,
            name: m.name(),
            damage_rate,
            life: if damage_rate > 0.0 {
                1.0 / damage_rate
            } else {
                f64::INFINITY
            },
        });
    }
    Ok(MethodComparison { estimates })
}
