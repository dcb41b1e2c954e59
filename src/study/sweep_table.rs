//! The table of a parameter study (`stochvib sweep`): one row per point and output with the swept values,
//! the exact mean, σ, variance, 3σ bounds, λ₂ and zero up-crossing rate, and optionally a Monte Carlo σ
//! with its interval; written as CSV, JSON or HDF5, whole or as shard files of a cluster run that
//! [`merge_sweep`] joins.
//!
//! # Shards
//! Part I of N of a study of P points evaluates the points ⌈I·P/N⌉ ≤ p < ⌈(I+1)·P/N⌉ (point p belongs to
//! part ⌊p·N/P⌋, the rule of [`Part`]) and writes `DIR/sweep-shard-<I>-of-<N>.json` ([`shard_file_name`])
//! under a temporary name renamed when complete. [`merge_sweep`] checks that the shard files belong to one
//! study (same scenario text, keys, values, mode, Monte Carlo options and toolkit version) and cover every
//! point once, then writes the table: the same numbers as one `stochvib sweep` of the whole study (each
//! point is evaluated alone, so the split cannot change it).
//!
//! # HDF5 layout (`-o TABLE.h5`)
//! ```text
//! table.h5
//! ├── @format "stochvib sweep table", @version 1, @toolkit_version, @scenario (text), @scenario_path,
//! │   @mode ("grid" | "zip"), @n_points u64, @keys string[], @outputs string[], @units string[],
//! │   @monte_carlo (JSON of the options, or "")
//! ├── params/<k>            string [n_values_k]  the values of key k as written (@key)
//! ├── value_index           u64 [n_points, n_keys]  which value of each key point p uses
//! ├── outputs/<name>/       @unit
//! │   ├── mean, variance, sigma, lower_3sigma, upper_3sigma, lambda2, zero_upcrossing_rate   f64 [n_points]
//! │   │                     (NaN where the value does not exist: infinite variance, failed point)
//! │   ├── method            u8 [n_points]  0 Lyapunov, 1 integral table, 2 quadrature,
//! │   │                     3 Lyapunov with delays, 255 failed
//! │   └── mc_sigma, mc_lower, mc_upper  f64 [n_points], mc_covers u8 [n_points]   (with Monte Carlo)
//! ├── verdicts/<k>          f64 [n_points]  @quantity, @unit: the k-th verdict column of `--verdicts`
//! │                         (σ, a_w, a_v, A8, VDV, damage_rate, life; SI; NaN where it does not exist)
//! └── errors/               point u64 [n_failed], message string [n_failed]
//! ```
//!
//! # Streaming
//! `stochvib sweep` does not build its CSV and HDF5 tables in memory:
//! [`write_sweep_table`](super::write_sweep_table) evaluates the points in blocks and writes each block
//! (HDF5 rows, CSV lines) on a writer thread while the next is evaluated; the file is the same as
//! [`SweepResults::write`] of the whole table. A JSON table is one document, written from the whole table.

use super::sweep_h5::H5TableWriter;
use crate::error::{Error, Result};
use crate::response::{PointStatistics, VarianceMethod};
use crate::simulate::{run_temporary, RunOptions};
use crate::store::Part;
use crate::study::{sweep_value_text, Sweep, SweepMode, FAILED_POINT};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The Monte Carlo batch run at every point (the same seed at every point: common random numbers, so that
/// differences between points are not masked by sampling noise).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SweepMonteCarlo {
    /// Realizations per point.
    pub realizations: usize,
    /// Duration of a realization, s.
    pub duration_s: f64,
    /// Time step, s.
    pub dt_s: f64,
    /// Master seed (every point).
    pub seed: u64,
    /// Realizations per internal shard.
    pub shard_size: usize,
    /// Confidence of the intervals.
    pub confidence: f64,
}

/// What identifies a study: shard files merge only when this is equal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepIdentity {
    /// The scenario file as given.
    pub scenario_path: String,
    /// Its text.
    pub scenario_text: String,
    /// The keys with their values as written.
    pub params: Vec<(String, Vec<String>)>,
    /// `grid` or `zip`.
    pub mode: String,
    /// The outputs (name, unit).
    pub outputs: Vec<(String, String)>,
    /// The Monte Carlo batch per point, if any.
    pub monte_carlo: Option<SweepMonteCarlo>,
    /// The verdict columns (quantity, unit) of `stochvib sweep --verdicts` ([`Sweep::with_verdicts`]);
    /// empty without.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub verdicts: Vec<(String, String)>,
    /// stochvib version.
    pub toolkit_version: String,
}

/// The code of a [`VarianceMethod`] in the HDF5 table's `method` dataset (255 marks a failed point).
pub(crate) fn method_code(m: VarianceMethod) -> u8 {
    match m {
        VarianceMethod::Lyapunov => 0,
        VarianceMethod::IntegralTable => 1,
        VarianceMethod::Quadrature => 2,
        VarianceMethod::LyapunovDelays => 3,
    }
}

/// The name of a [`VarianceMethod`] in the table's `method` column and in its JSON form (kebab case:
/// `lyapunov-delays` where the reports print [`VarianceMethod::name`], `lyapunov (delays)`).
fn method_name(m: VarianceMethod) -> &'static str {
    match m {
        VarianceMethod::Lyapunov => "lyapunov",
        VarianceMethod::IntegralTable => "integral-table",
        VarianceMethod::Quadrature => "quadrature",
        VarianceMethod::LyapunovDelays => "lyapunov-delays",
    }
}

