//! A nonlinear machine: a linear multi-degree-of-freedom model plus nonlinear elements between its points,
//! the ground and its base inputs.
//!
//! # Formula
//! ```text
//! M q̈ + B q̇ + C q = K_u u + B_u u̇ + F f − Σ_e d_e F_e(x_e, ẋ_e),     x_e = d_eᵀ q − u_{j(e)}
//! ```
//! with d_e = g_e − h_e (point weights minus far-end weights; the far end is the ground, a base input j or
//! another point) and F_e the nonlinear remainder of element e ([`ForceLaw`]); each element's linear part
//! (k_e, c_e) is in M, B, C (built by [`NonlinearModel::new`]). Coordinates are measured from the static
//! equilibrium, so clearances and static loads are distances and forces there.

use super::{Equivalent, ForceLaw};
use crate::error::{Error, Result};
use crate::system::{Attach, Element, FrequencyResponse, Mdof, Quantity};
use nalgebra::DVector;
use std::sync::Arc;

/// A nonlinear element placed on a model.
#[derive(Debug, Clone)]
pub struct NonlinearElement {
    /// Name (unique among the elements).
    pub name: String,
    /// The force law.
    pub law: Arc<dyn ForceLaw>,
    /// g: the element's point is gᵀq.
    pub point: Vec<f64>,
    /// The far end.
    pub to: Attach,
}

impl NonlinearElement {
    /// The direction d = g − h (g for the ground and base inputs).
    pub fn direction(&self) -> Vec<f64> {
        match &self.to {
            Attach::Point(h) => self.point.iter().zip(h).map(|(g, h)| g - h).collect(),
            _ => self.point.clone(),
        }
    }

    /// The base input at the far end, if any.
    pub fn base(&self) -> Option<usize> {
        match self.to {
            Attach::Base(j) => Some(j),
            _ => None,
        }
    }

    /// The linear part as a spring–damper element of the linear model (named after the element).
    fn linear_element(&self) -> Option<Element> {
        let (k, c) = self.law.linear_part();
        (k != 0.0 || c != 0.0).then(|| self.as_element(k, c))
    }

    /// A linear spring–damper (k, c) at the element's place.
    pub fn as_element(&self, k: f64, c: f64) -> Element {
        Element {
            name: self.name.clone(),
            point: self.point.clone(),
            to: self.to.clone(),
            stiffness: k,
            damping: c,
        }
    }
}

/// A linear model with nonlinear elements (see the module docs).
///
/// # Errors
/// [`NonlinearModel::new`] rejects elements on coordinates or base inputs the model does not have, zero
/// directions, duplicate names and linear parts with negative coefficients.
///
/// # Examples
/// ```
/// use stochvib::nonlinear::{CubicSpring, NonlinearElement, NonlinearModel};
/// use stochvib::system::{Attach, Drive, MassSpringDamper, Mdof, Quantity};
/// use std::sync::Arc;
/// // Duffing: m = 1 kg, k = 1 N/m, c = 0.2 N s/m, k₃ = 1 N/m³, force input
/// let lin = MassSpringDamper { mass: 1.0, stiffness: 1.0, damping: 0.2, drive: Drive::Force }.build().unwrap().with_output("x", Quantity::Displacement(vec![1.0])).unwrap();
/// let e = NonlinearElement { name: "cubic".into(), law: Arc::new(CubicSpring::new(0.0, 1.0).unwrap()),
///     point: vec![1.0], to: Attach::Ground };
/// let m = NonlinearModel::new(&lin, vec![e]).unwrap();
/// assert_eq!(m.kappa(0), 1.0);
/// ```
#[derive(Debug, Clone)]
pub struct NonlinearModel {
    linear: Mdof,
    elements: Vec<NonlinearElement>,
    kappa: Vec<f64>,
}

