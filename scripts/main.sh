#!/usr/bin/env bash
# The main job: the spectrum catalogue, the analysis of the example scenario, the book report and
# a Monte Carlo run written to HDF5 (out/run.h5) and summarised. Output files go to ./out.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/ensure-deps.sh
cargo build --release --locked --quiet
bin=target/release/stochvib
mkdir -p out
echo "== stochvib spectra"; $bin spectra
echo; echo "== stochvib analyze data/quarter-car.toml"; $bin analyze data/quarter-car.toml
echo; echo "== stochvib analyze data/operator-seat-verdicts.toml (ISO 2631-1 exposure and seat-spring fatigue verdicts)"
$bin analyze data/operator-seat-verdicts.toml
echo; echo "== stochvib book"; $bin book
# A small Monte Carlo batch on a catalogue model (exact route: Van Loan discretisation of the scraper with its
# road shaping filter), written to HDF5 and read back. A finished file is never overwritten by the writer:
# remove the previous one first (a leftover out/run.h5.tmp of the same run would be resumed).
rm -f out/run.h5
echo; echo "== stochvib simulate data/scraper-sprung-cab.toml (200 realizations x 20 s)"
$bin simulate data/scraper-sprung-cab.toml --realizations 200 --duration 20 --dt 0.01 --seed 2026 -o out/run.h5
echo; echo "== stochvib inspect out/run.h5"; $bin inspect out/run.h5
