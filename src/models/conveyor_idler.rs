//! Conveyor idler under a random lump load (Sukharev 2012, section 8.6, eqs. (8.51)–(8.63), Example 8.1).
//!
//! An idler (roller support) of mass m on a support of stiffness c and damping b carries the belt load
//! F(t) = M_F + F̊(t), whose fluctuation has the type-1 correlation K_F = D_F e^{−α|τ|} (lumps of material).

use super::{InputLayout, ModelInstance};
use crate::error::{require_non_negative, require_positive, Result};
use crate::fields::Fields;
use crate::models::worked_example::BookRow;
use crate::system::{Drive, MassSpringDamper, Quantity};
use crate::units::Dim;
use std::f64::consts::PI;
use std::sync::Arc;

/// The white-noise approximation (8.62) is flagged as poor when the exact/approximate variance ratio
/// differs from 1 by more than this (10 %).
pub const APPROXIMATION_TOLERANCE: f64 = 0.10;

/// A conveyor idler: mass m (kg), support stiffness c (N/m), support damping b (N s/m).
///
/// # Formula
/// ```text
/// m ÿ + b ẏ + c y = F(t)                                                    (8.54)
/// ω₀ = √(c/m),   β = ζ = b/(2mω₀)   (the book's β is the damping ratio)
/// H(iω) = y/F = 1/(m(ω₀² − ω² + 2iζω₀ω))                                     (8.58)/m
/// ```
/// Load (8.51)–(8.53): K_F = D_F e^{−α|τ|}, two-sided S_F = αD_F/(π(α² + ω²)); normalised f = F/m with
/// D_x = D_F/m², S_x = αD_x/(π(α² + ω²)). Results ([`IdlerResult`]):
/// ```text
/// M_y = M_F / c                                                              (8.59)
/// σ_y² (white noise, (8.62)) = π S_x(ω₀) / (2ζω₀³)
/// σ_y² (exact)  = D_x (α + 2ζω₀) / (2ζω₀³ (ω₀² + α² + 2αζω₀))                 (I₃ table integral)
/// σ_ẏ² (exact)  = D_x α / (2ζω₀ (ω₀² + α² + 2αζω₀))
/// exact / white = (α + 2ζω₀)(α² + ω₀²) / (α (ω₀² + α² + 2αζω₀))  ≈ 1 + 2ζω₀/α  for α ≪ ω₀
/// a* = M_y + 3σ_y                                                            (8.63)
/// ```
/// The white-noise approximation needs S_x flat across the resonance band, i.e. α ≫ 2ζω₀; it is flagged
/// poor when the ratio differs from 1 by more than [`APPROXIMATION_TOLERANCE`].
///
/// # Errors
/// [`ConveyorIdler::build`] rejects m ≤ 0, c ≤ 0, b ≤ 0 (the approximation and the variance need damping)
/// and non-finite values.
///
/// # Examples
/// ```
/// use stochvib::models::conveyor_idler::{ConveyorIdler, LumpLoad};
/// // Example 8.1: m = 100 kg, c = 70 kN/m, β = 0.2; M_F = 10 kN, σ_F = 2 kN, α = 0.5 1/s
/// let idler = ConveyorIdler { m: 100.0, c: 7.0e4, b: 0.0 }.with_damping_ratio(0.2).unwrap();
/// let r = idler.analyse(&LumpLoad { mean: 1.0e4, variance: 4.0e6, alpha: 0.5 }.build().unwrap());
/// assert!((r.sigma_exact - 0.029124).abs() < 1e-6);
/// assert!(r.approximation_poor);        // α = 0.5 ≪ 2ζω₀ = 10.6
/// assert!((r.variance_ratio - 22.0).abs() < 0.1);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConveyorIdler {
    /// m, the idler's mass, kg.
    pub m: f64,
    /// c, the support's stiffness, N/m.
    pub c: f64,
    /// b, the support's damping, N s/m.
    pub b: f64,
}

