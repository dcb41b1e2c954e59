//! Balancer bogie on a random road (Sukharev 2012, section 8.5, eqs. (8.38)–(8.50)).
//!
//! A balancer (walking-beam) bogie carries two wheels of radius r a distance ℓ apart; the frame is pinned
//! at ℓ₁ from the front wheel. Each wheel smooths the profile (its contact patch averages short waves);
//! the pivot height is the lever mix of the two smoothed profiles.

use super::{InputLayout, ModelInstance};
use crate::error::{require_positive, Error, Result};
use crate::fields::Fields;
use crate::models::worked_example::BookRow;
use crate::response::{variance_quadrature, Excitation};
use crate::spectrum::{AtSpeed, Domain, Spectrum};
use crate::system::{OutputInfo, StateSpace};
use crate::units::Dim;
use nalgebra::DMatrix;
use std::sync::Arc;

/// The book's criterion (8.50): the bogie is good enough when σ_y/σ_x ≤ 0.5.
pub const CRITERION: f64 = 0.5;

/// A balancer bogie: wheel radius r, wheel base ℓ, pivot at ℓ₁ behind the front wheel (all in metres).
///
/// # Formula
/// Road coordinate S (m), road angular frequency λ (rad/m). Front wheel profile Z₁(S), rear Z₂(S) = Z₁(S − ℓ),
/// each the road x(S) through the wheel filter (8.46); the pivot height is (8.38):
/// ```text
/// W(iλ) = 1 / (1 + 4 r iλ),        y(S) = Z₁(S)(ℓ − ℓ₁)/ℓ + Z₂(S) ℓ₁/ℓ
/// D_y = [((ℓ − ℓ₁)² + ℓ₁²) D_Z + 2 ℓ₁ (ℓ − ℓ₁) R_Z(ℓ)] / ℓ²                                (8.40)
/// ```
/// For the type-1 road (8.45) K_x = D_x e^{−α|S|} (two-sided S_x = αD_x/(π(α² + λ²))), with b = 1/(4r):
/// ```text
/// D_Z = D_x / (1 + 4αr)                                                                   (8.47)
/// R_Z(ℓ) = D_x (e^{−αℓ} − 4αr e^{−ℓ/4r}) / (1 − 16α²r²)                                    (8.48)
///        = D_x b/(b + α) · e^{−αℓ} [1 − α (e^{−(b−α)ℓ} − 1)/(b − α)]     (stable form, expm1)
///        → D_x (1 + αℓ) e^{−αℓ} / 2   at 4αr = 1 (removable singularity)
/// D_y/D_x from (8.49);  criterion (8.50): σ_y/σ_x = √(D_y/D_x) ≤ 0.5
/// ```
/// In time at speed v (m/s) the wheel filter is W(s) = 1/(1 + 4 r s / v) and the rear wheel is delayed by
/// ℓ/v; σ_y does not depend on v (checked in the tests).
///
/// # Errors
/// [`BalancerBogie::build`] rejects r ≤ 0, ℓ ≤ 0, ℓ₁ outside [0, ℓ] and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::balancer_bogie::BalancerBogie;
/// // book 8.5 example: r = 11 cm, ℓ = 60 cm, ℓ₁ = ℓ/2, road α = 0.035 1/cm, D_x = 2.25 cm²
/// let b = BalancerBogie { r: 0.11, ell: 0.60, ell1: 0.30 }.build().unwrap();
/// let c = b.closed_form(2.25e-4, 3.5).unwrap();
/// assert!((c.dy / 2.25e-4 - 0.29577).abs() < 1e-5);   // the book prints 0.28 (see the book rows)
/// assert!(!c.passes);                                 // σ_y/σ_x = 0.544 > 0.5
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BalancerBogie {
    /// r, the wheel radius, m.
    pub r: f64,
    /// ℓ, the wheel base, m.
    pub ell: f64,
    /// ℓ₁, the pivot's distance behind the front wheel, m.
    pub ell1: f64,
}

/// The closed-form results (8.47)–(8.50) for a type-1 road.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BogieClosedForm {
    /// D_Z, m²: variance of one smoothed wheel profile (8.47).
    pub dz: f64,
    /// R_Z(ℓ), m²: correlation of the two smoothed profiles (8.48).
    pub rz: f64,
    /// D_y, m²: variance of the pivot height (8.49).
    pub dy: f64,
    /// σ_y/σ_x.
    pub sigma_ratio: f64,
    /// Whether σ_y/σ_x ≤ [`CRITERION`] (8.50).
    pub passes: bool,
}

/// One point of [`sweep`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SweepPoint {
    /// Wheel radius r, m.
    pub r: f64,
    /// Wheel base ℓ, m.
    pub ell: f64,
    /// Pivot position ℓ₁, m.
    pub ell1: f64,
    /// D_y/D_x.
    pub ratio: f64,
}

