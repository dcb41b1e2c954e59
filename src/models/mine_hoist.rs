//! Single-end mine hoist: drum, head sheave and end mass on an elastic rope with slowly varying hanging
//! length, its natural frequencies and modes over the lift, and the "nodal point" of mode 1
//! (Dvornikov, Kondrakhin & Velebnik (2014); full citation in [`crate::models`]).

use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::fields::Fields;
use crate::models::results::{Cell, DeterministicModel, ResultTable};
use crate::models::worked_example::BookRow;
use crate::numbers::num;
use crate::system::modal_analysis;
use crate::units::Dim;
use nalgebra::{DMatrix, DVector};

/// Mass per unit length, kg/m.
const LINEAR_DENSITY: Dim = Dim::new(-1, 1, 0);
/// Mass per unit volume, kg/m³.
const DENSITY: Dim = Dim::new(-3, 1, 0);
/// Pressure / elastic modulus, Pa.
const PRESSURE: Dim = Dim::new(-1, 1, -2);

/// Physical parameters of the single-end hoist (SI units in every field name's doc).
#[derive(Debug, Clone, PartialEq)]
pub struct MineHoistParams {
    /// E, elastic modulus of the wire steel, Pa (source: 2.06·10¹¹ N/m², text after eq. (3)).
    pub young_modulus: f64,
    /// ā, dimensionless rope-construction factor of the metallic area ā d_k² (source ≈ 0.315, text after
    /// eq. (3)).
    pub rope_area_factor: f64,
    /// d_k, rope diameter, m.
    pub rope_diameter: f64,
    /// γ, rope mass per metre, kg/m (the model uses this value; source prints 8.4).
    pub rope_mass_per_metre: f64,
    /// γ̄, dimensionless rope-mass factor in γ = γ̄ γ_st d_k² (source 0.491, text after eq. (5)), if given.
    pub rope_mass_factor: Option<f64>,
    /// γ_st, steel density, kg/m³ (source 7800, text after eq. (5)), if given.
    pub steel_density: Option<f64>,
    /// R_b, drum radius, m.
    pub drum_radius: f64,
    /// R_s, head-sheave radius, m.
    pub sheave_radius: f64,
    /// l₁, length of the inclined rope chord drum–sheave, m (constant).
    pub chord_length: f64,
    /// H, lift height, m.
    pub lift_height: f64,
    /// L = l₀₂, largest hanging length (at the start of the lift), m.
    pub max_hanging_length: f64,
    /// α, inclination of the chord, rad (enters only the generalised forces Q, not M or C).
    pub chord_angle: f64,
    /// J₁, drum inertia with reduced drive parts (empty drum, ȳ = 0), kg m².
    pub drum_inertia: f64,
    /// J₂, head-sheave inertia, kg m².
    pub sheave_inertia: f64,
    /// m, loaded end mass (skip), kg.
    pub end_mass: f64,
}

