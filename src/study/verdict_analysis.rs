//! The analytic verdicts of a scenario: ISO 2631-1 weighted accelerations per axis (exactly, by the
//! Lyapunov covariance of the system augmented with the input's shaping filter and the weighting filter,
//! and by quadrature of the weighted output density, both shown and compared), the vector sum a_v, the
//! daily exposure A(8) and VDV against Directive 2002/44/EC (always with the health factors 1.4·a_wx,
//! 1.4·a_wy, a_wz, beside the evaluation of the scenario's purpose), and the spectral fatigue damage and life of a
//! stress output by every method, with the moments used.

use crate::comfort::{
    comfort_reactions, daily_exposure_a8, directive_factor, msdv, vdv_gaussian, weighted_output, Axis, AxisFactor,
    ComfortReaction, ExposureVerdict, HealthGuidanceZone, Location, Purpose, VectorSumTerm, Weighting,
};
use crate::error::{Error, Result};
use crate::fatigue::{compare_methods, SpectralMoments, TwoSidedAngularMoments};
use crate::response::{
    analyze_output_with, spectral_moment_quadrature, Excitation, OutputDensity, ResponseStatistics, VarianceMethod,
};
use crate::scenario::verdict_spec::{ComfortAxisSpec, ComfortSpec, FatigueSpec};
use crate::scenario::Scenario;
use crate::system::FrequencyResponse;
use serde::Serialize;
use std::f64::consts::PI;

/// One weighted axis.
#[derive(Debug, Clone, Serialize)]
pub struct ComfortAxisResult {
    /// The weighted output's name (`<output>_<W>`).
    pub output: String,
    /// Location.
    pub location: Location,
    /// Axis.
    pub axis: Axis,
    /// Weighting.
    pub weighting: Weighting,
    /// Multiplying factor k.
    pub k: f64,
    /// a_w by the Lyapunov route (exact; `None` where it does not apply), m/s².
    pub a_w_lyapunov: Option<f64>,
    /// a_w by quadrature of the weighted output density, m/s².
    pub a_w_quadrature: Option<f64>,
    /// |a_w,quad/a_w,Lyap − 1|.
    pub rel_diff: Option<f64>,
    /// The a_w used (the exact one where available), m/s².
    pub a_w: f64,
    /// k·a_w, m/s².
    pub weighted: f64,
    /// A(8) of this axis alone, k·a_w·√(T/8 h), m/s².
    pub a8: f64,
    /// VDV of this axis for the stationary Gaussian response, (3T)^{1/4}·k·a_w, m/s^1.75.
    pub vdv: f64,
    /// For a Wf (motion sickness) axis: the motion sickness dose value over the exposure T,
    /// MSDV = (∫₀ᵀ a_w² dt)^{1/2} = a_w·√T for the stationary response (ISO 2631-1:1997 clause 9.2; k is
    /// not applied), m/s^1.5; `None` for the other weightings.
    pub msdv: Option<f64>,
    /// Every variance method of the weighted output (value, agreement, why missing).
    pub statistics: ResponseStatistics,
    /// When the input stops below the weighting's band: the covered fraction and a_w with the input's power
    /// law continued ([`super::input_coverage`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub input_coverage: Option<super::input_coverage::InputCoverage>,
}

