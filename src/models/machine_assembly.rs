//! A machine as an assembly: a rigid body on axles (tyres with stiffness and damping; an oscillating axle or
//! suspended wheels as options), a cab on mounts and the textbook seat on the cab floor, built as an
//! [`Mdof`] from spring–damper elements.
//!
//! # Formula
//! Frame: x forward, y left, z up; the body's centre of gravity at x = y = 0 and height h_b. Each rigid body
//! (body, cab) has coordinates (z, θ, φ) at its centre of gravity: bounce, pitch (nose up > 0) and roll (left
//! side up > 0), the convention of [`crate::models::full_vehicle`]. Small motions:
//! ```text
//! vertical motion of a body point (x, y):        z + x θ + y φ
//! of a cab point:                                z_c + (x − x_c) θ_c + (y − y_c) φ_c
//! longitudinal, lateral motion at height h:      body: −(h − h_b) θ,  −(h − h_b) φ
//!   (cab, seat)                                  −(h_m − h_b) θ − (h − h_m) θ_c,  −(h_m − h_b) φ − (h − h_m) φ_c
//! ```
//! (h_m: the height of the cab-mount plane, where the mounts hold the cab horizontally to the body.) The
//! horizontal motion is the kinematic consequence of pitch and roll; the mounts, tyres and seat are vertical
//! springs and dampers, so the small horizontal forces this motion takes are not fed back (a linear model
//! of vertical, pitch and roll dynamics).
//! * Axle at x_a, track width w: a tyre (k_t, c_t) under each wheel at y = ±w/2. Rigid axle: the tyre acts
//!   on the body point. Oscillating axle: the axle rolls about a pin on the centre line (coordinate φ_a,
//!   roll inertia J_a, optional pin stiffness and damping to the body's roll); its wheels are at
//!   z + x_a θ ± (w/2) φ_a. Suspended wheels: an unsprung mass per wheel on its tyre, a suspension
//!   (k_s, c_s) between it and the body point.
//! * Cab mounts (k, c) at (x_m, y_m) between the cab point and the body point there.
//! * Seat: the textbook model ([`crate::models::operator_seat`]): m_pr = (5/7)m_operator + m_seat on the seat
//!   spring and damper between z_s and the cab floor point under it.
//! * Wheels on two tracks: the left wheel of each axle on track 0, the right on track 1, at x_front − x_a
//!   behind the front axle.
//! * Static deflection under gravity g = 9.80665 m/s²: C q_s = −g M e_z (e_z: 1 on every length coordinate),
//!   each element's deflection (g_point − g_far)ᵀ q_s.
//!
//! # Errors
//! [`MachineAssembly::mdof`] rejects masses, inertias, stiffnesses and track widths that are not finite and
//! positive, negative dampings, fewer than two axles or an axle of different track width from the first (the
//! road's two tracks are one distance apart), a cab with fewer than three mounts, a seat without a cab.

use super::{InputLayout, ModelInstance};
use crate::error::{require_positive, Error, Result};
use crate::system::{Attach, Element, Mdof, Quantity};
use std::sync::Arc;

/// Standard gravity, m/s² (for the static deflections).
pub use crate::system::mdof::GRAVITY;

/// A rigid body: mass, pitch and roll inertias about its centre of gravity, and where that is (x, y, z).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody {
    /// kg.
    pub mass: f64,
    /// kg m².
    pub pitch_inertia: f64,
    /// kg m².
    pub roll_inertia: f64,
    /// (x, y, height) of the centre of gravity, m (the body's x and y are 0 by definition).
    pub position: [f64; 3],
}

