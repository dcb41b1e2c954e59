#!/usr/bin/env python3
"""Measured records: `stochvib exposure` and `stochvib fatigue` on long HDF5 records against scipy.signal.

    python3 benches/compare/records.py run --binary target/release/stochvib --hours 1,2 [--dir DIR]
    python3 benches/compare/records.py run ... --rainflow 100000000,200000000     # also streamed rainflow
    python3 benches/compare/records.py make FILE --hours H [--seed 1]        # a three-axis record, 1 kHz
    python3 benches/compare/records.py make-stress FILE --samples N [--seed 1]
    python3 benches/compare/records.py scipy FILE --sos SOS.json             # the scipy evaluation alone

`make` writes a seeded three-axis seat record at 1 kHz (datasets x, y, z of f64 in m/s^2 with the
`sample_rate` attribute; each a low-passed Gaussian noise with a 4 Hz resonance, written block by block).
`run` writes records of the given lengths (kept in --dir, reused when present), and for each length runs
1. `stochvib exposure FILE --json` (x, y on Wd, z on Wk, seat surface): the digital weighting, a_w, VDV,
   peak, the linear running r.m.s. (tau = 1 s) and its MTVV, the exponential running r.m.s., the
   one-third-octave bands (streamed Welch) and the envelope of the picture;
2. the scipy peer `records.py scipy FILE`: the same second-order sections (printed by
   `stochvib weighting NAME --sample-rate 1000 --json`, gain folded into the first section) through
   `scipy.signal.sosfilt` block by block with the state carried (`zi`, started at rest on the first sample
   like ours, `sosfilt_zi(sos)*x[0]`), then per block sum y^2, sum y^4 (VDV), max |y|, the linear running
   mean square over the last 1000 samples (cumsum over the previous 999 samples and the block) and its
   maximum, and the exponential one (`lfilter` of y^2 with its state carried). It computes no band values
   and no envelope (less work than ours).
Both read the same file through HDF5 blocks of 65536 samples a dataset (h5py `read_direct` into one buffer,
ours a hyperslab a dataset) and run under `/usr/bin/time -v`: wall time and peak RSS. Both sides' a_w, VDV
and MTVV are printed and must agree to 1e-9 (relative). The rainflow rows run `stochvib fatigue` on a one-
channel stress record (a resonant AR(2) in MPa) of each length: wall time, peak RSS and samples per second.
Each exposure record is timed --reps times (default 3) on each side, alternated, and each side's fastest run
kept. On a shared machine: compare the ratio of one run, not absolute times; the load average is printed.
"""
import argparse
import json
import os
import re
import resource
import subprocess
import sys
import time

import numpy as np

FS = 1000.0
BLOCK = 65536
AXES = (("x", "Wd"), ("y", "Wd"), ("z", "Wk"))


# --- records ------------------------------------------------------------------------------------------------
def ar2(f0_hz, zeta):
    """Denominator of an AR(2) resonance at f0 (Hz) with damping ratio zeta, sampled at FS (poles of the
    continuous resonance mapped by z = e^{s/FS})."""
    w0 = 2 * np.pi * f0_hz / FS
    r = np.exp(-zeta * w0)
    return [1.0, -2 * r * np.cos(w0 * np.sqrt(1 - zeta * zeta)), r * r]


def make(path, hours, seed):
    """A three-axis seat record: per axis an AR(2) resonance at 4 Hz (zeta 0.2) driven by Gaussian noise,
    block by block (memory one block)."""
    import h5py
    from scipy.signal import lfilter

    n = int(round(hours * 3600 * FS))
    rng = np.random.default_rng(seed)
    a = ar2(4.0, 0.2)
    tmp = path + ".part"
    with h5py.File(tmp, "w") as f:
        dsets = {}
        for name, _ in AXES:
            d = f.create_dataset(name, shape=(n,), dtype="f8")
            d.attrs["unit"] = "m/s^2"
            d.attrs["sample_rate"] = FS
            dsets[name] = d
        zi = {name: np.zeros(2) for name, _ in AXES}
        scale = {"x": 0.001, "y": 0.0008, "z": 0.002}
        for start in range(0, n, 1 << 20):
            m = min(1 << 20, n - start)
            for name, _ in AXES:
                y, zi[name] = lfilter([scale[name]], a, rng.standard_normal(m), zi=zi[name])
                dsets[name][start : start + m] = y
    os.replace(tmp, path)


