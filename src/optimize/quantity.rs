//! The quantities an optimisation may minimise, maximise or constrain: the numbers `stochvib analyze`
//! reports for a scenario, named by short text.

use crate::error::{Error, Result};
use crate::response::{ExactEvaluator, PointStatistics};
use crate::scenario::Scenario;
use crate::study::{verdict_analysis, VerdictAnalysis};
use crate::units::{unit_dim, Dim};
use serde::Serialize;

/// What is computed of the scenario.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum QuantityKind {
    /// σ of an output (exact: integral table or Lyapunov), in the output's unit.
    Sigma(String),
    /// 3σ of an output (the half-width of the 3σ bounds about the mean).
    ThreeSigma(String),
    /// |mean| + 3σ of an output: the largest excursion of the 3σ bounds (e.g. travel with a static offset).
    Peak3(String),
    /// a_w of a comfort axis (`[analysis.comfort]`), by its output name, m/s².
    Aw(String),
    /// The vector sum a_v of the comfort axes, m/s².
    Av,
    /// The daily exposure A(8) of the Directive's dominant axis (health factors), m/s².
    A8,
    /// VDV of the Directive's dominant axis, m/s^1.75.
    Vdv,
    /// The largest damage rate over the spectral fatigue methods (`[analysis.fatigue]`), 1/s.
    DamageRate,
    /// The shortest life over the spectral fatigue methods, s.
    Life,
    /// The static compression of a spring element under gravity, m
    /// ([`static_sag`](crate::study::static_sag::static_sag); the kinds whose lengths are vertical).
    StaticSag(String),
}

/// A quantity as the user named it, with the dimension of its values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Quantity {
    /// The text as given, e.g. `sigma(body_acc)`.
    pub text: String,
    /// What it is.
    pub kind: QuantityKind,
    /// Its SI unit as text (for reports).
    pub unit: String,
    /// Its dimension (for limits written with units); `None` when the output's unit is not an SI unit.
    #[serde(skip)]
    pub dim: Option<Dim>,
}

/// The names [`Quantity::parse`] accepts, for error messages.
pub const QUANTITY_FORMS: &str = "sigma(OUTPUT), 3sigma(OUTPUT), peak3(OUTPUT), a_w(OUTPUT), a_v, A8, VDV, \
                                  damage_rate, life, static_sag(ELEMENT)";

impl Quantity {
    /// Parses `text` and checks it against the scenario: the output exists, or the scenario has the
    /// `[analysis.comfort]` / `[analysis.fatigue]` table the quantity needs.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `flag` and the text: an unknown form, an unknown output, a
    /// verdict quantity of a scenario without its table.
    pub fn parse(flag: &str, text: &str, sc: &Scenario) -> Result<Quantity> {
        let bad = |why: String| Error::invalid(flag, text, why);
        let t = text.trim();
        let (head, arg) = match t.split_once('(') {
            Some((h, rest)) => {
                let arg = rest
                    .strip_suffix(')')
                    .ok_or_else(|| bad("a closing `)` is missing".into()))?;
                (h.trim(), Some(arg.trim()))
            }
            None => (t, None),
        };
        let kind = match (head, arg) {
            ("sigma", Some(o)) => QuantityKind::Sigma(o.into()),
            ("3sigma", Some(o)) => QuantityKind::ThreeSigma(o.into()),
            ("peak3", Some(o)) => QuantityKind::Peak3(o.into()),
            ("a_w", Some(o)) => QuantityKind::Aw(o.into()),
            ("a_v", None) => QuantityKind::Av,
            ("A8", None) => QuantityKind::A8,
            ("VDV", None) => QuantityKind::Vdv,
            ("damage_rate", None) => QuantityKind::DamageRate,
            ("life", None) => QuantityKind::Life,
            ("static_sag", Some(e)) => QuantityKind::StaticSag(e.into()),
            _ => return Err(bad(format!("unknown quantity; the quantities are {QUANTITY_FORMS}"))),
        };
        let unit = unit_of(&kind, sc).map_err(bad)?;
        Ok(Quantity {
            text: t.to_string(),
            dim: unit_dim(&unit),
            kind,
            unit,
        })
    }

    /// The value of the quantity for scenario `sc` (SI).
    ///
    /// # Errors
    /// The evaluator's errors; an infinite variance, a missing verdict.
    pub fn value(&self, sc: &Scenario) -> Result<f64> {
        let none = |why: &str| Error::Numerical {
            what: self.text.clone(),
            reason: why.to_string(),
        };
        match &self.kind {
            QuantityKind::Sigma(o) | QuantityKind::ThreeSigma(o) | QuantityKind::Peak3(o) => {
                let i = sc.model.system.output_index(o)?;
                let st = ExactEvaluator::new(&sc.excitation).variances_only().evaluate(
                    sc.model.system.as_ref(),
                    &sc.excitation,
                    &[i],
                )?;
                self.of_statistics(&st[0])
            }
            QuantityKind::StaticSag(e) => crate::study::static_sag::static_sag_of(sc, e),
            _ => {
                let v = verdict_analysis(sc)?;
                verdict_value(&self.kind, sc, &v).ok_or_else(|| none("the verdict was not computed"))
            }
        }
    }

