//! The file references in `docs/` list every key the readers accept, and the readers accept every key the
//! references list.
//!
//! The readers are run with [`stochvib::fields::record_keys`] on: it records the file and the dotted path of
//! every key a [`stochvib::fields::Fields`] reader asks for (array indices as `[]`). They read every file of
//! `data/` and `spectra/` and the fixture scenarios of [`fixtures`], which reach the keys no shipped file
//! reaches; every fixture must be accepted. The documented keys are the first cells (in backticks) of the
//! tables that follow a marker line `<!-- keys: FILE PREFIX [kind=KIND] [pending] -->` in the reference
//! pages ([`PAGES`]):
//! * FILE is the kind of file (`scenario`, `spectrum`, `workday`, `reference`), PREFIX the dotted path of the
//!   table the keys are in (`.` for the top level of the file, `input[]` for the `[[input]]` tables);
//! * `kind=KIND` restricts the table to the `[model]` kind (scenario files), the spectrum kind (spectrum
//!   files) or the `reference` kind (reference tables) of the file;
//! * `pending` marks keys of readers not yet in this build: they count as documented, but are not required
//!   to be read.
//!
//! A key read by some reader but in no table fails the test, naming the key and the file that reached it; a
//! key in a table (not pending) that no reader asked for fails it too.
//!
//! The sections of the readers driven by a declarative key table ([`stochvib::scenario::key_table`]) are
//! those tables as rendered ([`key_tables_are_the_page`]): the tables are their one source, and through the
//! page they are checked against the keys the readers ask for. `STOCHVIB_WRITE_KEY_TABLES=1 cargo test --test
//! suite key_reference::` rewrites those sections from the tables. Keys read inside an inline spectrum
//! (`input.spectrum.alpha`, `input[].road.spectrum.kind`) are spectrum-file keys.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::common;

/// The pages holding the key tables.
const PAGES: [&str; 2] = ["docs/scenario-reference.md", "docs/spectrum-files.md"];

/// A key of one kind of file: (kind of file, kind of model/spectrum/table if the key depends on it, path).
type Key = (String, Option<String>, String);

