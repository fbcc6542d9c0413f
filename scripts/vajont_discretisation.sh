#!/usr/bin/env bash
# The Vajont back-analysed friction angle (c = 0, FS = 1 at reservoir 700.42 m) for several block
# layouts: 3 blocks (joints at the kinks only), then vertical joints every 100, 50, 25 m; each
# without kink blocks (a wide block's corner on each kink) and with the shipped 10 m kink blocks
# (section.kink_block_width). Run from the repository root after scripts/build. Prints a Markdown
# table (docs/vajont.md); about 6 minutes.
set -euo pipefail
mkdir -p out/vajont_layouts
echo "| layout | kink blocks | blocks | back-analysed φ (°) | forward runs | wall time (s) |"
echo "|---|---|---|---|---|---|"
for kink in 0 10; do
  for spacing in 0 100 50 25; do
    case_file="out/vajont_layouts/vajont_${spacing}_kink${kink}.json"
    python3 scripts/make_vajont_case.py --spacing "$spacing" --kink-block-width "$kink" --out "$case_file"
    blocks=$(build/ddaslope check "$case_file" | head -1 | sed -E 's/.*valid\. ([0-9]+) blocks.*/\1/')
    result=$(build/ddaslope critical "$case_file" --joint sliding_surface --solve friction --cohesion 0 --json)
    phi=$(echo "$result" | sed -n 's/.*"critical": \([0-9.]*\).*/\1/p')
    runs=$(echo "$result" | sed -n 's/.*"forward_runs": \([0-9]*\).*/\1/p')
    wall=$(echo "$result" | sed -n 's/.*"wall_time_s": \([0-9.]*\).*/\1/p')
    label=$([ "$spacing" = 0 ] && echo "joints at the two kinks only" || echo "vertical joints every $spacing m + lower kink")
    kinks=$([ "$kink" = 0 ] && echo "none" || echo "$kink m")
    printf "| %s | %s | %s | %.2f | %s | %.1f |\n" "$label" "$kinks" "$((blocks - 1))" "$phi" "$runs" "$wall"
  done
done
