//! The empirical coherence model of Ammon & Bormann for two parallel road tracks, with literature
//! parameter sets.

use super::{Coherence, CoherenceKind};
use crate::error::{require_positive, Result};
use crate::spectrum::{IsoBound, IsoClass, PowerLaw, PowerLawParameters, ISO_N0};
use std::f64::consts::PI;

/// The empirical two-track coherence model of Ammon & Bormann (1991; we could not obtain the paper and
/// give the form and parameters as used by later work, cited below).
///
/// # Formula
/// ```text
/// f(Ω) = [1 + (Ω B^a / Ω_p)^w]^{−p},    Ω = 2πn  (rad/m, n in cycles/m),   B track width in m
/// ```
/// Units: Ω_p in (rad/m)·m^a, so that Ω B^a/Ω_p is dimensionless; a, w, p dimensionless. f(0) = 1 and
/// f decreases monotonically to 0.
///
/// **Which quantity f is.** The original paper was not available to us; the constructor therefore takes
/// the [`CoherenceKind`] of f explicitly. The evidence we have: the study "Model of coherence function of
/// road unevenness in parallel tracks for vehicle simulation" (3492 measured road records) fitted this
/// model to the mean unbiased **squared** coherence γ² and found it the best of 11 models; and the
/// coherence estimated from measured tracks is conventionally the magnitude-squared coherence
/// |G_LR|²/(G_LL G_RR) (Bendat & Piersol, "Random Data", 4th ed. 2010, ch. 9). The presets of
/// [`AmmonBormannRoad`] are therefore taken as γ² ([`CoherenceKind::SquaredCoherence`]): ρ = √f. The
/// simulator Project Chrono, whose preset table we reproduce, calls f "the measured coherence function"
/// without saying which, and uses it as a linear blending weight of the two tracks' phases, which gives
/// neither ρ = f nor γ² = f.
///
/// # Errors
/// [`AmmonBormannParameters::build`] rejects non-positive or non-finite B, Ω_p, w, p and negative or non-finite a.
///
/// # Examples
/// ```
/// use stochvib::coherence::{AmmonBormann, AmmonBormannParameters, AmmonBormannRoad, Coherence, CoherenceKind};
/// // ISO class C preset (Ω_p = 3.0, p = 1.3, a = 1, w = 2) for a 2 m track width: at Ω = 1.5 rad/m,
/// // Ω B/Ω_p = 1 and f = 2^{−1.3}
/// let c = AmmonBormann::preset(AmmonBormannRoad::IsoC, 2.0).unwrap();
/// let n = 1.5 / (2.0 * std::f64::consts::PI);
/// assert!((c.formula_value(n) - 2f64.powf(-1.3)).abs() < 1e-15);
/// assert!((c.squared_coherence(n) - 2f64.powf(-1.3)).abs() < 1e-15);   // presets are γ²
/// // the same formula declared as an amplitude gives ρ = f:
/// let rho = AmmonBormannParameters {
///     track_width_m: 2.0,
///     omega_p: 3.0,
///     w: 2.0,
///     p: 1.3,
///     a: 1.0,
///     kind: CoherenceKind::CoherenceAmplitude,
/// }
/// .build()
/// .unwrap();
/// assert!((rho.coherence_amplitude(n) - 2f64.powf(-1.3)).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct AmmonBormann {
    track_width: f64,
    omega_p: f64,
    w: f64,
    p: f64,
    a: f64,
    kind: CoherenceKind,
    label: String,
}

/// The parameters of an [`AmmonBormann`] coherence as named fields; [`AmmonBormannParameters::build`]
/// checks them and gives the model.
///
/// # Formula
/// f(2πn) = [1 + (2πn B^a/Ω_p)^w]^{−p}, the amplitude ρ or the squared coherence γ² as `kind` says (see
/// [`AmmonBormann`]).
///
/// # Errors
/// [`AmmonBormannParameters::build`] rejects non-positive or non-finite B, Ω_p, w, p and negative or
/// non-finite a.
///
/// # Examples
/// ```
/// use stochvib::coherence::{AmmonBormannParameters, Coherence, CoherenceKind};
/// let rho = AmmonBormannParameters {
///     track_width_m: 2.0,
///     omega_p: 3.0,
///     w: 2.0,
///     p: 1.3,
///     a: 1.0,
///     kind: CoherenceKind::CoherenceAmplitude,
/// }
/// .build()
/// .unwrap();
/// assert_eq!(rho.coherence_amplitude(0.0), 1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AmmonBormannParameters {
    /// B, the track width, m.
    pub track_width_m: f64,
    /// Ω_p, (rad/m)·m^a.
    pub omega_p: f64,
    /// w, the exponent of the frequency (no unit).
    pub w: f64,
    /// p, the outer exponent (no unit).
    pub p: f64,
    /// a, the exponent of the track width (no unit).
    pub a: f64,
    /// Whether the formula's value is the amplitude ρ or the squared coherence γ².
    pub kind: CoherenceKind,
}

