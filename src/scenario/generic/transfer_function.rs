//! `kind = "transfer-function"`: a rational transfer function written in the scenario file.
//!
//! # Format
//! `numerator`, `denominator` (SI numbers, ascending powers of s), `output = { name, unit }`.

use super::io::output_info;
use crate::error::Result;
use crate::fields::Fields;
use crate::models::{InputLayout, ModelInstance};
use crate::system::TransferFunction;
use std::sync::Arc;

/// Builds the model of a `kind = "transfer-function"` `[model]` table (see the module docs).
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming the key, value and reason.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    let num = f.numbers("numerator")?;
    let den = f.numbers("denominator")?;
    let out = output_info(f, "output")?;
    let tf = TransferFunction::new(num, den, out).map_err(|e| f.wrap("denominator", e))?;
    Ok(ModelInstance {
        system: Arc::new(tf),
        layout: InputLayout::Single,
        description: "rational transfer function".into(),
    })
}
