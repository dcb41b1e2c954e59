//! The stale-binary guard of [`crate::common::cli_bin`] compares the CLI binary with the files listed in
//! [`crate::common::cli_bin::BUILD_INPUTS`]: every file the library embeds must be one of them, or an edit
//! of it would leave an old binary undetected.

use crate::common::cli_bin::BUILD_INPUTS;
use std::path::{Path, PathBuf};

/// The files embedded by `include_str!`/`include_bytes!` in `file` (whose text is `text`), resolved: a
/// literal path is relative to the file; `concat!(env!("CARGO_MANIFEST_DIR"), "/p")` is `root/p`.
fn embedded(file: &Path, text: &str, root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for line in text.lines().filter(|l| !l.trim_start().starts_with("//")) {
        for mac in ["include_str!(", "include_bytes!("] {
            let Some(at) = line.find(mac) else { continue };
            let call = &line[at..];
            let literal = call.rsplit('"').nth(1).expect("a string literal in the macro call");
            out.push(if call.contains("CARGO_MANIFEST_DIR") {
                root.join(literal.trim_start_matches('/'))
            } else {
                file.parent().expect("a file in a directory").join(literal)
            });
        }
    }
    out
}

#[test]
fn every_file_the_library_includes_is_a_build_input() {
    let root = crate::common::root();
    let mut files = Vec::new();
    crate::layers::rust_files(&root.join("src"), &mut files);
    let inputs: Vec<PathBuf> = BUILD_INPUTS
        .iter()
        .map(|p| root.join(p).canonicalize().unwrap())
        .collect();
    let mut found = 0;
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        for path in embedded(f, &text, &root) {
            let path = path
                .canonicalize()
                .unwrap_or_else(|e| panic!("{}: embeds {} ({e})", f.display(), path.display()));
            assert!(
                inputs.iter().any(|i| path.starts_with(i)),
                "{} embeds {}, which is not in BUILD_INPUTS (tests/common/cli_bin.rs)",
                f.display(),
                path.display()
            );
            found += 1;
        }
    }
    // the README, the run-file format, the font, two reference tables and the seat scenario at least
    assert!(found >= 6, "only {found} embedded files found: the scanner is broken");
}

#[test]
fn the_scanner_resolves_both_forms() {
    let root = Path::new("/r");
    let text = "x\nconst A: &str = include_str!(\"../../data/a.toml\");\n\
                // include_str!(\"comment.toml\")\n\
                include_bytes!(concat!(env!(\"CARGO_MANIFEST_DIR\"), \"/assets/f.ttf\"))\n";
    let got = embedded(Path::new("/r/src/m/x.rs"), text, root);
    assert_eq!(
        got,
        [
            PathBuf::from("/r/src/m/../../data/a.toml"),
            PathBuf::from("/r/assets/f.ttf")
        ]
    );
}

/// The guard's clock: the newest build input of a tree, searched through directories, other files ignored.
#[test]
fn the_newest_build_input_is_found_in_subdirectories() {
    use std::time::{Duration, SystemTime};
    let dir = crate::common::scratch_path("build_inputs", "tree");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("src/deep")).unwrap();
    std::fs::create_dir_all(dir.join("docs")).unwrap();
    let t0 = SystemTime::UNIX_EPOCH + Duration::from_secs(1_700_000_000);
    for (name, age_s) in [
        ("Cargo.toml", 30),
        ("src/lib.rs", 20),
        ("src/deep/x.rs", 10),
        ("docs/other.md", 0),
    ] {
        let f = std::fs::File::create(dir.join(name)).unwrap();
        f.set_modified(t0 - Duration::from_secs(age_s)).unwrap();
    }
    let (path, t) = crate::common::cli_bin::newest_input(&dir).unwrap();
    // docs/other.md is newer but no build input
    assert_eq!((path, t), (dir.join("src/deep/x.rs"), t0 - Duration::from_secs(10)));
}
