#!/usr/bin/env bash
# The Vajont critical friction (c = 0, FS = 1 at 700.42 m) against the width of the kink blocks
# (section.kink_block_width; the shipped case has 10 m), beside the limit equilibrium of the same
# blocks (scripts/block_equilibrium.py, which needs Debian's python3-scipy). Run from the
# repository root after scripts/build. Prints a Markdown table (docs/vajont.md); about 2 minutes.
set -euo pipefail
shipped=$(python3 -c 'import json; print(json.load(open("cases/vajont.json"))["section"].get("kink_block_width", 0))')
echo "| kink blocks | blocks | blocks' bound | ddaslope \`critical\` | forward runs | wall time (s) |"
echo "|---|---|---|---|---|---|"
for width in 0 6 10 15; do
  bound=$(/usr/bin/python3 scripts/block_equilibrium.py cases/vajont.json --joint sliding_surface --solve friction \
    --cohesion 0 --kink-block-width "$width" | sed -n 's/.*can stand: \([0-9.]*\) deg (\([0-9]*\) blocks.*/\1 \2/p')
  result=$(build/ddaslope critical cases/vajont.json --joint sliding_surface --solve friction --cohesion 0 \
    --set section.kink_block_width="$width" --json)
  phi=$(echo "$result" | sed -n 's/.*"critical": \([0-9.]*\).*/\1/p')
  runs=$(echo "$result" | sed -n 's/.*"forward_runs": \([0-9]*\).*/\1/p')
  wall=$(echo "$result" | sed -n 's/.*"wall_time_s": \([0-9.]*\).*/\1/p')
  label=$([ "$width" = 0 ] && echo "none" || echo "$width m")
  [ "$(python3 -c "print(float('$width') == float('$shipped'))")" = True ] && label="$label (shipped)"
  printf "| %s | %s | %.2f° | %.2f° | %s | %.1f |\n" "$label" "$(( ${bound#* } - 1 ))" "${bound% *}" "$phi" "$runs" "$wall"
done
