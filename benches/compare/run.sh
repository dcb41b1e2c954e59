#!/usr/bin/env bash
# Side-by-side timing of stochvib (Rust, release) against numpy/scipy/h5py on the same jobs and problem
# sizes, in one run, and the one table of benches/RESULTS.md written from it.
#
#   bash benches/compare/run.sh              # the full comparison (~40 min on 2 cores); writes the table
#                                            # into benches/RESULTS.md (between its table markers)
#   bash benches/compare/run.sh --smoke      # every harness once at tiny sizes (seconds; scripts/test.sh):
#                                            # fails when a harness breaks or a row of the table is missing
#   REPS=3 bash benches/compare/run.sh       # fewer repetitions (default 5; Monte Carlo at most 3)
#   bash benches/compare/run.sh --no-write   # the table only in $OUT/table.md
#   bash benches/compare/run.sh --tunables   # also the analytic/MC jobs with
#                                            # GLIBC_TUNABLES=glibc.cpu.x86_rep_movsb_threshold=100000000
#
# Order: the Rust jobs, then the Python jobs (quiet machine), then the densities again in alternating rounds
# (their table rows are the medians of the rounds), then `stochvib sweep` of 10^6 points to HDF5,
# to a CSV file and as CSV read from a pipe beside the scipy loop, once on the quiet machine and once with
# one core kept busy (stress-ng --cpu 1 when installed, else a shell busy loop), then the harnesses with
# tables of their own, each adding its rows: fatigue.py (rainflow, Dirlik), nonlinear.sh (route 2),
# transient.py (transient Monte Carlo), optimize.py, records.py (`stochvib exposure`). The Python package's
# call overhead (python/bench) and the ISO 2631 weighting sweep (weighting.py: scipy side only) are not in
# the table. The machine state (load average) is recorded before each phase. Timings are the best of REPS repetitions, the `stochvib sweep`
# rows the median of REPS runs. JSON results are left in $OUT (default: a temporary directory).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
smoke=0 write=1 tunables=0
for a in "$@"; do
    case "$a" in
    --smoke) smoke=1 write=0 ;;
    --no-write) write=0 ;;
    --tunables) tunables=1 ;;
    *) echo "run.sh: unknown option $a" >&2; exit 2 ;;
    esac
done
reps="${REPS:-5}"
out="${OUT:-$(mktemp -d)}"
mkdir -p "$out"
cd "$root"

# numpy/scipy/h5py: pip (plain, then --break-system-packages for an externally managed Python), then
# Debian's packages; the rainflow packages and FLife of fatigue.py: pip
if ! python3 -c "import numpy, scipy, h5py" 2>/dev/null; then
    echo "run.sh: installing numpy, scipy, h5py" >&2
    python3 -m pip install --quiet --disable-pip-version-check numpy scipy h5py 2>/dev/null \
        || python3 -m pip install --quiet --disable-pip-version-check --break-system-packages numpy scipy h5py 2>/dev/null \
        || { apt-get install -y -qq python3-numpy python3-scipy python3-h5py >/dev/null 2>&1 \
             || { apt-get update -qq >/dev/null 2>&1 && apt-get install -y -qq python3-numpy python3-scipy python3-h5py >/dev/null; }; }
    python3 -c "import numpy, scipy, h5py"
fi
if ! python3 -c "import rainflow, fatpack, FLife" 2>/dev/null; then
    echo "run.sh: installing rainflow, fatpack, FLife (fatigue.py's peers)" >&2
    python3 -m pip install --quiet --disable-pip-version-check rainflow fatpack FLife 2>/dev/null \
        || python3 -m pip install --quiet --disable-pip-version-check --break-system-packages rainflow fatpack FLife
fi
[ -x /usr/bin/time ] || apt-get install -y -qq time >/dev/null  # records.py times both sides with GNU time

target="${CARGO_TARGET_DIR:-$root/target}"
if [ "$smoke" = 1 ]; then
    # the test profile's library (already built by `cargo test --workspace`, with the same features): seconds,
    # not a release build
    echo "run.sh --smoke: building the harness and stochvib (test profile)" >&2
    cargo build --locked --quiet --workspace --profile test --example compare_rust --bin stochvib \
        --example compare_nonlinear --example fatigue_compare
    bin="$target/debug/examples/compare_rust" cli="$target/debug/stochvib" profile=test
    rust_args=(--smoke) py_args=(--smoke) cli_args=(--smoke --side 20 --reps 1)
else
    echo "run.sh: building the Rust side (release)" >&2
    cargo build --locked --release --quiet --example compare_rust --bin stochvib \
        --example compare_nonlinear --example fatigue_compare
    bin="$target/release/examples/compare_rust" cli="$target/release/stochvib" profile=release
    rust_args=(--reps "$reps") py_args=(--reps "$reps") cli_args=(--reps "$reps")
fi

