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

/// The 256-entry table of the reflected polynomial 0xEDB88320.
const TABLE: [u32; 256] = {
    let mut t = [0u32; 256];
    let mut i = 0;
    while i < 256 {
        let mut c = i as u32;
        let mut k = 0;
        while k < 8 {
            c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            k += 1;
        }
        t[i] = c;
        i += 1;
    }
    t
};

/// A running CRC-32.
#[derive(Debug, Clone, Copy)]
pub struct Crc32(u32);

impl Default for Crc32 {
    fn default() -> Self {
        Crc32(0xFFFF_FFFF)
    }
}

impl Crc32 {
    /// Adds bytes.
    pub fn update(&mut self, bytes: &[u8]) {
        let mut c = self.0;
        for &b in bytes {
            c = TABLE[((c ^ b as u32) & 0xFF) as usize] ^ (c >> 8);
        }
        self.0 = c;
    }

    /// Adds f64 values as their little-endian bytes.
    pub fn update_f64(&mut self, values: &[f64]) {
        for v in values {
            self.update(&v.to_le_bytes());
        }
    }

    /// The checksum of everything added.
    pub fn finish(self) -> u32 {
        self.0 ^ 0xFFFF_FFFF
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
}
