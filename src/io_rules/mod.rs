//! The rules every command follows with files and resources, in one place (see `docs/files-and-limits.md`):
//!
//! * [`output`](mod@output) — **one output rule**: a target that is one of the command's inputs, a directory,
//!   a link, a FIFO, a device or a file of another kind is refused with or without `--overwrite`; results
//!   are written to a temporary file and put in place by one rename at the end ([`Staged`]).
//! * [`input`](mod@input) — **one input rule**: only regular files are read, each kind has a size limit, and
//!   text is read in bounded pieces ([`open_input`], [`read_text`], [`BoundedLines`]).
//! * [`resources`](mod@resources) — **one resource rule**: memory, disk and time are estimated before the
//!   work and compared with what the machine has or a stated cap ([`check_memory`], [`check_disk`],
//!   [`check_time`]); counts are multiplied with overflow checks ([`checked_product`]).
//! * [`streaming`](mod@streaming) — the pages of outputs of hundreds of megabytes go to disk while the next
//!   ones are computed ([`WriteBehind`], [`start_write_out`]).
//! * [`excerpt`](mod@excerpt) — a bad value is quoted in a message as a bounded excerpt ([`excerpt()`]).

pub mod excerpt;
pub mod input;
pub mod output;
pub mod resources;
pub mod streaming;

pub use excerpt::{excerpt, excerpt_of, MAX_EXCERPT_CHARS, MAX_REASON_CHARS};
pub use input::{
    check_input, open_input, read_text, BoundedLines, InputKind, CSV_INPUT, HDF5_INPUT, JSON_SHARD_INPUT,
    MAX_LINE_BYTES, TOML_INPUT,
};
pub use output::{
    check_output, process_alive, remove_stale_temporaries, same_file, starts_with, temporary_path, OutputKind, Staged,
    HDF5_SIGNATURE,
};
pub use resources::{
    available_disk, available_memory, bytes_text, check_disk, check_memory, check_time, checked_product, duration_text,
    parent_dir,
};
pub use streaming::{start_write_out, WriteBehind, WRITE_BEHIND_BYTES};
