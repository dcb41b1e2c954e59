//! `kind = "transfer-function"`: a rational transfer function written in the scenario file.
//!
//! # Format
//! `denominator` (SI numbers, ascending powers of s), `output = { name, unit }`, and either
//! * `numerator = [n₀, n₁, …]`: one input, H(s) = N(s)/D(s); or
//! * `numerator = [[…], […], …]`: several inputs with one denominator, y = Σ_k N_k(s)/D(s) u_k
//!   ([`TransferRow`]), with optional `positions` (along the track, with units: the delays at the
//!   scenario's speed) and `gains`, as for the other model kinds.

use super::io::{output_info, track_layout};
use crate::error::Result;
use crate::fields::Fields;
use crate::models::{InputLayout, ModelInstance};
use crate::system::{TransferFunction, TransferRow};
use std::sync::Arc;

/// The key of the polynomial a constructor's error is about: `numerator` (`input k: numerator` of a row too)
/// or `denominator` (what a zero, a degree or a pole is measured against); non-finite coefficients are
/// reported by the reader before.
fn blamed_key(e: &crate::Error) -> &'static str {
    match e {
        crate::Error::InvalidParameter { name, .. } if name.ends_with("numerator") => "numerator",
        _ => "denominator",
    }
}

/// Builds the model of a `kind = "transfer-function"` `[model]` table (see the module docs).
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming the key, value and reason.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    let den = f.numbers("denominator")?;
    let out = output_info(f, "output")?;
    let rows = f
        .require("numerator")?
        .as_array()
        .is_some_and(|a| a.first().is_some_and(|x| x.is_array()));
    if !rows {
        let num = f.numbers("numerator")?;
        for key in ["positions", "gains"] {
            if let Some(v) = f.get(key) {
                return Err(f.error(
                    key,
                    v,
                    "a single numerator has one input: give `numerator = [[…], […]]` (one row per input) for \
                     several inputs on one track",
                ));
            }
        }
        let tf = TransferFunction::new(num, den, out).map_err(|e| f.wrap(blamed_key(&e), e))?;
        return Ok(ModelInstance {
            system: Arc::new(tf),
            layout: InputLayout::Single,
            description: "rational transfer function".into(),
        });
    }
    let nums = f.number_rows("numerator")?;
    let m = nums.len();
    let row = TransferRow::new(nums, den, out).map_err(|e| f.wrap(blamed_key(&e), e))?;
    let layout = track_layout(f, m)?;
    Ok(ModelInstance {
        system: Arc::new(row),
        layout,
        description: format!("rational transfer function of {m} inputs"),
    })
}
