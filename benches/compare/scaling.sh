#!/usr/bin/env bash
# Thread scaling and memory of the parallel routes: each route's command line run with RAYON_NUM_THREADS=1
# and =2, wall time, CPU time (user + sys) and peak RSS of the whole process from GNU time, one markdown
# table. A calibration row first: the same shell spin loop twice in a row and twice side by side, whose
# ratio is the second core actually available (2 on an idle 2-core machine); read every "2 threads vs 1"
# ratio against it.
#
#   bash benches/compare/scaling.sh                  # the size of benches/RESULTS.md ("Scaling and memory")
#   SCALE=0.1 bash benches/compare/scaling.sh        # a tenth of every count (a quick check that it works)
#   SAMPLES=262144 bash benches/compare/scaling.sh   # samples per realization of the mc-* routes (2^16)
#   BIN=target/debug/stochvib bash benches/compare/scaling.sh   # another build (default: release, built)
#   ROUTES="sweep transient" bash benches/compare/scaling.sh    # some routes only
#   PIN=1 bash benches/compare/scaling.sh            # "1 thread" = the whole process on one core (taskset):
#                                                    # a writer thread beside the one worker no longer has a core
#
# Routes (sizes at SCALE = 1): sweep (stochvib sweep of 10^6 points to HDF5), mc-spectral, mc-exact,
# mc-stream (stochvib simulate data/scraper-sprung-cab.toml, 200 realizations x 2^16 samples, the three routes),
# nonlinear (stochvib simulate data/quarter-car-bump-stops.toml, 64 realizations x 60 s), transient
# (stochvib transient benches/compare/transient-qc.toml --monte-carlo 10^4, 1200 steps each). Files go to
# $OUT (default: a temporary directory). Memory at other sizes: run twice with two SCALEs; what grows with
# the size is in benches/RESULTS.md.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
cd "$root"
scale="${SCALE:-1}"
routes="${ROUTES:-sweep mc-spectral mc-exact mc-stream nonlinear transient}"
out="${OUT:-$(mktemp -d)}"
mkdir -p "$out"
bin="${BIN:-}"
if [ -z "$bin" ]; then
    cargo build --locked --release --quiet --bin stochvib
    bin="${CARGO_TARGET_DIR:-$root/target}/release/stochvib"
fi
[ -x /usr/bin/time ] || { echo "scaling.sh: needs GNU time (apt-get install time)" >&2; exit 1; }

# n = round(x * SCALE), at least `min`
sized() { awk -v x="$1" -v s="$scale" -v m="${2:-2}" 'BEGIN { n = int(x * s + 0.5); print (n < m ? m : n) }'; }
side=$(sized 1000 10)
r_mc=$(sized 200) r_nl=$(sized 64) r_tr=$(sized 10000)
samples="${SAMPLES:-65536}"
dt=0.005 dur_mc=$(awk -v r="$samples" 'BEGIN { print r * 0.005 }') dur_nl=60

# route -> size text and command (the output file last, removed before each run)
size_of() {
    case "$1" in
    sweep) echo "$((side * side)) points" ;;
    mc-*) echo "$r_mc x $samples samples" ;;
    nonlinear) echo "$r_nl x $(awk -v d=$dur_nl 'BEGIN { print d / 0.005 }') samples" ;;
    transient) echo "$r_tr x 1200 steps" ;;
    esac
}
cmd_of() {
    local f="$out/$1.h5"
    case "$1" in
    sweep) echo "$bin sweep data/scraper-sprung-cab.toml --param model.omega2=1Hz..2.5Hz:$side \
--param model.zeta2=0.1..0.5:$side -o $f" ;;
    mc-spectral) echo "$bin simulate data/scraper-sprung-cab.toml --realizations $r_mc --dt $dt --duration $dur_mc \
--route spectral -o $f" ;;
    mc-exact) echo "$bin simulate data/scraper-sprung-cab.toml --realizations $r_mc --dt $dt --duration $dur_mc \
--route exact -o $f" ;;
    mc-stream) echo "$bin simulate data/scraper-sprung-cab.toml --realizations $r_mc --dt $dt --duration $dur_mc \
--route spectral-stream -o $f" ;;
    nonlinear) echo "$bin simulate data/quarter-car-bump-stops.toml --realizations $r_nl --dt $dt \
--duration $dur_nl -o $f" ;;
    transient) echo "$bin transient benches/compare/transient-qc.toml --monte-carlo $r_tr --shard-size 1000 \
-o $f" ;;
    *) echo "scaling.sh: unknown route $1" >&2; exit 2 ;;
    esac
}

# one timed run: prints "wall cpu rss_kib"
timed() {
    local threads="$1" route="$2" log="$out/$2-$1t"
    rm -f "$out/$route.h5" "$out/$route.h5.tmp"
    # PIN=1: the 1-thread run is the whole process on one core (its writer threads too), not one rayon worker
    local pin=()
    if [ "${PIN:-0}" = 1 ] && [ "$threads" = 1 ]; then pin=(taskset -c 0); fi
    # shellcheck disable=SC2046
    RAYON_NUM_THREADS="$threads" "${pin[@]}" /usr/bin/time -f "%e %U %S %M" -o "$log.time" \
        $(cmd_of "$route") >"$log.out" 2>"$log.err" || { echo "scaling.sh: $route failed:" >&2; cat "$log.err" >&2; exit 1; }
    awk '{ printf "%s %.2f %s\n", $1, $2 + $3, $4 }' "$log.time"
}

spin() { awk 'BEGIN { x = 0; for (i = 0; i < 5e6; i++) x += i * 1e-9; print x }' >/dev/null; }
calibrate() {
    local t0 t1 t2
    t0=$(date +%s.%N); spin; spin; t1=$(date +%s.%N)
    spin & spin & wait; t2=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN { printf "%.2f %.2f\n", b - a, c - b }'
}

cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "scaling.sh: $(nproc) cores, $cpu; load $(cut -d' ' -f1-3 /proc/loadavg); SCALE=$scale SAMPLES=$samples PIN=${PIN:-0}; \
files in $out" >&2
read -r seq par < <(calibrate)
echo "| route | size | wall 1 thread | wall 2 threads | 2 threads vs 1 | CPU 1 / 2 threads | peak RSS 1 / 2 threads | load |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
echo "| calibration: two spin loops in a row / side by side | 2 x 5e6 awk iterations | ${seq} s | ${par} s | \
$(awk -v a="$seq" -v b="$par" 'BEGIN { printf "%.2fx", a / b }') | - | - | $(cut -d' ' -f1 /proc/loadavg) |"
for route in $routes; do
    load=$(cut -d' ' -f1 /proc/loadavg)
    read -r w1 c1 m1 < <(timed 1 "$route")
    read -r w2 c2 m2 < <(timed 2 "$route")
    echo "| $route | $(size_of "$route") | $w1 s | $w2 s | $(awk -v a="$w1" -v b="$w2" 'BEGIN { printf "%.2fx", a / b }') \
| $c1 / $c2 s | $((m1 / 1024)) / $((m2 / 1024)) MiB | $load |"
done
echo "scaling.sh: commands and outputs in $out (*.out, *.err, *.time)" >&2
