//! The reader of a `kind = "full-vehicle"` `[model]` table ([`FullVehicle`]): the unknown-key check of each
//! sub-table (`suspension_stiffness`, `suspension_damping`, `unsprung_mass`, `seat`) is its key table in
//! [`super::model_keys`], which the reference `docs/scenario-reference.md` shows.

use super::key_table::KeyTable;
use super::model_keys::{
    FULL_VEHICLE_SEAT, FULL_VEHICLE_SUSPENSION_DAMPING, FULL_VEHICLE_SUSPENSION_STIFFNESS, FULL_VEHICLE_UNSPRUNG_MASS,
};
use crate::error::Result;
use crate::fields::Fields;
use crate::models::full_vehicle::FullVehicle;
use crate::units::Dim;

/// Reads the `[model]` table of `kind = "full-vehicle"`: `mass`, `pitch_inertia`, `roll_inertia`,
/// `front_distance`, `rear_distance`, `track_width`, `tyre_stiffness` (quantities with units), and
/// `suspension_stiffness`, `suspension_damping`, `unsprung_mass` as `{ front = …, rear = … }` (per
/// wheel), `seat = { ahead = …, left = … }` (the seat point from the centre of mass, default 0, 0).
///
/// # Formula
/// None: the values are stored as given (SI after unit conversion).
///
/// # Errors
/// [`crate::Error::File`] naming the key, value and reason (missing keys, wrong dimensions, unknown keys,
/// parameters that [`FullVehicle::validate`] refuses); the unknown-key check of each sub-table is its key
/// table in [`super::model_keys`].
///
/// # Examples
/// ```
/// use stochvib::fields::Fields;
/// use stochvib::models::full_vehicle::FullVehicle;
/// use stochvib::scenario::full_vehicle_keys::from_fields;
/// let t: toml::Table = toml::from_str(r#"
///     mass = "1400 kg"
///     pitch_inertia = "2100 kg*m^2"
///     roll_inertia = "500 kg*m^2"
///     front_distance = "1.2 m"
///     rear_distance = "1.5 m"
///     track_width = "1.5 m"
///     tyre_stiffness = "200 kN/m"
///     suspension_stiffness = { front = "25 kN/m", rear = "22 kN/m" }
///     suspension_damping = { front = "2000 N*s/m", rear = "1800 N*s/m" }
///     unsprung_mass = { front = "40 kg", rear = "35 kg" }
///     seat = { ahead = "0.3 m", left = "0.35 m" }
/// "#).unwrap();
/// let car = from_fields(&Fields::new("car.toml".as_ref(), "model", &t)).unwrap();
/// assert_eq!(car, FullVehicle::passenger_car());
/// ```
pub fn from_fields(f: &Fields) -> Result<FullVehicle> {
    let pair = |key: &str, table: &KeyTable, dim: Dim| -> Result<[f64; 2]> {
        let pf = f.sub(key)?;
        let v = [pf.quantity("front", dim)?, pf.quantity("rear", dim)?];
        table.finish(&pf, &[])?;
        Ok(v)
    };
    let seat = match f.get("seat") {
        None => [0.0, 0.0],
        Some(_) => {
            let sf = f.sub("seat")?;
            let v = [
                sf.opt_quantity("ahead", Dim::LENGTH)?.unwrap_or(0.0),
                sf.opt_quantity("left", Dim::LENGTH)?.unwrap_or(0.0),
            ];
            FULL_VEHICLE_SEAT.finish(&sf, &[])?;
            v
        }
    };
    let car = FullVehicle {
        mass: f.quantity("mass", Dim::MASS)?,
        pitch_inertia: f.quantity("pitch_inertia", Dim::INERTIA)?,
        roll_inertia: f.quantity("roll_inertia", Dim::INERTIA)?,
        front_distance: f.quantity("front_distance", Dim::LENGTH)?,
        rear_distance: f.quantity("rear_distance", Dim::LENGTH)?,
        track_width: f.quantity("track_width", Dim::LENGTH)?,
        suspension_stiffness: pair(
            "suspension_stiffness",
            &FULL_VEHICLE_SUSPENSION_STIFFNESS,
            Dim::STIFFNESS,
        )?,
        suspension_damping: pair("suspension_damping", &FULL_VEHICLE_SUSPENSION_DAMPING, Dim::DAMPING)?,
        unsprung_mass: pair("unsprung_mass", &FULL_VEHICLE_UNSPRUNG_MASS, Dim::MASS)?,
        tyre_stiffness: f.quantity("tyre_stiffness", Dim::STIFFNESS)?,
        seat,
    };
    car.validate().map_err(|e| f.wrap_param(e, "mass"))?;
    Ok(car)
}