/// Single-end mine hoist, 3-DOF, with "frozen" (slowly varying) hanging length l₂.
///
/// Coordinates X = (R_bφ_b, R_sφ_s, y) in metres (rope travel at drum and sheave, load position);
/// masses in kg, stiffnesses in N/m, ω in rad/s, lengths in m.
///
/// # Formula
/// Rope stiffnesses (3): C_str = Eād_k²/l₁, C_otv = Eād_k²/l₂; γ = γ̄γ_st d_k² (text after (5));
/// l₂ = L − ȳ (4); drum inertia with the wound rope (9): J₁′ = J₁ + γR_b²ȳ = J₁ + γR_b²(L − l₂).
/// Equations (13) M Ẍ + B Ẋ + C X = Q with B = 2δC and (14):
/// ```text
/// M(l₂) = [[J₁′/R_b² + γl₁/4, γl₁/4,                   0         ],
///          [γl₁/4,            J₂/R_s² + γ(l₁ + l₂)/4,  γl₂/4     ],
///          [0,                γl₂/4,                   m + γl₂/4 ]]
/// C(l₂) = [[C_str, −C_str, 0], [−C_str, C_str + C_otv, −C_otv], [0, −C_otv, C_otv]]
/// ```
/// det C ≡ 0 ⇒ ω₀ = 0 with Φ₀ = (1, 1, 1) (21); the total mass 1ᵀM1 = m_Σ = J₁/R_b² + J₂/R_s² + m + γ(l₁ + L)
/// is constant over the lift (the unnumbered N₀² = m_Σ after (23) prints J₁′ and l₂, which gives the same
/// sum). The frequency equation (15)/(16) det(C − ω²M) = 0 is, with λ = ω² and the tridiagonal entries
/// a_ij(λ) = C_ij − λM_ij,
/// ```text
/// a₁₁a₂₂a₃₃ − a₁₁a₂₃² − a₃₃a₁₂² = λ(c₁ + c₂λ + c₃λ²) = 0
/// ```
/// (no constant term, det C = 0); ω₁², ω₂² are the roots of the quadratic. Cofactor modes (20):
/// ```text
/// Φ_j ∝ ((C_str + ω_j²γl₁/4)a₃₃,  a₁₁a₃₃,  a₁₁(C_otv + ω_j²γl₂/4)),
/// a₁₁ = C_str − ω_j²(γl₁/4 + J₁′/R_b²),  a₃₃ = C_otv − ω_j²(m + γl₂/4)
/// ```
/// normalised (24) Φ̃_j = √m_Σ Φ_j/N_j, N_j² = Φ_jᵀMΦ_j (22)/(23).
///
/// **The nodal point** (point U of Fig. 2b; the unnumbered equations between Fig. 2 and (22)). The cofactor vector
/// vanishes when a₁₁ = a₃₃ = 0 together; then ω₁² = C_otv/(m + γl₂/4) = C_str/(γl₁/4 + J₁′/R_b²). The true eigenvector
/// there is not zero: it is ∝ (C_otv + ω²γl₂/4, 0, −(C_str + ω²γl₁/4)) — drum and load in anti-phase, sheave at rest —
/// so the "node" is an artefact of building the modes from one cofactor row, and the sheave component of the continuous
/// eigenvector changes sign there. Compatibility gives (with J₁′ = J₁ + γR_b²(L − l₂))
/// ```text
/// l₂* = (2/γ)[−(m + γl₁) + √((m + γl₁)² + γl₁(γl₁/4 + J₁/R_b² + γL))]
/// ```
/// The printed node formula (unnumbered, just before (22)) has J₁′ where **J₁** must stand (with J₁′ the
/// formula is implicit).
///
/// **Renormalisation (25)** as printed, Φ̄_jk = √m_Σ Φ_jk sgn(Φ_jk)/N_j, would make every component
/// non-negative: it is garbled. The intended rule is to flip the whole vector with the sign of one
/// component that changes sign at the node, e.g. sgn(a₃₃): Φ̄_j = √m_Σ sgn(a₃₃(ω_j)) Φ_j/N_j
/// ([`MineHoist::renormalised_cofactor_mode`]). [`MineHoist::sweep`] gets the same continuous family
/// from the eigensolver by choosing at every sweep point the sign with Φ̄(ξ_i)ᵀM(ξ_i)Φ̄(ξ_{i−1}) > 0,
/// starting from the sign of (25) at ξ = 0.
///
/// **Sweep parameter.** The print defines ξ = l₂/H ∈ [0, 1], but l₂ = L − ȳ runs over [L − H, L] =
/// [75, 700] m, i.e. l₂/H ∈ [0.12, 1.12]. This crate uses **ξ = ȳ/H ∈ [0, 1], l₂ = L − ξH** (ξ = 0 at the
/// start of the lift, ξ = 1 with the skip at the top).
///
/// # Errors
/// [`MineHoist::new`] rejects non-positive or non-finite E, ā, d_k, radii, l₁, H, L, J₁, J₂, m; negative γ;
/// H > L (the hanging length would become negative); functions of l₂ reject l₂ outside (0, L].
///
/// # Examples
/// ```
/// use stochvib::models::mine_hoist::MineHoist;
/// let h = MineHoist::printed();
/// // rigid mode and constant total mass
/// let modes = h.modes(700.0).unwrap();
/// assert_eq!(modes.omega[0], 0.0);
/// let m = h.mass_matrix(400.0).unwrap();
/// assert!((m.sum() - h.total_mass()).abs() < 1e-9 * h.total_mass());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct MineHoist {
    p: MineHoistParams,
}

/// Frequencies (rad/s, ascending; ω₀ = 0) and modes of the hoist at one hanging length.
#[derive(Debug, Clone, PartialEq)]
pub struct HoistModes {
    /// ω₀ = 0, ω₁, ω₂, rad/s.
    pub omega: [f64; 3],
    /// Columns Φ_j scaled so that Φ_jᵀMΦ_j = m_Σ (the √m_Σ normalisation of (24)), m (per unit modal
    /// coordinate); sign as returned by [`modal_analysis`] (largest component positive).
    pub shapes: DMatrix<f64>,
}

