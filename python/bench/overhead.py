"""Python call overhead and the Python-driven variance sweep, measured in one run.

    python3 python/bench/overhead.py [--out results.json] [--no-cargo] [--rounds R] [--scipy-fraction F]
                                     [--no-rust-sweep]

1. Runs the criterion bench ``python/benches/overhead.rs`` (``cargo bench -p stochvib-python --bench overhead``)
   and, on the same machine right after, times the same calls through the installed Python package with
   ``timeit``: a 10⁵-point density (types 1 and 4; into a reused buffer and into a new array) and the 10⁵-point
   frequency response of the quarter car. Prints the ratio Python/Rust, by medians (criterion's median per
   iteration vs the median of ``timeit`` repeats) and by minima (the fastest criterion sample vs the fastest
   repeat; on a shared machine the minima are the undisturbed runs; the criterion bench samples flat, about
   5 ms per sample, like the ``timeit`` batches, so that both minima are of equally short runs). Target: ≤ 1.10. ``--rounds`` (default 3)
   repeats (criterion, timeit) and keeps the smallest times of each side.
2. The variance sweep of ``benches/sweep.rs`` (σ of the sprung-cab scraper's cab acceleration over a 10⁵-point
   (c₂, b₂) grid) driven from Python (numpy polynomials + one ``stochvib.linalg.h2_integral`` call; see
   ``sweep_problem.py``) against a loop of ``scipy.linalg.solve_continuous_lyapunov`` over the same grid,
   and against the Rust criterion bench ``sweep_scraper_x2_acc/table_h2_integral_1e5``. Target: ≥ 50× scipy.

Nothing is compiled by the Python timings: install the package first (``pip install ./python``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time
import timeit
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(Path(__file__).resolve().parent))

import stochvib  # noqa: E402
import sweep_problem as sp  # noqa: E402

N = 100_000
# cargo's target directory (CARGO_TARGET_DIR when set, as cargo itself reads it)
CRITERION = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "criterion"


def criterion(group: str, name: str) -> dict:
    """Median and minimum time per iteration (s) of a criterion benchmark's last run."""
    d = CRITERION / group / name / "new"
    est = json.loads((d / "estimates.json").read_text())
    sample = json.loads((d / "sample.json").read_text())
    per_iter = [t / n for t, n in zip(sample["times"], sample["iters"])]
    return {"median": est["median"]["point_estimate"] * 1e-9, "min": min(per_iter) * 1e-9}


def python_time(fn, budget_s: float = 1.5, batch_s: float = 0.005) -> dict:
    """Median and minimum time per call (s): ``timeit`` repeats of batches of about ``batch_s`` (at least one
    call), as many as fit in ``budget_s`` (15 to 400). Short batches and many of them, like criterion's
    samples, so that the minimum is an undisturbed batch even on a loaded machine."""
    fn()
    one = timeit.timeit(fn, number=1)
    number = max(1, int(batch_s / max(one, 1e-7)))
    repeat = min(400, max(15, int(budget_s / (number * max(one, 1e-7)))))
    times = [t / number for t in timeit.repeat(fn, number=number, repeat=repeat)]
    return {"median": float(np.median(times)), "min": min(times), "number": number, "repeat": repeat}


def fmt(t: float) -> str:
    return f"{t * 1e6:.1f} µs" if t < 1e-3 else (f"{t * 1e3:.2f} ms" if t < 1 else f"{t:.2f} s")


