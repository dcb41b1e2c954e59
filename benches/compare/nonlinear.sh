#!/usr/bin/env bash
# Route 2 (nonlinear Monte Carlo) of data/quarter-car-bump-stops.toml against the numpy implementation of
# the same integrator and step vectorised over realizations (benches/compare/nonlinear.py), its 2-thread
# scaling, its cost per sample against the linear run of the same model (on the ISO road, and on a rational
# road where both take their exact routes), and route 1 per parameter point;
# prints the table of benches/RESULTS.md (section "Nonlinear machines") and, without --no-write, writes it
# there between its markers.
#
#   bash benches/compare/nonlinear.sh                # R = 512 realizations x 30 s, best of 3 (~5 min)
#   R=64 T=10 REPS=1 bash benches/compare/nonlinear.sh --no-write    # a quick look
#   CHUNK=128 bash benches/compare/nonlinear.sh      # numpy on 128 realizations at a time (default: all)
#   PROFILE=test bash benches/compare/nonlinear.sh   # the Rust side in the test profile (opt-level 2, debug
#                                                    # assertions on) when a release build is out of reach
#   NO_BUILD=1 bash benches/compare/nonlinear.sh     # the example binary as it is (no cargo build)
#   PY_PROCS=1 bash benches/compare/nonlinear.sh     # numpy in 1 process (default: the best of 3 processes,
#                                                    # each best of REPS: its time is bimodal between processes)
#   bash benches/compare/nonlinear.sh --scaling      # only route 2 and the calibration spin loops on 1 and
#                                                    # 2 threads (no numpy, nothing written): the scaling
#                                                    # rows, for an idle machine (~1 min at R=512, T=30 s)
#   BEFORE=path/to/compare_nonlinear BEFORE_LABEL="main at abc1234" bash benches/compare/nonlinear.sh
#                                                    # also an earlier build of the example, run just before
#                                                    # ours on the same job: a before/after row, and whether
#                                                    # the statistics' CRC-32 is the same (bit-identical)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
write=1 scaling=0
for a in "$@"; do
    case "$a" in
    --no-write) write=0 ;;
    --scaling) scaling=1 write=0 ;;
    *) echo "nonlinear.sh: unknown option $a" >&2; exit 2 ;;
    esac
done
r="${R:-512}" t="${T:-30}" reps="${REPS:-3}" chunk="${CHUNK:-0}" profile="${PROFILE:-release}"
out="${OUT:-$(mktemp -d)}"
mkdir -p "$out"
cd "$root"
python3 -c "import numpy, scipy" || { echo "nonlinear.sh: needs numpy and scipy (see run.sh)" >&2; exit 1; }
dir=$([ "$profile" = release ] && echo release || echo debug)
bin="${CARGO_TARGET_DIR:-$root/target}/$dir/examples/compare_nonlinear"
if [ "${NO_BUILD:-0}" = 1 ]; then
    echo "nonlinear.sh: the Rust side as built ($bin, $profile profile)" >&2
else
    echo "nonlinear.sh: building the Rust side ($profile profile)" >&2
    cargo build --locked --profile "$profile" --quiet --example compare_nonlinear
fi
echo "$profile" >"$out/profile.txt"
cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "$(nproc) cores, $cpu, $(awk '/MemTotal/ {printf "%.1f GiB", $2/1048576}' /proc/meminfo)" >"$out/machine.txt"
if [ "$scaling" = 1 ]; then
    load0="$(cut -d' ' -f1 /proc/loadavg)"
    echo "nonlinear.sh: route 2 and the spin loops on 1 and 2 threads, $r realizations x $t s" >&2
    "$bin" --realizations "$r" --duration "$t" --reps "$reps" --scaling >"$out/scaling.json"
    python3 - "$out/scaling.json" "$(cat "$out/machine.txt")" "$load0" "$(cut -d' ' -f1 /proc/loadavg)" <<'PY'
import json, sys
d, machine, l0, l1 = json.load(open(sys.argv[1])), sys.argv[2], sys.argv[3], sys.argv[4]
j = d["jobs"]
print(f"Thread scaling of route 2 ({d['realizations']} x {d['samples']} samples, best of the repetitions); "
      f"machine: {machine}; load average {l0} before, {l1} after (an idle machine reads < 0.5).")
