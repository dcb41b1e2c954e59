//! Exact variance, spectral moments and autocovariance of an output when the inputs are one rational
//! process felt with delays (a road under several wheels): the stationary covariance of the system
//! augmented with the input's shaping filter, carried across the delays by the matrix exponential.

use super::{Excitation, LyapunovMoments};
use crate::error::{Error, Result};
use crate::linalg::expm;
use crate::linalg::solve_continuous_lyapunov;
use crate::system::{FrequencyResponse, OutputInfo, StateSpace, TransferFunction};
use nalgebra::DMatrix;

/// Name of the method in errors and reports.
const METHOD: &str = "exact delayed-input (Lyapunov) covariance";

/// The system augmented with the shaping filter of a rational track input, one copy of the system's
/// states per delay group, driven by the one white noise w; and the undelayed response ȳ_g of output i
/// to each group.
///
/// # Formula
/// The track input is u_j(t) = g_j q(t − τ_j). Inputs with equal delays form a group g with delay τ_g and
/// combined columns b_g = Σ_{j∈g} g_j B_{:,j}, d_g = Σ g_j D_{ij}, e_g = Σ g_j E_{ij} (c = C_{i,:}). The
/// process is q = C_F x_F + D_F w with ẋ_F = A_F x_F + B_F w (the [`ShapingFilter`] of the rational
/// spectrum in controllable form; E[w(t)w(s)] = δ(t − s)). With x_g the system's states driven by b_g q
/// without delay and z = [x_F; x_1; …; x_G]:
/// ```text
/// ż = 𝒜 z + 𝒢 w,   𝒜 = [[A_F, 0, …, 0], [b_1 C_F, A, 0, …], …, [b_G C_F, 0, …, A]],   𝒢 = [B_F; b_1 D_F; …; b_G D_F]
/// ȳ_g = c x_g + d_g q + e_g q̇ = 𝒞_g z + f_g w + e_g D_F ẇ,
/// 𝒞_g = [d_g C_F + e_g C_F A_F, 0, …, c (block g), …, 0],   f_g = d_g D_F + e_g C_F B_F
/// y(t) = Σ_g ȳ_g(t − τ_g)
/// ```
/// y has finite variance iff f_g = 0 and e_g D_F = 0 for every g (white noise at distinct delays cannot
/// cancel; within a group it has already been summed).
///
/// [`ShapingFilter`]: crate::spectrum::ShapingFilter
///
/// # Errors
/// See [`delayed_augmented_system`].
///
/// # Examples
/// ```
/// use stochvib::response::{delayed_augmented_system, Excitation};
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::{OutputInfo, StateSpace};
/// use nalgebra::DMatrix;
/// use std::sync::Arc;
/// // y = ȳ₁ + ȳ₂ with T ȳ̇ + ȳ = u: a two-input first-order system, inputs 0.2 s apart on a type-1 process
/// let t = 0.1;
/// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0 / t), DMatrix::from_row_slice(1, 2, &[1.0 / t, 1.0 / t]),
///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("y", "m")]).unwrap();
/// let q = Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap());
/// let exc = Excitation::track(q, vec![0.0, 0.2], vec![1.0, 1.0], 0.0).unwrap();
/// let aug = delayed_augmented_system(&ss, &exc, 0).unwrap();
/// assert_eq!(aug.delays, vec![0.0, 0.2]);
/// assert_eq!(aug.a.nrows(), 1 + 2 * 1); // one filter state, two copies of one system state
/// ```
#[derive(Debug, Clone)]
pub struct DelayedAugmentedSystem {
    /// 𝒜, N × N with N = (filter states) + G·(system states).
    pub a: DMatrix<f64>,
    /// 𝒢, N × 1.
    pub g: DMatrix<f64>,
    /// τ_g of every group, s (in order of first appearance among the inputs).
    pub delays: Vec<f64>,
    /// 𝒞_g, 1 × N, per group.
    pub rows: Vec<DMatrix<f64>>,
    /// f_g, the coefficient of w in ȳ_g, per group.
    pub white: Vec<f64>,
    /// e_g D_F, the coefficient of ẇ in ȳ_g, per group.
    pub white_derivative: Vec<f64>,
    /// Output name (for messages).
    pub name: String,
}

