#!/usr/bin/env bash
# The cluster contract end to end on a real SLURM cluster with the real stochvib binary:
#
#   STOCHVIB=/path/to/stochvib tests/slurm/real-array.sh
#
# 1. starts a single-node SLURM cluster on localhost (scripts/slurm-cluster.sh: installs the Debian packages
#    when missing, state under a temporary directory, daemons stopped by their PIDs on exit, even on failure);
# 2. submits the shipped batch script examples/cluster/slurm-array.sbatch as an array of 4 shards
#    (`sbatch --array=0-3`), shard 2 made to fail (its `stochvib simulate` exits 1 while the file fail-2 exists);
# 3. checks that exactly index 2 failed (scripts/slurm-wait.sh), that the other three shard files exist, and
#    that `stochvib merge` refuses the run directory, naming shard 2 and `--array=2`, writing nothing;
# 4. resubmits index 2 alone (`sbatch --array=2`; the script passes --of 4 itself), merges, and compares the
#    merged file with a single-process run of the same scenario and seed bit for bit: every dataset and every
#    attribute under /statistics and /psd (h5py, as unsigned integers); `stochvib inspect` reads it (checksums).
#
# Exit 0: PASS. Exit 1: FAIL ("real-array: FAIL: ..."; the cluster's directory is kept). Exit 77: the cluster
# could not be started here (no root or sudo, no Debian packages, ports held): scripts/test.sh decides whether
# that fails the suite (see STOCHVIB_SLURM_TEST there). Times of every step go to stderr.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/../.." && pwd -P)"
CLUSTER="$ROOT/scripts/slurm-cluster.sh"
WAIT="$ROOT/scripts/slurm-wait.sh"
SBATCH_SCRIPT="$ROOT/examples/cluster/slurm-array.sbatch"
readonly JOB_TIMEOUT_S=180 # shards of a fraction of a second; the margin is for a loaded machine
BIN="${STOCHVIB:?set STOCHVIB to the stochvib binary (e.g. target/debug/stochvib)}"
BIN="$(realpath "$BIN")"
[ -x "$BIN" ] || {
  echo "real-array: FAIL: $BIN is not an executable" >&2
  exit 1
}

