#!/usr/bin/env bash
# The Monte Carlo routes against their floors (`examples/mc_floor`), over several processes. One process
# times every job in alternating rounds and keeps each job's best round; but on this kind of machine a job's
# best differs between processes by up to 30 % (the same binary, one mode per process: most likely where its
# buffers land in the physically indexed caches), which moves a route / floor ratio by more than what is being measured.
# So: P processes one after the other, and per job the best and the median of the processes' bests; the
# ratios from the bests (each side at its best placement) and from the medians.
#
#   bash benches/compare/mc_floor.sh                 # P = 7 processes, 5 rounds each, 200 x 2^16
#   P=3 ROUNDS=3 bash benches/compare/mc_floor.sh    # quicker
#   BIN=/path/to/mc_floor bash benches/compare/mc_floor.sh   # another build (default: release, built)
#   ARGS="--realizations 50" bash benches/compare/mc_floor.sh   # passed to every process
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
cd "$root"
procs="${P:-7}"
rounds="${ROUNDS:-5}"
case "$procs$rounds" in *[!0-9]*) echo "mc_floor.sh: P and ROUNDS are positive integers (P=$procs ROUNDS=$rounds)" >&2; exit 2 ;; esac
bin="${BIN:-}"
if [ -z "$bin" ]; then
    cargo build --locked --release --quiet --features campaigns --example mc_floor
    bin="${CARGO_TARGET_DIR:-$root/target}/release/examples/mc_floor"
fi
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
for _ in $(seq "$procs"); do
    # shellcheck disable=SC2086 # ARGS is a list of words
    "$bin" --rounds "$rounds" ${ARGS:-} >>"$out"
done
head -n 1 "$out" | sed "s/, load .*//"
echo "$procs processes one after the other; per job: the best and the median of the processes' bests (CPU time)"
echo
python3 - "$out" <<'EOF'
import statistics, sys
jobs = {}
for line in open(sys.argv[1]):
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if len(cells) == 5 and cells[1].endswith(" ms"):
        jobs.setdefault(cells[0], []).append(float(cells[1].split()[0]))
names = list(jobs)
print("| job | best | median | spread (max / min) | route / floor, bests | route / floor, medians |")
print("| --- | --- | --- | --- | --- | --- |")
for k, name in enumerate(names):
    t = jobs[name]
    best, med = min(t), statistics.median(t)
    if k % 2 == 0:
        fl = jobs[names[k + 1]]
        ratio = f"{best / min(fl):.3f}x | {med / statistics.median(fl):.3f}x"
    else:
        ratio = "floor | floor"
    print(f"| {name} | {best:.1f} ms | {med:.1f} ms | {max(t) / best:.2f} | {ratio} |")
EOF
