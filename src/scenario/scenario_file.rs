//! Scenario files (`data/*.toml`): a model, its random input and what to report; or a deterministic model;
//! or a reference table of the sources.
//!
//! # Format
//! ```toml
//! title = "Quarter car on an ISO class C road"
//! source = "illustrative"
//!
//! [model]
//! kind = "mdof"                  # a kind of the registry: `stochvib models` lists them
//! ...                            # the model's keys (see the kind's module: scenario::generic, models::*)
//!
//! [input]                        # stochastic kinds only
//! spectrum = "iso8608-c"         # a catalogue name, a path, or an inline table of spectrum keys
//! speed = "20 m/s"               # needed for spatial spectra and for delays between wheels
//! mean = 0.0                     # mean of the input process (default 0), in the process's unit
//! kurtosis = 6                   # optional: a non-Gaussian input of this marginal kurtosis (>= 3)
//! band = ["0.011 cycles/m", "30 cycles/m"]   # optional: the input's band (super::input_filters)
//! enveloping = { kind = "moving-average", length = "0.25 m" }   # optional: a tyre's enveloping of a road
//!
//! [analysis]                     # optional
//! outputs = ["body", "travel"]   # default: every output
//! band = ["0.5 Hz", "80 Hz"]     # also report the band-limited σ
//! duration = "1 h"               # for exceedance probabilities and expected largest peaks (default 1 h);
//!                                # with its unit: a bare number is refused (it would be seconds)
//! bands = "third-octave"         # or "octave": IEC 61260-1 base-10 band r.m.s. table of every output
//!                                # (simulate: also band r.m.s. from the realizations, with intervals)
//! [analysis.levels]              # optional levels per output for Rice crossing rates
//! travel = ["5 cm", "8 cm"]
//! ```
//!
//! The model kinds are those of [`MODEL_KINDS`](super::MODEL_KINDS): the generic `mdof`,
//! `transfer-function` and `state-space` ([`super::generic`]) and the catalogue models ([`crate::models`]).
//! A deterministic kind (the hoists and the chain of the articles) takes no `[input]`; `stochvib analyze`
//! prints its results ([`Document::Deterministic`]). A file with a root key `reference` instead of a
//! `[model]` is a reference table of the sources ([`Document::Reference`], `data/reference/`).
//!
//! Several independent inputs (a road of two tracks with a coherence, a force, …) are written as
//! `[[input]]` tables instead of the one `[input]` ([`super::inputs`] describes them); each names the model
//! inputs it drives. A road of two tracks alone may be written as its own `[road]` section (`spectrum`,
//! `coherence`, `track_width`, `speed`), the one `[[input]]` table it stands for.
//!
//! `[input] kurtosis = κ` (κ ≥ 3; absent: Gaussian) makes the input a Laplace moving average with the same
//! spectrum and marginal kurtosis κ ([`LaplaceMovingAverage`](crate::simulate::LaplaceMovingAverage),
//! Bogsjö, Podgórski & Rychlik 2012). The analytic results (σ, densities, Rice rates of the Gaussian law)
//! do not change; Monte Carlo runs (`simulate`, `analyze --monte-carlo`) synthesise it on the spectral route,
//! store κ in the run's generator name and its identity (`input_kurtosis`) and note ν and each output's
//! kurtosis, and with comfort verdicts the predicted VDV (κ_w T)^{1/4}σ_w of each weighted output beside the
//! Monte Carlo VDV. An `[[input]]` table of one process takes `kurtosis` too (its source alone is
//! non-Gaussian); a road of two tracks refuses it ([`super::inputs`]).
//!
//! Spectra named in `[input] spectrum` are resolved by the one rule of [`Catalogue`]; the scenario keeps the
//! spectrum's unit, where it came from and the catalogue directory.

use super::catalogue::{Catalogue, SpectrumOrigin};
use super::reference::ReferenceTable;
use super::registry::{build_model, BuiltModel, ModelContext};
use crate::error::{Error, Result};
use crate::fields::Fields;
use crate::models::results::DeterministicModel;
use crate::models::{InputLayout, ModelInstance};
use crate::quad_oscillatory::OscillatoryOptions;
use crate::response::Excitation;
use crate::simulate::RunInput;
use crate::spectrum::{AtSpeed, Domain, Spectrum};
use crate::store::{Provenance, Signal};
use crate::transient::{Envelope, SpeedProfile};
use crate::units::Dim;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What to report besides the defaults.
#[derive(Debug, Clone, Default)]
pub struct AnalysisOptions {
    /// Indices of the outputs to report.
    pub outputs: Vec<usize>,
    /// Band [ω₁, ω₂] in rad/s for band-limited σ.
    pub band: Option<(f64, f64)>,
    /// Duration (s) for exceedance probabilities and expected largest peaks.
    pub duration: f64,
    /// (output index, levels in the output's SI unit).
    pub levels: Vec<(usize, Vec<f64>)>,
    /// Tolerance and limits of the quadratures (`[analysis.quadrature]`: `rel_tol`, `max_subintervals`,
    /// `max_half_periods`).
    pub effort: OscillatoryOptions,
    /// `[analysis.comfort]` and `[analysis.fatigue]` ([`super::verdict_spec`]).
    pub verdicts: super::verdict_spec::VerdictSpec,
    /// `[analysis] bands = "octave" | "third-octave"`: report each output's band table
    /// ([`crate::comfort::output_band_table`]) and, in Monte Carlo runs, the band r.m.s. estimates.
    pub bands: Option<crate::comfort::BandFraction>,
    /// `[analysis.mission]`: the duration and clearances of P(max |y| > b within T)
    /// ([`super::transient_keys::mission`]).
    pub mission: Option<super::transient_keys::MissionSpec>,
}

