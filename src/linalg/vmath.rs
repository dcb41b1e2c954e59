//! Vectorised `exp` and `ln` for grids of points, with run-time CPU dispatch.
//!
//! [`exp`] and [`ln`] are branch-free scalar formulas (only `+ − × ÷`, comparisons and bit operations, no
//! call): inside a loop the compiler turns them into SIMD code. [`map`] and [`run`] compile such a loop
//! three times — for AVX-512 (8 lanes), AVX2 (4 lanes) and the x86-64 baseline SSE2 (2 lanes; on other
//! architectures the plain build) — and run the widest one the CPU has ([`Isa::detected`]). No fused
//! multiply-add is used (Rust never contracts `a * b + c`), so every [`Isa`] gives **the same bits** as
//! the scalar formula: the dispatch cannot change a number, only the speed.
//!
//! The oracle is the platform's `f64::exp` / `f64::ln` (libm): the densities' scalar `density` keeps using
//! it, and `density_into` on a grid uses these formulas, within the bounds below.
//!
//! # Formula
//! `exp`: Cody & Waite reduction x = k ln 2 + r, k = round(x/ln 2), |r| ≤ ln 2 / 2, with ln 2 split into
//! a 32-bit head (k·ln2_hi exact for |k| < 2²¹) and a tail; e^r by its Taylor polynomial of degree 13
//! (truncation < 4·10⁻¹⁸ relative), evaluated as 1 + (r + r²·p(r)); then 2^k as two exact power-of-two
//! factors 2^⌊k/2⌋·2^(k−⌊k/2⌋), so that results in the subnormal range are rounded once. e^x = +∞ above
//! 709.78…, 0 below −745.13…, NaN for NaN.
//!
//! `ln`: the reduction and rational approximation of fdlibm's `__ieee754_log` (Sun Microsystems, 1993):
//! x = 2^k·m, m ∈ [√½, √2), f = m − 1, s = f/(2 + f), ln m = f − (f²/2 − s(f²/2 + R(s²))) with R of
//! degree 14 in s (error < 2⁻⁵⁸·⁴⁵); subnormal x scaled by 2⁵⁴ first; ln 0 = −∞, ln x = NaN for x < 0,
//! ln ∞ = ∞.
//!
//! # Accuracy
//! Against the correctly rounded value the formulas are within 1 ulp (exp) and 1 ulp (ln); against glibc's
//! `exp`/`ln` (itself < 1 ulp) at most [`EXP_ULP_BOUND`] and [`LN_ULP_BOUND`] ulp, measured by the tests
//! over 10⁶ arguments each, including the tails, the overflow and underflow thresholds and the subnormal
//! range of the result (exp) and of the argument (ln).
//!
//! # Examples
//! ```
//! use stochvib::linalg::vmath::{exp, ln, map};
//! let x = [0.0, 1.0, -745.0, 700.0];
//! let mut e = [0.0; 4];
//! map(&x, &mut e, exp);
//! assert_eq!(e[0], 1.0);
//! assert!((e[1] - std::f64::consts::E).abs() <= 2.0 * f64::EPSILON);
//! assert!(e[2] > 0.0 && e[2] < f64::MIN_POSITIVE); // subnormal
//! assert!((ln(e[3]) - 700.0).abs() < 1e-12);
//! ```
//!
//! # Instruction-set cap
//! The environment variable `STOCHVIB_ISA` ([`ISA_ENV`]) = `avx2` or `baseline` makes [`Isa::detected`]
//! stop at that width, so that one AVX-512 machine measures what AVX2-only and SSE2-only machines run
//! (`benches/compare/run.sh` does, with numpy capped the same way by `NPY_DISABLE_CPU_FEATURES`).

use crate::error::{Error, Result};
use realfft::num_complex::Complex;

/// Largest difference, in units in the last place of the result, between [`exp`] and the platform's
/// `f64::exp` on normal results (the tests measure it over 10⁶ arguments; subnormal results differ by at most
/// one unit of the subnormal spacing).
pub const EXP_ULP_BOUND: u64 = 2;

/// Largest difference, in units in the last place, between [`ln`] and the platform's `f64::ln`.
pub const LN_ULP_BOUND: u64 = 2;

