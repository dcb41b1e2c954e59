//! HDF5 store of Monte Carlo runs: one file per run, readable by h5py and h5dump ([`RunWriter`] writes,
//! [`RunFile`] reads, [`layout`] names every group, dataset and attribute). The file format is described
//! once, in `docs/run-file-format.md`, included here:
//!
#![doc = include_str!("../../docs/run-file-format.md")]

pub mod checksum;
mod chunks;
pub mod layout;
mod merge_options;
mod parts;
mod rainflow;
mod reader;
mod response_histogram;
pub mod transient_series;
mod writer;

pub use merge_options::MergeOptions;
pub use parts::{find_run_files, MergedFrom, PartFile, PartSet, RawStorage, VirtualSource};
pub use rainflow::RainflowHistogram;
pub use reader::{abbreviated_list, RunFile, RunInfo, Verification, LISTED_FILES};
pub use response_histogram::ResponseHistogram;
pub(crate) use writer::metadata_differences;
pub use writer::RunWriter;
pub use writer::{process_alive, CreateOptions, GENERATOR_VERSION};

use crate::error::{Error, Result};
use crate::estimate::Interval;
use std::path::{Path, PathBuf};

/// The kind of file `simulate` and `merge` write, for the output rule ([`crate::io_rules::check_output`]): a
/// stochvib run file (an HDF5 file with `@format_version`); `--overwrite` replaces only such files.
pub const RUN_FILE: crate::io_rules::OutputKind = crate::io_rules::OutputKind {
    what: "stochvib run file",
    recognizes: writer::is_run_file,
    replaceable: false,
};

/// Compression of the raw signal datasets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(into = "String")]
pub enum Compression {
    /// Stored as is (the default: raw noise barely compresses and deflate is ~30× slower than the disk).
    #[default]
    None,
    /// Byte shuffle followed by deflate (gzip) at `level` 1 (fastest) … 9 (smallest).
    Deflate {
        /// Deflate level, 1–9.
        level: u8,
    },
}

impl Compression {
    /// Fastest deflate level.
    pub const DEFLATE_FAST: Compression = Compression::Deflate { level: 1 };
    /// zlib's default level, a compromise of speed and size.
    pub const DEFLATE_DEFAULT: Compression = Compression::Deflate { level: 6 };
    /// Smallest output.
    pub const DEFLATE_BEST: Compression = Compression::Deflate { level: 9 };

    /// Parses `"none"`, `"deflate"` (level 6), `"deflate:<1-9>"`, `"fast"`, `"best"`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `compression` for any other text.
    ///
    /// # Examples
    /// ```
    /// use stochvib::store::Compression;
    /// assert_eq!(Compression::parse("deflate:4").unwrap(), Compression::Deflate { level: 4 });
    /// assert_eq!(Compression::parse("none").unwrap(), Compression::None);
    /// assert!(Compression::parse("deflate:12").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Compression> {
        let t = text.trim().to_ascii_lowercase();
        let bad = || {
            Error::invalid(
                "compression",
                text,
                "expected `none`, `fast`, `best`, `deflate` or `deflate:<level 1-9>`",
            )
        };
        match t.as_str() {
            "none" => Ok(Compression::None),
            "fast" => Ok(Compression::DEFLATE_FAST),
            "best" => Ok(Compression::DEFLATE_BEST),
            "deflate" | "gzip" => Ok(Compression::DEFLATE_DEFAULT),
            _ => {
                let level = t
                    .strip_prefix("deflate:")
                    .or_else(|| t.strip_prefix("gzip:"))
                    .ok_or_else(bad)?
                    .parse::<u8>()
                    .map_err(|_| bad())?;
                if (1..=9).contains(&level) {
                    Ok(Compression::Deflate { level })
                } else {
                    Err(bad())
                }
            }
        }
    }

    /// The text stored in the `@compression` attribute (`"none"` or `"deflate:<level>"`).
    pub fn label(&self) -> String {
        match self {
            Compression::None => "none".to_string(),
            Compression::Deflate { level } => format!("deflate:{level}"),
        }
    }
}

