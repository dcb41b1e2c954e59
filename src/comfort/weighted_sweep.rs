//! The weighted r.m.s. a_w of one acceleration output over many systems under one rational input: the
//! fast path of comfort parameter studies (e.g. a seat stiffness × damping sweep).
//!
//! [`weighted_output`] followed by [`variance_lyapunov`] builds the cascade of the system and the weighting
//! filter and solves the Lyapunov equation of the system augmented with the input's shaping filter: order
//! n + 8 + filter order for W_k, a dense Schur decomposition per system. A [`WeightedEvaluator`] factors
//! the fixed parts **once** — the poles of the input's shaping filter and of the weighting's quadratic
//! sections, and the product of their numerators — and per system forms the output's transfer
//! polynomials by Faddeev–LeVerrier on the stack, finds the system's poles, and sums the residues of
//! G(s)G(−s). (The integral table I_n of the same order-15 polynomial is ill-conditioned for W_k: its
//! Hurwitz elimination's pivot ratio exceeds 1e6 because the poles span 0.4 Hz to 100 Hz.) An error
//! estimate of the residue sum (below) bounds its relative error; when it exceeds
//! [`INTEGRAL_TABLE_MAX_ERROR`] (near-coincident poles: the residues cancel) the point is computed by the
//! Lyapunov route instead, and the result says so ([`WeightedRoute::LyapunovFallback`]).
//!
//! # Formula
//! With the inputs combined into one (b = B g, d = D g, e = E g), Δ(s) = det(sI − A), the output's
//! numerator N_i(s) = Σ_k (c_i M_k b) s^{n−k} + (d_i + e_i s) Δ(s) (Faddeev–LeVerrier, M_k of adj(sI − A)),
//! the weighting W = N_W/D_W (ISO 2631-1 Annex A, the product of its sections) and the shaping filter
//! F = F_num/F_den of the input (S_q = |F(iω)|²/(2π)), the weighted transfer function from unit white
//! noise is G = P/Q with
//! ```text
//! P(s) = N_i(s)·[F_num N_W](s),   Q(s) = c·Π_k (s − p_k)   (p_k: roots of Δ, F_den and the sections' D)
//! a_w² = (1/2π) ∫ |G(iω)|² dω = Σ_k r_k G(−p_k),   r_k = P(p_k) / (c·Π_{j≠k} (p_k − p_j))
//! ```
//! (the residue theorem on the left half plane, all poles simple and in Re s < 0; a_w in the output's
//! unit). Error estimate, relative: ε·Σ_k |t_k|·(κ_P(p_k) + κ_P(−p_k) + 2K + |p_k|/δ_k) / |Σ_k t_k| with
//! t_k = r_k G(−p_k), K poles, κ_P(z) = P̃(|z|)/|P(z)| Horner's condition (P̃: absolute coefficients) and
//! δ_k = min_{j≠k} |p_k − p_j| (a pole error of ε|p_k| moves a term by about |p_k|/δ_k of itself).

use super::weighted::weighted_output;
use super::weighting::Weighting;
use crate::error::{Error, Result};
use crate::linalg::poly;
use crate::response::{variance_lyapunov, Excitation, INTEGRAL_TABLE_MAX_ERROR};
use crate::system::{FrequencyResponse, StateSpace};
use nalgebra::Complex;

/// Largest system order handled on the residue route (larger systems go by Lyapunov).
const MAX_SYSTEM_STATES: usize = 7;

/// The route that computed one a_w.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum WeightedRoute {
    /// Residue sum, its error estimate within [`INTEGRAL_TABLE_MAX_ERROR`].
    Residues,
    /// Lyapunov covariance of the weighted, augmented system, because the residue sum's error estimate
    /// exceeded [`INTEGRAL_TABLE_MAX_ERROR`] (near-coincident poles), a pole was not simple, or the system
    /// has more than 7 states.
    LyapunovFallback,
}

/// One weighted r.m.s. value with the route that computed it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WeightedValue {
    /// a_w, in the unit of the output (m/s² for translational weightings).
    pub a_w: f64,
    /// The route.
    pub route: WeightedRoute,
}

