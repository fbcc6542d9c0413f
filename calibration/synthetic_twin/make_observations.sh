#!/usr/bin/env bash
# Regenerates observations.csv: the block's horizontal displacement every 0.05 s, computed by
# ddaslope itself from case.json (c = 5 kPa, phi = 25 degrees). Run from the repository root
# after building: calibration/synthetic_twin/make_observations.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
tmp="$(mktemp -d)"
build/ddaslope run "$here/case.json" --out "$tmp" --quiet >/dev/null
awk -F, 'NR == 1 { print "time,ux"; next }
         { k = $1 * 20; if (k - int(k + 0.5) < 1e-6 && int(k + 0.5) - k < 1e-6) printf "%.2f,%.9g\n", $1, $4 }' \
    "$tmp/history.csv" > "$here/observations.csv"
rm -rf "$tmp"