/// [`OutputRow`]'s `method` in the JSON of a table or shard file, by [`method_name`], read back.
mod method_text {
    use super::{method_name, VarianceMethod};
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(m: &VarianceMethod, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(method_name(*m))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> std::result::Result<VarianceMethod, D::Error> {
        let text = String::deserialize(d)?;
        [
            VarianceMethod::Lyapunov,
            VarianceMethod::IntegralTable,
            VarianceMethod::Quadrature,
            VarianceMethod::LyapunovDelays,
        ]
        .into_iter()
        .find(|&m| method_name(m) == text)
        .ok_or_else(|| {
            serde::de::Error::unknown_variant(&text, &["lyapunov", "lyapunov-delays", "integral-table", "quadrature"])
        })
    }
}

/// The Monte Carlo σ of one output at one point: the `sigma` statistic of the point's run
/// ([`crate::store::Statistic`]) cut down to what a row of the table holds.
///
/// A separate type, not the stored [`Statistic`](crate::store::Statistic): a table row is flat and fixed
/// in size (four columns per output: `mc_sigma`, `mc_lower`, `mc_upper`, `mc_covers`), while the stored
/// statistic carries its name, unit, method text, analytic value and confidence (the table's confidence is
/// that of its [`SweepMonteCarlo`], one for every point). It is made from the stored statistic in one place
/// only, [`McValues::from_sigma`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct McValues {
    /// Estimate of σ.
    pub sigma: f64,
    /// Lower bound of its interval.
    pub lower: f64,
    /// Upper bound.
    pub upper: f64,
    /// Whether the interval covers the analytic σ.
    pub covers: bool,
}

impl McValues {
    /// The table's values of a run's `sigma` statistic: its estimate and interval bounds, and whether the
    /// interval covers the analytic σ (`false` when there is no analytic value to cover).
    pub fn from_sigma(s: &crate::store::Statistic) -> McValues {
        McValues {
            sigma: s.interval.estimate,
            lower: s.interval.lower,
            upper: s.interval.upper,
            covers: s.covers == Some(true),
        }
    }
}

/// The values of one output at one point: the exact statistics of the point, [`PointStatistics`] (which an
/// `OutputValues` dereferences to: `v.mean`, `v.sigma()`, `v.bounds(3.0)`), and the Monte Carlo σ when a
/// batch was run.
///
/// In a table or shard file (JSON) the row is flat — `mean`, `variance`, `lambda2`, `method` (the table's
/// method text, `lyapunov-delays`), `mc` — the layout of the private `OutputRow`, into and from which it converts (the one place
/// where the two meet).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "OutputRow", into = "OutputRow")]
pub struct OutputValues {
    /// The exact statistics (mean, variance, λ₂ and the route that computed them).
    pub exact: PointStatistics,
    /// Monte Carlo, when run (None also for an output the run skipped).
    pub mc: Option<McValues>,
}

impl std::ops::Deref for OutputValues {
    type Target = PointStatistics;
    fn deref(&self) -> &PointStatistics {
        &self.exact
    }
}

impl OutputValues {
    pub(crate) fn from_point(s: &PointStatistics) -> OutputValues {
        OutputValues { exact: *s, mc: None }
    }
}

/// The stored layout of [`OutputValues`] in the JSON of a table or shard file: one flat row.
#[derive(Clone, Copy, Serialize, Deserialize)]
struct OutputRow {
    mean: Option<f64>,
    variance: Option<f64>,
    lambda2: Option<f64>,
    #[serde(with = "method_text")]
    method: VarianceMethod,
    mc: Option<McValues>,
}

impl From<OutputRow> for OutputValues {
    fn from(r: OutputRow) -> OutputValues {
        let exact = PointStatistics {
            mean: r.mean,
            variance: r.variance,
            lambda2: r.lambda2,
            method: r.method,
        };
        OutputValues { exact, mc: r.mc }
    }
}

impl From<OutputValues> for OutputRow {
    fn from(v: OutputValues) -> OutputRow {
        let e = v.exact;
        OutputRow {
            mean: e.mean,
            variance: e.variance,
            lambda2: e.lambda2,
            method: e.method,
            mc: v.mc,
        }
    }
}

/// The results of a study for a range of its points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepResults {
    /// What identifies the study.
    pub identity: SweepIdentity,
    /// Points of the whole study.
    pub n_points: usize,
    /// The points held here (all of them for a whole table).
    pub points: std::ops::Range<usize>,
    /// The value index of every key at every point held (row-major: point, key).
    pub value_index: Vec<usize>,
    /// The values of every output at every point held (row-major: point, output); for a failed point the
    /// outputs hold no numbers.
    pub values: Vec<OutputValues>,
    /// Failed points with the reason.
    pub errors: Vec<(usize, String)>,
    /// The verdict columns' values at every point held (row-major: point, column of
    /// [`SweepIdentity::verdicts`]; SI; `None` where the value does not exist); empty without verdicts.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub verdicts: Vec<Option<f64>>,
}

/// The identity of `sweep` with Monte Carlo options `mc`.
pub fn sweep_identity(sweep: &Sweep, mc: Option<SweepMonteCarlo>) -> SweepIdentity {
    let sc = sweep.scenario();
    let names = sc.model.system.outputs();
    SweepIdentity {
        scenario_path: sc.path.display().to_string(),
        scenario_text: sc.text.clone(),
        params: sweep
            .spec()
            .params
            .iter()
            .map(|p| (p.key.clone(), p.values.iter().map(sweep_value_text).collect()))
            .collect(),
        mode: match sweep.spec().mode {
            SweepMode::Grid => "grid".into(),
            SweepMode::Zip => "zip".into(),
        },
        outputs: sc
            .analysis
            .outputs
            .iter()
            .map(|&i| (names[i].name.clone(), names[i].unit.clone()))
            .collect(),
        monte_carlo: mc,
        verdicts: sweep
            .verdicts()
            .iter()
            .map(|q| (q.text.clone(), q.unit.clone()))
            .collect(),
        toolkit_version: crate::store::layout::TOOLKIT_VERSION.to_string(),
    }
}

