//! The output rule: every command that writes a file (`simulate`, `merge`, `sweep`, `replay`, `plot` and
//! the pictures of every command) checks its target with [`check_output`] before any work, writes into a
//! temporary file of its own in the same directory ([`Staged`]), and puts the result under the final name
//! only at the end, in one atomic step. A target is refused, with or without `--overwrite`, when it is
//! one of the command's inputs (the same file: device and inode, so also through a symbolic or hard link),
//! a directory, a symbolic link, a FIFO, a device or a socket, or an existing file of another kind than the
//! command writes ([`OutputKind::recognizes`]); an existing file of the right kind is replaced only with
//! `--overwrite` (pictures in a picture directory are always replaced: [`OutputKind::replaceable`]).

use super::input::type_name;
use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// A kind of file a command writes.
#[derive(Debug, Clone, Copy)]
pub struct OutputKind {
    /// What the file is, in messages (e.g. `stochvib run file`).
    pub what: &'static str,
    /// Whether an existing regular file is of this kind (a look at its first bytes or its attributes).
    pub recognizes: fn(&Path) -> bool,
    /// Whether an existing file of this kind is replaced without `--overwrite` (pictures).
    pub replaceable: bool,
}

/// Whether the regular file `path` begins with `prefix` (reads at most `prefix.len()` bytes).
///
/// # Examples
/// ```
/// let f = std::env::temp_dir().join(format!("stochvib-doc-prefix-{}", std::process::id()));
/// std::fs::write(&f, "point,model.zeta2\n").unwrap();
/// assert!(stochvib::io_rules::starts_with(&f, b"point,"));
/// assert!(!stochvib::io_rules::starts_with(&f, b"time [s]"));
/// std::fs::remove_file(&f).unwrap();
/// ```
pub fn starts_with(path: &Path, prefix: &[u8]) -> bool {
    use std::io::Read;
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return false;
    };
    if !meta.is_file() {
        return false;
    }
    let mut buf = vec![0u8; prefix.len()];
    std::fs::File::open(path)
        .and_then(|mut f| f.read_exact(&mut buf))
        .is_ok()
        && buf == prefix
}

/// The HDF5 file signature.
pub const HDF5_SIGNATURE: &[u8] = b"\x89HDF\r\n\x1a\n";

/// Whether `a` and `b` are the same file (device and inode; symbolic links followed).
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        #[cfg(unix)]
        (Ok(x), Ok(y)) => {
            use std::os::unix::fs::MetadataExt;
            x.dev() == y.dev() && x.ino() == y.ino()
        }
        #[cfg(not(unix))]
        (Ok(_), Ok(_)) => match (a.canonicalize(), b.canonicalize()) {
            (Ok(x), Ok(y)) => x == y,
            _ => false,
        },
        _ => false,
    }
}

fn refuse(path: &Path, reason: String) -> Error {
    Error::Parse {
        file: path.to_path_buf(),
        reason,
    }
}

/// Checks that a command may write a `kind` file at `path` (see the module docs): its directory exists,
/// it is none of `inputs`, and it is absent, or an existing file of this kind with `overwrite` (or a
/// [`OutputKind::replaceable`] kind).
///
/// # Errors
/// [`Error::Parse`] naming `path` and the reason: a missing directory; an input of the command; a
/// directory, symbolic link, FIFO, device or socket; an existing file without `overwrite`; an existing file
/// of another kind (whatever `overwrite` says).
///
/// # Examples
/// ```
/// use stochvib::io_rules::{check_output, OutputKind};
/// let kind = OutputKind { what: "table", recognizes: |_| true, replaceable: false };
/// let e = check_output(std::path::Path::new("/dev/null"), &kind, &[], true).unwrap_err().to_string();
/// assert!(e.contains("character device") && e.contains("not a regular file"), "{e}");
/// ```
pub fn check_output(path: &Path, kind: &OutputKind, inputs: &[&Path], overwrite: bool) -> Result<()> {
    let dir = super::parent_dir(path);
    if !dir.is_dir() {
        return Err(refuse(
            path,
            format!("cannot create: directory `{}` does not exist", dir.display()),
        ));
    }
    if let Some(f) = inputs.iter().find(|f| same_file(f, path)) {
        return Err(refuse(
            path,
            format!(
                "is an input of the run ({}, the same file): choose another output; nothing was written",
                f.display()
            ),
        ));
    }
    let meta = match std::fs::symlink_metadata(path) {
        Err(_) => return Ok(()),
        Ok(m) => m,
    };
    let t = meta.file_type();
    if t.is_dir() {
        return Err(refuse(
            path,
            format!("is a directory: give the {}'s own file name (e.g. DIR/NAME)", kind.what),
        ));
    }
    if !t.is_file() {
        return Err(refuse(
            path,
            format!(
                "is {}, not a regular file: give the {}'s own path (nothing was written)",
                type_name(t),
                kind.what
            ),
        ));
    }
    if !(kind.recognizes)(path) {
        return Err(refuse(
            path,
            format!(
                "already exists and is not a {}: it is never replaced, whatever --overwrite says; choose another \
                 output",
                kind.what
            ),
        ));
    }
    if !overwrite && !kind.replaceable {
        return Err(refuse(
            path,
            format!(
                "already exists: a {} is never overwritten silently; remove it, choose another output name, or \
                 pass --overwrite",
                kind.what
            ),
        ));
    }
    Ok(())
}