def make_stress(path, samples, seed):
    """A one-channel stress record in MPa: a resonant AR(2) (50 Hz at 1 kHz, zeta 0.05) plus a mean."""
    import h5py
    from scipy.signal import lfilter

    rng = np.random.default_rng(seed)
    a = ar2(50.0, 0.05)
    tmp = path + ".part"
    with h5py.File(tmp, "w") as f:
        d = f.create_dataset("s", shape=(samples,), dtype="f8")
        d.attrs["unit"] = "MPa"
        d.attrs["sample_rate"] = FS
        zi = np.zeros(2)
        for start in range(0, samples, 1 << 20):
            m = min(1 << 20, samples - start)
            y, zi = lfilter([1.0], a, rng.standard_normal(m), zi=zi)
            d[start : start + m] = 30.0 + y
    os.replace(tmp, path)


# --- the scipy peer -----------------------------------------------------------------------------------------
def sos_of(binary, weighting):
    out = subprocess.run(
        [binary, "weighting", weighting, "--sample-rate", str(FS), "--json"], check=True, capture_output=True, text=True
    ).stdout
    d = json.loads(out)["digital"]
    sos = np.array([q["b"] + [1.0] + q["a"] for q in d["sections"]])
    sos[0, :3] *= d["gain"]
    return sos


def scipy_exposure(path, sos_by_weighting):
    """The scipy evaluation of the three axes (see the module docs), streamed."""
    import h5py
    from scipy.signal import lfilter, sosfilt, sosfilt_zi

    tau_n = int(round(1.0 * FS))
    alpha = np.exp(-1.0 / FS)
    out = {}
    with h5py.File(path, "r") as f:
        n = f["x"].shape[0]
        buf = np.empty(BLOCK)
        state = {}
        for name, w in AXES:
            sos = np.array(sos_by_weighting[w])
            state[name] = dict(sos=sos, zi=None, s2=0.0, s4=0.0, peak=0.0, tail=np.zeros(0), mx=0.0, ezi=np.zeros(1), emx=0.0)
        for start in range(0, n, BLOCK):
            m = min(BLOCK, n - start)
            for name, _ in AXES:
                st = state[name]
                x = buf[:m]
                f[name].read_direct(x, np.s_[start : start + m])
                if st["zi"] is None:
                    st["zi"] = sosfilt_zi(st["sos"]) * x[0]
                y, st["zi"] = sosfilt(st["sos"], x, zi=st["zi"])
                y2 = y * y
                st["s2"] += y2.sum()
                st["s4"] += (y2 * y2).sum()
                st["peak"] = max(st["peak"], np.abs(y).max())
                # linear running mean square over the last tau_n samples
                z = np.concatenate((st["tail"], y2))
                if len(z) >= tau_n:
                    c = np.concatenate(([0.0], np.cumsum(z)))
                    st["mx"] = max(st["mx"], (c[tau_n:] - c[:-tau_n]).max())
                st["tail"] = z[-(tau_n - 1) :]
                e, st["ezi"] = lfilter([1 - alpha], [1.0, -alpha], y2, zi=st["ezi"])
                st["emx"] = max(st["emx"], e.max())
        for name, _ in AXES:
            st = state[name]
            out[name] = dict(
                a_w=float(np.sqrt(st["s2"] / n)),
                vdv=float((st["s4"] / FS) ** 0.25),
                peak=float(st["peak"]),
                mtvv=float(np.sqrt(st["mx"] / tau_n)),
                mtvv_exponential=float(np.sqrt(st["emx"])),
            )
    return out


