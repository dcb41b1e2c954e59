//! A scenario replayed on a measured road profile: the scenario's wheels (its input map, tracks and
//! positions) follow the profile's tracks at a speed ([`crate::road::replay::replay()`]), and beside each replayed σ
//! the analytic σ of the same scenario whose road spectrum is the profile's own measured density
//! (`measured-profile`, [`crate::scenario::spectrum_file`]).

use crate::error::{Error, Result};
use crate::response::{analyze_output, Excitation, Source};
use crate::road::{Detrend, Profile, Replay, ReplayOptions, Start, Wheel};
use crate::scenario::scenario_file::{parse_scenario, Scenario};
use crate::spectrum::Domain;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Options of [`replay_scenario`].
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioReplayOptions {
    /// Speed, m/s; `None`: the scenario's `speed`.
    pub speed_m_s: Option<f64>,
    /// Length skipped before the statistics, m; `None`: [`crate::road::replay::settling_length`].
    pub skip_m: Option<f64>,
    /// Initial state (default [`Start::Static`]).
    pub start: Start,
    /// The profile column under a road of one track (`[input] spectrum` of a road, or an `[[input]]`
    /// `spectrum` that is spatial); `None`: the profile's first column. A road of two tracks
    /// (`road = { … }`) uses the columns `left` and `right`.
    pub track: Option<String>,
    /// What is removed from every track before the replay and before the Welch estimate of the analytic
    /// route (default [`Detrend::Linear`], as the `measured-profile` spectrum kind).
    pub detrend: Detrend,
}

impl Default for ScenarioReplayOptions {
    fn default() -> Self {
        ScenarioReplayOptions {
            speed_m_s: None,
            skip_m: None,
            start: Start::Static,
            track: None,
            detrend: Detrend::Linear,
        }
    }
}

/// The replayed and the analytic σ of one reported output.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReplayedOutput {
    /// Index of the output in the system.
    pub index: usize,
    /// The replay's statistics of the output.
    #[serde(flatten)]
    pub replayed: crate::road::OutputStatistics,
    /// σ of the output from the analytic route with the profile's measured density; `None` if the route
    /// gave no finite value.
    pub analytic_sigma: Option<f64>,
}

/// The result of [`replay_scenario`].
#[derive(Debug, Clone, Serialize)]
pub struct ScenarioReplay {
    /// The scenario file.
    pub scenario: PathBuf,
    /// The scenario's title.
    pub title: String,
    /// The profile file.
    pub profile: PathBuf,
    /// The detrending applied to every track.
    pub detrend: Detrend,
    /// The model input → (track, position m, gain, offset) map used.
    pub wheels: Vec<ReplayWheel>,
    /// The replay (grid, skipped length, statistics of every output; the histories are not serialised).
    pub replay: Replay,
    /// The reported outputs (`[analysis] outputs`), replayed and analytic.
    pub outputs: Vec<ReplayedOutput>,
    /// The profile column whose Welch density the analytic route uses (for a road of two tracks: its
    /// `left` track, with the scenario's coherence model between the tracks).
    pub analytic_track: String,
}

/// A wheel as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReplayWheel {
    /// Model input index.
    pub input: usize,
    /// Profile column.
    pub track: String,
    /// Distance behind the first contact, m.
    pub position_m: f64,
    /// Gain.
    pub gain: f64,
    /// Constant added, in the input's unit.
    pub offset: f64,
}

/// The inline `measured-profile` spectrum table of `profile` (an absolute path), column `track`.
fn measured_table(profile: &Path, track: &str, detrend: Detrend) -> toml::Value {
    let mut t = toml::Table::new();
    t.insert("kind".into(), "measured-profile".into());
    t.insert("file".into(), profile.to_string_lossy().into_owned().into());
    t.insert("track".into(), track.into());
    let d = match detrend {
        Detrend::Linear => "linear",
        Detrend::Mean => "mean",
    };
    t.insert("detrend".into(), d.into());
    toml::Value::Table(t)
}

