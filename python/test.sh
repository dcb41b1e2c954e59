#!/usr/bin/env bash
# The Python package's build and tests: installs maturin, numpy, scipy, pytest, pytest-xdist, h5py and pandas
# (the to_dataframe() tests) with pip when they are missing, builds the package from this checkout (maturin,
# abi3 wheel) and installs it, then runs the pytest suite with one worker per CPU (pytest-xdist; the tests
# keep no state between them, and pass with every core busy). Called by scripts/test.sh after the Rust suite
# (whose debug `stochvib` binary the tests compare against; they build it when it is missing).
#
# The package is built in cargo's dev profile (STOCHVIB_PYTHON_PROFILE=release for the release build a plain
# `pip install ./python` makes): its dependencies and the library are then the very artifacts `cargo test
# --workspace` compiled (same settings, same features; see Cargo.toml's profiles and python/Cargo.toml), and
# only the bindings and PyO3 are compiled here: the Python tests run the very library the Rust tests ran.
set -euo pipefail
cd "$(dirname "$0")/.."
PY="${PYTHON:-python3}"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
# pip as scripts/ensure-deps.sh uses it: plain, else with --break-system-packages (an externally managed
# system Python); the output is shown only when both fail.
pip_install() {
  "$PY" -m pip install --quiet --disable-pip-version-check "$@" >"$log" 2>&1 \
    || "$PY" -m pip install --quiet --disable-pip-version-check --break-system-packages "$@" >"$log" 2>&1 \
    || { cat "$log" >&2; return 1; }
}
missing=()
# module:pip package
for m in maturin:maturin numpy:numpy scipy:scipy pytest:pytest xdist:pytest-xdist h5py:h5py pandas:pandas; do
  "$PY" -c "import ${m%%:*}" >/dev/null 2>&1 || missing+=("${m#*:}")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "python/test.sh: installing ${missing[*]}" >&2
  pip_install "${missing[@]}"
fi
start=$(date +%s)
profile="${STOCHVIB_PYTHON_PROFILE:-dev}"
echo "python/test.sh: building and installing the stochvib Python package (cargo profile $profile)" >&2
MATURIN_PEP517_ARGS="--profile $profile" pip_install --no-build-isolation --force-reinstall --no-deps ./python
echo "python/test.sh: package built and installed in $(( $(date +%s) - start )) s" >&2
"$PY" -m pytest -q -n auto python/tests
