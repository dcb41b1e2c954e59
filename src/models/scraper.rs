//! Self-propelled scraper on a random road, rigid and sprung cab (Sukharev 2012, section 8.7,
//! eqs. (8.64)–(8.69), Table 8.1).
//!
//! The front (tractor) part of the scraper is a mass m₁ on its tyres (stiffness c₁, damping b₁) driven by
//! the road height q(t); with cab isolation a cab of mass m₂ sits on m₁ through c₂, b₂.

use super::{InputLayout, ModelInstance};
use crate::error::{require_non_negative, require_positive, Error, Result};
use crate::fields::{Fields, KeyReading};
use crate::models::worked_example::BookRow;
use crate::response::{analyze_output, Excitation, ResponseStatistics, TransferPolynomials};
use crate::spectrum::{two_pole_road::Form, AtSpeed, Domain, Exponential, Spectrum, TwoPoleRoad};
use crate::system::{OutputInfo, StateSpace};
use crate::units::Dim;
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;

/// The printed Table 8.1 (transcribed from the book, with units and the parameters it does not print).
pub const TABLE_8_1_TOML: &str = include_str!("../../data/reference/table-8-1.toml");

/// Scraper with a rigid cab (8.64): m₁ (kg) on tyres c₁ (N/m), b₁ (N s/m).
///
/// # Formula
/// ```text
/// m₁ẍ₁ + b₁ẋ₁ + c₁x₁ = c₁q + b₁q̇                                  (8.64)
/// H_{x1}(iω) = (c₁ + ib₁ω)/(c₁ − m₁ω² + ib₁ω),     H_{ẍ1} = −ω² H_{x1}
/// σ² = (1/2π)∫|W|² Ŝ_q dω  (8.67),  σ_ẍ² = (1/2π)∫|W|² ω⁴ Ŝ_q dω  (8.68)   (Ŝ = 2πS, engineering)
/// ```
/// With b₁ > 0 the acceleration transmissibility grows like (b₁/m₁)²ω² at high ω: under a road whose
/// density falls only like ω⁻² (the printed (8.66), or (8.69)) the acceleration variance is infinite and
/// the response module reports [`Error::Divergent`] (ask for a band instead).
///
/// # Errors
/// [`ScraperRigidCab::build`] rejects m₁ ≤ 0, c₁ ≤ 0, b₁ < 0 and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::scraper::{ScraperRigidCab, book_road_8_66, respond};
/// use stochvib::spectrum::two_pole_road::Form;
/// // ω₀ = 18.5 rad/s, ζ₁ = 0.1, m₁ = 30 t, consistent (8.66) road at 10 m/s
/// let m1 = 3.0e4;
/// let c1 = m1 * 18.5f64.powi(2);
/// let cab = ScraperRigidCab { m1, c1, b1: 2.0 * 0.1 * (c1 * m1).sqrt() }.build().unwrap();
/// let stats = respond(&cab.instance().unwrap(), book_road_8_66(Form::Consistent).unwrap(), 10.0).unwrap();
/// assert_eq!(stats[0].name, "x1");
/// assert!(stats[0].sigma.unwrap() > 0.035);   // above σ_q = 3.5 cm: resonance amplification
/// assert!(stats[1].sigma.is_some());          // finite acceleration under the ω⁻⁴ road
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScraperRigidCab {
    /// m₁, the machine's mass, kg.
    pub m1: f64,
    /// c₁, the tyres' stiffness, N/m.
    pub c1: f64,
    /// b₁, the tyres' damping, N s/m.
    pub b1: f64,
}

/// Scraper with a sprung (isolated) cab (8.65): adds the cab m₂ (kg) on c₂ (N/m), b₂ (N s/m).
///
/// # Formula
/// ```text
/// m₁ẍ₁ + b₁ẋ₁ + c₁x₁ + c₂(x₁ − x₂) + b₂(ẋ₁ − ẋ₂) = c₁q + b₁q̇
/// m₂ẍ₂ + b₂(ẋ₂ − ẋ₁) + c₂(x₂ − x₁) = 0                                (8.65)
/// k₁ = c₁ + ib₁ω, k₂ = c₂ + ib₂ω:
/// [[k₁ + k₂ − m₁ω², −k₂], [−k₂, k₂ − m₂ω²]] [X₁, X₂]ᵀ = [k₁, 0]ᵀ Q
/// H_{x2} = H_{x1} k₂/(k₂ − m₂ω²),   H_{ẍ} = −ω² H_x,   cab travel x₂ − x₁
/// ```
/// Outputs: `x1`, `x2`, `x1_acc`, `x2_acc`, `cab_travel` (x₂ − x₁). With b₁, b₂ > 0, |H_{ẍ2}|² tends to a
/// constant, so σ_ẍ2 is finite under any road falling at least like ω⁻²; σ_ẍ1 behaves as for the rigid cab.
///
/// # Errors
/// [`ScraperSprungCab::build`] rejects masses or stiffnesses ≤ 0, negative damping and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::scraper::{ScraperSprungCab, book_road_8_69, respond};
/// let (m1, m2) = (3.0e4, 2.0e3);
/// let (c1, c2) = (m1 * 18.5f64.powi(2), m2 * 9.42f64.powi(2));
/// let s = ScraperSprungCab { m1, c1, b1: 1.1e5, m2, c2, b2: 2.0 * 0.3 * (c2 * m2).sqrt() }.build().unwrap();
/// let stats = respond(&s.instance().unwrap(), book_road_8_69(), 10.0).unwrap();
/// let names: Vec<_> = stats.iter().map(|o| o.name.as_str()).collect();
/// assert_eq!(names, ["x1", "x2", "x1_acc", "x2_acc", "cab_travel"]);
/// assert!(stats[2].sigma.is_none());  // x1_acc diverges under (8.69) with b1 > 0
/// assert!(stats[3].sigma.is_some());  // the cab acceleration is finite
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScraperSprungCab {
    /// m₁, the machine's mass, kg.
    pub m1: f64,
    /// c₁, the tyres' stiffness, N/m.
    pub c1: f64,
    /// b₁, the tyres' damping, N s/m.
    pub b1: f64,
    /// m₂, the cab's mass, kg.
    pub m2: f64,
    /// c₂, the cab mounts' stiffness, N/m.
    pub c2: f64,
    /// b₂, the cab mounts' damping, N s/m.
    pub b2: f64,
}

