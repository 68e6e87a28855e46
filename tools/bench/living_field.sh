#!/bin/sh
# tools/bench/living_field.sh: what a living sky costs at the frame budget's rung (README "A living sky"): scenes
# (field_noon, one layer; kiosk_day and flight, two layers on winds of their own) at `medium`, 1/2 resolution,
# temporal grid 4 (where --target-fps 15 settles on field_noon), still and with the scene's time running 1/30 s a
# frame (real time at 30 fps) and 1 s a frame (a time-lapse), optionally against another build tree (e.g. a worktree
# of an older commit, built). Median and mean frame and the "shadows" pass (median) of 20 frames, rounds
# interleaved, the median over rounds. Usage: tools/bench/living_field.sh [ROUNDS] [SIZE] [OTHER_TREE|-] [SCENES];
# LP_NUM_THREADS as in the environment (the README quotes 2).
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
OTHER=${3:-}
[ "$OTHER" != - ] || OTHER=
SCENES=${4:-field_noon}
T=${TMPDIR:-/tmp}/cumulo-living-field.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
if [ -n "$OTHER" ] && [ ! -x "$OTHER/build/cumulo" ]; then
  echo "living_field.sh: $OTHER/build/cumulo is not built" >&2
  exit 2
fi

one() { # TREE TAG SCENE STEP: appends "tag scene step median mean shadows"
  o=""
  [ "$4" = 0 ] || o="--time-step $4"
  # shellcheck disable=SC2086 # $o is empty or two words
  out=$(CUMULO_DATA_DIR="$1/data" "$1/build/cumulo" bench "$1/scenes/$3.scene" --size "$SIZE" --frames 20 \
        --warmup 4 --passes --set quality.preset=medium --set quality.cloud_downsample=2 \
        --set quality.temporal_grid=4 $o 2>/dev/null)
  med=$(printf '%s\n' "$out" | sed -n 's/.*FrameTime: \([0-9.]*\) ms.*/\1/p' | head -1)
  mean=$(printf '%s\n' "$out" | sed -n 's/.* mean: \([0-9.]*\) ms.*/\1/p' | head -1)
  sh=$(printf '%s\n' "$out" | sed -n 's/.*shadows=\([0-9.]*\).*/\1/p' | head -1)
  echo "$2 $3 $4 $med $mean $sh" >>"$T/all"
}
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for sc in $SCENES; do
    for s in 0 0.0333333 1; do
      one "$PWD" this "$sc" "$s"
      [ -z "$OTHER" ] || one "$OTHER" other "$sc" "$s"
    done
  done
  r=$((r + 1))
done
med() { # TAG SCENE STEP COLUMN
  awk -v t="$1" -v n="$2" -v s="$3" -v c="$4" '$1 == t && $2 == n && $3 == s {print $c}' "$T/all" | sort -n |
    awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'
}
echo "machine: $(uname -m), $(nproc) cores, LP_NUM_THREADS=${LP_NUM_THREADS:-unset}," \
  "load $(cut -d' ' -f1 /proc/loadavg), $SIZE, $ROUNDS rounds; medium, 1/2 x grid 4"
echo "| scene | build | scene time a frame | median ms | mean ms | mean fps | shadows ms | mean / still |"
echo "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |"
for sc in $SCENES; do
  for t in this other; do
    [ "$t" = this ] || [ -n "$OTHER" ] || continue
    still=$(med "$t" "$sc" 0 5)
    for s in 0 0.0333333 1; do
      m=$(med "$t" "$sc" "$s" 5)
      name=this
      [ "$t" = this ] || name=$(basename "$OTHER")
      label=$(case $s in 0) echo "still" ;; 1) echo "1 s (time-lapse)" ;; *) echo "1/30 s (real time)" ;; esac)
      echo "| $sc | $name | $label | $(med "$t" "$sc" "$s" 4) | $m |" \
        "$(awk -v m="$m" 'BEGIN {printf "%.1f", 1000 / m}') | $(med "$t" "$sc" "$s" 6) |" \
        "$(awk -v m="$m" -v s="$still" 'BEGIN {printf "%.2f", m / s}') |"
    done
  done
done
