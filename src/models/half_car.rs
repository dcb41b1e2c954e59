//! Half-car bounce/pitch model (Sukharev (2012) 7.5, Example 7.1 and the excavator resonance-speed example).
//!
//! # Formula
//! Rigid body of mass M (kg) and radius of gyration ρ (m) about the centre of mass; springs c₁, c₂ (N/m)
//! and dampers b₁, b₂ (N s/m; the book calls them h₁, h₂) at distances a (front, ahead of the centre of
//! mass) and b (rear, behind it), L = a + b. Coordinates: bounce z (m, up) and pitch φ (rad, positive when
//! the front rises). **Sign convention** (the book's (7.28)): the front axle point moves z₁ = z + aφ, the
//! rear z₂ = z − bφ; road inputs q₁ (front, input 0) and q₂ (rear, input 1).
//! ```text
//! M z̈ + b₁(ż₁ − q̇₁) + b₂(ż₂ − q̇₂) + c₁(z₁ − q₁) + c₂(z₂ − q₂) = 0                      (7.27)
//! Mρ² φ̈ + a[b₁(ż₁ − q̇₁) + c₁(z₁ − q₁)] − b[b₂(ż₂ − q̇₂) + c₂(z₂ − q₂)] = 0
//! ```
//! In the axle coordinates (z₁, z₂) (book (7.28)–(7.31); z = (a z₂ + b z₁)/L, φ = (z₁ − z₂)/L):
//! ```text
//! M₁ z̈₁ + M₃ z̈₂ + b₁ ż₁ + c₁ z₁ = c₁ q₁ + b₁ q̇₁                                          (7.31)
//! M₃ z̈₁ + M₂ z̈₂ + b₂ ż₂ + c₂ z₂ = c₂ q₂ + b₂ q̇₂
//! M₁ = M(b² + ρ²)/L²,   M₂ = M(a² + ρ²)/L²,   M₃ = M(ab − ρ²)/L²,   M₁M₂ − M₃² = M²ρ²/L²
//! ```
//! (the print of (7.30) has the wrong sign on the pitch right-hand side and the text before (7.31) swaps the
//! combinations; (7.31) itself is right). Frequency equation (7.32) and its roots (7.33, corrected):
//! ```text
//! (M₁M₂ − M₃²) ω⁴ − (c₁M₂ + c₂M₁) ω² + c₁c₂ = 0
//! ω²₁,₂ = [c₁M₂ + c₂M₁ ∓ √((c₁M₂ − c₂M₁)² + 4M₃²c₁c₂)] / (2(M₁M₂ − M₃²))
//! ```
//! The printed (7.33) has M₁ and M₂ swapped ([`HalfCar::book_7_33_as_printed`]); the printed frequencies of
//! Example 7.1 come from the correct form. Decoupling (7.34): ab = ρ² ⇒ M₃ = 0 and the axles oscillate
//! independently with ω² = c₁/M₁, c₂/M₂; c₁a = c₂b ⇒ pure bounce ω² = (c₁+c₂)/M and pure pitch
//! ω² = (c₁a² + c₂b²)/(Mρ²). Random road on one track: q₂(t) = q₁(t − L/v). Periodic road of wavelength ℓ
//! at speed v forces at k = 2πv/ℓ, so the resonance speed is v = ωℓ/(2π) (7.36).
//!
//! # Examples
//! ```
//! use stochvib::models::half_car::HalfCar;
//! // Example 7.1: M = 1.49 kN s²/m, a = 1.42 m, b = 1.28 m, ρ = 1.23 m, c₁ = 32 kN/m, c₂ = 43 kN/m
//! let car = HalfCar { mass: 1490.0, radius_of_gyration: 1.23, front_distance: 1.42, rear_distance: 1.28, front_stiffness: 3.2e4, rear_stiffness: 4.3e4, front_damping: 0.0, rear_damping: 0.0 }.build().unwrap();
//! let [w1, w2] = car.frequency_equation_roots();
//! assert!((w1 - 6.93).abs() < 0.01 && (w2 - 7.89).abs() < 0.01);
//! ```

