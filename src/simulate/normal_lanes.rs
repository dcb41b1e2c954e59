//! The standard normals of [`LANES`] consecutive random streams of a seed, drawn side by side: the fastest
//! way this crate draws the normals of several realizations, used by the exact route's lockstep
//! realizations ([`GaussMarkovLanes`](super::GaussMarkovLanes)) and by the measurement of its floor.

use super::lane_normals::{LaneNormals, StreamRng};

/// Realizations stepped side by side by the lockstep paths of the exact route: one lane per realization.
pub const LANES: usize = 8;

/// The random streams of realizations `first .. first + LANES` of a seed, each in its own state.
///
/// # Formula
/// Lane l is [`stream`](super::stream)`(seed, first + l)`; its k-th draw is, bit for bit, the k-th
/// [`standard_normal`](super::standard_normal) of that stream (the ziggurat of `rand_distr`'s
/// `StandardNormal`), whatever the grouping of the draws into fills.
///
/// # Examples
/// ```
/// use stochvib::simulate::{fill_standard_normal, fill_standard_normal_lanes, stream, NormalLanes, LANES};
/// let mut lanes = NormalLanes::new(7, 16);
/// let mut x = vec![[0.0; LANES]; 100];
/// fill_standard_normal_lanes(&mut lanes, &mut x);
/// let mut one = vec![0.0; 100];
/// fill_standard_normal(&mut stream(7, 16 + 3), &mut one);
/// assert!(x.iter().zip(&one).all(|(a, b)| a[3].to_bits() == b.to_bits()));
/// ```
pub struct NormalLanes {
    pub(crate) inner: LaneNormals<LANES>,
}

impl NormalLanes {
    /// The streams of realizations `first .. first + LANES` of `seed`, at their start.
    pub fn new(seed: u64, first: u64) -> NormalLanes {
        NormalLanes {
            inner: LaneNormals::new(std::array::from_fn(|l| StreamRng::new(seed, first + l as u64))),
        }
    }
}

/// Fills `out` with the next `out.len()` standard normals of every lane: `out[k][l]` is lane l's k-th
/// (see [`NormalLanes`]).
pub fn fill_standard_normal_lanes(lanes: &mut NormalLanes, out: &mut [[f64; LANES]]) {
    lanes.inner.fill(out);
}
