#!/usr/bin/env bash
# Smoke test of the local SLURM cluster (scripts/slurm-cluster.sh) and of scripts/slurm-wait.sh.
#
#   tests/slurm/smoke.sh [CYCLES]      (default 1)
#
# Each cycle: start a cluster in a fresh temporary directory; submit a 4-task array (indices 0-3) whose task
# writes its index to out/task-<index>.txt, index 2 failing while the file fail-2 exists; wait and check that
# slurm-wait reports exactly index 2 as failed and that the other three outputs are there; remove fail-2,
# resubmit index 2 alone (--array=2), wait, check all four outputs; stop the cluster and check that no process
# of it is left and that its port locks are released. Prints the time of every step and a summary.
#
# Exit 0 on success; 1 with a "smoke: FAIL: ..." message on the first failure; 77 when the cluster cannot be
# started on this machine (scripts/test.sh decides by STOCHVIB_SLURM_TEST). The cluster is stopped in every
# case (trap on EXIT); on failure its directory (logs, job outputs) is kept and named in the message.
# The ports come from STOCHVIB_SLURM_CTLD_PORT / STOCHVIB_SLURM_SLURMD_PORT as for slurm-cluster.sh.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../.." && pwd -P)"
CLUSTER="$ROOT/scripts/slurm-cluster.sh"
WAIT="$ROOT/scripts/slurm-wait.sh"
CYCLES="${1:-1}"
[[ "$CYCLES" =~ ^[1-9][0-9]*$ ]] || {
  echo "usage: tests/slurm/smoke.sh [CYCLES]" >&2
  exit 2
}
# Bound on every wait for an array: tasks of a trivial job start within seconds, but a loaded CI machine and
# SLURM's scheduling steps can add tens of seconds.
readonly JOB_TIMEOUT_S=120

now() { date +%s.%3N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }

DIR=""       # the current cycle's cluster directory
FAILED_RUN=0 # set by fail(): keep DIR for inspection

fail() {
  FAILED_RUN=1
  echo "smoke: FAIL: $*" >&2
  if [ -n "$DIR" ]; then echo "smoke: cluster directory kept for inspection: $DIR" >&2; fi
  exit 1
}

# Every live process that belongs to the cluster in DIR: started with its marker, naming DIR on its command line,
# running in DIR, or holding a file in DIR open (slurmstepd), as "PID COMM" lines. Zombies (exited, not yet
# reaped by PID 1) do not count. One grep and one find over /proc, not a fork per process.
leftovers() {
  local pid state comm
  {
    grep -lzsxF "STOCHVIB_SLURM_CLUSTER=$DIR" /proc/[0-9]*/environ || true
    grep -lzsF "$DIR/" /proc/[0-9]*/cmdline || true
    find /proc/[0-9]*/cwd /proc/[0-9]*/fd -maxdepth 1 \( -lname "$DIR" -o -lname "$DIR/*" \) 2>/dev/null || true
  } | sed -n 's|^/proc/\([0-9]*\)/.*|\1|p' | sort -un | while read -r pid; do
    [ "$pid" != "$$" ] || continue
    state="$(sed -n 's/^State:[[:space:]]*\([A-Z]\).*/\1/p' "/proc/$pid/status" 2>/dev/null)" || continue
    if [ -z "$state" ] || [ "$state" = "Z" ]; then continue; fi
    { read -r comm <"/proc/$pid/comm"; } 2>/dev/null || continue
    echo "$pid $comm"
  done
}

