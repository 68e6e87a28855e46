#!/bin/sh
# tools/bench/impostor.sh: what quality.impostor_pixels buys on a field of clouds (README "Performance"): the frame
# time of each setting with a still camera and with one orbiting 1 degree a frame (cumulo bench: the median of 12
# frames after 3 warm-up frames, rounds interleaved, the median over rounds, the ratio to no impostors in the same
# run), and each setting's still frame against the one without (build/png_diff: the largest and the mean channel
# difference in 1/255).
# Usage: tools/bench/impostor.sh [ROUNDS] [SIZE] [PRESET] [SCENE] [SETTINGS]; LP_NUM_THREADS as in the environment.
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
PRESET=${3:-medium}
SCENE=${4:-field_noon}
SETTINGS=${5:-0 64 128 400}
C=${CUMULO:-build/cumulo}
D=${PNG_DIFF:-build/png_diff}
T=${TMPDIR:-/tmp}/cumulo-impostor-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for cam in static orbit; do
    for p in $SETTINGS; do
      ms=$($C bench "scenes/$SCENE.scene" --size "$SIZE" --frames 12 --warmup 3 --camera "$cam" \
             --set quality.preset="$PRESET" --set quality.impostor_pixels="$p" |
           sed -n 's/.*FrameTime: \([0-9.]*\) ms.*/\1/p' | head -1)
      echo "$cam $p $ms" >>"$T/all"
    done
  done
  r=$((r + 1))
done
for p in $SETTINGS; do
  $C render "scenes/$SCENE.scene" --size "$SIZE" --set quality.preset="$PRESET" --set quality.impostor_pixels="$p" \
    -o "$T/$p.png" >/dev/null
done
set -- $SETTINGS
base=$1
med() { awk -v c="$1" -v p="$2" '$1 == c && $2 == p { print $3 }' "$T/all" | sort -n |
        awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
printf '| impostor_pixels | still camera, ms | vs none | orbiting, ms | vs none | still frame against none (max, mean /255) |\n'
printf '| ---: | ---: | ---: | ---: | ---: | --- |\n'
for p in $SETTINGS; do
  s=$(med static "$p"); o=$(med orbit "$p")
  diff=$($D "$T/$base.png" "$T/$p.png" 255 4 | sed 's/ differ=.*//')
  printf '| %s | %.1f | %.2f | %.1f | %.2f | %s |\n' "$p" "$s" "$(echo "$s $(med static "$base")" | awk '{ print $1 / $2 }')" \
    "$o" "$(echo "$o $(med orbit "$base")" | awk '{ print $1 / $2 }')" "$diff"
done
echo
echo "($SCENE, $ROUNDS rounds, $SIZE, preset $PRESET, LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1-3 /proc/loadavg))"