    /// The values of `quantities` for scenario `sc` (SI), the verdicts computed once for all of them and
    /// the σ quantities' outputs in one evaluation (one Lyapunov solve on the Lyapunov routes).
    ///
    /// # Errors
    /// As [`value`](Self::value).
    pub fn values(quantities: &[&Quantity], sc: &Scenario) -> Result<Vec<f64>> {
        let verdict = |q: &Quantity| q.output().is_none() && !matches!(q.kind, QuantityKind::StaticSag(_));
        let verdicts = if quantities.iter().any(|q| verdict(q)) {
            Some(verdict_analysis(sc)?)
        } else {
            None
        };
        let sys = sc.model.system.as_ref();
        let outputs = quantities
            .iter()
            .filter_map(|q| q.output())
            .map(|o| sys.output_index(o))
            .collect::<Result<Vec<_>>>()?;
        let stats = if outputs.is_empty() {
            Vec::new()
        } else {
            ExactEvaluator::new(&sc.excitation)
                .variances_only()
                .evaluate(sys, &sc.excitation, &outputs)?
        };
        let mut stats = stats.iter();
        quantities
            .iter()
            .map(|q| match &verdicts {
                Some(v) if verdict(q) => verdict_value(&q.kind, sc, v).ok_or_else(|| Error::Numerical {
                    what: q.text.clone(),
                    reason: "the verdict was not computed".into(),
                }),
                _ if q.output().is_some() => match stats.next() {
                    Some(st) => q.of_statistics(st),
                    None => q.value(sc),
                },
                _ => q.value(sc),
            })
            .collect()
    }

    /// The output whose exact statistics give this quantity (σ, 3σ, peak3), `None` for a verdict quantity.
    pub fn output(&self) -> Option<&str> {
        match &self.kind {
            QuantityKind::Sigma(o) | QuantityKind::ThreeSigma(o) | QuantityKind::Peak3(o) => Some(o),
            _ => None,
        }
    }

    /// A σ quantity from its output's exact statistics.
    ///
    /// # Errors
    /// An infinite variance.
    pub fn of_statistics(&self, st: &PointStatistics) -> Result<f64> {
        let sigma = st.sigma().ok_or_else(|| Error::Numerical {
            what: self.text.clone(),
            reason: "the variance is infinite".into(),
        })?;
        Ok(match self.kind {
            QuantityKind::ThreeSigma(_) => 3.0 * sigma,
            QuantityKind::Peak3(_) => st.mean.unwrap_or(0.0).abs() + 3.0 * sigma,
            _ => sigma,
        })
    }
}

/// The unit of `kind` in scenario `sc`, or why the quantity does not exist there.
fn unit_of(kind: &QuantityKind, sc: &Scenario) -> std::result::Result<String, String> {
    let spec = &sc.analysis.verdicts;
    let output_unit = |o: &str| {
        let outs = sc.model.system.outputs();
        outs.iter()
            .find(|x| x.name == o)
            .map(|x| x.unit.clone())
            .ok_or_else(|| {
                let names: Vec<&str> = outs.iter().map(|x| x.name.as_str()).collect();
                format!("the model has no output `{o}` (its outputs: {})", names.join(", "))
            })
    };
    let comfort = || {
        spec.comfort
            .as_ref()
            .ok_or_else(|| "the scenario has no [analysis.comfort] table".to_string())
    };
    let fatigue = || {
        spec.fatigue
            .as_ref()
            .map(|_| ())
            .ok_or_else(|| "the scenario has no [analysis.fatigue] table".to_string())
    };
    match kind {
        QuantityKind::Sigma(o) | QuantityKind::ThreeSigma(o) | QuantityKind::Peak3(o) => output_unit(o),
        QuantityKind::Aw(o) => {
            if !comfort()?.axes.iter().any(|a| &a.output_name == o) {
                return Err(format!("`{o}` is not an axis of [analysis.comfort]"));
            }
            Ok("m/s^2".into())
        }
        QuantityKind::Av | QuantityKind::A8 => comfort().map(|_| "m/s^2".into()),
        QuantityKind::Vdv => comfort().map(|_| "m/s^1.75".into()),
        QuantityKind::DamageRate => fatigue().map(|_| "1/s".into()),
        QuantityKind::Life => fatigue().map(|_| "s".into()),
        QuantityKind::StaticSag(e) => {
            let springs = crate::study::static_sag::sag_elements(sc)?;
            if !springs.contains(e) {
                return Err(format!("no spring element `{e}` (its springs: {})", springs.join(", ")));
            }
            Ok("m".into())
        }
    }
}

/// A verdict quantity of `sc` (`None` when its verdict is missing).
fn verdict_value(kind: &QuantityKind, sc: &Scenario, v: &VerdictAnalysis) -> Option<f64> {
    let comfort = v.comfort.as_ref();
    let fatigue = v.fatigue.as_ref();
    match kind {
        QuantityKind::Aw(o) => {
            // the result's axes are those of the spec, in its order
            let spec = sc.analysis.verdicts.comfort.as_ref()?;
            let i = spec.axes.iter().position(|a| &a.output_name == o)?;
            comfort?.axes.get(i).map(|a| a.a_w)
        }
        QuantityKind::Av => Some(comfort?.a_v),
        QuantityKind::A8 => Some(comfort?.health.as_ref()?.verdict.a8),
        QuantityKind::Vdv => comfort?.health.as_ref()?.verdict.vdv,
        QuantityKind::DamageRate => fatigue?.methods.iter().map(|m| m.damage_rate).reduce(f64::max),
        QuantityKind::Life => fatigue?.methods.iter().map(|m| m.life_s).reduce(f64::min),
        _ => None,
    }
}
