//! The one error type of the crate.
//!
//! Every error names what was wrong (parameter or file key), the offending value and the reason, so that
//! an engineer can fix the input without reading the source.

use crate::io_rules::{excerpt, excerpt_of, MAX_EXCERPT_CHARS, MAX_REASON_CHARS};
use std::path::PathBuf;

/// A reason as shown: at most [`MAX_REASON_CHARS`] characters.
fn bounded(reason: &str) -> String {
    excerpt_of(reason, MAX_REASON_CHARS)
}

/// A value as shown: the constructors already cut it to an [`excerpt`] (with its `… (N bytes)` suffix,
/// which is not cut again); a value put into a variant directly is cut here.
fn shown(value: &str) -> String {
    excerpt_of(value, MAX_EXCERPT_CHARS + 32)
}

/// Result alias used throughout the crate.
pub type Result<T> = std::result::Result<T, Error>;

/// Everything that can go wrong in stochvib.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A constructor or function argument is outside its valid range.
    #[error("invalid parameter `{name}` = {}: {}", shown(value), bounded(reason))]
    InvalidParameter {
        /// Parameter name, e.g. `alpha`.
        name: String,
        /// The value as given.
        value: String,
        /// Why it was rejected.
        reason: String,
    },
    /// A quantity (variance, spectral moment, ...) is infinite; the reason says why and what to do.
    #[error("{quantity} is infinite: {reason}")]
    Divergent {
        /// What was asked for, e.g. `variance of x1_acc`.
        quantity: String,
        /// Why it diverges and what finite question could be asked instead (a band, a cut-off).
        reason: String,
    },
    /// Adaptive quadrature did not reach the requested tolerance.
    #[error(
        "quadrature of {what} did not converge: estimate {estimate:e} with error estimate {abs_error:e} \
         after {evaluations} evaluations ({reason})"
    )]
    Quadrature {
        /// What was integrated.
        what: String,
        /// Best estimate reached.
        estimate: f64,
        /// Its absolute error estimate.
        abs_error: f64,
        /// Number of integrand evaluations used.
        evaluations: usize,
        /// Why it stopped.
        reason: String,
    },
    /// A value read from a file is wrong: names the file, the key, the value and the reason.
    #[error("{}: key `{}` = {}: {}", file.display(), shown(key), shown(value), bounded(reason))]
    File {
        /// The file.
        file: PathBuf,
        /// Dotted key path inside the file, e.g. `spectrum.alpha`.
        key: String,
        /// The offending value as written (or `<missing>`).
        value: String,
        /// Why it was rejected.
        reason: String,
    },
    /// A file could not be read or parsed at all.
    #[error("{}: {}", file.display(), bounded(reason))]
    Parse {
        /// The file.
        file: PathBuf,
        /// Parser message.
        reason: String,
    },
    /// A physical quantity string could not be understood or has the wrong dimension.
    #[error("unit error in `{}`: {}", shown(text), bounded(reason))]
    Unit {
        /// The text as written, e.g. `"3.5 furlong"`.
        text: String,
        /// Why it was rejected.
        reason: String,
    },
    /// A numerical procedure failed (singular matrix, no convergence, ...).
    #[error("numerical failure in {what}: {reason}")]
    Numerical {
        /// The procedure.
        what: String,
        /// Why.
        reason: String,
    },
    /// A method does not apply to this problem (e.g. an exact method for a non-rational input); another
    /// method may.
    #[error("{method} does not apply: {reason}")]
    NotApplicable {
        /// The method.
        method: String,
        /// Why.
        reason: String,
    },
    /// A method computed a value but cannot vouch for it (an ill-conditioned elimination, a disagreement
    /// with an exact route): the value is reported as unreliable, never as a result.
    #[error("{method} is unreliable here (value {value:e}): {reason}")]
    Inaccurate {
        /// The method.
        method: String,
        /// The value it computed.
        value: f64,
        /// Why it cannot be trusted.
        reason: String,
    },
    /// An HDF5 run file could not be written or read, or is not a (complete) stochvib run file.
    #[error("{}: {}", path.display(), bounded(reason))]
    Hdf5 {
        /// The file.
        path: PathBuf,
        /// What went wrong and, where possible, what to do about it.
        reason: String,
    },
    /// Operating-system input/output error with the path involved.
    #[error("{}: {source}", path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
}

impl Error {
    /// This error with an [`Error::InvalidParameter`] named `from` renamed `to` (a library parameter named as
    /// the flag the user wrote); any other error unchanged.
    pub fn renamed(self, from: &str, to: &str) -> Error {
        match self {
            Error::InvalidParameter { name, value, reason } if name == from => Error::InvalidParameter {
                name: to.to_string(),
                value,
                reason,
            },
            other => other,
        }
    }

    /// Shorthand for [`Error::InvalidParameter`].
    pub fn invalid(name: &str, value: impl std::fmt::Display, reason: impl Into<String>) -> Self {
        Error::InvalidParameter {
            name: name.to_string(),
            value: excerpt(&value.to_string()),
            reason: reason.into(),
        }
    }

    /// Shorthand for [`Error::File`]: the file, the key (or line) in it, the value as written and the reason.
    ///
    /// # Examples
    /// ```
    /// use stochvib::Error;
    /// let e = Error::in_file(std::path::Path::new("road.csv"), "line 12", "x", "not a number");
    /// assert!(e.to_string().contains("road.csv") && e.to_string().contains("line 12"));
    /// ```
    pub fn in_file(
        file: &std::path::Path,
        key: impl Into<String>,
        value: impl std::fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Error::File {
            file: file.to_path_buf(),
            key: key.into(),
            value: excerpt(&value.to_string()),
            reason: reason.into(),
        }
    }
}

/// Checks that `value` is finite and strictly positive.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `name` otherwise.
pub fn require_positive(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "must be finite and > 0"))
    }
}

/// Checks that `value` is finite and ≥ 0.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `name` otherwise.
pub fn require_non_negative(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "must be finite and >= 0"))
    }
}

/// Checks that `value` is finite.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `name` otherwise.
pub fn require_finite(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "must be finite"))
    }
}