/// How an axle carries the body.
#[derive(Debug, Clone, PartialEq)]
pub enum AxleKind {
    /// Tyres directly under the body.
    Rigid,
    /// Rolls about a pin on the centre line: roll inertia, pin stiffness (N m/rad) and damping (N m s/rad).
    Oscillating {
        /// kg m².
        roll_inertia: f64,
        /// N m/rad.
        roll_stiffness: f64,
        /// N m s/rad.
        roll_damping: f64,
    },
    /// A suspended wheel at each end: suspension stiffness, damping, unsprung mass per wheel.
    Suspended {
        /// N/m.
        stiffness: f64,
        /// N s/m.
        damping: f64,
        /// kg per wheel.
        unsprung_mass: f64,
    },
}

/// An axle: its name, position ahead of the body's centre of gravity, track width and tyres (per tyre).
#[derive(Debug, Clone, PartialEq)]
pub struct Axle {
    /// Name (element and output names use it).
    pub name: String,
    /// x_a, m (negative behind the centre of gravity).
    pub position: f64,
    /// w, m.
    pub track_width: f64,
    /// Per tyre, N/m.
    pub tyre_stiffness: f64,
    /// Per tyre, N s/m.
    pub tyre_damping: f64,
    /// Rigid, oscillating or suspended.
    pub kind: AxleKind,
}

/// A cab mount at (x, y) with its vertical stiffness and damping.
#[derive(Debug, Clone, PartialEq)]
pub struct Mount {
    /// (x, y), m.
    pub position: [f64; 2],
    /// N/m.
    pub stiffness: f64,
    /// N s/m.
    pub damping: f64,
}

/// The cab: a rigid body on mounts, held horizontally at the mount plane.
#[derive(Debug, Clone, PartialEq)]
pub struct Cab {
    /// Mass, inertias, centre of gravity.
    pub body: RigidBody,
    /// h_m, m.
    pub mount_height: f64,
    /// At least three.
    pub mounts: Vec<Mount>,
}

/// The textbook seat at a point of the cab floor.
#[derive(Debug, Clone, PartialEq)]
pub struct Seat {
    /// (x, y, height) of the seat surface, m.
    pub position: [f64; 3],
    /// kg.
    pub operator_mass: f64,
    /// kg.
    pub seat_mass: f64,
    /// N/m.
    pub stiffness: f64,
    /// N s/m.
    pub damping: f64,
}

/// Which part a point belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The body.
    Body,
    /// The cab.
    Cab,
    /// The seat (vertical motion of the seat mass; horizontal and angular motion of the cab there).
    Seat,
}

/// A direction of motion of a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Longitudinal, m.
    X,
    /// Lateral, m.
    Y,
    /// Vertical, m.
    Z,
    /// Roll of the part, rad.
    Roll,
    /// Pitch of the part, rad.
    Pitch,
}

/// The assembly.
#[derive(Debug, Clone, PartialEq)]
pub struct MachineAssembly {
    /// The body (its position's x and y are ignored: the frame's origin).
    pub body: RigidBody,
    /// Two or more axles.
    pub axles: Vec<Axle>,
    /// The cab, if any.
    pub cab: Option<Cab>,
    /// The seat, if any (needs a cab).
    pub seat: Option<Seat>,
}

fn non_negative(name: &str, v: f64) -> Result<()> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(name, v, "must be finite and >= 0"))
    }
}

fn rigid(name: &str, b: &RigidBody) -> Result<()> {
    require_positive(&format!("{name}.mass"), b.mass)?;
    require_positive(&format!("{name}.pitch_inertia"), b.pitch_inertia)?;
    require_positive(&format!("{name}.roll_inertia"), b.roll_inertia)?;
    Ok(())
}