impl From<Compression> for String {
    fn from(c: Compression) -> String {
        c.label()
    }
}

impl std::str::FromStr for Compression {
    type Err = Error;
    /// As [`Compression::parse`].
    fn from_str(text: &str) -> Result<Compression> {
        Compression::parse(text)
    }
}

/// A named signal with its physical unit (e.g. `("x1_acc", "m/s^2")`).
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Signal {
    /// Dataset name: non-empty, no `/`, not `.`, unique within its group.
    pub name: String,
    /// Unit text, e.g. `m`, `m/s^2`, `N`.
    pub unit: String,
}

impl Signal {
    /// Shorthand constructor.
    pub fn new(name: &str, unit: &str) -> Signal {
        Signal {
            name: name.to_string(),
            unit: unit.to_string(),
        }
    }
}

/// One part of what a run was resolved from (the spectrum file's text, the model with its parameters, ...),
/// stored in `/provenance`.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Provenance {
    /// Name, e.g. `spectrum`.
    pub name: String,
    /// The text.
    pub text: String,
    /// Whether the part identifies the run (compared when resuming or merging), or only informs (e.g. the
    /// directory a spectrum was found in).
    pub identifies: bool,
}

impl Provenance {
    /// A part that identifies the run.
    pub fn identity(name: &str, text: impl Into<String>) -> Provenance {
        Provenance {
            name: name.to_string(),
            text: text.into(),
            identifies: true,
        }
    }

    /// A part that only informs.
    pub fn note(name: &str, text: impl Into<String>) -> Provenance {
        Provenance {
            name: name.to_string(),
            text: text.into(),
            identifies: false,
        }
    }
}

/// A cluster shard of a run: the file holding the `index`-th of `count` parts (`stochvib simulate --shard I
/// --of N`). A part holds whole internal shards (of [`RunMetadata::shard_size`] realizations), so that a merge
/// adds the per-shard accumulators in the same order as a single-process run with the same shard size.
///
/// # Formula
/// With B = ⌈R/shard_size⌉ internal shards, internal shard b belongs to part ⌊b·N/B⌋; part I holds the
/// internal shards ⌈I·B/N⌉ ≤ b < ⌈(I+1)·B/N⌉ (at least one each when N ≤ B), hence the realizations
/// ⌈I·B/N⌉·shard_size ≤ i < min(⌈(I+1)·B/N⌉·shard_size, R).
///
/// # Examples
/// ```
/// use stochvib::store::Part;
/// let p = Part::new(1, 3).unwrap();
/// // 8 internal shards over 3 parts: 0..3, 3..6, 6..8
/// assert_eq!(p.shards(8), 3..6);
/// assert_eq!(Part::owner(5, 8, 3), 1);
/// assert!(Part::new(3, 3).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Part {
    /// I, 0 ≤ I < N.
    pub index: usize,
    /// N, the number of parts of the run.
    pub count: usize,
}

impl Part {
    /// Part `index` of `count`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `shard` for `index` outside [0, count), or `of` for `count` = 0.
    pub fn new(index: usize, count: usize) -> Result<Part> {
        if count == 0 {
            return Err(Error::invalid("of", 0, "the number of shards must be >= 1"));
        }
        if index >= count {
            return Err(Error::invalid(
                "shard",
                index,
                format!("a shard index lies in [0, {count}) for --of {count} (indices start at 0)"),
            ));
        }
        Ok(Part { index, count })
    }

    /// The internal shards of this part among `n_shards`: ⌈I·B/N⌉ .. ⌈(I+1)·B/N⌉.
    pub fn shards(&self, n_shards: usize) -> std::ops::Range<usize> {
        let edge = |i: usize| ((i as u128 * n_shards as u128).div_ceil(self.count as u128)) as usize;
        edge(self.index)..edge(self.index + 1)
    }

    /// The part ⌊b·N/B⌋ that internal shard `shard` of `n_shards` belongs to when the run has `count` parts.
    pub fn owner(shard: usize, n_shards: usize, count: usize) -> usize {
        (shard as u128 * count as u128 / n_shards.max(1) as u128) as usize
    }

