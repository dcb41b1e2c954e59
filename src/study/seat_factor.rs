//! The SEAT value of `[analysis.seat_factor]` (the section is read by `scenario::seat_factor`): the ratio of
//! the frequency-weighted r.m.s. acceleration on the seat pan to that on the floor under the scenario's input.
//!
//! # Formula
//! ```text
//! SEAT = a_w,seat / a_w,floor,   a_w² = ∫ |W(iω)|² S_a(ω) dω                  (EN ISO 7096; ISO 10326-1)
//! ```
//! EN ISO 7096 and ISO 10326-1 define SEAT as this ratio of weighted r.m.s. values; Griffin's original SEAT
//! (Griffin, *Handbook of Human Vibration*, 1990) is the ratio of vibration dose values. For the stationary
//! Gaussian responses analysed here VDV = (3T)^{1/4}·a_w for both accelerations over the same T, so the two
//! ratios are the same number. Both a_w come from the Lyapunov covariance of the system augmented with the
//! weighting filter and from quadrature of the weighted density. A floor given as `base j` is the weighted
//! second derivative of the base displacement: with the weighting's strictly proper realisation (A, b, c)
//! with c·b = 0, s²·c(sI − A)⁻¹b = c·A·b + c·A²(sI − A)⁻¹b, a proper system driven by u_j.

use super::verdict_analysis::weighted_rms_pair;
use crate::comfort::Weighting;
use crate::error::{Error, Result};
use crate::scenario::seat_factor::{FloorSource, SeatFactorSpec};
use crate::scenario::Scenario;
use crate::system::{OutputInfo, StateSpace};
use nalgebra::DMatrix;
use serde::Serialize;

/// The SEAT value and the two weighted accelerations it is made of.
#[derive(Debug, Clone, Serialize)]
pub struct SeatFactorResult {
    /// The seat output.
    pub seat: String,
    /// The floor (an output name, or `base j`).
    pub floor: String,
    /// The weighting of both.
    pub weighting: Weighting,
    /// a_w on the seat pan, m/s² (the exact value where available).
    pub seat_a_w: f64,
    /// a_w on the floor, m/s².
    pub floor_a_w: f64,
    /// SEAT = seat_a_w / floor_a_w.
    pub seat_factor: f64,
    /// a_w of the seat and of the floor by the Lyapunov route, m/s² (`None` where it does not apply).
    pub a_w_lyapunov: [Option<f64>; 2],
    /// a_w of the seat and of the floor by quadrature, m/s².
    pub a_w_quadrature: [Option<f64>; 2],
}

impl SeatFactorResult {
    /// The lines `analyze` prints.
    pub fn lines(&self) -> Vec<String> {
        let s = crate::numbers::sig4;
        let both = |k: usize| match (self.a_w_lyapunov[k], self.a_w_quadrature[k]) {
            (Some(l), Some(q)) => format!("Lyapunov {}, quadrature {}", s(l), s(q)),
            (None, Some(q)) => format!("quadrature {}", s(q)),
            (Some(l), None) => format!("Lyapunov {}", s(l)),
            (None, None) => "-".into(),
        };
        vec![
            format!(
                "SEAT = a_w,seat / a_w,floor = {} ({} %), weighting {}",
                s(self.seat_factor),
                s(100.0 * self.seat_factor),
                self.weighting.name()
            ),
            format!("  seat  {}: a_w {} m/s^2 ({})", self.seat, s(self.seat_a_w), both(0)),
            format!("  floor {}: a_w {} m/s^2 ({})", self.floor, s(self.floor_a_w), both(1)),
        ]
    }
}

/// The weighted second derivative of base input `j` of a system with `m` inputs (see the module docs).
///
/// # Errors
/// [`Error::Numerical`] if the weighting's realisation is not strictly proper with c·b = 0 (it is, for
/// every ISO 2631-1 weighting); the errors of [`StateSpace::new`].
pub fn weighted_base_acceleration(w: Weighting, m: usize, j: usize) -> Result<StateSpace> {
    let (a, b, c, d) = w.cascade();
    // the cascade's c·b is 0 by construction (each section strictly proper); allow for rounding
    let cb = (&c * &b)[(0, 0)];
    if d != 0.0 || cb.abs() > 1e-12 * c.norm() * b.norm() {
        return Err(Error::Numerical {
            what: format!("the {} weighting of a base acceleration", w.name()),
            reason: "its realisation is not of relative degree 2".into(),
        });
    }
    let n = a.nrows();
    let mut bm = DMatrix::zeros(n, m);
    bm.column_mut(j).copy_from(&b.column(0));
    let mut dm = DMatrix::zeros(1, m);
    dm[(0, j)] = (&c * &a * &b)[(0, 0)];
    let cm = &c * &a * &a;
    let info = OutputInfo::new(format!("base_{j}_acc_{}", w.name()), "m/s^2");
    StateSpace::new(a, bm, cm, Some(dm), None, vec![info])
}

/// The SEAT value of a scenario with `[analysis.seat_factor]`.
///
/// # Errors
/// [`Error::File`] naming `analysis.seat_factor.seat` or `.floor` when a weighted r.m.s. cannot be computed;
/// [`Error::NotApplicable`] for a model without a state-space form.
pub fn seat_factor(sc: &Scenario, spec: &SeatFactorSpec) -> Result<SeatFactorResult> {
    let ss = sc.model.system.state_space().ok_or_else(|| Error::NotApplicable {
        method: "SEAT".into(),
        reason: "the model has no state-space form".into(),
    })?;
    let key = |k: &str| format!("analysis.seat_factor.{k}");
    let w = spec.weighting;
    let seat_ws = crate::comfort::weighted_output(ss, spec.seat.0, &w)?;
    let seat = weighted_rms_pair(sc, &seat_ws, &key("seat"), &spec.seat.1)?;
    let (floor_ws, floor_name) = match &spec.floor {
        FloorSource::Output(i, name) => (crate::comfort::weighted_output(ss, *i, &w)?, name.clone()),
        FloorSource::Base(j) => (weighted_base_acceleration(w, ss.b.ncols(), *j)?, format!("base {j}")),
    };
    let floor = weighted_rms_pair(sc, &floor_ws, &key("floor"), &floor_name)?;
    Ok(SeatFactorResult {
        seat: spec.seat.1.clone(),
        floor: floor_name,
        weighting: w,
        seat_a_w: seat.0,
        floor_a_w: floor.0,
        seat_factor: seat.0 / floor.0,
        a_w_lyapunov: [seat.1, floor.1],
        a_w_quadrature: [seat.2, floor.2],
    })
}
