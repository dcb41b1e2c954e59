//! Names of every group, dataset and attribute of a run file, the format version, and the chunking rule.
//!
//! These constants are the single source of truth for the layout documented in [`crate::store`]; the
//! writer, the reader and the tests all use them.

/// Version of the file layout of a whole run written by one process. Incremented on any incompatible change;
/// a reader refuses versions newer than [`NEWEST_FORMAT_VERSION`].
pub const FORMAT_VERSION: u32 = 2;

/// Version of the files that use the layout additions of version 3: shard files (`@part_index`, rows and
/// shard records of one part only) and merged files whose raw datasets are virtual (`/parts`). Readers of
/// version 2 must refuse them (they would read a shard file's rows as the first realizations, or a
/// virtual dataset whose source files are missing as fill values). Every other file is still written as
/// [`FORMAT_VERSION`].
pub const FORMAT_VERSION_PARTS: u32 = 3;

/// The newest version this crate reads (it reads every version from 1 up to this one).
pub const NEWEST_FORMAT_VERSION: u32 = 3;

/// Version of the crate that wrote the file (`CARGO_PKG_VERSION`).
pub const TOOLKIT_VERSION: &str = env!("CARGO_PKG_VERSION");

/// Suffix appended to the final file name while a run is being written (`run.h5` → `run.h5.tmp`).
pub const TMP_SUFFIX: &str = ".tmp";
/// Suffix of the file next to a `.tmp` that names the process writing it (`run.h5.tmp.owner`: its pid).
pub const OWNER_SUFFIX: &str = ".owner";

// ---- root attributes ----

/// Root attribute, u32: [`FORMAT_VERSION`] of the writer.
pub const ATTR_FORMAT_VERSION: &str = "format_version";
/// Root attribute, string: crate version of the writer.
pub const ATTR_TOOLKIT_VERSION: &str = "toolkit_version";
/// Root attribute, string: the scenario file (TOML) the run was made from, verbatim.
pub const ATTR_SCENARIO: &str = "scenario";
/// Root attribute, u64: master seed of the run.
pub const ATTR_SEED: &str = "seed";
/// Root attribute, string: name of the random generator / synthesis method (e.g. `xoshiro256++`).
pub const ATTR_GENERATOR: &str = "generator";
/// Root attribute, f64: time step in seconds.
pub const ATTR_DT: &str = "dt";
/// Root attribute, string: unit system statement (`"SI"`; time in s, ω in rad/s; per-signal `unit`).
pub const ATTR_UNITS: &str = "units";
/// Root attribute, u64: samples per realization (columns of every signal dataset).
pub const ATTR_N_SAMPLES: &str = "n_samples";
/// Root attribute, u64: number of realizations (rows of every signal dataset).
pub const ATTR_N_REALIZATIONS: &str = "n_realizations";
/// Root attribute, u64: realizations per shard (the last shard may be shorter).
pub const ATTR_SHARD_SIZE: &str = "shard_size";
/// Root attribute, u64: number of shards, ⌈n_realizations / shard_size⌉.
pub const ATTR_N_SHARDS: &str = "n_shards";
/// Root attribute, u8 (0/1): whether the raw realizations are stored in `/inputs` and `/outputs`.
pub const ATTR_STORE_RAW: &str = "store_raw";
/// Root attribute, string: compression of the raw datasets (`"none"` or `"deflate:<level>"`).
pub const ATTR_COMPRESSION: &str = "compression";
/// Root attribute, u8 = 1: written last, just before the rename; a file without it is incomplete.
pub const ATTR_COMPLETE: &str = "complete";
/// Root attribute, u32 (format ≥ 2): CRC-32 of the run metadata's canonical form (`RunMetadata::digest`).
pub const ATTR_METADATA_CRC32: &str = "metadata_crc32";

// ---- shard files (format 3): the part of the run the file holds ----

/// Root attribute of a shard file, u64: I, the index of the part (0 ≤ I < N).
pub const ATTR_PART_INDEX: &str = "part_index";
/// Root attribute of a shard file, u64: N, the number of parts of the run.
pub const ATTR_PART_COUNT: &str = "part_count";
/// Root attribute of a shard file, u64: the first internal shard it holds, ⌈I·B/N⌉ (row 0 of `/shards/*`).
pub const ATTR_FIRST_SHARD: &str = "first_shard";
/// Root attribute of a shard file, u64: the number of internal shards it holds (rows of `/shards/*`).
pub const ATTR_PART_SHARDS: &str = "part_shards";
/// Root attribute of a shard file, u64: the first realization it holds (row 0 of the raw datasets).
pub const ATTR_FIRST_REALIZATION: &str = "first_realization";
/// Root attribute of a shard file, u64: the number of realizations it holds (rows of the raw datasets).
pub const ATTR_PART_REALIZATIONS: &str = "part_realizations";
/// Root attribute of a shard file, u32 (optional): CRC-32 of the fingerprint of the values every shard
/// file of the run stores identically (each statistic's name and `@analytic`, every density's `analytic`
/// and `expected`, every rainflow histogram's `edges` and `dirlik`), so that a merge compares the files
/// without opening their statistics; written when the file is finished.
pub const ATTR_SHARED_CRC32: &str = "shared_crc32";
/// Root attribute of a shard file, u32 (optional): CRC-32 of the confidence levels of its statistics.
pub const ATTR_CONFIDENCE_CRC32: &str = "confidence_crc32";

