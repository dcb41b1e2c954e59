//! `[[model.nonlinear]]`: nonlinear elements on a stochastic model built from coordinates and elements (the
//! generic `mdof` kind, the quarter car, the operator seat, …), read key by key from the tables of
//! [`KEYS`].
//!
//! # Format
//! ```toml
//! [[model.nonlinear]]
//! kind = "bump-stop"              # one of the kinds of KEYS
//! name = "stops"                  # default: the kind, numbered
//! across = "suspension"           # a spring-damper element of the model: the same two ends
//! # or: point = [1, 0], to = "ground" | "base 0" | [0, 1]   (as the mdof kind's elements)
//! upper_clearance = "8 cm"        # the kind's keys (KEYS)
//! lower_clearance = "6 cm"
//! stiffness = "500 kN/m"
//! ```
//! Deflections are measured from the static equilibrium, positive when the element is stretched (the
//! point moves away from the far end); a damper's velocity is positive in extension (rebound). Every
//! element adds its linear part to the model; `tyre-contact` makes the linear spring it sits `across`
//! unilateral (that spring's stiffness is the tyre's). Elements act between lengths (a point weighting an
//! angle only is refused). See `docs/nonlinear.md`.

use crate::error::{Error, Result};
use crate::fields::Fields;
use crate::nonlinear::{
    BilinearDamper, BumpStop, CoulombFriction, CubicSpring, ForceLaw, NonlinearElement, NonlinearModel,
    QuadraticDamper, TyreContact,
};
use crate::system::{Attach, Mdof, Quantity};
use crate::units::Dim;
use std::sync::Arc;

/// N/m³ (cubic stiffness).
const CUBIC: Dim = Dim::new(-2, 1, -2);
/// N s²/m² (quadratic damping coefficient).
const QUADRATIC: Dim = Dim::new(-1, 1, 0);

/// How a key is read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KeyKind {
    /// A quantity of this dimension (a number is SI).
    Quantity(Dim),
}

/// One key of an element kind: name, reading, whether required, and what it means.
#[derive(Debug, Clone, Copy)]
pub struct Key {
    /// The key.
    pub name: &'static str,
    /// How it is read.
    pub kind: KeyKind,
    /// Required (else optional with the default of `meaning`).
    pub required: bool,
    /// What it is, with its unit and default.
    pub meaning: &'static str,
}

const fn q(name: &'static str, dim: Dim, required: bool, meaning: &'static str) -> Key {
    Key {
        name,
        kind: KeyKind::Quantity(dim),
        required,
        meaning,
    }
}

