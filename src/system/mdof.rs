//! Multi-degree-of-freedom models M q̈ + B q̇ + C q = K_u u + B_u u̇ + F f with named outputs.

use super::{FrequencyResponse, OutputInfo, StateSpace};
use crate::error::{Error, Result};
use crate::spectrum::Asymptote;
use nalgebra::{Complex, DMatrix, DVector};

/// Where the far end of a spring–damper element is attached.
#[derive(Debug, Clone, PartialEq)]
pub enum Attach {
    /// Fixed ground.
    Ground,
    /// Kinematic (base) input j: a prescribed displacement u_j(t), e.g. the road under a wheel.
    Base(usize),
    /// Another point of the structure, a linear combination gᵀq of the coordinates.
    Point(Vec<f64>),
}

/// A spring (stiffness k) in parallel with a damper (coefficient b) between the point gᵀq and `to`.
#[derive(Debug, Clone, PartialEq)]
pub struct Element {
    /// Name, used by force outputs.
    pub name: String,
    /// g: the point's displacement is gᵀq (e.g. z − aφ for the front axle of a half car).
    pub point: Vec<f64>,
    /// The other end.
    pub to: Attach,
    /// Stiffness, N/m (or N m/rad).
    pub stiffness: f64,
    /// Damping, N s/m (or N m s/rad).
    pub damping: f64,
}

/// What an output measures.
#[derive(Debug, Clone, PartialEq)]
pub enum Quantity {
    /// Displacement of a point gᵀq.
    Displacement(Vec<f64>),
    /// Velocity of a point.
    Velocity(Vec<f64>),
    /// Acceleration of a point.
    Acceleration(Vec<f64>),
    /// Deflection δ of element e (point minus far end; suspension travel).
    Deflection(usize),
    /// Spring force k δ of element e (positive when the element is stretched).
    SpringForce(usize),
    /// Damper force b δ̇ of element e.
    DamperForce(usize),
    /// Total force k δ + b δ̇ transmitted by element e.
    ElementForce(usize),
    /// Displacement of a point relative to a base input, gᵀq − u_j (e.g. a suspension travel written in
    /// the matrix form, where there are no elements to name).
    RelativeDisplacement {
        /// Weights of the coordinates.
        point: Vec<f64>,
        /// Index of the base input.
        base: usize,
    },
    /// Velocity of a point relative to a base input, gᵀq̇ − u̇_j.
    RelativeVelocity {
        /// Weights of the coordinates.
        point: Vec<f64>,
        /// Index of the base input.
        base: usize,
    },
}

/// A named output of an [`Mdof`] model.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    /// Name and unit.
    pub info: OutputInfo,
    /// What it measures.
    pub quantity: Quantity,
}

/// y = g_qᵀ q + g_vᵀ q̇ + g_aᵀ q̈ + h_uᵀ u + h_dᵀ u̇ (u: every input, base then force).
#[derive(Debug, Clone)]
struct Combination {
    q: DVector<f64>,
    v: DVector<f64>,
    a: DVector<f64>,
    u: DVector<f64>,
    du: DVector<f64>,
}

impl Combination {
    /// y = 0 for `n` coordinates and `nu` inputs.
    fn zero(n: usize, nu: usize) -> Combination {
        Combination {
            q: DVector::zeros(n),
            v: DVector::zeros(n),
            a: DVector::zeros(n),
            u: DVector::zeros(nu),
            du: DVector::zeros(nu),
        }
    }
}

