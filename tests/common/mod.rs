//! Helpers shared by the integration tests (each test file includes them with `mod common;`): the named
//! tolerances and the relative difference used in assertions.
#![allow(dead_code)] // each test binary uses a different subset

pub mod cli_bin;
pub mod response_only;
pub mod scenario_text;
pub mod tolerance;
pub mod two_wheel_body;

pub use cli_bin::{cli_bin, root};
pub use scenario_text::{quarter_car_scenario, two_wheels};

use std::path::PathBuf;

/// Relative difference |a − b| / max(|a|, |b|), 0 when both are 0 (the library's
/// [`stochvib::numbers::rel_diff`]).
pub fn rel(a: f64, b: f64) -> f64 {
    stochvib::numbers::rel_diff(a, b)
}

/// The scenario text of a random stiff three-mass chain on a base (the family of the stiff-chain
/// report: masses 0.05–0.5, 5 and 2000–2·10⁶ kg, stiffnesses 10⁴–10⁷ N/m, dampers 20–2000 N s/m, type-1
/// input), drawn from `rng`; outputs the first mass's displacement and the last element's force.
pub fn stiff_chain_text(rng: &mut rand::rngs::Xoshiro256PlusPlus) -> String {
    use rand::RngExt;
    let m = [
        0.05 * 10f64.powf(rng.random::<f64>()),
        5.0,
        2000.0 * 10f64.powf(rng.random::<f64>() * 3.0),
    ];
    let k: Vec<f64> = (0..3)
        .map(|_| 1e5 * 10f64.powf(rng.random::<f64>() * 3.0 - 1.0))
        .collect();
    let b: Vec<f64> = (0..3).map(|_| 20.0 * 10f64.powf(rng.random::<f64>() * 2.0)).collect();
    format!(
        r#"
[model]
kind = "mdof"
base_inputs = 1
coordinates = [{{ name = "a", unit = "m", mass = {} }}, {{ name = "b", unit = "m", mass = {} }}, {{ name = "c", unit = "m", mass = {} }}]
[[model.element]]
name = "k1"
point = [1, 0, 0]
to = "base 0"
stiffness = {}
damping = {}
[[model.element]]
name = "k2"
point = [0, 1, 0]
to = [1, 0, 0]
stiffness = {}
damping = {}
[[model.element]]
name = "k3"
point = [0, 0, 1]
to = [0, 1, 0]
stiffness = {}
damping = {}
[[model.output]]
name = "a"
quantity = "displacement"
point = [1, 0, 0]
[[model.output]]
name = "f3"
quantity = "element-force"
element = "k3"
[input]
spectrum = "type1"
"#,
        m[0], m[1], m[2], k[0], b[0], k[1], b[1], k[2], b[2]
    )
}

/// Asserts that `x` lies inside the interval `iv` (bounds included), naming `what` and both bounds.
pub fn assert_inside(iv: &stochvib::estimate::Interval, x: f64, what: &str) {
    assert!(
        iv.lower <= x && x <= iv.upper,
        "{what} {x} outside [{}, {}]",
        iv.lower,
        iv.upper
    );
}

/// Serialises, within one test binary, the tests that spawn child processes with the tests that hold HDF5
/// files open (take it at the top of every test of such a binary; the guard is held to the test's end).
///
/// Why: HDF5 locks every file it opens with flock(2), and that lock belongs to the open file description,
/// which a forked child shares through its copy of the descriptor. stochvib marks its descriptors
/// close-on-exec right after HDF5's open(2) ([`stochvib::store`]'s `open_sec2`), but a fork by another test
/// thread (`Command::spawn`, `output`, `status`) between that open(2) and the fcntl leaves the descriptor in
/// the child for its whole life, and even with the flag set the child holds it from fork to exec. While the
/// child holds it, a later open of the same file by the test (a reader after the writer closed it, a resume)
/// fails with "unable to lock file" — rarely, depending on thread timing. Disabling HDF5's locking
/// (HDF5_USE_FILE_LOCKING=FALSE) would hide it but would also change what the tests check (a run file being
/// written by another process is detected through that lock). With this lock no fork happens while any file
/// of the binary is open, so the outcome no longer depends on timing; each child process writes its own
/// files.
pub fn hdf5_serial() -> std::sync::MutexGuard<'static, ()> {
    static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());
    SERIAL.lock().unwrap_or_else(|e| e.into_inner())
}

/// The bits of every statistic of a run summary (estimate and interval bounds, in output order): what
/// "bit-identical statistics" compares.
pub fn statistic_bits(s: &stochvib::simulate::RunSummary) -> Vec<u64> {
    s.outputs
        .iter()
        .flat_map(|o| {
            o.statistics
                .iter()
                .flat_map(|st| [st.interval.estimate, st.interval.lower, st.interval.upper])
        })
        .map(f64::to_bits)
        .collect()
}

