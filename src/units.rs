//! Physical quantities with units: `"2.25 cm^2"`, `"0.035 1/cm"`, `"70 kN/m"` → SI numbers, with a dimension
//! check. (Being written: see the contract below.)
//!
//! # Contract
//! * [`Dim`] holds integer exponents of metre, kilogram and second; angles (rad, cycle = 2π rad) are
//!   dimensionless but *scale*: `"2 Hz"` read as an angular frequency is `4π rad/s`. That is an explicit
//!   unit written by the user, never a silent factor.
//! * [`parse_quantity`] returns the SI value and its dimension; [`parse_as`] also checks the dimension.

use crate::error::{Error, Result};

/// Dimension as integer exponents of (m, kg, s).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Dim {
    /// Exponent of metre.
    pub m: i8,
    /// Exponent of kilogram.
    pub kg: i8,
    /// Exponent of second.
    pub s: i8,
}

impl Dim {
    /// Builds a dimension from exponents of m, kg, s.
    pub const fn new(m: i8, kg: i8, s: i8) -> Dim {
        Dim { m, kg, s }
    }
    /// Pure number (also angles).
    pub const DIMENSIONLESS: Dim = Dim::new(0, 0, 0);
    /// Metre.
    pub const LENGTH: Dim = Dim::new(1, 0, 0);
    /// Square metre (variance of a displacement).
    pub const AREA: Dim = Dim::new(2, 0, 0);
    /// Kilogram.
    pub const MASS: Dim = Dim::new(0, 1, 0);
    /// Second.
    pub const TIME: Dim = Dim::new(0, 0, 1);
    /// 1/s (rad/s, Hz).
    pub const FREQUENCY: Dim = Dim::new(0, 0, -1);
    /// 1/m (rad/m, cycles/m).
    pub const WAVENUMBER: Dim = Dim::new(-1, 0, 0);
    /// m/s.
    pub const VELOCITY: Dim = Dim::new(1, 0, -1);
    /// m/s².
    pub const ACCELERATION: Dim = Dim::new(1, 0, -2);
    /// N = kg m/s².
    pub const FORCE: Dim = Dim::new(1, 1, -2);
    /// N/m = kg/s².
    pub const STIFFNESS: Dim = Dim::new(0, 1, -2);
    /// N s/m = kg/s.
    pub const DAMPING: Dim = Dim::new(0, 1, -1);
    /// kg m².
    pub const INERTIA: Dim = Dim::new(2, 1, 0);
    /// N m (torque; also N m/rad torsional stiffness).
    pub const TORQUE: Dim = Dim::new(2, 1, -2);
}

/// Parses `"<number> [unit expression]"` into its SI value and dimension.
///
/// # Errors
/// [`Error::Unit`] for an unknown unit or malformed text.
pub fn parse_quantity(text: &str) -> Result<(f64, Dim)> {
    Err(Error::Unit { text: text.to_string(), reason: "units parser not implemented yet".into() })
}

/// Parses a quantity and checks that it has dimension `expected`.
///
/// # Errors
/// [`Error::Unit`] for unknown units or a dimension mismatch.
pub fn parse_as(text: &str, expected: Dim) -> Result<f64> {
    let (v, d) = parse_quantity(text)?;
    if d != expected {
        return Err(Error::Unit { text: text.to_string(), reason: format!("dimension {d:?}, expected {expected:?}") });
    }
    Ok(v)
}
