//! Full vehicle: a rigid body in bounce, pitch and roll on four suspensions and four unsprung masses
//! (seven degrees of freedom), on two road tracks.

use super::{InputLayout, ModelInstance};
use crate::error::{require_positive, Error, Result};
use crate::system::{Attach, Element, Mdof, Quantity};
use nalgebra::DMatrix;
use std::sync::Arc;

/// Seven-degree-of-freedom vehicle: body bounce z (m), pitch θ (rad, nose up), roll φ (rad, left side
/// up), unsprung masses z_fl, z_fr, z_rl, z_rr (m); axles a ahead of and b behind the centre of mass,
/// wheels at ±B/2 laterally (left +).
///
/// # Formula
/// Body corner displacements: front left z + aθ + (B/2)φ, front right z + aθ − (B/2)φ, rear left
/// z − bθ + (B/2)φ, rear right z − bθ − (B/2)φ. Suspension i (stiffness k, damping c) between corner i
/// and unsprung mass i; tyre i (stiffness k_t) between unsprung mass i and the road under wheel i (base
/// input i: 0 fl, 1 fr, 2 rl, 3 rr). Equations M q̈ + C q̇ + K q = K_u u + C_u u̇ assembled by
/// [`Mdof::from_elements`] (Lagrange's equations of the spring–damper elements), M = diag(m, I_θ, I_φ,
/// m_f, m_f, m_r, m_r). Outputs: `seat_acc` (m/s², z̈ + x_s θ̈ + y_s φ̈ at the seat point x_s ahead of the
/// centre of mass and y_s to its left), `bounce` (m), `pitch` (rad), `roll` (rad), `travel_<w>` (corner
/// minus wheel, m), `tyre_force_<w>` (dynamic tyre force k_t(z_w − u_w), N, positive when the tyre is
/// unloaded), w ∈ {fl, fr, rl, rr}. A left–right symmetric vehicle on identical tracks (γ = 1) does not roll.
///
/// # Errors
/// Non-positive masses, inertias, lengths, stiffnesses; negative damping; a non-finite seat point.
///
/// # Examples
/// ```
/// use stochvib::models::full_vehicle::FullVehicle;
/// use stochvib::system::FrequencyResponse;
/// let car = FullVehicle::passenger_car();
/// let sys = car.mdof().unwrap();
/// assert_eq!(sys.n_inputs(), 4);
/// let (w, _) = car.modes().unwrap();
/// assert_eq!(w.len(), 7);
/// assert!(w[0] > 5.0 && w[0] < 10.0); // body modes near 1–1.5 Hz
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct FullVehicle {
    /// Sprung mass m, kg.
    pub mass: f64,
    /// Pitch inertia I_θ, kg m².
    pub pitch_inertia: f64,
    /// Roll inertia I_φ, kg m².
    pub roll_inertia: f64,
    /// a: front axle ahead of the centre of mass, m.
    pub front_distance: f64,
    /// b: rear axle behind the centre of mass, m.
    pub rear_distance: f64,
    /// B: track width, m.
    pub track_width: f64,
    /// Suspension stiffness front, rear (per wheel), N/m.
    pub suspension_stiffness: [f64; 2],
    /// Suspension damping front, rear (per wheel), N s/m.
    pub suspension_damping: [f64; 2],
    /// Unsprung mass front, rear (per wheel), kg.
    pub unsprung_mass: [f64; 2],
    /// Tyre stiffness (per wheel), N/m.
    pub tyre_stiffness: f64,
    /// Seat point (x_s ahead of, y_s left of the centre of mass), m.
    pub seat: [f64; 2],
}

const WHEELS: [&str; 4] = ["fl", "fr", "rl", "rr"];

