//! Embeds the spectrum catalogue (`spectra/*.toml`) in the library: `$OUT_DIR/spectra.rs` is a list of
//! (name, text) pairs, each text an `include_str!` of its file, so that an installed binary finds every
//! catalogue name without the source tree (an override directory still wins at run time).

use std::path::Path;

fn main() {
    let root = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let dir = Path::new(&root).join("spectra");
    println!("cargo:rerun-if-changed=spectra");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .expect("the spectra/ directory of the source tree")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    let mut list = String::from("&[\n");
    for f in &files {
        let name = f.file_stem().expect("a file name").to_string_lossy();
        list.push_str(&format!(
            "    ({name:?}, include_str!({:?})),\n",
            f.display().to_string()
        ));
    }
    list.push_str("]\n");
    let out = Path::new(&std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("spectra.rs");
    std::fs::write(out, list).expect("writing $OUT_DIR/spectra.rs");
}
