//! The CLI binary the tests run, and the source tree they read.
//!
//! The integration tests are a package of their own (`stochvib-tests`, compiled without optimisation), so
//! Cargo does not hand them the binary's path (`CARGO_BIN_EXE_*` exists only for a package's own
//! binaries). The binary is the one Cargo built beside the test executable: `<target>/<profile>/stochvib`
//! for `<target>/<profile>/deps/suite-<hash>`. `cargo test --workspace` builds it (the library's package
//! keeps an integration test, `tests/cli_build.rs`, for which Cargo builds its binaries). A command that
//! builds only this package (`cargo test -p stochvib-tests`) does not: the binary may then be older than
//! the sources, and the tests would check an old CLI. [`cli_bin`] refuses such a binary, with the command
//! that brings it up to date.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::SystemTime;

/// The source tree (the parent of this package's directory `tests/`).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ lies in the source tree")
        .to_path_buf()
}

/// What the library and the CLI are compiled from, relative to [`root`]: the files and directories
/// (searched recursively) whose change makes Cargo rebuild them. `build_inputs::every_file_the_library_includes_is_a_build_input`
/// checks that every `include_str!`/`include_bytes!` of `src/` lies here.
pub const BUILD_INPUTS: &[&str] = &[
    "src",
    "spectra",
    "assets",
    "data/reference",
    "data/operator-seat.toml",
    "docs/run-file-format.md",
    "README.md",
    "build.rs",
    "Cargo.toml",
    "Cargo.lock",
];

/// The CLI binary of this checkout (see the module docs), checked once: it exists and is not older than
/// any of the [`BUILD_INPUTS`].
///
/// # Panics
/// When the binary is missing or stale, with the file that is newer and the command that rebuilds it.
pub fn cli_bin() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        let exe = std::env::current_exe().expect("the test executable's path");
        let bin = exe
            .parent()
            .and_then(Path::parent)
            .map(|dir| dir.join(format!("stochvib{}", std::env::consts::EXE_SUFFIX)))
            .expect("the test executable lies in <target>/<profile>/deps/");
        let rebuild = "build it with `cargo test --workspace --no-run` (or run the tests with `cargo test \
                       --workspace --tests FILTER`, which builds it)";
        let built = std::fs::metadata(&bin)
            .and_then(|m| m.modified())
            .unwrap_or_else(|e| panic!("no CLI binary at {} ({e}): {rebuild}", bin.display()));
        if let Some((newer, _)) = newest_input(&root()).filter(|(_, t)| *t > built) {
            panic!(
                "the CLI binary {} is older than {}: the tests would run an old CLI; {rebuild}",
                bin.display(),
                newer.display()
            );
        }
        bin
    })
}

/// The newest file of the [`BUILD_INPUTS`] under `root`, with its modification time.
pub fn newest_input(root: &Path) -> Option<(PathBuf, SystemTime)> {
    let mut newest: Option<(PathBuf, SystemTime)> = None;
    let mut stack: Vec<PathBuf> = BUILD_INPUTS.iter().map(|p| root.join(p)).collect();
    while let Some(p) = stack.pop() {
        let Ok(meta) = std::fs::metadata(&p) else { continue };
        if meta.is_dir() {
            let entries = std::fs::read_dir(&p).expect("reading a source directory");
            stack.extend(entries.filter_map(|e| e.ok().map(|e| e.path())));
        } else if let Ok(t) = meta.modified()
            && newest.as_ref().is_none_or(|(_, n)| t > *n)
        {
            newest = Some((p, t));
        }
    }
    newest
}
