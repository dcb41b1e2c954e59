//! Corruption of HDF5 run files and of interrupted runs' `.tmp` files.
//!
//! Set-up: small run files are written with the library (`load_scenario(...).simulate(...)`) in four
//! variants (statistics only; raw data; raw data with `deflate:1`; a road scenario on the spectral route),
//! and for each a `.tmp` is left by a child process that aborts after 2 of its 4 shards. The commands'
//! outputs on the intact files are the baselines.
//!
//! A case copies one of these files and damages the copy: truncation, bit flips in the first 2 KiB
//! (superblock and root object header), bit flips anywhere, bit flips inside a dataset's data (extents
//! from h5py, `ds.id.get_offset()` / `get_chunk_info()`), or a zeroed block. A complete file then goes
//! through `stochvib inspect`, `stochvib inspect --json` and `stochvib plot FILE -o DIR`; a `.tmp` through
//! `stochvib inspect` and the `simulate` command that resumes it. Every command runs as a child process
//! with a time limit and an address-space limit.
//!
//! # Classification of each command
//! * `clean-error` — non-zero exit, and stderr starts with `error:` and names the file (not a finding);
//! * `ok-same` — exit 0 and the same output as on the intact file (not a finding);
//! * `crash` — killed by a signal (SIGSEGV from libhdf5, SIGABRT from a failed allocation, ...);
//! * `panic` — exit 101;
//! * `hang` — still running at the time limit;
//! * `error-message` — non-zero exit without an `error:` line naming the file;
//! * `silent-corruption` — exit 0 with different results: statistics or density estimates of `inspect`
//!   (text or JSON), pictures of `plot` (compared byte for byte; they do not depend on the file's path),
//!   statistics of the resumed run (compared with the uninterrupted run's, bit for bit through JSON);
//! * `silent-metadata-change` (soft: reported, not asserted) — exit 0, same statistics, but other printed
//!   metadata differ (e.g. a flipped character of the stored scenario text).

use super::process::{self, Exit};
use rand::{RngExt, SeedableRng};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use stochvib::scenario::load_scenario;
use stochvib::simulate::{splitmix64, RunOptions};
use stochvib::store::{tmp_path, Compression};

/// One kind of base run file.
#[derive(Debug, Clone, Copy)]
pub struct Variant {
    /// Short name.
    pub name: &'static str,
    /// Scenario file under the source tree.
    pub scenario: &'static str,
    /// Realizations.
    pub realizations: usize,
    /// Duration, s.
    pub duration: f64,
    /// Time step, s.
    pub dt: f64,
    /// Seed.
    pub seed: u64,
    /// Realizations per shard.
    pub shard_size: usize,
    /// `--store-raw`.
    pub store_raw: bool,
    /// `--compression`.
    pub compression: &'static str,
}

/// The base files: 8 realizations in 4 shards each.
pub const VARIANTS: [Variant; 4] = [
    Variant {
        name: "stats-only",
        scenario: "data/conveyor-idler.toml",
        realizations: 8,
        duration: 2.0,
        dt: 0.01,
        seed: 5,
        shard_size: 2,
        store_raw: false,
        compression: "none",
    },
    Variant {
        name: "raw",
        scenario: "data/conveyor-idler.toml",
        realizations: 8,
        duration: 2.0,
        dt: 0.01,
        seed: 5,
        shard_size: 2,
        store_raw: true,
        compression: "none",
    },
    Variant {
        name: "raw-deflate1",
        scenario: "data/conveyor-idler.toml",
        realizations: 8,
        duration: 2.0,
        dt: 0.01,
        seed: 5,
        shard_size: 2,
        store_raw: true,
        compression: "deflate:1",
    },
    Variant {
        name: "road-spectral-raw",
        scenario: "data/quarter-car-model.toml",
        realizations: 8,
        duration: 2.0,
        dt: 0.005,
        seed: 3,
        shard_size: 2,
        store_raw: true,
        compression: "none",
    },
];

impl Variant {
    /// The library options of this variant.
    pub fn options(&self) -> RunOptions {
        let mut o = RunOptions {
            realizations: self.realizations,
            duration_s: self.duration,
            dt_s: self.dt,
            seed: self.seed,
            ..RunOptions::default()
        };
        o.shard_size = self.shard_size;
        o.store_raw = self.store_raw;
        o.compression = Compression::parse(self.compression).expect("a valid compression");
        o
    }

    /// The equivalent `stochvib simulate` arguments (output and `--json` appended by the caller).
    pub fn cli_args(&self, root: &Path) -> Vec<String> {
        let mut a = vec![
            "simulate".to_string(),
            root.join(self.scenario).display().to_string(),
            "--realizations".into(),
            self.realizations.to_string(),
            "--duration".into(),
            self.duration.to_string(),
            "--dt".into(),
            self.dt.to_string(),
            "--seed".into(),
            self.seed.to_string(),
            "--shard-size".into(),
            self.shard_size.to_string(),
            "--spectra-dir".into(),
            root.join("spectra").display().to_string(),
        ];
        // --compression applies to the raw data only (without --store-raw it is refused as without effect)
        if self.store_raw {
            a.extend(["--store-raw".into(), "--compression".into(), self.compression.into()]);
        }
        a
    }

