//! Three-mass lifting mechanism at start-up: torsional chain motor – drum – load (Ofiy & Rakhmaniy (2010); full
//! citation in [`crate::models`]).
//!
//! The article derives the natural frequencies, the static parts and the amplitudes of the two link
//! moments of a three-mass torsional chain started by a step torque, but prints **no numerical example**;
//! the parameter set in `data/three-mass-hoist.toml` (see [`ThreeMassHoist::illustrative`]) is an
//! illustrative case chosen for this crate, not taken from the source.

use crate::error::{require_finite, require_positive, Error, Result};
use crate::fields::Fields;
use crate::models::results::{DeterministicModel, ResultTable};
use crate::models::worked_example::BookRow;
use crate::numbers::num;
use crate::system::modal_analysis;
use crate::units::Dim;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// Three-mass torsional chain I₁ –c₁– I₂ –c₂– I₃ started by a step torque M_sp on mass 1, with the load
/// torque M_B on mass 2 (Ofiy & Rakhmaniy (2010)).
///
/// Units: inertias I₁, I₂, I₃ in kg m², shaft stiffnesses c₁, c₂ in N m/rad, torques in N m, time in s,
/// angular frequencies in rad/s, link moments M₁₂ = c₁(φ₁ − φ₂), M₂₃ = c₂(φ₂ − φ₃) in N m.
///
/// # Formula
/// Equations of motion (1), with M_B acting on mass 2 as printed:
/// ```text
/// I₁φ̈₁ = M_sp − c₁(φ₁ − φ₂)
/// I₂φ̈₂ = c₁(φ₁ − φ₂) − c₂(φ₂ − φ₃) − M_B
/// I₃φ̈₃ = c₂(φ₂ − φ₃)
/// ```
/// Relative coordinates x₁ = φ₁ − φ₂, x₂ = φ₂ − φ₃ (2)–(4):
/// ```text
/// ẍ₁ = a₁₁x₁ + a₁₂x₂ + b₁,   ẍ₂ = a₂₁x₁ + a₂₂x₂ + b₂,
/// a₁₁ = −c₁(1/I₁ + 1/I₂), a₁₂ = c₂/I₂, a₂₁ = c₁/I₂, a₂₂ = −c₂(1/I₂ + 1/I₃),
/// b₁ = M_sp/I₁ + M_B/I₂,  b₂ = −M_B/I₂
/// ```
/// Natural frequencies (16) (the first of the two unnumbered forms printed just before (16) lacks the ½ in front
/// of the root):
/// ```text
/// ω²₁,₂ = ½(c₁/I₁ + (c₁+c₂)/I₂ + c₂/I₃) ∓ ½√[(c₁/I₁ + (c₁−c₂)/I₂ − c₂/I₃)² + 4c₁c₂/I₂²]
/// ```
/// — the two non-zero eigenvalues of the free–free chain K = [[c₁,−c₁,0],[−c₁,c₁+c₂,−c₂],[0,−c₂,c₂]],
/// M = diag(I₁, I₂, I₃); the third eigenvalue is 0 (rigid rotation of the whole chain).
///
/// Static parts (22), I = I₁ + I₂ + I₃ (rigid-body acceleration ε = (M_sp − M_B)/I):
/// ```text
/// D₁₂* = c₁D₁₂ = M_B + (M_sp − M_B)(I₂ + I₃)/I,   D₂₃* = c₂D₂₃ = (M_sp − M_B) I₃/I
/// ```
/// Solution with zero initial velocities (14)/(15):
/// x₁ = A₁cos ω₁t + B₁cos ω₂t + D₁₂, x₂ = A₂cos ω₁t + B₂cos ω₂t + D₂₃.
/// With the initial state x(0) = x₀ (the article: M₁₂(0) = c₁x₁(0) = M_sp, M₂₃(0) = 0, stated after (16') and
/// before (17)), u = x₀ − D and r = ẍ(0) = a x₀ + b, for each link i:
/// ```text
/// A_i = (r_i + ω₂² u_i)/(ω₂² − ω₁²),   B_i = −(r_i + ω₁² u_i)/(ω₂² − ω₁²)
/// ```
/// which for the article's initial state is exactly (20)/(21):
/// A₁ = [(M_B−M_sp)/I₂ + (M_sp/c₁ − D₁₂)ω₂²]/Δω², B₁ = [(M_sp−M_B)/I₂ − (M_sp/c₁ − D₁₂)ω₁²]/Δω²,
/// A₂ = [(M_sp−M_B)/I₂ − D₂₃ω₂²]/Δω², B₂ = [(M_B−M_sp)/I₂ + D₂₃ω₁²]/Δω².
/// Misprints in the intermediate forms: (18) B₂ has M_sp/I₂ for (M_sp−M_B)/I₂; (19) has “/2” for “/I₂”;
/// (12) uses ω₁ for ω₂ in the B terms; the remark after (21) that the link-2 amplitudes do not depend on c₂
/// is wrong (ω₁, ω₂, D₂₃ depend on c₂).
///
/// # Errors
/// [`ThreeMassHoist::build`] rejects non-positive or non-finite inertias and stiffnesses and non-finite
/// torques; time-history functions reject a non-positive or non-finite horizon or step.
///
/// # Examples
/// ```
/// use stochvib::models::three_mass_hoist::ThreeMassHoist;
/// let h = ThreeMassHoist::illustrative();
/// let (w1, w2) = h.natural_frequencies();
/// assert!(w1 > 0.0 && w2 > w1);
/// // static parts from the rigid-body acceleration: M₂₃ = I₃ ε
/// let (_, d23) = h.static_link_moments();
/// assert!((d23 - 50.0 * 400.0 / 62.0).abs() < 1e-9);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ThreeMassHoist {
    /// I₁, motor (with reduced rotating parts), kg m².
    pub i1: f64,
    /// I₂, drum, kg m².
    pub i2: f64,
    /// I₃, load reduced to the drum shaft, kg m².
    pub i3: f64,
    /// c₁, shaft motor–drum, N m/rad.
    pub c1: f64,
    /// c₂, rope (reduced), N m/rad.
    pub c2: f64,
    /// M_sp, mean starting torque on mass 1, N m.
    pub m_start: f64,
    /// M_B, load-weight torque on mass 2, N m.
    pub m_load: f64,
    /// Initial link moments (M₁₂(0), M₂₃(0)), N m; the article uses (M_sp, 0).
    pub initial_link_moments: (f64, f64),
}

