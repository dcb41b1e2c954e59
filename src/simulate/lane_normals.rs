//! The standard normals of L random streams drawn side by side: lane l gives, bit for bit, the variates
//! `rand_distr::StandardNormal` draws from stream l ([`super::stream`]), in the same order, with the stream
//! left in the same state; only the common case of the ziggurat is done here, many draws of a lane at a time.
//!
//! # Formula
//! xoshiro256++ (Blackman & Vigna, "Scrambled linear pseudorandom number generators", 2021), the state
//! seeded as `Xoshiro256PlusPlus::seed_from_u64` does (four SplitMix64 outputs). The ziggurat of
//! `rand_distr` 0.6 (Marsaglia & Tsang 2000, with its 256 boxes): a draw `b` gives the box i = b mod 256
//! and u = (2 + (b ≫ 12)·2⁻⁵¹) − 3 ∈ [−1, 1); x = u·X_i is accepted at once when |x| < X_{i+1}.
//! That case is done here; every other draw (≈ 1.2 %, and every draw of the two top boxes) is redone from
//! the stream's state before it by `rand_distr` itself, so the rare paths
//! (the tail, the wedges) are the crate's own code. The box edges X_i are read from `rand_distr` once
//! ([`edges`]): a draw of box i with u = 2⁻⁵¹ is accepted and returns 2⁻⁵¹·X_i exactly.
//!
//! Eight lanes on a CPU with AVX-512 are drawn side by side in vectors (`x86::fill8_avx512`); every other
//! case lane by lane in scalar code, which is the oracle of the vector path.

use rand::TryRng;
use rand_distr::{Distribution, StandardNormal};
use std::convert::Infallible;
use std::sync::OnceLock;

/// One random stream: the state of `rand`'s `Xoshiro256PlusPlus` held where the lanes can reach it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct StreamRng {
    s: [u64; 4],
}

impl StreamRng {
    /// Stream i of `seed`: the generator of [`super::stream`] in the same state.
    pub(crate) fn new(seed: u64, i: u64) -> Self {
        let mut state = super::stream_key(seed, i);
        let s = std::array::from_fn(|_| {
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let z = state;
            let z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            let z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        });
        StreamRng { s }
    }

    /// The next standard normal of the stream.
    #[inline]
    pub(crate) fn normal(&mut self) -> f64 {
        StandardNormal.sample(self)
    }
}

impl TryRng for StreamRng {
    type Error = Infallible;

    #[inline]
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        self.try_next_u64().map(|v| (v >> 32) as u32)
    }

    #[inline]
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        let s = &mut self.s;
        let res = s[0].wrapping_add(s[3]).rotate_left(23).wrapping_add(s[0]);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        Ok(res)
    }

    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        for chunk in dst.chunks_mut(8) {
            let v = self.try_next_u64()?.to_le_bytes();
            chunk.copy_from_slice(&v[..chunk.len()]);
        }
        Ok(())
    }
}

/// The ziggurat's box edges for the lanes: `x[i]` = X_i, and `accept[i]` = X_{i+1} for the boxes whose
/// edges were read, 0 (never accepted in the lanes) for the others.
struct Edges {
    x: [f64; 256],
    accept: [f64; 256],
}

/// A generator that returns one word, over and over.
struct Fixed(u64);

impl TryRng for Fixed {
    type Error = Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        Ok((self.0 >> 32) as u32)
    }
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        Ok(self.0)
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        dst.fill(0);
        Ok(())
    }
}

/// X_i for i < 255, read from `rand_distr`: the word with box i and mantissa 2⁵¹ + 1 gives u = 2⁻⁵¹ exactly,
/// accepted in every box below the top one (X_{i+1} > 2⁻⁵¹X_i), so the draw returns 2⁻⁵¹·X_i.
fn edges() -> &'static Edges {
    static EDGES: OnceLock<Edges> = OnceLock::new();
    EDGES.get_or_init(|| {
        let mut x = [0.0; 256];
        for (i, v) in x.iter_mut().enumerate().take(255) {
            let word = ((1u64 << 51) + 1) << 12 | i as u64;
            let x: f64 = StandardNormal.sample(&mut Fixed(word));
            *v = x * 2f64.powi(51);
        }
        // boxes 254 and 255 (X_255 unread) always go to the crate's code
        let accept = std::array::from_fn(|i| if i < 254 { x[i + 1] } else { 0.0 });
        Edges { x, accept }
    })
}

