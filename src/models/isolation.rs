//! Vibration isolation: single isolator and two-stage isolator (Sukharev (2012) 7.1, 7.2).
//!
//! # Formula
//! **Single isolator** (7.1)–(7.10): a mass m on a spring c in parallel with a viscous damper b, excited by a
//! force F₀ e^{ikt} on the mass (or, equivalently, by a base displacement u₀ e^{ikt} under the isolator,
//! the book's remark after (7.11)). With ω₀ = √(c/m), ζ = b/(2√(cm)) (the book's h = b/(2m), ζ = h/ω₀) and r = k/ω₀:
//! ```text
//! m ÿ + b ẏ + c y = F₀ e^{ikt}   ⇒   Y = F₀ / (c − m k² + i k b)
//! Q = c y + b ẏ (force on the foundation)   ⇒   Q/F₀ = (c + i k b)/(c − m k² + i k b)
//! η = |Q/F₀| = √[(1 + (2ζr)²) / ((1 − r²)² + (2ζr)²)]                                  (7.10)
//! ```
//! Base excitation: m z̈ + b(ż − u̇) + c(z − u) = 0 gives Z/U = (c + ikb)/(c − mk² + ikb), the same η.
//! η = 1 at r = √2 for every ζ, η < 1 for r > √2 (7.11). (The print of (7.1) has ÿ for ẏ and (7.2)
//! "ÿ = 2hẏ" for "ÿ + 2hẏ"; the formula above is the corrected one.)
//!
//! **Two-stage isolator** (7.12)–(7.17): the source m₁ on the stage c₁ (damper b₁) on an intermediate
//! mass m₂ on the stage c₂ (damper b₂) on the foundation; force F₀ e^{ikt} on m₁. With the complex
//! stiffnesses κ_j = c_j + i k b_j:
//! ```text
//! (κ₁ − m₁k²) Y₁ − κ₁ Y₂ = F₀,     −κ₁ Y₁ + (κ₁ + κ₂ − m₂k²) Y₂ = 0
//! Δ = (κ₁ − m₁k²)(κ₁ + κ₂ − m₂k²) − κ₁²,      Y₂ = κ₁ F₀ / Δ,      Q = κ₂ Y₂
//! η = |Q/F₀| = |κ₁ κ₂ / Δ|                                                   (exact, derived here)
//! ```
//! Undamped (b₁ = b₂ = 0), Δ expands to c₁c₂ − [c₁m₂ + (c₁ + c₂)m₁]k² + m₁m₂k⁴, and Q/F₀ equals the book's
//! (7.16) η* = c₁c₂ / (c₁c₂ − [c₁m₂ + (c₁+c₂)m₁]k² + m₁m₂k⁴) exactly. Where they differ: (i) the book's η*
//! is a signed ratio (negative between the two natural frequencies), the transmissibility is |η*|;
//! (ii) the book has no damping, so η* is infinite at the two natural frequencies (roots of
//! m₁m₂k⁴ − [c₁m₂ + (c₁+c₂)m₁]k² + c₁c₂ = 0) where the exact damped η stays finite, and for k above both
//! natural frequencies the damped η decays like |κ₁κ₂|/(m₁m₂k⁴) ~ b₁b₂/(m₁m₂k²) instead of (7.17)
//! c₁c₂/(m₁m₂k⁴). Base excitation under c₂ with the displacement of m₁ as output gives the same ratio
//! κ₁κ₂/Δ (reciprocity).
//!
//! # Examples
//! ```
//! use stochvib::models::isolation::{transmissibility, SingleIsolator};
//! assert!((transmissibility(2f64.sqrt(), 0.3) - 1.0).abs() < 1e-12);
//! let iso = SingleIsolator { mass: 100.0, stiffness: 1.0e4, damping: 200.0 }.build().unwrap();
//! assert!((iso.natural_frequency() - 10.0).abs() < 1e-12);
//! ```

use crate::error::{require_non_negative, require_positive, Result};
use crate::fields::Fields;
use crate::models::worked_example::BookRow;
use crate::models::{InputLayout, ModelInstance};
use crate::system::{Attach, Drive, Element, MassSpringDamper, Mdof, Quantity};
use crate::units::Dim;
use nalgebra::Complex;
use std::sync::Arc;