impl MachineAssembly {
    /// Checks every parameter (see the module's `# Errors`).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the parameter.
    pub fn validate(&self) -> Result<()> {
        rigid("body", &self.body)?;
        if self.axles.len() < 2 {
            return Err(Error::invalid(
                "axle",
                self.axles.len(),
                "a machine needs two or more axles",
            ));
        }
        for (i, a) in self.axles.iter().enumerate() {
            self.validate_axle(i, a)?;
        }
        if let Some(c) = &self.cab {
            rigid("cab", &c.body)?;
            if c.mounts.len() < 3 {
                return Err(Error::invalid(
                    "cab.mount",
                    c.mounts.len(),
                    "a cab needs three or more mounts",
                ));
            }
            for (i, m) in c.mounts.iter().enumerate() {
                require_positive(&format!("cab.mount[{i}].stiffness"), m.stiffness)?;
                non_negative(&format!("cab.mount[{i}].damping"), m.damping)?;
            }
        }
        if let Some(s) = &self.seat {
            if self.cab.is_none() {
                return Err(Error::invalid(
                    "seat",
                    "a seat",
                    "a seat sits on a cab: give [model.cab]",
                ));
            }
            require_positive("seat.operator_mass", s.operator_mass)?;
            non_negative("seat.seat_mass", s.seat_mass)?;
            require_positive("seat.stiffness", s.stiffness)?;
            non_negative("seat.damping", s.damping)?;
        }
        Ok(())
    }

    fn validate_axle(&self, i: usize, a: &Axle) -> Result<()> {
        let key = |k: &str| format!("axle[{i}].{k}");
        require_positive(&key("track_width"), a.track_width)?;
        if a.track_width != self.axles[0].track_width {
            return Err(Error::invalid(
                &key("track_width"),
                a.track_width,
                format!(
                    "every axle must have the track width of the first ({} m): the road's two tracks are one \
                     distance apart",
                    self.axles[0].track_width
                ),
            ));
        }
        require_positive(&key("tyre_stiffness"), a.tyre_stiffness)?;
        non_negative(&key("tyre_damping"), a.tyre_damping)?;
        if !a.position.is_finite() {
            return Err(Error::invalid(&key("position"), a.position, "must be finite"));
        }
        match a.kind {
            AxleKind::Rigid => Ok(()),
            AxleKind::Oscillating {
                roll_inertia,
                roll_stiffness,
                roll_damping,
            } => {
                require_positive(&key("oscillating.roll_inertia"), roll_inertia)?;
                non_negative(&key("oscillating.roll_stiffness"), roll_stiffness)?;
                non_negative(&key("oscillating.roll_damping"), roll_damping)
            }
            AxleKind::Suspended {
                stiffness,
                damping,
                unsprung_mass,
            } => {
                require_positive(&key("suspension.stiffness"), stiffness)?;
                non_negative(&key("suspension.damping"), damping)?;
                require_positive(&key("suspension.unsprung_mass"), unsprung_mass).map(drop)
            }
        }
    }

    /// The coordinates (name, unit, mass or inertia) in order: body z, θ, φ; each axle's φ (oscillating) or
    /// left and right wheel z (suspended); the cab's z, θ, φ; the seat's z.
    pub fn coordinates(&self) -> Vec<(String, &'static str, f64)> {
        let b = &self.body;
        let mut c = vec![
            ("z".to_string(), "m", b.mass),
            ("theta".to_string(), "rad", b.pitch_inertia),
            ("phi".to_string(), "rad", b.roll_inertia),
        ];
        for a in &self.axles {
            match a.kind {
                AxleKind::Rigid => {}
                AxleKind::Oscillating { roll_inertia, .. } => c.push((format!("phi_{}", a.name), "rad", roll_inertia)),
                AxleKind::Suspended { unsprung_mass, .. } => {
                    c.push((format!("z_{}_left", a.name), "m", unsprung_mass));
                    c.push((format!("z_{}_right", a.name), "m", unsprung_mass));
                }
            }
        }
        if let Some(cab) = &self.cab {
            let k = &cab.body;
            c.push(("z_cab".into(), "m", k.mass));
            c.push(("theta_cab".into(), "rad", k.pitch_inertia));
            c.push(("phi_cab".into(), "rad", k.roll_inertia));
        }
        if let Some(s) = &self.seat {
            c.push(("z_seat".into(), "m", 5.0 / 7.0 * s.operator_mass + s.seat_mass));
        }
        c
    }

