//! What a catalogue model hands to the analysis: a system and the layout of its random inputs.

use crate::system::FrequencyResponse;
use std::sync::Arc;

/// How the random input reaches the system's inputs.
#[derive(Debug, Clone, PartialEq)]
pub enum InputLayout {
    /// Every input is the same road track, input j at `positions[j]` metres behind the first contact
    /// point, scaled by `gains[j]`: u_j(t) = g_j q(t − ℓ_j/v). Needs a road spectrum and a speed.
    Track {
        /// ℓ_j, m (0 for the first contact point).
        positions: Vec<f64>,
        /// g_j.
        gains: Vec<f64>,
    },
    /// One temporal process (a force, a base acceleration) feeding input 0 (and nothing else).
    Single,
    /// Wheels on two parallel road tracks: input j on track `tracks[j]` (0 left, 1 right) at
    /// `positions[j]` m behind the first contact, scaled by `gains[j]`: u_j(t) = g_j x_{c_j}(t − ℓ_j/v).
    /// Needs a road of two tracks with a coherence (a scenario's `[[input]]` road).
    TwoTracks {
        /// c_j: 0 left, 1 right.
        tracks: Vec<usize>,
        /// ℓ_j, m.
        positions: Vec<f64>,
        /// g_j.
        gains: Vec<f64>,
        /// The distance between the two wheel tracks in m, if the model has one (a vehicle's track
        /// width): a road's `track_width` must equal it (the coherence between the tracks is a function
        /// of the distance between them).
        track_width: Option<f64>,
    },
}

/// A system built from a catalogue model, with the layout of its random inputs.
#[derive(Debug, Clone)]
pub struct ModelInstance {
    /// The linear system (outputs named, with units).
    pub system: Arc<dyn FrequencyResponse>,
    /// How the random input reaches the system.
    pub layout: InputLayout,
    /// One line: model, parameters, source section.
    pub description: String,
}