/// The random input of a scenario as written: the process, its unit and where it came from.
#[derive(Debug, Clone)]
pub struct ScenarioInput {
    /// The reference as written in `[input] spectrum` (a catalogue name or a path), or `inline`.
    pub reference: String,
    /// The process as given (a road in its spatial variable, before the speed turns it into time).
    pub spectrum: Arc<dyn Spectrum>,
    /// SI unit of the process (`m` for a road, `N` for a force, ...), from the spectrum file's `unit`.
    pub unit: String,
    /// Where the spectrum came from.
    pub origin: SpectrumOrigin,
    /// The spectrum file's text (the inline table's TOML for an inline spectrum).
    pub spectrum_text: String,
    /// `[input] speed`, m/s, if given.
    pub speed: Option<f64>,
    /// Mean of the process, in its unit.
    pub mean: f64,
    /// The name of the input's signal in run files: `road` or `input` for the single `[input]` table,
    /// `[[input]] name` (default `input_<i>`) for several.
    pub name: String,
    /// For a road of two tracks: the coherence model and track width, described.
    pub coherence: Option<String>,
    /// `[input] kurtosis` (or `[[input]] kurtosis` of a one-process table): the marginal kurtosis κ ≥ 3 of a
    /// non-Gaussian input (a Laplace moving average with
    /// the same spectrum, [`LaplaceMovingAverage`](crate::simulate::LaplaceMovingAverage)); `None` (key
    /// absent) for a Gaussian input. Monte Carlo runs honour it; the analytic statistics (σ, spectra) are the
    /// same for any κ.
    pub kurtosis: Option<f64>,
}

/// A loaded, validated stochastic scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The file.
    pub path: PathBuf,
    /// The file's text (stored with Monte Carlo runs).
    pub text: String,
    /// Title.
    pub title: String,
    /// Provenance.
    pub source: String,
    /// The model kind.
    pub kind: String,
    /// Model and input layout.
    pub model: ModelInstance,
    /// The random input as written (the first of [`Scenario::inputs`]).
    pub input: ScenarioInput,
    /// Every random input as written: the single `[input]`, or the `[[input]]` tables in order (one
    /// independent source each, [`super::inputs`]).
    pub inputs: Vec<ScenarioInput>,
    /// The catalogue directory the scenario's spectrum names were resolved in.
    pub spectra_dir: PathBuf,
    /// The excitation of the system's inputs.
    pub excitation: Excitation,
    /// Report options.
    pub analysis: AnalysisOptions,
    /// The nonlinear elements (`[[model.nonlinear]]`, [`super::nonlinear_keys`]) on `model`, whose system is
    /// then their linear part; `None` for a linear scenario.
    pub nonlinear: Option<Arc<crate::nonlinear::NonlinearModel>>,
    /// The non-stationary keys (`[input.speed_profile]`, `[input.envelope]`, `[transient]`,
    /// [`super::transient_keys`]); `None` when the scenario has none.
    pub transient: Option<Box<super::transient_keys::TransientSpec>>,
}

impl Scenario {
    /// The names and units of the input processes as a run records them: `road` (a spatial spectrum) or
    /// `input` for one process felt by every input, `input_k` for independent processes; the unit is the
    /// input spectrum's.
    pub fn input_signals(&self) -> Vec<Signal> {
        match &self.excitation {
            Excitation::Track { .. } => {
                let name = if self.input.spectrum.domain() == Domain::Spatial {
                    "road"
                } else {
                    "input"
                };
                vec![Signal::new(name, &self.input.unit)]
            }
            Excitation::Independent { spectra, .. } => (0..spectra.len())
                .map(|k| Signal::new(&format!("input_{k}"), &self.input.unit))
                .collect(),
            // `[[input]]` tables: one source each, named by the table (a road records its tracks)
            Excitation::Sources { sources, .. } if sources.len() == self.inputs.len() => sources
                .iter()
                .zip(&self.inputs)
                .flat_map(|(src, inp)| match src {
                    crate::response::Source::Process(_) => vec![Signal::new(&inp.name, &inp.unit)],
                    crate::response::Source::Matrix(m) => (0..m.n_components())
                        .map(|c| Signal::new(&format!("{}_{}", inp.name, m.component_name(c)), &inp.unit))
                        .collect(),
                })
                .collect(),
            Excitation::Sources { .. } => crate::simulate::source_signals(&self.excitation, &self.input.unit),
        }
    }