/// Evaluates a_w of one acceleration output of many systems under one delay-free rational input (see the
/// module docs).
///
/// # Examples
/// ```
/// use stochvib::comfort::{weighted_output, Weighting, WeightedEvaluator, WeightedRoute};
/// use stochvib::response::{variance_lyapunov, Excitation};
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::system::{Attach, Element, FrequencyResponse, Mdof, Quantity};
/// use std::sync::Arc;
/// let exc = Excitation::single(Arc::new(Exponential::new(1e-4, 20.0, Domain::Temporal).unwrap()), 0.0).unwrap();
/// let ev = WeightedEvaluator::new(&exc, Weighting::Wk).unwrap();
/// for k in [2e4, 5e4, 1e5] {
///     let el = Element { name: "cushion".into(), point: vec![1.0], to: Attach::Base(0), stiffness: k, damping: 1e3 };
///     let m = Mdof::from_elements(&[("z", "m")], &[80.0], vec![el], 1, &[]).unwrap()
///         .with_output("seat_acc", Quantity::Acceleration(vec![1.0])).unwrap();
///     let ss = m.state_space().unwrap();
///     let fast = ev.a_w(ss, 0, &exc).unwrap();
///     assert_eq!(fast.route, WeightedRoute::Residues);
///     // the reference route: Lyapunov covariance of the weighted output
///     let w = weighted_output(ss, 0, &Weighting::Wk).unwrap();
///     let slow = variance_lyapunov(&w, &exc, 0).unwrap().variance.sqrt();
///     assert!((fast.a_w / slow - 1.0).abs() < 1e-9);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct WeightedEvaluator {
    weighting: Weighting,
    gains: Vec<f64>,
    /// F_num·N_W, ascending in s.
    num: Vec<f64>,
    /// The poles of F and W.
    poles: Vec<Complex<f64>>,
    /// Leading coefficient of F_den·D_W.
    lead: f64,
}

impl WeightedEvaluator {
    /// Prepares the evaluation of a_w with weighting `weighting` under `exc`: multiplies the numerators of
    /// the input's shaping filter and the weighting, and finds the poles of both.
    ///
    /// # Formula
    /// \[F_num N_W\](s), the product of ascending coefficient lists; the roots of F_den and of every quadratic
    /// section's denominator of W (module docs).
    ///
    /// # Errors
    /// [`Error::NotApplicable`] when `exc` is not one delay-free rational process (several independent
    /// inputs, delays, or a non-rational spectrum): use [`weighted_output`] with the general routes; the
    /// shaping filter's factorisation errors.
    pub fn new(exc: &Excitation, weighting: Weighting) -> Result<WeightedEvaluator> {
        let not_applicable = |reason: &str| Error::NotApplicable {
            method: "weighted integral table".into(),
            reason: reason.into(),
        };
        let Excitation::Track { spectrum, gains, .. } = exc else {
            return Err(not_applicable(
                "several independent inputs: the table handles one rational process",
            ));
        };
        if !exc.delay_free() {
            return Err(not_applicable("delayed inputs make the integrand non-rational"));
        }
        let filter = spectrum
            .rational()
            .ok_or_else(|| not_applicable("the input spectrum is not rational"))?
            .shaping_filter()?;
        let (wn, _) = weighting.polynomials();
        let mut poles = poly::roots(&filter.den)?;
        for sec in weighting.sections() {
            poles.extend(poly::roots(&sec.den)?);
        }
        Ok(WeightedEvaluator {
            weighting,
            gains: gains.clone(),
            num: poly::mul(&filter.num, &wn),
            poles,
            lead: filter.den[filter.den.len() - 1],
        })
    }

    /// The weighting.
    pub fn weighting(&self) -> Weighting {
        self.weighting
    }

    /// a_w of output `output` of `ss` under `exc` (the excitation the evaluator was made for).
    ///
    /// # Formula
    /// See the module docs; the Lyapunov fallback is [`variance_lyapunov`] of [`weighted_output`].
    ///
    /// # Errors
    /// Those of [`weighted_output`] (output out of range, not an acceleration of the weighting's unit); a
    /// system that is not asymptotically stable; an input count that does not match `exc`.
    pub fn a_w(&self, ss: &StateSpace, output: usize, exc: &Excitation) -> Result<WeightedValue> {
        if ss.b.ncols() != self.gains.len() {
            return Err(Error::invalid(
                "excitation",
                format!("{} input(s)", self.gains.len()),
                format!("the system has {} input(s)", ss.b.ncols()),
            ));
        }
        super::weighted::check_weightable(ss, output, &self.weighting)?;
        if ss.n_states() <= MAX_SYSTEM_STATES
            && let Some(v) = self.residues(ss, output)
        {
            return Ok(WeightedValue {
                a_w: v.sqrt(),
                route: WeightedRoute::Residues,
            });
        }
        let w = weighted_output(ss, output, &self.weighting)?;
        Ok(WeightedValue {
            a_w: variance_lyapunov(&w, exc, 0)?.variance.sqrt(),
            route: WeightedRoute::LyapunovFallback,
        })
    }