use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::fields::Fields;
use crate::models::worked_example::BookRow;
use crate::models::{InputLayout, ModelInstance};
use crate::system::{modal_analysis, Attach, Element, Mdof, Quantity};
use crate::units::Dim;
use nalgebra::DMatrix;
use std::f64::consts::PI;
use std::sync::Arc;

/// Relative tolerance of the decoupling checks: |ab − ρ²| ≤ 1e-9·max(ab, ρ²) and likewise for c₁a = c₂b
/// (the conditions are design equalities; 1e-9 accepts values typed with ~9 significant digits).
pub const DECOUPLING_TOL: f64 = 1e-9;

/// Half-car bounce/pitch model (book 7.5).
///
/// # Formula
/// See the module docs.
///
/// # Errors
/// [`HalfCar::build`] rejects non-positive M, ρ, a, b, c₁, c₂, negative b₁, b₂ and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::half_car::HalfCar;
/// let car = HalfCar {
///     mass: 1490.0,
///     radius_of_gyration: 1.23,
///     front_distance: 1.42,
///     rear_distance: 1.28,
///     front_stiffness: 3.2e4,
///     rear_stiffness: 4.3e4,
///     front_damping: 0.0,
///     rear_damping: 0.0,
/// }
/// .build()
/// .unwrap();
/// let (m1, m2, m3) = car.masses();
/// assert!((m1 * m2 - m3 * m3 - (1490.0f64 * 1.23 / 2.7).powi(2)).abs() < 1e-6);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct HalfCar {
    /// M, kg.
    pub mass: f64,
    /// ρ, m (pitch moment of inertia Mρ²).
    pub radius_of_gyration: f64,
    /// a, m: front axle ahead of the centre of mass.
    pub front_distance: f64,
    /// b, m: rear axle behind the centre of mass.
    pub rear_distance: f64,
    /// c₁, N/m (front).
    pub front_stiffness: f64,
    /// c₂, N/m (rear).
    pub rear_stiffness: f64,
    /// b₁, N s/m (front).
    pub front_damping: f64,
    /// b₂, N s/m (rear).
    pub rear_damping: f64,
}

/// Which of the book's decoupling conditions hold (see [`HalfCar::decoupling`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Decoupling {
    /// ab − ρ², m².
    pub ab_minus_rho2: f64,
    /// c₁a − c₂b, N.
    pub c1a_minus_c2b: f64,
    /// ab = ρ² (within [`DECOUPLING_TOL`]): M₃ = 0, the axle points are conjugate (independent axle modes).
    pub conjugate_axles: bool,
    /// c₁a = c₂b (within [`DECOUPLING_TOL`]): pure bounce and pure pitch modes.
    pub bounce_pitch_uncoupled: bool,
}