    /// The subject of a Monte Carlo run of this scenario: its system, excitation, the outputs of
    /// `[analysis]`, the input signals, the scenario text, and what else the run was resolved from — the
    /// spectrum file's text and origin, the model with its parameters, the excitation, and for a
    /// `measured-profile` spectrum the CSV's name, size and CRC-32 (`measured_profile`, `measured_profile_<i>`)
    /// — so that a resume never mixes a changed spectrum, profile or model into an old run.
    pub fn run_input(&self) -> RunInput<'_> {
        let mut input = RunInput::new(
            self.model.system.as_ref(),
            &self.excitation,
            self.analysis.outputs.clone(),
            self.input_signals(),
            self.text.clone(),
        );
        input.provenance.extend([
            Provenance::identity("spectrum", self.input.spectrum_text.clone()),
            Provenance::identity("model", self.model.description.clone()),
            Provenance::note(
                "spectrum_origin",
                serde_json::to_string(&self.input.origin).unwrap_or_default(),
            ),
        ]);
        // the further `[[input]]` tables' spectra (the first is `spectrum` above)
        for (i, inp) in self.inputs.iter().enumerate().skip(1) {
            input.provenance.extend([
                Provenance::identity(&format!("spectrum_{i}"), inp.spectrum_text.clone()),
                Provenance::note(
                    &format!("spectrum_origin_{i}"),
                    serde_json::to_string(&inp.origin).unwrap_or_default(),
                ),
            ]);
        }
        input.kurtosis = self.process_kurtosis();
        match (&self.excitation, self.input.kurtosis) {
            (Excitation::Sources { .. }, _) => {
                // `[[input]]` tables: the kurtosis of each table that gives one
                let given: Vec<String> = self
                    .inputs
                    .iter()
                    .enumerate()
                    .filter_map(|(i, inp)| inp.kurtosis.map(|k| format!("input[{i}] `{}`: {k}", inp.name)))
                    .collect();
                if !given.is_empty() {
                    input.provenance.push(Provenance::identity(
                        "input_kurtosis",
                        format!(
                            "{} (Laplace moving averages with their inputs' spectra; the other inputs Gaussian)",
                            given.join("; ")
                        ),
                    ));
                }
            }
            (_, Some(k)) => input.provenance.push(Provenance::identity(
                "input_kurtosis",
                format!("{k} (Laplace moving average with the input's spectrum)"),
            )),
            (_, None) => {}
        }
        // the CSV behind a `measured-profile` spectrum: its name, size and CRC-32 identify the run
        for (i, inp) in self.inputs.iter().enumerate() {
            let name = if i == 0 {
                "measured_profile".to_string()
            } else {
                format!("measured_profile_{i}")
            };
            input
                .provenance
                .extend(super::profile_identity::profile_provenance(inp, &self.path, &name));
        }
        // `[analysis] bands`: band r.m.s. from the realizations too, on the bands of the analytic table
        input.bands = self.analysis.bands.map(|fraction| crate::simulate::RunBands {
            fraction,
            range_hz: self
                .analysis
                .band
                .map(|(a, b)| (a / (2.0 * std::f64::consts::PI), b / (2.0 * std::f64::consts::PI))),
        });
        input.source_files = self.source_files();
        input
    }

    /// The files this scenario was read from: the measured profiles behind `measured-profile` spectra, the
    /// scenario file, the spectrum files it names (what a command's output must never replace: the output
    /// rule, [`crate::io_rules::check_output`]).
    pub fn source_files(&self) -> Vec<PathBuf> {
        let mut files: Vec<PathBuf> = self
            .inputs
            .iter()
            .filter_map(|inp| super::profile_identity::measured_profile_file(inp, &self.path).map(|f| f.1))
            .collect();
        files.push(self.path.clone());
        for inp in &self.inputs {
            if let SpectrumOrigin::Catalogue { file, .. } | SpectrumOrigin::File { path: file } = &inp.origin
                && !files.contains(file)
            {
                files.push(file.clone());
            }
        }
        files
    }

    /// The kurtosis of every independent process a run draws, in the order of
    /// [`Excitation::spectra`] ([`RunInput::kurtosis`]): `[input] kurtosis` for each of them; for `[[input]]`
    /// tables each table's `kurtosis` for its source's components; empty when every input is Gaussian.
    pub fn process_kurtosis(&self) -> Vec<Option<f64>> {
        let per: Vec<Option<f64>> = match &self.excitation {
            Excitation::Sources { sources, .. } if sources.len() == self.inputs.len() => sources
                .iter()
                .zip(&self.inputs)
                .flat_map(|(s, inp)| vec![inp.kurtosis; s.n_components()])
                .collect(),
            e => vec![self.input.kurtosis; e.spectra().len()],
        };
        if per.iter().any(Option::is_some) {
            per
        } else {
            Vec::new()
        }
    }

    /// An error of a Monte Carlo run of this scenario, naming the scenario's key where the run refused a
    /// value the file gave: a kurtosis above what the run's grid can represent
    /// ([`max_kurtosis`](crate::simulate::laplace::max_kurtosis)) becomes an [`Error::File`] naming
    /// `input.kurtosis` (or `input[i].kurtosis`); any other error is returned as it is.
    pub fn name_run_error(&self, e: Error) -> Error {
        let Error::InvalidParameter { name, value, reason } = &e else {
            return e;
        };
        if name != "kurtosis" {
            return e;
        }
        let shown = |k: f64| crate::numbers::num(k) == *value;
        let key = match &self.excitation {
            Excitation::Sources { .. } if self.inputs.len() > 1 => self
                .inputs
                .iter()
                .position(|i| i.kurtosis.is_some_and(shown))
                .map_or("input".to_string(), |i| format!("input[{i}].kurtosis")),
            _ => "input.kurtosis".to_string(),
        };
        Error::in_file(&self.path, key, value, reason.clone())
    }
}

