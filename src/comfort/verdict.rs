//! Verdicts on a daily exposure: Directive 2002/44/EC action and limit values, the ISO 2631-1 Annex B
//! health guidance caution zone, and the ISO 2631-1 Annex C comfort reactions.

use super::exposure::REFERENCE_DURATION_S;
use crate::error::{Error, Result};

/// Daily exposure action and limit values for whole-body vibration.
///
/// # Formula
/// Directive 2002/44/EC, Article 3(2): limit 1.15 m/s² A(8) or, at the choice of the Member State, a VDV
/// of 21 m/s^1.75; action 0.5 m/s² A(8) or a VDV of 9.1 m/s^1.75. A value **exceeds** a threshold when it
/// is strictly greater ("once the exposure action value is exceeded", Art. 5(2)).
///
/// # Errors
/// None (constants).
///
/// # Examples
/// ```
/// use stochvib::comfort::DirectiveLimits;
/// let d = DirectiveLimits::WHOLE_BODY;
/// assert_eq!((d.a8_action, d.a8_limit, d.vdv_action, d.vdv_limit), (0.5, 1.15, 9.1, 21.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DirectiveLimits {
    /// Daily exposure action value, m/s² A(8).
    pub a8_action: f64,
    /// Daily exposure limit value, m/s² A(8).
    pub a8_limit: f64,
    /// Daily exposure action value as a VDV, m/s^1.75.
    pub vdv_action: f64,
    /// Daily exposure limit value as a VDV, m/s^1.75.
    pub vdv_limit: f64,
}

impl DirectiveLimits {
    /// Whole-body values of Directive 2002/44/EC, Article 3(2).
    pub const WHOLE_BODY: DirectiveLimits = DirectiveLimits {
        a8_action: 0.5,
        a8_limit: 1.15,
        vdv_action: 9.1,
        vdv_limit: 21.0,
    };
}

/// The health guidance caution zone of ISO 2631-1:1997 Annex B (seated persons, health).
///
/// # Formula
/// Annex B gives two acceleration–duration relations and draws a zone for each in Figure B.1:
///
/// ```text
/// (B.1)  a_w1 · T1^(1/2) = a_w2 · T2^(1/2)     (equal energy: the r.m.s. zone scales as T^(−1/2))
/// (B.2)  a_w1 · T1^(1/4) = a_w2 · T2^(1/4)     (the VDV zone: VDV ∝ a_w T^(1/4) for a given signal)
/// ```
/// Zone (B.1) is bounded by a_w·T^(1/2) = 3 m/s²·(10 min)^(1/2) and 6 m/s²·(10 min)^(1/2) (the dashed
/// lines of Figure B.1 run from 3 and 6 m/s² at 10 min down to 0.25 and 0.5 m/s² at 24 h), i.e. in terms
/// of the daily exposure A(8) = a_w√(T/8 h):
/// A(8)_lower = 3/√48 = 0.433 m/s², A(8)_upper = 6/√48 = 0.866 m/s² (often quoted rounded as 0.45–0.9).
/// Zone (B.2) is stated as VDV = 8.5 m/s^1.75 to 17 m/s^1.75 (B.3.1). Below the zone "health effects
/// have not been clearly documented and/or objectively observed", within it "caution with respect to
/// potential health risks is indicated", above it "health risks are likely"; the guidance is based mainly
/// on 4 h to 8 h exposures.
///
/// The (B.1) values are read from Figure B.1, the (B.2) values from the text of B.3.1; check them against
/// the printed standard before using them for compliance work. They are fields, so a caller may
/// substitute its own (e.g. the rounded 0.45–0.9 m/s²).
///
/// # Errors
/// [`HealthGuidanceZone::a_w_bounds`] rejects a non-positive duration.
///
/// # Examples
/// ```
/// use stochvib::comfort::HealthGuidanceZone;
/// let z = HealthGuidanceZone::ISO_2631_1;
/// // at 10 min the (B.1) zone is 3 to 6 m/s²
/// let (lo, hi) = z.a_w_bounds(600.0).unwrap();
/// assert!((lo - 3.0).abs() < 1e-12 && (hi - 6.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HealthGuidanceZone {
    /// Lower boundary of zone (B.1) expressed as A(8), m/s².
    pub a8_lower: f64,
    /// Upper boundary of zone (B.1) expressed as A(8), m/s².
    pub a8_upper: f64,
    /// Lower boundary of zone (B.2) as a VDV, m/s^1.75.
    pub vdv_lower: f64,
    /// Upper boundary of zone (B.2) as a VDV, m/s^1.75.
    pub vdv_upper: f64,
}