DIR=""
KEEP=0
T0="$(date +%s.%N)"
step() { awk -v a="$T0" -v b="$(date +%s.%N)" -v m="$*" 'BEGIN { printf "real-array: [%6.2f s] %s\n", b - a, m }' >&2; }
fail() {
  KEEP=1
  echo "real-array: FAIL: $*" >&2
  [ -z "$DIR" ] || echo "real-array: directory kept for inspection: $DIR" >&2
  exit 1
}
cleanup() {
  local rc=$?
  if [ -n "$DIR" ]; then
    "$CLUSTER" stop "$DIR/cluster" >/dev/null 2>&1 || echo "real-array: stopping the cluster failed" >&2
    if [ "$KEEP" -eq 0 ] && [ "$rc" -eq 0 ]; then rm -rf "$DIR"; fi
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Waits for job $1; sets WAIT_RC, FAILED (failed indices, space-separated) and TASKS (the TASK lines).
wait_job() {
  local out
  set +e
  out="$("$WAIT" "$1" "$JOB_TIMEOUT_S" 2>/dev/null)"
  WAIT_RC=$?
  set -e
  TASKS="$(grep '^TASK ' <<<"$out" || true)"
  FAILED="$(sed -n 's/^FAILED //p' <<<"$out" | tr '\n' ' ' | sed 's/ $//')"
}

DIR="$(mktemp -d "${TMPDIR:-/tmp}/stochvib-slurm-real.XXXXXX")"
chmod 0755 "$DIR"
if ! STOCHVIB_SLURM_LOCK_WAIT="${STOCHVIB_SLURM_LOCK_WAIT:-120}" "$CLUSTER" start "$DIR/cluster"; then
  echo "real-array: the SLURM cluster could not be started on this machine (see the messages above; its files: $DIR/cluster)" >&2
  KEEP=1
  exit 77
fi
eval "$("$CLUSTER" env "$DIR/cluster")"
step "cluster started"

WORK="$DIR/work"
mkdir -p "$WORK/logs"
cd "$WORK"
# The shard's command: the real binary, except that `simulate` fails while $WORK/fail-<index> exists.
cat >stochvib-with-failure <<EOF
#!/bin/sh
if [ "\$1" = simulate ] && [ -e "$WORK/fail-\${SLURM_ARRAY_TASK_ID:-none}" ]; then
  echo "shard \$SLURM_ARRAY_TASK_ID fails on purpose (injected by the test)" >&2
  exit 1
fi
exec "$BIN" "\$@"
EOF
chmod +x stochvib-with-failure
# 4 shards of 200 realizations of 1 s at dt = 0.01 s: 4 internal shards of 50 (the default --shard-size).
export STOCHVIB="$WORK/stochvib-with-failure"
export SCENARIO="$ROOT/data/quarter-car.toml" REALIZATIONS=200 DURATION=1 DT=0.01 SEED=2026 SHARDS=4
export RUNDIR="runs/qc"
RES=(--cpus-per-task=1 --mem=200M) # the example asks for 4 cores and 4 GB; this node may have 2 cores

# 1. The array, shard 2 failing.
touch fail-2
jid="$(sbatch --parsable --array=0-3 "${RES[@]}" "$SBATCH_SCRIPT")" || fail "sbatch of the array failed"
wait_job "$jid"
step "array $jid of 4 shards finished: $(tr '\n' ';' <<<"$TASKS")"
[ "$WAIT_RC" -eq 1 ] && [ "$FAILED" = "2" ] || fail "array $jid: slurm-wait exit $WAIT_RC, failed '$FAILED' (expected 1, '2')"
for k in 0 1 3; do [ -s "runs/qc/shard-$k-of-4.h5" ] || fail "no file of shard $k: $(cat "logs/stochvib-mc-${jid}_$k.out")"; done
[ ! -e runs/qc/shard-2-of-4.h5 ] || fail "the failed shard 2 left a finished file"

# 2. The merge refuses while index 2 is missing, and names it.
set +e
err="$("$BIN" merge runs/qc.h5 runs/qc/ 2>&1 >/dev/null)"
rc=$?
set -e
[ "$rc" -ne 0 ] || fail "merge accepted a run directory without shard 2"
grep -q "missing shard(s) 2 " <<<"$err" && grep -q -- "--array=2 " <<<"$err" ||
  fail "the merge's refusal does not name shard 2 and --array=2: $err"
[ ! -e runs/qc.h5 ] || fail "the refused merge wrote runs/qc.h5"
step "merge refused: $(head -c 300 <<<"$err")"

# 3. Resubmit index 2 alone, merge.
rm fail-2
jid2="$(sbatch --parsable --array=2 "${RES[@]}" "$SBATCH_SCRIPT")" || fail "sbatch of the rerun failed"
wait_job "$jid2"
[ "$WAIT_RC" -eq 0 ] || fail "rerun $jid2: slurm-wait exit $WAIT_RC: $TASKS"
step "rerun $jid2 of index 2 completed"
t="$(date +%s.%N)"
"$BIN" merge runs/qc.h5 runs/qc/ >merge.out 2>&1 || fail "merge failed: $(cat merge.out)"
step "merged 4 shard files ($(awk -v a="$t" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }') s)"

# 4. The same run in one process, and the comparison bit for bit.
"$BIN" simulate "$SCENARIO" --realizations "$REALIZATIONS" --duration "$DURATION" --dt "$DT" --seed "$SEED" \
  -o whole.h5 >whole.out 2>&1 || fail "single-process run failed: $(cat whole.out)"
step "single-process run done"
"$BIN" inspect runs/qc.h5 >inspect.out 2>&1 || fail "inspect of the merged file (checksums): $(cat inspect.out)"
python3 - runs/qc.h5 whole.h5 <<'EOF' || fail "the merged file differs from the single-process run (above)"
import sys, h5py, numpy as np

def bits(v):
    a = np.asarray(v)
    return a.view(np.uint64).tolist() if a.dtype == np.float64 else a.tolist()

def walk(f, root):
    out = {}
    def visit(name, obj):
        key = f"{root}/{name}"
        for k, v in obj.attrs.items():
            out[f"{key}@{k}"] = bits(v)
        if isinstance(obj, h5py.Dataset):
            out[key] = bits(obj[()])
    for k, v in f[root].attrs.items():
        out[f"{root}@{k}"] = bits(v)
    f[root].visititems(visit)
    return out

m, w = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
bad, n = [], 0
for root in ("statistics", "psd"):
    a, b = walk(m, root), walk(w, root)
    if a.keys() != b.keys():
        bad.append(f"{root}: different entries: {sorted(set(a) ^ set(b))}")
    for k in a.keys() & b.keys():
        n += 1
        if a[k] != b[k]:
            bad.append(k)
if bad:
    print("differ:", bad[:20], file=sys.stderr)
    sys.exit(1)
print(f"{n} datasets and attributes under /statistics and /psd identical bit for bit")
EOF
step "merged file = single-process run, bit for bit"

cd /
"$CLUSTER" stop "$DIR/cluster" >/dev/null 2>&1 || fail "stop failed"
step "cluster stopped"
echo "real-array: PASS"