    /// One line for reproducer notes.
    pub fn describe(&self) -> String {
        format!(
            "{} (`stochvib simulate {} --realizations {} --duration {} --dt {} --seed {} --shard-size {}{} --compression {}`)",
            self.name,
            self.scenario,
            self.realizations,
            self.duration,
            self.dt,
            self.seed,
            self.shard_size,
            if self.store_raw { " --store-raw" } else { "" },
            self.compression
        )
    }
}

/// Body of the child process that leaves a `.tmp`: runs `variant` into `final_path` and aborts the
/// process once `k` shards are written.
pub fn child_abort(root: &Path, variant: usize, final_path: &Path, k: usize) -> ! {
    let v = &VARIANTS[variant];
    let sc = load_scenario(&root.join(v.scenario), &root.join("spectra")).expect("the scenario loads");
    let _ = sc.simulate(&v.options(), final_path, &|done, _| {
        if done >= k {
            std::process::abort();
        }
    });
    eprintln!("the run finished without being aborted");
    std::process::exit(3);
}

/// A byte range of a file with a label.
#[derive(Debug, Clone)]
pub struct Region {
    /// Dataset path, e.g. `statistics/y/sigma`.
    pub name: String,
    /// First byte.
    pub start: u64,
    /// Length.
    pub len: u64,
}

/// Dataset data extents of an HDF5 file, from h5py.
const LAYOUT_PY: &str = r#"
import sys, json
import h5py
f = h5py.File(sys.argv[1], "r")
out = []
def visit(name, obj):
    if isinstance(obj, h5py.Dataset):
        lay = obj.id.get_create_plist().get_layout()
        if lay == 1:
            off = obj.id.get_offset()
            if off is not None:
                out.append([name, int(off), int(obj.id.get_storage_size())])
        elif lay == 2:
            for i in range(obj.id.get_num_chunks()):
                ci = obj.id.get_chunk_info(i)
                out.append(["%s#chunk%d" % (name, i), int(ci.byte_offset), int(ci.size)])
f.visititems(visit)
print(json.dumps(out))
"#;

/// The data extents of `file` by h5py, else (h5py missing) the 8-byte patterns of the `f64` values
/// in `values` found in the file (`(label, value)`).
pub fn layout(file: &Path, bytes: &[u8], values: &[(String, f64)]) -> (Vec<Region>, &'static str) {
    let mut cmd = Command::new("python3");
    cmd.arg("-c").arg(LAYOUT_PY).arg(file);
    cmd.stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    let out = stochvib::store::spawn_child(&mut cmd).and_then(|c| c.wait_with_output());
    if let Ok(o) = out
        && o.status.success()
        && let Ok(v) = serde_json::from_slice::<Vec<(String, u64, u64)>>(&o.stdout)
    {
        let r = v
            .into_iter()
            .map(|(name, start, len)| Region { name, start, len })
            .collect();
        return (r, "h5py");
    }
    let mut r = Vec::new();
    for (label, x) in values {
        let pat = x.to_le_bytes();
        if let Some(i) = bytes.windows(8).position(|w| w == pat) {
            r.push(Region {
                name: label.clone(),
                start: i as u64,
                len: 8,
            });
        }
    }
    (r, "float patterns")
}

/// The region class of a dataset name (for grouping): `statistics`, `psd`, `shards/complete`,
/// `shards/accumulators`, `raw outputs`, `raw inputs`.
pub fn region_class(name: &str) -> String {
    let n = name.split('#').next().unwrap_or(name);
    if n.starts_with("attr:") {
        "statistics attributes".into()
    } else if n.starts_with("statistics/") {
        "statistics".into()
    } else if n.starts_with("psd/") {
        "psd".into()
    } else if n == "shards/complete" {
        "shards/complete".into()
    } else if n.starts_with("shards/") {
        "shard accumulators".into()
    } else if n.starts_with("outputs/") {
        "raw outputs".into()
    } else if n.starts_with("inputs/") {
        "raw inputs".into()
    } else {
        n.into()
    }
}

/// One base file (complete or `.tmp`) with what the commands print for it.
#[derive(Debug, Clone)]
pub struct Base {
    /// Variant index.
    pub variant: usize,
    /// Whether it is the `.tmp` of an interrupted run.
    pub tmp: bool,
    /// Its bytes.
    pub bytes: Vec<u8>,
    /// File name used for copies (`run.h5` or `killed.h5.tmp`).
    pub file_name: String,
    /// Dataset data extents.
    pub regions: Vec<Region>,
    /// How the extents were found.
    pub layout_by: &'static str,
    /// Baseline outputs by command name.
    pub baseline: BTreeMap<String, Baseline>,
}

/// What a command printed on an intact file.
#[derive(Debug, Clone)]
pub enum Baseline {
    /// `inspect` text, with the file's path replaced by `<FILE>`.
    Text(String),
    /// `inspect --json` or `simulate --json`, without paths.
    Json(serde_json::Value),
    /// `plot`: file name → bytes.
    Files(BTreeMap<String, Vec<u8>>),
}

/// Builds the command of the child that leaves a `.tmp`: (variant index, final path, shards before the
/// abort).
pub type ChildCommand = Arc<dyn Fn(usize, &Path, usize) -> Command + Send + Sync>;

