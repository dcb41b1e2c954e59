//! The keys of a `kind = "butterworth-band"` spectrum (see `docs/spectrum-files.md`): a level in a named
//! convention, a Butterworth low pass and an optional high pass, and `integrate` to read an acceleration
//! class as the displacement that drives a base-excited model.

use crate::error::Result;
use crate::fields::Fields;
use crate::spectrum::{butterworth_band, ButterworthFilter, Convention, Domain, RationalSpectrum};
use crate::units::Dim;

/// Builds the spectrum of a `butterworth-band` table; `inv_lag` is the dimension of its frequencies.
///
/// # Errors
/// [`crate::Error::File`] naming the key: `convention`, `level` (finite, > 0), `high_pass.order`,
/// `high_pass.corner`, `low_pass.…` (a table `{ order, corner }`, order 1 … 8, a corner with a unit),
/// `integrate` (0, 1 or 2, at most the high-pass order).
pub(crate) fn butterworth_from_fields(f: &Fields, domain: Domain, inv_lag: Dim) -> Result<RationalSpectrum> {
    let c: Convention = f.string("convention")?.parse().map_err(|e| f.wrap("convention", e))?;
    let level = f.number("level")?;
    let (_, s0) = c.to_canonical(1.0, level);
    let high_pass = match f.get("high_pass") {
        None => None,
        Some(_) => Some(filter(f, "high_pass", inv_lag)?),
    };
    let low_pass = filter(f, "low_pass", inv_lag)?;
    let integrate = match f.get("integrate") {
        None => 0,
        Some(v) => v
            .as_integer()
            .filter(|k| (0..=2).contains(k))
            .ok_or_else(|| f.error("integrate", v, "expected 0, 1 or 2"))? as u32,
    };
    butterworth_band(s0, high_pass, low_pass, integrate, domain).map_err(|e| {
        let key = match &e {
            crate::Error::InvalidParameter { name, .. } => name.clone(),
            _ => "low_pass".to_string(),
        };
        f.wrap(&key, e)
    })
}

/// `{ order = n, corner = "1.5 Hz" }` under `key`.
fn filter(f: &Fields, key: &str, inv_lag: Dim) -> Result<ButterworthFilter> {
    let t = f.sub(key)?;
    let order = t.require("order")?;
    let order = order
        .as_integer()
        .filter(|n| (1..=crate::spectrum::MAX_BUTTERWORTH_ORDER as i64).contains(n))
        .ok_or_else(|| t.error("order", order, "expected a Butterworth order from 1 to 8"))? as u32;
    let cv = t.require("corner")?.clone();
    let corner = t.angular_frequency(&cv, "corner", inv_lag)?;
    t.finish()?;
    Ok(ButterworthFilter { order, corner })
}