/// Scenario texts (name, TOML) that reach the keys no file of `data/` reaches. Every one must be accepted.
fn fixtures() -> Vec<(&'static str, String)> {
    let mut all: Vec<(&str, String)> = [
        ("matrices", MATRICES),
        ("state-space", STATE_SPACE),
        ("transfer-rows", TRANSFER_ROWS),
        ("verdicts", VERDICTS),
    ]
    .into_iter()
    .map(|(name, text)| (name, text.to_string()))
    .collect();
    for (name, coherence) in [
        (
            "ammon-bormann-preset",
            r#"{ kind = "ammon-bormann", preset = "iso-c" }"#,
        ),
        (
            "ammon-bormann",
            r#"{ kind = "ammon-bormann", omega_p = 1.0, w = 2.0, p = 1.0, a = 1.0, values = "coherence_amplitude" }"#,
        ),
        (
            "tabulated",
            r#"{ kind = "tabulated", n = [0.01, 0.1, 1.0], squared_coherence = [1.0, 0.5, 0.0] }"#,
        ),
        ("constant", r#"{ kind = "constant", coherence_amplitude = 0.5 }"#),
    ] {
        let model = body_on_two_tracks(
            r#"tracks = ["left", "right"]
positions = ["0 m", "0 m"]
gains = [1, 1]"#,
        );
        all.push((name, model + &two_track_input(coherence)));
    }
    all.push(("road-section", body_on_two_tracks("") + ROAD_SECTION));
    all.push(("enveloped-road", body_on_two_tracks("") + ENVELOPED_ROAD));
    all.push(("enveloped-input", QUADRATIC_DAMPERS.to_string() + ENVELOPED_INPUT));
    all.push(("several-inputs", body_on_two_tracks("forces = [[1]]") + SEVERAL_INPUTS));
    all.push(("transient-table", TRANSIENT_TABLE.to_string()));
    all.push(("machine-suspended", machine_suspended()));
    all
}

/// The transient keys no catalogue scenario reaches: a speed-profile table, an intensity envelope, a stated
/// start, the exact route's tolerance and the evolutionary route's threshold.
const TRANSIENT_TABLE: &str = r#"
[model]
kind = "transfer-function"
numerator = [1.0]
denominator = [4.0, 0.4, 1.0]
output = { name = "y", unit = "m" }
[input]
spectrum = { kind = "exponential", domain = "spatial", variance = "1 cm^2", alpha = "0.2 1/m" }
[input.speed_profile]
times = ["0 s", "4 s"]
speeds = ["10 m/s", "0 m/s"]
[input.envelope]
times = ["0 s", "1 s"]
intensity = [0.0, 1.0]
[transient]
duration = "5 s"
state = [0.01, 0.0]
rel_tol = 1e-8
max_error = 0.1
"#;

/// A body on a spring and damper over each of two tracks (mdof) with the `[model]` keys `model_keys`; more
/// outputs, the inputs and the analysis follow.
fn body_on_two_tracks(model_keys: &str) -> String {
    let elements: String = ["left", "right"]
        .iter()
        .enumerate()
        .map(|(j, side)| {
            format!(
                "[[model.element]]\nname = \"{side}\"\npoint = [1]\nto = \"base {j}\"\nstiffness = \"20 kN/m\"\n\
                 damping = \"1 kN*s/m\"\n"
            )
        })
        .collect();
    format!(
        r#"
[model]
kind = "mdof"
base_inputs = 2
coordinates = [{{ name = "body", mass = "500 kg" }}]
{model_keys}
{elements}
[[model.output]]
name = "body"
quantity = "velocity"
point = [1]
"#
    )
}

/// An `[[input]]` road of two tracks with the coherence table `coherence`.
fn two_track_input(coherence: &str) -> String {
    format!(
        r#"[[input]]
road = {{ spectrum = "iso8608-c", track_width = "1.5 m", coherence = {coherence} }}
speed = "20 m/s"
tracks = ["left", "right"]
"#
    )
}

/// A `[road]` section with every key it takes.
const ROAD_SECTION: &str = r#"
[road]
name = "surface"
spectrum = "iso8608-b"
coherence = { kind = "dodds-robson" }
track_width = "1.6 m"
speed = "15 m/s"
mean = 0
drives = [0, 1]
tracks = ["left", "right"]
positions = ["0 m", "0 m"]
gains = [1, 1]
"#;

/// An `[[input]]` road on both tracks with an explicit band and a tyre's enveloping.
const ENVELOPED_ROAD: &str = r#"
[[input]]
spectrum = "iso8608-c"
band = ["0.011 cycles/m", "30 cycles/m"]
enveloping = { kind = "moving-average", length = "0.25 m" }
speed = "3 m/s"
drives = [0, 1]
positions = ["0 m", "0 m"]
gains = [1, 1]
"#;

/// A quarter car whose damper is two quadratic dampers (one symmetric coefficient, one asymmetric pair).
const QUADRATIC_DAMPERS: &str = r#"
[model]
kind = "quarter-car"
sprung_mass = "300 kg"
unsprung_mass = "40 kg"
suspension_stiffness = "20 kN/m"
suspension_damping = "1 kN*s/m"
tyre_stiffness = "200 kN/m"
[[model.nonlinear]]
kind = "quadratic-damper"
name = "symmetric"
across = "suspension"
coefficient = "500 N*s^2/m^2"
[[model.nonlinear]]
kind = "quadratic-damper"
name = "asymmetric"
across = "suspension"
rebound_coefficient = "800 N*s^2/m^2"
compression_coefficient = "300 N*s^2/m^2"
"#;

/// An `[input]` road with an explicit band and a tyre's enveloping.
const ENVELOPED_INPUT: &str = r#"
[input]
spectrum = "iso8608-c"
band = ["0.011 cycles/m", "30 cycles/m"]
enveloping = { kind = "moving-average", length = "0.25 m" }
speed = "3 m/s"
"#;

/// The quarter car of `data/quarter-car.toml` as full matrices, with a relative output.
const MATRICES: &str = r#"
[model]
kind = "mdof"
base_inputs = 1
coordinates = [{ name = "body", unit = "m" }, { name = "wheel", unit = "m" }]
mass_matrix = [[300, 0], [0, 40]]
damping_matrix = [[1500, -1500], [-1500, 1500]]
stiffness_matrix = [[20e3, -20e3], [-20e3, 220e3]]
base_stiffness = [[0], [200e3]]
base_damping = [[0], [0]]
[[model.output]]
name = "wheel_travel"
quantity = "relative-velocity"
point = [0, 1]
base = 0
[input]
spectrum = { kind = "power-law", domain = "spatial", g0 = 64e-6, n0 = "0.1 cycles/m", waviness = 2, band = ["0.011 cycles/m", "2.83 cycles/m"] }
speed = "20 m/s"
"#;

/// A mass on a spring as a state space (x, ẋ) under a force.
const STATE_SPACE: &str = r#"
[model]
kind = "state-space"
a = [[0, 1], [-100, -2]]
b = [[0], [1]]
c = [[1, 0]]
d = [[0]]
e = [[0]]
outputs = [{ name = "x", unit = "m" }]
positions = ["0 m"]
gains = [1]
[input]
spectrum = "white-1-80hz"
"#;

/// A transfer function of two inputs on one track (an axle 2 m behind the other) on a measured road.
const TRANSFER_ROWS: &str = r#"
[model]
kind = "transfer-function"
denominator = [100, 2, 1]
numerator = [[50], [50]]
output = { name = "y", unit = "m" }
positions = ["0 m", "2 m"]
gains = [1, 1]
[input]
spectrum = { kind = "measured-profile", file = "measured-profile.csv", track = "right", detrend = "mean", segment = 256 }
speed = "20 m/s"
mean = "1 mm"
kurtosis = 3
"#;

/// Every key of the verdict sections the shipped files leave out (the S–N curve by `c`).
/// A machine with suspended wheels (the keys of `model.axle[].suspension`) on a road of two tracks.
fn machine_suspended() -> String {
    common::CAR_AS_MACHINE.to_string()
        + r#"
[[input]]
name = "road"
road = { spectrum = "iso8608-c", track_width = "1.5 m", coherence = { kind = "dodds-robson", waviness = 2 } }
speed = "20 m/s"
"#
}

const VERDICTS: &str = r#"
[model]
kind = "operator-seat"
operator_mass = "80 kg"
seat_mass = "26 kg"
stiffness = "6500 N/m"
damping_rate = "4.22 1/s"
[input]
spectrum = { kind = "rational", domain = "temporal", unit = "m", numerator = [9.978705857784458], denominator = [124596039.48735943, -448861.0914846832, 404.2589962686201, 1.0] }
[analysis.comfort]
purpose = "comfort"
exposure = "6 h"
a8_action = "0.5 m/s^2"
a8_limit = "1.15 m/s^2"
vdv_action = 9.1
vdv_limit = 21
[[analysis.comfort.axis]]
output = "seat_acc"
location = "seat-surface"
axis = "z"
weighting = "Wk"
k = 1.0
[analysis.fatigue]
output = "travel"
stress_factor = 1.29313e10
k = 5
c = 1e50
endurance_limit = "30 MPa"
methods = ["dirlik", "narrow-band"]
design_life = "5000 h"
bins = 32
"#;

/// After [`body_on_two_tracks`] with a force on the body: one process under both springs and a force, two
/// `[[input]]` tables, with every `[analysis]` key outside the verdicts.
const SEVERAL_INPUTS: &str = r#"
[[model.output]]
name = "travel"
quantity = "relative-displacement"
point = [1]
base = 0
[[input]]
name = "ground"
spectrum = "iso8608-c"
speed = "20 m/s"
mean = "0 m"
drives = [0, 1]
positions = ["0 m", "1 m"]
gains = [1, 1]
kurtosis = 4
[[input]]
name = "load"
spectrum = { kind = "band-white", unit = "N", convention = "one-sided-cyclic", level = 1.0, band = ["1 Hz", "20 Hz"] }
drives = [2]
[analysis]
outputs = ["body", "travel"]
band = ["0.5 Hz", "50 Hz"]
duration = "2 h"
levels = { body = ["1 cm/s"] }
quadrature = { rel_tol = 1e-6, max_subintervals = 2000, max_half_periods = 2000 }
bands = "third-octave"
"#;

/// The documented keys of the reference pages: key → pending.
fn documented() -> BTreeMap<Key, bool> {
    let mut keys = BTreeMap::new();
    for page in PAGES {
        let text = std::fs::read_to_string(common::root().join(page)).unwrap_or_else(|e| panic!("{page}: {e}"));
        let mut table: Option<(String, String, Option<String>, bool)> = None;
        for line in text.lines() {
            if let Some(marker) = line
                .trim()
                .strip_prefix("<!-- keys:")
                .and_then(|m| m.strip_suffix("-->"))
            {
                table = Some(parse_marker(marker, page));
            } else if let Some((file, prefix, kind, pending)) = &table {
                if let Some(key) = first_cell_key(line) {
                    let path = if prefix == "." { key } else { format!("{prefix}.{key}") };
                    keys.insert((file.clone(), kind.clone(), path), *pending);
                } else if !line.trim_start().starts_with('|') && !line.trim().is_empty() {
                    table = None;
                }
            }
        }
    }
    keys
}

/// `scenario model kind=mdof pending` → (file, prefix, kind, pending).
fn parse_marker(marker: &str, page: &str) -> (String, String, Option<String>, bool) {
    let words: Vec<&str> = marker.split_whitespace().collect();
    assert!(words.len() >= 2, "{page}: marker `{marker}` needs FILE and PREFIX");
    let kind = words.iter().find_map(|w| w.strip_prefix("kind=")).map(str::to_string);
    (
        words[0].to_string(),
        words[1].to_string(),
        kind,
        words.contains(&"pending"),
    )
}

/// The key in backticks in the first cell of a table row (`| \`speed\` | …`), if the line is such a row.
fn first_cell_key(line: &str) -> Option<String> {
    let cell = line.trim().strip_prefix('|')?.split('|').next()?.trim();
    let key = cell.strip_prefix('`')?.split('`').next()?;
    Some(key.to_string())
}

/// The keys read while parsing one root file of kind `file_kind` (`text` read from `path`), each with the
/// file that reached it. Keys of other files (catalogue spectra) are spectrum keys.
fn keys_read(
    file_kind: &str,
    path: &Path,
    text: &str,
    parse: impl FnOnce() -> Result<(), String>,
) -> Vec<(Key, PathBuf)> {
    stochvib::fields::record_keys(true);
    let accepted = parse();
    let read = stochvib::fields::record_keys(false);
    if let Err(e) = accepted {
        panic!("{} is refused: {e}", path.display());
    }
    let root: toml::Table = toml::from_str(text).unwrap();
    read.into_iter()
        .map(|(file, key)| {
            let qualified = if file == path {
                qualify(file_kind, &root, key)
            } else {
                let spectrum: toml::Table = toml::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
                qualify("spectrum", &spectrum, key)
            };
            (qualified, path.to_path_buf())
        })
        .collect()
}

/// The key `key` of a file of kind `file_kind` with root table `root`, with the kind it depends on.
fn qualify(file_kind: &str, root: &toml::Table, key: String) -> Key {
    let kind_of = |t: &toml::Table, k: &str| t.get(k).and_then(|v| v.as_str()).map(str::to_string);
    if let Some(i) = key.find("spectrum.") {
        // an inline spectrum: of its kind where every table at this path has the same kind, else of any kind
        let kinds = inline_kinds(&toml::Value::Table(root.clone()), &key[..i + "spectrum".len()]);
        let kind = (kinds.len() == 1).then(|| kinds.into_iter().next()).flatten();
        return ("spectrum".into(), kind, key[i + "spectrum.".len()..].to_string());
    }
    let kind = match file_kind {
        "scenario" if key.starts_with("model.") && key != "model.kind" => root
            .get("model")
            .and_then(|m| m.as_table())
            .and_then(|m| kind_of(m, "kind")),
        "spectrum" if !SPECTRUM_COMMON.contains(&key.as_str()) => kind_of(root, "kind"),
        "reference" if !REFERENCE_COMMON.contains(&key.as_str()) => kind_of(root, "reference"),
        _ => None,
    };
    (file_kind.to_string(), kind, key)
}

/// The `kind`s of the tables at the dotted path `path` below `v` (`input[].spectrum`: of every `[[input]]`).
fn inline_kinds(v: &toml::Value, path: &str) -> BTreeSet<String> {
    let Some(t) = v.as_table() else {
        return BTreeSet::new();
    };
    if path.is_empty() {
        return t
            .get("kind")
            .and_then(|k| k.as_str())
            .map(str::to_string)
            .into_iter()
            .collect();
    }
    let (head, rest) = path.split_once('.').unwrap_or((path, ""));
    match (head.strip_suffix("[]"), t.get(head.trim_end_matches("[]"))) {
        (Some(_), Some(toml::Value::Array(items))) => items.iter().flat_map(|x| inline_kinds(x, rest)).collect(),
        (None, Some(x)) => inline_kinds(x, rest),
        _ => BTreeSet::new(),
    }
}

/// The keys of a spectrum file that every kind has.
const SPECTRUM_COMMON: [&str; 6] = ["kind", "name", "description", "source", "unit", "domain"];
/// The keys of a reference table that every kind has.
const REFERENCE_COMMON: [&str; 3] = ["reference", "title", "source"];

/// Every key read from the shipped files and the fixtures, each with the first file that reached it.
fn every_key_read() -> BTreeMap<Key, PathBuf> {
    let root = common::root();
    let spectra = root.join("spectra");
    let mut read = Vec::new();
    for (dir, file_kind) in [
        ("data", "scenario"),
        ("data/reference", "reference"),
        ("data/workday", "workday"),
        ("spectra", "spectrum"),
    ] {
        for path in toml_files(&root.join(dir)) {
            let text = std::fs::read_to_string(&path).unwrap();
            read.extend(keys_read(file_kind, &path, &text, || {
                match file_kind {
                    "workday" => stochvib::scenario::workday_file::parse_workday(&text, &path).map(drop),
                    "spectrum" => stochvib::scenario::parse_spectrum(&text, &path).map(drop),
                    _ => stochvib::scenario::parse_document(&text, &path, &spectra).map(drop),
                }
                .map_err(|e| e.to_string())
            }));
        }
    }
    for (name, text) in fixtures() {
        // never written: the path only names the fixture and resolves relative files against data/
        let path = root.join("data").join(format!("fixture-{name}.toml"));
        read.extend(keys_read("scenario", &path, &text, || {
            stochvib::scenario::parse_document(&text, &path, &spectra)
                .map(drop)
                .map_err(|e| e.to_string())
        }));
    }
    let mut first = BTreeMap::new();
    for (key, file) in read {
        first
            .entry(key)
            .or_insert_with(|| file.strip_prefix(&root).map_or(file.clone(), Path::to_path_buf));
    }
    first
}

/// The `.toml` files directly in `dir`, sorted.
fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
}