/// A linear multi-degree-of-freedom model with base (kinematic) and force inputs.
///
/// # Formula
/// ```text
/// M q̈ + B q̇ + C q = K_u u + B_u u̇ + F f
/// ```
/// Every spring–damper element (k, b) between a point gᵀq and a base input u_j adds k g gᵀ to C, b g gᵀ to
/// B, k g to column j of K_u and b g to column j of B_u (between two points g₁, g₂: (g₁ − g₂)(g₁ − g₂)ᵀ).
/// Inputs are ordered base inputs first, then force inputs. The frequency response is computed directly,
/// Q(iω) = (C − ω²M + iωB)⁻¹ [K_u + iωB_u, F]; the state-space form uses the state x = [q; M q̇ − B_u u],
/// which removes u̇ from the state equation:
/// ```text
/// A = [[0, M⁻¹], [−C, −B M⁻¹]],     B_ss = [[M⁻¹B_u, 0], [K_u − B M⁻¹ B_u, F]]
/// ```
/// (an acceleration output then carries the derivative feedthrough M⁻¹B_u u̇).
///
/// # Errors
/// [`Mdof::new`] rejects non-square or mismatched matrices, non-finite entries, a mass matrix that is
/// not symmetric positive definite (singular), non-symmetric B or C, and outputs or elements that refer to
/// coordinates or inputs that do not exist.
///
/// # Examples
/// ```
/// use stochvib::system::{Mdof, Element, Attach, Quantity, FrequencyResponse};
/// // quarter-car-like SDOF on a base: m = 100 kg, k = 1e4 N/m, b = 200 N s/m
/// let el = Element { name: "susp".into(), point: vec![1.0], to: Attach::Base(0), stiffness: 1e4, damping: 200.0 };
/// let m = Mdof::from_elements(&[("x", "m")], &[100.0], vec![el], 1, &[]).unwrap()
///     .with_output("x", Quantity::Displacement(vec![1.0])).unwrap();
/// // static transmissibility of a base-excited mass is 1
/// assert!((m.static_gain().unwrap()[(0, 0)] - 1.0).abs() < 1e-12);
/// assert!((m.natural_frequencies()[0] - 10.0).abs() < 1e-9);
/// ```
#[derive(Debug, Clone)]
pub struct Mdof {
    m: DMatrix<f64>,
    b: DMatrix<f64>,
    c: DMatrix<f64>,
    ku: DMatrix<f64>,
    bu: DMatrix<f64>,
    f: DMatrix<f64>,
    coords: Vec<(String, String)>,
    elements: Vec<Element>,
    outputs: Vec<Output>,
    infos: Vec<OutputInfo>,
    combos: Vec<Combination>,
    ss: Option<StateSpace>,
    m_inv: DMatrix<f64>,
}

fn check_square(name: &str, m: &DMatrix<f64>, n: usize) -> Result<()> {
    if m.nrows() != n || m.ncols() != n {
        return Err(Error::invalid(
            name,
            format!("{}x{}", m.nrows(), m.ncols()),
            format!("must be {n}x{n}"),
        ));
    }
    if m.iter().any(|v| !v.is_finite()) {
        return Err(Error::invalid(name, "matrix", "entries must be finite"));
    }
    Ok(())
}

fn check_symmetric(name: &str, m: &DMatrix<f64>) -> Result<()> {
    let scale = m.amax().max(1e-300);
    if (m - m.transpose()).amax() > 1e-12 * scale {
        return Err(Error::invalid(name, "matrix", "must be symmetric"));
    }
    Ok(())
}

