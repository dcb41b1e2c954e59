//! Lockstep arithmetic on `[f64; L]` lane arrays (one lane per realization) as explicit SIMD vectors, chosen
//! per instruction set by a marker type, so that it is vectorised at any optimisation level (the compiler's
//! own packing of eight scalar lanes, its SLP vectoriser, runs at opt-level 3 only).
//!
//! # Formula
//! `madd`: acc_l ← acc_l + a·x_l for every lane l: a multiply and an add, each rounded (never a fused
//! multiply-add), the operations of the scalar expression `acc + a * x`, so every lane has its bits on
//! every instruction set. [`run_lanes`] runs a [`LaneTask`] with the widest marker this CPU has
//! ([`Isa::detected`]), compiled for that instruction set by [`vmath::run`].

use super::vmath::{self, Isa, Task};
use std::marker::PhantomData;

/// The lane arithmetic of one instruction set on L lanes, in registers of type `V` (passed by value, so
/// that an accumulator stays in a register at any optimisation level).
pub trait LaneMath<const L: usize> {
    /// The register (or registers) of L lanes.
    type V: Copy;
    /// Every lane a.
    fn splat(a: f64) -> Self::V;
    /// acc_l + a·x_l for every lane (two roundings, as the scalar expression).
    fn madd(acc: Self::V, a: f64, x: &[f64; L]) -> Self::V;
    /// The lanes as an array.
    fn store(v: Self::V) -> [f64; L];
}

/// Plain loops: any CPU, and the oracle of the others.
pub struct Scalar;

/// AVX-512F: eight lanes in one vector (one lane: [`Scalar`]'s). Reached only through [`run_lanes`] on a
/// CPU that has AVX-512F.
pub struct Avx512;

/// AVX: eight lanes in two 4-wide vectors (one lane: [`Scalar`]'s). Reached only through [`run_lanes`] on
/// a CPU that has AVX2.
pub struct Avx2;

impl<const L: usize> LaneMath<L> for Scalar {
    type V = [f64; L];
    #[inline(always)]
    fn splat(a: f64) -> [f64; L] {
        [a; L]
    }
    #[inline(always)]
    fn madd(mut acc: [f64; L], a: f64, x: &[f64; L]) -> [f64; L] {
        for (s, v) in acc.iter_mut().zip(x) {
            *s += a * v;
        }
        acc
    }
    #[inline(always)]
    fn store(v: [f64; L]) -> [f64; L] {
        v
    }
}

/// One lane on any instruction set: [`Scalar`]'s arithmetic.
macro_rules! one_lane {
    ($isa:ty) => {
        impl LaneMath<1> for $isa {
            type V = [f64; 1];
            #[inline(always)]
            fn splat(a: f64) -> [f64; 1] {
                [a]
            }
            #[inline(always)]
            fn madd(acc: [f64; 1], a: f64, x: &[f64; 1]) -> [f64; 1] {
                <Scalar as LaneMath<1>>::madd(acc, a, x)
            }
            #[inline(always)]
            fn store(v: [f64; 1]) -> [f64; 1] {
                v
            }
        }
    };
}
one_lane!(Avx512);
one_lane!(Avx2);

#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::{Avx2, Avx512, LaneMath};
    use std::arch::x86_64::*;

    // SAFETY (every block below): these markers are used only by `run_lanes` when the CPU has the
    // instruction set (AVX-512F; AVX2, which implies AVX); the loads and stores are unaligned, of 8 f64.
    impl LaneMath<8> for Avx512 {
        type V = __m512d;
        #[inline(always)]
        fn splat(a: f64) -> __m512d {
            unsafe { _mm512_set1_pd(a) }
        }
        #[inline(always)]
        fn madd(acc: __m512d, a: f64, x: &[f64; 8]) -> __m512d {
            unsafe { _mm512_add_pd(acc, _mm512_mul_pd(_mm512_set1_pd(a), _mm512_loadu_pd(x.as_ptr()))) }
        }
        #[inline(always)]
        fn store(v: __m512d) -> [f64; 8] {
            let mut out = [0.0; 8];
            unsafe { _mm512_storeu_pd(out.as_mut_ptr(), v) };
            out
        }
    }

    impl LaneMath<8> for Avx2 {
        type V = [__m256d; 2];
        #[inline(always)]
        fn splat(a: f64) -> [__m256d; 2] {
            unsafe { [_mm256_set1_pd(a); 2] }
        }
        #[inline(always)]
        fn madd(acc: [__m256d; 2], a: f64, x: &[f64; 8]) -> [__m256d; 2] {
            unsafe {
                let s = _mm256_set1_pd(a);
                let (lo, hi) = (_mm256_loadu_pd(x.as_ptr()), _mm256_loadu_pd(x.as_ptr().add(4)));
                [
                    _mm256_add_pd(acc[0], _mm256_mul_pd(s, lo)),
                    _mm256_add_pd(acc[1], _mm256_mul_pd(s, hi)),
                ]
            }
        }
        #[inline(always)]
        fn store(v: [__m256d; 2]) -> [f64; 8] {
            let mut out = [0.0; 8];
            unsafe {
                _mm256_storeu_pd(out.as_mut_ptr(), v[0]);
                _mm256_storeu_pd(out.as_mut_ptr().add(4), v[1]);
            }
            out
        }
    }
}

