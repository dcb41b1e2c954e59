//! The poles of a scenario's model, as natural frequency and damping ratio: the pole table of the hand-over
//! report (`stochvib report`), which [`crate::report::handover`] prints.

use crate::scenario::Scenario;
use serde::Serialize;

/// One pole λ of the state space (one of a complex pair).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Pole {
    /// Natural frequency ω_n = |λ|, rad/s.
    pub natural_frequency_rad_s: f64,
    /// Damping ratio ζ = −Re λ / |λ| (≥ 1 for a real pole).
    pub damping_ratio: f64,
}

/// The poles of the model's state space with Im λ ≥ 0 (one of each complex pair) and λ ≠ 0, by increasing
/// natural frequency; `None` for a model without a finite state space.
///
/// # Formula
/// λ the eigenvalues of A; ω_n = |λ|, ζ = −Re λ / |λ|.
pub fn model_poles(sc: &Scenario) -> Option<Vec<Pole>> {
    let ss = sc.model.system.state_space()?;
    let mut poles: Vec<Pole> =
        ss.a.complex_eigenvalues()
            .iter()
            .filter(|l| l.im >= 0.0 && l.norm() > 0.0)
            .map(|l| Pole {
                natural_frequency_rad_s: l.norm(),
                damping_ratio: -l.re / l.norm(),
            })
            .collect();
    poles.sort_by(|a, b| a.natural_frequency_rad_s.total_cmp(&b.natural_frequency_rad_s));
    Some(poles)
}
