//! Two coherent road tracks built in Python: the excitation of a scenario's `[[input]] road = { spectrum,
//! coherence, track_width }` (left and right wheel tracks, the coherence between them, the wheelbase delays)
//! for a system given to `Scenario.from_system`.

use crate::errors::{call, invalid_input, lib};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;
use stochvib::coherence::TwoTracks;
use stochvib::models::InputLayout;
use stochvib::response::{Excitation, InputMap, Source};
use stochvib::spectrum::{Domain, Spectrum};
use stochvib::Error;

/// What `Scenario.from_system` was given for a road of two tracks.
pub struct TwoTrackArgs<'a, 'py> {
    /// The coherence model (a dict as a scenario road's `coherence` table).
    pub coherence: Option<&'a Bound<'py, PyDict>>,
    /// The distance between the wheel tracks, m (default the model's).
    pub track_width: Option<f64>,
    /// The track of each system input, 0 left, 1 right (default the model's layout).
    pub tracks: Option<Vec<usize>>,
}

impl TwoTrackArgs<'_, '_> {
    /// Whether the arguments ask for two tracks.
    pub fn given(&self) -> bool {
        self.coherence.is_some() || self.track_width.is_some() || self.tracks.is_some()
    }
}

/// "left"/0 → 0, "right"/1 → 1 for each element of `tracks`.
pub fn track_indices(py: Python<'_>, tracks: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    let bad = |x: &Bound<'_, PyAny>| {
        invalid_input(
            py,
            format!("`tracks`: {x} is not a track: \"left\" (0) or \"right\" (1) per system input"),
        )
    };
    tracks
        .try_iter()?
        .map(|x| {
            let x = x?;
            match (x.extract::<String>(), x.extract::<usize>()) {
                (Ok(s), _) if s == "left" => Ok(0),
                (Ok(s), _) if s == "right" => Ok(1),
                (_, Ok(i)) if i <= 1 => Ok(i),
                _ => Err(bad(&x)),
            }
        })
        .collect()
}

/// (tracks, positions, gains, track width) of the model's own two-track layout, if it has one.
type Layout = (Vec<usize>, Vec<f64>, Vec<f64>, Option<f64>);

fn model_layout(layout: &Option<InputLayout>) -> Option<Layout> {
    match layout {
        Some(InputLayout::TwoTracks {
            tracks,
            positions,
            gains,
            track_width,
        }) => Some((tracks.clone(), positions.clone(), gains.clone(), *track_width)),
        _ => None,
    }
}

/// The track width: the given one, else the model's; both must agree (the coherence is that of the
/// distance between the wheel tracks).
fn width(py: Python<'_>, given: Option<f64>, model: Option<f64>) -> PyResult<f64> {
    let w = match (given, model) {
        (Some(w), Some(b)) if (w - b).abs() > 1e-9 * b => {
            return lib(
                py,
                Err(Error::invalid(
                    "track_width",
                    w,
                    format!(
                        "the model's track width is {b} m: the coherence between the tracks is that of tracks {w} m \
                         apart, but the wheels run {b} m apart; give the model's width (or leave track_width out)"
                    ),
                )),
            )
        }
        (Some(w), _) | (None, Some(w)) => w,
        (None, None) => {
            return Err(invalid_input(
                py,
                "`track_width`: required for a road of two tracks (a length, e.g. \"1.5 m\"); the model has none",
            ))
        }
    };
    if !(w.is_finite() && w > 0.0) {
        return lib(py, Err(Error::invalid("track_width", w, "must be a finite length > 0")));
    }
    Ok(w)
}

/// The excitation of a system's `n_inputs` inputs by a road of two coherent tracks, and the coherence's
/// description: input j feels track c_j at ℓ_j behind the first contact, u_j(t) = g_j x_{c_j}(t − ℓ_j/v),
/// as a scenario file's `[[input]] road` gives it.
pub fn excitation(
    py: Python<'_>,
    (layout, n_inputs): (&Option<InputLayout>, usize),
    road: &Arc<dyn Spectrum>,
    (speed, positions, mean): (Option<f64>, Option<Vec<f64>>, f64),
    args: TwoTrackArgs<'_, '_>,
) -> PyResult<(Excitation, String)> {
    if road.domain() != Domain::Spatial {
        return Err(invalid_input(
            py,
            "a road of two tracks needs a spatial spectrum (a profile in cycles/m or rad/m)",
        ));
    }
    let Some(v) = speed else {
        return lib(
            py,
            Err(Error::invalid(
                "speed",
                "<missing>",
                "a road is a spatial process: give the speed",
            )),
        );
    };
    let own = model_layout(layout);
    let b = width(py, args.track_width, own.as_ref().and_then(|l| l.3))?;
    let Some(model) = args.coherence else {
        return Err(invalid_input(
            py,
            "`coherence`: a road of two tracks needs its coherence model, e.g. {\"kind\": \"dodds-robson\", \
             \"waviness\": 2} (the `coherence` table of a scenario's road)",
        ));
    };
    let text = toml::Value::Table(crate::convert::toml_table(py, "coherence", model)?).to_string();
    let coh = call(py, || stochvib::scenario::coherence_from_toml(&text, b))?;
    let desc = coh.describe();
    let tracks = call(py, || TwoTracks::new(road.clone(), coh, v))?;
    let component = |j: usize| -> PyResult<usize> {
        match (&args.tracks, &own) {
            (Some(t), _) => Ok(t[j]),
            (None, Some(l)) => Ok(l.0[j]),
            (None, None) => Err(invalid_input(
                py,
                format!("model input {j} has no track: give tracks=[\"left\", \"right\", …], one per system input"),
            )),
        }
    };
    let lengths = [
        args.tracks.as_ref().map(|t| ("tracks", t.len())),
        positions.as_ref().map(|p| ("positions", p.len())),
    ];
    if let Some((name, n)) = lengths.into_iter().flatten().find(|(_, n)| *n != n_inputs) {
        return Err(invalid_input(
            py,
            format!("`{name}` has {n} entries: the system has {n_inputs} inputs"),
        ));
    }
    let maps = (0..n_inputs)
        .map(|j| {
            let position = match (&positions, &own) {
                (Some(p), _) => p[j],
                (None, Some(l)) => l.1[j],
                (None, None) => 0.0,
            };
            let gain = own.as_ref().map_or(1.0, |l| l.2[j]);
            Ok(InputMap {
                source: 0,
                component: component(j)?,
                delay: position / v,
                gain,
                mean: gain * mean,
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let exc = call(py, || Excitation::sources(vec![Source::Matrix(Arc::new(tracks))], maps))?;
    Ok((exc, desc))
}