/// Evaluates the points `points` of `sweep` (exact statistics on every core with `parallel`; then, with
/// `mc`, one Monte Carlo batch per point, one point after the other, each on every core).
/// `progress(done, total)` is called after every Monte Carlo point.
///
/// # Errors
/// None for a failing point (its error is recorded in [`SweepResults::errors`]); the Monte Carlo set-up's
/// errors (temporary directory).
pub fn compute_sweep(
    sweep: &Sweep,
    points: std::ops::Range<usize>,
    parallel: bool,
    mc: Option<SweepMonteCarlo>,
    progress: &dyn Fn(usize, usize),
) -> Result<SweepResults> {
    let mut stats = vec![FAILED_POINT; points.len() * sweep.outputs().len()];
    let errors = sweep.evaluate_into(points.clone(), parallel, &mut stats);
    let mut t = tabulate(sweep, points, &stats, errors, mc);
    if let Some(m) = mc {
        add_monte_carlo(sweep, &mut t, m, progress);
    }
    super::sweep_verdicts::add_verdicts(sweep, &mut t, parallel);
    Ok(t)
}

/// The table of the points `points` from their rows `stats` and failed points `errors`
/// ([`Sweep::evaluate_into`]), for a study with Monte Carlo options `mc` (whose values are not set here).
fn tabulate(
    sweep: &Sweep,
    points: std::ops::Range<usize>,
    stats: &[PointStatistics],
    errors: Vec<(usize, String)>,
    mc: Option<SweepMonteCarlo>,
) -> SweepResults {
    let spec = sweep.spec();
    let mut value_index = vec![0; points.len() * spec.params.len()];
    if !spec.params.is_empty() {
        for (p, idx) in points.clone().zip(value_index.chunks_mut(spec.params.len())) {
            spec.indices_into(p, idx);
        }
    }
    SweepResults {
        identity: sweep_identity(sweep, mc),
        n_points: spec.n_points(),
        points,
        value_index,
        values: stats.iter().map(OutputValues::from_point).collect(),
        errors,
        verdicts: Vec::new(),
    }
}

/// Runs the Monte Carlo batch `m` at every point of `t` that did not fail, one point after the other
/// (each on every core), calling `progress(done, total)` after each; a batch that fails is recorded as the
/// point's error.
fn add_monte_carlo(sweep: &Sweep, t: &mut SweepResults, m: SweepMonteCarlo, progress: &dyn Fn(usize, usize)) {
    let n_out = sweep.outputs().len();
    let points = t.points.clone();
    let (values, errors) = (&mut t.values, &mut t.errors);
    let dir = std::env::temp_dir();
    for (k, p) in points.clone().enumerate() {
        if errors.iter().any(|e| e.0 == p) {
            progress(k + 1, points.len()); // a failed point has no batch, but it is done
            continue;
        }
        let run = || -> Result<Vec<Option<McValues>>> {
            let sc = sweep.scenario_at(p)?;
            let opts = RunOptions {
                shard_size: m.shard_size,
                confidence: m.confidence,
                realizations: m.realizations,
                duration_s: m.duration_s,
                dt_s: m.dt_s,
                seed: m.seed,
                ..RunOptions::default()
            };
            let (summary, ()) =
                run_temporary(&sc.run_input(), &opts, &dir, &|_, _| {}, |_| ()).map_err(|e| sc.name_run_error(e))?;
            Ok(sweep
                .outputs()
                .iter()
                .map(|name| summary.statistic(name, "sigma").map(McValues::from_sigma))
                .collect())
        };
        match run() {
            Ok(list) => {
                for (j, v) in list.into_iter().enumerate() {
                    values[k * n_out + j].mc = v;
                }
            }
            Err(e) => errors.push((p, format!("Monte Carlo: {e}"))),
        }
        progress(k + 1, points.len());
    }
    errors.sort_by_key(|e| e.0);
}

/// Output format of a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableFormat {
    /// Comma-separated values, one row per point and output.
    Csv,
    /// JSON: the identity and one object per point and output.
    Json,
    /// HDF5 (see the module docs).
    Hdf5,
}

impl TableFormat {
    /// From a file name's extension (`.csv`, `.json`, `.h5`/`.hdf5`).
    ///
    /// # Errors
    /// [`Error::Io`] naming the file for another extension.
    pub fn from_path(path: &Path) -> Result<TableFormat> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("csv") => Ok(TableFormat::Csv),
            Some("json") => Ok(TableFormat::Json),
            Some("h5" | "hdf5") => Ok(TableFormat::Hdf5),
            _ => Err(Error::Io {
                path: path.to_path_buf(),
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "a table is written as .csv, .json or .h5 (from the file name's extension); nothing was written",
                ),
            }),
        }
    }
}

/// `,lo,hi` as [`push_num`] writes each; where lo < 0 and hi = −lo (a zero mean: M ± 3σ = ±3σ) the text of hi is
/// cut from lo's (the same text without its sign, as `{:e}` writes −x) instead of formatted again.
fn push_bounds(s: &mut String, lo: Option<f64>, hi: Option<f64>) {
    let at = s.len();
    push_num(s, lo);
    match (lo, hi) {
        (Some(l), Some(h)) if l < 0.0 && h.to_bits() == (-l).to_bits() => {
            // s[at] is the comma, s[at + 1] the sign
            let end = s.len();
            s.push(',');
            s.extend_from_within(at + 2..end);
        }
        _ => push_num(s, hi),
    }
}

/// `,` and the value as `{:.9e}` writes it ([`TABLE_DIGITS`](super::float_text::TABLE_DIGITS) = 10
/// significant digits), appended to `s` without an intermediate string
/// ([`push_fixed`](super::float_text::push_fixed)).
fn push_num(s: &mut String, v: Option<f64>) {
    s.push(',');
    if let Some(x) = v {
        super::float_text::push_fixed(s, x);
    }
}