/// Builds the [`DelayedAugmentedSystem`] of output `i` of `ss` under a track excitation with a rational
/// spectrum.
///
/// # Formula
/// See [`DelayedAugmentedSystem`].
///
/// # Errors
/// * [`Error::NotApplicable`] for independent inputs (no delays: [`variance_lyapunov`] applies) and for a
///   spectrum that is not rational (no finite shaping filter: use the oscillatory quadrature
///   [`spectral_moment_oscillatory`]).
/// * [`Error::Divergent`] when the spectrum grows at high frequency (no shaping filter exists).
/// * [`Error::InvalidParameter`] for an output index out of range or an excitation with the wrong number
///   of inputs.
///
/// [`variance_lyapunov`]: super::variance_lyapunov
/// [`spectral_moment_oscillatory`]: super::spectral_moment_oscillatory
///
/// # Examples
/// See [`DelayedAugmentedSystem`].
pub fn delayed_augmented_system(ss: &StateSpace, exc: &Excitation, i: usize) -> Result<DelayedAugmentedSystem> {
    check_dims(ss, exc, i)?;
    let Excitation::Track {
        spectrum,
        delays,
        gains,
        ..
    } = exc
    else {
        return Err(Error::NotApplicable {
            method: METHOD.into(),
            reason: "the inputs are independent processes, not delayed copies of one process; the plain \
                     Lyapunov variance applies"
                .into(),
        });
    };
    let rational = spectrum.rational().ok_or_else(|| Error::NotApplicable {
        method: METHOD.into(),
        reason: format!(
            "the input spectrum ({}) is not rational (no finite shaping filter); the oscillatory quadrature \
             applies",
            spectrum.describe()
        ),
    })?;
    let filter = rational.shaping_filter()?;
    let fss = TransferFunction::new(filter.num.clone(), filter.den.clone(), OutputInfo::new("q", "-"))?
        .state_space()
        .cloned()
        .ok_or_else(|| Error::Numerical {
            what: METHOD.into(),
            reason: "the shaping filter has no state-space form".into(),
        })?;
    let (af, bf, cf, df) = (&fss.a, &fss.b, &fss.c, fss.d[(0, 0)]);
    let nf = af.nrows();
    // groups of equal delay, in order of first appearance
    let mut taus: Vec<f64> = Vec::new();
    let mut members: Vec<Vec<(usize, f64)>> = Vec::new();
    for (j, (&t, &g)) in delays.iter().zip(gains).enumerate() {
        match taus.iter().position(|&u| u == t) {
            Some(k) => members[k].push((j, g)),
            None => {
                taus.push(t);
                members.push(vec![(j, g)]);
            }
        }
    }
    let n = ss.n_states();
    let ng = taus.len();
    let big = nf + ng * n;
    let mut a = DMatrix::zeros(big, big);
    let mut g = DMatrix::zeros(big, 1);
    a.view_mut((0, 0), (nf, nf)).copy_from(af);
    g.view_mut((0, 0), (nf, 1)).copy_from(bf);
    let c = ss.c.rows(i, 1).into_owned();
    let cf_af = cf * af;
    let cf_bf = (cf * bf)[(0, 0)];
    let mut rows = Vec::with_capacity(ng);
    let mut white = Vec::with_capacity(ng);
    let mut white_derivative = Vec::with_capacity(ng);
    for (k, m) in members.iter().enumerate() {
        let mut bg = DMatrix::zeros(n, 1);
        let (mut dg, mut eg) = (0.0, 0.0);
        for &(j, gain) in m {
            bg += ss.b.columns(j, 1) * gain;
            dg += gain * ss.d[(i, j)];
            eg += gain * ss.e[(i, j)];
        }
        let off = nf + k * n;
        a.view_mut((off, off), (n, n)).copy_from(&ss.a);
        a.view_mut((off, 0), (n, nf)).copy_from(&(&bg * cf));
        g.view_mut((off, 0), (n, 1)).copy_from(&(&bg * df));
        let mut row = DMatrix::zeros(1, big);
        row.view_mut((0, 0), (1, nf)).copy_from(&(cf * dg + &cf_af * eg));
        row.view_mut((0, off), (1, n)).copy_from(&c);
        rows.push(row);
        white.push(dg * df + eg * cf_bf);
        white_derivative.push(eg * df);
    }
    Ok(DelayedAugmentedSystem {
        a,
        g,
        delays: taus,
        rows,
        white,
        white_derivative,
        name: ss.outputs()[i].name.clone(),
    })
}

