#!/usr/bin/env bash
# Waits for a SLURM job or job array to finish, then reports the final state of every array task.
#
#   scripts/slurm-wait.sh JOBID [TIMEOUT_S]
#
# JOBID is what `sbatch --parsable` printed (an array job id such as 12, a single task 12_3, or "12;cluster").
# TIMEOUT_S (default 3600) bounds the wait. The job is polled with `squeue -h -j JOBID -t <active states>` every
# SLURM_WAIT_POLL_S seconds (default 0.25): `sbatch --wait` polls at 2, 10, 42, 74 ... s and adds seconds to
# tens of seconds to every wait. Client commands find the cluster through SLURM_CONF, as usual. An squeue error
# other than "Invalid job id" (controller busy, restarting) is retried for SLURM_WAIT_UNREACHABLE_S seconds
# (default 30) in a row.
#
# Output on stdout, one line per array task, sorted by index (a job that is not an array has index "-"):
#   TASK <index> <state> <exit code>     e.g. "TASK 2 FAILED 1:0"; state as SLURM prints it (COMPLETED, FAILED,
#                                        CANCELLED, TIMEOUT, OUT_OF_MEMORY, NODE_FAIL, ...), UNKNOWN when the
#                                        controller no longer has the task's record (see MinJobAge); exit code
#                                        "status:signal", or "-" when unknown
#   FAILED <index>                       one line per task whose state is not COMPLETED (after all TASK lines)
# A caller gets the indices to resubmit with:  scripts/slurm-wait.sh "$jid" | sed -n 's/^FAILED //p'
# A summary goes to stderr.
#
# Final states come from `sacct` when accounting is enabled, else from `scontrol show job` (records kept
# MinJobAge seconds after a task ends), else from `squeue --states=all` (no exit codes).
#
# Exit codes: 0 every task COMPLETED; 1 at least one task did not (FAILED lines name them); 2 usage error;
# 3 timeout (the job is left running; TASK lines show the states at that moment, FAILED lines the tasks that
# already ended badly); 4 the controller does not know JOBID (never existed, or its records already expired);
# 5 the controller stopped answering (no TASK lines).
set -euo pipefail

readonly PROG="slurm-wait"
# Every state in which a job is not finished (squeue's short names): pending, running, completing,
# configuring, suspended, stopped, requeued, requeue_fed, requeue_hold, resizing, resv_del_hold, signaling,
# stage_out.
readonly ACTIVE_STATES="PD,R,CG,CF,S,ST,RQ,RF,RH,RS,RD,SI,SO"
POLL_S="${SLURM_WAIT_POLL_S:-0.25}"
UNREACHABLE_S="${SLURM_WAIT_UNREACHABLE_S:-30}"

usage() {
  sed -n '2,5p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
log() { echo "$PROG: $*" >&2; }
now() { date +%s.%3N; }
elapsed_since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }
within() { awk -v a="$1" -v b="$(now)" -v t="$2" 'BEGIN { exit !(b - a < t) }'; }

if [ "$#" -lt 1 ] || [ "$#" -gt 2 ]; then usage; fi
JOB="${1%%;*}" # sbatch --parsable prints "id;cluster" on multi-cluster setups
TIMEOUT_S="${2:-3600}"
[[ "$JOB" =~ ^[0-9]+(_[0-9]+)?$ ]] || {
  log "JOBID must look like 12 or 12_3 (got '$1')"
  exit 2
}
[[ "$TIMEOUT_S" =~ ^[0-9]+([.][0-9]+)?$ ]] || {
  log "TIMEOUT_S must be a number of seconds (got '$TIMEOUT_S')"
  exit 2
}

# index -> "STATE EXITCODE" of every task, and the indices known to exist.
declare -A RESULT=()
declare -A EXPECTED=()

# Records the indices the controller knows now (squeue -r expands a pending array into one line per index).
# Returns 1 when the controller does not know the job.
record_expected() {
  local out idx
  out="$(squeue -h -r -j "$JOB" --states=all -o '%K' 2>/dev/null)" || return 1
  [ -n "$out" ] || return 1
  while read -r idx; do
    [ "$idx" != "N/A" ] || idx="-"
    EXPECTED["$idx"]=1
  done <<<"$out"
}

# True while the job has a task that is not finished. An unknown job counts as finished (its records expired);
# any other squeue error (controller busy or restarting) counts as unfinished, so the poll goes on, unless the
# controller has not answered for UNREACHABLE_S seconds in a row (then exit 5).
unreachable_since=""
job_active() {
  local out
  if out="$(squeue -h -j "$JOB" -t "$ACTIVE_STATES" -o '%i' 2>&1)"; then
    unreachable_since=""
    [ -n "$out" ]
  elif [[ "$out" == *"Invalid job id"* ]]; then
    return 1
  else
    [ -n "$unreachable_since" ] || unreachable_since="$(now)"
    if ! within "$unreachable_since" "$UNREACHABLE_S"; then
      log "the controller has not answered for ${UNREACHABLE_S} s: $out"
      exit 5
    fi
    return 0
  fi
}