impl Mdof {
    /// Builds a model from full matrices: mass `m`, damping `b`, stiffness `c` (n × n), base-input
    /// stiffness and damping `ku`, `bu` (n × n_base) and force distribution `f` (n × n_force).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        coords: &[(&str, &str)],
        m: DMatrix<f64>,
        b: DMatrix<f64>,
        c: DMatrix<f64>,
        ku: DMatrix<f64>,
        bu: DMatrix<f64>,
        f: DMatrix<f64>,
    ) -> Result<Self> {
        let n = m.nrows();
        if n == 0 {
            return Err(Error::invalid("M", "0x0", "need at least one coordinate"));
        }
        check_square("M", &m, n)?;
        check_square("B", &b, n)?;
        check_square("C", &c, n)?;
        check_symmetric("M", &m)?;
        check_symmetric("B", &b)?;
        check_symmetric("C", &c)?;
        if coords.len() != n {
            return Err(Error::invalid(
                "coordinates",
                coords.len(),
                format!("need one name per coordinate ({n})"),
            ));
        }
        for (name, mat) in [("K_u", &ku), ("B_u", &bu), ("F", &f)] {
            if mat.nrows() != n {
                return Err(Error::invalid(name, mat.nrows(), format!("must have {n} rows")));
            }
            if mat.iter().any(|v| !v.is_finite()) {
                return Err(Error::invalid(name, "matrix", "entries must be finite"));
            }
        }
        if ku.ncols() != bu.ncols() {
            return Err(Error::invalid(
                "B_u",
                bu.ncols(),
                format!("must have as many columns as K_u ({})", ku.ncols()),
            ));
        }
        let chol = m.clone().cholesky().ok_or_else(|| {
            Error::invalid(
                "M",
                "matrix",
                "mass matrix is singular or not positive definite (every coordinate needs mass)",
            )
        })?;
        // f64 resolves the dynamics only when the masses are within about 10^12 of each other: beyond, the
        // light coordinates' equations lose every digit (e.g. a 1e308 kg body on a 40 kg wheel)
        let ev = m.clone().symmetric_eigenvalues();
        let (lo, hi) = ev
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
        if !(hi.is_finite() && hi / lo <= MAX_MASS_CONDITION) {
            return Err(Error::invalid(
                "M",
                format!("eigenvalues from {lo:e} to {hi:e}"),
                format!(
                    "the mass matrix is too badly scaled for double precision (condition {:.1e} > {MAX_MASS_CONDITION:.0e}): \
                     check the units of the masses and inertias",
                    hi / lo
                ),
            ));
        }
        let m_inv = chol.inverse();
        let mut model = Mdof {
            m,
            b,
            c,
            ku,
            bu,
            f,
            coords: coords.iter().map(|(a, b)| (a.to_string(), b.to_string())).collect(),
            elements: Vec::new(),
            outputs: Vec::new(),
            infos: Vec::new(),
            combos: Vec::new(),
            ss: None,
            m_inv,
        };
        model.rebuild_state_space()?;
        Ok(model)
    }

    /// Builds a model from coordinates with diagonal masses and spring–damper elements; `n_base` base
    /// inputs and force inputs given as distribution vectors (generalised force f_k·g_k).
    ///
    /// # Errors
    /// See the type's `# Errors`; also elements with negative k or b, or a wrong point length.
    pub fn from_elements(
        coords: &[(&str, &str)],
        masses: &[f64],
        elements: Vec<Element>,
        n_base: usize,
        forces: &[Vec<f64>],
    ) -> Result<Self> {
        let n = coords.len();
        if masses.len() != n {
            return Err(Error::invalid(
                "masses",
                masses.len(),
                format!("need one mass per coordinate ({n})"),
            ));
        }
        for (i, &mi) in masses.iter().enumerate() {
            if !(mi.is_finite() && mi > 0.0) {
                return Err(Error::invalid(
                    &format!("mass of `{}`", coords[i].0),
                    mi,
                    "must be finite and > 0",
                ));
            }
        }
        let m = DMatrix::from_diagonal(&DVector::from_column_slice(masses));
        let mut b = DMatrix::zeros(n, n);
        let mut c = DMatrix::zeros(n, n);
        let mut ku = DMatrix::zeros(n, n_base);
        let mut bu = DMatrix::zeros(n, n_base);
        for e in &elements {
            if e.point.len() != n {
                return Err(Error::invalid(
                    &format!("element `{}`.point", e.name),
                    e.point.len(),
                    format!("need {n} entries"),
                ));
            }
            for (what, v) in [("stiffness", e.stiffness), ("damping", e.damping)] {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(Error::invalid(
                        &format!("element `{}`.{what}", e.name),
                        v,
                        "must be finite and >= 0",
                    ));
                }
            }
            let g = DVector::from_column_slice(&e.point);
            let d = match &e.to {
                Attach::Ground => g.clone(),
                Attach::Base(j) => {
                    if *j >= n_base {
                        return Err(Error::invalid(
                            &format!("element `{}`.base", e.name),
                            j,
                            format!("only {n_base} base inputs"),
                        ));
                    }
                    ku.column_mut(*j).axpy(e.stiffness, &g, 1.0);
                    bu.column_mut(*j).axpy(e.damping, &g, 1.0);
                    g.clone()
                }
                Attach::Point(h) => {
                    if h.len() != n {
                        return Err(Error::invalid(
                            &format!("element `{}`.to", e.name),
                            h.len(),
                            format!("need {n} entries"),
                        ));
                    }
                    &g - DVector::from_column_slice(h)
                }
            };
            c += e.stiffness * &d * d.transpose();
            b += e.damping * &d * d.transpose();
        }
        let mut f = DMatrix::zeros(n, forces.len());
        for (k, g) in forces.iter().enumerate() {
            if g.len() != n {
                return Err(Error::invalid(
                    &format!("force input {k}"),
                    g.len(),
                    format!("need {n} entries"),
                ));
            }
            f.column_mut(k).copy_from_slice(g);
        }
        let mut model = Mdof::new(coords, m, b, c, ku, bu, f)?;
        model.elements = elements;
        Ok(model)
    }

    /// Adds a named output; its unit follows from the quantity and the coordinates' units: a point that
    /// weights lengths (m) and angles (rad) together, such as z + aφ, is in metres (the weight of an angle is a
    /// lever arm in m/rad), a point of angles alone in radians; velocities and accelerations add `/s`,
    /// `/s^2`; element forces are in N, or N m for an element between angles.
    ///
    /// # Errors
    /// A point of the wrong length or an element index out of range.
    pub fn with_output(self, name: &str, quantity: Quantity) -> Result<Self> {
        self.with_outputs(vec![(name, quantity)])
    }

    /// [`with_output`](Self::with_output) of each of `outputs` in order, the state space written once.
    ///
    /// # Errors
    /// As [`with_output`](Self::with_output), for the first output in error.
    pub fn with_outputs(mut self, outputs: Vec<(&str, Quantity)>) -> Result<Self> {
        for (name, quantity) in outputs {
            let (combo, unit) = self.combination(name, &quantity)?;
            let info = OutputInfo::new(name, unit);
            self.outputs.push(Output {
                info: info.clone(),
                quantity,
            });
            self.infos.push(info);
            self.combos.push(combo);
        }
        self.rebuild_state_space()?;
        Ok(self)
    }

    /// The point gᵀq of output `name`, which must have one weight per coordinate.
    fn output_point(&self, name: &str, g: &[f64]) -> Result<DVector<f64>> {
        let n = self.n_coords();
        if g.len() != n {
            return Err(Error::invalid(
                &format!("output `{name}`"),
                g.len(),
                format!("point needs {n} entries"),
            ));
        }
        Ok(DVector::from_column_slice(g))
    }

    /// The unit of a point: one weighting lengths (m) and angles (rad), e.g. z + aφ, is a length (the weight
    /// of an angle is then a lever arm in m/rad); a point of angles alone is an angle.
    fn point_unit(&self, g: &[f64]) -> String {
        let mut used = g
            .iter()
            .zip(&self.coords)
            .filter(|(w, _)| **w != 0.0)
            .map(|(_, c)| c.1.as_str());
        let first = used.next();
        match first {
            Some("rad") if used.all(|u| u == "rad") => "rad".to_string(),
            _ => "m".to_string(),
        }
    }

    /// The combination y of the output `name` of `quantity`, and its unit (see [`Mdof::with_output`]).
    fn combination(&self, name: &str, quantity: &Quantity) -> Result<(Combination, String)> {
        let zero = Combination::zero(self.n_coords(), self.n_inputs());
        Ok(match quantity {
            Quantity::Displacement(g) => (
                Combination {
                    q: self.output_point(name, g)?,
                    ..zero
                },
                self.point_unit(g),
            ),
            Quantity::Velocity(g) => (
                Combination {
                    v: self.output_point(name, g)?,
                    ..zero
                },
                format!("{}/s", self.point_unit(g)),
            ),
            Quantity::Acceleration(g) => (
                Combination {
                    a: self.output_point(name, g)?,
                    ..zero
                },
                format!("{}/s^2", self.point_unit(g)),
            ),
            Quantity::RelativeDisplacement { point: g, base } => self.relative(name, g, *base, false)?,
            Quantity::RelativeVelocity { point: g, base } => self.relative(name, g, *base, true)?,
            Quantity::Deflection(e) => {
                let el = self.output_element(name, *e)?;
                let (q, u) = self.deflection(el);
                (Combination { q, u, ..zero }, self.point_unit(&el.point))
            }
            Quantity::SpringForce(e) | Quantity::DamperForce(e) | Quantity::ElementForce(e) => {
                let el = self.output_element(name, *e)?;
                let (q, u) = self.deflection(el);
                let (k, b) = match quantity {
                    Quantity::SpringForce(_) => (el.stiffness, 0.0),
                    Quantity::DamperForce(_) => (0.0, el.damping),
                    _ => (el.stiffness, el.damping),
                };
                let unit = if self.point_unit(&el.point) == "rad" {
                    "N m"
                } else {
                    "N"
                };
                (
                    Combination {
                        q: &q * k,
                        v: &q * b,
                        u: &u * k,
                        du: &u * b,
                        ..zero
                    },
                    unit.to_string(),
                )
            }
        })
    }

    /// A point relative to base input `base` (its displacement, or with `velocity` its velocity), which
    /// must be a length.
    fn relative(&self, name: &str, g: &[f64], base: usize, velocity: bool) -> Result<(Combination, String)> {
        if base >= self.n_base() {
            return Err(Error::invalid(
                &format!("output `{name}`"),
                base,
                format!("only {} base inputs", self.n_base()),
            ));
        }
        let zero = Combination::zero(self.n_coords(), self.n_inputs());
        let mut u = DVector::zeros(self.n_inputs());
        u[base] = -1.0;
        let combo = if velocity {
            Combination {
                v: self.output_point(name, g)?,
                du: u,
                ..zero
            }
        } else {
            Combination {
                q: self.output_point(name, g)?,
                u,
                ..zero
            }
        };
        let unit = self.point_unit(g);
        if unit != "m" {
            return Err(Error::invalid(
                &format!("output `{name}`"),
                format!("{g:?}"),
                "a point relative to a base input must be a length (a base input is a displacement in m)",
            ));
        }
        Ok((combo, if velocity { "m/s".to_string() } else { unit }))
    }

    /// Element `e` of output `name`.
    fn output_element(&self, name: &str, e: usize) -> Result<&Element> {
        self.elements.get(e).ok_or_else(|| {
            Error::invalid(
                &format!("output `{name}`"),
                e,
                format!("only {} elements", self.elements.len()),
            )
        })
    }

    /// The deflection δ = (g − g_far)ᵀ q − u_j of an element, as (g − g_far, the input weights).
    fn deflection(&self, e: &Element) -> (DVector<f64>, DVector<f64>) {
        let g = DVector::from_column_slice(&e.point);
        let mut u = DVector::zeros(self.n_inputs());
        let q = match &e.to {
            Attach::Ground => g,
            Attach::Base(j) => {
                u[*j] = -1.0;
                g
            }
            Attach::Point(h) => g - DVector::from_column_slice(h),
        };
        (q, u)
    }

    /// [`Mdof::with_output`] for a point whose weights are lever arms (m/rad) on angles alone, such as the
    /// lateral or longitudinal motion of a point at a height from roll or pitch: a length (m, m/s, m/s²),
    /// where `with_output` would call a point of angles alone an angle.
    ///
    /// # Errors
    /// As [`Mdof::with_output`].
    pub fn with_lever_output(self, name: &str, quantity: Quantity) -> Result<Self> {
        let mut m = self.with_output(name, quantity)?;
        let last = m.infos.len() - 1;
        let info = OutputInfo::new(name, m.infos[last].unit.replacen("rad", "m", 1));
        m.outputs[last].info = info.clone();
        m.infos[last] = info;
        m.rebuild_state_space()?;
        Ok(m)
    }

    /// Number of coordinates.
    pub fn n_coords(&self) -> usize {
        self.m.nrows()
    }
    /// Number of base inputs.
    pub fn n_base(&self) -> usize {
        self.ku.ncols()
    }
    /// The mass matrix.
    pub fn mass(&self) -> &DMatrix<f64> {
        &self.m
    }
    /// The damping matrix.
    pub fn damping(&self) -> &DMatrix<f64> {
        &self.b
    }
    /// The stiffness matrix.
    pub fn stiffness(&self) -> &DMatrix<f64> {
        &self.c
    }
    /// The outputs.
    pub fn output_list(&self) -> &[Output] {
        &self.outputs
    }

    /// Natural frequencies (rad/s) and mass-normalised mode shapes of the undamped model from the
    /// generalised symmetric eigenproblem C φ = ω² M φ (Cholesky M = LLᵀ, symmetric eigen of L⁻¹CL⁻ᵀ).
    /// Rigid-body modes come out with ω = 0 (eigenvalues below 1e-10·max are set to zero).
    ///
    /// # Errors
    /// [`Error::Numerical`] if C is not positive semi-definite (a negative ω²).
    pub fn modes(&self) -> Result<(Vec<f64>, DMatrix<f64>)> {
        modal_analysis(&self.m, &self.c)
    }

    fn rebuild_state_space(&mut self) -> Result<()> {
        let n = self.n_coords();
        let (nb, nf) = (self.ku.ncols(), self.f.ncols());
        let mi = &self.m_inv;
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).copy_from(mi);
        a.view_mut((n, 0), (n, n)).copy_from(&(-&self.c));
        a.view_mut((n, n), (n, n)).copy_from(&(-(&self.b * mi)));
        let mut bss = DMatrix::zeros(2 * n, nb + nf);
        bss.view_mut((0, 0), (n, nb)).copy_from(&(mi * &self.bu));
        bss.view_mut((n, 0), (n, nb))
            .copy_from(&(&self.ku - &self.b * mi * &self.bu));
        bss.view_mut((n, nb), (n, nf)).copy_from(&self.f);
        // q = [I 0]x; q̇ = [0 M⁻¹]x + M⁻¹B_u u; q̈ = M⁻¹(−Cq − Bq̇ + K_u u + B_u u̇ + F f)
        let p = self.combos.len();
        let mut c = DMatrix::zeros(p, 2 * n);
        let mut d = DMatrix::zeros(p, nb + nf);
        let mut e = DMatrix::zeros(p, nb + nf);
        let mut full_u = DMatrix::zeros(n, nb + nf); // K_u u + F f
        full_u.view_mut((0, 0), (n, nb)).copy_from(&self.ku);
        full_u.view_mut((0, nb), (n, nf)).copy_from(&self.f);
        let mut full_du = DMatrix::zeros(n, nb + nf);
        full_du.view_mut((0, 0), (n, nb)).copy_from(&self.bu);
        // q̇ in terms of (x, u)
        let mut qdot_x = DMatrix::zeros(n, 2 * n);
        qdot_x.view_mut((0, n), (n, n)).copy_from(mi);
        let qdot_u = mi * &full_du;
        let mut q_x = DMatrix::zeros(n, 2 * n);
        q_x.view_mut((0, 0), (n, n)).copy_from(&DMatrix::identity(n, n));
        let qdd_x = mi * (-(&self.c) * &q_x - &self.b * &qdot_x);
        let qdd_u = mi * (&full_u - &self.b * &qdot_u);
        let qdd_du = mi * &full_du;
        for (r, k) in self.combos.iter().enumerate() {
            let row_c = k.q.transpose() * &q_x + k.v.transpose() * &qdot_x + k.a.transpose() * &qdd_x;
            let row_d = k.v.transpose() * &qdot_u + k.a.transpose() * &qdd_u + k.u.transpose();
            let row_e = k.a.transpose() * &qdd_du + k.du.transpose();
            c.row_mut(r).copy_from(&row_c);
            d.row_mut(r).copy_from(&row_d);
            e.row_mut(r).copy_from(&row_e);
        }
        self.ss = Some(StateSpace::new(a, bss, c, Some(d), Some(e), self.infos.clone())?);
        Ok(())
    }
}