/// The keys of every element kind (besides `kind`, `name`, `across`, `point`, `to`).
pub const KEYS: &[(&str, &[Key])] = &[
    (
        "cubic-spring",
        &[
            q(
                "cubic_stiffness",
                CUBIC,
                true,
                "k₃ in F = k₁x + k₃x³, N/m³ (> 0 hardening, < 0 softening)",
            ),
            q(
                "linear_stiffness",
                Dim::STIFFNESS,
                false,
                "k₁, N/m (default 0: the model's spring carries it)",
            ),
        ],
    ),
    (
        "bump-stop",
        &[
            q(
                "upper_clearance",
                Dim::LENGTH,
                false,
                "d_u ≥ 0, m: the stop engages for x > d_u (give a side or both)",
            ),
            q(
                "lower_clearance",
                Dim::LENGTH,
                false,
                "d_l ≥ 0, m: the stop engages for x < −d_l",
            ),
            q(
                "stiffness",
                Dim::STIFFNESS,
                false,
                "contact stiffness of both sides, N/m (> 0)",
            ),
            q(
                "upper_stiffness",
                Dim::STIFFNESS,
                false,
                "contact stiffness of the upper side, N/m (default: stiffness)",
            ),
            q(
                "lower_stiffness",
                Dim::STIFFNESS,
                false,
                "contact stiffness of the lower side, N/m (default: stiffness)",
            ),
        ],
    ),
    (
        "bilinear-damper",
        &[
            q(
                "rebound_damping",
                Dim::DAMPING,
                true,
                "c_r for extension (v > 0), N s/m (≥ 0)",
            ),
            q(
                "compression_damping",
                Dim::DAMPING,
                true,
                "c_c for compression (v < 0), N s/m (≥ 0)",
            ),
        ],
    ),
    (
        "quadratic-damper",
        &[
            q(
                "coefficient",
                QUADRATIC,
                false,
                "q of both sides in F = q v|v|, N s²/m²",
            ),
            q(
                "rebound_coefficient",
                QUADRATIC,
                false,
                "q_r for v > 0, N s²/m² (default: coefficient)",
            ),
            q(
                "compression_coefficient",
                QUADRATIC,
                false,
                "q_c for v < 0, N s²/m² (default: coefficient)",
            ),
        ],
    ),
    (
        "coulomb-friction",
        &[q("force", Dim::FORCE, true, "F_c in F = F_c sgn v, N (≥ 0)")],
    ),
    (
        "tyre-contact",
        &[q(
            "static_load",
            Dim::FORCE,
            true,
            "the static load P the tyre carries, N (> 0); lift-off at x > P/k_t",
        )],
    ),
];

/// The names of the element kinds.
pub fn kinds() -> Vec<&'static str> {
    KEYS.iter().map(|(k, _)| *k).collect()
}

/// Reads the `[[model.nonlinear]]` tables of `mf` on the model `lin` (which must be a multi-degree-of-freedom
/// model); `None` when there are none.
///
/// # Errors
/// [`Error::File`] naming the file, the key, the value and the reason.
pub fn parse_nonlinear(mf: &Fields, lin: Option<&Mdof>) -> Result<Option<NonlinearModel>> {
    let Some(v) = mf.get("nonlinear") else { return Ok(None) };
    let arr = v
        .as_array()
        .ok_or_else(|| mf.error("nonlinear", v, "expected [[model.nonlinear]] tables"))?;
    let lin = lin.ok_or_else(|| {
        mf.error(
            "nonlinear",
            "[[model.nonlinear]]",
            "nonlinear elements need a model of coordinates and elements (mdof, quarter-car, operator-seat, …)",
        )
    })?;
    let mut elements = Vec::new();
    for (i, e) in arr.iter().enumerate() {
        let key = format!("nonlinear[{i}]");
        let t = e.as_table().ok_or_else(|| mf.error(&key, e, "expected a table"))?;
        let ef = Fields::new(mf.file(), &mf.path(&key), t);
        let el = element(&ef, lin, i)?;
        if elements.iter().any(|o: &NonlinearElement| o.name == el.name) {
            return Err(ef.error("name", &el.name, "two nonlinear elements have this name"));
        }
        ef.finish()?;
        elements.push(el);
    }
    NonlinearModel::new(lin, elements)
        .map(Some)
        .map_err(|e| mf.wrap("nonlinear", e))
}

fn element(ef: &Fields, lin: &Mdof, i: usize) -> Result<NonlinearElement> {
    let kind = ef.string("kind")?;
    let keys = KEYS.iter().find(|(k, _)| *k == kind).map(|(_, k)| *k).ok_or_else(|| {
        ef.error(
            "kind",
            kind,
            format!("unknown nonlinear element; known kinds: {}", kinds().join(", ")),
        )
    })?;
    let name = ef
        .opt_string("name")?
        .map_or_else(|| format!("{kind}-{i}"), str::to_string);
    let (point, to, across) = placement(ef, lin)?;
    let value = |k: &str| -> Result<Option<f64>> {
        let key = keys.iter().find(|x| x.name == k).expect("a key of the kind");
        let KeyKind::Quantity(dim) = key.kind;
        let v = ef.opt_quantity(k, dim)?;
        if key.required && v.is_none() {
            return Err(ef.error(k, "<missing>", format!("required: {}", key.meaning)));
        }
        Ok(v)
    };
    let law = law(kind, &value, across, lin).map_err(|e| ef.wrap_param(e, "kind"))?;
    Ok(NonlinearElement { name, law, point, to })
}