/// Transmissibility of a single isolator, η(r, ζ) (book (7.10) and (7.42)).
///
/// # Formula
/// η = √[(1 + (2ζr)²) / ((1 − r²)² + (2ζr)²)], r = k/ω₀ (forcing over natural frequency), ζ damping ratio.
/// Returns +∞ at r = 1, ζ = 0.
///
/// # Examples
/// ```
/// use stochvib::models::isolation::transmissibility;
/// assert_eq!(transmissibility(0.0, 0.1), 1.0);
/// assert!((transmissibility(3.0, 0.0) - 1.0 / 8.0).abs() < 1e-15);
/// ```
pub fn transmissibility(r: f64, zeta: f64) -> f64 {
    let d = 2.0 * zeta * r;
    ((1.0 + d * d) / ((1.0 - r * r).powi(2) + d * d)).sqrt()
}

/// A mass on one spring–damper isolator (book 7.1).
///
/// # Formula
/// See the module docs: ω₀ = √(c/m) (rad/s), ζ = b/(2√(cm)), η(k) = [`transmissibility`](k/ω₀, ζ).
///
/// # Errors
/// [`SingleIsolator::build`] rejects m ≤ 0, c ≤ 0, b < 0 and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::isolation::SingleIsolator;
/// let iso = SingleIsolator { mass: 100.0, stiffness: 1.0e4, damping: 200.0 }.build().unwrap(); // ω₀ = 10 rad/s, ζ = 0.1
/// assert!((iso.damping_ratio() - 0.1).abs() < 1e-15);
/// assert!((iso.transmissibility(10.0 * 2f64.sqrt()) - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SingleIsolator {
    /// m, kg.
    pub mass: f64,
    /// c, N/m.
    pub stiffness: f64,
    /// b, N s/m.
    pub damping: f64,
}

impl SingleIsolator {
    /// The isolator of these fields, checked: m (kg), c (N/m), b (N s/m).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        let SingleIsolator {
            mass,
            stiffness,
            damping,
        } = self;
        Ok(SingleIsolator {
            mass: require_positive("mass", mass)?,
            stiffness: require_positive("stiffness", stiffness)?,
            damping: require_non_negative("damping", damping)?,
        })
    }

    /// ω₀ = √(c/m), rad/s.
    pub fn natural_frequency(&self) -> f64 {
        (self.stiffness / self.mass).sqrt()
    }

    /// ζ = b/(2√(cm)).
    pub fn damping_ratio(&self) -> f64 {
        self.damping / (2.0 * (self.stiffness * self.mass).sqrt())
    }

    /// η at forcing frequency k (rad/s).
    pub fn transmissibility(&self, k: f64) -> f64 {
        transmissibility(k / self.natural_frequency(), self.damping_ratio())
    }

    /// Base-excited model (input 0: base displacement u, m) with outputs `x` (m), `x_acc` (m/s²),
    /// `travel` (x − u, m) and `force` (c(x − u) + b(ẋ − u̇), N, on the base).
    ///
    /// # Errors
    /// None for a validated isolator (the `Result` is the [`Mdof`] constructor's).
    pub fn mdof_base(&self) -> Result<Mdof> {
        MassSpringDamper {
            mass: self.mass,
            stiffness: self.stiffness,
            damping: self.damping,
            drive: Drive::Base,
        }
        .build()?
        .with_output("x", Quantity::Displacement(vec![1.0]))?
        .with_output("x_acc", Quantity::Acceleration(vec![1.0]))?
        .with_output("travel", Quantity::Deflection(0))?
        .with_output("force", Quantity::ElementForce(0))
    }

    /// Force-excited model (input 0: force F on the mass, N, foundation fixed) with output `force`
    /// (Q = c x + b ẋ, N, transmitted to the foundation): |H| = η, the book's definition Q/F₀.
    ///
    /// # Errors
    /// As [`SingleIsolator::mdof_base`].
    pub fn mdof_force(&self) -> Result<Mdof> {
        MassSpringDamper {
            mass: self.mass,
            stiffness: self.stiffness,
            damping: self.damping,
            drive: Drive::Force,
        }
        .build()?
        .with_output("force", Quantity::ElementForce(0))
    }

    /// The base-excited model with a single random base displacement ([`InputLayout::Single`]).
    ///
    /// # Errors
    /// As [`SingleIsolator::mdof_base`].
    pub fn instance(&self) -> Result<ModelInstance> {
        Ok(ModelInstance {
            system: Arc::new(self.mdof_base()?),
            layout: InputLayout::Single,
            description: format!(
                "single isolator (Sukharev 7.1): m = {} kg, c = {} N/m, b = {} N s/m, base-excited",
                self.mass, self.stiffness, self.damping
            ),
        })
    }
}

