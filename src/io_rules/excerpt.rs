//! Bounded excerpts of user text quoted in messages: a bad value is shown, but never more than a few
//! hundred characters of it, whatever the file or flag held (a 10 MB CSV cell, a mutated array of a
//! million numbers).

/// Most characters of a value quoted in a message ([`excerpt`]).
pub const MAX_EXCERPT_CHARS: usize = 200;

/// Most characters of a reason (the explanation of an error, which may list names) shown in a message.
pub const MAX_REASON_CHARS: usize = 4000;

/// `text` as quoted in a message: unchanged when it has at most [`MAX_EXCERPT_CHARS`] characters, else its
/// beginning followed by `… (N bytes)` with N the length of the whole text in bytes.
///
/// # Examples
/// ```
/// use stochvib::io_rules::{excerpt, MAX_EXCERPT_CHARS};
/// assert_eq!(excerpt("3.5 furlong"), "3.5 furlong");
/// let long = "9".repeat(10_000_000);
/// let e = excerpt(&long);
/// assert!(e.chars().count() < MAX_EXCERPT_CHARS + 30 && e.ends_with("… (10000000 bytes)"), "{e}");
/// ```
pub fn excerpt(text: &str) -> String {
    excerpt_of(text, MAX_EXCERPT_CHARS)
}

/// `text` cut to at most `max_chars` characters as [`excerpt`] does (the cut falls on a character
/// boundary; the suffix `… (N bytes)` is added to a cut text). A text that would be cut and is one finite
/// decimal number, alone or followed by a short unit (Rust writes an `f64` such as 1e-300 with every digit,
/// 302 characters), is shown as that number in exponent notation instead, `1e-300 Hz (a number of N
/// characters)`: the cut digits would say nothing.
///
/// # Examples
/// ```
/// use stochvib::io_rules::excerpt_of;
/// assert_eq!(excerpt_of("abcdef", 10), "abcdef");
/// assert_eq!(excerpt_of("abcdefghijklmnop", 10), "abcdefghij… (16 bytes)");
/// assert_eq!(excerpt_of("ééééé", 2), "éé… (10 bytes)");
/// assert_eq!(excerpt_of(&1e-300.to_string(), 200), "1e-300 (a number of 302 characters)");
/// assert_eq!(excerpt_of(&(-2.5e250).to_string(), 200), "-2.5e250 (a number of 252 characters)");
/// assert_eq!(excerpt_of(&format!("{} Hz", 1e-300), 200), "1e-300 Hz (a number of 302 characters)");
/// ```
pub fn excerpt_of(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        None => text.to_string(),
        Some((cut, _)) => match long_number(text) {
            Some((v, unit, digits)) => format!("{v:e}{unit} (a number of {digits} characters)"),
            None => format!("{}… ({} bytes)", &text[..cut], text.len()),
        },
    }
}

/// Most characters of a unit after a long number that [`excerpt_of`] keeps with it (` Hz`, ` m/s²`).
const MAX_UNIT_CHARS: usize = 16;

/// `text` as (a finite f64, the unit after it with its space, the number's characters) when it is one
/// decimal number (sign, digits, point, exponent; no spaces), alone or followed by a space and at most
/// [`MAX_UNIT_CHARS`] characters.
fn long_number(text: &str) -> Option<(f64, &str, usize)> {
    let (number, unit) = text.find(' ').map_or((text, ""), |i| text.split_at(i));
    let plain = number
        .bytes()
        .all(|b| b.is_ascii_digit() || matches!(b, b'.' | b'-' | b'+' | b'e' | b'E'));
    if !plain || unit.chars().count() > MAX_UNIT_CHARS + 1 {
        return None;
    }
    let v: f64 = number.parse().ok()?;
    v.is_finite().then_some((v, unit, number.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Long user text stays an excerpt unless it is one finite number: ten million nines overflow f64
    /// (cut as before), a long list of numbers is not one number, a long word is not a number.
    #[test]
    fn only_one_finite_number_is_rewritten() {
        assert!(excerpt(&"9".repeat(10_000)).ends_with("… (10000 bytes)"));
        assert!(excerpt(&"1.5,".repeat(100)).ends_with("… (400 bytes)"));
        assert!(excerpt(&"e".repeat(300)).ends_with("… (300 bytes)"));
        assert_eq!(excerpt(&1e300.to_string()), "1e300 (a number of 301 characters)");
        assert_eq!(
            excerpt(&format!("0.{}1", "0".repeat(250))),
            "1e-251 (a number of 253 characters)"
        );
        assert_eq!(excerpt("1e-300"), "1e-300");
        assert_eq!(
            excerpt(&format!("{} m/s", 2.0e220)),
            "2e220 m/s (a number of 221 characters)"
        );
        // a long tail after the number is not a unit: cut as any text
        assert!(excerpt(&format!("{} {}", 1e-300, "x".repeat(40))).ends_with("… (343 bytes)"));
    }
}
