#!/bin/sh
# tools/bench/temporal.sh: what quality.temporal_grid (and cloud_downsample with it) buys with the camera moving
# (README "Performance"): the steady-state frame time of each preset on an orbiting camera (cumulo bench --camera
# orbit, one degree a frame) for the configurations "downsample x grid" 1x1 (every pixel every frame), 1x2, 1x4, 2x1,
# 2x2 and 2x4, rounds interleaved (every configuration once a round), the median of each case's 20 frames after 6
# warm-up frames, the median over rounds, and the ratio to 1x1 in the same run.
# Usage: tools/bench/temporal.sh [ROUNDS] [SIZE] [PRESETS] [SCENES]; LP_NUM_THREADS as in the environment.
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
PRESETS=${3:-high medium}
SCENES=${4:-cumulus silver_lining}
CONFIGS="1x1 1x2 1x4 2x1 2x2 2x4"
C=${CUMULO:-build/cumulo}
T=${TMPDIR:-/tmp}/cumulo-tg-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for s in $SCENES; do
    for p in $PRESETS; do
      for c in $CONFIGS; do
        ms=$($C bench "scenes/$s.scene" --size "$SIZE" --frames 20 --warmup 6 --camera orbit --set quality.preset="$p" \
               --set quality.cloud_downsample="${c%x*}" --set quality.temporal_grid="${c#*x}" |
             sed -n 's/.*FrameTime: \([0-9.]*\) ms.*/\1/p' | head -1)
        echo "$s $p $c $ms" >>"$T/all"
      done
    done
  done
  r=$((r + 1))
done
printf '| scene | preset |'
for c in $CONFIGS; do printf ' %s, ms |' "$c"; done
printf ' best gain |\n| --- | --- |'
for c in $CONFIGS; do printf ' ---: |'; done
printf ' ---: |\n'
for s in $SCENES; do
  for p in $PRESETS; do
    med() { awk -v s="$s" -v p="$p" -v c="$1" '$1 == s && $2 == p && $3 == c { print $4 }' "$T/all" | sort -n |
            awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
    base=$(med 1x1); best=$base
    printf '| %s | %s |' "$s" "$p"
    for c in $CONFIGS; do
      m=$(med "$c")
      printf ' %.1f |' "$m"
      best=$(echo "$best $m" | awk '{ print ($2 < $1 ? $2 : $1) }')
    done
    printf ' %.2fx |\n' "$(echo "$base $best" | awk '{ print $1 / $2 }')"
  done
done
echo
echo "(downsample x grid; $ROUNDS rounds, $SIZE, camera orbiting 1 degree a frame, LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1-3 /proc/loadavg))"