cleanup() {
  local rc=$?
  if [ -n "$DIR" ]; then
    "$CLUSTER" stop "$DIR" >/dev/null 2>&1 || echo "smoke: stopping the cluster in $DIR failed" >&2
    if [ "$FAILED_RUN" -eq 0 ] && [ "$rc" -eq 0 ]; then
      rm -rf "$DIR"
    elif [ "$FAILED_RUN" -eq 0 ]; then
      echo "smoke: interrupted (exit $rc); cluster stopped, directory kept: $DIR" >&2
    fi
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Checks that out/task-<i>.txt holds "<i>" for each index given.
check_outputs() {
  local i got
  for i in "$@"; do
    [ -f "$DIR/out/task-$i.txt" ] || fail "the output of task $i is missing ($DIR/out/task-$i.txt)"
    got="$(cut -d' ' -f1 "$DIR/out/task-$i.txt")"
    [ "$got" = "$i" ] || fail "the output of task $i holds '$got'"
  done
}

# Submits the array $1 (sbatch --array syntax), waits, and sets WAIT_RC, FAILED_INDICES and JOB_S.
run_array() {
  local t0 jid out
  t0="$(now)"
  jid="$(sbatch --parsable --array="$1" --job-name=smoke -D "$DIR" -o "$DIR/log/job-%A_%a.out" "$DIR/task.sh")" ||
    fail "sbatch --array=$1 failed"
  set +e
  out="$("$WAIT" "$jid" "$JOB_TIMEOUT_S" 2>"$DIR/wait.err")"
  WAIT_RC=$?
  set -e
  JOB_S="$(since "$t0")"
  printf '    %s\n' "${out//$'\n'/$'\n'    }"
  FAILED_INDICES="$(sed -n 's/^FAILED //p' <<<"$out" | tr '\n' ' ' | sed 's/ $//')"
}

# ---------------------------------------------------------------------------------------------------------------

t0="$(now)"
"$CLUSTER" install
echo "smoke: packages present after $(since "$t0") s"

summary=()
for cycle in $(seq 1 "$CYCLES"); do
  echo "smoke: cycle $cycle of $CYCLES"
  DIR="$(mktemp -d "${TMPDIR:-/tmp}/stochvib-slurm-smoke.XXXXXX")"
  chmod 0755 "$DIR" # munged wants every directory above its socket to be a+x
  mkdir -p "$DIR/out" "$DIR/log"

  t0="$(now)"
  if ! STOCHVIB_SLURM_LOCK_WAIT="${STOCHVIB_SLURM_LOCK_WAIT:-120}" "$CLUSTER" start "$DIR"; then
    echo "smoke: the SLURM cluster could not be started on this machine (see the messages above; its files: $DIR)" >&2
    FAILED_RUN=1
    exit 77
  fi
  start_s="$(since "$t0")"
  eval "$("$CLUSTER" env "$DIR")"

  # The task: writes "<index> <task count>" to out/task-<index>.txt; index 2 fails while fail-2 exists.
  cat >"$DIR/task.sh" <<'EOF'
#!/usr/bin/env bash
set -euo pipefail
i="$SLURM_ARRAY_TASK_ID"
if [ "$i" = 2 ] && [ -e fail-2 ]; then
  echo "task 2 fails on purpose" >&2
  exit 1
fi
echo "$i ${SLURM_ARRAY_TASK_COUNT:-?}" >"out/task-$i.txt"
EOF
  chmod +x "$DIR/task.sh"
  touch "$DIR/fail-2"

  # 1. The array 0-3 with index 2 failing.
  echo "  sbatch --array=0-3 (index 2 fails)"
  run_array 0-3
  [ "$WAIT_RC" -eq 1 ] || fail "slurm-wait exited $WAIT_RC for the array with a failing task (expected 1): $(cat "$DIR/wait.err")"
  [ "$FAILED_INDICES" = "2" ] || fail "slurm-wait reported failed indices '$FAILED_INDICES' (expected '2')"
  check_outputs 0 1 3
  [ ! -e "$DIR/out/task-2.txt" ] || fail "task 2 wrote an output although it failed"
  array_s="$JOB_S"

  # 2. Resubmit the failed index alone, the failure removed.
  rm -f "$DIR/fail-2"
  echo "  sbatch --array=2 (resubmission)"
  run_array 2
  [ "$WAIT_RC" -eq 0 ] || fail "slurm-wait exited $WAIT_RC for the resubmitted index (expected 0): $(cat "$DIR/wait.err")"
  [ -z "$FAILED_INDICES" ] || fail "slurm-wait reported failed indices '$FAILED_INDICES' for the resubmission"
  check_outputs 0 1 2 3
  # SLURM_ARRAY_TASK_COUNT is the count of the resubmitted array (1), not of the original one: a sharded
  # program must be given its number of shards explicitly.
  echo "  SLURM_ARRAY_TASK_COUNT seen by index 2 after resubmission: $(cut -d' ' -f2 "$DIR/out/task-2.txt")"
  resubmit_s="$JOB_S"

  # 3. Stop, and check that nothing is left.
  t0="$(now)"
  "$CLUSTER" stop "$DIR" || fail "stop failed"
  stop_s="$(since "$t0")"
  status_rc=0
  "$CLUSTER" status "$DIR" >/dev/null || status_rc=$?
  [ "$status_rc" -eq 3 ] || fail "status after stop exited $status_rc (expected 3: stopped)"
  left="$(leftovers)"
  [ -z "$left" ] || fail "processes left after stop: $(echo "$left" | tr '\n' ';')"
  for port in "${STOCHVIB_SLURM_CTLD_PORT:-6817}" "${STOCHVIB_SLURM_SLURMD_PORT:-6818}"; do
    lock="${STOCHVIB_SLURM_LOCK_DIR:-/tmp/stochvib-slurm-locks}/port-$port"
    if [ "$(readlink "$lock" 2>/dev/null || true)" = "$DIR" ]; then fail "the lock $lock was not released"; fi
  done
  rm -rf "$DIR"
  DIR=""
  line="cycle $cycle: start $start_s s, array 0-3 (one failure) $array_s s, resubmit index 2 $resubmit_s s, stop $stop_s s"
  echo "smoke: $line"
  summary+=("$line")
done

echo "smoke: PASS ($CYCLES cycle(s))"
printf '  %s\n' "${summary[@]}"
