#!/usr/bin/env bash
# Runs examples/cluster/slurm-array.sbatch on a local SLURM cluster (scripts/slurm-cluster.sh), as its README
# says: a 4-shard array with shard 2 failing, the dependent merge job (afterok, --kill-on-invalid-dep=yes),
# then the rerun of index 2 alone and the merge again.
#
#   tests/slurm/example-array.sh
#
# The stochvib commands are played by tests/slurm/stochvib-stub.sh, which checks the arguments and the
# environment every shard sees; with STOCHVIB_REAL=/path/to/stochvib it runs the real binary instead (the
# injected failure of shard 2 stays in the stub).
#
# Checks: the first array reports exactly index 2 failed; the merge depending on it is cancelled, not left
# pending; the rerun (--array=2) succeeds and its shard still gets --of 4; every shard ran with
# RAYON_NUM_THREADS = --cpus-per-task; the second merge completes and writes the run file; a log per task.
# Exit 0 on success, 1 with "example-array: FAIL: ..." otherwise, 77 when the cluster cannot be started on this
# machine (scripts/test.sh decides by STOCHVIB_SLURM_TEST); the cluster is stopped in every case.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../.." && pwd -P)"
CLUSTER="$ROOT/scripts/slurm-cluster.sh"
WAIT="$ROOT/scripts/slurm-wait.sh"
SBATCH_SCRIPT="$ROOT/examples/cluster/slurm-array.sbatch"
readonly JOB_TIMEOUT_S=120 # trivial shards; the margin is for a loaded machine

DIR=""
KEEP=0
fail() {
  KEEP=1
  echo "example-array: FAIL: $*" >&2
  if [ -n "$DIR" ]; then echo "example-array: directory kept for inspection: $DIR" >&2; fi
  exit 1
}
cleanup() {
  local rc=$?
  if [ -n "$DIR" ]; then
    "$CLUSTER" stop "$DIR/cluster" >/dev/null 2>&1 || echo "example-array: stopping the cluster failed" >&2
    if [ "$KEEP" -eq 0 ] && [ "$rc" -eq 0 ]; then
      rm -rf "$DIR"
    elif [ "$KEEP" -eq 0 ]; then
      echo "example-array: interrupted (exit $rc); cluster stopped, directory kept: $DIR" >&2
    fi
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Waits for job $1 and sets WAIT_RC and FAILED (the failed indices, space-separated) and TASKS (the TASK lines).
wait_job() {
  local out
  set +e
  out="$("$WAIT" "$1" "$JOB_TIMEOUT_S" 2>/dev/null)"
  WAIT_RC=$?
  set -e
  TASKS="$(grep '^TASK ' <<<"$out" || true)"
  FAILED="$(sed -n 's/^FAILED //p' <<<"$out" | tr '\n' ' ' | sed 's/ $//')"
}

DIR="$(mktemp -d "${TMPDIR:-/tmp}/stochvib-slurm-example.XXXXXX")"
chmod 0755 "$DIR"
if ! STOCHVIB_SLURM_LOCK_WAIT="${STOCHVIB_SLURM_LOCK_WAIT:-120}" "$CLUSTER" start "$DIR/cluster"; then
  echo "example-array: the SLURM cluster could not be started on this machine (see the messages above; its files: $DIR/cluster)" >&2
  KEEP=1
  exit 77
fi
eval "$("$CLUSTER" env "$DIR/cluster")"

# The user's side: a working directory with the log directory, the run parameters in the environment.
WORK="$DIR/work"
mkdir -p "$WORK/logs"
cd "$WORK"
export STOCHVIB="$ROOT/tests/slurm/stochvib-stub.sh"
export SCENARIO="$ROOT/data/quarter-car.toml" REALIZATIONS=40 DURATION=1 DT=0.01 SEED=2026 SHARDS=4
export RUNDIR="runs/quarter-car-2026"
export STUB_FAIL_DIR="$WORK"
MERGE_CMD="$STOCHVIB merge runs/quarter-car-2026.h5 runs/quarter-car-2026/"
# The example asks for 4 cores and 4 GB per shard; this node has 2 cores: one core each, two shards at once.
RES=(--cpus-per-task=1 --mem=200M)

# 1. The whole array, shard 2 failing, and the merge depending on it.
touch "$WORK/fail-2"
jid="$(sbatch --parsable --array=0-3 "${RES[@]}" "$SBATCH_SCRIPT")" || fail "sbatch of the array failed"
mid="$(sbatch --parsable --dependency="afterok:$jid" --kill-on-invalid-dep=yes --job-name=stochvib-merge \
  --output=logs/%x-%j.out --wrap "$MERGE_CMD")" || fail "sbatch of the merge failed"
wait_job "$jid"
if [ "$WAIT_RC" -ne 1 ] || [ "$FAILED" != "2" ]; then
  fail "array $jid: slurm-wait exit $WAIT_RC, failed '$FAILED' (expected 1, '2')"
fi
wait_job "$mid"
grep -q '^TASK - CANCELLED ' <<<"$TASKS" || fail "the merge $mid after a failed shard is not CANCELLED: $TASKS"
[ ! -e runs/quarter-car-2026.h5 ] || fail "the merge wrote a run file although shard 2 failed"
echo "example-array: array $jid: index 2 failed as injected; merge $mid cancelled (dependency never satisfied)"

# 2. Rerun index 2 alone, then merge again.
rm "$WORK/fail-2"
jid2="$(sbatch --parsable --array=2 "${RES[@]}" "$SBATCH_SCRIPT")" || fail "sbatch of the rerun failed"
mid2="$(sbatch --parsable --dependency="afterok:$jid2" --kill-on-invalid-dep=yes --job-name=stochvib-merge \
  --output=logs/%x-%j.out --wrap "$MERGE_CMD")" || fail "sbatch of the second merge failed"
wait_job "$jid2"
[ "$WAIT_RC" -eq 0 ] || fail "rerun $jid2: slurm-wait exit $WAIT_RC: $TASKS"
wait_job "$mid2"
[ "$WAIT_RC" -eq 0 ] || fail "merge $mid2: slurm-wait exit $WAIT_RC: $TASKS (log: $(cat logs/stochvib-merge-"$mid2".out 2>/dev/null))"
[ -s runs/quarter-car-2026.h5 ] || fail "the merge wrote no run file"

# 3. What every shard saw, and the logs.
if [ -z "${STOCHVIB_REAL:-}" ]; then
  for k in 0 1 2 3; do
    expected="shard=$k of=4 realizations=40 seed=2026 threads=1"
    got="$(sed -n "$((k + 1))p" runs/quarter-car-2026.h5)"
    [ "$got" = "$expected" ] || fail "merged line $k is '$got' (expected '$expected')"
  done
fi
grep -q "shard 2 of 4 " "logs/stochvib-mc-${jid2}_2.out" || fail "the log of the rerun lacks its banner"
for k in 0 1 2 3; do [ -s "logs/stochvib-mc-${jid}_$k.out" ] || fail "no log for task ${jid}_$k"; done
grep -q "fails on purpose" "logs/stochvib-mc-${jid}_2.out" || fail "the log of the failed task lacks its error"
echo "example-array: rerun $jid2 of index 2 and merge $mid2 completed; all 4 shards merged"

cd /
"$CLUSTER" stop "$DIR/cluster" || fail "stop failed"
echo "example-array: PASS"
