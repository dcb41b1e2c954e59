//! Cargo builds a package's binaries for its integration tests: this test makes `cargo test --workspace`
//! build the `stochvib` CLI, which the integration tests (the `stochvib-tests` package, tests/suite) run
//! from beside their own executable (tests/common/cli_bin.rs). It checks that the binary starts and names
//! the version of this package.

#[test]
fn the_cli_starts_and_names_its_version() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stochvib"))
        .arg("--version")
        .output()
        .expect("running the CLI binary");
    assert!(out.status.success(), "{out:?}");
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        concat!("stochvib ", env!("CARGO_PKG_VERSION"))
    );
}