impl HealthGuidanceZone {
    /// ISO 2631-1:1997 Annex B (see the type's `# Formula`): A(8) 3/√48 to 6/√48 m/s², VDV 8.5 to
    /// 17 m/s^1.75.
    pub const ISO_2631_1: HealthGuidanceZone = HealthGuidanceZone {
        // 3/√48 and 6/√48 (√48 = 6.928203230275509)
        a8_lower: 0.433_012_701_892_219_3,
        a8_upper: 0.866_025_403_784_438_6,
        vdv_lower: 8.5,
        vdv_upper: 17.0,
    };

    /// The (B.1) zone boundaries as weighted r.m.s. values for an exposure of duration T.
    ///
    /// # Formula
    /// a_w,bound(T) = A(8)_bound · √(T₀/T), T₀ = 8 h.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `duration_s` when not finite and > 0.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::HealthGuidanceZone;
    /// let (lo, hi) = HealthGuidanceZone::ISO_2631_1.a_w_bounds(8.0 * 3600.0).unwrap();
    /// assert!((lo - 0.433).abs() < 1e-3 && (hi - 0.866).abs() < 1e-3);
    /// ```
    pub fn a_w_bounds(&self, duration_s: f64) -> Result<(f64, f64)> {
        if !(duration_s.is_finite() && duration_s > 0.0) {
            return Err(Error::invalid(
                "duration_s",
                duration_s,
                "a duration must be finite and > 0 s",
            ));
        }
        let s = (REFERENCE_DURATION_S / duration_s).sqrt();
        Ok((self.a8_lower * s, self.a8_upper * s))
    }
}

/// Position of a value relative to a zone [lower, upper].
///
/// # Formula
/// Below: value < lower; Within: lower ≤ value ≤ upper; Above: value > upper.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::{ExposureVerdict, ZonePosition};
/// assert_eq!(ExposureVerdict::assess(0.3, None, None).unwrap().zone_a8.position, ZonePosition::Below);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum ZonePosition {
    /// value < lower.
    Below,
    /// lower ≤ value ≤ upper.
    Within,
    /// value > upper.
    Above,
}

/// A value compared with an action value and a limit value.
///
/// # Formula
/// exceeds_action = value > action; exceeds_limit = value > limit.
///
/// # Errors
/// None (part of [`ExposureVerdict`]).
///
/// # Examples
/// ```
/// use stochvib::comfort::ExposureVerdict;
/// let c = ExposureVerdict::assess(0.8, None, None).unwrap().directive_a8;
/// assert!(c.exceeds_action && !c.exceeds_limit && c.limit == 1.15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LimitCheck {
    /// The value.
    pub value: f64,
    /// The action value.
    pub action: f64,
    /// The limit value.
    pub limit: f64,
    /// value > action.
    pub exceeds_action: bool,
    /// value > limit.
    pub exceeds_limit: bool,
}

impl LimitCheck {
    fn new(value: f64, action: f64, limit: f64) -> Self {
        LimitCheck {
            value,
            action,
            limit,
            exceeds_action: value > action,
            exceeds_limit: value > limit,
        }
    }
}

