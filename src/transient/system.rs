//! The white-noise-driven, time-varying state-space form of a (possibly scheduled) system and its random
//! input: what the exact route propagates and the Monte Carlo route steps.

use super::affine_step::AffineNoise;
use super::schedule::{at_time, ModelAt, SystemFamily};
use super::sources::{check_model, frozen_blocks, Block, ExtraSource};
use super::{Envelope, SpeedProfile};
use crate::error::{Error, Result};
use crate::spectrum::ShapingFilter;
use crate::system::{FrequencyResponse, OutputInfo, StateSpace, TransferFunction};
use nalgebra::{DMatrix, DVector};
use std::borrow::Cow;
use std::f64::consts::PI;
use std::sync::Arc;

/// The random input process before its envelope, in the crate's convention (two-sided densities in
/// angular frequency; white noise of density S₀ has E\[w(t)w(t+τ)\] = 2πS₀δ(τ)).
#[derive(Debug, Clone)]
pub enum InputModel {
    /// White noise of two-sided density S₀ (unit² per rad/s).
    White {
        /// S₀.
        density: f64,
    },
    /// A temporal rational spectrum: its shaping filter (unit-intensity white noise in, the process out).
    Rational {
        /// B(s)/A(s), s in rad/s.
        filter: ShapingFilter,
    },
    /// A spatial rational road spectrum traversed at v(t): the filter in the road coordinate x becomes the
    /// time-varying filter A(t) = v(t)A_x, G(t) = √v(t)·B_x (exact).
    SpatialRational {
        /// B(s)/A(s), s in rad/m.
        filter: ShapingFilter,
        /// v(t).
        speed: SpeedProfile,
    },
    /// A road of waviness w = 2 without a band, S_Ω(Ω) = c/Ω² (c = πn₀²G_d(n₀) for ISO 8608): its slope is
    /// white in space, so the road velocity at the wheel is white in time with S₀(t) = c·v(t) (exact).
    WhiteSlope {
        /// c, m²·rad/m (S_Ω = c/Ω²).
        coefficient: f64,
        /// v(t).
        speed: SpeedProfile,
    },
}

/// The random input of a transient analysis: u(t) = a(t)·(M_u + s(t)), fed to the system's inputs with
/// the given gains (one process felt by every input, e.g. the wheels of one track at one position).
#[derive(Debug, Clone)]
pub struct TransientInput {
    /// The process s(t).
    pub model: InputModel,
    /// The envelope a(t).
    pub envelope: Envelope,
    /// The mean M_u of the process (its unit).
    pub mean: f64,
    /// Gain of the process at each system input.
    pub gains: Vec<f64>,
}

/// The frozen form at one time t: ż = F z + G w + b, y = H z + y₀, with unit-intensity white noise w
/// (E\[w(t)w(s)ᵀ\] = I δ(t − s)).
#[derive(Debug, Clone, PartialEq)]
pub struct Frozen {
    /// F (n × n).
    pub f: DMatrix<f64>,
    /// G (n × q).
    pub g: DMatrix<f64>,
    /// b (n): deterministic forcing.
    pub b: DVector<f64>,
    /// H (p × n).
    pub h: DMatrix<f64>,
    /// y₀ (p): deterministic part of the outputs not carried by the states.
    pub y0: DVector<f64>,
}

/// How the process is started at t = 0.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Start {
    /// Every state zero (the system at rest, the input filters at rest): P(0) = 0.
    Rest,
    /// The stationary state of the frozen system at t = 0 (it must be stable there).
    Stationary,
    /// The system's states (in the model's state order) equal to the given values, without scatter; the
    /// input filters in their stationary state.
    State(Vec<f64>),
}

/// The shaping filter as a state space ż_f = A_f z_f + B_f w, s = C_f z_f.
#[derive(Debug, Clone)]
pub(super) struct FilterParts {
    pub(super) a: DMatrix<f64>,
    pub(super) b: DMatrix<f64>,
    pub(super) c: DMatrix<f64>,
}