/// An output of [`base_excited`]: displacement or acceleration of the point gᵀq.
enum Out {
    Disp(Vec<f64>),
    Acc(Vec<f64>),
}

/// A well-scaled state space of M q̈ + B q̇ + C q = k_u u + b_u u̇ (diagonal M, one base input u):
/// state x = [q; q̇ − M⁻¹b_u u], so that
/// ```text
/// A = [[0, I], [−M⁻¹C, −M⁻¹B]],   B_ss = [M⁻¹b_u; M⁻¹k_u − M⁻¹B M⁻¹b_u]
/// gᵀq̈ = gᵀ(−M⁻¹C q − M⁻¹B x₂ + (M⁻¹k_u − M⁻¹B M⁻¹b_u) u + M⁻¹b_u u̇)
/// ```
/// Every entry is a frequency or a squared frequency. (`Mdof`'s state [q; M q̇ − B_u u] mixes entries of
/// size 1/m and c, ~1e-5 and ~1e7 for a 30 t axle, and the Lyapunov solver then mistakes the poles for
/// λᵢ + λⱼ ≈ 0.)
fn base_excited(
    masses: &[f64],
    c: &[f64],
    b: &[f64],
    ku: &[f64],
    bu: &[f64],
    outs: &[(&str, Out)],
) -> Result<StateSpace> {
    let n = masses.len();
    let minv = DMatrix::from_diagonal(&DVector::from_iterator(n, masses.iter().map(|m| 1.0 / m)));
    let mc = &minv * DMatrix::from_row_slice(n, n, c);
    let mb = &minv * DMatrix::from_row_slice(n, n, b);
    let mku = &minv * DVector::from_column_slice(ku);
    let mbu = &minv * DVector::from_column_slice(bu);
    let lower = &mku - &mb * &mbu;
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    a.view_mut((0, n), (n, n)).fill_with_identity();
    a.view_mut((n, 0), (n, n)).copy_from(&(-&mc));
    a.view_mut((n, n), (n, n)).copy_from(&(-&mb));
    let mut bs = DMatrix::zeros(2 * n, 1);
    bs.view_mut((0, 0), (n, 1)).copy_from(&mbu);
    bs.view_mut((n, 0), (n, 1)).copy_from(&lower);
    let p = outs.len();
    let (mut cs, mut d, mut e) = (DMatrix::zeros(p, 2 * n), DMatrix::zeros(p, 1), DMatrix::zeros(p, 1));
    let mut infos = Vec::with_capacity(p);
    for (i, (name, o)) in outs.iter().enumerate() {
        match o {
            Out::Disp(g) => {
                for (j, gj) in g.iter().enumerate() {
                    cs[(i, j)] = *gj;
                }
                infos.push(OutputInfo::new(*name, "m"));
            }
            Out::Acc(g) => {
                let g = DVector::from_column_slice(g);
                let gt = g.transpose();
                cs.view_mut((i, 0), (1, n)).copy_from(&(-(&gt * &mc)));
                cs.view_mut((i, n), (1, n)).copy_from(&(-(&gt * &mb)));
                d[(i, 0)] = (&gt * &lower)[(0, 0)];
                e[(i, 0)] = (&gt * &mbu)[(0, 0)];
                infos.push(OutputInfo::new(*name, "m/s^2"));
            }
        }
    }
    StateSpace::new(a, bs, cs, Some(d), Some(e), infos)
}

/// What [`fill_base_excited`] writes for one output row: the displacement (false) or the acceleration
/// (true) of the point gᵀq.
type OutRow<const N: usize> = (bool, [f64; N]);

/// Writes the matrices of [`base_excited`] for N masses into `ss` (which has its shape: 2N states, one
/// input, one row per entry of `outs`) with the same arithmetic, entry by entry, on the stack: the
/// products with the diagonal M⁻¹ are the single non-zero terms of nalgebra's sums, and every other sum runs
/// over k ascending as nalgebra's does. Returns false (nothing promised about `ss`) when an entry is not
/// finite or the shape differs: [`StateSpace::new`] would refuse the general path's matrices then.
#[allow(clippy::too_many_arguments)]
fn fill_base_excited<const N: usize>(
    masses: [f64; N],
    c: [[f64; N]; N],
    b: [[f64; N]; N],
    ku: [f64; N],
    bu: [f64; N],
    outs: &[OutRow<N>],
    ss: &mut StateSpace,
) -> bool {
    let n = N;
    if ss.a.shape() != (2 * n, 2 * n) || ss.b.shape() != (2 * n, 1) || ss.c.shape() != (outs.len(), 2 * n) {
        return false;
    }
    let minv = masses.map(|m| 1.0 / m);
    let mut mc = [[0.0; N]; N];
    let mut mb = [[0.0; N]; N];
    for i in 0..n {
        for j in 0..n {
            mc[i][j] = minv[i] * c[i][j];
            mb[i][j] = minv[i] * b[i][j];
        }
    }
    let mut mku = [0.0; N];
    let mut mbu = [0.0; N];
    let mut lower = [0.0; N];
    for i in 0..n {
        mku[i] = minv[i] * ku[i];
        mbu[i] = minv[i] * bu[i];
    }
    for i in 0..n {
        let mut s = 0.0;
        for j in 0..n {
            s += mb[i][j] * mbu[j];
        }
        lower[i] = mku[i] - s;
    }
    ss.a.fill(0.0);
    for i in 0..n {
        ss.a[(i, n + i)] = 1.0;
        for j in 0..n {
            ss.a[(n + i, j)] = -mc[i][j];
            ss.a[(n + i, n + j)] = -mb[i][j];
        }
        ss.b[(i, 0)] = mbu[i];
        ss.b[(n + i, 0)] = lower[i];
    }
    ss.c.fill(0.0);
    for (r, (acc, g)) in outs.iter().enumerate() {
        let (mut d, mut e) = (0.0, 0.0);
        if *acc {
            for j in 0..n {
                let (mut sc, mut sb) = (0.0, 0.0);
                for k in 0..n {
                    sc += g[k] * mc[k][j];
                    sb += g[k] * mb[k][j];
                }
                ss.c[(r, j)] = -sc;
                ss.c[(r, n + j)] = -sb;
            }
            for k in 0..n {
                d += g[k] * lower[k];
                e += g[k] * mbu[k];
            }
        } else {
            for (j, gj) in g.iter().enumerate() {
                ss.c[(r, j)] = *gj;
            }
        }
        ss.d[(r, 0)] = d;
        ss.e[(r, 0)] = e;
    }
    [&ss.a, &ss.b, &ss.c, &ss.d, &ss.e]
        .iter()
        .all(|m| m.iter().all(|v| v.is_finite()))
}