/// First occurrence of each signature: (base index, corruption, command).
type Firsts = BTreeMap<String, (usize, Corruption, String)>;

/// Settings of a corruption campaign.
#[derive(Clone)]
pub struct Config {
    /// Source tree.
    pub root: PathBuf,
    /// The `stochvib` binary.
    pub bin: PathBuf,
    /// Work directory (emptied first).
    pub work: PathBuf,
    /// Where to write reproducers.
    pub findings_dir: Option<PathBuf>,
    /// Number of cases.
    pub cases: u64,
    /// Master seed.
    pub seed: u64,
    /// Time limit of one command.
    pub limit: Duration,
    /// Parallel cases.
    pub jobs: u64,
    /// Starts the child that leaves a `.tmp`: (variant index, final path, shards before abort).
    pub child: ChildCommand,
    /// Progress on stderr.
    pub progress: bool,
}

fn cli(cfg: &Config, args: &[String]) -> process::Output {
    let mut cmd = Command::new(&cfg.bin);
    cmd.args(args).current_dir(&cfg.work);
    process::run(cmd, cfg.limit, process::DEFAULT_MEMORY_LIMIT)
}

fn strip_paths(v: &mut serde_json::Value) {
    if let Some(o) = v.as_object_mut() {
        o.remove("path");
        o.remove("resumed_shards");
    }
}

/// The commands of a case on `file` (a copy of base `b` in directory `dir`): (name, arguments).
fn commands(cfg: &Config, b: &Base, file: &Path, dir: &Path) -> Vec<(String, Vec<String>)> {
    let f = file.display().to_string();
    if b.tmp {
        let mut resume = VARIANTS[b.variant].cli_args(&cfg.root);
        let final_path = file.with_file_name(b.file_name.trim_end_matches(".tmp"));
        resume.extend(["--json".into(), "-o".into(), final_path.display().to_string()]);
        vec![("inspect".into(), vec!["inspect".into(), f]), ("resume".into(), resume)]
    } else {
        vec![
            ("inspect".into(), vec!["inspect".into(), f.clone()]),
            (
                "inspect --json".into(),
                vec!["inspect".into(), "--json".into(), f.clone()],
            ),
            (
                "plot".into(),
                vec!["plot".into(), f, "-o".into(), dir.join("plots").display().to_string()],
            ),
        ]
    }
}

fn read_plots(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut m = BTreeMap::new();
    if let Ok(rd) = std::fs::read_dir(dir.join("plots")) {
        for e in rd.flatten() {
            m.insert(
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap_or_default(),
            );
        }
    }
    m
}

fn observe(name: &str, out: &process::Output, file: &Path, dir: &Path) -> Option<Baseline> {
    if out.exit != Exit::Code(0) {
        return None;
    }
    Some(match name {
        "inspect" => Baseline::Text(out.stdout.replace(&file.display().to_string(), "<FILE>")),
        "plot" => Baseline::Files(read_plots(dir)),
        _ => {
            let mut v: serde_json::Value = serde_json::from_str(&out.stdout).ok()?;
            strip_paths(&mut v);
            Baseline::Json(v)
        }
    })
}

