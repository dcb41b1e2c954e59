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
    let mut out = [0u8; 40];
    let len = exp_form(buf.format_finite(x).as_bytes(), &mut out);
    // SAFETY: `out[..len]` holds ASCII only (Żmij's digits, '.', '-', 'e' and itoa's digits): valid UTF-8.
    s.push_str(unsafe { std::str::from_utf8_unchecked(&out[..len]) });
}

/// Rewrites Żmij's text (`-0.00123`, `12.5`, `100.0`, `1e+20`, `1.5e-7`, `0.0`) as `{:e}`'s (`-1.23e-3`,
/// `1.25e1`, `1e2`, `1e20`, `1.5e-7`, `0e0`) into `out`; returns the length written. Żmij writes no trailing
/// zero but the `.0` of an integer, and the exponential form only outside its fixed-point range.
fn exp_form(text: &[u8], out: &mut [u8; 40]) -> usize {
    let neg = usize::from(text[0] == b'-');
    let t = &text[neg..];
    out[0] = b'-';
    let mut len = neg;
    // Żmij's exponent is `e±d`, `e±dd` or `e-ddd`: its 'e' is one of the last five characters
    let e_at = (3..=5)
        .find(|&k| t.len() > k && t[t.len() - k] == b'e')
        .map(|k| t.len() - k);
    let e10 = if let Some(e) = e_at {
        // d[.ddd]e±x: the significand as it is
        out[len..len + e].copy_from_slice(&t[..e]);
        len += e;
        parse_exponent(&t[e + 1..])
    } else if t[0] != b'0' {
        // ddd.ddd or ddd00.0: the first digit, the point, the other digits without the point
        let p = t.iter().position(|&c| c == b'.').unwrap_or(t.len());
        let frac = if &t[p..] == b".0" { &[][..] } else { &t[p + 1..] };
        let mut int = &t[..p];
        if frac.is_empty() {
            while int.len() > 1 && int[int.len() - 1] == b'0' {
                int = &int[..int.len() - 1];
            }
        }
        out[len] = t[0];
        out[len + 1] = b'.';
        let rest = &int[1..];
        out[len + 2..len + 2 + rest.len()].copy_from_slice(rest);
        out[len + 2 + rest.len()..len + 2 + rest.len() + frac.len()].copy_from_slice(frac);
        let n = rest.len() + frac.len();
        len += if n == 0 { 1 } else { 2 + n };
        p as i32 - 1
    } else {
        // 0.000ddd (or 0.0)
        let zeros = t[2..].iter().take_while(|&&c| c == b'0').count();
        let d = &t[2 + zeros..];
        if d.is_empty() {
            out[len..len + 3].copy_from_slice(b"0e0");
            return len + 3;
        }
        out[len] = d[0];
        out[len + 1] = b'.';
        out[len + 2..len + 1 + d.len()].copy_from_slice(&d[1..]);
        len += if d.len() == 1 { 1 } else { 1 + d.len() };
        -(zeros as i32) - 1
    };
    out[len] = b'e';
    len += 1;
    let mut ib = itoa::Buffer::new();
    let e = ib.format(e10).as_bytes();
    out[len..len + e.len()].copy_from_slice(e);
    len + e.len()
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