/// An instruction set a kernel is compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    /// AVX-512 F and DQ: 8 lanes of f64.
    Avx512,
    /// AVX2: 4 lanes of f64.
    Avx2,
    /// What the build targets without extra features (SSE2 on x86-64: 2 lanes).
    Baseline,
}

impl Isa {
    /// Every variant, widest first.
    pub const ALL: [Isa; 3] = [Isa::Avx512, Isa::Avx2, Isa::Baseline];

    /// Whether this CPU runs code compiled for `self`.
    pub fn available(self) -> bool {
        match self {
            Isa::Baseline => true,
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => {
                std::arch::is_x86_feature_detected!("avx512f") && std::arch::is_x86_feature_detected!("avx512dq")
            }
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// The widest variant this CPU runs, no wider than the cap of [`ISA_ENV`] if that names one (detected
    /// once). An unreadable value of [`ISA_ENV`] is ignored here (the widest variant is used); the command
    /// line refuses it first through [`Isa::cap_from_env`].
    pub fn detected() -> Isa {
        static BEST: std::sync::OnceLock<Isa> = std::sync::OnceLock::new();
        *BEST.get_or_init(|| Isa::widest_up_to(Isa::cap_from_env().ok().flatten().unwrap_or(Isa::Avx512)))
    }

    /// The widest variant this CPU runs that is no wider than `cap`.
    pub fn widest_up_to(cap: Isa) -> Isa {
        Isa::ALL
            .into_iter()
            .skip_while(|&i| i != cap)
            .find(|i| i.available())
            .unwrap_or(Isa::Baseline)
    }

    /// The variant named `name`: `avx512`, `avx2` or `baseline`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for any other name.
    pub fn parse(name: &str) -> Result<Isa> {
        match name {
            "avx512" => Ok(Isa::Avx512),
            "avx2" => Ok(Isa::Avx2),
            "baseline" => Ok(Isa::Baseline),
            _ => Err(Error::InvalidParameter {
                name: format!("environment variable {ISA_ENV}"),
                value: name.to_string(),
                reason: "not an instruction set: use avx512, avx2 or baseline (the widest the kernels may use)".into(),
            }),
        }
    }

    /// The cap set by the environment variable [`ISA_ENV`], if it is set.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when it is set to anything but `avx512`, `avx2` or `baseline` (or is not
    /// Unicode).
    pub fn cap_from_env() -> Result<Option<Isa>> {
        match std::env::var_os(ISA_ENV) {
            None => Ok(None),
            Some(v) => Isa::parse(&v.to_string_lossy()).map(Some),
        }
    }
}

/// The environment variable that caps the instruction set of every dispatched kernel: `avx512`, `avx2` or
/// `baseline` (SSE2 on x86-64). A cap never changes a number (every variant gives the same bits); it makes
/// an AVX-512 machine run the code an AVX2-only or SSE2-only machine runs, for measurements.
pub const ISA_ENV: &str = "STOCHVIB_ISA";

/// A function of one f64 evaluated by [`map`]: implement it with `#[inline(always)]` on `at` for a body of
/// any size (a closure is inlined into the SIMD loop only while it is small; `at` always is).
pub trait Kernel {
    /// The value at `x`.
    fn at(&self, x: f64) -> f64;
}

impl<F: Fn(f64) -> f64> Kernel for F {
    #[inline(always)]
    fn at(&self, x: f64) -> f64 {
        self(x)
    }
}

/// A loop run by [`run`]: implement `run` with `#[inline(always)]` so that it is compiled for the
/// instruction set `run` selects.
pub trait Task {
    /// The work.
    fn run(&mut self);
}

/// `out[i] = k.at(x[i])` for i < min(x.len(), out.len()), compiled for the widest instruction set of this
/// CPU ([`Isa::detected`]).
#[inline]
pub fn map<K: Kernel>(x: &[f64], out: &mut [f64], k: K) {
    map_on(Isa::detected(), x, out, k);
}

/// `out[i] = k.at(x[i])` compiled for `isa`, or for [`Isa::Baseline`] when the CPU lacks `isa` (the tests
/// force every variant the CPU has through this).
#[inline]
pub fn map_on<K: Kernel>(isa: Isa, x: &[f64], out: &mut [f64], k: K) {
    #[cfg(target_arch = "x86_64")]
    {
        if isa == Isa::Avx512 && isa.available() {
            // SAFETY: the CPU has AVX-512 F and DQ (checked just above).
            return unsafe { x86::map_avx512(x, out, &k) };
        }
        if isa == Isa::Avx2 && isa.available() {
            // SAFETY: the CPU has AVX2 (checked just above).
            return unsafe { x86::map_avx2(x, out, &k) };
        }
    }
    map_loop(x, out, &k);
}

/// Runs `task` compiled for the widest instruction set of this CPU.
#[inline]
pub fn run<T: Task>(task: &mut T) {
    #[cfg(target_arch = "x86_64")]
    {
        let isa = Isa::detected();
        if isa == Isa::Avx512 {
            // SAFETY: `detected` returns only a variant the CPU has.
            return unsafe { x86::run_avx512(task) };
        }
        if isa == Isa::Avx2 {
            // SAFETY: as above.
            return unsafe { x86::run_avx2(task) };
        }
    }
    task.run();
}

/// `y[i] += a[i]·b[i]` (complex) for i < the shortest length, compiled for the widest instruction set of
/// this CPU: each element the operations of `Complex`'s `*` and `+=` in their order (re = a.re·b.re −
/// a.im·b.im, im = a.re·b.im + a.im·b.re, then the two additions; no fused multiply-add), so the same bits
/// on each instruction set and as the loop written with `Complex` arithmetic.
pub fn complex_mul_add(y: &mut [Complex<f64>], a: &[Complex<f64>], b: &[Complex<f64>]) {
    struct MulAdd<'a>(&'a mut [Complex<f64>], &'a [Complex<f64>], &'a [Complex<f64>]);
    impl Task for MulAdd<'_> {
        #[inline(always)]
        fn run(&mut self) {
            for ((y, a), b) in self.0.iter_mut().zip(self.1).zip(self.2) {
                *y += a * b;
            }
        }
    }
    run(&mut MulAdd(y, a, b));
}

