#!/usr/bin/env python3
"""The constrained quarter-car optimum, `stochvib optimize` against scipy.optimize over scipy's Lyapunov solver.

Problem (the same on both sides): quarter car m_s = 400 kg, m_u = 40 kg, k_s = 20 kN/m, k_t = 200 kN/m on an ISO
8608 class C road without band limits at 20 m/s (white road velocity, two-sided density S0 = pi n0^2 Gd(n0) v);
minimise sigma(body acceleration) over the suspension damping c in [0.2, 6] kN s/m subject to
3 sigma(travel) <= 40 mm. Closed form: c* = 9 pi S0 (m_s + m_u) / d^2 = 1250.6763 N s/m (the constraint is active).

Ours: the whole `stochvib optimize` process (start-up, scenario reading, 4 COBYLA starts), median of REPS runs;
and, with --bench-binary (the `optimize` bench, benches/optimize.rs), the same work in one process without the
start-up (read the scenario, build the problem, 4 starts), REPS x 20 repetitions, CPU and wall time per
repetition: the like-for-like row against scipy, whose process start-up is not counted either.
Peer: scipy.optimize.minimize(method="SLSQP") from the same 4 starts (the centre of the box and the Halton points
1/4, 3/4, 1/8 of it, as ours), each evaluation of the objective and of the constraint one
scipy.linalg.solve_continuous_lyapunov of the 4-state model (gradients by SLSQP's finite differences), in one
Python process already started (its start-up is not counted); median of REPS runs.

    python3 benches/compare/optimize.py --binary target/release/stochvib [--reps 7] \
        [--bench-binary target/release/deps/optimize-HASH]

Prints one markdown row per side with the machine state (load average, CPU).
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import numpy as np
from scipy.linalg import solve_continuous_lyapunov
from scipy.optimize import minimize

MS, MU, KS, KT = 400.0, 40.0, 20e3, 200e3
S0 = np.pi * 0.1**2 * 256e-6 * 20.0
LOW, HIGH, LIMIT = 200.0, 6000.0, 0.040
SCENARIO = """title = "Quarter car under white road velocity (optimisation benchmark)"
source = "benches/compare/optimize.py"
[model]
kind = "quarter-car"
sprung_mass = "400 kg"
unsprung_mass = "40 kg"
suspension_stiffness = "20 kN/m"
suspension_damping = "1.5 kN*s/m"
tyre_stiffness = "200 kN/m"
[input]
spectrum = { kind = "iso8608", class = "C", bound = "mean", unbounded = true }
speed = "20 m/s"
[analysis]
outputs = ["body_acc", "travel"]
"""


def covariance(c):
    a = np.array([[0, 1, 0, -1], [-KS / MS, -c / MS, 0, c / MS], [0, 0, 0, 1], [KS / MU, c / MU, -KT / MU, -c / MU]])
    b = np.array([[0.0], [0.0], [-1.0], [0.0]])
    return solve_continuous_lyapunov(a, -2 * np.pi * S0 * (b @ b.T))


def sigma_acc(c):
    p = covariance(c)
    row = np.array([-KS / MS, -c / MS, 0, c / MS])
    return np.sqrt(row @ p @ row)


def scipy_optimum():
    best = None
    for u in (0.5, 0.25, 0.75, 0.125):  # the centre, then the Halton points of [0, 1] (base 2), as ours
        x0 = [LOW + u * (HIGH - LOW)]
        r = minimize(lambda x: sigma_acc(x[0]), x0, method="SLSQP", bounds=[(LOW, HIGH)],
                     constraints=[dict(type="ineq", fun=lambda x: LIMIT - 3 * np.sqrt(covariance(x[0])[0, 0]))],
                     options=dict(ftol=1e-12, maxiter=200))
        if r.success and (best is None or r.fun < best.fun):
            best = r
    return best.x[0]


def ours(binary, path):
    args = [binary, "optimize", path, "--param", "model.suspension_damping=0.2:6 kN*s/m",
            "--minimize", "sigma(body_acc)", "--constraint", "3sigma(travel) <= 40 mm", "--json"]
    t = time.perf_counter()
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    dt = time.perf_counter() - t
    import json
    return dt, json.loads(out)["params"][0]["value"]


def in_process(bench, path, reps):
    """The bench binary's CPU and wall time per search (one run of `reps` searches in one process)."""
    import json
    out = subprocess.run([bench, path, str(reps)], check=True, capture_output=True, text=True,
                         cwd=os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))).stdout
    r = json.loads(out)
    return r["cpu_s"], r["wall_s"], r["c"]