/// The kind of file `stochvib sweep -o` and `merge` of sweep shards write, for the output rule
/// ([`crate::io_rules::check_output`]): a table of a parameter study, recognised by its beginning (CSV
/// `point,`, JSON `{ "identity"`, HDF5 `@format = "stochvib sweep table"`, from the target's extension).
pub const SWEEP_TABLE: crate::io_rules::OutputKind = crate::io_rules::OutputKind {
    what: "sweep table",
    recognizes: is_sweep_table,
    replaceable: false,
};

/// The kind of the shard files of `stochvib sweep --shard` ([`SWEEP_TABLE`]'s sibling).
pub const SWEEP_SHARD: crate::io_rules::OutputKind = crate::io_rules::OutputKind {
    what: "sweep shard file",
    recognizes: is_sweep_shard,
    replaceable: false,
};

/// Whether the existing file `path` is a sweep shard file (it begins with its `format` field).
fn is_sweep_shard(path: &Path) -> bool {
    crate::io_rules::starts_with(path, format!("{{\"format\":\"{SHARD_FORMAT}\"").as_bytes())
}

/// Whether the existing file `path` is a sweep table of the format its extension names.
fn is_sweep_table(path: &Path) -> bool {
    match TableFormat::from_path(path) {
        Ok(TableFormat::Csv) => crate::io_rules::starts_with(path, b"point,"),
        Ok(TableFormat::Json) => {
            crate::io_rules::starts_with(path, b"{\n  \"identity\"")
                || crate::io_rules::starts_with(path, b"{\n  \"columns\"")
        }
        Ok(TableFormat::Hdf5) => {
            crate::io_rules::starts_with(path, crate::io_rules::HDF5_SIGNATURE)
                && hdf5::File::open(path)
                    .and_then(|f| f.attr("format")?.read_scalar::<hdf5::types::VarLenUnicode>())
                    .is_ok_and(|v| v.as_str() == "stochvib sweep table")
        }
        Err(_) => false,
    }
}

/// The format of the table to be written to `path` (from its extension) and the staged file to write it
/// into, after the output rule has checked `path` against `inputs` ([`crate::io_rules::Staged`]).
///
/// # Errors
/// An unknown extension; the refusals of the output rule (an input, a directory, a device, a file of
/// another kind; an existing table without `overwrite`).
pub(crate) fn prepare_table(
    path: &Path,
    overwrite: bool,
    inputs: &[&Path],
) -> Result<(TableFormat, crate::io_rules::Staged)> {
    let format = TableFormat::from_path(path)?;
    let staged = crate::io_rules::Staged::begin(path, SWEEP_TABLE, inputs, overwrite)?;
    Ok((format, staged))
}

/// The bytes one point takes in a table of `identity` in `format`, at most (failed points add their
/// message): the rows of one point whose every number is printed at the greatest width (17 characters,
/// `-1.234567890e-308`) and whose every key takes its longest value, measured with the writers
/// themselves.
pub(crate) fn point_bytes(identity: &SweepIdentity, format: TableFormat) -> u128 {
    let wide = -1.234_567_890_123_456_7e-308;
    let widest = Some(wide);
    let value = OutputValues {
        exact: PointStatistics {
            mean: widest,
            variance: Some(f64::MAX),
            lambda2: widest,
            method: VarianceMethod::LyapunovDelays,
        },
        mc: identity.monte_carlo.map(|_| McValues {
            sigma: wide,
            lower: wide,
            upper: wide,
            covers: false,
        }),
    };
    let longest: Vec<usize> = identity
        .params
        .iter()
        .map(|(_, vals)| (0..vals.len()).max_by_key(|&i| vals[i].len()).unwrap_or(0))
        .collect();
    let one = SweepResults {
        identity: identity.clone(),
        n_points: usize::MAX / 2,
        points: usize::MAX / 2 - 1..usize::MAX / 2,
        value_index: longest,
        values: vec![value; identity.outputs.len()],
        errors: Vec::new(),
        verdicts: vec![widest; identity.verdicts.len()],
    };
    let empty = SweepResults {
        points: 0..0,
        value_index: Vec::new(),
        values: Vec::new(),
        verdicts: Vec::new(),
        ..one.clone()
    };
    let size = |t: &SweepResults| match format {
        TableFormat::Json => t.to_json().map_or(0, |j| j.len()),
        // HDF5: a number is 8 bytes, a method byte, the key indices 8 bytes each: far below CSV
        TableFormat::Csv | TableFormat::Hdf5 => {
            let mut text = String::new();
            t.push_csv_rows(&mut text);
            text.len()
        }
    };
    // a verdict table's CSV line per point: its columns as wide as numbers can be
    let verdict_row = (identity.params.len() + identity.verdicts.len() + 2) * 25;
    (size(&one).saturating_sub(size(&empty)) + if identity.verdicts.is_empty() { 0 } else { verdict_row }) as u128
}

/// The resource rule for a study's table at `path`: a JSON table, whose rows are built whole in memory
/// before its text is written, must fit the available memory (the rows' values and statistics, and the
/// value indices); every table's size on disk (points × `point_bytes`) the free space of its disk.
///
/// # Errors
/// [`Error::InvalidParameter`] naming `param` with the number of points and the sizes.
pub fn check_table_resources(
    sweep: &Sweep,
    path: &Path,
    format: TableFormat,
    mc: Option<SweepMonteCarlo>,
) -> Result<()> {
    let identity = sweep_identity(sweep, mc);
    let n = sweep.spec().n_points() as u128;
    let rows = n * identity.outputs.len() as u128;
    let file = n * point_bytes(&identity, format) + (1 << 16);
    let points = format!("{n} points × {} outputs", identity.outputs.len());
    if format == TableFormat::Json {
        // the rows and their results in memory (the text itself is streamed to the file)
        let per_row = std::mem::size_of::<OutputValues>() + std::mem::size_of::<PointStatistics>();
        let memory = rows * per_row as u128 + n * identity.params.len() as u128 * 8;
        crate::io_rules::check_memory(
            memory,
            "--param",
            &points,
            "a JSON table (built whole before it is written)",
            "write a .csv or .h5 table instead (streamed in bounded memory), or use fewer points",
        )?;
    }
    crate::io_rules::check_disk(
        file,
        path,
        "--param",
        &points,
        "the table",
        "fewer values per --param, fewer keys, or another disk (CSV on stdout without -o needs no disk)",
    )
}