/// A system and its random input in the time-varying white-noise-driven form (see the module docs of
/// [`crate::transient`]): the states are z = \[filter states; system states\].
///
/// # Formula
/// With the frozen system ẋ = Ax + Bu + f, y = Cx + Du + Eu̇ at t, u = a(M_u + s):
/// ```text
/// white s (E ss = 2πS₀δ):   F = A,  G = a√(2πS₀) B,  H = C                 (D or E ≠ 0: σ_y = ∞)
/// filtered s = C_f z_f:     F = [[A_f, 0], [aBC_f, A]],  G = [B_f; 0],
///                           H = [aDC_f + E(ȧC_f + aC_fA_f), C]            (E C_f B_f ≠ 0: σ_y = ∞)
///   temporal filter: A_f, B_f constant;  spatial filter under v(t): A_f = vA_x, B_f = √v B_x
/// w = 2 road (u̇ white, S₀ = c v):  x̃ = x + A⁻¹Bu,  F = A,  G = √(2πcv) A⁻¹B,  H = C
///                           (outputs with H(0) = D − CA⁻¹B ≠ 0 follow the Brownian elevation: unbounded)
/// b = [0; aBM_u + f],  y₀ = (aD + ȧE)M_u
/// ```
#[derive(Clone)]
pub struct TimeVaryingSystem {
    family: Arc<dyn SystemFamily>,
    input: TransientInput,
    filter: Option<FilterParts>,
    extra: Vec<(ExtraSource, Option<FilterParts>)>,
    n_system: usize,
    outputs: Vec<OutputInfo>,
    unavailable: Vec<Option<String>>,
    knots: Vec<f64>,
    invariant: bool,
    /// A⁻¹B of a w = 2 road (its system is time-invariant): solved once, not at every frozen time.
    slope_gain: Option<DMatrix<f64>>,
    /// The model of a constant family and its inputs combined with the gains: built once, not at every
    /// frozen time.
    constant: Option<Combined>,
    /// F, b, H constant and GGᵀ = κ(t)·ḠḠᵀ with κ linear between knots (None: not of that structure, or
    /// invariant).
    affine: Option<AffineNoise>,
}

/// A model at one time and its state space with the inputs combined with the input's gains.
#[derive(Debug, Clone)]
struct Combined {
    model: ModelAt,
    ss: StateSpace,
}

impl std::fmt::Debug for TimeVaryingSystem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TimeVaryingSystem")
            .field("family", &self.family.describe())
            .field("input", &self.input)
            .field("outputs", &self.outputs)
            .finish()
    }
}

fn filter_parts(f: &ShapingFilter) -> Result<FilterParts> {
    let tf = TransferFunction::new(f.num.clone(), f.den.clone(), OutputInfo::new("s", "-"))?;
    let ss = tf.state_space().cloned().ok_or_else(|| Error::Numerical {
        what: "shaping filter".into(),
        reason: "no state space".into(),
    })?;
    if ss.d.iter().any(|v| *v != 0.0) {
        return Err(Error::Divergent {
            quantity: "variance of the input".into(),
            reason: "the input spectrum does not decay at high frequency (a white component): no finite \
                     shaping filter state"
                .into(),
        });
    }
    Ok(FilterParts {
        a: ss.a.clone(),
        b: ss.b.clone(),
        c: ss.c.clone(),
    })
}

impl TimeVaryingSystem {
    /// The time-varying form of `family` driven by `input`.
    ///
    /// # Errors
    /// Gains that do not match the system's inputs; a filter with a white component; a w = 2 road on a
    /// scheduled system or on one with a free rigid-body mode (singular A); a model error at t = 0.
    pub fn new(family: Arc<dyn SystemFamily>, input: TransientInput) -> Result<Self> {
        Self::with_sources(family, input, Vec::new())
    }