/// Amplitudes of the relative twists (rad) in x₁ = A₁cos ω₁t + B₁cos ω₂t + D₁₂, x₂ = A₂cos ω₁t + B₂cos ω₂t + D₂₃.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TwistAmplitudes {
    /// A₁, rad.
    pub a1: f64,
    /// B₁, rad.
    pub b1: f64,
    /// A₂, rad.
    pub a2: f64,
    /// B₂, rad.
    pub b2: f64,
    /// D₁₂, rad.
    pub d12: f64,
    /// D₂₃, rad.
    pub d23: f64,
}

/// One sample of the link moments.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkMoments {
    /// t, s.
    pub t: f64,
    /// M₁₂ = c₁(φ₁ − φ₂), N m.
    pub m12: f64,
    /// M₂₃ = c₂(φ₂ − φ₃), N m.
    pub m23: f64,
}

fn check_horizon(t_end: f64) -> Result<f64> {
    require_positive("t_end", t_end)
}

impl ThreeMassHoist {
    /// The chain of these fields, checked: inertias I₁, I₂, I₃ (kg m²), stiffnesses c₁, c₂ (N m/rad), torques
    /// M_sp, M_B (N m) and the initial link moments (N m; the article's initial state is M₁₂(0) = M_sp,
    /// M₂₃(0) = 0, stated after (16') and before (17)) as named fields instead of seven bare numbers.
    ///
    /// # Errors
    /// Inertias and stiffnesses must be finite and > 0; torques and initial moments finite.
    ///
    /// # Examples
    /// ```
    /// use stochvib::models::three_mass_hoist::ThreeMassHoist;
    /// let h = ThreeMassHoist {
    ///     i1: 10.0,
    ///     i2: 2.0,
    ///     i3: 50.0,
    ///     c1: 1e4,
    ///     c2: 5e3,
    ///     m_start: 1000.0,
    ///     m_load: 600.0,
    ///     initial_link_moments: (1000.0, 0.0),
    /// }
    /// .build()
    /// .unwrap();
    /// assert_eq!(h, ThreeMassHoist::illustrative());
    /// ```
    pub fn build(self) -> Result<Self> {
        require_positive("I1", self.i1)?;
        require_positive("I2", self.i2)?;
        require_positive("I3", self.i3)?;
        require_positive("c1", self.c1)?;
        require_positive("c2", self.c2)?;
        require_finite("M_sp", self.m_start)?;
        require_finite("M_B", self.m_load)?;
        require_finite("M12(0)", self.initial_link_moments.0)?;
        require_finite("M23(0)", self.initial_link_moments.1)?;
        Ok(self)
    }

