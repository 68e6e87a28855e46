#!/bin/sh
# tools/bench/budget.sh: what the frame budget (quality.target_fps) holds with the camera moving (README
# "Performance"): each scene on an orbiting camera (cumulo bench --camera orbit, one degree a frame) without a budget
# and with each target, rounds interleaved (every case once a round); a case's frame time is the median of 30 frames
# after 40 warm-up frames (the budget walks its ladder in the warm-up: a rung takes 7 frames), the median over
# rounds; the rung the budget ended on and the ratio to no budget in the same run; and the mean of the 30 frames (its
# median over rounds): frames a second as a viewer counts them, spikes included.
# Usage: tools/bench/budget.sh [ROUNDS] [SIZE] [PRESET] [SCENES] [TARGETS]; LP_NUM_THREADS as in the environment.
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
PRESET=${3:-medium}
SCENES=${4:-cumulus silver_lining field_noon}
TARGETS=${5:-off 10 20 30}
C=${CUMULO:-build/cumulo}
T=${TMPDIR:-/tmp}/cumulo-budget-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for s in $SCENES; do
    for f in $TARGETS; do
      fps=$f
      [ "$f" = off ] && fps=0
      $C bench "scenes/$s.scene" --size "$SIZE" --frames 30 --warmup 40 --camera orbit --set quality.preset="$PRESET" \
        --target-fps "$fps" >"$T/out"
      ms=$(sed -n 's/.*FrameTime: \([0-9.]*\) ms.*/\1/p' "$T/out" | head -1)
      mean=$(sed -n 's/.*FrameTime: .* mean: \([0-9.]*\) ms.*/\1/p' "$T/out" | head -1)
      rung=$(sed -n 's/.*budget: clouds at 1\/\([0-9]*\) resolution, temporal grid \([0-9]*\).*/\1x\2/p' "$T/out")
      echo "$s $f $ms ${rung:-1x1} $mean" >>"$T/all"
    done
  done
  r=$((r + 1))
done
printf '| scene | target fps | median frame, ms | fps | vs no budget | mean frame, ms | frames a second |'
printf ' downsample x grid at the end (each round) |\n'
printf '| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n'
for s in $SCENES; do
  med() { awk -v s="$s" -v f="$1" -v c="${2:-3}" '$1 == s && $2 == f { print $c }' "$T/all" | sort -n |
          awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
  base=$(med off)
  for f in $TARGETS; do
    m=$(med "$f")
    a=$(med "$f" 5)
    rungs=$(awk -v s="$s" -v f="$f" '$1 == s && $2 == f { printf "%s%s", sep, $4; sep = " " }' "$T/all")
    printf '| %s | %s | %.1f | %.1f | %.2f | %.1f | %.1f | %s |\n' "$s" "$f" "$m" \
      "$(echo "$m" | awk '{ print 1000 / $1 }')" "$(echo "$m $base" | awk '{ print $1 / $2 }')" "$a" \
      "$(echo "$a" | awk '{ print 1000 / $1 }')" "$rungs"
  done
done
echo
echo "($ROUNDS rounds, $SIZE, preset $PRESET, camera orbiting 1 degree a frame," \
  "LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1-3 /proc/loadavg))"
