#!/usr/bin/env bash
# Stand-in for the stochvib command line of the cluster contract, used by tests/slurm/example-array.sh:
#
#   stochvib-stub.sh simulate SCENARIO --realizations R --duration T --dt DT --seed S --shard auto|K --of N -o RUNDIR/
#   stochvib-stub.sh merge RUN RUNDIR/
#
# simulate fails (exit 1) while the file $STUB_FAIL_DIR/fail-<shard> exists: the test's injected failure.
# Otherwise, when STOCHVIB_REAL names a stochvib binary, the command is passed to it unchanged; without it the
# stub checks the arguments and the environment a shard sees and writes RUNDIR/shard-<K>.txt (one line: the
# shard, the shard count, R, the seed, the thread count), and merge checks that shards 0..N-1 are all there
# with the same N, R and seed, and writes their lines in shard order to RUN.
set -euo pipefail

die() {
  echo "stochvib-stub: $*" >&2
  exit 2
}

[ "$#" -ge 1 ] || die "no subcommand"
cmd="$1"
shift
case "$cmd" in
simulate)
  args=("$@")
  [ "$#" -ge 1 ] || die "simulate: no scenario"
  scenario="$1"
  shift
  r="" seed="" shard="" of="" out=""
  while [ "$#" -gt 0 ]; do
    [ "$#" -ge 2 ] || die "simulate: $1 needs a value"
    case "$1" in
    --realizations) r="$2" ;;
    --duration | --dt) ;;
    --seed) seed="$2" ;;
    --shard) shard="$2" ;;
    --of) of="$2" ;;
    -o) out="$2" ;;
    *) die "simulate: unknown option $1" ;;
    esac
    shift 2
  done
  [ -r "$scenario" ] || die "simulate: cannot read the scenario $scenario"
  for v in "$r" "$seed" "$shard" "$of" "$out"; do [ -n "$v" ] || die "simulate: missing option"; done
  # --shard auto: the index of the array task (SLURM) or of the indexed job (Kubernetes).
  if [ "$shard" = "auto" ]; then
    shard="${SLURM_ARRAY_TASK_ID:-${JOB_COMPLETION_INDEX:-}}"
    [ -n "$shard" ] || die "simulate: --shard auto outside an array task or indexed job"
  fi
  [ "$shard" -lt "$of" ] || die "simulate: shard $shard is not below --of $of"
  if [ "${out: -1}" != "/" ] || [ ! -d "$out" ]; then die "simulate: -o $out is not an existing directory ending in /"; fi
  if [ -e "${STUB_FAIL_DIR:-/nonexistent}/fail-$shard" ]; then
    echo "stochvib-stub: shard $shard fails on purpose" >&2
    exit 1
  fi
  if [ -n "${STOCHVIB_REAL:-}" ]; then exec "$STOCHVIB_REAL" simulate "${args[@]}"; fi
  echo "shard=$shard of=$of realizations=$r seed=$seed threads=${RAYON_NUM_THREADS:-unset}" >"$out/shard-$shard.txt.tmp"
  mv "$out/shard-$shard.txt.tmp" "$out/shard-$shard.txt"
  ;;
merge)
  [ "$#" -eq 2 ] || die "merge: usage: merge RUN RUNDIR/"
  if [ -n "${STOCHVIB_REAL:-}" ]; then exec "$STOCHVIB_REAL" merge "$@"; fi
  run="$1" dir="$2"
  [ -f "$dir/shard-0.txt" ] || die "merge: shard 0 is missing in $dir"
  line="$(cat "$dir/shard-0.txt")"
  of="${line#* of=}"
  of="${of%% *}"
  common="$(sed 's/^shard=[0-9]* //; s/ threads=.*//' <<<"$line")"
  : >"$run.tmp"
  for ((k = 0; k < of; k++)); do
    [ -f "$dir/shard-$k.txt" ] || die "merge: shard $k of $of is missing"
    line="$(cat "$dir/shard-$k.txt")"
    [ "$(sed 's/^shard=[0-9]* //; s/ threads=.*//' <<<"$line")" = "$common" ] || die "merge: shard $k differs: $line"
    echo "$line" >>"$run.tmp"
  done
  mv "$run.tmp" "$run"
  ;;
*) die "unknown subcommand $cmd" ;;
esac