impl FullVehicle {
    /// A mid-size passenger car (typical textbook values, e.g. Jazar, *Vehicle Dynamics*, 2008, §15.6):
    /// m = 1400 kg, I_θ = 2100 kg m², I_φ = 500 kg m², a = 1.2 m, b = 1.5 m, B = 1.5 m,
    /// k = 25/22 kN/m, c = 2000/1800 N s/m (front/rear), m_u = 40/35 kg, k_t = 200 kN/m, driver's seat at
    /// (0.3 m, 0.35 m).
    pub fn passenger_car() -> FullVehicle {
        FullVehicle {
            mass: 1400.0,
            pitch_inertia: 2100.0,
            roll_inertia: 500.0,
            front_distance: 1.2,
            rear_distance: 1.5,
            track_width: 1.5,
            suspension_stiffness: [25e3, 22e3],
            suspension_damping: [2000.0, 1800.0],
            unsprung_mass: [40.0, 35.0],
            tyre_stiffness: 200e3,
            seat: [0.3, 0.35],
        }
    }

    /// Checks the parameters.
    ///
    /// # Errors
    /// See the type's `# Errors`, naming the parameter.
    pub fn validate(&self) -> Result<()> {
        require_positive("mass", self.mass)?;
        require_positive("pitch_inertia", self.pitch_inertia)?;
        require_positive("roll_inertia", self.roll_inertia)?;
        require_positive("front_distance", self.front_distance)?;
        require_positive("rear_distance", self.rear_distance)?;
        require_positive("track_width", self.track_width)?;
        for (k, name) in ["front", "rear"].iter().enumerate() {
            require_positive(&format!("suspension_stiffness.{name}"), self.suspension_stiffness[k])?;
            require_positive(&format!("unsprung_mass.{name}"), self.unsprung_mass[k])?;
            let c = self.suspension_damping[k];
            if !(c.is_finite() && c >= 0.0) {
                return Err(Error::invalid(
                    &format!("suspension_damping.{name}"),
                    c,
                    "must be finite and >= 0",
                ));
            }
        }
        require_positive("tyre_stiffness", self.tyre_stiffness)?;
        for (k, v) in self.seat.iter().enumerate() {
            crate::error::require_finite(&format!("seat[{k}]"), *v)?;
        }
        Ok(())
    }

    /// The random-road model: the [`FullVehicle::mdof`] system and the layout of its wheels on two tracks
    /// ([`InputLayout::TwoTracks`]: fl left at 0, fr right at 0, rl left at L, rr right at L, unit gains);
    /// the description lists the undamped natural frequencies in Hz.
    ///
    /// # Formula
    /// f_i = ω_i/(2π) with ω_i from [`FullVehicle::modes`].
    ///
    /// # Errors
    /// As [`FullVehicle::mdof`].
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::{full_vehicle::FullVehicle, InputLayout};
    /// let m = FullVehicle::passenger_car().instance().unwrap();
    /// assert!(matches!(m.layout, InputLayout::TwoTracks { .. }));
    /// assert!(m.description.contains("natural frequencies"));
    /// ```
    pub fn instance(&self) -> Result<ModelInstance> {
        let sys = self.mdof()?;
        let (w, _) = sys.modes()?;
        let hz: Vec<String> = w
            .iter()
            .map(|w| format!("{:.3}", w / (2.0 * std::f64::consts::PI)))
            .collect();
        let wheels = self.wheels();
        Ok(ModelInstance {
            system: Arc::new(sys),
            layout: InputLayout::TwoTracks {
                tracks: wheels.iter().map(|w| w.0).collect(),
                positions: wheels.iter().map(|w| w.1).collect(),
                gains: vec![1.0; 4],
                track_width: Some(self.track_width),
            },
            description: format!(
                "full vehicle, 7 DOF (bounce, pitch, roll, 4 unsprung masses): m = {} kg, I_theta = {} kg m^2, \
                 I_phi = {} kg m^2, a = {} m, b = {} m, B = {} m, k = {}/{} N/m, c = {}/{} N s/m, m_u = {}/{} kg, \
                 k_t = {} N/m, seat ({}, {}) m; undamped natural frequencies {} Hz",
                self.mass,
                self.pitch_inertia,
                self.roll_inertia,
                self.front_distance,
                self.rear_distance,
                self.track_width,
                self.suspension_stiffness[0],
                self.suspension_stiffness[1],
                self.suspension_damping[0],
                self.suspension_damping[1],
                self.unsprung_mass[0],
                self.unsprung_mass[1],
                self.tyre_stiffness,
                self.seat[0],
                self.seat[1],
                hz.join(", ")
            ),
        })
    }

