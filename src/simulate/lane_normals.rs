//! The standard normals of L random streams drawn side by side: lane l gives, bit for bit, the variates
//! `rand_distr::StandardNormal` draws from stream l ([`super::stream`]), in the same order, with the stream
//! left in the same state; the common case of the ziggurat is done here many draws of a lane at a time, the
//! rest draw by draw.
//!
//! # Formula
//! xoshiro256++ (Blackman & Vigna, "Scrambled linear pseudorandom number generators", 2021), the state
//! seeded as `Xoshiro256PlusPlus::seed_from_u64` does (four SplitMix64 outputs). The ziggurat of
//! `rand_distr` 0.6 (Marsaglia & Tsang 2000, with its 256 boxes): a draw `b` gives the box i = b mod 256
//! and u = (2 + (b ≫ 12)·2⁻⁵¹) − 3 ∈ [−1, 1); x = u·X_i is accepted at once when |x| < X_{i+1}.
//! Every other draw (≈ 1.2 %, every draw of the top box among them) is finished as the crate does:
//! - a wedge (boxes 1..=255): with the next uniform v = (b′ ≫ 11)·2⁻⁵³, x is accepted when
//!   f_{i+1} + (f_i − f_{i+1})·v < e^(−x²/2), the crate's test with its heights f_i ([`super::ziggurat_f`])
//!   and libm's `exp`; a rejected draw starts the ziggurat's loop again, with a fresh draw;
//! - the tail box (i = 0): the crate's own code from the state before the draw.
//!
//! In the vector path the wedges of a row are decided side by side, by a short exponential with a proven
//! bound (relative 2⁻²⁶, `x86::exp_near`) and by libm's `exp` only where y lies within that bound of it, so
//! that every decision is libm's; the lanes a wedge rejects draw again side by side. In scalar code each
//! such draw is redone alone from the stream's state before it ([`redo`]).
//!
//! The box edges X_i are read from `rand_distr` once ([`edges`]): a draw of box i with u = 2⁻⁵¹ is
//! accepted and returns 2⁻⁵¹·X_i exactly (X_255 through its wedge, which accepts any v > 0 there).
//!
//! Eight lanes on a CPU with AVX-512 are drawn side by side in vectors (`x86::fill8_avx512`); every other
//! case lane by lane in scalar code, which is the oracle of the vector path.

use super::ziggurat_f::ZIG_NORM_F;
use rand::{Rng, RngExt, TryRng};
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

/// The ziggurat's box edges for the lanes: `x[i]` = X_i (X_256 = 0), and `accept[i]` = X_{i+1}.
struct Edges {
    x: [f64; 257],
    accept: [f64; 256],
}

/// A generator that returns the words of a list, the last one over and over.
#[derive(Clone)]
struct Words<'a>(&'a [u64]);

impl TryRng for Words<'_> {
    type Error = Infallible;
    fn try_next_u32(&mut self) -> Result<u32, Infallible> {
        self.try_next_u64().map(|v| (v >> 32) as u32)
    }
    fn try_next_u64(&mut self) -> Result<u64, Infallible> {
        let w = self.0.first().copied().unwrap_or(0);
        if self.0.len() > 1 {
            self.0 = &self.0[1..];
        }
        Ok(w)
    }
    fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
        dst.fill(0);
        Ok(())
    }
}

/// The word of box i whose u is m·2⁻⁵¹ − 1 (m < 2⁵²).
fn box_word(i: usize, m: u64) -> u64 {
    m << 12 | i as u64
}