    /// The time-varying form of `family` driven by `input` and the independent `extra` sources, their
    /// filters block-diagonal ahead of the system ([`super::sources`]); the envelope is the first input's.
    ///
    /// # Errors
    /// Those of [`TimeVaryingSystem::new`]; a w = 2 road (white road velocity) among several sources (it is
    /// exact only as the one input); gains of an extra source that do not match the system's inputs.
    pub fn with_sources(family: Arc<dyn SystemFamily>, input: TransientInput, extra: Vec<ExtraSource>) -> Result<Self> {
        let model0 = family.at(0.0).map_err(|e| at_time(e, 0.0))?;
        let ss0 = model0.ss.clone();
        if !extra.is_empty() {
            check_model(&input.model)?;
        }
        let extra = extra
            .into_iter()
            .map(|x| extra_parts(x, ss0.b.ncols()))
            .collect::<Result<Vec<_>>>()?;
        if input.gains.len() != ss0.b.ncols() {
            return Err(Error::invalid(
                "gains",
                input.gains.len(),
                format!("the system has {} inputs", ss0.b.ncols()),
            ));
        }
        let filter = match &input.model {
            InputModel::Rational { filter } | InputModel::SpatialRational { filter, .. } => Some(filter_parts(filter)?),
            InputModel::White { density } if !(density.is_finite() && *density >= 0.0) => {
                return Err(Error::invalid(
                    "density",
                    density,
                    "a white-noise density is finite and >= 0",
                ));
            }
            _ => None,
        };
        let speed = speed_of(&input.model);
        if matches!(input.model, InputModel::WhiteSlope { .. }) {
            if !family.is_constant() {
                return Err(Error::NotApplicable {
                    method: "exact route for a w = 2 road".into(),
                    reason: "the relative coordinates x + A⁻¹Bu need a time-invariant system; a scheduled system \
                             on this road: use Monte Carlo"
                        .into(),
                });
            }
            if !input.envelope.is_unit() {
                return Err(Error::NotApplicable {
                    method: "exact route for a w = 2 road".into(),
                    reason: "the elevation of a w = 2 road is not a stationary process that an envelope could \
                             modulate; put the envelope on a road with a band-limited (rational) spectrum"
                        .into(),
                });
            }
        }
        let mut knots: Vec<f64> = family.knots();
        knots.extend(input.envelope.knots());
        let speeds: Vec<&SpeedProfile> = speed
            .into_iter()
            .chain(extra.iter().filter_map(|(x, _)| speed_of(&x.model)))
            .collect();
        for v in &speeds {
            knots.extend(v.knots());
        }
        knots.retain(|t| *t > 0.0);
        knots.sort_by(f64::total_cmp);
        knots.dedup();
        let invariant =
            family.is_constant() && input.envelope.is_unit() && speeds.iter().all(|v| v.table_points().is_constant());
        let combined = ss0.combine_inputs(&input.gains)?;
        let slope_gain = match input.model {
            InputModel::WhiteSlope { .. } => Some(slope_gain(&combined, 0.0)?),
            _ => None,
        };
        let constant = family.is_constant().then(|| Combined {
            model: model0,
            ss: combined.clone(),
        });
        let mut unavailable = unavailable_outputs(&combined, &input.model, filter.as_ref())?;
        for (x, fp) in &extra {
            let more = unavailable_outputs(&ss0.combine_inputs(&x.gains)?, &x.model, fp.as_ref())?;
            for (u, m) in unavailable.iter_mut().zip(more) {
                *u = u.take().or(m);
            }
        }
        let mut sys = TimeVaryingSystem {
            n_system: ss0.n_states(),
            outputs: ss0.outputs().to_vec(),
            family,
            input,
            filter,
            extra,
            unavailable,
            knots,
            invariant,
            slope_gain,
            constant,
            affine: None,
        };
        sys.affine = sys.affine_structure()?;
        Ok(sys)
    }

