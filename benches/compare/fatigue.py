#!/usr/bin/env python3
"""Fatigue comparison: stochvib's streaming rainflow and Dirlik against the Python packages.

    python3 benches/compare/fatigue.py run [--n 100000000] [--reps 3] [--check 1000000]
    python3 benches/compare/fatigue.py reference      # FLife values used by tests/fatigue.rs

Installs nothing: run it where numpy, fatpack, rainflow, py-fatigue and FLife are installed
(`python3 -m pip install numpy scipy fatpack rainflow py-fatigue FLife`); a missing package is skipped.

`run` builds and runs examples/fatigue_compare.rs (release), which writes the seeded resonant AR(2) record
of benches/common/fatigue_signal.rs as raw f64 and the cycles of its first `--check` samples, then:
1. checks that every package counts the same cycles as stochvib on that prefix (same ranges, means and
   counts, half cycles included), with exact turning points given to packages that would otherwise
   quantise them (fatpack's find_reversals classifies the signal into k = 64 levels by default);
2. times the rainflow count of the whole record (packages written as Python loops are timed on a prefix
   and reported per sample; the ratio is per sample);
3. times FLife's Dirlik life on the same single-mode density (tabulated on a grid, as FLife needs) against
   stochvib's (moments by adaptive quadrature of the density, then the damage).
Timings are the best of `--reps`; on a shared machine compare ratios, not absolute times.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time
import warnings

import numpy as np

warnings.filterwarnings("ignore")
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))

# --- the density of the Dirlik benchmark (benches/common/fatigue_signal.rs) ----------------------------------
SDOF_FN, SDOF_ZETA, SDOF_F_MAX = 50.0, 0.05, 500.0
SN_K, SN_C = 5.0, 1e16


def sdof_density(f):
    u = f / SDOF_FN
    return 10.0 / ((1.0 - u * u) ** 2 + (2.0 * SDOF_ZETA * u) ** 2) + 0.1


def best_of(reps, fn):
    best, out = math.inf, None
    for _ in range(reps):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def exact_reversals(y):
    """Turning points as stochvib defines them (first sample, every change of direction with plateaus
    merged at their first sample, last extreme), vectorised with numpy."""
    keep = np.concatenate(([True], y[1:] != y[:-1]))
    idx = np.flatnonzero(keep)
    v = y[idx]
    if len(v) < 3:
        return v, idx
    d = np.diff(v)
    turn = np.flatnonzero(d[:-1] * d[1:] < 0) + 1
    sel = np.concatenate(([0], turn, [len(v) - 1]))
    return v[sel], idx[sel]


def cycles_fatpack(y):
    import fatpack

    rev, _ = exact_reversals(y)
    cyc, res = fatpack.find_rainflow_cycles(rev)
    full = np.column_stack((np.abs(cyc[:, 1] - cyc[:, 0]), 0.5 * (cyc[:, 0] + cyc[:, 1]), np.ones(len(cyc)))) if len(cyc) else np.zeros((0, 3))
    half = np.column_stack((np.abs(np.diff(res)), 0.5 * (res[1:] + res[:-1]), np.full(len(res) - 1, 0.5)))
    return np.vstack((full, half))


def cycles_rainflow(y):
    import rainflow

    return np.array([(r, m, c) for r, m, c, _, _ in rainflow.extract_cycles(y)])


def cycles_pyfatigue(y):
    from py_fatigue.cycle_count.rainflow import rainflow as pf_rainflow

    rfs = pf_rainflow(y, extended_output=False)  # columns: amplitude, mean, count (zero ranges dropped)
    return np.column_stack((2.0 * rfs[:, 0], rfs[:, 1], rfs[:, 2]))


def canonical(c):
    c = np.asarray(c, dtype=float).reshape(-1, 3)
    c = c[c[:, 0] > 0]  # zero-range cycles (plateaus of equal extremes) carry no damage; py-fatigue drops them
    return c[np.lexsort((c[:, 2], c[:, 1], c[:, 0]))]


def run(args):
    if not args.no_build:
        subprocess.run(["cargo", "build", "--locked", "--profile", args.profile, "--quiet", "--example",
                        "fatigue_compare"], cwd=ROOT, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    binary = os.path.join(target, "release" if args.profile == "release" else "debug", "examples", "fatigue_compare")
    table = []  # rows of benches/RESULTS.md's table (--rows)
    out = subprocess.run(
        [binary, "--n", str(args.n), "--reps", str(args.reps), "--check", str(args.check), "--dir", args.dir],
        check=True, capture_output=True, text=True,
    ).stdout
    rust = json.loads(out)
    y = np.fromfile(os.path.join(args.dir, "signal.f64"), dtype="<f8")
    assert len(y) == args.n
    ref = canonical(np.fromfile(os.path.join(args.dir, "cycles_prefix.f64"), dtype="<f8"))
    prefix = y[: args.check]
    print(f"signal: {args.n} samples, {len(exact_reversals(prefix)[0])} turning points in the first {args.check}")
    print(f"stochvib rainflow + Miner (k = 3), whole record: {rust['rainflow_s']:.3f} s "
          f"({rust['rainflow_s'] / args.n * 1e9:.2f} ns/sample), {rust['cycles']:.1f} cycles")

    rows = []
    packages = [("fatpack (exact reversals)", cycles_fatpack, args.n),
                ("rainflow", cycles_rainflow, args.check),
                ("py-fatigue", cycles_pyfatigue, args.check)]
    for name, fn, n_time in packages:
        try:
            got = canonical(fn(prefix))
        except ImportError as e:
            print(f"{name}: not installed ({e})")
            continue
        same = got.shape == ref.shape and np.array_equal(got, ref)
        print(f"{name}: same cycles as stochvib on the first {args.check} samples: {same} "
              f"({len(got)} vs {len(ref)} cycles)")
        reps = args.reps if n_time <= args.check else 1
        t, _ = best_of(reps, lambda: fn(y[:n_time]))
        per = t / n_time
        rows.append((name, n_time, t, per))
    if rows:
        print(f"\n{'rainflow':<28}{'samples':>12}{'time (s)':>12}{'ns/sample':>12}{'stochvib x':>12}")
        rs = rust["rainflow_s"] / args.n
        print(f"{'stochvib':<28}{args.n:>12}{rust['rainflow_s']:>12.3f}{rs * 1e9:>12.2f}{1.0:>12.1f}")
        for name, n_time, t, per in rows:
            print(f"{name:<28}{n_time:>12}{t:>12.3f}{per * 1e9:>12.2f}{per / rs:>12.1f}")
        # the fastest package, per sample (the Python loops are timed on a prefix)
        name, n_time, t, per = min(rows, key=lambda r: r[3])
        table.append(dict(job="rainflow count + Miner, per sample", size=f"{args.n} samples",
                          ours_s=rust["rainflow_s"] / args.n, peer=f"{name} ({n_time} samples)", peer_s=per))
    try:
        import fatpack

        t, _ = best_of(1, lambda: fatpack.find_rainflow_cycles(fatpack.find_reversals(y)[0]))
        print(f"(fatpack as documented, find_reversals with k = 64 levels, quantised count: {t:.3f} s for "
              f"{args.n} samples = {t / args.n * 1e9:.2f} ns/sample, x{t / rust['rainflow_s']:.1f})")
    except ImportError:
        pass

    # --- Dirlik ---
    try:
        import FLife
    except ImportError:
        print("FLife: not installed")
        write_rows(args.rows, table)
        return
    print(f"\nDirlik, single-mode density (fn = {SDOF_FN} Hz, zeta = {SDOF_ZETA}), k = {SN_K}, C = {SN_C:g}")
    print(f"stochvib: moments by quadrature + damage {rust['dirlik_density_s'] * 1e6:.1f} us, damage from "
          f"moments {rust['dirlik_moments_s'] * 1e9:.0f} ns, life {rust['dirlik_life_s']:.10e} s")
    for step in (0.1, 0.01):
        f = np.linspace(0.0, SDOF_F_MAX, int(round(SDOF_F_MAX / step)) + 1)
        g = sdof_density(f)

        def flife_all():
            sd = FLife.SpectralData(input={"PSD": g, "f": f})
            return float(FLife.Dirlik(sd).get_life(C=SN_C, k=SN_K))

        t_all, life = best_of(max(args.reps, 5), flife_all)
        sd = FLife.SpectralData(input={"PSD": g, "f": f})
        t_dk, _ = best_of(max(args.reps, 5), lambda: float(FLife.Dirlik(sd).get_life(C=SN_C, k=SN_K)))
        t_tab, life_tab = rust["dirlik_table"][str(step)]
        print(f"PSD tabulated on a {step} Hz grid ({len(f)} points):")
        print(f"  stochvib from the table (exact moments of the linear interpolant) + Dirlik: {t_tab * 1e6:.1f} us, "
              f"life {life_tab:.10e} s")
        print(f"  FLife SpectralData + Dirlik: {t_all * 1e6:.0f} us (x{t_all / t_tab:.0f} the table route, "
              f"x{t_all / rust['dirlik_density_s']:.0f} the quadrature route); Dirlik from moments {t_dk * 1e6:.1f} us "
              f"(x{t_dk / rust['dirlik_moments_s']:.0f}); life {life:.10e} s, relative difference to stochvib's "
              f"table {abs(life / life_tab - 1):.1e}, to its quadrature {abs(life / rust['dirlik_life_s'] - 1):.1e}")
        table.append(dict(job="Dirlik life from a tabulated PSD", size=f"{len(f)} points", ours_s=t_tab,
                          peer="FLife SpectralData + Dirlik", peer_s=t_all))
    write_rows(args.rows, table)


def write_rows(path, table):
    """The rows of benches/RESULTS.md's table as JSON (run.sh), when asked for."""
    if path:
        cmd = "`fatigue.py run`"
        with open(path, "w") as f:
            json.dump([dict(r, cmd=cmd) for r in table], f, indent=1)


