//! The spectrum catalogue (`spectra/`): the one place where a spectrum reference written in a scenario file or
//! on the command line is turned into a spectrum file.
//!
//! # Resolution rule
//! * A **catalogue name** — letters, digits, `-`, `_` and `.`, not starting with `.`, without a path separator
//!   and not ending in `.toml` (e.g. `iso8608-c`) — is looked up as `<dir>/<name>.toml` in the catalogue
//!   directory, and nowhere else: a name can never leave the catalogue.
//! * Anything else is an **explicit path** to a spectrum file: as written (relative to the working
//!   directory), else, when relative, next to the scenario file that names it.
//!
//! The directory is chosen by the caller: the command-line tool takes `--spectra-dir`, else
//! `$STOCHVIB_SPECTRA`, else `./spectra`, else the built-in catalogue ([`Catalogue::bundled`]: every
//! `spectra/*.toml` of the source tree, embedded in the library when it is built, so that an installed
//! binary needs no source tree); nothing below the command-line tool reads environment variables.

use super::spectrum_file::{load_spectrum, parse_spectrum, SpectrumFile};
use crate::error::{Error, Result};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Where a spectrum came from: recorded with every scenario and run so that a result can be traced.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum SpectrumOrigin {
    /// A catalogue name resolved in a catalogue directory.
    Catalogue {
        /// The name as written.
        name: String,
        /// The catalogue directory.
        dir: PathBuf,
        /// The file it resolved to.
        file: PathBuf,
    },
    /// An explicit path to a spectrum file.
    File {
        /// The file it resolved to.
        path: PathBuf,
    },
    /// An inline table of a scenario file.
    Inline,
}

/// The name of the built-in catalogue ([`Catalogue::bundled`]) where a directory would be named: its
/// spectrum `iso8608-d` is `<built-in>/iso8608-d.toml` in messages and provenance.
pub const BUILT_IN: &str = "<built-in>";

/// (name, text) of every `spectra/*.toml` of the source tree, embedded by `build.rs`.
static BUILT_IN_FILES: &[(&str, &str)] = include!(concat!(env!("OUT_DIR"), "/spectra.rs"));

/// A directory of spectrum files, one named spectrum per `<name>.toml`.
///
/// # Examples
/// ```
/// use stochvib::scenario::Catalogue;
/// let c = Catalogue::bundled();
/// let f = c.resolve("iso8608-c", None).unwrap();
/// assert_eq!(f.unit, "m");
/// assert!(c.resolve("../Cargo", None).is_err()); // not a catalogue name, and no such file
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Catalogue {
    dir: PathBuf,
}

/// One entry of a catalogue directory.
#[derive(Debug, Clone)]
pub struct CatalogueEntry {
    /// The file.
    pub path: PathBuf,
    /// The parsed spectrum, or the error that names what is wrong with the file.
    pub spectrum: std::result::Result<SpectrumFile, String>,
}

