#!/usr/bin/env python3
"""The transient Monte Carlo of the accelerating quarter car: `stochvib transient --monte-carlo R` against
benches/compare/transient_mc.py (the same generator and integrator in numpy, vectorised over the
realizations, one BLAS thread), both as whole processes, wall and CPU time (user + sys of the child).

    python3 benches/compare/transient.py --binary target/release/stochvib [--realizations 10000] [--reps 5]
        [--ours-per-rep 5] [--rows FILE]

The scenario is data/quarter-car-accelerating.toml without [analysis.comfort] (its weighting filter adds
states that the numpy version does not have); --rows writes the rows of benches/RESULTS.md's table.

The sides are alternated --reps times; in each, ours runs --ours-per-rep times in a row (≈ 0.12 s each)
and numpy once (≈ 1.2 s), so that each side is sampled over about the same stretch of time and a burst of
load on a shared machine (it has made single runs of ours 40 % slower, CPU time included) weighs on a
median of ours no more than on numpy's, which averages over its longer run. Each side's median is reported,
with every run."""
import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))


def timed(args, env=None):
    """(wall s, CPU s of the child, stdout) of one process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    out = subprocess.run(args, check=True, capture_output=True, text=True, env=env, cwd=ROOT).stdout
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), out


def scenario(d):
    """The accelerating quarter car without its comfort axes, written into d."""
    text = open(os.path.join(ROOT, "data", "quarter-car-accelerating.toml")).read()
    # drop [analysis.comfort] and its [[analysis.comfort.axis]] tables (up to the next other table)
    text = re.sub(r"(?ms)^\[\[?analysis\.comfort[^\n]*\n.*?(?=^\[(?!\[?analysis\.comfort))", "", text)
    path = os.path.join(d, "qc.toml")
    open(path, "w").write(text)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--binary", default="target/release/stochvib")
    ap.add_argument("--realizations", type=int, default=10000)
    ap.add_argument("--rows", default=None)
    ap.add_argument("--reps", type=int, default=5, help="alternations of the two sides; the medians are reported")
    ap.add_argument("--ours-per-rep", type=int, default=5, help="runs of ours in each alternation")
    a = ap.parse_args()
    if a.reps < 1 or a.ours_per_rep < 1:
        ap.error(f"--reps {a.reps}, --ours-per-rep {a.ours_per_rep}: each must be at least 1")
    r = a.realizations
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    runs, peers = [], []
    with tempfile.TemporaryDirectory() as d:
        qc = scenario(d)
        exact = timed([a.binary, "transient", qc])
        # alternated (ours, numpy, ours, ...) so that a change of load hits both sides; a fresh run file each time
        for k in range(a.reps):
            for j in range(a.ours_per_rep):
                runs.append(timed([a.binary, "transient", qc, "--monte-carlo", str(r), "--shard-size",
                                   str(min(r, 1000)), "-o", os.path.join(d, f"qc{k}-{j}.h5")]))
            peers.append(timed([sys.executable, os.path.join(HERE, "transient_mc.py"), str(r)], env))
    median = lambda xs: sorted(xs)[len(xs) // 2]
    ours = (median([x[0] for x in runs]), median([x[1] for x in runs]))
    peer = (median([x[0] for x in peers]), median([x[1] for x in peers]), peers[-1][2])
    print(f"ours (median of {len(runs)}): {ours[0]:.3f} s wall, {ours[1]:.3f} s CPU (runs: "
          f"{', '.join(f'{x[0]:.3f}' for x in runs)} s; exact route alone {exact[1]:.3f} s CPU); numpy (median of "
          f"{len(peers)}): {peer[0]:.3f} s wall, {peer[1]:.3f} s CPU (runs: {', '.join(f'{x[0]:.3f}' for x in peers)} "
          f"s); {peer[2].strip()}")
    if a.rows:
        size = f"{r} x 1200 steps"
        cmd = f"`transient.py --reps {a.reps} --ours-per-rep {a.ours_per_rep}` (medians, alternated)"
        rows = [
            dict(job="transient MC, accelerating quarter car (wall)", size=size, ours_s=ours[0],
                 peer="numpy (vectorised over realizations, 1 BLAS thread)", peer_s=peer[0], cmd=cmd),
            dict(job="transient MC, accelerating quarter car (CPU time)", size=size, ours_s=ours[1],
                 peer="numpy (process CPU time)", peer_s=peer[1], cmd=cmd),
        ]
        with open(a.rows, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