impl HalfCar {
    /// The car of these fields, checked: M (kg), ρ (m), a, b (m), c₁, c₂ (N/m), b₁, b₂ (N s/m) as named
    /// fields instead of eight bare numbers of different meaning.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        let HalfCar {
            mass,
            radius_of_gyration,
            front_distance,
            rear_distance,
            front_stiffness,
            rear_stiffness,
            front_damping,
            rear_damping,
        } = self;
        Ok(HalfCar {
            mass: require_positive("mass", mass)?,
            radius_of_gyration: require_positive("radius_of_gyration", radius_of_gyration)?,
            front_distance: require_positive("front_distance", front_distance)?,
            rear_distance: require_positive("rear_distance", rear_distance)?,
            front_stiffness: require_positive("front_stiffness", front_stiffness)?,
            rear_stiffness: require_positive("rear_stiffness", rear_stiffness)?,
            front_damping: require_non_negative("front_damping", front_damping)?,
            rear_damping: require_non_negative("rear_damping", rear_damping)?,
        })
    }

    /// Wheelbase L = a + b, m.
    pub fn wheelbase(&self) -> f64 {
        self.front_distance + self.rear_distance
    }

    /// (M₁, M₂, M₃), kg: M(b²+ρ²)/L², M(a²+ρ²)/L², M(ab−ρ²)/L².
    pub fn masses(&self) -> (f64, f64, f64) {
        let (m, r2, a, b) = (
            self.mass,
            self.radius_of_gyration.powi(2),
            self.front_distance,
            self.rear_distance,
        );
        let l2 = self.wheelbase().powi(2);
        (m * (b * b + r2) / l2, m * (a * a + r2) / l2, m * (a * b - r2) / l2)
    }

    /// Natural frequencies (rad/s, ascending) from the frequency equation (7.32), i.e. the corrected (7.33).
    ///
    /// # Formula
    /// ω²₁,₂ = [c₁M₂ + c₂M₁ ∓ √((c₁M₂ − c₂M₁)² + 4M₃²c₁c₂)] / (2(M₁M₂ − M₃²)); the smaller root is taken
    /// from Vieta's product c₁c₂/(M₁M₂ − M₃²) to avoid cancellation.
    pub fn frequency_equation_roots(&self) -> [f64; 2] {
        let (m1, m2, m3) = self.masses();
        let (c1, c2) = (self.front_stiffness, self.rear_stiffness);
        let det = m1 * m2 - m3 * m3;
        let s = c1 * m2 + c2 * m1;
        let disc = ((c1 * m2 - c2 * m1).powi(2) + 4.0 * m3 * m3 * c1 * c2).sqrt();
        let hi = (s + disc) / (2.0 * det);
        let lo = c1 * c2 / (det * hi);
        [lo.sqrt(), hi.sqrt()]
    }

    /// The book's (7.33) **as printed** (M₁ and M₂ swapped, a misprint):
    /// ω²₁,₂ = [c₁M₁ + c₂M₂ ∓ √((c₁M₁ − c₂M₂)² + 4M₃²c₁c₂)] / (2(M₁M₂ − M₃²)). For the book rows only.
    pub fn book_7_33_as_printed(&self) -> [f64; 2] {
        let (m1, m2, m3) = self.masses();
        let (c1, c2) = (self.front_stiffness, self.rear_stiffness);
        let det = m1 * m2 - m3 * m3;
        let s = c1 * m1 + c2 * m2;
        let disc = ((c1 * m1 - c2 * m2).powi(2) + 4.0 * m3 * m3 * c1 * c2).sqrt();
        [((s - disc) / (2.0 * det)).sqrt(), ((s + disc) / (2.0 * det)).sqrt()]
    }

    /// Mass and stiffness matrices of the (z, φ) model: M_b = diag(M, Mρ²),
    /// K_b = [[c₁ + c₂, c₁a − c₂b], [c₁a − c₂b, c₁a² + c₂b²]].
    pub fn bounce_pitch_matrices(&self) -> (DMatrix<f64>, DMatrix<f64>) {
        let (a, b, c1, c2) = (
            self.front_distance,
            self.rear_distance,
            self.front_stiffness,
            self.rear_stiffness,
        );
        let m = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(vec![
            self.mass,
            self.mass * self.radius_of_gyration.powi(2),
        ]));
        let k = DMatrix::from_row_slice(
            2,
            2,
            &[c1 + c2, c1 * a - c2 * b, c1 * a - c2 * b, c1 * a * a + c2 * b * b],
        );
        (m, k)
    }

    /// Natural frequencies (rad/s) and mass-normalised modes (columns: (z, φ)) by [`modal_analysis`] of the
    /// (z, φ) matrices — an independent route to [`HalfCar::frequency_equation_roots`].
    ///
    /// # Errors
    /// Those of [`modal_analysis`] (none for a validated model).
    pub fn modes(&self) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let (m, k) = self.bounce_pitch_matrices();
        modal_analysis(&m, &k)
    }

    /// Reports the decoupling conditions ab = ρ² and c₁a = c₂b (book 7.5, (7.34) and the text around it).
    pub fn decoupling(&self) -> Decoupling {
        let (a, b, r2) = (self.front_distance, self.rear_distance, self.radius_of_gyration.powi(2));
        let (c1a, c2b) = (self.front_stiffness * a, self.rear_stiffness * b);
        Decoupling {
            ab_minus_rho2: a * b - r2,
            c1a_minus_c2b: c1a - c2b,
            conjugate_axles: (a * b - r2).abs() <= DECOUPLING_TOL * (a * b).max(r2),
            bounce_pitch_uncoupled: (c1a - c2b).abs() <= DECOUPLING_TOL * c1a.max(c2b),
        }
    }

    /// The (z, φ) model as an [`Mdof`]: coordinates `z` (m), `phi` (rad); elements `front` (point z + aφ to
    /// base input 0) and `rear` (point z − bφ to base input 1); outputs `bounce` (z, m), `pitch` (φ, rad),
    /// `front_travel` (z + aφ − q₁, m), `rear_travel` (z − bφ − q₂, m), `body_acc` (z̈ + x_p φ̈ at the
    /// point x_p = `acc_point` metres ahead of the centre of mass, m/s²: the points combine z (m) and φ (rad),
    /// whose weights are lever arms in m/rad).
    ///
    /// # Errors
    /// Non-finite `acc_point`.
    pub fn mdof(&self, acc_point: f64) -> Result<Mdof> {
        if !acc_point.is_finite() {
            return Err(Error::invalid("acc_point", acc_point, "must be finite"));
        }
        let (a, b) = (self.front_distance, self.rear_distance);
        let els = vec![
            Element {
                name: "front".into(),
                point: vec![1.0, a],
                to: Attach::Base(0),
                stiffness: self.front_stiffness,
                damping: self.front_damping,
            },
            Element {
                name: "rear".into(),
                point: vec![1.0, -b],
                to: Attach::Base(1),
                stiffness: self.rear_stiffness,
                damping: self.rear_damping,
            },
        ];
        Mdof::from_elements(
            &[("z", "m"), ("phi", "rad")],
            &[self.mass, self.mass * self.radius_of_gyration.powi(2)],
            els,
            2,
            &[],
        )?
        .with_output("bounce", Quantity::Displacement(vec![1.0, 0.0]))?
        .with_output("pitch", Quantity::Displacement(vec![0.0, 1.0]))?
        .with_output("front_travel", Quantity::Deflection(0))?
        .with_output("rear_travel", Quantity::Deflection(1))?
        .with_output("body_acc", Quantity::Acceleration(vec![1.0, acc_point]))
    }

    /// The random-road model: the [`HalfCar::mdof`] system (travels labelled m, `body_acc` m/s²) and
    /// `InputLayout::Track { positions: [0, L], gains: [1, 1] }` — the rear wheel follows the front wheel's
    /// track with the delay L/v.
    ///
    /// # Errors
    /// As [`HalfCar::mdof`].
    pub fn instance(&self, acc_point: f64) -> Result<ModelInstance> {
        let mdof = self.mdof(acc_point)?;
        Ok(ModelInstance {
            system: Arc::new(mdof),
            layout: InputLayout::Track {
                positions: vec![0.0, self.wheelbase()],
                gains: vec![1.0, 1.0],
            },
            description: format!(
                "half car bounce/pitch (Sukharev 7.5): M = {} kg, rho = {} m, a = {} m, b = {} m, c1 = {} N/m, \
                 c2 = {} N/m, b1 = {} N s/m, b2 = {} N s/m, acceleration at {} m ahead of the centre of mass",
                self.mass,
                self.radius_of_gyration,
                self.front_distance,
                self.rear_distance,
                self.front_stiffness,
                self.rear_stiffness,
                self.front_damping,
                self.rear_damping,
                acc_point
            ),
        })
    }
}

