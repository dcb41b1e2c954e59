//! The one registry of model kinds that a scenario file may name in `[model] kind`: the generic kinds and
//! every catalogue model. The list of known kinds in error messages, `stochvib models` and the docs' tables
//! are all derived from [`MODEL_KINDS`].

use super::generic;
use crate::error::{Error, Result};
use crate::fields::{Fields, KeyReading};
use crate::models::results::DeterministicModel;
use crate::models::{
    balancer_bogie, conveyor_idler, dynamic_stiffness_chain::DynamicStiffnessChain, half_car, isolation,
    mine_hoist::MineHoist, operator_seat, quarter_car::QuarterCar, scraper, three_mass_hoist::ThreeMassHoist,
    ModelInstance,
};
use crate::response::TransferBuilder;
use crate::system::StateSpace;
use serde::Serialize;

/// What a model may need from the rest of the scenario file.
#[derive(Debug, Clone, Copy, Default)]
pub struct ModelContext {
    /// `[input] speed` (or the common speed of the `[[input]]` tables), m/s.
    pub speed: Option<f64>,
    /// Whether the scenario has `[[input]]` tables (several independent sources), so that a model may mix
    /// inputs of different units (base displacements and forces).
    pub several_inputs: bool,
}

/// What a model kind builds from its `[model]` table.
#[derive(Debug)]
pub enum BuiltModel {
    /// A linear system with the layout of its random inputs: `analyze` reports response statistics and
    /// `simulate` runs Monte Carlo; the scenario needs an `[input]`.
    Stochastic(ModelInstance),
    /// A deterministic model (frequencies, modes, time histories, harmonic response): `analyze` prints its
    /// result tables; the scenario has no `[input]`.
    Deterministic(Box<dyn DeterministicModel>),
}

/// Generic (written out in the file) or a model of the source documents' catalogue.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// Matrices, elements or polynomials written in the scenario file.
    Generic,
    /// A model of the catalogue with physical parameters (`src/models/`).
    Catalogue,
}

/// One model kind.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ModelKind {
    /// The name written in `[model] kind`.
    pub name: &'static str,
    /// Generic or catalogue.
    pub family: Family,
    /// Whether the kind takes a random input (`analyze` statistics, `simulate`) or is deterministic.
    pub stochastic: bool,
    /// One line: what it is and where it comes from.
    pub summary: &'static str,
    /// A scenario file of the kind in `data/`.
    pub example: &'static str,
    #[serde(skip)]
    build: fn(&Fields, ModelContext) -> Result<BuiltModel>,
    /// The numeric builder of the kind, if it has one (parameter studies substitute numbers through it).
    #[serde(skip)]
    numeric: Option<NumericModel>,
}

/// The numeric builder of a stochastic model kind: what a parameter study uses instead of rebuilding the
/// model from its substituted `[model]` table at every point (see [`Sweep`](crate::study::Sweep)).
///
/// `keys` lists every key the kind's table reader accepts, with how it reads each; `fill` takes one value
/// per key (None: the key is absent from the table) and writes the state-space matrices that the table
/// reader's model would have into a state space of the kind's shape, or returns false where the reader or
/// the model would fail (the caller then takes the general path, which names the error). A kind has a
/// numeric builder only when its input layout, its output names and its state-space shape do not depend
/// on the values, and `fill` writes the same numbers as the general path (tests/fast_sweep.rs checks it).
/// A kind may also have closed-form transfer polynomials (the scraper kinds): their table values equal the
/// state-space route's within rounding, not bit for bit (tests/fast_sweep.rs checks every output of a grid
/// with stiff corners against the general path and Lyapunov).
#[derive(Debug, Clone, Copy)]
pub struct NumericModel {
    /// The keys of the kind's `[model]` table (besides `kind`) and how each is read.
    pub keys: &'static [(&'static str, KeyReading)],
    /// Writes the matrices for the values (one per key of `keys`) into `ss`; false: ask the general path.
    pub fill: fn(&[Option<f64>], &mut StateSpace) -> bool,
    /// The kind's closed-form transfer polynomials, if it has them: writes Δ(s) and every output's N_i(s)
    /// (the instance's output order, single input) for the values; false where `fill` is false. A study
    /// then evaluates the integral table on them directly (no state space, no Faddeev–LeVerrier pass per
    /// point) and uses `fill` only for an output whose table value fails its check (computed by Lyapunov).
    pub(crate) transfer: Option<TransferBuilder>,
}

