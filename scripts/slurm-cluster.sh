#!/usr/bin/env bash
# A real single-node SLURM cluster on localhost, for tests (Debian/Ubuntu; works without systemd).
#
#   scripts/slurm-cluster.sh start  DIR   install what is missing, start munged + slurmctld + slurmd, wait for an idle node
#   scripts/slurm-cluster.sh stop   DIR   cancel the cluster's jobs, stop the daemons this cluster started (munged last)
#   scripts/slurm-cluster.sh status DIR   one line per daemon and the node state (exit 0 running, 1 partly, 3 stopped)
#   scripts/slurm-cluster.sh env    DIR   print the line(s) a caller evaluates: eval "$(scripts/slurm-cluster.sh env DIR)"
#   scripts/slurm-cluster.sh install      install the packages when missing (start does it too)
#
# Everything the cluster owns lives under DIR: the munge key, socket, seed, pid and log files, slurm.conf, the
# controller's state, the node's spool directory and the logs. Client commands (sbatch, squeue, scontrol, ...)
# find the cluster through SLURM_CONF=DIR/slurm.conf, which the `env` subcommand prints; slurm.conf names the
# cluster's own munge socket (AuthInfo=socket=...), so nothing outside DIR is used (no /run/munge, no /etc/slurm).
#
# Environment (all optional):
#   STOCHVIB_SLURM_CTLD_PORT      slurmctld port (default 6817)
#   STOCHVIB_SLURM_SLURMD_PORT    slurmd port (default 6818)
#   STOCHVIB_SLURM_START_TIMEOUT  seconds to wait for each start step and for the idle node (default 60)
#   STOCHVIB_SLURM_LOCK_DIR       where the port locks live (default /tmp/stochvib-slurm-locks)
#   STOCHVIB_SLURM_LOCK_WAIT      seconds `start` waits for ports held by another running cluster (default 0:
#                                 fail at once)
#
# Exit codes: 0 success; 1 failure (message on stderr, for start with the tail of the logs); 2 usage error;
# 3 `status` of a stopped cluster.
#
# Ports: a cluster holds one lock per port (a symlink LOCK_DIR/port-N -> DIR). A second cluster asking for a port
# held by a running cluster fails with a message naming the holder (after STOCHVIB_SLURM_LOCK_WAIT s); a lock
# whose holder is no longer running is taken over. A port in use by anything else is detected by connecting to
# it before starting.
#
# Processes: every daemon is started with STOCHVIB_SLURM_CLUSTER=DIR in its environment. `stop` signals a PID only
# when /proc/PID/comm is the expected daemon name AND that marker is in /proc/PID/environ, so it never touches
# another cluster's daemons or a recycled PID.
#
# Tested as root on Debian 12 (SLURM 22.05.8, munge 0.5.15). As another user the daemons run as that user
# (SlurmUser/SlurmdUser = the caller), which can only run that user's jobs; package installation uses sudo.
set -euo pipefail

readonly PROG="slurm-cluster"
readonly PACKAGES=(slurmctld slurmd slurm-client munge)
# Commands the script and its callers need; a missing one triggers the package installation.
readonly COMMANDS=(munged mungekey munge unmunge slurmctld slurmd sbatch squeue scontrol sinfo scancel)
readonly MARKER_VAR="STOCHVIB_SLURM_CLUSTER"

CTLD_PORT="${STOCHVIB_SLURM_CTLD_PORT:-6817}"
SLURMD_PORT="${STOCHVIB_SLURM_SLURMD_PORT:-6818}"
START_TIMEOUT="${STOCHVIB_SLURM_START_TIMEOUT:-60}"
LOCK_DIR="${STOCHVIB_SLURM_LOCK_DIR:-/tmp/stochvib-slurm-locks}"
LOCK_WAIT="${STOCHVIB_SLURM_LOCK_WAIT:-0}"

# ---------------------------------------------------------------------------------------------------------------
# Small helpers

log() { echo "$PROG: $*" >&2; }
die() {
  echo "$PROG: error: $*" >&2
  exit 1
}
# Prints the subcommand summary (the header above) and exits with $1 (default 2: usage error).
usage() {
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit "${1:-2}"
}