/// Resonance speed on a periodic road of wavelength ℓ (m) for a natural frequency ω (rad/s) (7.36).
///
/// # Formula
/// The road z = (h/2)(1 − cos 2πx/ℓ) traversed at speed v forces at k = 2πv/ℓ; k = ω at v = ωℓ/(2π) (m/s).
///
/// # Errors
/// Non-positive or non-finite ω or ℓ.
///
/// # Examples
/// ```
/// use stochvib::models::half_car::resonance_speed;
/// assert!((resonance_speed(2.0 * std::f64::consts::PI, 7.0).unwrap() - 7.0).abs() < 1e-15);
/// ```
pub fn resonance_speed(natural_frequency: f64, wavelength: f64) -> Result<f64> {
    require_positive("natural_frequency", natural_frequency)?;
    require_positive("wavelength", wavelength)?;
    Ok(natural_frequency * wavelength / (2.0 * PI))
}

/// An axle load Q on a spring c under gravity g (book 7.5, the excavator example, Fig. 7.7). Named fields:
/// three positive numbers of different units cannot be swapped silently.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxleOnSpring {
    /// c, N/m.
    pub stiffness: f64,
    /// Q, the axle load (a force), N.
    pub axle_load: f64,
    /// g, m/s².
    pub gravity: f64,
}

