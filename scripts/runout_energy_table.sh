#!/usr/bin/env bash
# Energy created by impacts (issue #14): the Vajont run-out with water (calibration/vajont_runout)
# at one residual friction, with rigid and deformable blocks at Δt = 10, 5, 2.5 and 1 ms. Prints
# the largest rise of the mechanical energy within one step and since t = 0, each as a fraction of
# the run's energy scale (summary.json), beside the steps, Δt cuts and steps with frozen contacts.
# Usage: scripts/runout_energy_table.sh [PHI_RES] [BIN]   (about 2 minutes; from the repository root)
set -euo pipefail
phi="${1:-12}"
bin="${2:-build/ddaslope}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
echo "| blocks | Δt (ms) | steps | Δt cuts | frozen steps | largest step rise / scale | rise since t = 0 / scale |"
echo "|---|---|---|---|---|---|---|"
for blocks in rigid deformable; do
  for dt in 0.01 0.005 0.0025 0.001; do
    "$bin" run calibration/vajont_runout/case.json --out "$tmp/r" --quiet --blocks "$blocks" --time-step "$dt" \
      --set joints.sliding_surface.friction_angle="$phi" >/dev/null 2>&1
    python3 - "$tmp/r/summary.json" "$blocks" "$dt" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
e = s["energy_J_per_m"]
print(f"| {sys.argv[2]} | {1000 * float(sys.argv[3]):g} | {s['steps']} | {s['time_step_cuts']} | "
      f"{s['steps_with_frozen_contacts']} | {e['largest_step_gain'] / e['scale']:.1e} | {e['largest_gain'] / e['scale']:.1e} |")
PY
  done
done