/// The resource rule for the Monte Carlo batches of a study: every point runs `mc.realizations`
/// realizations, so the study's time lower bound is the points times that of one batch
/// ([`crate::simulate::resources::run_time_lower_bound`]); refused above `max_hours`.
///
/// # Errors
/// The batch's invalid options; [`Error::InvalidParameter`] naming `monte-carlo` with the estimate.
pub fn check_monte_carlo_time(sweep: &Sweep, mc: &SweepMonteCarlo, max_hours: f64) -> Result<()> {
    let n = RunOptions {
        realizations: mc.realizations,
        duration_s: mc.duration_s,
        dt_s: mc.dt_s,
        seed: mc.seed,
        ..RunOptions::default()
    }
    .samples()?;
    let points = sweep.spec().n_points();
    let processes = sweep.scenario().excitation.spectra().len();
    let threads = rayon::current_num_threads();
    let t =
        crate::simulate::resources::run_time_lower_bound(points as f64 * mc.realizations as f64, n, processes, threads);
    crate::io_rules::check_time(
        t,
        max_hours,
        "monte-carlo",
        mc.realizations,
        &format!(
            "{points} points × {} realizations × {n} samples on {threads} threads",
            mc.realizations
        ),
        "fewer points or realizations, a shorter --duration, or a cluster run (--shard I --of N)",
    )
}

/// The header line of the CSV form of a study's table.
pub fn csv_header(identity: &SweepIdentity) -> String {
    let mut s = String::from("point");
    for (k, _) in &identity.params {
        let _ = write!(s, ",{}", csv_field(k));
    }
    s.push_str(",output,unit,method,mean,sigma,variance,lower_3sigma,upper_3sigma,lambda2,zero_upcrossing_rate");
    if identity.monte_carlo.is_some() {
        s.push_str(",mc_sigma,mc_lower,mc_upper,mc_covers");
    }
    s.push_str(",error\n");
    s
}

pub(crate) fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The CSV lines of a table's points ([`csv_header`]'s columns), with the fields that repeat from row to
/// row quoted once: the one place where a CSV row is written, for a whole table and for a streamed one.
pub(crate) struct CsvRows {
    /// The quoted text of every value of every key.
    params: Vec<Vec<String>>,
    /// `,output,unit,` of every output.
    outputs: Vec<String>,
    monte_carlo: bool,
}

impl CsvRows {
    pub(crate) fn new(identity: &SweepIdentity) -> CsvRows {
        CsvRows {
            params: identity
                .params
                .iter()
                .map(|(_, vals)| vals.iter().map(|v| csv_field(v)).collect())
                .collect(),
            outputs: identity
                .outputs
                .iter()
                .map(|(name, unit)| format!(",{},{},", csv_field(name), csv_field(unit)))
                .collect(),
            monte_carlo: identity.monte_carlo.is_some(),
        }
    }

    /// Appends the lines of point `p` (one per output) to `s`: `keys` are its value indices, `value(j)`
    /// output j's values, `err` the point's failure.
    pub(crate) fn push_point(
        &self,
        s: &mut String,
        p: usize,
        keys: &[usize],
        value: impl Fn(usize) -> OutputValues,
        err: Option<&str>,
    ) {
        let at = s.len();
        super::float_text::push_int(s, p);
        for (vals, &k) in self.params.iter().zip(keys) {
            s.push(',');
            s.push_str(&vals[k]);
        }
        let point = at..s.len();
        for (j, output) in self.outputs.iter().enumerate() {
            if j > 0 {
                s.extend_from_within(point.clone());
            }
            let v = value(j);
            let (lo, hi) = v.bounds(3.0).unzip();
            s.push_str(output);
            s.push_str(if err.is_some() { "" } else { method_name(v.method) });
            for x in [v.mean, v.sigma(), v.variance] {
                push_num(s, x);
            }
            push_bounds(s, lo, hi);
            for x in [v.lambda2, v.zero_upcrossing_rate()] {
                push_num(s, x);
            }
            if self.monte_carlo {
                let m = v.mc;
                for x in [m.map(|m| m.sigma), m.map(|m| m.lower), m.map(|m| m.upper)] {
                    push_num(s, x);
                }
                s.push(',');
                s.push_str(m.map_or("", |m| if m.covers { "yes" } else { "no" }));
            }
            s.push(',');
            if let Some(e) = err {
                s.push_str(&csv_field(e));
            }
            s.push('\n');
        }
        if self.outputs.is_empty() {
            s.truncate(at);
        }
    }
}

impl SweepResults {
    fn n_keys(&self) -> usize {
        self.identity.params.len()
    }

    pub(crate) fn error_of(&self, point: usize) -> Option<&str> {
        self.errors
            .binary_search_by_key(&point, |e| e.0)
            .ok()
            .map(|i| self.errors[i].1.as_str())
    }

    /// The table as CSV: a header line, then one line per point and output. A table with verdict columns
    /// is written as CSV and JSON in the form of `stochvib sweep --verdicts` (one row per point,
    /// [`VerdictSweep`](super::sweep_verdicts::VerdictSweep)), as HDF5 whole with its `verdicts/` group.
    pub fn to_csv(&self) -> String {
        if !self.identity.verdicts.is_empty() {
            return super::sweep_verdicts::VerdictSweep::of(self).to_csv();
        }
        let mut s = csv_header(&self.identity);
        self.push_csv_rows(&mut s);
        s
    }