/// The scenario text with every road spectrum replaced by the profile's measured density and every speed
/// by `speed`; also the column of the analytic route.
fn measured_text(
    scenario: &Scenario,
    profile: &Path,
    columns: &Profile,
    track: &str,
    opts: &ScenarioReplayOptions,
    speed: f64,
) -> Result<(String, String)> {
    let file = &scenario.path;
    let mut root: toml::Table = crate::fields::parse_toml(&scenario.text, file)?;
    // a `[road]` section is the one `[[input]]` table it stands for
    crate::scenario::inputs::road_section_as_input(&mut root, file)?;
    let replacement = Replacement {
        scenario,
        profile,
        columns,
        track,
        opts,
        speed_text: toml::Value::String(format!("{speed:?} m/s")),
    };
    let analytic_track = match root.get_mut("input") {
        Some(toml::Value::Table(t)) => replacement.one_input(t)?,
        Some(toml::Value::Array(tables)) => replacement.several_inputs(tables)?,
        _ => {
            return Err(Error::in_file(
                file,
                "input",
                "<missing>",
                "the scenario has no input to replay",
            ));
        }
    };
    let text = toml::to_string(&root).map_err(|e| {
        Error::in_file(
            file,
            "input",
            "…",
            format!("cannot rewrite the scenario with the measured density: {e}"),
        )
    })?;
    Ok((text, analytic_track))
}

/// What a replay puts in place of the scenario's road inputs: the measured density of the profile's
/// column(s) and the replay's speed.
struct Replacement<'a> {
    scenario: &'a Scenario,
    /// The profile file, and its columns.
    profile: &'a Path,
    columns: &'a Profile,
    /// The column under a road of one track.
    track: &'a str,
    opts: &'a ScenarioReplayOptions,
    speed_text: toml::Value,
}

impl Replacement<'_> {
    /// The error of an input that is not a road (its spectrum is temporal).
    fn not_a_road(&self, key: &str, reference: &str) -> Error {
        Error::in_file(
            &self.scenario.path,
            key,
            reference,
            "this input is not a road (its spectrum is temporal): a road profile cannot replay it",
        )
    }

    /// A column the replay needs (`what`: why) and the profile lacks, named with the profile file.
    fn need(&self, name: &str, what: &str) -> Result<()> {
        self.columns.track(name).map(|_| ()).map_err(|e| {
            let reason = match e {
                Error::InvalidParameter { reason, .. } => reason,
                other => other.to_string(),
            };
            Error::in_file(self.profile, "track", name, format!("{what}: {reason}"))
        })
    }

    /// The one `[input]` table `t` replaced; the column of the analytic route.
    fn one_input(&self, t: &mut toml::Table) -> Result<String> {
        let scenario = self.scenario;
        if scenario.input.spectrum.domain() != Domain::Spatial {
            return Err(self.not_a_road("input.spectrum", &scenario.input.reference));
        }
        self.need(
            self.track,
            "the road of the scenario's [input] runs on this track (--track)",
        )?;
        t.insert(
            "spectrum".into(),
            measured_table(self.profile, self.track, self.opts.detrend),
        );
        t.insert("speed".into(), self.speed_text.clone());
        Ok(self.track.to_string())
    }

    /// The `[[input]]` tables replaced (one road at most, of one track or two); the column of the analytic
    /// route.
    fn several_inputs(&self, tables: &mut [toml::Value]) -> Result<String> {
        let (scenario, profile, track, opts) = (self.scenario, self.profile, self.track, self.opts);
        let file = &scenario.path;
        let mut analytic_track = track.to_string();
        let mut roads = 0;
        for (i, v) in tables.iter_mut().enumerate() {
            let Some(t) = v.as_table_mut() else { continue };
            let inp = &scenario.inputs[i];
            if inp.spectrum.domain() != Domain::Spatial {
                return Err(self.not_a_road(&format!("input[{i}].spectrum"), &inp.reference));
            }
            roads += 1;
            if roads > 1 {
                return Err(Error::in_file(
                    file,
                    format!("input[{i}]"),
                    &inp.name,
                    "a second road input: one profile replays one road (the scenario's roads are \
                     independent sources, a replay would make them identical)",
                ));
            }
            if let Some(toml::Value::Table(road)) = t.get_mut("road") {
                if let Some(given) = &opts.track {
                    return Err(Error::invalid(
                        "--track",
                        given,
                        format!(
                            "input[{i}] is a road of two tracks, replayed on the profile's columns `left` and \
                             `right`; --track chooses the column under a road of one track: leave it out"
                        ),
                    ));
                }
                for side in ["left", "right"] {
                    self.need(side, &format!("input[{i}] is a road of two tracks, `left` and `right`"))?;
                }
                analytic_track = "left".into();
                road.insert("spectrum".into(), measured_table(profile, "left", opts.detrend));
            } else {
                self.need(track, &format!("input[{i}] is a road of one track (--track)"))?;
                t.insert("spectrum".into(), measured_table(profile, track, opts.detrend));
            }
            t.insert("speed".into(), self.speed_text.clone());
        }
        Ok(analytic_track)
    }
}