/// `[analysis.comfort]` answered.
#[derive(Debug, Clone, Serialize)]
pub struct ComfortVerdict {
    /// Health or comfort: the factors k of `axes` and `a_v`.
    pub purpose: Purpose,
    /// Daily exposure T, s.
    pub exposure_s: f64,
    /// One row per axis, with the purpose's factors k (their `a8` and `vdv` too; the Directive's values are
    /// those of `health`).
    pub axes: Vec<ComfortAxisResult>,
    /// a_v = √(Σ k² a_w²) with the purpose's factors, m/s² (for comfort: the overall vibration total value).
    pub a_v: f64,
    /// The axis with the largest k·a_w with the purpose's factors.
    pub dominant: String,
    /// ISO 2631-1 Annex C reactions to a_v (purpose comfort; empty for health).
    pub comfort_reactions: Vec<ComfortReaction>,
    /// The Directive 2002/44/EC and ISO 2631-1 Annex B evaluation, always with the health factors
    /// 1.4·a_wx, 1.4·a_wy, a_wz ([`directive_factor`]); `None` when no axis enters it (`health_note` says why).
    pub health: Option<HealthEvaluation>,
    /// Why there is no health evaluation, if there is none.
    pub health_note: Option<String>,
    /// For a non-Gaussian input (`kurtosis`): the inputs' kurtosis as written. The VDV values above are
    /// then those of a Gaussian input with the same spectrum and do not hold (E a_w⁴ = κ_w σ_w⁴ with the
    /// weighted output's own kurtosis κ_w); a Monte Carlo run states the predicted (κ_w T)^{1/4}σ_w.
    pub non_gaussian_input: Option<String>,
}

/// One axis of the Directive / health evaluation.
#[derive(Debug, Clone, Serialize)]
pub struct HealthAxisResult {
    /// The weighted output's name (`<output>_<W>`).
    pub output: String,
    /// Location, axis, the health weighting (Wd for x, y; Wk for z) and factor (1.4 for x, y; 1 for z), a_w
    /// with that weighting and k·a_w (m/s²).
    #[serde(flatten)]
    pub term: VectorSumTerm,
    /// A(8) = k·a_w·√(T/8 h), m/s².
    pub a8: f64,
    /// VDV = (3T)^{1/4}·k·a_w (stationary Gaussian), m/s^1.75.
    pub vdv: f64,
}

/// The Directive 2002/44/EC A(8) and VDV and the ISO 2631-1 Annex B zones, with the health factors whatever
/// the purpose of `[analysis.comfort]`.
#[derive(Debug, Clone, Serialize)]
pub struct HealthEvaluation {
    /// The factors, as the Directive writes them.
    pub factors: String,
    /// The axes that enter (seat surface, or the floor of a standing worker: x, y, z).
    pub axes: Vec<HealthAxisResult>,
    /// The axis with the largest k·a_w: A(8) and VDV are those of this axis.
    pub dominant: String,
    /// A(8) and VDV of the dominant axis against the action and limit values and the Annex B zones.
    pub verdict: ExposureVerdict,
    /// What the reader must know (e.g. axes left out, Annex B for seated persons).
    pub notes: Vec<String>,
}

/// One spectral method's answer.
#[derive(Debug, Clone, Serialize)]
pub struct FatigueMethodResult {
    /// Method name with its reference.
    pub method: String,
    /// Damage rate, 1/s.
    pub damage_rate: f64,
    /// Life 1/rate, s.
    pub life_s: f64,
    /// Life / design life (≥ 1 passes), if a design life is given.
    pub safety_factor: Option<f64>,
}

/// `[analysis.fatigue]` answered.
#[derive(Debug, Clone, Serialize)]
pub struct FatigueVerdict {
    /// The output.
    pub output: String,
    /// Stress per unit of the output.
    pub stress_factor: f64,
    /// The S–N curve.
    pub sn_curve: String,
    /// One-sided Hz moments of the stress m₀, m₁, m₂, m₄ (Pa², Pa²·Hz, Pa²·Hz², Pa²·Hz⁴), as used: λ₀, λ₂,
    /// λ₄ by the exact route where it applies, λ₁ by quadrature.
    pub moments: [f64; 4],
    /// How the moments were obtained.
    pub moments_method: String,
    /// The same moments all by quadrature of the output density (a check), if they converged.
    pub moments_quadrature: Option<[f64; 4]>,
    /// Largest relative difference between the two moment sets.
    pub moments_rel_diff: Option<f64>,
    /// Irregularity factors α₁, α₂ and the bandwidth ε.
    pub alpha1: f64,
    /// α₂ = m₂/√(m₀m₄).
    pub alpha2: f64,
    /// Rate of peaks ν_p = √(m₄/m₂), 1/s.
    pub nu_peak: f64,
    /// One row per method.
    pub methods: Vec<FatigueMethodResult>,
    /// Longest life / shortest life over the methods.
    pub spread: f64,
    /// Design life, s, if given.
    pub design_life_s: Option<f64>,
    /// How the design life was given.
    pub design_life_text: Option<String>,
    /// Every method's life ≥ the design life (`None` without a design life).
    pub passes: Option<bool>,
    /// When the input stops below 10 × the model's fastest natural frequency: the moments with the
    /// input's power law continued there ([`super::input_coverage::moment_coverage`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub input_coverage: Option<super::input_coverage::MomentCoverage>,
}