/// One point of the ξ sweep with sign-continuous modes.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    /// ξ = ȳ/H.
    pub xi: f64,
    /// l₂ = L − ξH, m.
    pub l2: f64,
    /// ω₁, rad/s.
    pub omega1: f64,
    /// ω₂, rad/s.
    pub omega2: f64,
    /// Renormalised Φ̄₁ (drum, sheave, load), Φ̄ᵀMΦ̄ = m_Σ.
    pub mode1: [f64; 3],
    /// Renormalised Φ̄₂.
    pub mode2: [f64; 3],
}

impl MineHoist {
    /// Builds the model.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn new(p: MineHoistParams) -> Result<Self> {
        for (name, v) in [
            ("young_modulus", p.young_modulus),
            ("rope_area_factor", p.rope_area_factor),
            ("rope_diameter", p.rope_diameter),
            ("drum_radius", p.drum_radius),
            ("sheave_radius", p.sheave_radius),
            ("chord_length", p.chord_length),
            ("lift_height", p.lift_height),
            ("max_hanging_length", p.max_hanging_length),
            ("drum_inertia", p.drum_inertia),
            ("sheave_inertia", p.sheave_inertia),
            ("end_mass", p.end_mass),
        ] {
            require_positive(name, v)?;
        }
        require_non_negative("rope_mass_per_metre", p.rope_mass_per_metre)?;
        if let Some(v) = p.rope_mass_factor {
            require_positive("rope_mass_factor", v)?;
        }
        if let Some(v) = p.steel_density {
            require_positive("steel_density", v)?;
        }
        if !p.chord_angle.is_finite() {
            return Err(Error::invalid("chord_angle", p.chord_angle, "must be finite"));
        }
        if p.lift_height >= p.max_hanging_length {
            return Err(Error::invalid(
                "lift_height",
                p.lift_height,
                format!(
                    "must be < max_hanging_length = {} m (the hanging rope length L − H must stay positive)",
                    p.max_hanging_length
                ),
            ));
        }
        Ok(MineHoist { p })
    }

    /// The parameters printed in the source (E and ā after eq. (3), γ̄ and γ_st after eq. (5), and the
    /// input data listed for Fig. 2), with the printed γ = 8.4 kg/m.
    pub fn printed() -> Self {
        MineHoist {
            p: MineHoistParams {
                young_modulus: 2.06e11,
                rope_area_factor: 0.315,
                rope_diameter: 0.0465,
                rope_mass_per_metre: 8.4,
                rope_mass_factor: Some(0.491),
                steel_density: Some(7800.0),
                drum_radius: 2.0,
                sheave_radius: 2.0,
                chord_length: 30.0,
                lift_height: 625.0,
                max_hanging_length: 700.0,
                chord_angle: std::f64::consts::PI / 6.0,
                drum_inertia: 625000.0,
                sheave_inertia: 30000.0,
                end_mass: 10000.0,
            },
        }
    }

    /// Reads the `[model]` table: `young_modulus` (Pa), `rope_area_factor` (–), `rope_diameter` (m),
    /// `rope_mass_per_metre` (kg/m), optional `rope_mass_factor` (–) and `steel_density` (kg/m³),
    /// `drum_radius`, `sheave_radius`, `chord_length`, `lift_height`, `max_hanging_length` (m),
    /// `chord_angle` (rad, or `"30 deg"`), `drum_inertia`, `sheave_inertia` (kg m²), `end_mass` (kg).
    ///
    /// # Errors
    /// Missing keys, wrong units, invalid values (named by file and key).
    pub fn from_fields(f: &Fields) -> Result<Self> {
        let p = MineHoistParams {
            young_modulus: f.quantity("young_modulus", PRESSURE)?,
            rope_area_factor: f.quantity("rope_area_factor", Dim::DIMENSIONLESS)?,
            rope_diameter: f.quantity("rope_diameter", Dim::LENGTH)?,
            rope_mass_per_metre: f.quantity("rope_mass_per_metre", LINEAR_DENSITY)?,
            rope_mass_factor: f.opt_quantity("rope_mass_factor", Dim::DIMENSIONLESS)?,
            steel_density: f.opt_quantity("steel_density", DENSITY)?,
            drum_radius: f.quantity("drum_radius", Dim::LENGTH)?,
            sheave_radius: f.quantity("sheave_radius", Dim::LENGTH)?,
            chord_length: f.quantity("chord_length", Dim::LENGTH)?,
            lift_height: f.quantity("lift_height", Dim::LENGTH)?,
            max_hanging_length: f.quantity("max_hanging_length", Dim::LENGTH)?,
            chord_angle: f.quantity("chord_angle", Dim::DIMENSIONLESS)?,
            drum_inertia: f.quantity("drum_inertia", Dim::INERTIA)?,
            sheave_inertia: f.quantity("sheave_inertia", Dim::INERTIA)?,
            end_mass: f.quantity("end_mass", Dim::MASS)?,
        };
        MineHoist::new(p).map_err(|e| match &e {
            Error::InvalidParameter { name, .. } => {
                let key = name.clone();
                f.wrap(&key, e)
            }
            _ => e,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &MineHoistParams {
        &self.p
    }

    /// E ā d_k², N (the axial stiffness times length of the rope).
    pub fn rope_axial_rigidity(&self) -> f64 {
        self.p.young_modulus * self.p.rope_area_factor * self.p.rope_diameter * self.p.rope_diameter
    }

    /// γ = γ̄ γ_st d_k² (text after eq. (5)), kg/m, when γ̄ and γ_st are given.
    pub fn rope_mass_per_metre_formula(&self) -> Option<f64> {
        Some(self.p.rope_mass_factor? * self.p.steel_density? * self.p.rope_diameter.powi(2))
    }

    /// C_str = Eād_k²/l₁, N/m (3).
    pub fn chord_stiffness(&self) -> f64 {
        self.rope_axial_rigidity() / self.p.chord_length
    }

    /// C_otv = Eād_k²/l₂, N/m (3).
    ///
    /// # Errors
    /// l₂ outside (0, L].
    pub fn hanging_stiffness(&self, l2: f64) -> Result<f64> {
        self.check_l2(l2)?;
        Ok(self.rope_axial_rigidity() / l2)
    }

    /// J₁′ = J₁ + γR_b²(L − l₂), kg m² (9).
    ///
    /// # Errors
    /// l₂ outside (0, L].
    pub fn drum_inertia_with_rope(&self, l2: f64) -> Result<f64> {
        self.check_l2(l2)?;
        Ok(self.j1_prime(l2))
    }

    fn j1_prime(&self, l2: f64) -> f64 {
        self.p.drum_inertia + self.p.rope_mass_per_metre * self.p.drum_radius.powi(2) * (self.p.max_hanging_length - l2)
    }

    fn check_l2(&self, l2: f64) -> Result<()> {
        if !(l2.is_finite() && l2 > 0.0 && l2 <= self.p.max_hanging_length) {
            return Err(Error::invalid(
                "l2",
                l2,
                format!("hanging length must be in (0, {}] m", self.p.max_hanging_length),
            ));
        }
        Ok(())
    }

    /// l₂ = L − ξH, m, for ξ = ȳ/H (this crate's choice; see the type's docs).
    ///
    /// # Errors
    /// ξ outside [0, 1].
    pub fn hanging_length(&self, xi: f64) -> Result<f64> {
        if !(0.0..=1.0).contains(&xi) {
            return Err(Error::invalid("xi", xi, "xi = y/H must be in [0, 1]"));
        }
        Ok(self.p.max_hanging_length - xi * self.p.lift_height)
    }

    /// Diagonal-block entries (M₁₁, M₁₂, M₂₂, M₂₃, M₃₃) of (14), kg.
    fn m_entries(&self, l2: f64) -> [f64; 5] {
        let g = self.p.rope_mass_per_metre;
        let l1 = self.p.chord_length;
        [
            self.j1_prime(l2) / self.p.drum_radius.powi(2) + g * l1 / 4.0,
            g * l1 / 4.0,
            self.p.sheave_inertia / self.p.sheave_radius.powi(2) + g * (l1 + l2) / 4.0,
            g * l2 / 4.0,
            self.p.end_mass + g * l2 / 4.0,
        ]
    }

    /// M(l₂) of (14), kg.
    ///
    /// # Errors
    /// l₂ outside (0, L].
    pub fn mass_matrix(&self, l2: f64) -> Result<DMatrix<f64>> {
        self.check_l2(l2)?;
        let [m11, m12, m22, m23, m33] = self.m_entries(l2);
        Ok(DMatrix::from_row_slice(
            3,
            3,
            &[m11, m12, 0.0, m12, m22, m23, 0.0, m23, m33],
        ))
    }

    /// C(l₂) of (14), N/m.
    ///
    /// # Errors
    /// l₂ outside (0, L].
    pub fn stiffness_matrix(&self, l2: f64) -> Result<DMatrix<f64>> {
        let (cs, co) = (self.chord_stiffness(), self.hanging_stiffness(l2)?);
        Ok(DMatrix::from_row_slice(
            3,
            3,
            &[cs, -cs, 0.0, -cs, cs + co, -co, 0.0, -co, co],
        ))
    }

    /// m_Σ = J₁/R_b² + J₂/R_s² + m + γ(l₁ + L), kg (N₀² = m_Σ, the unnumbered formula after (23); constant over
    /// the lift).
    pub fn total_mass(&self) -> f64 {
        let p = &self.p;
        p.drum_inertia / p.drum_radius.powi(2)
            + p.sheave_inertia / p.sheave_radius.powi(2)
            + p.end_mass
            + p.rope_mass_per_metre * (p.chord_length + p.max_hanging_length)
    }

    /// Frequencies and √m_Σ-scaled mass-normalised modes at hanging length l₂ from [`modal_analysis`].
    ///
    /// # Errors
    /// l₂ outside (0, L]; failures of [`modal_analysis`].
    pub fn modes(&self, l2: f64) -> Result<HoistModes> {
        let (m, c) = (self.mass_matrix(l2)?, self.stiffness_matrix(l2)?);
        let (w, phi) = modal_analysis(&m, &c)?;
        Ok(HoistModes {
            omega: [w[0], w[1], w[2]],
            shapes: phi * self.total_mass().sqrt(),
        })
    }

    /// Coefficients (c₁, c₂, c₃) of det(C − λM) = λ(c₁ + c₂λ + c₃λ²), expanded from the tridiagonal
    /// determinant (16) (the constant term det C vanishes identically and is dropped).
    ///
    /// # Errors
    /// l₂ outside (0, L].
    pub fn characteristic_polynomial(&self, l2: f64) -> Result<[f64; 3]> {
        let (cs, co) = (self.chord_stiffness(), self.hanging_stiffness(l2)?);
        let [m11, m12, m22, m23, m33] = self.m_entries(l2);
        // linear polynomials a = (const, λ-coefficient)
        let a11 = [cs, -m11];
        let a12 = [-cs, -m12];
        let a22 = [cs + co, -m22];
        let a23 = [-co, -m23];
        let a33 = [co, -m33];
        let mul = |x: &[f64], y: &[f64]| -> Vec<f64> {
            let mut r = vec![0.0; x.len() + y.len() - 1];
            for (i, a) in x.iter().enumerate() {
                for (j, b) in y.iter().enumerate() {
                    r[i + j] += a * b;
                }
            }
            r
        };
        let t1 = mul(&mul(&a11, &a22), &a33);
        let t2 = mul(&a11, &mul(&a23, &a23));
        let t3 = mul(&a33, &mul(&a12, &a12));
        Ok([t1[1] - t2[1] - t3[1], t1[2] - t2[2] - t3[2], t1[3] - t2[3] - t3[3]])
    }

    /// (ω₁, ω₂), rad/s, from the roots of the quadratic factor of the characteristic polynomial
    /// (independent of the eigensolver).
    ///
    /// # Errors
    /// l₂ outside (0, L]; [`Error::Numerical`] for a negative discriminant or root (not for valid
    /// parameters: M is positive definite and C positive semi-definite).
    pub fn frequencies_closed_form(&self, l2: f64) -> Result<(f64, f64)> {
        let [c1, c2, c3] = self.characteristic_polynomial(l2)?;
        let disc = c2 * c2 - 4.0 * c3 * c1;
        if disc < 0.0 {
            return Err(Error::Numerical {
                what: "mine hoist frequency equation".into(),
                reason: format!("negative discriminant {disc:e}"),
            });
        }
        // stable quadratic roots
        let q = -0.5 * (c2 + c2.signum() * disc.sqrt());
        let (r1, r2) = (q / c3, c1 / q);
        let (lo, hi) = if r1 < r2 { (r1, r2) } else { (r2, r1) };
        if lo <= 0.0 {
            return Err(Error::Numerical {
                what: "mine hoist frequency equation".into(),
                reason: format!("non-positive root ω² = {lo:e}"),
            });
        }
        Ok((lo.sqrt(), hi.sqrt()))
    }

    /// a₁₁ = C_str − ω²(γl₁/4 + J₁′/R_b²) and a₃₃ = C_otv − ω²(m + γl₂/4) (20), N/m.
    fn a11_a33(&self, l2: f64, omega: f64) -> (f64, f64) {
        let [m11, _, _, _, m33] = self.m_entries(l2);
        let w2 = omega * omega;
        (
            self.chord_stiffness() - w2 * m11,
            self.rope_axial_rigidity() / l2 - w2 * m33,
        )
    }

    /// Cofactor mode (20) at frequency ω (rad/s): components scaled by c = 1/(C_str C_otv), m per m.
    ///
    /// # Errors
    /// l₂ outside (0, L].
    pub fn cofactor_mode(&self, l2: f64, omega: f64) -> Result<[f64; 3]> {
        let (cs, co) = (self.chord_stiffness(), self.hanging_stiffness(l2)?);
        let g = self.p.rope_mass_per_metre;
        let w2 = omega * omega;
        let (a11, a33) = self.a11_a33(l2, omega);
        let c = 1.0 / (cs * co);
        Ok([
            c * (cs + w2 * g * self.p.chord_length / 4.0) * a33,
            c * a11 * a33,
            c * a11 * (co + w2 * g * l2 / 4.0),
        ])
    }

    /// Cofactor mode normalised by (24), Φ̃ = √m_Σ Φ/N, and the renormalised (intended (25)) mode
    /// Φ̄ = sgn(a₃₃) Φ̃ at frequency ω; returns (Φ̃, Φ̄).
    ///
    /// # Errors
    /// l₂ outside (0, L]; [`Error::Numerical`] exactly at the node (N = 0).
    pub fn renormalised_cofactor_mode(&self, l2: f64, omega: f64) -> Result<([f64; 3], [f64; 3])> {
        let phi = self.cofactor_mode(l2, omega)?;
        let m = self.mass_matrix(l2)?;
        let v = DVector::from_column_slice(&phi);
        let n2 = (v.transpose() * &m * &v)[(0, 0)];
        if n2.is_nan() || n2 <= 0.0 {
            return Err(Error::Numerical {
                what: "mine hoist cofactor mode".into(),
                reason: format!("norm N = 0 at l2 = {l2} m (the nodal point of the cofactor construction)"),
            });
        }
        let s = self.total_mass().sqrt() / n2.sqrt();
        let tilde = phi.map(|x| x * s);
        let (_, a33) = self.a11_a33(l2, omega);
        let sg = if a33 < 0.0 { -1.0 } else { 1.0 };
        Ok((tilde, tilde.map(|x| x * sg)))
    }

    /// Node location l₂* (m) from the corrected closed form (J₁, not J₁′; see the type's docs).
    ///
    /// For γ = 0 (no rope mass) the node condition is linear and the same expression gives
    /// l₂* = l₁J₁/(R_b²m).
    ///
    /// # Errors
    /// None today (the `Result` is kept for the API).
    pub fn node_closed_form(&self) -> Result<f64> {
        Ok(self.node_formula(self.p.drum_inertia))
    }

    /// The node formula as printed (unnumbered, just before (22)), with a given drum inertia `j1_prime` (kg m²) in
    /// place of J₁:
    /// l₂ = (2/γ)[−(m + γl₁) + √((m + γl₁)² + γl₁(γl₁/4 + J₁′/R_b² + γL))], m.
    pub fn node_printed_formula(&self, j1_prime: f64) -> f64 {
        self.node_formula(j1_prime)
    }

    /// l₂ = (2/γ)[−b + √(b² + X)] with b = m + γl₁, X = γl₁(γl₁/4 + J/R_b² + γL), evaluated without the
    /// cancellation and the division by γ: −b + √(b² + X) = X/(b + √(b² + X)), so
    /// l₂ = 2l₁(γl₁/4 + J/R_b² + γL)/(b + √(b² + X)) (finite for γ → 0, where it tends to l₁J/(R_b²m)).
    fn node_formula(&self, j1: f64) -> f64 {
        let p = &self.p;
        let g = p.rope_mass_per_metre;
        let j1r = j1 / p.drum_radius.powi(2);
        let b = p.end_mass + g * p.chord_length;
        let inner = g * p.chord_length / 4.0 + j1r + g * p.max_hanging_length;
        let under = b * b + g * p.chord_length * inner;
        2.0 * p.chord_length * inner / (b + under.sqrt())
    }

    /// Sheave component of the mode-1 eigenvector (eigensolver, M-normalised, sign fixed so that the load
    /// component is positive), at l₂.
    fn sheave_component_mode1(&self, l2: f64) -> Result<f64> {
        let m = self.modes(l2)?;
        let s = if m.shapes[(2, 1)] < 0.0 { -1.0 } else { 1.0 };
        Ok(s * m.shapes[(1, 1)])
    }

    /// Node location l₂* (m) by root finding, independent of the closed form: the sheave component of the
    /// sign-continuous mode-1 eigenvector from [`modal_analysis`] (load component > 0) changes sign at the
    /// node; it is bracketed on a grid of `n_grid` hanging lengths over [L − H, L] and refined by bisection
    /// to 1e-9 m.
    ///
    /// # Errors
    /// `n_grid` < 2; [`Error::Numerical`] when no sign change is found (no node within the lift).
    pub fn node_by_root_finding(&self, n_grid: usize) -> Result<f64> {
        if n_grid < 2 {
            return Err(Error::invalid("n_grid", n_grid, "need at least 2 points"));
        }
        let (lo, hi) = (
            self.p.max_hanging_length - self.p.lift_height,
            self.p.max_hanging_length,
        );
        let mut prev = (lo, self.sheave_component_mode1(lo)?);
        for i in 1..n_grid {
            let l = lo + (hi - lo) * i as f64 / (n_grid - 1) as f64;
            let v = self.sheave_component_mode1(l)?;
            if prev.1 == 0.0 {
                return Ok(prev.0);
            }
            if prev.1 * v <= 0.0 {
                let (mut a, mut fa, mut b) = (prev.0, prev.1, l);
                while b - a > 1e-9 * (1.0 + b.abs()) && 0.5 * (a + b) > a && 0.5 * (a + b) < b {
                    let mid = 0.5 * (a + b);
                    let fm = self.sheave_component_mode1(mid)?;
                    if fm == 0.0 {
                        return Ok(mid);
                    }
                    if fa * fm < 0.0 {
                        b = mid;
                    } else {
                        a = mid;
                        fa = fm;
                    }
                }
                return Ok(0.5 * (a + b));
            }
            prev = (l, v);
        }
        Err(Error::Numerical {
            what: "mine hoist node search".into(),
            reason: "the sheave component of mode 1 does not change sign over the lift (no nodal point)".into(),
        })
    }

    /// Sweep over ξ = ȳ/H at `n_points` equally spaced values in [0, 1] (l₂ = L − ξH): ω₁, ω₂ from
    /// [`modal_analysis`] and renormalised modes with a sign convention continuous across the node:
    /// at ξ = 0 the sign of (25) (sgn(a₃₃) times the cofactor mode (24), compared in the M-inner product),
    /// then at every next point the sign with Φ̄(ξ_i)ᵀM(ξ_i)Φ̄(ξ_{i−1}) > 0.
    ///
    /// # Errors
    /// `n_points` < 2; failures of [`MineHoist::modes`].
    pub fn sweep(&self, n_points: usize) -> Result<Vec<SweepPoint>> {
        if n_points < 2 {
            return Err(Error::invalid("n_points", n_points, "need at least 2 points"));
        }
        let mut out: Vec<SweepPoint> = Vec::with_capacity(n_points);
        let mut prev: Option<[DVector<f64>; 2]> = None;
        for i in 0..n_points {
            let xi = i as f64 / (n_points - 1) as f64;
            let l2 = self.hanging_length(xi)?;
            let md = self.modes(l2)?;
            let m = self.mass_matrix(l2)?;
            let mut cols = [md.shapes.column(1).into_owned(), md.shapes.column(2).into_owned()];
            for (j, col) in cols.iter_mut().enumerate() {
                let reference = match &prev {
                    Some(p) => p[j].clone(),
                    None => {
                        let (_, bar) = self.renormalised_cofactor_mode(l2, md.omega[j + 1])?;
                        DVector::from_column_slice(&bar)
                    }
                };
                if (col.transpose() * &m * &reference)[(0, 0)] < 0.0 {
                    *col *= -1.0;
                }
            }
            out.push(SweepPoint {
                xi,
                l2,
                omega1: md.omega[1],
                omega2: md.omega[2],
                mode1: [cols[0][0], cols[0][1], cols[0][2]],
                mode2: [cols[1][0], cols[1][1], cols[1][2]],
            });
            prev = Some(cols);
        }
        Ok(out)
    }
}

impl DeterministicModel for MineHoist {
    fn description(&self) -> String {
        let p = &self.p;
        format!(
            "single-end mine hoist: lift H = {} m, hanging length up to L = {} m, end mass {} kg, drum J1 = {} kg m^2 \
             (Dvornikov, Kondrakhin & Velebnik, Natural frequencies and modes of a single-end hoisting machine, 2014)",
            num(p.lift_height),
            num(p.max_hanging_length),
            num(p.end_mass),
            num(p.drum_inertia)
        )
    }

    /// The natural frequencies ω₁, ω₂ and the renormalised modes (25) over the lift ξ = 0 … 1 (11 points),
    /// and the node of mode 1 (closed form, corrected, and root finding).
    fn results(&self) -> Result<Vec<ResultTable>> {
        let mut sweep = ResultTable::new(
            "Natural frequencies and renormalised modes over the lift (14), (20)-(25)",
            &[
                ("xi", "-"),
                ("l2", "m"),
                ("omega1", "rad/s"),
                ("omega2", "rad/s"),
                ("mode 1 drum", "m"),
                ("mode 1 sheave", "m"),
                ("mode 1 load", "m"),
                ("mode 2 drum", "m"),
                ("mode 2 sheave", "m"),
                ("mode 2 load", "m"),
            ],
        )
        .with_note(
            "omega0 = 0 (rigid mode); modes scaled so that phi' M phi = m_Sigma, signs continuous across the node",
        );
        for p in self.sweep(11)? {
            let mut row: Vec<Cell> = vec![p.xi.into(), p.l2.into(), p.omega1.into(), p.omega2.into()];
            row.extend(p.mode1.iter().chain(&p.mode2).map(|&v| Cell::from(v)));
            sweep.push(row);
        }
        let mut node = ResultTable::new("Node of mode 1 (the sheave at rest)", &[("method", "-"), ("l2*", "m")]);
        node.push(vec![
            "closed form (J1 in place of the printed J1')".into(),
            self.node_closed_form()?.into(),
        ]);
        node.push(vec![
            "root finding on the eigenvectors".into(),
            self.node_by_root_finding(400)?.into(),
        ]);
        Ok(vec![sweep, node])
    }
}

/// Rows of the `book` report for Dvornikov, Kondrakhin & Velebnik (2014). The article prints only parameters (its
/// results are in Figs. 2 and 3); rows compare the printed numbers that can be recomputed (γ, the range of ξ)
/// and list the key computed values with `printed = None`.
pub fn book_rows() -> Vec<BookRow> {
    let h = MineHoist::printed();
    let p = h.params();
    let ex = "Dvornikov, Kondrakhin & Velebnik (2014), single-end mine hoist (printed parameters, gamma = 8.4 kg/m)";
    let mut rows = Vec::new();
    let mut push = |q: &str, u: &str, printed: Option<f64>, c: Option<f64>, e: &str| {
        rows.push(BookRow {
            example: ex.to_string(),
            quantity: q.to_string(),
            unit: u.to_string(),
            printed,
            computed: c,
            explanation: e.to_string(),
        })
    };
    push(
        "gamma = gamma_bar * gamma_st * d_k^2 (text after (5))",
        "kg/m",
        Some(8.4),
        h.rope_mass_per_metre_formula(),
        "printed 8.4 kg/m is not the formula value from the printed 0.491, 7800 kg/m3, 46.5 mm; the model uses 8.4",
    );
    push(
        "upper end of xi = l2/H (text introducing Fig. 2)",
        "-",
        Some(1.0),
        Some(p.max_hanging_length / p.lift_height),
        "definition conflict: l2 runs over [L-H, L] = [75, 700] m so l2/H reaches L/H; this crate uses xi = y/H in [0, 1]",
    );
    let fig = "not printed (figure only); key computed value";
    push(
        "total mass m_Sigma = 1'M1 at l2 = L (N0^2 after (23))",
        "kg",
        None,
        h.mass_matrix(p.max_hanging_length).ok().map(|m| m.sum()),
        "formula only in the source; computed as the sum of M(l2) entries",
    );
    push("C_str (3)", "N/m", None, Some(h.chord_stiffness()), fig);
    push(
        "C_otv(l2 = L) (3)",
        "N/m",
        None,
        h.hanging_stiffness(p.max_hanging_length).ok(),
        fig,
    );
    for (name, l2) in [
        ("start, l2 = L", p.max_hanging_length),
        ("top, l2 = L - H", p.max_hanging_length - p.lift_height),
    ] {
        let md = h.modes(l2).ok();
        push(
            &format!("omega_1 ({name})"),
            "rad/s",
            None,
            md.as_ref().map(|m| m.omega[1]),
            "Fig. 2a only",
        );
        push(
            &format!("omega_2 ({name})"),
            "rad/s",
            None,
            md.as_ref().map(|m| m.omega[2]),
            "Fig. 2a only",
        );
    }
    let node = h.node_by_root_finding(64).ok();
    push(
        "node l2* (root of sheave component of mode 1)",
        "m",
        None,
        node,
        "point U of Fig. 2b, no value printed; closed form with J1 (corrected node formula before (22)) agrees",
    );
    push(
        "node l2* (closed form, J1)",
        "m",
        None,
        h.node_closed_form().ok(),
        "node formula before (22) corrected: J1' replaced by J1",
    );
    push(
        "node l2* (printed formula before (22), J1' at the node)",
        "m",
        None,
        node.and_then(|l| h.drum_inertia_with_rope(l).ok())
            .map(|j| h.node_printed_formula(j)),
        "printed formula is implicit in J1'; evaluated with J1' at the true node it misses the node",
    );
    push(
        "omega_1 at the node (eigensolver)",
        "rad/s",
        None,
        node.and_then(|l| h.modes(l).ok()).map(|m| m.omega[1]),
        "equals sqrt(C_otv/(m + gamma l2/4)) there; not printed",
    );
    rows
}
