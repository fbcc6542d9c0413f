#!/usr/bin/env bash
# ddaslope against ntdda (Shi's DDA) on the same brick wall, the two runs interleaved so that both
# meet the same machine speed (this shared machine drifts by ±30 % within an hour): the quiet wall
# (ms per step after the equilibrium, deformable and rigid) and the sudden-gravity start (seconds
# for 0.1 s simulated, the CLI on the case ntdda runs, with its cuts and energy line). Prints the
# fastest of REPS runs of each and the ratios (issue #16). One core each; run it on a quiet machine.
# usage: bench/against_ntdda.sh NTDDA_RUN SHARED_NTDDA_DIR [ROWS] [REPS] [SUDDEN_ROWS]
#   NTDDA_RUN         ntdda's headless driver, built by ../shared/ntdda/build.sh (its last line)
#   SHARED_NTDDA_DIR  ../shared/ntdda (make_wall.py, json2ntdda.py, wall_case.py)
#   ROWS              walls of R rows (default "22 31 45": 495, 976 and 2047 free blocks)
#   SUDDEN_ROWS       walls also started with gravity at step 1 (default "22 31")
set -euo pipefail
cd "$(dirname "$0")/.."
nt=$(readlink -f "${1:?usage: bench/against_ntdda.sh NTDDA_RUN SHARED_NTDDA_DIR [ROWS] [REPS] [SUDDEN_ROWS]}")
shared=$(readlink -f "${2:?usage: bench/against_ntdda.sh NTDDA_RUN SHARED_NTDDA_DIR [ROWS] [REPS] [SUDDEN_ROWS]}")
rows=${3:-"22 31 45"} reps=${4:-2} sudden=${5:-"22 31"}
bench=$(readlink -f build/ddaslope_bench) cli=$(readlink -f build/ddaslope)
export OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

wall() {  # R: the wall for both codes in $work/wR
  local d=$work/w$1
  [ -d "$d" ] && return
  mkdir -p "$d"
  python3 "$shared/make_wall.py" "$1" > "$d/wall.json"
  python3 "$shared/json2ntdda.py" "$d/wall.json" "$d/wall" --steps 100 --penalty 1e11 > /dev/null
  python3 "$shared/wall_case.py" "$d/wall.json" "$d/sudden.json" --penalty 1e11 --steps 100 --no-equilibrium
}
ntdda() {  # R: seconds of ntdda's loop after step 1, and of its first step
  # ntdda prints its timing and may then abort while freeing memory (the 2047-brick wall, exit
  # 134): the timing line is what counts.
  local out
  (cd "$work/w$1" && "$nt" wall.geo wall.ana nt > /dev/null 2> nt.err) 2> /dev/null || true
  out=$(tr ' ' '\n' < "$work/w$1/nt.err" | { grep -E '^(loop_s|first_step_s)=' || true; } | tr '\n' ' ')
  [ -n "$out" ] || { echo "ntdda printed no timing on the $1-row wall" >&2; exit 1; }
  echo "$out"
}
field() { tr ' ' '\n' | grep "^$1=" | cut -d= -f2; }
step_ms() {  # R [bench args]: ms per step of the bench's quiet wall
  "$bench" --anchor-rows "$@" --steps 100 2> /dev/null | grep -E '^[0-9]+,' | cut -d, -f5
}
min() { sort -g | head -n1; }

echo "quiet wall: ms per step (fastest of $reps), ntdda timed between the ddaslope runs"
echo "rows,free_blocks,ntdda_ms,deformable_ms,deformable_ratio,rigid_ms,rigid_ratio,peak_resident_mb_deformable"
for r in $rows; do
  wall "$r"
  : > "$work/nt" ; : > "$work/def" ; : > "$work/rig"
  for _ in $(seq "$reps"); do
    ntdda "$r" | field loop_s | awk '{ print $1 * 1000 / 99 }' >> "$work/nt"
    step_ms "$r" >> "$work/def"
    step_ms "$r" --blocks rigid >> "$work/rig"
  done
  n=$(min < "$work/nt") d=$(min < "$work/def") g=$(min < "$work/rig")
  line=$("$bench" --anchor-rows "$r" --steps 20 2> /dev/null | grep -E '^[0-9]+,')
  awk -v r="$r" -v b="$(echo "$line" | cut -d, -f1)" -v n="$n" -v d="$d" -v g="$g" -v p="$(echo "$line" | cut -d, -f18)" \
    'BEGIN { printf "%s,%s,%.1f,%.2f,%.1f,%.2f,%.1f,%s\n", r, b, n, d, n / d, g, n / g, p }'
done

echo
echo "sudden gravity (no equilibrium, full gravity at step 1): seconds for 0.1 s simulated"
for r in $sudden; do
  wall "$r"
  : > "$work/nt" ; : > "$work/ds"
  for _ in $(seq "$reps"); do
    ntdda "$r" | awk '{ split($0, f, /[= ]/); for (i = 1; i < length(f); i += 2) v[f[i]] = f[i + 1]; print v["loop_s"] + v["first_step_s"] }' >> "$work/nt"
    "$cli" run "$work/w$r/sudden.json" --out "$work/w$r/out" --quiet > "$work/w$r/run.txt" 2>&1
    grep -o '[0-9.]* s wall' "$work/w$r/run.txt" | cut -d' ' -f1 >> "$work/ds"
  done
  echo "$r rows: ntdda $(min < "$work/nt") s, ddaslope $(min < "$work/ds") s; $(head -n1 "$work/w$r/run.txt" | cut -d: -f2)"
  grep energy "$work/w$r/run.txt"
done
