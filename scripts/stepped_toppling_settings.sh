#!/usr/bin/env bash
# F of cases/stepped_toppling.json across the settings that must not matter (issue #13), one
# line per setting: Δt 0.2-4 ms, presets, threads, contact treatment, rigid blocks.
#   scripts/stepped_toppling_settings.sh [BINARY] [extra ddaslope options...]
# e.g. with the default failure displacement (1e-3 w0 = 7.4 cm) instead of the case's 0.5 m:
#   scripts/stepped_toppling_settings.sh build/ddaslope --set analysis.failure_displacement=0
# CASE=cases/stepped_toppling_tjunctions.json runs the same slope written with T-junction vertices.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/ddaslope}; shift || true
f() {
  "$bin" fos "${CASE:-cases/stepped_toppling.json}" --json "$@" | python3 -c "
import json, sys
d = json.load(sys.stdin)
print(f\"{sys.argv[1]:28s} F = {d['factor_of_safety']:.4f}  ({d['forward_runs']} runs, {d['wall_time_s']:.1f} s)\")" "${label}"
}
label="case settings (1 ms)" f "$@"
label="--threads 1" f --threads 1 "$@"
for dt in 2e-4 5e-4 2e-3 4e-3; do label="--time-step $dt" f --time-step $dt "$@"; done
for p in fast balanced accurate; do label="--preset $p" f --preset $p "$@"; done
label="--contact-treatment vertex" f --contact-treatment vertex "$@"
label="--blocks rigid" f --blocks rigid "$@"