/// c from `c` (N/m) or from `omega` = √(c/m) (rad/s), as the table reader derives it; None where the
/// reader fails (both or neither given, ω ≤ 0).
fn stiffness_value(c: Option<f64>, w: Option<f64>, m: f64) -> Option<f64> {
    match (c, w) {
        (Some(c), None) => Some(c),
        (None, Some(w)) if w > 0.0 => Some(m * w * w),
        _ => None,
    }
}

/// b from `b` (N s/m) or from the damping ratio ζ, b = 2ζ√(cm), as the table reader derives it; None where
/// the reader fails (both or neither given, ζ < 0).
fn damping_value(b: Option<f64>, z: Option<f64>, m: f64, c: f64) -> Option<f64> {
    match (b, z) {
        (Some(b), None) => Some(b),
        (None, Some(z)) if z >= 0.0 => Some(2.0 * z * (c * m).sqrt()),
        _ => None,
    }
}

/// The numeric keys of a `scraper-rigid-cab` table, in the order of [`rigid_fill`]'s values.
pub(crate) const RIGID_KEYS: &[(&str, KeyReading)] = &[
    ("m1", KeyReading::Quantity(Dim::MASS)),
    ("c1", KeyReading::Quantity(Dim::STIFFNESS)),
    ("omega1", KeyReading::AngularFrequency(Dim::FREQUENCY)),
    ("b1", KeyReading::Quantity(Dim::DAMPING)),
    ("zeta1", KeyReading::Number),
];

/// The numeric keys of a `scraper-sprung-cab` table, in the order of [`sprung_fill`]'s values.
pub(crate) const SPRUNG_KEYS: &[(&str, KeyReading)] = &[
    ("m1", KeyReading::Quantity(Dim::MASS)),
    ("c1", KeyReading::Quantity(Dim::STIFFNESS)),
    ("omega1", KeyReading::AngularFrequency(Dim::FREQUENCY)),
    ("b1", KeyReading::Quantity(Dim::DAMPING)),
    ("zeta1", KeyReading::Number),
    ("m2", KeyReading::Quantity(Dim::MASS)),
    ("c2", KeyReading::Quantity(Dim::STIFFNESS)),
    ("omega2", KeyReading::AngularFrequency(Dim::FREQUENCY)),
    ("b2", KeyReading::Quantity(Dim::DAMPING)),
    ("zeta2", KeyReading::Number),
];

/// The numeric builder of `scraper-rigid-cab`: the state space of [`rigid_from_fields`] for the values of
/// [`RIGID_KEYS`] (None: key absent), written into `ss` (the shape of an instance). False where the table
/// reader or the model would fail: the caller then asks the general path, which names the error.
pub(crate) fn rigid_fill(v: &[Option<f64>], ss: &mut StateSpace) -> bool {
    let Some(s) = rigid_model(v) else { return false };
    fill_base_excited(
        [s.m1],
        [[s.c1]],
        [[s.b1]],
        [s.c1],
        [s.b1],
        &[(false, [1.0]), (true, [1.0])],
        ss,
    )
}

/// The rigid-cab model of the values of [`RIGID_KEYS`], as the table reader derives it; None where the
/// reader or the model would fail.
fn rigid_model(v: &[Option<f64>]) -> Option<ScraperRigidCab> {
    let m1 = v[0]?;
    let c1 = stiffness_value(v[1], v[2], m1)?;
    let b1 = damping_value(v[3], v[4], m1, c1)?;
    ScraperRigidCab { m1, c1, b1 }.build().ok()
}

/// The closed-form transfer polynomials of `scraper-rigid-cab` for the values of [`RIGID_KEYS`] (the
/// numeric path of a parameter study: no state space per point). False where the reader or the model would
/// fail.
///
/// # Formula
/// From (8.64), m₁ẍ₁ + b₁ẋ₁ + c₁x₁ = c₁q + b₁q̇, divided by m₁ (a₁ = c₁/m₁, β₁ = b₁/m₁):
/// ```text
/// Δ(s) = s² + β₁ s + a₁ = det(sI − A),   N_x1(s) = β₁ s + a₁,   N_x1_acc(s) = s² (β₁ s + a₁)
/// ```
/// (outputs in the instance's order `x1`, `x1_acc`). `tp` arrives zeroed
/// ([`TransferBuilder`](crate::response::TransferBuilder)): only the non-zero coefficients are written.
pub(crate) fn rigid_transfer(v: &[Option<f64>], tp: &mut TransferPolynomials) -> bool {
    let Some(s) = rigid_model(v) else { return false };
    let (a1, beta1) = (s.c1 / s.m1, s.b1 / s.m1);
    if !(a1.is_finite() && beta1.is_finite()) {
        return false;
    }
    tp.n = 2;
    tp.den[..3].copy_from_slice(&[a1, beta1, 1.0]);
    tp.num[0][..2].copy_from_slice(&[a1, beta1]);
    tp.num[1][2..4].copy_from_slice(&[a1, beta1]);
    true
}