# Prints one index per line of an array index expression such as "2-3,5,8-14:3%2" (ranges, steps, throttle).
expand_indices() {
  local spec="${1%%\%*}" part first last step i
  local -a parts
  IFS=, read -ra parts <<<"$spec"
  for part in "${parts[@]}"; do
    [[ "$part" =~ ^([0-9]+)(-([0-9]+))?(:([0-9]+))?$ ]] || continue
    first="${BASH_REMATCH[1]}"
    last="${BASH_REMATCH[3]:-$first}"
    step="${BASH_REMATCH[5]:-1}"
    [ "$step" -gt 0 ] || step=1
    for ((i = first; i <= last; i += step)); do echo "$i"; done
  done
}

# Stores "STATE EXITCODE" for the index expression $1 (one index, "-", or a range of still pending tasks).
store() {
  local spec="$1" state="$2" code="$3" idx
  if [ "$spec" = "-" ]; then
    RESULT["-"]="$state $code"
    return
  fi
  while read -r idx; do
    [ -n "$idx" ] && RESULT["$idx"]="$state $code"
  done < <(expand_indices "$spec")
}

# Final states from sacct (accounting enabled). Returns 1 when sacct is absent or accounting is disabled.
states_from_sacct() {
  local out id state code
  command -v sacct >/dev/null 2>&1 || return 1
  out="$(sacct -n -X -P -j "$JOB" -o JobID,State,ExitCode 2>/dev/null)" || return 1
  [ -n "$out" ] || return 1
  while IFS='|' read -r id state code; do
    if [[ "$id" == *_* ]]; then id="${id#*_}"; else id="-"; fi
    id="${id#[}"
    id="${id%]}"                                    # an aggregated pending record such as 12_[4-7]
    store "$id" "${state%% *}" "${code:--}" # "CANCELLED by 0" -> CANCELLED
  done <<<"$out"
}

# Final states from the controller's job records (kept MinJobAge seconds after each task ends).
states_from_scontrol() {
  local out line idx state code
  out="$(scontrol -o show job "$JOB" 2>/dev/null)" || return 1
  [ -n "$out" ] || return 1
  while read -r line; do
    [[ " $line " =~ \ JobState=([^ ]+) ]] || continue
    state="${BASH_REMATCH[1]}"
    code="-"
    [[ " $line " =~ \ ExitCode=([^ ]+) ]] && code="${BASH_REMATCH[1]}"
    idx="-"
    [[ " $line " =~ \ ArrayTaskId=([^ ]+) ]] && idx="${BASH_REMATCH[1]}"
    store "$idx" "$state" "$code" # idx may be a range of pending tasks such as 4-7 (after a timeout)
  done <<<"$out"
}

# Last resort: squeue's view (states only).
states_from_squeue() {
  local out idx state
  out="$(squeue -h -r -j "$JOB" --states=all -o '%K %T' 2>/dev/null)" || return 1
  while read -r idx state; do
    [ -n "$idx" ] || continue
    [ "$idx" != "N/A" ] || idx="-"
    store "$idx" "$state" "-"
  done <<<"$out"
}

# ---------------------------------------------------------------------------------------------------------------

start="$(now)"
if ! record_expected; then
  log "job $JOB is not known to the controller (SLURM_CONF=${SLURM_CONF:-unset})"
  exit 4
fi

timed_out=0
while job_active; do
  if ! within "$start" "$TIMEOUT_S"; then
    timed_out=1
    break
  fi
  sleep "$POLL_S"
done
waited="$(elapsed_since "$start")"

states_from_sacct || states_from_scontrol || states_from_squeue || true
for idx in "${!EXPECTED[@]}"; do
  [ -n "${RESULT[$idx]:-}" ] || RESULT["$idx"]="UNKNOWN -"
done

# Indices in numeric order ("-" alone for a job that is not an array).
mapfile -t indices < <(printf '%s\n' "${!RESULT[@]}" | sort -n)
failed=()
for idx in "${indices[@]}"; do
  echo "TASK $idx ${RESULT[$idx]}"
  state="${RESULT[$idx]%% *}"
  if [ "$state" != "COMPLETED" ]; then
    # After a timeout only the tasks that already ended badly count as failed.
    if [ "$timed_out" -eq 0 ] || [[ ! "$state" =~ ^(PENDING|RUNNING|COMPLETING|CONFIGURING|SUSPENDED|REQUEUED|RESIZING|SIGNALING|STAGE_OUT|STOPPED|REQUEUE_HOLD|REQUEUE_FED|RESV_DEL_HOLD)$ ]]; then
      failed+=("$idx")
    fi
  fi
done
for idx in "${failed[@]}"; do echo "FAILED $idx"; done

if [ "$timed_out" -eq 1 ]; then
  log "job $JOB still running after ${TIMEOUT_S} s (${#failed[@]} task(s) failed so far)"
  exit 3
fi
if [ "${#failed[@]}" -gt 0 ]; then
  log "job $JOB finished in $waited s: ${#failed[@]} of ${#indices[@]} task(s) failed (index ${failed[*]})"
  exit 1
fi
log "job $JOB finished in $waited s: all ${#indices[@]} task(s) COMPLETED"