/// A loaded deterministic scenario: a model without a random input.
#[derive(Debug)]
pub struct DeterministicScenario {
    /// The file.
    pub path: PathBuf,
    /// Title.
    pub title: String,
    /// Provenance.
    pub source: String,
    /// The model kind.
    pub kind: String,
    /// The model.
    pub model: Box<dyn DeterministicModel>,
}

/// Any file of `data/`.
#[derive(Debug)]
pub enum Document {
    /// A model with a random input.
    Stochastic(Box<Scenario>),
    /// A deterministic model.
    Deterministic(DeterministicScenario),
    /// A reference table of the sources.
    Reference(ReferenceTable),
}

fn read(path: &Path) -> Result<String> {
    crate::fields::read_text_file(path)
}

/// Loads any file of `data/` (see the module docs); spectra named by catalogue name are looked up in
/// `spectra_dir`.
///
/// # Errors
/// [`Error::Io`], [`Error::Parse`], or [`Error::File`] naming the key, value and reason.
pub fn load_document(path: &Path, spectra_dir: &Path) -> Result<Document> {
    parse_document(&read(path)?, path, spectra_dir)
}

/// Parses the text of any file of `data/` (see [`load_document`]).
///
/// # Errors
/// As [`load_document`].
pub fn parse_document(text: &str, path: &Path, spectra_dir: &Path) -> Result<Document> {
    let mut root: toml::Table = crate::fields::parse_toml(text, path)?;
    if super::inputs::road_section_as_input(&mut root, path)? {
        // errors name the keys as written: `road.<key>`, not the `[[input]]` table it stands for
        return parse_root(root, text, path, spectra_dir).map_err(super::inputs::road_section_keys);
    }
    parse_root(root, text, path, spectra_dir)
}

fn parse_root(root: toml::Table, text: &str, path: &Path, spectra_dir: &Path) -> Result<Document> {
    if root.contains_key("reference") && !root.contains_key("model") {
        return ReferenceTable::parse(text, path).map(Document::Reference);
    }
    let f = Fields::new(path, "", &root);
    let title = f.opt_string("title")?.unwrap_or("").to_string();
    let source = f.opt_string("source")?.unwrap_or("").to_string();
    let several_inputs = matches!(root.get("input"), Some(toml::Value::Array(_)));
    let (speed, speed_profile) = input_speed(&root, path)?;
    let mf = f.sub("model")?;
    let kind = mf.string("kind")?.to_string();
    let built = build_model(&kind, &mf, ModelContext { speed, several_inputs })?;
    let has_nonlinear = mf.get("nonlinear").is_some();
    let model = match built {
        BuiltModel::Deterministic(model) => {
            return deterministic_document(&f, &mf, &root, kind, model, has_nonlinear, (title, source));
        }
        BuiltModel::Stochastic(m) => m,
    };
    let (model, nonlinear, regime_outputs) = super::nonlinear_keys::attach(&mf, model)?;
    model_finish(&mf, &kind)?;
    check_model(&f, &kind, &model, nonlinear.is_none())?;
    let catalogue = Catalogue::new(spectra_dir);
    let (inputs, excitation, envelope) = match root.get("input") {
        Some(toml::Value::Array(tables)) => {
            let _ = f.get("input");
            let (n, layout) = (model.system.n_inputs(), &model.layout);
            let (inputs, excitation) = super::inputs::parse_inputs(&f, tables, n, layout, speed, &catalogue)?;
            (inputs, excitation, None)
        }
        _ => one_process(&f, &model, speed, &catalogue)?,
    };
    let mut analysis = analysis_section(&f, &model, speed, nonlinear.is_some())?;
    let transient = super::transient_keys::assemble(&f, speed_profile.map(|p| p.0), envelope)?;
    super::top_keys::TOP.finish(&f, &[])?;
    // every regime (contact, lift-off) is counted on an output: the outputs added for them are simulated
    for name in &regime_outputs {
        if let Ok(i) = model.system.output_index(name)
            && !analysis.outputs.contains(&i)
        {
            analysis.outputs.push(i);
        }
    }
    Ok(Document::Stochastic(Box::new(Scenario {
        path: path.to_path_buf(),
        text: text.to_string(),
        title,
        source,
        kind,
        model,
        input: inputs[0].clone(),
        inputs,
        spectra_dir: spectra_dir.to_path_buf(),
        excitation,
        analysis,
        nonlinear,
        transient,
    })))
}