/// Writes the base files and records the baselines.
///
/// # Panics
/// If a base file cannot be made or a command fails on an intact file (set-up errors, not findings).
pub fn setup(cfg: &Config) -> Vec<Base> {
    let _ = std::fs::remove_dir_all(&cfg.work);
    std::fs::create_dir_all(&cfg.work).unwrap();
    let mut bases = Vec::new();
    for (vi, v) in VARIANTS.iter().enumerate() {
        let dir = cfg.work.join("base").join(v.name);
        std::fs::create_dir_all(&dir).unwrap();
        let run = dir.join("run.h5");
        let sc = load_scenario(&cfg.root.join(v.scenario), &cfg.root.join("spectra")).expect("scenario");
        let summary = sc.simulate(&v.options(), &run, &|_, _| {}).expect("base run");
        let values: Vec<(String, f64)> = summary
            .outputs
            .iter()
            .flat_map(|o| {
                o.statistics
                    .iter()
                    .map(move |s| (format!("statistics/{}/{}", o.output, s.name), s.interval.estimate))
            })
            .collect();
        // the interrupted run
        let killed = dir.join("killed.h5");
        let st = process::run(
            (cfg.child)(vi, &killed, 2),
            Duration::from_secs(120),
            process::DEFAULT_MEMORY_LIMIT,
        );
        assert!(
            matches!(st.exit, Exit::Signal(_)),
            "the child must abort: {} {}",
            st.exit,
            st.stderr
        );
        let tmp = tmp_path(&killed);
        assert!(tmp.exists(), "the aborted child left no {}", tmp.display());
        let attrs: Vec<(String, f64)> = summary
            .outputs
            .iter()
            .flat_map(|o| {
                o.statistics.iter().flat_map(move |s| {
                    let n = format!("statistics/{}/{}", o.output, s.name);
                    [
                        (format!("attr:{n}@lower"), Some(s.interval.lower)),
                        (format!("attr:{n}@upper"), Some(s.interval.upper)),
                        (format!("attr:{n}@analytic"), s.analytic),
                    ]
                })
            })
            .filter_map(|(n, v)| v.filter(|x| *x != 0.0).map(|x| (n, x)))
            .collect();
        for (path, is_tmp) in [(run, false), (tmp, true)] {
            let bytes = std::fs::read(&path).unwrap();
            let (mut regions, by) = layout(&path, &bytes, &values);
            // attributes live in object headers: find the statistics' interval bounds by their bytes
            for (name, x) in &attrs {
                let pat = x.to_le_bytes();
                for (i, w) in bytes.windows(8).enumerate() {
                    let inside = regions
                        .iter()
                        .any(|r| (i as u64) >= r.start && (i as u64) < r.start + r.len);
                    if w == pat && !inside {
                        regions.push(Region {
                            name: name.clone(),
                            start: i as u64,
                            len: 8,
                        });
                    }
                }
            }
            let file_name = path.file_name().unwrap().to_string_lossy().into_owned();
            let mut b = Base {
                variant: vi,
                tmp: is_tmp,
                bytes,
                file_name,
                regions,
                layout_by: by,
                baseline: BTreeMap::new(),
            };
            let cdir = cfg.work.join("baseline").join(format!("{}-{}", v.name, is_tmp));
            std::fs::create_dir_all(&cdir).unwrap();
            let copy = cdir.join(&b.file_name);
            std::fs::write(&copy, &b.bytes).unwrap();
            for (name, args) in commands(cfg, &b, &copy, &cdir) {
                let out = cli(cfg, &args);
                let obs = observe(&name, &out, &copy, &cdir).unwrap_or_else(|| {
                    panic!(
                        "{name} fails on the intact {} file: {} {}",
                        v.name, out.exit, out.stderr
                    )
                });
                if name == "resume"
                    && let Baseline::Json(j) = &obs
                {
                    // the resumed run must reproduce the uninterrupted one (else the CLI and the
                    // library disagree on the run's options and the case is meaningless)
                    // both sides through text and the same parser (serde_json without `float_roundtrip`
                    // may parse a float one ulp off, identically for identical text)
                    let mut whole: serde_json::Value =
                        serde_json::from_str(&serde_json::to_string(&summary).unwrap()).unwrap();
                    strip_paths(&mut whole);
                    assert_eq!(j["outputs"], whole["outputs"], "resume of the intact {} .tmp", v.name);
                    let resumed: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
                    assert_eq!(resumed["resumed_shards"], 2, "the intact .tmp resumes 2 shards");
                }
                b.baseline.insert(name, obs);
            }
            bases.push(b);
        }
    }
    bases
}

/// A corruption of a file's bytes.
#[derive(Debug, Clone)]
pub enum Corruption {
    /// Keep the first `len` bytes.
    Truncate {
        /// New length.
        len: usize,
    },
    /// Flip bits: (byte offset, bit).
    Flip {
        /// `header`, `anywhere` or `data`.
        kind: &'static str,
        /// The flips.
        flips: Vec<(usize, u8)>,
    },
    /// Zero `len` bytes at `offset`.
    Zero {
        /// Start.
        offset: usize,
        /// Length.
        len: usize,
    },
}

impl Corruption {
    /// The damaged copy of `bytes`.
    pub fn apply(&self, bytes: &[u8]) -> Vec<u8> {
        let mut b = bytes.to_vec();
        match self {
            Corruption::Truncate { len } => b.truncate(*len),
            Corruption::Flip { flips, .. } => {
                for (i, bit) in flips {
                    if *i < b.len() {
                        b[*i] ^= 1 << bit;
                    }
                }
            }
            Corruption::Zero { offset, len } => {
                let end = (offset + len).min(b.len());
                for x in &mut b[*offset.min(&end)..end] {
                    *x = 0;
                }
            }
        }
        b
    }

    /// Short operation name.
    pub fn op(&self) -> &'static str {
        match self {
            Corruption::Truncate { .. } => "truncation",
            Corruption::Flip { kind: "header", .. } => "bit flip in the first 2 KiB",
            Corruption::Flip { kind: "data", .. } => {
                "bit flip in a stored value (dataset data or statistics attribute)"
            }
            Corruption::Flip { .. } => "bit flip anywhere",
            Corruption::Zero { .. } => "zeroed block",
        }
    }
}

/// Where an offset is: a dataset's data, the first 2 KiB, or other metadata/free space.
pub fn locate(b: &Base, offset: usize) -> String {
    for r in &b.regions {
        if (offset as u64) >= r.start && (offset as u64) < r.start + r.len {
            return match r.name.strip_prefix("attr:") {
                Some(a) => format!(
                    "attribute {} (+{}, found by its bytes)",
                    a.replace('@', " @"),
                    offset as u64 - r.start
                ),
                None => format!("data of {} (+{})", r.name, offset as u64 - r.start),
            };
        }
    }
    if offset < 2048 {
        "first 2 KiB (superblock / root object header)".into()
    } else {
        "metadata or free space".into()
    }
}

fn locate_class(b: &Base, offset: usize) -> String {
    for r in &b.regions {
        if (offset as u64) >= r.start && (offset as u64) < r.start + r.len {
            return region_class(&r.name);
        }
    }
    if offset < 2048 {
        "first 2 KiB".into()
    } else {
        "metadata".into()
    }
}