/// A loop over lane arrays of L lanes, written once for any [`LaneMath`]: implement `run` with
/// `#[inline(always)]`.
pub trait LaneTask<const L: usize> {
    /// The work, with the lane arithmetic `M`.
    fn run<M: LaneMath<L>>(&mut self);
}

/// A [`LaneTask`] with its marker, as a [`vmath::Task`].
struct With<'a, T, M, const L: usize>(&'a mut T, PhantomData<M>);

impl<const L: usize, T: LaneTask<L>, M: LaneMath<L>> Task for With<'_, T, M, L> {
    #[inline(always)]
    fn run(&mut self) {
        self.0.run::<M>();
    }
}

/// Runs `task` with the lane arithmetic of the widest instruction set of this CPU, compiled for it
/// ([`vmath::run`] selects the same [`Isa::detected`]).
pub fn run_lanes<const L: usize, T: LaneTask<L>>(task: &mut T)
where
    Avx512: LaneMath<L>,
    Avx2: LaneMath<L>,
{
    match Isa::detected() {
        #[cfg(target_arch = "x86_64")]
        Isa::Avx512 => vmath::run(&mut With::<T, Avx512, L>(task, PhantomData)),
        #[cfg(target_arch = "x86_64")]
        Isa::Avx2 => vmath::run(&mut With::<T, Avx2, L>(task, PhantomData)),
        _ => vmath::run(&mut With::<T, Scalar, L>(task, PhantomData)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sums of products over awkward values (signed zeros, subnormals, huge and tiny magnitudes, an overflow to ∞)
    /// on every marker this CPU runs: the bits of the scalar loop.
    #[test]
    fn every_instruction_set_gives_the_scalar_bits() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -1.5,
            f64::MIN_POSITIVE / 3.0,
            1e300,
            -1e-300,
            0.1,
            std::f64::consts::PI,
            -7.25e-3,
            2.0f64.powi(-1074),
        ];
        let lanes = |k: usize| -> [f64; 8] { std::array::from_fn(|l| values[(k * 5 + l * 7) % values.len()]) };
        struct Sum<'a>(&'a mut [f64; 8], [[f64; 8]; 11], [f64; 11]);
        impl LaneTask<8> for Sum<'_> {
            #[inline(always)]
            fn run<M: LaneMath<8>>(&mut self) {
                let mut acc = M::splat(self.0[0]);
                for (a, x) in self.2.iter().zip(&self.1) {
                    acc = M::madd(acc, *a, x);
                }
                *self.0 = M::store(acc);
            }
        }
        let xs: [[f64; 8]; 11] = std::array::from_fn(lanes);
        let bits = |v: &[f64; 8]| v.map(f64::to_bits);
        for start in [0.0, -0.0, 1e-310] {
            let mut want = [start; 8];
            let mut got = [start; 8];
            Sum(&mut want, xs, values).run::<Scalar>();
            run_lanes(&mut Sum(&mut got, xs, values));
            assert_eq!(bits(&got), bits(&want), "detected {:?}", Isa::detected());
            for isa in [Isa::Avx512, Isa::Avx2].into_iter().filter(|i| i.available()) {
                let mut one = [start; 8];
                match isa {
                    Isa::Avx512 => Sum(&mut one, xs, values).run::<Avx512>(),
                    _ => Sum(&mut one, xs, values).run::<Avx2>(),
                }
                assert_eq!(bits(&one), bits(&want), "{isa:?}");
            }
        }
    }
}