/// A speed profile with the speed of the stationary analyses (m/s).
type ProfileAndSpeed = (SpeedProfile, f64);

/// The speed of the scenario (m/s): `[input] speed`, else the stationary speed of `[input.speed_profile]`
/// (with the profile), or the common speed of the `[[input]]` tables.
///
/// # Errors
/// A speed that is not > 0, a malformed profile, `[[input]]` tables of different speeds.
fn input_speed(root: &toml::Table, path: &Path) -> Result<(Option<f64>, Option<ProfileAndSpeed>)> {
    match root.get("input") {
        Some(toml::Value::Table(t)) => {
            let inf = Fields::new(path, "input", t);
            let v = inf.opt_quantity("speed", Dim::VELOCITY)?;
            if let Some(v) = v
                && (v.is_nan() || v <= 0.0)
            {
                return Err(inf.error("speed", v, "must be > 0"));
            }
            let profile = super::transient_keys::input_speed_profile(&inf)?;
            Ok((v.or(profile.as_ref().map(|p| p.1)), profile))
        }
        Some(toml::Value::Array(tables)) => {
            let profile = super::inputs::common_speed_profile(path, tables)?;
            let v = super::inputs::common_speed(path, tables)?;
            Ok((v.or(profile.as_ref().map(|p| p.1)), profile))
        }
        _ => Ok((None, None)),
    }
}

/// The document of a deterministic model: its `[model]` (`mf`) checked, no nonlinear elements, no `[input]`
/// or `[analysis]`; `header` is (title, source).
///
/// # Errors
/// An unknown key, nonlinear elements, an `[input]` or `[analysis]` section.
fn deterministic_document(
    f: &Fields,
    mf: &Fields,
    root: &toml::Table,
    kind: String,
    model: Box<dyn DeterministicModel>,
    has_nonlinear: bool,
    (title, source): (String, String),
) -> Result<Document> {
    model_finish(mf, &kind)?;
    if has_nonlinear {
        return Err(mf.error(
            "nonlinear",
            "[[model.nonlinear]]",
            format!("kind `{kind}` is a deterministic model: nonlinear elements need a model with a random input"),
        ));
    }
    for key in ["input", "analysis"] {
        if let Some(v) = root.get(key) {
            return Err(f.error(
                key,
                v,
                format!("kind `{kind}` is a deterministic model: it takes no [{key}] section"),
            ));
        }
    }
    f.finish()?;
    Ok(Document::Deterministic(DeterministicScenario {
        path: f.file().to_path_buf(),
        title,
        source,
        kind,
        model,
    }))
}

/// The one process of `[input]` (a table): its spectrum with the band and enveloping, mean, kurtosis and
/// envelope, and the excitation of the model's inputs at `speed`.
///
/// # Errors
/// The errors of each key (file, key, value, reason).
fn one_process(
    f: &Fields,
    model: &ModelInstance,
    speed: Option<f64>,
    catalogue: &Catalogue,
) -> Result<(Vec<ScenarioInput>, Excitation, Option<Envelope>)> {
    let inf = f.sub("input")?;
    let _ = inf.get("speed");
    let (reference, mut sf) = super::inputs::resolve_spectrum(&inf, "spectrum", catalogue, f.file().parent())?;
    sf.spectrum = super::input_filters::apply_input_keys(&inf, &sf, &reference)?;
    // the mean is in the input process's own unit: a number (SI) or a quantity of that dimension
    let mean = match inf.get("mean") {
        None => 0.0,
        Some(v) => quantity_in_unit(&inf, "mean", v, &sf.unit, &format!("the input process `{reference}`"))?,
    };
    let kurtosis = input_kurtosis(&inf)?;
    let _ = inf.get("speed_profile");
    let envelope = match inf.get("envelope") {
        None => None,
        Some(_) => Some(super::transient_keys::envelope(&inf.sub("envelope")?)?),
    };
    super::input_keys::PROCESS.finish(&inf, &[])?;
    let excitation = build_excitation(&inf, &model.layout, sf.spectrum.clone(), speed, mean)?;
    let name = if sf.spectrum.domain() == Domain::Spatial {
        "road"
    } else {
        "input"
    };
    let input = ScenarioInput {
        reference,
        spectrum: sf.spectrum,
        unit: sf.unit,
        origin: sf.origin,
        spectrum_text: sf.text,
        speed,
        mean,
        name: name.to_string(),
        coherence: None,
        kurtosis,
    };
    Ok((vec![input], excitation, envelope))
}