/// Both verdicts of a scenario.
#[derive(Debug, Clone, Serialize, Default)]
pub struct VerdictAnalysis {
    /// Comfort / exposure.
    pub comfort: Option<ComfortVerdict>,
    /// Fatigue.
    pub fatigue: Option<FatigueVerdict>,
    /// The SEAT value of `[analysis.seat_factor]`.
    pub seat_factor: Option<super::seat_factor::SeatFactorResult>,
}

/// The verdicts of `[analysis.comfort]` and `[analysis.fatigue]` of a scenario (empty without them).
///
/// # Formula
/// a_w = σ of W(s)·H_i(s) ([`weighted_output`]) by every variance method ([`analyze_output_with`]); per
/// axis A(8) = k a_w √(T/T₀), T₀ = 8 h, VDV = (3T)^{1/4} k a_w (stationary Gaussian response, ISO 2631-1
/// 6.3.2 note) with the purpose's factors k; a_v = √(Σ kᵢ² a_wᵢ²) (ISO 2631-1 (9)); the Directive's A(8) and
/// VDV and the Annex B zones are those of the dominant axis with the *health* factors whatever the purpose
/// (Directive 2002/44/EC Annex B 1: the highest of 1.4a_wx, 1.4a_wy, a_wz; [`directive_factor`]).
/// Fatigue: stress = s·y, m_j = s² (2π)^{−j} λ_j ([`TwoSidedAngularMoments`]), each
/// method's damage rate ([`compare_methods`]), life = 1/rate.
///
/// # Errors
/// [`Error::File`] naming the scenario key when an axis' weighted output or the fatigue moments cannot be
/// computed (a divergent λ₄, say); the errors of the fatigue methods.
pub fn verdict_analysis(sc: &Scenario) -> Result<VerdictAnalysis> {
    let spec = &sc.analysis.verdicts;
    let comfort = match &spec.comfort {
        Some(c) => Some(comfort_verdict(sc, c)?),
        None => None,
    };
    let fatigue = match &spec.fatigue {
        Some(f) => Some(fatigue_verdict(sc, f)?),
        None => None,
    };
    let seat_factor = match &spec.seat_factor {
        Some(s) => Some(super::seat_factor::seat_factor(sc, s)?),
        None => None,
    };
    Ok(VerdictAnalysis {
        comfort,
        fatigue,
        seat_factor,
    })
}

/// a_w of an already weighted system `ws` under the scenario's input: (the exact value where available, by
/// Lyapunov, by quadrature); errors name `key` and `name`.
pub(crate) fn weighted_rms_pair(
    sc: &Scenario,
    ws: &crate::system::StateSpace,
    key: &str,
    name: &str,
) -> Result<(f64, Option<f64>, Option<f64>)> {
    let st = analyze_output_with(ws, &sc.excitation, 0, &sc.analysis.effort)?;
    let a_w = st.sigma.ok_or_else(|| {
        file_error(
            sc,
            key,
            name,
            Error::Numerical {
                what: format!("weighted r.m.s. of `{name}`"),
                reason: st.variance_outcome.describe(),
            },
        )
    })?;
    let value = |m: &[VarianceMethod]| {
        (st.methods.iter())
            .find(|v| m.contains(&v.method))
            .and_then(|v| v.value())
            .map(f64::sqrt)
    };
    let lyap = value(&[VarianceMethod::Lyapunov, VarianceMethod::LyapunovDelays]);
    Ok((a_w, lyap, value(&[VarianceMethod::Quadrature])))
}

