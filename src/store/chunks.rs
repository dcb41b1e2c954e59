//! Compressed shard writes: each chunk is filtered by the writer (byte shuffle, then zlib-format deflate),
//! all chunks of a shard in parallel, and handed to HDF5 already filtered with `H5Dwrite_chunk`.
//!
//! HDF5 runs a dataset's filter pipeline serially, inside its global lock, so a compressed write through
//! `H5Dwrite` uses one core. The bytes written here are exactly what HDF5's own pipeline for the dataset
//! (`H5Pset_shuffle` then `H5Pset_deflate`, declared when the dataset is created) expects to undo on read:
//! any HDF5 reader (the crate's [`RunFile`](super::RunFile), h5py, `h5dump`) decompresses them with its
//! standard filters. The deflate stream comes from zlib-rs instead of the C zlib, so the compressed
//! bytes (not the data) may differ from what `H5Dwrite` would have stored.
//!
//! # Compression levels
//! zlib-rs (like zlib-ng) implements level 1 as `deflate_quick`, which codes with the static Huffman
//! table only. On shuffled measurement noise, where nearly all of the gain is the entropy coding of the
//! sign/exponent byte planes, that leaves the data almost uncompressed: 0.973 of the raw size for
//! N(0, 0.02²) doubles, against 0.882 for C zlib level 1 (HDF5's and h5py's filter). Level 1 is therefore
//! written with zlib-rs level 2 (`deflate_fast` with dynamic Huffman codes: 0.878, the size C zlib level 1
//! gives, and faster than it); levels 2–9 are passed through. See [`zlib_rs_level`].
//!
//! # Formula
//! A chunk of `r × c` elements (padded with zeros where it extends beyond the dataset, as HDF5 itself
//! stores edge chunks) is the row-major byte image b of its f64 values in the dataset's (native) byte
//! order. The shuffle filter with element size 8 stores byte `j` of element `i` at position `j·(r·c) + i`;
//! deflate then compresses that buffer as one zlib stream at the dataset's level.

use flate2::write::ZlibEncoder;
use ndarray::ArrayView2;
use rayon::prelude::*;
use std::io::Write;

/// Byte shuffle of `values` with element size 8 (HDF5's `H5Z_FILTER_SHUFFLE`): byte `j` of element `i`
/// goes to `out[j·n + i]`, `n = values.len()`.
pub(crate) fn shuffle_f64(values: &[f64], out: &mut Vec<u8>) {
    let n = values.len();
    out.clear();
    out.resize(8 * n, 0);
    let (p0, rest) = out.split_at_mut(n);
    let (p1, rest) = rest.split_at_mut(n);
    let (p2, rest) = rest.split_at_mut(n);
    let (p3, rest) = rest.split_at_mut(n);
    let (p4, rest) = rest.split_at_mut(n);
    let (p5, rest) = rest.split_at_mut(n);
    let (p6, p7) = rest.split_at_mut(n);
    for (i, v) in values.iter().enumerate() {
        let b = v.to_ne_bytes();
        p0[i] = b[0];
        p1[i] = b[1];
        p2[i] = b[2];
        p3[i] = b[3];
        p4[i] = b[4];
        p5[i] = b[5];
        p6[i] = b[6];
        p7[i] = b[7];
    }
}

/// The zlib-rs level used for the HDF5 deflate level `level` (1–9): level 1 becomes 2 (see the module's
/// *Compression levels*), every other level is unchanged. The dataset's filter pipeline keeps the
/// requested level; a deflate reader does not depend on it.
pub(crate) fn zlib_rs_level(level: u8) -> u32 {
    u32::from(level.max(2))
}

/// One filtered chunk: its offset in the dataset (element coordinates) and its stored bytes.
pub(crate) struct FilteredChunk {
    pub offset: [u64; 2],
    pub bytes: Vec<u8>,
}

/// Filters every chunk of the block `data` (rows `row0 ..` of a dataset of `n_cols` columns, chunk shape
/// `chunk`), in parallel. `row0` must be a multiple of `chunk.0`; the block's last chunk row and column may
/// be partial (they are zero-padded to the full chunk).
pub(crate) fn filter_block(
    data: ArrayView2<'_, f64>,
    row0: usize,
    chunk: (usize, usize),
    level: u8,
) -> Vec<FilteredChunk> {
    let (rows, cols) = data.dim();
    let (cr, cc) = chunk;
    debug_assert!(cr > 0 && cc > 0 && row0.is_multiple_of(cr));
    let chunk_rows = rows.div_ceil(cr);
    let chunk_cols = cols.div_ceil(cc);
    (0..chunk_rows * chunk_cols)
        .into_par_iter()
        .map_init(
            || (Vec::<f64>::new(), Vec::<u8>::new()),
            |(vals, shuffled), k| {
                let (ki, kj) = (k / chunk_cols, k % chunk_cols);
                vals.clear();
                vals.resize(cr * cc, 0.0);
                for r in 0..cr.min(rows - ki * cr) {
                    let src = data.row(ki * cr + r);
                    let c1 = cc.min(cols - kj * cc);
                    for (d, s) in vals[r * cc..r * cc + c1].iter_mut().zip(src.iter().skip(kj * cc)) {
                        *d = *s;
                    }
                }
                shuffle_f64(vals, shuffled);
                let mut enc = ZlibEncoder::new(
                    Vec::with_capacity(shuffled.len() / 2),
                    flate2::Compression::new(zlib_rs_level(level)),
                );
                // Writing into a Vec cannot fail.
                enc.write_all(shuffled).expect("deflate into memory");
                let bytes = enc.finish().expect("deflate into memory");
                FilteredChunk {
                    offset: [(row0 + ki * cr) as u64, (kj * cc) as u64],
                    bytes,
                }
            },
        )
        .collect()
}