/// (output, statistic, bits of estimate/lower/upper/confidence/analytic, covers, n_used).
pub type StatBits = (String, String, [u64; 5], Option<bool>, u64);

/// Every stored statistic of a run file with its name and all its bits: what "bit-identical statistics"
/// of a merged run and a single-process run compares, statistic by statistic.
pub fn stored_statistic_bits(s: &[stochvib::store::OutputStatistics]) -> Vec<StatBits> {
    s.iter()
        .flat_map(|o| {
            o.statistics.iter().map(move |st| {
                let iv = &st.interval;
                (
                    o.output.clone(),
                    st.name.clone(),
                    [
                        iv.estimate.to_bits(),
                        iv.lower.to_bits(),
                        iv.upper.to_bits(),
                        iv.confidence.to_bits(),
                        st.analytic.unwrap_or(f64::NAN).to_bits(),
                    ],
                    st.covers,
                    o.n_used,
                )
            })
        })
        .collect()
}

/// The bits of every stored Welch density value of the run file `out`.
pub fn psd_bits(out: &std::path::Path) -> Vec<u64> {
    let run = stochvib::store::RunFile::open(out).unwrap();
    run.psd()
        .unwrap()
        .iter()
        .flat_map(|p| p.density.iter().map(|x| x.to_bits()).collect::<Vec<_>>())
        .collect()
}

/// `Command::output`, `status` and `spawn` through [`stochvib::store::spawn_child`]: no child process of
/// the test binary (one process for every integration test) inherits the descriptor, and the flock(2) lock,
/// of a run file another test thread is opening.
pub trait SpawnSerial {
    /// Like `Command::output` (stdin closed, stdout and stderr captured).
    fn output_serial(&mut self) -> std::io::Result<std::process::Output>;
    /// Like `Command::status` (the standard streams as configured).
    fn status_serial(&mut self) -> std::io::Result<std::process::ExitStatus>;
    /// Like `Command::spawn`.
    fn spawn_serial(&mut self) -> std::io::Result<std::process::Child>;
}

impl SpawnSerial for std::process::Command {
    fn output_serial(&mut self) -> std::io::Result<std::process::Output> {
        use std::process::Stdio;
        self.stdin(Stdio::null()).stdout(Stdio::piped()).stderr(Stdio::piped());
        stochvib::store::spawn_child(self)?.wait_with_output()
    }
    fn status_serial(&mut self) -> std::io::Result<std::process::ExitStatus> {
        stochvib::store::spawn_child(self)?.wait()
    }
    fn spawn_serial(&mut self) -> std::io::Result<std::process::Child> {
        stochvib::store::spawn_child(self)
    }
}

/// Runs the command-line tool in `cwd` with the source tree's catalogue (`$STOCHVIB_SPECTRA`), stdin
/// closed, output captured; a command still running after `limit` has hung (a FIFO opened for writing
/// blocks until a reader comes, one opened for reading until a writer does): it is killed and the test
/// fails naming it. Both pipes are read while the child runs (one thread each), so a child that writes
/// more than a pipe holds (64 KiB on Linux) does not block on a full pipe while the test waits for it.
pub fn cli_within<S: AsRef<std::ffi::OsStr>>(
    args: &[S],
    cwd: &std::path::Path,
    limit: std::time::Duration,
) -> std::process::Output {
    cli_limited(args, cwd, limit, None)
}

/// Resource limits of a child process: CPU seconds (`RLIMIT_CPU`: the kernel stops a child that computes
/// longer, whatever the load of the machine) and bytes of address space (`RLIMIT_AS`: an allocation
/// beyond it fails).
#[derive(Debug, Clone, Copy)]
pub struct ChildLimits {
    /// CPU time, s (user + system, all threads).
    pub cpu_s: u64,
    /// Address space, bytes.
    pub memory: u64,
}

/// [`cli_within`] with the child under `limits` (applied between fork and exec).
pub fn cli_limited<S: AsRef<std::ffi::OsStr>>(
    args: &[S],
    cwd: &std::path::Path,
    limit: std::time::Duration,
    limits: Option<ChildLimits>,
) -> std::process::Output {
    use std::io::Read;
    let mut cmd = std::process::Command::new(cli_bin());
    cmd.current_dir(cwd)
        .env("STOCHVIB_SPECTRA", root().join("spectra"))
        .args(args)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    if let Some(l) = limits {
        set_limits(&mut cmd, l);
    }
    let mut child = cmd.spawn_serial().unwrap();
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            let _ = r.read_to_end(&mut v);
            v
        })
    };
    let out = drain(Box::new(child.stdout.take().unwrap()));
    let err = drain(Box::new(child.stderr.take().unwrap()));
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(st) = child.try_wait().unwrap() {
            break st;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            let words: Vec<String> = args.iter().map(|a| a.as_ref().to_string_lossy().into_owned()).collect();
            panic!("`stochvib {}` hung", words.join(" "));
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    std::process::Output {
        status,
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    }
}