/// The value of a key that several parameters share, refused under its own name unless finite and > 0
/// (`strict`) or ≥ 0.
fn shared(value: &dyn Fn(&str) -> Result<Option<f64>>, key: &str, strict: bool) -> Result<Option<f64>> {
    let v = value(key)?;
    match v {
        Some(x) if !(x.is_finite() && (x > 0.0 || (!strict && x == 0.0))) => Err(Error::invalid(
            key,
            x,
            if strict {
                "must be finite and > 0"
            } else {
                "must be finite and >= 0"
            },
        )),
        _ => Ok(v),
    }
}

/// The law of `kind` from its keys (`value(key)`); `across` the linear element it sits across.
fn law(
    kind: &str,
    value: &dyn Fn(&str) -> Result<Option<f64>>,
    across: Option<usize>,
    lin: &Mdof,
) -> Result<Arc<dyn ForceLaw>> {
    Ok(match kind {
        "cubic-spring" => Arc::new(CubicSpring::new(
            value("linear_stiffness")?.unwrap_or(0.0),
            value("cubic_stiffness")?.unwrap_or(0.0),
        )?),
        "bump-stop" => {
            // a shared value is checked under its own key (the law would name the side it went to)
            let k = shared(value, "stiffness", true)?;
            let side = |d: Option<f64>, ks: Option<f64>, name: &str| -> Result<Option<(f64, f64)>> {
                match (d, ks.or(k)) {
                    (None, _) => Ok(None),
                    (Some(d), Some(k)) => Ok(Some((d, k))),
                    (Some(_), None) => Err(Error::invalid(
                        &format!("{name}_stiffness"),
                        "<missing>",
                        "give `stiffness` or the side's own",
                    )),
                }
            };
            Arc::new(BumpStop::new(
                side(value("upper_clearance")?, value("upper_stiffness")?, "upper")?,
                side(value("lower_clearance")?, value("lower_stiffness")?, "lower")?,
            )?)
        }
        "bilinear-damper" => Arc::new(BilinearDamper::new(
            value("rebound_damping")?.unwrap_or(0.0),
            value("compression_damping")?.unwrap_or(0.0),
        )?),
        "quadratic-damper" => {
            let c = shared(value, "coefficient", false)?;
            let (r, p) = (value("rebound_coefficient")?, value("compression_coefficient")?);
            if c.is_none() && r.is_none() && p.is_none() {
                return Err(Error::invalid(
                    "coefficient",
                    "<missing>",
                    "give `coefficient` (or `rebound_coefficient`, `compression_coefficient`), > 0 on one side",
                ));
            }
            Arc::new(QuadraticDamper::new(r.or(c).unwrap_or(0.0), p.or(c).unwrap_or(0.0))?)
        }
        "coulomb-friction" => Arc::new(CoulombFriction::new(value("force")?.unwrap_or(0.0))?),
        "tyre-contact" => {
            let e = across.ok_or_else(|| {
                Error::invalid(
                    "across",
                    "<missing>",
                    "a tyre contact makes a linear spring unilateral: name it with `across`",
                )
            })?;
            let k = lin.elements()[e].stiffness;
            Arc::new(
                TyreContact::new(k, value("static_load")?.unwrap_or(0.0)).map_err(|err| match err {
                    Error::InvalidParameter { name, value, reason } if name == "stiffness" => {
                        Error::invalid("across", value, format!("the element it sits across: {reason}"))
                    }
                    other => other,
                })?,
            )
        }
        _ => unreachable!("the kinds of KEYS"),
    })
}

