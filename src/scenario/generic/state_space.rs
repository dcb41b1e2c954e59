//! `kind = "state-space"`: a state-space system written in the scenario file.
//!
//! # Format
//! `a`, `b`, `c`, optional `d`, `e` (arrays of rows, SI numbers) of ẋ = A x + B u, y = C x + D u + E u̇;
//! `outputs = [{ name, unit }]`; optional `positions`/`gains` for several inputs on one track.

use super::io::{output_list, track_layout};
use crate::error::Result;
use crate::fields::Fields;
use crate::models::ModelInstance;
use crate::system::StateSpace;
use std::sync::Arc;

/// Builds the model of a `kind = "state-space"` `[model]` table (see the module docs).
///
/// # Errors
/// [`Error::File`](crate::Error::File) naming the key, value and reason.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    let a = f.matrix("a")?;
    let b = f.matrix("b")?;
    let c = f.matrix("c")?;
    let d = f.get("d").map(|_| f.matrix("d")).transpose()?;
    let e = f.get("e").map(|_| f.matrix("e")).transpose()?;
    let outs = output_list(f, "outputs")?;
    let m = b.ncols();
    let ss = StateSpace::new(a, b, c, d, e, outs).map_err(|e| f.wrap("a", e))?;
    let layout = track_layout(f, m)?;
    Ok(ModelInstance {
        system: Arc::new(ss),
        layout,
        description: "state-space system".into(),
    })
}