/// D_Z/D_x = b/(α + b), b = 1/(4r) (8.47).
fn dz_ratio(alpha: f64, r: f64) -> f64 {
    1.0 / (1.0 + 4.0 * alpha * r)
}

impl BalancerBogie {
    /// R_Z(ℓ)/D_x of (8.48) for the type-1 road K_x = D_x e^{−α|S|} (α in 1/m), in a form without
    /// cancellation near 4αr = 1.
    ///
    /// # Formula
    /// With b = 1/(4r), δ = b − α:
    /// ```text
    /// R_Z/D_x = b/(b + α) · [e^{−αℓ} − α (e^{−bℓ} − e^{−αℓ})/δ]
    /// e^{−bℓ} − e^{−αℓ} = e^{−αℓ} expm1(−δℓ)  (δ ≥ 0)   = −e^{−bℓ} expm1(δℓ)  (δ < 0)
    /// ```
    /// and (e^{−bℓ} − e^{−αℓ})/δ → −ℓ e^{−αℓ} as δ → 0 (no 0/0 is ever formed: expm1 keeps full relative accuracy).
    pub fn rz_ratio(&self, alpha: f64) -> f64 {
        let (r, ell) = (self.r, self.ell);
        let b = 1.0 / (4.0 * r);
        let delta = b - alpha;
        let ea = (-alpha * ell).exp();
        let diff_over_delta = if delta == 0.0 {
            -ell * ea
        } else if delta > 0.0 {
            ea * (-delta * ell).exp_m1() / delta
        } else {
            -(-b * ell).exp() * (delta * ell).exp_m1() / delta
        };
        b / (b + alpha) * (ea - alpha * diff_over_delta)
    }