def reference(_args):
    """FLife lives for tests/fatigue.rs::methods_agree_with_flife_on_a_bimodal_density."""
    import FLife

    f = np.linspace(0.0, 200.0, 2_000_001)
    d = 1e-9  # resolve the jumps of the bands by 1e-9 Hz steps, so that the trapezoid rule is exact there
    f = np.sort(np.concatenate([f, [20 - d, 60 + d, 100 - d, 120 + d]]))
    g = np.where((f >= 20) & (f <= 60), 0.125, 0.0) + np.where((f >= 100) & (f <= 120), 0.1, 0.0)
    sd = FLife.SpectralData(input={"PSD": g, "f": f})
    w = 2 * np.pi
    exact = [0.125 * (60 ** (j + 1) - 20 ** (j + 1)) / (j + 1) + 0.1 * (120 ** (j + 1) - 100 ** (j + 1)) / (j + 1) for j in range(5)]
    print("FLife moments / exact - 1:", sd.moments / np.array([e * w ** j for j, e in enumerate(exact)]) - 1)
    for C, k in [(1e12, 3.0), (1.8e22, 7.3)]:
        lives = [
            FLife.Narrowband(sd).get_life(C, k),
            FLife.WirschingLight(sd).get_life(C, k),
            FLife.Dirlik(sd).get_life(C, k),
            FLife.TovoBenasciutti(sd).get_life(C, k, method="method 2"),
            FLife.TovoBenasciutti(sd).get_life(C, k, method="method 1"),
            FLife.ZhaoBaker(sd).get_life(C, k, method="method 1"),
            FLife.ZhaoBaker(sd).get_life(C, k, method="method 2"),
        ]
        print(f"k = {k}, C = {C:g}: NB, WL, Dirlik, TB2005, TB2002, ZB general, ZB k=3:")
        print("    " + ", ".join(repr(float(x)) for x in lives))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--n", type=int, default=100_000_000)
    r.add_argument("--reps", type=int, default=3)
    r.add_argument("--check", type=int, default=1_000_000)
    r.add_argument("--no-build", action="store_true", help="use the example binary as already built")
    r.add_argument("--profile", default="release", help="the cargo profile of the Rust side (run.sh --smoke: test)")
    r.add_argument("--rows", default=None, help="also write the rows of benches/RESULTS.md's table to this JSON file")
    r.add_argument("--dir", default=os.path.join(os.environ.get("TMPDIR", "/tmp"), "stochvib-fatigue"))
    sub.add_parser("reference")
    a = p.parse_args()
    {"run": run, "reference": reference}[a.cmd](a)


if __name__ == "__main__":
    sys.exit(main())