/// A value compared with a zone.
///
/// # Formula
/// See [`ZonePosition`].
///
/// # Errors
/// None (part of [`ExposureVerdict`]).
///
/// # Examples
/// ```
/// use stochvib::comfort::{ExposureVerdict, ZonePosition};
/// let z = ExposureVerdict::assess(0.5, Some(20.0), None).unwrap().zone_vdv.unwrap();
/// assert_eq!((z.lower, z.upper, z.position), (8.5, 17.0, ZonePosition::Above));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ZoneCheck {
    /// The value.
    pub value: f64,
    /// Lower boundary.
    pub lower: f64,
    /// Upper boundary.
    pub upper: f64,
    /// Where the value lies.
    pub position: ZonePosition,
}

impl ZoneCheck {
    fn new(value: f64, lower: f64, upper: f64) -> Self {
        let position = if value < lower {
            ZonePosition::Below
        } else if value > upper {
            ZonePosition::Above
        } else {
            ZonePosition::Within
        };
        ZoneCheck {
            value,
            lower,
            upper,
            position,
        }
    }
}

/// The likely reactions to a vibration total value in public transport (ISO 2631-1:1997, C.2.3).
///
/// # Formula
/// | reaction               | overall vibration total value a_v, m/s² |
/// |------------------------|------------------------------------------|
/// | not uncomfortable      | less than 0.315                          |
/// | a little uncomfortable | 0.315 to 0.63                            |
/// | fairly uncomfortable   | 0.5 to 1                                 |
/// | uncomfortable          | 0.8 to 1.6                               |
/// | very uncomfortable     | 1.25 to 2.5                              |
/// | extremely uncomfortable| greater than 2                           |
///
/// The ranges overlap; every reaction whose range contains a_v applies ("x to y": x ≤ a_v ≤ y; "less
/// than x": a_v < x; "greater than y": a_v > y).
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::ComfortReaction;
/// assert_eq!(ComfortReaction::FairlyUncomfortable.range(), (0.5, 1.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum ComfortReaction {
    /// a_v < 0.315 m/s².
    NotUncomfortable,
    /// 0.315 ≤ a_v ≤ 0.63 m/s².
    ALittleUncomfortable,
    /// 0.5 ≤ a_v ≤ 1 m/s².
    FairlyUncomfortable,
    /// 0.8 ≤ a_v ≤ 1.6 m/s².
    Uncomfortable,
    /// 1.25 ≤ a_v ≤ 2.5 m/s².
    VeryUncomfortable,
    /// a_v > 2 m/s².
    ExtremelyUncomfortable,
}

impl ComfortReaction {
    /// All reactions, mildest first.
    pub const ALL: [ComfortReaction; 6] = [
        ComfortReaction::NotUncomfortable,
        ComfortReaction::ALittleUncomfortable,
        ComfortReaction::FairlyUncomfortable,
        ComfortReaction::Uncomfortable,
        ComfortReaction::VeryUncomfortable,
        ComfortReaction::ExtremelyUncomfortable,
    ];

    /// The range (lower, upper) in m/s² (0 and ∞ for the open ends).
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::ComfortReaction;
    /// assert_eq!(ComfortReaction::ExtremelyUncomfortable.range(), (2.0, f64::INFINITY));
    /// ```
    pub fn range(self) -> (f64, f64) {
        match self {
            ComfortReaction::NotUncomfortable => (0.0, 0.315),
            ComfortReaction::ALittleUncomfortable => (0.315, 0.63),
            ComfortReaction::FairlyUncomfortable => (0.5, 1.0),
            ComfortReaction::Uncomfortable => (0.8, 1.6),
            ComfortReaction::VeryUncomfortable => (1.25, 2.5),
            ComfortReaction::ExtremelyUncomfortable => (2.0, f64::INFINITY),
        }
    }