/// Largest accepted ratio of the largest to the smallest eigenvalue of the mass matrix: beyond it the
/// equations of the lightest coordinates lose all significant digits in double precision.
pub const MAX_MASS_CONDITION: f64 = 1e12;

/// Natural frequencies (rad/s, ascending) and mass-normalised modes (columns) of C φ = ω² M φ.
///
/// # Errors
/// [`Error::InvalidParameter`] for a mass matrix that is not positive definite; [`Error::Numerical`] for a
/// stiffness matrix with a negative eigenvalue.
pub fn modal_analysis(m: &DMatrix<f64>, c: &DMatrix<f64>) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let chol = m
        .clone()
        .cholesky()
        .ok_or_else(|| Error::invalid("M", "matrix", "mass matrix is singular or not positive definite"))?;
    let l = chol.l();
    let li = l
        .clone()
        .try_inverse()
        .ok_or_else(|| Error::invalid("M", "matrix", "singular Cholesky factor"))?;
    let k = &li * c * li.transpose();
    let k = (&k + k.transpose()) * 0.5;
    let eig = k.symmetric_eigen();
    let scale = eig.eigenvalues.amax().max(1e-300);
    let mut idx: Vec<usize> = (0..eig.eigenvalues.len()).collect();
    idx.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let mut freqs = Vec::new();
    let mut modes = DMatrix::zeros(m.nrows(), m.nrows());
    for (col, &i) in idx.iter().enumerate() {
        let lam = eig.eigenvalues[i];
        if lam < -1e-10 * scale {
            return Err(Error::Numerical {
                what: "modal analysis".into(),
                reason: format!("stiffness matrix has a negative eigenvalue ω² = {lam:e}: statically unstable"),
            });
        }
        freqs.push(if lam.abs() <= 1e-10 * scale { 0.0 } else { lam.sqrt() });
        let phi = li.transpose() * eig.eigenvectors.column(i);
        // sign convention: largest component positive
        let s = if phi
            .iter()
            .cloned()
            .fold(0.0f64, |a, v| if v.abs() > a.abs() { v } else { a })
            < 0.0
        {
            -1.0
        } else {
            1.0
        };
        modes.column_mut(col).copy_from(&(phi * s));
    }
    Ok((freqs, modes))
}