    /// The wheelbase a + b, m.
    pub fn wheelbase(&self) -> f64 {
        self.front_distance + self.rear_distance
    }

    /// The wheels as (track, position behind the front axle in m): fl (0, 0), fr (1, 0), rl (0, L), rr
    /// (1, L) — the argument of [`Excitation::two_tracks`](crate::response::Excitation::two_tracks).
    pub fn wheels(&self) -> [(usize, f64); 4] {
        let l = self.wheelbase();
        [(0, 0.0), (1, 0.0), (0, l), (1, l)]
    }

    /// The seven-degree-of-freedom [`Mdof`] (see the type's `# Formula` for coordinates and outputs).
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn mdof(&self) -> Result<Mdof> {
        self.validate()?;
        let (a, b, h) = (self.front_distance, self.rear_distance, self.track_width / 2.0);
        let corner = [(a, h), (a, -h), (-b, h), (-b, -h)];
        let mut els = Vec::new();
        for (w, &(x, y)) in corner.iter().enumerate() {
            let axle = w / 2;
            let mut g = vec![1.0, x, y, 0.0, 0.0, 0.0, 0.0];
            g[3 + w] = -1.0;
            els.push(Element {
                name: format!("suspension_{}", WHEELS[w]),
                point: g,
                to: Attach::Ground,
                stiffness: self.suspension_stiffness[axle],
                damping: self.suspension_damping[axle],
            });
        }
        for w in 0..4 {
            let mut g = vec![0.0; 7];
            g[3 + w] = 1.0;
            els.push(Element {
                name: format!("tyre_{}", WHEELS[w]),
                point: g,
                to: Attach::Base(w),
                stiffness: self.tyre_stiffness,
                damping: 0.0,
            });
        }
        let (mf, mr) = (self.unsprung_mass[0], self.unsprung_mass[1]);
        let mut m = Mdof::from_elements(
            &[
                ("z", "m"),
                ("theta", "rad"),
                ("phi", "rad"),
                ("z_fl", "m"),
                ("z_fr", "m"),
                ("z_rl", "m"),
                ("z_rr", "m"),
            ],
            &[self.mass, self.pitch_inertia, self.roll_inertia, mf, mf, mr, mr],
            els,
            4,
            &[],
        )?
        .with_output(
            "seat_acc",
            Quantity::Acceleration(vec![1.0, self.seat[0], self.seat[1], 0.0, 0.0, 0.0, 0.0]),
        )?
        .with_output(
            "bounce",
            Quantity::Displacement(vec![1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
        )?
        .with_output("pitch", Quantity::Displacement(vec![0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0]))?
        .with_output("roll", Quantity::Displacement(vec![0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0]))?;
        for (w, name) in WHEELS.iter().enumerate() {
            m = m.with_output(&format!("travel_{name}"), Quantity::Deflection(w))?;
        }
        for (w, name) in WHEELS.iter().enumerate() {
            m = m.with_output(&format!("tyre_force_{name}"), Quantity::ElementForce(4 + w))?;
        }
        Ok(m)
    }

    /// Undamped natural frequencies (rad/s, ascending) and mass-normalised modes (columns over
    /// (z, θ, φ, z_fl, z_fr, z_rl, z_rr)) by [`Mdof::modes`].
    ///
    /// # Errors
    /// Invalid parameters.
    pub fn modes(&self) -> Result<(Vec<f64>, DMatrix<f64>)> {
        self.mdof()?.modes()
    }
}
