#!/bin/bash
# The bilinear slab's F over the settings (docs/research/bilinear-slab.md), for the shipped case and
# for the section with its cross joint moved by hand d metres up the bedding (then nothing ends on
# the bend and the reader moves nothing), with the blocks' own bound for each.
# Usage (from the checkout): docs/research/bilinear-slab/sweep.sh [BINARY] [d ...]
set -e
DDA=${1:-build/ddaslope}
shift || true
OUT=$(mktemp -d)
settings=("" "--set analysis.penalty_factor=10" "--set analysis.penalty_factor=20" "--set analysis.penalty_factor=100"
          "--set analysis.penalty_factor=200" "--set analysis.penalty_factor=500" "--set analysis.penalty_factor=1000"
          "--set analysis.penalty_factor=2000" "--preset fast" "--preset accurate" "--time-step 2e-4" "--time-step 4e-3"
          "--threads 1" "--blocks rigid" "--contact-treatment vertex")
sweep() {
  local row="$1:"
  for s in "${settings[@]}"; do
    # shellcheck disable=SC2086
    row="$row $("$DDA" fos "$1" --json --quiet $s 2>/dev/null |
      /usr/bin/python3 -c "import json,sys; f=json.load(sys.stdin).get('factor_of_safety'); print('%.4f' % f if f else 'none')")"
  done
  echo "$row"
  /usr/bin/python3 scripts/block_equilibrium.py "$1" --solve fos --ddaslope "$DDA" | tail -1
}
echo "columns: default ${settings[*]:1}" | sed 's/ --/ | --/g'
sweep cases/bilinear_slab.json
for d in "$@"; do
  /usr/bin/python3 - "$d" "$OUT/moved_$d.json" <<'PY'
import json, math, sys
d = json.load(open("cases/bilinear_slab.json"))
delta = float(sys.argv[1])
up = (-math.cos(math.radians(50)), math.sin(math.radians(50)))  # up the bedding
d["section"]["joints"][0] = [[p[0] + delta * up[0], p[1] + delta * up[1]] for p in d["section"]["joints"][0]]
json.dump(d, open(sys.argv[2], "w"), indent=1)
PY
  sweep "$OUT/moved_$d.json"
done
rm -rf "$OUT"
