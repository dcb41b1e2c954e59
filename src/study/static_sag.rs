//! The static sag of a scenario's springs: how far each spring element is compressed by the weight of the
//! masses it carries, for the model kinds whose length coordinates are vertical ([`STATIC_SAG_KINDS`]).
//!
//! # Formula
//! K q_s = −g M e (e: a unit lift of every length coordinate), each element's compression
//! δ = hᵀq_s − gᵀq_s (see [`Mdof::static_deflections`](crate::system::Mdof::static_deflections)). A quarter
//! car: δ_suspension = m_s g/k_s, δ_tyre = (m_s + m_u) g/k_t; the textbook seat: δ = m_pr g/k with
//! m_pr = (5/7) m_operator + m_seat.

use crate::error::{Error, Result};
use crate::scenario::Scenario;
use serde::Serialize;

/// The kinds whose length coordinates are all vertical, so that gravity and the springs define a static
/// sag (the generic `mdof` kind does not say which of its coordinates are vertical).
pub const STATIC_SAG_KINDS: &[&str] = &[
    "quarter-car",
    "half-car",
    "full-vehicle",
    "machine",
    "operator-seat",
    "isolator-single",
    "isolator-two-stage",
];

/// The static compression of one spring element.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StaticSag {
    /// The element's name.
    pub element: String,
    /// Its compression under the weights, m (> 0 compressed).
    pub deflection_m: f64,
}

/// The static sag of every spring element (stiffness > 0) of `sc`; `None` for a kind that does not define
/// one ([`STATIC_SAG_KINDS`]).
///
/// # Errors
/// A stiffness matrix that holds no static position (a part on dampers alone).
pub fn static_sag(sc: &Scenario) -> Option<Result<Vec<StaticSag>>> {
    if !STATIC_SAG_KINDS.contains(&sc.kind.as_str()) {
        return None;
    }
    let m = sc.model.system.as_mdof()?;
    let springs: Vec<bool> = m.elements().iter().map(|e| e.stiffness > 0.0).collect();
    Some(m.static_deflections().map(|d| {
        d.into_iter()
            .zip(springs)
            .filter(|(_, spring)| *spring)
            .map(|((element, deflection_m), _)| StaticSag { element, deflection_m })
            .collect()
    }))
}

/// The static sag of the element `element` of `sc`.
///
/// # Errors
/// [`Error::Numerical`] naming the quantity when the kind defines none or has no such spring; those of
/// [`static_sag`].
pub fn static_sag_of(sc: &Scenario, element: &str) -> Result<f64> {
    let list = static_sag(sc).ok_or_else(|| sag_undefined(sc))??;
    list.iter()
        .find(|s| s.element == element)
        .map(|s| s.deflection_m)
        .ok_or_else(|| Error::Numerical {
            what: format!("static_sag({element})"),
            reason: format!("no spring element `{element}` (its springs: {})", names(&list)),
        })
}

/// The spring elements of `sc` that have a static sag, or why there are none (for the quantity's parser).
pub fn sag_elements(sc: &Scenario) -> std::result::Result<Vec<String>, String> {
    match static_sag(sc) {
        None => Err(sag_undefined(sc).to_string()),
        Some(Err(e)) => Err(e.to_string()),
        Some(Ok(list)) => Ok(list.into_iter().map(|s| s.element).collect()),
    }
}

fn names(list: &[StaticSag]) -> String {
    list.iter().map(|s| s.element.as_str()).collect::<Vec<_>>().join(", ")
}

fn sag_undefined(sc: &Scenario) -> Error {
    Error::Numerical {
        what: "static_sag".into(),
        reason: format!(
            "kind `{}` has no static sag: it is defined for the kinds whose length coordinates are vertical ({})",
            sc.kind,
            STATIC_SAG_KINDS.join(", ")
        ),
    }
}