impl AxleOnSpring {
    /// Natural frequency of the axle load on its spring, rad/s.
    ///
    /// # Formula
    /// m = Q/g, so ω = √(c/m) = √(c g/Q).
    ///
    /// # Errors
    /// Non-positive or non-finite fields, each named.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::half_car::AxleOnSpring;
    /// let a = AxleOnSpring { stiffness: 9.0e4, axle_load: 2.86e4, gravity: 9.8 };
    /// assert!((a.natural_frequency().unwrap() - 5.5533).abs() < 1e-4);
    /// ```
    pub fn natural_frequency(&self) -> Result<f64> {
        require_positive("stiffness", self.stiffness)?;
        require_positive("axle_load", self.axle_load)?;
        require_positive("gravity", self.gravity)?;
        Ok((self.stiffness * self.gravity / self.axle_load).sqrt())
    }
}

/// Reads a `kind = "half-car"` `[model]` table: `mass`, `radius_of_gyration`, `front_distance` (a),
/// `rear_distance` (b), `front_stiffness` (c₁), `rear_stiffness` (c₂), optional `front_damping` (b₁),
/// `rear_damping` (b₂) (default 0) and `acc_point` (m ahead of the centre of mass, default 0).
///
/// # Errors
/// [`Error::File`] naming the key for a missing or invalid value.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    let car = HalfCar {
        mass: f.quantity("mass", Dim::MASS)?,
        radius_of_gyration: f.quantity("radius_of_gyration", Dim::LENGTH)?,
        front_distance: f.quantity("front_distance", Dim::LENGTH)?,
        rear_distance: f.quantity("rear_distance", Dim::LENGTH)?,
        front_stiffness: f.quantity("front_stiffness", Dim::STIFFNESS)?,
        rear_stiffness: f.quantity("rear_stiffness", Dim::STIFFNESS)?,
        front_damping: f.opt_quantity("front_damping", Dim::DAMPING)?.unwrap_or(0.0),
        rear_damping: f.opt_quantity("rear_damping", Dim::DAMPING)?.unwrap_or(0.0),
    }
    .build()
    .map_err(|e| f.wrap_param(e, "kind"))?;
    let x = f.opt_quantity("acc_point", Dim::LENGTH)?.unwrap_or(0.0);
    car.instance(x).map_err(|e| f.wrap("acc_point", e))
}

/// Example 7.1 (Sukharev (2012) 7.5): M = 1.49 kN s²/m, a = 1.42 m, b = 1.28 m, ρ = 1.23 m, c₁ = 32 kN/m,
/// c₂ = 43 kN/m (no damping printed; none needed for natural frequencies).
pub fn example_7_1() -> HalfCar {
    HalfCar {
        mass: 1490.0,
        radius_of_gyration: 1.23,
        front_distance: 1.42,
        rear_distance: 1.28,
        front_stiffness: 3.2e4,
        rear_stiffness: 4.3e4,
        front_damping: 0.0,
        rear_damping: 0.0,
    }
    .build()
    .expect("valid book parameters")
}