    /// Replaces the initial link moments (M₁₂(0), M₂₃(0)) in N m (initial velocities stay zero).
    ///
    /// # Errors
    /// Non-finite values.
    pub fn with_initial_link_moments(mut self, m12: f64, m23: f64) -> Result<Self> {
        require_finite("M12(0)", m12)?;
        require_finite("M23(0)", m23)?;
        self.initial_link_moments = (m12, m23);
        Ok(self)
    }

    /// The illustrative case of `data/three-mass-hoist.toml` (not from the source, which prints none):
    /// I₁ = 10, I₂ = 2, I₃ = 50 kg m², c₁ = 1e4, c₂ = 5e3 N m/rad, M_sp = 1000, M_B = 600 N m.
    pub fn illustrative() -> Self {
        ThreeMassHoist {
            i1: 10.0,
            i2: 2.0,
            i3: 50.0,
            c1: 1e4,
            c2: 5e3,
            m_start: 1000.0,
            m_load: 600.0,
            initial_link_moments: (1000.0, 0.0),
        }
    }

    /// Reads the `[model]` table: `I1`, `I2`, `I3` (kg m²), `c1`, `c2` (N m/rad), `M_start`, `M_load` (N m),
    /// optional `M12_initial`, `M23_initial` (N m; default M_sp and 0 as in the article).
    ///
    /// # Errors
    /// Missing keys, wrong units, invalid values (named by file and key).
    pub fn from_fields(f: &Fields) -> Result<Self> {
        let pos = |k: &str, d: Dim| -> Result<f64> {
            let v = f.quantity(k, d)?;
            require_positive(k, v).map_err(|e| f.wrap(k, e))
        };
        let (i1, i2, i3) = (
            pos("I1", Dim::INERTIA)?,
            pos("I2", Dim::INERTIA)?,
            pos("I3", Dim::INERTIA)?,
        );
        let (c1, c2) = (pos("c1", Dim::TORQUE)?, pos("c2", Dim::TORQUE)?);
        let m_start = f.quantity("M_start", Dim::TORQUE)?;
        let m_load = f.quantity("M_load", Dim::TORQUE)?;
        let m12 = f.opt_quantity("M12_initial", Dim::TORQUE)?.unwrap_or(m_start);
        let m23 = f.opt_quantity("M23_initial", Dim::TORQUE)?.unwrap_or(0.0);
        ThreeMassHoist {
            i1,
            i2,
            i3,
            c1,
            c2,
            m_start,
            m_load,
            initial_link_moments: (m12, m23),
        }
        .build()
    }

    /// I = I₁ + I₂ + I₃, kg m².
    pub fn total_inertia(&self) -> f64 {
        self.i1 + self.i2 + self.i3
    }