/// (point, far end, index of the linear element named by `across`).
fn placement(ef: &Fields, lin: &Mdof) -> Result<(Vec<f64>, Attach, Option<usize>)> {
    let n = lin.n_coords();
    let placed = if let Some(a) = ef.opt_string("across")? {
        let names: Vec<&str> = lin.elements().iter().map(|e| e.name.as_str()).collect();
        let i = names.iter().position(|x| *x == a).ok_or_else(|| {
            ef.error(
                "across",
                a,
                format!("no such element of the model; its elements: {}", names.join(", ")),
            )
        })?;
        for k in ["point", "to"] {
            if let Some(v) = ef.get(k) {
                return Err(ef.error(k, v, "give either `across` or `point` and `to`"));
            }
        }
        let e = &lin.elements()[i];
        (e.point.clone(), e.to.clone(), Some(i))
    } else {
        let point = weights(ef, "point", ef.require("point")?, n)?;
        let to = super::generic::mdof::attachment(ef, n, lin.n_base())?;
        (point, to, None)
    };
    let angles_only = placed
        .0
        .iter()
        .zip(lin.coordinates())
        .all(|(w, c)| *w == 0.0 || c.1 == "rad");
    if angles_only {
        return Err(ef.error(
            if placed.2.is_some() { "across" } else { "point" },
            format!("{:?}", placed.0),
            "nonlinear elements act on lengths: this point weights angles only",
        ));
    }
    Ok(placed)
}

fn weights(ef: &Fields, key: &str, v: &toml::Value, n: usize) -> Result<Vec<f64>> {
    super::generic::mdof::coordinate_weights(ef, key, v, n)
}

/// The model with an output `<element>_deflection` for every element with a regime (contact, lift-off)
/// that no output of the model is proportional to, so that every regime is counted; returns the names
/// added.
///
/// # Errors
/// An output name already taken.
pub fn with_regime_outputs(model: NonlinearModel) -> Result<(NonlinearModel, Vec<String>)> {
    let p = model.linear().outputs().len();
    let missing: Vec<usize> = (0..model.elements().len())
        .filter(|&e| {
            model.elements()[e].law.regime().is_some() && !(0..p).any(|r| model.deflection_factor(r, e).is_some())
        })
        .collect();
    let mut added = Vec::new();
    let mut m = model;
    for e in missing {
        let el = &m.elements()[e];
        let name = format!("{}_deflection", el.name);
        let d = el.direction();
        let quantity = match el.base() {
            Some(base) => Quantity::RelativeDisplacement { point: d, base },
            None => Quantity::Displacement(d),
        };
        m = m.with_output(&name, quantity)?;
        added.push(name);
    }
    Ok((m, added))
}

use crate::system::FrequencyResponse;

/// Reads `[[model.nonlinear]]` of `mf` onto `model`: the model's system becomes the linear part (with the
/// elements' linear parts and an output per otherwise uncounted regime); returns the outputs added.
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming the key, value and reason.
pub(super) fn attach(
    mf: &Fields,
    model: crate::models::ModelInstance,
) -> Result<(crate::models::ModelInstance, Option<Arc<NonlinearModel>>, Vec<String>)> {
    let Some(nl) = parse_nonlinear(mf, model.system.as_mdof())? else {
        return Ok((model, None, Vec::new()));
    };
    let (nl, added) = with_regime_outputs(nl).map_err(|e| mf.wrap("nonlinear", e))?;
    let names: Vec<String> = nl
        .elements()
        .iter()
        .map(|e| format!("{} ({})", e.name, e.law.describe()))
        .collect();
    let instance = crate::models::ModelInstance {
        system: Arc::new(nl.linear().clone()),
        layout: model.layout,
        description: format!("{}; nonlinear elements: {}", model.description, names.join("; ")),
    };
    Ok((instance, Some(Arc::new(nl)), added))
}
