//! Axes, measurement locations and multiplying factors k of ISO 2631-1, and the vector sum of several
//! weighted axis values.

use super::weighting::Weighting;
use crate::error::{Error, Result};

/// What the evaluation is for: the weightings and factors k differ.
///
/// # Formula
/// Selects the table of [`axis_factor`].
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::{axis_factor, Axis, Location, Purpose};
/// let h = axis_factor(Purpose::Health, Location::SeatSurface, Axis::Y).unwrap().k;
/// let c = axis_factor(Purpose::Comfort, Location::SeatSurface, Axis::Y).unwrap().k;
/// assert_eq!((h, c), (1.4, 1.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Purpose {
    /// Health of a seated person (ISO 2631-1:1997, clause 7; Directive 2002/44/EC).
    Health,
    /// Comfort (ISO 2631-1:1997, clause 8.2).
    Comfort,
}

/// Where the vibration enters the body.
///
/// # Formula
/// Selects the row of [`axis_factor`].
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::{axis_factor, Axis, Location, Purpose};
/// assert_eq!(axis_factor(Purpose::Comfort, Location::Feet, Axis::Z).unwrap().k, 0.4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Location {
    /// Seat surface under a seated person (translational x, y, z and rotational r_x, r_y, r_z).
    SeatSurface,
    /// Seat back of a seated person.
    SeatBack,
    /// Feet of a seated person.
    Feet,
    /// Floor under a standing person.
    StandingFloor,
}

/// The basicentric axis (ISO 2631-1:1997, Figure 1): x back-to-chest, y right-to-left side, z
/// foot(buttocks)-to-head; r_x, r_y, r_z the rotations about them.
///
/// # Formula
/// Selects the column of [`axis_factor`]; rotational values are in rad/s² and their k in m/rad.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::{axis_factor, Axis, Location, Purpose, Weighting};
/// let f = axis_factor(Purpose::Comfort, Location::SeatSurface, Axis::Rx).unwrap();
/// assert_eq!((f.weighting, f.k), (Weighting::We, 0.63));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// Fore-and-aft translation.
    X,
    /// Lateral translation.
    Y,
    /// Vertical translation.
    Z,
    /// Roll (rotation about x), rad/s².
    Rx,
    /// Pitch (rotation about y), rad/s².
    Ry,
    /// Yaw (rotation about z), rad/s².
    Rz,
}

impl Purpose {
    /// The purpose as a scenario file writes it: `health`, `comfort`.
    pub fn label(self) -> &'static str {
        match self {
            Purpose::Health => "health",
            Purpose::Comfort => "comfort",
        }
    }
}

impl Location {
    /// The location as a scenario file writes it: `seat-surface`, `seat-back`, `feet`, `standing-floor`.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(stochvib::comfort::Location::SeatSurface.label(), "seat-surface");
    /// ```
    pub fn label(self) -> &'static str {
        match self {
            Location::SeatSurface => "seat-surface",
            Location::SeatBack => "seat-back",
            Location::Feet => "feet",
            Location::StandingFloor => "standing-floor",
        }
    }
}

impl Axis {
    /// The axis as a scenario file writes it: `x`, `y`, `z`, `rx`, `ry`, `rz`.
    pub fn label(self) -> &'static str {
        match self {
            Axis::X => "x",
            Axis::Y => "y",
            Axis::Z => "z",
            Axis::Rx => "rx",
            Axis::Ry => "ry",
            Axis::Rz => "rz",
        }
    }
}

/// The weighting and multiplying factor of one (purpose, location, axis).
///
/// # Formula
/// The axis contributes k·a_w (m/s²) to a vector sum, a_w computed with `weighting`.
///
/// # Errors
/// None (returned by [`axis_factor`]).
///
/// # Examples
/// ```
/// use stochvib::comfort::{axis_factor, Axis, Location, Purpose};
/// assert_eq!(axis_factor(Purpose::Health, Location::SeatSurface, Axis::Z).unwrap().clause, "7.2.3");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct AxisFactor {
    /// Frequency weighting to apply.
    pub weighting: Weighting,
    /// Multiplying factor k (dimensionless; m/rad for rotations, turning rad/s² into m/s²).
    pub k: f64,
    /// Clause of ISO 2631-1:1997 that gives it.
    pub clause: &'static str,
}