/// `[analysis]` with its verdicts (every output over 1 h when absent).
///
/// # Errors
/// The errors of each key; verdicts on a model with nonlinear elements. (A fatigue output of infinite λ₄ is
/// refused where it is evaluated, `study::fatigue_moments`: reading evaluates nothing.)
fn analysis_section(f: &Fields, model: &ModelInstance, speed: Option<f64>, nonlinear: bool) -> Result<AnalysisOptions> {
    if f.get("analysis").is_none() {
        return Ok(AnalysisOptions {
            outputs: (0..model.system.outputs().len()).collect(),
            duration: 3600.0,
            ..Default::default()
        });
    }
    let af = f.sub("analysis")?;
    let mut opts = analysis_options(&af, model)?;
    opts.verdicts = super::verdict_spec::parse_verdicts(&af, model, speed)?;
    if nonlinear && !opts.verdicts.is_empty() {
        return Err(af.error(
            "comfort",
            "[analysis.comfort] / [analysis.fatigue]",
            "verdicts are evaluated on linear models only: a model with [[model.nonlinear]] elements takes none",
        ));
    }
    super::analysis_keys::ANALYSIS.finish(&af, &[])?;
    Ok(opts)
}

/// The unknown-key check of `[model]` of kind `kind`: the table of its kind with the keys of every kind
/// ([`super::top_keys::MODEL`]).
///
/// # Errors
/// The first key of the table that the kind does not take.
fn model_finish(mf: &Fields, kind: &str) -> Result<()> {
    match super::model_keys::model_table(kind) {
        Some(table) => table.finish(mf, &super::top_keys::MODEL.names()),
        None => mf.finish(),
    }
}

/// `[input] kurtosis`: absent (Gaussian), or a finite number ≥ 3, else an error naming the file, the key, the
/// value and the reason.
pub(super) fn input_kurtosis(inf: &Fields) -> Result<Option<f64>> {
    let Some(v) = inf.get("kurtosis") else {
        return Ok(None);
    };
    let k = v
        .as_float()
        .or_else(|| v.as_integer().map(|n| n as f64))
        .ok_or_else(|| {
            inf.error(
                "kurtosis",
                v,
                "expected a number >= 3 (the marginal kurtosis E x⁴/(E x²)²)",
            )
        })?;
    if !(k.is_finite() && k >= 3.0) {
        return Err(inf.error(
            "kurtosis",
            v,
            "the kurtosis E x⁴/(E x²)² of a non-Gaussian (Laplace moving average) input must be finite and >= 3: \
             3 is the Gaussian road, larger values give heavier tails; omit the key for a Gaussian input",
        ));
    }
    Ok(Some(k))
}

/// Output names unique, and (`stable`) the system asymptotically stable (a stationary response exists), else
/// an error naming the file and the `[model]` table. A model with nonlinear elements is not checked for
/// stability here: its Gaussian equivalent's stability is route 1's outcome.
fn check_model(f: &Fields, kind: &str, model: &ModelInstance, stable: bool) -> Result<()> {
    let outs = model.system.outputs();
    if let Some(k) = (1..outs.len()).find(|&k| outs[..k].iter().any(|o| o.name == outs[k].name)) {
        return Err(f.error(
            "model.output",
            &outs[k].name,
            "two outputs have this name: every output needs its own name",
        ));
    }
    if let Some(ss) = model.system.state_space().filter(|_| stable) {
        ss.require_stable().map_err(|e| {
            let reason = match e {
                Error::InvalidParameter { value, reason, .. } => format!("{reason} ({value})"),
                other => other.to_string(),
            };
            // a transfer function's poles are the roots of its denominator: name it
            let denominator = f
                .get("model")
                .and_then(|m| m.get("denominator"))
                .filter(|_| kind == "transfer-function");
            match denominator {
                Some(d) => f.error(
                    "model.denominator",
                    d,
                    format!("{reason}: D(s) has a root with Re s ≥ 0 (a pole in the right half-plane or on the axis)"),
                ),
                None => f.error(
                    "model",
                    kind,
                    format!("{reason}: check the stiffnesses, dampings and masses (or poles) of the model"),
                ),
            }
        })?;
    }
    Ok(())
}

/// A value in the unit `unit` (of a process or an output): a plain number is taken as SI in that unit, a
/// string must carry a unit of the same dimension; NaN and infinities are refused.
pub(super) fn quantity_in_unit(f: &Fields, key: &str, v: &toml::Value, unit: &str, what: &str) -> Result<f64> {
    let x = match (v, crate::units::unit_dim(unit)) {
        (toml::Value::String(_), Some(dim)) => crate::units::parse_value(v, dim)
            .map_err(|reason| f.error(key, v, format!("{reason} ({what} is in {unit})")))?,
        (toml::Value::String(_), None) => {
            return Err(f.error(
                key,
                v,
                format!(
                    "{what} is in `{unit}`, which has no dimension to check a unit against: write a plain SI number"
                ),
            ))
        }
        (toml::Value::Float(_) | toml::Value::Integer(_), _) => {
            crate::units::parse_value(v, crate::units::Dim::DIMENSIONLESS).map_err(|reason| f.error(key, v, reason))?
        }
        _ => return Err(f.error(key, v, format!("expected a number or a quantity in {unit}"))),
    };
    Ok(x)
}

