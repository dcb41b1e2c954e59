//! Problem definitions of the HDF5-write and dynamic-stiffness-chain jobs, shared by the criterion benches
//! (`benches/store.rs`, `benches/chain.rs`) and the comparison binary (`examples/compare_rust.rs`). The
//! numpy/h5py/scipy side (`benches/compare/compare.py`, functions `h5_*` and `chain_*`) builds the same
//! data from the same formulas.
#![allow(dead_code)] // every bench target uses a different subset

use nalgebra::Complex;
use ndarray::Array2;
use std::path::{Path, PathBuf};
use stochvib::models::dynamic_stiffness_chain::TorsionalChain;
use stochvib::store::{Compression, RunFile, RunMetadata, RunWriter, Signal, SignalGroup};

// ---- HDF5 write -------------------------------------------------------------------------------------

/// Realizations of the uncompressed write job (rows of the dataset).
pub const H5_ROWS: usize = 1000;
/// Samples per realization (columns): 2¹⁶, so the dataset is 1000 × 2¹⁶ f64 = 524 MB.
pub const H5_COLS: usize = 1 << 16;
/// Realizations per shard (= per `write_shard` call): `simulate`'s default `shard_size`.
pub const H5_SHARD: usize = 50;
/// Realizations of the deflate job (deflate runs at tens of MB/s: 100 × 2¹⁶ f64 = 52 MB).
pub const H5_DEFLATE_ROWS: usize = 100;

/// Value `i` of the test data: splitmix64(i) mapped to [−0.5, 0.5) (noise-like, so deflate barely helps,
/// as on real realizations; identical in compare.py, which uses the same integer arithmetic in uint64).
///
/// # Formula
/// ```text
/// z = (i + 1)·0x9E3779B97F4A7C15;  z = (z ^ z>>30)·0xBF58476D1CE4E5B9;  z = (z ^ z>>27)·0x94D049BB133111EB;
/// z ^= z>>31;  x = (z >> 11)·2⁻⁵³ − 0.5                                  (all mod 2⁶⁴)
/// ```
#[inline]
pub fn h5_value(i: u64) -> f64 {
    let mut z = (i.wrapping_add(1)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 * (1.0 / (1u64 << 53) as f64) - 0.5
}

/// The `[rows, cols]` test data, x[i, k] = [`h5_value`]`(i·cols + k)`.
pub fn h5_data(rows: usize, cols: usize) -> Array2<f64> {
    Array2::from_shape_fn((rows, cols), |(i, k)| h5_value((i * cols + k) as u64))
}

/// Σ x² over an array (the check value both sides compare: it must survive the write and read back).
pub fn sum_squares(a: &[f64]) -> f64 {
    // 4 partial sums: the reference is numpy's pairwise sum; both agree to ~1e-13 relative.
    let mut s = [0.0; 4];
    let mut chunks = a.chunks_exact(4);
    for c in &mut chunks {
        for j in 0..4 {
            s[j] += c[j] * c[j];
        }
    }
    s.iter().sum::<f64>() + chunks.remainder().iter().map(|x| x * x).sum::<f64>()
}

/// Run metadata of the write job: one output signal `x`, `rows × cols`, shards of [`H5_SHARD`], no
/// inputs or accumulators, raw data stored with `compression`. The chunk shape is the library's rule
/// (`layout::chunk_shape(2¹⁶, 50)` = (2, 2¹⁶), 1 MiB), which compare.py passes to h5py as `chunks=`.
pub fn h5_meta(rows: usize, cols: usize, compression: Compression) -> RunMetadata {
    RunMetadata {
        scenario_text: "# benchmark: HDF5 write throughput\n".into(),
        seed: 1,
        generator: "splitmix64 test pattern".into(),
        dt: 1e-3,
        n_samples: cols,
        n_realizations: rows,
        shard_size: H5_SHARD.min(rows),
        inputs: vec![],
        outputs: vec![Signal::new("x", "m")],
        accumulators: vec![],
        store_raw: true,
        compression,
        provenance: vec![],
    }
}

/// Writes `data` to a new run file at `path` through the library writer, as `simulate` does:
/// `RunWriter::create`, one `write_shard` per shard, then `finish` (sets `@complete`, closes, fsyncs and
/// renames) when `finish` is true, or drops the writer (closes the file, no fsync, leaves `<path>.tmp`)
/// when it is false. Returns the file written.
pub fn h5_write_library(path: &Path, data: &Array2<f64>, compression: Compression, finish: bool) -> PathBuf {
    let (rows, cols) = data.dim();
    let meta = h5_meta(rows, cols, compression);
    let mut w = RunWriter::create(path, &meta).expect("create the run file");
    for shard in 0..meta.n_shards() {
        let r = meta.shard_range(shard);
        let view = data.slice(ndarray::s![r, ..]);
        w.write_shard(shard, &[], &[view], &[]).expect("write a shard");
    }
    if finish {
        w.finish().expect("finish the run file")
    } else {
        let tmp = w.tmp_path().to_path_buf();
        drop(w);
        tmp
    }
}

/// Reads the whole signal `x` back through the library reader and returns Σ x² (complete files only;
/// for a `.tmp` it opens with `RunFile::open_any`).
pub fn h5_read_check(path: &Path) -> f64 {
    let run = RunFile::open_any(path).expect("open the run file");
    let n = run.metadata().n_realizations;
    let a = run
        .read_signals(SignalGroup::Outputs, "x", 0..n)
        .expect("read the signal back");
    sum_squares(a.as_slice().expect("standard layout"))
}

/// A fresh temporary directory for the write jobs (under `$TMPDIR`).
pub fn h5_tmpdir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stochvib-h5bench-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("create a temporary directory");
    d
}

// ---- dynamic-stiffness chain ---------------------------------------------------------------------------

/// Forcing frequency of the chain jobs, rad/s (inside the pass band of the chain, above √(10/I) ≈ 3 rad/s and below
/// 2√(C/I) ≈ 160–270 rad/s, so the response does not decay along it and no value becomes subnormal).
pub const CHAIN_P: f64 = 40.0;

/// The benchmark chain of `n` masses (index k from 0), identical in compare.py:
/// I_k = 1 + 0.1·(k mod 7) kg m², ground spring 10 N m/rad and damper 0.5 N m s/rad on every mass,
/// shafts C_k = 10⁴·(1 + 0.2·(k mod 5)) N m/rad with damping 2 N m s/rad; torque amplitudes M̄_k = 1 N m
/// on every mass (a load on every mass keeps every amplitude of order one).
pub fn chain(n: usize) -> (TorsionalChain, Vec<Complex<f64>>) {
    let inertia = (0..n).map(|k| 1.0 + 0.1 * (k % 7) as f64).collect();
    let shafts = n.saturating_sub(1);
    let stiff = (0..shafts).map(|k| 1.0e4 * (1.0 + 0.2 * (k % 5) as f64)).collect();
    let ch = TorsionalChain::new(inertia, vec![10.0; n], vec![0.5; n], stiff, vec![2.0; shafts]).expect("valid chain");
    (ch, vec![Complex::new(1.0, 0.0); n])
}

/// Check value of a chain response: Σ_k |Φ_k| + Σ_k |M_{k,k+1}|.
pub fn chain_check(r: &stochvib::models::dynamic_stiffness_chain::ChainResponse) -> f64 {
    r.angles.iter().map(|z| z.norm()).sum::<f64>() + r.shaft_torques.iter().map(|z| z.norm()).sum::<f64>()
}
