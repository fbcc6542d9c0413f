#!/usr/bin/env bash
# The Vajont back-analysed friction angle (c = 0, FS = 1 at reservoir 700.42 m) for several block
# layouts: 3 blocks (joints at the kinks only), then vertical joints every 100, 50, 25 m.
# Run from the repository root after scripts/build. Prints a Markdown table (docs/vajont.md).
set -euo pipefail
mkdir -p out/vajont_layouts
echo "| layout | blocks | back-analysed φ (°) | forward runs | wall time (s) |"
echo "|---|---|---|---|---|"
for spacing in 0 100 50 25; do
  case_file="out/vajont_layouts/vajont_${spacing}.json"
  python3 scripts/make_vajont_case.py --spacing "$spacing" --out "$case_file"
  blocks=$(build/ddaslope check "$case_file" | head -1 | sed -E 's/.*valid\. ([0-9]+) blocks.*/\1/')
  result=$(build/ddaslope critical "$case_file" --joint sliding_surface --solve friction --cohesion 0 --json)
  phi=$(echo "$result" | sed -n 's/.*"critical": \([0-9.]*\).*/\1/p')
  runs=$(echo "$result" | sed -n 's/.*"forward_runs": \([0-9]*\).*/\1/p')
  wall=$(echo "$result" | sed -n 's/.*"wall_time_s": \([0-9.]*\).*/\1/p')
  label=$([ "$spacing" = 0 ] && echo "joints at the two kinks only" || echo "vertical joints every $spacing m + lower kink")
  printf "| %s | %s | %.2f | %s | %.1f |\n" "$label" "$((blocks - 1))" "$phi" "$runs" "$wall"
done