/// The stationary covariance of a [`DelayedAugmentedSystem`] and the output statistics that follow from
/// it: variance, λ₂, λ₄ and the autocovariance at any lag, exactly (no quadrature).
///
/// # Formula
/// P solves 𝒜 P + P 𝒜ᵀ + 𝒢𝒢ᵀ = 0 (stationary E[z zᵀ]; [`solve_continuous_lyapunov`]). For Δ ≥ 0,
/// z(t+Δ) = e^{𝒜Δ} z(t) + ∫_t^{t+Δ} e^{𝒜(t+Δ−s)} 𝒢 w(s) ds and the integral is independent of z(t)
/// (which depends on w up to t only), so E[z(t+Δ) z(t)ᵀ] = e^{𝒜Δ} P and, when ȳ_g is free of white noise,
/// ```text
/// R_gh(Δ) = E[ȳ_g(t+Δ) ȳ_h(t)] = 𝒞_g e^{𝒜Δ} P 𝒞_hᵀ   (Δ ≥ 0),      R_gh(−Δ) = R_hg(Δ)
/// R_y(s) = E[y(t+s) y(t)] = Σ_{g,h} R_gh(s − τ_g + τ_h),      D_y = R_y(0) = Σ_{g,h} R_gh(τ_h − τ_g)
/// ```
/// The n-th derivative is ȳ_g⁽ⁿ⁾ = 𝒞_g 𝒜ⁿ z when 𝒞_g 𝒜^m 𝒢 = 0 for m < n (otherwise it contains white
/// noise and has infinite variance), so λ₂ = Var(ẏ) and λ₄ = Var(ÿ) are the same sums with the rows
/// 𝒞_g 𝒜 and 𝒞_g 𝒜². The matrix exponential is [`expm()`] (scaling and squaring with a Padé approximant,
/// Higham, "The scaling and squaring method for the matrix exponential revisited", SIAM J. Matrix Anal.
/// Appl. 26, 2005), once per distinct lag. With all delays equal there is one group and P, D_y and the
/// moments are those of [`variance_lyapunov`](super::variance_lyapunov) (the same augmented system, up to
/// the rounding of the products that form it).
///
/// # Errors
/// As [`delayed_augmented_system`]; [`Error::InvalidParameter`] for an unstable system;
/// [`Error::Numerical`] if the Lyapunov solve or the exponential fails.
///
/// # Examples
/// ```
/// use stochvib::response::{DelayedCovariance, Excitation};
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::{OutputInfo, StateSpace};
/// use nalgebra::DMatrix;
/// use std::sync::Arc;
/// // y = ȳ(t) + ȳ(t − τ), T ẏ + ȳ = q: two inputs of the same first-order system
/// let t = 0.1;
/// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0 / t), DMatrix::from_row_slice(1, 2, &[1.0 / t, 1.0 / t]),
///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("y", "m")]).unwrap();
/// let (d, alpha, tau) = (1.0, 2.0, 0.3);
/// let q = Arc::new(Exponential::new(d, alpha, Domain::Temporal).unwrap());
/// let exc = Excitation::track(q, vec![0.0, tau], vec![1.0, 1.0], 0.0).unwrap();
/// let cov = DelayedCovariance::new(&ss, &exc, 0).unwrap();
/// // R(u) = Dβ(βe^{−α|u|} − αe^{−β|u|})/(β² − α²), β = 1/T; D_y = 2R(0) + 2R(τ)
/// let b = 1.0 / t;
/// let r = |u: f64| d * b * (b * (-alpha * u).exp() - alpha * (-b * u).exp()) / (b * b - alpha * alpha);
/// let m = cov.moments().unwrap();
/// assert!((m.variance - (2.0 * r(0.0) + 2.0 * r(tau))).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct DelayedCovariance {
    /// The augmented system.
    pub system: DelayedAugmentedSystem,
    /// P = E[z zᵀ].
    pub covariance: DMatrix<f64>,
}