/// The frequency weighting and multiplying factor k of ISO 2631-1 for a purpose, location and axis.
///
/// # Formula
/// Health, seated person, seat surface (ISO 2631-1:1997, 7.2.3; also Directive 2002/44/EC Annex B:
/// "1,4a_wx, 1,4a_wy, a_wz for a seated or standing worker"):
///
/// | axis | weighting | k   |
/// |------|-----------|-----|
/// | x, y | Wd        | 1.4 |
/// | z    | Wk        | 1   |
///
/// Comfort (ISO 2631-1:1997, 8.2):
///
/// | location       | x          | y          | z          | r_x         | r_y        | r_z        |
/// |----------------|------------|------------|------------|-------------|------------|------------|
/// | seat surface   | Wd, 1      | Wd, 1      | Wk, 1      | We, 0.63 m/rad | We, 0.4 m/rad | We, 0.2 m/rad |
/// | seat back      | Wc, 0.8    | Wd, 0.5    | Wd, 0.4    |             |            |            |
/// | feet (seated)  | Wk, 0.25   | Wk, 0.25   | Wk, 0.4    |             |            |            |
/// | standing floor | Wd, 1      | Wd, 1      | Wk, 1      |             |            |            |
///
/// # Errors
/// [`Error::NotApplicable`] for a combination the standard does not define (health outside the seat
/// surface or for rotations; rotations other than on the seat surface).
///
/// # Examples
/// ```
/// use stochvib::comfort::{axis_factor, Axis, Location, Purpose, Weighting};
/// let f = axis_factor(Purpose::Health, Location::SeatSurface, Axis::X).unwrap();
/// assert_eq!((f.weighting, f.k), (Weighting::Wd, 1.4));
/// let b = axis_factor(Purpose::Comfort, Location::SeatBack, Axis::X).unwrap();
/// assert_eq!((b.weighting, b.k), (Weighting::Wc, 0.8));
/// assert!(axis_factor(Purpose::Health, Location::SeatBack, Axis::X).is_err());
/// ```
pub fn axis_factor(purpose: Purpose, location: Location, axis: Axis) -> Result<AxisFactor> {
    use Axis::*;
    use Location::*;
    use Weighting::*;
    let f = |weighting, k, clause| AxisFactor { weighting, k, clause };
    let found = match purpose {
        Purpose::Health => match (location, axis) {
            (SeatSurface, X) | (SeatSurface, Y) => Some(f(Wd, 1.4, "7.2.3")),
            (SeatSurface, Z) => Some(f(Wk, 1.0, "7.2.3")),
            _ => None,
        },
        Purpose::Comfort => match (location, axis) {
            (SeatSurface, X) | (SeatSurface, Y) => Some(f(Wd, 1.0, "8.2")),
            (SeatSurface, Z) => Some(f(Wk, 1.0, "8.2")),
            (SeatSurface, Rx) => Some(f(We, 0.63, "8.2")),
            (SeatSurface, Ry) => Some(f(We, 0.4, "8.2")),
            (SeatSurface, Rz) => Some(f(We, 0.2, "8.2")),
            (SeatBack, X) => Some(f(Wc, 0.8, "8.2")),
            (SeatBack, Y) => Some(f(Wd, 0.5, "8.2")),
            (SeatBack, Z) => Some(f(Wd, 0.4, "8.2")),
            (Feet, X) | (Feet, Y) => Some(f(Wk, 0.25, "8.2")),
            (Feet, Z) => Some(f(Wk, 0.4, "8.2")),
            (StandingFloor, X) | (StandingFloor, Y) => Some(f(Wd, 1.0, "8.2")),
            (StandingFloor, Z) => Some(f(Wk, 1.0, "8.2")),
            _ => None,
        },
    };
    found.ok_or_else(|| Error::NotApplicable {
        method: format!("ISO 2631-1 {} evaluation", purpose.label()),
        reason: format!(
            "no weighting and factor k are defined for axis {} at {} (health: seat surface x, y, z only; \
             rotations: seat surface only)",
            axis.label(),
            location.label()
        ),
    })
}