    fn index(&self, name: &str) -> usize {
        self.coordinates()
            .iter()
            .position(|c| c.0 == name)
            .unwrap_or(usize::MAX)
    }

    fn unit(&self, i: usize) -> Vec<f64> {
        let mut g = vec![0.0; self.coordinates().len()];
        if let Some(w) = g.get_mut(i) {
            *w = 1.0;
        }
        g
    }

    /// Weights of (z, θ, φ) at `names` with lever arms (1, x, y): the vertical motion z + xθ + yφ.
    fn vertical(&self, names: [&str; 3], x: f64, y: f64) -> Vec<f64> {
        let mut g = vec![0.0; self.coordinates().len()];
        for (n, w) in names.iter().zip([1.0, x, y]) {
            g[self.index(n)] += w;
        }
        g
    }

    /// The point weights of the motion of `part` at `point` = (x, y, height) in `direction` (see the module's
    /// `# Formula`).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a cab or seat point of a machine without a cab or seat.
    pub fn point_weights(&self, part: Part, point: [f64; 3], direction: Direction) -> Result<Vec<f64>> {
        let [x, y, h] = point;
        let hb = self.body.position[2];
        if part == Part::Seat && self.seat.is_none() {
            return Err(Error::invalid("part", "seat", "the machine has no seat"));
        }
        let body = ["z", "theta", "phi"];
        let mut g = match part {
            Part::Body => match direction {
                Direction::Z => self.vertical(body, x, y),
                Direction::X | Direction::Y => vec![0.0; self.coordinates().len()],
                Direction::Pitch => self.unit(1),
                Direction::Roll => self.unit(2),
            },
            Part::Cab | Part::Seat => {
                let cab = self
                    .cab
                    .as_ref()
                    .ok_or_else(|| Error::invalid("part", "cab", "the machine has no cab"))?;
                let [xc, yc, _] = cab.body.position;
                let cabc = ["z_cab", "theta_cab", "phi_cab"];
                match direction {
                    Direction::Z if part == Part::Seat => self.unit(self.index("z_seat")),
                    Direction::Z => self.vertical(cabc, x - xc, y - yc),
                    Direction::Pitch => self.unit(self.index("theta_cab")),
                    Direction::Roll => self.unit(self.index("phi_cab")),
                    Direction::X | Direction::Y => vec![0.0; self.coordinates().len()],
                }
            }
        };
        // horizontal motion from pitch (x) and roll (y): −(lever) × angle
        let (body_angle, cab_angle) = match direction {
            Direction::X => (1, "theta_cab"),
            Direction::Y => (2, "phi_cab"),
            _ => return Ok(g),
        };
        match (part, &self.cab) {
            (Part::Body, _) => g[body_angle] -= h - hb,
            (_, Some(cab)) => {
                g[body_angle] -= cab.mount_height - hb;
                g[self.index(cab_angle)] -= h - cab.mount_height;
            }
            (_, None) => {}
        }
        Ok(g)
    }

    /// The wheels as (track, position behind the front axle in m), in input order (each axle left, right).
    pub fn wheels(&self) -> Vec<(usize, f64)> {
        let front = self.axles.iter().map(|a| a.position).fold(f64::NEG_INFINITY, f64::max);
        self.axles
            .iter()
            .flat_map(|a| [(0, front - a.position), (1, front - a.position)])
            .collect()
    }
}