    /// The CSV lines of the points held (no header), appended to `s`: [`to_csv`](Self::to_csv) of a table is
    /// its header followed by the lines of its blocks, in order.
    pub fn push_csv_rows(&self, s: &mut String) {
        let blocks = self.csv_row_blocks();
        s.reserve(blocks.iter().map(String::len).sum());
        for b in &blocks {
            s.push_str(b);
        }
    }

    /// The CSV lines of the points held, formatted in blocks of 4096 points on all cores: joined in order
    /// they are [`push_csv_rows`](Self::push_csv_rows)'s text (a stream writes them one by one, without
    /// the copy of joining them).
    pub(crate) fn csv_row_blocks(&self) -> Vec<String> {
        let n_out = self.identity.outputs.len();
        let nk = self.n_keys();
        let lines = CsvRows::new(&self.identity);
        // rows formatted in blocks on all cores, joined in order (the same text as one pass)
        use rayon::prelude::*;
        const BLOCK: usize = 4096;
        let n_rows = self.points.len();
        (0..n_rows.div_ceil(BLOCK))
            .into_par_iter()
            .map(|blk| {
                let rows = blk * BLOCK..((blk + 1) * BLOCK).min(n_rows);
                let mut s = String::with_capacity(rows.len() * n_out * 200);
                for row in rows {
                    let p = self.points.start + row;
                    let keys = &self.value_index[row * nk..(row + 1) * nk];
                    lines.push_point(&mut s, p, keys, |j| self.values[row * n_out + j], self.error_of(p));
                }
                s
            })
            .collect()
    }

    /// The table as JSON: the identity and one object per point and output.
    ///
    /// # Errors
    /// A serialisation error (none is expected for these types).
    pub fn to_json(&self) -> Result<String> {
        let mut buf = Vec::new();
        self.write_json(&mut buf)?;
        String::from_utf8(buf).map_err(|e| Error::Numerical {
            what: "writing JSON".into(),
            reason: e.to_string(),
        })
    }

    /// Writes [`to_json`](Self::to_json)'s text to `w`, row by row: memory does not grow with the number of
    /// points (before, a 10⁶-point study built the whole document first: 6.5 GB peak for a 2.2 GB file).
    ///
    /// # Errors
    /// I/O errors of `w`.
    pub fn write_json(&self, mut w: impl std::io::Write) -> Result<()> {
        if !self.identity.verdicts.is_empty() {
            // the one-row-per-point form (see to_csv)
            let text = super::sweep_verdicts::VerdictSweep::of(self).to_json()?;
            return w.write_all(text.as_bytes()).map_err(|e| Error::Numerical {
                what: "writing JSON".into(),
                reason: e.to_string(),
            });
        }
        #[derive(Serialize)]
        struct Row<'a> {
            point: usize,
            params: serde_json::Map<String, serde_json::Value>,
            output: &'a str,
            unit: &'a str,
            method: Option<&'static str>,
            mean: Option<f64>,
            sigma: Option<f64>,
            variance: Option<f64>,
            lower_3sigma: Option<f64>,
            upper_3sigma: Option<f64>,
            lambda2: Option<f64>,
            zero_upcrossing_rate: Option<f64>,
            monte_carlo: Option<McValues>,
            error: Option<&'a str>,
        }
        /// The rows, made one at a time while the serializer writes them.
        struct Rows<'a>(&'a SweepResults);
        impl Serialize for Rows<'_> {
            fn serialize<S: serde::Serializer>(&self, ser: S) -> std::result::Result<S::Ok, S::Error> {
                let t = self.0;
                let n_out = t.identity.outputs.len();
                let nk = t.n_keys();
                ser.collect_seq(t.points.clone().enumerate().flat_map(move |(row, p)| {
                    let err = t.error_of(p);
                    t.identity.outputs.iter().enumerate().map(move |(j, (name, unit))| {
                        let v = &t.values[row * n_out + j];
                        let mut params = serde_json::Map::new();
                        for k in 0..nk {
                            let (key, vals) = &t.identity.params[k];
                            params.insert(key.clone(), vals[t.value_index[row * nk + k]].clone().into());
                        }
                        let (lo, hi) = v.bounds(3.0).unzip();
                        Row {
                            point: p,
                            params,
                            output: name,
                            unit,
                            method: err.is_none().then(|| method_name(v.method)),
                            mean: v.mean,
                            sigma: v.sigma(),
                            variance: v.variance,
                            lower_3sigma: lo,
                            upper_3sigma: hi,
                            lambda2: v.lambda2,
                            zero_upcrossing_rate: v.zero_upcrossing_rate(),
                            monte_carlo: v.mc,
                            error: err,
                        }
                    })
                }))
            }
        }
        #[derive(Serialize)]
        struct Table<'a> {
            identity: &'a SweepIdentity,
            n_points: usize,
            rows: Rows<'a>,
        }
        let mut w = std::io::BufWriter::with_capacity(1 << 16, w);
        serde_json::to_writer_pretty(
            &mut w,
            &Table {
                identity: &self.identity,
                n_points: self.n_points,
                rows: Rows(self),
            },
        )
        .map_err(|e| Error::Numerical {
            what: "writing JSON".into(),
            reason: e.to_string(),
        })?;
        std::io::Write::flush(&mut w).map_err(|e| Error::Numerical {
            what: "writing JSON".into(),
            reason: e.to_string(),
        })
    }

    /// Writes the table to `path` (format from its extension) under the output rule: into a temporary file
    /// of this process, renamed when complete; an existing table is only replaced with `overwrite`, and
    /// `inputs` (the files the table was computed from) never.
    ///
    /// # Errors
    /// An unknown extension; the refusals of [`crate::io_rules::check_output`]; I/O and HDF5 errors.
    pub fn write(&self, path: &Path, overwrite: bool) -> Result<()> {
        self.write_from(path, overwrite, &[])
    }

    /// [`write`](Self::write) with the files the table was read from (never replaced).
    ///
    /// # Errors
    /// As [`write`](Self::write).
    pub fn write_from(&self, path: &Path, overwrite: bool, inputs: &[&Path]) -> Result<()> {
        let (format, staged) = prepare_table(path, overwrite, inputs)?;
        self.write_format(staged.temporary(), format)?;
        staged.commit().map(|_| ())
    }

    /// Writes the table to the new file `tmp` in `format`.
    pub(crate) fn write_format(&self, tmp: &Path, format: TableFormat) -> Result<()> {
        let io = |source| Error::Io {
            path: tmp.to_path_buf(),
            source,
        };
        match format {
            TableFormat::Csv => std::fs::write(tmp, self.to_csv()).map_err(io),
            TableFormat::Json => std::fs::File::create(tmp)
                .map_err(io)
                .and_then(|file| self.write_json(file)),
            TableFormat::Hdf5 => self.write_h5(tmp),
        }
    }

    fn write_h5(&self, path: &Path) -> Result<()> {
        let mut w = H5TableWriter::create(path, &self.identity, self.n_points, self.points.clone())?;
        w.append(self)?;
        w.finish()
    }
}