    /// The bogie of these fields, checked: wheel radius `r` (m), wheel base `ell` (m), pivot `ell1` (m) behind
    /// the front wheel.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        let BalancerBogie { r, ell, ell1 } = self;
        require_positive("r", r)?;
        require_positive("ell", ell)?;
        if !(ell1.is_finite() && (0.0..=ell).contains(&ell1)) {
            return Err(Error::invalid("ell1", ell1, format!("must lie in [0, ell = {ell}] m")));
        }
        Ok(BalancerBogie { r, ell, ell1 })
    }

    /// Wheel radius r, m.
    pub fn r(&self) -> f64 {
        self.r
    }
    /// Wheel base ℓ, m.
    pub fn ell(&self) -> f64 {
        self.ell
    }
    /// Pivot position ℓ₁ behind the front wheel, m.
    pub fn ell1(&self) -> f64 {
        self.ell1
    }

    /// Closed form (8.47)–(8.50) for the type-1 road K_x = D_x e^{−α|S|} (D_x in m², α in 1/m).
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Errors
    /// D_x < 0 or α ≤ 0 or non-finite.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::balancer_bogie::BalancerBogie;
    /// // at 4αr = 1 the printed (8.48) is 0/0; the limit is D_x (1 + αℓ) e^{−αℓ}/2
    /// let b = BalancerBogie { r: 1.0 / (4.0 * 3.5), ell: 0.6, ell1: 0.3 }.build().unwrap();
    /// let c = b.closed_form(1.0, 3.5).unwrap();
    /// assert!((c.rz - 3.1 * (-2.1f64).exp() / 2.0).abs() < 1e-15);
    /// ```
    pub fn closed_form(&self, dx: f64, alpha: f64) -> Result<BogieClosedForm> {
        if !(dx.is_finite() && dx >= 0.0) {
            return Err(Error::invalid("D_x", dx, "must be finite and >= 0"));
        }
        require_positive("alpha", alpha)?;
        let (l, l1) = (self.ell, self.ell1);
        let dz = dx * dz_ratio(alpha, self.r);
        let rz = dx * self.rz_ratio(alpha);
        let dy = (((l - l1).powi(2) + l1 * l1) * dz + 2.0 * l1 * (l - l1) * rz) / (l * l);
        let sigma_ratio = if dx > 0.0 { (dy / dx).sqrt() } else { 0.0 };
        Ok(BogieClosedForm {
            dz,
            rz,
            dy,
            sigma_ratio,
            passes: sigma_ratio <= CRITERION,
        })
    }

    /// The lever gains of the two wheels: ((ℓ − ℓ₁)/ℓ, ℓ₁/ℓ).
    pub fn lever(&self) -> (f64, f64) {
        ((self.ell - self.ell1) / self.ell, self.ell1 / self.ell)
    }

    /// The bogie as a 2-input system in time at speed `speed` (m/s): inputs are the road under the front and
    /// the rear wheel (`InputLayout::Track` with positions [0, ℓ], gains [1, 1]); outputs `y` (pivot height,
    /// m), `z1`, `z2` (smoothed wheel profiles, m).
    ///
    /// # Formula
    /// ```text
    /// ż_j = (v/4r)(u_j − z_j),  j = 1, 2;      y = (ℓ − ℓ₁)/ℓ · z₁ + ℓ₁/ℓ · z₂
    /// ```
    /// (each z_j = W(s) u_j with W(s) = 1/(1 + 4 r s / v)).
    ///
    /// # Errors
    /// speed ≤ 0 or non-finite.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::{balancer_bogie::BalancerBogie, InputLayout};
    /// use stochvib::system::FrequencyResponse;
    /// let m = BalancerBogie { r: 0.11, ell: 0.6, ell1: 0.3 }.build().unwrap().instance(10.0).unwrap();
    /// assert_eq!(m.layout, InputLayout::Track { positions: vec![0.0, 0.6], gains: vec![1.0, 1.0] });
    /// assert_eq!(m.system.n_inputs(), 2);
    /// ```
    pub fn instance(&self, speed: f64) -> Result<ModelInstance> {
        require_positive("speed", speed)?;
        let k = speed / (4.0 * self.r);
        let (g1, g2) = self.lever();
        let a = DMatrix::from_row_slice(2, 2, &[-k, 0.0, 0.0, -k]);
        let b = DMatrix::from_row_slice(2, 2, &[k, 0.0, 0.0, k]);
        let c = DMatrix::from_row_slice(3, 2, &[g1, g2, 1.0, 0.0, 0.0, 1.0]);
        let ss = StateSpace::new(
            a,
            b,
            c,
            None,
            None,
            vec![
                OutputInfo::new("y", "m"),
                OutputInfo::new("z1", "m"),
                OutputInfo::new("z2", "m"),
            ],
        )?;
        Ok(ModelInstance {
            system: Arc::new(ss),
            layout: InputLayout::Track {
                positions: vec![0.0, self.ell],
                gains: vec![1.0, 1.0],
            },
            description: format!(
                "balancer bogie (Sukharev 8.5, eqs. (8.38), (8.46)): r = {} m, ell = {} m, ell1 = {} m, wheel filter \
                 in time at v = {speed} m/s",
                self.r, self.ell, self.ell1
            ),
        })
    }

    /// D_y/D_x for any spatial road spectrum (rad/m), by the general route: the 2-input system at speed
    /// `speed`, the road turned into time ([`AtSpeed`]), the rear wheel delayed by ℓ/v, and adaptive
    /// quadrature of S_y ([`variance_quadrature`]). Returns (D_y, D_x) in m².
    ///
    /// # Formula
    /// ```text
    /// D_y = ∫ |g₁ W(iω) + g₂ W(iω) e^{−iωℓ/v}|² S_x(ω/v)/v dω,      D_x = ∫ S_x(Ω) dΩ
    /// ```
    ///
    /// # Errors
    /// A road that is not spatial, speed ≤ 0, a divergent or non-converging integral, a road whose
    /// variance is infinite.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::balancer_bogie::BalancerBogie;
    /// use stochvib::spectrum::{Exponential, Domain};
    /// use std::sync::Arc;
    /// let b = BalancerBogie { r: 0.15, ell: 0.6, ell1: 0.3 }.build().unwrap();
    /// let road = Arc::new(Exponential::new(2.25e-4, 3.5, Domain::Spatial).unwrap());
    /// let (dy, dx) = b.variance_numerical(road, 5.0).unwrap();
    /// assert!((dy / dx - b.closed_form(dx, 3.5).unwrap().dy / dx).abs() < 1e-8);
    /// ```
    pub fn variance_numerical(&self, road: Arc<dyn Spectrum>, speed: f64) -> Result<(f64, f64)> {
        if road.domain() != Domain::Spatial {
            return Err(Error::invalid(
                "road",
                road.describe(),
                "the bogie is driven by a spatial road spectrum (rad/m)",
            ));
        }
        let dx = road.variance()?;
        let inst = self.instance(speed)?;
        let exc = Excitation::track(
            Arc::new(AtSpeed::new(road, speed)?),
            vec![0.0, self.ell / speed],
            vec![1.0, 1.0],
            0.0,
        )?;
        let q = variance_quadrature(inst.system.as_ref(), &exc, 0)?;
        Ok((q.value, dx))
    }
}

