//! Route 2 (nonlinear Monte Carlo) on the inputs of the spectral route — wheelbase delays, two coherent
//! tracks, a non-Gaussian (Laplace) road — with zero nonlinearity against the linear analytic answer; resume
//! of an interrupted nonlinear run; `inspect` and `plot` of a nonlinear run file.
//!
//! Zero nonlinearity: a two-sided stop with a clearance of 10 m on a suspension whose travel has σ of a few
//! centimetres (a 100σ event: never reached), so the equations of motion are the linear part's and route 2
//! must reproduce the linear part's σ, which the analytic machinery (Lyapunov, quadrature) gives
//! independently of any time stepping. Every such assertion is a Student-t interval across realizations at
//! confidence 1 − MC_FALSE_FAILURE (false failure ≤ 2·10⁻⁷ each, at most three per test: ≤ 10⁻⁶ per test).
//! The per-realization variances are time averages over hundreds of correlation times (close to normal), and
//! a synthesised record's variance is the sum of its spectral lines, which differs from the continuous
//! integral by far less than the interval's half-width at these record lengths. Seeded: a given build gives
//! the same numbers every time.

use crate::common;
use common::tolerance::{CRAWL_QUASI_STATIC, LOCKED_MODE, MC_FALSE_FAILURE};
use std::path::Path;
use stochvib::nonlinear::monte_carlo::{NonlinearRunOptions, NonlinearRunSummary};
use stochvib::scenario::{parse_scenario, Scenario};
use stochvib::simulate::RunOptions;
use stochvib::store::{OutputStatistics, RunFile};
use stochvib::study::NonlinearAnswers;

/// A stop too far away to be reached, `across` the named element (soft, so that it does not shorten the
/// step route 2 takes for its contact frequency).
fn far_stop(across: &str) -> String {
    format!(
        "\n[[model.nonlinear]]\nkind = \"bump-stop\"\nname = \"far_stop\"\nacross = \"{across}\"\n\
         upper_clearance = \"10 m\"\nlower_clearance = \"10 m\"\nstiffness = \"1 kN/m\"\n"
    )
}

/// The catalogue scenario `file` with `extra` inserted before its `[input]` (or `[[input]]`) table and
/// `replace` applied.
fn variant(file: &str, extra: &str, replace: Option<(&str, &str)>) -> Scenario {
    let path = common::root().join("data").join(file);
    let mut text = std::fs::read_to_string(&path).unwrap();
    if let Some((from, to)) = replace {
        assert!(text.contains(from), "{file} has no `{from}`");
        text = text.replace(from, to);
    }
    let at = text.find("\n[[input]]").or_else(|| text.find("\n[input]")).unwrap();
    let text = format!("{}{extra}{}", &text[..at], &text[at..]);
    parse_scenario(&text, &path, &common::root().join("spectra")).unwrap()
}

fn options(r: usize, t: f64, dt: f64, seed: u64) -> NonlinearRunOptions {
    NonlinearRunOptions {
        run: RunOptions {
            confidence: 1.0 - MC_FALSE_FAILURE,
            overwrite: true,
            realizations: r,
            duration_s: t,
            dt_s: dt,
            seed,
            ..RunOptions::default()
        },
        burn_in_s: None,
        halving_checks: None,
    }
}

/// Route 2 of `sc` at its suggested step into `dir/run.h5`.
fn run(sc: &Scenario, dir: &Path, r: usize, t: f64, seed: u64) -> NonlinearRunSummary {
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let dt = sc.suggest_nonlinear_step(&answers).unwrap().dt_s;
    let _serial = common::hdf5_serial();
    sc.simulate_nonlinear(&answers, &options(r, t, dt, seed), &dir.join("run.h5"), &|_, _| {})
        .unwrap()
}

fn stat<'a>(o: &'a OutputStatistics, name: &str) -> &'a stochvib::store::Statistic {
    o.get(name)
        .unwrap_or_else(|| panic!("no statistic `{name}` for {}", o.output))
}

/// The quarter car with bump stops on its ISO road (route 2's spectral route) and on the exponential road
/// `book-8-45` (its exact route), each with its route name, route 1's answers and the suggested step.
fn quarter_cars_on_both_routes() -> Vec<(&'static str, Scenario, NonlinearAnswers, f64)> {
    [(None, "spectral"), (Some(("\"iso8608-d\"", "\"book-8-45\"")), "exact")]
        .into_iter()
        .map(|(road, route)| {
            let sc = variant("quarter-car-bump-stops.toml", "", road);
            let answers = sc.nonlinear_answers().unwrap().unwrap();
            let dt = sc.suggest_nonlinear_step(&answers).unwrap().dt_s;
            (route, sc, answers, dt)
        })
        .collect()
}

/// The linear part's analytic σ of every output named, inside route 2's interval of σ.
fn assert_linear_sigma(sc: &Scenario, s: &NonlinearRunSummary, names: &[&str]) {
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let linear = answers.linear_statistics.unwrap();
    for name in names {
        let exact = linear.iter().find(|l| l.name == *name).unwrap().sigma.unwrap();
        let o = s.run.outputs.iter().find(|o| o.output == *name).unwrap();
        let iv = &stat(o, "sigma_response").interval;
        assert!(
            iv.lower <= exact && exact <= iv.upper,
            "{name}: the linear σ {exact} outside route 2's [{}, {}]",
            iv.lower,
            iv.upper
        );
    }
}