/// Two-stage isolator (book 7.2, (7.12)–(7.17)), with optional damping in each stage.
///
/// # Formula
/// See the module docs: η(k) = |κ₁κ₂/Δ|, κ_j = c_j + ikb_j,
/// Δ = (κ₁ − m₁k²)(κ₁ + κ₂ − m₂k²) − κ₁²; undamped natural frequencies from
/// m₁m₂ω⁴ − [c₁m₂ + (c₁+c₂)m₁]ω² + c₁c₂ = 0.
///
/// # Errors
/// [`TwoStageIsolator::build`] rejects non-positive masses and stiffnesses, negative damping, non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::isolation::TwoStageIsolator;
/// let t = TwoStageIsolator { mass_1: 100.0, stiffness_1: 1e4, damping_1: 0.0, mass_2: 50.0, stiffness_2: 2e4, damping_2: 0.0 }.build().unwrap();
/// // undamped: the exact formula is |(7.16)|
/// let k = 40.0;
/// assert!((t.transmissibility(k) - t.book_7_16(k).abs()).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TwoStageIsolator {
    /// m₁, kg (the source / protected object, on top).
    pub mass_1: f64,
    /// c₁, N/m (upper stage, between m₁ and m₂).
    pub stiffness_1: f64,
    /// b₁, N s/m.
    pub damping_1: f64,
    /// m₂, kg (intermediate mass).
    pub mass_2: f64,
    /// c₂, N/m (lower stage, between m₂ and the foundation).
    pub stiffness_2: f64,
    /// b₂, N s/m.
    pub damping_2: f64,
}

impl TwoStageIsolator {
    /// The isolator of these fields, checked: m₁, c₁, b₁, m₂, c₂, b₂ (kg, N/m, N s/m) as named fields
    /// instead of six bare numbers of different meaning.
    ///
    /// # Errors
    /// See the type's `# Errors`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::isolation::TwoStageIsolator;
    /// let iso = TwoStageIsolator {
    ///     mass_1: 100.0,
    ///     stiffness_1: 1e5,
    ///     damping_1: 500.0,
    ///     mass_2: 20.0,
    ///     stiffness_2: 4e5,
    ///     damping_2: 0.0,
    /// }
    /// .build()
    /// .unwrap();
    /// // both stages pass a slow load one to one
    /// assert!((iso.transmissibility(1e-6) - 1.0).abs() < 1e-9);
    /// ```
    pub fn build(self) -> Result<Self> {
        let TwoStageIsolator {
            mass_1,
            stiffness_1,
            damping_1,
            mass_2,
            stiffness_2,
            damping_2,
        } = self;
        Ok(TwoStageIsolator {
            mass_1: require_positive("mass_1", mass_1)?,
            stiffness_1: require_positive("stiffness_1", stiffness_1)?,
            damping_1: require_non_negative("damping_1", damping_1)?,
            mass_2: require_positive("mass_2", mass_2)?,
            stiffness_2: require_positive("stiffness_2", stiffness_2)?,
            damping_2: require_non_negative("damping_2", damping_2)?,
        })
    }

    /// Complex ratio Q/F₀ = κ₁κ₂/Δ at k (rad/s).
    pub fn ratio(&self, k: f64) -> Complex<f64> {
        let k1 = Complex::new(self.stiffness_1, k * self.damping_1);
        let k2 = Complex::new(self.stiffness_2, k * self.damping_2);
        let m1 = self.mass_1 * k * k;
        let m2 = self.mass_2 * k * k;
        let delta = (k1 - m1) * (k1 + k2 - m2) - k1 * k1;
        k1 * k2 / delta
    }

    /// Exact transmissibility η(k) = |κ₁κ₂/Δ| (+∞ at an undamped natural frequency).
    pub fn transmissibility(&self, k: f64) -> f64 {
        self.ratio(k).norm()
    }