/// The reason of a failed spectrum resolution, without repeating the reference (the key error names it).
pub(super) fn resolution_reason(e: Error) -> String {
    match e {
        Error::InvalidParameter { reason, .. } => reason,
        other => other.to_string(),
    }
}

/// Loads a stochastic scenario file; spectra named by catalogue name are looked up in `spectra_dir`.
///
/// # Errors
/// [`Error::Io`], [`Error::Parse`], or [`Error::File`] naming the key, value and reason; a deterministic
/// model or a reference table is an [`Error::File`] saying what the file is.
pub fn load_scenario(path: &Path, spectra_dir: &Path) -> Result<Scenario> {
    parse_scenario(&read(path)?, path, spectra_dir)
}

/// Parses stochastic scenario text (see [`load_scenario`]).
///
/// # Errors
/// As [`load_scenario`].
pub fn parse_scenario(text: &str, path: &Path, spectra_dir: &Path) -> Result<Scenario> {
    match parse_document(text, path, spectra_dir)? {
        Document::Stochastic(sc) => Ok(*sc),
        Document::Deterministic(d) => Err(Error::File {
            file: path.to_path_buf(),
            key: "model.kind".into(),
            value: d.kind,
            reason: "a deterministic model without a random input: `stochvib analyze` prints its results; there is \
                     nothing to simulate"
                .into(),
        }),
        Document::Reference(r) => Err(Error::File {
            file: path.to_path_buf(),
            key: "reference".into(),
            value: r.reference,
            reason: "a reference table of the sources, not a scenario: `stochvib analyze` prints it".into(),
        }),
    }
}

pub(crate) fn build_excitation(
    f: &Fields,
    layout: &InputLayout,
    spectrum: Arc<dyn Spectrum>,
    speed: Option<f64>,
    mean: f64,
) -> Result<Excitation> {
    let temporal = |s: Arc<dyn Spectrum>| -> Result<Arc<dyn Spectrum>> {
        match (s.domain(), speed) {
            (Domain::Temporal, _) => Ok(s),
            (Domain::Spatial, Some(v)) => Ok(Arc::new(AtSpeed::new(s, v).map_err(|e| f.wrap("speed", e))?)),
            (Domain::Spatial, None) => Err(f.error(
                "speed",
                "<missing>",
                "the input spectrum is spatial (a road): give the speed to turn it into time",
            )),
        }
    };
    match layout {
        InputLayout::Single => Excitation::single(temporal(spectrum)?, mean).map_err(|e| f.wrap("spectrum", e)),
        InputLayout::Track { positions, gains } => {
            let delays = if positions.iter().all(|p| *p == 0.0) {
                vec![0.0; positions.len()]
            } else {
                let v = speed.ok_or_else(|| {
                    f.error(
                        "speed",
                        "<missing>",
                        "the wheels are at different positions: the delays need a speed",
                    )
                })?;
                positions.iter().map(|p| p / v).collect()
            };
            Excitation::track(temporal(spectrum)?, delays, gains.clone(), mean).map_err(|e| f.wrap("spectrum", e))
        }
        InputLayout::TwoTracks { .. } => Err(f.error(
            "spectrum",
            f.get("spectrum").map_or(String::new(), |v| v.to_string()),
            "the model stands on two tracks: write an [[input]] table with road = { spectrum, track_width, \
             coherence = { kind = \"dodds-robson\" } } instead of [input]",
        )),
    }
}

fn analysis_options(f: &Fields, model: &ModelInstance) -> Result<AnalysisOptions> {
    let names: Vec<String> = model.system.outputs().iter().map(|o| o.name.clone()).collect();
    let outputs = analysis_outputs(f, &names)?;
    let band = analysis_band(f)?;
    // the duration of the exceedance probabilities and expected peaks: with its unit (a bare `8` is not 8 h)
    let duration = f
        .opt_everyday_quantity("duration", crate::fields::EverydayUnit::HOUR)?
        .unwrap_or(3600.0);
    if duration.is_nan() || duration <= 0.0 {
        return Err(f.error("duration", duration, "must be > 0"));
    }
    let levels = analysis_levels(f, model, &names)?;
    let effort = match f.get("quadrature") {
        None => OscillatoryOptions::default(),
        Some(_) => quadrature_effort(&f.sub("quadrature")?)?,
    };
    let mission = match f.get("mission") {
        None => None,
        Some(_) => Some(super::transient_keys::mission(
            &f.sub("mission")?,
            model.system.outputs(),
        )?),
    };
    let bands = match f.get("bands") {
        None => None,
        Some(v) => Some(match v.as_str() {
            Some("octave") => crate::comfort::BandFraction::Octave,
            Some("third-octave") => crate::comfort::BandFraction::ThirdOctave,
            _ => {
                return Err(f.error(
                    "bands",
                    v,
                    "unknown band table: expected \"octave\" or \"third-octave\" (IEC 61260-1 base-10 bands)",
                ))
            }
        }),
    };
    Ok(AnalysisOptions {
        outputs,
        band,
        duration,
        levels,
        effort,
        verdicts: Default::default(),
        bands,
        mission,
    })
}