/// Whether `doc` documents the key `read`: the same file kind and path, and the same kind or none.
fn documents(doc: &Key, read: &Key) -> bool {
    doc.0 == read.0 && doc.2 == read.2 && (doc.1.is_none() || read.1.is_none() || doc.1 == read.1)
}

fn show(k: &Key) -> String {
    match &k.1 {
        Some(kind) => format!("{} file, kind {kind}: `{}`", k.0, k.2),
        None => format!("{} file: `{}`", k.0, k.2),
    }
}

/// Every key a reader asks for is in a table of the reference pages.
#[test]
fn every_key_read_is_documented() {
    let doc = documented();
    let missing: Vec<String> = every_key_read()
        .iter()
        .filter(|(k, _)| !doc.keys().any(|d| documents(d, k)))
        .map(|(k, file)| format!("{} (reached by {})", show(k), file.display()))
        .collect();
    assert!(
        missing.is_empty(),
        "keys read but not documented in {PAGES:?}:\n{}",
        missing.join("\n")
    );
}

/// Every key of a table of the reference pages (not marked pending) is asked for by a reader.
#[test]
fn every_documented_key_is_read() {
    let read: BTreeSet<Key> = every_key_read().into_keys().collect();
    let doc = documented();
    assert!(
        doc.len() > 100,
        "only {} documented keys found: are the markers in place?",
        doc.len()
    );
    let unread: Vec<String> = doc
        .iter()
        .filter(|(k, pending)| !**pending && !read.iter().any(|r| documents(k, r)))
        .map(|(k, _)| show(k))
        .collect();
    assert!(
        unread.is_empty(),
        "documented keys no reader accepts:\n{}",
        unread.join("\n")
    );
}