/// Stores already-filtered chunks (filter mask 0: every filter of the pipeline was applied).
pub(crate) fn write_filtered(ds: &hdf5::Dataset, chunks: &[FilteredChunk]) -> hdf5::Result<()> {
    hdf5::sync::sync(|| {
        for c in chunks {
            // SAFETY: `ds.id()` is an open dataset of rank 2 (checked by the writer when it was created),
            // `offset` has 2 entries and `bytes` is a live buffer of the given length.
            hdf5::h5check(unsafe {
                hdf5_sys::h5d::H5Dwrite_chunk(
                    ds.id(),
                    hdf5_sys::h5p::H5P_DEFAULT,
                    0,
                    c.offset.as_ptr(),
                    c.bytes.len(),
                    c.bytes.as_ptr().cast(),
                )
            })?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shuffle against its definition, written as a slow oracle: out[j·n + i] = byte j of value i.
    #[test]
    fn shuffle_matches_its_definition() {
        let v: Vec<f64> = (0..37).map(|i| (i as f64 * 0.37).sin() * 1e3 - 7.0).collect();
        let mut out = Vec::new();
        shuffle_f64(&v, &mut out);
        let n = v.len();
        for (i, x) in v.iter().enumerate() {
            for (j, b) in x.to_ne_bytes().iter().enumerate() {
                assert_eq!(out[j * n + i], *b, "element {i}, byte {j}");
            }
        }
    }

    /// Deflate level 1 of shuffled Gaussian noise reaches the size an entropy coder must reach.
    ///
    /// Bound (independent of any zlib): a Huffman code of a byte plane with order-0 entropy H bits per
    /// byte costs less than H + 1 bits per byte, and never needs more than 8 (a plane of uniform random
    /// mantissa bytes is coded at ≈ 8). So the compressed size is at most Σ_planes min(8, H + 1)/8 · n bytes,
    /// plus block headers (allowed 1 %). For N(0, 0.02²) noise the two top planes (sign and exponent) have
    /// H ≈ 1.3 and 6.1 bits, the six mantissa planes ≈ 8: the bound is ≈ 0.90 of the raw size. zlib-rs's
    /// own level 1 (`deflate_quick`, static Huffman table) gives 0.973 and fails this test; C zlib level 1,
    /// which HDF5's filter and h5py use, gives 0.882.
    #[test]
    fn level_one_compresses_noise_like_an_entropy_coder() {
        use std::f64::consts::PI;
        let n = 1 << 16;
        // splitmix64 + Box–Muller: a self-contained normal source, seed 7.
        let mut state = 7u64;
        let mut uniform = || {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        };
        let v: Vec<f64> = (0..n)
            .map(|_| {
                let (u1, u2) = (1.0 - uniform(), uniform());
                0.02 * (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
            })
            .collect();
        let mut shuffled = Vec::new();
        shuffle_f64(&v, &mut shuffled);
        let mut bound_bits = 0.0;
        for plane in shuffled.chunks(n) {
            let mut counts = [0usize; 256];
            plane.iter().for_each(|&b| counts[b as usize] += 1);
            let h: f64 = counts
                .iter()
                .filter(|&&c| c > 0)
                .map(|&c| {
                    let p = c as f64 / n as f64;
                    -p * p.log2()
                })
                .sum();
            bound_bits += (h + 1.0).min(8.0) * n as f64;
        }
        let bound = 1.01 * bound_bits / 8.0 / shuffled.len() as f64;
        let a = ndarray::Array2::from_shape_vec((1, n), v).unwrap();
        let chunks = filter_block(a.view(), 0, (1, n), 1);
        let ratio = chunks[0].bytes.len() as f64 / shuffled.len() as f64;
        assert!(
            ratio <= bound,
            "deflate:1 ratio {ratio:.4} > entropy-coder bound {bound:.4}"
        );
        assert!(
            bound < 0.95,
            "bound {bound:.4}: the noise should have low-entropy exponent planes"
        );
    }

    /// Offsets and padding of partial edge chunks: decompress, unshuffle and compare with the block.
    #[test]
    fn edge_chunks_are_padded_and_placed() {
        use flate2::read::ZlibDecoder;
        use std::io::Read;
        let (rows, cols, cr, cc) = (5, 7, 2, 3);
        let a = ndarray::Array2::from_shape_fn((rows, cols), |(i, j)| (10 * i + j) as f64 + 0.5);
        let chunks = filter_block(a.view(), 4, (cr, cc), 1);
        assert_eq!(chunks.len(), 3 * 3);
        for c in &chunks {
            let mut raw = Vec::new();
            ZlibDecoder::new(&c.bytes[..]).read_to_end(&mut raw).unwrap();
            let n = cr * cc;
            assert_eq!(raw.len(), 8 * n);
            for e in 0..n {
                let mut b = [0u8; 8];
                for (j, bj) in b.iter_mut().enumerate() {
                    *bj = raw[j * n + e];
                }
                let (r, col) = (c.offset[0] as usize - 4 + e / cc, c.offset[1] as usize + e % cc);
                let want = if r < rows && col < cols { a[(r, col)] } else { 0.0 };
                assert_eq!(f64::from_ne_bytes(b), want, "chunk {:?}, element {e}", c.offset);
            }
        }
    }
}