fn file_error(sc: &Scenario, key: &str, value: &str, e: Error) -> Error {
    Error::File {
        file: sc.path.clone(),
        key: key.into(),
        value: value.into(),
        reason: e.to_string(),
    }
}

/// The weighted output of `output` under `w`, its statistics and its a_w (the exact value where available).
fn weighted_rms(
    sc: &Scenario,
    ss: &crate::system::StateSpace,
    output: (usize, &str),
    w: &Weighting,
    key: &str,
) -> Result<(crate::system::StateSpace, ResponseStatistics, f64)> {
    let ws = weighted_output(ss, output.0, w).map_err(|e| file_error(sc, key, output.1, e))?;
    let st = analyze_output_with(&ws, &sc.excitation, 0, &sc.analysis.effort)?;
    let name = ws.outputs()[0].name.clone();
    let a_w = st.sigma.ok_or_else(|| {
        file_error(
            sc,
            key,
            output.1,
            Error::Numerical {
                what: format!("weighted r.m.s. of `{name}`"),
                reason: st.variance_outcome.describe(),
            },
        )
    })?;
    Ok((ws, st, a_w))
}

fn comfort_axis(
    sc: &Scenario,
    ss: &crate::system::StateSpace,
    j: usize,
    a: &ComfortAxisSpec,
    t: f64,
) -> Result<ComfortAxisResult> {
    let key = format!("analysis.comfort.axis[{j}].output");
    let (ws, st, a_w) = weighted_rms(sc, ss, (a.output, &a.output_name), &a.weighting, &key)?;
    let names = super::input_coverage::source_names(sc);
    let input_coverage =
        super::input_coverage::input_coverage(&ws, &sc.excitation, a.weighting, a_w, &sc.analysis.effort, &names)
            .map_err(|e| file_error(sc, &key, &a.output_name, e))?;
    let value = |m: &[VarianceMethod]| {
        st.methods
            .iter()
            .find(|v| m.contains(&v.method))
            .and_then(|v| v.value())
            .map(f64::sqrt)
    };
    let lyap = value(&[VarianceMethod::Lyapunov, VarianceMethod::LyapunovDelays]);
    let quad = value(&[VarianceMethod::Quadrature]);
    let weighted = a.k * a_w;
    Ok(ComfortAxisResult {
        input_coverage,
        output: ws.outputs()[0].name.clone(),
        location: a.location,
        axis: a.axis,
        weighting: a.weighting,
        k: a.k,
        a_w_lyapunov: lyap,
        a_w_quadrature: quad,
        rel_diff: match (lyap, quad) {
            (Some(l), Some(q)) if l > 0.0 => Some((q / l - 1.0).abs()),
            _ => None,
        },
        a_w,
        weighted,
        a8: daily_exposure_a8(weighted, t)?,
        vdv: vdv_gaussian(weighted, t)?,
        msdv: match a.weighting {
            Weighting::Wf => Some(msdv(a_w, t)?),
            _ => None,
        },
        statistics: st,
    })
}