/// The lines of the table below the one marker line `marker` of `text`: (index of the marker, the table's
/// lines with their newlines).
fn section(text: &str, marker: &str) -> (usize, String) {
    let lines: Vec<&str> = text.lines().collect();
    let at: Vec<usize> = (0..lines.len()).filter(|&i| lines[i].trim() == marker).collect();
    assert_eq!(at.len(), 1, "{}: the marker `{marker}` must stand once", PAGES[0]);
    let table: String = lines[at[0] + 1..]
        .iter()
        .take_while(|l| l.trim_start().starts_with('|'))
        .map(|l| format!("{l}\n"))
        .collect();
    (at[0], table)
}

/// `text` with the section of every key table replaced by the table as rendered.
fn with_key_tables(text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for table in stochvib::scenario::key_table::KEY_TABLES {
        let (at, old) = section(&(lines.join("\n") + "\n"), &table.marker());
        let new: Vec<String> = table.markdown().lines().map(str::to_string).collect();
        lines.splice(at + 1..at + 1 + old.lines().count(), new);
    }
    lines.join("\n") + "\n"
}

/// The sections of [`stochvib::scenario::key_table::KEY_TABLES`] on the reference page are the tables as
/// rendered, row for row; with `STOCHVIB_WRITE_KEY_TABLES=1` the page is rewritten from the tables first.
#[test]
fn key_tables_are_the_page() {
    let path = common::root().join(PAGES[0]);
    let mut text = std::fs::read_to_string(&path).unwrap();
    if std::env::var_os("STOCHVIB_WRITE_KEY_TABLES").is_some() {
        text = with_key_tables(&text);
        std::fs::write(&path, &text).unwrap();
    }
    assert!(stochvib::scenario::key_table::KEY_TABLES.len() >= 57);
    for table in stochvib::scenario::key_table::KEY_TABLES {
        let (_, written) = section(&text, &table.marker());
        assert_eq!(
            written,
            table.markdown(),
            "{}: the table below `{}` is not the key table (STOCHVIB_WRITE_KEY_TABLES=1 rewrites it)",
            PAGES[0],
            table.marker()
        );
    }
}