/// The wheel of every model input of the measured scenario `s` at speed `speed`.
fn wheels_of(s: &Scenario, track: &str, speed: f64) -> Result<Vec<Wheel>> {
    let file = &s.path;
    match &s.excitation {
        Excitation::Track {
            delays, gains, mean, ..
        } => Ok(delays
            .iter()
            .zip(gains)
            .map(|(&d, &g)| Wheel {
                track: track.to_string(),
                position_m: d * speed,
                gain: g,
                offset: g * mean,
            })
            .collect()),
        Excitation::Independent { .. } => Err(Error::in_file(
            file,
            "input",
            "independent processes",
            "each model input has its own independent process: a road profile cannot replay them",
        )),
        Excitation::Sources { sources, inputs } => inputs
            .iter()
            .enumerate()
            .map(|(j, m)| {
                let name = match &sources[m.source] {
                    Source::Matrix(_) => match m.component {
                        0 => "left",
                        1 => "right",
                        c => {
                            return Err(Error::in_file(
                                file,
                                format!("input[{}]", m.source),
                                c,
                                format!("model input {j}: a road has two tracks (left, right)"),
                            ))
                        }
                    },
                    Source::Process(_) => track,
                };
                Ok(Wheel {
                    track: name.to_string(),
                    position_m: m.delay * speed,
                    gain: m.gain,
                    offset: m.mean,
                })
            })
            .collect(),
    }
}

/// Replays the profile `profile_path` through the scenario `scenario` (spectra resolved as it was) and
/// computes, for each reported output, the analytic σ with the profile's own measured density.
///
/// # Formula
/// The wheels are the scenario's input map at speed v: model input j on track c_j (a road of two tracks:
/// `left`, `right`; one track: [`ScenarioReplayOptions::track`]) at position p_j = τ_j v behind the first
/// contact, u_j = g_j z_{c_j}(x − p_j) + g_j μ ([`crate::road::replay::replay()`]). The analytic σ is that of the
/// same scenario with the road's spectrum replaced by `{ kind = "measured-profile", file, track, detrend }`
/// and its speed by v ([`crate::response::analyze_output`]): the Welch estimate Ĝ_d(n) of the (detrended)
/// track, zero outside its bins; for two tracks the density of `left` with the scenario's coherence model.
///
/// # Errors
/// [`Error::File`] naming the scenario (an input that is not a road, two roads, independent processes,
/// no speed) or the profile (a missing track, too short for the wheelbase and the skipped length), and the
/// errors of [`crate::road::replay::replay()`].
pub fn replay_scenario(
    scenario: &Scenario,
    profile_path: &Path,
    opts: &ScenarioReplayOptions,
) -> Result<ScenarioReplay> {
    let speed = match opts.speed_m_s.or(scenario.input.speed) {
        Some(v) if v.is_finite() && v > 0.0 => v,
        Some(v) => return Err(Error::invalid("--speed", v, "must be a finite speed > 0 m/s")),
        None => {
            return Err(Error::in_file(
                &scenario.path,
                "input.speed",
                "<missing>",
                "the scenario gives no speed: pass --speed",
            ))
        }
    };
    let profile = Profile::read_csv(profile_path)?;
    require_representable(&profile, profile_path)?;
    let track = match &opts.track {
        Some(t) => t.clone(),
        None => profile.tracks[0].name.clone(),
    };
    let abs = std::fs::canonicalize(profile_path).map_err(|source| Error::Io {
        path: profile_path.to_path_buf(),
        source,
    })?;
    let (text, analytic_track) = measured_text(scenario, &abs, &profile, &track, opts, speed)?;
    let measured = parse_scenario(&text, &scenario.path, &scenario.spectra_dir).map_err(|e| match e {
        // the speed the text holds is --speed's when one was given
        Error::File { key, reason, .. } if opts.speed_m_s.is_some() && key.ends_with("speed") => {
            Error::invalid("--speed", crate::numbers::num(speed), format!("{reason} (m/s)"))
        }
        e => e,
    })?;
    let wheels = wheels_of(&measured, &track, speed)?;
    let ss = measured.model.system.state_space().ok_or_else(|| {
        Error::in_file(
            &scenario.path,
            "model.kind",
            &scenario.kind,
            "the model has no state-space form: it cannot be stepped in time",
        )
    })?;
    let detrended = profile.detrended(opts.detrend);
    let replay = crate::road::replay::replay(
        ss,
        &wheels,
        &detrended,
        profile_path,
        &ReplayOptions {
            speed_m_s: speed,
            skip_m: opts.skip_m,
            start: opts.start,
        },
    )
    .map_err(|e| match e {
        // the length skipped is --skip's
        Error::InvalidParameter { name, value, reason } if name == "skip" => Error::InvalidParameter {
            name: "--skip".into(),
            value,
            reason,
        },
        e => e,
    })?;
    require_finite_statistics(&replay, &profile, profile_path)?;
    let mut outputs = Vec::new();
    for &i in &scenario.analysis.outputs {
        let analytic_sigma = analyze_output(measured.model.system.as_ref(), &measured.excitation, i)?
            .sigma
            .filter(|s| s.is_finite());
        outputs.push(ReplayedOutput {
            index: i,
            replayed: replay.outputs[i].clone(),
            analytic_sigma,
        });
    }
    Ok(ScenarioReplay {
        scenario: scenario.path.clone(),
        title: scenario.title.clone(),
        profile: profile_path.to_path_buf(),
        detrend: opts.detrend,
        wheels: wheels
            .iter()
            .enumerate()
            .map(|(j, w)| ReplayWheel {
                input: j,
                track: w.track.clone(),
                position_m: w.position_m,
                gain: w.gain,
                offset: w.offset,
            })
            .collect(),
        replay,
        outputs,
        analytic_track,
    })
}

