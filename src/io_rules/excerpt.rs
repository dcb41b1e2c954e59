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
/// boundary; the suffix `… (N bytes)` is added to a cut text).
///
/// # Examples
/// ```
/// use stochvib::io_rules::excerpt_of;
/// assert_eq!(excerpt_of("abcdef", 10), "abcdef");
/// assert_eq!(excerpt_of("abcdefghijklmnop", 10), "abcdefghij… (16 bytes)");
/// assert_eq!(excerpt_of("ééééé", 2), "éé… (10 bytes)");
/// ```
pub fn excerpt_of(text: &str, max_chars: usize) -> String {
    match text.char_indices().nth(max_chars) {
        None => text.to_string(),
        Some((cut, _)) => format!("{}… ({} bytes)", &text[..cut], text.len()),
    }
}