    /// a_w of the output whose transfer function from the input process is H(s) = N(s)/D(s) (`num`, `den`
    /// ascending in s, s in rad/s; the output in the weighting's acceleration unit per unit of the input
    /// process). This is the entry of parameter studies that know their transfer function in closed form
    /// (e.g. [`OperatorSeat::seat_acc_transfer`](crate::models::operator_seat::OperatorSeat::seat_acc_transfer)):
    /// no state space is built per point. The evaluator must have been made for an excitation of one input
    /// with gain 1 (a [`Excitation::single`]), so that the input process is the system's input.
    ///
    /// # Formula
    /// The residue sum of the module docs with N_i = N/d_n and Δ = D/d_n (d_n the leading coefficient of
    /// D); the Lyapunov fallback is [`variance_lyapunov`] of [`weighted_output`] of H realised in
    /// controllable canonical form ([`TransferFunction`](crate::system::TransferFunction)).
    ///
    /// # Errors
    /// An evaluator made for several inputs or a gain ≠ 1; D of degree 0 or > 7, N of degree > deg D + 1,
    /// non-finite coefficients; a system that is not asymptotically stable (named by the Lyapunov route).
    ///
    /// # Examples
    /// ```
    /// use stochvib::comfort::{WeightedEvaluator, Weighting, WeightedRoute};
    /// use stochvib::models::operator_seat::OperatorSeat;
    /// use stochvib::response::Excitation;
    /// use stochvib::spectrum::{Domain, Exponential};
    /// use stochvib::system::FrequencyResponse;
    /// use std::sync::Arc;
    /// let exc = Excitation::single(Arc::new(Exponential::new(1e-4, 20.0, Domain::Temporal).unwrap()), 0.0).unwrap();
    /// let ev = WeightedEvaluator::new(&exc, Weighting::Wk).unwrap();
    /// let seat = OperatorSeat { operator_mass: 80.0, seat_mass: 26.0, stiffness: 6500.0, damping: 600.0 }.build().unwrap();
    /// let (num, den) = seat.seat_acc_transfer();
    /// let fast = ev.a_w_rational(&num, &den, &exc).unwrap();
    /// assert_eq!(fast.route, WeightedRoute::Residues);
    /// // the same a_w through the model's state space
    /// let m = seat.instance().unwrap();
    /// let ss = m.system.state_space().unwrap();
    /// let i = ss.outputs().iter().position(|o| o.name == "seat_acc").unwrap();
    /// assert!((fast.a_w / ev.a_w(ss, i, &exc).unwrap().a_w - 1.0).abs() < 1e-9); // within the error estimate
    /// ```
    pub fn a_w_rational(&self, num: &[f64], den: &[f64], exc: &Excitation) -> Result<WeightedValue> {
        if self.gains.len() != 1 || self.gains[0] != 1.0 {
            return Err(Error::invalid(
                "excitation",
                format!("gains {:?}", self.gains),
                "a transfer function N/D is driven by one input of gain 1: make the evaluator from Excitation::single",
            ));
        }
        let n = den.len().saturating_sub(1);
        let lead = den.last().copied().unwrap_or(0.0);
        if n == 0 || n > MAX_SYSTEM_STATES || num.len() > n + 2 || lead == 0.0 {
            return Err(Error::invalid(
                "transfer function",
                format!("{num:?} / {den:?}"),
                format!(
                    "needs 1 <= deg D <= {MAX_SYSTEM_STATES}, deg N <= deg D + 1 and a non-zero leading coefficient"
                ),
            ));
        }
        if !num.iter().chain(den).all(|v| v.is_finite()) {
            return Err(Error::invalid(
                "transfer function",
                format!("{num:?} / {den:?}"),
                "coefficients must be finite",
            ));
        }
        let mut ni = [0.0; MAX_SYSTEM_STATES + 2];
        let mut delta = [0.0; MAX_SYSTEM_STATES + 1];
        for (o, v) in ni.iter_mut().zip(num) {
            *o = v / lead;
        }
        for (o, v) in delta.iter_mut().zip(den) {
            *o = v / lead;
        }
        if let Some(v) = self.residue_sum(&ni[..n + 2], &delta[..=n]) {
            return Ok(WeightedValue {
                a_w: v.sqrt(),
                route: WeightedRoute::Residues,
            });
        }
        let tf = crate::system::TransferFunction::new(
            num.to_vec(),
            den.to_vec(),
            crate::system::OutputInfo::new("a", self.weighting.quantity().unit),
        )?;
        let ss = tf.state_space().ok_or_else(|| Error::Numerical {
            what: "a_w".into(),
            reason: "the transfer function has no state-space form".into(),
        })?;
        let w = weighted_output(ss, 0, &self.weighting)?;
        Ok(WeightedValue {
            a_w: variance_lyapunov(&w, exc, 0)?.variance.sqrt(),
            route: WeightedRoute::LyapunovFallback,
        })
    }