    /// The file name of this part in a run directory: `shard-<I>-of-<N>.h5`, I zero-padded to the width of
    /// N − 1 so that the names sort in shard order.
    ///
    /// # Examples
    /// ```
    /// assert_eq!(stochvib::store::Part::new(3, 16).unwrap().file_name(), "shard-03-of-16.h5");
    /// ```
    pub fn file_name(&self) -> String {
        let width = (self.count - 1).max(1).to_string().len();
        format!("shard-{:0width$}-of-{}.h5", self.index, self.count)
    }
}

/// Everything that identifies a run; stored as root attributes and compared when resuming.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RunMetadata {
    /// The scenario file text (TOML), verbatim.
    pub scenario_text: String,
    /// Master seed.
    pub seed: u64,
    /// Name of the random generator / synthesis method.
    pub generator: String,
    /// Time step, s.
    pub dt: f64,
    /// Samples per realization.
    pub n_samples: usize,
    /// Number of realizations.
    pub n_realizations: usize,
    /// Realizations per shard (the unit of writing and of resuming).
    pub shard_size: usize,
    /// Excitation signals.
    pub inputs: Vec<Signal>,
    /// Response signals.
    pub outputs: Vec<Signal>,
    /// Per-shard accumulators `(name, length)`: vectors of partial results written with each shard.
    pub accumulators: Vec<(String, usize)>,
    /// Whether the raw realizations are stored (optional for large batches).
    pub store_raw: bool,
    /// Compression of the raw datasets.
    pub compression: Compression,
    /// What the run was resolved from besides the scenario text (empty in format-version-1 files).
    pub provenance: Vec<Provenance>,
    /// The part of the run this file holds (a shard file of `stochvib simulate --shard I --of N`), or `None`
    /// for a whole run. Not serialised when `None`, so the digest of a whole run is that of format 2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub part: Option<Part>,
}

impl RunMetadata {
    /// CRC-32 of the metadata's canonical JSON form ([`checksum::crc32`]): stored as `@metadata_crc32`
    /// and checked when the file is opened.
    pub fn digest(&self) -> u32 {
        let mut canonical = self.clone();
        canonical.provenance.sort_by(|a, b| a.name.cmp(&b.name));
        checksum::crc32(serde_json::to_string(&canonical).unwrap_or_default().as_bytes())
    }

    /// Upper bound of the bytes the run file takes on disk: raw datasets, accumulators, checksums.
    pub fn estimated_file_bytes(&self) -> u128 {
        let raw_signals = if self.store_raw {
            (self.inputs.len() + self.outputs.len()) as u128
        } else {
            0
        };
        let (rows, shards) = (
            self.local_realizations().len() as u128,
            self.local_shards().len() as u128,
        );
        let raw = raw_signals * rows * self.n_samples as u128 * 8;
        let acc: u128 = self.accumulators.iter().map(|a| a.1 as u128).sum::<u128>() * 8 * shards;
        let checks = (raw_signals + self.accumulators.len() as u128 + 1) * 4 * shards;
        raw + acc + checks + (1 << 20)
    }
    /// Number of shards, ⌈n_realizations / shard_size⌉.
    pub fn n_shards(&self) -> usize {
        self.n_realizations.div_ceil(self.shard_size.max(1))
    }

    /// Realizations of shard `shard`: `[shard·shard_size, min((shard+1)·shard_size, n_realizations))`.
    pub fn shard_range(&self, shard: usize) -> std::ops::Range<usize> {
        let start = (shard * self.shard_size).min(self.n_realizations);
        start..(start + self.shard_size).min(self.n_realizations)
    }

    /// The internal shards this file holds: all of them for a whole run, those of its [`Part`] otherwise.
    pub fn local_shards(&self) -> std::ops::Range<usize> {
        match self.part {
            None => 0..self.n_shards(),
            Some(p) => p.shards(self.n_shards()),
        }
    }

