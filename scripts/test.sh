#!/usr/bin/env bash
# The whole test suite: installs what is missing, then runs every test (unit, integration, doc).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/ensure-deps.sh --with-h5py
cargo test --locked "$@"