impl DelayedCovariance {
    /// Builds the augmented system of output `i` and solves its Lyapunov equation.
    ///
    /// # Formula
    /// 𝒜 P + P 𝒜ᵀ + 𝒢𝒢ᵀ = 0 (see the type's `# Formula`).
    ///
    /// # Errors
    /// See the type's `# Errors`.
    ///
    /// # Examples
    /// ```
    /// use stochvib::response::{DelayedCovariance, Excitation};
    /// use stochvib::spectrum::{Domain, Exponential};
    /// use stochvib::system::{OutputInfo, StateSpace};
    /// use nalgebra::DMatrix;
    /// use std::sync::Arc;
    /// let t = 0.1; // y = ȳ(t) + ȳ(t − τ), T ȳ̇ + ȳ = q
    /// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0 / t),
    ///     DMatrix::from_row_slice(1, 2, &[1.0 / t, 1.0 / t]),
    ///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("y", "m")]).unwrap();
    /// let (d, alpha, tau) = (1.0, 2.0, 0.3);
    /// let exc = Excitation::track(Arc::new(Exponential::new(d, alpha, Domain::Temporal).unwrap()),
    ///     vec![0.0, tau], vec![1.0, 1.0], 0.0).unwrap();
    /// let cov = DelayedCovariance::new(&ss, &exc, 0).unwrap();
    /// assert_eq!(cov.covariance.nrows(), 3); // one filter state, two copies of one system state
    /// ```
    pub fn new(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<Self> {
        let ss = sys.state_space().ok_or_else(|| Error::NotApplicable {
            method: METHOD.into(),
            reason: "the system has no finite state-space form".into(),
        })?;
        check_dims(ss, exc, i)?;
        ss.require_stable()?;
        let system = delayed_augmented_system(ss, exc, i)?;
        let q = &system.g * system.g.transpose();
        let covariance = solve_continuous_lyapunov(&system.a, &q)?;
        Ok(DelayedCovariance { system, covariance })
    }

    /// The rows 𝒞_g 𝒜ⁿ of the n-th derivative (n = 0, 1, 2), or why it contains white noise.
    fn derivative_rows(&self, n: u32) -> Result<Vec<DMatrix<f64>>> {
        let s = &self.system;
        let divergent = |k: u32| divergence(&s.name, k);
        if s.white.iter().chain(&s.white_derivative).any(|v| *v != 0.0) {
            return Err(divergent(0));
        }
        let gnorm = s.g.norm();
        let mut rows = s.rows.clone();
        for k in 1..=n {
            for r in &rows {
                let rg = r * &s.g;
                if rg.amax() > 1e-12 * (r.norm() * gnorm).max(1e-300) {
                    return Err(divergent(2 * k));
                }
            }
            rows = rows.iter().map(|r| r * &s.a).collect();
        }
        Ok(rows)
    }

    /// Σ_{g,h} 𝒞'_g e^{𝒜Δ} P 𝒞'_hᵀ over the pairs at lag s (Δ = s − τ_g + τ_h), with e^{𝒜Δ}P cached per Δ.
    fn pair_sum(&self, rows: &[DMatrix<f64>], s: f64, cache: &mut Vec<(f64, DMatrix<f64>)>) -> Result<f64> {
        let taus = &self.system.delays;
        let mut total = 0.0;
        for (g, rg) in rows.iter().enumerate() {
            for (h, rh) in rows.iter().enumerate() {
                let lag = s - taus[g] + taus[h];
                let (first, second) = if lag >= 0.0 { (rg, rh) } else { (rh, rg) };
                let d = lag.abs();
                let ep = match cache.iter().position(|(l, _)| *l == d) {
                    Some(k) => &cache[k].1,
                    None => {
                        let m = if d == 0.0 {
                            self.covariance.clone()
                        } else {
                            expm(&(&self.system.a * d))? * &self.covariance
                        };
                        cache.push((d, m));
                        &cache[cache.len() - 1].1
                    }
                };
                total += (first * ep * second.transpose())[(0, 0)];
            }
        }
        Ok(total)
    }

    /// Autocovariance E[y⁽ⁿ⁾(t+s) y⁽ⁿ⁾(t)] of the n-th derivative of the output (n = 0, 1, 2) at lag `s`
    /// (s, any sign).
    ///
    /// # Formula
    /// See the type's `# Formula`; n = 0 gives R_y(s), and at s = 0: D_y, λ₂, λ₄ for n = 0, 1, 2.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for n > 2 or a non-finite lag; [`Error::Divergent`] when the n-th
    /// derivative contains white noise (its autocovariance then has a Dirac delta);
    /// [`Error::Numerical`] if the matrix exponential fails.
    ///
    /// # Examples
    /// ```
    /// use stochvib::response::{DelayedCovariance, Excitation};
    /// use stochvib::spectrum::{Domain, Exponential};
    /// use stochvib::system::{OutputInfo, StateSpace};
    /// use nalgebra::DMatrix;
    /// use std::sync::Arc;
    /// let t = 0.1; // y = ȳ(t) + ȳ(t − τ), T ȳ̇ + ȳ = q
    /// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0 / t),
    ///     DMatrix::from_row_slice(1, 2, &[1.0 / t, 1.0 / t]),
    ///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("y", "m")]).unwrap();
    /// let (d, alpha, tau) = (1.0, 2.0, 0.3);
    /// let exc = Excitation::track(Arc::new(Exponential::new(d, alpha, Domain::Temporal).unwrap()),
    ///     vec![0.0, tau], vec![1.0, 1.0], 0.0).unwrap();
    /// let cov = DelayedCovariance::new(&ss, &exc, 0).unwrap();
    /// // R_y(s) = 2R(s) + R(s + τ) + R(s − τ), R(u) = Dβ(βe^{−α|u|} − αe^{−β|u|})/(β² − α²), β = 1/T
    /// let b = 1.0 / t;
    /// let r = |u: f64| {
    ///     d * b * (b * (-alpha * u.abs()).exp() - alpha * (-b * u.abs()).exp()) / (b * b - alpha * alpha)
    /// };
    /// let s = 0.12;
    /// let ry = 2.0 * r(s) + r(s + tau) + r(s - tau);
    /// assert!((cov.autocovariance(s, 0).unwrap() - ry).abs() < 1e-12);
    /// assert!((cov.autocovariance(0.0, 0).unwrap() - cov.moments().unwrap().variance).abs() < 1e-15);
    /// ```
    pub fn autocovariance(&self, s: f64, n: u32) -> Result<f64> {
        if n > 2 {
            return Err(Error::invalid("derivative order", n, "must be 0, 1 or 2"));
        }
        crate::error::require_finite("lag", s)?;
        let rows = self.derivative_rows(n)?;
        self.pair_sum(&rows, s, &mut Vec::new())
    }

    /// D_y, λ₂ = Var(ẏ) and λ₄ = Var(ÿ).
    ///
    /// # Formula
    /// See the type's `# Formula`.
    ///
    /// # Errors
    /// [`Error::Divergent`] when the output itself contains white noise; λ₂ and λ₄ carry their own
    /// [`Error::Divergent`] when only a derivative does.
    ///
    /// # Examples
    /// ```
    /// use stochvib::response::{DelayedCovariance, Excitation};
    /// use stochvib::spectrum::{Domain, Exponential};
    /// use stochvib::system::{OutputInfo, StateSpace};
    /// use nalgebra::DMatrix;
    /// use std::sync::Arc;
    /// let t = 0.1; // y = ȳ(t) + ȳ(t − τ), T ȳ̇ + ȳ = q
    /// let ss = StateSpace::new(DMatrix::from_element(1, 1, -1.0 / t),
    ///     DMatrix::from_row_slice(1, 2, &[1.0 / t, 1.0 / t]),
    ///     DMatrix::from_element(1, 1, 1.0), None, None, vec![OutputInfo::new("y", "m")]).unwrap();
    /// let (d, alpha, tau) = (1.0, 2.0, 0.3);
    /// let exc = Excitation::track(Arc::new(Exponential::new(d, alpha, Domain::Temporal).unwrap()),
    ///     vec![0.0, tau], vec![1.0, 1.0], 0.0).unwrap();
    /// let cov = DelayedCovariance::new(&ss, &exc, 0).unwrap();
    /// let m = cov.moments().unwrap();
    /// // type 1 through a first-order filter: ẏ has finite variance, ÿ contains white noise
    /// assert!(m.lambda2.is_ok() && matches!(m.lambda4, Err(stochvib::Error::Divergent { .. })));
    /// ```
    pub fn moments(&self) -> Result<LyapunovMoments> {
        let mut cache = Vec::new();
        let r0 = self.derivative_rows(0)?;
        let variance = self.pair_sum(&r0, 0.0, &mut cache)?;
        let lambda2 = self.derivative_rows(1).and_then(|r| self.pair_sum(&r, 0.0, &mut cache));
        let lambda4 = match &lambda2 {
            Ok(_) => self.derivative_rows(2).and_then(|r| self.pair_sum(&r, 0.0, &mut cache)),
            Err(_) => Err(divergence(&self.system.name, 4)),
        };
        Ok(LyapunovMoments {
            variance,
            lambda2,
            lambda4,
        })
    }
}

/// Exact variance, λ₂ and λ₄ of output `i` when the inputs are one rational process felt with delays:
/// [`DelayedCovariance::new`] then [`DelayedCovariance::moments`]. The row "lyapunov (delays)" of a
/// report.
///
/// # Formula
/// ```text
/// D_y = Σ_{g,h} 𝒞_g e^{𝒜(τ_h − τ_g)} P 𝒞_hᵀ (the pair ordered so the lag is ≥ 0),   λ₂, λ₄: rows 𝒞_g𝒜, 𝒞_g𝒜²
/// ```
/// (see [`DelayedCovariance`]; equal delays reduce to [`variance_lyapunov`](super::variance_lyapunov)).
///
/// # Errors
/// [`Error::NotApplicable`] (independent inputs, non-rational spectrum, no state-space form),
/// [`Error::Divergent`] (white noise in the output; λ₂, λ₄ individually inside the result),
/// [`Error::InvalidParameter`] (unstable system, bad output index or input count), [`Error::Numerical`].
///
/// # Examples
/// ```
/// use stochvib::response::{variance_lyapunov_delayed, Excitation};
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::{Attach, Element, Mdof, Quantity};
/// use std::sync::Arc;
/// // a rigid bar on two wheels 2.6 m apart at 11 m/s (bounce z, pitch φ about the midpoint)
/// let el = |name: &str, x: f64, j: usize| Element { name: name.into(), point: vec![1.0, x], to: Attach::Base(j),
///     stiffness: 4e4, damping: 2.5e3 };
/// let m = Mdof::from_elements(&[("z", "m"), ("phi", "rad")], &[1500.0, 1500.0 * 1.2f64.powi(2)],
///     vec![el("front", 1.3, 0), el("rear", -1.3, 1)], 2, &[]).unwrap()
///     .with_output("body_vel", Quantity::Velocity(vec![1.0, 0.0])).unwrap();
/// let road = Arc::new(Exponential::new(1e-4, 1.1, Domain::Temporal).unwrap());
/// let exc = Excitation::track(road, vec![0.0, 2.6 / 11.0], vec![1.0, 1.0], 0.0).unwrap();
/// let mo = variance_lyapunov_delayed(&m, &exc, 0).unwrap();
/// assert!(mo.variance > 0.0 && mo.variance.is_finite());
/// // the velocity's derivative (an acceleration with the damper's q̇ term) is not mean-square finite
/// assert!(matches!(mo.lambda2, Err(stochvib::Error::Divergent { .. })));
/// ```
pub fn variance_lyapunov_delayed(sys: &dyn FrequencyResponse, exc: &Excitation, i: usize) -> Result<LyapunovMoments> {
    DelayedCovariance::new(sys, exc, i)?
        .moments()?
        .checked("Lyapunov variance with delays")
}

fn check_dims(ss: &StateSpace, exc: &Excitation, i: usize) -> Result<()> {
    if exc.n_inputs() != ss.b.ncols() {
        return Err(Error::invalid(
            "excitation",
            format!("{} inputs", exc.n_inputs()),
            format!("the system has {} inputs", ss.b.ncols()),
        ));
    }
    if i >= ss.c.nrows() {
        return Err(Error::invalid(
            "output",
            i,
            format!("the system has {} outputs", ss.c.nrows()),
        ));
    }
    Ok(())
}

/// The white-noise divergence of moment λ_k (k = 0: the variance), worded as `variance_lyapunov`'s.
fn divergence(name: &str, k: u32) -> Error {
    Error::Divergent {
        quantity: if k == 0 {
            format!("variance of `{name}`")
        } else {
            format!("spectral moment λ{k} of `{name}`")
        },
        reason: format!(
            "{} contains a white-noise component (the system augmented with the input's shaping filter feeds \
             the driving noise straight through to it, at one of the input delays, where no other input can \
             cancel it), so its density does not decay; ask for a band-limited value",
            match k {
                0 => "the output",
                2 => "the derivative of the output",
                _ => "the second derivative of the output",
            }
        ),
    }
}