    /// The realizations this file holds (rows of its raw datasets, in order).
    pub fn local_realizations(&self) -> std::ops::Range<usize> {
        let s = self.local_shards();
        if s.is_empty() {
            return 0..0;
        }
        self.shard_range(s.start).start..self.shard_range(s.end - 1).end
    }

    /// The same metadata without the part: what every shard file of one run has in common.
    pub fn whole(&self) -> RunMetadata {
        RunMetadata {
            part: None,
            ..self.clone()
        }
    }

    /// Checks sizes, names and the time step.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the field: zero sizes, non-positive `dt`, a bad or duplicate
    /// name, a compression level outside 1–9, a scenario text containing a NUL character.
    pub fn validate(&self) -> Result<()> {
        crate::error::require_positive("dt", self.dt)?;
        for (name, v) in [
            ("n_samples", self.n_samples),
            ("n_realizations", self.n_realizations),
            ("shard_size", self.shard_size),
        ] {
            if v == 0 {
                return Err(Error::invalid(name, v, "must be >= 1"));
            }
        }
        if let Compression::Deflate { level } = self.compression
            && !(1..=9).contains(&level)
        {
            return Err(Error::invalid("compression", level, "deflate level must be 1-9"));
        }
        for (field, text) in [("scenario_text", &self.scenario_text), ("generator", &self.generator)]
            .into_iter()
            .chain(self.provenance.iter().map(|p| ("provenance", &p.text)))
        {
            if text.contains('\0') {
                return Err(Error::invalid(field, "<text>", "must not contain a NUL character"));
            }
        }
        for (i, p) in self.provenance.iter().enumerate() {
            check_name("provenance", &p.name)?;
            if self.provenance[..i].iter().any(|q| q.name == p.name) {
                return Err(Error::invalid("provenance", &p.name, "duplicate name"));
            }
        }
        let groups = [
            (
                "inputs",
                self.inputs.iter().map(|s| s.name.as_str()).collect::<Vec<_>>(),
            ),
            ("outputs", self.outputs.iter().map(|s| s.name.as_str()).collect()),
            ("accumulators", self.accumulators.iter().map(|a| a.0.as_str()).collect()),
        ];
        for (field, names) in groups {
            for (i, n) in names.iter().enumerate() {
                check_name(field, n)?;
                if names[..i].contains(n) {
                    return Err(Error::invalid(field, n, "duplicate name"));
                }
            }
        }
        for s in self.inputs.iter().chain(&self.outputs) {
            if s.unit.contains('\0') {
                return Err(Error::invalid("unit", &s.unit, "must not contain a NUL character"));
            }
        }
        if self.accumulators.iter().any(|a| a.0 == layout::DS_SHARDS_COMPLETE) {
            return Err(Error::invalid(
                "accumulators",
                layout::DS_SHARDS_COMPLETE,
                "name is reserved",
            ));
        }
        if let Some((n, _)) = self.accumulators.iter().find(|a| a.1 == 0) {
            return Err(Error::invalid("accumulators", n, "length must be >= 1"));
        }
        if let Some(p) = self.part {
            Part::new(p.index, p.count)?;
            if p.count > self.n_shards() {
                return Err(Error::invalid(
                    "of",
                    p.count,
                    format!(
                        "{} shards need at least {} internal shards, but {} realizations in internal shards of \
                         --shard-size {} make only {}: a shard file holds whole internal shards, so that the merge \
                         is bit-identical to a single-process run with the same --shard-size; use --of <= {} or a \
                         smaller --shard-size (<= {})",
                        p.count,
                        p.count,
                        self.n_realizations,
                        self.shard_size,
                        self.n_shards(),
                        self.n_shards(),
                        (self.n_realizations / p.count).max(1)
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Checks a name used as an HDF5 link name.
fn check_name(field: &str, name: &str) -> Result<()> {
    if name.is_empty() || name == "." || name.contains('/') || name.contains('\0') {
        Err(Error::invalid(
            field,
            name,
            "a name must be non-empty, not `.`, without `/` or NUL",
        ))
    } else {
        Ok(())
    }
}

/// One across-realization statistic of one output, with its interval and optional analytic value.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Statistic {
    /// Name, e.g. `mean`, `variance`, `sigma`.
    pub name: String,
    /// Estimate and interval (serialised flat: `estimate`, `lower`, `upper`, `confidence`).
    #[serde(flatten)]
    pub interval: Interval,
    /// Unit of the estimate, e.g. `m^2` for a variance of a displacement.
    pub unit: String,
    /// How it was estimated (free text, e.g. `Student-t`, `chi-square`).
    pub method: String,
    /// Analytic value, if known.
    pub analytic: Option<f64>,
    /// Whether the interval covers the analytic value (stored only with `analytic`).
    pub covers: Option<bool>,
}

/// The statistics of one output.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct OutputStatistics {
    /// Output name (as in [`RunMetadata::outputs`]).
    pub output: String,
    /// Unit of the output signal.
    pub unit: String,
    /// Number of realizations the statistics were computed from.
    pub n_used: u64,
    /// The statistics, in order.
    pub statistics: Vec<Statistic>,
}

impl Statistic {
    /// CRC-32 of the statistic's values and texts (stored as its `@crc32`).
    pub fn checksum(&self) -> u32 {
        let mut c = checksum::Crc32::default();
        let iv = &self.interval;
        c.update_f64(&[
            iv.estimate,
            iv.lower,
            iv.upper,
            iv.confidence,
            self.analytic.unwrap_or(f64::NAN),
        ]);
        c.update(&[self.covers.map_or(2, u8::from)]);
        for s in [&self.name, &self.unit, &self.method] {
            c.update(s.as_bytes());
            c.update(&[0]);
        }
        c.finish()
    }
}

impl OutputStatistics {
    /// The statistic called `name`, if present.
    pub fn get(&self, name: &str) -> Option<&Statistic> {
        self.statistics.iter().find(|s| s.name == name)
    }
}

/// A spectral density estimate of one output in the crate's canonical convention (two-sided angular,
/// variance = ∫_{-∞}^{∞} S(ω) dω), stored for ω ≥ 0.
#[derive(Debug, Clone, PartialEq)]
pub struct PsdEstimate {
    /// Output name.
    pub output: String,
    /// Unit of the density, e.g. `m^2 s/rad`.
    pub unit: String,
    /// Angular frequencies ω, rad/s.
    pub omega: Vec<f64>,
    /// Estimated S(ω).
    pub density: Vec<f64>,
    /// Lower interval bound.
    pub lower: Vec<f64>,
    /// Upper interval bound.
    pub upper: Vec<f64>,
    /// Analytic S(ω) at the same ω, if known (the continuous-time density).
    pub analytic: Option<Vec<f64>>,
    /// The exact mean of the estimate, if known: the window's spectral kernel convolved with the density of
    /// the simulated (sampled, aliased) process — what the interval should cover.
    pub expected: Option<Vec<f64>>,
    /// χ² degrees of freedom ν of the interval (2K for K averaged segments).
    pub dof: f64,
    /// Confidence level of the interval.
    pub confidence: f64,
    /// How it was estimated (free text, e.g. `Welch, Hann, 50 % overlap`).
    pub method: String,
}

impl PsdEstimate {
    /// CRC-32 of the estimate's arrays, numbers and texts (stored as the `@crc32` of its group).
    pub fn checksum(&self) -> u32 {
        let mut c = checksum::Crc32::default();
        for a in [&self.omega, &self.density, &self.lower, &self.upper] {
            c.update_f64(a);
        }
        if let Some(a) = &self.analytic {
            c.update_f64(a);
        }
        if let Some(a) = &self.expected {
            c.update(b"expected");
            c.update_f64(a);
        }
        c.update_f64(&[self.dof, self.confidence]);
        for s in [&self.output, &self.unit, &self.method] {
            c.update(s.as_bytes());
            c.update(&[0]);
        }
        c.finish()
    }
}

impl PsdEstimate {
    /// Bins where the estimate measures the density: the expected estimate is within
    /// [`RESOLVED_BIAS`] of the continuous-time density, |E Ŝ(ω_j)/S(ω_j) − 1| ≤ 0.25 (`None` without an
    /// expectation or an analytic density). Elsewhere the window's leakage from stronger bins, the filling of
    /// a notch or aliasing near the Nyquist frequency dominates the estimate: there the χ² band is a band on
    /// a few strong distant lines, narrower than the estimate's real scatter, and says little about S.
    pub fn resolved(&self) -> Option<Vec<bool>> {
        let (e, a) = (self.expected.as_ref()?, self.analytic.as_ref()?);
        Some(
            e.iter()
                .zip(a)
                .map(|(e, a)| *a > 0.0 && (e / a - 1.0).abs() <= RESOLVED_BIAS)
                .collect(),
        )
    }

    /// How many bins have their expectation inside the interval, in all and among the
    /// [`resolved`](Self::resolved) bins (`None` without an expectation).
    pub fn coverage(&self) -> Option<Coverage> {
        let e = self.expected.as_ref()?;
        let resolved = self.resolved().unwrap_or_else(|| vec![false; e.len()]);
        let mut c = Coverage {
            bins: e.len(),
            ..Coverage::default()
        };
        for ((v, (lo, hi)), r) in e.iter().zip(self.lower.iter().zip(&self.upper)).zip(resolved) {
            let inside = *lo <= *v && *v <= *hi;
            c.covered += usize::from(inside);
            c.resolved += usize::from(r);
            c.covered_resolved += usize::from(inside && r);
        }
        Some(c)
    }
}

/// Largest relative difference between the expected Welch estimate and the continuous-time density at a
/// bin still counted as resolved ([`PsdEstimate::resolved`]).
pub const RESOLVED_BIAS: f64 = 0.25;

/// How often the χ² band of a [`PsdEstimate`] covers the estimate's exact mean.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Coverage {
    /// Bins with an expectation.
    pub bins: usize,
    /// Of them, bins whose band covers it.
    pub covered: usize,
    /// Resolved bins ([`PsdEstimate::resolved`]).
    pub resolved: usize,
    /// Resolved bins whose band covers the expectation: at about the confidence level.
    pub covered_resolved: usize,
}

/// Which group a raw signal lives in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SignalGroup {
    /// `/inputs`.
    Inputs,
    /// `/outputs`.
    Outputs,
}

impl SignalGroup {
    /// The group name in the file.
    pub fn group_name(&self) -> &'static str {
        match self {
            SignalGroup::Inputs => layout::GROUP_INPUTS,
            SignalGroup::Outputs => layout::GROUP_OUTPUTS,
        }
    }
}

/// `<final>.tmp`, the name a run is written under until it is complete.
///
/// # Examples
/// ```
/// use std::path::Path;
/// assert_eq!(stochvib::store::tmp_path(Path::new("out/run.h5")), Path::new("out/run.h5.tmp"));
/// ```
pub fn tmp_path(final_path: &Path) -> PathBuf {
    let mut name = final_path.file_name().map(|n| n.to_os_string()).unwrap_or_default();
    name.push(layout::TMP_SUFFIX);
    final_path.with_file_name(name)
}

/// Maps an HDF5 error to [`Error::Hdf5`] with the path and a context phrase.
pub(crate) fn h5err(path: &Path, context: &str) -> impl Fn(hdf5::Error) -> Error + 'static + use<> {
    let context = context.to_string();
    let path = path.to_path_buf();
    move |e| Error::Hdf5 {
        path: path.clone(),
        reason: format!("{context}: {e}"),
    }
}

/// How [`open_sec2`] opens a file.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum OpenMode {
    /// Create; fail if the file exists.
    CreateExcl,
    /// Read and write an existing file.
    ReadWrite,
    /// Read only.
    Read,
}

