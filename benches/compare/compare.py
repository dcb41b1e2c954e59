#!/usr/bin/env python3
"""numpy/scipy side of the stochvib benchmark comparison (see benches/RESULTS.md).

    python3 compare.py run [--reps N] [--smoke] [--only density|h5] > py.json   time the jobs, print JSON
                                                       (--smoke: tiny sizes, once; --only: one group)
    python3 compare.py table rust.json py.json         print the comparison table
    python3 compare.py sweep [--reps N]                only the scipy sweep loops (benches/RESULTS.md)
    python3 compare.py sweep-cli [--reps N]            `stochvib sweep` of 10^6 points beside the scipy loop
                                                       (run from the repository root after cargo build --release)

Same jobs and problem sizes as examples/compare_rust.rs (constants mirror benches/common/mod.rs):
the sprung-cab scraper of data/scraper-sprung-cab.toml (Sukharev 8.7, eq. (8.65)) under the graded dirt
road (8.69) at 10 m/s, and under a type-4 (Gauss-cosine) input. Every job is written the way a competent
numpy/scipy user would: vectorised where numpy can vectorise, one scipy call per point where it cannot.
"""
import argparse
import json
import math
import os
import shutil
import sys
import time

import numpy as np
from scipy.integrate import quad
from scipy.linalg import solve_continuous_lyapunov

# --- the model (benches/common/mod.rs) ---------------------------------------------------------------
M1, OMEGA1, ZETA1 = 3.0e4, 18.5, 0.1
M2, OMEGA2, ZETA2 = 2.0e3, 2 * math.pi * 1.5, 0.3
SPEED = 10.0
C1 = M1 * OMEGA1**2
B1 = 2 * ZETA1 * math.sqrt(C1 * M1)
C2N = M2 * OMEGA2**2
B2N = 2 * ZETA2 * math.sqrt(C2N * M2)
# road (8.69): spatial type 1, D = 32 cm^2, alpha = 0.16 1/m; in time a = alpha v, filter g/(s + a),
# g = sqrt(2 D a) (S(w) = |g/(iw + a)|^2 / (2 pi) = D a / (pi (a^2 + w^2)))
ROAD_D, ROAD_ALPHA = 32e-4, 0.16
ROAD_A = ROAD_ALPHA * SPEED
ROAD_G = math.sqrt(2 * ROAD_D * ROAD_A)
N_C2, N_B2 = 400, 250
T4 = (1.0e-3, 20.0, 15.0)  # type 4: D, alpha (1/s^2), beta (rad/s)
W_HI = T4[2] + 40 * math.sqrt(T4[1])
N_DENSITY = 10_000


def best(reps, fn, inner=1):
    """Smallest wall time over reps runs of fn (per call when inner > 1) and the last result."""
    t_best, out = float("inf"), None
    for _ in range(reps):
        t0 = time.perf_counter()
        for _ in range(inner):
            out = fn()
        t_best = min(t_best, (time.perf_counter() - t0) / inner)
    return t_best, float(out)


# --- 1. densities, vectorised --------------------------------------------------------------------------
def densities():
    tab_x = 10.0 ** (-1 + 3 * np.arange(20) / 19)
    tab_v = 1 / (1 + tab_x**2)
    ltx, ltv = np.log(tab_x), np.log(tab_v)

    def exponential(w, d=1.0, a=2.0):
        return a * d / (math.pi * (a * a + w * w))

    def gaussian(w, d=1.0, a=2.0):
        return d / (2 * math.sqrt(math.pi * a)) * np.exp(-w * w / (4 * a))

    def exp_cosine(w, d=1.0, a=1.0, b=5.0):
        w2 = w * w
        return a * d * (w2 + a * a + b * b) / (math.pi * ((w2 - a * a - b * b) ** 2 + 4 * a * a * w2))

    def gauss_cosine(w, d=1.0, a=2.0, b=5.0):
        k = d / (4 * math.sqrt(math.pi * a))
        return k * (np.exp(-((w - b) ** 2) / (4 * a)) + np.exp(-((w + b) ** 2) / (4 * a)))

    def rational(w):
        x = w * w
        return (1 + 0.5 * x) / (1 + x * (0.3 + 0.02 * x))

    def band_white(w):
        aw = np.abs(w)
        return np.where((aw >= 1.0) & (aw <= 50.0), 0.1, 0.0)

    def tabulated(w):
        aw = np.abs(w)
        inside = (aw >= tab_x[0]) & (aw <= tab_x[-1])
        return np.where(inside, np.exp(np.interp(np.log(aw), ltx, ltv)), 0.0)

    def iso8608_c(w):
        n = np.abs(w) / (2 * math.pi)
        g = 256e-6 * (n / 0.1) ** -2.0
        return np.where((n >= 0.011) & (n <= 2.83), g / (4 * math.pi), 0.0)

    def two_pole_road(w, dq=0.035**2, a=0.3, b=12.0):
        w2 = w * w
        return dq * a * b * (a + b) / (math.pi * (a * a + w2) * (b * b + w2))

    def at_speed(w):
        return exponential(w / SPEED, ROAD_D, ROAD_ALPHA) / SPEED

    return {
        "exponential": exponential,
        "gaussian": gaussian,
        "exp_cosine": exp_cosine,
        "gauss_cosine": gauss_cosine,
        "rational": rational,
        "band_white": band_white,
        "tabulated": tabulated,
        "iso8608_c": iso8608_c,
        "two_pole_road": two_pole_road,
        "at_speed": at_speed,
    }


# --- 2./3. Lyapunov variance of the cab acceleration ----------------------------------------------------
# z = [x_F, x1, x2, v1, v2];  m1 v1' = -(c1+c2)x1 + c2 x2 - (b1+b2)v1 + b2 v2 + c1 q + b1 q',  q = x_F,
# q' = -a x_F + g w;  m2 v2' = c2(x1 - x2) + b2(v1 - v2);  x2'' = h z
G = np.array([ROAD_G, 0.0, 0.0, B1 * ROAD_G / M1, 0.0])
QNEG = -np.outer(G, G)  # scipy solves A X + X A^T = Q


def state_matrices(c2, b2):
    """A (N,5,5) and h (N,5) for arrays c2, b2 (vectorised)."""
    n = c2.size
    a = np.zeros((n, 5, 5))
    a[:, 0, 0] = -ROAD_A
    a[:, 1, 3] = 1.0
    a[:, 2, 4] = 1.0
    a[:, 3, 0] = (C1 - B1 * ROAD_A) / M1
    a[:, 3, 1] = -(C1 + c2) / M1
    a[:, 3, 2] = c2 / M1
    a[:, 3, 3] = -(B1 + b2) / M1
    a[:, 3, 4] = b2 / M1
    a[:, 4, 1] = c2 / M2
    a[:, 4, 2] = -c2 / M2
    a[:, 4, 3] = b2 / M2
    a[:, 4, 4] = -b2 / M2
    h = np.stack([np.zeros(n), c2 / M2, -c2 / M2, b2 / M2, -b2 / M2], axis=1)
    return a, h


SMOKE = False  # tiny sizes (compare.py run --smoke, beside compare_rust --smoke): apply_smoke()


def grid():
    w = lambda f: 2 * math.pi * f  # noqa: E731
    c2s = np.linspace(M2 * w(0.8) ** 2, M2 * w(2.5) ** 2, N_C2)
    b2s = np.linspace(1.0e3, 3.0e4, N_B2)
    if SMOKE:  # every 20th and 25th value, as examples/compare_rust.rs --smoke
        c2s, b2s = c2s[::20], b2s[::25]
    c2, b2 = np.meshgrid(c2s, b2s, indexing="ij")
    return c2.ravel(), b2.ravel()