    /// (ω₁, ω₂) in rad/s from the closed form (16).
    pub fn natural_frequencies(&self) -> (f64, f64) {
        let (i1, i2, i3, c1, c2) = (self.i1, self.i2, self.i3, self.c1, self.c2);
        let s = c1 / i1 + (c1 + c2) / i2 + c2 / i3;
        let d = c1 / i1 + (c1 - c2) / i2 - c2 / i3;
        let root = (d * d + 4.0 * c1 * c2 / (i2 * i2)).sqrt();
        // ω₁² = (s − root)/2 computed without cancellation: ω₁²ω₂² = c₁c₂ I/(I₁I₂I₃)
        let w2sq = 0.5 * (s + root);
        let prod = c1 * c2 * self.total_inertia() / (i1 * i2 * i3);
        ((prod / w2sq).sqrt(), w2sq.sqrt())
    }

    /// Mass (diag I) and stiffness K of the free–free chain in absolute angles (φ₁, φ₂, φ₃).
    pub fn matrices(&self) -> (DMatrix<f64>, DMatrix<f64>) {
        let m = DMatrix::from_diagonal(&DVector::from_vec(vec![self.i1, self.i2, self.i3]));
        let (c1, c2) = (self.c1, self.c2);
        let k = DMatrix::from_row_slice(3, 3, &[c1, -c1, 0.0, -c1, c1 + c2, -c2, 0.0, -c2, c2]);
        (m, k)
    }

