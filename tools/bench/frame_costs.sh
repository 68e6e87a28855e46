#!/bin/sh
# tools/bench/frame_costs.sh: what a frame costs when no cloud is on screen and when the sun moves every frame (issue
# 14's targets: at most 0.10x and 1.2x of the still cloud view), for each preset and for the uniform ray march, on
# the default cumulus: the cloud view; the camera turned away from the cloud (look_at behind it); the sun turned
# 0.01 degree every frame (cumulo bench --sun-every-frame: a slow knob, or the time of day; the maps follow it every
# fifth frame) and 0.6 degree every frame (--sun-step 0.6: a knob turned fast, 18 degrees a second at 30 fps; the maps
# are made again a band a frame over quality.sun_map_frames frames, and a diffusion grid is solved again every half
# degree, within ms.frame_work a frame). The row "ms.mode = octaves" is medium with the octaves' multiple scattering
# instead of diffusion's (the presets before 2026-12-06's sweep of a turning sun).
# The columns "in one run" turn the sun for 24 frames and hold it for 24, in turn, over 144 frames (cumulo bench
# --sun-blocks 24; a held block must outlast the 2K frames maps made in K bands take to settle): the ratio of the
# turning frames' mean to the held ones' (once the picture has settled), measured in one process, so that the
# machine's drift and a process's own speed cancel; the other ratios divide the means of two runs.
# Each case: the mean of 20 frames after 5 warm-up ones (a cheap frame's first few run slower: llvmpipe's threads
# and caches warming; the mean, not the median, so that work done every few frames, a band of the maps or the energy
# closure once a degree, counts at its average). The row "sun_map_frames = 1" is the whole maps every frame, as
# before the bands; "low, sun_map_frames = 8" spreads them over 8 frames. Rounds interleaved (every case once a
# round), medians over rounds, ratios to the cloud view in the same run. The row "sky_grid = 0" draws the sky at
# every pixel, as before the grid. Prints a Markdown table.
# Usage: tools/bench/frame_costs.sh [ROUNDS] [SIZE]; LP_NUM_THREADS as in the environment.
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
C=${CUMULO:-build/cumulo}
S=scenes/cumulus.scene
T=${TMPDIR:-/tmp}/cumulo-fc-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
CONFIGS="high medium exact low low8 whole octaves uniform"
sets() {
  case $1 in
    uniform) echo "--set quality.method=uniform --set ms.mode=octaves --set quality.uniform_steps=16 \
--set quality.uniform_sun_steps=4 --set quality.noise_baked=on" ;;
    octaves) echo "--set quality.preset=medium --set ms.mode=octaves" ;;
    whole) echo "--set quality.preset=medium --set quality.sun_map_frames=1" ;;
    exact) echo "--set quality.preset=medium --set quality.sky_grid=0" ;;
    low8) echo "--set quality.preset=low --set quality.sun_map_frames=8" ;;
    *) echo "--set quality.preset=$1" ;;
  esac
}
time_of() { # CONFIG CASE; the empty view looks away from the cloud (it is behind the camera)
  case $2 in
    empty) $C bench $S --size "$SIZE" --frames 20 --warmup 5 $(sets "$1") --set "camera.look_at=0 150 -2400" ;;
    sun) $C bench $S --size "$SIZE" --frames 20 --warmup 5 $(sets "$1") --sun-every-frame ;;
    fast) $C bench $S --size "$SIZE" --frames 20 --warmup 5 $(sets "$1") --sun-step 0.6 ;;
    sunp) $C bench $S --size "$SIZE" --frames 144 --warmup 5 $(sets "$1") --sun-every-frame --sun-blocks 24 ;;
    fastp) $C bench $S --size "$SIZE" --frames 144 --warmup 5 $(sets "$1") --sun-step 0.6 --sun-blocks 24 ;;
    *) $C bench $S --size "$SIZE" --frames 20 --warmup 5 $(sets "$1") ;;
  esac | sed -n -e 's/.*FrameTime: .* mean: \([0-9.]*\) ms.*/\1/p' -e 's/^turning\/held mean frame time: \([0-9.]*\).*/\1/p' |
    tail -1
}
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for c in $CONFIGS; do
    for k in cloud empty sun fast sunp fastp; do
      echo "$c $k $(time_of "$c" "$k")" >>"$T/all"
    done
  done
  r=$((r + 1))
done
med() { awk -v c="$1" -v k="$2" '$1 == c && $2 == k { print $3 }' "$T/all" | sort -n |
        awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
echo "| configuration | cloud view (ms) | no cloud on screen (ms) | ratio | sun 0.01° a frame (ms) | ratio" \
  "| in one run | sun 0.6° a frame (ms) | ratio | in one run |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for c in $CONFIGS; do
  a=$(med "$c" cloud); b=$(med "$c" empty); s=$(med "$c" sun); f=$(med "$c" fast); sp=$(med "$c" sunp)
  fp=$(med "$c" fastp)
  label=$c
  [ "$c" = uniform ] && label="uniform march 16/4, baked noise"
  [ "$c" = octaves ] && label="medium, ms.mode = octaves"
  [ "$c" = whole ] && label="medium, sun_map_frames = 1"
  [ "$c" = exact ] && label="medium, sky_grid = 0"
  [ "$c" = low8 ] && label="low, sun_map_frames = 8"
  printf '| %s | %s | %s | %.2f | %s | %.2f | %.2f | %s | %.2f | %.2f |\n' "$label" "$a" "$b" \
    "$(echo "$b $a" | awk '{print $1/$2}')" "$s" "$(echo "$s $a" | awk '{print $1/$2}')" "$sp" "$f" \
    "$(echo "$f $a" | awk '{print $1/$2}')" "$fp"
done
echo
echo "($ROUNDS rounds, $SIZE, LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1-3 /proc/loadavg))"
