#!/usr/bin/env python3
"""The transient Monte Carlo of the accelerating quarter car: `stochvib transient --monte-carlo R` against
benches/compare/transient_mc.py (the same generator and integrator in numpy, vectorised over the
realizations, one BLAS thread), both as whole processes, wall and CPU time (user + sys of the child).

    python3 benches/compare/transient.py --binary target/release/stochvib [--realizations 10000] [--rows FILE]

The scenario is data/quarter-car-accelerating.toml without [analysis.comfort] (its weighting filter adds
states that the numpy version does not have); --rows writes the rows of benches/RESULTS.md's table."""
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
    a = ap.parse_args()
    r = a.realizations
    with tempfile.TemporaryDirectory() as d:
        qc = scenario(d)
        ours = timed([a.binary, "transient", qc, "--monte-carlo", str(r), "--shard-size", str(min(r, 1000)),
                      "-o", os.path.join(d, "qc.h5")])
        exact = timed([a.binary, "transient", qc])
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    peer = timed([sys.executable, os.path.join(HERE, "transient_mc.py"), str(r)], env)
    print(f"ours: {ours[0]:.3f} s wall, {ours[1]:.3f} s CPU (exact route alone {exact[1]:.3f} s CPU); "
          f"numpy: {peer[0]:.3f} s wall, {peer[1]:.3f} s CPU; {peer[2].strip()}")
    if a.rows:
        size = f"{r} x 1200 steps"
        cmd = "`transient.py`"
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