/// The numeric builder of `scraper-sprung-cab` (as [`rigid_fill`], values of [`SPRUNG_KEYS`]).
pub(crate) fn sprung_fill(v: &[Option<f64>], ss: &mut StateSpace) -> bool {
    let Some(s) = sprung_model(v) else { return false };
    let (c1, c2, b1, b2) = (s.c1, s.c2, s.b1, s.b2);
    fill_base_excited(
        [s.m1, s.m2],
        [[c1 + c2, -c2], [-c2, c2]],
        [[b1 + b2, -b2], [-b2, b2]],
        [c1, 0.0],
        [b1, 0.0],
        &[
            (false, [1.0, 0.0]),
            (false, [0.0, 1.0]),
            (true, [1.0, 0.0]),
            (true, [0.0, 1.0]),
            (false, [-1.0, 1.0]),
        ],
        ss,
    )
}

/// The sprung-cab model of the values of [`SPRUNG_KEYS`], as the table reader derives it; None where the
/// reader or the model would fail.
fn sprung_model(v: &[Option<f64>]) -> Option<ScraperSprungCab> {
    let m1 = v[0]?;
    let c1 = stiffness_value(v[1], v[2], m1)?;
    let b1 = damping_value(v[3], v[4], m1, c1)?;
    let m2 = v[5]?;
    let c2 = stiffness_value(v[6], v[7], m2)?;
    let b2 = damping_value(v[8], v[9], m2, c2)?;
    ScraperSprungCab { m1, c1, b1, m2, c2, b2 }.build().ok()
}

/// The closed-form transfer polynomials of `scraper-sprung-cab` for the values of [`SPRUNG_KEYS`] (the
/// numeric path of a parameter study: no state space or Faddeev–LeVerrier pass per point). False where the
/// reader or the model would fail.
///
/// # Formula
/// (8.65) in the Laplace domain, with k₁ = b₁s + c₁, k₂ = b₂s + c₂, P₁ = m₁s² + k₁ + k₂, P₂ = m₂s² + k₂:
/// ```text
/// [[P₁, −k₂], [−k₂, P₂]] [X₁, X₂]ᵀ = [k₁, 0]ᵀ Q   ⇒   X₁ = k₁P₂ Q/Δ_m,  X₂ = k₁k₂ Q/Δ_m,  Δ_m = P₁P₂ − k₂²
/// Δ_m = m₁m₂s⁴ + (m₁b₂ + m₂(b₁ + b₂))s³ + (m₁c₂ + m₂(c₁ + c₂) + b₁b₂)s² + (b₁c₂ + b₂c₁)s + c₁c₂
/// ```
/// (P₁P₂ − k₂² = m₁m₂s⁴ + m₁s²k₂ + m₂s²(k₁ + k₂) + k₁k₂). Divided by m₁m₂, with a_j = c_j/m_j,
/// β_j = b_j/m_j, μ = m₂/m₁ and K_j = β_j s + a_j (so Δ is monic, as det(sI − A) of the instance):
/// ```text
/// Δ(s) = s⁴ + (β₁ + β₂ + μβ₂)s³ + (a₁ + a₂ + μa₂ + β₁β₂)s² + (β₁a₂ + β₂a₁)s + a₁a₂
/// N_x1 = K₁(s² + K₂),   N_x2 = K₁K₂,   N_x1_acc = s²N_x1,   N_x2_acc = s²N_x2,
/// N_cab_travel = N_x2 − N_x1 = −s²K₁
/// ```
/// (outputs in the instance's order `x1`, `x2`, `x1_acc`, `x2_acc`, `cab_travel`). `tp` arrives zeroed
/// ([`TransferBuilder`](crate::response::TransferBuilder)): only the non-zero coefficients are written.
pub(crate) fn sprung_transfer(v: &[Option<f64>], tp: &mut TransferPolynomials) -> bool {
    let Some(s) = sprung_model(v) else { return false };
    let (a1, beta1) = (s.c1 / s.m1, s.b1 / s.m1);
    let (a2, beta2) = (s.c2 / s.m2, s.b2 / s.m2);
    let mu = s.m2 / s.m1;
    let den = [
        a1 * a2,
        beta1 * a2 + beta2 * a1,
        a1 + a2 + mu * a2 + beta1 * beta2,
        beta1 + beta2 + mu * beta2,
        1.0,
    ];
    // K₁(s² + K₂) = a₁a₂ + (a₁β₂ + β₁a₂)s + (a₁ + β₁β₂)s² + β₁s³,   K₁K₂ = a₁a₂ + (a₁β₂ + β₁a₂)s + β₁β₂s²
    let x1 = [a1 * a2, a1 * beta2 + beta1 * a2, a1 + beta1 * beta2, beta1];
    let x2 = [a1 * a2, a1 * beta2 + beta1 * a2, beta1 * beta2];
    if !den.iter().chain(&x1).chain(&x2).all(|v| v.is_finite()) {
        return false;
    }
    tp.n = 4;
    tp.den[..5].copy_from_slice(&den);
    tp.num[0][..4].copy_from_slice(&x1);
    tp.num[1][..3].copy_from_slice(&x2);
    tp.num[2][2..6].copy_from_slice(&x1);
    tp.num[3][2..5].copy_from_slice(&x2);
    tp.num[4][2..4].copy_from_slice(&[-a1, -beta1]);
    true
}

fn track_layout() -> InputLayout {
    InputLayout::Track {
        positions: vec![0.0],
        gains: vec![1.0],
    }
}

impl ScraperRigidCab {
    /// The model of these fields, checked: m₁ (kg), c₁ (N/m), b₁ (N s/m).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        let ScraperRigidCab { m1, c1, b1 } = self;
        Ok(ScraperRigidCab {
            m1: require_positive("m1", m1)?,
            c1: require_positive("c1", c1)?,
            b1: require_non_negative("b1", b1)?,
        })
    }

    /// The model as a single-road-input system (base input q, m; layout `Track` with one contact point);
    /// outputs `x1` (m), `x1_acc` (m/s²).
    ///
    /// # Errors
    /// None for a validated model (kept as `Result` for the system constructor).
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::scraper::ScraperRigidCab;
    /// use stochvib::system::FrequencyResponse;
    /// let m = ScraperRigidCab { m1: 3.0e4, c1: 1.0e7, b1: 1.0e5 }.build().unwrap().instance().unwrap();
    /// assert!((m.system.static_gain().unwrap()[(0, 0)] - 1.0).abs() < 1e-12); // x1 follows q statically
    /// ```
    pub fn instance(&self) -> Result<ModelInstance> {
        let sys = base_excited(
            &[self.m1],
            &[self.c1],
            &[self.b1],
            &[self.c1],
            &[self.b1],
            &[("x1", Out::Disp(vec![1.0])), ("x1_acc", Out::Acc(vec![1.0]))],
        )?;
        Ok(ModelInstance {
            system: Arc::new(sys),
            layout: track_layout(),
            description: format!(
                "scraper, rigid cab (Sukharev 8.7, eq. (8.64)): m1 = {} kg, c1 = {} N/m, b1 = {} N s/m",
                self.m1, self.c1, self.b1
            ),
        })
    }
}

