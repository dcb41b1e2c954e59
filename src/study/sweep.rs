//! Parameter studies: a scenario evaluated over a grid (cartesian product) or a list (zipped values) of
//! scenario keys, e.g. `model.suspension_stiffness=15 kN/m,20 kN/m,25 kN/m` and `input.speed=10..30:5 m/s`.
//!
//! # Keys and values
//! A key is the dotted path of a value of the scenario file (`model.omega2`, `input.speed`; an element of an
//! array of tables by its index, `model.element.0.stiffness`). Values are written as in scenario files, SI
//! numbers or quantities with units, in one of two forms ([`SweepParam::parse`]):
//!
//! * a list `V1,V2,…` (`20 kN/m,30 kN/m`, `0.1,0.2`);
//! * a range `A..B:n` of n values spaced evenly from A to B inclusive, or `A..B:n:log` spaced
//!   geometrically (A, B > 0), with one unit for both ends (`1 Hz..2.5 Hz:7`, `10..30:5 m/s`).
//!
//! [`SweepMode::Grid`] evaluates every combination (the first key varies slowest), [`SweepMode::Zip`] the
//! k-th values of every key together (the lists must have one length).
//!
//! # Evaluation
//! Each point is the scenario with the values substituted, evaluated by the exact routes of
//! [`ExactEvaluator`] (integral table or Lyapunov; quadrature only where no exact route exists) without the
//! cross-checks of `stochvib analyze`. When only `model.*` keys (and `input.speed`) vary, the model is
//! rebuilt from its substituted `[model]` table and the resolved spectrum is reused (no file is read per
//! point, and the input's shaping filter is factored once per distinct speed); any other key goes through
//! the scenario reader with the substituted text ([`Sweep::scenario_at`]), which gives the same scenario.
//!
//! When the model kind has a numeric builder ([`NumericModel`](crate::scenario::NumericModel)) and every key of the
//! `[model]` table and every swept `model.*` key is one of its keys, the study takes the numeric path
//! ([`SweepPath::Numeric`]): every value of every key is read once (as the model's reader reads it), and
//! per point the numbers are substituted and the state space is written in place (one per worker), then
//! evaluated as above — the same matrices, hence the same numbers, as the rebuilt model, without parsing,
//! names or descriptions per point. Where the kind also has closed-form transfer polynomials (the scraper
//! kinds), the numeric path writes Δ(s) and every output's N_i(s) directly in the swept values instead,
//! and the integral table runs on them (one Hurwitz elimination of Δ·F_den per point, a back substitution
//! per value, the pivot-ratio check on each; an output that fails it is computed by Lyapunov on the
//! state space and says `lyapunov`): no state space or Faddeev–LeVerrier pass per point. Its numbers equal
//! the general path's within rounding, not bit for bit (the polynomials are formed by other arithmetic).
//! A point the builder declines (a value its reader or the model refuses) takes the general path, which
//! names the error. [`Sweep::path`] says which path a study takes and why not the numeric one.

use crate::error::{Error, Result};
use crate::fields::Fields;
use crate::response::{
    lyapunov_point, ExactEvaluator, Excitation, PointStatistics, TransferBuilder, TransferPolynomials, VarianceMethod,
};
use crate::scenario::scenario_file::{build_excitation, parse_scenario, Scenario};
use crate::scenario::{build_model, BuiltModel, ModelContext};
use crate::system::StateSpace;
use crate::units::Dim;
use serde::Serialize;

/// How the values of several keys combine into points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum SweepMode {
    /// Every combination (cartesian product); the first key varies slowest.
    #[default]
    Grid,
    /// The k-th value of every key together; every key has the same number of values.
    Zip,
}

/// One swept key and its values as they are substituted into the scenario.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepParam {
    /// Dotted key, e.g. `model.omega2`.
    pub key: String,
    /// The values (TOML values: numbers, or strings with units).
    #[serde(serialize_with = "values_as_text")]
    pub values: Vec<toml::Value>,
}

fn values_as_text<S: serde::Serializer>(v: &[toml::Value], s: S) -> std::result::Result<S::Ok, S::Error> {
    s.collect_seq(v.iter().map(value_text))
}