def variance_single():
    a, h = state_matrices(np.array([C2N]), np.array([B2N]))
    p = solve_continuous_lyapunov(a[0], QNEG)
    return h[0] @ p @ h[0]


def sweep_lyapunov():
    c2, b2 = grid()
    a, h = state_matrices(c2, b2)
    p = np.empty_like(a)
    for i in range(c2.size):
        p[i] = solve_continuous_lyapunov(a[i], QNEG)
    var = np.einsum("ni,nij,nj->n", h, p, h)
    return np.sqrt(var).sum()


def scenario_grid(n_w2=100, n_z2=100):
    """(c2, b2) of the scenario sweep of benches/sweep.rs and `stochvib sweep` on data/scraper-sprung-cab.toml:
    model.omega2 = 1 Hz..2.5 Hz (n_w2 values) x model.zeta2 = 0.1..0.5 (n_z2 values), the first key slowest;
    c2 = m2 w2^2, b2 = 2 zeta2 sqrt(c2 m2) as the model's table reader derives them."""
    f2 = np.linspace(1.0, 2.5, n_w2)
    z2 = np.linspace(0.1, 0.5, n_z2)
    f, z = np.meshgrid(f2, z2, indexing="ij")
    c2 = M2 * (2 * math.pi * f.ravel()) ** 2
    return c2, 2 * z.ravel() * np.sqrt(c2 * M2)


def sweep_lyapunov_4_outputs(n_w2=100, n_z2=100):
    """The job `Sweep::evaluate_range` and `stochvib sweep` do on the scenario's grid, the scipy way: one
    solve_continuous_lyapunov (5 x 5) per point gives the covariance P of z = [x_F, x1, x2, v1, v2], from which
    the 4 outputs of the scenario (x1, x2, x2_acc, cab_travel) follow by cheap einsums: the variance of each,
    and lambda2 = Var(dy/dt) of the displacements (v1, v2, v2 - v1 are states: P[3,3], P[4,4],
    P33 + P44 - 2 P34). x2_acc's lambda2 is infinite under this road (dy/dt has a white-noise part), as the
    Rust side reports. Means are zero (zero-mean road). The numbers are kept in arrays (the Rust side keeps
    a Vec per point). Returns a checksum."""
    c2, b2 = scenario_grid(n_w2, n_z2)
    a, h = state_matrices(c2, b2)
    p = np.empty_like(a)
    for i in range(c2.size):
        p[i] = solve_continuous_lyapunov(a[i], QNEG)
    var = np.stack(
        [
            p[:, 1, 1],
            p[:, 2, 2],
            np.einsum("ni,nij,nj->n", h, p, h),
            p[:, 1, 1] + p[:, 2, 2] - 2 * p[:, 1, 2],
        ],
        axis=1,
    )
    lam2 = np.stack([p[:, 3, 3], p[:, 4, 4], p[:, 3, 3] + p[:, 4, 4] - 2 * p[:, 3, 4]], axis=1)
    return np.sqrt(var).sum() + np.sqrt(lam2).sum()


def sweep_jobs(reps):
    """The sweep rows of benches/RESULTS.md: the 1-output 10^5-point loop (the historical baseline) and the
    4-output loop on the scenario's 10^4-point grid (the same job as the Rust rows)."""
    out = {}
    side = 10 if SMOKE else 100
    for key, n, fn in [
        ("sweep_lyapunov", grid()[0].size, sweep_lyapunov),
        ("sweep_lyapunov_4_outputs", side * side, lambda: sweep_lyapunov_4_outputs(side, side)),
    ]:
        t, check = best(reps, fn)
        out[key] = {"seconds": t, "n": n, "us_per_point": t / n * 1e6, "check": check}
        print(f"{key:28} {n:7d} points  {t / n * 1e6:8.2f} us/point  check {check:.12e}", file=sys.stderr)
    return out


def sweep_cli(reps, binary, out_dir, n_side=1000):
    """`stochvib sweep` of n_side^2 points through the command line, the whole process timed (start, scenario
    read, evaluation on every core, the table written and renamed): the same 4-output job as
    sweep_lyapunov_4_outputs on the same grid family (omega2 1..2.5 Hz x zeta2 0.1..0.5, here n_side x n_side
    values), to an HDF5 table, to a CSV file, as CSV through a pipe to this process (drain), and to HDF5 with
    one thread and the process on one core (h5-1core). Wall time by perf_counter around the child; user and
    system time of the child from wait4, its peak RSS from /usr/bin/time when installed. Best and median of
    `reps` runs each; each table's I/O floor (io_floor, `reps` times); then the scipy loop (best of 2, per
    point, on its 10^4-point grid) in the same minutes and the ratios scipy time of n_side^2 points /
    stochvib wall time."""
    import statistics
    import subprocess

    args = [
        binary,
        "sweep",
        "data/scraper-sprung-cab.toml",
        "--param",
        f"model.omega2=1 Hz..2.5 Hz:{n_side}",
        "--param",
        f"model.zeta2=0.1..0.5:{n_side}",
    ]
    n = n_side * n_side
    rows = {}
    # (name, extra arguments, environment, CSV read from a pipe)
    # h5-1core: one rayon thread and the whole process (its writer thread too) on one core, so that
    # "2 threads vs 1" compares two cores with one (the writer would otherwise take the idle second core)
    one = dict(os.environ, RAYON_NUM_THREADS="1")
    core = ["taskset", "-c", str(min(os.sched_getaffinity(0)))] if shutil.which("taskset") else []
    for name, extra, env, pipe in [("h5", ["-o", os.path.join(out_dir, "table.h5")], None, False),
                                   ("csv", ["-o", os.path.join(out_dir, "table.csv")], None, False),
                                   ("csv-pipe", [], None, True),
                                   ("h5-1core", ["-o", os.path.join(out_dir, "table.h5")], one, False)]:
        runs = []
        for _ in range(reps):
            for f in ("table.h5", "table.csv"):
                if os.path.exists(os.path.join(out_dir, f)):
                    os.remove(os.path.join(out_dir, f))
            # peak RSS from GNU time's %M when it is installed (wait4's ru_maxrss would count the
            # Python parent's pages the child holds between fork and exec)
            rss_file = os.path.join(out_dir, "rss")
            wrap = ["/usr/bin/time", "-f", "%M", "-o", rss_file] if os.path.exists("/usr/bin/time") else []
            pin = core if name == "h5-1core" else []
            # stderr to a file, read after the child ends (a pipe read only then would block a child that
            # writes more than the pipe holds)
            with open(os.path.join(out_dir, "stderr"), "w+b") as err_file:
                t0 = time.perf_counter()
                child = subprocess.Popen(wrap + pin + args + extra, env=env, stderr=err_file,
                                         stdout=subprocess.PIPE if pipe else subprocess.DEVNULL)
                if pipe:  # the table read from a pipe as a consumer would, 1 MiB at a time
                    piped = drain(child.stdout.fileno())
                    child.stdout.close()
                _, status, ru = os.wait4(child.pid, 0)
                wall = time.perf_counter() - t0
                err_file.seek(0)
                err = err_file.read().decode()
            if os.waitstatus_to_exitcode(status) != 0:
                raise SystemExit(f"stochvib sweep failed: {err}")
            rss = float(open(rss_file).read().split()[-1]) / 1024.0 if wrap else float("nan")
            runs.append((wall, ru.ru_utime, ru.ru_stime, rss))
        walls = [r[0] for r in runs]
        best_run = min(runs)
        rows[name] = {
            "points": n,
            "pinned": bool(core) if name == "h5-1core" else None,
            "best_wall_s": best_run[0],
            "median_wall_s": statistics.median(walls),
            "walls_s": walls,
            "best_user_s": best_run[1],
            "best_sys_s": best_run[2],
            "peak_rss_mb": max(r[3] for r in runs),
        }
        if name in ("h5", "csv", "csv-pipe"):  # the I/O floor of the table's bytes, the runs' sizes
            size = piped if pipe else os.path.getsize(os.path.join(out_dir, f"table.{name}"))
            floor = [io_floor(out_dir, size, pipe) for _ in range(reps)]
            rows[name].update(table_bytes=size, floor_best_s=min(floor), floor_median_s=statistics.median(floor))
    scipy = sweep_jobs(1 if SMOKE else 2)["sweep_lyapunov_4_outputs"]["us_per_point"]
    for name, r in rows.items():
        t_scipy = scipy * 1e-6 * n
        r["scipy_us_per_point"] = scipy
        r["ratio_best"] = t_scipy / r["best_wall_s"]
        r["ratio_median"] = t_scipy / r["median_wall_s"]
        print(
            f"stochvib sweep {n} points -> {name:10} best {r['best_wall_s']:.3f} s (user {r['best_user_s']:.2f}, "
            f"sys {r['best_sys_s']:.2f}), median {r['median_wall_s']:.3f} s, peak RSS {r['peak_rss_mb']:.0f} MB; "
            f"scipy {scipy:.2f} us/pt -> {r['ratio_best']:.0f}x best, {r['ratio_median']:.0f}x median"
            + (f"; its {r['table_bytes'] / 1e6:.0f} MB alone {r['floor_median_s']:.3f} s (median)" if "table_bytes" in r
               else ""),
            file=sys.stderr,
        )
    return rows