    /// The book's (7.16) as printed (signed, damping ignored):
    /// η* = c₁c₂ / (c₁c₂ − [c₁m₂ + (c₁+c₂)m₁]k² + m₁m₂k⁴).
    pub fn book_7_16(&self, k: f64) -> f64 {
        let (c1, c2, m1, m2) = (self.stiffness_1, self.stiffness_2, self.mass_1, self.mass_2);
        let k2 = k * k;
        c1 * c2 / (c1 * c2 - (c1 * m2 + (c1 + c2) * m1) * k2 + m1 * m2 * k2 * k2)
    }

    /// The book's high-frequency approximation (7.17): (c₁/(m₁k²))·(c₂/(m₂k²)).
    pub fn book_7_17(&self, k: f64) -> f64 {
        self.stiffness_1 / (self.mass_1 * k * k) * self.stiffness_2 / (self.mass_2 * k * k)
    }

    /// Undamped natural frequencies (rad/s, ascending): roots of m₁m₂ω⁴ − [c₁m₂ + (c₁+c₂)m₁]ω² + c₁c₂ = 0.
    ///
    /// # Formula
    /// ω² = (B ∓ √(B² − 4m₁m₂c₁c₂))/(2m₁m₂), B = c₁m₂ + (c₁+c₂)m₁; with X = c₁m₂, Y = c₂m₁, Z = c₁m₁ the
    /// discriminant is (X − Y)² + Z² + 2Z(X + Y) > 0, so the roots are real and distinct. The smaller root
    /// is taken from Vieta's product c₁c₂/(m₁m₂) to avoid cancellation.
    pub fn natural_frequencies(&self) -> [f64; 2] {
        let (c1, c2, m1, m2) = (self.stiffness_1, self.stiffness_2, self.mass_1, self.mass_2);
        let a = m1 * m2;
        let b = c1 * m2 + (c1 + c2) * m1;
        let c = c1 * c2;
        let disc = (b * b - 4.0 * a * c).max(0.0).sqrt();
        let hi = (b + disc) / (2.0 * a);
        let lo = c / (a * hi); // Vieta: product of roots c/a, no cancellation
        [lo.sqrt(), hi.sqrt()]
    }

    fn elements(&self, lower_to: Attach) -> Vec<Element> {
        vec![
            Element {
                name: "upper".into(),
                point: vec![1.0, 0.0],
                to: Attach::Point(vec![0.0, 1.0]),
                stiffness: self.stiffness_1,
                damping: self.damping_1,
            },
            Element {
                name: "lower".into(),
                point: vec![0.0, 1.0],
                to: lower_to,
                stiffness: self.stiffness_2,
                damping: self.damping_2,
            },
        ]
    }

    /// Force-excited model (input 0: force on m₁, N) with output `force` (force transmitted by the lower
    /// stage to the foundation, N): H = Q/F₀.
    ///
    /// # Errors
    /// None for a validated isolator (the `Result` is the [`Mdof`] constructor's).
    pub fn mdof_force(&self) -> Result<Mdof> {
        let coords = [("y1", "m"), ("y2", "m")];
        Mdof::from_elements(
            &coords,
            &[self.mass_1, self.mass_2],
            self.elements(Attach::Ground),
            0,
            &[vec![1.0, 0.0]],
        )?
        .with_output("force", Quantity::ElementForce(1))
    }

    /// Base-excited model (input 0: displacement u of the foundation under c₂, m) with outputs `y1`, `y1_acc`,
    /// `y2`, `travel_upper` (y₁ − y₂), `travel_lower` (y₂ − u), all SI.
    ///
    /// # Errors
    /// As [`TwoStageIsolator::mdof_force`].
    pub fn mdof_base(&self) -> Result<Mdof> {
        let coords = [("y1", "m"), ("y2", "m")];
        Mdof::from_elements(
            &coords,
            &[self.mass_1, self.mass_2],
            self.elements(Attach::Base(0)),
            1,
            &[],
        )?
        .with_output("y1", Quantity::Displacement(vec![1.0, 0.0]))?
        .with_output("y1_acc", Quantity::Acceleration(vec![1.0, 0.0]))?
        .with_output("y2", Quantity::Displacement(vec![0.0, 1.0]))?
        .with_output("travel_upper", Quantity::Deflection(0))?
        .with_output("travel_lower", Quantity::Deflection(1))
    }