// ---- /parts: what a merged file was merged from ----

/// Group of a merged file: the shard files it was merged from, one entry per part in shard order.
pub const GROUP_PARTS: &str = "parts";
/// Attribute of `/parts`, string array: each shard file's path as the virtual datasets reference it
/// (relative to the merged file's directory unless absolute).
pub const ATTR_PART_FILES: &str = "files";
/// Attribute of `/parts`, u64 array: the first realization of each shard file.
pub const ATTR_PART_FIRST_REALIZATIONS: &str = "first_realizations";
/// Attribute of `/parts`, u64 array: the number of realizations of each shard file.
pub const ATTR_PART_REALIZATION_COUNTS: &str = "realizations";
/// Attribute of `/parts`, string: where the raw realizations are: `virtual` (virtual datasets mapping the
/// shard files' rows), `copied` (copied into the merged file) or `none` (statistics only).
pub const ATTR_RAW_STORAGE: &str = "raw";

// ---- /provenance (format ≥ 2) ----

/// Group of what the run was resolved from: one string attribute per part.
pub const GROUP_PROVENANCE: &str = "provenance";
/// Attribute of `/provenance`, string array: the names of the parts that identify the run (compared when
/// resuming and merging); the other parts only inform.
pub const ATTR_IDENTIFIES: &str = "identifies";

/// Dataset `/shards/checksums`, u32 `[n_shards, n_checked]` (format ≥ 2): CRC-32 of each shard's rows of every
/// raw input, raw output, then accumulator, in that order (the columns are named by `@checked`).
pub const DS_SHARDS_CHECKSUMS: &str = "checksums";
/// Attribute of `/shards/checksums`, string array: the dataset path of each column.
pub const ATTR_CHECKED: &str = "checked";
/// Attribute of a statistic dataset or a PSD group, u32 (format ≥ 2): CRC-32 of its values.
pub const ATTR_CRC32: &str = "crc32";

/// The value of [`ATTR_UNITS`].
pub const UNITS_VALUE: &str = "SI (time s, angular frequency rad/s); each signal has its own `unit` attribute";

// ---- groups ----

/// Group of the excitation signals (one dataset per input when raw data are stored).
pub const GROUP_INPUTS: &str = "inputs";
/// Group of the response signals (one dataset per output when raw data are stored).
pub const GROUP_OUTPUTS: &str = "outputs";
/// Group recording shard completion and per-shard accumulators.
pub const GROUP_SHARDS: &str = "shards";
/// Group of across-realization statistics, one subgroup per output.
pub const GROUP_STATISTICS: &str = "statistics";
/// Group of spectral density estimates, one subgroup per output.
pub const GROUP_PSD: &str = "psd";
/// Group of the rainflow range histograms of fatigue verdict channels (optional).
pub const GROUP_RAINFLOW: &str = "rainflow";
/// Dataset of a rainflow histogram: range edges.
pub const DS_EDGES: &str = "edges";
/// Dataset of a rainflow histogram: cycles per bin per realization.
pub const DS_COUNTS: &str = "counts";
/// Dataset of a rainflow histogram: Dirlik's expected cycles per bin (optional).
pub const DS_DIRLIK: &str = "dirlik";
/// Attribute of a rainflow histogram: cycles above the top edge per realization.
pub const ATTR_OVERFLOW: &str = "overflow";

// ---- attributes of /inputs and /outputs ----

/// Group attribute, string array: signal names in order (present even when raw data are not stored).
pub const ATTR_NAMES: &str = "names";
/// Group attribute, string array: units of the signals, same order as [`ATTR_NAMES`].
pub const ATTR_UNITS_LIST: &str = "units";
/// Dataset attribute, string: physical unit of a signal, a statistic or a density.
pub const ATTR_UNIT: &str = "unit";

// ---- /shards ----

/// Dataset `/shards/complete`, u8 `[n_shards]`: 1 once the shard's data are flushed to disk.
pub const DS_SHARDS_COMPLETE: &str = "complete";
/// Group attribute of `/shards`, string array: accumulator names in order.
pub const ATTR_ACCUMULATORS: &str = "accumulators";

// ---- /statistics/<output>/<statistic> ----