    /// The affine-intensity structure of the system, read from the kind of input: a constant family with
    /// one source, either a w = 2 road (κ = v(t)) or white noise with zero mean under an intensity envelope
    /// (κ = e(t)); see [`AffineNoise`]. None for an invariant system and for every other structure (an
    /// amplitude envelope makes a² quadratic between knots; a mean under an intensity envelope makes b ∝ √e;
    /// a filtered input puts a(t) or v(t) into F).
    ///
    /// # Errors
    /// The model's error at t = 0.
    fn affine_structure(&self) -> Result<Option<AffineNoise>> {
        if self.invariant || !self.extra.is_empty() || self.constant.is_none() {
            return Ok(None);
        }
        let (g, factor) = match (&self.input.model, &self.slope_gain) {
            (InputModel::WhiteSlope { coefficient, speed }, Some(aib)) => {
                (aib * (2.0 * PI * coefficient).sqrt(), speed.table_points().clone())
            }
            (InputModel::White { density }, _) if self.input.envelope.is_intensity() && self.input.mean == 0.0 => {
                let ss = &self.constant.as_ref().expect("checked above").ss;
                (
                    &ss.b * (2.0 * PI * density).sqrt(),
                    self.input.envelope.points().clone(),
                )
            }
            _ => return Ok(None),
        };
        let mut unit = self.frozen(0.0)?;
        unit.g = g;
        Ok(Some(AffineNoise { unit, factor }))
    }

    /// Number of states n (filter states first).
    pub fn n_states(&self) -> usize {
        self.n_filter() + self.n_system
    }

    /// Number of filter states.
    pub fn n_filter(&self) -> usize {
        let extra: usize = self
            .extra
            .iter()
            .map(|(_, f)| f.as_ref().map_or(0, |f| f.a.nrows()))
            .sum();
        self.filter.as_ref().map_or(0, |f| f.a.nrows()) + extra
    }

    /// The independent sources besides [`TimeVaryingSystem::input`].
    pub fn extra_sources(&self) -> impl Iterator<Item = &ExtraSource> {
        self.extra.iter().map(|(x, _)| x)
    }

    /// The outputs.
    pub fn outputs(&self) -> &[OutputInfo] {
        &self.outputs
    }

    /// Why output i has no finite σ(t) (None: it has one).
    pub fn unavailable(&self, i: usize) -> Option<&str> {
        self.unavailable.get(i).and_then(|u| u.as_deref())
    }

    /// Times where a coefficient has a kink (steps of the exact route end there).
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Whether no coefficient depends on time.
    pub fn is_invariant(&self) -> bool {
        self.invariant
    }

    /// The affine-intensity structure ([`AffineNoise`]: F, b, H constant, GGᵀ = κ(t)·ḠḠᵀ with κ linear
    /// between knots), if the system has it and is not invariant.
    pub fn affine_noise(&self) -> Option<&AffineNoise> {
        self.affine.as_ref()
    }

    /// The input.
    pub fn input(&self) -> &TransientInput {
        &self.input
    }

    /// The family.
    pub fn family(&self) -> &Arc<dyn SystemFamily> {
        &self.family
    }

    /// One line: the model, its schedules and the input.
    pub fn describe(&self) -> String {
        let inp = match &self.input.model {
            InputModel::White { density } => format!("white noise S0 = {density:e}"),
            InputModel::Rational { .. } => "rational input (shaping filter)".to_string(),
            InputModel::SpatialRational { .. } => "rational road under v(t)".to_string(),
            InputModel::WhiteSlope { coefficient, .. } => format!("w = 2 road, S(Omega) = {coefficient:e}/Omega^2"),
        };
        let env = if self.input.envelope.is_unit() {
            ""
        } else {
            ", enveloped"
        };
        let more = match self.extra.len() {
            0 => String::new(),
            k => format!(" + {k} more independent input(s)"),
        };
        format!("{}; {inp}{env}{more}", self.family.describe())
    }

