#!/usr/bin/env bash
# The bounds on the Jiufengershan bedding's peak friction (docs/jiufengershan.md), c = 0:
#  - from below: it stood before the earthquake (the record scaled to 0);
#  - from above: it failed under the record, scaled to each nearby station's PGA [Q: USGS ShakeMap
#    station list], and under the nearest station's without its vertical component;
# and the yield coefficient k_y at the case's peak. About 1.5 minutes.
# With --sensitivity instead: the bounds against what the case assumes or the model chooses
# (strain damping, block model, Δt, weakening distance, toe block width, the record's seed and
# sign). About 4 minutes.
#   scripts/jiufengershan_table.sh [BINARY] [--sensitivity]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/ddaslope}
mode=${2:-}
case=cases/jiufengershan.json
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
crit() {
  "$bin" critical "$1" --joint bedding --solve friction --cohesion 0 --json "${@:2}" |
    python3 -c "import json, sys; d = json.load(sys.stdin); print(f\"{d['critical']:.2f}\")"
}
# A copy of the case with its record file made absolute and one change made by a Python snippet
# acting on the dict c (e.g. moving the toe joint).
variant() {
  python3 - "$case" "$tmp/variant.json" "$1" <<'PY'
import json, os, sys
c = json.load(open(sys.argv[1]))
rec = c["seismic"]["record"]
rec["file"] = os.path.join(os.path.abspath(os.path.dirname(sys.argv[1])), rec["file"])
exec(sys.argv[3])
json.dump(c, open(sys.argv[2], "w"))
PY
  echo "$tmp/variant.json"
}
if [ "$mode" = "--sensitivity" ]; then
  echo "| what changes | lower bound, no record (°) | upper bound, TCU071 (°) |"
  echo "|---|---|---|"
  row() { echo "| $1 | $(crit "${@:2}" --set seismic.record.scale=0) | $(crit "${@:2}") |"; }
  row "the case as shipped (strain damping 1, deformable, Δt 5 ms, weakening over 1 m, toe block 160 m)" $case
  row "strain damping 0 (Shi's undamped blocks)" $case --set analysis.strain_damping=0
  row "strain damping 0.3" $case --set analysis.strain_damping=0.3
  row "strain damping 3" $case --set analysis.strain_damping=3
  row "rigid blocks" $case --blocks rigid
  row "Δt 2 ms" $case --time-step 0.002
  row "weakening over 0.3 m" $case --set joints.bedding.weakening_distance=0.3
  row "weakening over 3 m" $case --set joints.bedding.weakening_distance=3
  for w in 100 250; do
    v=$(variant "import math; a = math.radians(22); c['section']['joint_sets'][0]['origin'] = [1390.8 - $w * math.cos(a), $w * math.sin(a)]")
    row "toe block $w m up-dip" "$v"
  done
  for seed in 7 2000; do
    python3 scripts/synthetic_record.py "$tmp/seed$seed.csv" --pga 0.655 --pgv 69.4 --vertical-ratio 0.6 --seed $seed >/dev/null
    v=$(variant "c['seismic']['record']['file'] = '$tmp/seed$seed.csv'")
    row "the record's seed $seed (same PGA, PGV and envelope)" "$v"
  done
  row "the record reversed (scale −1)" $case --set seismic.record.scale=-1
  exit 0
fi
echo "| input | PGA (g) | critical peak friction (°) |"
echo "|---|---|---|"
echo "| none: the slope before the earthquake (lower bound) | 0 | $(crit $case --set seismic.record.scale=0) |"
for s in "TCU089 0.333" "TCU072 0.489" "TCU071 0.655" "TCU084 1.157"; do
  set -- $s
  echo "| record scaled to $1 (upper bound) | $2 | $(crit $case --set seismic.record.scale=$(python3 -c "print($2 / 0.655)")) |"
done
# Without the vertical component: the same case with the record's vertical column left out.
echo "| TCU071, horizontal only | 0.655 | $(crit "$(variant "c['seismic']['record'].pop('vertical_column')")") |"
"$bin" critical $case --solve seismic-coefficient --direction +x --json |
  python3 -c "import json, sys; d = json.load(sys.stdin); print(f\"\nyield coefficient at the case's peak friction: k_y = {d['critical']:.4f}\")"
