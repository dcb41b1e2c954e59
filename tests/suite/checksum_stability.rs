//! Value stability of the run files' checksums: a file written by the store's earlier CRC-32 (a
//! byte-at-a-time table loop) still verifies after the change to `crc32fast`.
//!
//! The fixture `tests/data/run-written-with-table-crc.h5` was written by `stochvib simulate
//! data/isolator-single.toml --realizations 4 --shard-size 2 --store-raw --duration 1 --dt 0.01 --seed 3`
//! with the table-loop CRC (53 kB: raw inputs and outputs, accumulators, statistics, densities, each with
//! its stored `@crc32`).

use crate::common;
use std::path::PathBuf;
use stochvib::store::{RunFile, SignalGroup};

fn fixture() -> PathBuf {
    crate::common::root().join("tests/data/run-written-with-table-crc.h5")
}

/// Every checksum of the old file matches the values computed now (raw rows of 2 shards × 3 signals,
/// accumulators, statistics, densities), and a flipped bit in a raw sample of the same file is still
/// reported: the check compares real values, not nothing.
#[test]
fn a_file_checksummed_by_the_table_loop_still_verifies() {
    let _serial = common::hdf5_serial();
    let v = RunFile::open(fixture()).unwrap().verify().unwrap();
    assert!(v.format_version == 2 && v.checked >= 2 * 3, "{v:?}");
    assert!(RunFile::open(fixture()).unwrap().statistics().is_ok());
    let raw = RunFile::open(fixture())
        .unwrap()
        .read_signal(SignalGroup::Outputs, "x", 1)
        .unwrap();
    let bytes = std::fs::read(fixture()).unwrap();
    let pat = raw[40].to_le_bytes();
    let at = bytes
        .windows(8)
        .position(|w| w == pat)
        .expect("the sample is in the file");
    let mut damaged = bytes.clone();
    damaged[at] ^= 0x01;
    let p = crate::common::scratch_kept("crc-stability", "damaged").join("run.h5");
    std::fs::write(&p, damaged).unwrap();
    let e = RunFile::open(&p).and_then(|r| r.verify()).unwrap_err().to_string();
    let _ = std::fs::remove_file(&p);
    assert!(e.contains("checksum mismatch") && e.contains("outputs/x"), "{e}");
}
