//! Fast number text for large tables: every number with [`TABLE_DIGITS`] significant digits, as Rust's
//! `{:.9e}` writes it (`6.681463614e-2`, `-1.000000000e0`, `0.000000000e0`, `NaN`, `inf`), byte for byte,
//! and integers by [`itoa`].
//!
//! # Formula
//! For a finite x ≠ 0 with decimal exponent E (10^E ≤ |x| < 10^(E+1)) the digits are the integer
//! d = round(|x|·10^(9−E)) ∈ [10⁹, 10¹⁰] (10¹⁰ carries into E + 1), rounded to nearest. The product
//! q = |x|·10^(9−E) is one multiplication by 10^(9−E) rounded to f64 (exact for 0 ≤ 9 − E ≤ 22): two
//! correctly rounded steps, so q is within (2⁻⁵² + 2⁻¹⁰⁶)·q < 2.3·10⁻⁶ of the exact product for
//! q < 10¹⁰; where the fraction of q is within 2⁻¹⁶ of ½, or |x| is outside 10⁻³⁵…10⁵³, the digits are
//! left to `core::fmt`'s exact formatting (Grisu with the Dragon4 fallback), which also breaks exact ties:
//! the text is the same in every case (`float_text::tests::the_text_of_fixed_digits`), the fast path taken
//! by all but about 1 in 30 000 numbers of a table's magnitudes. The rounding to an integer is the exact
//! (q + 2⁵²) − 2⁵²; eight of the digits are cut from it at once in the lanes of one 64-bit word
//! ([`eight_digits`]) and the exponent's text comes from a table, straight into the string.

use std::fmt::Write as _;

/// The significant digits of every number in a CSV sweep table: 10, i.e. a relative rounding of at most
/// 5·10⁻¹¹, far below what a scenario's inputs, a Monte Carlo interval or a quadrature tolerance can
/// resolve (the JSON and HDF5 tables keep every f64 exactly), while a shortest round-trip text needs up to 17.
pub(crate) const TABLE_DIGITS: usize = 10;

/// The most a scaling exponent k = 9 − E may be in size (|x| within 10⁻³⁵…10⁵³).
const K_MAX: i32 = 44;

/// 10^k rounded to f64 (Rust's literals are correctly rounded), k = −44…44 at index k + 44.
const POW10: [f64; 89] = [
    1e-44, 1e-43, 1e-42, 1e-41, 1e-40, 1e-39, 1e-38, 1e-37, 1e-36, 1e-35, 1e-34, 1e-33, 1e-32, 1e-31, 1e-30, 1e-29,
    1e-28, 1e-27, 1e-26, 1e-25, 1e-24, 1e-23, 1e-22, 1e-21, 1e-20, 1e-19, 1e-18, 1e-17, 1e-16, 1e-15, 1e-14, 1e-13,
    1e-12, 1e-11, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7,
    1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22, 1e23, 1e24, 1e25, 1e26,
    1e27, 1e28, 1e29, 1e30, 1e31, 1e32, 1e33, 1e34, 1e35, 1e36, 1e37, 1e38, 1e39, 1e40, 1e41, 1e42, 1e43, 1e44,
];

/// Appends `x` as `format!("{x:.9e}")` writes it ([`TABLE_DIGITS`] significant digits; see the module docs).
///
/// # Examples
/// ```ignore
/// let mut s = String::new();
/// push_fixed(&mut s, 0.0015);
/// assert_eq!(s, "1.500000000e-3");
/// ```
pub(crate) fn push_fixed(s: &mut String, x: f64) {
    // SAFETY: the string grows by 32 zero bytes, the text is written over them and the string cut back to
    // it; that text is ASCII ('-', digits, '.', 'e'), so the string stays valid UTF-8. The text goes
    // straight into the string: a copy from a buffer on the stack stalls on reading back narrow stores.
    let v = unsafe { s.as_mut_vec() };
    let at = v.len();
    v.extend_from_slice(&[0u8; 32]);
    let out: &mut [u8; 32] = (&mut v[at..at + 32]).try_into().unwrap_or_else(|_| unreachable!());
    match fixed_text(x, out) {
        Some(len) => v.truncate(at + len),
        None => {
            v.truncate(at);
            let _ = write!(s, "{x:.*e}", TABLE_DIGITS - 1);
        }
    }
}

