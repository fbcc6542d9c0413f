#!/bin/sh
# Users' critical-value searches: critical cohesion and friction, the support or load
# for a factor of safety, and the yield seismic coefficient, on shipped cases, with what a search's
# cost is made of: forward runs, runs made ahead of need and not used, wall time, steps summed over
# the trials (after t = 0, and before it: the equilibrium's static and settling steps; a search
# whose trials are not listed at the top level leaves them empty); and the answer,
# which must not change when the search gets faster. Prints one CSV line per search.
#
#   bench/critical_searches.sh [BUILD_DIR] [THREADS] [EXTRA ARGUMENTS...]
#   bench/critical_searches.sh build 2                    # as shipped
#   bench/critical_searches.sh build 2 --no-look-ahead    # no trial run ahead of need
#
# Time nothing else while it runs (2 cores).
set -eu
build=${1:-build}
threads=${2:-2}
[ $# -ge 2 ] && shift 2 || shift $#
here=$(cd "$(dirname "$0")/.." && pwd)
echo "search,critical,forward_runs,runs_ahead_unused,wall_s,steps,equilibrium_steps"
while IFS='|' read -r name args; do
  out=$(mktemp)
  start=$(date +%s.%N)
  # shellcheck disable=SC2086
  "$build/ddaslope" critical $args --json --threads "$threads" "$@" > "$out" 2>/dev/null || true
  end=$(date +%s.%N)
  python3 - "$name" "$out" "$start" "$end" <<'PY'
import json, sys
name, path, start, end = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
d = json.load(open(path))
trials = d.get("trials")
steps = sum(t["steps"] for t in trials) if trials else ""
before = sum(t["equilibrium_steps"] for t in trials) if trials else ""
print(f"{name},{d.get('critical')},{d.get('forward_runs')},{d.get('runs_ahead_unused', '')},{end - start:.2f},{steps},{before}")
PY
  rm -f "$out"
done <<LIST
chair_cohesion|$here/cases/chair_slide.json --joint sliding_surface --solve cohesion --friction 18
multiblock_cohesion|$here/cases/planar_multiblock_slide.json --joint sliding_surface --solve cohesion
vajont_friction|$here/cases/vajont.json --joint sliding_surface --solve friction --cohesion 0
goodman_bray_toe_anchor|$here/cases/goodman_bray_toppling_anchor.json --solve support --support toe_anchor
planar_anchor_fos_1.5|$here/cases/planar_failure_anchor.json --solve support --support anchor --target-fos 1.5
vajont_anchor_fos_1.3|$here/cases/vajont_anchor.json --solve support --support anchor --target-fos 1.3
planar_crack_seismic|$here/cases/planar_failure_crack.json --solve seismic-coefficient --direction +x
jiufengershan_cohesion_record|$here/cases/jiufengershan.json --joint bedding --solve cohesion
LIST