def scipy_in_process(reps):
    """scipy's CPU and wall time per search, `reps` searches."""
    c0, w0 = time.process_time(), time.perf_counter()
    for _ in range(reps):
        c = scipy_optimum()
    return (time.process_time() - c0) / reps, (time.perf_counter() - w0) / reps, c


def cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--binary", default="target/release/stochvib")
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--bench-binary", default=None, help="the built `optimize` bench (benches/optimize.rs)")
    ap.add_argument("--rows", default=None, help="also write the row of benches/RESULTS.md's table to this JSON file")
    a = ap.parse_args()
    closed = 9 * np.pi * S0 * (MS + MU) / LIMIT**2
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "quarter-car-white.toml")
        open(path, "w").write(SCENARIO)
        load0 = os.getloadavg()[0]
        rust, py = [], []
        for _ in range(a.reps):  # alternated, so that both sides see the same machine
            dt, c_ours = ours(a.binary, path)
            rust.append(dt)
            t = time.perf_counter()
            c_py = scipy_optimum()
            py.append(time.perf_counter() - t)
        rows = []
        if a.bench_binary:
            for _ in range(a.reps):  # alternated blocks of 20 searches a side
                rows.append((in_process(a.bench_binary, path, 20), scipy_in_process(20)))
        load1 = os.getloadavg()[0]
    r, p = statistics.median(rust), statistics.median(py)
    print(f"closed form c* = {closed:.6f}; ours {c_ours:.6f}; scipy SLSQP {c_py:.6f}")
    print(f"CPU: {cpu_name()}, {os.cpu_count()} cores; load average {load0:.2f} before, {load1:.2f} after")
    print("| job | ours | peer | peer time | ratio peer/ours |")
    print("|---|---|---|---|---|")
    print(f"| quarter car, min sigma_acc s.t. 3 sigma_travel <= 40 mm, 4 starts | {r * 1e3:.2f} ms (whole process) "
          f"| scipy SLSQP + solve_continuous_lyapunov | {p * 1e3:.2f} ms | {p / r:.2f}x |")
    if rows:
        med = lambda k, j: statistics.median(row[k][j] for row in rows)
        ours_cpu, ours_wall, peer_cpu, peer_wall = med(0, 0), med(0, 1), med(1, 0), med(1, 1)
        print(f"in process: ours c* = {rows[-1][0][2]:.6f}, scipy c* = {rows[-1][1][2]:.6f}")
        print(f"| same, in process (no start-up on either side), median of {len(rows)} blocks of 20 "
              f"| {ours_cpu * 1e3:.3f} ms CPU, {ours_wall * 1e3:.3f} ms wall | scipy SLSQP + solve_continuous_lyapunov "
              f"| {peer_cpu * 1e3:.2f} ms CPU, {peer_wall * 1e3:.2f} ms wall "
              f"| {peer_cpu / ours_cpu:.1f}x CPU ({peer_wall / ours_wall:.1f}x wall) |")
    if a.rows:
        import json
        row = dict(job="`stochvib optimize`, quarter car, 1 constraint, 4 starts (whole process)", size="1 parameter",
                   ours_s=r, peer="scipy SLSQP + solve_continuous_lyapunov", peer_s=p, cmd="`optimize.py`")
        with open(a.rows, "w") as f:
            json.dump([row], f, indent=1)


if __name__ == "__main__":
    main()