/// `y[i] = 0 + a[i]·b[i]` (complex) for i < the shortest length: the first term of a sum begun at zero,
/// with the bits [`complex_mul_add`] gives on a zeroed `y` (each part of the product added to +0.0, which
/// turns a −0.0 into +0.0), in one pass instead of two; compiled for the widest instruction set of this
/// CPU. Where `a` or `b` is shorter than `y`, the rest of `y` is left as it was (not zeroed): callers pass
/// operands as long as `y`.
pub fn complex_mul_from_zero(y: &mut [Complex<f64>], a: &[Complex<f64>], b: &[Complex<f64>]) {
    struct MulFromZero<'a>(&'a mut [Complex<f64>], &'a [Complex<f64>], &'a [Complex<f64>]);
    impl Task for MulFromZero<'_> {
        #[inline(always)]
        fn run(&mut self) {
            for ((y, a), b) in self.0.iter_mut().zip(self.1).zip(self.2) {
                *y = Complex::new(0.0, 0.0) + a * b;
            }
        }
    }
    run(&mut MulFromZero(y, a, b));
}

/// `x[i] /= d` for every i, compiled for the widest instruction set of this CPU (the same bits on each).
pub fn div_in_place(x: &mut [f64], d: f64) {
    struct Div<'a>(&'a mut [f64], f64);
    impl Task for Div<'_> {
        #[inline(always)]
        fn run(&mut self) {
            let d = self.1;
            self.0.iter_mut().for_each(|v| *v /= d);
        }
    }
    run(&mut Div(x, d));
}

#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::{map_loop, Kernel, Task};

    #[target_feature(enable = "avx512f,avx512dq")]
    pub(super) fn map_avx512<K: Kernel>(x: &[f64], out: &mut [f64], k: &K) {
        map_loop(x, out, k);
    }

    #[target_feature(enable = "avx2")]
    pub(super) fn map_avx2<K: Kernel>(x: &[f64], out: &mut [f64], k: &K) {
        map_loop(x, out, k);
    }

    #[target_feature(enable = "avx512f,avx512dq")]
    pub(super) fn run_avx512<T: Task>(task: &mut T) {
        task.run();
    }

    #[target_feature(enable = "avx2")]
    pub(super) fn run_avx2<T: Task>(task: &mut T) {
        task.run();
    }
}

#[inline(always)]
fn map_loop<K: Kernel>(x: &[f64], out: &mut [f64], k: &K) {
    for (o, &v) in out.iter_mut().zip(x) {
        *o = k.at(v);
    }
}

