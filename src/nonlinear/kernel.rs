//! An element's force law as a closed form for route 2's inner loop: the force, the impulse of its exact
//! flow over a fixed τ and its regime, with every constant of the step computed once.
//!
//! # Formula
//! The same expressions, evaluated in the same order, as the law's own [`ForceLaw`](super::ForceLaw)
//! methods (so a run gives the same bits through either):
//! * a bump stop, F(x) = k_u (x − d_u)₊ − k_l (−d_l − x)₊, impulse τF(x), engaged beyond either clearance;
//! * a tyre contact, F(x) = −k_t (x − s₀)₊, impulse τF(x), engaged (off the road) for x > s₀;
//! * a bilinear damper's remainder F(v) = Δ|v|, whose flow v(τ) = v e^{−κΔτ sgn v} gives the impulse
//!   J = −v (e^{∓κΔτ} − 1)/κ: the two factors e^{−κΔτ} − 1 (v > 0) and e^{κΔτ} − 1 (v < 0) are the
//!   kernel's constants instead of an `expm1` at every kick.
//!
//! Laws without a kernel are evaluated through their trait methods.

/// A force law in closed form with the constants of one kick duration τ (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kernel {
    /// A bump stop.
    Stop {
        /// (clearance d_u, m; stiffness k_u, N/m) of the upper side.
        upper: Option<(f64, f64)>,
        /// (clearance d_l, m; stiffness k_l, N/m) of the lower side.
        lower: Option<(f64, f64)>,
        /// τ, s.
        tau: f64,
    },
    /// A tyre contact.
    Lift {
        /// k_t, N/m.
        stiffness: f64,
        /// s₀, m.
        deflection: f64,
        /// τ, s.
        tau: f64,
    },
    /// A bilinear damper's remainder.
    Bilinear {
        /// Δ = (c_r − c_c)/2, N s/m.
        half_difference: f64,
        /// κ, 1/kg.
        kappa: f64,
        /// κΔτ.
        rate: f64,
        /// e^{−κΔτ} − 1 (the flow factor for v > 0).
        rebound: f64,
        /// e^{κΔτ} − 1 (for v < 0).
        compression: f64,
    },
}

impl Kernel {
    /// The kernel of a bilinear damper with Δ = `half_difference` at κ and τ.
    pub fn bilinear(half_difference: f64, kappa: f64, tau: f64) -> Kernel {
        let rate = kappa * half_difference * tau;
        Kernel::Bilinear {
            half_difference,
            kappa,
            rate,
            rebound: (-rate).exp_m1(),
            compression: rate.exp_m1(),
        }
    }

    /// The remainder F(x, v), N.
    #[inline(always)]
    pub fn force(&self, x: f64, v: f64) -> f64 {
        match *self {
            Kernel::Stop { upper, lower, .. } => {
                let up = upper.map_or(0.0, |(d, k)| k * (x - d).max(0.0));
                let lo = lower.map_or(0.0, |(d, k)| k * (-d - x).max(0.0));
                up - lo
            }
            Kernel::Lift {
                stiffness, deflection, ..
            } => -stiffness * (x - deflection).max(0.0),
            Kernel::Bilinear { half_difference, .. } => half_difference * v.abs(),
        }
    }

    /// The impulse of the exact flow over τ, N s.
    #[inline]
    pub fn impulse(&self, x: f64, v: f64) -> f64 {
        match *self {
            Kernel::Stop { tau, .. } | Kernel::Lift { tau, .. } => tau * self.force(x, v),
            Kernel::Bilinear {
                kappa,
                rate,
                rebound,
                compression,
                ..
            } => {
                if rate == 0.0 || v == 0.0 {
                    return 0.0;
                }
                let f = if v > 0.0 {
                    rebound
                } else if v < 0.0 {
                    compression
                } else {
                    (-rate * v.signum()).exp_m1()
                };
                -v * f / kappa
            }
        }
    }

