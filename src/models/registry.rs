//! Scenario-file kinds of the catalogue models.

use super::{
    balancer_bogie, conveyor_idler, dynamic_stiffness_chain, half_car, isolation, mine_hoist, operator_seat, scraper,
    three_mass_hoist, ModelInstance,
};
use crate::error::Result;
use crate::scenario::Fields;

/// What a model may need from the rest of the scenario file.
#[derive(Debug, Clone, Copy, Default)]
pub struct ModelContext {
    /// `[input] speed`, m/s.
    pub speed: Option<f64>,
}

/// The catalogue model kinds that scenario files may name in `[model] kind`.
pub const KINDS: &[&str] = &[
    "balancer-bogie",
    "conveyor-idler",
    "scraper-rigid-cab",
    "scraper-sprung-cab",
];

/// Builds catalogue model `kind` from the `[model]` table, or `None` if the kind is not a catalogue model.
pub fn from_fields(kind: &str, f: &Fields, ctx: ModelContext) -> Option<Result<ModelInstance>> {
    Some(match kind {
        "balancer-bogie" => balancer_bogie::from_fields(f, ctx.speed),
        "conveyor-idler" => conveyor_idler::from_fields(f),
        "scraper-rigid-cab" => scraper::rigid_from_fields(f),
        "scraper-sprung-cab" => scraper::sprung_from_fields(f),
        "half-car" => half_car::from_fields(f),
        "operator-seat" => operator_seat::from_fields(f),
        "isolator-single" => isolation::from_fields_single(f),
        "isolator-two-stage" => isolation::from_fields_two_stage(f),
        _ => return None,
    })
}

/// Every catalogue model's worked-example rows for the `book` report, in source order.
pub fn book_rows() -> Vec<crate::report::book::BookRow> {
    let mut rows = Vec::new();
    rows.extend(balancer_bogie::book_rows());
    rows.extend(conveyor_idler::book_rows());
    rows.extend(scraper::book_rows());
    rows.extend(isolation::book_rows());
    rows.extend(half_car::book_rows());
    rows.extend(operator_seat::book_rows());
    rows.extend(three_mass_hoist::book_rows());
    rows.extend(dynamic_stiffness_chain::book_rows());
    rows.extend(mine_hoist::book_rows());
    rows
}
