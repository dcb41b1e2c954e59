//! Physical quantities with units: `"2.25 cm^2"`, `"0.035 1/cm"`, `"70 kN/m"` → SI numbers, with a
//! dimension check.
//!
//! Scenario and spectrum files (TOML) may write a quantity either as a bare TOML number, which is taken to
//! be *already SI in the expected dimension*, or as a string with an explicit unit, which is converted to
//! SI and checked against the expected dimension (see [`parse_value`]).
//!
//! # Contract
//! * [`Dim`] holds integer exponents of metre, kilogram and second; angles (rad, cycle = 2π rad) are
//!   dimensionless but *scale*: `"2 Hz"` read as an angular frequency is `4π rad/s`. That is an explicit
//!   unit written by the user, never a silent factor.
//! * [`parse_quantity`] returns the SI value and its dimension; [`parse_as`] also checks the dimension.
//!
//! # Angular convention (read this)
//! The SI value of every frequency-like quantity is **angular**: radians per second, radians per metre.
//! `rad` is 1 and `cycle` / `cycles` is 2π, and `Hz` *means* cycles per second. Hence
//! * `"12 rad/s"` → `12` with dimension `s^-1`,
//! * `"2 Hz"` → `4π ≈ 12.566` with dimension `s^-1` (not 2!),
//! * `"0.1 cycles/m"` → `0.2π ≈ 0.628` with dimension `m^-1`,
//! * `"1/s"` → `1` (a bare `1/s` carries no cycle, so it is read as rad/s).
//!
//! A caller that wants a value in hertz must divide by 2π itself; this module never does it silently.
//!
//! # Sample rates
//! A sample rate counts samples per second; it is no angle. [`parse_sample_rate`] reads `Hz` as one per
//! second and `S` (`sample`, `samples`; with prefixes: `kS/s`) as a count, and refuses angles: `"200 Hz"`,
//! `"200 1/s"` and `"200 S/s"` are all 200 per second. Every other text parses as above.
//!
//! # Formula
//! The accepted grammar (whitespace may appear between any two tokens except where noted):
//!
//! ```text
//! quantity    := number [unit-expr]
//! number      := [+|-] digits [. digits] [(e|E) [+|-] digits]     (also "5." and ".5")
//! unit-expr   := numerator [ "/" denominator ]   |   "/" denominator
//! numerator   := "1" | product                   ("1" only in "1/...", e.g. "0.035 1/cm")
//! denominator := product | "(" product ")"       (everything after "/" is in the denominator)
//! product     := factor { [sep] factor }          (sep: "*", "·" U+00B7, "⋅" U+22C5 or whitespace)
//! factor      := unit [power]                      (no whitespace between unit and power)
//! power       := "^" int | "**" int | superscript  (int: [+|-] digits; superscripts ⁻ ⁰ ¹ ² ³ … ⁹)
//! unit        := name | prefix name              (names and prefixes in the tables below)
//! ```
//!
//! The SI value is `number × Π scale(unit)^power`, and the dimension is `Σ power × dim(unit)`. Decimal
//! scales are accumulated as an exact power of ten and applied by a single multiplication or division,
//! so `"x cm"` is exactly the correctly rounded `x / 100`.
//!
//! Named units (case-sensitive):
//!
//! | name              | SI value                | dimension      | prefixes |
//! |-------------------|-------------------------|----------------|----------|
//! | `m`               | 1 m                     | m              | yes      |
//! | `g`               | 10⁻³ kg                 | kg             | yes      |
//! | `t` (tonne)       | 10³ kg                  | kg             | no       |
//! | `s`               | 1 s                     | s              | yes      |
//! | `min`             | 60 s                    | s              | no       |
//! | `h` (hour)        | 3600 s                  | s              | no       |
//! | `N`               | 1 kg m s⁻²              | m kg s^-2      | yes      |
//! | `Pa`              | 1 kg m⁻¹ s⁻²            | m^-1 kg s^-2   | yes      |
//! | `J`               | 1 kg m² s⁻²             | m^2 kg s^-2    | yes      |
//! | `W`               | 1 kg m² s⁻³             | m^2 kg s^-3    | yes      |
//! | `Hz`              | 2π rad/s                | s^-1           | yes      |
//! | `rad`             | 1                       | dimensionless  | yes      |
//! | `cycle`, `cycles` | 2π                      | dimensionless  | no       |
//! | `deg`             | π/180                   | dimensionless  | no       |
//!
//! Prefixes: `G` 10⁹, `M` 10⁶, `k` 10³, `c` 10⁻², `m` 10⁻³, `u` / `µ` (U+00B5) / `μ` (U+03BC) 10⁻⁶,
//! `n` 10⁻⁹. There is **no hecto** (`h` is the hour) and no deca.
//!
//! ## Ambiguities, resolved deterministically
//! 1. A unit token (a maximal run of letters) is first matched *whole* against the names; only if that
//!    fails is it split as one prefix character + a prefixable name. So `m` is metre, `min` is minute,
//!    `mm` is millimetre, `ms` is millisecond, `Ms` is megasecond, `kg` is kilogram, `h` is hour.
//! 2. Juxtaposed letters are never a product: `mN` is milli-newton, not metre·newton; `Nm` is rejected
//!    (write `N m` or `N*m`, the error message says so); `mHz` is milli-hertz.
//! 3. `.` is never a multiplication sign (it is the decimal point); `N.m` is rejected.
//! 4. Only one `/`: `m/s/s` is rejected; write `m/s^2` or `m/(s s)`.
//! 5. Percent is **not** accepted: `"20 %"` is an error; write the fraction `0.2`. (A silent factor of
//!    0.01 next to damping ratios is too easy to get wrong.)
//! 6. A number is required: `"m"` alone is an error. `"1/s"` is the number 1 followed by the unit `/s`,
//!    and in general `"5/s"` is 5 per second.
//! 7. Matching is case-sensitive: `KN`, `HZ`, `Kg` are unknown units.
//!
//! # Errors
//! Every failure is [`Error::Unit`] with the text as written and a reason naming the offending token:
//! empty text, missing or non-finite number (`1e400`, `inf`, `NaN`), unknown unit, dangling operator
//! (`"3 m/"`, `"3 m*"`, `"3 m^"`), misplaced number or power, second `/`, unbalanced parenthesis, `%`,
//! a value that overflows after conversion, and — in [`parse_as`] — a dimension mismatch, reported with
//! both dimensions in readable form (`m s^-1`, `dimensionless`; see the `Display` impl of [`Dim`]).
//!
//! # Examples
//! ```
//! use stochvib::units::{parse_as, parse_quantity, Dim};
//!
//! assert_eq!(parse_as("70 kN/m", Dim::STIFFNESS).unwrap(), 70_000.0);
//! assert_eq!(parse_as("36 km/h", Dim::VELOCITY).unwrap(), 10.0);
//! assert_eq!(parse_as("3.5 cm", Dim::LENGTH).unwrap(), 0.035);
//! assert_eq!(parse_quantity("1 t").unwrap(), (1000.0, Dim::MASS));
//! assert_eq!(parse_quantity("9.81 m/s²").unwrap(), (9.81, Dim::ACCELERATION));
//!
//! // Hz is cycles per second: the SI value is angular (rad/s).
//! let w = parse_as("2 Hz", Dim::FREQUENCY).unwrap();
//! assert!((w - 4.0 * std::f64::consts::PI).abs() < 1e-15);
//!
//! // Dimension mismatch names both dimensions.
//! let err = parse_as("5 m/s", Dim::LENGTH).unwrap_err().to_string();
//! assert!(err.contains("m s^-1") && err.contains("expected m"), "{err}");
//!
//! // Unknown units and ambiguous juxtapositions are rejected.
//! assert!(parse_quantity("3 furlong").is_err());
//! assert!(parse_quantity("2.5e4 Nm").is_err());
//! assert_eq!(parse_quantity("2.5e4 N m").unwrap(), (2.5e4, Dim::TORQUE));
//! ```