# --- timing -------------------------------------------------------------------------------------------------
def timed(cmd):
    """Runs cmd under /usr/bin/time -v: (wall s, peak RSS MiB, CPU s, stdout). The CPU time (user + system)
    is the waited child's rusage, to the microsecond (GNU time prints hundredths of a second, which a
    smoke-sized record undercuts); it includes GNU time's own, about a millisecond."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    p = subprocess.run(["/usr/bin/time", "-v"] + cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"records.py: {' '.join(cmd)} failed:\n{p.stderr[-3000:]}")
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1)) / 1024
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, rss, cpu, p.stdout


def load():
    return open("/proc/loadavg").read().split()[0]


def run(args):
    os.makedirs(args.dir, exist_ok=True)
    sos = {w: sos_of(args.binary, w).tolist() for w in ("Wd", "Wk")}
    sos_file = os.path.join(args.dir, "sos.json")
    json.dump(sos, open(sos_file, "w"))
    rows = []
    for hours in [float(h) for h in args.hours.split(",") if h]:
        path = os.path.join(args.dir, f"seat-{hours:g}h.h5")
        if not os.path.exists(path):
            print(f"records.py: writing {path}", file=sys.stderr)
            make(path, hours, args.seed)
        n = int(round(hours * 3600 * FS))
        subprocess.run(["cat", path], stdout=subprocess.DEVNULL, check=True)  # into the page cache, both sides alike
        # alternated, each side's fastest run (wall) kept: one run of each on this shared machine read
        # 0.21-0.31 s for the same binary
        runs = [(timed([args.binary, "exposure", path, "--json"]),
                 timed([sys.executable, os.path.abspath(__file__), "scipy", path, "--sos", sos_file]))
                for _ in range(args.reps)]
        ours = min((r[0] for r in runs), key=lambda t: t[0])
        peer = min((r[1] for r in runs), key=lambda t: t[0])
        got, want = json.loads(ours[3]), json.loads(peer[3])
        worst = 0.0
        for a in got["axes"]:
            p = want[a["channel"]]
            for ours_v, theirs in (
                (a["metrics"]["a_w"], p["a_w"]),
                (a["metrics"]["vdv"], p["vdv"]),
                (a["metrics"]["mtvv"], p["mtvv"]),
                (a["mtvv_exponential"], p["mtvv_exponential"]),
                (a["metrics"]["peak"], p["peak"]),
            ):
                worst = max(worst, abs(ours_v - theirs) / abs(theirs))
        if worst > 1e-9:
            sys.exit(f"records.py: the two sides disagree ({worst:.2e} relative) on {path}")
        rows.append(
            dict(
                job="exposure, 3 axes",
                hours=hours,
                samples=3 * n,
                ours_s=ours[0],
                ours_cpu_s=ours[2],
                ours_rss_mib=ours[1],
                scipy_s=peer[0],
                scipy_cpu_s=peer[2],
                scipy_rss_mib=peer[1],
                ratio=peer[0] / ours[0],
                agree_rel=worst,
                a_w=[a["metrics"]["a_w"] for a in got["axes"]],
                load=load(),
            )
        )
        print(json.dumps(rows[-1]), file=sys.stderr)
    for samples in [int(float(s)) for s in args.rainflow.split(",") if s]:
        path = os.path.join(args.dir, f"stress-{samples}.h5")
        if not os.path.exists(path):
            print(f"records.py: writing {path}", file=sys.stderr)
            make_stress(path, samples, args.seed)
        subprocess.run(["cat", path], stdout=subprocess.DEVNULL, check=True)
        ours = timed([args.binary, "fatigue", path, "--sn-slope", "5", "--sn-range", "160 MPa", "--json"])
        got = json.loads(ours[3])
        rows.append(
            dict(
                job="fatigue (rainflow + Welch + spectral methods)",
                samples=samples,
                ours_s=ours[0],
                ours_cpu_s=ours[2],
                ours_rss_mib=ours[1],
                samples_per_s=samples / ours[0],
                full_cycles=got["full_cycles"],
                load=load(),
            )
        )
        print(json.dumps(rows[-1]), file=sys.stderr)
    print(json.dumps(rows, indent=1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("--binary", required=True)
    r.add_argument("--hours", default="1,2")
    r.add_argument("--reps", type=int, default=3, help="runs of each side per record, alternated (the fastest kept)")
    r.add_argument("--rainflow", default="")
    r.add_argument("--dir", default="/tmp/stochvib-records-bench")
    r.add_argument("--seed", type=int, default=1)
    m = sub.add_parser("make")
    m.add_argument("file")
    m.add_argument("--hours", type=float, required=True)
    m.add_argument("--seed", type=int, default=1)
    ms = sub.add_parser("make-stress")
    ms.add_argument("file")
    ms.add_argument("--samples", type=float, required=True)
    ms.add_argument("--seed", type=int, default=1)
    s = sub.add_parser("scipy")
    s.add_argument("file")
    s.add_argument("--sos", required=True)
    a = ap.parse_args()
    if a.cmd == "run":
        run(a)
    elif a.cmd == "make":
        make(a.file, a.hours, a.seed)
    elif a.cmd == "make-stress":
        make_stress(a.file, int(a.samples), a.seed)
    else:
        print(json.dumps(scipy_exposure(a.file, json.load(open(a.sos)))))


if __name__ == "__main__":
    main()
