//! `stochvib sweep --verdicts`: one row per point of a study with the swept values as SI numbers in their
//! own columns and every number `stochvib analyze` reports for the scenario as a verdict: σ of each output,
//! a_w of each comfort axis, a_v, A(8), VDV, the largest damage rate and the shortest life.
//!
//! Each point is the scenario with the values substituted and read again by the scenario reader
//! ([`Sweep::scenario_at`]), then the quantities of [`crate::optimize::Quantity`] are computed on it: the
//! same numbers as `stochvib analyze` of the substituted file.

use super::sweep_table::csv_field;
use crate::error::{Error, Result};
use crate::optimize::Quantity;
use crate::scenario::Scenario;
use crate::study::{sweep_value_text, Sweep};
use crate::units::{parse_quantity, Dim};
use serde::Serialize;

/// The table.
#[derive(Debug, Clone, Serialize)]
pub struct VerdictSweep {
    /// Column names with their units, e.g. `model.stiffness [kg s^-2]`, `a_v [m/s^2]`.
    pub columns: Vec<String>,
    /// One row per point: the point, the swept values (SI) and the quantities (SI; `None` where the value
    /// does not exist), and the point's error.
    pub rows: Vec<VerdictRow>,
}

/// One point.
#[derive(Debug, Clone, Serialize)]
pub struct VerdictRow {
    /// Point index.
    pub point: usize,
    /// The swept values (SI) then the quantities, in the order of the columns after `point`.
    pub values: Vec<Option<f64>>,
    /// Why the point failed, if it did.
    pub error: Option<String>,
}

/// The quantities `analyze` reports for `sc`: σ of each `[analysis] outputs` entry, then a_w of each
/// comfort axis, a_v, A(8) and VDV with `[analysis.comfort]`, the damage rate and life with
/// `[analysis.fatigue]`.
///
/// # Errors
/// None expected (every name is taken from the scenario).
pub fn verdict_quantities(sc: &Scenario) -> Result<Vec<Quantity>> {
    let names = sc.model.system.outputs();
    let mut text: Vec<String> = sc
        .analysis
        .outputs
        .iter()
        .map(|&i| format!("sigma({})", names[i].name))
        .collect();
    if let Some(c) = &sc.analysis.verdicts.comfort {
        text.extend(c.axes.iter().map(|a| format!("a_w({})", a.output_name)));
        text.extend(["a_v".into(), "A8".into(), "VDV".into()]);
    }
    if sc.analysis.verdicts.fatigue.is_some() {
        text.extend(["damage_rate".into(), "life".into()]);
    }
    text.iter().map(|t| Quantity::parse("--verdicts", t, sc)).collect()
}

/// A swept value as an SI number and its dimension (`None` for a value that is not a quantity).
fn si_value(v: &toml::Value) -> Option<(f64, Dim)> {
    match v {
        toml::Value::Float(x) => Some((*x, Dim::DIMENSIONLESS)),
        toml::Value::Integer(i) => Some((*i as f64, Dim::DIMENSIONLESS)),
        other => parse_quantity(&sweep_value_text(other)).ok(),
    }
}

/// Evaluates every point of `sweep` (one after the other).
///
/// # Errors
/// When the base scenario's quantities cannot be named; a failing point is recorded in its row.
pub fn sweep_verdicts(sweep: &Sweep) -> Result<VerdictSweep> {
    let quantities = verdict_quantities(sweep.scenario())?;
    let q: Vec<&Quantity> = quantities.iter().collect();
    let spec = sweep.spec();
    let mut columns = vec!["point".to_string()];
    for p in &spec.params {
        let unit = si_value(&p.values[0]).map_or_else(|| "text".to_string(), |(_, d)| dim_text(d));
        columns.push(format!("{} [{unit}]", p.key));
    }
    columns.extend(quantities.iter().map(|q| format!("{} [{}]", q.text, q.unit)));
    let mut rows = Vec::with_capacity(spec.n_points());
    for point in 0..spec.n_points() {
        let mut values: Vec<Option<f64>> = spec
            .values(point)
            .into_iter()
            .map(|v| si_value(v).map(|x| x.0))
            .collect();
        let answer = sweep
            .scenario_at(point)
            .map_err(|e| sweep.name_point_error(point, e))
            .and_then(|sc| Quantity::values(&q, &sc));
        let error = match answer {
            Ok(v) => {
                values.extend(v.into_iter().map(Some));
                None
            }
            Err(e) => {
                values.extend(q.iter().map(|_| None));
                Some(e.to_string())
            }
        };
        rows.push(VerdictRow { point, values, error });
    }
    Ok(VerdictSweep { columns, rows })
}

fn dim_text(d: Dim) -> String {
    if d == Dim::DIMENSIONLESS {
        "1".into()
    } else {
        d.to_string()
    }
}

impl VerdictSweep {
    /// The table as CSV: the header, then one line per point (empty fields where a value does not exist; the
    /// error in the last column).
    pub fn to_csv(&self) -> String {
        let mut s = self.columns.iter().map(|c| csv_field(c)).collect::<Vec<_>>().join(",");
        s.push_str(",error\n");
        for r in &self.rows {
            s.push_str(&r.point.to_string());
            for v in &r.values {
                s.push(',');
                if let Some(x) = v {
                    s.push_str(&format!("{x:e}"));
                }
            }
            s.push(',');
            s.push_str(&r.error.as_deref().map(csv_field).unwrap_or_default());
            s.push('\n');
        }
        s
    }

    /// The table as JSON.
    ///
    /// # Errors
    /// A serialisation error (none expected).
    pub fn to_json(&self) -> Result<String> {
        serde_json::to_string_pretty(self).map_err(|e| Error::Numerical {
            what: "writing JSON".into(),
            reason: e.to_string(),
        })
    }
}