use std::f64::consts::PI;
use std::fmt;

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
    /// Cubic metre (e.g. a road-displacement spectral density per unit wavenumber, m²/(rad/m)).
    pub const VOLUME: Dim = Dim::new(3, 0, 0);
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

    /// `self × other^power`, or `None` if an exponent leaves the `i8` range.
    fn times_pow(self, other: Dim, power: i32) -> Option<Dim> {
        let f = |a: i8, b: i8| -> Option<i8> {
            let v = i32::from(a).checked_add(i32::from(b).checked_mul(power)?)?;
            i8::try_from(v).ok()
        };
        Some(Dim::new(
            f(self.m, other.m)?,
            f(self.kg, other.kg)?,
            f(self.s, other.s)?,
        ))
    }
}

/// Readable form: `m^2 kg s^-2`, `m s^-1`, `kg`, or `dimensionless`. Exponent 1 is omitted and zero
/// exponents are left out. The output (other than `dimensionless`) is itself a valid unit expression:
/// `parse_quantity(&format!("1 {d}"))` gives `(1.0, d)`.
impl fmt::Display for Dim {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == Dim::DIMENSIONLESS {
            return f.write_str("dimensionless");
        }
        let mut first = true;
        for (name, e) in [("m", self.m), ("kg", self.kg), ("s", self.s)] {
            if e == 0 {
                continue;
            }
            if !first {
                f.write_str(" ")?;
            }
            first = false;
            if e == 1 {
                f.write_str(name)?;
            } else {
                write!(f, "{name}^{e}")?;
            }
        }
        Ok(())
    }
}

/// Largest magnitude of a physical input value (SI): products and powers of a few such values stay far from
/// the overflow of f64 (≈ 1.8e308), so a result can never become infinite or NaN from the inputs' sizes alone.
pub const MAX_INPUT_MAGNITUDE: f64 = 1e100;
/// Smallest non-zero magnitude of a physical input value (SI), for the same reason (underflow to zero and
/// division by a subnormal).
pub const MIN_INPUT_MAGNITUDE: f64 = 1e-100;

/// Checks that an input value is finite and, unless zero, within [`MIN_INPUT_MAGNITUDE`,
/// `MAX_INPUT_MAGNITUDE`] in magnitude.
///
/// # Errors
/// The reason, as text.
///
/// # Examples
/// ```
/// use stochvib::units::check_magnitude;
/// assert_eq!(check_magnitude(0.035), Ok(0.035));
/// assert!(check_magnitude(1e300).is_err() && check_magnitude(1e-320).is_err() && check_magnitude(f64::NAN).is_err());
/// ```
pub fn check_magnitude(x: f64) -> std::result::Result<f64, String> {
    if !x.is_finite() {
        return Err(format!("number {x} is not finite"));
    }
    let a = x.abs();
    if a != 0.0 && !(MIN_INPUT_MAGNITUDE..=MAX_INPUT_MAGNITUDE).contains(&a) {
        return Err(format!(
            "{x:e} (SI) is outside the working range of physical inputs, {MIN_INPUT_MAGNITUDE:e} to \
             {MAX_INPUT_MAGNITUDE:e} in magnitude (or 0): check the units"
        ));
    }
    Ok(x)
}

/// Parses `"<number> [unit expression]"` into its SI value and dimension.
///
/// The grammar, the unit and prefix tables and the angular convention (`Hz` → rad/s) are in the
/// [module documentation](self).
///
/// # Errors
/// [`Error::Unit`] for empty text, a missing or non-finite number, an unknown unit, a dangling or
/// misplaced operator, or a value that overflows after conversion.
///
/// # Examples
/// ```
/// use stochvib::units::{parse_quantity, Dim};
/// assert_eq!(parse_quantity("0.5").unwrap(), (0.5, Dim::DIMENSIONLESS));
/// assert_eq!(parse_quantity("3000 N*s/m").unwrap(), (3000.0, Dim::DAMPING));
/// assert_eq!(parse_quantity("450 kg m^2").unwrap(), (450.0, Dim::INERTIA));
/// ```
pub fn parse_quantity(text: &str) -> Result<(f64, Dim)> {
    parse_quantity_in(text, Reading::Angular)
}

/// Parses a sample rate (a count of samples per second): `"200 Hz"`, `"200 1/s"`, `"200 S/s"`, `"2 kS/s"`,
/// `"200 samples/s"`, `"0.2 1/ms"` → 200 (per second). Here `Hz` is one event per second — not 2π rad/s as
/// in [`parse_quantity`] — and `S` (`sample`, `samples`) counts samples; an angle (`rad`, `cycle`, `deg`) is
/// refused. Every other unit reads as in [`parse_quantity`]; a bare number is refused (it has no dimension).
///
/// # Errors
/// [`Error::Unit`] for everything [`parse_quantity`] rejects, an angle, and a dimension other than `s^-1`.
///
/// # Examples
/// ```
/// use stochvib::units::parse_sample_rate;
/// assert_eq!(parse_sample_rate("200 Hz").unwrap(), 200.0);
/// assert_eq!(parse_sample_rate("200 1/s").unwrap(), 200.0);
/// assert_eq!(parse_sample_rate("2 kS/s").unwrap(), 2000.0);
/// assert!(parse_sample_rate("200 rad/s").is_err() && parse_sample_rate("200 m").is_err());
/// ```
pub fn parse_sample_rate(text: &str) -> Result<f64> {
    let (v, d) = parse_quantity_in(text, Reading::Count)?;
    if d != Dim::FREQUENCY {
        return Err(Error::Unit {
            text: text.to_string(),
            reason: format!(
                "dimension is {d}, expected s^-1 (a sample rate: samples per second, e.g. \"200 Hz\", \"200 1/s\" \
                 or \"200 S/s\")"
            ),
        });
    }
    Ok(v)
}