impl ScraperSprungCab {
    /// The model of these fields, checked: m₁, c₁, b₁ of the machine and m₂, c₂, b₂ of the cab (kg, N/m,
    /// N s/m) as named fields instead of six bare numbers of different meaning.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        let ScraperSprungCab { m1, c1, b1, m2, c2, b2 } = self;
        Ok(ScraperSprungCab {
            m1: require_positive("m1", m1)?,
            c1: require_positive("c1", c1)?,
            b1: require_non_negative("b1", b1)?,
            m2: require_positive("m2", m2)?,
            c2: require_positive("c2", c2)?,
            b2: require_non_negative("b2", b2)?,
        })
    }

    /// The model as a single-road-input system; outputs `x1`, `x2` (m), `x1_acc`, `x2_acc` (m/s²),
    /// `cab_travel` (x₂ − x₁, m).
    ///
    /// # Errors
    /// None for a validated model.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::scraper::ScraperSprungCab;
    /// use stochvib::system::FrequencyResponse;
    /// let m = ScraperSprungCab { m1: 3.0e4, c1: 1.0e7, b1: 1.0e5, m2: 2.0e3, c2: 1.8e5, b2: 1.1e4 }.build().unwrap().instance().unwrap();
    /// let g = m.system.static_gain().unwrap();
    /// assert!((g[(1, 0)] - 1.0).abs() < 1e-12 && g[(4, 0)].abs() < 1e-12); // cab follows q, no static travel
    /// ```
    pub fn instance(&self) -> Result<ModelInstance> {
        // C and B of (8.65): tyre on x1 to the road, cab mount between x1 and x2
        let (c1, c2, b1, b2) = (self.c1, self.c2, self.b1, self.b2);
        let sys = base_excited(
            &[self.m1, self.m2],
            &[c1 + c2, -c2, -c2, c2],
            &[b1 + b2, -b2, -b2, b2],
            &[c1, 0.0],
            &[b1, 0.0],
            &[
                ("x1", Out::Disp(vec![1.0, 0.0])),
                ("x2", Out::Disp(vec![0.0, 1.0])),
                ("x1_acc", Out::Acc(vec![1.0, 0.0])),
                ("x2_acc", Out::Acc(vec![0.0, 1.0])),
                ("cab_travel", Out::Disp(vec![-1.0, 1.0])),
            ],
        )?;
        Ok(ModelInstance {
            system: Arc::new(sys),
            layout: track_layout(),
            description: format!(
                "scraper, sprung cab (Sukharev 8.7, eq. (8.65)): m1 = {} kg, c1 = {} N/m, b1 = {} N s/m, m2 = {} kg, \
                 c2 = {} N/m, b2 = {} N s/m",
                self.m1, self.c1, self.b1, self.m2, self.c2, self.b2
            ),
        })
    }
}

/// The book's scraper road (8.66), spatial (rad/m): √D_q = 3.5 cm, α = 0.3, β = 12, read as 1/m (units
/// not printed), in the printed or the dimensionally consistent form (see [`TwoPoleRoad`]).
///
/// # Errors
/// None in practice (constant valid parameters).
pub fn book_road_8_66(form: Form) -> Result<Arc<dyn Spectrum>> {
    Ok(Arc::new(
        TwoPoleRoad {
            dq: 0.035 * 0.035,
            alpha: 0.3,
            beta: 12.0,
            form,
        }
        .build()?,
    ))
}

/// The book's graded dirt road (8.69): spatial type 1, D_q = 32 cm², α = 0.16·10⁻² 1/cm = 0.16 1/m.
pub fn book_road_8_69() -> Arc<dyn Spectrum> {
    Arc::new(Exponential::new(32e-4, 0.16, Domain::Spatial).expect("valid constants"))
}

/// Statistics of every output of a scraper instance driven by the spatial road `road` at `speed` (m/s):
/// the road is turned into time ([`AtSpeed`], S_t(ω) = S(ω/v)/v) and every output goes through
/// [`analyze_output`], which reports an infinite variance (`sigma = None`, `variance_note` naming the
/// divergence) instead of a number.
///
/// # Errors
/// A non-spatial road, speed ≤ 0, an instance whose layout is not a single-point track.
pub fn respond(inst: &ModelInstance, road: Arc<dyn Spectrum>, speed: f64) -> Result<Vec<ResponseStatistics>> {
    let InputLayout::Track { positions, gains } = &inst.layout else {
        return Err(Error::invalid(
            "layout",
            "single",
            "the scraper is driven by a road track",
        ));
    };
    let delays = positions.iter().map(|p| p / speed).collect();
    let exc = Excitation::track(Arc::new(AtSpeed::new(road, speed)?), delays, gains.clone(), 0.0)?;
    (0..inst.system.outputs().len())
        .map(|i| analyze_output(inst.system.as_ref(), &exc, i))
        .collect()
}

fn stiffness_or_frequency(f: &Fields, c_key: &str, w_key: &str, m: f64) -> Result<f64> {
    match (f.get(c_key), f.get(w_key)) {
        (Some(_), None) => f.quantity(c_key, Dim::STIFFNESS),
        (None, Some(v)) => {
            let w = f.angular_frequency(v, w_key, Dim::FREQUENCY)?;
            if w <= 0.0 {
                return Err(f.error(w_key, v, "must be > 0"));
            }
            Ok(m * w * w)
        }
        (Some(_), Some(_)) => Err(f.error(w_key, "both", format!("give `{c_key}` or `{w_key}`, not both"))),
        (None, None) => Err(f.error(
            c_key,
            "<missing>",
            format!("give `{c_key}` (N/m) or `{w_key}` (natural frequency sqrt(c/m), with unit)"),
        )),
    }
}

