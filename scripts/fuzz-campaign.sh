#!/usr/bin/env bash
# The fuzz campaign of tests/fuzz/README.md: CASES generated cases of SEED (TOML inputs, road profiles,
# replay, sweep grids and flags, merge sets, workday files; every CLI_EVERY-th also through the CLI) plus
# the special files and output targets, stopped after BUDGET seconds at the latest, at the lowest CPU
# priority and with one worker process. The totals per format and command (cases, CLI runs, panics,
# signals, hangs, findings) go to TOTALS (JSON), reproducers of any finding to FINDINGS.
#
#   scripts/fuzz-campaign.sh --cases 250000 --seed 2801 --budget-s 21600 --totals tests/fuzz/campaigns/2801.json
#
# Options (defaults): --cases N (10000), --seed S (1), --budget-s S (none), --cli-every K (1000),
# --timeout-ms T (10000, per in-process case), --totals FILE (target/tmp/fuzz-campaign-SEED.json),
# --findings DIR (target/tmp/fuzz-campaign-findings-SEED). Exit status 1 if an asserted invariant broke.
set -euo pipefail
cd "$(dirname "$0")/.."
cases=10000 seed=1 budget=null cli_every=1000 timeout_ms=10000 totals="" findings=""
while [ $# -gt 0 ]; do
    case "$1" in
        --cases) cases=$2; shift 2 ;;
        --seed) seed=$2; shift 2 ;;
        --budget-s) budget=$2; shift 2 ;;
        --cli-every) cli_every=$2; shift 2 ;;
        --timeout-ms) timeout_ms=$2; shift 2 ;;
        --totals) totals=$(realpath -m "$2"); shift 2 ;;
        --findings) findings=$(realpath -m "$2"); shift 2 ;;
        *) sed -n '2,16p' "$0"; exit 2 ;;
    esac
done
json="{\"seed\": $seed, \"cases\": $cases, \"budget_s\": $budget, \"cli_every\": $cli_every, \"timeout_ms\": $timeout_ms"
[ -n "$totals" ] && json="$json, \"totals\": \"$totals\""
[ -n "$findings" ] && json="$json, \"findings\": \"$findings\""
json="$json}"
# a snapshot of the two binaries, so that a rebuild while the campaign runs changes nothing of it
snap=$(realpath -m "target/tmp/fuzz-campaign-bin-$seed-$$")
mkdir -p "$snap"
exe=$(nice -n 19 cargo test --locked --workspace --tests --no-run --message-format=json \
    | sed -n 's/.*"executable":"\([^"]*\/suite-[^"]*\)".*/\1/p' | tail -n 1)
[ -x "$exe" ] || { echo "fuzz campaign: no test binary built" >&2; exit 2; }
cp "$exe" "$snap/suite"
cp target/debug/stochvib "$snap/stochvib"
json="${json%\}}, \"bin\": \"$snap/stochvib\"}"
log=$(mktemp)
STOCHVIB_FUZZ_CAMPAIGN="$json" nice -n 19 "$snap/suite" fuzz_inputs::fuzz_campaign \
    --ignored --exact --nocapture --test-threads=1 | tee "$log"
rm -rf "$snap"
# the campaign reports broken invariants in its summary; any asserted class fails the script
if grep -q '^cases with findings, by class (hard): none' "$log"; then
    rm -f "$log"
else
    echo "fuzz campaign: asserted invariants broken (see the summary above)" >&2
    rm -f "$log"
    exit 1
fi