/// How a unit expression reads frequencies: as angles per second (`Hz` = 2π rad/s; [`parse_quantity`]) or
/// as counts of events per second (`Hz` = 1/s, `S` a sample; [`parse_sample_rate`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Reading {
    Angular,
    Count,
}

/// [`parse_quantity`] in the reading `reading`.
fn parse_quantity_in(text: &str, reading: Reading) -> Result<(f64, Dim)> {
    let err = |reason: String| Error::Unit {
        text: text.to_string(),
        reason,
    };
    let trimmed = text.trim();
    if trimmed.is_empty() {
        return Err(err(
            "empty text; expected a number followed by an optional unit, e.g. \"3.5 cm\"".into(),
        ));
    }
    let (number_str, rest) = split_number(trimmed).ok_or_else(|| {
        err(format!(
            "expected a number at the start, found `{}` (write e.g. \"1 {}\")",
            trimmed, trimmed
        ))
    })?;
    let number: f64 = number_str
        .parse()
        .map_err(|_| err(format!("malformed number `{number_str}`")))?;
    if !number.is_finite() {
        return Err(err(format!("number `{number_str}` is not finite")));
    }
    let tokens = tokenize(rest).map_err(err)?;
    let unit = parse_unit_expr(&tokens, reading).map_err(err)?;
    if !unit.scale_is_representable() {
        return Err(err(format!(
            "the scale of unit `{}` is outside the range of f64",
            rest.trim()
        )));
    }
    let value = unit.apply(number);
    if !value.is_finite() {
        return Err(err(format!(
            "value {number_str} converted to SI is not finite (overflow)"
        )));
    }
    let value = check_magnitude(value).map_err(err)?;
    Ok((value, unit.dim))
}

/// The dimension of a coherent SI unit written as text (`"m"`, `"m/s^2"`, `"N"`, `"rad"`, `"1"`), or `None`
/// when the text is not such a unit (unknown, or a unit with a scale other than 1, e.g. `"cm"`).
///
/// # Examples
/// ```
/// use stochvib::units::{unit_dim, Dim};
/// assert_eq!(unit_dim("m/s^2"), Some(Dim::ACCELERATION));
/// assert_eq!(unit_dim("1"), Some(Dim::DIMENSIONLESS));
/// assert_eq!(unit_dim("cm"), None);
/// assert_eq!(unit_dim("[mixed]"), None);
/// ```
pub fn unit_dim(unit: &str) -> Option<Dim> {
    if unit.trim() == "1" || unit.trim() == "-" {
        return Some(Dim::DIMENSIONLESS);
    }
    match parse_quantity(&format!("1 {unit}")) {
        Ok((1.0, dim)) => Some(dim),
        _ => None,
    }
}

/// Parses a quantity and checks that it has dimension `expected`.
///
/// # Errors
/// [`Error::Unit`] for everything [`parse_quantity`] rejects, and for a dimension mismatch; the reason
/// then names both dimensions, e.g. `dimension is m s^-1, expected m`.
///
/// # Examples
/// ```
/// use stochvib::units::{parse_as, Dim};
/// assert_eq!(parse_as("1.5 kN·s/m", Dim::DAMPING).unwrap(), 1500.0);
/// assert!(parse_as("1.5 kN", Dim::DAMPING).is_err());
/// ```
pub fn parse_as(text: &str, expected: Dim) -> Result<f64> {
    let (v, d) = parse_quantity(text)?;
    if d != expected {
        let hint = if d == Dim::DIMENSIONLESS {
            " (no unit was given; write one, e.g. \"1 m\")"
        } else {
            ""
        };
        return Err(Error::Unit {
            text: text.to_string(),
            reason: format!("dimension is {d}, expected {expected}{hint}"),
        });
    }
    Ok(v)
}

/// Reads a quantity from a TOML value.
///
/// * A TOML float or integer is taken as **already SI in the expected dimension** (`k = 70000` for a
///   stiffness means 70000 N/m). It must be finite.
/// * A TOML string is parsed with units by [`parse_as`] and must have dimension `expected`. A string
///   without a unit is dimensionless, so `"0.5"` is accepted only where a dimensionless value is
///   expected (write `0.5` without quotes to mean an SI number).
///
/// On failure it returns the bare reason; callers wrap it into an error naming the file and the key.
///
/// # Examples
/// ```
/// use stochvib::units::{parse_value, Dim};
/// let v = toml::Value::String("3.5 cm".into());
/// assert_eq!(parse_value(&v, Dim::LENGTH), Ok(0.035));
/// assert_eq!(parse_value(&toml::Value::Integer(1200), Dim::MASS), Ok(1200.0));
/// assert!(parse_value(&toml::Value::Boolean(true), Dim::MASS).is_err());
/// ```
pub fn parse_value(v: &toml::Value, expected: Dim) -> std::result::Result<f64, String> {
    match v {
        toml::Value::Float(x) => check_magnitude(*x),
        // i64 → f64 rounds beyond 2^53; no physical input is that precise.
        toml::Value::Integer(i) => check_magnitude(*i as f64),
        toml::Value::String(s) => match parse_as(s, expected) {
            Ok(x) => Ok(x),
            Err(Error::Unit { reason, .. }) => Err(reason),
            Err(other) => Err(other.to_string()),
        },
        other => Err(format!(
            "expected a number (SI, {expected}) or a quantity string like \"3.5 cm\", found a {}",
            other.type_str()
        )),
    }
}

// ---------------------------------------------------------------------------------------------------
// Implementation
// ---------------------------------------------------------------------------------------------------

/// Splits the leading number off `s` (already trimmed). Returns `None` if `s` does not start with one.
pub(crate) fn split_number(s: &str) -> Option<(&str, &str)> {
    let b = s.as_bytes();
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let int_start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let mut digits = i - int_start;
    if i < b.len() && b[i] == b'.' {
        let frac_start = i + 1;
        let mut j = frac_start;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        digits += j - frac_start;
        i = j;
    }
    if digits == 0 {
        return None;
    }
    // Exponent only if followed by at least one digit ("2em" is the number 2 and the unit `em`).
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        let mut j = i + 1;
        if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        let exp_start = j;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        if j > exp_start {
            i = j;
        }
    }
    Some((&s[..i], &s[i..]))
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    /// A run of letters: a unit with optional prefix.
    Word(String),
    /// The literal `1` (only valid as the numerator of `1/...`).
    One,
    /// `*`, `·` or `⋅`.
    Star,
    /// `/`.
    Slash,
    /// An integer power; `spaced` records whitespace before it (not allowed).
    Pow {
        p: i32,
        text: String,
        spaced: bool,
    },
    LParen,
    RParen,
}

