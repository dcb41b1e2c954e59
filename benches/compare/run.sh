#!/usr/bin/env bash
# Side-by-side timing of stochvib (Rust, release) against numpy/scipy on the same jobs and problem sizes.
#
#   bash benches/compare/run.sh            # from the repository root (or anywhere)
#   REPS=3 bash benches/compare/run.sh     # fewer repetitions
#
# Runs both sides twice: with GLIBC_TUNABLES unset, then with
# GLIBC_TUNABLES=glibc.cpu.x86_rep_movsb_threshold=100000000 (see DESIGN.md §8), and prints one table per
# setting. Timings are the best of REPS repetitions; on a shared machine compare the ratios, not the
# absolute times. JSON results are left in $OUT (default: a temporary directory).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
reps="${REPS:-5}"
out="${OUT:-$(mktemp -d)}"
mkdir -p "$out"

if ! python3 -c "import numpy, scipy, h5py" 2>/dev/null; then
    echo "installing numpy, scipy, h5py with pip" >&2
    python3 -m pip install --quiet numpy scipy h5py \
        || python3 -m pip install --quiet --break-system-packages numpy scipy h5py
fi

echo "building the Rust side (release)" >&2
(cd "$root" && cargo build --release --quiet --example compare_rust)
target="${CARGO_TARGET_DIR:-$root/target}"
bin="$target/release/examples/compare_rust"

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), \
$(awk '/MemTotal/ {printf "%.1f GiB", $2/1048576}' /proc/meminfo)"
for tun in "" "glibc.cpu.x86_rep_movsb_threshold=100000000"; do
    tag="${tun:+tunables}"
    tag="${tag:-plain}"
    echo "running ($tag): Rust, then Python" >&2
    if [ -n "$tun" ]; then
        GLIBC_TUNABLES="$tun" "$bin" --reps "$reps" >"$out/rust-$tag.json"
        GLIBC_TUNABLES="$tun" python3 "$here/compare.py" run --reps "$reps" >"$out/python-$tag.json"
    else
        env -u GLIBC_TUNABLES "$bin" --reps "$reps" >"$out/rust-$tag.json"
        env -u GLIBC_TUNABLES python3 "$here/compare.py" run --reps "$reps" >"$out/python-$tag.json"
    fi
    echo
    python3 "$here/compare.py" table "$out/rust-$tag.json" "$out/python-$tag.json"
done
echo
# ISO 2631-1 weighted r.m.s. over a 100 x 100 seat sweep (issue 18): the scipy Lyapunov loop; the Rust side
# of the same sweep is the criterion bench `cargo bench --bench weighting` (see benches/RESULTS.md)
echo "running: ISO 2631-1 a_w sweep, scipy side" >&2
echo "ISO 2631-1 a_w sweep (scipy tf2ss + solve_continuous_lyapunov; Rust: cargo bench --bench weighting)"
env -u GLIBC_TUNABLES python3 "$here/weighting.py" --reps "$(( reps < 3 ? reps : 3 ))" | tee "$out/weighting-python.txt"
echo
echo "JSON results in $out" >&2
