//! The input rule: every file a command reads is opened through [`open_input`] (or checked by
//! [`check_input`] when a library such as HDF5 opens it), which refuses what is not a regular file —
//! a directory, a FIFO (which would block the reader until some process writes to it), a device
//! (`/dev/zero` never ends) or a socket — before a byte is read, and refuses a file larger than its
//! kind's limit ([`InputKind::max_bytes`]) with both sizes. Text is then read in bounded pieces: whole for
//! small files ([`read_text`]), line by line with a bounded line length for record files
//! ([`BoundedLines`]).

use crate::error::{Error, Result};
use std::io::{BufRead, Read};
use std::path::Path;

/// A kind of input file and the largest size a command accepts for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InputKind {
    /// What the file is, in messages (e.g. `TOML file`).
    pub what: &'static str,
    /// Largest size, bytes; `None` for files no reader reads whole (HDF5 run files are read a shard at a
    /// time).
    pub max_bytes: Option<u64>,
    /// What to do with a file that is too large (ends the message).
    pub too_large_hint: &'static str,
}

/// Scenario, spectrum, reference and limit files (TOML): 16 MiB.
pub const TOML_INPUT: InputKind = InputKind {
    what: "TOML file",
    max_bytes: Some(crate::fields::MAX_INPUT_FILE_BYTES),
    too_large_hint: "a scenario, spectrum or limits file is a few kilobytes; long tables belong in a CSV file",
};

/// Road profiles and measured records (CSV): 1 GiB (about 40 million rows of two tracks).
pub const CSV_INPUT: InputKind = InputKind {
    what: "CSV file",
    max_bytes: Some(1 << 30),
    too_large_hint: "split the record into sections, or resample it to a coarser step",
};

/// Sweep shard files (JSON, `stochvib sweep --shard`): 1 GiB.
pub const JSON_SHARD_INPUT: InputKind = InputKind {
    what: "sweep shard file",
    max_bytes: Some(1 << 30),
    too_large_hint: "split the study into more shards (--of)",
};

/// HDF5 run and table files: no size limit (every reader reads a bounded part at a time: one shard's
/// rows, one statistic), but only regular files.
pub const HDF5_INPUT: InputKind = InputKind {
    what: "HDF5 file",
    max_bytes: None,
    too_large_hint: "",
};

/// Longest line of a record file ([`BoundedLines`]), bytes.
pub const MAX_LINE_BYTES: usize = 1 << 16;

/// What a file type is, in words.
pub(crate) fn type_name(t: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a directory"
    } else if t.is_symlink() {
        "a symbolic link"
    } else if t.is_file() {
        "a regular file"
    } else {
        "not a regular file"
    }
}

fn refuse(path: &Path, reason: String) -> Error {
    Error::Parse {
        file: path.to_path_buf(),
        reason,
    }
}

/// Checks the type and size of an input (following symbolic links) without opening it.
fn check_metadata(path: &Path, meta: &std::fs::Metadata, kind: InputKind) -> Result<u64> {
    if !meta.is_file() {
        return Err(refuse(
            path,
            format!(
                "is {}, not a regular file: give a {} (nothing was read)",
                type_name(meta.file_type()),
                kind.what
            ),
        ));
    }
    if let Some(max) = kind.max_bytes
        && meta.len() > max
    {
        return Err(refuse(
            path,
            format!(
                "{} bytes is larger than the {max} bytes a {} may have: {}",
                meta.len(),
                kind.what,
                kind.too_large_hint
            ),
        ));
    }
    Ok(meta.len())
}