fn damping_or_ratio(f: &Fields, b_key: &str, z_key: &str, m: f64, c: f64) -> Result<f64> {
    match (f.get(b_key), f.get(z_key)) {
        (Some(_), None) => f.quantity(b_key, Dim::DAMPING),
        (None, Some(v)) => {
            let z = f.number(z_key)?;
            if z < 0.0 {
                return Err(f.error(z_key, v, "a damping ratio must be >= 0"));
            }
            Ok(2.0 * z * (c * m).sqrt())
        }
        (Some(_), Some(_)) => Err(f.error(z_key, "both", format!("give `{b_key}` or `{z_key}`, not both"))),
        (None, None) => Err(f.error(
            b_key,
            "<missing>",
            format!("give `{b_key}` (N s/m) or `{z_key}` (damping ratio)"),
        )),
    }
}

/// Reads the `[model]` table of a `scraper-rigid-cab` scenario: `m1` (mass), `c1` (N/m) or `omega1`
/// (√(c₁/m₁), with unit), `b1` (N s/m) or `zeta1` (damping ratio).
///
/// # Errors
/// Missing, conflicting or invalid keys, named with the file.
pub fn rigid_from_fields(f: &Fields) -> Result<ModelInstance> {
    let m1 = f.quantity("m1", Dim::MASS)?;
    let c1 = stiffness_or_frequency(f, "c1", "omega1", m1)?;
    let b1 = damping_or_ratio(f, "b1", "zeta1", m1, c1)?;
    ScraperRigidCab { m1, c1, b1 }
        .build()
        .map_err(|e| f.wrap_param(e, "m1"))?
        .instance()
}

/// Reads the `[model]` table of a `scraper-sprung-cab` scenario: as [`rigid_from_fields`] plus `m2`,
/// `c2` or `omega2`, `b2` or `zeta2` for the cab.
///
/// # Errors
/// Missing, conflicting or invalid keys, named with the file.
pub fn sprung_from_fields(f: &Fields) -> Result<ModelInstance> {
    let m1 = f.quantity("m1", Dim::MASS)?;
    let c1 = stiffness_or_frequency(f, "c1", "omega1", m1)?;
    let b1 = damping_or_ratio(f, "b1", "zeta1", m1, c1)?;
    let m2 = f.quantity("m2", Dim::MASS)?;
    let c2 = stiffness_or_frequency(f, "c2", "omega2", m2)?;
    let b2 = damping_or_ratio(f, "b2", "zeta2", m2, c2)?;
    ScraperSprungCab { m1, c1, b1, m2, c2, b2 }
        .build()
        .map_err(|e| f.wrap_param(e, "m1"))?
        .instance()
}

/// Reads either scraper `[model]` table: the sprung cab when any of `m2`, `c2`, `omega2` is present,
/// else the rigid cab. (The caller dispatches on `kind`; prefer [`rigid_from_fields`] /
/// [`sprung_from_fields`] when the kind is known.)
///
/// # Errors
/// As [`rigid_from_fields`] / [`sprung_from_fields`].
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    if f.get("m2").is_some() || f.get("c2").is_some() || f.get("omega2").is_some() {
        sprung_from_fields(f)
    } else {
        rigid_from_fields(f)
    }
}

/// The values assumed for the parameters Table 8.1 needs but the book does not print. Chosen a priori
/// from the printed ranges and typical machine values — never fitted to the table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Table81Assumptions {
    /// m₁, kg: middle of the printed front-axle mass range 20…40 t.
    pub m1: f64,
    /// ω₀ = √(c₁/m₁), rad/s: middle of the printed range 17…20 1/s.
    pub omega1: f64,
    /// ζ₁ = b₁/(2√(c₁m₁)): b₁ not printed; 0.1 is a typical large-tyre damping ratio.
    pub zeta1: f64,
    /// m₂, kg: not printed; a 2 t cab.
    pub m2: f64,
    /// ω₂ = √(c₂/m₂), rad/s: not printed; 1.5 Hz, a usual cab-mount frequency.
    pub omega2: f64,
    /// ζ₂: not printed; 0.3, a usual cab-mount damping ratio.
    pub zeta2: f64,
    /// Reading of (8.66): the consistent two-pole form (the printed form makes σ_ẍ1 infinite).
    pub road_form: Form,
}

impl Default for Table81Assumptions {
    fn default() -> Self {
        Table81Assumptions {
            m1: 3.0e4,
            omega1: 18.5,
            zeta1: 0.1,
            m2: 2.0e3,
            omega2: 2.0 * std::f64::consts::PI * 1.5,
            zeta2: 0.3,
            road_form: Form::Consistent,
        }
    }
}

impl Table81Assumptions {
    /// One line stating every assumption.
    pub fn describe(&self) -> String {
        format!(
            "assumed (not printed, not fitted): m1 = {} t, omega0 = {} rad/s, zeta1 = {}, m2 = {} t, omega2 = {:.2} rad/s, \
             zeta2 = {}; road (8.66) {} with alpha, beta in 1/m",
            self.m1 / 1e3,
            self.omega1,
            self.zeta1,
            self.m2 / 1e3,
            self.omega2,
            self.zeta2,
            match self.road_form {
                Form::Consistent => "consistent form",
                Form::AsPrinted => "as printed",
            }
        )
    }

    /// The two models these assumptions define.
    ///
    /// # Errors
    /// Invalid assumed values.
    pub fn models(&self) -> Result<(ScraperRigidCab, ScraperSprungCab)> {
        let c1 = self.m1 * self.omega1 * self.omega1;
        let b1 = 2.0 * self.zeta1 * (c1 * self.m1).sqrt();
        let c2 = self.m2 * self.omega2 * self.omega2;
        let b2 = 2.0 * self.zeta2 * (c2 * self.m2).sqrt();
        Ok((
            ScraperRigidCab { m1: self.m1, c1, b1 }.build()?,
            ScraperSprungCab {
                m1: self.m1,
                c1,
                b1,
                m2: self.m2,
                c2,
                b2,
            }
            .build()?,
        ))
    }
}