/// L streams drawn side by side (see the module's formula).
pub(crate) struct LaneNormals<const L: usize> {
    s: [[u64; L]; 4],
    edges: &'static Edges,
}

impl<const L: usize> LaneNormals<L> {
    /// The lanes of `streams` (lane l from `streams[l]`, in its state).
    pub(crate) fn new(streams: [StreamRng; L]) -> Self {
        LaneNormals {
            s: std::array::from_fn(|k| std::array::from_fn(|l| streams[l].s[k])),
            edges: edges(),
        }
    }

    /// Lane l's stream in its current state.
    pub(crate) fn stream(&self, l: usize) -> StreamRng {
        StreamRng {
            s: std::array::from_fn(|k| self.s[k][l]),
        }
    }

    /// The next standard normal of every lane.
    #[cfg(test)]
    pub(crate) fn draw(&mut self) -> [f64; L] {
        let mut x = [[0.0; L]];
        self.fill(&mut x);
        x[0]
    }

    /// The next `out.len()` standard normals of every lane: `out[k][l]` is lane l's k-th (as `out.len()`
    /// calls of [`Self::draw`] would give them).
    ///
    /// Lane by lane, each draw in scalar code: a tight loop over one stream, its state in registers and the
    /// box edges in cache (the lanes side by side in vectors made the compiler extract and reinsert every
    /// lane's word for the box look-ups).
    pub(crate) fn fill(&mut self, out: &mut [[f64; L]]) {
        #[cfg(target_arch = "x86_64")]
        if L == 8 && crate::linalg::vmath::Isa::detected() == crate::linalg::vmath::Isa::Avx512 {
            // SAFETY: L = 8, so `[[u64; L]; 4]` is `[[u64; 8]; 4]` and `[f64; L]` is `[f64; 8]` (the same
            // types, hence the same layout); the CPU has AVX-512 F (`Isa::Avx512` is detected only then).
            unsafe {
                let s = &mut *(&mut self.s as *mut [[u64; L]; 4] as *mut [[u64; 8]; 4]);
                let out = std::slice::from_raw_parts_mut(out.as_mut_ptr() as *mut [f64; 8], out.len());
                x86::fill8_avx512(s, self.edges, out);
            }
            return;
        }
        self.fill_scalar(out);
    }

    /// [`Self::fill`] in scalar code, lane by lane: the oracle of the vector path (and the path of every
    /// other lane count and CPU).
    pub(crate) fn fill_scalar(&mut self, out: &mut [[f64; L]]) {
        let e = self.edges;
        for l in 0..L {
            let mut r = self.stream(l);
            for row in out.iter_mut() {
                row[l] = r.fast_normal(e);
            }
            (0..4).for_each(|k| self.s[k][l] = r.s[k]);
        }
    }
}

impl StreamRng {
    /// The next standard normal: the ziggurat's common case here, every other draw redone by `rand_distr`
    /// from the state before it (see the module's formula).
    #[inline(always)]
    fn fast_normal(&mut self, e: &Edges) -> f64 {
        let [s0, s1, s2, s3] = self.s;
        let bits = rand::Rng::next_u64(self);
        let i = (bits & 0xff) as usize;
        let u = f64::from_bits((bits >> 12) | 0x4000_0000_0000_0000) - 3.0;
        let x = u * e.x[i];
        if x.abs() < e.accept[i] {
            return x;
        }
        let x;
        (x, self.s) = redo(s0, s1, s2, s3);
        x
    }
}

/// A draw not accepted at once, redone by `rand_distr` from the stream's state (s0, s1, s2, s3): the variate
/// and the state after it (the words by value, in registers, so that the draw loop keeps its state there;
/// ≈ 1.2 % of draws).
#[cold]
#[inline(never)]
fn redo(s0: u64, s1: u64, s2: u64, s3: u64) -> (f64, [u64; 4]) {
    let mut r = StreamRng { s: [s0, s1, s2, s3] };
    (r.normal(), r.s)
}