/// A description with offsets, bits and what they hit.
pub fn describe(c: &Corruption, b: &Base) -> String {
    let total = b.bytes.len();
    match c {
        Corruption::Truncate { len } => format!("truncated to {len} of {total} bytes (cut in {})", locate(b, *len)),
        Corruption::Flip { flips, .. } => flips
            .iter()
            .map(|(i, bit)| {
                format!(
                    "flip bit {bit} of byte {i} ({:#04x} -> {:#04x}; {})",
                    b.bytes[*i],
                    b.bytes[*i] ^ (1 << bit),
                    locate(b, *i)
                )
            })
            .collect::<Vec<_>>()
            .join("; "),
        Corruption::Zero { offset, len } => format!("zeroed bytes {offset}..{} ({})", offset + len, locate(b, *offset)),
    }
}

/// The region class used in signatures.
fn where_class(c: &Corruption, b: &Base) -> String {
    match c {
        Corruption::Truncate { len } => locate_class(b, *len),
        Corruption::Flip { flips, .. } => locate_class(b, flips[0].0),
        Corruption::Zero { offset, .. } => locate_class(b, *offset),
    }
}

/// Case `index` of `seed`: which base file and which corruption.
pub fn generate(bases: &[Base], seed: u64, index: u64) -> (usize, Corruption) {
    let mut rng = super::mutate::Rng::seed_from_u64(splitmix64(seed ^ splitmix64(index ^ 0xc0de_0bad)));
    // 3 of 4 cases on complete files
    let want_tmp = rng.random_bool(0.25);
    let cands: Vec<usize> = (0..bases.len()).filter(|&i| bases[i].tmp == want_tmp).collect();
    let bi = cands[rng.random_range(0..cands.len())];
    let b = &bases[bi];
    let n = b.bytes.len();
    let c = match rng.random_range(0..100) {
        0..=19 => {
            let len = if rng.random_bool(0.2) {
                n - rng.random_range(1..=64.min(n))
            } else {
                rng.random_range(0..n)
            };
            Corruption::Truncate { len }
        }
        20..=44 => {
            let k = rng.random_range(1..=2);
            let flips = (0..k)
                .map(|_| (rng.random_range(0..2048.min(n)), rng.random_range(0..8u8)))
                .collect();
            Corruption::Flip { kind: "header", flips }
        }
        45..=64 => {
            let k = rng.random_range(1..=3);
            let flips = (0..k)
                .map(|_| (rng.random_range(0..n), rng.random_range(0..8u8)))
                .collect();
            Corruption::Flip {
                kind: "anywhere",
                flips,
            }
        }
        65..=89 if !b.regions.is_empty() => {
            let r = &b.regions[rng.random_range(0..b.regions.len())];
            let off = r.start as usize + rng.random_range(0..r.len.max(1) as usize);
            Corruption::Flip {
                kind: "data",
                flips: vec![(off.min(n - 1), rng.random_range(0..8u8))],
            }
        }
        _ => {
            let len = [1usize, 8, 64, 512, 4096][rng.random_range(0..5)];
            let offset = if rng.random_bool(0.5) {
                (rng.random_range(0..n) / len) * len
            } else {
                rng.random_range(0..n)
            };
            Corruption::Zero { offset, len }
        }
    };
    (bi, c)
}

/// The classification of one command of a case.
#[derive(Debug, Clone)]
pub struct Verdict {
    /// Command name.
    pub command: String,
    /// Class (see the module docs).
    pub class: String,
    /// Grouping key.
    pub signature: String,
    /// The signature without where the damage was (reduction keeps it).
    pub core: String,
    /// This occurrence.
    pub detail: String,
}

/// Classes that are not findings.
pub fn is_benign(class: &str) -> bool {
    class == "clean-error" || class == "ok-same"
}

/// Classes reported but not asserted.
pub fn is_soft(class: &str) -> bool {
    class == "silent-metadata-change"
}

fn first_difference(a: &str, b: &str) -> (String, String, String) {
    let mut section = "header".to_string();
    for (x, y) in a.lines().zip(b.lines()) {
        if x.starts_with("  /") {
            section = x.trim().split([' ', ':']).next().unwrap_or("").to_string();
        } else if x.starts_with("  scenario") {
            section = "scenario text".into();
        }
        if x != y {
            return (section, x.to_string(), y.to_string());
        }
    }
    (
        section,
        format!("{} lines", a.lines().count()),
        format!("{} lines", b.lines().count()),
    )
}