/// The lump load: mean M_F (N), variance D_F (N²), correlation decay α (1/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LumpLoad {
    /// M_F, N.
    pub mean: f64,
    /// D_F, N².
    pub variance: f64,
    /// α, 1/s.
    pub alpha: f64,
}

impl LumpLoad {
    /// The load of these fields, checked: K_F = D_F e^{−α|τ|} with mean M_F (N), D_F (N²), α (1/s).
    ///
    /// # Errors
    /// Non-finite mean, D_F < 0, α ≤ 0.
    pub fn build(self) -> Result<Self> {
        let LumpLoad { mean, variance, alpha } = self;
        crate::error::require_finite("mean", mean)?;
        Ok(LumpLoad {
            mean,
            variance: require_non_negative("variance", variance)?,
            alpha: require_positive("alpha", alpha)?,
        })
    }
}

/// The statistics of the idler displacement, exact and by the book's white-noise approximation.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct IdlerResult {
    /// ω₀ = √(c/m), rad/s.
    pub omega0: f64,
    /// ζ (the book's β).
    pub zeta: f64,
    /// S_x(ω₀), two-sided density of f = F/m at ω₀, m²/s³.
    pub s_x_omega0: f64,
    /// M_y = M_F/c, m.
    pub mean_y: f64,
    /// σ_y exact, m.
    pub sigma_exact: f64,
    /// σ_y by the white-noise approximation (8.62), m.
    pub sigma_white_noise: f64,
    /// σ_ẏ exact, m/s.
    pub sigma_velocity_exact: f64,
    /// σ_y²(exact) / σ_y²(8.62).
    pub variance_ratio: f64,
    /// a* = M_y + 3σ_y with the exact σ_y, m.
    pub a_star_exact: f64,
    /// a* = M_y + 3σ_y with the white-noise σ_y, m.
    pub a_star_white_noise: f64,
    /// Whether |ratio − 1| > [`APPROXIMATION_TOLERANCE`].
    pub approximation_poor: bool,
    /// Why the approximation is poor (None when it is adequate).
    pub warning: Option<String>,
}