impl NonlinearModel {
    /// The model `base` with `elements`: their linear parts are added to `base` (see the module docs).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(base: &Mdof, elements: Vec<NonlinearElement>) -> Result<Self> {
        let n = base.n_coords();
        for (i, e) in elements.iter().enumerate() {
            check_element(e, n, base.n_base())?;
            if elements[..i].iter().any(|o| o.name == e.name) {
                return Err(Error::invalid(
                    "nonlinear element",
                    &e.name,
                    "two elements have this name",
                ));
            }
            let (k, c) = e.law.linear_part();
            if !(k >= 0.0 && c >= 0.0) {
                return Err(Error::invalid(
                    &e.name,
                    format!("k = {k}, c = {c}"),
                    "linear part must be >= 0",
                ));
            }
        }
        let linear_parts: Vec<Element> = elements.iter().filter_map(|e| e.linear_element()).collect();
        let linear = base.with_added_elements(&linear_parts)?;
        let m_inv = linear.mass_inverse();
        let kappa = elements
            .iter()
            .map(|e| {
                let d = DVector::from_vec(e.direction());
                (d.transpose() * m_inv * &d)[(0, 0)]
            })
            .collect();
        Ok(NonlinearModel {
            linear,
            elements,
            kappa,
        })
    }

    /// The linear part (the model with every element's linear part, and its outputs).
    pub fn linear(&self) -> &Mdof {
        &self.linear
    }

    /// The model with one more output of its linear part.
    ///
    /// # Errors
    /// A name already taken; the errors of [`Mdof::with_output`].
    pub fn with_output(self, name: &str, quantity: Quantity) -> Result<Self> {
        if self.linear.outputs().iter().any(|o| o.name == name) {
            return Err(Error::invalid("output", name, "the model has an output of this name"));
        }
        Ok(NonlinearModel {
            linear: self.linear.with_output(name, quantity)?,
            ..self
        })
    }

    /// The nonlinear elements.
    pub fn elements(&self) -> &[NonlinearElement] {
        &self.elements
    }

    /// κ_e = d_eᵀ M⁻¹ d_e, 1/kg: the inverse effective mass along element e.
    pub fn kappa(&self, e: usize) -> f64 {
        self.kappa[e]
    }

    /// Whether every element's remainder vanishes (the model is its linear part).
    pub fn is_linear(&self) -> bool {
        self.elements.iter().all(|e| e.law.is_zero())
    }

    /// The linear part with the Gaussian equivalents `eq` (one per element) added as springs and dampers
    /// (elements with k_eq = c_eq = 0 are skipped, so zero equivalents give the linear part itself).
    ///
    /// # Errors
    /// `eq` of the wrong length; non-finite coefficients.
    pub fn equivalent(&self, eq: &[Equivalent]) -> Result<Mdof> {
        self.with_equivalents(&self.linear, eq)
    }

    /// `base` (the linear part, possibly with more outputs) with the equivalents `eq` added.
    pub(crate) fn with_equivalents(&self, base: &Mdof, eq: &[Equivalent]) -> Result<Mdof> {
        if eq.len() != self.elements.len() {
            return Err(Error::invalid(
                "equivalents",
                eq.len(),
                format!("need one per element ({})", self.elements.len()),
            ));
        }
        let extra: Vec<Element> = self
            .elements
            .iter()
            .zip(eq)
            .filter(|(_, q)| q.stiffness != 0.0 || q.damping != 0.0)
            .map(|(e, q)| e.as_element(q.stiffness, q.damping))
            .collect();
        base.with_added_elements(&extra)
    }

    /// The linear part with two more outputs per element, its deflection x_e and its rate ẋ_e, named
    /// `<element>:x` and `<element>:v`, after the model's own outputs (output index p + 2e and p + 2e + 1,
    /// p = the number of the model's outputs).
    ///
    /// # Errors
    /// An element between angles on a base input (a base input is a displacement).
    pub fn with_element_outputs(&self) -> Result<Mdof> {
        let mut m = self.linear.clone();
        for e in &self.elements {
            let d = e.direction();
            let (x, v) = match e.base() {
                Some(base) => (
                    Quantity::RelativeDisplacement { point: d.clone(), base },
                    Quantity::RelativeVelocity { point: d, base },
                ),
                None => (Quantity::Displacement(d.clone()), Quantity::Velocity(d)),
            };
            m = m
                .with_output(&format!("{}:x", e.name), x)?
                .with_output(&format!("{}:v", e.name), v)?;
        }
        Ok(m)
    }

    /// The factor f with output r = f·x_e (the output is proportional to element e's deflection: its
    /// coordinate and base weights are f times the element's, with no velocity or acceleration weights),
    /// if it is.
    pub fn deflection_factor(&self, r: usize, e: usize) -> Option<f64> {
        let w = self.linear.output_weights(r)?;
        if [w.v, w.a, w.du].iter().any(|s| s.iter().any(|x| *x != 0.0)) {
            return None;
        }
        let el = &self.elements[e];
        let d = el.direction();
        let mut u = vec![0.0; w.u.len()];
        if let Some(j) = el.base() {
            u[j] = -1.0;
        }
        let a: Vec<f64> = w.q.iter().chain(w.u).copied().collect();
        let b: Vec<f64> = d.into_iter().chain(u).collect();
        proportional(&a, &b)
    }
}

/// f with a = f·b (b not all zero), within rounding.
fn proportional(a: &[f64], b: &[f64]) -> Option<f64> {
    let k = b.iter().enumerate().max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))?.0;
    if b[k] == 0.0 {
        return None;
    }
    let f = a[k] / b[k];
    let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1e-300);
    (f != 0.0 && a.iter().zip(b).all(|(x, y)| (x - f * y).abs() <= 1e-12 * scale)).then_some(f)
}

fn check_element(e: &NonlinearElement, n: usize, n_base: usize) -> Result<()> {
    let key = format!("element `{}`", e.name);
    if e.point.len() != n || e.point.iter().any(|w| !w.is_finite()) {
        return Err(Error::invalid(
            &format!("{key}.point"),
            format!("{:?}", e.point),
            format!("need {n} finite weights"),
        ));
    }
    match &e.to {
        Attach::Base(j) if *j >= n_base => {
            return Err(Error::invalid(
                &format!("{key}.to"),
                j,
                format!("the model has {n_base} base inputs"),
            ));
        }
        Attach::Point(h) if h.len() != n || h.iter().any(|w| !w.is_finite()) => {
            return Err(Error::invalid(
                &format!("{key}.to"),
                format!("{h:?}"),
                format!("need {n} finite weights"),
            ));
        }
        _ => {}
    }
    if e.direction().iter().all(|w| *w == 0.0) {
        return Err(Error::invalid(
            &format!("{key}.point"),
            format!("{:?}", e.point),
            "the element joins a point to itself (its direction is zero)",
        ));
    }
    Ok(())
}