/// The weighting and factor with which an axis enters the daily exposure of Directive 2002/44/EC, whatever
/// the purpose of the ISO 2631-1 evaluation the axis was written for; `None` for an axis that does not.
///
/// # Formula
/// Directive 2002/44/EC, Annex B 1: A(8) and VDV are those of the highest of "1,4a_wx, 1,4a_wy, a_wz for a
/// seated or standing worker", the a_w weighted as ISO 2631-1:1997 (Wd for x, y; Wk for z, 7.2.3). So the
/// translational axes of the seat surface and of the floor under a standing person enter, with k = 1.4,
/// 1.4, 1; seat back, feet and rotations do not. The health guidance zones of ISO 2631-1 Annex B use the same
/// factors, for seated persons.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::comfort::{directive_factor, Axis, Location, Weighting};
/// let f = directive_factor(Location::StandingFloor, Axis::Y).unwrap();
/// assert_eq!((f.weighting, f.k), (Weighting::Wd, 1.4));
/// assert!(directive_factor(Location::SeatBack, Axis::X).is_none());
/// ```
pub fn directive_factor(location: Location, axis: Axis) -> Option<AxisFactor> {
    let seated_or_standing = matches!(location, Location::SeatSurface | Location::StandingFloor);
    let (weighting, k) = match axis {
        Axis::X | Axis::Y => (Weighting::Wd, 1.4),
        Axis::Z => (Weighting::Wk, 1.0),
        _ => return None,
    };
    seated_or_standing.then_some(AxisFactor {
        weighting,
        k,
        clause: "7.2.3",
    })
}

/// The weighted r.m.s. a_w measured (or computed) on one axis at one location (m/s², rad/s² for
/// rotations), before the factor k.
///
/// # Formula
/// Input term of [`vector_sum`]: contributes k·a_w.
///
/// # Errors
/// [`vector_sum`] rejects a non-finite or negative a_w.
///
/// # Examples
/// ```
/// use stochvib::comfort::{vector_sum, Axis, AxisValue, Location, Purpose};
/// let z = AxisValue { location: Location::SeatSurface, axis: Axis::Z, a_w: 0.3 };
/// assert_eq!(vector_sum(Purpose::Comfort, &[z]).unwrap().a_v, 0.3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct AxisValue {
    /// Where.
    pub location: Location,
    /// Which axis.
    pub axis: Axis,
    /// Weighted r.m.s. (with the weighting of [`axis_factor`]), m/s² or rad/s².
    pub a_w: f64,
}

/// One term of a vector sum.
///
/// # Formula
/// `weighted` = k·a_w.
///
/// # Errors
/// None (part of [`VectorSum`]).
///
/// # Examples
/// ```
/// use stochvib::comfort::{vector_sum, Axis, AxisValue, Location, Purpose};
/// let x = AxisValue { location: Location::SeatSurface, axis: Axis::X, a_w: 0.5 };
/// let t = vector_sum(Purpose::Health, &[x]).unwrap().terms[0];
/// assert!((t.weighted - 0.7).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct VectorSumTerm {
    /// Where.
    pub location: Location,
    /// Which axis.
    pub axis: Axis,
    /// The weighting that a_w must have been computed with.
    pub weighting: Weighting,
    /// The factor k.
    pub k: f64,
    /// The axis value a_w.
    pub a_w: f64,
    /// k·a_w, m/s².
    pub weighted: f64,
}