pub(crate) fn comfort_verdict(sc: &Scenario, spec: &ComfortSpec) -> Result<ComfortVerdict> {
    let ss = sc.model.system.state_space().ok_or_else(|| Error::NotApplicable {
        method: "frequency weighting".into(),
        reason: "the model has no state-space form".into(),
    })?;
    let t = spec.exposure_s;
    let axes = (spec.axes.iter().enumerate())
        .map(|(j, a)| comfort_axis(sc, ss, j, a, t))
        .collect::<Result<Vec<_>>>()?;
    // motion sickness (Wf) is judged by its MSDV, not combined with the health and comfort axes (ISO
    // 2631-1:1997 clause 9), unless there is nothing else
    let judged: Vec<&ComfortAxisResult> = match axes.iter().filter(|a| a.weighting != Weighting::Wf).count() {
        0 => axes.iter().collect(),
        _ => axes.iter().filter(|a| a.weighting != Weighting::Wf).collect(),
    };
    let a_v = judged.iter().map(|a| a.weighted * a.weighted).sum::<f64>().sqrt();
    let dom = judged
        .iter()
        .max_by(|x, y| x.weighted.total_cmp(&y.weighted))
        .ok_or_else(|| Error::invalid("analysis.comfort.axis", "[]", "no axis"))?;
    let (health, health_note) = match health_evaluation(sc, ss, spec, &axes)? {
        Ok(h) => (Some(h), None),
        Err(why) => (None, Some(why)),
    };
    let given: Vec<String> = sc
        .inputs
        .iter()
        .filter_map(|i| i.kurtosis.map(|k| format!("{} kurtosis {k}", i.name)))
        .collect();
    Ok(ComfortVerdict {
        non_gaussian_input: (!given.is_empty()).then(|| given.join(", ")),
        purpose: spec.purpose,
        exposure_s: t,
        dominant: dom.output.clone(),
        comfort_reactions: match spec.purpose {
            Purpose::Comfort => comfort_reactions(a_v)?,
            Purpose::Health => Vec::new(),
        },
        axes,
        a_v,
        health,
        health_note,
    })
}

/// The axes that enter the Directive's daily exposure: the translational axes of the seat surface (a seated
/// worker) or, without them, of a standing worker's floor; not the motion-sickness (Wf) rows. Returns the
/// indices into `spec.axes` with their factors, and notes on what was left out.
fn health_axes(spec: &ComfortSpec) -> (Vec<(usize, AxisFactor)>, Vec<String>) {
    let eligible: Vec<(usize, AxisFactor, Location)> = (spec.axes.iter().enumerate())
        .filter(|(_, a)| a.weighting != Weighting::Wf)
        .filter_map(|(j, a)| directive_factor(a.location, a.axis).map(|f| (j, f, a.location)))
        .collect();
    let seated = eligible.iter().any(|e| e.2 == Location::SeatSurface);
    let mut notes = Vec::new();
    if seated && eligible.iter().any(|e| e.2 == Location::StandingFloor) {
        notes.push("standing-floor axes left out: a worker is either seated or standing".to_string());
    }
    if !seated && !eligible.is_empty() {
        notes.push(
            "standing worker: the Directive's values apply; ISO 2631-1 Annex B gives its zones for seated persons"
                .to_string(),
        );
    }
    let chosen = eligible
        .into_iter()
        .filter(|e| (e.2 == Location::SeatSurface) == seated)
        .map(|e| (e.0, e.1))
        .collect();
    (chosen, notes)
}

/// The Directive 2002/44/EC / ISO 2631-1 Annex B evaluation with the health factors ([`directive_factor`]),
/// reusing an axis' a_w where its weighting is the health one; `Err(why)` when no axis enters it.
fn health_evaluation(
    sc: &Scenario,
    ss: &crate::system::StateSpace,
    spec: &ComfortSpec,
    axes: &[ComfortAxisResult],
) -> Result<std::result::Result<HealthEvaluation, String>> {
    let (chosen, mut notes) = health_axes(spec);
    if chosen.is_empty() {
        return Ok(Err(
            "no x, y or z axis of the seat surface or of a standing person's floor: Directive \
                       2002/44/EC and ISO 2631-1 Annex B do not apply to these axes"
                .into(),
        ));
    }
    let t = spec.exposure_s;
    let mut rows = Vec::new();
    for (j, f) in chosen {
        let (a, r) = (&spec.axes[j], &axes[j]);
        let (output, a_w) = if a.weighting == f.weighting {
            (r.output.clone(), r.a_w)
        } else {
            let key = format!("analysis.comfort.axis[{j}].output");
            let (ws, _, a_w) = weighted_rms(sc, ss, (a.output, &a.output_name), &f.weighting, &key)?;
            let name = ws.outputs()[0].name.clone();
            notes.push(format!(
                "{name}: the {} axis weighted with {} for health",
                a.axis.label(),
                f.weighting.name()
            ));
            (name, a_w)
        };
        let weighted = f.k * a_w;
        rows.push(HealthAxisResult {
            output,
            term: VectorSumTerm {
                location: a.location,
                axis: a.axis,
                weighting: f.weighting,
                k: f.k,
                a_w,
                weighted,
            },
            a8: daily_exposure_a8(weighted, t)?,
            vdv: vdv_gaussian(weighted, t)?,
        });
    }
    let dom = (rows.iter().max_by(|x, y| x.term.weighted.total_cmp(&y.term.weighted))).expect("at least one axis");
    let verdict = ExposureVerdict::assess_with(
        dom.a8,
        Some(dom.vdv),
        None,
        &spec.limits,
        &HealthGuidanceZone::ISO_2631_1,
    )?;
    Ok(Ok(HealthEvaluation {
        factors: "1.4·a_wx, 1.4·a_wy, a_wz (Directive 2002/44/EC Annex B 1; ISO 2631-1:1997 7.2.3)".into(),
        dominant: dom.output.clone(),
        axes: rows,
        verdict,
        notes,
    }))
}