    /// The frozen form at time t.
    ///
    /// # Errors
    /// The model's error at t (with the time).
    pub fn frozen(&self, t: f64) -> Result<Frozen> {
        let at = self.combined_at(t)?;
        let (m, ss) = (&at.model, &at.ss);
        if !self.extra.is_empty() {
            return self.frozen_several(&m.ss, m.forcing.clone(), t);
        }
        let (a, ad, mu) = (
            self.input.envelope.value(t),
            self.input.envelope.slope(t),
            self.input.mean,
        );
        let forcing = m.forcing.clone().unwrap_or_else(|| DVector::zeros(self.n_system));
        let y0 = (&ss.d * a + &ss.e * ad).column(0) * mu;
        let bx = ss.b.column(0) * (a * mu) + forcing;
        match (&self.input.model, &self.filter) {
            (InputModel::White { density }, _) => Ok(Frozen {
                f: ss.a.clone(),
                g: &ss.b * (a * (2.0 * PI * density).sqrt()),
                b: bx,
                h: ss.c.clone(),
                y0,
            }),
            (InputModel::WhiteSlope { coefficient, speed }, _) => {
                let aib = match &self.slope_gain {
                    Some(g) => g.clone(),
                    None => slope_gain(ss, t)?,
                };
                let q = 2.0 * PI * coefficient * speed.speed(t);
                Ok(Frozen {
                    f: ss.a.clone(),
                    g: aib * q.sqrt(),
                    b: bx,
                    h: ss.c.clone(),
                    y0: DVector::zeros(ss.c.nrows()),
                })
            }
            (model, Some(fp)) => {
                let v = match model {
                    InputModel::SpatialRational { speed, .. } => speed.speed(t),
                    _ => 1.0,
                };
                Ok(self.filtered(ss, fp, v, a, ad, bx, y0))
            }
            (_, None) => Err(Error::Numerical {
                what: "transient system".into(),
                reason: "a filtered input without its filter".into(),
            }),
        }
    }

    /// The model at t and its inputs combined with the gains (a constant family's, built once, borrowed).
    ///
    /// # Errors
    /// The model's error at t (with the time).
    fn combined_at(&self, t: f64) -> Result<Cow<'_, Combined>> {
        if let Some(c) = &self.constant {
            return Ok(Cow::Borrowed(c));
        }
        let model = self.family.at(t).map_err(|e| at_time(e, t))?;
        let ss = model.ss.combine_inputs(&self.input.gains)?;
        Ok(Cow::Owned(Combined { model, ss }))
    }

    /// The frozen form with several independent sources ([`frozen_blocks`]).
    fn frozen_several(&self, ss: &StateSpace, forcing: Option<DVector<f64>>, t: f64) -> Result<Frozen> {
        let first = Block {
            model: &self.input.model,
            filter: self.filter.as_ref(),
            gains: &self.input.gains,
            mean: self.input.mean,
            a: self.input.envelope.value(t),
            ad: self.input.envelope.slope(t),
        };
        let blocks: Vec<Block> = std::iter::once(first)
            .chain(self.extra.iter().map(|(x, fp)| Block {
                model: &x.model,
                filter: fp.as_ref(),
                gains: &x.gains,
                mean: x.mean,
                a: 1.0,
                ad: 0.0,
            }))
            .collect();
        let forcing = forcing.unwrap_or_else(|| DVector::zeros(self.n_system));
        frozen_blocks(ss, &blocks, forcing, t)
    }

    /// The frozen form with the input filter ahead of the system (see the type's formula).
    #[allow(clippy::too_many_arguments)]
    fn filtered(
        &self,
        ss: &StateSpace,
        fp: &FilterParts,
        v: f64,
        a: f64,
        ad: f64,
        bx: DVector<f64>,
        y0: DVector<f64>,
    ) -> Frozen {
        let (nf, ns, p) = (fp.a.nrows(), self.n_system, ss.c.nrows());
        let af = &fp.a * v;
        let n = nf + ns;
        let mut f = DMatrix::zeros(n, n);
        f.view_mut((0, 0), (nf, nf)).copy_from(&af);
        f.view_mut((nf, 0), (ns, nf)).copy_from(&(&ss.b * &fp.c * a));
        f.view_mut((nf, nf), (ns, ns)).copy_from(&ss.a);
        let mut g = DMatrix::zeros(n, 1);
        g.view_mut((0, 0), (nf, 1)).copy_from(&(&fp.b * v.sqrt()));
        let mut h = DMatrix::zeros(p, n);
        h.view_mut((0, 0), (p, nf))
            .copy_from(&(&ss.d * &fp.c * a + &ss.e * (&fp.c * ad + &fp.c * &af * a)));
        h.view_mut((0, nf), (p, ns)).copy_from(&ss.c);
        let mut b = DVector::zeros(n);
        b.rows_mut(nf, ns).copy_from(&bx);
        Frozen { f, g, b, h, y0 }
    }

    /// The mean and covariance of the states at t = 0 for `start`.
    ///
    /// # Errors
    /// A stationary start of a system that is not stable at t = 0 (no stationary state: start from rest);
    /// a stated state of the wrong length.
    pub fn start(&self, start: &Start) -> Result<(DMatrix<f64>, DVector<f64>)> {
        let n = self.n_states();
        let fr = self.frozen(0.0)?;
        match start {
            Start::Rest => Ok((DMatrix::zeros(n, n), DVector::zeros(n))),
            Start::Stationary => stationary(&fr, "the system"),
            Start::State(x0) => {
                if x0.len() != self.n_system {
                    return Err(Error::invalid(
                        "state",
                        x0.len(),
                        format!("the model has {} states (positions, then velocities)", self.n_system),
                    ));
                }
                let nf = self.n_filter();
                let mut p = DMatrix::zeros(n, n);
                if nf > 0 {
                    let sub = Frozen {
                        f: fr.f.view((0, 0), (nf, nf)).into_owned(),
                        g: fr.g.rows(0, nf).into_owned(),
                        b: DVector::zeros(nf),
                        h: DMatrix::zeros(0, nf),
                        y0: DVector::zeros(0),
                    };
                    if crate::linalg::is_stable(&sub.f) {
                        p.view_mut((0, 0), (nf, nf))
                            .copy_from(&stationary(&sub, "the input filter")?.0);
                    }
                }
                let mut m = DVector::zeros(n);
                m.rows_mut(nf, self.n_system).copy_from(&DVector::from_column_slice(x0));
                Ok((p, m))
            }
        }
    }
}

