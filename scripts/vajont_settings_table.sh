#!/usr/bin/env bash
# The Vajont rows of docs/accuracy.md's rigid-block and preset tables: the critical friction of
# cases/vajont.json (c = 0) and the run-out at φ_res = 5.54° (a fixed input, so that the rows compare
# across versions; the back-analysed estimate is docs/vajont.md's), each with the case's own settings,
# rigid blocks and the three presets, with wall times.
# Usage: scripts/vajont_settings_table.sh [BIN]   (about 4 minutes; from the repository root; time
# it on an otherwise idle machine)
set -euo pipefail
bin="${1:-build/ddaslope}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
phi_res=5.54
echo "| settings | critical φ (°), wall (s) | run-out at ${phi_res}°: crown travel (m), peak speed (m/s), wall (s) |"
echo "|---|---|---|"
for opt in "" "--blocks rigid" "--preset fast" "--preset balanced" "--preset accurate"; do
  # shellcheck disable=SC2086
  crit=$("$bin" critical cases/vajont.json --joint sliding_surface --solve friction --cohesion 0 $opt --json)
  # shellcheck disable=SC2086
  "$bin" run calibration/vajont_runout/case.json --set joints.sliding_surface.friction_angle="$phi_res" $opt \
    --out "$tmp/r" --quiet >/dev/null
  label="${opt:-own settings}"
  python3 - "$label" "$crit" "$tmp/r" <<'PY'
import csv, json, math, sys
label, crit, d = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3]
rows = list(csv.DictReader(open(d + "/history.csv")))
s = json.load(open(d + "/summary.json"))
travel = max(float(r["crown_ux"]) for r in rows)
speed = max(math.hypot(float(r["crown_vx"]), float(r["crown_vy"])) for r in rows)
print(f"| {label} | {crit['critical']:.3f}, {crit['wall_time_s']:.1f} | {travel:.0f}, {speed:.1f}, {s['wall_time_s']:.1f} |")
PY
done