/// X_i, read from `rand_distr`: the word with box i and mantissa 2⁵¹ + 1 gives u = 2⁻⁵¹ exactly, accepted
/// in every box below the top one (X_{i+1} > 2⁻⁵¹X_i), so the draw returns 2⁻⁵¹·X_i; in the top box (X_256
/// = 0) through its wedge, e^(−x²/2) = 1 = f_256 > f_256 + (f_255 − f_256)·v for the second word's v > 0.
fn edges() -> &'static Edges {
    static EDGES: OnceLock<Edges> = OnceLock::new();
    EDGES.get_or_init(|| {
        let mut x = [0.0; 257];
        for (i, v) in x.iter_mut().enumerate().take(256) {
            let words = [box_word(i, (1 << 51) + 1), u64::MAX];
            let x: f64 = StandardNormal.sample(&mut Words(&words));
            *v = x * 2f64.powi(51);
        }
        let accept = std::array::from_fn(|i| x[i + 1]);
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
    /// The next standard normal: the ziggurat's common case here, every other draw redone from the state
    /// before it (see the module's formula).
    #[inline(always)]
    fn fast_normal(&mut self, e: &Edges) -> f64 {
        let [s0, s1, s2, s3] = self.s;
        if let Some(x) = common_case(rand::Rng::next_u64(self), e) {
            return x;
        }
        let x;
        (x, self.s) = redo(s0, s1, s2, s3, e);
        x
    }
}

/// The ziggurat's common case for the draw `bits`: box i = bits mod 256, u from the upper 52 bits, x = u·X_i
/// when |x| < X_{i+1}, else None (the draw is to be redone; see the module's formula).
#[inline(always)]
fn common_case(bits: u64, e: &Edges) -> Option<f64> {
    let i = (bits & 0xff) as usize;
    let u = f64::from_bits((bits >> 12) | 0x4000_0000_0000_0000) - 3.0;
    let x = u * e.x[i];
    (x.abs() < e.accept[i]).then_some(x)
}

/// The next `out.len()` standard normals of the one stream `r`, in order, with the bits of
/// `rand_distr::StandardNormal` and `r` left in the same state ([`StreamNormals`] for one run).
pub(crate) fn fill_stream<R: Rng + Clone>(r: &mut R, out: &mut [f64]) {
    let mut s = StreamNormals::new(r);
    s.fill(out);
    *r = s.into_rng();
}

/// The standard normals of one stream, drawn over many calls (a loop's steps) with the generator held here
/// by value: the variates of `rand_distr::StandardNormal`, bit for bit, in order. The ziggurat's common
/// case is inline at the call, every other draw redone from the state before it (see the module's formula).
/// The crate's own draw is a call the compiler may or may not inline where it is used; here the common case
/// always is, and the generator's words can stay in registers through the loop.
pub(crate) struct StreamNormals<R> {
    g: R,
    e: &'static Edges,
}

impl<R: Rng + Clone> StreamNormals<R> {
    /// Draws that continue the stream `r` (a copy of it; [`Self::into_rng`] gives its state back).
    pub(crate) fn new(r: &R) -> Self {
        StreamNormals {
            g: r.clone(),
            e: edges(),
        }
    }

    /// The generator in its state after the draws so far.
    pub(crate) fn into_rng(self) -> R {
        self.g
    }

    /// The generator itself, to draw from it in between (the draws here continue after those).
    pub(crate) fn rng_mut(&mut self) -> &mut R {
        &mut self.g
    }

    /// The next standard normal.
    #[inline(always)]
    pub(crate) fn next(&mut self) -> f64 {
        let before = self.g.clone();
        if let Some(x) = common_case(self.g.next_u64(), self.e) {
            return x;
        }
        let y;
        (y, self.g) = redraw_cold(before, self.e);
        y
    }

    /// The next `out.len()` standard normals, in order.
    #[inline(always)]
    pub(crate) fn fill(&mut self, out: &mut [f64]) {
        for v in out.iter_mut() {
            *v = self.next();
        }
    }
}

/// [`redraw`] from the stream's state `g` before the draw, out of the draw loop of [`StreamNormals`] (≈ 1.2 %
/// of draws): the variate and the state after it.
#[cold]
#[inline(never)]
fn redraw_cold<R: Rng + Clone>(mut g: R, e: &Edges) -> (f64, R) {
    (redraw(&mut g, e), g)
}

/// A draw not accepted at once, redone from the stream's state (s0, s1, s2, s3): the variate and the state
/// after it (the words by value, in registers, so that the draw loop keeps its state there; ≈ 1.2 % of
/// draws).
#[cold]
#[inline(never)]
fn redo(s0: u64, s1: u64, s2: u64, s3: u64, e: &Edges) -> (f64, [u64; 4]) {
    let mut r = StreamRng { s: [s0, s1, s2, s3] };
    (redraw(&mut r, e), r.s)
}

/// The next standard normal of `r` as `rand_distr` draws it, its wedges decided here (see the module's
/// formula).
fn redraw<R: Rng + Clone>(r: &mut R, e: &Edges) -> f64 {
    let before = r.clone();
    let bits = r.next_u64();
    let i = (bits & 0xff) as usize;
    if i == 0 {
        *r = before;
        return StandardNormal.sample(r);
    }
    let u = f64::from_bits((bits >> 12) | 0x4000_0000_0000_0000) - 3.0;
    let x = u * e.x[i];
    if x.abs() < e.x[i + 1] {
        return x;
    }
    let f = &ZIG_NORM_F;
    let y = f[i + 1] + (f[i] - f[i + 1]) * r.random::<f64>();
    if y < (-x * x / 2.0).exp() {
        x
    } else {
        StandardNormal.sample(r)
    }
}

/// Eight lanes in one AVX-512 vector.
#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::{redo, Edges, ZIG_NORM_F};
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
    /// box and u, the box edges gathered, the common case accepted by a mask; the lanes outside it are
    /// finished by [`finish_row`].
    ///
    /// # Safety
    /// The CPU has AVX-512 F and DQ.
    #[target_feature(enable = "avx512f,avx512dq")]
    pub(super) unsafe fn fill8_avx512(s: &mut [[u64; 8]; 4], e: &Edges, out: &mut [[f64; 8]]) {
        let mut st = State::load(s);
        for row in out.iter_mut() {
            let before = st.0;
            let bits = st.next();
            let (i, x, ok) = common_case(bits, e);
            // SAFETY: a row is 8 writable f64.
            unsafe { _mm512_storeu_pd(row.as_mut_ptr(), x) };
            if ok != 0xff {
                // SAFETY: the CPU has AVX-512 F and DQ (this function's contract).
                unsafe { finish_row(&mut st, before, i, x, !ok, e, row) };
            }
        }
        st.store(s);
    }

    /// Every lane's box i, x = u·X_i and whether |x| < X_{i+1} (the common case), from its word `bits`.
    #[target_feature(enable = "avx512f")]
    #[inline]
    fn common_case(bits: __m512i, e: &Edges) -> (__m512i, __m512d, __mmask8) {
        let i = _mm512_and_si512(bits, _mm512_set1_epi64(0xff));
        let u = _mm512_sub_pd(
            _mm512_castsi512_pd(_mm512_or_si512(
                _mm512_srli_epi64::<12>(bits),
                _mm512_set1_epi64(0x4000_0000_0000_0000),
            )),
            _mm512_set1_pd(3.0),
        );
        // SAFETY: every index is a box number 0..=255, inside the tables of 257 and 256 entries.
        let (xi, ai) = unsafe {
            (
                _mm512_i64gather_pd::<8>(i, e.x.as_ptr()),
                _mm512_i64gather_pd::<8>(i, e.accept.as_ptr()),
            )
        };
        let x = _mm512_mul_pd(u, xi);
        (i, x, _mm512_cmp_pd_mask::<_CMP_LT_OQ>(_mm512_abs_pd(x), ai))
    }

    /// The lanes `pending` of a row (their draw from the state `before`: box `i`, value `x`, already stored
    /// in `row`) finished as `rand_distr` does, side by side: a lane in the tail box is redone alone from
    /// `before`; the wedges draw their uniform v (the state words of the other lanes kept by masks) and
    /// are decided by [`below_density`]; the lanes rejected draw again, until every lane has its variate.
    ///
    /// # Safety
    /// The CPU has AVX-512 F and DQ.
    #[target_feature(enable = "avx512f,avx512dq")]
    #[cold]
    #[inline(never)]
    unsafe fn finish_row(
        st: &mut State,
        mut before: [__m512i; 4],
        mut i: __m512i,
        mut x: __m512d,
        mut pending: __mmask8,
        e: &Edges,
        row: &mut [f64; 8],
    ) {
        loop {
            let tail = pending & _mm512_cmpeq_epi64_mask(i, _mm512_setzero_si512());
            redo_lanes(st, &before, tail, e, row);
            let wedge = pending & !tail;
            if wedge != 0 {
                let v = masked_next(st, wedge);
                let v = _mm512_mul_pd(
                    _mm512_cvtepu64_pd(_mm512_srli_epi64::<11>(v)),
                    _mm512_set1_pd(1.0 / (1u64 << 53) as f64),
                );
                let f = ZIG_NORM_F.as_ptr();
                // SAFETY: i ≤ 255, so i and i + 1 index the table of 257 heights.
                let (f0, f1) = unsafe {
                    (
                        _mm512_i64gather_pd::<8>(i, f),
                        _mm512_i64gather_pd::<8>(_mm512_add_epi64(i, _mm512_set1_epi64(1)), f),
                    )
                };
                let y = _mm512_add_pd(f1, _mm512_mul_pd(_mm512_sub_pd(f0, f1), v));
                let t = _mm512_div_pd(
                    _mm512_mul_pd(_mm512_sub_pd(_mm512_setzero_pd(), x), x),
                    _mm512_set1_pd(2.0),
                );
                pending = wedge & !below_density(y, t, wedge);
            } else {
                pending = 0;
            }
            if pending == 0 {
                return;
            }
            before = st.0;
            let bits = masked_next(st, pending);
            let ok;
            (i, x, ok) = common_case(bits, e);
            // SAFETY: a row is 8 writable f64.
            unsafe { _mm512_mask_storeu_pd(row.as_mut_ptr(), pending, x) };
            pending &= !ok;
        }
    }

    /// The next word of the lanes `lanes` (the streams of the others left where they are).
    #[target_feature(enable = "avx512f")]
    #[inline]
    fn masked_next(st: &mut State, lanes: __mmask8) -> __m512i {
        let old = st.0;
        let bits = st.next();
        for (w, o) in st.0.iter_mut().zip(old) {
            *w = _mm512_mask_blend_epi64(lanes, o, *w);
        }
        bits
    }

    /// The lanes `lanes` redone one at a time by [`redo`] from their state `before`: the lane's words moved
    /// out of the vectors and its new state merged back by masks (in registers: a store of lanes and a
    /// vector reload would stall on store forwarding).
    #[target_feature(enable = "avx512f")]
    #[inline]
    fn redo_lanes(st: &mut State, before: &[__m512i; 4], mut lanes: __mmask8, e: &Edges, row: &mut [f64; 8]) {
        while lanes != 0 {
            let l = lanes.trailing_zeros() as usize;
            lanes &= lanes - 1;
            let at = _mm512_set1_epi64(l as i64);
            let word = |v: __m512i| _mm_cvtsi128_si64(_mm512_castsi512_si128(_mm512_permutexvar_epi64(at, v))) as u64;
            let (v, after) = redo(word(before[0]), word(before[1]), word(before[2]), word(before[3]), e);
            row[l] = v;
            for (w, a) in st.0.iter_mut().zip(after) {
                *w = _mm512_mask_set1_epi64(*w, 1 << l, a as i64);
            }
        }
    }

    /// The relative error bound of [`exp_near`] on the wedges' exponents, with room for rounding: the
    /// band in which [`below_density`] leaves the decision to libm.
    pub(super) const EXP_NEAR_BOUND: f64 = 1.0 / (1u64 << 26) as f64;

    /// e^t for t ∈ [−8, 0], within [`EXP_NEAR_BOUND`] (a bound for the wedge test, not a result).
    ///
    /// # Formula
    /// t = k·ln 2 + r with k = round(t/ln 2), |r| ≤ ln 2 / 2 (k·ln 2 and the subtraction in one fused
    /// operation: an error of ~10⁻¹⁵ in r for |k| ≤ 12); e^r by its Taylor polynomial of degree 7, whose
    /// remainder is at most r⁸·e^|r|/8! ≤ 0.3466⁸·1.415/40320 < 7.5·10⁻⁹ relative (Horner's scheme in fused
    /// operations adds ~10⁻¹⁵); then 2^k exactly (`vscalefpd`). Total < 7.6·10⁻⁹ < 2⁻²⁶ = 1.49·10⁻⁸.
    #[target_feature(enable = "avx512f")]
    #[inline]
    pub(super) fn exp_near(t: __m512d) -> __m512d {
        let k = _mm512_roundscale_pd::<{ _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC }>(_mm512_mul_pd(
            t,
            _mm512_set1_pd(std::f64::consts::LOG2_E),
        ));
        let r = _mm512_fnmadd_pd(k, _mm512_set1_pd(std::f64::consts::LN_2), t);
        let mut p = _mm512_set1_pd(1.0 / 5040.0);
        for c in [1.0 / 720.0, 1.0 / 120.0, 1.0 / 24.0, 1.0 / 6.0, 0.5, 1.0, 1.0] {
            p = _mm512_fmadd_pd(p, r, _mm512_set1_pd(c));
        }
        _mm512_scalef_pd(p, k)
    }

    /// y < e^t in the lanes `lanes`, as libm's `exp` decides it: by [`exp_near`] where y lies outside
    /// e^t·(1 ± [`EXP_NEAR_BOUND`]), by libm's `exp` lane by lane inside that band (≈ 10⁻⁶ of the wedges).
    #[target_feature(enable = "avx512f")]
    pub(super) fn below_density(y: __m512d, t: __m512d, lanes: __mmask8) -> __mmask8 {
        let p = exp_near(t);
        let below = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(y, _mm512_mul_pd(p, _mm512_set1_pd(1.0 - EXP_NEAR_BOUND)));
        let above = _mm512_cmp_pd_mask::<_CMP_GT_OQ>(y, _mm512_mul_pd(p, _mm512_set1_pd(1.0 + EXP_NEAR_BOUND)));
        let mut band = lanes & !(below | above);
        let mut decided = lanes & below;
        if band != 0 {
            let (mut ya, mut ta) = ([0.0; 8], [0.0; 8]);
            // SAFETY: 8 writable f64 each.
            unsafe {
                _mm512_storeu_pd(ya.as_mut_ptr(), y);
                _mm512_storeu_pd(ta.as_mut_ptr(), t);
            }
            while band != 0 {
                let l = band.trailing_zeros() as usize;
                band &= band - 1;
                if ya[l] < ta[l].exp() {
                    decided |= 1 << l;
                }
            }
        }
        decided
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::{fill_standard_normal, standard_normal, stream};
    use rand::Rng;

    /// `rand_distr`'s own draws, one call at a time: the oracle of every fill here.
    fn crate_draws(rng: &mut rand::rngs::Xoshiro256PlusPlus, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = standard_normal(rng));
    }

    /// One stream filled in runs of uneven lengths (2·10⁶ draws: ≈ 24,000 off the common case, ≈ 190 from
    /// the tail box) has the bits of `rand_distr`'s draws one at a time and leaves the stream where they
    /// leave it, for streams of two seeds.
    #[test]
    fn one_stream_fill_gives_the_bits_of_rand_distr() {
        for (seed, i) in [(3, 0), (2024, 17)] {
            let (mut a, mut b) = (stream(seed, i), stream(seed, i));
            for m in [1, 2, 999, 1_000_000, 0, 999_998] {
                let (mut got, mut want) = (vec![0.0; m], vec![0.0; m]);
                fill_standard_normal(&mut a, &mut got);
                crate_draws(&mut b, &mut want);
                assert!(
                    got.iter().zip(&want).all(|(g, w)| g.to_bits() == w.to_bits()),
                    "seed {seed}, run of {m}"
                );
                assert_eq!(
                    a.clone().next_u64(),
                    b.clone().next_u64(),
                    "seed {seed}: the state after {m}"
                );
            }
        }
    }

    #[test]
    fn stream_rng_is_the_stream_of_rand() {
        for i in [0, 1, 77, u64::MAX] {
            let (mut a, mut b) = (StreamRng::new(5, i), stream(5, i));
            for _ in 0..1000 {
                assert_eq!(a.next_u64(), b.next_u64());
            }
        }
    }

    /// 8 lanes × 2·10⁵ draws (≈ 19,000 of them finished off the common case, ≈ 140 beyond X_0 = 3.91 from
    /// the tail box among them) have the bits of `rand_distr`'s draws on each lane's stream, and leave
    /// each stream where it leaves it.
    #[test]
    fn lanes_give_the_bits_of_rand_distr() {
        const L: usize = 8;
        let n = 200_000;
        let mut lanes = LaneNormals::<L>::new(std::array::from_fn(|l| StreamRng::new(3, l as u64)));
        let got: Vec<[f64; L]> = (0..n).map(|_| lanes.draw()).collect();
        for l in 0..L {
            let mut want = vec![0.0; n];
            let mut rng = stream(3, l as u64);
            crate_draws(&mut rng, &mut want);
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

    /// The wedge decisions of [`redraw`] are those of `rand_distr`, at the switch: for every box 1..=255 and
    /// three points x of its wedge (just beyond X_{i+1}, midway, and at X_i), the smallest word of the
    /// uniform v at which the crate accepts x is found by bisection over the 2⁵³ values of v (acceptance
    /// grows with v), and the redone draw must reject one word below it and accept at it. A rejected draw
    /// goes on to a third word, u = 0 in box 1, which returns 0 (never a wedge's x).
    #[test]
    fn wedges_decide_as_rand_distr_does() {
        let e = edges();
        let next = box_word(1, 1 << 51);
        let (mut switches, mut ends) = (0, 0);
        for i in 1..=255 {
            let ratio = e.x[i + 1] / e.x[i];
            let lo = ((1.0 + ratio) * 2f64.powi(51)).ceil() as u64 + 1;
            let hi = (1u64 << 52) - 1;
            for m in [lo, (lo + hi) / 2, hi] {
                let words = |k: u64| [box_word(i, m), k << 11, next];
                let theirs = |k: u64| {
                    let v: f64 = StandardNormal.sample(&mut Words(&words(k)));
                    v != 0.0
                };
                let ours = |k: u64| redraw(&mut Words(&words(k)), e) != 0.0;
                let top = (1u64 << 53) - 1;
                if theirs(0) == theirs(top) {
                    assert_eq!((ours(0), ours(top)), (theirs(0), theirs(top)), "box {i}, m = {m}");
                    ends += 1;
                    continue;
                }
                let (mut a, mut b) = (0, top);
                while b - a > 1 {
                    let c = a + (b - a) / 2;
                    if theirs(c) {
                        b = c
                    } else {
                        a = c
                    }
                }
                assert!(
                    !ours(a) && ours(b),
                    "box {i}, m = {m}: the crate switches at v word {b}"
                );
                switches += 1;
            }
        }
        assert!(switches > 700, "{switches} switches found, {ends} wedges without one");
    }

    /// `n` rows of 8 exponents t spread evenly over the wedges' range [−X_1²/2, 0] (the AVX-512 tests' grid),
    /// or none on a CPU without AVX-512 (those tests then pass without checking).
    #[cfg(target_arch = "x86_64")]
    fn wedge_exponents(n: usize) -> Vec<[f64; 8]> {
        if crate::linalg::vmath::Isa::detected() != crate::linalg::vmath::Isa::Avx512 {
            return Vec::new();
        }
        let lo = -edges().x[1].powi(2) / 2.0;
        (0..n)
            .map(|k| std::array::from_fn(|l| lo * ((8 * k + l) as f64 / (8 * n) as f64)))
            .collect()
    }

    /// The short exponential of the vector wedge test is within its bound: over 10⁶ exponents t on the
    /// wedges' range [−X_1²/2, 0], |e_near(t)/exp(t) − 1| ≤ half of `EXP_NEAR_BOUND` (the formula gives
    /// 7.6·10⁻⁹ = 0.51 of it). Skipped (passes) on a CPU without AVX-512.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_short_exponential_is_within_its_bound() {
        use std::arch::x86_64::*;
        let rows = wedge_exponents(125_000);
        if rows.is_empty() {
            return;
        }
        let mut worst: f64 = 0.0;
        for t in rows {
            let mut p = [0.0; 8];
            // SAFETY: the CPU has AVX-512 F (checked above); 8 readable and writable f64.
            unsafe { _mm512_storeu_pd(p.as_mut_ptr(), x86::exp_near(_mm512_loadu_pd(t.as_ptr()))) };
            for l in 0..8 {
                worst = worst.max((p[l] / t[l].exp() - 1.0).abs());
            }
        }
        assert!(worst <= x86::EXP_NEAR_BOUND / 2.0, "worst relative error {worst:e}");
        assert!(worst > 1e-10, "the polynomial's remainder shows: {worst:e}");
    }

    /// The wedge test of the vector path decides as libm's `exp` does: for 2·10⁵ exponents t over the
    /// wedges' range [−X_1²/2, 0] and heights y at 0, ±1, ±2, ±10³ and ±10⁶ ulp of libm's e^t (inside the
    /// band where libm decides) and at ±1.1, ±1.5 and ±4 bounds from it (outside the band, where the
    /// short exponential does), every lane's answer is `y < t.exp()`. Skipped (passes) on a CPU without
    /// AVX-512.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_vector_wedge_test_decides_as_libm() {
        use std::arch::x86_64::*;
        let rows = wedge_exponents(200_000);
        if rows.is_empty() {
            return;
        }
        let ulps = [0i64, 1, -1, 2, -2, 1000, -1000, 1_000_000, -1_000_000];
        let bounds = [1.1, -1.1, 1.5, -1.5, 4.0, -4.0];
        let mut checked = 0;
        for t in rows {
            let e: [f64; 8] = std::array::from_fn(|l| t[l].exp());
            let heights = ulps
                .iter()
                .map(|&d| std::array::from_fn(|l| f64::from_bits((e[l].to_bits() as i64 + d) as u64)))
                .chain(
                    bounds
                        .iter()
                        .map(|&b| std::array::from_fn(|l| e[l] * (1.0 + b * x86::EXP_NEAR_BOUND))),
                );
            for y in heights {
                let y: [f64; 8] = y;
                // SAFETY: the CPU has AVX-512 F (checked above); 8 readable f64 each.
                let got = unsafe { x86::below_density(_mm512_loadu_pd(y.as_ptr()), _mm512_loadu_pd(t.as_ptr()), 0xff) };
                for l in 0..8 {
                    assert_eq!(got >> l & 1 == 1, y[l] < e[l], "y = {:e}, t = {:e}", y[l], t[l]);
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 200_000 * 8 * 15);
    }

    /// The dispatched fill of 8 lanes (the AVX-512 path where the CPU has it) against the scalar oracle,
    /// bit for bit: 1.1·10⁶ draws per lane in fills of uneven lengths (1, 37, 64, 5000, ...; about 1.2 % of
    /// the draws, ≈ 10⁵ over the lanes, are finished off the common case, the tail and the wedges among them), and
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
    /// 64, a long one), have the bits of `rand_distr`'s draws on each lane's stream and leave each stream
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
            crate_draws(&mut rng, &mut want);
            assert_eq!(
                bits(&mut got.iter().map(|g| g[l])),
                bits(&mut want.into_iter()),
                "lane {l}"
            );
            assert_eq!(lanes.stream(l).next_u64(), rng.next_u64(), "lane {l}: its state");
        }
    }
}