    /// The base-excited model with a single random base displacement ([`InputLayout::Single`]).
    ///
    /// # Errors
    /// As [`TwoStageIsolator::mdof_force`].
    pub fn instance(&self) -> Result<ModelInstance> {
        Ok(ModelInstance {
            system: Arc::new(self.mdof_base()?),
            layout: InputLayout::Single,
            description: format!(
                "two-stage isolator (Sukharev 7.2): m1 = {} kg, c1 = {} N/m, b1 = {} N s/m, m2 = {} kg, c2 = {} N/m, \
                 b2 = {} N s/m, base-excited under c2",
                self.mass_1, self.stiffness_1, self.damping_1, self.mass_2, self.stiffness_2, self.damping_2
            ),
        })
    }
}

/// Reads a `kind = "isolator-single"` `[model]` table: `mass`, `stiffness`, and either `damping` (N s/m)
/// or `damping_ratio` (ζ, plain number); neither means undamped.
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming the key for a missing or invalid value, or when both damping keys are given.
pub fn from_fields_single(f: &Fields) -> Result<ModelInstance> {
    let m = f.quantity("mass", Dim::MASS)?;
    let c = f.quantity("stiffness", Dim::STIFFNESS)?;
    let b = match (f.opt_quantity("damping", Dim::DAMPING)?, f.get("damping_ratio")) {
        (Some(_), Some(v)) => {
            return Err(f.error("damping_ratio", v, "give either `damping` or `damping_ratio`, not both"))
        }
        (Some(b), None) => b,
        (None, Some(_)) => {
            let z = f.number("damping_ratio")?;
            if !z.is_finite() || z < 0.0 {
                return Err(f.error("damping_ratio", z, "must be >= 0"));
            }
            2.0 * z * (c * m).abs().sqrt()
        }
        (None, None) => 0.0,
    };
    SingleIsolator {
        mass: m,
        stiffness: c,
        damping: b,
    }
    .build()
    .map_err(|e| f.wrap_param(e, "kind"))?
    .instance()
}

/// Reads a `kind = "isolator-two-stage"` `[model]` table: `mass_1`, `stiffness_1`, `damping_1` (optional,
/// default 0), `mass_2`, `stiffness_2`, `damping_2` (optional, default 0).
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming the key for a missing or invalid value.
pub fn from_fields_two_stage(f: &Fields) -> Result<ModelInstance> {
    let m1 = f.quantity("mass_1", Dim::MASS)?;
    let c1 = f.quantity("stiffness_1", Dim::STIFFNESS)?;
    let b1 = f.opt_quantity("damping_1", Dim::DAMPING)?.unwrap_or(0.0);
    let m2 = f.quantity("mass_2", Dim::MASS)?;
    let c2 = f.quantity("stiffness_2", Dim::STIFFNESS)?;
    let b2 = f.opt_quantity("damping_2", Dim::DAMPING)?.unwrap_or(0.0);
    TwoStageIsolator {
        mass_1: m1,
        stiffness_1: c1,
        damping_1: b1,
        mass_2: m2,
        stiffness_2: c2,
        damping_2: b2,
    }
    .build()
    .map_err(|e| f.wrap_param(e, "kind"))?
    .instance()
}

/// Frequency ratio r > 0 at which η(r, ζ) = 1, found by bisection on [1, 10] (η > 1 just above r = 1 and
/// η < 1 at r = 10 for ζ ≤ 1). The book's (7.11) says √2 for every ζ.
fn unit_crossing(zeta: f64) -> f64 {
    let (mut lo, mut hi) = (1.0 + 1e-9, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if transmissibility(mid, zeta) > 1.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Book rows of 7.1–7.2. The sections print no worked example; the one printed number is the ratio √2
/// of (7.11) above which η < 1 (for any damping), checked by solving η(r, ζ) = 1 numerically.
pub fn book_rows() -> Vec<BookRow> {
    [0.0, 0.2, 0.5]
        .iter()
        .map(|&z| BookRow {
            example: "Sukharev (2012) 7.1, (7.11) (single isolator)".into(),
            quantity: format!("k/omega where eta = 1 (zeta = {z})"),
            unit: "1".into(),
            printed: Some(2f64.sqrt()),
            computed: Some(unit_crossing(z)),
            explanation: "bisection on the closed-form transmissibility (7.10)".into(),
        })
        .collect()
}