/// A value as written in a table (strings without quotes).
pub fn value_text(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Splits `"2.5 Hz"` into (2.5, "Hz"): the longest leading number, then the unit text (trimmed).
fn number_and_unit(text: &str) -> Option<(f64, String)> {
    let t = text.trim();
    let mut best = None;
    for (i, _) in t.char_indices().skip(1).chain(std::iter::once((t.len(), ' '))) {
        if let Ok(x) = t[..i].trim().parse::<f64>()
            && !t[..i].contains(|c: char| c.is_alphabetic() && c != 'e' && c != 'E')
        {
            best = Some((x, t[i..].trim().to_string()));
        }
    }
    best
}

/// A list item as a TOML value: an integer, a float, a boolean, or a string (quotes optional).
fn item_value(text: &str) -> toml::Value {
    let t = text.trim();
    if let Ok(i) = t.parse::<i64>() {
        return toml::Value::Integer(i);
    }
    if let Ok(x) = t.parse::<f64>() {
        return toml::Value::Float(x);
    }
    match t {
        "true" => toml::Value::Boolean(true),
        "false" => toml::Value::Boolean(false),
        _ => toml::Value::String(t.trim_matches(|c| c == '"' || c == '\'').to_string()),
    }
}

/// Most values a range `A..B:n` may have (n ≤ 10⁶): the values of a key are held in memory.
pub const MAX_RANGE_VALUES: usize = 1_000_000;

/// Most points of a grid (2⁵³ ≈ 9·10¹⁵, so that a point index is exact as a number in every table): the
/// product of the numbers of values is checked against it without overflow.
pub const MAX_POINTS: usize = 1 << 53;

impl SweepParam {
    /// Parses `KEY=VALUES` (see the module docs).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `param`: no `=`, an empty key or value, a malformed range (ends
    /// that are not numbers, different units, fewer than 2 points, a geometric range through 0).
    ///
    /// # Examples
    /// ```
    /// use stochvib::study::SweepParam;
    /// let p = SweepParam::parse("model.omega2=1 Hz..2 Hz:3").unwrap();
    /// assert_eq!(p.key, "model.omega2");
    /// let v: Vec<String> = p.values.iter().map(stochvib::study::sweep_value_text).collect();
    /// assert_eq!(v, ["1 Hz", "1.5 Hz", "2 Hz"]);
    /// let q = SweepParam::parse("model.zeta2=0.2,0.3").unwrap();
    /// assert_eq!(q.values, vec![toml::Value::Float(0.2), toml::Value::Float(0.3)]);
    /// assert!(SweepParam::parse("model.zeta2").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<SweepParam> {
        let bad = |why: &str| Error::invalid("--param", text, why.to_string());
        let (key, values) = text
            .split_once('=')
            .ok_or_else(|| bad("expected KEY=VALUES, e.g. model.omega2=1 Hz,1.5 Hz or input.speed=10..30:5 m/s"))?;
        let key = key.trim();
        if key.is_empty() || key.split('.').any(|s| s.trim().is_empty()) {
            return Err(bad("the key must be a dotted path such as model.omega2"));
        }
        let values = values.trim();
        if values.is_empty() {
            return Err(bad("no values after `=`"));
        }
        let values = match values.split_once("..") {
            Some((a, rest)) => {
                let mut parts = rest.split(':');
                let b = parts.next().unwrap_or("");
                let n_text = parts
                    .next()
                    .ok_or_else(|| bad("a range is A..B:n (n values) or A..B:n:log, e.g. 1 Hz..2 Hz:5"))?;
                let mut log = false;
                let mut unit_after = String::new();
                // `n`, `n log`, `n:log`, or a unit after the count (`10..30:5 m/s`)
                let (n_str, tail) = match n_text.trim().split_once(char::is_whitespace) {
                    Some((n, t)) => (n, t.trim().to_string()),
                    None => (n_text.trim(), String::new()),
                };
                if !tail.is_empty() {
                    unit_after = tail;
                }
                for extra in parts {
                    match extra.trim() {
                        "log" => log = true,
                        "lin" => {}
                        other if other.starts_with("log") => {
                            log = true;
                            unit_after = other.trim_start_matches("log").trim().to_string();
                        }
                        _ => return Err(bad("a range ends with :n, :n:log or :n:lin")),
                    }
                }
                let n: usize = n_str.parse().map_err(|_| {
                    bad(&format!(
                        "the number of values after `:` must be an integer from 2 to {MAX_RANGE_VALUES}"
                    ))
                })?;
                if n < 2 {
                    return Err(bad("a range needs at least 2 values"));
                }
                if n > MAX_RANGE_VALUES {
                    return Err(bad(&format!(
                        "a range has at most {MAX_RANGE_VALUES} values (the values of one key are held in memory, \
                         about 60 bytes each); split the study into several ranges or use --shard"
                    )));
                }
                let (a, ua) = number_and_unit(a).ok_or_else(|| bad("the start of the range is not a number"))?;
                let (b, ub) = number_and_unit(b).ok_or_else(|| bad("the end of the range is not a number"))?;
                let units: Vec<&String> = [&ua, &ub, &unit_after].into_iter().filter(|u| !u.is_empty()).collect();
                if units.windows(2).any(|w| w[0] != w[1]) {
                    return Err(bad("both ends of a range need the same unit"));
                }
                let unit = units.first().map(|u| u.to_string()).unwrap_or_default();
                if !(a.is_finite() && b.is_finite()) || (log && !(a > 0.0 && b > 0.0)) {
                    return Err(bad("the ends must be finite (and > 0 for :log)"));
                }
                (0..n)
                    .map(|k| {
                        let x = if k == n - 1 {
                            b
                        } else if log {
                            a * (b / a).powf(k as f64 / (n - 1) as f64)
                        } else {
                            a + (b - a) * (k as f64) / ((n - 1) as f64)
                        };
                        if unit.is_empty() {
                            toml::Value::Float(x)
                        } else {
                            toml::Value::String(format!("{x} {unit}"))
                        }
                    })
                    .collect()
            }
            None => values.split(',').map(item_value).collect::<Vec<_>>(),
        };
        Ok(SweepParam {
            key: key.to_string(),
            values,
        })
    }
}

/// The swept keys, their values and how they combine.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepSpec {
    /// The keys and values, in the order given.
    pub params: Vec<SweepParam>,
    /// Grid or zip.
    pub mode: SweepMode,
}

