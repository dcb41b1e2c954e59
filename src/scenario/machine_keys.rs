//! The reader of a `kind = "machine"` `[model]` table ([`MachineAssembly`]): each sub-table's unknown-key check
//! is its key table in [`super::model_keys`] (`MACHINE_BODY`, `MACHINE_AXLE`, …), which the reference
//! `docs/scenario-reference.md` shows.

use super::model_keys::{
    MACHINE_AXLE, MACHINE_BODY, MACHINE_CAB, MACHINE_MOUNT, MACHINE_OSCILLATING, MACHINE_OUTPUT, MACHINE_SEAT,
    MACHINE_SUSPENSION,
};
use crate::error::Result;
use crate::fields::Fields;
use crate::models::machine_assembly::{Axle, AxleKind, Cab, Direction, MachineAssembly, Mount, Part, RigidBody, Seat};
use crate::models::ModelInstance;
use crate::system::Quantity;
use crate::units::Dim;

/// Builds the machine of a `[model]` table with `kind = "machine"`.
///
/// # Errors
/// [`crate::Error::File`] naming the key, value and reason: a missing or malformed key, a value the model
/// refuses (see [`MachineAssembly::validate`]), an output on a part the machine does not have.
pub fn from_fields(f: &Fields) -> Result<ModelInstance> {
    let bf = f.sub("body")?;
    let body = RigidBody {
        mass: bf.quantity("mass", Dim::MASS)?,
        pitch_inertia: bf.quantity("pitch_inertia", Dim::INERTIA)?,
        roll_inertia: bf.quantity("roll_inertia", Dim::INERTIA)?,
        position: [0.0, 0.0, bf.quantity("height", Dim::LENGTH)?],
    };
    MACHINE_BODY.finish(&bf, &[])?;
    let axles = tables(f, "axle")?.iter().map(axle).collect::<Result<Vec<_>>>()?;
    let cab = match f.get("cab") {
        None => None,
        Some(_) => Some(cab(&f.sub("cab")?)?),
    };
    let seat = match f.get("seat") {
        None => None,
        Some(_) => {
            let sf = f.sub("seat")?;
            let s = Seat {
                position: lengths::<3>(&sf, "position")?,
                operator_mass: sf.quantity("operator_mass", Dim::MASS)?,
                seat_mass: sf.quantity("seat_mass", Dim::MASS)?,
                stiffness: sf.quantity("stiffness", Dim::STIFFNESS)?,
                damping: sf.quantity("damping", Dim::DAMPING)?,
            };
            MACHINE_SEAT.finish(&sf, &[])?;
            Some(s)
        }
    };
    let machine = MachineAssembly { body, axles, cab, seat };
    machine.validate().map_err(|e| f.wrap_param(e, "body"))?;
    let extra = match f.get("output") {
        None => Vec::new(),
        Some(_) => tables(f, "output")?
            .iter()
            .map(|of| output(of, &machine))
            .collect::<Result<_>>()?,
    };
    machine.instance(extra).map_err(|e| f.wrap_param(e, "output"))
}

/// The tables of the array `key` (`[[model.axle]]`), each as [`Fields`].
fn tables<'a>(f: &Fields<'a>, key: &str) -> Result<Vec<Fields<'a>>> {
    let v = f.require(key)?;
    let arr = v
        .as_array()
        .ok_or_else(|| f.error(key, v, format!("expected [[model.{key}]] tables")))?;
    arr.iter()
        .enumerate()
        .map(|(i, x)| {
            let k = format!("{key}[{i}]");
            let t = x.as_table().ok_or_else(|| f.error(&k, x, "expected a table"))?;
            Ok(Fields::new(f.file(), &f.path(&k), t))
        })
        .collect()
}

/// `N` lengths with units under `key` (a point).
fn lengths<const N: usize>(f: &Fields, key: &str) -> Result<[f64; N]> {
    let v = f.require(key)?;
    let arr = v
        .as_array()
        .filter(|a| a.len() == N)
        .ok_or_else(|| f.error(key, v, format!("expected {N} lengths with units, e.g. [\"1.2 m\", …]")))?;
    let mut out = [0.0; N];
    for (i, x) in arr.iter().enumerate() {
        out[i] = crate::units::parse_value(x, Dim::LENGTH).map_err(|r| f.error(&format!("{key}[{i}]"), x, r))?;
    }
    Ok(out)
}