/// Book rows: Example 7.1 (M₁, M₂, M₃, ω₁, ω₂, also through the printed (7.33) and through modal analysis)
/// and the excavator resonance-speed example (ω, v in m/s and km/h).
pub fn book_rows() -> Vec<BookRow> {
    let ex = "Sukharev (2012) 7.5, Example 7.1 (half car)";
    let car = example_7_1();
    let (m1, m2, m3) = car.masses();
    let roots = car.frequency_equation_roots();
    let printed_form = car.book_7_33_as_printed();
    let modal = car.modes().map(|(w, _)| w).ok();
    let row = |q: &str, unit: &str, printed: f64, computed: Option<f64>, why: &str| BookRow {
        example: ex.into(),
        quantity: q.into(),
        unit: unit.into(),
        printed: Some(printed),
        computed,
        explanation: why.into(),
    };
    let mut rows = vec![
        row("M1", "kg", 643.0, Some(m1), "M(b^2+rho^2)/L^2; printed 0.643 t"),
        row("M2", "kg", 721.0, Some(m2), "M(a^2+rho^2)/L^2; printed 0.721 t"),
        row("M3", "kg", 63.0, Some(m3), "M(ab-rho^2)/L^2; printed 0.063 t (rounded)"),
        row(
            "omega_1",
            "rad/s",
            6.93,
            Some(roots[0]),
            "frequency equation (7.32) / corrected (7.33)",
        ),
        row(
            "omega_2",
            "rad/s",
            7.92,
            Some(roots[1]),
            "frequency equation (7.32) / corrected (7.33); the rounded M1, M2, M3 give 7.893, the rest is the \
             book's arithmetic",
        ),
        row(
            "omega_1 (modal analysis of the (z, phi) model)",
            "rad/s",
            6.93,
            modal.as_ref().map(|w| w[0]),
            "generalised eigenproblem K_b phi = w^2 M_b phi (independent of (7.32))",
        ),
        row(
            "omega_2 (modal analysis of the (z, phi) model)",
            "rad/s",
            7.92,
            modal.as_ref().map(|w| w[1]),
            "generalised eigenproblem K_b phi = w^2 M_b phi (independent of (7.32))",
        ),
        row(
            "omega_1 via (7.33) as printed",
            "rad/s",
            6.93,
            Some(printed_form[0]),
            "misprint: printed (7.33) swaps M1 and M2; the printed omegas come from the correct form (row omega_1)",
        ),
        row(
            "omega_2 via (7.33) as printed",
            "rad/s",
            7.92,
            Some(printed_form[1]),
            "misprint: printed (7.33) swaps M1 and M2; the printed omegas come from the correct form (row omega_2)",
        ),
    ];
    rows.extend(excavator_rows());
    rows
}

/// Book rows of the excavator resonance-speed example (ω, v in m/s and km/h).
fn excavator_rows() -> Vec<BookRow> {
    let mut rows = Vec::new();
    // Excavator example (Sukharev (2012) 7.5, the first of the two examples numbered 7.2; Fig. 7.7):
    // ℓ = 7 m, Q = 28.6 kN, c = 90 kN/m, g = 9.8 m/s².
    let ex2 = "Sukharev (2012) 7.5, excavator resonance-speed example (Fig. 7.7)";
    let w = AxleOnSpring {
        stiffness: 9.0e4,
        axle_load: 2.86e4,
        gravity: 9.8,
    }
    .natural_frequency()
    .ok();
    let v = w.and_then(|w| resonance_speed(w, 7.0).ok());
    for (q, unit, printed, computed, why) in [
        (
            "omega = sqrt(c g / Q)",
            "rad/s",
            5.56,
            w,
            "c = 90 kN/m, Q = 28.6 kN, g = 9.8 m/s^2",
        ),
        (
            "v_res = omega l / (2 pi)",
            "m/s",
            6.2,
            v,
            "l = 7 m; printed 6.2 m/s (the book takes pi = 3.14)",
        ),
        (
            "v_res in km/h",
            "m/s",
            22.3 / 3.6,
            v,
            "printed 22.3 km/h, converted to m/s",
        ),
    ] {
        rows.push(BookRow {
            example: ex2.into(),
            quantity: q.into(),
            unit: unit.into(),
            printed: Some(printed),
            computed,
            explanation: why.into(),
        });
    }
    rows
}