impl SweepSpec {
    /// Checks the parameters: at least one, distinct keys, one length for [`SweepMode::Zip`].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `param`.
    pub fn new(params: Vec<SweepParam>, mode: SweepMode) -> Result<SweepSpec> {
        if params.is_empty() {
            return Err(Error::invalid(
                "--param",
                "<none>",
                "give at least one --param KEY=VALUES",
            ));
        }
        for (i, p) in params.iter().enumerate() {
            if params[..i].iter().any(|q| q.key == p.key) {
                return Err(Error::invalid("--param", &p.key, "the key is given twice"));
            }
        }
        // each key with its number of values, for the messages
        let counts = |sep: &str| {
            params
                .iter()
                .map(|p| format!("{}: {}", p.key, p.values.len()))
                .collect::<Vec<_>>()
                .join(sep)
        };
        if mode == SweepMode::Zip && params.iter().any(|p| p.values.len() != params[0].values.len()) {
            return Err(Error::invalid(
                "--param",
                counts(", "),
                "--zip needs the same number of values for every key",
            ));
        }
        if mode == SweepMode::Grid
            && crate::io_rules::checked_product(params.iter().map(|p| p.values.len())).is_none_or(|n| n > MAX_POINTS)
        {
            return Err(Error::invalid(
                "--param",
                counts(" × "),
                format!("the grid has more than {MAX_POINTS:e} points: fewer values, fewer keys, or --zip"),
            ));
        }
        Ok(SweepSpec { params, mode })
    }

    /// Number of points.
    pub fn n_points(&self) -> usize {
        match self.mode {
            SweepMode::Grid => self
                .params
                .iter()
                .map(|p| p.values.len())
                .fold(1, usize::saturating_mul),
            SweepMode::Zip => self.params[0].values.len(),
        }
    }

    /// The index of each key's value at point `point` (grid: mixed radix, the last key fastest).
    pub fn indices(&self, point: usize) -> Vec<usize> {
        let mut idx = vec![0; self.params.len()];
        self.indices_into(point, &mut idx);
        idx
    }

    /// [`indices`](Self::indices) written into `idx` (one slot per key).
    pub fn indices_into(&self, point: usize, idx: &mut [usize]) {
        match self.mode {
            SweepMode::Zip => idx.fill(point),
            SweepMode::Grid => {
                let mut rest = point;
                for (slot, p) in idx.iter_mut().zip(&self.params).rev() {
                    *slot = rest % p.values.len();
                    rest /= p.values.len();
                }
            }
        }
    }

    /// The values at point `point`, one per key.
    pub fn values(&self, point: usize) -> Vec<&toml::Value> {
        self.indices(point)
            .iter()
            .zip(&self.params)
            .map(|(&i, p)| &p.values[i])
            .collect()
    }
}

/// Sets the dotted `key` of `root` to `value` (an array element by its index).
pub(crate) fn set_key(root: &mut toml::Table, key: &str, value: toml::Value) -> std::result::Result<(), String> {
    let segs: Vec<&str> = key.split('.').map(str::trim).collect();
    let mut table = root;
    for (i, seg) in segs[..segs.len() - 1].iter().enumerate() {
        let next = table
            .get_mut(*seg)
            .ok_or_else(|| format!("the scenario has no `{}`", segs[..=i].join(".")))?;
        table = match next {
            toml::Value::Table(t) => t,
            toml::Value::Array(a) => {
                let k: usize = segs
                    .get(i + 1)
                    .and_then(|s| s.parse().ok())
                    .ok_or_else(|| format!("`{}` is an array: give an index", segs[..=i].join(".")))?;
                let len = a.len();
                let el = a
                    .get_mut(k)
                    .ok_or_else(|| format!("`{}` has {len} elements", segs[..=i].join(".")))?;
                if i + 2 == segs.len() {
                    *el = value;
                    return Ok(());
                }
                match el {
                    toml::Value::Table(t) => {
                        // skip the index segment
                        return set_key(t, &segs[i + 2..].join("."), value);
                    }
                    _ => return Err(format!("`{}.{k}` is not a table", segs[..=i].join("."))),
                }
            }
            _ => return Err(format!("`{}` is a value, not a table", segs[..=i].join("."))),
        };
    }
    table.insert(segs[segs.len() - 1].to_string(), value);
    Ok(())
}

/// The excitation at one speed, with its evaluator.
struct SpeedExcitation {
    speed: Option<f64>,
    excitation: Excitation,
    evaluator: ExactEvaluator,
}

/// How a point's excitation is obtained.
enum Excitations {
    /// Only `model.*` keys vary and the model's input layout stays the base's: the base excitation.
    Base(Box<ExactEvaluator>),
    /// `input.speed` varies too: one excitation per distinct speed value (index of its value), built at its
    /// first use (a study of 10⁶ speeds does not build 10⁶ excitations before its first point).
    PerSpeed { param: usize, cache: Vec<SpeedCache> },
}

/// The excitation of one speed value once built; `None` inside: that speed is refused.
type SpeedCache = std::sync::OnceLock<Option<Box<SpeedExcitation>>>;

/// Largest number of keys of a numeric builder (the values of a point live on the stack).
const MAX_NUMERIC_KEYS: usize = 16;

/// The numeric path of a study (module docs): every value read once, the state space written in place.
struct NumericPath {
    fill: fn(&[Option<f64>], &mut StateSpace) -> bool,
    /// The kind's closed-form transfer polynomials, if any (then the state space is written only for an
    /// output whose table value fails its check).
    transfer: Option<TransferBuilder>,
    /// The base table's value of every key of the builder (None: absent).
    base: Vec<Option<f64>>,
    /// Per swept key: the builder's index of the key and the value read at every value of the key (None:
    /// the reader fails there; the point then takes the general path, which names the error). None for
    /// `input.speed`.
    swept: Vec<Option<(usize, Vec<Option<f64>>)>>,
    /// The base model's state space (its shape and names; the numbers are overwritten per point).
    template: StateSpace,
    /// The indices of the outputs in the model.
    outputs: Vec<usize>,
}