/// D_y/D_x over a grid of wheel radii `r` (m), wheel bases `ell` (m) and pivot fractions `ell1_fraction`
/// (ℓ₁/ℓ ∈ [0, 1]) for the type-1 road with α (1/m): the closed form (8.49), one point per combination in
/// the order r (outer), ℓ, ℓ₁ (inner).
///
/// # Formula
/// D_y/D_x = [((ℓ − ℓ₁)² + ℓ₁²)/(1 + 4αr) + 2ℓ₁(ℓ − ℓ₁) R_Z(ℓ)/D_x]/ℓ², R_Z in the stable form of
/// [`BalancerBogie::rz_ratio`].
///
/// # Errors
/// Any invalid r, ℓ, fraction or α.
///
/// # Examples
/// ```
/// use stochvib::models::balancer_bogie::sweep;
/// let s = sweep(3.5, &[0.05, 0.11, 0.15], &[0.6], &[0.5]).unwrap();
/// assert_eq!(s.len(), 3);
/// // larger wheels smooth more (book 8.5, text after (8.50))
/// assert!(s[0].ratio > s[1].ratio && s[1].ratio > s[2].ratio);
/// ```
pub fn sweep(alpha: f64, r: &[f64], ell: &[f64], ell1_fraction: &[f64]) -> Result<Vec<SweepPoint>> {
    let mut out = Vec::with_capacity(r.len() * ell.len() * ell1_fraction.len());
    for &ri in r {
        for &li in ell {
            for &fi in ell1_fraction {
                if !(fi.is_finite() && (0.0..=1.0).contains(&fi)) {
                    return Err(Error::invalid("ell1_fraction", fi, "must lie in [0, 1]"));
                }
                let b = BalancerBogie {
                    r: ri,
                    ell: li,
                    ell1: fi * li,
                }
                .build()?;
                let c = b.closed_form(1.0, alpha)?;
                out.push(SweepPoint {
                    r: ri,
                    ell: li,
                    ell1: fi * li,
                    ratio: c.dy,
                });
            }
        }
    }
    Ok(out)
}

/// Reads the `[model]` table of a `balancer-bogie` scenario: `r`, `ell`, `ell1` (lengths). The wheel
/// filter in time depends on the speed, which comes from the scenario's `[input] speed` (`speed`), so the
/// two can never disagree.
///
/// # Errors
/// Missing or invalid keys, named with the file; a missing input speed.
pub fn from_fields(f: &Fields, speed: Option<f64>) -> Result<ModelInstance> {
    let r = f.quantity("r", Dim::LENGTH)?;
    let ell = f.quantity("ell", Dim::LENGTH)?;
    let ell1 = f.quantity("ell1", Dim::LENGTH)?;
    let b = BalancerBogie { r, ell, ell1 }
        .build()
        .map_err(|e| f.wrap_param(e, "r"))?;
    let speed = speed.ok_or_else(|| {
        f.error(
            "kind",
            "balancer-bogie",
            "the bogie is driven along the road: give [input] speed",
        )
    })?;
    b.instance(speed).map_err(|e| f.wrap("kind", e))
}

/// The book's worked example (Sukharev (2012) 8.5, the numerical example after (8.50)): r = 11 and 15 cm,
/// ℓ = 60 cm, ℓ₁ = ℓ/2, α = 0.035 1/cm, D_x = 2.25 cm²; the book prints D_y/D_x = 0.28 and 0.24.
pub fn book_rows() -> Vec<BookRow> {
    let example = "Sukharev (2012) 8.5, eq. (8.49) worked example (balancer bogie)";
    let (dx, alpha) = (2.25e-4, 3.5);
    let mut rows = Vec::new();
    for (r, printed) in [(0.11, 0.28), (0.15, 0.24)] {
        let c = BalancerBogie {
            r,
            ell: 0.60,
            ell1: 0.30,
        }
        .build()
        .and_then(|b| b.closed_form(dx, alpha));
        let computed = c.as_ref().ok().map(|c| c.dy / dx);
        rows.push(BookRow {
            example: example.into(),
            quantity: format!("D_y/D_x at r = {} cm", r * 100.0),
            unit: "1".into(),
            printed: Some(printed),
            computed,
            explanation: "(8.49) with the printed α = 0.035 1/cm gives this; no convention factor explains the print, \
                          which is reproduced by α ≈ 0.038 1/cm (unprinted/rounded α or arithmetic slip)"
                .into(),
        });
        if let Ok(c) = c {
            rows.push(BookRow {
                example: example.into(),
                quantity: format!("sigma_y/sigma_x at r = {} cm (criterion <= 0.5)", r * 100.0),
                unit: "1".into(),
                printed: None,
                computed: Some(c.sigma_ratio),
                explanation: format!(
                    "not printed; the book calls the bogie adequate but the criterion (8.50) {}",
                    if c.passes { "holds" } else { "fails" }
                ),
            });
        }
    }
    rows
}