/// The decimal exponent E of a ≥ 2⁻¹⁰²² from its binary exponent (floor(e₂·log₁₀2) is E or E − 1,
/// 78913/2¹⁸ ≈ log₁₀2) and one comparison with 10^(E+1) rounded, which can still be one too low or high next
/// to a power of ten that f64 does not hold (the digits' range check in [`fixed_text`] mends that).
#[inline]
fn decimal_exponent(a: f64) -> i32 {
    let e2 = ((a.to_bits() >> 52) as i32) - 1023;
    let e10 = (e2 * 78_913) >> 18;
    let above = POW10.get((e10 + 1 + K_MAX) as usize).is_some_and(|&p| a >= p);
    e10 + i32::from(above)
}

/// The 10 significant digits of a > 0 as an integer in [10⁹, 10¹⁰) with the decimal exponent, or None where
/// `core::fmt` must decide (see the module docs): a rounding too close to a tie, a outside 10⁻³⁵…10⁵³.
#[inline]
fn digits_of(a: f64) -> Option<(u64, i32)> {
    const LOW: f64 = 1e9;
    const HIGH: f64 = 1e10;
    /// 2⁵²: for 0 ≤ q < 2⁵², (q + 2⁵²) − 2⁵² is q rounded to the nearest integer (exact sums).
    const ROUND: f64 = 4_503_599_627_370_496.0;
    let mut e10 = decimal_exponent(a);
    for _ in 0..3 {
        let k = 9 - e10;
        if !(-K_MAX..=K_MAX).contains(&k) {
            return None;
        }
        let q = a * POW10[(k + K_MAX) as usize];
        if q >= HIGH {
            // 10¹⁰ ≤ q: one decade too low (q < 2⁵² below, where the rounding by ROUND holds)
            e10 += 1;
            continue;
        }
        let d = (q + ROUND) - ROUND;
        // |q − d| ≤ ½ exactly; within 2⁻¹⁶ of ½: a tie or nearly, left to core::fmt
        if (q - d).abs() >= 0.5 - 1.0 / 65_536.0 {
            return None;
        }
        if d < LOW {
            e10 -= 1;
        } else if d == HIGH {
            return Some((1_000_000_000, e10 + 1));
        } else {
            return Some((d as i64 as u64, e10)); // 10⁹ ≤ d < 10¹⁰: the signed conversion is exact
        }
    }
    None
}

/// The eight decimal digits of v < 10⁸ as ASCII, the first digit in the lowest byte (so in memory order
/// when stored little-endian): v split into 4-digit halves, each into pairs by a multiplication with
/// ⌈2²⁰/100⌉ = 10486 (exact quotient below 43,699), each pair into digits by ⌈2¹⁰/10⌉ = 103 (exact below
/// 179), every lane of the word at once.
#[inline]
fn eight_digits(v: u32) -> u64 {
    let x = u64::from(v / 10_000) | (u64::from(v % 10_000) << 32);
    let hundreds = ((x * 10_486) >> 20) & 0x0000_007f_0000_007f;
    let x = hundreds | ((x - hundreds * 100) << 16);
    let tens = ((x * 103) >> 10) & 0x000f_000f_000f_000f;
    let x = tens | ((x - tens * 10) << 8);
    x | 0x3030_3030_3030_3030
}

/// The text of `{:.9e}` for x into `out` with its length, or None where `core::fmt` must decide (see the
/// module docs): a rounding too close to a tie, |x| outside 10⁻³⁵…10⁵³, NaN and infinities.
#[inline]
fn fixed_text(x: f64, out: &mut [u8; 32]) -> Option<usize> {
    if !x.is_finite() {
        return None;
    }
    let neg = usize::from(x.is_sign_negative());
    out[0] = b'-';
    if x == 0.0 {
        out[neg..neg + 13].copy_from_slice(b"0.000000000e0");
        return Some(neg + 13);
    }
    let (digits, e10) = digits_of(x.abs())?;
    // d.ddddddddd: the first digit and the point, eight digits at once, the last digit
    let first = digits / 1_000_000_000;
    let rest = (digits - first * 1_000_000_000) as u32;
    out[neg] = b'0' + first as u8;
    out[neg + 1] = b'.';
    out[neg + 2..neg + 10].copy_from_slice(&eight_digits(rest / 10).to_le_bytes());
    out[neg + 10] = b'0' + (rest % 10) as u8;
    // the exponent: −35 ≤ E ≤ 54 here (53 and a carry); its text (up to four bytes, "e-35") from the table
    let (text, len) = EXPONENTS[(e10 + EXP_MIN) as usize];
    out[neg + 11..neg + 15].copy_from_slice(&text);
    Some(neg + 11 + len)
}

/// The smallest exponent of the fast path, negated: E ≥ −35 (|x| ≥ 10⁻³⁵ > 10^(9 − K_MAX)).
const EXP_MIN: i32 = 35;

