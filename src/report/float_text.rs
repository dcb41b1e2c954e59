//! Fast number text for large tables: the exact text of Rust's `{:e}` (the shortest digits that read back
//! to the same f64, as `d.ddde-x`), produced from the digits of [`zmij`] (Zverovich's Żmij algorithm, a
//! maintained shortest round-trip formatter several times faster than `core::fmt`), and integers by
//! [`itoa`]. Tables written with it are byte for byte those written with `format!("{x:e}")`.

/// Appends `x` as `format!("{x:e}")` would: the shortest round-trip digits, one before the point, and the
/// decimal exponent (`1.5e-3`, `-2e0`, `0e0`, `NaN`, `inf`).
///
/// # Examples
/// ```ignore
/// let mut s = String::new();
/// push_exp(&mut s, 0.0015);
/// assert_eq!(s, "1.5e-3");
/// ```
pub(crate) fn push_exp(s: &mut String, x: f64) {
    if !x.is_finite() {
        s.push_str(if x.is_nan() {
            "NaN"
        } else if x > 0.0 {
            "inf"
        } else {
            "-inf"
        });
        return;
    }
    let mut buf = zmij::Buffer::new();
    let text = buf.format_finite(x).as_bytes();
    let (neg, text) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, text),
    };
    let (mantissa, exp) = match text.iter().position(|&c| c == b'e') {
        Some(i) => (&text[..i], parse_exponent(&text[i + 1..])),
        None => (text, 0),
    };
    // the significant digits and how many of the mantissa's digits stand before its point
    let mut digits = [0u8; 24];
    let (mut n, mut before_point, mut seen_point, mut leading_zeros) = (0, 0i32, false, 0i32);
    for &c in mantissa {
        if c == b'.' {
            seen_point = true;
        } else if n == 0 && c == b'0' {
            leading_zeros += 1;
            before_point += i32::from(!seen_point);
        } else {
            digits[n] = c;
            n += 1;
            before_point += i32::from(!seen_point);
        }
    }
    while n > 0 && digits[n - 1] == b'0' {
        n -= 1;
    }
    if neg {
        s.push('-');
    }
    if n == 0 {
        s.push_str("0e0");
        return;
    }
    s.push(digits[0] as char);
    if n > 1 {
        s.push('.');
        // ASCII digits only
        s.push_str(std::str::from_utf8(&digits[1..n]).unwrap_or_default());
    }
    s.push('e');
    // the first significant digit stands at 10^(digits before the point − 1 − leading zeros + exponent)
    push_int(s, exp + before_point - 1 - leading_zeros);
}

/// A decimal exponent as zmij writes it (`+20`, `-7`, `5`).
fn parse_exponent(t: &[u8]) -> i32 {
    let (sign, t) = match t.split_first() {
        Some((b'-', r)) => (-1, r),
        Some((b'+', r)) => (1, r),
        _ => (1, t),
    };
    sign * t.iter().fold(0i32, |a, &c| a * 10 + i32::from(c - b'0'))
}

/// Appends an integer.
pub(crate) fn push_int(s: &mut String, v: impl itoa::Integer) {
    s.push_str(itoa::Buffer::new().format(v));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Byte for byte the text of `{:e}` (core::fmt, an independent implementation: Grisu with Dragon4
    /// fallback) on 10⁶ random bit patterns (every exponent, subnormals), on round numbers and powers of
    /// ten where the digit count changes, and on the special values.
    #[test]
    fn the_text_of_lower_exp() {
        let mut x = 0x2545_F491_4F6C_DD1Du64;
        let mut values: Vec<f64> = (0..1_000_000)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                f64::from_bits(x)
            })
            .collect();
        for e in -30..30 {
            let p = 10f64.powi(e);
            values.extend([p, -p, 1.5 * p, 123.0 * p, 0.1 + p, 9.999_999_999_999_999 * p]);
        }
        values.extend([0.0, -0.0, 5e-324, f64::MAX, f64::MIN_POSITIVE, f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
        values.extend((0..2000).map(|k| k as f64 * 0.25));
        let mut s = String::new();
        for v in values {
            s.clear();
            push_exp(&mut s, v);
            assert_eq!(s, format!("{v:e}"), "{:x}", v.to_bits());
        }
    }
}
