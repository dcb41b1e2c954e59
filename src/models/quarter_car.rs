//! Quarter car: one corner of a vehicle, a sprung (body) mass on the suspension above an unsprung (wheel)
//! mass on the tyre, driven by the road profile under the tyre.
//!
//! # Formula
//! Body z_s, wheel z_u (m, up from static equilibrium), road u (m):
//! ```text
//! m_s z̈_s + c_s (ż_s − ż_u) + k_s (z_s − z_u) = 0
//! m_u z̈_u − c_s (ż_s − ż_u) − k_s (z_s − z_u) + c_t (ż_u − u̇) + k_t (z_u − u) = 0
//! ```
//! Outputs: `body` z_s (m), `body_acc` z̈_s (m/s²), `travel` z_s − z_u (m, suspension deflection), and
//! `tyre_force` k_t (z_u − u) (N, the dynamic part of the tyre's spring force, positive when the tyre is
//! stretched, i.e. negative in compression).
//!
//! With c_t = 0, H_body(s) = k_t (c_s s + k_s) / Δ(s),
//! Δ(s) = m_s m_u s⁴ + c_s (m_s + m_u) s³ + (m_s (k_s + k_t) + m_u k_s) s² + c_s k_t s + k_s k_t.
//!
//! The "golden car" of the International Roughness Index (Sayers, Gillespie & Queiroz 1986, World Bank
//! Technical Paper 46; ASTM E1926) is this model with m_s = 1 and k_s = 63.3, c_s = 6.0, m_u = 0.15,
//! k_t = 653 per unit sprung mass ([`QuarterCar::golden_car`]).
//!
//! # Errors
//! [`QuarterCar::build`] rejects non-positive masses and stiffnesses, negative damping, non-finite values.
//!
//! # Examples
//! ```
//! use stochvib::models::quarter_car::QuarterCar;
//! use stochvib::system::FrequencyResponse;
//! let car = QuarterCar {
//!     sprung_mass: 300.0,
//!     unsprung_mass: 40.0,
//!     suspension_stiffness: 20e3,
//!     suspension_damping: 1.5e3,
//!     tyre_stiffness: 200e3,
//!     tyre_damping: 0.0,
//! }
//! .build()
//! .unwrap();
//! let sys = car.system().unwrap();
//! // the body follows a slow road one to one
//! assert!((sys.static_gain().unwrap()[(0, 0)] - 1.0).abs() < 1e-12);
//! ```

use super::{InputLayout, ModelInstance};
use crate::error::{require_non_negative, require_positive, Result};
use crate::fields::Fields;
use crate::numbers::num;
use crate::system::{Attach, Element, Mdof, Quantity};
use crate::units::Dim;
use std::sync::Arc;

/// A quarter car (see the module docs); masses in kg, stiffnesses in N/m, damping in N s/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuarterCar {
    /// m_s, body mass of the corner, kg.
    pub sprung_mass: f64,
    /// m_u, wheel, tyre, brake and axle share, kg.
    pub unsprung_mass: f64,
    /// k_s, suspension spring, N/m.
    pub suspension_stiffness: f64,
    /// c_s, suspension damper, N s/m.
    pub suspension_damping: f64,
    /// k_t, tyre vertical stiffness, N/m.
    pub tyre_stiffness: f64,
    /// c_t, tyre damping, N s/m (usually 0).
    pub tyre_damping: f64,
}

impl QuarterCar {
    /// The car of these fields, checked: named fields instead of five bare numbers of different meaning.
    ///
    /// # Errors
    /// See the module's `# Errors`.
    pub fn build(self) -> Result<Self> {
        self.validated()
    }

    /// The same car with tyre damping c_t (N s/m).
    ///
    /// # Errors
    /// c_t negative or non-finite.
    pub fn with_tyre_damping(self, tyre_damping: f64) -> Result<Self> {
        QuarterCar { tyre_damping, ..self }.validated()
    }

