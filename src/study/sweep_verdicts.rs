//! `stochvib sweep --verdicts`: one row per point of a study with the swept values as SI numbers in their
//! own columns and every number `stochvib analyze` reports for the scenario as a verdict: σ of each output,
//! a_w of each comfort axis, a_v, A(8), VDV, the largest damage rate, the shortest life and the static sag
//! of every spring.
//!
//! Each point is the scenario with the values substituted and read again by the scenario reader
//! ([`Sweep::scenario_at`]), then the quantities of [`crate::optimize::Quantity`] are computed on it: the
//! same numbers as `stochvib analyze` of the substituted file.

use super::sweep_table::{compute_sweep, csv_field, SweepResults};
use crate::error::{Error, Result};
use crate::optimize::Quantity;
use crate::scenario::Scenario;
use crate::study::Sweep;
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
/// `[analysis.fatigue]`, then the static sag of every spring where the kind defines it
/// ([`static_sag`](super::static_sag::static_sag)).
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
    if let Ok(springs) = super::static_sag::sag_elements(sc) {
        text.extend(springs.iter().map(|e| format!("static_sag({e})")));
    }
    text.iter().map(|t| Quantity::parse("--verdicts", t, sc)).collect()
}

/// A swept value, as the table holds its text, as an SI number and its dimension (`None` for a value that is
/// not a quantity, e.g. a spectrum's name).
fn si_value(text: &str) -> Option<(f64, Dim)> {
    match text.trim().parse::<f64>() {
        Ok(x) => Some((x, Dim::DIMENSIONLESS)),
        Err(_) => parse_quantity(text).ok(),
    }
}

/// Evaluates every point of `sweep` with its verdict columns (on every core): the table of
/// [`compute_sweep`] of the study [`with_verdicts`](Sweep::with_verdicts), in its one-row-per-point form.
///
/// # Errors
/// When the base scenario's quantities cannot be named; a failing point is recorded in its row.
pub fn sweep_verdicts(sweep: &Sweep) -> Result<VerdictSweep> {
    let n = sweep.spec().n_points();
    let t = if sweep.verdicts().is_empty() {
        let with = Sweep::new(sweep.scenario(), sweep.spec().clone())?.with_verdicts()?;
        compute_sweep(&with, 0..n, true, None, &|_, _| {})?
    } else {
        compute_sweep(sweep, 0..n, true, None, &|_, _| {})?
    };
    Ok(VerdictSweep::of(&t))
}

/// Computes the verdict columns of `sweep` at every point of `t` that did not fail (on every core with
/// `parallel`): each point's scenario is read again with its values ([`Sweep::scenario_at`]) and the
/// quantities computed on it, the numbers `stochvib analyze` prints for it. A point whose verdicts fail is
/// recorded in [`SweepResults::errors`] (`verdicts: …`). Nothing is done for a study without verdicts.
pub(crate) fn add_verdicts(sweep: &Sweep, t: &mut SweepResults, parallel: bool) {
    let q: Vec<&Quantity> = sweep.verdicts().iter().collect();
    if q.is_empty() {
        return;
    }
    let mut failed: Vec<usize> = t.errors.iter().map(|e| e.0).collect();
    failed.sort_unstable();
    let one = |p: usize| -> Option<Result<Vec<f64>>> {
        failed.binary_search(&p).is_err().then(|| {
            sweep
                .scenario_at(p)
                .map_err(|e| sweep.name_point_error(p, e))
                .and_then(|sc| Quantity::values(&q, &sc))
        })
    };
    let answers: Vec<Option<Result<Vec<f64>>>> = if parallel {
        use rayon::prelude::*;
        t.points.clone().into_par_iter().map(one).collect()
    } else {
        t.points.clone().map(one).collect()
    };
    t.verdicts = Vec::with_capacity(t.points.len() * q.len());
    for (p, a) in t.points.clone().zip(answers) {
        match a {
            Some(Ok(v)) => t.verdicts.extend(v.into_iter().map(Some)),
            other => {
                t.verdicts.extend(q.iter().map(|_| None));
                if let Some(Err(e)) = other {
                    t.errors.push((p, format!("verdicts: {e}")));
                }
            }
        }
    }
    t.errors.sort_by_key(|e| e.0);
}

fn dim_text(d: Dim) -> String {
    if d == Dim::DIMENSIONLESS {
        "1".into()
    } else {
        d.to_string()
    }
}

impl VerdictSweep {
    /// The one-row-per-point form of a table with verdict columns ([`SweepResults::verdicts`]): the point,
    /// the swept values as SI numbers (their unit in the header), the verdicts, the point's error.
    pub fn of(t: &SweepResults) -> VerdictSweep {
        let id = &t.identity;
        let mut columns = vec!["point".to_string()];
        for (key, values) in &id.params {
            let unit = values
                .first()
                .and_then(|v| si_value(v))
                .map_or_else(|| "text".to_string(), |(_, d)| dim_text(d));
            columns.push(format!("{key} [{unit}]"));
        }
        columns.extend(id.verdicts.iter().map(|(q, unit)| format!("{q} [{unit}]")));
        let (nk, width) = (id.params.len(), id.verdicts.len());
        let rows = t
            .points
            .clone()
            .enumerate()
            .map(|(row, point)| {
                let mut values: Vec<Option<f64>> = (0..nk)
                    .map(|k| {
                        let i = t.value_index.get(row * nk + k)?;
                        si_value(id.params[k].1.get(*i)?).map(|x| x.0)
                    })
                    .collect();
                values.extend((0..width).map(|k| t.verdicts.get(row * width + k).copied().flatten()));
                let error = t.error_of(point).map(str::to_string);
                VerdictRow { point, values, error }
            })
            .collect();
        VerdictSweep { columns, rows }
    }

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