fn compare(name: &str, base: &Baseline, now: &Baseline) -> Option<(bool, String, String)> {
    // (statistics differ?, what, detail)
    match (base, now) {
        (Baseline::Text(a), Baseline::Text(b)) => {
            if a == b {
                return None;
            }
            let (section, x, y) = first_difference(a, b);
            let stats = section.starts_with("/statistics") || section.starts_with("/psd");
            Some((
                stats,
                format!("{section} section"),
                format!("`{}` became `{}`", x.trim(), y.trim()),
            ))
        }
        (Baseline::Json(a), Baseline::Json(b)) => {
            if a == b {
                return None;
            }
            let key = if name == "resume" { "outputs" } else { "statistics" };
            if a.get(key) != b.get(key) {
                return Some((true, key.into(), json_diff(&a[key], &b[key])));
            }
            let field = a
                .as_object()
                .and_then(|o| o.keys().find(|k| a.get(*k) != b.get(*k)).cloned())
                .unwrap_or_else(|| "?".into());
            Some((false, format!("field `{field}`"), json_diff(&a[&field], &b[&field])))
        }
        (Baseline::Files(a), Baseline::Files(b)) => {
            if a == b {
                return None;
            }
            let mut kinds: Vec<String> = a
                .keys()
                .chain(b.keys())
                .filter(|k| a.get(*k) != b.get(*k))
                .map(|k| {
                    let stem = k.rsplit_once('.').map(|x| x.0).unwrap_or(k);
                    stem.rsplit_once('-').map(|x| x.1).unwrap_or(stem).to_string()
                })
                .collect();
            kinds.sort();
            kinds.dedup();
            let n = a.keys().chain(b.keys()).filter(|k| a.get(*k) != b.get(*k)).count();
            Some((
                true,
                format!("pictures ({})", kinds.join(", ")),
                format!("{n} picture file(s) differ"),
            ))
        }
        _ => Some((true, "output kind".into(), String::new())),
    }
}

fn json_diff(a: &serde_json::Value, b: &serde_json::Value) -> String {
    fn walk(a: &serde_json::Value, b: &serde_json::Value, path: String) -> Option<String> {
        use serde_json::Value as V;
        match (a, b) {
            (V::Object(x), V::Object(y)) => {
                for (k, v) in x {
                    if let Some(d) = walk(v, y.get(k).unwrap_or(&V::Null), format!("{path}.{k}")) {
                        return Some(d);
                    }
                }
                None
            }
            (V::Array(x), V::Array(y)) if x.len() == y.len() => {
                for (i, (p, q)) in x.iter().zip(y).enumerate() {
                    if let Some(d) = walk(p, q, format!("{path}[{i}]")) {
                        return Some(d);
                    }
                }
                None
            }
            _ if a == b => None,
            _ => Some(format!(
                "{path}: {} -> {}",
                super::mutate::short(&a.to_string()),
                super::mutate::short(&b.to_string())
            )),
        }
    }
    walk(a, b, String::new()).unwrap_or_default()
}

/// Runs the commands of one case and classifies them.
pub fn run_case(cfg: &Config, b: &Base, c: &Corruption, dir: &Path) -> Vec<Verdict> {
    run_commands(cfg, b, c, dir, None)
}

/// As [`run_case`], only the command named `only` if given.
fn run_commands(cfg: &Config, b: &Base, c: &Corruption, dir: &Path, only: Option<&str>) -> Vec<Verdict> {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join(&b.file_name);
    let damaged = c.apply(&b.bytes);
    let wc = where_class(c, b);
    let kind = if b.tmp { ".tmp" } else { "complete file" };
    let mut out = Vec::new();
    for (name, args) in commands(cfg, b, &file, dir) {
        if only.is_some_and(|o| o != name) {
            continue;
        }
        // every command gets a fresh copy (resume changes the file)
        if b.tmp {
            // the resumed run's output from a previous command
            let _ = std::fs::remove_file(dir.join(b.file_name.trim_end_matches(".tmp")));
        }
        std::fs::write(&file, &damaged).unwrap();
        let _ = std::fs::remove_dir_all(dir.join("plots"));
        let o = cli(cfg, &args);
        let at = format!("{} in {wc} of a {kind}", c.op());
        let (class, core, detail) = match o.exit {
            Exit::Timeout => (
                "hang".to_string(),
                format!("`{name}` hangs"),
                format!("killed after {:?}", o.elapsed),
            ),
            Exit::Signal(s) => (
                "crash".into(),
                format!("`{name}` killed by {}", process::signal_name(s)),
                process::tail(&o.stderr, 400),
            ),
            Exit::Code(101) => {
                let loc = o
                    .stderr
                    .lines()
                    .find(|l| l.contains("panicked at"))
                    .map(|l| l.split("panicked at").nth(1).unwrap_or("").trim().to_string())
                    .unwrap_or_default();
                (
                    "panic".into(),
                    format!("`{name}` panics at {loc}"),
                    process::tail(&o.stderr, 400),
                )
            }
            Exit::Code(0) => {
                let now = observe(&name, &o, &file, dir);
                let base = &b.baseline[&name];
                match now.as_ref().and_then(|n| compare(&name, base, n)) {
                    None if now.is_some() => ("ok-same".into(), String::new(), String::new()),
                    None => (
                        "silent-corruption".into(),
                        format!("`{name}` exit 0 with unreadable output"),
                        super::mutate::short_to(&o.stdout, 200),
                    ),
                    Some((true, what, d)) => (
                        "silent-corruption".into(),
                        format!("`{name}` exit 0 with different {what}"),
                        d,
                    ),
                    Some((false, what, d)) => (
                        "silent-metadata-change".into(),
                        format!("`{name}` exit 0 with different {what}"),
                        d,
                    ),
                }
            }
            Exit::Code(code) => {
                let first = o
                    .stderr
                    .lines()
                    .find(|l| !l.trim().is_empty())
                    .unwrap_or("")
                    .to_string();
                let names_file =
                    o.stderr.contains(&b.file_name) || o.stderr.contains(b.file_name.trim_end_matches(".tmp"));
                if first.starts_with("error:") && names_file && code == 1 {
                    ("clean-error".into(), format!("`{name}` clean error"), first)
                } else {
                    (
                        "error-message".into(),
                        format!("`{name}` exit {code} without an error naming the file"),
                        super::mutate::short_to(&first, 200),
                    )
                }
            }
        };
        let signature = if class == "panic" {
            core.clone()
        } else {
            format!("{core} after {at}")
        };
        out.push(Verdict {
            command: name,
            class,
            signature,
            core,
            detail: detail.replace(&dir.display().to_string(), "<DIR>"),
        });
    }
    out
}

