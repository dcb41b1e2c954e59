#!/usr/bin/env bash
# The whole test suite: installs what is missing, then runs every test (unit, integration, doc), then builds
# the Python package and runs its tests (python/test.sh; STOCHVIB_SKIP_PYTHON=1 skips them).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/ensure-deps.sh --with-h5py
cargo test --locked "$@"
if [ "${STOCHVIB_SKIP_PYTHON:-0}" != 1 ]; then
  bash python/test.sh
fi