def drain(fd):
    """Reads `fd` to its end into one reused 1 MiB buffer and returns the bytes read: the cheapest consumer
    Python has (os.read would allocate and shrink a 1 MiB object a read, which costs the 2-core machine
    0.1-0.15 s of a 677 MB table's wall time, measured)."""
    buf, n = bytearray(1 << 20), 0
    while got := os.readv(fd, [buf]):
        n += got
    return n


def io_floor(out_dir, size, pipe):
    """The wall time of moving `size` bytes (zeros, 1 MiB a write) where a table of that size goes, with
    nothing computed or formatted: to a file, with the durability steps of `stochvib sweep`'s tables (a
    temporary file beside the output fsynced, renamed over its name, the directory fsynced); or, with `pipe`,
    from a child process (`head -c`) through a pipe to this process, read as sweep_cli reads the table
    (drain). Below this time no writer of the same bytes gets on this machine in this state."""
    import subprocess

    if pipe:
        t0 = time.perf_counter()
        child = subprocess.Popen(["head", "-c", str(size), "/dev/zero"], stdout=subprocess.PIPE)
        drain(child.stdout.fileno())
        child.stdout.close()
        child.wait()
        return time.perf_counter() - t0
    block = bytes(1 << 20)
    tmp, final = os.path.join(out_dir, "floor.tmp"), os.path.join(out_dir, "floor.bin")
    t0 = time.perf_counter()
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    left = size
    while left > 0:
        left -= os.write(fd, block[: min(left, len(block))])
    os.fsync(fd)
    os.close(fd)
    os.rename(tmp, final)
    dfd = os.open(out_dir, os.O_RDONLY)
    os.fsync(dfd)
    os.close(dfd)
    t = time.perf_counter() - t0
    os.remove(final)
    return t


def sweep_numpy_table():
    """Fully vectorised alternative (not what the brief's baseline does): the integral table I_5 of
    |s^2 k1 k2 g / (Delta (s + a))|^2 as one batched 5x5 linear solve (same formula as
    stochvib::linalg::integral_i_n)."""
    c2, b2 = grid()
    n = 5
    delta = np.stack(
        [C1 * c2, C1 * b2 + B1 * c2, (C1 + c2) * M2 + B1 * b2 + M1 * c2, (B1 + b2) * M2 + M1 * b2, np.full_like(c2, M1 * M2)],
        axis=1,
    )
    den = np.zeros((c2.size, n + 1))
    den[:, :5] += ROAD_A * delta
    den[:, 1:] += delta
    num = ROAD_G * np.stack([np.zeros_like(c2), np.zeros_like(c2), C1 * c2, C1 * b2 + B1 * c2, B1 * b2], axis=1)
    m = np.zeros((c2.size, n, n))
    d = np.zeros((c2.size, n))
    sgn = lambda j: 1.0 if j % 2 == 0 else -1.0  # noqa: E731
    for k in range(n):
        for j in range(n):
            i = 2 * k - j
            if 0 <= i <= n:
                m[:, k, j] = 2 * sgn(j) * den[:, i]
        for j in range(min(n, 2 * k + 1)):
            i = 2 * k - j
            if i < n:
                d[:, k] += sgn(j) * num[:, i] * num[:, j]
    c = np.linalg.solve(m, d[:, :, None])[:, :, 0]
    var = c[:, n - 1] / den[:, n]  # (2 pi c_{n-1}/a_n) / (2 pi)
    return np.sqrt(var).sum()


# --- 4. type-4 input by quadrature ---------------------------------------------------------------------
def quad4():
    d, al, be = T4
    k4 = d / (4 * math.sqrt(math.pi * al))
    c1, b1, c2, b2 = C1, B1, C2N, B2N
    exp = math.exp

    def f(w):
        s2 = -w * w
        k1 = complex(c1, b1 * w)
        k2 = complex(c2, b2 * w)
        h = s2 * k1 * k2 / ((s2 * M1 + k1 + k2) * (s2 * M2 + k2) - k2 * k2)
        return (h.real * h.real + h.imag * h.imag) * k4 * (exp(-((w - be) ** 2) / (4 * al)) + exp(-((w + be) ** 2) / (4 * al)))

    a, _ = state_matrices(np.array([C2N]), np.array([B2N]))
    poles = np.abs(np.linalg.eigvals(a[0, 1:, 1:]))  # the 2-DOF system's natural frequencies
    pts = sorted({float(p) for p in poles if 0 < p < W_HI} | {be})
    val, _err, info = quad(f, 0.0, W_HI, points=pts, epsabs=0, epsrel=1e-8, limit=200, full_output=1)[:3]
    quad4.evaluations = info["neval"]
    quad4.points = pts
    return 2 * val


def run_densities(reps):
    """The density jobs alone (run.sh alternates them with the Rust side's, round after round)."""
    jobs = {}
    w = np.linspace(0.01, 100.0, N_DENSITY)
    for name, fn in densities().items():
        t, check = best(reps, lambda: fn(w).sum(), inner=20)
        jobs[f"density_{name}"] = {"seconds": t, "n": N_DENSITY, "check": check}
    return {"side": "python", "numpy": np.__version__, "simd": numpy_simd()[0], "jobs": jobs}


def numpy_simd():
    """(the run-time-dispatched SIMD targets numpy uses in this process, all it could use on this CPU)."""
    try:
        from numpy._core import _multiarray_umath as m
    except ImportError:  # numpy 1.x
        from numpy.core import _multiarray_umath as m
    have = [k for k in m.__cpu_dispatch__ if m.__cpu_features__.get(k)]
    return have, [k for k in m.__cpu_dispatch__]


def npy_cap(level):
    """The NPY_DISABLE_CPU_FEATURES value that stops numpy's dispatch at `level` (avx2: nothing with
    AVX-512; baseline: none of the dispatched targets, numpy's compiled-in baseline only)."""
    _, dispatch = numpy_simd()
    if level == "baseline":
        return " ".join(dispatch)
    return " ".join(k for k in dispatch if "512" in k or k in ("X86_V4", "AVX512F", "AVX512CD"))