    /// The IRI reference quarter car per unit sprung mass (see the module docs).
    pub fn golden_car() -> Self {
        QuarterCar {
            sprung_mass: 1.0,
            unsprung_mass: 0.15,
            suspension_stiffness: 63.3,
            suspension_damping: 6.0,
            tyre_stiffness: 653.0,
            tyre_damping: 0.0,
        }
    }

    fn validated(self) -> Result<Self> {
        require_positive("sprung_mass", self.sprung_mass)?;
        require_positive("unsprung_mass", self.unsprung_mass)?;
        require_positive("suspension_stiffness", self.suspension_stiffness)?;
        require_non_negative("suspension_damping", self.suspension_damping)?;
        require_positive("tyre_stiffness", self.tyre_stiffness)?;
        require_non_negative("tyre_damping", self.tyre_damping)?;
        Ok(self)
    }

    /// Reads the `[model]` table of a `quarter-car` scenario: `sprung_mass`, `unsprung_mass` (kg),
    /// `suspension_stiffness`, `tyre_stiffness` (N/m), `suspension_damping`, optional `tyre_damping` (N s/m).
    ///
    /// # Errors
    /// Missing keys, wrong units, invalid values (named by file and key).
    pub fn from_fields(f: &Fields) -> Result<Self> {
        let car = QuarterCar {
            sprung_mass: f.quantity("sprung_mass", Dim::MASS)?,
            unsprung_mass: f.quantity("unsprung_mass", Dim::MASS)?,
            suspension_stiffness: f.quantity("suspension_stiffness", Dim::STIFFNESS)?,
            suspension_damping: f.quantity("suspension_damping", Dim::DAMPING)?,
            tyre_stiffness: f.quantity("tyre_stiffness", Dim::STIFFNESS)?,
            tyre_damping: 0.0,
        }
        .build()
        .map_err(|e| f.wrap_param(e, "sprung_mass"))?;
        match f.opt_quantity("tyre_damping", Dim::DAMPING)? {
            Some(ct) => car.with_tyre_damping(ct).map_err(|e| f.wrap_param(e, "tyre_damping")),
            None => Ok(car),
        }
    }

    /// The two-mass model with outputs `body`, `body_acc`, `travel`, `tyre_force` (input 0: road, m).
    ///
    /// # Errors
    /// None for a validated car (the `Result` is the [`Mdof`] constructor's).
    pub fn system(&self) -> Result<Mdof> {
        let els = vec![
            Element {
                name: "suspension".into(),
                point: vec![1.0, 0.0],
                to: Attach::Point(vec![0.0, 1.0]),
                stiffness: self.suspension_stiffness,
                damping: self.suspension_damping,
            },
            Element {
                name: "tyre".into(),
                point: vec![0.0, 1.0],
                to: Attach::Base(0),
                stiffness: self.tyre_stiffness,
                damping: self.tyre_damping,
            },
        ];
        Mdof::from_elements(
            &[("body", "m"), ("wheel", "m")],
            &[self.sprung_mass, self.unsprung_mass],
            els,
            1,
            &[],
        )?
        .with_outputs(vec![
            ("body", Quantity::Displacement(vec![1.0, 0.0])),
            ("body_acc", Quantity::Acceleration(vec![1.0, 0.0])),
            ("travel", Quantity::Deflection(0)),
            ("tyre_force", Quantity::SpringForce(1)),
        ])
    }

    /// The model driven by one road track ([`InputLayout::Single`]).
    ///
    /// # Errors
    /// As [`QuarterCar::system`].
    pub fn instance(&self) -> Result<ModelInstance> {
        Ok(ModelInstance {
            system: Arc::new(self.system()?),
            layout: InputLayout::Single,
            description: format!(
                "quarter car: m_s = {} kg, m_u = {} kg, k_s = {} N/m, c_s = {} N s/m, k_t = {} N/m, c_t = {} N s/m",
                num(self.sprung_mass),
                num(self.unsprung_mass),
                num(self.suspension_stiffness),
                num(self.suspension_damping),
                num(self.tyre_stiffness),
                num(self.tyre_damping)
            ),
        })
    }
}