/// One signature's record.
#[derive(Debug, Clone)]
pub struct Record {
    /// Class.
    pub class: String,
    /// Signature.
    pub signature: String,
    /// Cases.
    pub count: usize,
    /// First case.
    pub first: u64,
    /// Its base file and corruption.
    pub describe: String,
    /// Its detail.
    pub detail: String,
    /// Reproducer directory.
    pub reproducer: Option<PathBuf>,
}

/// Result of a campaign.
#[derive(Debug, Clone, Default)]
pub struct Summary {
    /// Seed.
    pub seed: u64,
    /// Cases.
    pub cases: u64,
    /// Command runs.
    pub commands: u64,
    /// Command outcomes by class.
    pub by_class: BTreeMap<String, usize>,
    /// Command outcomes by (command, class).
    pub by_command: BTreeMap<String, BTreeMap<String, usize>>,
    /// Cases per corruption op.
    pub by_op: BTreeMap<String, usize>,
    /// Findings per signature.
    pub records: BTreeMap<String, Record>,
    /// How the dataset extents were found.
    pub layout_by: String,
    /// Wall time.
    pub elapsed: Duration,
}

impl Summary {
    /// Command outcomes of asserted finding classes, by class.
    pub fn hard(&self) -> BTreeMap<String, usize> {
        self.by_class
            .iter()
            .filter(|(c, _)| !is_benign(c) && !is_soft(c))
            .map(|(c, n)| (c.clone(), *n))
            .collect()
    }

    /// Text report.
    pub fn render(&self) -> String {
        use super::input_campaign::fmt_counts;
        use std::fmt::Write as _;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "run-file corruption: seed {}, {} cases, {} command runs, {:.1} s; dataset extents by {}",
            self.seed,
            self.cases,
            self.commands,
            self.elapsed.as_secs_f64(),
            self.layout_by
        );
        let _ = writeln!(s, "cases by corruption: {}", fmt_counts(&self.by_op));
        let _ = writeln!(s, "command outcomes: {}", fmt_counts(&self.by_class));
        for (c, m) in &self.by_command {
            let _ = writeln!(s, "  {c}: {}", fmt_counts(m));
        }
        let _ = writeln!(s, "findings (hard): {}", fmt_counts(&self.hard()));
        let mut recs: Vec<&Record> = self.records.values().collect();
        recs.sort_by(|a, b| {
            (is_soft(&a.class), &a.class, &a.signature).cmp(&(is_soft(&b.class), &b.class, &b.signature))
        });
        let _ = writeln!(s, "{} signatures:", recs.len());
        for r in recs {
            let _ = writeln!(
                s,
                "- [{}] {} — {} command run(s); first case {}",
                r.class, r.signature, r.count, r.first
            );
            let _ = writeln!(s, "    {}", r.describe);
            if !r.detail.is_empty() {
                let _ = writeln!(s, "    detail: {}", r.detail);
            }
            if let Some(p) = &r.reproducer {
                let _ = writeln!(s, "    reproducer: {}", p.display());
            }
        }
        s
    }
}

/// Tries to show `sig` (a finding of command `command`) with less damage: one flip instead of several, a
/// smaller zeroed block. Hangs are not reduced (each try would cost the whole time limit).
fn reduce(cfg: &Config, b: &Base, c: &Corruption, command: &str, r: &Record, dir: &Path) -> Corruption {
    if r.class == "hang" {
        return c.clone();
    }
    let shows = |c: &Corruption| {
        run_commands(cfg, b, c, dir, Some(command))
            .iter()
            .any(|v| v.class == r.class && r.signature.starts_with(&v.core))
    };
    match c {
        Corruption::Flip { kind, flips } if flips.len() > 1 => {
            for f in flips {
                let one = Corruption::Flip { kind, flips: vec![*f] };
                if shows(&one) {
                    return one;
                }
            }
            c.clone()
        }
        Corruption::Zero { offset, len } if *len > 1 => {
            let (mut o, mut l) = (*offset, *len);
            while l > 1 {
                let h = l / 2;
                let first = Corruption::Zero { offset: o, len: h };
                let second = Corruption::Zero {
                    offset: o + h,
                    len: l - h,
                };
                if shows(&first) {
                    l = h;
                } else if shows(&second) {
                    o += h;
                    l -= h;
                } else {
                    break;
                }
            }
            Corruption::Zero { offset: o, len: l }
        }
        _ => c.clone(),
    }
}

