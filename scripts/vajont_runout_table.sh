#!/usr/bin/env bash
# The Vajont run-out against the residual friction of the sliding surface: the crown's peak speed
# and horizontal travel, the toe's horizontal travel and rise, when the mass comes to rest, and the
# energy check. Run from the repository root after scripts/build. Prints a Markdown table
# (docs/vajont.md); the runs go to out/vajont_runout/phi_<angle>/.
set -euo pipefail
echo "| φ_res (°) | peak speed, crown (m/s) | horizontal travel, crown / toe (m) | toe rise (m) | at rest by (s) | energy gained / released | wall time (s) |"
echo "|---|---|---|---|---|---|---|"
for phi in "$@"; do
  dir="out/vajont_runout/phi_$phi"
  build/ddaslope run calibration/vajont_runout/case.json --set joints.sliding_surface.friction_angle="$phi" \
    --out "$dir" --quiet > /dev/null
  python3 - "$phi" "$dir" <<'PY'
import csv, json, math, sys
phi, d = sys.argv[1], sys.argv[2]
rows = list(csv.DictReader(open(d + "/history.csv")))
summary = json.load(open(d + "/summary.json"))
speed = lambda r, m: math.hypot(float(r[m + "_vx"]), float(r[m + "_vy"]))
peak = max(speed(r, "crown") for r in rows)
last = rows[-1]
rest = next((float(r["time"]) for r in rows if float(r["time"]) > 1 and float(r["kinetic_energy"]) < 1e-6 * summary["energy_J_per_m"]["scale"]), None)
e = summary["energy_J_per_m"]
print(f"| {phi} | {peak:.1f} | {float(last['crown_ux']):.0f} / {float(last['toe_ux']):.0f} | {float(last['toe_uy']):.0f} | "
      f"{'%.0f' % rest if rest else 'still moving'} | {e['largest_gain'] / e['scale']:.0e} | {summary['wall_time_s']:.0f} |")
PY
done