impl ConveyorIdler {
    /// The idler of these fields, checked: m (kg), c (N/m), b (N s/m).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    pub fn build(self) -> Result<Self> {
        Ok(ConveyorIdler {
            m: require_positive("m", self.m)?,
            c: require_positive("c", self.c)?,
            b: require_positive("b", self.b)?,
        })
    }

    /// The idler of these fields with the damping set from the damping ratio ζ (the book's β):
    /// b = 2ζ√(cm) replaces `b`; checked.
    ///
    /// # Errors
    /// As [`ConveyorIdler::build`]; ζ ≤ 0.
    pub fn with_damping_ratio(self, zeta: f64) -> Result<Self> {
        let (m, c) = (self.m, self.c);
        require_positive("m", m)?;
        require_positive("c", c)?;
        require_positive("zeta", zeta)?;
        ConveyorIdler {
            b: 2.0 * zeta * (c * m).sqrt(),
            ..self
        }
        .build()
    }

    /// ω₀ = √(c/m), rad/s.
    pub fn omega0(&self) -> f64 {
        (self.c / self.m).sqrt()
    }
    /// ζ = b/(2√(cm)).
    pub fn zeta(&self) -> f64 {
        self.b / (2.0 * (self.c * self.m).sqrt())
    }

    /// Exact and approximate statistics under `load` (see the type's `# Formula`).
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::conveyor_idler::{ConveyorIdler, LumpLoad};
    /// // a fast-varying load (α = 500 1/s ≫ 2ζω₀): the approximation is adequate
    /// let idler = ConveyorIdler { m: 100.0, c: 7.0e4, b: 0.0 }.with_damping_ratio(0.2).unwrap();
    /// let r = idler.analyse(&LumpLoad { mean: 0.0, variance: 4.0e6, alpha: 500.0 }.build().unwrap());
    /// assert!(!r.approximation_poor && r.warning.is_none());
    /// ```
    pub fn analyse(&self, load: &LumpLoad) -> IdlerResult {
        let (w0, z, a) = (self.omega0(), self.zeta(), load.alpha);
        let dx = load.variance / (self.m * self.m);
        let s_x_omega0 = a * dx / (PI * (a * a + w0 * w0));
        let var_white = PI * s_x_omega0 / (2.0 * z * w0.powi(3));
        let q = w0 * w0 + a * a + 2.0 * a * z * w0;
        let var_exact = dx * (a + 2.0 * z * w0) / (2.0 * z * w0.powi(3) * q);
        let var_vel = dx * a / (2.0 * z * w0 * q);
        let variance_ratio = (a + 2.0 * z * w0) * (a * a + w0 * w0) / (a * q);
        let mean_y = load.mean / self.c;
        let approximation_poor = (variance_ratio - 1.0).abs() > APPROXIMATION_TOLERANCE;
        let warning = approximation_poor.then(|| {
            if a < 2.0 * z * w0 {
                format!(
                    "white-noise approximation (8.62) invalid: exact/approx variance = {variance_ratio:.3}; the load \
                     spectrum is not flat around ω₀ = {w0:.4} rad/s: its correlation decay α = {a} 1/s is small \
                     against the resonance half-width 2ζω₀ = {:.4} rad/s, so the load power lies far below ω₀ and \
                     the response is quasi-static (σ_y → σ_F/c)",
                    2.0 * z * w0
                )
            } else {
                format!(
                    "white-noise approximation (8.62) poor: exact/approx variance = {variance_ratio:.3}; the load \
                     spectrum varies across the resonance band (α = {a} 1/s is not ≫ 2ζω₀ = {:.4} rad/s)",
                    2.0 * z * w0
                )
            }
        });
        IdlerResult {
            omega0: w0,
            zeta: z,
            s_x_omega0,
            mean_y,
            sigma_exact: var_exact.sqrt(),
            sigma_white_noise: var_white.sqrt(),
            sigma_velocity_exact: var_vel.sqrt(),
            variance_ratio,
            a_star_exact: mean_y + 3.0 * var_exact.sqrt(),
            a_star_white_noise: mean_y + 3.0 * var_white.sqrt(),
            approximation_poor,
            warning,
        }
    }

    /// The idler as a single-input system (input: the force F(t), N; `InputLayout::Single`); outputs `y`
    /// (m), `y_vel` (m/s), `y_acc` (m/s²), `support_force` (c y + b ẏ, N).
    ///
    /// # Formula
    /// m ÿ + b ẏ + c y = F (an [`Mdof`](crate::system::Mdof) with one coordinate, one element to ground, one force input).
    ///
    /// # Errors
    /// None for a validated idler (kept as `Result` for the system constructor).
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::conveyor_idler::ConveyorIdler;
    /// use stochvib::system::FrequencyResponse;
    /// let m = ConveyorIdler { m: 100.0, c: 7.0e4, b: 0.0 }.with_damping_ratio(0.2).unwrap().instance().unwrap();
    /// assert!((m.system.static_gain().unwrap()[(0, 0)] - 1.0 / 7.0e4).abs() < 1e-18);
    /// ```
    pub fn instance(&self) -> Result<ModelInstance> {
        let sys = MassSpringDamper {
            mass: self.m,
            stiffness: self.c,
            damping: self.b,
            drive: Drive::Force,
        }
        .build()?
        .with_output("y", Quantity::Displacement(vec![1.0]))?
        .with_output("y_vel", Quantity::Velocity(vec![1.0]))?
        .with_output("y_acc", Quantity::Acceleration(vec![1.0]))?
        .with_output("support_force", Quantity::ElementForce(0))?;
        Ok(ModelInstance {
            system: Arc::new(sys),
            layout: InputLayout::Single,
            description: format!(
                "conveyor idler (Sukharev 8.6, eq. (8.54)): m = {} kg, c = {} N/m, b = {} N s/m (omega0 = {:.4} rad/s, \
                 zeta = {:.4}), force input",
                self.m,
                self.c,
                self.b,
                self.omega0(),
                self.zeta()
            ),
        })
    }
}

