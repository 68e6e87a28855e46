#!/bin/sh
# tools/bench/living_sky.sh: what a field of clouds costs (README "Performance: a living sky"): the frame time with
# 1, 10, 100 and 1000 clouds in the scene and the same one on screen (culling: it should stay flat), with 1 to 50 on
# screen, and a time step each frame against a still frame. Generated scenes, `cumulo bench` lines, rounds
# interleaved (every configuration once per round), the median over rounds. Usage: tools/bench/living_sky.sh
# [ROUNDS] [SIZE]; LP_NUM_THREADS as in the environment (the README quotes 2).
set -eu
ROUNDS=${1:-3}
SIZE=${2:-480x320}
C=${CUMULO:-build/cumulo}
T=${TMPDIR:-/tmp}/cumulo-sky-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT

scene_head() { # the camera at 300 m looks north (-z); the sun in the north, so clouds behind the camera shade nothing seen
  printf '[camera]\nposition = 0 300 0\nlook_at = 0 600 -3000\nfov = 60\n[sun]\nelevation = 50\nazimuth = 10\n'
}
cloud() { # x z: a cloud of three ellipsoids at 900 m
  printf '[cloud]\n[ellipsoid]\ncenter = %s 900 %s\nradii = 220 140 200\n' "$1" "$2"
  printf '[ellipsoid]\ncenter = %s 980 %s\nradii = 150 120 150\n' "$(($1 + 120))" "$2"
  printf '[ellipsoid]\ncenter = %s 960 %s\nradii = 140 110 140\n' "$(($1 - 130))" "$(($2 + 40))"
}
# N in the scene, 1 on screen (2.5 km ahead), the rest on a grid behind the camera (z 4 km .. south)
for n in 1 10 100 1000; do
  { scene_head
    cloud 0 -2500
    k=1; while [ "$k" -lt "$n" ]; do cloud $(((k % 40) * 600 - 12000)) $((4000 + (k / 40) * 600)); k=$((k + 1)); done
  } > "$T/scene_$n.scene"
done
# 1 .. 50 on screen: rows across the view
for n in 1 5 10 20 50; do
  { scene_head; k=0
    while [ "$k" -lt "$n" ]; do cloud $(((k % 10) * 500 - 2250)) $((-2000 - (k / 10) * 1200)); k=$((k + 1)); done
  } > "$T/screen_$n.scene"
done

run() { # file tag options...: prints "tag median_ms"
  f=$1; tag=$2; shift 2
  line=$("$C" bench "$f" --frames 10 --warmup 2 --size "$SIZE" "$@" 2>/dev/null | grep 'FrameTime:' | head -1)
  ms=$(printf '%s\n' "$line" | sed 's/.*FrameTime: \([0-9.]*\) ms.*/\1/')
  echo "$tag $ms"
}
: > "$T/all"
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for n in 1 10 100 1000; do run "$T/scene_$n.scene" "scene$n" >> "$T/all"; done
  for n in 1 5 10 20 50; do run "$T/screen_$n.scene" "screen$n" >> "$T/all"; done
  run scenes/field_noon.scene field_still >> "$T/all"
  run scenes/field_noon.scene field_step --time-step 1 >> "$T/all"
  run scenes/cumulus.scene lone_still >> "$T/all"
  run scenes/cumulus.scene lone_step --time-step 1 >> "$T/all"
  run scenes/cumulus.scene lone_sun --sun-every-frame >> "$T/all"
  run scenes/field_noon.scene field_lod0 --set quality.lod_pixels=0 >> "$T/all"
  r=$((r + 1))
done
med() { grep "^$1 " "$T/all" | awk '{print $2}' | sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
echo "machine: $(uname -m), $(nproc) cores, LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1 /proc/loadavg), $SIZE, $ROUNDS rounds"
echo "| clouds in the scene (1 on screen) | median frame time, ms | vs 1 |"
echo "| ---: | ---: | ---: |"
b=$(med scene1)
for n in 1 10 100 1000; do m=$(med scene$n); echo "| $n | $m | $(echo "$m $b" | awk '{printf "%.2f", $1/$2}') |"; done
echo
echo "| clouds on screen | median frame time, ms | vs 1 |"
echo "| ---: | ---: | ---: |"
b=$(med screen1)
for n in 1 5 10 20 50; do m=$(med screen$n); echo "| $n | $m | $(echo "$m $b" | awk '{printf "%.2f", $1/$2}') |"; done
echo
echo "| scene | still, ms | a 1 s time step each frame, ms | step / still |"
echo "| --- | ---: | ---: | ---: |"
for s in field lone; do a=$(med ${s}_still); b=$(med ${s}_step)
  echo "| $([ $s = field ] && echo field_noon.scene || echo cumulus.scene) | $a | $b | $(echo "$b $a" | awk '{printf "%.2f", $1/$2}') |"; done
a=$(med lone_still); b=$(med lone_sun)
echo "| cumulus.scene, the sun 0.01 deg a frame (--sun-every-frame) | $a | $b | $(echo "$b $a" | awk '{printf "%.2f", $1/$2}') |"
a=$(med field_lod0); b=$(med field_still)
echo
echo "field_noon.scene: lod_pixels = 0 (every cloud marched in full) $a ms, the default 48 $b ms: $(echo "$b $a" | awk '{printf "%.2f", $1/$2}')"