fn superscript_digit(c: char) -> Option<u32> {
    match c {
        '⁰' => Some(0),
        '¹' => Some(1),
        '²' => Some(2),
        '³' => Some(3),
        '⁴' => Some(4),
        '⁵' => Some(5),
        '⁶' => Some(6),
        '⁷' => Some(7),
        '⁸' => Some(8),
        '⁹' => Some(9),
        _ => None,
    }
}

fn parse_power_int(digits: &str, negative: bool, text: &str) -> std::result::Result<i32, String> {
    let p: i32 = digits
        .parse()
        .ok()
        .filter(|p: &i32| *p <= 99)
        .ok_or_else(|| format!("power `{text}` is too large"))?;
    Ok(if negative { -p } else { p })
}

fn tokenize(s: &str) -> std::result::Result<Vec<Tok>, String> {
    let chars: Vec<char> = s.chars().collect();
    let mut toks = Vec::new();
    let mut i = 0;
    let mut spaced = false;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            spaced = true;
            i += 1;
            continue;
        }
        let was_spaced = std::mem::replace(&mut spaced, false);
        let (tok, next) = if c == '^' || (c == '*' && chars.get(i + 1) == Some(&'*')) {
            ascii_power(&chars, i, was_spaced)?
        } else if c == '⁻' || c == '⁺' || superscript_digit(c).is_some() {
            superscript_power(&chars, i, was_spaced)?
        } else if c.is_ascii_digit() {
            leading_one(&chars, i)?
        } else if c.is_alphabetic() {
            let mut j = i;
            while j < chars.len() && chars[j].is_alphabetic() {
                j += 1;
            }
            (Tok::Word(chars[i..j].iter().collect()), j)
        } else {
            (single_char_token(c)?, i + 1)
        };
        toks.push(tok);
        i = next;
    }
    Ok(toks)
}

/// The token of a one-character operator or parenthesis, or why `c` is refused.
fn single_char_token(c: char) -> std::result::Result<Tok, String> {
    match c {
        '*' | '·' | '⋅' => Ok(Tok::Star),
        '/' => Ok(Tok::Slash),
        '(' => Ok(Tok::LParen),
        ')' => Ok(Tok::RParen),
        '.' => Err("`.` is not a multiplication sign (it is the decimal point); write `*`, `·` or a space".into()),
        '%' => Err("`%` is not supported: write the fraction as a plain number (20 % → 0.2)".into()),
        _ => Err(format!("unexpected character `{c}`")),
    }
}

/// The power `^p` or `**p` (an optional sign, then digits) at `chars[i]`, and the index after it.
fn ascii_power(chars: &[char], i: usize, spaced: bool) -> std::result::Result<(Tok, usize), String> {
    let op_len = if chars[i] == '^' { 1 } else { 2 };
    let op: String = chars[i..i + op_len].iter().collect();
    let mut j = i + op_len;
    let negative = match chars.get(j) {
        Some('-') => {
            j += 1;
            true
        }
        Some('+') => {
            j += 1;
            false
        }
        _ => false,
    };
    let start = j;
    while j < chars.len() && chars[j].is_ascii_digit() {
        j += 1;
    }
    let text: String = chars[i..j].iter().collect();
    if j == start {
        return Err(format!(
            "dangling `{op}`: expected an integer power after it, e.g. `m{op}2`"
        ));
    }
    let digits: String = chars[start..j].iter().collect();
    let p = parse_power_int(&digits, negative, &text)?;
    Ok((Tok::Pow { p, text, spaced }, j))
}

/// The superscript power (`⁻²`, `³`) at `chars[i]`, and the index after it.
fn superscript_power(chars: &[char], i: usize, spaced: bool) -> std::result::Result<(Tok, usize), String> {
    let c = chars[i];
    let mut j = i;
    let negative = c == '⁻';
    if c == '⁻' || c == '⁺' {
        j += 1;
    }
    let start = j;
    let mut digits = String::new();
    while let Some(d) = chars.get(j).and_then(|&c| superscript_digit(c)) {
        digits.push(char::from_digit(d, 10).unwrap_or('0'));
        j += 1;
    }
    let text: String = chars[i..j].iter().collect();
    if j == start {
        return Err(format!("dangling superscript `{text}`: expected digits after it"));
    }
    let p = parse_power_int(&digits, negative, &text)?;
    Ok((Tok::Pow { p, text, spaced }, j))
}

/// The number at `chars[i]`: only `1` (of `1/...`) may stand in a unit.
fn leading_one(chars: &[char], i: usize) -> std::result::Result<(Tok, usize), String> {
    let mut j = i;
    while j < chars.len() && (chars[j].is_ascii_digit() || chars[j] == '.') {
        j += 1;
    }
    let num: String = chars[i..j].iter().collect();
    if num != "1" {
        return Err(format!(
            "unexpected number `{num}` inside the unit (the number goes first; only `1/...` \
             may start a unit)"
        ));
    }
    Ok((Tok::One, j))
}

/// A unit: value = number × `num` / `den` × 10^`pow10`, with dimension `dim`.
#[derive(Debug, Clone, Copy)]
struct Unit {
    num: f64,
    den: f64,
    pow10: i32,
    dim: Dim,
}

impl Unit {
    const ONE: Unit = Unit {
        num: 1.0,
        den: 1.0,
        pow10: 0,
        dim: Dim::DIMENSIONLESS,
    };

    /// Whether the scale factor is a finite, non-zero `f64` (false for absurd powers like `nm^99`).
    fn scale_is_representable(&self) -> bool {
        let ok = |x: f64| x.is_finite() && x != 0.0 && x.abs().log10().abs() < 300.0;
        ok(self.num) && ok(self.den) && self.pow10.abs() <= 300
    }

    /// Converts `x` in this unit to SI with as few roundings as possible: the power of ten joins the
    /// numerator or the denominator as an exact `f64` (up to 10^22), so `x cm` is exactly `x / 100`.
    fn apply(&self, x: f64) -> f64 {
        let p10 = 10f64.powi(self.pow10.abs());
        let (num, den) = if self.pow10 >= 0 {
            (self.num * p10, self.den)
        } else {
            (self.num, self.den * p10)
        };
        if num == 1.0 {
            x / den
        } else if den == 1.0 {
            x * num
        } else {
            x * num / den
        }
    }

    /// `self × other^power`.
    fn times_pow(self, other: &Unit, power: i32) -> std::result::Result<Unit, String> {
        let dim = self
            .dim
            .times_pow(other.dim, power)
            .ok_or_else(|| "dimension exponent out of range".to_string())?;
        let (n, d) = if power >= 0 {
            (other.num.powi(power), other.den.powi(power))
        } else {
            (other.den.powi(-power), other.num.powi(-power))
        };
        Ok(Unit {
            num: self.num * n,
            den: self.den * d,
            pow10: self.pow10 + other.pow10 * power,
            dim,
        })
    }
}

