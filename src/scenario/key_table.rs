//! Declarative key tables: one table per section of a scenario file, listing each key the section's reader
//! accepts with its type and unit, its default, and its allowed values with the error a bad value gets.
//!
//! The readers take their set of keys from these tables, and the scenario file reference
//! (`docs/scenario-reference.md`) shows each table as [`KeyTable::markdown`] renders it, below a marker line
//! [`KeyTable::marker`]; the key reference test checks that the page holds exactly that text, and that the
//! keys the readers ask for are the keys of the tables.

use crate::error::Result;
use crate::fields::Fields;

/// One key of a section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    /// The key as written in the file.
    pub name: &'static str,
    /// Its type and unit (`quantity, m/s`, `array of lengths, one per input`).
    pub ty: &'static str,
    /// Its default, or `required` (and when it is required).
    pub default: &'static str,
    /// The allowed values, what the key means, and the error a bad value gets (quoted).
    pub allowed: &'static str,
}

/// The keys of one section of a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KeyTable {
    /// The kind of file: `scenario`.
    pub file: &'static str,
    /// The dotted path of the section (`input[]` for the `[[input]]` tables, `model` for `[model]`).
    pub prefix: &'static str,
    /// The `kind` the section's keys belong to (a `[model] kind`, a coherence kind), if they depend on one.
    pub kind: Option<&'static str>,
    /// The keys, in the order the readers list them in their "known keys" messages.
    pub keys: &'static [Key],
}

/// A [`Key`] (for the tables' rows).
pub const fn key(name: &'static str, ty: &'static str, default: &'static str, allowed: &'static str) -> Key {
    Key {
        name,
        ty,
        default,
        allowed,
    }
}

impl KeyTable {
    /// The names of the keys, in table order.
    pub fn names(&self) -> Vec<&'static str> {
        self.keys.iter().map(|k| k.name).collect()
    }

    /// Whether `name` is a key of the table.
    pub fn contains(&self, name: &str) -> bool {
        self.keys.iter().any(|k| k.name == name)
    }

    /// The unknown-key check of a reader of this section, once it has read the table `f`: the first key of `f`
    /// that is neither a key of this table nor one of `also` is refused, "unknown key (known keys here: …)"
    /// listing those keys alphabetically; then [`Fields::finish`] refuses a key of the table that this reading
    /// left unread (a key of the section's other form, e.g. `from` beside `times`), as before.
    ///
    /// # Errors
    /// [`crate::Error::File`] naming the key, its value and the reason.
    pub fn finish(&self, f: &Fields, also: &[&str]) -> Result<()> {
        if let Some((k, v)) = f
            .entries()
            .find(|(k, _)| !self.contains(k) && !also.contains(&k.as_str()))
        {
            let mut known = self.names();
            known.extend(also);
            known.sort_unstable();
            known.dedup();
            return Err(f.error(k, v, format!("unknown key (known keys here: {})", known.join(", "))));
        }
        f.finish()
    }

    /// The marker line that precedes the table in the reference page: `<!-- keys: FILE PREFIX [kind=KIND] -->`.
    pub fn marker(&self) -> String {
        match self.kind {
            Some(kind) => format!("<!-- keys: {} {} kind={kind} -->", self.file, self.prefix),
            None => format!("<!-- keys: {} {} -->", self.file, self.prefix),
        }
    }

    /// The table as markdown (a header row, a rule and one row per key; each line ends with a newline).
    pub fn markdown(&self) -> String {
        let mut out =
            String::from("| key | type, unit | default | allowed values, and the error |\n|---|---|---|---|\n");
        for k in self.keys {
            let allowed = if k.allowed.is_empty() {
                String::new()
            } else {
                format!("{} ", k.allowed)
            };
            out.push_str(&format!("| `{}` | {} | {} | {allowed}|\n", k.name, k.ty, k.default));
        }
        out
    }
}

/// Every section whose reference is generated from its key table, in the order of the reference page.
pub const KEY_TABLES: &[&KeyTable] = &[
    &super::top_keys::TOP,
    &super::top_keys::MODEL,
    &super::generic::mdof_keys::MDOF,
    &super::generic::mdof_keys::COORDINATE,
    &super::generic::mdof_keys::ELEMENT,
    &super::generic::mdof_keys::OUTPUT,
    &super::model_keys::TRANSFER_FUNCTION,
    &super::model_keys::TRANSFER_FUNCTION_OUTPUT,
    &super::model_keys::STATE_SPACE,
    &super::model_keys::STATE_SPACE_OUTPUTS,
    &super::model_keys::QUARTER_CAR,
    &super::model_keys::ISOLATOR_SINGLE,
    &super::model_keys::ISOLATOR_TWO_STAGE,
    &super::model_keys::HALF_CAR,
    &super::model_keys::FULL_VEHICLE,
    &super::model_keys::FULL_VEHICLE_SUSPENSION_STIFFNESS,
    &super::model_keys::FULL_VEHICLE_SUSPENSION_DAMPING,
    &super::model_keys::FULL_VEHICLE_UNSPRUNG_MASS,
    &super::model_keys::FULL_VEHICLE_SEAT,
    &super::model_keys::MACHINE,
    &super::model_keys::MACHINE_BODY,
    &super::model_keys::MACHINE_AXLE,
    &super::model_keys::MACHINE_OSCILLATING,
    &super::model_keys::MACHINE_SUSPENSION,
    &super::model_keys::MACHINE_CAB,
    &super::model_keys::MACHINE_MOUNT,
    &super::model_keys::MACHINE_SEAT,
    &super::model_keys::MACHINE_OUTPUT,
    &super::model_keys::OPERATOR_SEAT,
    &super::model_keys::BALANCER_BOGIE,
    &super::model_keys::CONVEYOR_IDLER,
    &super::model_keys::SCRAPER_RIGID_CAB,
    &super::model_keys::SCRAPER_SPRUNG_CAB,
    &super::model_keys::THREE_MASS_HOIST,
    &super::model_keys::DYNAMIC_STIFFNESS_CHAIN,
    &super::model_keys::MINE_HOIST,
    &super::input_keys::PROCESS,
    &super::input_keys::ENVELOPING,
    &super::input_keys::ENVELOPING_EACH,
    &super::input_keys::INPUT,
    &super::input_keys::ROAD,
    &super::input_keys::COHERENCE,
    &super::input_keys::DODDS_ROBSON,
    &super::input_keys::AMMON_BORMANN,
    &super::input_keys::TABULATED,
    &super::input_keys::CONSTANT,
    &super::input_keys::SPEED_PROFILE,
    &super::input_keys::ENVELOPE,
    &super::analysis_keys::ANALYSIS,
    &super::analysis_keys::QUADRATURE,
    &super::analysis_keys::COMFORT,
    &super::analysis_keys::COMFORT_AXIS,
    &super::analysis_keys::FATIGUE,
    &super::analysis_keys::SEAT_FACTOR,
    &super::analysis_keys::MISSION,
    &super::transient_key_table::TRANSIENT,
    &super::transient_key_table::SCHEDULE,
    &super::transient_key_table::ROPE,
];
