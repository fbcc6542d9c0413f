#!/bin/sh
# A small probability of failure (issue #42): the planar failure with c ~ N(35 kPa, 5) and
# phi ~ N(33 deg, 3) (calibration/planar_failure/probability_small.json, exact Pf 1.80736e-3),
# estimated by importance sampling around FORM's design point, by active learning (AK-MCS) on a
# population of 100 000, and by plain Latin-hypercube sampling with the same number of forward
# runs and with 55 000 samples; then Vajont's Pf (calibration/vajont/probability.json) by
# importance sampling (verdict measure) and by active learning on 10 000 points.
# Prints one CSV line per study: forward runs, Pf, its 95 % interval, coefficient of variation, wall.
#
#   bench/small_pf.sh [BUILD_DIR] [THREADS] [--no-vajont]
#
# Time nothing else while it runs (2 cores).
set -eu
build=${1:-build}
threads=${2:-2}
vajont=yes
[ "${3:-}" = "--no-vajont" ] && vajont=no
here=$(cd "$(dirname "$0")/.." && pwd)
small="$here/calibration/planar_failure/probability_small.json"
echo "study,method,samples,forward_runs,pf,interval_low,interval_high,cov,wall_s"
run() {
  name=$1
  shift
  out=$(mktemp -d)
  start=$(date +%s.%N)
  "$build/ddaslope" probability "$@" --quiet --json --threads "$threads" --out "$out/study" > "$out/summary.json"
  end=$(date +%s.%N)
  python3 - "$name" "$out/summary.json" "$start" "$end" <<'PY'
import json, sys
name, path, start, end = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
d = json.load(open(path))
samples = d.get("samples_finished", d.get("population"))
runs = d.get("forward_runs", samples)
cov = d.get("coefficient_of_variation")
print(f"{name},{d['method']},{samples},{runs},{d['probability_of_failure']:.5g},"
      f"{d['interval_95'][0]:.5g},{d['interval_95'][1]:.5g},{'' if cov is None else f'{cov:.3f}'},{end - start:.2f}")
PY
  rm -rf "$out"
}
run planar_small "$small"
run planar_small "$small" --method active_learning --samples 100000
run planar_small "$small" --method sampling --samples 1071
run planar_small "$small" --method sampling --samples 55000
if [ "$vajont" = yes ]; then
  run vajont "$here/calibration/vajont/probability.json" --measure verdict --method importance_sampling --samples 200
  run vajont "$here/calibration/vajont/probability.json" --method active_learning --samples 10000
fi