/// Named unit: (name, numerator, denominator, power of ten, dimension, accepts prefixes).
type NamedUnit = (&'static str, f64, f64, i32, Dim, bool);

const UNITS: &[NamedUnit] = &[
    ("m", 1.0, 1.0, 0, Dim::LENGTH, true),
    ("g", 1.0, 1.0, -3, Dim::MASS, true),
    ("t", 1.0, 1.0, 3, Dim::MASS, false),
    ("s", 1.0, 1.0, 0, Dim::TIME, true),
    ("min", 60.0, 1.0, 0, Dim::TIME, false),
    ("h", 3600.0, 1.0, 0, Dim::TIME, false),
    ("N", 1.0, 1.0, 0, Dim::FORCE, true),
    ("Pa", 1.0, 1.0, 0, Dim::new(-1, 1, -2), true),
    ("J", 1.0, 1.0, 0, Dim::TORQUE, true),
    ("W", 1.0, 1.0, 0, Dim::new(2, 1, -3), true),
    ("Hz", 2.0 * PI, 1.0, 0, Dim::FREQUENCY, true),
    ("rad", 1.0, 1.0, 0, Dim::DIMENSIONLESS, true),
    ("cycle", 2.0 * PI, 1.0, 0, Dim::DIMENSIONLESS, false),
    ("cycles", 2.0 * PI, 1.0, 0, Dim::DIMENSIONLESS, false),
    ("deg", PI, 180.0, 0, Dim::DIMENSIONLESS, false),
];

/// The units of [`Reading::Count`] that differ from [`UNITS`]: `Hz` is one event per second and a sample
/// `S` (`sample`, `samples`) is a count; the angles of [`UNITS`] (its dimensionless units) are not counts.
const COUNT_UNITS: &[NamedUnit] = &[
    ("Hz", 1.0, 1.0, 0, Dim::FREQUENCY, true),
    ("S", 1.0, 1.0, 0, Dim::DIMENSIONLESS, true),
    ("sample", 1.0, 1.0, 0, Dim::DIMENSIONLESS, false),
    ("samples", 1.0, 1.0, 0, Dim::DIMENSIONLESS, false),
];

/// The named unit `name` in `reading`.
fn named_unit(name: &str, reading: Reading) -> Option<&'static NamedUnit> {
    let angular = || UNITS.iter().find(|u| u.0 == name);
    match reading {
        Reading::Angular => angular(),
        Reading::Count => COUNT_UNITS
            .iter()
            .find(|u| u.0 == name)
            .or_else(|| angular().filter(|u| u.4 != Dim::DIMENSIONLESS)),
    }
}

const PREFIXES: &[(char, i32)] = &[
    ('G', 9),
    ('M', 6),
    ('k', 3),
    ('c', -2),
    ('m', -3),
    ('u', -6),
    ('µ', -6),
    ('μ', -6),
    ('n', -9),
];

/// Whole-name match first, then one prefix character + a prefixable name.
fn lookup_unit(word: &str, reading: Reading) -> Option<Unit> {
    let named = |name: &str| named_unit(name, reading);
    if let Some(&(_, num, den, pow10, dim, _)) = named(word) {
        return Some(Unit { num, den, pow10, dim });
    }
    let mut chars = word.chars();
    let first = chars.next()?;
    let rest = chars.as_str();
    let &(_, p) = PREFIXES.iter().find(|(c, _)| *c == first)?;
    let &(_, num, den, pow10, dim, prefixable) = named(rest)?;
    prefixable.then_some(Unit {
        num,
        den,
        pow10: pow10 + p,
        dim,
    })
}

fn unknown_unit(word: &str, reading: Reading) -> String {
    if reading == Reading::Count && lookup_unit(word, Reading::Angular).is_some() {
        return format!(
            "`{word}` is an angle, not a count: a sample rate is in samples per second (write e.g. \"200 Hz\", \
             \"200 1/s\" or \"200 S/s\")"
        );
    }
    let lookup_unit = |w: &str| lookup_unit(w, reading);
    let mut reason = format!("unknown unit `{word}`");
    // A product written without a separator, e.g. `Nm`, `kgm`.
    let split = word
        .char_indices()
        .skip(1)
        .map(|(i, _)| word.split_at(i))
        .find(|(a, b)| lookup_unit(a).is_some() && lookup_unit(b).is_some());
    if word.starts_with('h') && lookup_unit(&word[1..]).is_some() {
        reason.push_str(
            " (the hecto prefix is not supported: `h` is the hour; \
             for hour times a unit write a space or `*`)",
        );
    } else if let Some((a, b)) = split {
        reason.push_str(&format!(
            " (for a product write `{a} {b}` or `{a}*{b}`; letters written together are one unit)"
        ));
    } else {
        let known = match reading {
            Reading::Angular => "m g t s min h N Pa J W Hz rad cycle cycles deg",
            Reading::Count => "m g t s min h N Pa J W Hz S sample samples",
        };
        reason.push_str(&format!(" (known: {known}, prefixes G M k c m u µ n)"));
    }
    reason
}

fn describe(t: &Tok) -> String {
    match t {
        Tok::Word(w) => format!("`{w}`"),
        Tok::One => "`1`".into(),
        Tok::Star => "`*`".into(),
        Tok::Slash => "`/`".into(),
        Tok::Pow { text, .. } => format!("`{text}`"),
        Tok::LParen => "`(`".into(),
        Tok::RParen => "`)`".into(),
    }
}

/// Parses `product := factor { [sep] factor }` starting at `*i`; stops before `/`, `)` or the end.
fn parse_product(toks: &[Tok], i: &mut usize, reading: Reading) -> std::result::Result<Unit, String> {
    let mut unit = Unit::ONE;
    loop {
        let word = match toks.get(*i) {
            Some(Tok::Word(w)) => w,
            Some(Tok::Pow { text, .. }) => return Err(format!("power `{text}` does not follow a unit")),
            Some(Tok::Star) => return Err("dangling `*`: expected a unit before it".into()),
            Some(Tok::Slash) => return Err("dangling `/`: expected a unit before it".into()),
            Some(t) => return Err(format!("expected a unit, found {}", describe(t))),
            None => return Err("expected a unit, found the end of the text".into()),
        };
        let factor = lookup_unit(word, reading).ok_or_else(|| unknown_unit(word, reading))?;
        *i += 1;
        let mut power = 1;
        if let Some(Tok::Pow { p, text, spaced }) = toks.get(*i) {
            if *spaced {
                return Err(format!(
                    "power `{text}` must follow the unit directly, e.g. `{word}{text}`"
                ));
            }
            power = *p;
            *i += 1;
        }
        unit = unit.times_pow(&factor, power)?;
        match toks.get(*i) {
            Some(Tok::Star) => {
                *i += 1;
                if !matches!(toks.get(*i), Some(Tok::Word(_))) {
                    return Err(match toks.get(*i) {
                        Some(t) => format!("dangling `*`: expected a unit after it, found {}", describe(t)),
                        None => "dangling `*`: expected a unit after it".into(),
                    });
                }
            }
            Some(Tok::Word(_)) => {}
            Some(Tok::Pow { text, .. }) => return Err(format!("power `{text}` follows another power")),
            _ => return Ok(unit),
        }
    }
}