impl Catalogue {
    /// The catalogue in `dir`.
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Catalogue { dir: dir.into() }
    }

    /// The built-in catalogue: the `spectra/*.toml` files of the source tree, embedded when the crate was
    /// built. Its [`dir`](Self::dir) is `BUILT_IN`, a name, not a directory on disk.
    pub fn bundled() -> Self {
        Catalogue::new(BUILT_IN)
    }

    /// The catalogue a command uses: `dir` if given (`--spectra-dir`, `spectra_dir=`), else
    /// `$STOCHVIB_SPECTRA`, else `./spectra` if it exists, else the [built-in](Self::bundled) one.
    pub fn chosen(dir: Option<&Path>) -> Self {
        if let Some(d) = dir {
            return Catalogue::new(d);
        }
        if let Ok(d) = std::env::var("STOCHVIB_SPECTRA") {
            return Catalogue::new(d);
        }
        let local = PathBuf::from("spectra");
        if local.is_dir() {
            return Catalogue::new(local);
        }
        Catalogue::bundled()
    }

    /// Whether this is the built-in catalogue.
    pub fn is_built_in(&self) -> bool {
        self.dir == Path::new(BUILT_IN)
    }

    /// The text of the built-in spectrum `name`.
    fn built_in_text(name: &str) -> Option<&'static str> {
        BUILT_IN_FILES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
    }

    /// Parses a built-in spectrum under its name `<built-in>/<name>.toml`.
    fn built_in_spectrum(file: &Path, text: &str) -> Result<SpectrumFile> {
        let mut sf = parse_spectrum(text, file)?;
        sf.origin = SpectrumOrigin::File {
            path: file.to_path_buf(),
        };
        Ok(sf)
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Whether `reference` is a catalogue name (see the module docs) rather than a path.
    ///
    /// # Examples
    /// ```
    /// use stochvib::scenario::Catalogue;
    /// assert!(Catalogue::is_name("iso8608-c"));
    /// assert!(!Catalogue::is_name("../../etc/passwd"));
    /// assert!(!Catalogue::is_name("spectra/type1.toml"));
    /// ```
    pub fn is_name(reference: &str) -> bool {
        !reference.is_empty()
            && !reference.starts_with('.')
            && !reference.ends_with(".toml")
            && reference
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'))
    }

    /// Resolves a spectrum reference (see the module docs); `base` is the directory of the file that names
    /// it, for relative explicit paths.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] (`spectrum`) when nothing is found, naming where it looked; the errors of
    /// [`load_spectrum`] for a file that is found but invalid.
    pub fn resolve(&self, reference: &str, base: Option<&Path>) -> Result<SpectrumFile> {
        if Catalogue::is_name(reference) {
            let file = self.dir.join(format!("{reference}.toml"));
            let built_in = self.is_built_in().then(|| Catalogue::built_in_text(reference));
            if built_in == Some(None) || (built_in.is_none() && !file.is_file()) {
                return Err(Error::invalid(
                    "spectrum",
                    reference,
                    format!("no `{}` in the catalogue {}", file.display(), self.dir.display()),
                ));
            }
            let mut sf = match built_in.flatten() {
                Some(text) => Catalogue::built_in_spectrum(&file, text)?,
                None => load_spectrum(&file)?,
            };
            sf.origin = SpectrumOrigin::Catalogue {
                name: reference.to_string(),
                dir: self.dir.clone(),
                file,
            };
            return Ok(sf);
        }
        let given = Path::new(reference);
        let mut candidates = vec![given.to_path_buf()];
        if let Some(b) = base.filter(|_| given.is_relative()) {
            candidates.push(b.join(given));
        }
        // anything that exists goes to the reader, whose input rule names a FIFO, a device or a directory
        let Some(path) = candidates.iter().find(|p| p.exists()) else {
            return Err(Error::invalid(
                "spectrum",
                reference,
                format!(
                    "not a catalogue name and no such file ({})",
                    candidates
                        .iter()
                        .map(|p| p.display().to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            ));
        };
        let mut sf = load_spectrum(path)?;
        sf.origin = SpectrumOrigin::File { path: path.clone() };
        Ok(sf)
    }

    /// Every `*.toml` spectrum file of the directory, sorted by name; invalid files are listed with their
    /// error rather than hidden.
    ///
    /// # Errors
    /// [`Error::Io`] if the directory cannot be read.
    pub fn entries(&self) -> Result<Vec<CatalogueEntry>> {
        if self.is_built_in() {
            return Ok(BUILT_IN_FILES
                .iter()
                .map(|(name, text)| {
                    let path = self.dir.join(format!("{name}.toml"));
                    CatalogueEntry {
                        spectrum: Catalogue::built_in_spectrum(&path, text).map_err(|e| e.to_string()),
                        path,
                    }
                })
                .collect());
        }
        let rd = std::fs::read_dir(&self.dir).map_err(|source| Error::Io {
            path: self.dir.clone(),
            source,
        })?;
        let mut paths: Vec<PathBuf> = rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        paths.sort();
        Ok(paths
            .into_iter()
            .map(|path| CatalogueEntry {
                spectrum: load_spectrum(&path).map_err(|e| e.to_string()),
                path,
            })
            .collect())
    }
}

/// Every spectrum file in `dir` ([`Catalogue::entries`]).
///
/// # Errors
/// As [`Catalogue::entries`].
pub fn spectrum_catalogue(dir: &Path) -> Result<Vec<CatalogueEntry>> {
    Catalogue::new(dir).entries()
}