/// The file name of part `part` of a study: `sweep-shard-<I>-of-<N>.json`.
pub fn shard_file_name(part: Part) -> String {
    part.file_name()
        .replacen("shard-", "sweep-shard-", 1)
        .replace(".h5", ".json")
}

/// The shard file of a cluster study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepShard {
    /// `"stochvib sweep shard"`.
    pub format: String,
    /// The part.
    pub part: Part,
    /// Its results.
    pub results: SweepResults,
}

const SHARD_FORMAT: &str = "stochvib sweep shard";

/// Evaluates part `part` of `sweep` and writes its shard file into `dir` (see the module docs); a rerun
/// whose shard file is already there for the same study does nothing and returns it.
///
/// # Errors
/// More parts than points; a file of another study (or not a shard file) under the shard's name, which is
/// never replaced without `overwrite`; I/O errors.
pub fn run_sweep_shard(
    sweep: &Sweep,
    part: Part,
    dir: &Path,
    parallel: bool,
    mc: Option<SweepMonteCarlo>,
    overwrite: bool,
    progress: &dyn Fn(usize, usize),
) -> Result<(PathBuf, SweepShard, bool)> {
    let n_points = sweep.spec().n_points();
    if part.count > n_points {
        return Err(Error::invalid(
            "of",
            part.count,
            format!("the study has only {n_points} points: use --of <= {n_points}"),
        ));
    }
    let path = dir.join(shard_file_name(part));
    let identity = sweep_identity(sweep, mc);
    if std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) && !overwrite {
        let existing = read_shard(&path).map_err(|e| Error::Hdf5 {
            path: path.clone(),
            reason: format!("is in the way and is not a sweep shard file ({e}); nothing is overwritten"),
        })?;
        if existing.results.identity == identity && existing.part == part {
            return Ok((path, existing, false));
        }
        return Err(Error::Hdf5 {
            path,
            reason: "holds a shard of another study (scenario, keys, values or options differ); nothing is \
                     overwritten: use another directory, or pass --overwrite"
                .into(),
        });
    }
    let inputs = sweep.scenario().source_files();
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let staged = crate::io_rules::Staged::begin(&path, SWEEP_SHARD, &inputs, overwrite)?;
    let results = compute_sweep(sweep, part.shards(n_points), parallel, mc, progress)?;
    let shard = SweepShard {
        format: SHARD_FORMAT.into(),
        part,
        results,
    };
    let text = serde_json::to_string(&shard).map_err(|e| Error::Numerical {
        what: "writing JSON".into(),
        reason: e.to_string(),
    })?;
    std::fs::write(staged.temporary(), text).map_err(|source| Error::Io {
        path: staged.temporary().to_path_buf(),
        source,
    })?;
    staged.commit()?;
    Ok((path, shard, true))
}

/// Reads a sweep shard file.
///
/// # Errors
/// I/O; not a sweep shard file.
pub fn read_shard(path: &Path) -> Result<SweepShard> {
    let text = crate::io_rules::read_text(path, crate::io_rules::JSON_SHARD_INPUT)?;
    let shard: SweepShard = serde_json::from_str(&text).map_err(|e| Error::Hdf5 {
        path: path.to_path_buf(),
        reason: format!("not a sweep shard file: {e}"),
    })?;
    if shard.format != SHARD_FORMAT {
        return Err(Error::Hdf5 {
            path: path.to_path_buf(),
            reason: "not a sweep shard file".into(),
        });
    }
    Ok(shard)
}

/// The sweep shard files named by `inputs` (directories stand for their `sweep-shard-*.json` files, files
/// ending in `.json` for themselves).
///
/// # Errors
/// I/O errors reading a directory.
pub fn find_sweep_shards(inputs: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for i in inputs {
        if i.is_dir() {
            let mut v: Vec<PathBuf> = std::fs::read_dir(i)
                .map_err(|source| Error::Io {
                    path: i.clone(),
                    source,
                })?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.file_name().is_some_and(|n| {
                        let n = n.to_string_lossy();
                        // not the temporary file of a shard being written (or of a killed writer)
                        n.starts_with("sweep-shard-") && n.ends_with(".json") && !n.contains(".tmp-")
                    })
                })
                .collect();
            v.sort();
            out.extend(v);
        } else if i.extension().is_some_and(|e| e == "json") {
            out.push(i.clone());
        }
    }
    Ok(out)
}