    /// The wording of the standard, e.g. "a little uncomfortable".
    ///
    /// # Formula
    /// None.
    ///
    /// # Errors
    /// None.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::ComfortReaction;
    /// assert_eq!(ComfortReaction::VeryUncomfortable.label(), "very uncomfortable");
    /// ```
    pub fn label(self) -> &'static str {
        match self {
            ComfortReaction::NotUncomfortable => "not uncomfortable",
            ComfortReaction::ALittleUncomfortable => "a little uncomfortable",
            ComfortReaction::FairlyUncomfortable => "fairly uncomfortable",
            ComfortReaction::Uncomfortable => "uncomfortable",
            ComfortReaction::VeryUncomfortable => "very uncomfortable",
            ComfortReaction::ExtremelyUncomfortable => "extremely uncomfortable",
        }
    }

    fn contains(self, a_v: f64) -> bool {
        let (lo, hi) = self.range();
        match self {
            ComfortReaction::NotUncomfortable => a_v < hi,
            ComfortReaction::ExtremelyUncomfortable => a_v > lo,
            _ => lo <= a_v && a_v <= hi,
        }
    }
}

/// Every comfort reaction of ISO 2631-1:1997 C.2.3 whose range contains a_v (mildest first).
///
/// # Formula
/// See [`ComfortReaction`].
///
/// # Errors
/// [`Error::InvalidParameter`] naming `a_v` when not finite and ≥ 0.
///
/// # Examples
/// ```
/// use stochvib::comfort::{comfort_reactions, ComfortReaction::*};
/// assert_eq!(comfort_reactions(0.9).unwrap(), vec![FairlyUncomfortable, Uncomfortable]);
/// ```
pub fn comfort_reactions(a_v: f64) -> Result<Vec<ComfortReaction>> {
    if !(a_v.is_finite() && a_v >= 0.0) {
        return Err(Error::invalid("a_v", a_v, "must be finite and >= 0 m/s^2"));
    }
    Ok(ComfortReaction::ALL.into_iter().filter(|r| r.contains(a_v)).collect())
}

/// The verdict on one daily exposure: health against Directive 2002/44/EC and ISO 2631-1 Annex B, and
/// comfort against ISO 2631-1 Annex C, with the numbers behind it.
///
/// # Formula
/// * `directive_a8`: A(8) against 0.5 (action) and 1.15 m/s² (limit); `directive_vdv`: the daily VDV
///   against 9.1 and 21 m/s^1.75 ([`DirectiveLimits`]).
/// * `below_action`: no given value exceeds its action value; `above_limit`: some given value exceeds its
///   limit value (strictly greater, as in the Directive).
/// * `zone_a8`: A(8) against the (B.1) caution zone; `zone_vdv`: the VDV against the (B.2) zone
///   ([`HealthGuidanceZone`]).
/// * `comfort_reactions`: [`comfort_reactions`] of the overall comfort total value a_v, when given.
///
/// The A(8) (and VDV) given are those of the dominant axis with the health factors k applied
/// (1.4 a_wx, 1.4 a_wy, a_wz), see [`crate::comfort::vector_sum`] and
/// [`crate::comfort::daily_exposure_a8`]; a_v is the comfort-weighted total value (m/s²).
///
/// # Errors
/// [`ExposureVerdict::assess`] rejects non-finite or negative values (naming `a8`, `vdv` or
/// `comfort_a_v`).
///
/// # Examples
/// ```
/// use stochvib::comfort::{ExposureVerdict, ZonePosition};
/// let v = ExposureVerdict::assess(0.6, Some(12.0), Some(0.9)).unwrap();
/// assert!(!v.below_action && !v.above_limit);
/// assert_eq!(v.zone_a8.position, ZonePosition::Within);
/// assert_eq!(v.comfort_reactions.len(), 2);
/// let json = serde_json::to_string(&v).unwrap();
/// assert!(json.contains("\"exceeds_action\":true"));
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ExposureVerdict {
    /// Daily exposure A(8), m/s².
    pub a8: f64,
    /// Daily total VDV, m/s^1.75, if given.
    pub vdv: Option<f64>,
    /// Overall comfort vibration total value a_v, m/s², if given.
    pub comfort_a_v: Option<f64>,
    /// A(8) against the Directive's action and limit values.
    pub directive_a8: LimitCheck,
    /// VDV against the Directive's action and limit values.
    pub directive_vdv: Option<LimitCheck>,
    /// No given value exceeds its action value.
    pub below_action: bool,
    /// Some given value exceeds its limit value.
    pub above_limit: bool,
    /// A(8) against the ISO 2631-1 (B.1) caution zone.
    pub zone_a8: ZoneCheck,
    /// VDV against the ISO 2631-1 (B.2) caution zone.
    pub zone_vdv: Option<ZoneCheck>,
    /// ISO 2631-1 Annex C reactions to a_v (empty when a_v is not given).
    pub comfort_reactions: Vec<ComfortReaction>,
}

