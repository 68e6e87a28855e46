#!/bin/sh
# tools/bench/against_build.sh: issue 17's target measured as it is stated: `medium` in steady state with the camera
# moving (cumulo bench --camera orbit, one degree a frame), this build against another build of cumulo (the commit
# before the frame-budget work, a4a00b1, built in a worktree of its own), as ratios in one interleaved run. Rows: the
# other build's medium (every pixel every frame: what it could do), this build's medium the same way, and this build's
# medium with the clouds at half resolution and the temporal grid 4 (quality.cloud_downsample = 2,
# quality.temporal_grid = 4: the coarsest rung the frame budget takes by default). Each case: the median of 20 frames
# after 6 warm-up frames; rounds interleaved (every case once a round), the median over rounds. Each build reads its
# own data directory and scenes (the scenes measured are the same files in both: git diff a4a00b1 -- scenes/).
# Usage: tools/bench/against_build.sh OTHER_TREE [ROUNDS] [SIZE] [SCENES]
#   OTHER_TREE: a built checkout (OTHER_TREE/build/cumulo), e.g.
#   git worktree add ../old17 a4a00b1 && (cd ../old17 && ./configure && make build/cumulo)
set -eu
OLD=${1:?usage: tools/bench/against_build.sh OTHER_TREE [ROUNDS] [SIZE] [SCENES]}
ROUNDS=${2:-3}
SIZE=${3:-800x480}
SCENES=${4:-cumulus silver_lining}
C=${CUMULO:-build/cumulo}
[ -x "$OLD/build/cumulo" ] || { echo "against_build.sh: $OLD/build/cumulo is not built" >&2; exit 2; }
T=${TMPDIR:-/tmp}/cumulo-ab-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
frame() { sed -n 's/.*FrameTime: \([0-9.]*\) ms.*/\1/p' | head -1; }
time_of() { # SCENE CASE
  case $2 in
    other) CUMULO_DATA_DIR="$OLD/data" "$OLD/build/cumulo" bench "$OLD/scenes/$1.scene" --size "$SIZE" --frames 20 \
             --warmup 6 --camera orbit --set quality.preset=medium | frame ;;
    this) CUMULO_DATA_DIR="$PWD/data" $C bench "scenes/$1.scene" --size "$SIZE" --frames 20 --warmup 6 \
            --camera orbit --set quality.preset=medium | frame ;;
    this2x4) CUMULO_DATA_DIR="$PWD/data" $C bench "scenes/$1.scene" --size "$SIZE" --frames 20 --warmup 6 \
               --camera orbit --set quality.preset=medium --set quality.cloud_downsample=2 \
               --set quality.temporal_grid=4 | frame ;;
  esac
}
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for s in $SCENES; do
    for k in other this this2x4; do
      echo "$s $k $(time_of "$s" "$k")" >>"$T/all"
    done
  done
  r=$((r + 1))
done
med() { awk -v s="$1" -v k="$2" '$1 == s && $2 == k { print $3 }' "$T/all" | sort -n |
        awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
echo "| scene | other build's medium, ms | this build's medium, ms | speed-up |" \
  "this build's medium at 1/2 × grid 4, ms" \
  "| speed-up |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for s in $SCENES; do
  o=$(med "$s" other); a=$(med "$s" this); b=$(med "$s" this2x4)
  printf '| %s | %s | %s | %.2f× | %s | %.2f× |\n' "$s" "$o" "$a" "$(echo "$o $a" | awk '{print $1/$2}')" "$b" \
    "$(echo "$o $b" | awk '{print $1/$2}')"
done
echo
echo "(other build: $(git -C "$OLD" log -1 --format=%h 2>/dev/null || echo "$OLD"); $ROUNDS rounds, $SIZE," \
  "LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1-3 /proc/loadavg))"