fn set_limits(cmd: &mut std::process::Command, l: ChildLimits) {
    use std::os::unix::process::CommandExt;
    // SAFETY: only async-signal-safe calls (setrlimit) run between fork and exec.
    unsafe {
        cmd.pre_exec(move || {
            for (resource, soft, hard) in [
                (libc::RLIMIT_CPU, l.cpu_s, l.cpu_s + 5),
                (libc::RLIMIT_AS, l.memory, l.memory),
                (libc::RLIMIT_CORE, 0, 0),
            ] {
                let lim = libc::rlimit {
                    rlim_cur: soft as libc::rlim_t,
                    rlim_max: hard as libc::rlim_t,
                };
                if libc::setrlimit(resource, &lim) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
            }
            Ok(())
        });
    }
}

/// The directory of this run of the suite, `stochvib-suite-PID` in the system's temporary directory: made on
/// first use and removed with everything in it when the suite process exits (an `atexit` handler: it runs
/// when the test harness returns or calls `exit`, whether tests passed or failed), so repeated runs leave
/// nothing behind. Set `STOCHVIB_KEEP_SCRATCH=1` to keep it for a post-mortem; a run killed by a signal
/// leaves it too.
static SUITE_SCRATCH: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

extern "C" fn remove_suite_scratch() {
    if let Some(d) = SUITE_SCRATCH.get() {
        let _ = std::fs::remove_dir_all(d);
    }
}

fn suite_scratch() -> &'static std::path::Path {
    SUITE_SCRATCH.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("stochvib-suite-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        if std::env::var_os("STOCHVIB_KEEP_SCRATCH").is_none() {
            // SAFETY: registers a plain `extern "C"` function; it only reads a set `OnceLock` and removes files.
            let registered = unsafe { libc::atexit(remove_suite_scratch) };
            assert_eq!(registered, 0, "atexit refused the scratch cleanup");
        }
        d
    })
}

/// The path `GROUP-TAG` in this run's scratch directory (the path itself is not created; its parent is). The
/// suite is one binary whose tests run in parallel threads of one process: the process id only separates
/// concurrent runs of the suite, so every test names its own `(group, tag)` (the file's group, the test's
/// tag).
pub fn scratch_path(group: &str, tag: &str) -> PathBuf {
    suite_scratch().join(format!("{group}-{tag}"))
}

