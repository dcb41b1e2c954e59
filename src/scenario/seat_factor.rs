//! `[analysis.seat_factor]`: the SEAT value (seat effective amplitude transmissibility) of a seat, the
//! ratio of the frequency-weighted r.m.s. acceleration on the seat pan to that on the floor (platform)
//! under the scenario's input.
//!
//! # Format
//! ```toml
//! [analysis.seat_factor]
//! seat = "seat_acc"        # an acceleration output on the seat pan (m/s²)
//! floor = "floor_acc"      # an acceleration output of the floor under the seat, or "base 0": the second
//!                          # derivative of base input 0 (the cab floor that drives a seat model directly)
//! # weighting = "Wk"       # default Wk (ISO 2631-1:1997 7.2.3, vertical, seated)
//! ```
//!
//! The value is computed by `study::seat_factor` (its formula is documented there).

use crate::comfort::Weighting;
use crate::error::Result;
use crate::fields::Fields;
use crate::models::ModelInstance;

/// Where the floor acceleration comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum FloorSource {
    /// An acceleration output of the model (index, name).
    Output(usize, String),
    /// The second derivative of base input j (a displacement in m).
    Base(usize),
}

/// `[analysis.seat_factor]`.
#[derive(Debug, Clone, PartialEq)]
pub struct SeatFactorSpec {
    /// The seat-pan acceleration output (index, name).
    pub seat: (usize, String),
    /// The floor.
    pub floor: FloorSource,
    /// The frequency weighting (default Wk).
    pub weighting: Weighting,
}

/// Reads `[analysis.seat_factor]` (the table `f`).
///
/// # Errors
/// [`crate::Error::File`] naming `seat`, `floor` or `weighting`: an unknown output, a base input the model does
/// not have, an unknown weighting; a seat or floor output that is not an acceleration.
pub fn parse_seat_factor(f: &Fields, model: &ModelInstance) -> Result<SeatFactorSpec> {
    let outs = model.system.outputs();
    let index = |key: &str, name: &str| -> Result<usize> {
        outs.iter().position(|o| o.name == name).ok_or_else(|| {
            let names: Vec<&str> = outs.iter().map(|o| o.name.as_str()).collect();
            f.error(
                key,
                name,
                format!("no such output; the model has: {}", names.join(", ")),
            )
        })
    };
    let seat_name = f.string("seat")?;
    let seat = (index("seat", seat_name)?, seat_name.to_string());
    let floor_text = f.string("floor")?;
    let floor = match floor_text.strip_prefix("base") {
        Some(rest) => {
            let n_base = model.system.as_mdof().map_or(0, |m| m.n_base());
            let j = rest
                .trim()
                .parse::<usize>()
                .ok()
                .filter(|j| *j < n_base)
                .ok_or_else(|| {
                    f.error(
                        "floor",
                        floor_text,
                        format!("expected \"base <j>\" with j below the model's {n_base} base (displacement) inputs"),
                    )
                })?;
            FloorSource::Base(j)
        }
        None => FloorSource::Output(index("floor", floor_text)?, floor_text.to_string()),
    };
    let weighting = match f.opt_string("weighting")? {
        None => Weighting::Wk,
        Some(w) => Weighting::parse(w).map_err(|e| f.wrap("weighting", e))?,
    };
    let ss = model
        .system
        .state_space()
        .ok_or_else(|| f.error("seat", seat_name, "the model has no state-space form to weight"))?;
    let mut check = vec![("seat", seat.0, seat_name)];
    if let FloorSource::Output(i, name) = &floor {
        check.push(("floor", *i, name.as_str()));
    }
    for (key, i, name) in check {
        crate::comfort::check_weightable(ss, i, &weighting).map_err(|e| f.error(key, name, e.to_string()))?;
    }
    Ok(SeatFactorSpec { seat, floor, weighting })
}