/// A vector sum with its terms and the dominant (largest k·a_w) term.
///
/// # Formula
/// a_v = √(Σᵢ kᵢ² a_wᵢ²); see [`vector_sum`].
///
/// # Errors
/// None (returned by [`vector_sum`]).
///
/// # Examples
/// ```
/// use stochvib::comfort::{vector_sum, Axis, AxisValue, Location, Purpose};
/// let v = |axis, a_w| AxisValue { location: Location::StandingFloor, axis, a_w };
/// let s = vector_sum(Purpose::Comfort, &[v(Axis::X, 0.3), v(Axis::Z, 0.4)]).unwrap();
/// assert!((s.a_v - 0.5).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct VectorSum {
    /// Health or comfort.
    pub purpose: Purpose,
    /// a_v = √(Σ kᵢ² a_wᵢ²), m/s².
    pub a_v: f64,
    /// Every term, in input order.
    pub terms: Vec<VectorSumTerm>,
    /// The term with the largest k·a_w (the axis the Directive's A(8) is based on).
    pub dominant: VectorSumTerm,
}

/// The vector sum (root sum of squares of k·a_w) of several axis values.
///
/// # Formula
/// ISO 2631-1:1997, 6.5, for one point: a_v = (k_x² a_wx² + k_y² a_wy² + k_z² a_wz²)^(1/2); for
/// comfort the same root sum of squares over all axes of all locations is the overall vibration total
/// value (8.2). The factors k and weightings are those of [`axis_factor`]. For health the standard
/// assesses each axis separately, the dominant term k·a_w (reported here) deciding; the vector sum is an
/// additional indicator when several axes are comparable (7.2.2).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `values` when empty or when a (location, axis) appears twice, or
/// `values[i].a_w` when not finite and ≥ 0; [`Error::NotApplicable`] from [`axis_factor`].
///
/// # Examples
/// ```
/// use stochvib::comfort::{vector_sum, Axis, AxisValue, Location, Purpose};
/// let v = |axis, a_w| AxisValue { location: Location::SeatSurface, axis, a_w };
/// let s = vector_sum(Purpose::Health, &[v(Axis::X, 0.3), v(Axis::Y, 0.4), v(Axis::Z, 0.5)]).unwrap();
/// // √(1.4²·0.09 + 1.4²·0.16 + 0.25) = √0.74
/// assert!((s.a_v - 0.74f64.sqrt()).abs() < 1e-15);
/// assert_eq!(s.dominant.axis, Axis::Y); // 1.4·0.4 = 0.56 > 0.5
/// ```
pub fn vector_sum(purpose: Purpose, values: &[AxisValue]) -> Result<VectorSum> {
    if values.is_empty() {
        return Err(Error::invalid("values", "[]", "need at least one axis value"));
    }
    let mut terms: Vec<VectorSumTerm> = Vec::with_capacity(values.len());
    for (i, v) in values.iter().enumerate() {
        if !(v.a_w.is_finite() && v.a_w >= 0.0) {
            return Err(Error::invalid(
                &format!("values[{i}].a_w"),
                v.a_w,
                "must be finite and >= 0",
            ));
        }
        if terms.iter().any(|t| t.location == v.location && t.axis == v.axis) {
            return Err(Error::invalid(
                "values",
                format!("{:?} {:?} (entry {i})", v.location, v.axis),
                "each (location, axis) may appear only once",
            ));
        }
        let f = axis_factor(purpose, v.location, v.axis)?;
        terms.push(VectorSumTerm {
            location: v.location,
            axis: v.axis,
            weighting: f.weighting,
            k: f.k,
            a_w: v.a_w,
            weighted: f.k * v.a_w,
        });
    }
    let a_v = terms.iter().map(|t| t.weighted * t.weighted).sum::<f64>().sqrt();
    let dominant = *terms
        .iter()
        .max_by(|a, b| a.weighted.total_cmp(&b.weighted))
        .expect("non-empty");
    Ok(VectorSum {
        purpose,
        a_v,
        terms,
        dominant,
    })
}