/// Opens an HDF5 file with the POSIX (sec2) driver, whatever `HDF5_DRIVER` says, `customize`d (file-access
/// options), and marks its descriptor close-on-exec.
///
/// HDF5 opens files without `O_CLOEXEC`, so a child process started while a run file is open (a user's
/// `Command`, a test harness starting helpers) would inherit the descriptor and with it HDF5's `flock` on
/// the file: after the writer closes and renames the file, opening it again would fail with "unable to
/// lock file" until that child exits. The open and the `fcntl` happen under one hold of the HDF5 library
/// lock, so no other HDF5 call can delay the `fcntl`; a child forked in the microseconds between the two
/// system calls can still inherit the descriptor (HDF5 offers no way to pass `O_CLOEXEC`).
///
/// Even a descriptor marked close-on-exec lives in a child from its fork to its exec (milliseconds on a busy
/// machine): an open of an existing file that finds it locked (`EAGAIN`) is tried again after 10, 20, 40, …
/// ms, [`LOCK_RETRIES`] times (about 2.5 s in all), before the error is returned. A file really held by
/// another writer stays locked for that long and is still reported.
pub(crate) fn open_sec2(
    path: &Path,
    mode: OpenMode,
    customize: impl Fn(&mut hdf5::FileBuilder),
) -> hdf5::Result<hdf5::File> {
    let open = || {
        hdf5::sync::sync(|| {
            let mut b = hdf5::File::with_options();
            b.with_fapl(|p| p.sec2());
            customize(&mut b);
            let file = match mode {
                OpenMode::CreateExcl => b.create_excl(path),
                OpenMode::ReadWrite => b.open_rw(path),
                OpenMode::Read => b.open(path),
            }?;
            close_on_exec(&file);
            Ok(file)
        })
    };
    let mut wait = std::time::Duration::from_millis(10);
    for _ in 0..LOCK_RETRIES {
        match open() {
            Err(e) if mode != OpenMode::CreateExcl && is_lock_busy(&e) => std::thread::sleep(wait),
            other => return other,
        }
        wait *= 2;
    }
    open()
}