state() { # the machine state of a phase: what else runs, and the load average
    printf '%s, load %s' "$1" "$(cut -d' ' -f1 /proc/loadavg)" >"$out/state-$2.txt"
}
cpu="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
simd="$(grep -m1 '^flags' /proc/cpuinfo | grep -o -w -E 'avx512f|avx2|sse2' | sort -u | tr '\n' ' ')"
echo "machine: $(nproc) cores, $cpu ($simd), $(awk '/MemTotal/ {printf "%.1f GiB", $2/1048576}' /proc/meminfo)" | tee "$out/machine.txt"

state "as found" run
echo "run.sh: Rust jobs, then Python jobs" >&2
env -u GLIBC_TUNABLES "$bin" "${rust_args[@]}" >"$out/rust.json"
env -u GLIBC_TUNABLES python3 "$here/compare.py" run "${py_args[@]}" >"$out/python.json"
python3 "$here/compare.py" table "$out/rust.json" "$out/python.json" >"$out/details.md"

# the Monte Carlo routes against their floors in several processes: a job's best time differs between
# processes (by up to 30 % on the 2-core AMD EPYC VM) more than between the rounds of one process
floor_procs=$([ "$smoke" = 1 ] && echo 2 || echo 7)
echo "run.sh: Monte Carlo routes against their floors, $floor_procs processes" >&2
state "as found" floors
for i in $(seq 1 "$floor_procs"); do
    env -u GLIBC_TUNABLES "$bin" --only floors "${rust_args[@]}" >"$out/floors-$i.json" 2>/dev/null
done
python3 "$here/rows.py" floors "$out" >"$out/rows-floors.json"

# the densities take microseconds: a load that changes between the Rust and the Python phase above would
# decide their ratio, so they are also run in alternating rounds (Rust, numpy, Rust, ...), median per side
rounds=$([ "$smoke" = 1 ] && echo 1 || echo 5)
echo "run.sh: densities, $rounds alternating rounds" >&2
state "as found" density
for i in $(seq 1 "$rounds"); do
    env -u GLIBC_TUNABLES "$bin" --only density "${rust_args[@]}" >"$out/density-rust-$i.json" 2>/dev/null
    env -u GLIBC_TUNABLES python3 "$here/compare.py" run --only density "${py_args[@]}" >"$out/density-python-$i.json"
done

# the same rounds with both sides capped to the narrower instruction sets this CPU also runs: our kernels by
# STOCHVIB_ISA, numpy's dispatch by NPY_DISABLE_CPU_FEATURES (what an AVX2-only or an SSE2/x86-64-v2 machine
# runs, measured on this one)
caps=()
grep -q -w avx512f /proc/cpuinfo && caps+=(avx2)
grep -q -w avx2 /proc/cpuinfo && caps+=(baseline)
for cap in "${caps[@]}"; do
    echo "run.sh: densities capped to $cap, $rounds alternating rounds" >&2
    state "as found" "isa-$cap"
    npy="$(python3 "$here/compare.py" npy-cap "$cap")"
    for i in $(seq 1 "$rounds"); do
        env -u GLIBC_TUNABLES STOCHVIB_ISA="$cap" "$bin" --only density "${rust_args[@]}" \
            >"$out/isa-$cap-rust-$i.json" 2>/dev/null
        env -u GLIBC_TUNABLES NPY_DISABLE_CPU_FEATURES="$npy" python3 "$here/compare.py" run --only density \
            "${py_args[@]}" >"$out/isa-$cap-python-$i.json"
    done
done

echo "run.sh: stochvib sweep beside the scipy loop, quiet machine" >&2
state "as found" quiet
python3 "$here/compare.py" sweep-cli --binary "$cli" "${cli_args[@]}" >"$out/sweep-quiet.json"
echo "run.sh: the same with one core busy" >&2
if command -v stress-ng >/dev/null; then
    stress-ng --cpu 1 --quiet --timeout 3600s & busy=$!
    what="1 core busy (stress-ng --cpu 1)"
else
    bash -c 'while :; do :; done' & busy=$!
    what="1 core busy (shell loop)"
fi
trap 'kill "$busy" 2>/dev/null || true' EXIT
sleep 2
state "$what" busy
python3 "$here/compare.py" sweep-cli --binary "$cli" "${cli_args[@]}" >"$out/sweep-busy.json"
kill "$busy" 2>/dev/null || true
wait "$busy" 2>/dev/null || true
trap - EXIT

# the harnesses with tables of their own, each writing rows-NAME.json for the one table (compare.py summary)
if [ "$smoke" = 1 ]; then
    fatigue_args=(--n 200000 --check 20000 --reps 1) nl=(R=8 T=2 REPS=1 PY_PROCS=1) transient_r=40 transient_reps=1 transient_ours=1 opt_reps=1 hours=0.005 rec_reps=1
else
    fatigue_args=(--n 100000000 --check 1000000 --reps 3) nl=(R=512 T=30 REPS=3) transient_r=10000 transient_reps=5 transient_ours=5
    opt_reps=7 hours=1 rec_reps=3