fn parse_unit_expr(toks: &[Tok], reading: Reading) -> std::result::Result<Unit, String> {
    let mut i = 0;
    let numerator = match toks.first() {
        None => return Ok(Unit::ONE),
        Some(Tok::One) => {
            if toks.get(1) != Some(&Tok::Slash) {
                return Err("`1` inside a unit is only allowed as `1/...`, e.g. `1/cm`".into());
            }
            i = 1;
            Unit::ONE
        }
        Some(Tok::Slash) => Unit::ONE,
        Some(_) => parse_product(toks, &mut i, reading)?,
    };
    let mut unit = numerator;
    if toks.get(i) == Some(&Tok::Slash) {
        i += 1;
        let den = match toks.get(i) {
            None => return Err("dangling `/`: expected a unit after it".into()),
            Some(Tok::LParen) => {
                i += 1;
                let d = parse_product(toks, &mut i, reading)?;
                if toks.get(i) != Some(&Tok::RParen) {
                    return Err("unbalanced `(`: expected `)` after the denominator".into());
                }
                i += 1;
                d
            }
            Some(_) => parse_product(toks, &mut i, reading)?,
        };
        unit = unit.times_pow(&den, -1)?;
    }
    match toks.get(i) {
        None => Ok(unit),
        Some(Tok::Slash) => Err(
            "only one `/` is allowed; everything after `/` is already in the denominator \
             (write `m/s^2` or `m/(s s)`)"
                .into(),
        ),
        Some(Tok::RParen) => Err("unbalanced `)`".into()),
        Some(Tok::LParen) => Err("parentheses are only allowed around the whole denominator, e.g. `kg/(m s)`".into()),
        Some(t) => Err(format!("unexpected {} after the unit", describe(t))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::ULPS;
    use proptest::prelude::*;

    /// |a − b| ≤ ULPS relative.
    fn close(a: f64, b: f64) -> bool {
        a == b || (a - b).abs() <= ULPS * b.abs().max(a.abs())
    }

    #[track_caller]
    fn check(text: &str, value: f64, dim: Dim) {
        let (v, d) = parse_quantity(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(d, dim, "{text}");
        assert!(close(v, value), "{text}: got {v:e}, expected {value:e}");
    }

    #[track_caller]
    fn reason(text: &str) -> String {
        match parse_quantity(text) {
            Err(Error::Unit { text: t, reason }) => {
                assert_eq!(t, text);
                reason
            }
            other => panic!("{text}: expected a unit error, got {other:?}"),
        }
    }

    // Expected values below follow from the SI definitions of the units and prefixes.

    #[test]
    fn brief_examples() {
        check("2.25 cm^2", 2.25e-4, Dim::AREA);
        check("0.035 1/cm", 3.5, Dim::WAVENUMBER);
        check("70 kN/m", 70_000.0, Dim::STIFFNESS);
        check("3.5 cm", 0.035, Dim::LENGTH);
        check("1200 kg", 1200.0, Dim::MASS);
        check("5 m/s", 5.0, Dim::VELOCITY);
        check("36 km/h", 10.0, Dim::VELOCITY);
        check("0.16e-2 1/cm", 0.16, Dim::WAVENUMBER);
        check("16e-6 m^3", 16e-6, Dim::VOLUME);
        check("2 Hz", 4.0 * PI, Dim::FREQUENCY);
        check("12 rad/s", 12.0, Dim::FREQUENCY);
        check("0.1 cycles/m", 0.2 * PI, Dim::WAVENUMBER);
        check("3000 N*s/m", 3000.0, Dim::DAMPING);
        check("1.5 kN·s/m", 1500.0, Dim::DAMPING);
        check("1 kN·s/m", 1000.0, Dim::DAMPING);
        check("2.5e4 N m", 2.5e4, Dim::TORQUE);
        check("450 kg m^2", 450.0, Dim::INERTIA);
        check("9.81 m/s^2", 9.81, Dim::ACCELERATION);
        check("4 mm", 4e-3, Dim::LENGTH);
        check("1 t", 1000.0, Dim::MASS);
        check("0.5", 0.5, Dim::DIMENSIONLESS);
        check("1/s", 1.0, Dim::FREQUENCY);
        check("5 s^-1", 5.0, Dim::FREQUENCY);
        check("3 m²", 3.0, Dim::AREA);
        check("3 m³", 3.0, Dim::VOLUME);
        check("7 s⁻¹", 7.0, Dim::FREQUENCY);
    }

    #[test]
    fn exact_where_representable() {
        assert_eq!(parse_as("70 kN/m", Dim::STIFFNESS).unwrap(), 70_000.0);
        assert_eq!(parse_as("36 km/h", Dim::VELOCITY).unwrap(), 10.0);
        assert_eq!(parse_as("3.5 cm", Dim::LENGTH).unwrap(), 3.5 / 100.0);
        assert_eq!(parse_as("1 kN·s/m", Dim::DAMPING).unwrap(), 1000.0);
        assert_eq!(parse_as("2 min", Dim::TIME).unwrap(), 120.0);
        assert_eq!(parse_as("1.5 h", Dim::TIME).unwrap(), 5400.0);
    }

    #[test]
    fn operators_and_powers() {
        check("9.81 m/s²", 9.81, Dim::ACCELERATION);
        check("9.81 m s^-2", 9.81, Dim::ACCELERATION);
        check("9.81 m*s**-2", 9.81, Dim::ACCELERATION);
        check("9.81 m/(s s)", 9.81, Dim::ACCELERATION);
        check("9.81 m / s^2", 9.81, Dim::ACCELERATION);
        check("2 kg/(m s)", 2.0, Dim::new(-1, 1, -1));
        check("2 kg/m s", 2.0, Dim::new(-1, 1, -1));
        check("2 kg·m²", 2.0, Dim::INERTIA);
        check("2 kg⋅m^+2", 2.0, Dim::INERTIA);
        check("5/s", 5.0, Dim::FREQUENCY);
        check("4mm", 4e-3, Dim::LENGTH);
        check("2e3m", 2e3, Dim::LENGTH);
        check("-3 cm", -0.03, Dim::LENGTH);
        check("+.5 m", 0.5, Dim::LENGTH);
        check("5. m", 5.0, Dim::LENGTH);
        check("  2 m  ", 2.0, Dim::LENGTH);
        check("1 m^-2", 1.0, Dim::new(-2, 0, 0));
        check("3 cm^-1", 300.0, Dim::WAVENUMBER);
        check("1 m^0", 1.0, Dim::DIMENSIONLESS);
    }

    #[test]
    fn prefixes_and_ambiguities() {
        check("1 m", 1.0, Dim::LENGTH);
        check("1 mm", 1e-3, Dim::LENGTH);
        check("1 ms", 1e-3, Dim::TIME);
        check("1 Ms", 1e6, Dim::TIME);
        check("1 min", 60.0, Dim::TIME);
        check("1 h", 3600.0, Dim::TIME);
        check("1 km", 1e3, Dim::LENGTH);
        check("1 Gm", 1e9, Dim::LENGTH);
        check("1 um", 1e-6, Dim::LENGTH);
        check("1 µm", 1e-6, Dim::LENGTH);
        check("1 μm", 1e-6, Dim::LENGTH);
        check("1 nm", 1e-9, Dim::LENGTH);
        check("1 g", 1e-3, Dim::MASS);
        check("1 mg", 1e-6, Dim::MASS);
        check("1 Mg", 1e3, Dim::MASS);
        check("1 mN", 1e-3, Dim::FORCE);
        check("1 MPa", 1e6, Dim::new(-1, 1, -2));
        check("1 kJ", 1e3, Dim::TORQUE);
        check("1 kW", 1e3, Dim::new(2, 1, -3));
        check("1 kHz", 2e3 * PI, Dim::FREQUENCY);
        check("1 mHz", 2e-3 * PI, Dim::FREQUENCY);
        check("1 mrad", 1e-3, Dim::DIMENSIONLESS);
        check("1 cycle", 2.0 * PI, Dim::DIMENSIONLESS);
        check("180 deg", PI, Dim::DIMENSIONLESS);
        check("1 cycles/s", 2.0 * PI, Dim::FREQUENCY);
        check("60 cycles/min", 2.0 * PI, Dim::FREQUENCY);
    }

    #[test]
    fn errors_empty_and_number() {
        assert!(reason("").contains("empty"));
        assert!(reason("   ").contains("empty"));
        assert!(reason("m").contains("expected a number"));
        assert!(reason("s^-1").contains("expected a number"));
        assert!(reason("inf").contains("expected a number"));
        assert!(reason("NaN m").contains("expected a number"));
        assert!(reason(".").contains("expected a number"));
        assert!(reason("1e400 m").contains("`1e400` is not finite"));
        assert!(reason("1e308 Gm").contains("not finite"));
    }

    #[test]
    fn errors_unknown_units() {
        let r = reason("3 furlong");
        assert!(r.contains("unknown unit `furlong`"), "{r}");
        let r = reason("2.5e4 Nm");
        assert!(r.contains("`Nm`") && r.contains("`N m`"), "{r}");
        let r = reason("3 kgm");
        assert!(r.contains("`kg m`"), "{r}");
        let r = reason("3 hPa");
        assert!(r.contains("hecto"), "{r}");
        assert!(reason("3 KN").contains("`KN`"));
        assert!(reason("3 kt").contains("`kt`"));
        assert!(reason("3 kmin").contains("`kmin`"));
        assert!(reason("3 l").contains("`l`"));
        assert!(reason("2 em").contains("`em`"));
        assert!(reason("20 %").contains('%'));
        assert!(reason("20%").contains('%'));
        assert!(reason("3 N.m").contains("`.`"));
        assert!(reason("3 m#").contains("`#`"));
    }

    #[test]
    fn errors_operators() {
        assert!(reason("3 m/").contains("dangling `/`"));
        assert!(reason("3 m*").contains("dangling `*`"));
        assert!(reason("3 m*/s").contains("dangling `*`"));
        assert!(reason("3 *m").contains("dangling `*`"));
        assert!(reason("3 m^").contains("dangling `^`"));
        assert!(reason("3 m^x").contains("dangling `^`"));
        assert!(reason("3 m**").contains("dangling `**`"));
        assert!(reason("3 m⁻").contains("dangling superscript"));
        assert!(reason("3 ^2").contains("does not follow a unit"));
        assert!(reason("3 m ^2").contains("must follow the unit directly"));
        assert!(reason("3 m^2^2").contains("follows another power"));
        assert!(reason("3 m^999").contains("too large"));
        assert!(reason("3 m^99 m^99").contains("out of range"));
        assert!(reason("3 nm^99").contains("scale"));
        assert!(reason("3 m/s/s").contains("only one `/`"));
        assert!(reason("3 kg/(m s").contains("unbalanced `(`"));
        assert!(reason("3 kg/m)").contains("unbalanced `)`"));
        assert!(reason("3 (kg)/m").contains("expected a unit"));
        assert!(reason("3 kg/m (s)").contains("parentheses"));
        assert!(reason("3 1").contains("only allowed as `1/"));
        assert!(reason("3 2/s").contains("unexpected number `2`"));
        assert!(reason("3 m 1/s").contains("unexpected `1`"));
    }

    #[test]
    fn errors_dimension_mismatch() {
        let e = parse_as("5 m/s", Dim::LENGTH).unwrap_err();
        let Error::Unit { text, reason } = &e else {
            panic!("{e:?}")
        };
        assert_eq!(text, "5 m/s");
        assert_eq!(reason, "dimension is m s^-1, expected m");
        let e = parse_as("0.5", Dim::LENGTH).unwrap_err().to_string();
        assert!(
            e.contains("dimension is dimensionless, expected m") && e.contains("no unit"),
            "{e}"
        );
        let e = parse_as("70 kN", Dim::STIFFNESS).unwrap_err().to_string();
        assert!(e.contains("dimension is m kg s^-2, expected kg s^-2"), "{e}");
        // An error from parse_quantity passes through unchanged.
        assert!(parse_as("3 furlong", Dim::LENGTH)
            .unwrap_err()
            .to_string()
            .contains("unknown unit"));
    }

    #[test]
    fn display_dim() {
        assert_eq!(Dim::DIMENSIONLESS.to_string(), "dimensionless");
        assert_eq!(Dim::LENGTH.to_string(), "m");
        assert_eq!(Dim::MASS.to_string(), "kg");
        assert_eq!(Dim::FREQUENCY.to_string(), "s^-1");
        assert_eq!(Dim::TORQUE.to_string(), "m^2 kg s^-2");
        assert_eq!(Dim::STIFFNESS.to_string(), "kg s^-2");
        assert_eq!(Dim::new(-1, 1, -2).to_string(), "m^-1 kg s^-2");
    }

    #[test]
    fn display_round_trip_named() {
        for d in [
            Dim::LENGTH,
            Dim::AREA,
            Dim::VOLUME,
            Dim::MASS,
            Dim::TIME,
            Dim::FREQUENCY,
            Dim::WAVENUMBER,
            Dim::VELOCITY,
            Dim::ACCELERATION,
            Dim::FORCE,
            Dim::STIFFNESS,
            Dim::DAMPING,
            Dim::INERTIA,
            Dim::TORQUE,
        ] {
            assert_eq!(parse_quantity(&format!("1 {d}")).unwrap(), (1.0, d), "{d}");
        }
    }

    #[test]
    fn toml_values() {
        use toml::Value;
        assert_eq!(parse_value(&Value::Float(0.035), Dim::LENGTH), Ok(0.035));
        assert_eq!(parse_value(&Value::Integer(70000), Dim::STIFFNESS), Ok(70000.0));
        assert_eq!(
            parse_value(&Value::String("70 kN/m".into()), Dim::STIFFNESS),
            Ok(70000.0)
        );
        assert_eq!(parse_value(&Value::String("0.5".into()), Dim::DIMENSIONLESS), Ok(0.5));
        let r = parse_value(&Value::String("0.5".into()), Dim::LENGTH).unwrap_err();
        assert!(r.contains("dimensionless") && r.contains("expected m"), "{r}");
        let r = parse_value(&Value::String("3 furlong".into()), Dim::LENGTH).unwrap_err();
        assert!(r.starts_with("unknown unit `furlong`"), "{r}");
        assert!(parse_value(&Value::Float(f64::NAN), Dim::LENGTH)
            .unwrap_err()
            .contains("not finite"));
        assert!(parse_value(&Value::Float(f64::INFINITY), Dim::LENGTH)
            .unwrap_err()
            .contains("not finite"));
        let r = parse_value(&Value::Boolean(true), Dim::MASS).unwrap_err();
        assert!(r.contains("boolean") && r.contains("kg"), "{r}");
        // Values read from an actual TOML document.
        let doc: toml::Table = toml::from_str("a = 1.5\nb = \"36 km/h\"\nc = 2\n").unwrap();
        assert_eq!(parse_value(&doc["a"], Dim::VELOCITY), Ok(1.5));
        assert_eq!(parse_value(&doc["b"], Dim::VELOCITY), Ok(10.0));
        assert_eq!(parse_value(&doc["c"], Dim::VELOCITY), Ok(2.0));
    }

    /// A sample rate counts samples per second (no 2π): every spelling of 200 per second is 200.
    #[test]
    fn sample_rates_are_counts_per_second() {
        for text in [
            "200 Hz",
            "200 1/s",
            "200 /s",
            "200 S/s",
            "200 samples/s",
            "200 s^-1",
            "0.2 kHz",
            "0.2 kS/s",
        ] {
            let v = parse_sample_rate(text).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert!(close(v, 200.0), "{text}: {v}");
        }
        assert_eq!(parse_sample_rate("12000 1/min").unwrap(), 200.0);
        assert_eq!(parse_sample_rate("1 MS/s").unwrap(), 1e6);
    }

    /// Angles, other dimensions and bare numbers are no sample rates; the reason says what one is.
    #[test]
    fn sample_rate_errors() {
        let reason = |text: &str| match parse_sample_rate(text) {
            Err(Error::Unit { text: t, reason }) => {
                assert_eq!(t, text);
                reason
            }
            other => panic!("{text}: expected a unit error, got {other:?}"),
        };
        assert!(
            reason("200 rad/s").contains("`rad` is an angle"),
            "{}",
            reason("200 rad/s")
        );
        assert!(reason("200 cycles/s").contains("`cycles` is an angle"));
        for text in ["200 m", "200", "200 Hz s"] {
            assert!(
                reason(text).contains("expected s^-1 (a sample rate"),
                "{text}: {}",
                reason(text)
            );
        }
        assert!(reason("200 furlong/s").contains("known: m g t s min h N Pa J W Hz S sample samples"));
    }

    /// The sample-rate reading leaves every other parse as it was: `Hz` stays 2π rad/s and `S` unknown.
    #[test]
    fn the_angular_reading_is_unchanged() {
        check("2 Hz", 4.0 * PI, Dim::FREQUENCY);
        assert!(reason("200 S/s").starts_with("unknown unit `S`"));
        assert!(reason("3 samples").starts_with("unknown unit `samples`"));
    }

    proptest! {
        // a fixed seed: the same cases on every run (proptest's default seed is random)
        #![proptest_config(ProptestConfig { rng_seed: proptest::test_runner::RngSeed::Fixed(0x5eed_2026), failure_persistence: None, ..ProptestConfig::default() })]
        #[test]
        fn metre_is_identity(x in any::<f64>().prop_filter("in the working range", |x| *x == 0.0 || (1e-98..=1e98).contains(&x.abs()))) {
            let (v, d) = parse_quantity(&format!("{x} m")).unwrap();
            prop_assert_eq!(d, Dim::LENGTH);
            prop_assert_eq!(v, x);
            // Exponent notation too.
            let (v, _) = parse_quantity(&format!("{x:e} m")).unwrap();
            prop_assert_eq!(v, x);
        }

        #[test]
        fn centimetre_is_hundredth(x in any::<f64>().prop_filter("in the working range", |x| *x == 0.0 || (1e-98..=1e98).contains(&x.abs()))) {
            let (v, d) = parse_quantity(&format!("{x} cm")).unwrap();
            prop_assert_eq!(d, Dim::LENGTH);
            let expected = x / 100.0;
            prop_assert!(
                v == expected || (v - expected).abs() <= ULPS * expected.abs(),
                "{} cm -> {:e}, expected {:e}", x, v, expected
            );
        }

        #[test]
        fn values_outside_the_working_range_are_refused(e in 101i32..300, neg in any::<bool>()) {
            let x = if neg { -1.0 } else { 1.0 } * 10f64.powi(e);
            let (big, small) = (format!("{x:e} m"), format!("{:e} m", 1.0 / x));
            prop_assert!(parse_quantity(&big).is_err());
            prop_assert!(parse_quantity(&small).is_err());
        }

        #[test]
        fn arbitrary_text_never_panics(s in "[0-9a-zA-Zµμ .*/^()+\\-·⋅²³⁻¹%#]{0,16}") {
            match parse_quantity(&s) {
                Ok((v, _)) => prop_assert!(v.is_finite()),
                Err(Error::Unit { text, reason }) => {
                    prop_assert_eq!(text, s);
                    prop_assert!(!reason.is_empty());
                }
                Err(e) => prop_assert!(false, "unexpected error kind {:?}", e),
            }
        }

        #[test]
        fn sample_rate_text_never_panics(s in "[0-9a-zA-Zµμ .*/^()+\\-·⋅²³⁻¹%#]{0,16}") {
            match parse_sample_rate(&s) {
                Ok(v) => prop_assert!(v.is_finite()),
                Err(Error::Unit { text, reason }) => {
                    prop_assert_eq!(text, s);
                    prop_assert!(!reason.is_empty());
                }
                Err(e) => prop_assert!(false, "unexpected error kind {:?}", e),
            }
        }

        #[test]
        fn dim_display_round_trip(m in -9i8..=9, kg in -9i8..=9, s in -9i8..=9) {
            let d = Dim::new(m, kg, s);
            prop_assume!(d != Dim::DIMENSIONLESS);
            prop_assert_eq!(parse_quantity(&format!("1 {d}")).unwrap(), (1.0, d));
        }
    }
}
