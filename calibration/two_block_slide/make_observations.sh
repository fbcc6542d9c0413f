#!/usr/bin/env bash
# Regenerates observations.csv: the monitored block's horizontal displacement every 0.05 s
# (linear interpolation between steps), computed by ddaslope itself from case.json.
# Run from the repository root after building: calibration/two_block_slide/make_observations.sh
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
tmp="$(mktemp -d)"
build/ddaslope run "$here/case.json" --out "$tmp" --quiet >/dev/null
awk -F, -v column=4 -v every=0.05 -v name=ux -f scripts/sample_history.awk "$tmp/history.csv" > "$here/observations.csv"
rm -rf "$tmp"