/// Checks an input that another library opens (HDF5): it must be a regular file of at most the kind's
/// size. Returns its size.
///
/// # Errors
/// [`Error::Io`] if it cannot be examined; [`Error::Parse`] naming the file for a directory, FIFO, device
/// or socket, or a file that is too large.
///
/// # Examples
/// ```
/// use stochvib::io_rules::{check_input, HDF5_INPUT};
/// let e = check_input(std::path::Path::new("/dev/null"), HDF5_INPUT).unwrap_err().to_string();
/// assert!(e.contains("character device"), "{e}");
/// ```
pub fn check_input(path: &Path, kind: InputKind) -> Result<u64> {
    let meta = std::fs::metadata(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    check_metadata(path, &meta, kind)
}

/// Opens an input for reading: without blocking on a FIFO (the type is checked on the open descriptor, so
/// nothing can swap the file in between), refusing anything but a regular file of at most the kind's
/// size. Returns the file and its size.
///
/// # Errors
/// As [`check_input`].
pub fn open_input(path: &Path, kind: InputKind) -> Result<(std::fs::File, u64)> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        // a FIFO opened for reading would wait for a writer; O_NONBLOCK opens it at once (and does nothing
        // for a regular file), O_NOCTTY keeps a terminal device from becoming the controlling terminal
        options.custom_flags(libc::O_NONBLOCK | libc::O_NOCTTY);
    }
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = options.open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    let len = check_metadata(path, &meta, kind)?;
    Ok((file, len))
}

/// Reads a whole text input of at most the kind's size ([`open_input`]), valid UTF-8.
///
/// # Errors
/// As [`open_input`]; [`Error::Parse`] for text that is not UTF-8 (naming the byte, not echoing the
/// content) or a file that grew past the limit while it was read.
///
/// # Examples
/// ```
/// use stochvib::io_rules::{read_text, TOML_INPUT};
/// let e = read_text(std::path::Path::new("/dev/zero"), TOML_INPUT).unwrap_err().to_string();
/// assert!(e.contains("/dev/zero") && e.contains("character device"), "{e}");
/// ```
pub fn read_text(path: &Path, kind: InputKind) -> Result<String> {
    let (file, len) = open_input(path, kind)?;
    let limit = kind.max_bytes.unwrap_or(u64::MAX);
    let mut bytes = Vec::with_capacity(len.min(limit) as usize);
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    if bytes.len() as u64 > limit {
        return Err(refuse(
            path,
            format!("grew past the {limit} bytes a {} may have while it was read", kind.what),
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        refuse(
            path,
            format!(
                "not a text file: invalid UTF-8 at byte {}",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// The lines of a text input, each at most [`MAX_LINE_BYTES`] long, read one at a time (memory: one line).
/// Yields (1-based line number, line without its `\n` or `\r\n`).
pub struct BoundedLines<R> {
    reader: R,
    file: std::path::PathBuf,
    line: usize,
    buf: Vec<u8>,
}

impl<R: BufRead> BoundedLines<R> {
    /// Lines of `reader`; `file` names it in errors.
    pub fn new(reader: R, file: &Path) -> Self {
        BoundedLines {
            reader,
            file: file.to_path_buf(),
            line: 0,
            buf: Vec::new(),
        }
    }

    /// The next line, `None` at the end.
    ///
    /// # Errors
    /// [`Error::Io`] on a read error; [`Error::File`] naming the line for a line longer than
    /// [`MAX_LINE_BYTES`] (quoting its beginning) or one that is not UTF-8.
    pub fn next_line(&mut self) -> Result<Option<(usize, &str)>> {
        self.buf.clear();
        self.line += 1;
        let n = (&mut self.reader)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', &mut self.buf)
            .map_err(|source| Error::Io {
                path: self.file.clone(),
                source,
            })?;
        if n == 0 {
            return Ok(None);
        }
        let key = format!("line {}", self.line);
        if self.buf.last() != Some(&b'\n') && n > MAX_LINE_BYTES {
            let start = String::from_utf8_lossy(&self.buf[..self.buf.len().min(120)]).into_owned();
            return Err(Error::in_file(
                &self.file,
                key,
                format!("{start}…"),
                format!("the line is longer than the {MAX_LINE_BYTES} bytes a line may have (is it a text file?)"),
            ));
        }
        while matches!(self.buf.last(), Some(b'\n' | b'\r')) {
            self.buf.pop();
        }
        match std::str::from_utf8(&self.buf) {
            Ok(s) => Ok(Some((self.line, s))),
            Err(e) => Err(Error::in_file(
                &self.file,
                key,
                format!("<byte {}>", e.valid_up_to()),
                "not UTF-8 text",
            )),
        }
    }
}
