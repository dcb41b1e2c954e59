//! Fast number text for large tables: the exact text of Rust's `{:e}` (the shortest digits that read back
//! to the same f64, as `d.ddde-x`), produced from the digits of [`zmij`] (Zverovich's Żmij algorithm, a
//! maintained shortest round-trip formatter several times faster than `core::fmt`), and integers by
//! [`itoa`]. The text is that of `format!("{x:e}")` except when the shortest digits end on an exact tie
//! (x has a 17th significant digit 5 and nothing after it), where Żmij and `core::fmt` break the tie
//! differently: the two texts differ by one in the last digit and read back to the same f64.

/// Appends `x` as `format!("{x:e}")` would (see the module docs for the one exception): the shortest
/// round-trip digits (at most 17), one before the point, and the decimal exponent (`1.5e-3`, `-2e0`, `0e0`,
/// `NaN`, `inf`).
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
    let mut out = [0u8; 40];
    let mut len = 0;
    let text = match text.split_first() {
        Some((b'-', rest)) => {
            out[0] = b'-';
            len = 1;
            rest
        }
        _ => text,
    };
    let (mantissa, exp) = match text.iter().position(|&c| c == b'e') {
        Some(i) => (&text[..i], parse_exponent(&text[i + 1..])),
        None => (text, 0),
    };
    let point = mantissa.iter().position(|&c| c == b'.').unwrap_or(mantissa.len());
    let (int, frac) = (&mantissa[..point], mantissa.get(point + 1..).unwrap_or(&[]));
    // the significant digits (zmij writes no leading zero but the "0" of 0.000ddd) and the decimal exponent
    // of the first one
    let mut digits = [0u8; 32];
    let (n, e10) = if int != b"0" {
        digits[..int.len()].copy_from_slice(int);
        digits[int.len()..int.len() + frac.len()].copy_from_slice(frac);
        (int.len() + frac.len(), exp + int.len() as i32 - 1)
    } else {
        let zeros = frac.iter().take_while(|&&c| c == b'0').count();
        digits[..frac.len() - zeros].copy_from_slice(&frac[zeros..]);
        (frac.len() - zeros, exp - 1 - zeros as i32)
    };
    let n = digits[..n].iter().rposition(|&c| c != b'0').map_or(0, |i| i + 1);
    if n == 0 {
        out[len..len + 3].copy_from_slice(b"0e0");
        len += 3;
    } else {
        out[len] = digits[0];
        len += 1;
        if n > 1 {
            out[len] = b'.';
            out[len + 1..len + n].copy_from_slice(&digits[1..n]);
            len += n;
        }
        out[len] = b'e';
        len += 1;
        let mut ib = itoa::Buffer::new();
        let e = ib.format(e10).as_bytes();
        out[len..len + e.len()].copy_from_slice(e);
        len += e.len();
    }
    // ASCII digits, '.', 'e' and '-' only
    s.push_str(std::str::from_utf8(&out[..len]).unwrap_or_default());
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
    /// ten where the digit count changes, and on the special values; where the two differ, only at a tie
    /// of the last digit: the same number of digits and exponent, the last digit one apart, and both read
    /// back to the same bits (such ties are rare: 226 of the 10⁶ random bit patterns).
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
        values.extend([
            0.0,
            -0.0,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ]);
        values.extend((0..2000).map(|k| k as f64 * 0.25));
        let mut s = String::new();
        let mut ties = 0;
        for v in values {
            s.clear();
            push_exp(&mut s, v);
            let core = format!("{v:e}");
            if s != core {
                ties += 1;
                let (a, b) = (s.as_bytes(), core.as_bytes());
                let e = a.iter().position(|&c| c == b'e').unwrap();
                // the same text but the digit before the exponent, one apart
                assert!(
                    a.len() == b.len()
                        && a[..e - 1] == b[..e - 1]
                        && a[e..] == b[e..]
                        && a[e - 1].abs_diff(b[e - 1]) == 1,
                    "{:x}: {s} vs {core}",
                    v.to_bits()
                );
                assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{s}");
            }
        }
        assert!(ties < 1000, "{ties} ties in 10⁶ values");
    }
}