impl AmmonBormannParameters {
    /// The model of these parameters, checked.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<AmmonBormann> {
        let AmmonBormannParameters {
            track_width_m,
            omega_p,
            w,
            p,
            a,
            kind,
        } = self;
        require_positive("track_width", track_width_m)?;
        require_positive("omega_p", omega_p)?;
        require_positive("w", w)?;
        require_positive("p", p)?;
        crate::error::require_non_negative("a", a)?;
        Ok(AmmonBormann {
            track_width: track_width_m,
            omega_p,
            w,
            p,
            a,
            kind,
            label: "Ammon & Bormann coherence".into(),
        })
    }
}

/// Published parameter sets of the [`AmmonBormann`] model, as tabulated in Project Chrono's
/// `RandomSurfaceTerrain` (R. Gericke, 2020; it names Löhe & Zehelein 2005, "Modellierung und
/// Parametrierung stochastischer Fahrbahnunebenheiten mit Hub-, Wank-, Nick- und Verspannanteil", and
/// Mitschke & Wallentowitz, "Dynamik der Kraftfahrzeuge", 2014, as its sources). Chrono uses the road's
/// waviness as the exponent w of the coherence.
///
/// | preset | Φ_h(Ω₀) m³ | w | Ω_p | p | a |
/// |---|---|---|---|---|---|
/// | `IsoA` … `IsoE` | ISO class | 2 | 8.5, 5.3, 3.0, 1.6, 0.8 | 3.5, 2.2, 1.3, 0.8, 0.5 | 1 |
/// | `MajorRoadConcrete` | 3.7e-6 | 2.0 | 0.96 | 0.47 | 0.96 |
/// | `MajorRoadAsphalticConcrete` | 2.6e-6 | 2.1 | 0.73 | 0.45 | 0.60 |
/// | `MainRoadAsphalticConcreteOnPavement` | 2.6e-6 | 2.3 | 1.53 | 0.45 | 0.56 |
/// | `MainRoadAsphalticConcrete` | 5.0e-6 | 2.2 | 3.3 | 0.88 | 0.97 |
/// | `TrackTiledConcretePavement` | 10e-6 | 2.0 | 0.99 | 0.50 | 0.94 |
///
/// Φ_h(Ω₀) is the one-sided density in Ω (rad/m) at Ω₀ = 1 rad/m, Φ_h(Ω) = Φ_h(Ω₀)(Ω/Ω₀)^{−w}
/// (German convention); [`AmmonBormannRoad::profile_spectrum`] converts it to ISO 8608's G_d.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AmmonBormannRoad {
    /// ISO 8608 class A, Ω_p = 8.5, p = 3.5.
    IsoA,
    /// ISO 8608 class B, Ω_p = 5.3, p = 2.2.
    IsoB,
    /// ISO 8608 class C, Ω_p = 3.0, p = 1.3.
    IsoC,
    /// ISO 8608 class D, Ω_p = 1.6, p = 0.8.
    IsoD,
    /// ISO 8608 class E, Ω_p = 0.8, p = 0.5.
    IsoE,
    /// Major road, concrete.
    MajorRoadConcrete,
    /// Major road, asphaltic concrete.
    MajorRoadAsphalticConcrete,
    /// Main road, asphaltic concrete on pavement.
    MainRoadAsphalticConcreteOnPavement,
    /// Main road, asphaltic concrete.
    MainRoadAsphalticConcrete,
    /// Track, tiled concrete pavement.
    TrackTiledConcretePavement,
}

impl AmmonBormannRoad {
    /// All presets.
    pub const ALL: [AmmonBormannRoad; 10] = [
        AmmonBormannRoad::IsoA,
        AmmonBormannRoad::IsoB,
        AmmonBormannRoad::IsoC,
        AmmonBormannRoad::IsoD,
        AmmonBormannRoad::IsoE,
        AmmonBormannRoad::MajorRoadConcrete,
        AmmonBormannRoad::MajorRoadAsphalticConcrete,
        AmmonBormannRoad::MainRoadAsphalticConcreteOnPavement,
        AmmonBormannRoad::MainRoadAsphalticConcrete,
        AmmonBormannRoad::TrackTiledConcretePavement,
    ];

    /// (Φ_h(Ω₀) in m³ or `None` for the ISO classes, w, Ω_p, p, a) from the table of the type docs.
    fn row(self) -> (Option<f64>, f64, f64, f64, f64) {
        use AmmonBormannRoad::*;
        match self {
            IsoA => (None, 2.0, 8.5, 3.5, 1.0),
            IsoB => (None, 2.0, 5.3, 2.2, 1.0),
            IsoC => (None, 2.0, 3.0, 1.3, 1.0),
            IsoD => (None, 2.0, 1.6, 0.8, 1.0),
            IsoE => (None, 2.0, 0.8, 0.5, 1.0),
            MajorRoadConcrete => (Some(3.7e-6), 2.0, 0.96, 0.47, 0.96),
            MajorRoadAsphalticConcrete => (Some(2.6e-6), 2.1, 0.73, 0.45, 0.6),
            MainRoadAsphalticConcreteOnPavement => (Some(2.6e-6), 2.3, 1.53, 0.45, 0.56),
            MainRoadAsphalticConcrete => (Some(5e-6), 2.2, 3.3, 0.88, 0.97),
            TrackTiledConcretePavement => (Some(10e-6), 2.0, 0.99, 0.5, 0.94),
        }
    }