impl FrequencyResponse for Mdof {
    fn n_inputs(&self) -> usize {
        self.ku.ncols() + self.f.ncols()
    }
    fn outputs(&self) -> &[OutputInfo] {
        &self.infos
    }
    /// Direct dynamic-stiffness solve (independent of the state-space form, which tests compare it with).
    fn response(&self, omega: f64) -> DMatrix<Complex<f64>> {
        let n = self.n_coords();
        let (nb, nf) = (self.ku.ncols(), self.f.ncols());
        let s = Complex::new(0.0, omega);
        let cx = |m: &DMatrix<f64>| m.map(|v| Complex::new(v, 0.0));
        let dyn_stiff = cx(&self.c) + cx(&self.b) * s + cx(&self.m) * (s * s);
        let mut rhs = DMatrix::zeros(n, nb + nf);
        rhs.view_mut((0, 0), (n, nb))
            .copy_from(&(cx(&self.ku) + cx(&self.bu) * s));
        rhs.view_mut((0, nb), (n, nf)).copy_from(&cx(&self.f));
        let q = match dyn_stiff.lu().solve(&rhs) {
            Some(q) => q,
            None => return DMatrix::from_element(self.combos.len(), nb + nf, Complex::new(f64::INFINITY, 0.0)),
        };
        let mut h = DMatrix::zeros(self.combos.len(), nb + nf);
        for (r, k) in self.combos.iter().enumerate() {
            let w = cx(&DMatrix::from_column_slice(1, n, k.q.as_slice()))
                + cx(&DMatrix::from_column_slice(1, n, k.v.as_slice())) * s
                + cx(&DMatrix::from_column_slice(1, n, k.a.as_slice())) * (s * s);
            let mut row = w * &q;
            for j in 0..nb + nf {
                row[(0, j)] += Complex::new(k.u[j], 0.0) + s * k.du[j];
            }
            h.row_mut(r).copy_from(&row);
        }
        h
    }
    fn static_gain(&self) -> Option<DMatrix<f64>> {
        self.ss.as_ref()?.static_gain()
    }
    fn high_frequency(&self) -> Vec<Vec<Asymptote>> {
        self.ss.as_ref().map(|s| s.high_frequency()).unwrap_or_default()
    }
    fn low_frequency(&self) -> Vec<Vec<Asymptote>> {
        self.ss.as_ref().map(|s| s.low_frequency()).unwrap_or_default()
    }
    fn natural_frequencies(&self) -> Vec<f64> {
        self.ss.as_ref().map(|s| s.natural_frequencies()).unwrap_or_default()
    }
    fn state_space(&self) -> Option<&StateSpace> {
        self.ss.as_ref()
    }
    fn as_mdof(&self) -> Option<&Mdof> {
        Some(self)
    }
}