fi
echo "run.sh: fatigue.py (rainflow, Dirlik)" >&2
state "as found" fatigue
python3 "$here/fatigue.py" run --no-build --profile "$profile" "${fatigue_args[@]}" --dir "$out/fatigue" \
    --rows "$out/rows-fatigue.json" >"$out/fatigue.txt"
rm -f "$out"/fatigue/*.f64
echo "run.sh: nonlinear.sh (route 2 against numpy)" >&2
state "as found" nonlinear
env "${nl[@]}" OUT="$out/nonlinear" PROFILE="$profile" NO_BUILD=1 bash "$here/nonlinear.sh" --no-write >"$out/nonlinear.txt"
python3 "$here/rows.py" nonlinear "$out/nonlinear" >"$out/rows-nonlinear.json"
echo "run.sh: transient.py (transient Monte Carlo against numpy)" >&2
state "as found" transient
python3 "$here/transient.py" --binary "$cli" --realizations "$transient_r" --reps "$transient_reps" \
    --ours-per-rep "$transient_ours" --rows "$out/rows-transient.json" \
    >"$out/transient.txt"
echo "run.sh: optimize.py (stochvib optimize against scipy.optimize)" >&2
state "as found" optimize
python3 "$here/optimize.py" --binary "$cli" --reps "$opt_reps" --rows "$out/rows-optimize.json" >"$out/optimize.txt"
echo "run.sh: records.py (stochvib exposure against scipy.signal)" >&2
state "as found" records
python3 "$here/records.py" run --binary "$cli" --hours "$hours" --reps "$rec_reps" --dir "$out/records" >"$out/records.json" \
    2>"$out/records.log"
rm -f "$out"/records/*.h5
python3 "$here/rows.py" records "$out/records.json" >"$out/rows-records.json"

python3 "$here/compare.py" summary "$out" >"$out/table.md"
{
    echo "One run of \`bash benches/compare/run.sh\` at commit \`$(git rev-parse --short HEAD 2>/dev/null || echo '?')\`, $(date -u '+%Y-%m-%d %H:%M UTC'); $(cat "$out/machine.txt")."
    echo "Rust $(rustc --version | cut -d' ' -f2) release (generic x86-64: SIMD chosen at run time); $(python3 -c 'import sys, numpy, scipy, h5py; print(f"Python {sys.version.split()[0]}, numpy {numpy.__version__}, scipy {scipy.__version__}, h5py {h5py.__version__} (HDF5 {h5py.version.hdf5_version})")')."
    echo
    cat "$out/table.md"
} >"$out/results.md"
cat "$out/results.md"

if [ "$smoke" = 1 ]; then
    # every row of the table present, every time a number
    rows=$(grep -c '^| ' "$out/table.md")
    for h in floors fatigue nonlinear transient optimize records; do
        if ! grep -q '"job"' "$out/rows-$h.json"; then
            echo "run.sh --smoke: the $h harness gave no row (see $out/$h.txt)" >&2
            exit 1
        fi
    done
    if [ "$(grep -c 'moving its bytes alone' "$out/table.md")" -ne 6 ]; then
        echo "run.sh --smoke: the sweep's I/O-floor rows (3 formats x 2 machine states) are missing (see $out)" >&2
        exit 1
    fi
    if [ "$rows" -lt 40 ] || grep -q -E '\| (nan|inf|-) ' "$out/table.md"; then
        echo "run.sh --smoke: the table is incomplete ($((rows - 2)) rows): a harness is broken (see $out)" >&2
        exit 1
    fi
    echo "run.sh --smoke: every harness ran, $((rows - 2)) rows ($out)" >&2
fi
if [ "$tunables" = 1 ]; then
    tun="glibc.cpu.x86_rep_movsb_threshold=100000000"
    GLIBC_TUNABLES="$tun" "$bin" "${rust_args[@]}" >"$out/rust-tunables.json"
    GLIBC_TUNABLES="$tun" python3 "$here/compare.py" run "${py_args[@]}" >"$out/python-tunables.json"
    python3 "$here/compare.py" table "$out/rust-tunables.json" "$out/python-tunables.json" | tee "$out/details-tunables.md"
fi
if [ "$smoke" = 0 ]; then
    # ISO 2631-1 weighted r.m.s. over a 100 x 100 seat sweep: the scipy side (the Rust side is the criterion
    # bench `cargo bench --workspace --bench weighting`; see benches/HISTORY.md)
    env -u GLIBC_TUNABLES python3 "$here/weighting.py" --reps "$(( reps < 3 ? reps : 3 ))" | tee "$out/weighting-python.txt"
fi
if [ "$write" = 1 ]; then
    python3 "$here/write_section.py" "$root/benches/RESULTS.md" "$out/results.md" \
        "<!-- table: written by benches/compare/run.sh -->" "<!-- end of table -->"
    echo "run.sh: the table is in benches/RESULTS.md" >&2
fi
echo "run.sh: JSON and tables in $out" >&2
