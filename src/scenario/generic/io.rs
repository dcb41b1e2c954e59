//! Pieces of the `[model]` table shared by the generic model kinds: named outputs and the layout of several
//! inputs on one road track.

use crate::error::Result;
use crate::fields::Fields;
use crate::models::InputLayout;
use crate::system::OutputInfo;
use crate::units::Dim;

/// Reads the output table `key` = `{ name, unit }` (unit default `m`).
///
/// # Errors
/// Missing key, not a table, missing name, unknown keys.
pub fn output_info(f: &Fields, key: &str) -> Result<OutputInfo> {
    let v = f.require(key)?;
    let t = v
        .as_table()
        .ok_or_else(|| f.error(key, v, "expected { name = \"..\", unit = \"..\" }"))?;
    let of = Fields::new(f.file(), &f.path(key), t);
    let info = OutputInfo::new(of.string("name")?, of.opt_string("unit")?.unwrap_or("m"));
    crate::scenario::model_keys::TRANSFER_FUNCTION_OUTPUT.finish(&of, &[])?;
    Ok(info)
}

/// Reads the output list `key` = `[{ name, unit }, …]` (unit default `m`).
///
/// # Errors
/// Missing key, not an array of tables, missing names, unknown keys.
pub fn output_list(f: &Fields, key: &str) -> Result<Vec<OutputInfo>> {
    let v = f.require(key)?;
    let arr = v
        .as_array()
        .ok_or_else(|| f.error(key, v, "expected an array of { name, unit }"))?;
    arr.iter()
        .enumerate()
        .map(|(i, x)| {
            let t = x
                .as_table()
                .ok_or_else(|| f.error(&format!("{key}[{i}]"), x, "expected { name, unit }"))?;
            let of = Fields::new(f.file(), &f.path(&format!("{key}[{i}]")), t);
            let info = OutputInfo::new(of.string("name")?, of.opt_string("unit")?.unwrap_or("m"));
            crate::scenario::model_keys::STATE_SPACE_OUTPUTS.finish(&of, &[])?;
            Ok(info)
        })
        .collect()
}

/// Reads optional `positions` (with units) and `gains` for `m` inputs on one track, and optional `tracks`
/// (`"left"`/`"right"` per input) for inputs on two tracks ([`InputLayout::TwoTracks`]).
///
/// # Errors
/// Lengths that differ from `m`, negative positions, values that are not lengths or numbers, a track other
/// than left or right.
pub fn track_layout(f: &Fields, m: usize) -> Result<InputLayout> {
    let positions = match f.get("positions") {
        None => vec![0.0; m],
        Some(v) => {
            let arr = v
                .as_array()
                .ok_or_else(|| f.error("positions", v, "expected an array of lengths"))?;
            arr.iter()
                .enumerate()
                .map(|(i, x)| {
                    crate::units::parse_value(x, Dim::LENGTH).map_err(|r| f.error(&format!("positions[{i}]"), x, r))
                })
                .collect::<Result<Vec<_>>>()?
        }
    };
    let gains = match f.get("gains") {
        None => vec![1.0; m],
        Some(_) => f.numbers("gains")?,
    };
    if positions.len() != m || gains.len() != m {
        return Err(f.error(
            "positions",
            positions.len(),
            format!("need one position and one gain per input ({m})"),
        ));
    }
    if let Some((i, p)) = positions.iter().enumerate().find(|(_, p)| **p < 0.0) {
        return Err(f.error(
            &format!("positions[{i}]"),
            p,
            "must be >= 0 (distance behind the first contact)",
        ));
    }
    if let Some(v) = f.get("tracks") {
        let arr = v.as_array().filter(|a| a.len() == m).ok_or_else(|| {
            f.error(
                "tracks",
                v,
                format!("expected {m} tracks (\"left\" or \"right\"), one per input"),
            )
        })?;
        let tracks = arr
            .iter()
            .enumerate()
            .map(|(i, x)| crate::scenario::inputs::track_index(f, &format!("tracks[{i}]"), x))
            .collect::<Result<Vec<_>>>()?;
        return Ok(InputLayout::TwoTracks {
            tracks,
            positions,
            gains,
            track_width: None,
        });
    }
    Ok(InputLayout::Track { positions, gains })
}
