#!/usr/bin/env bash
# Renders the same reports and tables with two builds of stochvib and diffs them: `analyze` (text, JSON,
# markdown) of every data/*.toml, and parameter studies as CSV, JSON, HDF5 (dumped by h5py: every
# attribute and dataset, values in full precision; the files are also compared byte for byte), with
# verdicts, with a Monte Carlo batch, and split into shard files and merged; and one `optimize`.
#
#   scripts/compare-outputs.sh OLD_BINARY NEW_BINARY OUT_DIR
#
# Exit status 0 when every pair is identical; the differing files are listed otherwise.
set -u
old=$1 new=$2 out=$3
root=$(cd "$(dirname "$0")/.." && pwd)
if [ -e "$out/old" ] || [ -e "$out/new" ]; then
    echo "$out/old or $out/new exists: give an empty or new OUT_DIR" >&2
    exit 2
fi
mkdir -p "$out/old" "$out/new"

h5text() { # every attribute and dataset of an HDF5 file, sorted by path
    python3 - "$1" <<'EOF'
import sys, h5py, numpy as np
np.set_printoptions(threshold=sys.maxsize, precision=17, floatmode="unique")
def show(name, obj):
    print(name, dict(sorted((k, repr(v)) for k, v in obj.attrs.items())))
    if isinstance(obj, h5py.Dataset):
        print(" ", obj.dtype, obj.shape, repr(obj[()]))
with h5py.File(sys.argv[1], "r") as f:
    show("/", f)
    f.visititems(show)
EOF
}

render() { # render BINARY SIDE
    local b=$1 d=$out/$2
    for sc in "$root"/data/*.toml; do
        local n
        n=$(basename "$sc" .toml)
        "$b" analyze "$sc" >"$d/$n.analyze.txt" 2>&1
        "$b" analyze "$sc" --json >"$d/$n.analyze.json" 2>&1
        "$b" analyze "$sc" --format markdown >"$d/$n.analyze.md" 2>&1
    done
    local qc=$root/data/quarter-car.toml ht=$root/data/half-car.toml seat=$root/data/operator-seat-verdicts.toml
    local grid=(--param "model.element.0.damping=500..3000:7" --param "input.speed=5..30:4")
    "$b" sweep "$qc" "${grid[@]}" >"$d/qc.sweep.csv" 2>&1
    "$b" sweep "$qc" "${grid[@]}" --json >"$d/qc.sweep.json" 2>&1
    "$b" sweep "$qc" "${grid[@]}" -o "$d/qc.sweep.h5" >/dev/null 2>&1
    h5text "$d/qc.sweep.h5" >"$d/qc.sweep.h5.txt" 2>&1
    "$b" sweep "$ht" --param "input.speed=2..40:9" -o "$d/ht.sweep.h5" >/dev/null 2>&1
    h5text "$d/ht.sweep.h5" >"$d/ht.sweep.h5.txt" 2>&1
    "$b" sweep "$ht" --param "input.speed=2..40:9" >"$d/ht.sweep.csv" 2>&1
    "$b" sweep "$seat" --param "input.speed=2..12:4" --verdicts -o "$d/seat.verdicts.h5" >/dev/null 2>&1
    h5text "$d/seat.verdicts.h5" >"$d/seat.verdicts.h5.txt" 2>&1
    "$b" sweep "$seat" --param "input.speed=2..12:4" --verdicts --json >"$d/seat.verdicts.json" 2>&1
    "$b" sweep "$qc" --param "input.speed=10,20" --monte-carlo 20 --seed 3 --json >"$d/qc.mc.json" 2>&1
    "$b" sweep "$qc" --param "input.speed=10,20" --monte-carlo 20 --seed 3 -o "$d/qc.mc.h5" >/dev/null 2>&1
    h5text "$d/qc.mc.h5" >"$d/qc.mc.h5.txt" 2>&1
    "$b" sweep "$root/data/isolator-single.toml" --param "model.damping_ratio=0.05..0.5:4" -o "$d/iso.h5" >/dev/null 2>&1
    h5text "$d/iso.h5" >"$d/iso.h5.txt" 2>&1
    "$b" sweep "$root/data/conveyor-idler.toml" --param "model.zeta=0.05..0.5:4" --json >"$d/idler.json" 2>&1
    "$b" sweep "$root/data/scraper-sprung-cab.toml" --param "model.zeta2=0.1..0.4:4" >"$d/scraper.csv" 2>&1
    "$b" optimize "$root/data/quarter-car-model.toml" --param "model.suspension_damping=0.2:6 kN*s/m" \
        --minimize "sigma(body_acc)" --constraint "3sigma(travel) <= 40 mm" >"$d/optimize.txt" 2>&1
    for i in 0 1 2; do
        "$b" sweep "$qc" "${grid[@]}" --shard "$i" --of 3 -o "$d/shards" >/dev/null 2>&1
    done
    "$b" merge "$d/merged.csv" "$d/shards" >/dev/null 2>&1
    "$b" merge "$d/merged.json" "$d/shards" >/dev/null 2>&1
}

render "$old" old
render "$new" new
# the HDF5 files name their own path in no attribute; compare them byte for byte too
status=0 count=0
for f in "$out"/old/* "$out"/old/shards/*; do
    [ -f "$f" ] || continue
    rel=${f#"$out"/old/}
    count=$((count + 1))
    if ! cmp -s "$f" "$out/new/$rel"; then
        echo "differs: $rel"
        status=1
    fi
done
echo "$count files compared"
exit $status