/// Group attribute of `/statistics/<output>`, u64: realizations the statistics were computed from.
pub const ATTR_N_USED: &str = "n_used";
/// Attribute of a statistic dataset, f64: lower interval bound.
pub const ATTR_LOWER: &str = "lower";
/// Attribute of a statistic dataset, f64: upper interval bound.
pub const ATTR_UPPER: &str = "upper";
/// Attribute of a statistic dataset / PSD group, f64: confidence level of the interval (e.g. 0.95).
pub const ATTR_CONFIDENCE: &str = "confidence";
/// Attribute of a statistic dataset, f64 (optional): analytic value.
pub const ATTR_ANALYTIC: &str = "analytic";
/// Attribute of a statistic dataset, u8 0/1 (optional, only with `analytic`): interval covers it.
pub const ATTR_COVERS: &str = "covers";
/// Attribute of a statistic dataset / PSD group, string: how it was estimated (free text).
pub const ATTR_METHOD: &str = "method";

// ---- /psd/<output> ----

/// Dataset, f64 `[n_freq]`: angular frequencies ω in rad/s.
pub const DS_OMEGA: &str = "omega";
/// Dataset, f64 `[n_freq]`: estimated two-sided density S(ω).
pub const DS_DENSITY: &str = "density";
/// Dataset, f64 `[n_freq]`: lower interval bound of the density.
pub const DS_LOWER: &str = "lower";
/// Dataset, f64 `[n_freq]`: upper interval bound of the density.
pub const DS_UPPER: &str = "upper";
/// Dataset, f64 `[n_freq]` (optional): analytic density at the same ω.
pub const DS_ANALYTIC: &str = "analytic";
/// Dataset, f64 `[n_freq]` (optional, format ≥ 2): the exact mean of the estimate (window kernel ⊛ density of
/// the simulated sampled process).
pub const DS_EXPECTED: &str = "expected";
/// Group attribute, string: the density convention ([`PSD_CONVENTION`]).
pub const ATTR_CONVENTION: &str = "convention";
/// Group attribute, f64: χ² degrees of freedom ν of the interval (ν = 2K for K averaged segments).
pub const ATTR_DOF: &str = "dof";

/// The value of [`ATTR_CONVENTION`]: the crate's canonical density (see [`crate::spectrum`]).
pub const PSD_CONVENTION: &str = "two-sided angular: S(omega) for omega in rad/s, K(tau) = integral of S(omega) \
                                  exp(i omega tau) d omega over (-inf, inf), variance = integral of S d omega; \
                                  stored for omega >= 0 only";

/// Target size of one chunk of a raw signal dataset, bytes (1 MiB, HDF5's default chunk-cache size).
pub const CHUNK_TARGET_BYTES: usize = 1 << 20;
/// Largest number of columns (samples) of one chunk: 2²⁰ samples = 8 MiB of f64.
pub const CHUNK_MAX_COLUMNS: usize = 1 << 20;

/// Chunk shape `(rows, columns)` of a raw signal dataset `[n_realizations, n_samples]`.
///
/// # Formula
/// columns = min(n_samples, 2²⁰); rows = the largest divisor of `shard_size` that is
/// ≤ max(1, ⌊1 MiB / (8 · columns)⌋). Rows divide the shard so that every shard write covers whole
/// chunks (no chunk is shared by two shards: a shard's write never rewrites another shard's chunk, and
/// reading one realization touches one chunk row); a chunk stays near 1 MiB, large enough for full-speed
/// sequential writes, small enough that reading one realization does not read the whole file.
///
/// # Errors
/// None; zero arguments are treated as 1.
///
/// # Examples
/// ```
/// use stochvib::store::layout::chunk_shape;
/// // 64 samples of 8 bytes = 512 B per row; 1 MiB / 512 B = 2048 ≥ 3 rows: one chunk per shard.
/// assert_eq!(chunk_shape(64, 3), (3, 64));
/// // 2^16 samples = 512 KiB per row: 2 rows per chunk; 2 divides 10.
/// assert_eq!(chunk_shape(1 << 16, 10), (2, 1 << 16));
/// ```
pub fn chunk_shape(n_samples: usize, shard_size: usize) -> (usize, usize) {
    let columns = n_samples.clamp(1, CHUNK_MAX_COLUMNS);
    let shard = shard_size.max(1);
    let limit = (CHUNK_TARGET_BYTES / (8 * columns)).max(1).min(shard);
    let rows = (1..=limit).rev().find(|r| shard.is_multiple_of(*r)).unwrap_or(1);
    (rows, columns)
}

/// Group of the response histograms of a nonlinear run (optional: only runs of a model with nonlinear
/// elements have it); one subgroup per output ([`super::ResponseHistogram`]).
pub const GROUP_RESPONSE_HISTOGRAM: &str = "response_histogram";
/// Dataset: route 1's Gaussian density at the bin centres (optional).
pub const DS_GAUSSIAN: &str = "gaussian";
/// Dataset: the exact (Fokker–Planck) density at the bin centres (optional).
pub const DS_EXACT: &str = "exact";
/// Attribute: fraction of the samples below the first edge.
pub const ATTR_BELOW: &str = "below";
/// Attribute: fraction of the samples above the last edge.
pub const ATTR_ABOVE: &str = "above";
/// Attribute: samples counted.
pub const ATTR_SAMPLES: &str = "samples";