print()
print("| job | 1 thread (wall / CPU) | 2 threads (wall / CPU) | speed-up (wall) |")
print("|---|---|---|---|")
for name, key in (("route 2", "route2"), ("calibration spin loops", "spin")):
    a, b = j[f"{key}_1_threads"], j[f"{key}_2_threads"]
    print(f"| {name} | {a['seconds']:.3g} s / {a['cpu_seconds']:.3g} s | {b['seconds']:.3g} s / {b['cpu_seconds']:.3g} s "
          f"| {a['seconds'] / b['seconds']:.3g}x |")
PY
    echo "nonlinear.sh: JSON in $out" >&2
    exit 0
fi
if [ -n "${BEFORE:-}" ]; then
    cut -d' ' -f1 /proc/loadavg >"$out/load-before.txt"
    echo "nonlinear.sh: the earlier build $BEFORE, $r realizations x $t s" >&2
    "$BEFORE" --realizations "$r" --duration "$t" --reps "$reps" >"$out/before.json"
    echo "${BEFORE_LABEL:-the earlier build}" >"$out/before-label.txt"
fi
cut -d' ' -f1 /proc/loadavg >"$out/load-rust.txt"
echo "nonlinear.sh: Rust side, $r realizations x $t s" >&2
"$bin" --realizations "$r" --duration "$t" --reps "$reps" >"$out/rust.json"
read -r n burn dt < <(python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(d['samples'], d['burn'], d['dt'])" "$out/rust.json")
cut -d' ' -f1 /proc/loadavg >"$out/load-python.txt"
# numpy's time is bimodal between processes on these VMs (1.47 s or 2.48 s for R = 512, T = 30 s in
# consecutive runs of the same command, the same within each process): the peer is its best process
procs="${PY_PROCS:-3}"
echo "nonlinear.sh: numpy side, the same $r x ($burn + $n) steps of $dt s, best of $procs processes" >&2
for i in $(seq 1 "$procs"); do
    python3 "$here/nonlinear.py" --realizations "$r" --samples "$n" --burn "$burn" --dt "$dt" --chunk "$chunk" \
        --reps "$reps" >"$out/python-$i.json"
done
python3 - "$out" "$procs" <<'PY'
import json, sys
out, procs = sys.argv[1], int(sys.argv[2])
runs = [json.load(open(f"{out}/python-{i}.json")) for i in range(1, procs + 1)]
best = min(runs, key=lambda d: d["seconds"])
best["process_seconds"] = [d["seconds"] for d in runs]
json.dump(best, open(f"{out}/python.json", "w"))
PY
python3 - "$out" <<'PY' >"$out/table.md"
import json, os, subprocess, sys, datetime
out = sys.argv[1]
rs, py = json.load(open(f"{out}/rust.json")), json.load(open(f"{out}/python.json"))
j = rs["jobs"]
machine, lr, lp, profile = (open(f"{out}/{f}").read().strip()
                             for f in ("machine.txt", "load-rust.txt", "load-python.txt", "profile.txt"))
def t(s):
    return f"{s * 1e3:.3g} ms" if s < 1 else f"{s:.3g} s"
def pair(d):
    return f"{t(d['seconds'])} (CPU {t(d['cpu_seconds'])})"
size = f"{rs['realizations']} x {rs['samples']} (+{rs['burn']} burn-in), dt = {rs['dt']:.3g} s"
cmd = "`bash benches/compare/nonlinear.sh`"
one, two, lin = j["route2_1_threads"], j["route2_2_threads"], j["linear_1_thread"]
rows = [
    ("route 2 vs numpy, 1 thread (wall)", size, pair(one), f"numpy, {py['chunk']} realizations at a time", pair(py),
     f"{py['seconds'] / one['seconds']:.3g}x", f"load {lr} / {lp}"),
    ("route 2 vs numpy, 1 thread (CPU time)", size, t(one["cpu_seconds"]), "numpy (process CPU time)", t(py["cpu_seconds"]),
     f"{py['cpu_seconds'] / one['cpu_seconds']:.3g}x", f"load {lr} / {lp}"),
    ("route 2, 2 threads vs 1", size, pair(two), "ours, 1 thread", pair(one),
     f"{one['seconds'] / two['seconds']:.3g}x", f"load {lr}"),
    ("calibration spin loops, 2 threads vs 1", "64 x 3.1e5 multiply-adds", pair(j["spin_2_threads"]), "ours, 1 thread",
     pair(j["spin_1_threads"]), f"{j['spin_1_threads']['seconds'] / j['spin_2_threads']['seconds']:.3g}x", f"load {lr}"),
    ("route 2 per sample vs linear run per sample, 1 thread", f"{size}; linear: {lin['route']} route", pair(one),
     "linear run of the linear part", pair(lin), f"{lin['seconds'] / one['seconds']:.3g}x (route 2 costs {one['seconds'] / lin['seconds']:.3g}x)", f"load {lr}"),
    ("route 1 per parameter point", "1 point, 3 outputs", pair(j["route1_point"]), "-", "-", "-", f"load {lr}"),
]
e2, le = j["route2_exact_1_thread"], j["linear_exact_1_thread"]
rows.insert(-1, ("route 2 per sample vs the linear exact route, 1 thread", f"{size}; rational road (book-8-45): route 2 "
                 f"{e2['route']}, linear {le['route']} route", pair(e2), "linear run of the linear part", pair(le),
                 f"{le['seconds'] / e2['seconds']:.3g}x (route 2 costs {e2['seconds'] / le['seconds']:.3g}x, CPU "
                 f"{e2['cpu_seconds'] / le['cpu_seconds']:.3g}x)", f"load {lr}"))
if "route1_point_2_threads" in j:  # an example built before this row existed has no such job
    r1, r2 = j["route1_point"], j["route1_point_2_threads"]
    rows.append(("route 1 per parameter point, 2 threads vs 1", "1 point, 3 outputs", pair(r2), "ours, 1 thread",
                 pair(r1), f"{r1['seconds'] / r2['seconds']:.3g}x", f"load {lr}"))
before = None
if os.path.exists(f"{out}/before.json"):
    before = json.load(open(f"{out}/before.json"))
    b1 = before["jobs"]["route2_1_threads"]
    label, lb = (open(f"{out}/{f}").read().strip() for f in ("before-label.txt", "load-before.txt"))
    rows.insert(2, ("route 2, this build vs an earlier one, 1 thread (CPU time)", size, t(one["cpu_seconds"]), label,
                    t(b1["cpu_seconds"]), f"{b1['cpu_seconds'] / one['cpu_seconds']:.3g}x", f"load {lb} / {lr}"))
print(f"One run of {cmd} (R={rs['realizations']}, T={rs['samples'] * rs['dt']:.3g} s) on "
      f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC; machine: {machine}; Rust {profile} profile; "
      f"numpy {py['numpy']}.")
print(f"Checks both sides agree on: σ of the travel {rs['sigma_travel_m']:.4g} m (ours) / {py['sigma_travel_m']:.4g} m (numpy); "
      f"stop contact fraction {rs['stop_contact_fraction']:.3g} / {py['stop_contact_fraction']:.3g}.")
if before is not None:
    same = before["statistics_crc32"] == rs["statistics_crc32"]
    print(f"CRC-32 of every statistic's bits: {before['statistics_crc32']} ({label}) / {rs['statistics_crc32']} (this build): "
          f"{'bit-identical' if same else 'DIFFERENT'}.")
print()
print("| job | size | ours | peer | peer time | ratio peer/ours | machine state |")
print("|---|---|---|---|---|---|---|")
for row in rows:
    print("| " + " | ".join(row) + " |")
PY
cat "$out/table.md"
if [ "$write" = 1 ]; then
    python3 "$here/write_section.py" "$root/benches/RESULTS.md" "$out/table.md" \
        "<!-- nonlinear table: written by benches/compare/nonlinear.sh -->" "<!-- end of nonlinear table -->"
    echo "nonlinear.sh: the table is in benches/RESULTS.md" >&2
fi
echo "nonlinear.sh: JSON in $out" >&2