    /// Natural frequencies (rad/s, ascending: 0 for the rigid mode, ω₁, ω₂) and mass-normalised modes
    /// from [`modal_analysis`] of the chain (independent of the closed form (16)).
    ///
    /// # Errors
    /// As [`modal_analysis`].
    pub fn modal(&self) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let (m, k) = self.matrices();
        modal_analysis(&m, &k)
    }

    /// Static link moments (D₁₂*, D₂₃*) in N m, (22).
    pub fn static_link_moments(&self) -> (f64, f64) {
        let i = self.total_inertia();
        let dm = self.m_start - self.m_load;
        (self.m_load + dm * (self.i2 + self.i3) / i, dm * self.i3 / i)
    }

    /// Coefficients a (2×2) and b of the relative-coordinate equations (4).
    fn relative_system(&self) -> ([[f64; 2]; 2], [f64; 2]) {
        let (i1, i2, i3, c1, c2) = (self.i1, self.i2, self.i3, self.c1, self.c2);
        (
            [
                [-c1 * (1.0 / i1 + 1.0 / i2), c2 / i2],
                [c1 / i2, -c2 * (1.0 / i2 + 1.0 / i3)],
            ],
            [self.m_start / i1 + self.m_load / i2, -self.m_load / i2],
        )
    }

    /// Initial relative twists x₀ = (M₁₂(0)/c₁, M₂₃(0)/c₂), rad.
    fn x0(&self) -> [f64; 2] {
        [
            self.initial_link_moments.0 / self.c1,
            self.initial_link_moments.1 / self.c2,
        ]
    }

    /// Amplitudes (20)/(21) generalised to the initial state, rad (see the type's `# Formula`).
    pub fn amplitudes(&self) -> TwistAmplitudes {
        let (w1, w2) = self.natural_frequencies();
        let (w1s, w2s) = (w1 * w1, w2 * w2);
        let dw = w2s - w1s;
        let (a, b) = self.relative_system();
        let (d12s, d23s) = self.static_link_moments();
        let d = [d12s / self.c1, d23s / self.c2];
        let x0 = self.x0();
        let mut amp = [[0.0; 2]; 2];
        for i in 0..2 {
            let u = x0[i] - d[i];
            let r = a[i][0] * x0[0] + a[i][1] * x0[1] + b[i];
            amp[i] = [(r + w2s * u) / dw, -(r + w1s * u) / dw];
        }
        TwistAmplitudes {
            a1: amp[0][0],
            b1: amp[0][1],
            a2: amp[1][0],
            b2: amp[1][1],
            d12: d[0],
            d23: d[1],
        }
    }

    /// Link moments at time t (s) from the closed-form solution (14)/(15), N m.
    pub fn link_moments(&self, t: f64) -> LinkMoments {
        let (w1, w2) = self.natural_frequencies();
        let a = self.amplitudes();
        let (c1t, c2t) = ((w1 * t).cos(), (w2 * t).cos());
        LinkMoments {
            t,
            m12: self.c1 * (a.a1 * c1t + a.b1 * c2t + a.d12),
            m23: self.c2 * (a.a2 * c1t + a.b2 * c2t + a.d23),
        }
    }

    /// Link moments at the times `ts` (s) by the exact solution of the undamped relative-coordinate state
    /// space (4): z = (x₁, x₂, ẋ₁, ẋ₂), ż = F z + g, z(t) = z_s + e^{Ft}(z₀ − z_s) with nalgebra's matrix
    /// exponential (independent of the closed-form frequencies and amplitudes).
    ///
    /// # Errors
    /// [`Error::Numerical`] if the static state cannot be solved (never for valid parameters).
    pub fn link_moments_expm(&self, ts: &[f64]) -> Result<Vec<LinkMoments>> {
        let (a, b) = self.relative_system();
        let am = DMatrix::from_row_slice(2, 2, &[a[0][0], a[0][1], a[1][0], a[1][1]]);
        let xs = am
            .clone()
            .lu()
            .solve(&DVector::from_vec(vec![-b[0], -b[1]]))
            .ok_or_else(|| Error::Numerical {
                what: "three-mass hoist static state".into(),
                reason: "singular relative stiffness".into(),
            })?;
        let mut f = DMatrix::zeros(4, 4);
        f[(0, 2)] = 1.0;
        f[(1, 3)] = 1.0;
        f.view_mut((2, 0), (2, 2)).copy_from(&am);
        let x0 = self.x0();
        let dz = DVector::from_vec(vec![x0[0] - xs[0], x0[1] - xs[1], 0.0, 0.0]);
        Ok(ts
            .iter()
            .map(|&t| {
                let z = (&f * t).exp() * &dz;
                LinkMoments {
                    t,
                    m12: self.c1 * (xs[0] + z[0]),
                    m23: self.c2 * (xs[1] + z[1]),
                }
            })
            .collect())
    }

    /// Link moments on [0, t_end] by classical fourth-order Runge–Kutta with fixed step `dt` applied to the
    /// absolute-angle equations (1) (a third, independent route), sampled every step.
    ///
    /// # Errors
    /// Non-positive or non-finite `t_end` or `dt`, or more than 10⁸ steps.
    pub fn link_moments_rk4(&self, t_end: f64, dt: f64) -> Result<Vec<LinkMoments>> {
        check_horizon(t_end)?;
        require_positive("dt", dt)?;
        let steps = (t_end / dt).ceil();
        if steps > 1e8 {
            return Err(Error::invalid(
                "dt",
                dt,
                format!("{steps:e} steps to t_end = {t_end} s is too many"),
            ));
        }
        let steps = steps as usize;
        let h = t_end / steps as f64;
        let (i1, i2, i3, c1, c2, ms, mb) = (self.i1, self.i2, self.i3, self.c1, self.c2, self.m_start, self.m_load);
        // state (φ₁, φ₂, φ₃, φ̇₁, φ̇₂, φ̇₃); φ₃(0) = 0
        let deriv = |s: &[f64; 6]| -> [f64; 6] {
            let t12 = c1 * (s[0] - s[1]);
            let t23 = c2 * (s[1] - s[2]);
            [s[3], s[4], s[5], (ms - t12) / i1, (t12 - t23 - mb) / i2, t23 / i3]
        };
        let x0 = self.x0();
        let mut s = [x0[0] + x0[1], x0[1], 0.0, 0.0, 0.0, 0.0];
        let sample = |t: f64, s: &[f64; 6]| LinkMoments {
            t,
            m12: c1 * (s[0] - s[1]),
            m23: c2 * (s[1] - s[2]),
        };
        let mut out = Vec::with_capacity(steps + 1);
        out.push(sample(0.0, &s));
        for k in 0..steps {
            let add = |s: &[f64; 6], d: &[f64; 6], w: f64| -> [f64; 6] { std::array::from_fn(|i| s[i] + w * d[i]) };
            let k1 = deriv(&s);
            let k2 = deriv(&add(&s, &k1, 0.5 * h));
            let k3 = deriv(&add(&s, &k2, 0.5 * h));
            let k4 = deriv(&add(&s, &k3, h));
            s = std::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
            out.push(sample((k + 1) as f64 * h, &s));
        }
        Ok(out)
    }

    /// Closed-form link-moment history on [0, t_end] at `n + 1` equally spaced times.
    ///
    /// # Errors
    /// Non-positive `t_end` or `n = 0`.
    pub fn link_moment_history(&self, t_end: f64, n: usize) -> Result<Vec<LinkMoments>> {
        check_horizon(t_end)?;
        if n == 0 {
            return Err(Error::invalid("n", n, "need at least one interval"));
        }
        Ok((0..=n)
            .map(|k| self.link_moments(t_end * k as f64 / n as f64))
            .collect())
    }

    /// Maxima of M₁₂(t) and M₂₃(t) over [0, t_end] (N m) from the closed form: sampled at a step of
    /// T₂/64 (T₂ = 2π/ω₂), each best sample refined by golden-section search on its two neighbouring steps.
    ///
    /// # Errors
    /// Non-positive or non-finite `t_end`, or more than 10⁸ samples.
    pub fn peak_link_moments(&self, t_end: f64) -> Result<(f64, f64)> {
        check_horizon(t_end)?;
        let (_, w2) = self.natural_frequencies();
        let samples = (t_end * w2 / (2.0 * std::f64::consts::PI) * 64.0).ceil();
        if samples > 1e8 {
            return Err(Error::invalid(
                "t_end",
                t_end,
                format!("{samples:e} samples at T2/64 is too many; use a shorter horizon"),
            ));
        }
        let n = (samples as usize).max(64);
        let dt = t_end / n as f64;
        let mut best = [(f64::NEG_INFINITY, 0.0); 2];
        for k in 0..=n {
            let t = k as f64 * dt;
            let m = self.link_moments(t);
            for (j, v) in [m.m12, m.m23].into_iter().enumerate() {
                if v > best[j].0 {
                    best[j] = (v, t);
                }
            }
        }
        let refine = |j: usize, t0: f64| -> f64 {
            let g = |t: f64| {
                let m = self.link_moments(t);
                if j == 0 {
                    m.m12
                } else {
                    m.m23
                }
            };
            let (mut lo, mut hi) = ((t0 - dt).max(0.0), (t0 + dt).min(t_end));
            let r = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..80 {
                let (a, b) = (hi - r * (hi - lo), lo + r * (hi - lo));
                if g(a) > g(b) {
                    hi = b;
                } else {
                    lo = a;
                }
            }
            g(0.5 * (lo + hi)).max(g(t0))
        };
        Ok((refine(0, best[0].1), refine(1, best[1].1)))
    }

    /// Upper bounds of the link moments, D* + |c A| + |c B| (N m), reached when both cosines are ±1 together.
    pub fn peak_bounds(&self) -> (f64, f64) {
        let a = self.amplitudes();
        (
            self.c1 * (a.d12 + a.a1.abs() + a.b1.abs()),
            self.c2 * (a.d23 + a.a2.abs() + a.b2.abs()),
        )
    }
}

