#!/usr/bin/env bash
# Samples per minute of a probability study on 1 and 2 MPI ranks, the efficiency, the cost of
# MPI per forward run, and a paper estimate for 10 000 fos samples of Vajont on a cluster
# (issue #18). One thread per rank; run it on a quiet machine.
# usage: bench/probability_ranks.sh [DDASLOPE_CLI] [SAMPLES]   (defaults: build/ddaslope 600)
set -euo pipefail
cd "$(dirname "$0")/.."
cli=${1:-build/ddaslope} n=${2:-600}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
study=calibration/planar_failure/probability.json

calc() { awk "BEGIN { print $* }"; }
seconds() {  # wall time of a command, in seconds
  local t0 t1
  t0=$(date +%s.%N)
  "$@" > /dev/null
  t1=$(date +%s.%N)
  calc "$t1 - $t0"
}
best() {  # the fastest of three runs
  local b=1e9 t
  for _ in 1 2 3; do
    rm -rf "$work/out"
    t=$(seconds "$@")
    b=$(calc "($t < $b) ? $t : $b")
  done
  echo "$b"
}

start1=$(best mpirun -np 1 "$cli" --version)
start2=$(best mpirun -np 2 --oversubscribe "$cli" --version)
serial=$(best "$cli" probability "$study" --samples "$n" --threads 1 --out "$work/out")
rank1=$(best mpirun -np 1 "$cli" probability "$study" --samples "$n" --threads 1 --out "$work/out")
rank2=$(best mpirun -np 2 "$cli" probability "$study" --samples "$n" --threads 1 --out "$work/out")
# The same two cores used by threads of one process: what the machine itself gives two workers.
threads2=$(best "$cli" probability "$study" --samples "$n" --threads 2 --out "$work/out")

rate() { calc "60 * $n / ($1)"; }
printf 'planar failure, %d verdict samples (one forward run each), one thread per rank, fastest of 3\n' "$n"
printf '| processes | wall s | mpirun start s | samples per minute (start excluded) | efficiency |\n|---|---|---|---|---|\n'
r0=$(rate "$serial")
r1=$(rate "$rank1 - $start1")
r2=$(rate "$rank2 - $start2")
printf '| 1, no mpirun | %.2f | – | %.0f | – |\n' "$serial" "$r0"
printf '| 1 rank | %.2f | %.2f | %.0f | %.2f |\n' "$rank1" "$start1" "$r1" "$(calc "$r1 / $r0")"
printf '| 2 ranks | %.2f | %.2f | %.0f | %.2f |\n' "$rank2" "$start2" "$r2" "$(calc "$r2 / (2 * $r0)")"
rt=$(rate "$threads2")
printf '| 1 process, 2 threads | %.2f | – | %.0f | %.2f |\n' "$threads2" "$rt" "$(calc "$rt / (2 * $r0)")"
# What dealing a task costs, apart from the machine's noise: tasks that keep a core busy for as long
# as a forward run of this study takes (the farm bench, core/task_farm.hpp).
run_us=$(calc "1e6 * $serial / $n")
farm=$(dirname "$cli")/ddaslope_farm_bench
echo "the farm's cost per task, tasks of ${run_us%.*} µs (a forward run of this study):"
"$farm" --tasks 2000 --work-us "$run_us" --threads 2 | sed 's/^/  /'
mpirun -np 2 "$farm" --tasks 2000 --work-us "$run_us" --threads 1 | sed 's/^/  /'

# Vajont: the mean time of a strength-reduction sample on one core, and what 10 000 would take.
vajont=calibration/vajont/probability.json
m=${VAJONT_SAMPLES:-4}
"$cli" probability "$vajont" --samples "$m" --threads 1 --out "$work/vajont" > "$work/vajont.txt"
per=$(awk -F, 'NR > 1 { s += $NF; n++ } END { print s / n }' "$work/vajont/samples.csv")
eff=$(calc "$r2 / (2 * $r0)")
printf 'Vajont, fos measure: %.1f s per sample on one core (mean of %d)\n' "$per" "$m"
printf '10 000 samples: %.1f h on one core; on 10 nodes of 32 cores at the 2-rank efficiency %.2f: %.2f h\n' \
  "$(calc "10000 * $per / 3600")" "$eff" "$(calc "10000 * $per / (320 * $eff) / 3600")"
