#!/usr/bin/env python3
"""The rows of benches/RESULTS.md's table from the JSON of the harnesses that print their own (run.sh):

    python3 benches/compare/rows.py nonlinear DIR  > rows-nonlinear.json   # nonlinear.sh's OUT directory
    python3 benches/compare/rows.py records FILE   > rows-records.json     # records.py run's stdout
    python3 benches/compare/rows.py floors DIR     > rows-floors.json      # DIR/floors-*.json: one per process

Each row: job, size, ours_s, peer, peer_s, cmd (compare.py summary adds the machine state and the ratio)."""
import json
import sys


def nonlinear(d):
    rs, py = json.load(open(f"{d}/rust.json")), json.load(open(f"{d}/python.json"))
    one = rs["jobs"]["route2_1_threads"]
    size = f"{rs['realizations']} x {rs['samples']} (+{rs['burn']} burn-in)"
    cmd = "`nonlinear.sh`"
    peer = f"numpy, {py['chunk']} realizations at a time"
    return [
        dict(job="nonlinear MC (route 2), quarter car with stops, 1 thread (wall)", size=size,
             ours_s=one["seconds"], peer=peer, peer_s=py["seconds"], cmd=cmd),
        dict(job="nonlinear MC (route 2), 1 thread (CPU time)", size=size, ours_s=one["cpu_seconds"],
             peer=peer + " (CPU time)", peer_s=py["cpu_seconds"], cmd=cmd),
    ]


def floors(d):
    """The Monte Carlo routes against their floors over P processes of `compare_rust --only floors` (each the
    best of its alternating rounds; a job's best differs between processes by up to 30 %, so one process is
    not a measurement): per route the best over the processes against the floor's best, and the medians."""
    import glob
    import statistics
    runs = [json.load(open(f)) for f in sorted(glob.glob(f"{d}/floors-*.json"))]
    if not runs:
        return []
    size = f"{runs[0]['realizations']} x {runs[0]['samples']}, {len(runs)} processes"
    cmd = "`compare_rust --only floors` in P processes (run.sh; `mc_floor.sh` per job)"
    rows = []
    for route, floor, job in [("mc_pipeline_fft", "mc_floor", "MC one FFT / its floor (normals + 1 irfft)"),
                              ("mc_exact", "mc_exact_floor", "MC exact route / its floor (its normals)"),
                              ("mc_streamed", "mc_streamed_floor",
                               "MC streamed route / its floor (normals + FFT pair per segment)")]:
        t = [r["jobs"][route]["cpu_seconds"] for r in runs]
        f = [r["jobs"][floor]["cpu_seconds"] for r in runs]
        rows.append(dict(job=f"{job}, best of the processes", size=size, ours_s=min(t),
                         peer="Rust floor, best of the same processes", peer_s=min(f), cmd=cmd))
        rows.append(dict(job=f"{job}, median of the processes", size=size, ours_s=statistics.median(t),
                         peer="Rust floor, median of the same processes", peer_s=statistics.median(f), cmd=cmd))
    return rows


def records(path):
    rows = []
    for r in json.load(open(path)):
        if "scipy_s" not in r:
            continue
        size = f"{r['samples']} samples ({r['hours']:g} h)"
        peer = "scipy sosfilt + numpy, streamed"
        rows.append(dict(job="`stochvib exposure`, 3 axes (wall)", size=size, ours_s=r["ours_s"], peer=peer,
                         peer_s=r["scipy_s"], cmd="`records.py run`"))
        rows.append(dict(job="`stochvib exposure`, 3 axes (CPU time)", size=size, ours_s=r["ours_cpu_s"],
                         peer=peer + " (CPU time)", peer_s=r["scipy_cpu_s"], cmd="`records.py run`"))
    return rows


if __name__ == "__main__":
    kind, arg = sys.argv[1], sys.argv[2]
    print(json.dumps({"nonlinear": nonlinear, "records": records, "floors": floors}[kind](arg), indent=1))
