//! Random streams: one documented, portable generator; realization `i` of seed `s` has its own stream.

use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use rand_distr::StandardNormal;

/// The generator and stream derivation used by every Monte Carlo routine of the crate.
///
/// Results depend only on (seed, realization index), never on the number of threads or on how a batch is
/// split into shards.
pub const GENERATOR: &str = "xoshiro256++ (rand 0.10 `Xoshiro256PlusPlus`); realization i of seed s uses \
    Xoshiro256PlusPlus::seed_from_u64(splitmix64(s XOR splitmix64(i XOR 0x6a09e667f3bcc909))); normal \
    variates by rand_distr 0.6 `StandardNormal` (ziggurat)";

/// The SplitMix64 finaliser (Steele, Lea & Flood 2014; the mixer of Vigna's `splitmix64.c`): a bijection
/// of `u64` with good avalanche.
///
/// # Formula
/// ```text
/// z = x + 0x9e3779b97f4a7c15;  z = (z ⊕ z≫30)·0xbf58476d1ce4e5b9;  z = (z ⊕ z≫27)·0x94d049bb133111eb;
/// return z ⊕ z≫31          (wrapping arithmetic)
/// ```
///
/// # Examples
/// ```
/// use stochvib::simulate::splitmix64;
/// // first output of Vigna's splitmix64.c seeded with 0 (published reference value)
/// assert_eq!(splitmix64(0), 0xe220a8397b1dcdaf);
/// ```
pub fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The 64-bit key of realization `i` of `seed`.
///
/// # Formula
/// ```text
/// key(s, i) = splitmix64(s ⊕ splitmix64(i ⊕ 0x6a09e667f3bcc909))
/// ```
/// For a fixed seed, i ↦ key is a bijection (composition of bijections), so distinct realizations get
/// distinct keys, and `Xoshiro256PlusPlus::seed_from_u64` maps distinct keys to distinct 256-bit states
/// (its first state word is a bijection of the key). Streams are not jump-separated; with a period of
/// 2²⁵⁶ − 1 an overlap of two streams of practical length has negligible probability.
///
/// # Examples
/// ```
/// use stochvib::simulate::stream_key;
/// assert_ne!(stream_key(42, 0), stream_key(42, 1));
/// ```
pub fn stream_key(seed: u64, i: u64) -> u64 {
    splitmix64(seed ^ splitmix64(i ^ 0x6a09_e667_f3bc_c909))
}

/// The random stream of realization `i` of `seed` (see [`GENERATOR`]).
///
/// # Examples
/// ```
/// use stochvib::simulate::{stream, standard_normal};
/// let mut a = stream(42, 3);
/// let mut b = stream(42, 3);
/// assert_eq!(standard_normal(&mut a), standard_normal(&mut b));
/// ```
pub fn stream(seed: u64, i: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(stream_key(seed, i))
}

/// One standard normal variate N(0, 1).
#[inline]
pub fn standard_normal(rng: &mut Xoshiro256PlusPlus) -> f64 {
    rng.sample(StandardNormal)
}

/// Fills `out` with independent standard normal variates, in order: the variates of `out.len()` calls of
/// [`standard_normal`], bit for bit, with `rng` left in the same state (the ziggurat's common case is done
/// inline in the loop, the rest by `rand_distr`; see `lane_normals`).
#[inline]
pub fn fill_standard_normal(rng: &mut Xoshiro256PlusPlus, out: &mut [f64]) {
    super::lane_normals::fill_stream(rng, out);
}

/// A uniform variate on [0, 1) (53 random bits).
#[inline]
pub fn uniform01(rng: &mut Xoshiro256PlusPlus) -> f64 {
    rng.random::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix_reference_sequence() {
        // Vigna's splitmix64.c with state x = 0: successive outputs are splitmix64(k·φ) for k = 0, 1, 2 in
        // our "add then mix" form; the published first three outputs are below.
        let phi = 0x9e37_79b9_7f4a_7c15u64;
        assert_eq!(splitmix64(0), 0xe220_a839_7b1d_cdaf);
        assert_eq!(splitmix64(phi), 0x6e78_9e6a_a1b9_65f4);
        assert_eq!(splitmix64(phi.wrapping_mul(2)), 0x06c4_5d18_8009_454f);
    }

    #[test]
    fn keys_distinct_for_many_realizations() {
        let mut keys: Vec<u64> = (0..10_000).map(|i| stream_key(7, i)).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), 10_000);
    }
}