/// One printed row of Table 8.1.
#[derive(Debug, Clone, PartialEq)]
pub struct Table81Row {
    /// `rigid` or `sprung`.
    pub cab: String,
    /// Output name of the model (`x1`, `x1_acc`, `x2`, `x2_acc`).
    pub output: String,
    /// Unit as printed (`cm`, `m/s^2`).
    pub unit: String,
    /// Printed values, in the printed unit, one per speed.
    pub values: Vec<f64>,
}

/// The printed Table 8.1 from `data/reference/table-8-1.toml`: the speeds (m/s) and the rows.
///
/// # Errors
/// A malformed data file (a build-time constant, so only a broken edit of the file).
pub fn table_8_1() -> Result<(Vec<f64>, Vec<Table81Row>)> {
    parse_table_8_1(TABLE_8_1_TOML, std::path::Path::new("data/reference/table-8-1.toml"))
}

/// Parses a Table 8.1 file (`path` for messages): the speeds (m/s) and the rows.
///
/// # Errors
/// [`Error::Parse`] or [`Error::File`] naming the key.
pub fn parse_table_8_1(text: &str, path: &std::path::Path) -> Result<(Vec<f64>, Vec<Table81Row>)> {
    let table: toml::Table = crate::fields::parse_toml(text, path)?;
    let f = Fields::new(path, "", &table);
    let speeds = f
        .require("speeds")?
        .as_array()
        .ok_or_else(|| f.error("speeds", "?", "expected an array"))?
        .iter()
        .map(|v| crate::units::parse_value(v, Dim::VELOCITY).map_err(|r| f.error("speeds", v, r)))
        .collect::<Result<Vec<f64>>>()?;
    if speeds.is_empty() {
        return Err(f.error("speeds", "[]", "the table needs at least one speed (a column)"));
    }
    let rows = f
        .require("row")?
        .as_array()
        .ok_or_else(|| f.error("row", "?", "expected an array of tables"))?
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let t = r.as_table().ok_or_else(|| f.error("row", i, "expected a table"))?;
            let rf = Fields::new(path, &format!("row[{i}]"), t);
            let row = Table81Row {
                cab: rf.string("cab")?.to_string(),
                output: rf.string("output")?.to_string(),
                unit: rf.string("unit")?.to_string(),
                values: rf.numbers("values")?,
            };
            rf.opt_string("printed_symbol")?;
            if row.values.len() != speeds.len() {
                return Err(rf.error(
                    "values",
                    row.values.len(),
                    format!("need one value per speed ({})", speeds.len()),
                ));
            }
            rf.finish()?;
            Ok(row)
        })
        .collect::<Result<Vec<_>>>()?;
    if rows.is_empty() {
        return Err(f.error("row", "[]", "the table needs at least one [[row]]: nothing to report"));
    }
    // the transcription's descriptive keys: read (so that a misspelt one is refused) but not used
    for k in ["reference", "title", "source", "status"] {
        f.opt_string(k)?;
    }
    if f.get("printed_parameters").is_some() {
        let pf = f.sub("printed_parameters")?;
        for k in [
            "front_axle_mass",
            "sqrt_dq",
            "alpha",
            "beta",
            "omega0",
            "speed_range",
            "acceleration_limit",
        ] {
            pf.opt_string(k)?;
        }
        pf.finish()?;
    }
    if f.get("not_printed").is_some() {
        let nf = f.sub("not_printed")?;
        if let Some(v) = nf.get("parameters") {
            let arr = v
                .as_array()
                .ok_or_else(|| nf.error("parameters", v, "expected an array of strings"))?;
            if let Some((j, x)) = arr.iter().enumerate().find(|(_, x)| !x.is_str()) {
                return Err(nf.error(&format!("parameters[{j}]"), x, "expected a string"));
            }
        }
        nf.finish()?;
    }
    f.finish()?;
    Ok((speeds, rows))
}

/// Table 8.1, every printed cell against the models built from `assumptions`, driven by the (8.66) road at
/// the printed speeds. Values in SI (cm → m). Adds, for each σ_x2 cell, a row reading x₂ as the cab travel
/// x₂ − x₁ (the only reading in which the printed magnitudes are possible).
///
/// # Errors
/// A malformed table file, invalid assumptions.
pub fn table_8_1_comparison(assumptions: &Table81Assumptions) -> Result<Vec<BookRow>> {
    let (speeds, rows) = table_8_1()?;
    let (rigid, sprung) = assumptions.models()?;
    let (ri, si) = (rigid.instance()?, sprung.instance()?);
    let road = book_road_8_66(assumptions.road_form)?;
    let example = "Sukharev (2012) 8.7, Table 8.1 (scraper, rigid and sprung cab)";
    let assumed = assumptions.describe();
    let mut out = Vec::new();
    for (k, &v) in speeds.iter().enumerate() {
        let rs = respond(&ri, road.clone(), v)?;
        let ss = respond(&si, road.clone(), v)?;
        let pick =
            |stats: &[ResponseStatistics], name: &str| stats.iter().find(|s| s.name == name).and_then(|s| s.sigma);
        for row in &rows {
            let scale = if row.unit == "cm" { 0.01 } else { 1.0 };
            let unit = if row.unit == "cm" { "m" } else { "m/s^2" };
            let stats = if row.cab == "rigid" { &rs } else { &ss };
            let why = match row.output.as_str() {
                "x1" => {
                    "σ_x1 cannot be below σ_q = 3.5 cm at 5 m/s (|H_x1| ≥ 1 for ω ≤ √2ω₀, where the road power lies)"
                }
                "x2" => {
                    "an absolute cab displacement of 1–2.5 cm ≪ σ_q = 3.5 cm is impossible (|H_x2(0)| = 1); the print \
                         matches the cab travel x₂ − x₁ in size"
                }
                _ => "acceleration depends on the unprinted damping",
            };
            out.push(BookRow {
                example: example.into(),
                quantity: format!("sigma_{} ({} cab) at {v} m/s", row.output, row.cab),
                unit: unit.into(),
                printed: Some(row.values[k] * scale),
                computed: pick(stats, &row.output),
                explanation: format!("table not reproducible from printed parameters: {why}; {assumed}"),
            });
            if row.output == "x2" {
                out.push(BookRow {
                    example: example.into(),
                    quantity: format!("sigma_x2 read as cab travel x2 - x1 (sprung cab) at {v} m/s"),
                    unit: "m".into(),
                    printed: Some(row.values[k] * scale),
                    computed: pick(stats, "cab_travel"),
                    explanation: format!(
                        "reading x₂ of Table 8.1 as the cab travel; cab parameters not printed; {assumed}"
                    ),
                });
            }
        }
    }
    Ok(out)
}