impl MachineAssembly {
    /// The spring–damper elements (tyres, suspensions, axle pins, mounts, seat) and the number of base inputs.
    fn elements(&self) -> (Vec<Element>, usize) {
        let mut els = Vec::new();
        let mut base = 0;
        let el = |name: String, point: Vec<f64>, to: Attach, k: f64, c: f64| Element {
            name,
            point,
            to,
            stiffness: k,
            damping: c,
        };
        for a in &self.axles {
            for (side, y) in [("left", a.track_width / 2.0), ("right", -a.track_width / 2.0)] {
                let corner = self.vertical(["z", "theta", "phi"], a.position, y);
                let tyre_point = match a.kind {
                    AxleKind::Rigid => corner,
                    AxleKind::Oscillating { .. } => {
                        self.vertical(["z", "theta", &format!("phi_{}", a.name)], a.position, y)
                    }
                    AxleKind::Suspended { stiffness, damping, .. } => {
                        let wheel = self.unit(self.index(&format!("z_{}_{side}", a.name)));
                        let name = format!("suspension_{}_{side}", a.name);
                        els.push(el(name, corner, Attach::Point(wheel.clone()), stiffness, damping));
                        wheel
                    }
                };
                let name = format!("tyre_{}_{side}", a.name);
                els.push(el(
                    name,
                    tyre_point,
                    Attach::Base(base),
                    a.tyre_stiffness,
                    a.tyre_damping,
                ));
                base += 1;
            }
            if let AxleKind::Oscillating {
                roll_stiffness,
                roll_damping,
                ..
            } = a.kind
                && roll_stiffness + roll_damping > 0.0
            {
                let pin = self.unit(self.index(&format!("phi_{}", a.name)));
                els.push(el(
                    format!("pin_{}", a.name),
                    pin,
                    Attach::Point(self.unit(2)),
                    roll_stiffness,
                    roll_damping,
                ));
            }
        }
        if let Some(cab) = &self.cab {
            let [xc, yc, _] = cab.body.position;
            for (i, m) in cab.mounts.iter().enumerate() {
                let [x, y] = m.position;
                let on_cab = self.vertical(["z_cab", "theta_cab", "phi_cab"], x - xc, y - yc);
                let on_body = self.vertical(["z", "theta", "phi"], x, y);
                els.push(el(
                    format!("mount_{i}"),
                    on_cab,
                    Attach::Point(on_body),
                    m.stiffness,
                    m.damping,
                ));
            }
            if let Some(s) = &self.seat {
                let floor = self.vertical(
                    ["z_cab", "theta_cab", "phi_cab"],
                    s.position[0] - xc,
                    s.position[1] - yc,
                );
                let seat = self.unit(self.index("z_seat"));
                els.push(el("seat".into(), seat, Attach::Point(floor), s.stiffness, s.damping));
            }
        }
        (els, base)
    }

    /// The [`Mdof`] with the standard outputs: `bounce`, `pitch`, `roll` of the body; per tyre
    /// `tyre_force_<axle>_<side>`; per suspended wheel `travel_<axle>_<side>`; with a cab `cab_bounce`,
    /// `cab_pitch`, `cab_roll` and `mount_<i>_deflection`; with a seat `seat_acc` (vertical), `floor_acc` (the
    /// cab floor under the seat, vertical) and `seat_travel`.
    ///
    /// # Errors
    /// See the module's `# Errors`; those of [`Mdof::from_elements`].
    pub fn mdof(&self) -> Result<Mdof> {
        self.validate()?;
        let coords = self.coordinates();
        let names: Vec<(&str, &str)> = coords.iter().map(|c| (c.0.as_str(), c.1)).collect();
        let masses: Vec<f64> = coords.iter().map(|c| c.2).collect();
        let (els, n_base) = self.elements();
        let mut outs = vec![
            ("bounce".to_string(), Quantity::Displacement(self.unit(0))),
            ("pitch".to_string(), Quantity::Displacement(self.unit(1))),
            ("roll".to_string(), Quantity::Displacement(self.unit(2))),
        ];
        for (i, e) in els.iter().enumerate() {
            if let Some(t) = e.name.strip_prefix("tyre_") {
                outs.push((format!("tyre_force_{t}"), Quantity::ElementForce(i)));
            } else if let Some(t) = e.name.strip_prefix("suspension_") {
                outs.push((format!("travel_{t}"), Quantity::Deflection(i)));
            } else if e.name.starts_with("mount_") {
                outs.push((format!("{}_deflection", e.name), Quantity::Deflection(i)));
            } else if e.name == "seat" {
                outs.push(("seat_travel".into(), Quantity::Deflection(i)));
            }
        }
        if let Some(cab) = &self.cab {
            let p = cab.body.position;
            outs.push((
                "cab_bounce".into(),
                Quantity::Displacement(self.point_weights(Part::Cab, p, Direction::Z)?),
            ));
            outs.push((
                "cab_pitch".into(),
                Quantity::Displacement(self.point_weights(Part::Cab, p, Direction::Pitch)?),
            ));
            outs.push((
                "cab_roll".into(),
                Quantity::Displacement(self.point_weights(Part::Cab, p, Direction::Roll)?),
            ));
        }
        if let Some(s) = &self.seat {
            let seat = self.point_weights(Part::Seat, s.position, Direction::Z)?;
            let floor = self.point_weights(Part::Cab, s.position, Direction::Z)?;
            outs.push(("seat_acc".into(), Quantity::Acceleration(seat)));
            outs.push(("floor_acc".into(), Quantity::Acceleration(floor)));
        }
        let mut m = Mdof::from_elements(&names, &masses, els, n_base, &[])?;
        for (name, q) in outs {
            m = m.with_output(&name, q)?;
        }
        Ok(m)
    }

