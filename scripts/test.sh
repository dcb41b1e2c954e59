#!/usr/bin/env bash
# The whole test suite: installs what is missing, then runs every test (unit, integration, doc), then the
# comparison harnesses at tiny sizes (benches/compare/run.sh --smoke), then builds
# the Python package and runs its tests (python/test.sh; STOCHVIB_SKIP_PYTHON=1 skips them), then the
# cluster tests on a real single-node SLURM cluster (tests/slurm/smoke.sh, example-array.sh and
# real-array.sh: about 5-8 s each, plus about 16 s the first time for the Debian packages slurmctld, slurmd,
# slurm-client and munge, which scripts/slurm-cluster.sh installs).
#
# STOCHVIB_SLURM_TEST decides what happens when that cluster cannot be started on this machine:
#   require   the suite fails (CI: .ci/run sets it; also the default when CI is set in the environment)
#   auto      the default elsewhere: the suite passes, but ends with a warning banner that says the SLURM
#             test did NOT run and why
#   skip      do not try (the banner says so too)
# A cluster that starts and a test that then fails always fails the suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/ensure-deps.sh --with-h5py --with-browser
# --workspace: the dependencies get the features of the whole workspace, the Python package's included (its
# crate has no Rust tests, nothing of it is compiled here), so that python/test.sh reuses this build
cargo test --locked --workspace "$@"
# the API documentation builds without a warning (a link to a missing or private item, an unescaped E[x]
# read as a link)
RUSTDOCFLAGS="-D warnings" cargo doc --locked --no-deps --workspace --quiet
# the comparison harnesses (Rust and numpy/scipy/h5py sides) once at tiny sizes, ~1 min: a change that breaks
# one of them, or a row of benches/RESULTS.md's table, fails here (STOCHVIB_SKIP_COMPARE=1 skips it)
if [ "${STOCHVIB_SKIP_COMPARE:-0}" != 1 ]; then
  bash benches/compare/run.sh --smoke >/dev/null
fi
if [ "${STOCHVIB_SKIP_PYTHON:-0}" != 1 ]; then
  bash python/test.sh
fi

mode="${STOCHVIB_SLURM_TEST:-$([ -n "${CI:-}" ] && echo require || echo auto)}"
banner() {
  printf '\n%s\n%s\n%s\n\n' "!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!" \
    "!!! $*" "!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!!" >&2
}
case "$mode" in
skip)
  banner "the SLURM cluster tests (tests/slurm/*.sh) were NOT run: STOCHVIB_SLURM_TEST=skip"
  exit 0
  ;;
require | auto) ;;
*)
  echo "test.sh: STOCHVIB_SLURM_TEST must be require, auto or skip (got '$mode')" >&2
  exit 2
  ;;
esac
# the binary `cargo test` built (a no-op after it; `cargo build --bin stochvib` would compile the library once
# more, without the dev-dependencies' features)
cargo test --locked --workspace --no-run --quiet
# the cluster tests, in order: the cluster itself (tests/slurm/smoke.sh, one cycle), the shipped
# examples/cluster/slurm-array.sbatch with its dependent merge job (tests/slurm/example-array.sh, stochvib
# played by a stub that checks every argument), and the real run (tests/slurm/real-array.sh); exit 77 of
# any = the cluster cannot be started here
for t in smoke example-array real-array; do
  set +e
  STOCHVIB=target/debug/stochvib bash "tests/slurm/$t.sh"
  rc=$?
  set -e
  if [ "$rc" -eq 77 ]; then
    if [ "$mode" = require ]; then
      banner "FAILED: the SLURM cluster could not be started for tests/slurm/$t.sh, and STOCHVIB_SLURM_TEST=require (see above)"
      exit 1
    fi
    banner "the SLURM cluster tests did NOT run: the cluster could not be started on this machine (see above); set STOCHVIB_SLURM_TEST=require to make this an error"
    exit 0
  fi
  [ "$rc" -eq 0 ] || exit "$rc"
done