    fn iso_class(self) -> Option<IsoClass> {
        match self {
            AmmonBormannRoad::IsoA => Some(IsoClass::A),
            AmmonBormannRoad::IsoB => Some(IsoClass::B),
            AmmonBormannRoad::IsoC => Some(IsoClass::C),
            AmmonBormannRoad::IsoD => Some(IsoClass::D),
            AmmonBormannRoad::IsoE => Some(IsoClass::E),
            _ => None,
        }
    }

    /// The single-track profile spectrum that goes with the preset, in ISO 8608 form, optionally
    /// band-limited (cycles/m).
    ///
    /// # Formula
    /// ISO presets: the class's geometric mean G_d(n₀) with w = 2. Literature roads: Φ_h(Ω) one-sided in
    /// Ω (∫₀^∞ Φ_h dΩ = σ²) and G_d(n) one-sided in n (∫₀^∞ G_d dn = σ²) give G_d(n) = 2π Φ_h(2πn), so
    /// ```text
    /// G_d(n₀) = 2π Φ_h(Ω₀) (2π n₀/Ω₀)^{−w},   Ω₀ = 1 rad/m,   n₀ = 0.1 cycles/m
    /// ```
    ///
    /// # Errors
    /// As [`PowerLawParameters::build`](crate::spectrum::PowerLawParameters::build) for the band.
    ///
    /// # Examples
    /// ```
    /// use stochvib::coherence::AmmonBormannRoad;
    /// let s = AmmonBormannRoad::MajorRoadConcrete.profile_spectrum(None).unwrap();
    /// let g0 = 2.0 * std::f64::consts::PI * 3.7e-6 * (0.2 * std::f64::consts::PI).powi(-2);
    /// assert!((s.one_sided_cyclic(0.1) - g0).abs() < 1e-18);
    /// ```
    pub fn profile_spectrum(self, band: Option<(f64, f64)>) -> Result<PowerLaw> {
        if let Some(class) = self.iso_class() {
            return PowerLaw::iso8608(class, IsoBound::GeometricMean, band);
        }
        let (phi0, w, ..) = self.row();
        let phi0 = phi0.unwrap_or(f64::NAN);
        let g0 = 2.0 * PI * phi0 * (2.0 * PI * ISO_N0).powf(-w);
        PowerLawParameters {
            g0,
            n0: ISO_N0,
            waviness: w,
            band,
            domain: crate::spectrum::Domain::Spatial,
        }
        .build()
    }
}

impl AmmonBormann {
    /// A preset of [`AmmonBormannRoad`] for track width `track_width_m` (m), taken as the squared
    /// coherence (see the type docs).
    ///
    /// # Errors
    /// A non-positive or non-finite track width.
    pub fn preset(road: AmmonBormannRoad, track_width_m: f64) -> Result<Self> {
        let (_, w, omega_p, p, a) = road.row();
        let mut m = AmmonBormannParameters {
            track_width_m,
            omega_p,
            w,
            p,
            a,
            kind: CoherenceKind::SquaredCoherence,
        }
        .build()?;
        m.label = format!("Ammon & Bormann coherence, preset {road:?}");
        Ok(m)
    }

    /// The value of the formula f(2πn) = [1 + (2πn B^a/Ω_p)^w]^{−p} (of kind [`AmmonBormann::kind`]).
    pub fn formula_value(&self, n: f64) -> f64 {
        if !n.is_finite() {
            return f64::NAN;
        }
        let u = 2.0 * PI * n.abs() * self.track_width.powf(self.a) / self.omega_p;
        (1.0 + u.powf(self.w)).powf(-self.p)
    }

    /// Whether [`AmmonBormann::formula_value`] is ρ or γ².
    pub fn kind(&self) -> CoherenceKind {
        self.kind
    }
}

impl Coherence for AmmonBormann {
    fn describe(&self) -> String {
        format!(
            "{} [1 + (Ω B^a/Ω_p)^w]^-p taken as {}, B = {} m, Ω_p = {}, w = {}, p = {}, a = {}",
            self.label,
            self.kind,
            crate::numbers::num(self.track_width),
            crate::numbers::num(self.omega_p),
            crate::numbers::num(self.w),
            crate::numbers::num(self.p),
            crate::numbers::num(self.a)
        )
    }

    fn coherence_amplitude(&self, n: f64) -> f64 {
        self.kind.to_amplitude(self.formula_value(n))
    }

    fn track_width(&self) -> Option<f64> {
        Some(self.track_width)
    }
}
