//! The output rule, the same for every command that writes (`simulate`, `merge` of runs and of sweep
//! shards, `sweep` tables and shard files, `replay -o`, `report -o`, and the pictures of `plot`, `analyze --plots` and
//! `road --plots`): one table of commands × hostile targets — the command's own input (named directly, or
//! through a symbolic or hard link), a directory, a FIFO, a device node, a file of another kind — run with
//! and without `--overwrite`. Every case must fail with a message naming the target, leave the target and
//! the inputs exactly as they were (type, inode, bytes), and leave no file behind. Before the rule,
//! `replay -o PROFILE --overwrite` replaced its own profile, `sweep -o run.h5 --overwrite` a Monte Carlo run
//! file, and a device node given as `-o` became a regular file.
//!
//! A killed `sweep` leaves only its temporary file `<stem>.tmp-<pid>.<ext>`, which the next run of the same
//! output removes (`a_killed_sweep_leaves_a_temporary_the_next_run_removes`).

use crate::common::{self, listing, mkfifo, root, SpawnSerial};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn scratch(tag: &str) -> PathBuf {
    crate::common::scratch_dir("output-rule", tag)
}

/// Runs the tool in `cwd`; 120 s means it hung (a FIFO opened for writing blocks until a reader comes).
fn cli(args: &[String], cwd: &Path) -> Output {
    common::cli_within(args, cwd, Duration::from_secs(120))
}

fn ok(args: &[String], cwd: &Path) {
    let o = cli(args, cwd);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

fn s(v: &[&str]) -> Vec<String> {
    v.iter().map(|x| x.to_string()).collect()
}

fn p(path: &Path) -> String {
    path.display().to_string()
}

/// Makes a character device node with the numbers of /dev/null (1, 3) at `path`, in a temporary directory:
/// writing to it would be harmless, but the rule must not even replace it. `Err` with the reason where
/// this process may not create device nodes (not root).
fn mknod(path: &Path) -> Result<(), String> {
    let c = std::ffi::CString::new(p(path)).unwrap();
    // SAFETY: a valid NUL-terminated path; makedev only combines numbers
    let rc = unsafe { libc::mknod(c.as_ptr(), libc::S_IFCHR | 0o666, libc::makedev(1, 3)) };
    if rc == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error().to_string())
    }
}

/// What a target is: its type, inode and (regular file) bytes or (link) destination.
#[derive(Debug, PartialEq)]
struct Fingerprint {
    kind: String,
    inode: u64,
    content: Vec<u8>,
}

