#!/bin/sh
# Users' back-analyses (issue #42): the shipped jobs whose evaluations are forward runs (the
# Vajont run-out of the demo, Jiufengershan) or factor-of-safety searches (Vajont), with the
# figures their cost is made of: the optimisers' evaluations, the forward runs they took, the
# runs made ahead of need and not asked for (not in forward_runs), the job's wall time; and the
# estimate and misfit, which must not change when the job gets faster. One CSV line per job.
#
#   bench/backanalyses.sh [BUILD_DIR] [JOB...]
#   bench/backanalyses.sh build                          # vajont_runout jiufengershan vajont
#   bench/backanalyses.sh build vajont_runout
#
# About a minute in all. Time nothing else while it runs (2 cores).
set -eu
build=${1:-build}
[ $# -ge 1 ] && shift
jobs=${*:-vajont_runout jiufengershan vajont}
here=$(cd "$(dirname "$0")/.." && pwd)
echo "job,estimate,misfit,evaluations,forward_runs,runs_ahead_unused,wall_s"
for job in $jobs; do
  out=$(mktemp -d)
  "$build/ddaslope" backanalyse "$here/calibration/$job/job.json" --out "$out" --quiet > /dev/null
  python3 - "$job" "$out/result.json" <<'PY'
import json, sys
job, path = sys.argv[1], sys.argv[2]
r = json.load(open(path))
estimate = " ".join(f"{k}={v!r}" for k, v in r["estimate"].items())
print(f"{job},{estimate},{r['misfit']!r},{r['evaluations']},{r['forward_runs']},{r.get('runs_ahead_unused', '')},{r['wall_time_s']:.2f}")
PY
  rm -rf "$out"
done