/// Which way a study's points are computed ([`Sweep::path`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SweepPath {
    /// The kind's numeric builder ([`NumericModel`](crate::scenario::NumericModel)): per point the swept numbers are
    /// substituted and the state space is written in place; nothing is parsed or named per point.
    Numeric {
        /// The model kind.
        kind: String,
    },
    /// The model rebuilt from its substituted `[model]` table at every point, with the reason the numeric
    /// builder is not used.
    ModelTable {
        /// Why not numeric.
        reason: String,
    },
    /// The whole scenario re-read at every point, with the reason.
    Scenario {
        /// Why not numeric or by model table.
        reason: String,
    },
}

impl std::fmt::Display for SweepPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SweepPath::Numeric { kind } => write!(f, "numeric builder of `{kind}` (values read once)"),
            SweepPath::ModelTable { reason } => write!(f, "model rebuilt from its table per point ({reason})"),
            SweepPath::Scenario { reason } => write!(f, "scenario re-read per point ({reason})"),
        }
    }
}

/// A parameter study of one scenario (see the module docs).
pub struct Sweep<'a> {
    base: &'a Scenario,
    root: toml::Table,
    spec: SweepSpec,
    fast: Option<Excitations>,
    numeric: Option<NumericPath>,
    path: SweepPath,
    output_names: Vec<String>,
    /// The verdict columns of every point ([`with_verdicts`](Sweep::with_verdicts)); empty: none.
    verdicts: Vec<crate::optimize::Quantity>,
}

impl std::fmt::Debug for Sweep<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Sweep")
            .field("scenario", &self.base.path)
            .field("spec", &self.spec)
            .field("path", &self.path)
            .finish()
    }
}

