//! Which exact route an input spectrum has under a speed profile, or why it has none.

use super::system::InputModel;
use super::SpeedProfile;
use crate::error::{Error, Result};
use crate::spectrum::{Asymptote, Domain, Spectrum};

/// The exact-route form of `spectrum` (a temporal process, or a spatial road traversed at `speed`).
///
/// # Formula
/// * temporal, rational with a constant density S₀ (numerator and denominator of degree 0): white noise;
/// * temporal, rational: its shaping filter ([`InputModel::Rational`]);
/// * spatial, rational: its filter in the road coordinate, made time-varying by v(t)
///   ([`InputModel::SpatialRational`]);
/// * spatial, S(Ω) = c/Ω² for every Ω (waviness w = 2 without a band): the road velocity is white in
///   time with S₀(t) = c·v(t) ([`InputModel::WhiteSlope`]).
///
/// # Errors
/// [`Error::NotApplicable`] for every other spectrum, with the reason: a non-rational temporal spectrum has
/// no finite state (the evolutionary route applies to it when it is only modulated in amplitude; else use
/// Monte Carlo); a non-rational road under a varying speed is not a uniformly modulated process (its
/// frequency content moves with v): not available, use Monte Carlo. A spatial spectrum without a speed.
pub fn input_model(spectrum: &dyn Spectrum, speed: Option<&SpeedProfile>) -> Result<InputModel> {
    match (spectrum.domain(), speed) {
        (Domain::Temporal, _) => match spectrum.rational() {
            Some(r) if r.numerator().len() == 1 && r.denominator().len() == 1 => Ok(InputModel::White {
                density: r.numerator()[0] / r.denominator()[0],
            }),
            Some(r) => Ok(InputModel::Rational {
                filter: r.shaping_filter()?,
            }),
            None => Err(Error::NotApplicable {
                method: "exact (differential Lyapunov) route".into(),
                reason: format!(
                    "the input spectrum ({}) is not rational: it has no finite shaping filter. A stationary input \
                     with an amplitude envelope through a time-invariant system has the evolutionary-spectrum \
                     route; otherwise not available: use Monte Carlo",
                    spectrum.describe()
                ),
            }),
        },
        (Domain::Spatial, None) => Err(Error::invalid(
            "speed",
            "<missing>",
            "a road (spatial) spectrum needs a speed or a speed profile",
        )),
        (Domain::Spatial, Some(v)) => {
            if let Some(r) = spectrum.rational() {
                return Ok(InputModel::SpatialRational {
                    filter: r.shaping_filter()?,
                    speed: v.clone(),
                });
            }
            if let Some(c) = white_slope_coefficient(spectrum) {
                return Ok(InputModel::WhiteSlope {
                    coefficient: c,
                    speed: v.clone(),
                });
            }
            Err(Error::NotApplicable {
                method: "exact (differential Lyapunov) route".into(),
                reason: format!(
                    "the road spectrum ({}) is neither rational nor of waviness w = 2 without a band: under a \
                     varying speed its temporal content moves with v(t), which is not a modulated stationary \
                     process (no evolutionary form); not available: use Monte Carlo",
                    spectrum.describe()
                ),
            })
        }
    }
}

/// c when S(Ω) = c/Ω² for all Ω > 0: both asymptotes Ω⁻² with the same coefficient, support (0, ∞), and the
/// density equal to c/Ω² (within 10⁻¹²) at a spread of check points.
pub fn white_slope_coefficient(spectrum: &dyn Spectrum) -> Option<f64> {
    let (lo, hi) = (spectrum.low_frequency(), spectrum.high_frequency());
    let c = match (lo, hi) {
        (
            Asymptote::Power {
                exponent: e1,
                coefficient: c1,
            },
            Asymptote::Power {
                exponent: e2,
                coefficient: c2,
            },
        ) if e1 == -2.0 && e2 == -2.0 && (c1 - c2).abs() <= 1e-12 * c1.abs() => c1,
        _ => return None,
    };
    if spectrum.support() != (0.0, f64::INFINITY) || !(c.is_finite() && c > 0.0) {
        return None;
    }
    let fits = [1e-4, 0.01, 0.3, 1.0, 7.0, 100.0, 1e4]
        .iter()
        .all(|&w| (spectrum.density(w) * w * w - c).abs() <= 1e-12 * c);
    fits.then_some(c)
}