impl DeterministicModel for ThreeMassHoist {
    fn description(&self) -> String {
        format!(
            "three-mass hoist I = ({}, {}, {}) kg m^2, c = ({}, {}) N m/rad, M_start = {} N m, M_load = {} N m \
             (Ofiy & Rakhmaniy, Determination of dynamic loads in three-mass systems, 2010)",
            num(self.i1),
            num(self.i2),
            num(self.i3),
            num(self.c1),
            num(self.c2),
            num(self.m_start),
            num(self.m_load)
        )
    }

    /// Natural frequencies (closed form (16) and modal analysis), the static parts (22), the amplitudes
    /// (20)–(21) as link moments, and the maxima of the link moments over ten periods of the slower mode
    /// (closed-form time history, refined) with their bounds D* + |cA| + |cB|.
    fn results(&self) -> Result<Vec<ResultTable>> {
        let (w1, w2) = self.natural_frequencies();
        let (modal, _) = self.modal()?;
        let mut freq = ResultTable::new(
            "Natural frequencies (16)",
            &[
                ("mode", "-"),
                ("omega", "rad/s"),
                ("f", "Hz"),
                ("omega (modal analysis)", "rad/s"),
            ],
        )
        .with_note("closed form (16) against the eigenvalues of the free-free chain; mode 0 is the rigid rotation");
        for (j, (w, wm)) in [(0.0, modal[0]), (w1, modal[1]), (w2, modal[2])]
            .into_iter()
            .enumerate()
        {
            freq.push(vec![j.to_string().into(), w.into(), (w / (2.0 * PI)).into(), wm.into()]);
        }
        let (d12, d23) = self.static_link_moments();
        let a = self.amplitudes();
        let horizon = 10.0 * 2.0 * PI / w1;
        let (p12, p23) = self.peak_link_moments(horizon)?;
        let (b12, b23) = self.peak_bounds();
        let mut links = ResultTable::new(
            "Link moments after the start (14), (15), (20)-(22)",
            &[
                ("link", "-"),
                ("static part D*", "N m"),
                ("amplitude at omega1", "N m"),
                ("amplitude at omega2", "N m"),
                ("maximum over 10 periods", "N m"),
                ("bound D* + |cA| + |cB|", "N m"),
            ],
        )
        .with_note(format!(
            "maxima of the closed-form history over [0, {}] s (10 periods of omega1), sampled at T2/64 and refined \
             by golden-section search",
            num(horizon)
        ));
        links.push(vec![
            "M12".into(),
            d12.into(),
            (self.c1 * a.a1).into(),
            (self.c1 * a.b1).into(),
            p12.into(),
            b12.into(),
        ]);
        links.push(vec![
            "M23".into(),
            d23.into(),
            (self.c2 * a.a2).into(),
            (self.c2 * a.b2).into(),
            p23.into(),
            b23.into(),
        ]);
        Ok(vec![freq, links])
    }
}