    /// a_w² by the residue sum, or None when its error estimate is too large or a pole is not simple or
    /// not in the left half plane (the Lyapunov route then decides, and names an unstable system).
    fn residues(&self, ss: &StateSpace, output: usize) -> Option<f64> {
        use crate::response::Leverrier;
        let lv = Leverrier::new(ss, &self.gains);
        if lv.residual.is_nan() || lv.residual > INTEGRAL_TABLE_MAX_ERROR {
            return None;
        }
        let n = lv.n;
        let ni = lv.numerator(ss, &self.gains, output);
        self.residue_sum(&ni[..n + 2], &lv.delta[..=n])
    }

    /// a_w² of the output N_i/Δ (Δ monic, ascending) by the residue sum of the module docs, or None (see
    /// [`residues`](Self::residues)).
    fn residue_sum(&self, ni: &[f64], delta: &[f64]) -> Option<f64> {
        let mut poles = poly::roots(delta).ok()?;
        poles.extend_from_slice(&self.poles);
        if poles.iter().any(|p| p.re.is_nan() || p.re >= 0.0) {
            return None;
        }
        let k_poles = poles.len();
        // P and its Horner bound P̃(|z|) at z
        let eval = |z: Complex<f64>, z_abs: f64| {
            let (mut a, mut abs_a) = (Complex::new(0.0, 0.0), 0.0);
            for &c in ni.iter().rev() {
                a = a * z + c;
                abs_a = abs_a * z_abs + c.abs();
            }
            let (mut b, mut abs_b) = (Complex::new(0.0, 0.0), 0.0);
            for &c in self.num.iter().rev() {
                b = b * z + c;
                abs_b = abs_b * z_abs + c.abs();
            }
            (a * b, abs_a * abs_b)
        };
        let (mut sum, mut abs_err) = (Complex::new(0.0, 0.0), 0.0);
        for (k, &p) in poles.iter().enumerate() {
            let (mut dq, mut q_minus) = (Complex::new(self.lead, 0.0), Complex::new(self.lead, 0.0));
            let mut sep2 = f64::INFINITY;
            for (j, &pj) in poles.iter().enumerate() {
                q_minus *= -p - pj;
                if j != k {
                    dq *= p - pj;
                    sep2 = sep2.min((p - pj).norm_sqr());
                }
            }
            if sep2 == 0.0 {
                return None;
            }
            let (p_abs, sep) = (p.norm(), sep2.sqrt());
            let (pp, pp_abs) = eval(p, p_abs);
            let (pm, pm_abs) = eval(-p, p_abs);
            let t = pp / dq * (pm / q_minus);
            let kappa = |v: Complex<f64>, bound: f64| if v.norm() > 0.0 { bound / v.norm() } else { 0.0 };
            sum += t;
            abs_err += t.norm() * (kappa(pp, pp_abs) + kappa(pm, pm_abs) + 2.0 * k_poles as f64 + p_abs / sep);
        }
        let value = sum.re;
        if !(value.is_finite() && value > 0.0) || abs_err * f64::EPSILON > INTEGRAL_TABLE_MAX_ERROR * value {
            return None;
        }
        Some(value)
    }
}