fn fingerprint(path: &Path) -> Fingerprint {
    use std::os::unix::fs::{FileTypeExt, MetadataExt};
    let m = std::fs::symlink_metadata(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let t = m.file_type();
    let kind = if t.is_symlink() {
        "symlink"
    } else if t.is_dir() {
        "dir"
    } else if t.is_fifo() {
        "fifo"
    } else if t.is_char_device() {
        "char device"
    } else {
        "file"
    };
    let content = if t.is_file() {
        std::fs::read(path).unwrap()
    } else if t.is_symlink() {
        p(&std::fs::read_link(path).unwrap()).into_bytes()
    } else {
        Vec::new()
    };
    Fingerprint {
        kind: kind.into(),
        inode: m.ino(),
        content,
    }
}

/// A command line built from the output path.
type Arguments = Box<dyn Fn(&Path) -> Vec<String>>;

/// A command that writes: its arguments for a target, the input the target must never replace, and
/// where the target lies (the argument itself, or a file in the directory given as argument).
struct Writer {
    name: &'static str,
    /// The arguments, given the path written after `-o` (or the output argument).
    args: Arguments,
    /// The file the target is named, or, with `in_dir`, the picture/shard file inside the directory.
    target: &'static str,
    in_dir: bool,
    /// An input of the command (protected by the rule).
    input: PathBuf,
    /// Whether the command has `--overwrite`.
    overwrite: bool,
    /// Files of another kind to put under the target's name.
    others: Vec<PathBuf>,
}

/// One hostile target.
#[derive(Clone, Copy, Debug)]
enum Hostile {
    /// The input itself as the argument.
    Input,
    Symlink,
    HardLink,
    Directory,
    Fifo,
    Device,
    Other(usize),
}

/// Prepares `h` at `target`; `false` (with the reason printed) if it cannot be made here.
fn make(h: Hostile, target: &Path, w: &Writer) -> bool {
    match h {
        Hostile::Input => {}
        Hostile::Symlink => std::os::unix::fs::symlink(&w.input, target).unwrap(),
        Hostile::HardLink => std::fs::hard_link(&w.input, target).unwrap(),
        Hostile::Directory => std::fs::create_dir(target).unwrap(),
        Hostile::Fifo => mkfifo(target),
        Hostile::Device => {
            if let Err(e) = mknod(target) {
                println!("skipped the device-node cases: mknod needs root ({e})");
                return false;
            }
        }
        Hostile::Other(k) => {
            std::fs::copy(&w.others[k], target).unwrap();
        }
    }
    true
}

/// The inputs every writer needs, made once: a scenario with a local spectrum file, a road scenario and
/// its profile, a run file, two shard files of a run, two sweep shard files.
struct Inputs {
    dir: PathBuf,
    scenario: PathBuf,
    road_scenario: PathBuf,
    profile: PathBuf,
    run: PathBuf,
    shards: PathBuf,
    sweep_shards: PathBuf,
}

fn inputs(d: &Path) -> Inputs {
    let dir = d.join("inputs");
    std::fs::create_dir_all(dir.join("spectra")).unwrap();
    std::fs::copy(
        root().join("spectra/conveyor-lump-load.toml"),
        dir.join("spectra/lump.toml"),
    )
    .unwrap();
    let text = std::fs::read_to_string(root().join("data/conveyor-idler.toml"))
        .unwrap()
        .replace("spectrum = \"conveyor-lump-load\"", "spectrum = \"spectra/lump.toml\"");
    let scenario = dir.join("idler.toml");
    std::fs::write(&scenario, text).unwrap();
    let road_scenario = dir.join("quarter-car.toml");
    std::fs::copy(root().join("data/quarter-car.toml"), &road_scenario).unwrap();
    let profile = dir.join("profile.csv");
    std::fs::copy(root().join("data/measured-profile.csv"), &profile).unwrap();
    let small = [
        "--realizations",
        "4",
        "--dt",
        "0.01",
        "--duration",
        "1",
        "--shard-size",
        "2",
    ];
    let run = dir.join("run.h5");
    let mut a = s(&["simulate", &p(&scenario), "--store-raw", "-o", &p(&run)]);
    a.extend(s(&small));
    ok(&a, &dir);
    let shards = dir.join("shards");
    for i in ["0", "1"] {
        let mut a = s(&["simulate", &p(&scenario), "--shard", i, "--of", "2", "-o", &p(&shards)]);
        a.extend(s(&small));
        ok(&a, &dir);
    }
    let sweep_shards = dir.join("sweep-shards");
    for i in ["0", "1"] {
        let a = s(&[
            "sweep",
            &p(&scenario),
            "--param",
            "model.zeta=0.05,0.1,0.2",
            "--shard",
            i,
            "--of",
            "2",
            "-o",
            &p(&sweep_shards),
        ]);
        ok(&a, &dir);
    }
    Inputs {
        dir,
        scenario,
        road_scenario,
        profile,
        run,
        shards,
        sweep_shards,
    }
}

fn writers(i: &Inputs) -> Vec<Writer> {
    let small = || s(&["--realizations", "4", "--dt", "0.01", "--duration", "1"]);
    let sc = p(&i.scenario);
    let road = p(&i.road_scenario);
    let profile = p(&i.profile);
    let run = p(&i.run);
    let shards = p(&i.shards);
    let sweep_shards = p(&i.sweep_shards);
    let shard0 = i.shards.join("shard-0-of-2.h5");
    let sweep0 = i.sweep_shards.join("sweep-shard-0-of-2.json");
    vec![
        Writer {
            name: "simulate",
            args: Box::new({
                let sc = sc.clone();
                move |t| {
                    let mut a = s(&["simulate", &sc, "-o", &p(t)]);
                    a.extend(small());
                    a
                }
            }),
            target: "out.h5",
            in_dir: false,
            input: i.scenario.clone(),
            overwrite: true,
            others: vec![i.profile.clone(), i.scenario.clone()],
        },
        Writer {
            name: "merge",
            args: Box::new({
                let shards = shards.clone();
                move |t| s(&["merge", &p(t), &shards])
            }),
            target: "merged.h5",
            in_dir: false,
            input: shard0,
            overwrite: true,
            others: vec![i.profile.clone(), i.scenario.clone()],
        },
        Writer {
            name: "sweep",
            args: Box::new({
                let sc = sc.clone();
                move |t| s(&["sweep", &sc, "--param", "model.zeta=0.05,0.1", "-o", &p(t)])
            }),
            target: "table.csv",
            in_dir: false,
            input: i.scenario.clone(),
            overwrite: true,
            others: vec![i.profile.clone(), i.run.clone()],
        },
        Writer {
            name: "sweep (HDF5 table)",
            args: Box::new({
                let sc = sc.clone();
                move |t| s(&["sweep", &sc, "--param", "model.zeta=0.05,0.1", "-o", &p(t)])
            }),
            target: "table.h5",
            in_dir: false,
            input: i.scenario.clone(),
            overwrite: true,
            others: vec![i.run.clone(), i.profile.clone()],
        },
        Writer {
            name: "sweep --shard",
            args: Box::new({
                let sc = sc.clone();
                move |t| {
                    s(&[
                        "sweep",
                        &sc,
                        "--param",
                        "model.zeta=0.05,0.1",
                        "--shard",
                        "0",
                        "--of",
                        "1",
                        "-o",
                        &p(t),
                    ])
                }
            }),
            target: "sweep-shard-0-of-1.json",
            in_dir: true,
            input: i.scenario.clone(),
            overwrite: true,
            others: vec![i.profile.clone(), i.run.clone()],
        },
        Writer {
            name: "merge (sweep shards)",
            args: Box::new(move |t| s(&["merge", &p(t), &sweep_shards])),
            target: "table.json",
            in_dir: false,
            input: sweep0,
            overwrite: true,
            others: vec![i.profile.clone(), i.run.clone()],
        },
        Writer {
            name: "replay",
            args: Box::new({
                let (road, profile) = (road.clone(), profile.clone());
                move |t| s(&["replay", &road, &profile, "--skip", "1", "-o", &p(t)])
            }),
            target: "history.csv",
            in_dir: false,
            input: i.profile.clone(),
            overwrite: true,
            others: vec![i.profile.clone(), i.run.clone(), i.scenario.clone()],
        },
        Writer {
            name: "plot (scenario)",
            args: Box::new({
                let sc = sc.clone();
                move |t| s(&["plot", &sc, "-o", &p(t)])
            }),
            target: "input-density.svg",
            in_dir: true,
            input: i.scenario.clone(),
            overwrite: false,
            others: vec![i.scenario.clone(), i.run.clone()],
        },
        Writer {
            name: "plot (run file)",
            args: Box::new(move |t| s(&["plot", &run, "-o", &p(t)])),
            target: "y-welch.svg",
            in_dir: true,
            input: i.run.clone(),
            overwrite: false,
            others: vec![i.scenario.clone(), i.run.clone()],
        },
        Writer {
            name: "report",
            args: Box::new({
                let sc = sc.clone();
                move |t| s(&["report", &sc, "-o", &p(t)])
            }),
            target: "report.html",
            in_dir: false,
            input: i.scenario.clone(),
            overwrite: true,
            others: vec![i.profile.clone(), i.run.clone()],
        },
        Writer {
            name: "analyze --plots",
            args: Box::new(move |t| s(&["analyze", &sc, "--plots", &p(t)])),
            target: "input-density.svg",
            in_dir: true,
            input: i.scenario.clone(),
            overwrite: false,
            others: vec![i.profile.clone()],
        },
        Writer {
            name: "road --plots",
            args: Box::new(move |t| s(&["road", &profile, "--plots", &p(t)])),
            target: "road-density-left.svg",
            in_dir: true,
            input: i.profile.clone(),
            overwrite: false,
            others: vec![i.profile.clone()],
        },
    ]
}

/// Every writer × every hostile target × with and without `--overwrite`: refused, naming the target;
/// target, inputs and directories untouched. A device node needs root: without it those cases are
/// skipped with the reason printed.
#[test]
fn every_writer_refuses_hostile_targets() {
    let _serial = common::hdf5_serial(); // no fork while a file of this binary is open
    let d = scratch("table");
    let inp = inputs(&d);
    let input_listing = |i: &Inputs| {
        let mut v = listing(&i.dir);
        v.extend(listing(&i.shards));
        v.extend(listing(&i.sweep_shards));
        v
    };
    let before_inputs = input_listing(&inp);
    let input_bytes: Vec<(PathBuf, Vec<u8>)> = [&inp.scenario, &inp.road_scenario, &inp.profile, &inp.run]
        .iter()
        .map(|f| (f.to_path_buf(), std::fs::read(f).unwrap()))
        .collect();
    let mut cases = 0;
    for w in writers(&inp) {
        // the writer works on a plain target (the table is not vacuous)
        let fine = d.join(format!("fine-{}", w.name.replace([' ', '(', ')', '-'], "_")));
        std::fs::create_dir_all(&fine).unwrap();
        let arg = if w.in_dir {
            fine.join("pictures")
        } else {
            fine.join(w.target)
        };
        ok(&(w.args)(&arg), &d);
        let mut hostiles = vec![
            Hostile::Input,
            Hostile::Symlink,
            Hostile::HardLink,
            Hostile::Directory,
            Hostile::Fifo,
            Hostile::Device,
        ];
        hostiles.extend((0..w.others.len()).map(Hostile::Other));
        for h in hostiles {
            for overwrite in [false, true] {
                if overwrite && !w.overwrite {
                    continue;
                }
                let case = d.join(format!("case-{cases}"));
                std::fs::create_dir_all(&case).unwrap();
                let (arg, target) = match (h, w.in_dir) {
                    // the input itself as the output (a directory writer gets it as its directory)
                    (Hostile::Input, _) => (w.input.clone(), w.input.clone()),
                    (_, true) => (case.clone(), case.join(w.target)),
                    (_, false) => (case.join(w.target), case.join(w.target)),
                };
                if !make(h, &target, &w) {
                    continue;
                }
                let before = fingerprint(&target);
                let files = listing(&case);
                let mut args = (w.args)(&arg);
                if overwrite {
                    args.push("--overwrite".into());
                }
                let o = cli(&args, &d);
                let err = String::from_utf8_lossy(&o.stderr);
                let what = format!("{} with {h:?} (--overwrite: {overwrite})", w.name);
                assert!(o.status.code() == Some(1), "{what}: {:?}\n{err}", o.status);
                let named = target.file_name().unwrap().to_string_lossy().into_owned();
                assert!(
                    err.contains(&named) || err.contains(&p(&arg)),
                    "{what}: the message names the target\n{err}"
                );
                assert!(!err.contains("panicked"), "{what}: {err}");
                assert_eq!(fingerprint(&target), before, "{what}: the target changed\n{err}");
                assert_eq!(listing(&case), files, "{what}: files were left or removed\n{err}");
                cases += 1;
            }
        }
    }
    assert_eq!(
        input_listing(&inp),
        before_inputs,
        "nothing was added to or removed from the inputs"
    );
    for (f, bytes) in input_bytes {
        assert_eq!(std::fs::read(&f).unwrap(), bytes, "{} changed", f.display());
    }
    println!("{cases} hostile cases refused");
    assert!(cases >= 120, "only {cases} cases ran");
    let _ = std::fs::remove_dir_all(&d);
}

/// A `sweep` killed (SIGKILL) while it writes its table leaves nothing under the table's name, only its
/// temporary `table.tmp-<pid>.csv`; the next `sweep` of the same table removes it (the killed process is
/// gone) and writes the complete table. Studies are recomputed, not resumed: a table has no partial state
/// worth keeping (`--shard` splits a long study into files that are kept).
#[test]
fn a_killed_sweep_leaves_a_temporary_the_next_run_removes() {
    let d = scratch("kill");
    let table = d.join("table.csv");
    let sc = p(&root().join("data/scraper-sprung-cab.toml"));
    // 100 points with a Monte Carlo batch each: many seconds of work, so that the kill comes while the
    // table is being written (its temporary file is created before the first point is computed)
    let args = s(&[
        "sweep",
        &sc,
        "--param",
        "model.zeta2=0.1..0.4:100",
        "--monte-carlo",
        "400",
        "--dt",
        "0.01",
        "--duration",
        "100",
    ]);
    let mut a = args.clone();
    a.extend(s(&["-o", &p(&table)]));
    let mut child = Command::new(crate::common::cli_bin())
        .current_dir(&d)
        .env("STOCHVIB_SPECTRA", root().join("spectra"))
        .args(&a)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn_serial()
        .unwrap();
    let tmp = d.join(format!("table.tmp-{}.csv", child.id()));
    let start = Instant::now();
    while !tmp.exists() && child.try_wait().unwrap().is_none() {
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "the sweep never started its table"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(
        child.try_wait().unwrap().is_none(),
        "the sweep ended before the kill: make it longer"
    );
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    assert_eq!(listing(&d), [tmp.file_name().unwrap().to_string_lossy().into_owned()]);
    // the next run of the same table: the dead process's temporary is removed, the table written
    let mut a = s(&[
        "sweep",
        &sc,
        "--param",
        "model.zeta2=0.1..0.4:3",
        "--param",
        "input.speed=5..20:2",
    ]);
    a.extend(s(&["-o", &p(&table)]));
    let o = cli(&a, &d);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(listing(&d), ["table.csv"]);
    let text = std::fs::read_to_string(&table).unwrap();
    assert!(text.starts_with("point,") && text.lines().count() > 6, "{text}");
    let _ = std::fs::remove_dir_all(&d);
}

/// The temporary file a killed `sweep --shard` leaves (`sweep-shard-0-of-1.tmp-<pid>.json`, here of a pid
/// above Linux's largest, so certainly gone, and cut in the middle) is passed over by `merge` and removed
/// by the next `sweep --shard` of the same part.
#[test]
fn a_killed_shard_writer_leaves_nothing_a_merge_reads() {
    let d = scratch("shard-tmp");
    let sc = p(&root().join("data/conveyor-idler.toml"));
    let dir = d.join("shards");
    std::fs::create_dir_all(&dir).unwrap();
    let stale = dir.join("sweep-shard-0-of-1.tmp-4194305.json");
    std::fs::write(&stale, "{\"format\":\"stochvib sweep shard\",\"part\":").unwrap();
    let shard = s(&[
        "sweep",
        &sc,
        "--param",
        "model.zeta=0.1,0.2",
        "--shard",
        "0",
        "--of",
        "1",
        "-o",
        &p(&dir),
    ]);
    ok(&shard, &d);
    assert_eq!(listing(&dir), ["sweep-shard-0-of-1.json"]);
    std::fs::write(&stale, "{\"format\":\"stochvib sweep shard\",\"part\":").unwrap();
    ok(&s(&["merge", &p(&d.join("table.csv")), &p(&dir)]), &d);
    let table = std::fs::read_to_string(d.join("table.csv")).unwrap();
    assert_eq!(table.lines().count(), 1 + 2 * 2, "{table}");
    let _ = std::fs::remove_dir_all(&d);
}