/// Runs the campaign.
pub fn run(cfg: &Config) -> Summary {
    let t0 = Instant::now();
    let bases = Arc::new(setup(cfg));
    if cfg.progress {
        for b in bases.iter() {
            eprintln!(
                "[corrupt] base {} {}: {} bytes, {} dataset extents ({})",
                VARIANTS[b.variant].name,
                b.file_name,
                b.bytes.len(),
                b.regions.len(),
                b.layout_by
            );
        }
    }
    let summary = Arc::new(Mutex::new(Summary {
        seed: cfg.seed,
        layout_by: bases[0].layout_by.to_string(),
        ..Summary::default()
    }));
    let first_cases: Arc<Mutex<Firsts>> = Arc::default();
    let jobs = cfg.jobs.max(1);
    let mut handles = Vec::new();
    for j in 0..jobs {
        let (cfg, bases, summary, first_cases) = (cfg.clone(), bases.clone(), summary.clone(), first_cases.clone());
        handles.push(std::thread::spawn(move || {
            let dir = cfg.work.join(format!("case-{j}"));
            let mut i = j;
            while i < cfg.cases {
                let (bi, c) = generate(&bases, cfg.seed, i);
                let b = &bases[bi];
                let verdicts = run_case(&cfg, b, &c, &dir);
                let mut s = summary.lock().unwrap();
                s.cases += 1;
                *s.by_op.entry(c.op().to_string()).or_default() += 1;
                for v in &verdicts {
                    s.commands += 1;
                    *s.by_class.entry(v.class.clone()).or_default() += 1;
                    *s.by_command
                        .entry(format!("{} ({})", v.command, if b.tmp { ".tmp" } else { "complete" }))
                        .or_default()
                        .entry(v.class.clone())
                        .or_default() += 1;
                    if is_benign(&v.class) {
                        continue;
                    }
                    let r = s.records.entry(v.signature.clone()).or_insert_with(|| Record {
                        class: v.class.clone(),
                        signature: v.signature.clone(),
                        count: 0,
                        first: i,
                        describe: format!(
                            "{} of variant {}: {}",
                            b.file_name,
                            VARIANTS[b.variant].name,
                            describe(&c, b)
                        ),
                        detail: v.detail.clone(),
                        reproducer: None,
                    });
                    r.count += 1;
                    first_cases.lock().unwrap().entry(v.signature.clone()).or_insert((
                        bi,
                        c.clone(),
                        v.command.clone(),
                    ));
                }
                if cfg.progress && s.cases % 100 == 0 {
                    eprintln!(
                        "[corrupt] {} cases, {:.0} s: {}",
                        s.cases,
                        t0.elapsed().as_secs_f64(),
                        super::input_campaign::fmt_counts(&s.by_class)
                    );
                }
                drop(s);
                i += jobs;
            }
        }));
    }
    for h in handles {
        h.join().expect("corruption thread");
    }
    let mut s = Arc::try_unwrap(summary).unwrap().into_inner().unwrap();
    if let Some(fd) = &cfg.findings_dir {
        let out = fd.join("runs");
        let _ = std::fs::remove_dir_all(&out);
        std::fs::create_dir_all(&out).unwrap();
        let firsts = first_cases.lock().unwrap().clone();
        let mut md = String::from("# Run-file corruption reproducers\n\n");
        for (n, (sig, r)) in s.records.iter_mut().enumerate() {
            let Some((bi, c, command)) = firsts.get(sig) else {
                continue;
            };
            let b = &bases[*bi];
            let c = reduce(cfg, b, c, command, r, &cfg.work.join("reduce"));
            let sub = out.join(format!("{:03}-{}", n + 1, slug(&r.class)));
            std::fs::create_dir_all(&sub).unwrap();
            std::fs::write(sub.join(&b.file_name), c.apply(&b.bytes)).unwrap();
            let v = &VARIANTS[b.variant];
            r.describe = format!("{} of variant {}: {}", b.file_name, v.name, describe(&c, b));
            let how = match command.as_str() {
                "resume" => format!(
                    "stochvib simulate {} --realizations {} --duration {} --dt {} --seed {} --shard-size {}{} --compression {} -o killed.h5 --json  (in the directory of this killed.h5.tmp)",
                    v.scenario, v.realizations, v.duration, v.dt, v.seed, v.shard_size,
                    if v.store_raw { " --store-raw" } else { "" }, v.compression
                ),
                "plot" => format!("stochvib plot {} -o plots", b.file_name),
                other => format!("stochvib {other} {}", b.file_name),
            };
            let note = format!(
                "[{}] {}\nbase file: {} of {}{}\ncorruption: {}\ncommand: {how}\ndetail: {}\n",
                r.class,
                r.signature,
                b.file_name,
                v.describe(),
                if b.tmp { ", interrupted after 2 of 4 shards" } else { "" },
                describe(&c, b),
                r.detail
            );
            std::fs::write(sub.join("CASE.txt"), &note).unwrap();
            md.push_str(&format!(
                "## {}\n\n```text\n{note}```\n\n",
                sub.file_name().unwrap().to_string_lossy()
            ));
            r.reproducer = Some(sub);
        }
        s.elapsed = t0.elapsed();
        let _ = std::fs::write(out.join("REPRODUCERS.md"), md);
        let _ = std::fs::write(out.join("SUMMARY.txt"), s.render());
    }
    s.elapsed = t0.elapsed();
    s
}

fn slug(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect()
}