def run_analytic(reps):
    jobs = {}

    def put(key, n, r):
        print(f"{key:32} {r[0]:12.6e} s   check {r[1]:.12e}", file=sys.stderr)
        jobs[key] = {"seconds": r[0], "n": n, "check": r[1]}

    w = np.linspace(0.01, 100.0, N_DENSITY)
    for name, fn in densities().items():
        put(f"density_{name}", N_DENSITY, best(reps, lambda: fn(w).sum(), inner=20))
    put("variance_lyapunov", 1, best(reps, variance_single, inner=200))
    put("sweep_numpy_table", grid()[0].size, best(reps, sweep_numpy_table))
    put("sweep_lyapunov", grid()[0].size, best(min(reps, 2), sweep_lyapunov))
    put("quad4", 1, best(reps, quad4, inner=5))
    return {
        "side": "python",
        "numpy": np.__version__,
        "scipy": __import__("scipy").__version__,
        "python": sys.version.split()[0],
        "glibc_tunables": os.environ.get("GLIBC_TUNABLES", ""),
        "quad4_points": quad4.points,
        "quad4_evaluations": quad4.evaluations,
        "jobs": jobs,
    }


# --- the table -------------------------------------------------------------------------------------------
# (label, rust job, python job, target ratio python/rust or None)
ROWS = [(f"density, {n} (10^4 pts)", f"density_{n}", f"density_{n}", None) for n in densities()] + [
    ("variance, 1 model, Lyapunov (API) vs scipy lyap", "variance_lyapunov", "variance_lyapunov", None),
    ("variance, 1 model, integral table (API) vs scipy lyap", "variance_table", "variance_lyapunov", None),
    ("variance, 1 model, quadrature rel 1e-10 (API)", "variance_quadrature", None, None),
    ("SWEEP 10^5: Rust table I_n vs scipy lyap/pt", "sweep_table", "sweep_lyapunov", 100.0),
    ("sweep 10^5: Rust table I_n, all cores (rayon) vs scipy", "sweep_table_par", "sweep_lyapunov", None),
    ("sweep 10^5: Rust lyap/pt vs scipy lyap/pt", "sweep_lyapunov", "sweep_lyapunov", None),
    ("sweep 10^5: Rust API/pt vs scipy lyap/pt", "sweep_api", "sweep_lyapunov", None),
    ("sweep 10^5: Rust table I_n vs numpy batched I_n", "sweep_table", "sweep_numpy_table", None),
    ("TYPE-4 QUAD rel 1e-8: library integrand vs quad", "quad4_library", "quad4", 20.0),
    ("type-4 quad rel 1e-8: dense reference integrand vs quad", "quad4_library_dense", "quad4", None),
    ("type-4 quad rel 1e-8: closed-form integrand vs quad", "quad4_closed", "quad4", None),
    ("type-4 variance_quadrature (1e-10, [0,inf)) vs quad", "quad4_variance_quadrature", "quad4", None),
]


def fmt_t(t):
    if t is None:
        return "-"
    for unit, f in (("s", 1), ("ms", 1e3), ("us", 1e6), ("ns", 1e9)):
        if t * f >= 1:
            return f"{t * f:.3g} {unit}"
    return f"{t * 1e9:.3g} ns"