/// Rows of the `book` report for Ofiy & Rakhmaniy (2010). The article prints no numerical example, so
/// every row has `printed = None`; the computed values are for the illustrative case
/// ([`ThreeMassHoist::illustrative`]).
pub fn book_rows() -> Vec<BookRow> {
    let h = ThreeMassHoist::illustrative();
    let ex = "Ofiy & Rakhmaniy (2010), three-mass hoist \
              (illustrative case I=10/2/50 kg m2, c=1e4/5e3 N m/rad, M_sp=1000, M_B=600 N m)";
    let none = "article prints no numerical example; value for the illustrative case";
    let (w1, w2) = h.natural_frequencies();
    let (d12, d23) = h.static_link_moments();
    let a = h.amplitudes();
    let mut rows = vec![
        ("omega_1 (16)", "rad/s", Some(w1)),
        ("omega_2 (16)", "rad/s", Some(w2)),
        ("D12* (22)", "N m", Some(d12)),
        ("D23* (22)", "N m", Some(d23)),
        ("c1 A1 (20)", "N m", Some(h.c1 * a.a1)),
        ("c1 B1 (20)", "N m", Some(h.c1 * a.b1)),
        ("c2 A2 (21)", "N m", Some(h.c2 * a.a2)),
        ("c2 B2 (21)", "N m", Some(h.c2 * a.b2)),
    ];
    let peaks = h.peak_link_moments(2.0).ok();
    rows.push(("max M12 on 0-2 s", "N m", peaks.map(|p| p.0)));
    rows.push(("max M23 on 0-2 s", "N m", peaks.map(|p| p.1)));
    rows.into_iter()
        .map(|(q, u, c)| BookRow {
            example: ex.to_string(),
            quantity: q.to_string(),
            unit: u.to_string(),
            printed: None,
            computed: c,
            explanation: none.to_string(),
        })
        .collect()
}