/// Refuses a profile whose elevations are too large for the statistics of a replay and of its measured
/// density to stay finite: every |z| must be below √(f64::MAX)/N (N samples), so that a sum of N squares
/// (σ, r.m.s., the Welch sums) stays below f64::MAX.
///
/// # Errors
/// [`Error::File`] naming the profile, the track and the largest |elevation|.
fn require_representable(profile: &Profile, file: &Path) -> Result<()> {
    let bound = f64::MAX.sqrt() / profile.len() as f64;
    if largest_elevation(profile).2.abs() < bound {
        return Ok(());
    }
    let n = crate::numbers::num;
    Err(elevation_error(profile, file, |at| {
        format!(
            "the elevation at distance {} m is beyond what the statistics of {} samples can hold in f64 (|z| < {} \
             m); check the column's values and unit",
            n(at),
            profile.len(),
            n(bound)
        )
    }))
}

/// The track, index and value of the largest |elevation| of `profile`.
fn largest_elevation(profile: &Profile) -> (&crate::road::Track, usize, f64) {
    profile
        .tracks
        .iter()
        .flat_map(|t| t.elevation_m.iter().enumerate().map(move |(k, z)| (t, k, *z)))
        .fold(None, |best: Option<(&crate::road::Track, usize, f64)>, c| match best {
            Some(b) if b.2.abs() >= c.2.abs() => Some(b),
            _ => Some(c),
        })
        .expect("a profile has a track of at least 2 samples")
}

/// An error naming the profile, the track of its largest |elevation| and that value, with the reason
/// `why(distance of that elevation, m)`.
fn elevation_error(profile: &Profile, file: &Path, why: impl FnOnce(f64) -> String) -> Error {
    let (track, k, z) = largest_elevation(profile);
    Error::in_file(
        file,
        format!("track `{}`", track.name),
        format!("{} m", crate::numbers::num(z)),
        why(profile.distance_m(k)),
    )
}

/// Refuses a replay whose statistics left the range of f64 (elevations so large that their squares or
/// the response overflow), naming the profile's largest elevation: its track, distance and value.
///
/// # Errors
/// [`Error::File`] naming the profile, the track and the largest |elevation|.
fn require_finite_statistics(replay: &Replay, profile: &Profile, file: &Path) -> Result<()> {
    let bad = replay.outputs.iter().find(|o| {
        let crest_ok = o.sigma == 0.0 || o.crest_factor.is_finite();
        !([o.mean, o.sigma, o.rms, o.min, o.max].iter().all(|v| v.is_finite()) && crest_ok)
    });
    let Some(o) = bad else { return Ok(()) };
    let n = crate::numbers::num;
    Err(elevation_error(profile, file, |at| {
        format!(
            "the replayed output `{}` leaves the range of f64 (mean {}, σ {}, r.m.s. {}): the largest elevation, \
             at distance {} m, is not a road's; check the column's values and unit",
            o.name,
            n(o.mean),
            n(o.sigma),
            n(o.rms),
            n(at)
        )
    }))
}