/// The weights of an output y = g_qᵀ q + g_vᵀ q̇ + g_aᵀ q̈ + h_uᵀ u + h_dᵀ u̇ (u: every input, base then
/// force), as [`Mdof::output_weights`] returns them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputWeights<'a> {
    /// g_q.
    pub q: &'a [f64],
    /// g_v.
    pub v: &'a [f64],
    /// g_a.
    pub a: &'a [f64],
    /// h_u.
    pub u: &'a [f64],
    /// h_d.
    pub du: &'a [f64],
}

/// Standard gravity, m/s² (static deflections).
pub const GRAVITY: f64 = 9.80665;

impl Mdof {
    /// The static deflection of every element under gravity, (element name, m; > 0 is compression), for a
    /// model whose every length coordinate is vertical (positive up) and whose angles carry no weight.
    ///
    /// # Formula
    /// K q_s = −g M e (e: 1 on each length coordinate, 0 on each angle: a unit lift of the whole model),
    /// and an element from its point gᵀq to its far end hᵀq (a base or the ground: 0) is compressed by
    /// δ = hᵀq_s − gᵀq_s. A mass m on a spring k from the ground: δ = m g/k.
    ///
    /// # Errors
    /// [`Error::Numerical`] when K is singular (a part held by no spring).
    ///
    /// # Examples
    /// ```
    /// use stochvib::system::{Drive, MassSpringDamper, Mdof, mdof::GRAVITY};
    /// let m = MassSpringDamper { mass: 80.0, stiffness: 8000.0, damping: 400.0, drive: Drive::Base }.build().unwrap();
    /// let d = m.static_deflections().unwrap();
    /// assert!((d[0].1 - 80.0 * GRAVITY / 8000.0).abs() < 1e-15);
    /// ```
    pub fn static_deflections(&self) -> Result<Vec<(String, f64)>> {
        let lift = DVector::from_iterator(self.n_coords(), self.coords.iter().map(|c| f64::from(c.1 == "m")));
        let load = -GRAVITY * (&self.m * lift);
        let q = self.c.clone().lu().solve(&load).ok_or_else(|| Error::Numerical {
            what: "static deflection".into(),
            reason: "the stiffness matrix is singular: a part is not held by a spring".into(),
        })?;
        let at = |w: &[f64]| w.iter().zip(q.iter()).map(|(w, x)| w * x).sum::<f64>();
        Ok(self
            .elements
            .iter()
            .map(|e| {
                let far = match &e.to {
                    Attach::Point(h) => at(h),
                    _ => 0.0,
                };
                (e.name.clone(), far - at(&e.point))
            })
            .collect())
    }
}