/// The speed profile of a road process.
fn speed_of(model: &InputModel) -> Option<&SpeedProfile> {
    match model {
        InputModel::SpatialRational { speed, .. } | InputModel::WhiteSlope { speed, .. } => Some(speed),
        _ => None,
    }
}

/// An extra source checked against the system's `m` inputs, with its filter.
fn extra_parts(x: ExtraSource, m: usize) -> Result<(ExtraSource, Option<FilterParts>)> {
    check_model(&x.model)?;
    if x.gains.len() != m {
        return Err(Error::invalid(
            "gains",
            x.gains.len(),
            format!("the system has {m} inputs"),
        ));
    }
    let fp = match &x.model {
        InputModel::Rational { filter } | InputModel::SpatialRational { filter, .. } => Some(filter_parts(filter)?),
        _ => None,
    };
    Ok((x, fp))
}

/// A⁻¹B of the frozen system at t (the gain of the relative coordinates x + A⁻¹Bu of a w = 2 road).
///
/// # Errors
/// A singular A (a free rigid-body mode), naming t.
fn slope_gain(ss: &StateSpace, t: f64) -> Result<DMatrix<f64>> {
    ss.a.clone().lu().solve(&ss.b).ok_or_else(|| singular(t))
}

fn singular(t: f64) -> Error {
    Error::NotApplicable {
        method: "exact route for a w = 2 road".into(),
        reason: format!(
            "A is singular at t = {t} s (a free rigid-body mode): the relative coordinates x + A⁻¹Bu do not exist"
        ),
    }
}

/// The stationary covariance and mean of a frozen form: F P + P Fᵀ + GGᵀ = 0, F m + b = 0.
fn stationary(fr: &Frozen, what: &str) -> Result<(DMatrix<f64>, DVector<f64>)> {
    if !crate::linalg::is_stable(&fr.f) {
        return Err(Error::NotApplicable {
            method: "stationary start".into(),
            reason: format!(
                "{what} is not asymptotically stable at t = 0 (a standing vehicle, a rigid-body mode, a zero \
                 speed): it has no stationary state; start from rest"
            ),
        });
    }
    let p = crate::linalg::solve_continuous_lyapunov(&fr.f, &(&fr.g * fr.g.transpose()))?;
    let m =
        fr.f.clone()
            .lu()
            .solve(&(-&fr.b))
            .unwrap_or_else(|| DVector::zeros(fr.b.len()));
    Ok((p, m))
}