/// Eight lanes in one AVX-512 vector.
#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::{redo, Edges};
    use std::arch::x86_64::*;

    /// The 8 streams' state words as 4 vectors (word k of every lane in vector k).
    struct State([__m512i; 4]);

    impl State {
        /// # Safety
        /// AVX-512 F.
        #[target_feature(enable = "avx512f")]
        fn load(s: &[[u64; 8]; 4]) -> State {
            // SAFETY: each `s[k]` is 64 readable bytes (unaligned loads).
            State(std::array::from_fn(|k| unsafe {
                _mm512_loadu_si512(s[k].as_ptr().cast())
            }))
        }

        /// # Safety
        /// AVX-512 F.
        #[target_feature(enable = "avx512f")]
        fn store(&self, s: &mut [[u64; 8]; 4]) {
            for (k, v) in self.0.iter().enumerate() {
                // SAFETY: each `s[k]` is 64 writable bytes (unaligned stores).
                unsafe { _mm512_storeu_si512(s[k].as_mut_ptr().cast(), *v) };
            }
        }

        /// xoshiro256++'s output and step, every lane at once (the scalar `try_next_u64`).
        #[target_feature(enable = "avx512f")]
        #[inline]
        fn next(&mut self) -> __m512i {
            let [s0, s1, s2, s3] = self.0;
            let res = _mm512_add_epi64(_mm512_rol_epi64::<23>(_mm512_add_epi64(s0, s3)), s0);
            let t = _mm512_slli_epi64::<17>(s1);
            let s2 = _mm512_xor_si512(s2, s0);
            let s3 = _mm512_xor_si512(s3, s1);
            let s1 = _mm512_xor_si512(s1, s2);
            let s0 = _mm512_xor_si512(s0, s3);
            let s2 = _mm512_xor_si512(s2, t);
            let s3 = _mm512_rol_epi64::<45>(s3);
            self.0 = [s0, s1, s2, s3];
            res
        }
    }

    /// The rows of `out` from the 8 lanes' streams `s` (left in their new state): per row, every lane's word,
    /// box and u, the box edges gathered, the common case accepted by a mask; a lane outside it is redone
    /// by `rand_distr` from its state before this draw, and its state after that put back.
    ///
    /// # Safety
    /// The CPU has AVX-512 F.
    #[target_feature(enable = "avx512f")]
    pub(super) unsafe fn fill8_avx512(s: &mut [[u64; 8]; 4], e: &Edges, out: &mut [[f64; 8]]) {
        let mut st = State::load(s);
        let (xt, at) = (e.x.as_ptr(), e.accept.as_ptr());
        let low_byte = _mm512_set1_epi64(0xff);
        let exponent = _mm512_set1_epi64(0x4000_0000_0000_0000);
        let three = _mm512_set1_pd(3.0);
        for row in out.iter_mut() {
            let before = [st.0[0], st.0[1], st.0[2], st.0[3]];
            let bits = st.next();
            let i = _mm512_and_si512(bits, low_byte);
            let u = _mm512_sub_pd(
                _mm512_castsi512_pd(_mm512_or_si512(_mm512_srli_epi64::<12>(bits), exponent)),
                three,
            );
            // SAFETY: every index is a box number 0..=255, inside the two 256-entry tables.
            let (xi, ai) = unsafe { (_mm512_i64gather_pd::<8>(i, xt), _mm512_i64gather_pd::<8>(i, at)) };
            let x = _mm512_mul_pd(u, xi);
            let ok = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(_mm512_abs_pd(x), ai);
            // SAFETY: a row is 8 writable f64.
            unsafe { _mm512_storeu_pd(row.as_mut_ptr(), x) };
            // the lanes outside the common case, one at a time: the lane's words moved out of the vectors
            // and its new state merged back by masks (in registers: a store of lanes and a vector reload
            // would stall on store forwarding)
            let mut redone = !ok;
            while redone != 0 {
                let l = redone.trailing_zeros() as usize;
                redone &= redone - 1;
                let at = _mm512_set1_epi64(l as i64);
                let word =
                    |v: __m512i| _mm_cvtsi128_si64(_mm512_castsi512_si128(_mm512_permutexvar_epi64(at, v))) as u64;
                let (v, after) = redo(word(before[0]), word(before[1]), word(before[2]), word(before[3]));
                row[l] = v;
                for (w, a) in st.0.iter_mut().zip(after) {
                    *w = _mm512_mask_set1_epi64(*w, 1 << l, a as i64);
                }
            }
        }
        st.store(s);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::{fill_standard_normal, stream};
    use rand::Rng;

    #[test]
    fn stream_rng_is_the_stream_of_rand() {
        for i in [0, 1, 77, u64::MAX] {
            let (mut a, mut b) = (StreamRng::new(5, i), stream(5, i));
            for _ in 0..1000 {
                assert_eq!(a.next_u64(), b.next_u64());
            }
        }
    }

    /// 8 lanes × 2·10⁵ draws (≈ 19,000 of them redone by `rand_distr`, ≈ 140 beyond X_0 = 3.91 from the tail
    /// box among them) have the
    /// bits of `fill_standard_normal` on each lane's stream, and leave each stream where it leaves it.
    #[test]
    fn lanes_give_the_bits_of_rand_distr() {
        const L: usize = 8;
        let n = 200_000;
        let mut lanes = LaneNormals::<L>::new(std::array::from_fn(|l| StreamRng::new(3, l as u64)));
        let got: Vec<[f64; L]> = (0..n).map(|_| lanes.draw()).collect();
        for l in 0..L {
            let mut want = vec![0.0; n];
            let mut rng = stream(3, l as u64);
            fill_standard_normal(&mut rng, &mut want);
            assert!(
                got.iter().zip(&want).all(|(g, w)| g[l].to_bits() == w.to_bits()),
                "lane {l}"
            );
            assert_eq!(
                lanes.stream(l).next_u64(),
                rng.next_u64(),
                "lane {l}: the stream's state"
            );
        }
        assert!(
            got.iter().any(|g| g.iter().any(|v| v.abs() > 3.92)),
            "the tail box was drawn"
        );
    }

    /// The dispatched fill of 8 lanes (the AVX-512 path where the CPU has it) against the scalar oracle,
    /// bit for bit: 1.1·10⁶ draws per lane in fills of uneven lengths (1, 37, 64, 5000, ...; about 1.2 % of
    /// the draws, ≈ 10⁵ over the lanes, are redone by `rand_distr`, the tail and the wedges among them), and
    /// every lane's stream left in the same state.
    #[test]
    fn the_vector_fill_gives_the_bits_of_the_scalar_fill() {
        const L: usize = 8;
        let streams: [StreamRng; L] = std::array::from_fn(|l| StreamRng::new(0x5eed, 7 * l as u64 + 1));
        let (mut fast, mut slow) = (LaneNormals::<L>::new(streams), LaneNormals::<L>::new(streams));
        let lengths = [1usize, 37, 64, 5000, 3, 1_094_895];
        let n: usize = lengths.iter().sum();
        let (mut a, mut b) = (vec![[0.0; L]; n], vec![[0.0; L]; n]);
        let mut at = 0;
        for m in lengths {
            fast.fill(&mut a[at..at + m]);
            slow.fill_scalar(&mut b[at..at + m]);
            at += m;
        }
        for l in 0..L {
            let first_bad = (0..n).find(|&k| a[k][l].to_bits() != b[k][l].to_bits());
            assert_eq!(first_bad, None, "lane {l}");
            assert_eq!(fast.stream(l), slow.stream(l), "lane {l}: its state");
        }
        // beyond X_0 = 3.91 only the tail sampling of `rand_distr` draws: the redone path ran in every lane
        // (P(|x| > 3.91) ≈ 9·10⁻⁵, about 100 such draws per lane; the streams are fixed, so this is exact)
        for l in 0..L {
            assert!(a.iter().any(|r| r[l].abs() > 3.92), "lane {l}: a tail draw was redone");
        }
    }

    /// Draws filled many steps at a time, in fills of uneven lengths (one row, part of a chunk, a chunk of
    /// 64, a long one), have the bits of `fill_standard_normal` on each lane's stream and leave each stream
    /// where it leaves it.
    #[test]
    fn fills_give_the_bits_of_rand_distr() {
        const L: usize = 4;
        let lengths = [1, 37, 64, 5000, 3];
        let n: usize = lengths.iter().sum();
        let mut lanes = LaneNormals::<L>::new(std::array::from_fn(|l| StreamRng::new(11, 100 + l as u64)));
        let mut got = vec![[0.0; L]; n];
        let mut at = 0;
        for m in lengths {
            lanes.fill(&mut got[at..at + m]);
            at += m;
        }
        let bits = |v: &mut dyn Iterator<Item = f64>| v.map(f64::to_bits).collect::<Vec<_>>();
        for l in 0..L {
            let mut rng = stream(11, 100 + l as u64);
            let mut want = vec![0.0; n];
            fill_standard_normal(&mut rng, &mut want);
            assert_eq!(
                bits(&mut got.iter().map(|g| g[l])),
                bits(&mut want.into_iter()),
                "lane {l}"
            );
            assert_eq!(lanes.stream(l).next_u64(), rng.next_u64(), "lane {l}: its state");
        }
    }
}