/// Reads the `[model]` table of a `conveyor-idler` scenario: `m` (mass), `c` (stiffness) and either `b`
/// (damping, N s/m) or `zeta` (damping ratio, the book's β).
///
/// # Errors
/// Missing, conflicting or invalid keys, named with the file.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    let m = f.quantity("m", Dim::MASS)?;
    let c = f.quantity("c", Dim::STIFFNESS)?;
    let b = f.opt_quantity("b", Dim::DAMPING)?;
    let zeta = match f.get("zeta") {
        None => None,
        Some(_) => Some(f.number("zeta")?),
    };
    let idler = match (b, zeta) {
        (Some(b), None) => ConveyorIdler { m, c, b }.build(),
        (None, Some(z)) => ConveyorIdler { m, c, b: 0.0 }.with_damping_ratio(z),
        (Some(_), Some(_)) => return Err(f.error("zeta", "both", "give `b` or `zeta`, not both")),
        (None, None) => return Err(f.error("b", "<missing>", "give `b` (N s/m) or `zeta` (damping ratio)")),
    }
    .map_err(|e| f.wrap_param(e, "m"))?;
    idler.instance()
}

/// Example 8.1 (Sukharev (2012) 8.6, Example 8.1): every printed number against the code.
pub fn book_rows() -> Vec<BookRow> {
    let example = "Sukharev (2012) 8.6, Example 8.1 (conveyor idler under lump load)";
    let Ok(idler) = ConveyorIdler {
        m: 100.0,
        c: 7.0e4,
        b: 0.0,
    }
    .with_damping_ratio(0.2) else {
        return Vec::new();
    };
    let Ok(load) = LumpLoad {
        mean: 1.0e4,
        variance: 2.0e3 * 2.0e3,
        alpha: 0.5,
    }
    .build() else {
        return Vec::new();
    };
    let r = idler.analyse(&load);
    let invalid = format!(
        "white-noise approximation invalid: α = 0.5 1/s ≪ 2ζω₀ = {:.2} rad/s, exact/approx variance = {:.1}; the \
         response is quasi-static",
        2.0 * r.zeta * r.omega0,
        r.variance_ratio
    );
    let row = |q: &str, unit: &str, printed: f64, computed: f64, expl: String| BookRow {
        example: example.into(),
        quantity: q.into(),
        unit: unit.into(),
        printed: Some(printed),
        computed: Some(computed),
        explanation: expl,
    };
    vec![
        row("omega0", "rad/s", 26.0, r.omega0, "rounding of √700 = 26.46".into()),
        row(
            "S_x(omega0)",
            "m^2/s^3",
            0.2,
            r.s_x_omega0,
            "computed two-sided (8.53) as (8.61)/(8.62) require; the print ≈ the one-sided 2S = 0.18 rounded up".into(),
        ),
        row(
            "sigma_y by (8.62)",
            "m",
            0.009,
            r.sigma_white_noise,
            "the print follows from the one-sided S_x(ω₀) = 0.2; with the two-sided value (8.62) needs, σ_y = 0.0062 m"
                .into(),
        ),
        row("M_y", "m", 0.143, r.mean_y, "M_F/c (8.59); rounding".into()),
        row(
            "a* = M_y + 3 sigma_y by (8.62)",
            "m",
            0.17,
            r.a_star_white_noise,
            "the print uses σ_y = 0.009 m from the one-sided S_x(ω₀); with the two-sided (8.62) a* = 0.161 m".into(),
        ),
        row("sigma_y exact", "m", 0.009, r.sigma_exact, invalid.clone()),
        row("a* = M_y + 3 sigma_y exact", "m", 0.17, r.a_star_exact, invalid),
    ]
}