/// The name of process `pid`'s temporary file for `path`: `<stem>.tmp-<pid>.<extension>` in the same
/// directory (the extension kept, for writers that choose the format from it).
///
/// # Examples
/// ```
/// use std::path::Path;
/// let t = stochvib::io_rules::temporary_path(Path::new("out/table.csv"), 42);
/// assert_eq!(t, Path::new("out/table.tmp-42.csv"));
/// ```
pub fn temporary_path(path: &Path, pid: u32) -> PathBuf {
    let (prefix, suffix) = temporary_affixes(path);
    path.with_file_name(format!("{prefix}{pid}{suffix}"))
}

/// What comes before and after the pid in a temporary name of `path`.
fn temporary_affixes(path: &Path) -> (String, String) {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    match path.extension() {
        Some(e) => (format!("{stem}.tmp-"), format!(".{}", e.to_string_lossy())),
        None => (format!("{stem}.tmp-"), String::new()),
    }
}

/// Whether a process with this pid exists (Linux: `/proc/<pid>`; elsewhere assumed gone).
pub fn process_alive(pid: u32) -> bool {
    Path::new(&format!("/proc/{pid}")).exists()
}

/// Removes the temporary files of `path` ([`temporary_path`]) whose process is gone (a killed writer's
/// leftovers); returns how many.
pub fn remove_stale_temporaries(path: &Path) -> usize {
    let dir = super::parent_dir(path);
    let (prefix, suffix) = temporary_affixes(path);
    let Ok(rd) = std::fs::read_dir(dir) else { return 0 };
    let mut removed = 0;
    for entry in rd.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = name.strip_prefix(&prefix).and_then(|r| r.strip_suffix(&suffix)) else {
            continue;
        };
        if let Ok(pid) = pid.parse::<u32>()
            && pid != std::process::id()
            && !process_alive(pid)
            && entry.file_type().is_ok_and(|t| t.is_file())
            && std::fs::remove_file(entry.path()).is_ok()
        {
            removed += 1;
        }
    }
    removed
}

/// A file being written under the output rule: checked by [`Staged::begin`], written at
/// [`Staged::temporary`], and put under its final name by [`Staged::commit`]; dropped without a commit, the
/// temporary file is removed. A writer killed before the commit leaves only its temporary file, which the
/// next writer of the same output removes ([`remove_stale_temporaries`]).
#[derive(Debug)]
pub struct Staged {
    path: PathBuf,
    tmp: PathBuf,
    kind: OutputKind,
    inputs: Vec<PathBuf>,
    overwrite: bool,
    committed: bool,
}

impl Staged {
    /// Checks `path` ([`check_output`]), removes what killed writers of it left, and names this process's
    /// temporary file.
    ///
    /// # Errors
    /// As [`check_output`].
    pub fn begin(path: &Path, kind: OutputKind, inputs: &[&Path], overwrite: bool) -> Result<Staged> {
        check_output(path, &kind, inputs, overwrite)?;
        remove_stale_temporaries(path);
        let tmp = temporary_path(path, std::process::id());
        let _ = std::fs::remove_file(&tmp);
        Ok(Staged {
            path: path.to_path_buf(),
            tmp,
            kind,
            inputs: inputs.iter().map(|p| p.to_path_buf()).collect(),
            overwrite,
            committed: false,
        })
    }

    /// The temporary file to write.
    pub fn temporary(&self) -> &Path {
        &self.tmp
    }

    /// The final name.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Syncs the temporary file to disk, checks the target again (something may have appeared meanwhile),
    /// and puts the file under its final name: an atomic rename over an old file of the kind with
    /// `overwrite` (or a replaceable kind), else a hard link that fails if the name is taken; returns the
    /// final path.
    ///
    /// # Errors
    /// [`Error::Io`] if the temporary file is missing or cannot be synced or linked; the errors of
    /// [`check_output`] (the temporary file is then removed and the target untouched).
    pub fn commit(mut self) -> Result<PathBuf> {
        let io = |p: &Path| {
            let p = p.to_path_buf();
            move |source| Error::Io { path: p, source }
        };
        std::fs::File::open(&self.tmp)
            .and_then(|f| f.sync_all())
            .map_err(io(&self.tmp))?;
        let inputs: Vec<&Path> = self.inputs.iter().map(PathBuf::as_path).collect();
        check_output(&self.path, &self.kind, &inputs, self.overwrite)?;
        if self.overwrite || self.kind.replaceable {
            std::fs::rename(&self.tmp, &self.path).map_err(io(&self.path))?;
        } else {
            match std::fs::hard_link(&self.tmp, &self.path) {
                Ok(()) => {
                    let _ = std::fs::remove_file(&self.tmp);
                }
                // a file system without hard links: the check above is the last word
                Err(e) if e.kind() != std::io::ErrorKind::AlreadyExists => {
                    std::fs::rename(&self.tmp, &self.path).map_err(io(&self.path))?
                }
                Err(e) => return Err(io(&self.path)(e)),
            }
        }
        self.committed = true;
        // make the rename itself durable; best effort (not every platform can open a directory)
        let _ = std::fs::File::open(super::parent_dir(&self.path)).and_then(|d| d.sync_all());
        Ok(self.path.clone())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}
