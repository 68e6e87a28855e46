#!/bin/sh
# tools/bench/sky.sh: what the sky costs with no cloud in view, by quality.sky_grid (0: the sky at every pixel), on
# three views of the default cumulus turned away from the cloud: up (the Perez sky alone), level (sky, the horizon
# and the ground) and down (the ground alone), and the level view with the camera turning 0.2 degrees a frame (every
# frame a new view: what the sky's plan of cells costs, pass_sky.c, made again whenever the view moves). Each case:
# the mean of 30 frames after 5 warm-up ones (cumulo bench, `medium`); rounds interleaved (every case once a round),
# medians over rounds. Prints a Markdown table.
# Usage: tools/bench/sky.sh [ROUNDS] [SIZE] [GRIDS]; LP_NUM_THREADS as in the environment.
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
GRIDS=${3:-0 8 16 32}
C=${CUMULO:-build/cumulo}
T=${TMPDIR:-/tmp}/cumulo-sky-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
look() {
  case $1 in
    up) echo "0 1500 -2400" ;;
    level | turning) echo "0 150 -2400" ;;
    *) echo "0 -1500 -2400" ;;
  esac
}
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for g in $GRIDS; do
    for v in up level down turning; do
      ms=$($C bench scenes/cumulus.scene --size "$SIZE" --frames 30 --warmup 5 --set quality.preset=medium \
        --set "quality.sky_grid=$g" --set "camera.look_at=$(look $v)" \
        $([ "$v" = turning ] && echo "--camera orbit --orbit-step 0.2") |
        sed -n 's/.*mean: \([0-9.]*\) ms.*/\1/p' | head -1)
      echo "$g $v $ms" >>"$T/all"
    done
  done
  r=$((r + 1))
done
med() { awk -v g="$1" -v v="$2" '$1 == g && $2 == v { print $3 }' "$T/all" | sort -n |
        awk '{ x[NR] = $1 } END { print x[int((NR + 1) / 2)] }'; }
echo "| quality.sky_grid | up: sky alone, ms | level: sky, horizon, ground, ms | down: ground alone, ms |\
 level, the camera turning, ms |"
echo "| ---: | ---: | ---: | ---: | ---: |"
for g in $GRIDS; do
  printf '| %s | %s | %s | %s | %s |\n' "$g" "$(med "$g" up)" "$(med "$g" level)" "$(med "$g" down)" \
    "$(med "$g" turning)"
done
echo
echo "($ROUNDS rounds, $SIZE, LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1-3 /proc/loadavg))"
