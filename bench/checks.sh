#!/bin/sh
# A design's question: does each shipped real slope meet a required F? `fos --check F`
# runs the one trial a search would run at F instead of the search (docs/calibration.md, "Checking a
# required F"). Prints one CSV line per case and F: the verdict, forward runs, steps after t = 0
# and before it (the equilibrium's static and settling steps), and wall time; compare the wall with
# bench/searches.sh, whose F tells which checks lie near the slope's F.
#
#   bench/checks.sh [BUILD_DIR] [FACTORS...]
#   bench/checks.sh build               # F = 1.0, 1.3 and 1.5
#   bench/checks.sh build 1.1 1.2
#
# Time nothing else while it runs (2 cores).
set -eu
build=${1:-build}
[ $# -ge 1 ] && shift
[ $# -ge 1 ] || set -- 1.0 1.3 1.5
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
echo "case,check,verdict,forward_runs,steps,equilibrium_steps,wall_s"
for case in vajont jiufengershan goodman_bray_toppling toppling_slope stepped_toppling bilinear_slab chair_slide planar_failure; do
  for f in "$@"; do
    start=$(date +%s.%N)
    # A check that fails to run prints no JSON: its line says so and the bench goes on.
    "$build/ddaslope" fos "$here/cases/$case.json" --check "$f" --quiet --json --out "$dir" > "$dir/out.json" || true
    end=$(date +%s.%N)
    python3 - "$case" "$f" "$dir/out.json" "$start" "$end" <<'PY'
import json, sys
case, f, path, start, end = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5])
try:
    d = json.load(open(path))
except ValueError:
    print(f"{case},{f},no result (see the command's error),,,,{end - start:.2f}")
    sys.exit(0)
trials = d.get("trials", [])
steps = sum(t["steps"] for t in trials)
before = sum(t["equilibrium_steps"] for t in trials)
print(f"{case},{f},{d['verdict']},{d['forward_runs']},{steps},{before},{end - start:.2f}")
PY
  done
done