/// Table 8.1 rows with the default [`Table81Assumptions`] (one row carrying the error if the data file
/// were broken, so the failure is visible in the report).
pub fn book_rows() -> Vec<BookRow> {
    table_8_1_comparison(&Table81Assumptions::default()).unwrap_or_else(|e| {
        vec![BookRow {
            example: "Sukharev (2012) 8.7, Table 8.1 (scraper, rigid and sprung cab)".into(),
            quantity: "Table 8.1".into(),
            unit: "-".into(),
            printed: None,
            computed: None,
            explanation: format!("could not be computed: {e}"),
        }]
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::ILL_CONDITIONED;

    /// N(iω)/Δ(iω) by Horner's rule on the ascending coefficients.
    fn ratio_at(num: &[f64], den: &[f64], w: f64) -> nalgebra::Complex<f64> {
        let s = nalgebra::Complex::new(0.0, w);
        let horner = |p: &[f64]| {
            p.iter()
                .rev()
                .fold(nalgebra::Complex::new(0.0, 0.0), |acc, &c| acc * s + c)
        };
        horner(num) / horner(den)
    }

    /// The closed-form transfer polynomials (derived in the doc comments of `rigid_transfer` and
    /// `sprung_transfer` from (8.64), (8.65)) against a different computation of the same transfer
    /// functions: the instance's state-space frequency response C(iωI − A)⁻¹B + D + iωE by a linear solve, at
    /// 41 frequencies from 0.3 to 1200 rad/s (through both modes), for parameter sets from mild to stiff
    /// (cab 20 kg … 200 t, 0.05 … 40 Hz, ζ₂ 0 … 2), relative to max(|H|, 1e-3·max_ω|H|) so that the
    /// displacement transmissibilities falling at high ω are compared on the output's scale. The state-space
    /// value of an acceleration output at low ω is a cancelling sum (D ~ ω₁² against C(iωI − A)⁻¹B, to a
    /// result ~ω²): condition number ω₁²/ω² ≤ 1600/0.09 ≈ 2e4 on this grid, hence ILL_CONDITIONED (up to
    /// ~10⁵).
    #[test]
    fn transfer_polynomials_equal_state_space_response() {
        use crate::system::FrequencyResponse;
        let w = |f: f64| 2.0 * std::f64::consts::PI * f;
        let omegas: Vec<f64> = (0..41).map(|k| 0.3 * 10f64.powf(3.6 * k as f64 / 40.0)).collect();
        let check = |sys: &StateSpace, tp: &TransferPolynomials, n_out: usize, what: &str| {
            let n = tp.n;
            for i in 0..n_out {
                let pairs: Vec<_> = omegas
                    .iter()
                    .map(|&om| {
                        (
                            sys.response(om)[(i, 0)],
                            ratio_at(&tp.num[i][..n + 2], &tp.den[..=n], om),
                        )
                    })
                    .collect();
                let peak = pairs.iter().fold(0.0f64, |m, (h, _)| m.max(h.norm()));
                for (k, (h, r)) in pairs.iter().enumerate() {
                    let e = (h - r).norm() / h.norm().max(1e-3 * peak);
                    assert!(
                        e <= ILL_CONDITIONED,
                        "{what}, output {i}, ω = {}: {h} vs {r} ({e:e})",
                        omegas[k]
                    );
                }
            }
        };
        for &(m1, w1, z1, m2, w2, z2) in &[
            (3.0e4, 18.5, 0.1, 2.0e3, w(1.5), 0.3),
            (3.0e4, 18.5, 0.1, 20.0, w(0.05), 0.005),
            (3.0e4, 18.5, 0.1, 2.0e5, w(40.0), 2.0),
            (5.0e3, 40.0, 0.5, 2.0e3, w(0.2), 0.0),
        ] {
            let vals = [
                Some(m1),
                None,
                Some(w1),
                None,
                Some(z1),
                Some(m2),
                None,
                Some(w2),
                None,
                Some(z2),
            ];
            let inst = sprung_model(&vals).unwrap().instance().unwrap();
            let mut tp = TransferPolynomials::zero();
            assert!(sprung_transfer(&vals, &mut tp));
            assert_eq!(tp.n, 4);
            check(inst.system.state_space().unwrap(), &tp, 5, "sprung");
            // rigid cab: the front part alone
            let vals = [Some(m1), None, Some(w1), None, Some(z1)];
            let r = rigid_model(&vals).unwrap().instance().unwrap();
            let mut tp = TransferPolynomials::zero(); // builders write into zeroed polynomials
            assert!(rigid_transfer(&vals, &mut tp));
            assert_eq!(tp.n, 2);
            check(r.system.state_space().unwrap(), &tp, 2, "rigid");
        }
        // values the reader or the model refuse: no polynomials
        let mut tp = TransferPolynomials::zero();
        let bad_m1 = [
            Some(0.0),
            None,
            Some(1.0),
            None,
            Some(0.1),
            Some(1.0),
            None,
            Some(1.0),
            None,
            Some(0.1),
        ];
        assert!(!sprung_transfer(&bad_m1, &mut tp));
        assert!(!rigid_transfer(
            &[Some(1.0), None, Some(1.0), None, Some(-0.1)],
            &mut tp
        ));
    }
}