/// A fresh empty directory [`scratch_path`]`(group, tag)` (what an earlier run left there is removed).
pub fn scratch_dir(group: &str, tag: &str) -> PathBuf {
    let d = scratch_path(group, tag);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The directory [`scratch_path`]`(group, tag)`, created if missing and kept if there (for a test that
/// comes back to its files).
pub fn scratch_kept(group: &str, tag: &str) -> PathBuf {
    let d = scratch_path(group, tag);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The stderr of `stochvib ARGS` run in `cwd` ([`cli_within`], 120 s), which must fail with status `code`
/// (1: refused by the tool; 2: by the argument parser) without a panic.
pub fn cli_fails(code: i32, args: &[&str], cwd: &std::path::Path) -> String {
    let o = cli_within(args, cwd, std::time::Duration::from_secs(120));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(
        o.status.code(),
        Some(code),
        "`{}`: {:?}\n{err}",
        args.join(" "),
        o.status
    );
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// The names in `dir`, sorted.
pub fn listing(dir: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Makes a FIFO at `path` (in a test's temporary directory).
pub fn mkfifo(path: &std::path::Path) {
    let c = std::ffi::CString::new(path.display().to_string()).unwrap();
    // SAFETY: a valid NUL-terminated path
    assert_eq!(
        unsafe { libc::mkfifo(c.as_ptr(), 0o644) },
        0,
        "mkfifo {}",
        path.display()
    );
}

/// The configuration of every `proptest!` block of the suite: `cases` cases from a FIXED seed, so a run
/// draws the same cases on every machine and every day (proptest's default seed is random: a rare
/// failing case would make the suite flaky instead of failing it every time), and no regression files
/// written into the source tree. A different seed can be tried with `PROPTEST_RNG_SEED=N` (the
/// environment wins over this configuration only when set).
pub fn proptest_config(cases: u32) -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, RngSeed};
    let seed = std::env::var("PROPTEST_RNG_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0x5eed_2026);
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}

/// ∫_a^b f(x) dx by the composite Simpson rule on `n` (even) intervals, a < b. For a smooth integrand the
/// error is O(h⁴), h = (b − a)/n (the tests say why their n suffices).
pub fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    assert!(n.is_multiple_of(2) && b > a);
    let h = (b - a) / n as f64;
    let mut sum = f(a) + f(b);
    for k in 1..n {
        sum += if k % 2 == 1 { 4.0 } else { 2.0 } * f(a + k as f64 * h);
    }
    sum * h / 3.0
}

/// ∫_a^b f(x) dx for 0 < a < b by Simpson's rule in u = ln x on `n` (even) intervals: ∫ f(eᵘ) eᵘ du. For
/// a smooth integrand the error is O(h⁴), h = ln(b/a)/n (the tests say why their n suffices).
pub fn simpson_log(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    assert!(a > 0.0);
    simpson(|u: f64| f(u.exp()) * u.exp(), a.ln(), b.ln(), n)
}

/// Options of a streamed spectral run (route `SpectralStream`) of `realizations` realizations of
/// `duration` s at steps of `dt` s from `seed`.
pub fn streamed(realizations: usize, duration: f64, dt: f64, seed: u64) -> stochvib::simulate::RunOptions {
    let mut o = stochvib::simulate::RunOptions {
        realizations,
        duration_s: duration,
        dt_s: dt,
        seed,
        ..stochvib::simulate::RunOptions::default()
    };
    o.route = stochvib::simulate::Route::SpectralStream;
    o
}

/// The bits of every statistic of the run summary `s` and of every Welch density of its run file `out`.
pub fn run_bits(s: &stochvib::simulate::RunSummary, out: &std::path::Path) -> Vec<u64> {
    let mut v = statistic_bits(s);
    v.extend(psd_bits(out));
    v
}

/// The passenger car of `data/full-vehicle-two-tracks.toml` written as a machine: suspended wheels, no tyre
/// damping, no cab; a body point at the full vehicle's seat (0.3 m ahead, 0.35 m left).
pub const CAR_AS_MACHINE: &str = r#"title = "car as machine"
[model]
kind = "machine"
body = { mass = "1400 kg", pitch_inertia = "2100 kg*m^2", roll_inertia = "500 kg*m^2", height = "0.5 m" }
[[model.axle]]
name = "front"
position = "1.2 m"
track_width = "1.5 m"
tyre_stiffness = "200 kN/m"
suspension = { stiffness = "25 kN/m", damping = "2000 N*s/m", unsprung_mass = "40 kg" }
[[model.axle]]
name = "rear"
position = "-1.5 m"
track_width = "1.5 m"
tyre_stiffness = "200 kN/m"
suspension = { stiffness = "22 kN/m", damping = "1800 N*s/m", unsprung_mass = "35 kg" }
[[model.output]]
name = "seat_acc"
part = "body"
point = ["0.3 m", "0.35 m", "0.9 m"]
direction = "z"
[analysis]
outputs = ["bounce", "pitch", "roll", "seat_acc", "travel_front_left", "tyre_force_rear_right"]
"#;

/// The speed profile of the accelerating-car tests: from 5 to 15 m/s at 1 m/s², starting at t = 0 (so at
/// 15 m/s from t = 10 s on).
pub fn accelerating_5_to_15() -> stochvib::transient::SpeedProfile {
    stochvib::transient::ConstantAcceleration {
        from_m_s: 5.0,
        to_m_s: 15.0,
        acceleration_m_s2: 1.0,
        start_s: 0.0,
    }
    .build()
    .unwrap()
}

/// The passenger-car corner of `data/quarter-car.toml` (300 kg, 40 kg, 20 kN/m, 1.5 kN s/m, tyre 200 kN/m, no
/// tyre damping), the model the transient tests drive.
pub fn passenger_quarter_car() -> stochvib::models::quarter_car::QuarterCar {
    stochvib::models::quarter_car::QuarterCar {
        sprung_mass: 300.0,
        unsprung_mass: 40.0,
        suspension_stiffness: 20e3,
        suspension_damping: 1.5e3,
        tyre_stiffness: 200e3,
        tyre_damping: 0.0,
    }
    .build()
    .unwrap()
}

/// The half car of Sukharev (2012) Example 7.1 (M = 1.49 kN s²/m, ρ = 1.23 m, a = 1.42 m, b = 1.28 m,
/// c₁ = 32 kN/m, c₂ = 43 kN/m) with the dampers the delay and axle-coordinate tests assume (2.2 and 2.6 kN s/m;
/// the book prints none).
pub fn damped_book_half_car() -> stochvib::models::half_car::HalfCar {
    stochvib::models::half_car::HalfCar {
        mass: 1490.0,
        radius_of_gyration: 1.23,
        front_distance: 1.42,
        rear_distance: 1.28,
        front_stiffness: 3.2e4,
        rear_stiffness: 4.3e4,
        front_damping: 2.2e3,
        rear_damping: 2.6e3,
    }
    .build()
    .unwrap()
}