/// The one-sided Hz moments of s·y_i: exact λ₀, λ₂, λ₄ where the Lyapunov route applies (else
/// quadrature), λ₁ by quadrature; and the all-quadrature set of the same moments.
///
/// # Formula
/// m_j = s² (2π)^{−j} λ_j, λ_j = ∫|ω|^j S_y dω.
///
/// # Errors
/// [`Error::Divergent`] when λ₄ (or λ₀, λ₂) is infinite; quadrature failures.
#[allow(clippy::type_complexity)]
pub fn stress_moments(
    sys: &dyn FrequencyResponse,
    exc: &Excitation,
    i: usize,
    stress_factor: f64,
    effort: &crate::quad_oscillatory::OscillatoryOptions,
) -> Result<(SpectralMoments, String, Option<[f64; 4]>)> {
    let st = analyze_output_with(sys, exc, i, effort)?;
    let divergent = |what: &str, o: &crate::response::Outcome| Error::Divergent {
        quantity: format!("{what} of `{}`", st.name),
        reason: o.describe(),
    };
    let l0 = st.variance.ok_or_else(|| divergent("variance", &st.variance_outcome))?;
    let l2 = st.lambda2.ok_or_else(|| divergent("λ₂", &st.lambda2_outcome))?;
    let l4 = st.lambda4.ok_or_else(|| divergent("λ₄", &st.lambda4_outcome))?;
    let l1 = spectral_moment_quadrature(sys, exc, i, 1)?.value;
    let s2 = stress_factor * stress_factor;
    let m = TwoSidedAngularMoments {
        lambda0: s2 * l0,
        lambda1: s2 * l1,
        lambda2: s2 * l2,
        lambda4: s2 * l4,
    }
    .build()?;
    let exact = st
        .methods
        .iter()
        .any(|v| matches!(v.method, VarianceMethod::Lyapunov | VarianceMethod::LyapunovDelays) && v.value().is_some());
    let how = if exact {
        "λ0, λ2, λ4 exact (Lyapunov of the augmented system), λ1 by quadrature".to_string()
    } else {
        "λ0, λ1, λ2, λ4 by quadrature of the output density".to_string()
    };
    // all by quadrature of the one-sided Hz density G(f) = 4π S(2πf)
    let quad = OutputDensity::new(sys, exc, i).ok().and_then(|d| {
        SpectralMoments::from_one_sided_hz(|f| s2 * 4.0 * PI * d.density(2.0 * PI * f), 0.0, f64::INFINITY, &[])
            .ok()
            .map(|q| [q.m0(), q.m1(), q.m2(), q.m4()])
    });
    Ok((m, how, quad))
}

/// Why a damage rate of 0 (underflow: the life exceeds the range of f64) or ∞ is not a result.
fn damage_out_of_range(method: &str, rate: f64, m: &SpectralMoments) -> Error {
    let what = if rate == 0.0 {
        "is 0 within the range of f64 (no damage: the life would be infinite)".to_string()
    } else {
        format!(
            "is {rate}, not a finite number (the method's formula fails for these spectral moments, or the stress \
             overflows the S–N curve)"
        )
    };
    Error::NotApplicable {
        method: format!("the fatigue life of {method}"),
        reason: format!(
            "the damage rate {what} for a stress of σ = {} (stress_factor and the S–N curve make no life that \
             can be printed)",
            crate::numbers::num(m.m0().sqrt())
        ),
    }
}

