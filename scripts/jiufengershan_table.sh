#!/usr/bin/env bash
# The bounds on the Jiufengershan bedding's peak friction (docs/jiufengershan.md), c = 0:
#  - from below: it stood before the earthquake (the record scaled to 0);
#  - from above: it failed under the record, scaled to each nearby station's PGA [Q: USGS ShakeMap
#    station list] and without the vertical component;
# and the yield coefficient k_y at the case's peak. About 1.5 minutes.
#   scripts/jiufengershan_table.sh [BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/ddaslope}
case=cases/jiufengershan.json
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
crit() {
  "$bin" critical "$1" --joint bedding --solve friction --cohesion 0 --json "${@:2}" |
    python3 -c "import json, sys; d = json.load(sys.stdin); print(f\"{d['critical']:.2f}\")"
}
echo "| input | PGA (g) | critical peak friction (°) |"
echo "|---|---|---|"
echo "| none: the slope before the earthquake (lower bound) | 0 | $(crit $case --set seismic.record.scale=0) |"
for s in "TCU089 0.333" "TCU072 0.489" "TCU071 0.655" "TCU084 1.157"; do
  set -- $s
  echo "| record scaled to $1 (upper bound) | $2 | $(crit $case --set seismic.record.scale=$(python3 -c "print($2 / 0.655)")) |"
done
# Without the vertical component: the same case with the record's vertical column left out.
python3 - "$case" "$tmp/h_only.json" <<'PY'
import json, os, sys
c = json.load(open(sys.argv[1]))
c["seismic"]["record"].pop("vertical_column")
c["seismic"]["record"]["file"] = os.path.join(os.path.abspath(os.path.dirname(sys.argv[1])), c["seismic"]["record"]["file"])
json.dump(c, open(sys.argv[2], "w"))
PY
echo "| TCU071, horizontal only | 0.655 | $(crit "$tmp/h_only.json") |"
"$bin" critical $case --solve seismic-coefficient --direction +x --json |
  python3 -c "import json, sys; d = json.load(sys.stdin); print(f\"\nyield coefficient at the case's peak friction: k_y = {d['critical']:.4f}\")"