/// The parts of a model that nonlinear elements are built on ([`crate::nonlinear`]).
impl Mdof {
    /// The spring–damper elements (empty for a model given by its matrices).
    pub fn elements(&self) -> &[Element] {
        &self.elements
    }
    /// The coordinates' names and units.
    pub fn coordinates(&self) -> &[(String, String)] {
        &self.coords
    }
    /// M⁻¹.
    pub fn mass_inverse(&self) -> &DMatrix<f64> {
        &self.m_inv
    }
    /// K_u (n × base inputs).
    pub fn base_stiffness(&self) -> &DMatrix<f64> {
        &self.ku
    }
    /// B_u (n × base inputs).
    pub fn base_damping(&self) -> &DMatrix<f64> {
        &self.bu
    }
    /// F (n × force inputs).
    pub fn force_distribution(&self) -> &DMatrix<f64> {
        &self.f
    }
    /// The weights of output `r`, if it exists.
    pub fn output_weights(&self, r: usize) -> Option<OutputWeights<'_>> {
        self.combos.get(r).map(|k| OutputWeights {
            q: k.q.as_slice(),
            v: k.v.as_slice(),
            a: k.a.as_slice(),
            u: k.u.as_slice(),
            du: k.du.as_slice(),
        })
    }

    /// The model with more spring–damper elements, of any sign (the Gaussian equivalents of nonlinear
    /// elements may stiffen or soften): each adds k d dᵀ to C, b d dᵀ to B (and k g, b g to the base
    /// columns of a base element), as in [`Mdof::from_elements`]; the outputs are kept. Adding no element
    /// gives an identical model.
    ///
    /// # Errors
    /// A point of the wrong length, an unknown base input, non-finite values.
    pub fn with_added_elements(&self, extra: &[Element]) -> Result<Mdof> {
        let n = self.n_coords();
        let mut out = self.clone();
        for e in extra {
            if e.point.len() != n || !(e.stiffness.is_finite() && e.damping.is_finite()) {
                return Err(Error::invalid(
                    &format!("element `{}`", e.name),
                    format!("{:?}, k = {}, b = {}", e.point, e.stiffness, e.damping),
                    format!("need {n} point weights and finite coefficients"),
                ));
            }
            let g = DVector::from_column_slice(&e.point);
            let d = match &e.to {
                Attach::Ground => g.clone(),
                Attach::Base(j) if *j < self.n_base() => {
                    out.ku.column_mut(*j).axpy(e.stiffness, &g, 1.0);
                    out.bu.column_mut(*j).axpy(e.damping, &g, 1.0);
                    g.clone()
                }
                Attach::Point(h) if h.len() == n => &g - DVector::from_column_slice(h),
                other => {
                    return Err(Error::invalid(
                        &format!("element `{}`.to", e.name),
                        format!("{other:?}"),
                        "not an input or a point of this model",
                    ))
                }
            };
            out.c += e.stiffness * &d * d.transpose();
            out.b += e.damping * &d * d.transpose();
            out.elements.push(e.clone());
        }
        if !extra.is_empty() {
            out.rebuild_state_space()?;
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::{Mdof, Quantity};
    use crate::system::FrequencyResponse;
    use nalgebra::DMatrix;

    /// A two-coordinate model with a base input (stiffness and damping to it) and a force input.
    fn two_masses() -> Mdof {
        let m = DMatrix::from_row_slice(2, 2, &[300.0, 0.0, 0.0, 40.0]);
        let b = DMatrix::from_row_slice(2, 2, &[1500.0, -1500.0, -1500.0, 1500.0]);
        let c = DMatrix::from_row_slice(2, 2, &[2.0e4, -2.0e4, -2.0e4, 2.0e4 + 2.0e5]);
        let ku = DMatrix::from_row_slice(2, 1, &[0.0, 2.0e5]);
        let bu = DMatrix::from_row_slice(2, 1, &[0.0, 50.0]);
        let f = DMatrix::from_row_slice(2, 1, &[1.0, 0.0]);
        Mdof::new(&[("body", "m"), ("wheel", "m")], m, b, c, ku, bu, f).expect("a valid model")
    }

    fn outputs() -> Vec<(&'static str, Quantity)> {
        vec![
            ("body", Quantity::Displacement(vec![1.0, 0.0])),
            ("body_vel", Quantity::Velocity(vec![1.0, 0.0])),
            ("body_acc", Quantity::Acceleration(vec![1.0, 0.0])),
            ("travel", Quantity::Displacement(vec![1.0, -1.0])),
            (
                "tyre",
                Quantity::RelativeDisplacement {
                    point: vec![0.0, 1.0],
                    base: 0,
                },
            ),
            (
                "tyre_rate",
                Quantity::RelativeVelocity {
                    point: vec![0.0, 1.0],
                    base: 0,
                },
            ),
        ]
    }

    /// All outputs at once (the state space written once) give the model that adding them one at a time
    /// gives (the state space written after each): the same outputs and the same bits in A, B, C, D and E.
    #[test]
    fn outputs_at_once_give_the_model_of_outputs_one_at_a_time() {
        let at_once = two_masses().with_outputs(outputs()).expect("valid outputs");
        let mut one_by_one = two_masses();
        for (name, q) in outputs() {
            one_by_one = one_by_one.with_output(name, q).expect("a valid output");
        }
        assert_eq!(at_once.outputs(), one_by_one.outputs());
        let (a, b) = (
            at_once.state_space().expect("a state space"),
            one_by_one.state_space().expect("a state space"),
        );
        let bits = |m: &DMatrix<f64>| m.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        for (x, y) in [(&a.a, &b.a), (&a.b, &b.b), (&a.c, &b.c), (&a.d, &b.d), (&a.e, &b.e)] {
            assert_eq!(x.shape(), y.shape());
            assert_eq!(bits(x), bits(y));
        }
        assert_eq!(a.c.nrows(), 6);
    }
}