    /// [`Kernel::force`] of every lane (realizations in lockstep): the same expressions lane by lane, the
    /// variant chosen once outside the lane loop so that the lanes vectorise. A stop side that is absent
    /// acts as clearance ∞ and stiffness 0, whose term k (x − d)₊ is +0 as the absent side's 0 is.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub fn forces<const L: usize>(&self, x: &[f64; L], v: &[f64; L], f: &mut [f64; L]) {
        match *self {
            Kernel::Stop { upper, lower, .. } => {
                let (du, ku) = upper.unwrap_or((f64::INFINITY, 0.0));
                let (dl, kl) = lower.unwrap_or((f64::INFINITY, 0.0));
                for l in 0..L {
                    let up = ku * (x[l] - du).max(0.0);
                    let lo = kl * (-dl - x[l]).max(0.0);
                    f[l] = up - lo;
                }
            }
            Kernel::Lift {
                stiffness, deflection, ..
            } => {
                for l in 0..L {
                    f[l] = -stiffness * (x[l] - deflection).max(0.0);
                }
            }
            Kernel::Bilinear { half_difference, .. } => {
                for l in 0..L {
                    f[l] = half_difference * v[l].abs();
                }
            }
        }
    }

    /// [`Kernel::impulse`] of every lane (realizations in lockstep): the same expressions lane by lane, with
    /// the branches as selects so that the lanes vectorise (a stop's and a tyre's τF through
    /// [`Kernel::forces`]).
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane loops index several arrays at once
    pub fn impulses<const L: usize>(&self, x: &[f64; L], v: &[f64; L], j: &mut [f64; L]) {
        match *self {
            Kernel::Stop { tau, .. } | Kernel::Lift { tau, .. } => {
                self.forces(x, v, j);
                for l in 0..L {
                    j[l] *= tau;
                }
            }
            Kernel::Bilinear {
                kappa,
                rate,
                rebound,
                compression,
                ..
            } => {
                // rate = 0 tested once, not in every lane
                if rate == 0.0 {
                    *j = [0.0; L];
                    return;
                }
                #[cfg(target_arch = "x86_64")]
                if L.is_multiple_of(2) {
                    bilinear_pairs(v, rebound, compression, kappa, j);
                    return;
                }
                for l in 0..L {
                    // v NaN: −v·f/κ is v's NaN, as through the law's e^{…} − 1 of NaN
                    let f = if v[l] > 0.0 { rebound } else { compression };
                    let flow = -v[l] * f / kappa;
                    j[l] = if v[l] == 0.0 { 0.0 } else { flow };
                }
            }
        }
    }

    /// [`Kernel::engaged`] of every lane, the variant chosen once outside the lane loop.
    #[inline(always)]
    pub fn engaged_lanes<const L: usize>(&self, x: &[f64; L]) -> [bool; L] {
        match *self {
            Kernel::Stop { upper, lower, .. } => {
                let du = upper.map_or(f64::INFINITY, |(d, _)| d);
                let dl = lower.map_or(f64::INFINITY, |(d, _)| d);
                x.map(|x| x > du || x < -dl)
            }
            Kernel::Lift { deflection, .. } => x.map(|x| x > deflection),
            Kernel::Bilinear { .. } => [false; L],
        }
    }

    /// Whether the element is in its regime at deflection x.
    #[inline(always)]
    pub fn engaged(&self, x: f64) -> bool {
        match *self {
            Kernel::Stop { upper, lower, .. } => {
                upper.is_some_and(|(d, _)| x > d) || lower.is_some_and(|(d, _)| x < -d)
            }
            Kernel::Lift { deflection, .. } => x > deflection,
            Kernel::Bilinear { .. } => false,
        }
    }
}