fn axle(af: &Fields) -> Result<Axle> {
    let kind = match (af.get("oscillating"), af.get("suspension")) {
        (Some(_), Some(_)) => {
            return Err(af.error("suspension", "{ … }", "an axle is oscillating or suspended, not both"));
        }
        (Some(_), None) => {
            let o = af.sub("oscillating")?;
            let k = AxleKind::Oscillating {
                roll_inertia: o.quantity("roll_inertia", Dim::INERTIA)?,
                roll_stiffness: o.opt_quantity("roll_stiffness", Dim::TORQUE)?.unwrap_or(0.0),
                roll_damping: o.opt_quantity("roll_damping", Dim::new(2, 1, -1))?.unwrap_or(0.0),
            };
            MACHINE_OSCILLATING.finish(&o, &[])?;
            k
        }
        (None, Some(_)) => {
            let s = af.sub("suspension")?;
            let k = AxleKind::Suspended {
                stiffness: s.quantity("stiffness", Dim::STIFFNESS)?,
                damping: s.quantity("damping", Dim::DAMPING)?,
                unsprung_mass: s.quantity("unsprung_mass", Dim::MASS)?,
            };
            MACHINE_SUSPENSION.finish(&s, &[])?;
            k
        }
        (None, None) => AxleKind::Rigid,
    };
    let a = Axle {
        name: af.string("name")?.to_string(),
        position: af.quantity("position", Dim::LENGTH)?,
        track_width: af.quantity("track_width", Dim::LENGTH)?,
        tyre_stiffness: af.quantity("tyre_stiffness", Dim::STIFFNESS)?,
        tyre_damping: af.opt_quantity("tyre_damping", Dim::DAMPING)?.unwrap_or(0.0),
        kind,
    };
    MACHINE_AXLE.finish(af, &[])?;
    Ok(a)
}

fn cab(cf: &Fields) -> Result<Cab> {
    let body = RigidBody {
        mass: cf.quantity("mass", Dim::MASS)?,
        pitch_inertia: cf.quantity("pitch_inertia", Dim::INERTIA)?,
        roll_inertia: cf.quantity("roll_inertia", Dim::INERTIA)?,
        position: lengths::<3>(cf, "position")?,
    };
    let mount_height = cf.quantity("mount_height", Dim::LENGTH)?;
    let mounts = tables(cf, "mount")?
        .iter()
        .map(|mf| {
            let m = Mount {
                position: lengths::<2>(mf, "position")?,
                stiffness: mf.quantity("stiffness", Dim::STIFFNESS)?,
                damping: mf.opt_quantity("damping", Dim::DAMPING)?.unwrap_or(0.0),
            };
            MACHINE_MOUNT.finish(mf, &[])?;
            Ok(m)
        })
        .collect::<Result<Vec<_>>>()?;
    MACHINE_CAB.finish(cf, &[])?;
    Ok(Cab {
        body,
        mount_height,
        mounts,
    })
}

/// One `[[model.output]]`: name, part, point (default: the part's reference point), direction, quantity.
fn output(of: &Fields, m: &MachineAssembly) -> Result<(String, Quantity, Direction)> {
    let name = of.string("name")?.to_string();
    let part_text = of.string("part")?;
    let part = match part_text {
        "body" => Part::Body,
        "cab" => Part::Cab,
        "seat" => Part::Seat,
        p => return Err(of.error("part", p, "expected body, cab or seat")),
    };
    let direction = match of.string("direction")? {
        "x" => Direction::X,
        "y" => Direction::Y,
        "z" => Direction::Z,
        "roll" => Direction::Roll,
        "pitch" => Direction::Pitch,
        d => return Err(of.error("direction", d, "expected x, y, z, roll or pitch")),
    };
    let reference = match part {
        Part::Body => Some(m.body.position),
        Part::Cab => m.cab.as_ref().map(|c| c.body.position),
        Part::Seat => m.seat.as_ref().map(|s| s.position),
    };
    let point = match of.get("point") {
        Some(_) => lengths::<3>(of, "point")?,
        None => reference.unwrap_or_default(),
    };
    let g = m
        .point_weights(part, point, direction)
        .map_err(|e| of.error("part", part_text, e.to_string()))?;
    let quantity = match of.opt_string("quantity")?.unwrap_or("acceleration") {
        "displacement" => Quantity::Displacement(g),
        "velocity" => Quantity::Velocity(g),
        "acceleration" => Quantity::Acceleration(g),
        q => return Err(of.error("quantity", q, "expected displacement, velocity or acceleration")),
    };
    MACHINE_OUTPUT.finish(of, &[])?;
    Ok((name, quantity, direction))
}