/// The half car of `data/half-car.toml` (ISO 8608 class C at 10 m/s, the rear wheel 0.27 s behind the front
/// one) with a far stop on the front suspension: route 2 (spectral route, the delay a circular shift of the
/// synthesised road) covers the linear σ of the pitch, which the delay decides (in phase the two wheels
/// excite bounce only), and of the rear travel. 20 realizations × 150 s.
#[test]
fn route2_zero_nonlinearity_with_wheelbase_delay_gives_the_linear_sigma() {
    let dir = common::scratch_dir("nl-runs", "delay");
    let sc = variant("half-car.toml", &far_stop("front"), None);
    let s = run(&sc, &dir, 20, 150.0, 11);
    assert!(s.run.notes.iter().any(|n| n.contains("delay")), "{:?}", s.run.notes);
    assert_linear_sigma(&sc, &s, &["pitch", "rear_travel"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The full vehicle of `data/full-vehicle-two-tracks.toml` (two coherent tracks of an ISO 8608 class C road,
/// Dodds–Robson coherence, rear wheels 0.135 s behind) with a far stop on the front-left suspension: route 2
/// covers the linear σ of the roll (decided by the coherence of the two tracks) and of the rear-right travel.
/// 20 realizations × 100 s.
#[test]
fn route2_zero_nonlinearity_on_two_coherent_tracks_gives_the_linear_sigma() {
    let dir = common::scratch_dir("nl-runs", "tracks");
    let sc = variant("full-vehicle-two-tracks.toml", &far_stop("suspension_fl"), None);
    let s = run(&sc, &dir, 20, 100.0, 12);
    assert!(
        s.run.notes.iter().any(|n| n.contains("two coherent tracks")),
        "{:?}",
        s.run.notes
    );
    assert_linear_sigma(&sc, &s, &["roll", "travel_rr"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The quarter car of `data/quarter-car-model.toml` on a Laplace road of kurtosis 6 (the same spectrum,
/// heavier tails) with a far stop on the suspension: the σ of a linear response depends on the spectrum
/// only, so route 2 covers the linear σ of the travel and of the body acceleration, while the travel's
/// kurtosis interval lies above the Gaussian 3 (a filtered Laplace moving average keeps excess kurtosis;
/// the direction is the prediction, its size is checked for linear runs in `laplace_road.rs`).
/// 30 realizations × 100 s.
#[test]
fn route2_zero_nonlinearity_on_a_laplace_road_gives_the_linear_sigma() {
    let dir = common::scratch_dir("nl-runs", "laplace");
    let sc = variant(
        "quarter-car-model.toml",
        &far_stop("suspension"),
        Some(("speed = \"20 m/s\"", "speed = \"20 m/s\"\nkurtosis = 6")),
    );
    let s = run(&sc, &dir, 30, 100.0, 13);
    assert!(s.run.generator.contains("Laplace"), "{}", s.run.generator);
    assert_linear_sigma(&sc, &s, &["travel", "body_acc"]);
    let travel = s.run.outputs.iter().find(|o| o.output == "travel").unwrap();
    let k = &stat(travel, "kurtosis").interval;
    assert!(k.lower > 3.0, "travel kurtosis [{}, {}] not above 3", k.lower, k.upper);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A force on the body beside the road: `data/quarter-car-road-and-load.toml` at a constant 15 m/s, its
/// load a band-limited white force (no shaping filter, so route 2 takes the spectral route), with a far
/// stop. The body acceleration's output row holds the force input itself (D ≠ 0 for a force on the body),
/// which route 2's spectral path must read beside the road's rate; route 2 covers the linear σ of body_acc
/// and travel. 20 realizations × 100 s; each interval at confidence 1 − `MC_FALSE_FAILURE`, two of them:
/// false-failure probability ≤ 4·10⁻⁷.
#[test]
fn route2_zero_nonlinearity_with_a_force_input_on_the_spectral_route_gives_the_linear_sigma() {
    let dir = common::scratch_dir("nl-runs", "force");
    let path = common::root().join("data/quarter-car-road-and-load.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut text = text[..text.find("[transient]").unwrap()].to_string();
    for (from, to) in [
        (
            r#"speed_profile = { from = "5 m/s", to = "15 m/s", acceleration = "1 m/s^2", start = "1 s" }"#,
            r#"speed = "15 m/s""#,
        ),
        (
            r#"spectrum = { kind = "exponential", unit = "N", variance = "1e4 N^2", alpha = "3 1/s" }"#,
            r#"spectrum = { kind = "band-white", domain = "temporal", unit = "N", convention = "one-sided-cyclic", level = 100.0, band = ["0.5 Hz", "20 Hz"] }"#,
        ),
    ] {
        assert!(text.contains(from), "the scenario has no `{from}`");
        text = text.replace(from, to);
    }
    let at = text.find("\n[[input]]").unwrap();
    let text = format!("{}{}{}", &text[..at], far_stop("suspension"), &text[at..]);
    let sc = parse_scenario(&text, &path, &common::root().join("spectra")).unwrap();
    let s = run(&sc, &dir, 20, 100.0, 14);
    assert!(
        s.run.notes.iter().any(|n| n.contains("spectral route")),
        "{:?}",
        s.run.notes
    );
    assert_linear_sigma(&sc, &s, &["body_acc", "travel"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A nonlinear run interrupted after two of its four shards (the progress callback panics; the dropped
/// writer leaves `run.h5.tmp`) resumes them and ends with every statistic, the Welch densities and the
/// response histograms bit-identical to an uninterrupted run.
#[test]
fn interrupted_nonlinear_run_resumes_bit_identically() {
    let dir = common::scratch_dir("nl-runs", "resume");
    let sc = variant("quarter-car-bump-stops.toml", "", None);
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let dt = sc.suggest_nonlinear_step(&answers).unwrap().dt_s;
    let opts = |overwrite| NonlinearRunOptions {
        run: RunOptions {
            shard_size: 2,
            overwrite,
            realizations: 8,
            duration_s: 5.0,
            dt_s: dt,
            seed: 21,
            ..RunOptions::default()
        },
        burn_in_s: None,
        halving_checks: None,
    };
    let _serial = common::hdf5_serial();
    let (cut, whole) = (dir.join("cut.h5"), dir.join("whole.h5"));
    let interrupted = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        sc.simulate_nonlinear(&answers, &opts(false), &cut, &|done, _| {
            assert!(done < 2, "interrupted after two shards");
        })
    }));
    assert!(interrupted.is_err());
    assert!(!cut.exists() && stochvib::store::tmp_path(&cut).exists());
    let resumed = sc.simulate_nonlinear(&answers, &opts(false), &cut, &|_, _| {}).unwrap();
    assert_eq!((resumed.run.resumed_shards, resumed.run.n_shards), (2, 4));
    let full = sc
        .simulate_nonlinear(&answers, &opts(true), &whole, &|_, _| {})
        .unwrap();
    assert_eq!(
        common::stored_statistic_bits(&resumed.run.outputs),
        common::stored_statistic_bits(&full.run.outputs)
    );
    assert_eq!(common::psd_bits(&cut), common::psd_bits(&whole));
    let hist = |p: &Path| RunFile::open(p).unwrap().response_histograms().unwrap();
    assert_eq!(hist(&cut), hist(&whole));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Route 2 steps its realizations eight at a time in lockstep and the rest of a shard in groups of 4, 2 and
/// 1, each lane doing the arithmetic of a lone realization: a run whose one shard holds 15 realizations
/// (groups of 8, 4, 2 and 1) and the same run in shards of 1 (every realization alone) give the same
/// statistics, Welch densities and histograms bit for bit, the Δt-halving checks of realizations 0..4
/// included — on the spectral route (the ISO road, synthesised inputs) and on
/// the exact route (the same quarter car on the exponential road `book-8-45`, whose shaping filter gives
/// each lane its own normals from its own stream, nz a step, as a lone realization draws them).
#[test]
fn lockstep_realizations_give_the_bits_of_lone_ones() {
    for (route, sc, answers, dt) in quarter_cars_on_both_routes() {
        let dir = common::scratch_dir("nl-runs", &format!("lockstep-{route}"));
        let opts = |shard_size| {
            let mut o = options(15, 5.0, dt, 33);
            o.run.shard_size = shard_size;
            o
        };
        let _serial = common::hdf5_serial();
        let (lanes, alone) = (dir.join("lanes.h5"), dir.join("alone.h5"));
        let a = sc.simulate_nonlinear(&answers, &opts(15), &lanes, &|_, _| {}).unwrap();
        let b = sc.simulate_nonlinear(&answers, &opts(1), &alone, &|_, _| {}).unwrap();
        assert_eq!(
            (a.run.n_shards, b.run.n_shards, a.halving_checks),
            (1, 15, 4),
            "{route}"
        );
        assert_eq!(format!("{:?}", a.run.route).to_lowercase(), route);
        assert_eq!(
            common::stored_statistic_bits(&a.run.outputs),
            common::stored_statistic_bits(&b.run.outputs),
            "{route}"
        );
        assert_eq!(common::psd_bits(&lanes), common::psd_bits(&alone), "{route}");
        let hist = |p: &Path| RunFile::open(p).unwrap().response_histograms().unwrap();
        assert_eq!(hist(&lanes), hist(&alone), "{route}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// Route 2's threads take the lockstep groups of every pending shard in order, up to two shards ahead of the
/// next one to write, and the calling thread writes each shard when its groups are done
/// (`simulate::shard_pipeline`): a run of 21 realizations in shards of 4 (five of 4 and one of 1) on two
/// threads gives the statistics, Welch densities, histograms and every shard's stored checksums of the same
/// run on one thread, bit for bit, on the spectral and on the exact route, with one progress report per
/// shard, in order.
#[test]
fn shards_written_as_the_threads_finish_them_give_the_bits_of_one_thread() {
    for (route, sc, answers, dt) in quarter_cars_on_both_routes() {
        let dir = common::scratch_dir("nl-runs", &format!("pipeline-{route}"));
        let mut opts = options(21, 3.0, dt, 35);
        opts.run.shard_size = 4;
        opts.halving_checks = Some(2);
        let _serial = common::hdf5_serial();
        let (two, one) = (dir.join("two.h5"), dir.join("one.h5"));
        let pool = |n| rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
        let reports = std::sync::Mutex::new(Vec::new());
        let a = pool(2)
            .install(|| {
                sc.simulate_nonlinear(&answers, &opts, &two, &|done, total| {
                    reports.lock().unwrap().push((done, total))
                })
            })
            .unwrap();
        let b = pool(1)
            .install(|| sc.simulate_nonlinear(&answers, &opts, &one, &|_, _| {}))
            .unwrap();
        assert_eq!(
            *reports.lock().unwrap(),
            (0..=6).map(|d| (d, 6)).collect::<Vec<_>>(),
            "{route}"
        );
        assert_eq!((a.run.n_shards, b.run.n_shards), (6, 6), "{route}");
        assert_eq!(
            common::stored_statistic_bits(&a.run.outputs),
            common::stored_statistic_bits(&b.run.outputs),
            "{route}"
        );
        assert_eq!(common::psd_bits(&two), common::psd_bits(&one), "{route}");
        let file = |p: &Path| RunFile::open(p).unwrap();
        assert_eq!(
            file(&two).response_histograms().unwrap(),
            file(&one).response_histograms().unwrap(),
            "{route}"
        );
        for shard in 0..6 {
            let sums = |p: &Path| file(p).shard_checksums(shard).unwrap();
            assert!(!sums(&one).is_empty(), "{route} shard {shard} has stored checksums");
            assert_eq!(sums(&two), sums(&one), "{route} shard {shard}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// `stochvib simulate` of the Duffing catalogue scenario writes a nonlinear run; `inspect` lists its
/// nonlinear statistics (text and JSON) and `plot` draws every output's response histogram against route 1's
/// Gaussian, and the displacement's also against route 3's exact density, on a linear and a logarithmic
/// axis (Δt = 0.01 s: h·ω_c = 0.43 at the stiffest point route 1 predicts).
#[test]
fn inspect_and_plot_of_a_nonlinear_run() {
    let dir = common::scratch_dir("nl-runs", "cli");
    let scenario = common::root().join("data/duffing-white-noise.toml");
    let limit = std::time::Duration::from_secs(600);
    let ok = |args: &[&str]| {
        let o = common::cli_within(args, &dir, limit);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "`stochvib {}`: {err}", args.join(" "));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let sc = scenario.to_str().unwrap();
    ok(&[
        "simulate",
        sc,
        "--realizations",
        "4",
        "--duration",
        "100",
        "--dt",
        "0.01",
        "-o",
        "run.h5",
    ]);
    let text = ok(&["inspect", "run.h5"]);
    for word in ["sigma_response", "kurtosis", "max_abs"] {
        assert!(text.contains(word), "inspect lacks `{word}`:\n{text}");
    }
    let json: serde_json::Value = serde_json::from_str(&ok(&["inspect", "run.h5", "--json"])).unwrap();
    assert!(json.to_string().contains("kurtosis"));
    ok(&["plot", "run.h5", "-o", "pictures"]);
    let pictures = dir.join("pictures");
    let svg = |name: &str| std::fs::read_to_string(pictures.join(name)).unwrap();
    // x (displacement) has route 3's exact density; v (velocity) has routes 1 and 2 only
    for (name, exact) in [("x", true), ("v", false)] {
        for file in [format!("{name}-histogram.svg"), format!("{name}-histogram-log.svg")] {
            let s = svg(&file);
            assert!(s.contains("response density"), "{file}");
            assert!(s.contains("route 2: nonlinear Monte Carlo"), "{file}");
            assert!(s.contains("route 1: Gaussian"), "{file}");
            assert_eq!(s.contains("route 3: exact stationary density"), exact, "{file}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The friction seat with F_c = 5 kN on its guide: the spring (6.5 kN/m) and damper never pull that hard
/// on the floor's 2.5 mm, so the seat sticks to the floor all the time and its acceleration is the floor's:
/// for the gauss-cosine floor K(τ) = D e^{−ατ²} cos βτ, Var ü = K⁗(0) = D(β⁴ + 12αβ² + 12α²) (the τ⁴ term of
/// the product of the two series, times 4!), D = 6.25 mm², α = 9 s⁻², β = 2π·3 rad/s: σ = 1.0173 m/s². Route
/// 2's seat acceleration must hold it (Student-t interval at 1 − MC_FALSE_FAILURE; at Δt = 2 ms the step's
/// averaging of the constraint force lowers σ by sinc(βΔt/2), 6·10⁻⁵), and its largest value must be a floor
/// acceleration's, not the F_c/m = 60 m/s² that generator version 2 read while the friction stuck (F_c·sgn v
/// at v = 0 is 0, so the output lost the constraint force: σ = 29.6 m/s²).
#[test]
fn route2_acceleration_of_a_stuck_friction_seat_is_the_floors() {
    let sc = variant(
        "operator-seat-friction.toml",
        "",
        Some(("force = \"15 N\"", "force = \"5000 N\"")),
    );
    let (d, alpha, beta) = (6.25e-6f64, 9.0f64, 2.0 * std::f64::consts::PI * 3.0);
    let exact = (d * (beta.powi(4) + 12.0 * alpha * beta * beta + 12.0 * alpha * alpha)).sqrt();
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let dir = common::scratch_dir("nl-runs", "stuck-seat");
    let s = {
        let _serial = common::hdf5_serial();
        sc.simulate_nonlinear(&answers, &options(8, 60.0, 0.002, 5), &dir.join("run.h5"), &|_, _| {})
            .unwrap()
    };
    let o = s.run.outputs.iter().find(|o| o.output == "seat_acc").unwrap();
    common::assert_inside(&stat(o, "sigma_response").interval, exact, "the floor's acceleration σ");
    let max = stat(o, "max_abs").interval.estimate;
    assert!(max < 8.0 * exact, "max |a| = {max} m/s² (the floor's σ is {exact})");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A bump stop so stiff (10¹⁰ and 10¹² N/m against a 20 kN/m suspension) that route 1's Gaussian
/// equivalent locks the suspension: the car is then one mass m_s + m_u = 340 kg on the undamped tyre
/// (c_t = 0), a mode at √(k_t/(m_s + m_u)) = √(200 000/340) = 24.25 rad/s that nothing damps (the tyre
/// contact's equivalent stiffness, about 1 % of k_t, moves it by under 1 %: LOCKED_MODE). Route 1 must say so — at
/// 10¹⁰ N/m its variance quadrature cannot resolve the peak (the mode almost undamped), at 10¹² N/m the
/// eigenvalues cannot tell its decay from zero — and name that mode, not blame a softening element or a
/// velocity of infinite variance (as it did).
#[test]
fn a_stop_stiff_enough_to_lock_the_suspension_names_the_undamped_mode() {
    let locked = (200_000.0f64 / 340.0).sqrt();
    for (k, says) in [("1e10", "is almost undamped"), ("1e12", "cannot tell from zero")] {
        let sc = variant(
            "quarter-car-bump-stops.toml",
            "",
            Some(("stiffness = \"300 kN/m\"", &format!("stiffness = \"{k} N/m\""))),
        );
        let answers = sc.nonlinear_answers().unwrap().unwrap();
        let stochvib::nonlinear::Route1Outcome::NotConverged { reason, advice, .. } = &answers.route1 else {
            panic!("{k} N/m: route 1 converged")
        };
        let text = format!("{reason}; {advice}");
        assert!(text.contains(says), "{k} N/m: {text}");
        assert!(
            !text.contains("softening element has lost") && !text.contains("finite variance"),
            "{text}"
        );
        let at = text
            .split("mode at ")
            .nth(1)
            .and_then(|t| t.split(" rad/s").next())
            .unwrap();
        let w: f64 = at.parse().unwrap();
        assert!(
            (w / locked - 1.0).abs() < LOCKED_MODE,
            "{k} N/m: mode at {w} rad/s, locked suspension {locked}"
        );
    }
}

/// The quarter car with stops at a crawl (0.01 m/s on the ISO 8608 class D road): the car follows the road,
/// so route 1's body acceleration has the road acceleration's variance, (2π)⁴ G_d(n₀) n₀² v (f₂³ − f₁³)/3 for
/// G_d(n) = G_d(n₀)(n/n₀)⁻² on the band n₁ = 0.011 … n₂ = 2.83 cycles/m (f = v n; G_d(n₀) = 1024·10⁻⁶ m³,
/// n₀ = 0.1 cycles/m), and the tyre force (m_s + m_u)² times it. Route 1 used to give up here: the tyre
/// deflection's variance (∝ ω⁴, 3.5·10⁻¹⁵ m² in all) had a head piece of rounding noise that could not meet
/// its own share of the tolerance, though the whole met it by eleven orders of magnitude.
#[test]
fn route1_at_a_crawl_is_the_quasi_static_answer() {
    let sc = variant(
        "quarter-car-bump-stops.toml",
        "",
        Some(("speed = \"15 m/s\"", "speed = \"0.01 m/s\"")),
    );
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let st = answers
        .route1_statistics
        .as_ref()
        .unwrap_or_else(|| panic!("route 1: {:?}", answers.route1));
    let (v, gd, n0, (n1, n2)) = (0.01f64, 1024e-6, 0.1, (0.011f64, 2.83f64));
    let road_acc =
        (2.0 * std::f64::consts::PI).powi(4) * gd * n0 * n0 * v * ((v * n2).powi(3) - (v * n1).powi(3)) / 3.0;
    let var = |name: &str| st.iter().find(|s| s.name == name).unwrap().values.variance.unwrap();
    assert!(
        common::rel(var("body_acc"), road_acc) < CRAWL_QUASI_STATIC,
        "{} vs {road_acc}",
        var("body_acc")
    );
    let tyre = 340.0f64.powi(2) * road_acc;
    assert!(
        common::rel(var("tyre_force"), tyre) < CRAWL_QUASI_STATIC,
        "{} vs {tyre}",
        var("tyre_force")
    );
}

/// A mistyped duration (10¹² s at the Duffing oscillator's 5.8 ms step: 1.7·10¹⁴ samples, each needing at
/// least one normal draw, at most MAX_DRAWS_PER_S a thread) is refused at once with the lower bound of its
/// time against --max-hours, and no file; on the exact route nothing is allocated per sample, so before the
/// check the run started and would have taken years (and the search for its FFT-friendly length alone ran
/// for hours).
#[test]
fn a_route2_run_beyond_max_hours_is_refused_at_once() {
    let path = common::root().join("data/duffing-white-noise.toml");
    let sc = stochvib::scenario::load_scenario(&path, &common::root().join("spectra")).unwrap();
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let dir = common::scratch_dir("nl-runs", "max-hours");
    let out = dir.join("run.h5");
    let e = {
        let _serial = common::hdf5_serial();
        sc.simulate_nonlinear(&answers, &options(2, 1e12, 0.0058, 1), &out, &|_, _| {})
            .expect_err("years of computing")
            .to_string()
    };
    assert!(e.contains("would take at least") && e.contains("--max-hours 24"), "{e}");
    assert!(!out.exists() && !stochvib::store::tmp_path(&out).exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The Duffing scenario with its cubic term reversed (εσ₀² = −1: a softening spring whose potential has its
/// barrier at x_b = 1/√|ε| = σ₀ = 1 cm, height βV_b = 1/(4|ε|σ₀²) = 0.25): route 1 finds no Gaussian
/// equivalent, and route 2's realizations cross the barrier within a few periods (Kramers' rate at βV_b =
/// 0.25 is of the order of the natural frequency, 1 Hz: a realization that stays in the well for the 100 s
/// of the library run has a probability below e⁻⁵⁰; the run is seeded). The escape is route 2's outcome, not
/// a number: the library names it (realization, output, the softening element) and writes no run file; the
/// report and `analyze --monte-carlo` print routes 1 and 3 with route 2's "no stationary response" and a
/// verdict, exit 0.
#[test]
fn an_escaping_response_is_route_2s_outcome_not_a_number() {
    let reversed = (
        "cubic_stiffness = \"394784.1760435743 N/m^3\"",
        "cubic_stiffness = \"-394784.1760435743 N/m^3\"",
    );
    let sc = variant("duffing-white-noise.toml", "", Some(reversed));
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    assert!(answers.route1.converged().is_none());
    let dir = common::scratch_dir("nl-runs", "escape");
    let out = dir.join("run.h5");
    let e = {
        let _serial = common::hdf5_serial();
        sc.simulate_nonlinear(&answers, &options(4, 100.0, 0.01, 1), &out, &|_, _| {})
            .expect_err("a softening spring past its barrier escapes")
    };
    let reason = stochvib::study::escaped(&e).unwrap_or_else(|| panic!("not an escape: {e}"));
    for needle in ["realization ", "output `x`", "`hardening`", "no stationary response"] {
        assert!(reason.contains(needle), "`{needle}` not in: {reason}");
    }
    assert!(!out.exists(), "a run file was written");
    let report = stochvib::study::nonlinear_report_escaped(&sc, &answers, &reason)
        .unwrap()
        .to_string();
    for needle in [
        "route 2   nonlinear Monte Carlo: NO STATIONARY RESPONSE",
        "verdict   route 2's response escaped",
    ] {
        assert!(report.contains(needle), "`{needle}` not in the report:\n{report}");
    }
    // the command line: the same report, exit 0
    let file = dir.join("softening.toml");
    let text = std::fs::read_to_string(common::root().join("data/duffing-white-noise.toml")).unwrap();
    std::fs::write(&file, text.replace(reversed.0, reversed.1)).unwrap();
    let o = common::cli_within(
        &["analyze", file.to_str().unwrap(), "--monte-carlo", "2"],
        &dir,
        std::time::Duration::from_secs(600),
    );
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("NO STATIONARY RESPONSE"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Φ(x) by the complementary error function of statrs (an independent implementation).
fn normal_cdf(x: f64) -> f64 {
    0.5 * statrs::function::erf::erfc(-x / std::f64::consts::SQRT_2)
}

/// The quarter car of `data/quarter-car-model.toml` (ISO 8608 class C at 20 m/s) whose tyre may lift off
/// (`tyre-contact`), with the static load set to u = 3 times the linear σ_F of the dynamic tyre force:
/// lift-off is rare and the unilateral tyre acts only during it, so route 2's fraction of time lifted and
/// its rate of lift-offs are the Gaussian closed forms of the linear quarter car, P = Φ(−u) = 1.35·10⁻³
/// and Rice's ν = σ_Ḟ/(2πσ_F)·e^{−u²/2}, within RARE_LIFT_OFF (the effect of the unilateral contact, see
/// its derivation) plus the Monte Carlo interval (two intervals at 1 − MC_FALSE_FAILURE). σ_F and σ_Ḟ are
/// the linear analytic answers (Lyapunov/quadrature of the linear part, not route 2).
/// 40 realizations × 600 s.
#[test]
fn route2_rare_tyre_lift_off_matches_the_gaussian_closed_form() {
    use common::tolerance::RARE_LIFT_OFF;
    let dir = common::scratch_dir("nl-runs", "lift-off");
    let contact = |load: f64| {
        format!(
            "\n[[model.nonlinear]]\nkind = \"tyre-contact\"\nname = \"tyre_contact\"\nacross = \"tyre\"\n\
             static_load = \"{load} N\"\n"
        )
    };
    let probe = variant("quarter-car-model.toml", &contact(1e6), None);
    let linear = probe.nonlinear_answers().unwrap().unwrap().linear_statistics.unwrap();
    let f = linear.iter().find(|l| l.name == "tyre_force").unwrap();
    let (sigma_f, sigma_fdot) = (f.sigma.unwrap(), f.lambda2.unwrap().sqrt());
    let u = 3.0;
    let sc = variant("quarter-car-model.toml", &contact(u * sigma_f), None);
    let s = run(&sc, &dir, 40, 600.0, 31);
    let find = |prefix: &str| {
        s.run
            .outputs
            .iter()
            .flat_map(|o| o.statistics.iter())
            .find(|st| st.name.starts_with(prefix))
            .unwrap_or_else(|| panic!("no `{prefix}`"))
            .interval
    };
    let p = normal_cdf(-u);
    let rate = sigma_fdot / (2.0 * std::f64::consts::PI * sigma_f) * (-0.5 * u * u).exp();
    for (name, exact, iv) in [
        ("fraction", p, find("lift_off_fraction")),
        ("rate", rate, find("lift_off_rate")),
    ] {
        let (lo, hi) = (exact * (1.0 - RARE_LIFT_OFF), exact * (1.0 + RARE_LIFT_OFF));
        assert!(
            iv.lower <= hi && iv.upper >= lo,
            "lift-off {name}: route 2 [{}, {}] apart from the Gaussian {exact} ± {RARE_LIFT_OFF} relative",
            iv.lower,
            iv.upper
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The friction seat of the catalogue (`data/operator-seat-friction.toml`): its default step is derived from
/// the system — at most the linear part's π/(8ω_max) (ω_max = √(k/m) for this underdamped oscillator
/// of reduced mass m = 1/κ, stiffness k = 6500 N/m) and at most 0.05·σ_v/(κF_c) (F_c = 15 N, σ_v route 1's
/// σ of the sliding velocity), the duration at least 20/σ_min of the linear part (σ_min = b/(2m), the decay
/// rate of the frictionless seat, b = 2·4.22 1/s·m) and at least ten burn-ins (BURN_IN_DECAY/σ_min of the
/// Gaussian equivalent) — and `analyze --monte-carlo` runs on it without --dt/--duration.
#[test]
fn friction_seat_default_step_is_derived_from_the_system() {
    use stochvib::nonlinear::monte_carlo::{BURN_IN_DECAY, RECORD_BURN_INS};
    use stochvib::system::FrequencyResponse;
    let path = common::root().join("data/operator-seat-friction.toml");
    let sc = stochvib::scenario::load_scenario(&path, &common::root().join("spectra")).unwrap();
    let answers = sc.nonlinear_answers().unwrap().unwrap();
    let s = sc.suggest_nonlinear_step(&answers).unwrap();
    let model = sc.nonlinear_model().unwrap();
    let m = 1.0 / model.kappa(0);
    let omega_max = (6500.0 / m).sqrt();
    let sigma_v = answers.route1.converged().unwrap().moments[0].sigma_v;
    let decay = 4.22;
    assert!(s.dt_s <= std::f64::consts::PI / (8.0 * omega_max), "{s:?}");
    assert!(s.dt_s * 15.0 / m <= 0.05 * sigma_v * (1.0 + 1e-12), "{s:?}");
    assert!(s.duration_s >= 20.0 / decay, "{s:?}");
    // at least RECORD_BURN_INS burn-ins of BURN_IN_DECAY/σ_min, σ_min the Gaussian equivalent's slowest decay
    let eq = &answers.route1.converged().unwrap().equivalent;
    let ev = eq.state_space().unwrap().a.complex_eigenvalues();
    let smin = ev.iter().map(|l| -l.re).fold(f64::INFINITY, f64::min);
    assert!(s.duration_s >= RECORD_BURN_INS * BURN_IN_DECAY / smin, "{s:?}");
    assert!(s.reason.contains("dry friction"), "{}", s.reason);
    let dir = common::scratch_dir("nl-runs", "seat");
    let o = common::cli_within(
        &["analyze", path.to_str().unwrap(), "--monte-carlo", "4"],
        &dir,
        std::time::Duration::from_secs(600),
    );
    let (out, err) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success(), "{err}");
    assert!(err.contains("suggested for route 2"), "{err}");
    assert!(out.contains("sigma_response"), "{out}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Route 2's Welch segment (version 2 of its generator: the largest even 2^a·3^b·5^c ≤ n/8, 900 = 2²3²5² for
/// a record of 7380 samples, where version 1 took 922 = 2·461) estimates a known density with the exact
/// normalisation: 256 records of a stationary AR(1) process x_k = ½x_{k−1} + e_k (e_k standard normal, x_0
/// drawn from the stationary law N(0, 4/3)), whose autocovariance is (4/3)·2^{−|τ|}, give Welch estimates
/// whose sum over the interior bins equals that of the exact mean of the estimate (`Welch::expected_all`)
/// within WELCH_SEGMENT_NORMALISATION (7 standard deviations: false failure < 10⁻¹¹), and the frequency grid
/// is ω_j = 2πj/(MΔt) with M = 900.
#[test]
fn route2_welch_segment_estimates_a_known_density_exactly_normalised() {
    use common::tolerance::WELCH_SEGMENT_NORMALISATION;
    use rand::{RngExt, SeedableRng};
    let (n, dt, a): (usize, f64, f64) = (7380, 0.004, 0.5);
    let m = stochvib::nonlinear::monte_carlo::welch_segment(n);
    assert_eq!(m, 900);
    let welch = stochvib::estimate::Welch::new(m, dt).unwrap();
    let mut rng = rand::rngs::Xoshiro256PlusPlus::seed_from_u64(90);
    let mut sums = welch.sums();
    let mut scratch = welch.scratch();
    let var = 1.0 / (1.0 - a * a);
    for _ in 0..256 {
        let mut x = Vec::with_capacity(n);
        let mut prev = var.sqrt() * rng.sample::<f64, _>(rand_distr::StandardNormal);
        for _ in 0..n {
            x.push(prev);
            prev = a * prev + rng.sample::<f64, _>(rand_distr::StandardNormal);
        }
        welch.accumulate(&x, &mut sums, &mut scratch).unwrap();
    }
    let est = welch.finish(&sums).unwrap();
    let autocov: Vec<f64> = (0..m).map(|lag| var * a.powi(lag as i32)).collect();
    let expected = welch.expected_all(&autocov);
    let interior = 1..m / 2;
    let (got, want): (f64, f64) = (
        est.density[interior.clone()].iter().sum(),
        expected[interior].iter().sum(),
    );
    assert!(
        ((got - want) / want).abs() < WELCH_SEGMENT_NORMALISATION,
        "Σ Ŝ = {got}, exact mean {want}"
    );
    let step = 2.0 * std::f64::consts::PI / (m as f64 * dt);
    assert!(est
        .omega
        .iter()
        .enumerate()
        .all(|(j, w)| (w - j as f64 * step).abs() <= 1e-12 * step * j as f64));
}

/// Shard files of version 1 of route 2's generator (before its 2^a·3^b·5^c lengths), written by the build
/// before the change with `stochvib simulate data/quarter-car-bump-stops.toml --realizations 2 --shard-size 1
/// --duration 0.2 --seed 7 --shard I --of 2 -o DIR/` (I = 0, 1; `tests/data/nonlinear-generator-v1/`), are
/// never mixed with this build's realizations: their merge is refused naming the file and both versions
/// (and leaves no file); the same command now refuses an interrupted version-1 shard under its `.tmp` name,
/// naming the generator version as the difference.
#[test]
fn run_files_of_generator_version_1_are_neither_resumed_nor_merged() {
    use stochvib::study::{merge_runs, MergeOptions};
    let dir = common::scratch_dir("nl-runs", "version-1");
    let fixture = common::root().join("tests/data/nonlinear-generator-v1");
    let (parts, cut) = (dir.join("parts"), dir.join("cut"));
    std::fs::create_dir_all(&parts).unwrap();
    std::fs::create_dir_all(&cut).unwrap();
    let name = |i: usize| format!("shard-{i}-of-2.h5");
    for i in 0..2 {
        std::fs::copy(fixture.join(name(i)), parts.join(name(i))).unwrap();
    }
    let _serial = common::hdf5_serial();
    let files: Vec<_> = (0..2).map(|i| parts.join(name(i))).collect();
    let merged = dir.join("merged.h5");
    let e = merge_runs(&merged, &files, &MergeOptions::default(), &|_, _| {})
        .unwrap_err()
        .to_string();
    for part in [
        "shard-0-of-2.h5",
        "generator version 1 (not recorded)",
        "this build writes version 3",
        "new file",
    ] {
        assert!(e.contains(part), "`{part}` not in: {e}");
    }
    assert!(!merged.exists() && !stochvib::store::tmp_path(&merged).exists());
    let scenario = common::root().join("data/quarter-car-bump-stops.toml");
    let simulate = |out: &Path| {
        let args = [
            "simulate",
            scenario.to_str().unwrap(),
            "--realizations",
            "2",
            "--shard-size",
            "1",
            "--duration",
            "0.2",
            "--seed",
            "7",
            "--shard",
            "0",
            "--of",
            "2",
            "-o",
            out.to_str().unwrap(),
        ]
        .map(String::from);
        common::cli_fails(1, &args.iter().map(String::as_str).collect::<Vec<_>>(), &dir)
    };
    let version = "generator version (1 (not recorded: written before versions were recorded) against 3 (";
    std::fs::copy(fixture.join(name(0)), stochvib::store::tmp_path(&cut.join(name(0)))).unwrap();
    let e = simulate(&cut);
    assert!(
        e.contains("an interrupted run with 1 completed shards") && e.contains(version),
        "{e}"
    );
    assert!(!cut.join(name(0)).exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