/// 1.5·2⁵²: adding it rounds a number of magnitude < 2⁵¹ to an integer held in the low mantissa bits.
pub(crate) const SHIFT: f64 = 6_755_399_441_055_744.0;
/// ln 2 with its last 21 bits zero (fdlibm's `ln2_hi`, 0x3fe62e42fee00000): k·LN2_HI is exact for |k| < 2²¹.
#[allow(clippy::excessive_precision)] // fdlibm's digits, verbatim
const LN2_HI: f64 = 6.931_471_803_691_238_164_90e-1;
/// ln 2 − LN2_HI (fdlibm's `ln2_lo`, 0x3dea39ef35793c76).
#[allow(clippy::excessive_precision)] // fdlibm's digits, verbatim
const LN2_LO: f64 = 1.908_214_929_270_587_700_02e-10;

/// 2^k for −1022 ≤ k ≤ 1023, exactly, from the exponent bits.
#[inline(always)]
fn pow2i(k: i64) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// e^x (see the module docs for the formula and the accuracy).
#[inline(always)]
pub fn exp(x: f64) -> f64 {
    const INV_LN2: f64 = std::f64::consts::LOG2_E;
    // round(x / ln 2) by the shift; clamp first so that the shift stays exact far outside the range. Where
    // the result is 0 (x below the underflow threshold) the formula runs on x = 0 instead: on x ≈ −746 its
    // last product would underflow into a subnormal, which costs a microcode assist of ~100 cycles per
    // lane on x86 (the result is replaced by 0 below either way)
    let xc = if x < -745.133_219_101_941_2 {
        0.0
    } else {
        x.clamp(-746.0, 710.0)
    };
    let kd = xc * INV_LN2 + SHIFT;
    let k = kd.to_bits() as i64 - SHIFT.to_bits() as i64;
    let kd = kd - SHIFT;
    let r = (xc - kd * LN2_HI) - kd * LN2_LO;
    // e^r − 1 − r = r²(1/2! + r/3! + … + r¹¹/13!)
    const C: [f64; 12] = [
        1.0 / 2.0,
        1.0 / 6.0,
        1.0 / 24.0,
        1.0 / 120.0,
        1.0 / 720.0,
        1.0 / 5040.0,
        1.0 / 40320.0,
        1.0 / 362_880.0,
        1.0 / 3_628_800.0,
        1.0 / 39_916_800.0,
        1.0 / 479_001_600.0,
        1.0 / 6_227_020_800.0,
    ];
    // Estrin's scheme on r² (shorter dependency chains than Horner, the same operations on every path)
    let r2 = r * r;
    let r4 = r2 * r2;
    let r8 = r4 * r4;
    let p01 = C[0] + r * C[1];
    let p23 = C[2] + r * C[3];
    let p45 = C[4] + r * C[5];
    let p67 = C[6] + r * C[7];
    let p89 = C[8] + r * C[9];
    let p1011 = C[10] + r * C[11];
    let p03 = p01 + r2 * p23;
    let p47 = p45 + r2 * p67;
    let p811 = p89 + r2 * p1011;
    let p = p03 + r4 * p47 + r8 * p811;
    let er = 1.0 + (r + r2 * p);
    // ⌊k/2⌋ by a logical shift of k + 2048 > 0 (k ≥ −1077 after the clamp): SSE2 and AVX2 have no 64-bit
    // arithmetic shift, and `k >> 1` on i64 made the compiler leave the vector loop for scalar code there
    let k1 = ((k + 2048) as u64 >> 1) as i64 - 1024;
    let y = er * pow2i(k1) * pow2i(k - k1);
    if x > 709.782_712_893_384 {
        f64::INFINITY
    } else if x < -745.133_219_101_941_2 {
        0.0
    } else {
        y
    }
}