impl ModelKind {
    /// Builds the model from its `[model]` table.
    ///
    /// # Errors
    /// [`Error::File`](crate::Error::File) naming the key, value and reason.
    pub fn build(&self, f: &Fields, ctx: ModelContext) -> Result<BuiltModel> {
        (self.build)(f, ctx)
    }

    /// The kind's numeric builder, if it has one (see [`NumericModel`]).
    pub fn numeric(&self) -> Option<&NumericModel> {
        self.numeric.as_ref()
    }
}

fn stochastic(r: Result<ModelInstance>) -> Result<BuiltModel> {
    r.map(BuiltModel::Stochastic)
}

fn deterministic<M: DeterministicModel + 'static>(r: Result<M>) -> Result<BuiltModel> {
    r.map(|m| BuiltModel::Deterministic(Box::new(m)))
}

/// Every model kind, generic first, then the catalogue in the order of the sources.
pub const MODEL_KINDS: &[ModelKind] = &[
    ModelKind {
        name: "mdof",
        family: Family::Generic,
        stochastic: true,
        summary: "multi-degree-of-freedom model from elements or full matrices, base inputs on a track",
        example: "data/quarter-car.toml",
        build: |f, ctx| stochastic(generic::mdof::from_fields_in(f, ctx.several_inputs)),
        numeric: None,
    },
    ModelKind {
        name: "transfer-function",
        family: Family::Generic,
        stochastic: true,
        summary: "rational transfer function N(s)/D(s), one input",
        example: "",
        build: |f, _| stochastic(generic::transfer_function::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "state-space",
        family: Family::Generic,
        stochastic: true,
        summary: "state space A, B, C, D, E (y = Cx + Du + E du/dt), inputs on a track",
        example: "",
        build: |f, _| stochastic(generic::state_space::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "quarter-car",
        family: Family::Catalogue,
        stochastic: true,
        summary: "quarter car: body on the suspension, wheel on the tyre, one road track",
        example: "data/quarter-car-model.toml",
        build: |f, _| stochastic(QuarterCar::from_fields(f).and_then(|c| c.instance())),
        numeric: None,
    },
    ModelKind {
        name: "isolator-single",
        family: Family::Catalogue,
        stochastic: true,
        summary: "single-stage vibration isolator (Sukharev 2012, 7.1)",
        example: "data/isolator-single.toml",
        build: |f, _| stochastic(isolation::from_fields_single(f)),
        numeric: None,
    },
    ModelKind {
        name: "isolator-two-stage",
        family: Family::Catalogue,
        stochastic: true,
        summary: "two-stage vibration isolator (Sukharev 2012, 7.2, eq. (7.16))",
        example: "data/isolator-two-stage.toml",
        build: |f, _| stochastic(isolation::from_fields_two_stage(f)),
        numeric: None,
    },
    ModelKind {
        name: "half-car",
        family: Family::Catalogue,
        stochastic: true,
        summary: "half car bounce and pitch with the wheelbase delay (Sukharev 2012, 7.5, Example 7.1)",
        example: "data/half-car.toml",
        build: |f, _| stochastic(half_car::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "full-vehicle",
        family: Family::Catalogue,
        stochastic: true,
        summary: "full vehicle, 7 DOF (bounce, pitch, roll, four unsprung masses) on two road tracks",
        example: "data/full-vehicle-two-tracks.toml",
        build: |f, _| stochastic(super::full_vehicle_keys::from_fields(f).and_then(|c| c.instance())),
        numeric: None,
    },
    ModelKind {
        name: "machine",
        family: Family::Catalogue,
        stochastic: true,
        summary: "machine assembly: body on axles (oscillating or suspended as options), cab on mounts, seat; two road tracks",
        example: "data/wheel-loader-cab-seat.toml",
        build: |f, _| stochastic(super::machine_keys::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "operator-seat",
        family: Family::Catalogue,
        stochastic: true,
        summary: "operator seat under cab-floor motion, octave bands (Sukharev 2012, 7.6, Example 7.2)",
        example: "data/operator-seat.toml",
        build: |f, _| stochastic(operator_seat::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "balancer-bogie",
        family: Family::Catalogue,
        stochastic: true,
        summary: "balancer bogie on a random road (Sukharev 2012, 8.5, eqs. (8.38)-(8.50))",
        example: "data/balancer-bogie.toml",
        build: |f, ctx| stochastic(balancer_bogie::from_fields(f, ctx.speed)),
        numeric: None,
    },
    ModelKind {
        name: "conveyor-idler",
        family: Family::Catalogue,
        stochastic: true,
        summary: "conveyor idler under a random lump load (Sukharev 2012, 8.6, Example 8.1)",
        example: "data/conveyor-idler.toml",
        build: |f, _| stochastic(conveyor_idler::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "scraper-rigid-cab",
        family: Family::Catalogue,
        stochastic: true,
        summary: "scraper with a rigid cab on a random road (Sukharev 2012, 8.7, eq. (8.64))",
        example: "data/scraper-rigid-cab.toml",
        build: |f, _| stochastic(scraper::rigid_from_fields(f)),
        numeric: Some(NumericModel {
            keys: scraper::RIGID_KEYS,
            fill: scraper::rigid_fill,
            transfer: Some(scraper::rigid_transfer),
        }),
    },
    ModelKind {
        name: "scraper-sprung-cab",
        family: Family::Catalogue,
        stochastic: true,
        summary: "scraper with a sprung cab on a random road (Sukharev 2012, 8.7, eq. (8.65))",
        example: "data/scraper-sprung-cab.toml",
        build: |f, _| stochastic(scraper::sprung_from_fields(f)),
        numeric: Some(NumericModel {
            keys: scraper::SPRUNG_KEYS,
            fill: scraper::sprung_fill,
            transfer: Some(scraper::sprung_transfer),
        }),
    },
    ModelKind {
        name: "three-mass-hoist",
        family: Family::Catalogue,
        stochastic: false,
        summary: "three-mass hoist at start-up: frequencies, static parts, link moments (Ofiy & Rakhmaniy 2010)",
        example: "data/three-mass-hoist.toml",
        build: |f, _| deterministic(ThreeMassHoist::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "dynamic-stiffness-chain",
        family: Family::Catalogue,
        stochastic: false,
        summary: "harmonic response of a torsional chain by dynamic stiffness (Yurchenko 2011)",
        example: "data/dynamic-stiffness-chain.toml",
        build: |f, _| deterministic(DynamicStiffnessChain::from_fields(f)),
        numeric: None,
    },
    ModelKind {
        name: "mine-hoist",
        family: Family::Catalogue,
        stochastic: false,
        summary: "single-end mine hoist: frequencies and modes over the lift, node (Dvornikov et al. 2014)",
        example: "data/mine-hoist.toml",
        build: |f, _| deterministic(MineHoist::from_fields(f)),
        numeric: None,
    },
];

/// The kind called `name`, if any.
pub fn model_kind(name: &str) -> Option<&'static ModelKind> {
    MODEL_KINDS.iter().find(|k| k.name == name)
}

/// The names of every kind, in registry order.
///
/// # Examples
/// ```
/// let names = stochvib::scenario::kind_names();
/// assert!(names.contains(&"mdof") && names.contains(&"mine-hoist"));
/// ```
pub fn kind_names() -> Vec<&'static str> {
    MODEL_KINDS.iter().map(|k| k.name).collect()
}

/// Builds the model of `[model]` (`f`) of kind `kind`.
///
/// # Errors
/// [`Error::File`](crate::Error::File) for an unknown kind (listing every known kind) or bad keys.
pub fn build_model(kind: &str, f: &Fields, ctx: ModelContext) -> Result<BuiltModel> {
    match model_kind(kind) {
        // every failure names the file: a model's own error (a badly scaled mass matrix, an unstable
        // system) is reported under the model's table with its kind
        Some(k) => k.build(f, ctx).map_err(|e| match e {
            e @ (Error::File { .. } | Error::Parse { .. } | Error::Io { .. }) => e,
            other => f.error(
                "kind",
                kind,
                format!("the model cannot be built from these parameters: {other}"),
            ),
        }),
        None => Err(f.error(
            "kind",
            kind,
            format!("unknown model kind; known kinds: {}", kind_names().join(", ")),
        )),
    }
}