impl ExposureVerdict {
    /// The verdict with the Directive's whole-body values and the ISO 2631-1 Annex B zone.
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `a8`, `vdv` or `comfort_a_v` when not finite and ≥ 0.
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::ExposureVerdict;
    /// let v = ExposureVerdict::assess(1.2, None, None).unwrap();
    /// assert!(v.above_limit && v.directive_vdv.is_none());
    /// ```
    pub fn assess(a8: f64, vdv: Option<f64>, comfort_a_v: Option<f64>) -> Result<Self> {
        Self::assess_with(
            a8,
            vdv,
            comfort_a_v,
            &DirectiveLimits::WHOLE_BODY,
            &HealthGuidanceZone::ISO_2631_1,
        )
    }

    /// The verdict against given limits and zone.
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Errors
    /// As [`ExposureVerdict::assess`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{DirectiveLimits, ExposureVerdict, HealthGuidanceZone};
    /// let stricter = DirectiveLimits { a8_action: 0.4, ..DirectiveLimits::WHOLE_BODY };
    /// let v = ExposureVerdict::assess_with(0.45, None, None, &stricter, &HealthGuidanceZone::ISO_2631_1).unwrap();
    /// assert!(!v.below_action);
    /// ```
    pub fn assess_with(
        a8: f64,
        vdv: Option<f64>,
        comfort_a_v: Option<f64>,
        limits: &DirectiveLimits,
        zone: &HealthGuidanceZone,
    ) -> Result<Self> {
        let check = |name: &str, v: f64| -> Result<f64> {
            if v.is_finite() && v >= 0.0 {
                Ok(v)
            } else {
                Err(Error::invalid(name, v, "must be finite and >= 0"))
            }
        };
        check("a8", a8)?;
        if let Some(v) = vdv {
            check("vdv", v)?;
        }
        if let Some(v) = comfort_a_v {
            check("comfort_a_v", v)?;
        }
        let directive_a8 = LimitCheck::new(a8, limits.a8_action, limits.a8_limit);
        let directive_vdv = vdv.map(|v| LimitCheck::new(v, limits.vdv_action, limits.vdv_limit));
        let below_action = !directive_a8.exceeds_action && !directive_vdv.is_some_and(|c| c.exceeds_action);
        let above_limit = directive_a8.exceeds_limit || directive_vdv.is_some_and(|c| c.exceeds_limit);
        let comfort_reactions = match comfort_a_v {
            Some(v) => comfort_reactions(v)?,
            None => Vec::new(),
        };
        Ok(ExposureVerdict {
            a8,
            vdv,
            comfort_a_v,
            directive_a8,
            directive_vdv,
            below_action,
            above_limit,
            zone_a8: ZoneCheck::new(a8, zone.a8_lower, zone.a8_upper),
            zone_vdv: vdv.map(|v| ZoneCheck::new(v, zone.vdv_lower, zone.vdv_upper)),
            comfort_reactions,
        })
    }
}