/// The bilinear damper's lane impulses of [`Kernel::impulses`] two lanes at a time in SSE2 vector operations
/// (in the x86-64 baseline, and VEX-encoded where the caller is compiled for AVX2 or AVX-512): written as
/// scalar selects, the compiler kept a scalar division per lane.
///
/// # Formula
/// f = `rebound` where v > 0, `compression` otherwise (a bit mask from the comparison); J = (−v)·f/κ with
/// −v the sign bit flipped (as Rust's negation), then J's bits ANDed with the mask of v ≠ 0 (+0 where
/// v = ±0). The same IEEE operations in the same order as the scalar lane loop: the same bits, NaN
/// included.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn bilinear_pairs<const L: usize>(v: &[f64; L], rebound: f64, compression: f64, kappa: f64, j: &mut [f64; L]) {
    use std::arch::x86_64::{
        _mm_and_pd, _mm_andnot_pd, _mm_cmpgt_pd, _mm_cmpneq_pd, _mm_cvtsd_f64, _mm_div_pd, _mm_mul_pd, _mm_or_pd,
        _mm_set1_pd, _mm_set_pd, _mm_setzero_pd, _mm_unpackhi_pd, _mm_xor_pd,
    };
    // SAFETY: SSE2 is part of the x86-64 baseline, so every x86-64 CPU has these instructions; none of
    // them touches memory.
    unsafe {
        let (rb, cb, k) = (_mm_set1_pd(rebound), _mm_set1_pd(compression), _mm_set1_pd(kappa));
        let (zero, sign) = (_mm_setzero_pd(), _mm_set1_pd(-0.0));
        for (vc, jc) in v.chunks_exact(2).zip(j.chunks_exact_mut(2)) {
            let x = _mm_set_pd(vc[1], vc[0]);
            let positive = _mm_cmpgt_pd(x, zero);
            let f = _mm_or_pd(_mm_and_pd(positive, rb), _mm_andnot_pd(positive, cb));
            let q = _mm_div_pd(_mm_mul_pd(_mm_xor_pd(x, sign), f), k);
            let q = _mm_and_pd(q, _mm_cmpneq_pd(x, zero));
            jc[0] = _mm_cvtsd_f64(q);
            jc[1] = _mm_cvtsd_f64(_mm_unpackhi_pd(q, q));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Kernel;
    use crate::linalg::vmath::{self, Task};

    /// Velocities at the damper's edges: ±0, the smallest subnormal (whose impulse underflows to ±0), the
    /// smallest normal, ordinary values, the largest finite values, ±∞ and NaN.
    const V: [f64; 16] = [
        0.0,
        -0.0,
        f64::from_bits(1),
        -f64::from_bits(1),
        f64::MIN_POSITIVE,
        -f64::MIN_POSITIVE,
        1e-300,
        -1e-300,
        0.3,
        -0.3,
        f64::MAX,
        f64::MIN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        -f64::NAN,
    ];

    struct Lanes<'a>(&'a Kernel, [f64; 16]);

    impl Task for Lanes<'_> {
        #[inline(always)]
        fn run(&mut self) {
            self.0.impulses(&[0.0; 16], &V, &mut self.1);
        }
    }

    /// The lane forms of the bilinear damper's impulse ([`Kernel::impulses`]: SSE2 pairs on x86-64, the
    /// lane loop of selects for an odd number of lanes) give the bits of the scalar [`Kernel::impulse`]
    /// (branches) for every velocity above, compiled for this CPU's widest instruction set through
    /// [`vmath::run`] and in the baseline build, for both signs of Δ (a rebound factor below 0 and above 0),
    /// a Δ whose impulses underflow, and a rate of 0; a NaN velocity gives NaN.
    #[test]
    fn bilinear_lanes_give_the_bits_of_the_scalar_impulse() {
        let (kappa, tau) = (1.0 / 300.0 + 1.0 / 40.0, 0.5 * 0.0027);
        for delta in [700.0, -700.0, 0.0, 1e-300, -1e-300] {
            let k = Kernel::bilinear(delta, kappa, tau);
            let mut widest = Lanes(&k, [1.0; 16]);
            vmath::run(&mut widest);
            let mut baseline = Lanes(&k, [1.0; 16]);
            baseline.run();
            // an odd number of lanes takes the lane loop instead of the pairs
            let mut odd = [1.0; 15];
            let v15: &[f64; 15] = V[..15].try_into().expect("15 velocities");
            k.impulses(&[0.0; 15], v15, &mut odd);
            for (l, &v) in V.iter().enumerate() {
                let scalar = k.impulse(0.0, v);
                let odd = odd.get(l).copied().unwrap_or(scalar);
                for (lanes, build) in [(widest.1[l], "widest"), (baseline.1[l], "baseline"), (odd, "odd lanes")] {
                    if v.is_nan() && delta != 0.0 {
                        assert!(
                            lanes.is_nan() && scalar.is_nan(),
                            "{build} Δ = {delta} J({v}) = {lanes}"
                        );
                    } else {
                        assert_eq!(
                            lanes.to_bits(),
                            scalar.to_bits(),
                            "{build} Δ = {delta} J({v}): {lanes} ≠ {scalar}"
                        );
                    }
                }
            }
        }
    }
}