impl<'a> Sweep<'a> {
    /// Prepares the study of `base` over `spec` and checks the first point (so that a misspelt key or a
    /// value of the wrong unit fails at once, naming the key).
    ///
    /// # Errors
    /// A key that is not in the scenario's tables; the first point's scenario errors ([`Error::File`]
    /// naming the key and value).
    ///
    /// # Examples
    /// ```
    /// use stochvib::scenario::load_scenario;
    /// use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec};
    /// use std::path::Path;
    /// let sc = load_scenario(Path::new("data/scraper-sprung-cab.toml"), Path::new("spectra")).unwrap();
    /// let spec = SweepSpec::new(vec![SweepParam::parse("model.omega2=1 Hz,2 Hz").unwrap()], SweepMode::Grid).unwrap();
    /// let sweep = Sweep::new(&sc, spec).unwrap();
    /// let stiffer = sweep.evaluate(1).unwrap();
    /// let softer = sweep.evaluate(0).unwrap();
    /// let x2_acc = sweep.outputs().iter().position(|o| o == "x2_acc").unwrap();
    /// assert!(stiffer[x2_acc].sigma().unwrap() > softer[x2_acc].sigma().unwrap()); // a stiffer cab mount shakes more
    /// ```
    pub fn new(base: &'a Scenario, spec: SweepSpec) -> Result<Sweep<'a>> {
        let root = crate::fields::parse_toml(&base.text, &base.path)?;
        for p in &spec.params {
            let mut probe = root.clone();
            set_key(&mut probe, &p.key, p.values[0].clone()).map_err(|why| Error::invalid("--param", &p.key, why))?;
        }
        let model_only = |k: &str| k.starts_with("model.");
        let speed = spec.params.iter().position(|p| p.key == "input.speed");
        let fast = if spec.params.iter().all(|p| model_only(&p.key) || p.key == "input.speed")
            && root.get("model").is_some_and(|m| m.is_table())
        {
            Some(match speed {
                None => Excitations::Base(Box::new(ExactEvaluator::new(&base.excitation))),
                Some(k) => Excitations::PerSpeed {
                    param: k,
                    cache: Vec::new(),
                },
            })
        } else {
            None
        };
        let names = base.model.system.outputs();
        let output_names = base.analysis.outputs.iter().map(|&i| names[i].name.clone()).collect();
        let mut sweep = Sweep {
            base,
            root,
            spec,
            fast,
            numeric: None,
            path: SweepPath::Scenario {
                reason: "a key outside `model.*` and `input.speed` varies".into(),
            },
            output_names,
            verdicts: Vec::new(),
        };
        if let Some(Excitations::PerSpeed { param, .. }) = &sweep.fast {
            let param = *param;
            let n = sweep.spec.params[param].values.len();
            let cache = (0..n).map(|_| SpeedCache::new()).collect();
            sweep.fast = Some(Excitations::PerSpeed { param, cache });
        }
        if sweep.fast.is_some() {
            sweep.path = match sweep.numeric_path() {
                Ok(p) => {
                    sweep.numeric = Some(p);
                    SweepPath::Numeric {
                        kind: base.kind.clone(),
                    }
                }
                Err(reason) => SweepPath::ModelTable { reason },
            };
        }
        sweep.scenario_at(0).map_err(|e| sweep.name_point_error(0, e))?;
        sweep.evaluate(0).map_err(|e| sweep.name_first_point_error(e))?;
        Ok(sweep)
    }

    /// An error of the study's first point, evaluated before the study starts: a key of the file or a flag
    /// as [`name_point_error`](Self::name_point_error) names it; any other error (a moment quadrature that
    /// does not converge, an output the substituted model lacks) is `--param` with the point's values, the
    /// scenario file and the point in the reason.
    fn name_first_point_error(&self, e: Error) -> Error {
        match self.name_point_error(0, e) {
            e @ Error::File { .. } => e,
            Error::InvalidParameter { name, value, reason } if name.starts_with("--") => {
                Error::InvalidParameter { name, value, reason }
            }
            other => {
                let at: Vec<String> = self
                    .spec
                    .params
                    .iter()
                    .zip(self.spec.indices(0))
                    .map(|(p, i)| format!("{}={}", p.key, value_text(&p.values[i])))
                    .collect();
                Error::invalid(
                    "--param",
                    at.join(" "),
                    format!("point 0 of the study of {}: {other}", self.base.path.display()),
                )
            }
        }
    }

    /// An error of point `point` about a key the study varies (the key, or a key inside it), named as the
    /// user wrote it: `--param KEY=VALUE` with the value at that point, instead of the scenario file's key
    /// (the file does not hold that value); any other error unchanged.
    pub fn name_point_error(&self, point: usize, e: Error) -> Error {
        let Error::File { file, key, reason, .. } = &e else {
            return e;
        };
        // `model.element[0].stiffness` as a sweep key is `model.element.0.stiffness`
        let key = key.replace('[', ".").replace(']', "");
        let inside = |p: &SweepParam| key == p.key || key.starts_with(&format!("{}.", p.key));
        let Some(k) = self
            .spec
            .params
            .iter()
            .position(inside)
            .filter(|_| *file == self.base.path)
        else {
            return e;
        };
        let p = &self.spec.params[k];
        let value = value_text(&p.values[self.spec.indices(point)[k]]);
        Error::invalid(
            "--param",
            format!("{}={value}", p.key),
            format!("{reason} (point {point} of the study)"),
        )
    }

    /// The numeric path of this study, or why there is none.
    fn numeric_path(&self) -> std::result::Result<NumericPath, String> {
        let kind = &self.base.kind;
        let numeric = crate::scenario::model_kind(kind)
            .and_then(|k| k.numeric())
            .ok_or_else(|| format!("kind `{kind}` has no numeric builder"))?;
        let keys = numeric.keys;
        if keys.len() > MAX_NUMERIC_KEYS {
            return Err(format!("kind `{kind}` has more than {MAX_NUMERIC_KEYS} keys"));
        }
        let table = self.root["model"].as_table().cloned().unwrap_or_default();
        let f = Fields::new(&self.base.path, "model", &table);
        let mut base = vec![None; keys.len()];
        for (k, _) in &table {
            if k == "kind" {
                continue;
            }
            let i = keys
                .iter()
                .position(|(name, _)| name == k)
                .ok_or_else(|| format!("`model.{k}` is not a numeric key of `{kind}`"))?;
            base[i] = Some(f.read(k, keys[i].1).map_err(|e| e.to_string())?);
        }
        let mut swept = Vec::with_capacity(self.spec.params.len());
        for p in &self.spec.params {
            if p.key == "input.speed" {
                swept.push(None);
                continue;
            }
            let name = p.key.strip_prefix("model.").unwrap_or(&p.key);
            let i = keys
                .iter()
                .position(|(k, _)| *k == name)
                .ok_or_else(|| format!("`{}` is not a numeric key of `{kind}`", p.key))?;
            let values = p
                .values
                .iter()
                .map(|v| {
                    let mut one = toml::Table::new();
                    one.insert(name.to_string(), v.clone());
                    Fields::new(&self.base.path, "model", &one).read(name, keys[i].1).ok()
                })
                .collect();
            swept.push(Some((i, values)));
        }
        let template = self
            .base
            .model
            .system
            .state_space()
            .cloned()
            .ok_or_else(|| format!("the model of kind `{kind}` has no state-space form"))?;
        Ok(NumericPath {
            fill: numeric.fill,
            transfer: numeric.transfer,
            base,
            swept,
            template,
            outputs: self.check_outputs(&self.base.model).map_err(|e| e.to_string())?,
        })
    }

    /// Which way the points are computed, with the reason when it is not the numeric builder.
    pub fn path(&self) -> &SweepPath {
        &self.path
    }

    /// The swept keys and values.
    pub fn spec(&self) -> &SweepSpec {
        &self.spec
    }

    /// The base scenario.
    pub fn scenario(&self) -> &Scenario {
        self.base
    }

    /// The names of the outputs evaluated at every point (the scenario's `[analysis] outputs`).
    pub fn outputs(&self) -> &[String] {
        &self.output_names
    }

    /// The study with the verdict columns of `stochvib sweep --verdicts` at every point
    /// ([`verdict_quantities`](super::sweep_verdicts::verdict_quantities)): every table, shard file and
    /// merge of it carries them.
    ///
    /// # Errors
    /// None expected (every name is taken from the scenario).
    pub fn with_verdicts(mut self) -> Result<Self> {
        self.verdicts = super::sweep_verdicts::verdict_quantities(self.base)?;
        Ok(self)
    }

    /// The verdict columns (empty without [`with_verdicts`](Self::with_verdicts)).
    pub fn verdicts(&self) -> &[crate::optimize::Quantity] {
        &self.verdicts
    }

    /// The scenario's root table with point `point`'s values substituted.
    pub fn table_at(&self, point: usize) -> Result<toml::Table> {
        let mut root = self.root.clone();
        for (p, v) in self.spec.params.iter().zip(self.spec.values(point)) {
            set_key(&mut root, &p.key, v.clone()).map_err(|why| Error::invalid("--param", &p.key, why))?;
        }
        Ok(root)
    }

    /// The scenario of point `point`: the substituted text read by the scenario reader (so that
    /// `stochvib analyze` of that text gives the same scenario).
    ///
    /// # Errors
    /// The scenario reader's errors for the substituted values.
    pub fn scenario_at(&self, point: usize) -> Result<Scenario> {
        let text = toml::to_string(&self.table_at(point)?).map_err(|e| Error::Numerical {
            what: "writing the substituted scenario".into(),
            reason: e.to_string(),
        })?;
        parse_scenario(&text, &self.base.path, &self.base.spectra_dir)
    }

    /// The excitation at value `v` of the speed key `param` from `cache`, built at its first use; `None` for
    /// a speed that is refused ([`speed_excitation`](Self::speed_excitation) gives the error).
    fn speed_entry<'s>(&self, cache: &'s [SpeedCache], param: usize, v: usize) -> Option<&'s SpeedExcitation> {
        cache
            .get(v)?
            .get_or_init(|| self.speed_excitation(param, v).ok().map(Box::new))
            .as_deref()
    }

    /// The excitation of the base model's input layout at value `v` of the speed parameter `param`.
    fn speed_excitation(&self, param: usize, v: usize) -> Result<SpeedExcitation> {
        let mut input = self
            .root
            .get("input")
            .and_then(|i| i.as_table())
            .cloned()
            .unwrap_or_default();
        input.insert("speed".into(), self.spec.params[param].values[v].clone());
        let f = Fields::new(&self.base.path, "input", &input);
        let speed = f.opt_quantity("speed", Dim::VELOCITY)?;
        if let Some(s) = speed
            && (s.is_nan() || s <= 0.0)
        {
            return Err(f.error("speed", s, "must be > 0"));
        }
        let exc = build_excitation(
            &f,
            &self.base.model.layout,
            self.base.input.spectrum.clone(),
            speed,
            self.base.input.mean,
        )?;
        Ok(SpeedExcitation {
            speed,
            evaluator: ExactEvaluator::new(&exc),
            excitation: exc,
        })
    }

    /// The exact statistics of every output at point `point`, in the order of [`outputs`](Self::outputs).
    ///
    /// # Errors
    /// The substituted scenario's errors (a value out of range, an unstable model), the evaluator's errors.
    pub fn evaluate(&self, point: usize) -> Result<Vec<PointStatistics>> {
        let mut scratch = self.numeric.as_ref().map(|n| n.template.clone());
        let mut out = Vec::new();
        self.evaluate_in(point, scratch.as_mut(), &mut out)?;
        Ok(out)
    }

    /// [`evaluate`](Self::evaluate) into `out` (cleared first), with a state space to write the numeric
    /// path's matrices into.
    fn evaluate_in(
        &self,
        point: usize,
        scratch: Option<&mut StateSpace>,
        out: &mut Vec<PointStatistics>,
    ) -> Result<()> {
        self.evaluate_point(point, scratch, out)
            .map_err(|e| self.name_point_error(point, e))
    }

    /// [`evaluate_in`](Self::evaluate_in) with the errors as the evaluation gives them.
    fn evaluate_point(
        &self,
        point: usize,
        scratch: Option<&mut StateSpace>,
        out: &mut Vec<PointStatistics>,
    ) -> Result<()> {
        out.clear();
        if let (Some(num), Some(ss), Some(fast)) = (&self.numeric, scratch, &self.fast)
            && let Some(r) = self.numeric_at(point, num, ss, fast, out)
        {
            return r;
        }
        *out = self.evaluate_general(point)?;
        Ok(())
    }

    /// The statistics of point `point` by the numeric path alone ([`SweepPath::Numeric`]), or None where it
    /// does not apply: the study has no numeric path, or the builder declines this point (a value its
    /// reader or the model refuses, a speed whose excitation failed), and [`evaluate`](Self::evaluate)
    /// then takes [`evaluate_general`](Self::evaluate_general), which names the error.
    ///
    /// # Errors
    /// The evaluator's errors (an unstable model) inside the `Some`.
    pub fn evaluate_numeric(&self, point: usize) -> Option<Result<Vec<PointStatistics>>> {
        let (num, fast) = (self.numeric.as_ref()?, self.fast.as_ref()?);
        let mut ss = num.template.clone();
        let mut out = Vec::new();
        Some(self.numeric_at(point, num, &mut ss, fast, &mut out)?.map(|()| out))
    }

    /// The numeric path at `point` with `ss` to write into, the statistics pushed to `out` (empty) (see
    /// [`evaluate_numeric`](Self::evaluate_numeric)).
    fn numeric_at(
        &self,
        point: usize,
        num: &NumericPath,
        ss: &mut StateSpace,
        fast: &Excitations,
        out: &mut Vec<PointStatistics>,
    ) -> Option<Result<()>> {
        let mut values = [None; MAX_NUMERIC_KEYS];
        values[..num.base.len()].copy_from_slice(&num.base);
        let mut speed_index = None;
        // the value index of every key (grid: mixed radix, the last key fastest)
        let mut rest = point;
        for (k, p) in self.spec.params.iter().enumerate().rev() {
            let v = match self.spec.mode {
                SweepMode::Zip => point,
                SweepMode::Grid => {
                    let v = rest % p.values.len();
                    rest /= p.values.len();
                    v
                }
            };
            match &num.swept[k] {
                Some((i, read)) => values[*i] = Some((*read.get(v)?)?),
                None => speed_index = Some(v),
            }
        }
        let values = &values[..num.base.len()];
        let (ev, exc) = match (fast, speed_index) {
            (Excitations::Base(ev), _) => (&**ev, &self.base.excitation),
            (Excitations::PerSpeed { param, cache }, Some(v)) => {
                let e = self.speed_entry(cache, *param, v)?;
                (&e.evaluator, &e.excitation)
            }
            (Excitations::PerSpeed { .. }, None) => return None,
        };
        if let Some(transfer) = num.transfer {
            let mut tp = TransferPolynomials::zero();
            if !transfer(values, &mut tp) {
                return None;
            }
            match ev.evaluate_transfer(&tp, &num.outputs, out) {
                Some(Ok(())) => {
                    // an output whose table value failed its check: Lyapunov on the state space
                    let mut filled = false;
                    for (st, &i) in out.iter_mut().zip(&num.outputs) {
                        if st.method == VarianceMethod::Lyapunov {
                            if !filled {
                                if !(num.fill)(values, ss) {
                                    return None;
                                }
                                filled = true;
                            }
                            *st = match lyapunov_point(&*ss, exc, i) {
                                Ok(s) => s,
                                Err(e) => return Some(Err(e)),
                            };
                        }
                    }
                    return Some(Ok(()));
                }
                Some(Err(e)) => return Some(Err(e)),
                None => out.clear(),
            }
        }
        if !(num.fill)(values, ss) {
            return None;
        }
        Some(ev.evaluate(&*ss, exc, &num.outputs).map(|v| *out = v))
    }

    /// The statistics of point `point` by the general path, whatever [`path`](Self::path) says: the model
    /// rebuilt from its substituted `[model]` table (or the scenario re-read when keys outside `model.*` and
    /// `input.speed` vary). The reference the numeric path is tested against.
    ///
    /// # Errors
    /// As [`evaluate`](Self::evaluate).
    pub fn evaluate_general(&self, point: usize) -> Result<Vec<PointStatistics>> {
        self.general_point(point).map_err(|e| self.name_point_error(point, e))
    }

    /// [`evaluate_general`](Self::evaluate_general) with the errors as the evaluation gives them.
    fn general_point(&self, point: usize) -> Result<Vec<PointStatistics>> {
        let Some(fast) = &self.fast else {
            let sc = self.scenario_at(point)?;
            let outputs = self.check_outputs(&sc.model)?;
            return ExactEvaluator::new(&sc.excitation).evaluate(sc.model.system.as_ref(), &sc.excitation, &outputs);
        };
        let values = self.spec.values(point);
        let idx = self.spec.indices(point);
        let mut model_table = self.root["model"].as_table().cloned().unwrap_or_default();
        for (p, v) in self.spec.params.iter().zip(&values) {
            if let Some(rest) = p.key.strip_prefix("model.") {
                set_key(&mut model_table, rest, (*v).clone()).map_err(|why| Error::invalid("--param", &p.key, why))?;
            }
        }
        let fresh;
        let at_speed = match fast {
            Excitations::Base(_) => None,
            Excitations::PerSpeed { param, cache } => match self.speed_entry(cache, *param, idx[*param]) {
                Some(e) => Some(e),
                None => {
                    fresh = self.speed_excitation(*param, idx[*param])?;
                    Some(&fresh)
                }
            },
        };
        let speed = at_speed.map_or(self.base.input.speed, |e| e.speed);
        let kind = &self.base.kind;
        let f = Fields::new(&self.base.path, "model", &model_table);
        let _ = f.get("kind"); // read by the scenario reader, not by the model
        let model = match build_model(
            kind,
            &f,
            ModelContext {
                speed,
                several_inputs: false,
            },
        )? {
            BuiltModel::Stochastic(m) => m,
            BuiltModel::Deterministic(_) => {
                return Err(Error::invalid(
                    "model.kind",
                    kind,
                    "a deterministic model has no response statistics",
                ))
            }
        };
        f.finish()?;
        let outputs = self.check_outputs(&model)?;
        let same_layout = model.layout == self.base.model.layout;
        match (fast, at_speed) {
            (Excitations::Base(ev), _) if same_layout => {
                ev.evaluate(model.system.as_ref(), &self.base.excitation, &outputs)
            }
            (Excitations::PerSpeed { .. }, Some(e)) if same_layout => {
                e.evaluator.evaluate(model.system.as_ref(), &e.excitation, &outputs)
            }
            _ => {
                // the input layout changed with the model (e.g. a wheelbase): the whole scenario
                let sc = self.scenario_at(point)?;
                let outputs = self.check_outputs(&sc.model)?;
                ExactEvaluator::new(&sc.excitation).evaluate(sc.model.system.as_ref(), &sc.excitation, &outputs)
            }
        }
    }

    /// The indices of the base's outputs in `model`, which must name them alike.
    fn check_outputs(&self, model: &crate::models::ModelInstance) -> Result<Vec<usize>> {
        let names = model.system.outputs();
        self.output_names
            .iter()
            .zip(&self.base.analysis.outputs)
            .map(|(n, &i)| {
                if names.get(i).is_some_and(|o| o.name == *n) {
                    Ok(i)
                } else {
                    names
                        .iter()
                        .position(|o| o.name == *n)
                        .ok_or_else(|| Error::invalid("model", n, "the substituted model has no output of this name"))
                }
            })
            .collect()
    }

    /// Evaluates the points `points` (in parallel with `parallel`), each result in point order; a point
    /// that fails gives its error message (the study goes on). One `Vec` per point: for large studies
    /// [`evaluate_into`](Self::evaluate_into) writes the same rows into one buffer.
    pub fn evaluate_range(
        &self,
        points: std::ops::Range<usize>,
        parallel: bool,
    ) -> Vec<std::result::Result<Vec<PointStatistics>, String>> {
        use rayon::prelude::*;
        let n_out = self.outputs().len();
        // one state space per worker for the numeric path, overwritten point after point
        let scratch = || self.numeric.as_ref().map(|n| n.template.clone());
        let one = |s: &mut Option<StateSpace>, p: usize| {
            let mut row = Vec::with_capacity(n_out);
            self.evaluate_in(p, s.as_mut(), &mut row)
                .map(|()| row)
                .map_err(|e| e.to_string())
        };
        if parallel {
            points
                .into_par_iter()
                .with_min_len(256)
                .map_init(scratch, one)
                .collect()
        } else {
            let mut s = scratch();
            points.map(|p| one(&mut s, p)).collect()
        }
    }

    /// Evaluates the points `points` (in parallel with `parallel`) into `out`, row-major (point, output in
    /// the order of [`outputs`](Self::outputs)); on the closed-form path nothing is allocated per point.
    /// Every row is written: a point that fails gets [`FAILED_POINT`] and gives its error message, in the
    /// returned list (ascending points; the study goes on). A study has at least one output (the scenario
    /// refuses an empty list).
    ///
    /// # Errors
    /// None: see above.
    ///
    /// # Panics
    /// If `out.len()` is not `points.len()` times the number of outputs (a caller's bug).
    ///
    /// # Examples
    /// ```
    /// use stochvib::scenario::load_scenario;
    /// use stochvib::study::{Sweep, SweepMode, SweepParam, SweepSpec, FAILED_POINT};
    /// use std::path::Path;
    /// let sc = load_scenario(Path::new("data/scraper-sprung-cab.toml"), Path::new("spectra")).unwrap();
    /// let spec = SweepSpec::new(vec![SweepParam::parse("model.zeta2=0.1..0.4:4").unwrap()], SweepMode::Grid).unwrap();
    /// let sweep = Sweep::new(&sc, spec).unwrap();
    /// let n_out = sweep.outputs().len();
    /// let mut rows = vec![FAILED_POINT; 4 * n_out];
    /// assert!(sweep.evaluate_into(0..4, true, &mut rows).is_empty());
    /// assert_eq!(&rows[2 * n_out..3 * n_out], &sweep.evaluate(2).unwrap()[..]); // point 2's row
    /// ```
    pub fn evaluate_into(
        &self,
        points: std::ops::Range<usize>,
        parallel: bool,
        out: &mut [PointStatistics],
    ) -> Vec<(usize, String)> {
        use rayon::prelude::*;
        const CHUNK: usize = 256;
        let n_out = self.outputs().len().max(1);
        assert_eq!(out.len(), points.len() * self.outputs().len(), "one row per point");
        // per worker: a state space for the numeric path, overwritten point after point, and one row
        let scratch = || {
            (
                self.numeric.as_ref().map(|n| n.template.clone()),
                Vec::with_capacity(n_out),
            )
        };
        let chunk = |(ss, row): &mut (Option<StateSpace>, Vec<PointStatistics>),
                     (c, rows): (usize, &mut [PointStatistics])|
         -> Vec<(usize, String)> {
            let mut errors = Vec::new();
            let first = points.start + c * CHUNK;
            for (k, slot) in rows.chunks_mut(n_out).enumerate() {
                match self.evaluate_in(first + k, ss.as_mut(), row) {
                    Ok(()) if row.len() == slot.len() => slot.copy_from_slice(row),
                    r => {
                        slot.fill(FAILED_POINT);
                        let why = r
                            .err()
                            .map_or("the model gave another number of outputs".into(), |e| e.to_string());
                        errors.push((first + k, why));
                    }
                }
            }
            errors
        };
        if self.outputs().is_empty() {
            return Vec::new();
        }
        if parallel {
            out.par_chunks_mut(CHUNK * n_out)
                .enumerate()
                .map_init(scratch, chunk)
                .flatten_iter()
                .collect()
        } else {
            let mut s = scratch();
            out.chunks_mut(CHUNK * n_out)
                .enumerate()
                .flat_map(|c| chunk(&mut s, c))
                .collect()
        }
    }
}

/// The row of a point that failed ([`Sweep::evaluate_into`]): no mean, variance or λ₂.
pub const FAILED_POINT: PointStatistics = PointStatistics {
    mean: None,
    variance: None,
    lambda2: None,
    method: VarianceMethod::Quadrature,
};

/// The root table of a scenario file with `point` values substituted, as TOML text (for `stochvib analyze`
/// of one point of a study).
///
/// # Errors
/// As [`Sweep::table_at`].
pub fn substituted_text(sweep: &Sweep, point: usize) -> Result<String> {
    toml::to_string(&sweep.table_at(point)?).map_err(|e| Error::Numerical {
        what: "writing the substituted scenario".into(),
        reason: e.to_string(),
    })
}