/// "e-35" … "e54": the exponent's text (padded to four bytes) and its length, E at index E + 35.
const EXPONENTS: [([u8; 4], usize); 90] = {
    let mut t = [([0u8; 4], 0usize); 90];
    let mut i = 0;
    while i < 90 {
        let e = i as i32 - EXP_MIN;
        let (mut text, mut len) = ([b'e', 0, 0, 0], 1);
        if e < 0 {
            text[1] = b'-';
            len = 2;
        }
        let m = e.unsigned_abs() as u8;
        if m >= 10 {
            text[len] = b'0' + m / 10;
            len += 1;
        }
        text[len] = b'0' + m % 10;
        t[i] = (text, len + 1);
        i += 1;
    }
    t
};

/// Appends an integer.
pub(crate) fn push_int(s: &mut String, v: impl itoa::Integer) {
    s.push_str(itoa::Buffer::new().format(v));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xorshift(mut x: u64) -> impl FnMut() -> u64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    }

    /// Byte for byte the text of `format!("{x:.9e}")` (core::fmt's exact mode: Grisu with the Dragon4
    /// fallback, an independent implementation) on 10⁶ random bit patterns (every exponent, subnormals,
    /// NaN payloads), 10⁶ random values of either sign across 10⁻⁴⁰…10⁶⁰ (the fast path's range and past
    /// both its ends), the powers of ten and their neighbours, values a hair either side of a rounding tie
    /// of the 10th digit and of a carry into the next exponent (9.9999999995·10^e), and the special values;
    /// the fast path leaves fewer than 10⁻⁴ of the values inside its range to `core::fmt`.
    #[test]
    fn the_text_of_fixed_digits() {
        let mut bits = xorshift(0x2545_F491_4F6C_DD1D);
        let mut values: Vec<f64> = (0..1_000_000).map(|_| f64::from_bits(bits())).collect();
        let mut uniform = xorshift(0x9E37_79B9_7F4A_7C15);
        let mut unit = move || (uniform() >> 11) as f64 / (1u64 << 53) as f64;
        let spread: Vec<f64> = (0..1_000_000)
            .map(|i| {
                let v = (1.0 + 9.0 * unit()) * 10f64.powi((unit() * 100.0) as i32 - 40);
                if i % 2 == 0 {
                    v
                } else {
                    -v
                }
            })
            .collect();
        values.extend(&spread);
        for e in -45..62 {
            let p = 10f64.powi(e);
            for v in [
                p,
                9.999_999_999_5 * p,
                1.000_000_000_5 * p,
                1.234_567_890_5 * p,
                2.5 * p,
            ] {
                values.extend([v, -v, v.next_up(), v.next_down()]);
            }
        }
        values.extend((0..5000).map(|k| k as f64 * 0.25 + 1e9));
        values.extend([
            0.0,
            -0.0,
            5e-324,
            -5e-324,
            2.225e-308,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ]);
        let mut s = String::new();
        for v in &values {
            s.clear();
            push_fixed(&mut s, *v);
            assert_eq!(s, format!("{v:.9e}"), "{:x}", v.to_bits());
        }
        let mut out = [0u8; 32];
        // the fast path's range, but for the ends' decades (where the first estimate of E can fall outside it)
        let inside = spread.iter().filter(|v| (1e-34..1e52).contains(&v.abs()));
        let (n, slow) = inside.fold((0, 0), |(n, slow), v| {
            (n + 1, slow + usize::from(fixed_text(*v, &mut out).is_none()))
        });
        assert!(slow * 10_000 < n, "{slow} of {n} values left to core::fmt");
    }

    /// The eight digits of the lanes against `format!("{v:08}")` (core::fmt's integer text): 10⁵ values
    /// spread over 0…10⁸ − 1, and every value next to a multiple of 10, 100 and 10⁴.
    #[test]
    fn eight_digits_are_the_integer_text() {
        let mut bits = xorshift(0xD1B5_4A32_D192_ED03);
        let mut values: Vec<u32> = (0..100_000).map(|_| (bits() % 100_000_000) as u32).collect();
        for m in [10u32, 100, 10_000, 1_000_000] {
            values.extend((1..100).flat_map(|k| [k * m - 1, k * m, k * m + 1]));
        }
        values.extend([0, 1, 9, 99_999_999, 99_990_000, 10_000_000]);
        for v in values {
            assert_eq!(eight_digits(v).to_le_bytes(), *format!("{v:08}").as_bytes(), "{v}");
        }
    }

    /// The integers' text is `itoa`'s, that of `Display`.
    #[test]
    fn integers() {
        let mut s = String::new();
        for v in [0usize, 7, 10, 123_456_789, usize::MAX] {
            s.clear();
            push_int(&mut s, v);
            assert_eq!(s, v.to_string());
        }
    }
}
