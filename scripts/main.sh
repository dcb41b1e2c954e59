#!/usr/bin/env bash
# The main job: the spectrum catalogue and the analysis of the example scenario (later: the book report and
# a Monte Carlo run written to HDF5). Output files go to ./out.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/ensure-deps.sh
cargo build --release --locked --quiet
bin=target/release/stochvib
mkdir -p out
echo "== stochvib spectra"; $bin spectra
echo; echo "== stochvib analyze data/quarter-car.toml"; $bin analyze data/quarter-car.toml