/// Joins the shard files of a study into one table written to `out` (format from its extension).
///
/// # Errors
/// [`Error::Hdf5`] listing every problem, naming the files: unreadable files, files of another study,
/// points held twice (duplicates or overlaps), points missing (the indices to resubmit); inputs that hold
/// run files beside the shard files ([`refuse_mixed`](super::merge_kind::refuse_mixed)); the table
/// writer's errors.
pub fn merge_sweep(out: &Path, inputs: &[PathBuf], overwrite: bool) -> Result<SweepResults> {
    let files = find_sweep_shards(inputs)?;
    let fail = |reason: String| Error::Hdf5 {
        path: inputs.first().cloned().unwrap_or_default(),
        reason,
    };
    if files.is_empty() {
        return Err(fail("no sweep shard files (sweep-shard-*.json)".into()));
    }
    super::merge_kind::refuse_mixed(out, &files[0], inputs)?;
    // the resource rule: every shard is read whole, and the table is built in memory
    let bytes: u128 = files
        .iter()
        .map(|f| std::fs::metadata(f).map_or(0, |m| m.len() as u128))
        .sum();
    crate::io_rules::check_memory(
        3 * bytes,
        "inputs",
        format!(
            "{} sweep shard files of {}",
            files.len(),
            crate::io_rules::bytes_text(bytes)
        ),
        "merging them (the shards and the table in memory)",
        "merge on a machine with more memory, or split the study into several smaller ones",
    )?;
    let mut problems = Vec::new();
    let mut shards = Vec::new();
    for f in &files {
        match read_shard(f) {
            Ok(s) => shards.push((f.clone(), s)),
            Err(e) => problems.push(e.to_string()),
        }
    }
    if shards.is_empty() {
        return Err(fail(problems.join("\n  ")));
    }
    // the study most files belong to
    let mut groups: Vec<(SweepIdentity, usize)> = Vec::new();
    for (_, s) in &shards {
        match groups.iter_mut().find(|g| g.0 == s.results.identity) {
            Some(g) => g.1 += 1,
            None => groups.push((s.results.identity.clone(), 1)),
        }
    }
    groups.sort_by_key(|g| std::cmp::Reverse(g.1));
    let identity = groups[0].0.clone();
    shards.retain(|(f, s)| {
        let same = s.results.identity == identity;
        if !same {
            problems.push(format!(
                "{}: foreign shard file: another study (scenario, keys, values, mode, Monte Carlo options or toolkit \
                 version differ)",
                f.display()
            ));
        }
        same
    });
    let n_points = shards[0].1.results.n_points;
    let width = identity.verdicts.len();
    for (f, s) in &shards {
        if s.results.verdicts.len() != s.results.points.len() * width {
            problems.push(format!(
                "{}: holds {} verdict values for {} points of {width} verdict columns",
                f.display(),
                s.results.verdicts.len(),
                s.results.points.len()
            ));
        }
    }
    problems.extend(coverage_problems(&shards, n_points));
    if !problems.is_empty() {
        return Err(fail(format!(
            "cannot merge the sweep shards:\n  {}",
            problems.join("\n  ")
        )));
    }
    shards.sort_by_key(|(_, s)| s.results.points.start);
    let mut all = SweepResults {
        identity,
        n_points,
        points: 0..n_points,
        value_index: Vec::new(),
        values: Vec::new(),
        errors: Vec::new(),
        verdicts: Vec::new(),
    };
    for (_, s) in shards {
        all.value_index.extend(s.results.value_index);
        all.values.extend(s.results.values);
        all.errors.extend(s.results.errors);
        all.verdicts.extend(s.results.verdicts);
    }
    // in point order whatever a shard file holds (the HDF5 writer marks failed rows by a binary search)
    all.errors.sort_by_key(|e| e.0);
    let files: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    all.write_from(out, overwrite, &files)?;
    Ok(all)
}

/// The points of a study of `n_points` that the shards hold twice (duplicate or overlapping files, named)
/// or that no shard holds (the shard indices to resubmit), from the shards' point ranges: memory and time
/// in the number of shards, whatever `n_points` a file claims.
fn coverage_problems(shards: &[(PathBuf, SweepShard)], n_points: usize) -> Vec<String> {
    let mut problems = Vec::new();
    let mut order: Vec<usize> = (0..shards.len()).collect();
    order.sort_by_key(|&k| (shards[k].1.results.points.start, shards[k].1.results.points.end));
    let describe = |k: usize| {
        let s = &shards[k].1;
        format!(
            "{} (shard {} of {}, points {}..{})",
            shards[k].0.display(),
            s.part.index,
            s.part.count,
            s.results.points.start,
            s.results.points.end
        )
    };
    let mut gaps: Vec<std::ops::Range<usize>> = Vec::new();
    let mut covered = 0; // every point below is held by some shard
    let mut last: Option<usize> = None; // the shard reaching furthest so far
    for &k in &order {
        let r = &shards[k].1.results.points;
        let r = r.start.min(n_points)..r.end.min(n_points);
        if r.is_empty() {
            continue;
        }
        if r.start > covered {
            gaps.push(covered..r.start);
        } else if let Some(j) = last
            && r.start < covered
        {
            problems.push(format!(
                "{} and {} hold the same points twice; keep one of them",
                describe(j),
                describe(k)
            ));
        }
        if r.end > covered {
            covered = r.end;
            last = Some(k);
        }
    }
    if covered < n_points {
        gaps.push(covered..n_points);
    }
    if !gaps.is_empty() {
        let n = shards[0].1.part.count;
        let mut idx: Vec<usize> = Vec::new();
        for g in &gaps {
            for i in Part::owner(g.start, n_points, n)..=Part::owner(g.end - 1, n_points, n) {
                if idx.last() != Some(&i) {
                    idx.push(i);
                }
            }
        }
        let list: Vec<String> = idx.iter().map(|i| i.to_string()).collect();
        problems.push(format!(
            "missing shard(s) {} of {n}: no file holds their points; resubmit exactly these indices (sbatch \
             --array={} ...), then merge again",
            list.join(", "),
            list.join(",")
        ));
    }
    problems
}
