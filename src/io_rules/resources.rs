//! The resource rule: what a command will need — memory, disk, work — is estimated before anything is
//! allocated or written, and compared with what the machine has (`MemAvailable` of `/proc/meminfo`, the
//! free space `statvfs` reports for an unprivileged writer) or with a stated cap; a command that would not
//! fit is refused with both numbers and the option that changes them. Counts a user writes are combined
//! with overflow checks ([`checked_product`]).

use crate::error::{Error, Result};
use std::path::Path;

/// Memory the system can still give (Linux `MemAvailable`), bytes; `None` where unknown.
pub fn available_memory() -> Option<u128> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u128 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// Free space for an unprivileged writer on the file system of `dir`, bytes; `None` where unknown.
pub fn available_disk(dir: &Path) -> Option<u128> {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        let c = std::ffi::CString::new(dir.as_os_str().as_bytes()).ok()?;
        let mut s: libc::statvfs = unsafe { std::mem::zeroed() };
        // SAFETY: `c` is a valid NUL-terminated path and `s` a writable statvfs.
        if unsafe { libc::statvfs(c.as_ptr(), &mut s) } != 0 {
            return None;
        }
        Some(s.f_bavail as u128 * s.f_frsize as u128)
    }
    #[cfg(not(unix))]
    {
        let _ = dir;
        None
    }
}

/// The directory a file `path` will be written in (`.` for a bare file name).
pub fn parent_dir(path: &Path) -> &Path {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// Bytes in words: `1.234 GiB` (or `512 bytes` below 1 KiB).
///
/// # Examples
/// ```
/// assert_eq!(stochvib::io_rules::bytes_text(3 << 30), "3.000 GiB");
/// assert_eq!(stochvib::io_rules::bytes_text(12 << 20), "12.000 MiB");
/// assert_eq!(stochvib::io_rules::bytes_text(100), "100 bytes");
/// ```
pub fn bytes_text(b: u128) -> String {
    let units = [("TiB", 40), ("GiB", 30), ("MiB", 20), ("KiB", 10)];
    for (name, shift) in units {
        if b >= 1u128 << shift {
            return format!("{:.3} {name}", b as f64 / (1u128 << shift) as f64);
        }
    }
    format!("{b} bytes")
}

/// A duration in words: seconds, minutes, hours, days or years, 3 significant digits.
///
/// # Examples
/// ```
/// assert_eq!(stochvib::io_rules::duration_text(90.0), "1.50 min");
/// assert_eq!(stochvib::io_rules::duration_text(3.0e7), "347 days");
/// ```
pub fn duration_text(s: f64) -> String {
    let (v, unit) = if s < 60.0 {
        (s, "s")
    } else if s < 3600.0 {
        (s / 60.0, "min")
    } else if s < 86400.0 {
        (s / 3600.0, "h")
    } else if s < 3.156e8 {
        (s / 86400.0, "days")
    } else {
        (s / 3.156e7, "years")
    };
    let decimals = (2 - v.abs().max(1e-300).log10().floor() as i32).max(0) as usize;
    format!("{v:.decimals$} {unit}")
}

/// The product of counts, `None` when it does not fit in a `usize`.
///
/// # Examples
/// ```
/// use stochvib::io_rules::checked_product;
/// assert_eq!(checked_product([1000, 1000, 1000]), Some(1_000_000_000));
/// assert_eq!(checked_product([usize::MAX, 2]), None);
/// ```
pub fn checked_product(counts: impl IntoIterator<Item = usize>) -> Option<usize> {
    counts.into_iter().try_fold(1usize, |acc, n| acc.checked_mul(n))
}

/// Refuses a need of `need` bytes of memory above what the system has available (nothing is checked where
/// the available memory is unknown). `what` says what needs it, `fix` the options that change it.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `flag` with `value`, both numbers and `fix`.
pub fn check_memory(need: u128, flag: &str, value: impl std::fmt::Display, what: &str, fix: &str) -> Result<()> {
    match available_memory() {
        Some(have) if need > have => Err(Error::invalid(
            flag,
            value,
            format!(
                "{what} needs about {} of memory but {} are available: {fix}",
                bytes_text(need),
                bytes_text(have)
            ),
        )),
        _ => Ok(()),
    }
}

/// Refuses a file of `need` bytes that would not fit in the free space of the disk `path` is written to
/// (nothing is checked where the free space is unknown). `what` says what the file holds, `fix` the
/// options that change its size.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `flag` with `value`, both numbers, the directory and `fix`.
pub fn check_disk(
    need: u128,
    path: &Path,
    flag: &str,
    value: impl std::fmt::Display,
    what: &str,
    fix: &str,
) -> Result<()> {
    let dir = parent_dir(path);
    match available_disk(dir) {
        Some(have) if need > have => Err(Error::invalid(
            flag,
            value,
            format!(
                "{what} would take about {} but {} are free on the disk of {}: {fix}",
                bytes_text(need),
                bytes_text(have),
                dir.display()
            ),
        )),
        _ => Ok(()),
    }
}

/// Refuses work whose estimated duration `seconds` (a lower bound) exceeds the cap `max_hours`.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `flag` with `value`, the estimate, the cap and `fix`.
pub fn check_time(
    seconds: f64,
    max_hours: f64,
    flag: &str,
    value: impl std::fmt::Display,
    what: &str,
    fix: &str,
) -> Result<()> {
    if seconds > max_hours * 3600.0 {
        return Err(Error::invalid(
            flag,
            value,
            format!(
                "{what} would take at least {} (the cap is --max-hours {}): {fix}, or raise --max-hours",
                duration_text(seconds),
                crate::numbers::num(max_hours)
            ),
        ));
    }
    Ok(())
}
