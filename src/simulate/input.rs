//! What a Monte Carlo run simulates: a system, its random excitation, the outputs to record, the names and
//! units of the input processes, and the provenance text stored with the run.

use crate::response::Excitation;
use crate::store::{Provenance, Signal};
use std::path::PathBuf;

/// One line per input process with its parameters, delays and gains: what identifies the excitation.
pub fn describe(exc: &Excitation) -> String {
    match exc {
        Excitation::Track {
            spectrum,
            delays,
            gains,
            mean,
        } => format!(
            "one process felt by {} input(s): {}; delays {delays:?} s; gains {gains:?}; mean {mean}",
            gains.len(),
            spectrum.describe()
        ),
        Excitation::Independent { spectra, means } => spectra
            .iter()
            .zip(means)
            .enumerate()
            .map(|(k, (s, m))| format!("input {k}: {}; mean {m}", s.describe()))
            .collect::<Vec<_>>()
            .join("\n"),
        Excitation::Sources { sources, inputs } => sources
            .iter()
            .enumerate()
            .map(|(k, s)| format!("source {k}: {}", s.describe()))
            .chain(inputs.iter().enumerate().map(|(j, m)| {
                format!(
                    "input {j}: source {} component {}, delay {} s, gain {}, mean {}",
                    m.source, m.component, m.delay, m.gain, m.mean
                )
            }))
            .collect::<Vec<_>>()
            .join("\n"),
    }
}
use crate::system::FrequencyResponse;

/// The signals a run records for the generators of a `Sources` excitation (one per component of each
/// source, in order): `source_s` for a single process; for a multi-component source `source_s_<name>`
/// per component (`source_0_left`, `source_0_right` for two tracks) — a spectral run synthesises
/// component k as Σ_l M_kl c_l from independent generators c_l (see the run notes), and the raw record
/// holds these mixed components. Other excitations: `input_k`, unit `unit`.
///
/// # Errors
/// None.
///
/// # Examples
/// ```
/// use stochvib::response::Excitation;
/// use stochvib::simulate::source_signals;
/// use stochvib::spectrum::{Domain, Exponential};
/// use std::sync::Arc;
/// let x = Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap());
/// let e = Excitation::independent(vec![x.clone(), x], vec![0.0, 0.0]).unwrap().to_sources();
/// assert_eq!(source_signals(&e, "m")[1].name, "source_1");
/// ```
pub fn source_signals(exc: &Excitation, unit: &str) -> Vec<Signal> {
    match exc {
        Excitation::Sources { sources, .. } => sources
            .iter()
            .enumerate()
            .flat_map(|(s, src)| match src {
                crate::response::Source::Process(_) => vec![Signal::new(&format!("source_{s}"), unit)],
                crate::response::Source::Matrix(m) => (0..m.n_components())
                    .map(|c| Signal::new(&format!("source_{s}_{}", m.component_name(c)), unit))
                    .collect(),
            })
            .collect(),
        _ => (0..exc.spectra().len())
            .map(|k| Signal::new(&format!("input_{k}"), unit))
            .collect(),
    }
}

/// The subject of a Monte Carlo run (built from a scenario by
/// [`Scenario::run_input`](crate::scenario::Scenario::run_input), or by hand).
///
/// # Examples
/// ```
/// use stochvib::response::Excitation;
/// use stochvib::simulate::RunInput;
/// use stochvib::spectrum::{Domain, Exponential};
/// use stochvib::store::Signal;
/// use stochvib::system::StateSpace;
/// use std::sync::Arc;
/// let sys = StateSpace::oscillator(10.0, 0.1).unwrap();
/// let exc = Excitation::single(Arc::new(Exponential::new(1.0, 2.0, Domain::Temporal).unwrap()), 0.0).unwrap();
/// let input = RunInput::new(&sys, &exc, vec![0], vec![Signal::new("force", "N/kg")], "unit oscillator");
/// assert_eq!(input.outputs, vec![0]);
/// ```
#[derive(Debug, Clone)]
pub struct RunInput<'a> {
    /// The system.
    pub system: &'a dyn FrequencyResponse,
    /// Its random excitation.
    pub excitation: &'a Excitation,
    /// Indices of the outputs to simulate (outputs with an infinite variance are skipped with the reason).
    pub outputs: Vec<usize>,
    /// Names and units of the independent input processes, recorded with raw realizations: one signal for
    /// a track (`road` for a road, `input` otherwise), `input_k` for independent processes.
    pub input_signals: Vec<Signal>,
    /// The scenario file's text, stored as the run file's `@scenario` (compared when resuming).
    pub scenario_text: String,
    /// What else the run was resolved from (the spectrum file's text, the model with its parameters, ...),
    /// stored in `/provenance`; the identifying parts are compared when an interrupted run is resumed, so a
    /// changed spectrum file is never mixed into an old run.
    pub provenance: Vec<Provenance>,
    /// The files the run was read from: the run file may not be one of them.
    pub source_files: Vec<PathBuf>,
    /// Verdict channels evaluated on every realization (ISO 2631-1 metrics, rainflow damage); empty for
    /// none.
    pub verdicts: super::VerdictChannels,
    /// Marginal kurtosis of the input processes, one entry per independent process the run draws (its
    /// generators: the excitation's spectra in the order of [`Excitation::spectra`]): empty (the default) or
    /// all `None` for Gaussian processes; `Some(κ)`, κ ≥ 3, for a Laplace moving average with that process's
    /// spectrum ([`LaplaceMovingAverage`](super::LaplaceMovingAverage)). A run with any `Some` is simulated on
    /// the spectral route, its `None` processes drawn the Laplace way with κ = 3 (the Gaussian law).
    pub kurtosis: Vec<Option<f64>>,
    /// Octave or one-third-octave band r.m.s. of every output from the realizations' Welch estimates
    /// (`[analysis] bands`; [`super::bands`]), or `None` (no band accumulators, the run file as without).
    pub bands: Option<super::RunBands>,
}

impl<'a> RunInput<'a> {
    /// Collects the parts of a run's subject.
    pub fn new(
        system: &'a dyn FrequencyResponse,
        excitation: &'a Excitation,
        outputs: Vec<usize>,
        input_signals: Vec<Signal>,
        scenario_text: impl Into<String>,
    ) -> Self {
        RunInput {
            system,
            excitation,
            outputs,
            input_signals,
            scenario_text: scenario_text.into(),
            provenance: vec![Provenance::identity("excitation", describe(excitation))],
            source_files: Vec::new(),
            verdicts: super::VerdictChannels::default(),
            kurtosis: Vec::new(),
            bands: None,
        }
    }

    /// Whether any input process is non-Gaussian (a `Some` in [`RunInput::kurtosis`]).
    pub fn is_non_gaussian(&self) -> bool {
        self.kurtosis.iter().any(Option::is_some)
    }

    /// The kurtosis as written in notes and the generator name: `κ` when every process has the same `Some(κ)`,
    /// else one entry per process (`3 (Gaussian)` for `None`), e.g. `[6, 3 (Gaussian)]`.
    pub(crate) fn kurtosis_text(&self) -> String {
        match self.kurtosis.first() {
            Some(Some(k)) if self.kurtosis.iter().all(|x| *x == Some(*k)) => format!("{k}"),
            _ => format!(
                "[{}] per input process",
                self.kurtosis
                    .iter()
                    .map(|k| k.map_or("3 (Gaussian)".to_string(), |k| format!("{k}")))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
    }
}
