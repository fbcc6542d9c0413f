#!/usr/bin/env bash
# Peak resident memory (VmHWM) of a brick wall of N blocks, each size in its own process so that
# no size inherits another's heap: equilibrium plus STEPS steps. Prints a Markdown table.
# usage: scripts/memory_scaling.sh [deformable|rigid] [sizes, default 10,100,200,500,1000,2000] [steps, default 5]
set -euo pipefail
blocks=${1:-deformable}
sizes=${2:-10,100,200,500,1000,2000}
steps=${3:-5}
bench=${BENCH:-build/ddaslope_bench}
# The first size is the baseline (the process and its libraries): the last column is the memory
# each further block adds.
echo "| blocks | peak resident (MB) | per block above the first size (kB) |"
echo "|---|---|---|"
base_n=""
for n in ${sizes//,/ }; do
  row=$("$bench" --sizes "$n" --steps "$steps" --blocks "$blocks" 2>/dev/null | tail -1)
  peak=${row##*,}
  if [ -z "$base_n" ]; then base_n=$n; base_p=$peak; fi
  awk -v n="$n" -v p="$peak" -v bn="$base_n" -v bp="$base_p" \
    'BEGIN { if (n == bn) printf "| %d | %.1f | (baseline) |\n", n, p; else printf "| %d | %.1f | %.1f |\n", n, p, 1024 * (p - bp) / (n - bn) }'
done
