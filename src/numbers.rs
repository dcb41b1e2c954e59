//! Small numeric helpers shared by every layer: the relative difference used by agreement columns and the
//! number formatter of descriptions and reports.

/// Relative difference |a − b| / max(|a|, |b|), 0 when both are 0.
pub fn rel_diff(a: f64, b: f64) -> f64 {
    let m = a.abs().max(b.abs());
    if m == 0.0 {
        0.0
    } else {
        (a - b).abs() / m
    }
}

/// Formats a number with up to 6 significant digits, plain for 1e-3 ≤ |x| < 1e6, scientific otherwise;
/// used in descriptions and reports.
pub fn num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if (1e-3..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let s = format!("{x:.5e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.')
        } else {
            m
        };
        format!("{m}e{e}")
    }
}

/// Significant figures of the numbers in report tables (`--format markdown`) and in the values echoed by error
/// messages.
pub const REPORT_SIGNIFICANT: usize = 4;

/// How the numbers of one column are written.
///
/// # Formula
/// [`Notation::Fixed`]: positional, e.g. `0.4330`, `12.35`; [`Notation::Scientific`]: one digit before the
/// point and an exponent, e.g. `4.330e-1`.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::numbers::{column_notation, Notation};
/// assert_eq!(column_notation(&[0.5, 12.0, 1999.0]), Notation::Fixed);
/// assert_eq!(column_notation(&[0.5, 2e-6]), Notation::Scientific);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Notation {
    /// Positional notation.
    Fixed,
    /// One digit before the point and a power of ten.
    Scientific,
}

/// Smallest magnitude written in [`Notation::Fixed`]: below it a 4-figure number needs more than 6 decimals.
pub const FIXED_MIN: f64 = 1e-3;
/// Magnitude from which [`Notation::Fixed`] is not used: at and above it 4 figures would not reach the units.
pub const FIXED_MAX: f64 = 1e4;

/// The one notation of a column: fixed when every finite non-zero value lies in [[`FIXED_MIN`],
/// [`FIXED_MAX`]) in magnitude *after* rounding to [`REPORT_SIGNIFICANT`] figures, scientific otherwise. A
/// column is read down: one notation keeps the decimal points (or the exponents) comparable.
///
/// # Formula
/// Fixed ⇔ ∀ finite x ≠ 0: 10⁻³ ≤ |round₄(x)| < 10⁴.
///
/// # Errors
/// None (zeros and non-finite values do not count).
///
/// # Examples
/// ```
/// use stochvib::numbers::{column_notation, Notation};
/// assert_eq!(column_notation(&[]), Notation::Fixed);
/// assert_eq!(column_notation(&[9999.6]), Notation::Scientific); // rounds to 1.000e4
/// assert_eq!(column_notation(&[0.0, f64::NAN, 3.0]), Notation::Fixed);
/// ```
pub fn column_notation(values: &[f64]) -> Notation {
    let fixed = values
        .iter()
        .filter(|x| x.is_finite() && **x != 0.0)
        .all(|x| (-3..=3).contains(&decimal_exponent(*x, REPORT_SIGNIFICANT)));
    if fixed {
        Notation::Fixed
    } else {
        Notation::Scientific
    }
}

/// The decimal exponent of `x` once rounded to `sig` significant figures (`9.9996` → 1).
fn decimal_exponent(x: f64, sig: usize) -> i32 {
    let s = format!("{:.*e}", sig.saturating_sub(1), x);
    s.split_once('e').and_then(|(_, e)| e.parse().ok()).unwrap_or(0)
}

/// `x` with `sig` significant figures in `notation`; zero is `0`, non-finite values `inf`, `-inf`, `NaN`.
///
/// # Formula
/// The digits are the correctly rounded decimal expansion of `x` (the standard library's `{:.N}` and
/// `{:.Ne}` formatting, round-half-to-even on the exact binary value): scientific `{:.(sig−1)e}`; fixed
/// with max(0, sig − 1 − e) decimals, e the exponent of the rounded value, so that trailing zeros are kept
/// (`0.5000`: four figures).
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::numbers::{sig, Notation::*};
/// assert_eq!(sig(0.43301270, 4, Fixed), "0.4330");
/// assert_eq!(sig(1234.56, 4, Fixed), "1235");
/// assert_eq!(sig(9.99996, 4, Fixed), "10.00");
/// assert_eq!(sig(-2.5e-7, 4, Scientific), "-2.500e-7");
/// assert_eq!(sig(0.0, 4, Scientific), "0");
/// ```
pub fn sig(x: f64, sig: usize, notation: Notation) -> String {
    let sig = sig.max(1);
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return format!("{x}");
    }
    match notation {
        Notation::Scientific => format!("{:.*e}", sig - 1, x),
        Notation::Fixed => {
            let e = decimal_exponent(x, sig);
            let decimals = (sig as i32 - 1 - e).max(0) as usize;
            format!("{x:.decimals$}")
        }
    }
}

/// A column of numbers written with [`REPORT_SIGNIFICANT`] figures in the column's one notation
/// ([`column_notation`]); `None` cells become `—`.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::numbers::sig_column;
/// assert_eq!(sig_column(&[Some(0.5), Some(12.0), None]), ["0.5000", "12.00", "—"]);
/// assert_eq!(sig_column(&[Some(0.5), Some(2e-6)]), ["5.000e-1", "2.000e-6"]);
/// ```
pub fn sig_column(values: &[Option<f64>]) -> Vec<String> {
    let present: Vec<f64> = values.iter().flatten().copied().collect();
    let n = column_notation(&present);
    values
        .iter()
        .map(|v| v.map_or_else(|| "—".to_string(), |x| sig(x, REPORT_SIGNIFICANT, n)))
        .collect()
}

/// One value with [`REPORT_SIGNIFICANT`] figures in the notation its own magnitude calls for (a column of one).
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// assert_eq!(stochvib::numbers::sig4(0.61237), "0.6124");
/// assert_eq!(stochvib::numbers::sig4(123456.0), "1.235e5");
/// ```
pub fn sig4(x: f64) -> String {
    sig(x, REPORT_SIGNIFICANT, column_notation(&[x]))
}

/// `x` with at most [`REPORT_SIGNIFICANT`] significant figures and no trailing zeros, positional below 10⁶
/// (all integer digits kept) and scientific beyond: for values echoed in sentences (`6 h`, `0.008333 h`,
/// `200000 km`), where a table's fixed figures would read `6.000 h`.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::numbers::short;
/// assert_eq!(short(6.0), "6");
/// assert_eq!(short(30.0 / 3600.0), "0.008333");
/// assert_eq!(short(200000.0), "200000");
/// assert_eq!(short(1.5e-7), "1.5e-7");
/// ```
pub fn short(x: f64) -> String {
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = decimal_exponent(x, REPORT_SIGNIFICANT);
    if (-3..6).contains(&e) {
        let decimals = (REPORT_SIGNIFICANT as i32 - 1 - e).max(0) as usize;
        trim(format!("{x:.decimals$}"))
    } else {
        let s = format!("{:.*e}", REPORT_SIGNIFICANT - 1, x);
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{e}", trim(m.to_string()))
    }
}
