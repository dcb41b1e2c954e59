//! The results of a deterministic scenario (a model without a random input): its model's result tables,
//! every number of them finite.

use crate::error::{Error, Result};
use crate::models::results::{Cell, ResultTable};
use crate::scenario::DeterministicScenario;

/// Every result table of the model of `d`.
///
/// # Errors
/// [`Error::File`] naming the file, the key `model` and the kind: a numerical failure of the model
/// ([`DeterministicModel::results`](crate::models::results::DeterministicModel::results)), or a cell that is
/// not a finite number (values beyond double precision), naming its table and column.
pub fn deterministic_tables(d: &DeterministicScenario) -> Result<Vec<ResultTable>> {
    let fail = |reason: String| Error::File {
        file: d.path.clone(),
        key: "model".into(),
        value: d.kind.clone(),
        reason,
    };
    let tables = d.model.results().map_err(|e| {
        fail(format!(
            "the model's results cannot be computed for these parameters: {e}"
        ))
    })?;
    for t in &tables {
        for row in &t.rows {
            for (j, c) in row.iter().enumerate() {
                if matches!(c, Cell::Number(v) if !v.is_finite()) {
                    return Err(fail(format!(
                        "table \"{}\", column \"{}\": not a finite number for these parameters (values beyond \
                         double precision; check the units)",
                        t.title,
                        t.columns.get(j).map_or("?", |c| c.name.as_str())
                    )));
                }
            }
        }
    }
    Ok(tables)
}