def table_analytic(rust_path, py_path):
    rust = json.load(open(rust_path))
    py = json.load(open(py_path))
    rj, pj = rust["jobs"], py["jobs"]
    tun = rust.get("glibc_tunables") or "(unset)"
    out = [
        f"GLIBC_TUNABLES = {tun}; numpy {py['numpy']}, scipy {py['scipy']}, Python {py['python']}",
        "",
        "| job | Rust | Python | ratio Py/Rust | target | met? | checks agree |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, rk, pk, target in ROWS:
        r = rj.get(rk)
        p = pj.get(pk) if pk else None
        ratio = p["seconds"] / r["seconds"] if (r and p) else None
        agree = "-"
        if r and p and rk != "sweep_api":
            rel = abs(r["check"] - p["check"]) / max(abs(p["check"]), 1e-300)
            agree = f"yes ({rel:.0e})" if rel < 1e-6 else f"NO ({rel:.1e})"
        met = "-" if target is None or ratio is None else ("yes" if ratio >= target else "no")
        out.append(
            f"| {label} | {fmt_t(r and r['seconds'])} | {fmt_t(p and p['seconds'])} | "
            f"{'-' if ratio is None else f'{ratio:.3g}x'} | {'-' if target is None else f'>= {target:g}x'} | {met} | {agree} |"
        )
    n = rj["sweep_table"]["n"]
    out += [
        "",
        f"sweep throughput: Rust table {n / rj['sweep_table']['seconds']:.3g} points/s, "
        f"Rust Lyapunov {n / rj['sweep_lyapunov']['seconds']:.3g} points/s, "
        f"Rust API {n / rj['sweep_api']['seconds']:.3g} points/s (timed on 1/10 of the grid), "
        f"scipy Lyapunov {n / pj['sweep_lyapunov']['seconds']:.3g} points/s, "
        f"numpy batched table {n / pj['sweep_numpy_table']['seconds']:.3g} points/s",
        f"type-4 quadrature evaluations: Rust {rust['quad4_evaluations']}, scipy {py['quad4_evaluations']}; "
        f"breakpoints Rust {[round(x, 4) for x in rust['quad4_points']]}, scipy {[round(x, 4) for x in py['quad4_points']]}",
    ]
    print("\n".join(out))


# --- HDF5 write (h5py) and the dynamic-stiffness chain (scipy banded / numpy dense) -------------
# Same problems as benches/h5chain/mod.rs.
H5_ROWS, H5_COLS, H5_SHARD, H5_DEFLATE_ROWS = 1000, 1 << 16, 50, 100
H5_CHUNK = (2, 1 << 16)  # stochvib::store::layout::chunk_shape(2^16, 50): 1 MiB chunks
CHAIN_P = 40.0


def h5_data(rows, cols):
    """x[i, k] = splitmix64(i cols + k) mapped to [-0.5, 0.5) (benches/h5chain/mod.rs::h5_value)."""
    with np.errstate(over="ignore"):
        z = (np.arange(rows * cols, dtype=np.uint64) + np.uint64(1)) * np.uint64(0x9E3779B97F4A7C15)
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        z ^= z >> np.uint64(31)
    return ((z >> np.uint64(11)).astype(np.float64) * 2.0**-53 - 0.5).reshape(rows, cols)


def h5_write(path, data, compression, fsync):
    """What a competent h5py user writes: create the file and the chunked dataset (library chunk shape),
    write it in blocks of H5_SHARD rows (as the library writes shards), close; then fsync if asked (the
    library's finish() fsyncs). Returns the wall time."""
    import h5py

    kw = {"compression": "gzip", "compression_opts": 1, "shuffle": True} if compression else {}
    rows, cols = data.shape
    t0 = time.perf_counter()
    with h5py.File(path, "w") as f:
        ds = f.create_dataset("x", shape=(rows, cols), dtype="f8", chunks=H5_CHUNK, **kw)
        for a in range(0, rows, H5_SHARD):
            ds[a : a + H5_SHARD] = data[a : a + H5_SHARD]
    if fsync:
        fd = os.open(path, os.O_RDONLY)
        os.fsync(fd)
        os.close(fd)
    return time.perf_counter() - t0


def h5_jobs(reps):
    import tempfile

    import h5py

    out = {}
    data = h5_data(H5_ROWS, H5_COLS)
    with tempfile.TemporaryDirectory(prefix="stochvib-h5py-") as d:
        for key, rows, comp, fsync, r in [
            ("h5_write_none", H5_ROWS, False, True, reps),
            ("h5_write_none_nosync", H5_ROWS, False, False, reps),
            ("h5_write_deflate1", H5_DEFLATE_ROWS, True, True, min(reps, 2)),
        ]:
            x = data[:rows]
            path = os.path.join(d, key + ".h5")
            t = float("inf")
            for _ in range(max(r, 1)):
                if os.path.exists(path):
                    os.remove(path)
                t = min(t, h5_write(path, x, comp, fsync))
            with h5py.File(path, "r") as f:
                back = f["x"][...]
            flat = back.ravel()
            size = os.path.getsize(path)
            os.remove(path)
            nbytes = rows * H5_COLS * 8
            out[key] = {"seconds": t, "n": nbytes, "check": float(np.dot(flat, flat)), "mb_per_s": nbytes / t / 1e6, "file_bytes": size}
    out["h5py"] = h5py.__version__
    out["hdf5"] = h5py.version.hdf5_version
    return out


def chain_arrays(n):
    """The chain of benches/h5chain/mod.rs::chain(n)."""
    k = np.arange(n)
    inertia = 1.0 + 0.1 * (k % 7)
    ks = np.arange(n - 1)
    return inertia, np.full(n, 10.0), np.full(n, 0.5), 1.0e4 * (1.0 + 0.2 * (ks % 5)), np.full(n - 1, 2.0), np.ones(n, complex)


def chain_banded(n, p=CHAIN_P):
    """The competent scipy user's O(n) solve of the tridiagonal dynamic-stiffness system (same work as the
    library sweep: assemble d_k, s_k at p, solve, shaft torques)."""
    from scipy.linalg import solve_banded

    inertia, kg, bg, c, bs, m = chain_arrays(n)
    s = c + 1j * bs * p
    diag = kg - inertia * p * p + 1j * bg * p
    diag[:-1] += s
    diag[1:] += s
    ab = np.zeros((3, n), complex)
    ab[0, 1:] = -s
    ab[1] = diag
    ab[2, :-1] = -s
    phi = solve_banded((1, 1), ab, m, check_finite=False)
    torque = s * (phi[:-1] - phi[1:])
    return np.abs(phi).sum() + np.abs(torque).sum()


def chain_dense(n, p=CHAIN_P):
    """Dense n x n complex assembly and numpy.linalg.solve (LAPACK zgesv), the textbook O(n^3) route."""
    inertia, kg, bg, c, bs, m = chain_arrays(n)
    s = c + 1j * bs * p
    z = np.zeros((n, n), complex)
    i = np.arange(n)
    z[i, i] = kg - inertia * p * p + 1j * bg * p
    z[i[:-1], i[:-1]] += s
    z[i[1:], i[1:]] += s
    z[i[:-1], i[1:]] -= s
    z[i[1:], i[:-1]] -= s
    phi = np.linalg.solve(z, m)
    torque = s * (phi[:-1] - phi[1:])
    return np.abs(phi).sum() + np.abs(torque).sum()


def chain_jobs(reps):
    out = {}
    for key, n, fn in [
        ("chain_banded_400", 400, chain_banded),
        ("chain_banded_1e4", 10_000, chain_banded),
        ("chain_banded_1e5", 100_000, chain_banded),
        ("chain_banded_1e6", 1_000_000, chain_banded),
        ("chain_dense_400", 400, chain_dense),
    ]:
        n = min(n, 10_000) if SMOKE else n
        inner = max(1, min(100, 1_000_000 // n)) if fn is chain_banded else 5
        t, check = best(reps, lambda: fn(n), inner=inner)
        out[key] = {"seconds": t, "n": n, "check": check, "seconds_per_mass": t / n}
    return out


def run_h5_chain(reps, doc):
    """HDF5 write and chain jobs, added to `doc` (the document of run_analytic)."""
    h5 = h5_jobs(reps)
    doc["h5py"], doc["hdf5"] = h5.pop("h5py"), h5.pop("hdf5")
    for key, job in list(h5.items()) + list(chain_jobs(reps).items()):
        print(f"{key:32} {job['seconds']:12.6e} s   check {job['check']:.12e}", file=sys.stderr)
        doc["jobs"][key] = job


MB = H5_ROWS * H5_COLS * 8 / 1e6
ROWS += [
    (f"HDF5 WRITE {H5_ROWS}x2^16 f64 ({MB:.0f} MB), none, create..fsync: store vs h5py", "h5_write_none", "h5_write_none", 1.0),
    (f"HDF5 WRITE {H5_ROWS}x2^16 f64, none, create..close (no fsync)", "h5_write_none_nosync", "h5_write_none_nosync", 1.0),
    (f"HDF5 WRITE {H5_DEFLATE_ROWS}x2^16 f64, shuffle+deflate:1, create..fsync", "h5_write_deflate1", "h5_write_deflate1", 1.0),
    ("chain n=400: O(n) sweep vs scipy solve_banded", "chain_sweep_400", "chain_banded_400", None),
    ("chain n=10^4: O(n) sweep vs scipy solve_banded", "chain_sweep_1e4", "chain_banded_1e4", None),
    ("chain n=10^5: O(n) sweep vs scipy solve_banded", "chain_sweep_1e5", "chain_banded_1e5", None),
    ("CHAIN n=10^6: O(n) sweep vs scipy solve_banded", "chain_sweep_1e6", "chain_banded_1e6", None),
    ("chain n=400: library dense LU (oracle) vs numpy solve", "chain_dense_400", "chain_dense_400", None),
    ("chain n=400: O(n) sweep vs numpy dense solve", "chain_sweep_400", "chain_dense_400", None),
]

def table_h5_chain(rust_path, py_path):
    """Summary lines of the HDF5 and chain jobs (their rows are in ROWS)."""
    rj, pj = json.load(open(rust_path))["jobs"], json.load(open(py_path))
    py_hdf5 = f"h5py {pj.get('h5py', '?')} (HDF5 {pj.get('hdf5', '?')})"
    pj = pj["jobs"]
    lines = []
    if "h5_write_none" in rj and "h5_write_none" in pj:
        parts = []
        for k in ("h5_write_none", "h5_write_none_nosync", "h5_write_deflate1"):
            parts.append(f"{k}: store {rj[k]['mb_per_s']:.0f} MB/s, h5py {pj[k]['mb_per_s']:.0f} MB/s")
        lines.append(f"HDF5 write throughput ({py_hdf5}): " + "; ".join(parts))
        lines.append(
            f"deflate:1 file size / raw: store {rj['h5_write_deflate1']['file_bytes'] / rj['h5_write_deflate1']['n']:.3f}, "
            f"h5py {pj['h5_write_deflate1']['file_bytes'] / pj['h5_write_deflate1']['n']:.3f}"
        )
    if "chain_sweep_1e6" in rj:
        t6 = rj["chain_sweep_1e6"]["seconds"]
        per = ", ".join(f"n={rj[k]['n']:.0e}: {rj[k]['seconds_per_mass'] * 1e9:.3g} ns" for k in ("chain_sweep_1e4", "chain_sweep_1e5", "chain_sweep_1e6"))
        lines.append(f"CHAIN n = 10^6 at one frequency: {fmt_t(t6)}, target < 1 s: {'met' if t6 < 1.0 else 'NOT met'}; time per mass {per}")
    print("\n".join([""] + lines))


# --- 5. Monte Carlo pipeline ----------------------------------------------------------------
# Same job as McSpectral in benches/common/mod.rs: SDOF x'' + 2 zeta w x' + w^2 x = u (w = 10 rad/s,
# zeta = 0.05, output x) under K(tau) = e^{-3|tau|}; MC_REAL realizations x 2^16 samples, dt = 0.01 s.
# Spectral representation with Rayleigh amplitudes on the FFT grid (numpy real FFT), the model discretised
# once (first-order hold, scipy.signal.cont2discrete) and run with scipy.signal.lfilter along the time axis
# through (warm-up + 1) periods of the periodic input (filter state carried by zi), then per realization
# m_i = mean y, v_i = mean y^2 and Student-t intervals across realizations. Vectorised over blocks of
# MC_CHUNK realizations (a full 1000 x 2^16 block needs ~2 GB and runs slower).
MC_REAL, MC_N, MC_DT, MC_SEED, MC_CHUNK = 1000, 1 << 16, 0.01, 2024, 50
MC_W, MC_ZETA, MC_D, MC_ALPHA = 10.0, 0.05, 1.0, 3.0
MC_WARMUP_DECAY = 36.0  # stochvib::simulate::run::WARMUP_DECAY


def mc_setup():
    from scipy.signal import cont2discrete, ss2tf

    dw = 2 * math.pi / (MC_N * MC_DT)
    w = np.arange(MC_N // 2 + 1) * dw
    scale = np.sqrt(MC_D * MC_ALPHA / (math.pi * (MC_ALPHA**2 + w * w)) * dw)
    a = np.array([[0.0, 1.0], [-MC_W**2, -2 * MC_ZETA * MC_W]])
    b = np.array([[0.0], [1.0]])
    c = np.array([[1.0, 0.0]])
    d = np.zeros((1, 1))
    ad, bd, cd, dd, _ = cont2discrete((a, b, c, d), MC_DT, method="foh")
    num, den = ss2tf(ad, bd, cd, dd)
    sigma_min = min(-np.linalg.eigvals(a).real)
    warmup = max(1, math.ceil(MC_WARMUP_DECAY / (sigma_min * MC_N * MC_DT)))
    return scale, num[0], den, warmup


def mc_stats(m, v):
    from scipy.stats import t as student_t

    r = m.size
    q = student_t.ppf(0.975, r - 1)
    out = {}
    for name, x in (("mean", m), ("var", v)):
        est, h = x.mean(), q * x.std(ddof=1) / math.sqrt(r)
        out[name] = [est - h, est, est + h]
    out["sigma"] = [math.sqrt(max(out["var"][0], 0.0)), math.sqrt(out["var"][1]), math.sqrt(out["var"][2])]
    out["check_se"] = (out["var"][2] - out["var"][1]) / q
    return out


def mc_pipeline():
    from scipy.signal import lfilter

    scale, num, den, warmup = mc_setup()
    rng = np.random.default_rng(MC_SEED)
    m, v = np.empty(MC_REAL), np.empty(MC_REAL)
    zi0 = np.zeros((MC_CHUNK, den.size - 1))
    half = scale * math.sqrt(0.5)
    for r0 in range(0, MC_REAL, MC_CHUNK):
        z = rng.standard_normal((MC_CHUNK, MC_N // 2 + 1, 2))
        coef = z.view(np.complex128)[..., 0]  # shares memory with z
        ends = z[:, 0, 0] * scale[0], z[:, -1, 0] * scale[-1]
        coef *= half
        coef[:, 0], coef[:, -1] = ends
        u = np.fft.irfft(coef, n=MC_N, axis=1)
        u *= MC_N  # numpy's inverse FFT carries 1/N; the synthesis is the plain sum of cosines
        zi = zi0
        for _ in range(warmup + 1):
            y, zi = lfilter(num, den, u, axis=1, zi=zi)
        m[r0 : r0 + MC_CHUNK] = y.mean(axis=1)
        v[r0 : r0 + MC_CHUNK] = np.einsum("ij,ij->i", y, y) / MC_N
    mc_pipeline.stats = mc_stats(m, v)
    return mc_pipeline.stats["var"][1]


def mc_pipeline_fft():
    """The same periodic steady state in one FFT: the coefficients times the sampled system's frequency
    response H_d(e^{i w_j dt}) (scipy.signal.freqz of the same FOH filter), one irfft, statistics."""
    from scipy.signal import freqz

    scale, num, den, _ = mc_setup()
    _, h = freqz(num, den, worN=2 * math.pi * np.arange(MC_N // 2 + 1) / MC_N)
    g = scale * math.sqrt(0.5) * h
    rng = np.random.default_rng(MC_SEED)
    m, v = np.empty(MC_REAL), np.empty(MC_REAL)
    for r0 in range(0, MC_REAL, MC_CHUNK):
        z = rng.standard_normal((MC_CHUNK, MC_N // 2 + 1, 2))
        coef = z.view(np.complex128)[..., 0]
        coef[:, 0] = z[:, 0, 0] * math.sqrt(2)
        coef[:, -1] = z[:, -1, 0] * math.sqrt(2)
        coef *= g
        y = np.fft.irfft(coef, n=MC_N, axis=1)
        y *= MC_N
        m[r0 : r0 + MC_CHUNK] = y.mean(axis=1)
        v[r0 : r0 + MC_CHUNK] = np.einsum("ij,ij->i", y, y) / MC_N
    mc_pipeline_fft.stats = mc_stats(m, v)
    return mc_pipeline_fft.stats["var"][1]


def mc_floor():
    """Draw the normals and one inverse real FFT per realization (blocks of MC_CHUNK)."""
    rng = np.random.default_rng(MC_SEED)
    acc = 0.0
    for _ in range(0, MC_REAL, MC_CHUNK):
        z = rng.standard_normal((MC_CHUNK, MC_N // 2 + 1, 2))
        x = np.fft.irfft(z.view(np.complex128)[..., 0], n=MC_N, axis=1)
        acc += x[:, 1].sum()
    return acc


def run_mc(reps, jobs):
    reps = min(reps, 3)
    for key, fn in (("mc_pipeline", mc_pipeline), ("mc_pipeline_fft", mc_pipeline_fft), ("mc_floor", mc_floor)):
        t, check = best(reps, fn)
        jobs[key] = {"seconds": t, "n": MC_REAL * MC_N, "check": check}
        print(f"{key:32} {t:12.6e} s   check {check:.12e}", file=sys.stderr)
    jobs["mc_pipeline"].update(mc_pipeline.stats)
    jobs["mc_pipeline_fft"].update(mc_pipeline_fft.stats)


def run(reps):
    """All jobs: analytic, HDF5 write and chain, Monte Carlo."""
    doc = run_analytic(reps)
    run_h5_chain(reps, doc)
    run_mc(reps, doc["jobs"])
    doc["mc"] = {"realizations": MC_REAL, "samples": MC_N, "chunk": MC_CHUNK, "warmup_periods": mc_setup()[3]}
    return doc


# (label, rust job, python job, target ratio python/rust or None)
MC_ROWS = [
    ("MC PIPELINE 1000x2^16, time stepping (1 thread) vs numpy/scipy lfilter", "mc_pipeline_1t", "mc_pipeline", 20.0),
    ("MC pipeline 1000x2^16, time stepping (2 threads) vs numpy/scipy lfilter", "mc_pipeline_2t", "mc_pipeline", None),
    ("MC PIPELINE 1000x2^16, one FFT (1 thread) vs numpy one FFT", "mc_pipeline_fft_1t", "mc_pipeline_fft", 20.0),
    ("MC pipeline 1000x2^16, one FFT (2 threads) vs numpy one FFT", "mc_pipeline_fft_2t", "mc_pipeline_fft", None),
    ("MC pipeline 1000x2^16, one FFT (1 thread) vs numpy/scipy lfilter", "mc_pipeline_fft_1t", "mc_pipeline", None),
    ("MC floor (normals + 1 irfft per realization)", "mc_floor_1t", "mc_floor", None),
    ("MC exact route (augmented Gauss-Markov), 1 thread", "mc_exact_1t", None, None),
    ("MC exact route (augmented Gauss-Markov), 2 threads", "mc_exact_2t", None, None),
]


def mc_table(rust, py):
    """The Monte Carlo rows (printed last by `table`): ratios to numpy, Rust pipeline vs Rust floor, 1 vs 2
    threads, with targets."""
    rj, pj = rust["jobs"], py["jobs"]
    out = [
        "",
        "| job | Rust | Python | ratio Py/Rust | target | met? | checks agree |",
        "|---|---|---|---|---|---|---|",
    ]
    for label, rk, pk, target in MC_ROWS:
        r, p = rj.get(rk), (pj.get(pk) if pk else None)
        ratio = p["seconds"] / r["seconds"] if (r and p) else None
        agree = "-"
        if r and p and "check_se" in r and "check_se" in p:
            zs = (r["check"] - p["check"]) / math.hypot(r["check_se"], p["check_se"])
            agree = f"{'yes' if abs(zs) < 4 else 'NO'} (sigma^2, z = {zs:+.1f})"
        met = "-" if target is None or ratio is None else ("yes" if ratio >= target else "no")
        out.append(
            f"| {label} | {fmt_t(r and r['seconds'])} | {fmt_t(p and p['seconds'])} | "
            f"{'-' if ratio is None else f'{ratio:.3g}x'} | {'-' if target is None else f'>= {target:g}x'} | {met} | {agree} |"
        )
    floor = rj.get("mc_floor_1t")
    for tag, name in (("", "time stepping"), ("_fft", "one FFT")):
        one, two = rj.get(f"mc_pipeline{tag}_1t"), rj.get(f"mc_pipeline{tag}_2t")
        if one and floor:
            q = one["seconds"] / floor["seconds"]
            out.append(
                f"| MC pipeline ({name}) / Rust floor, 1 thread | {q:.3g}x | | | <= 2x | {'yes' if q <= 2 else 'no'} | |"
            )
        if one and two:
            q = one["seconds"] / two["seconds"]
            out.append(
                f"| MC pipeline ({name}) speed-up 2 threads vs 1 | {q:.3g}x | | | >= 1.8x | {'yes' if q >= 1.8 else 'no'} | |"
            )
    s1, s2 = rj.get("mc_spin_1t"), rj.get("mc_spin_2t")
    if s1 and s2:
        q = s1["seconds"] / s2["seconds"]
        out.append(f"| calibration: independent spin loops, speed-up 2 threads vs 1 (ideal 2) | {q:.3g}x | | | - | - | |")
    one = rj.get("mc_pipeline_1t")
    if one:
        st = one.get("sigma")
        an = rust.get("mc", {}).get("analytic_variance")
        if st and an:
            out.append(
                f"\nMC sigma (Rust, 1000 realizations): {st[1]:.6g} in [{st[0]:.6g}, {st[2]:.6g}] (95 %); "
                f"analytic sigma {math.sqrt(an):.6g}"
            )
    print("\n".join(out))


def table(rust_path, py_path):
    """The ratio table (ROWS), the HDF5/chain summary lines, then the Monte Carlo rows."""
    table_analytic(rust_path, py_path)
    table_h5_chain(rust_path, py_path)
    mc_table(json.load(open(rust_path)), json.load(open(py_path)))


# --- the one table (benches/RESULTS.md) ------------------------------------------------------------------
CMD_RUN = "`compare_rust` + `compare.py run`"
CMD_CLI = "`compare.py sweep-cli`"
CMD_DENS = "`compare_rust --only density` / `compare.py run --only density`, alternated, median of the rounds"


def summary_rows(rust, py, sweeps):
    """(job, size, ours s, peer name, peer s or None, ratio, ratio text, state key, command) of every row."""
    rj, pj = rust["jobs"], py["jobs"]
    rows = []

    def vs(job, size, rk, peer, pk, cmd=CMD_RUN, state="run"):
        r, p = rj.get(rk), pj.get(pk)
        if r and p:
            rows.append((job, size, r["seconds"], peer, p["seconds"], p["seconds"] / r["seconds"], state, cmd))

    for k in sorted(k[8:] for k in rj if k.startswith("density_")):
        if "density_rounds" in rust:  # medians of the alternating rounds (run.sh)
            t, tp = rust["density_rounds"][k], py["density_rounds"][k]
            rows.append((f"density, {k}", f"{rj['density_' + k]['n']} pts", t, "numpy (vectorised)", tp, tp / t,
                         "density", CMD_DENS))
            continue
        vs(f"density, {k}", f"{rj['density_' + k]['n']} pts", "density_" + k, "numpy (vectorised)", "density_" + k)
    for cap, rounds in rust.get("isa_rounds", {}).items():  # the rounds capped to a narrower instruction set
        cmd = (f"`STOCHVIB_ISA={cap} compare_rust --only density` / `NPY_DISABLE_CPU_FEATURES=... compare.py run "
               f"--only density` (`compare.py npy-cap {cap}`), alternated, median of the rounds")
        for k in sorted(rounds):
            t, tp = rounds[k], py["isa_rounds"][cap][k]
            rows.append((f"density, {k}, capped to {cap}", f"{rj['density_' + k]['n']} pts", t, "numpy (vectorised)",
                         tp, tp / t, f"isa-{cap}", cmd))
    vs("variance, 1 model, integral table", "1 model", "variance_table", "scipy solve_continuous_lyapunov", "variance_lyapunov")
    n = rj["sweep_table"]["n"]
    vs("variance sweep, table I_n, 1 thread", f"{n} pts", "sweep_table", "scipy lyap per point", "sweep_lyapunov")
    vs("variance sweep, table I_n, 2 threads", f"{n} pts", "sweep_table_par", "scipy lyap per point", "sweep_lyapunov")
    vs("type-4 quadrature rel 1e-8", "1 integral", "quad4_library", "scipy quad", "quad4")
    mb = rj["h5_write_none"]["n"] / 1e6
    vs("HDF5 write, no compression, until fsync", f"{mb:.0f} MB", "h5_write_none", "h5py", "h5_write_none")
    vs("HDF5 write, no compression, until close", f"{mb:.0f} MB", "h5_write_none_nosync", "h5py", "h5_write_none_nosync")
    mbd = rj["h5_write_deflate1"]["n"] / 1e6
    vs("HDF5 write, shuffle+deflate:1, until fsync", f"{mbd:.0f} MB", "h5_write_deflate1", "h5py", "h5_write_deflate1")
    vs("chain, O(n) sweep", f"n = {rj['chain_sweep_1e6']['n']}", "chain_sweep_1e6", "scipy solve_banded", "chain_banded_1e6")
    mc = f"{rust['mc']['realizations']} x {rust['mc']['samples']}"
    vs("MC one FFT, 1 thread", mc, "mc_pipeline_fft_1t", "numpy one FFT", "mc_pipeline_fft")
    vs("MC time stepping, 1 thread", mc, "mc_pipeline_1t", "numpy/scipy lfilter", "mc_pipeline")
    # ours against ours: the scaling (1 thread / 2 threads); the floors (ratio = floor / ours, target >= 1/1.1)
    # come from several processes (rows-floors.json, run.sh), one process's being no measurement of them
    for job, k in [("MC one FFT", "mc_pipeline_fft"), ("MC time stepping", "mc_pipeline"), ("MC exact route", "mc_exact"),
                   ("calibration spin loops", "mc_spin")]:
        if f"{k}_1t" in rj and f"{k}_2t" in rj:
            t1, t2 = rj[f"{k}_1t"]["seconds"], rj[f"{k}_2t"]["seconds"]
            rows.append((f"{job}, 2 threads vs 1", mc, t2, "ours, 1 thread", t1, t1 / t2, "run", CMD_RUN))
    for state, sw in sweeps.items():
        for fmt, r in sw.items():
            if not isinstance(r, dict) or "median_wall_s" not in r:
                continue
            t_scipy = r["scipy_us_per_point"] * 1e-6 * r["points"]
            rows.append((f"`stochvib sweep` -> {fmt}", f"{r['points']} pts", r["median_wall_s"],
                         "scipy lyap per point (4 outputs)", t_scipy, t_scipy / r["median_wall_s"], state, CMD_CLI))
        for fmt, r in sw.items():  # ours against the I/O floor of the same bytes (ratio = floor / ours)
            if isinstance(r, dict) and "floor_median_s" in r:
                where = "through a pipe to the same reader" if fmt == "csv-pipe" else "to a file, fsync, rename"
                rows.append((f"`stochvib sweep` -> {fmt} vs moving its bytes alone", f"{r['table_bytes'] / 1e6:.3g} MB",
                             r["median_wall_s"], f"the same bytes {where}, nothing computed (I/O floor)",
                             r["floor_median_s"], r["floor_median_s"] / r["median_wall_s"], state, CMD_CLI))
        if "h5" in sw and "h5-1core" in sw:
            t1, t2 = sw["h5-1core"]["median_wall_s"], sw["h5"]["median_wall_s"]
            pinned = sw["h5-1core"].get("pinned", True)
            rows.append((f"`stochvib sweep` -> h5, 2 threads vs 1{' on 1 core' if pinned else ' (not pinned: no taskset)'}",
                         f"{sw['h5']['points']} pts", t2,
                         "ours, 1 thread, the process on 1 core" if pinned else "ours, 1 thread", t1, t1 / t2, state,
                         CMD_CLI))
    return rows


def summary(d):
    """Prints the one table of benches/RESULTS.md from run.sh's output directory `d`."""
    rust, py = json.load(open(os.path.join(d, "rust.json"))), json.load(open(os.path.join(d, "python.json")))
    rounds = sorted(f for f in os.listdir(d) if f.startswith("density-rust-"))
    if rounds:  # median over the alternating rounds of each side
        import statistics

        for side, doc, prefix in (("rust", rust, "density-rust-"), ("python", py, "density-python-")):
            runs = [json.load(open(os.path.join(d, f.replace("density-rust-", prefix))))["jobs"] for f in rounds]
            doc["density_rounds"] = {k[8:]: statistics.median(r[k]["seconds"] for r in runs) for k in runs[0]}
    states = {}
    for cap in ("avx2", "baseline"):  # the capped density rounds, if run.sh ran them
        caps = sorted(f for f in os.listdir(d) if f.startswith(f"isa-{cap}-rust-"))
        if not caps:
            continue
        import statistics

        used = {}
        for side, doc in (("rust", rust), ("python", py)):
            runs = [json.load(open(os.path.join(d, f.replace("-rust-", f"-{side}-")))) for f in caps]
            doc.setdefault("isa_rounds", {})[cap] = {
                k[8:]: statistics.median(r["jobs"][k]["seconds"] for r in runs) for k in runs[0]["jobs"]}
            used[side] = runs[0].get("isa") if side == "rust" else " ".join(runs[0].get("simd", [])) or "its baseline"
        f = os.path.join(d, f"state-isa-{cap}.txt")
        load = open(f).read().strip() if os.path.exists(f) else "?"
        states[f"isa-{cap}"] = f"{load}; ours {used['rust']}, numpy {used['python']}"
    sweeps = {}
    for name in ("quiet", "busy"):
        f = os.path.join(d, f"sweep-{name}.json")
        if os.path.exists(f):
            sweeps[name] = json.load(open(f))
    for name in ("run", "density", "quiet", "busy"):
        f = os.path.join(d, f"state-{name}.txt")
        states[name] = open(f).read().strip() if os.path.exists(f) else "?"
    out = [
        "| job | size | ours | best Python peer | peer | ratio peer/ours | machine state | command |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for job, size, t, peer, tp, ratio, state, cmd in summary_rows(rust, py, sweeps):
        out.append(f"| {job} | {size} | {fmt_t(t)} | {peer} | {fmt_t(tp)} | {ratio:.3g}x | {states[state]} | {cmd} |")
    # the harnesses with tables of their own (fatigue, nonlinear, transient, optimize, records): rows-NAME.json,
    # measured in the state of state-NAME.txt
    for f in sorted(f for f in os.listdir(d) if f.startswith("rows-") and f.endswith(".json")):
        name = f[5:-5]
        sf = os.path.join(d, f"state-{name}.txt")
        state = open(sf).read().strip() if os.path.exists(sf) else "?"
        for r in json.load(open(os.path.join(d, f))):
            t, tp = r["ours_s"], r["peer_s"]
            out.append(f"| {r['job']} | {r['size']} | {fmt_t(t)} | {r['peer']} | {fmt_t(tp)} | {tp / t:.3g}x | {state} "
                       f"| {r['cmd']} |")
    print("\n".join(out))


def apply_smoke():
    """Tiny sizes for the CI smoke run (the same as examples/compare_rust.rs --smoke)."""
    global SMOKE, H5_ROWS, H5_DEFLATE_ROWS, H5_COLS, H5_CHUNK, MC_REAL, MC_N, MC_CHUNK
    SMOKE = True
    H5_ROWS, H5_DEFLATE_ROWS, H5_COLS, H5_CHUNK = 4, 2, 1 << 12, (2, 1 << 12)
    MC_REAL, MC_N, MC_CHUNK = 4, 1 << 12, 4


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--reps", type=int, default=5)
    r.add_argument("--smoke", action="store_true", help="every job once at a tiny size")
    r.add_argument("--only", choices=["density", "h5"], help="only the density jobs, or the HDF5 write and chain jobs")
    t = sub.add_parser("table")
    t.add_argument("rust")
    t.add_argument("python")
    w = sub.add_parser("sweep", help="only the scipy sweep loops (1 output, and 4 outputs with lambda2)")
    w.add_argument("--reps", type=int, default=2)
    c = sub.add_parser("sweep-cli", help="`stochvib sweep` of 10^6 points (HDF5, CSV) beside the scipy loop")
    c.add_argument("--reps", type=int, default=7)
    c.add_argument("--binary", default="target/release/stochvib")
    c.add_argument("--out-dir", default=None, help="where the tables go (default: a temporary directory)")
    c.add_argument("--side", type=int, default=1000, help="values per key (points = side^2)")
    c.add_argument("--smoke", action="store_true", help="tiny scipy loop (10 x 10 points)")
    cap = sub.add_parser("npy-cap", help="print the NPY_DISABLE_CPU_FEATURES value of an instruction-set cap")
    cap.add_argument("level", choices=["avx2", "baseline"])
    m = sub.add_parser("summary", help="the one table of benches/RESULTS.md from the JSON of one run.sh run")
    m.add_argument("dir", help="run.sh's output directory (rust.json, python.json, sweep-*.json, state-*.txt)")
    a = ap.parse_args()
    if a.cmd == "summary":
        summary(a.dir)
        return
    if a.cmd == "npy-cap":
        print(npy_cap(a.level))
        return
    if a.cmd == "sweep-cli":
        import tempfile

        if a.smoke:
            apply_smoke()
        with tempfile.TemporaryDirectory() as tmp:
            print(json.dumps(sweep_cli(a.reps, a.binary, a.out_dir or tmp, a.side), indent=1))
        return
    if a.cmd == "run":
        if a.smoke:
            apply_smoke()
        if a.only == "density":
            print(json.dumps(run_densities(a.reps), indent=1))
        elif a.only == "h5":
            doc = {"side": "python", "jobs": {}}
            run_h5_chain(1 if a.smoke else a.reps, doc)
            print(json.dumps(doc, indent=1))
        else:
            print(json.dumps(run(1 if a.smoke else a.reps), indent=1))
    elif a.cmd == "sweep":
        print(json.dumps(sweep_jobs(a.reps), indent=1))
    else:
        table(a.rust, a.python)


if __name__ == "__main__":
    main()