/// ln x (see the module docs for the formula and the accuracy).
#[inline(always)]
pub fn ln(x: f64) -> f64 {
    // fdlibm's Lg1..Lg7, verbatim
    #[allow(clippy::excessive_precision)]
    const LG: [f64; 7] = [
        6.666_666_666_666_735_13e-1,
        3.999_999_999_940_941_91e-1,
        2.857_142_874_366_239_15e-1,
        2.222_219_843_214_978_40e-1,
        1.818_357_216_161_805_01e-1,
        1.531_383_769_920_937_33e-1,
        1.479_819_860_511_658_59e-1,
    ];
    const TWO54: f64 = 18_014_398_509_481_984.0;
    let sub = x < f64::MIN_POSITIVE;
    let xs = if sub { x * TWO54 } else { x };
    let bits = xs.to_bits() as i64;
    // the exponent field by a logical shift (no 64-bit arithmetic shift on SSE2 and AVX2; the mask makes the
    // two shifts equal)
    let mut k = ((xs.to_bits() >> 52) & 0x7ff) as i64 - 1023 - if sub { 54 } else { 0 };
    let mant = bits & 0x000f_ffff_ffff_ffff;
    // m ∈ [√½, √2): the mantissa with exponent 0, or −1 above √2 (0x6a09e: the top bits of √2)
    // compared as the doubles 1.mant (monotonic in mant): SSE2 has no 64-bit integer comparison, and an
    // integer one made the compiler leave the vector loop there
    let big = f64::from_bits(mant as u64 | 0x3ff0_0000_0000_0000) >= f64::from_bits(0x3ff6_a09e_667f_3bcd);
    let m = f64::from_bits(
        (mant
            | if big {
                0x3fe0_0000_0000_0000
            } else {
                0x3ff0_0000_0000_0000
            }) as u64,
    );
    k += big as i64;
    let f = m - 1.0;
    let s = f / (2.0 + f);
    let z = s * s;
    let w = z * z;
    let t1 = w * (LG[1] + w * (LG[3] + w * LG[5]));
    let t2 = z * (LG[0] + w * (LG[2] + w * (LG[4] + w * LG[6])));
    let r = t2 + t1;
    let hfsq = 0.5 * f * f;
    // k as f64 exactly, without a (non-vectorisable on AVX2) integer conversion
    let dk = f64::from_bits((SHIFT.to_bits() as i64 + k) as u64) - SHIFT;
    let y = dk * LN2_HI - ((hfsq - (s * (hfsq + r) + dk * LN2_LO)) - f);
    if x.is_nan() || x == f64::INFINITY {
        x + x
    } else if x == 0.0 {
        f64::NEG_INFINITY
    } else if x < 0.0 {
        f64::NAN
    } else {
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The complex multiply-add compiled for this CPU's widest instruction set gives the bits of the loop
    /// written with `Complex` arithmetic (compiled for the baseline here), over 4099 elements of magnitudes
    /// 10⁻³⁰⁸…10³⁰⁰ and signs mixed, with zeros of both signs, subnormals, infinities and NaN among them, in
    /// three rounds (the accumulator reused); a shorter operand bounds the elements touched. NaN results
    /// count as equal whatever their payloads. `complex_mul_from_zero` over the same operands (one product
    /// of −0.0 among them) gives the bits of `complex_mul_add` on a zeroed accumulator.
    #[test]
    fn complex_mul_add_gives_the_bits_of_the_complex_loop() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(11);
        let z: Vec<f64> = (0..6 * 4099).map(|_| rng.random::<f64>() - 0.5).collect();
        let special = [
            0.0,
            -0.0,
            5e-324,
            -2.2e-308,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e300,
        ];
        let v: Vec<f64> = z
            .iter()
            .enumerate()
            .map(|(i, x)| {
                if i % 97 < 8 {
                    special[i % 97]
                } else {
                    x * 10f64.powi((i % 601) as i32 - 300)
                }
            })
            .collect();
        let c = |k: usize| Complex::new(v[2 * k], v[2 * k + 1]);
        let (a, b): (Vec<_>, Vec<_>) = (0..4099).map(|k| (c(k), c(4099 + k))).unzip();
        let mut want: Vec<Complex<f64>> = (0..4099).map(|k| c(2 * 4099 + k)).collect();
        let mut got = want.clone();
        for _ in 0..3 {
            for ((y, a), b) in want.iter_mut().zip(&a).zip(&b) {
                *y += a * b;
            }
            complex_mul_add(&mut got, &a, &b);
        }

        // the bits, every NaN as one value (x86 may carry either operand's NaN payload, an order the
        // compiler may commute)
        let key = |x: f64| if x.is_nan() { u64::MAX } else { x.to_bits() };
        let bits = |y: &[Complex<f64>]| y.iter().map(|c| (key(c.re), key(c.im))).collect::<Vec<_>>();
        assert_eq!(bits(&got), bits(&want));
        // a sum begun at zero in one pass: the bits of the product added to a zeroed y; a product of
        // −0.0 (−0·1 − 0·0) becomes +0.0 there as it does here
        let (mut a0, mut b0) = (a.clone(), b.clone());
        (a0[5], b0[5]) = (Complex::new(-0.0, 0.0), Complex::new(1.0, 0.0));
        let mut zeroed = vec![Complex::new(0.0, 0.0); 4099];
        complex_mul_add(&mut zeroed, &a0, &b0);
        let mut first = vec![Complex::new(f64::NAN, 1.0); 4099];
        complex_mul_from_zero(&mut first, &a0, &b0);
        assert_eq!(bits(&first), bits(&zeroed));
        assert_eq!((a0[5] * b0[5]).re.to_bits(), (-0.0f64).to_bits());
        assert_eq!(first[5].re.to_bits(), 0);
        let before = got.clone();
        complex_mul_add(&mut got, &a[..10], &b);
        assert_eq!(bits(&got[10..]), bits(&before[10..]));
    }

    /// Distance in units in the last place between two finite f64 of the same sign (or zeros).
    pub(crate) fn ulps(a: f64, b: f64) -> u64 {
        let key = |x: f64| {
            let b = x.to_bits() as i64;
            if b < 0 {
                i64::MIN - b
            } else {
                b
            }
        };
        key(a).abs_diff(key(b))
    }

    #[test]
    fn special_values() {
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-0.0), 1.0);
        assert_eq!(exp(f64::INFINITY), f64::INFINITY);
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert!(exp(f64::NAN).is_nan());
        assert_eq!(exp(710.0), f64::INFINITY);
        assert_eq!(exp(-746.0), 0.0);
        assert_eq!(exp(-745.13), 5e-324); // the smallest subnormal, as libm gives
        assert_eq!(ln(1.0), 0.0);
        assert_eq!(ln(0.0), f64::NEG_INFINITY);
        assert_eq!(ln(-0.0), f64::NEG_INFINITY);
        assert!(ln(-1.0).is_nan() && ln(f64::NAN).is_nan() && ln(f64::NEG_INFINITY).is_nan());
        assert_eq!(ln(f64::INFINITY), f64::INFINITY);
        // ln 2⁻¹⁰⁷⁴ = −1074 ln 2 (the smallest subnormal)
        assert!((ln(5e-324) + 1074.0 * std::f64::consts::LN_2).abs() <= 2.0 * 744.5 * f64::EPSILON);
    }

    /// A xorshift stream of u64 (the tests' arguments; any fixed sequence will do).
    fn stream(mut x: u64) -> impl FnMut() -> u64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    }

    /// Arguments of `exp`: uniform over the whole finite-result range, the neighbourhoods of the overflow
    /// threshold, of the first subnormal result, of the underflow threshold and of 0 (|x| down to 1e-300).
    fn exp_arguments() -> Vec<f64> {
        let mut next = stream(0x2545_F491_4F6C_DD1D);
        let mut u = move || (next() >> 11) as f64 / (1u64 << 53) as f64;
        let mut v: Vec<f64> = (0..600_000).map(|_| -745.2 + 1455.0 * u()).collect();
        for c in [709.782_712_893_384, -708.396_418_532_264_1, -745.133_219_101_941_2, 0.0] {
            v.extend((0..50_000).map(|_| c + 1e-6 * (u() - 0.5)));
        }
        v.extend((0..200_000).map(|_| (if u() < 0.5 { -1.0 } else { 1.0 }) * 10f64.powf(-300.0 + 295.0 * u())));
        v
    }

    /// Arguments of `ln`: random bit patterns over every positive finite double (log-uniform), every
    /// subnormal binade, and the neighbourhood of 1 (where ln x → 0 and cancellation is the risk).
    fn ln_arguments() -> Vec<f64> {
        let mut next = stream(0x9E37_79B9_7F4A_7C15);
        let mut v: Vec<f64> = (0..600_000)
            .map(|_| f64::from_bits(next() % 0x7FF0_0000_0000_0000))
            .filter(|x| *x > 0.0)
            .collect();
        v.extend((0..200_000).map(|_| f64::from_bits(1 + next() % ((1u64 << 52) - 1))));
        v.extend((0..200_000).map(|_| 1.0 + ((next() >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 1e-3));
        v
    }

    /// [`exp`] is within [`EXP_ULP_BOUND`] ulp of libm's `exp` over 10⁶ arguments (tails and the subnormal
    /// range of the result included), and its result is 0 or +∞ exactly where libm's is.
    #[test]
    fn exp_within_the_bound_of_libm() {
        let worst = exp_arguments()
            .into_iter()
            .map(|x| {
                let (a, b) = (exp(x), x.exp());
                assert_eq!(
                    (a == 0.0, a.is_infinite()),
                    (b == 0.0, b.is_infinite()),
                    "exp({x:e}) = {a:e}, libm {b:e}"
                );
                (ulps(a, b), x)
            })
            .max_by_key(|p| p.0)
            .unwrap();
        assert!(
            worst.0 <= EXP_ULP_BOUND,
            "exp({:e}): {} ulp from libm",
            worst.1,
            worst.0
        );
    }

    /// [`ln`] is within [`LN_ULP_BOUND`] ulp of libm's `ln` over 10⁶ arguments (subnormal arguments and the
    /// neighbourhood of 1 included).
    #[test]
    fn ln_within_the_bound_of_libm() {
        let worst = ln_arguments()
            .into_iter()
            .map(|x| (ulps(ln(x), x.ln()), x))
            .max_by_key(|p| p.0)
            .unwrap();
        assert!(worst.0 <= LN_ULP_BOUND, "ln({:e}): {} ulp from libm", worst.1, worst.0);
    }

    /// Every instruction set the CPU has — AVX-512, AVX2 and the baseline forced in turn — gives the bits
    /// of the scalar formula (no contraction into FMA, no other reassociation), also on the slice tails
    /// that the vector loops leave to scalar code (lengths 0..=19).
    #[test]
    fn every_isa_gives_the_bits_of_the_scalar_formula() {
        // kernels as types, so that `map_on` compiles each formula into its vector loops (a function pointer
        // would stay an indirect call there, and the loops scalar)
        #[derive(Clone, Copy)]
        struct Exp;
        impl Kernel for Exp {
            #[inline(always)]
            fn at(&self, x: f64) -> f64 {
                exp(x)
            }
        }
        #[derive(Clone, Copy)]
        struct Ln;
        impl Kernel for Ln {
            #[inline(always)]
            fn at(&self, x: f64) -> f64 {
                ln(x)
            }
        }
        fn check<K: Kernel + Copy>(k: K, x: &[f64], scalar: fn(f64) -> f64) {
            for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
                for len in (0..=19).chain([x.len()]) {
                    let mut out = vec![0.0; len];
                    map_on(isa, &x[..len], &mut out, k);
                    assert!(
                        out.iter()
                            .zip(&x[..len])
                            .all(|(o, &v)| o.to_bits() == scalar(v).to_bits()),
                        "{isa:?}, {len} points"
                    );
                }
            }
        }
        check(Exp, &exp_arguments(), exp);
        check(Ln, &ln_arguments(), ln);
        // the detected variant is one the CPU has
        assert!(Isa::detected().available());
    }

    /// A cap names a variant no wider than itself, one the CPU has; the baseline is always there; the three
    /// names parse and anything else is refused with the variable's name and the value.
    #[test]
    fn a_cap_gives_a_variant_no_wider_than_itself() {
        let width = |i: Isa| 3 - Isa::ALL.iter().position(|&j| j == i).unwrap();
        for cap in Isa::ALL {
            let got = Isa::widest_up_to(cap);
            assert!(got.available() && width(got) <= width(cap), "{cap:?} gave {got:?}");
            if cap.available() {
                assert_eq!(got, cap);
            }
        }
        assert_eq!(Isa::widest_up_to(Isa::Baseline), Isa::Baseline);
        for (name, isa) in [
            ("avx512", Isa::Avx512),
            ("avx2", Isa::Avx2),
            ("baseline", Isa::Baseline),
        ] {
            assert_eq!(Isa::parse(name).unwrap(), isa);
        }
        let e = Isa::parse("AVX2 ").unwrap_err().to_string();
        assert!(
            e.contains(ISA_ENV) && e.contains("AVX2 ") && e.contains("baseline"),
            "{e}"
        );
    }
}
