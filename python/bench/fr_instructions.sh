#!/usr/bin/env bash
# Instruction counts (callgrind: independent of the machine's load) of one 10⁴-point frequency response of
# the quarter car through the Python package and in Rust: each side runs K = 1 and K = 3 calls, and half the
# difference is one call. Needs valgrind and the package installed (pip install ./python).
set -euo pipefail
cd "$(dirname "$0")/../.."
PY="${PYTHON:-python3}"
PY="$("$PY" -c 'import sys; print(sys.executable)')" # the interpreter itself, not a shim script
cargo bench -q -p stochvib-python --bench fr_instructions --no-run 2>/dev/null
exe="$(ls -t "${CARGO_TARGET_DIR:-target}"/release/deps/fr_instructions-* | grep -v '\.d$' | head -1)"
count() { valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null | sed -n 's/.*Collected : //p'; }
r1=$(count "$exe" 1); r3=$(count "$exe" 3)
p1=$(count "$PY" python/bench/fr_instructions.py 1); p3=$(count "$PY" python/bench/fr_instructions.py 3)
python3 - "$r1" "$r3" "$p1" "$p3" <<'PY'
import sys
r1, r3, p1, p3 = map(int, sys.argv[1:])
rust, py = (r3 - r1) / 2, (p3 - p1) / 2
print(f"one 10^4-point frequency response: Rust {rust / 1e6:.2f} M instructions, Python {py / 1e6:.2f} M, ratio {py / rust:.3f}")
PY
