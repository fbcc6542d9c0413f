#!/usr/bin/env bash
# F of each shipped slope as shipped and written another way (scripts/case_variants.py), with
# default settings: the table of docs/calibration.md, "The same slope written another way".
#   scripts/invariance_table.sh [VARIANT ARGS...]     (default: split; e.g. tjunctions, translate 5e5 5e6)
# DDASLOPE=path/to/ddaslope picks the binary (default build/ddaslope).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${DDASLOPE:-build/ddaslope}
variant=("${@:-split}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| case | as shipped | ${variant[*]} | change |"
echo "|---|---|---|---|"
for name in cohesive_block_42kpa chair_slide planar_failure_water planar_failure toppling_slope vajont stable_block_40deg; do
  src=cases/$name.json
  if grep -q '"section"' "$src"; then
    "$bin" cut "$src" --out "$work/$name" >/dev/null
    src=$work/$name/blocks.json
  fi
  python3 scripts/case_variants.py "$src" "$work/$name.variant.json" "${variant[@]}"
  a=$("$bin" fos "$src" --json --quiet | python3 -c "import json,sys; print('%.4f' % json.load(sys.stdin)['factor_of_safety'])")
  b=$("$bin" fos "$work/$name.variant.json" --json --quiet | python3 -c "import json,sys; print('%.4f' % json.load(sys.stdin)['factor_of_safety'])")
  echo "| $name | $a | $b | $(python3 -c "print('%+.1f %%' % (100 * ($b / $a - 1)))") |"
done
