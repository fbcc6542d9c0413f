#!/usr/bin/env bash
# Sensitivity of the Vajont back-analysed friction angle (c = 0, FS = 1 at 700.42 m a.s.l.) to the
# two reconstructed inputs that matter most: the upper kink x_b of the sliding surface (560-700 m)
# and the datum of the model frame (600-630 m a.s.l.). Run from the repository root after
# scripts/build. Prints a Markdown table (docs/vajont.md).
set -euo pipefail
mkdir -p out/vajont_sensitivity
echo "| x_b (m) | datum (m a.s.l.) | reservoir in the model (y, m) | back-analysed φ (°) | forward runs | wall time (s) |"
echo "|---|---|---|---|---|---|"
run() {
  local kink=$1 datum=$2 file="out/vajont_sensitivity/vajont_${1}_${2}.json"
  python3 scripts/make_vajont_case.py --kink "$kink" --datum "$datum" --out "$file"
  local result phi runs wall
  result=$(build/ddaslope critical "$file" --joint sliding_surface --solve friction --cohesion 0 --json)
  phi=$(echo "$result" | sed -n 's/.*"critical": \([0-9.]*\).*/\1/p')
  runs=$(echo "$result" | sed -n 's/.*"forward_runs": \([0-9]*\).*/\1/p')
  wall=$(echo "$result" | sed -n 's/.*"wall_time_s": \([0-9.]*\).*/\1/p')
  printf "| %s | %s | %.2f | %.2f | %s | %.1f |\n" "$kink" "$datum" "$(echo "700.42 - $datum" | bc)" "$phi" "$runs" "$wall"
}
for kink in 560 600 650 700; do run "$kink" 630; done
run 650 600