# Monotonic-enough wall clock in seconds with millisecond resolution (for timeouts and the printed durations).
now() { date +%s.%3N; }
elapsed_since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }
# True while fewer than $2 seconds have passed since $1.
within() { awk -v a="$1" -v b="$(now)" -v t="$2" 'BEGIN { exit !(b - a < t) }'; }

is_port() { [[ "$1" =~ ^[0-9]+$ ]] && [ "$1" -ge 1 ] && [ "$1" -le 65535 ]; }

# Sets every path of the cluster rooted at $1 (made absolute; the directory need not exist yet).
set_paths() {
  [ -n "$1" ] || usage
  DIR="$(realpath -m -- "$1")"
  CONF="$DIR/slurm.conf"
  MUNGE_DIR="$DIR/munge"             # key, seed, pid and log of munged (0700)
  MUNGE_SOCKET_DIR="$DIR/munge-socket" # munged requires its socket directory to be a+x (0755)
  MUNGE_SOCKET="$MUNGE_SOCKET_DIR/munge.socket"
  MUNGE_KEY="$MUNGE_DIR/munge.key"
  MUNGE_PID="$MUNGE_DIR/munged.pid"
  STATE_DIR="$DIR/state"             # slurmctld StateSaveLocation
  SPOOL_DIR="$DIR/spool"             # slurmd SlurmdSpoolDir
  LOG_DIR="$DIR/log"
  PID_DIR="$DIR/pid"
  CTLD_PID="$PID_DIR/slurmctld.pid"
  SLURMD_PID="$PID_DIR/slurmd.pid"
}

# The PID in pid file $2 when that process is alive, is named $1 and carries this cluster's marker; else nothing.
owned_pid() {
  local comm="$1" pidfile="$2" pid
  [ -r "$pidfile" ] || return 0
  pid="$(tr -dc '0-9' <"$pidfile")"
  [ -n "$pid" ] || return 0
  is_ours "$pid" "$comm" && echo "$pid"
  return 0
}

# True when process $1 is named $2 and was started by this cluster (marker in its environment; for a
# slurmstepd see is_our_step).
is_ours() {
  local pid="$1" comm="$2" actual
  if [ "$comm" = "slurmstepd" ]; then
    is_our_step "$pid"
    return
  fi
  { read -r actual <"/proc/$pid/comm"; } 2>/dev/null || return 1
  [ "$actual" = "$comm" ] || return 1
  # A process that has exited but is not yet reaped (zombie) has no readable environment: not alive.
  local environ
  environ="$({ tr '\0' '\n' <"/proc/$pid/environ"; } 2>/dev/null)" || return 1
  [[ $'\n'"$environ"$'\n' == *$'\n'"$MARKER_VAR=$DIR"$'\n'* ]]
}