/// Retries of an open that found the file locked ([`open_sec2`]).
const LOCK_RETRIES: usize = 8;

/// Whether HDF5 refused an open because another open file description holds the file's lock.
fn is_lock_busy(e: &hdf5::Error) -> bool {
    let text = e.to_string();
    text.contains("unable to lock file") && text.contains("errno = 11")
}

/// Starts a child process so that it inherits no descriptor of a run file: the spawn runs under HDF5's
/// global lock, which every open of a run file holds from its open(2) to the `FD_CLOEXEC` that follows it.
///
/// Why: HDF5 locks each file it opens with flock(2), a lock of the open file description that a forked
/// child shares through its copy of the descriptor. A fork by another thread between HDF5's open(2) and
/// the close-on-exec flag leaves the descriptor, and the lock, in the child for its whole life; a later
/// open of the same file by this process then fails with "unable to lock file". A program that opens run
/// files on some threads and starts processes on others (a test harness, a GUI, a service) starts them
/// through this function. `Command::spawn` returns once the child has exec'd (or failed to), so no
/// descriptor outlives the call in the child.
///
/// # Errors
/// What [`std::process::Command::spawn`] returns.
pub fn spawn_child(cmd: &mut std::process::Command) -> std::io::Result<std::process::Child> {
    hdf5::sync::sync(|| cmd.spawn())
}

/// Marks the descriptor of a file opened with the sec2 driver close-on-exec (best effort: nothing happens
/// where the handle cannot be obtained).
fn close_on_exec(file: &hdf5::File) {
    #[cfg(unix)]
    hdf5::sync::sync(|| {
        let mut handle: *mut std::ffi::c_void = std::ptr::null_mut();
        // SAFETY: `file` is open with the sec2 driver (open_sec2), whose VFD handle is a pointer to its
        // `int` descriptor, valid while the file is open; fcntl on a valid descriptor has no other effect.
        unsafe {
            let rc = hdf5_sys::h5f::H5Fget_vfd_handle(file.id(), hdf5_sys::h5p::H5P_DEFAULT, &mut handle);
            if rc >= 0 && !handle.is_null() {
                let fd = *(handle as *const libc::c_int);
                let flags = libc::fcntl(fd, libc::F_GETFD);
                if flags >= 0 {
                    libc::fcntl(fd, libc::F_SETFD, flags | libc::FD_CLOEXEC);
                }
            }
        }
    });
}
