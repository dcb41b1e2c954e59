//! Scenario-file kinds of the catalogue models.

use super::ModelInstance;
use crate::error::Result;
use crate::scenario::Fields;

/// The catalogue model kinds that scenario files may name in `[model] kind`.
pub const KINDS: &[&str] = &[];

/// Builds catalogue model `kind` from the `[model]` table, or `None` if the kind is not a catalogue model.
pub fn from_fields(kind: &str, f: &Fields) -> Option<Result<ModelInstance>> {
    let _ = f;
    match kind {
        _ => None,
    }
}

/// Every catalogue model's worked-example rows for the `book` report, in source order.
pub fn book_rows() -> Vec<crate::report::book::BookRow> {
    let rows = Vec::new();
    rows
}
