//! Every message names what the user wrote: each case here was reported against the wrong thing before —
//! `replay --speed 1e308` blamed the scenario's `input.speed`; a bad `--param` of `sweep` was blamed on the
//! scenario file; a two-row profile reported "segment length = 2"; `merge` did not name a damaged shard
//! file; merging into a shard said "missing shard 0, resubmit"; a garbage `.tmp` reported
//! "18446744073709551615 completed shards"; `--dt 1e-300` said "gives 0 samples"; `omega_p = "1 rad/m"` was
//! refused as "expected a finite number"; a real pole of a rational spectrum was blamed on its numerator.
//! The expectations are the names the user typed (flags, keys, files), nothing computed by the code.

use crate::common::{self, root};
use std::path::{Path, PathBuf};
use std::time::Duration;

fn scratch(tag: &str) -> PathBuf {
    common::scratch_dir("messages", tag)
}

/// The stderr of a command that must be refused by the tool (status 1) without a panic.
fn refused(args: &[&str], cwd: &Path) -> String {
    common::cli_fails(1, args, cwd)
}

fn data(p: &str) -> String {
    root().join("data").join(p).display().to_string()
}

/// `replay --speed 1e308`: the speed came from the flag, so the flag is named, not the scenario's key.
#[test]
fn replay_names_the_speed_flag() {
    let d = scratch("speed");
    let e = refused(
        &[
            "replay",
            &data("quarter-car.toml"),
            &data("measured-profile.csv"),
            "--speed",
            "1e308",
        ],
        &d,
    );
    assert!(e.contains("--speed"), "{e}");
    assert!(!e.contains("input.speed"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// A `--param` value the model refuses (a negative mass) is named as the flag and the value the user
/// wrote, with the point of the study, not as a key of the scenario file (which does not hold that value).
#[test]
fn sweep_names_the_param_flag() {
    let d = scratch("param");
    let e = refused(
        &[
            "sweep",
            &data("quarter-car-model.toml"),
            "--param",
            "model.sprung_mass=-300 kg,310 kg",
        ],
        &d,
    );
    assert!(
        e.contains("--param") && e.contains("model.sprung_mass=") && e.contains("point 0"),
        "{e}"
    );
    assert!(!e.contains("key `model.sprung_mass`"), "{e}");
    let e = refused(
        &[
            "sweep",
            &data("quarter-car-model.toml"),
            "--param",
            "model.no_such_key=1,2",
        ],
        &d,
    );
    assert!(e.contains("--param") && e.contains("model.no_such_key"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// `simulate --dt 1e-300`: the message names both flags and the sample count the two give, never
/// "gives 0 samples" (10³⁰⁰ samples per realization is what 1 s at that step means).
#[test]
fn a_tiny_time_step_is_reported_as_too_many_samples() {
    let d = scratch("dt");
    let args = [
        "simulate",
        &data("quarter-car-model.toml"),
        "--realizations",
        "4",
        "--dt",
        "1e-300",
        "-o",
        "x.h5",
    ];
    let e = refused(&args, &d);
    assert!(
        e.contains("--duration") && e.contains("--dt") && e.contains("samples per realization"),
        "{e}"
    );
    assert!(!e.contains("gives 0 samples"), "{e}");
    assert!(common::listing(&d).is_empty(), "{:?}", common::listing(&d));
    let _ = std::fs::remove_dir_all(&d);
}

/// `omega_p` of the Ammon–Bormann coherence is a plain number in (rad/m)·m^a: a quantity text is refused
/// saying so, naming the file and the key, not as "expected a finite number".
#[test]
fn omega_p_with_a_unit_is_refused_saying_it_takes_a_plain_number() {
    let d = scratch("omega-p");
    let text = std::fs::read_to_string(data("full-vehicle-two-tracks.toml")).unwrap();
    let t = text.replacen(
        "coherence = { kind = \"dodds-robson\", waviness = 2 }",
        "coherence = { kind = \"ammon-bormann\", omega_p = \"1 rad/m\", w = 2, p = 0.5 }",
        1,
    );
    assert_ne!(t, text, "the shipped file has the Dodds–Robson coherence");
    let p = d.join("omega-p.toml");
    std::fs::write(&p, t).unwrap();
    let e = stochvib::scenario::load_scenario(&p, &root().join("spectra"))
        .unwrap_err()
        .to_string();
    for part in ["omega-p.toml", "omega_p", "without a unit", "(rad/m)·m^a"] {
        assert!(e.contains(part), "{part}: {e}");
    }
    assert!(!e.contains("expected a finite number"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// D(ω²) = ω² − 1 vanishes at ω = 1 rad/s: a real pole, a fault of the denominator whatever the numerator
/// is — also when the numerator N(ω²) = −1 is negative too (it was blamed on the numerator before).
#[test]
fn a_real_pole_is_blamed_on_the_denominator() {
    use stochvib::spectrum::{Domain, RationalSpectrum};
    for num in [vec![1.0], vec![-1.0]] {
        let e = RationalSpectrum::new(num, vec![-1.0, 1.0], Domain::Temporal).unwrap_err();
        match &e {
            stochvib::Error::InvalidParameter { name, .. } => assert_eq!(name, "denominator", "{e}"),
            other => panic!("{other}"),
        }
        assert!(e.to_string().contains("pole"), "{e}");
    }
    // a numerator negative somewhere with a good denominator is the numerator's fault
    let e = RationalSpectrum::new(vec![-1.0], vec![1.0, 1.0], Domain::Temporal).unwrap_err();
    assert!(
        matches!(&e, stochvib::Error::InvalidParameter { name, .. } if name == "numerator"),
        "{e}"
    );
}

/// A garbage file where a run's `.tmp` goes is named as such (not an HDF5 file, not an interrupted run)
/// and left in place; before, it was "an interrupted run with 18446744073709551615 completed shards".
#[test]
fn a_garbage_tmp_is_named_as_not_a_run() {
    let d = scratch("tmp");
    std::fs::write(d.join("g.h5.tmp"), b"garbage, not a run").unwrap();
    let args = [
        "simulate",
        &data("conveyor-idler.toml"),
        "--realizations",
        "4",
        "--duration",
        "2",
        "--dt",
        "0.01",
    ];
    let e = refused(&[&args[..], &["-o", "g.h5"]].concat(), &d);
    assert!(
        e.contains("g.h5.tmp") && e.contains("not an HDF5 file") && e.contains("--overwrite"),
        "{e}"
    );
    assert!(!e.contains("18446744073709551615"), "{e}");
    assert_eq!(std::fs::read(d.join("g.h5.tmp")).unwrap(), b"garbage, not a run");
    assert!(!d.join("g.h5").exists());
    let _ = std::fs::remove_dir_all(&d);
}

/// `merge` names the shard file whose accumulator data do not match their checksums (a bit flipped in the
/// data, not in HDF5's metadata), and refuses a shard file as its output ("missing shard 0, resubmit"
/// before), leaving that shard byte for byte as it was.
#[test]
fn merge_names_the_damaged_shard_and_refuses_a_shard_as_output() {
    let d = scratch("merge");
    let fixtures = {
        let _g = common::hdf5_serial();
        crate::fuzz::commands::Fixtures::ensure(&root(), &d.join("fixtures"))
    };
    let shard = |i: usize| fixtures.dir.join(format!("a/shard-{i}-of-3.h5")).display().to_string();
    let damaged = d.join("shard-1-of-3.h5");
    std::fs::copy(shard(1), &damaged).unwrap();
    crate::fuzz::commands::damage_accumulator(&damaged, 3);
    assert_ne!(std::fs::read(&damaged).unwrap(), std::fs::read(shard(1)).unwrap());
    let e = refused(&["merge", "m.h5", &shard(0), damaged.to_str().unwrap(), &shard(2)], &d);
    assert!(e.contains(damaged.to_str().unwrap()) && e.contains("damaged"), "{e}");
    assert!(!d.join("m.h5").exists() && !d.join("m.h5.tmp").exists());
    let before = std::fs::read(shard(0)).unwrap();
    let s: Vec<String> = (0..3).map(shard).collect();
    for extra in [&[][..], &["--overwrite"][..]] {
        let args = [&["merge", s[0].as_str(), &s[1], &s[2]][..], extra].concat();
        let e = refused(&args, &d);
        assert!(e.contains("shard") && e.contains(&s[0]), "{e}");
        assert!(!e.contains("missing shard 0") && !e.contains("resubmit"), "{e}");
    }
    assert_eq!(std::fs::read(shard(0)).unwrap(), before);
    let _ = std::fs::remove_dir_all(&d);
}

/// Found by the fuzz campaign: the S–N intercept C = N·S_a^k derived from the reference point overflows
/// for k = 2⁶⁰; the message named `analysis.fatigue.C`, a key the file does not have. It names `k`.
#[test]
fn a_derived_sn_intercept_is_blamed_on_a_key_of_the_file() {
    let d = scratch("sn");
    let text = std::fs::read_to_string(data("operator-seat-verdicts.toml")).unwrap();
    let t = text.replacen("\nk = 5 ", "\nk = 1152921504606846976 ", 1);
    assert_ne!(t, text);
    let p = d.join("sn.toml");
    std::fs::write(&p, t).unwrap();
    let e = stochvib::scenario::load_scenario(&p, &root().join("spectra"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("sn.toml") && e.contains("analysis.fatigue.k"), "{e}");
    assert!(!e.contains("analysis.fatigue.C"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

/// Found by the fuzz campaign: `replay --skip -1` named the library's parameter `skip`; `merge` into a
/// sweep table named `output.txt` named a parameter `output` (merge's output is an argument, not a flag):
/// the flag, and the file, are named.
#[test]
fn replay_skip_and_a_table_extension_name_what_the_user_wrote() {
    let d = scratch("skip");
    let e = refused(
        &[
            "replay",
            &data("quarter-car.toml"),
            &data("measured-profile.csv"),
            "--skip=-1",
        ],
        &d,
    );
    assert!(e.contains("--skip"), "{e}");
    let sc = data("quarter-car-model.toml");
    let e = refused(
        &[
            "sweep",
            &sc,
            "--param",
            "model.sprung_mass=300 kg,310 kg",
            "-o",
            "table.txt",
        ],
        &d,
    );
    assert!(e.contains("table.txt") && e.contains(".csv, .json or .h5"), "{e}");
    assert!(!e.contains("parameter `output`"), "{e}");
    assert!(common::listing(&d).is_empty(), "{:?}", common::listing(&d));
    let _ = std::fs::remove_dir_all(&d);
}

/// Found by the fuzz campaign: a sweep of 10⁶ speeds with a key the scenario does not have built the
/// excitation of every speed before it looked at point 0 (145 s on a loaded 2-core machine) and then
/// refused the key; the excitations are built at their first use, so the refusal comes at once. The limit
/// of 60 s is 100 times what the refusal takes on an idle machine.
#[test]
fn a_sweep_of_a_million_speeds_refuses_a_bad_key_at_once() {
    let d = scratch("speeds");
    let args = [
        "sweep",
        &data("balancer-bogie.toml"),
        "--param",
        "input.speed=4..6:1000000 m/s",
        "--param",
        "model.nope=1,2",
    ];
    let o = common::cli_within(&args, &d, Duration::from_secs(60));
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("model.nope"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}