/// The index of the output `name` among `names`, else an error at `key` listing them.
fn output_position(f: &Fields, names: &[String], key: &str, name: &str) -> Result<usize> {
    names.iter().position(|x| x == name).ok_or_else(|| {
        f.error(
            key,
            name,
            format!("no such output; the model has: {}", names.join(", ")),
        )
    })
}

/// `[analysis] outputs`: the indices of the named outputs (every output when absent).
///
/// # Errors
/// Not an array of names, an empty array, an unknown name, a name twice.
fn analysis_outputs(f: &Fields, names: &[String]) -> Result<Vec<usize>> {
    let Some(v) = f.get("outputs") else {
        return Ok((0..names.len()).collect());
    };
    let arr = v
        .as_array()
        .ok_or_else(|| f.error("outputs", v, "expected an array of output names"))?;
    if arr.is_empty() {
        return Err(f.error(
            "outputs",
            v,
            format!(
                "names no output: leave the key out for every output ({})",
                names.join(", ")
            ),
        ));
    }
    let idx = arr
        .iter()
        .map(|x| {
            x.as_str()
                .ok_or_else(|| f.error("outputs", x, "expected a string"))
                .and_then(|n| output_position(f, names, "outputs", n))
        })
        .collect::<Result<Vec<_>>>()?;
    if let Some(k) = (1..idx.len()).find(|&k| idx[..k].contains(&idx[k])) {
        return Err(f.error("outputs", v, format!("names `{}` twice", names[idx[k]])));
    }
    Ok(idx)
}

/// `[analysis] band`: two frequencies (rad/s), if given.
///
/// # Errors
/// Not two frequencies, or not 0 ≤ low < high.
fn analysis_band(f: &Fields) -> Result<Option<(f64, f64)>> {
    let Some(v) = f.get("band") else {
        return Ok(None);
    };
    let arr = v
        .as_array()
        .filter(|a| a.len() == 2)
        .ok_or_else(|| f.error("band", v, "expected two frequencies"))?;
    let lo = f.angular_frequency(&arr[0], "band[0]", Dim::FREQUENCY)?;
    let hi = f.angular_frequency(&arr[1], "band[1]", Dim::FREQUENCY)?;
    if !(lo >= 0.0 && hi > lo) {
        return Err(f.error("band", v, "need 0 <= low < high"));
    }
    Ok(Some((lo, hi)))
}

/// `[analysis] levels`: per output the levels in its unit (SI).
///
/// # Errors
/// Not a table, an unknown output, a level that is not a value of the output's dimension.
fn analysis_levels(f: &Fields, model: &ModelInstance, names: &[String]) -> Result<Vec<(usize, Vec<f64>)>> {
    let mut levels = Vec::new();
    let Some(v) = f.get("levels") else {
        return Ok(levels);
    };
    let t = v
        .as_table()
        .ok_or_else(|| f.error("levels", v, "expected a table: output name = [levels]"))?;
    for (name, lv) in t {
        let key = format!("levels.{name}");
        let i = output_position(f, names, &key, name)?;
        let arr = lv.as_array().ok_or_else(|| f.error(&key, lv, "expected an array"))?;
        let unit = &model.system.outputs()[i].unit;
        let vals = arr
            .iter()
            .map(|x| quantity_in_unit(f, &key, x, unit, &format!("output `{name}`")))
            .collect::<Result<Vec<_>>>()?;
        levels.push((i, vals));
    }
    Ok(levels)
}

/// `[analysis.quadrature]` (`q`): the effort of the adaptive quadrature, the defaults where a key is absent.
///
/// # Errors
/// A count outside 1 … 10⁸, a tolerance the quadrature refuses, an unknown key.
fn quadrature_effort(q: &Fields) -> Result<OscillatoryOptions> {
    let d = OscillatoryOptions::default();
    let count = |key: &str, default: usize| -> Result<usize> {
        match q.get(key) {
            None => Ok(default),
            Some(v) => v
                .as_integer()
                .filter(|k| (1..=100_000_000).contains(k))
                .map(|k| k as usize)
                .ok_or_else(|| q.error(key, v, "expected a count from 1 to 10^8")),
        }
    };
    let effort = OscillatoryOptions {
        rel_tol: match q.get("rel_tol") {
            None => d.rel_tol,
            Some(_) => q.number("rel_tol")?,
        },
        max_subintervals: count("max_subintervals", d.max_subintervals)?,
        max_half_periods: count("max_half_periods", d.max_half_periods)?,
        ..d
    };
    effort.validate().map_err(|e| q.wrap_param(e, "rel_tol"))?;
    super::analysis_keys::QUADRATURE.finish(q, &[])?;
    Ok(effort)
}
