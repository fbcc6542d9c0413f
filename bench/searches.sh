#!/bin/sh
# Users' workloads (issue #42): a factor of safety of each shipped real slope, with the figures a
# search's cost is made of: forward runs, steps summed over its trials (after t = 0, and before it:
# the equilibrium's static and settling steps), wall time, runs made ahead of need and not used
# (their steps are not in the sums); and F, which
# must not change when the search gets faster. Prints one CSV line per case and setting.
#
#   bench/searches.sh [BUILD_DIR] [THREADS] [EXTRA --set ARGUMENTS...]
#   bench/searches.sh build 2                                   # as shipped
#   bench/searches.sh build 2 --set analysis.early_rest=false   # without early rest
#   bench/searches.sh build 2 --no-look-ahead                   # no trial run ahead of need
#   bench/searches.sh /tmp/old/build 2                          # an older build, for a same-hour ratio
#
# A case an older build cannot read prints empty figures; equilibrium steps it did not report
# print as 0.
# Time nothing else while it runs (2 cores).
set -eu
build=${1:-build}
threads=${2:-2}
[ $# -ge 2 ] && shift 2 || shift $#
here=$(cd "$(dirname "$0")/.." && pwd)
echo "case,factor_of_safety,forward_runs,steps,equilibrium_steps,early_rest_trials,wall_s,runs_ahead_unused"
for case in vajont jiufengershan goodman_bray_toppling toppling_slope stepped_toppling bilinear_slab chair_slide planar_failure; do
  out=$(mktemp)
  start=$(date +%s.%N)
  "$build/ddaslope" fos "$here/cases/$case.json" --quiet --json --threads "$threads" "$@" > "$out" || true
  end=$(date +%s.%N)
  python3 - "$case" "$out" "$start" "$end" <<'PY'
import json, sys
case, path, start, end = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
try:
    d = json.load(open(path))
except ValueError:  # the build could not run the case (an older build: a key it does not know)
    print(f"{case},,,,,,{end - start:.2f},")
    sys.exit(0)
trials = d.get("trials", [])
steps = sum(t["steps"] for t in trials)
before = sum(t.get("equilibrium_steps", 0) for t in trials)  # older builds did not count them
early = sum(1 for t in trials if t.get("early_rest"))
print(f"{case},{d['factor_of_safety']},{d['forward_runs']},{steps},{before},{early},{end - start:.2f},{d.get('runs_ahead_unused', '')}")
PY
  rm -f "$out"
done