/// The scenario key that names the fatigue output.
const FATIGUE_OUTPUT_KEY: &str = "analysis.fatigue.output";

/// [`stress_moments`] of the `[analysis.fatigue]` output of `sc`, an error naming the file, the key
/// `analysis.fatigue.output` and the output; a divergent moment says that the spectral methods need finite
/// moments up to λ₄ (the rate of peaks).
///
/// # Errors
/// [`Error::File`] with the reason of [`stress_moments`].
pub(crate) fn fatigue_moments(
    sc: &Scenario,
    spec: &FatigueSpec,
) -> Result<(SpectralMoments, String, Option<[f64; 4]>)> {
    stress_moments(
        sc.model.system.as_ref(),
        &sc.excitation,
        spec.output,
        spec.stress_factor,
        &sc.analysis.effort,
    )
    .map_err(|e| {
        let reason = match e {
            e @ Error::Divergent { .. } => {
                format!("{e}: the spectral fatigue methods need finite moments up to λ₄ (the rate of peaks)")
            }
            e => e.to_string(),
        };
        Error::File {
            file: sc.path.clone(),
            key: FATIGUE_OUTPUT_KEY.into(),
            value: spec.output_name.clone(),
            reason,
        }
    })
}

fn fatigue_verdict(sc: &Scenario, spec: &FatigueSpec) -> Result<FatigueVerdict> {
    let key = FATIGUE_OUTPUT_KEY;
    let sys = sc.model.system.as_ref();
    let (m, how, quad) = fatigue_moments(sc, spec)?;
    let input_coverage = super::input_coverage::moment_coverage(
        sys,
        &sc.excitation,
        spec.output,
        spec.stress_factor,
        &m,
        &sc.analysis.effort,
        &super::input_coverage::source_names(sc),
    )
    .map_err(|e| file_error(sc, key, &spec.output_name, e))?;
    let all = compare_methods(&m, &spec.sn)?;
    let chosen = all.estimates.iter().filter(|e| spec.methods.contains(&e.kind));
    if let Some(e) = chosen
        .clone()
        .find(|e| !(e.damage_rate.is_finite() && e.damage_rate > 0.0))
    {
        return Err(file_error(
            sc,
            key,
            &spec.output_name,
            damage_out_of_range(e.name, e.damage_rate, &m),
        ));
    }
    let methods: Vec<FatigueMethodResult> = chosen
        .map(|e| FatigueMethodResult {
            method: e.name.to_string(),
            damage_rate: e.damage_rate,
            life_s: e.life,
            safety_factor: spec.design_life_s.map(|d| e.life / d),
        })
        .collect();
    let lo = methods.iter().map(|e| e.life_s).fold(f64::INFINITY, f64::min);
    let hi = methods.iter().map(|e| e.life_s).fold(0.0, f64::max);
    let used = [m.m0(), m.m1(), m.m2(), m.m4()];
    let moments_rel_diff = quad.map(|q| {
        q.iter()
            .zip(&used)
            .map(|(a, b)| (a / b - 1.0).abs())
            .fold(0.0, f64::max)
    });
    Ok(FatigueVerdict {
        output: spec.output_name.clone(),
        stress_factor: spec.stress_factor,
        sn_curve: spec.sn.describe(),
        moments: used,
        moments_method: how,
        moments_quadrature: quad,
        moments_rel_diff,
        alpha1: m.alpha1(),
        alpha2: m.alpha2(),
        nu_peak: m.nu_peak(),
        passes: spec.design_life_s.map(|d| methods.iter().all(|e| e.life_s >= d)),
        spread: hi / lo,
        methods,
        design_life_s: spec.design_life_s,
        design_life_text: spec.design_life_text.clone(),
        input_coverage,
    })
}
