//! CRC-32 checksums of what a run file stores, so that silent corruption of a file is reported.
//!
//! # Formula
//! CRC-32 of IEEE 802.3 (the checksum of zlib and PNG): reflected polynomial 0xEDB88320, initial value and
//! final XOR 0xFFFFFFFF. f64 data are checksummed as their little-endian bytes, in row-major order.
//!
//! # Examples
//! ```
//! use stochvib::store::checksum::crc32;
//! assert_eq!(crc32(b"123456789"), 0xCBF4_3926); // the standard check value
//! ```

/// A running CRC-32.
///
/// Computed by [`crc32fast`] (carry-less multiplication with PCLMULQDQ, or VPCLMULQDQ on AVX2/AVX-512
/// CPUs, chosen at run time; a table fallback elsewhere): the same CRC-32/ISO-HDLC as the byte-at-a-time
/// table loop the store used before, so every stored check value is unchanged.
#[derive(Debug, Clone, Default)]
pub struct Crc32(crc32fast::Hasher);

impl Crc32 {
    /// Adds bytes.
    pub fn update(&mut self, bytes: &[u8]) {
        self.0.update(bytes);
    }

    /// Adds f64 values as their little-endian bytes (in place on a little-endian machine: no copy).
    pub fn update_f64(&mut self, values: &[f64]) {
        #[cfg(target_endian = "little")]
        self.0.update(bytemuck::cast_slice(values));
        #[cfg(not(target_endian = "little"))]
        for chunk in values.chunks(512) {
            let mut buf = [0u8; 512 * 8];
            for (b, v) in buf.chunks_exact_mut(8).zip(chunk) {
                b.copy_from_slice(&v.to_le_bytes());
            }
            self.0.update(&buf[..chunk.len() * 8]);
        }
    }

    /// The checksum of everything added.
    pub fn finish(self) -> u32 {
        self.0.finalize()
    }
}

/// CRC-32 of `bytes`.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut c = Crc32::default();
    c.update(bytes);
    c.finish()
}

/// CRC-32 of f64 values (little-endian bytes).
pub fn crc32_f64(values: &[f64]) -> u32 {
    let mut c = Crc32::default();
    c.update_f64(values);
    c.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Check values of CRC-32/ISO-HDLC (the catalogue of parametrised CRC algorithms, Greg Cook): "" → 0,
    /// "123456789" → 0xCBF43926, "a" → 0xE8B7BE43; and the f64 form equals the bytes form.
    #[test]
    fn standard_check_values() {
        assert_eq!(crc32(b""), 0);
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(b"a"), 0xE8B7_BE43);
        let v = [1.5f64, -2.0];
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        assert_eq!(crc32_f64(&v), crc32(&bytes));
        // streaming in pieces equals one pass
        let mut c = Crc32::default();
        c.update(b"1234");
        c.update(b"56789");
        assert_eq!(c.finish(), 0xCBF4_3926);
    }

    /// The byte-at-a-time table loop of CRC-32/ISO-HDLC (reflected polynomial 0xEDB88320, initial value and
    /// final XOR 0xFFFFFFFF; Sarwate, "Computation of cyclic redundancy checks via table look-up", CACM
    /// 31(8), 1988): the store's implementation before it used `crc32fast`, kept here as the oracle.
    fn crc32_table_loop(bytes: &[u8]) -> u32 {
        let table: Vec<u32> = (0..256u32)
            .map(|i| (0..8).fold(i, |c, _| if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 }))
            .collect();
        !bytes.iter().fold(0xFFFF_FFFFu32, |c, &b| {
            table[((c ^ b as u32) & 0xFF) as usize] ^ (c >> 8)
        })
    }

    /// Value stability: every stored check value is unchanged. The maintained implementation equals the
    /// table loop on every length 0..=600 (all the tails and alignments of the SIMD folding loops, whose
    /// blocks are 16–256 bytes), at every start offset 0..8 of a buffer, and on 1 MiB and on f64 data,
    /// including NaN payloads, ±0, subnormals and infinities.
    #[test]
    fn same_values_as_the_table_loop() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let bytes: Vec<u8> = (0..(1 << 20) + 7)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 24) as u8
            })
            .collect();
        for off in 0..8 {
            for len in 0..=600 {
                assert_eq!(
                    crc32(&bytes[off..off + len]),
                    crc32_table_loop(&bytes[off..off + len]),
                    "{off} {len}"
                );
            }
        }
        assert_eq!(crc32(&bytes), crc32_table_loop(&bytes));
        let v: Vec<f64> = [
            f64::NAN,
            -0.0,
            0.0,
            5e-324,
            -2.2e-308,
            f64::INFINITY,
            f64::MIN,
            1.0 / 3.0,
        ]
        .into_iter()
        .chain(
            bytes
                .chunks_exact(8)
                .take(5000)
                .map(|b| f64::from_le_bytes(b.try_into().unwrap())),
        )
        .collect();
        let le: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        assert_eq!(crc32_f64(&v), crc32_table_loop(&le));
    }
}