# True when process $1 is a job step daemon (slurmstepd) of this cluster. slurmd starts slurmstepd with an empty
# environment (no marker), detached from itself (parent 1), but in slurmd's working directory (DIR/log) and
# holding slurmd's log file open: either path under DIR identifies the cluster.
is_our_step() {
  local pid="$1" fd comm
  { read -r comm <"/proc/$pid/comm"; } 2>/dev/null || return 1
  [ "$comm" = "slurmstepd" ] || return 1
  case "$(readlink "/proc/$pid/cwd" 2>/dev/null)" in "$DIR"/*) return 0 ;; esac
  for fd in "/proc/$pid/fd/"*; do
    case "$(readlink "$fd" 2>/dev/null)" in "$DIR"/*) return 0 ;; esac
  done
  return 1
}

# Every live slurmstepd of this cluster (job steps have no pid file).
step_pids() {
  local p
  for p in /proc/[0-9]*; do
    is_our_step "${p#/proc/}" && echo "${p#/proc/}"
  done
  return 0
}

# Prints "PID STARTTIME" for every descendant of the processes given (the job processes under a slurmstepd).
# One pass over /proc/*/stat, read by bash itself; STARTTIME (field 22, clock ticks after boot) tells a process
# from a later one that reuses its PID.
descendants() {
  local p line pid ppid
  local -a f queue
  local -A children=() start=()
  for p in /proc/[0-9]*; do
    { read -r line <"$p/stat"; } 2>/dev/null || continue
    pid="${line%% *}"
    read -ra f <<<"${line##*) }" # fields 3.. (state, ppid, ...), after the command name in parentheses
    ppid="${f[1]}"
    start["$pid"]="${f[19]}"
    children["$ppid"]+=" $pid"
  done
  queue=("$@")
  while [ "${#queue[@]}" -gt 0 ]; do
    p="${queue[0]}"
    queue=("${queue[@]:1}")
    for pid in ${children[$p]:-}; do
      echo "$pid ${start[$pid]}"
      queue+=("$pid")
    done
  done
}

# True when process $1 still exists, is not a zombie, and started at tick $2.
same_process() {
  local line
  local -a f
  { read -r line <"/proc/$1/stat"; } 2>/dev/null || return 1
  read -ra f <<<"${line##*) }"
  [ "${f[0]}" != "Z" ] && [ "${f[19]}" = "$2" ]
}

# Ends the job processes listed by descendants (lines "PID STARTTIME" on stdin): SIGTERM, up to 2 s (as
# KillWait), then SIGKILL.
kill_listed() {
  local pid st t0 alive p
  local -a procs=()
  while read -r pid st; do procs+=("$pid:$st"); done
  [ "${#procs[@]}" -gt 0 ] || return 0
  log "ending ${#procs[@]} job process(es) left by this cluster's job steps"
  for p in "${procs[@]}"; do
    if same_process "${p%:*}" "${p#*:}"; then kill -TERM "${p%:*}" 2>/dev/null || true; fi
  done
  t0="$(now)"
  while within "$t0" 2; do
    alive=0
    for p in "${procs[@]}"; do same_process "${p%:*}" "${p#*:}" && alive=1; done
    [ "$alive" -eq 1 ] || return 0
    sleep 0.05
  done
  for p in "${procs[@]}"; do
    if same_process "${p%:*}" "${p#*:}"; then kill -KILL "${p%:*}" 2>/dev/null || true; fi
  done
}

# SIGTERM the given PIDs (each re-checked against comm $1), wait up to $2 s for them to exit, then SIGKILL.
terminate() {
  local comm="$1" wait_s="$2" pid start alive
  shift 2
  [ "$#" -gt 0 ] || return 0
  for pid in "$@"; do
    if is_ours "$pid" "$comm"; then kill -TERM "$pid" 2>/dev/null || true; fi
  done
  start="$(now)"
  while :; do
    alive=()
    for pid in "$@"; do
      is_ours "$pid" "$comm" && alive+=("$pid")
    done
    [ "${#alive[@]}" -gt 0 ] || return 0
    within "$start" "$wait_s" || break
    sleep 0.05
  done
  log "$comm (pid ${alive[*]}) did not exit ${wait_s} s after SIGTERM: sending SIGKILL"
  for pid in "${alive[@]}"; do
    if is_ours "$pid" "$comm"; then kill -KILL "$pid" 2>/dev/null || true; fi
  done
  start="$(now)"
  while within "$start" 5; do
    alive=()
    for pid in "$@"; do
      is_ours "$pid" "$comm" && alive+=("$pid")
    done
    [ "${#alive[@]}" -gt 0 ] || return 0
    sleep 0.05
  done
  die "$comm (pid ${alive[*]}) survived SIGKILL"
}

# Prints the last lines of every log of the cluster (for error messages).
show_logs() {
  local f
  for f in "$MUNGE_DIR/munged.log" "$LOG_DIR/slurmctld.log" "$LOG_DIR/slurmd.log"; do
    if [ -s "$f" ]; then
      echo "----- last lines of $f" >&2
      tail -n 20 "$f" >&2
    fi
  done
}

# Fails the start: logs, stops whatever was started, exits 1.
start_failed() {
  echo "$PROG: error: $*" >&2
  show_logs
  log "stopping what was started (state and logs stay in $DIR)"
  do_stop >/dev/null 2>&1 || true
  exit 1
}

# Slurm client commands for this cluster.
sl() { SLURM_CONF="$CONF" "$@"; }

# ---------------------------------------------------------------------------------------------------------------
# install

do_install() {
  local missing=() c sudo="" start
  for c in "${COMMANDS[@]}"; do
    command -v "$c" >/dev/null 2>&1 || missing+=("$c")
  done
  [ "${#missing[@]}" -gt 0 ] || return 0
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  log "installing ${PACKAGES[*]} (missing: ${missing[*]})"
  start="$(now)"
  # policy-rc.d is not touched: without an init system invoke-rc.d starts nothing; any daemon a package
  # starts anyway uses its own files (/run/munge, /etc/slurm) and is not this cluster's.
  if ! DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" \
    >/dev/null 2>&1; then
    # Stale or missing package lists: refresh once and retry, showing the output this time.
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" >/dev/null
  fi
  for c in "${COMMANDS[@]}"; do
    command -v "$c" >/dev/null 2>&1 || die "$c is still missing after installing ${PACKAGES[*]}"
  done
  log "installed in $(elapsed_since "$start") s"
}

# ---------------------------------------------------------------------------------------------------------------
# Port locks

# Takes the locks of both ports for this cluster, or fails naming the cluster that holds one. The check and
# the take run under a flock on LOCK_DIR/mutex, so that two starts never both take a stale lock; the mutex is
# released before any daemon starts (a daemon must not inherit it).
lock_ports() {
  local mutex
  mkdir -p "$LOCK_DIR"
  chmod 1777 "$LOCK_DIR" 2>/dev/null || true # shared by every user, like /tmp
  touch "$LOCK_DIR/mutex"
  chmod 0666 "$LOCK_DIR/mutex" 2>/dev/null || true
  exec {mutex}<"$LOCK_DIR/mutex"
  flock "$mutex"
  lock_port "$CTLD_PORT"
  lock_port "$SLURMD_PORT"
  exec {mutex}<&-
}

# Takes the lock of port $1 (a symlink LOCK_DIR/port-N -> DIR), waiting up to LOCK_WAIT s while a running
# cluster holds it; a lock whose cluster is not running is stale and taken over.
lock_port() {
  local port="$1" link holder t0
  link="$LOCK_DIR/port-$port"
  t0="$(now)"
  while :; do
    # -n: an existing link to a directory is not followed (ln would create a link inside that directory).
    ln -sn "$DIR" "$link" 2>/dev/null && return 0
    holder="$(readlink "$link" 2>/dev/null)" || continue # removed meanwhile: try again
    [ "$holder" != "$DIR" ] || return 0                   # ours already (idempotent start)
    if (set_paths "$holder" && cluster_running_any); then
      if within "$t0" "$LOCK_WAIT"; then
        sleep 0.5
        continue
      fi
      unlock_ports # the other port, if this start took it already
      die "port $port is held by the running cluster in $holder; stop it (scripts/slurm-cluster.sh stop $holder), choose other ports (STOCHVIB_SLURM_CTLD_PORT, STOCHVIB_SLURM_SLURMD_PORT) or wait for it (STOCHVIB_SLURM_LOCK_WAIT)"
    fi
    log "taking over the stale lock of port $port (its cluster in $holder is not running)"
    rm -f "$link"
  done
}

unlock_ports() {
  local link
  for link in "$LOCK_DIR/port-$CTLD_PORT" "$LOCK_DIR/port-$SLURMD_PORT"; do
    if [ "$(readlink "$link" 2>/dev/null || true)" = "$DIR" ]; then rm -f "$link"; fi
  done
  return 0
}

# True when something accepts TCP connections on 127.0.0.1:$1.
port_in_use() { timeout 2 bash -c "exec 3<>/dev/tcp/127.0.0.1/$1" 2>/dev/null; }

# ---------------------------------------------------------------------------------------------------------------
# Configuration

# Creates the directories and the munge key (kept across restarts) and writes slurm.conf (every start).
prepare_files() {
  local node_line host user
  mkdir -p "$DIR" "$STATE_DIR" "$SPOOL_DIR" "$LOG_DIR" "$PID_DIR" "$MUNGE_DIR" "$MUNGE_SOCKET_DIR"
  chmod 0700 "$MUNGE_DIR"
  chmod 0755 "$MUNGE_SOCKET_DIR"
  # A key of our own, owned by the caller: munged refuses the packaged key when run as root ("insecure",
  # it belongs to the munge user).
  if [ ! -s "$MUNGE_KEY" ]; then
    mungekey -c -k "$MUNGE_KEY" >/dev/null 2>&1 || die "mungekey -c -k $MUNGE_KEY failed"
  fi
  chmod 0600 "$MUNGE_KEY"
  # The unix socket path must fit in sockaddr_un.sun_path (108 bytes including the NUL).
  [ "${#MUNGE_SOCKET}" -lt 108 ] || die "the cluster directory is too deep: $MUNGE_SOCKET is over 107 bytes"

  host="$(hostname -s)"
  user="$(id -un)"
  # The node as this machine reports it (CPUs, sockets, cores, threads, memory), reached on the loopback.
  node_line="$(slurmd -C 2>/dev/null)" || die "slurmd -C failed"
  node_line="$(sed -n '/^NodeName=/{p;q}' <<<"$node_line")"
  [ -n "$node_line" ] || die "slurmd -C printed no NodeName line"
  cat >"$CONF" <<EOF
# Generated by scripts/slurm-cluster.sh for the single-node test cluster in $DIR. Regenerated at every start.
ClusterName=stochvib-local
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=$user
SlurmdUser=$user
# Authentication through this cluster's own munged.
AuthType=auth/munge
AuthInfo=socket=$MUNGE_SOCKET
CredType=cred/munge
# No cgroups, no accounting daemon: plain process tracking, no task binding (every task sees every core,
# so a task must set its own thread count).
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# Schedule at once; bring the node back by itself after a restart.
SchedulerParameters=batch_sched_delay=0
ReturnToService=2
# Keep finished job records 300 s: a task that failed early is still visible when the last task ends
# (SLURM 22.05 forgets a finished task MinJobAge seconds after it ended, even while its array still runs).
MinJobAge=300
# Short grace between SIGTERM and SIGKILL of a cancelled job, so that stop is quick.
KillWait=2
StateSaveLocation=$STATE_DIR
SlurmdSpoolDir=$SPOOL_DIR/slurmd-%n
SlurmctldPidFile=$CTLD_PID
SlurmdPidFile=$SLURMD_PID
SlurmctldLogFile=$LOG_DIR/slurmctld.log
SlurmdLogFile=$LOG_DIR/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
$node_line NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
}

# ---------------------------------------------------------------------------------------------------------------
# State

# Sets MUNGED, SLURMCTLD, SLURMD to the PIDs of this cluster's live daemons (empty when not running).
read_pids() {
  MUNGED="$(owned_pid munged "$MUNGE_PID")"
  SLURMCTLD="$(owned_pid slurmctld "$CTLD_PID")"
  SLURMD="$(owned_pid slurmd "$SLURMD_PID")"
}
cluster_running_all() { read_pids && [ -n "$MUNGED" ] && [ -n "$SLURMCTLD" ] && [ -n "$SLURMD" ]; }
cluster_running_any() { read_pids && [ -n "$MUNGED$SLURMCTLD$SLURMD" ]; }

# State of the node as the controller sees it ("idle", "mixed", "down*", ...), or nothing.
node_state() { sl sinfo -h -N -o '%T' 2>/dev/null | head -n1 || true; }

# ---------------------------------------------------------------------------------------------------------------
# start

# Waits until command "$@" succeeds; $1 is what is waited for (for the error message).
wait_for() {
  local what="$1" start
  shift
  start="$(now)"
  until "$@" >/dev/null 2>&1; do
    within "$start" "$START_TIMEOUT" || start_failed "timed out after ${START_TIMEOUT} s waiting for $what"
    sleep 0.05
  done
}

munge_works() { munge -n -S "$MUNGE_SOCKET" | unmunge -S "$MUNGE_SOCKET"; }
pid_alive() { [ -n "$(owned_pid "$1" "$2")" ]; }
node_idle() { [ "$(node_state)" = "idle" ]; }

do_start() {
  local start state
  if ! is_port "$CTLD_PORT" || ! is_port "$SLURMD_PORT"; then
    die "ports must be integers in 1..65535 (got $CTLD_PORT, $SLURMD_PORT)"
  fi
  [ "$CTLD_PORT" != "$SLURMD_PORT" ] || die "the slurmctld and slurmd ports must differ (both $CTLD_PORT)"
  do_install
  start="$(now)"
  if cluster_running_all; then
    state="$(node_state)"
    log "already running in $DIR (munged $MUNGED, slurmctld $SLURMCTLD, slurmd $SLURMD; node ${state:-unknown};" \
      "ports $(sed -n 's/^SlurmctldPort=//p' "$CONF")/$(sed -n 's/^SlurmdPort=//p' "$CONF") from its slurm.conf)"
    return 0
  fi
  if cluster_running_any; then
    log "partly running in $DIR: stopping the rest before a clean start"
    do_stop
  fi
  lock_ports
  local p
  for p in "$CTLD_PORT" "$SLURMD_PORT"; do
    if port_in_use "$p"; then
      unlock_ports
      die "port $p is already in use by another program; choose other ports (STOCHVIB_SLURM_CTLD_PORT, STOCHVIB_SLURM_SLURMD_PORT)"
    fi
  done
  prepare_files
  rm -f "$MUNGE_PID" "$CTLD_PID" "$SLURMD_PID"

  # The daemons get no terminal and none of the caller's pipes (stdin from /dev/null, output to their logs), so
  # a caller that reads this script's output through a pipe sees it end.
  # 1. munged, with every file it uses under DIR; --force lets it replace a socket left by a killed munged.
  env "$MARKER_VAR=$DIR" munged --force --socket="$MUNGE_SOCKET" --key-file="$MUNGE_KEY" \
    --pid-file="$MUNGE_PID" --log-file="$MUNGE_DIR/munged.log" --seed-file="$MUNGE_DIR/munged.seed" \
    </dev/null >>"$MUNGE_DIR/munged.log" 2>&1 || start_failed "munged did not start"
  wait_for "munged to answer on $MUNGE_SOCKET" munge_works
  wait_for "munged's pid file" pid_alive munged "$MUNGE_PID"

  # 2. slurmctld (-c: forget the job and node state of a previous run). It daemonises and writes its pid file.
  env "$MARKER_VAR=$DIR" slurmctld -c -f "$CONF" </dev/null >>"$LOG_DIR/slurmctld.log" 2>&1 ||
    start_failed "slurmctld did not start"
  wait_for "slurmctld's pid file" pid_alive slurmctld "$CTLD_PID"
  # 3. slurmd, once the controller answers: a slurmd started earlier fails its first registration and
  # retries a second later (start 1.3 s instead of 0.2 s).
  wait_for "slurmctld to answer (scontrol ping)" sl scontrol ping
  env "$MARKER_VAR=$DIR" slurmd -f "$CONF" </dev/null >>"$LOG_DIR/slurmd.log" 2>&1 || start_failed "slurmd did not start"
  wait_for "slurmd's pid file" pid_alive slurmd "$SLURMD_PID"

  # 4. The node registers and becomes idle.
  local t0
  t0="$(now)"
  until node_idle; do
    read_pids
    [ -n "$SLURMCTLD" ] || start_failed "slurmctld exited during start"
    [ -n "$SLURMD" ] || start_failed "slurmd exited during start"
    within "$t0" "$START_TIMEOUT" || start_failed "the node is not idle after ${START_TIMEOUT} s (state: $(node_state))"
    sleep 0.05
  done
  read_pids
  log "started in $(elapsed_since "$start") s: munged $MUNGED, slurmctld $SLURMCTLD, slurmd $SLURMD; node idle (ports $CTLD_PORT/$SLURMD_PORT)"
}

# ---------------------------------------------------------------------------------------------------------------
# stop

do_stop() {
  local start ids t0 steps
  start="$(now)"
  read_pids
  if [ -z "$MUNGED$SLURMCTLD$SLURMD" ] && [ -z "$(step_pids)" ]; then
    unlock_ports_from_conf
    log "not running in $DIR"
    return 0
  fi
  # 1. Cancel every job still known to the controller, so that no job step outlives the cluster, and wait
  #    (KillWait=2 s plus margin) until none is pending, running or completing.
  if [ -n "$SLURMCTLD" ] && [ -n "$MUNGED" ]; then
    ids="$(sl squeue -h -o '%A' 2>/dev/null | tr '\n' ' ' || true)"
    if [ -n "${ids// /}" ]; then
      # shellcheck disable=SC2086 # one argument per job id
      sl scancel $ids 2>/dev/null || true
      t0="$(now)"
      while within "$t0" 15 && [ -n "$(sl squeue -h -o '%A' 2>/dev/null || true)" ]; do sleep 0.1; done
    fi
  fi
  # 2. slurmd, slurmctld, then any job step (slurmstepd) of this cluster they left, munged last (the daemons
  #    authenticate through it while they shut down). Each is waited for before the next is signalled.
  terminate slurmd 10 ${SLURMD:+"$SLURMD"}
  terminate slurmctld 20 ${SLURMCTLD:+"$SLURMCTLD"}
  # A job step survives its slurmd (by design) and is left running when the jobs could not be cancelled
  # (controller or munged already dead): end its job processes, then the step itself.
  steps="$(step_pids | tr '\n' ' ')"
  if [ -n "${steps// /}" ]; then
    # shellcheck disable=SC2086 # one argument per pid
    descendants $steps | kill_listed
    # A step whose controller is gone does not exit on SIGTERM (it keeps trying to report): 2 s, then SIGKILL.
    # shellcheck disable=SC2086
    terminate slurmstepd 2 $steps
  fi
  terminate munged 10 ${MUNGED:+"$MUNGED"}
  rm -f "$MUNGE_PID" "$CTLD_PID" "$SLURMD_PID"
  unlock_ports_from_conf
  log "stopped in $(elapsed_since "$start") s"
}

# Releases the port locks of this cluster: the ports it was started with are the ones in its slurm.conf.
unlock_ports_from_conf() {
  if [ -r "$CONF" ]; then
    CTLD_PORT="$(sed -n 's/^SlurmctldPort=//p' "$CONF")"
    SLURMD_PORT="$(sed -n 's/^SlurmdPort=//p' "$CONF")"
  fi
  unlock_ports
}

# ---------------------------------------------------------------------------------------------------------------
# status, env

do_status() {
  local state name var pid
  read_pids
  for name in munged slurmctld slurmd; do
    var="${name^^}" # MUNGED, SLURMCTLD, SLURMD
    pid="${!var}"
    if [ -n "$pid" ]; then printf '%-10s running pid %s\n' "$name" "$pid"; else printf '%-10s stopped\n' "$name"; fi
  done
  if [ -n "$MUNGED" ] && [ -n "$SLURMCTLD" ]; then state="$(node_state)"; else state=""; fi
  printf '%-10s %s\n' node "${state:-unknown}"
  if [ -n "$MUNGED" ] && [ -n "$SLURMCTLD" ] && [ -n "$SLURMD" ]; then return 0; fi
  if [ -z "$MUNGED$SLURMCTLD$SLURMD" ]; then return 3; fi
  return 1
}

do_env() { printf 'export SLURM_CONF=%q\n' "$CONF"; }

# ---------------------------------------------------------------------------------------------------------------

main() {
  [ "$#" -ge 1 ] || usage
  local cmd="$1"
  shift
  case "$cmd" in
  install)
    [ "$#" -eq 0 ] || usage
    do_install
    ;;
  start | stop | status | env)
    [ "$#" -eq 1 ] || usage
    set_paths "$1"
    "do_$cmd"
    ;;
  -h | --help | help) usage 0 ;;
  *) usage ;;
  esac
}

main "$@"