/// Per output, why its variance is not finite (structure of the frozen system at t = 0).
fn unavailable_outputs(ss: &StateSpace, model: &InputModel, fp: Option<&FilterParts>) -> Result<Vec<Option<String>>> {
    let p = ss.c.nrows();
    let scale = |i: usize| ss.c.row(i).amax().max(ss.d.row(i).amax()).max(1e-300);
    let gain0 = match model {
        InputModel::WhiteSlope { .. } => Some(slope_gain(ss, 0.0)?),
        _ => None,
    };
    Ok((0..p)
        .map(|i| {
            let (d, e) = (ss.d[(i, 0)], ss.e[(i, 0)]);
            match model {
                InputModel::White { .. } if d != 0.0 || e != 0.0 => {
                    Some("the output passes the white input directly (D or E ≠ 0): its variance is infinite".into())
                }
                InputModel::Rational { .. } | InputModel::SpatialRational { .. } => fp.and_then(|f| {
                    let cb = (&f.c * &f.b)[(0, 0)];
                    (e * cb != 0.0).then(|| {
                        "the output contains E·u̇ and u̇ has a white component: its variance is infinite".to_string()
                    })
                }),
                InputModel::WhiteSlope { .. } => {
                    let static_gain = d - (ss.c.row(i) * gain0.as_ref().expect("set above"))[(0, 0)];
                    if e != 0.0 {
                        Some("the output contains E·u̇, the white road velocity: its variance is infinite".into())
                    } else if static_gain.abs() > 1e-9 * scale(i) {
                        Some(
                            "the output follows the road elevation (static gain ≠ 0), a Brownian motion on a w = 2 \
                             road: its variance grows without bound; report a relative output (travel, tyre \
                             deflection, force, acceleration)"
                                .into(),
                        )
                    } else {
                        None
                    }
                }
                _ => None,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::ULPS;
    use crate::transient::FixedSystem;

    /// x″ + c x′ + k x = u on a w = 2 road, S_Ω = c_r/Ω², under v(t) = 5 + t m/s up to 15 m/s at t = 10 s.
    ///
    /// # Formula
    /// A = [[0, 1], [−k, −c]], B = [0; 1]: A⁻¹B = [−1/k; 0], so the frozen form at t is F = A,
    /// G = [−1/k; 0]·√(2π c_r v(t)) (the type's formula), whichever times were frozen before.
    #[test]
    fn a_w2_road_frozen_form_is_the_closed_form_at_every_time() {
        let (k, c, cr) = (4.0, 0.3, 2.5e-6);
        let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -k, -c]);
        let ss = StateSpace::new(
            a.clone(),
            DMatrix::from_row_slice(2, 1, &[0.0, 1.0]),
            DMatrix::from_row_slice(1, 2, &[1.0, 0.0]),
            None,
            None,
            vec![OutputInfo::new("x", "m")],
        )
        .unwrap();
        let speed = SpeedProfile::table(vec![0.0, 10.0], vec![5.0, 15.0]).unwrap();
        let input = TransientInput {
            model: InputModel::WhiteSlope { coefficient: cr, speed },
            envelope: Envelope::unit(),
            mean: 0.0,
            gains: vec![1.0],
        };
        let sys = TimeVaryingSystem::new(Arc::new(FixedSystem::new(ss, None, "oscillator").unwrap()), input).unwrap();
        for t in [2.0, 0.0, 7.5, 2.0, 20.0] {
            let fr = sys.frozen(t).unwrap();
            let v = (5.0 + t).min(15.0);
            let g = -(2.0 * PI * cr * v).sqrt() / k;
            assert_eq!(fr.f, a, "F = A at t = {t}");
            assert!(
                // a few roundings on each side (2π c_r v, √, the LU's −1/k, one product): the shared ULPS bound
                (fr.g[(0, 0)] - g).abs() <= ULPS * g.abs(),
                "G₀ at t = {t}: {}",
                fr.g[(0, 0)]
            );
            assert_eq!(fr.g[(1, 0)], 0.0, "G₁ at t = {t}");
        }
    }
}