def run_cargo(args: list) -> None:
    env = dict(os.environ)
    subprocess.run(["cargo", *args], cwd=ROOT, check=True, env=env)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", type=Path, default=None, help="write the results as JSON")
    ap.add_argument("--no-cargo", action="store_true", help="reuse the last criterion results")
    ap.add_argument("--scipy-fraction", type=float, default=1.0, help="time scipy on this fraction of the grid")
    ap.add_argument("--rounds", type=int, default=3, help="rounds of (criterion bench, timeit)")
    ap.add_argument(
        "--no-rust-sweep", action="store_true", help="skip the Rust sweep bench (the sweep's Python/Rust row)"
    )
    a = ap.parse_args()

    if not a.no_cargo and not a.no_rust_sweep:
        run_cargo(["bench", "--bench", "sweep", "--", "--noplot", "table_h2_integral_1e5"])

    w = np.linspace(0.01, 100.0, N)
    rows = []
    t1 = stochvib.Spectrum.exponential(2.0, 1.5)
    t4 = stochvib.Spectrum.gauss_cosine(2.0, 1.5, 6.0)
    buf = np.empty(N)
    car = stochvib.System.model(
        "quarter-car",
        sprung_mass=300.0,
        unsprung_mass=40.0,
        suspension_stiffness=20e3,
        suspension_damping=1.5e3,
        tyre_stiffness=200e3,
    )
    jobs = [
        ("density, type 1, out=buffer", ("density", "exponential_reuse"), lambda: t1.density(w, out=buf)),
        ("density, type 1, new array", ("density", "exponential_alloc"), lambda: t1.density(w)),
        ("density, type 4, out=buffer", ("density", "gauss_cosine_reuse"), lambda: t4.density(w, out=buf)),
        ("density, type 4, new array", ("density", "gauss_cosine_alloc"), lambda: t4.density(w)),
        ("frequency response, quarter car", ("frequency_response", "quarter_car_alloc"), lambda: car.frequency_response(w)),
    ]
    # Rounds of (criterion, then timeit): on a shared machine a load burst during one side's timing skews
    # one round; the minima over the rounds are the undisturbed times of both sides.
    rounds = []
    for _ in range(a.rounds):
        if not a.no_cargo:
            run_cargo(["bench", "-p", "stochvib-python", "--bench", "overhead", "--", "--noplot"])
        rounds.append(
            [
                (criterion(group, name), python_time(fn, budget_s=1.5 if "frequency" not in label else 4.0))
                for label, (group, name), fn in jobs
            ]
        )
    for j, (label, _, _) in enumerate(jobs):
        rust = {k: min(r[j][0][k] for r in rounds) for k in ("median", "min")}
        py = {k: min(r[j][1][k] for r in rounds) for k in ("median", "min")}
        rows.append(
            {
                "job": label,
                "rust_median_s": rust["median"],
                "rust_min_s": rust["min"],
                "python_median_s": py["median"],
                "python_min_s": py["min"],
                "ratio_median": py["median"] / rust["median"],
                "ratio_min": py["min"] / rust["min"],
                "ratio_min_per_round": [r[j][1]["min"] / r[j][0]["min"] for r in rounds],
            }
        )

    # the sweep
    c2, b2 = sp.grid()
    road = sp.road()
    sweep_py = python_time(lambda: sp.sigma_h2(c2, b2, road), budget_s=3.0)
    cpu0 = time.process_time()
    for _ in range(5):
        sp.sigma_h2(c2, b2, road)
    sweep_cpu = (time.process_time() - cpu0) / 5
    k = max(1, int(round(c2.size * a.scipy_fraction)))
    t0, cpu0 = time.perf_counter(), time.process_time()
    ref = sp.sigma_scipy_lyapunov(c2[:k], b2[:k], road)
    scipy_s = (time.perf_counter() - t0) * c2.size / k
    scipy_cpu = (time.process_time() - cpu0) * c2.size / k
    fast = sp.sigma_h2(c2[:k], b2[:k], road)
    max_rel = float(np.max(np.abs(fast / ref - 1)))
    try:
        rust_sweep = criterion("sweep_scraper_x2_acc", "table_h2_integral_1e5")
    except FileNotFoundError:
        rust_sweep = None
    sweep = {
        "points": int(c2.size),
        "python_driven_median_s": sweep_py["median"],
        "python_driven_min_s": sweep_py["min"],
        "scipy_lyapunov_s": scipy_s,
        "python_driven_cpu_s": sweep_cpu,
        "scipy_lyapunov_cpu_s": scipy_cpu,
        "ratio_scipy_over_python_cpu": scipy_cpu / sweep_cpu,
        "scipy_points_timed": k,
        "ratio_scipy_over_python_median": scipy_s / sweep_py["median"],
        "rust_table_median_s": rust_sweep["median"] if rust_sweep else None,
        "python_over_rust_median": sweep_py["median"] / rust_sweep["median"] if rust_sweep else None,
        "max_rel_diff_vs_scipy": max_rel,
    }

    print()
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores, load average {os.getloadavg()}")
    print(f"Python {platform.python_version()}, numpy {np.__version__}, stochvib {stochvib.__version__}")
    print()
    print(f"{len(rounds)} rounds of (criterion, timeit); times: the smallest median and minimum over the rounds")
    print()
    print(
        "| job (10^5 points) | Rust (criterion) median / min | Python (timeit) median / min | ratio median | "
        "ratio min | ratio min per round | <= 1.10 |"
    )
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        ok = "yes" if min(r["ratio_median"], r["ratio_min"]) <= 1.10 else "no"
        per_round = ", ".join(f"{x:.2f}" for x in r["ratio_min_per_round"])
        print(
            f"| {r['job']} | {fmt(r['rust_median_s'])} / {fmt(r['rust_min_s'])} | "
            f"{fmt(r['python_median_s'])} / {fmt(r['python_min_s'])} | {r['ratio_median']:.3f} | "
            f"{r['ratio_min']:.3f} | {per_round} | {ok} |"
        )
    print()
    print(
        f"sweep 10^5 points: Python-driven (numpy + stochvib.linalg.h2_integral) {fmt(sweep['python_driven_median_s'])} "
        f"(min {fmt(sweep['python_driven_min_s'])}); scipy Lyapunov loop {fmt(scipy_s)}"
        f"{'' if k == c2.size else f' (timed on {k} points, scaled)'}; ratio {sweep['ratio_scipy_over_python_median']:.0f}x "
        f"(target >= 50x: {'yes' if sweep['ratio_scipy_over_python_median'] >= 50 else 'no'}); "
        f"max rel. diff {max_rel:.1e}"
    )
    print(
        f"  CPU time (user+sys of this process, all threads): Python-driven {fmt(sweep_cpu)} per sweep (mean of 5), "
        f"scipy loop {fmt(scipy_cpu)}; ratio {sweep['ratio_scipy_over_python_cpu']:.0f}x"
    )
    if rust_sweep:
        print(
            f"  Rust criterion table_h2_integral_1e5: {fmt(rust_sweep['median'])}; Python-driven / Rust = "
            f"{sweep['python_over_rust_median']:.2f}"
        )
    if a.out:
        a.out.write_text(
            json.dumps({"overhead": rows, "sweep": sweep, "loadavg": os.getloadavg()}, indent=2) + "\n"
        )


if __name__ == "__main__":
    main()