    /// The static deflection of every element under the machine's weight, (element name, m or rad; > 0 is
    /// compression).
    ///
    /// # Formula
    /// C q_s = −g M e_z, δ = (g_point − g_far)ᵀ q_s (see the module docs); a compressed element has δ < 0,
    /// reported as −δ.
    ///
    /// # Errors
    /// [`Error::Numerical`] if the stiffness matrix is singular (a mechanism).
    pub fn static_deflections(&self, m: &Mdof) -> Result<Vec<(String, f64)>> {
        m.static_deflections()
    }

    /// The random-road model: [`MachineAssembly::mdof`] with its extra outputs `extra` (name, quantity at a
    /// point from [`MachineAssembly::point_weights`], its direction), the wheels on two
    /// tracks, and a description with the natural frequencies and the static deflections.
    ///
    /// # Errors
    /// As [`MachineAssembly::mdof`]; an extra output the model refuses.
    pub fn instance(&self, extra: Vec<(String, Quantity, Direction)>) -> Result<ModelInstance> {
        let mut sys = self.mdof()?;
        let sag = self.static_deflections(&sys)?;
        for (name, q, d) in extra {
            // the horizontal motion from pitch and roll is a length, though its weights are on angles
            sys = match d {
                Direction::X | Direction::Y => sys.with_lever_output(&name, q)?,
                _ => sys.with_output(&name, q)?,
            };
        }
        let (w, _) = sys.modes()?;
        let hz: Vec<String> = w
            .iter()
            .map(|w| format!("{:.3}", w / (2.0 * std::f64::consts::PI)))
            .collect();
        let sag: Vec<String> = sag
            .iter()
            .map(|(n, d)| format!("{n} {}", crate::numbers::sig4(*d)))
            .collect();
        let wheels = self.wheels();
        Ok(ModelInstance {
            system: Arc::new(sys),
            layout: InputLayout::TwoTracks {
                tracks: wheels.iter().map(|w| w.0).collect(),
                positions: wheels.iter().map(|w| w.1).collect(),
                gains: vec![1.0; wheels.len()],
                track_width: Some(self.axles[0].track_width),
            },
            description: format!(
                "machine assembly: {} axles{}{}; natural frequencies [Hz]: {}; static deflection under gravity \
                 [m or rad]: {}",
                self.axles.len(),
                if self.cab.is_some() { ", cab on mounts" } else { "" },
                if self.seat.is_some() { ", seat" } else { "" },
                hz.join(", "),
                sag.join(", ")
            ),
        })
    }
}
