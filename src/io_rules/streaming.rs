//! Write-behind for outputs of hundreds of megabytes (a sweep table of 10⁶ points is 240 MB of HDF5 or
//! 680 MB of CSV): best effort, never an error, and no change to a single byte of what is written.
//!
//! The output rule syncs a finished file to disk before it renames it
//! ([`Staged::commit`](super::Staged::commit)). Left to itself the kernel starts writing dirty pages out only
//! after about 30 s or when a share of the memory is dirty, so that final sync wrote the whole file while
//! the cores waited. Asking for the write-out of what is already written, block by block, lets the disk
//! work while the next block is computed; the final sync then waits for the last block only. On Linux
//! this is `sync_file_range(fd, 0, 0, SYNC_FILE_RANGE_WRITE)`: it starts the write-out of the dirty pages
//! and does not wait for it (sync_file_range(2)); it makes nothing durable by itself, which is why the
//! final sync stays. Elsewhere nothing is done.
//!
//! Where it does not pay: a file whose pages are written again after their write-out has started waits
//! for the disk on every such page. HDF5 rewrites its metadata (object headers, the chunk index) at every
//! flush, so a run file flushed after every shard is not given write-behind (measured: the whole-file
//! request after each shard took the write of 524 MB from 0.35 s to 0.25 s until the sync, but from 0.13 s
//! to 0.24 s until close without a sync; see `benches/HISTORY.md`). A sweep table is flushed once, at
//! its end.

use std::fs::File;
use std::io::Write;

/// Bytes written between two requests of [`WriteBehind`]: large enough that a request is rare, small
/// enough that the final sync finds little left to write.
pub const WRITE_BEHIND_BYTES: u64 = 8 << 20;

/// Starts the write-out to disk of the pages of `file` written so far and returns without waiting for it
/// (Linux; elsewhere nothing). Any open handle of the file will do: the pages are the file's, not the
/// handle's, so a file another library writes (HDF5) can be handed on through a handle opened for reading.
pub fn start_write_out(file: &File) {
    #[cfg(target_os = "linux")]
    {
        use std::os::fd::AsRawFd;
        // SAFETY: the descriptor is open for the life of `file`; the call only reads its arguments.
        // Offset 0 and length 0 mean the whole file. A failure (e.g. a file system without write-out)
        // leaves the final sync to do the work, as without this call.
        unsafe {
            libc::sync_file_range(file.as_raw_fd(), 0, 0, libc::SYNC_FILE_RANGE_WRITE);
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = file;
}

/// A file written front to back whose pages are sent to disk as it grows: after every
/// [`WRITE_BEHIND_BYTES`] written, [`start_write_out`]. The bytes are the file's writes, unchanged.
///
/// # Examples
/// ```
/// use std::io::Write;
/// let path = std::env::temp_dir().join(format!("stochvib-doc-behind-{}", std::process::id()));
/// let mut w = stochvib::io_rules::WriteBehind::new(std::fs::File::create(&path).unwrap());
/// w.write_all(b"point,output\n").unwrap();
/// w.flush().unwrap();
/// assert_eq!(std::fs::read(&path).unwrap(), b"point,output\n");
/// std::fs::remove_file(&path).unwrap();
/// ```
#[derive(Debug)]
pub struct WriteBehind {
    file: File,
    unsent: u64,
}

impl WriteBehind {
    /// Wraps `file` (positioned where writing goes on).
    pub fn new(file: File) -> WriteBehind {
        WriteBehind { file, unsent: 0 }
    }
}

impl Write for WriteBehind {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.file.write(buf)?;
        self.unsent += n as u64;
        if self.unsent >= WRITE_BEHIND_BYTES {
            start_write_out(&self.file);
            self.unsent = 0;
        }
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    /// The bytes through a [`WriteBehind`] are the bytes written, across several write-out requests.
    #[test]
    fn write_behind_writes_the_bytes_unchanged() {
        let dir = std::env::temp_dir().join(format!("stochvib-behind-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("table.csv");
        let piece: Vec<u8> = (0..=255u8).cycle().take(3 << 20).collect();
        let mut w = WriteBehind::new(File::create(&path).unwrap());
        for _ in 0..7 {
            w.write_all(&piece).unwrap(); // 21 MiB: two requests
        }
        w.flush().unwrap();
        drop(w);
        let mut back = Vec::new();
        File::open(&path).unwrap().read_to_end(&mut back).unwrap();
        assert_eq!(back.len(), 7 * piece.len());
        assert!(back.chunks(piece.len()).all(|c| c == &piece[..]));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
