#!/bin/sh
# tools/bench/edge_refine.sh: what quality.edge_refine costs and buys (README "Speed against accuracy"): the frame time
# of low with and without it, and of medium (low is medium at half resolution), on the four views of the methods
# study (scenes/sweep_*_hg.scene) at a display's size, with each one's error against medium at the same size (cloud
# rel. RMSE, the sun's disk left out: how far from its own full resolution each gets). The rim a half-resolution
# pass smears is a line of pixels, its share of a cloud's pixels falls as the frame grows: the trade depends on the
# size, so give the size you display at. Rounds interleaved (every configuration once a round), medians over rounds
# of the median of 15 frames after 3 warm-up ones. Prints a Markdown table.
# Usage: tools/bench/edge_refine.sh [ROUNDS] [SIZE]; LP_NUM_THREADS as in the environment; needs /usr/bin/python3
# with numpy for the errors (else they are left out).
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
C=${CUMULO:-build/cumulo}
T=${TMPDIR:-/tmp}/cumulo-er-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
VIEWS="sweep_cumulus_hg sweep_silver_lining_hg sweep_below_hg sweep_low_sun_hg"
CONFIGS="medium medium2 low low2 r10 r6 r3 r3s2"
sets() {
  case $1 in
    medium) echo "--set quality.preset=medium" ;;
    medium2) echo "--set quality.preset=medium --set quality.segments=2 --set quality.hull_tessellation=6" ;;
    low) echo "--set quality.preset=low" ;;
    low2) echo "--set quality.preset=low --set quality.segments=2 --set quality.hull_tessellation=6" ;;
    r10) echo "--set quality.preset=low --set quality.edge_refine=1" ;;
    r6) echo "--set quality.preset=low --set quality.edge_refine=0.6" ;;
    r3) echo "--set quality.preset=low --set quality.edge_refine=0.3" ;;
    r3s2) echo "--set quality.preset=low --set quality.segments=2 --set quality.hull_tessellation=6 \
--set quality.edge_refine=0.3" ;;
  esac
}
label() {
  case $1 in
    medium) echo "medium" ;;
    medium2) echo "medium, 2 segments, hull 6" ;;
    low) echo "low" ;;
    low2) echo "low, 2 segments, hull 6" ;;
    r10) echo "low, edge_refine 1 (its passes, nothing marked)" ;;
    r6) echo "low, edge_refine 0.6" ;;
    r3) echo "low, edge_refine 0.3" ;;
    r3s2) echo "low, 2 segments, hull 6, edge_refine 0.3" ;;
  esac
}
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for v in $VIEWS; do
    for c in $CONFIGS; do
      t=$($C bench "scenes/$v.scene" --size "$SIZE" --frames 15 --warmup 3 $(sets "$c") |
          sed -n 's/.*FrameTime: \([0-9.]*\) ms.*/\1/p' | head -1)
      echo "$v $c $t" >>"$T/all"
    done
  done
  r=$((r + 1))
done
have_numpy=0
/usr/bin/python3 -c 'import numpy' 2>/dev/null && have_numpy=1
if [ "$have_numpy" = 1 ]; then
  for v in $VIEWS; do
    for c in $CONFIGS; do
      $C render "scenes/$v.scene" --size "$SIZE" $(sets "$c") -o "$T/$v-$c.pfm" >/dev/null
    done
  done
fi
err() { # VIEW CONFIG: cloud rel. RMSE against medium (pixels differing from the top-left sky pixel by 1 %)
  [ "$have_numpy" = 1 ] || { echo "-"; return; }
  /usr/bin/python3 - "$T/$1-$2.pfm" "$T/$1-medium.pfm" <<'PY'
import sys, numpy as np
def rd(p):
    f = open(p, 'rb'); f.readline(); w, h = map(int, f.readline().split()); s = float(f.readline())
    return np.frombuffer(f.read(), dtype='<f4' if s < 0 else '>f4').reshape(h, w, 3).astype(np.float64)
a, b = rd(sys.argv[1]), rd(sys.argv[2])
sky = b[-1, 0]  # PFM rows run bottom to top: the image's top-left pixel
cloud = (np.abs(a - sky) > 0.01 * sky).any(axis=2) | (np.abs(b - sky) > 0.01 * sky).any(axis=2)
cloud &= b[:, :, 1] < 1000 * sky[1]  # not the sun's disk
print("%.4f" % np.sqrt(((a - b)[cloud] ** 2).sum() / (b[cloud] ** 2).sum()))
PY
}
med() { awk -v v="$1" -v c="$2" '$1 == v && $2 == c { print $3 }' "$T/all" | sort -n |
        awk '{ x[NR] = $1 } END { print x[int((NR + 1) / 2)] }'; }
echo "| view | configuration | ms | / medium | error against medium |"
echo "| --- | --- | ---: | ---: | ---: |"
for v in $VIEWS; do
  m=$(med "$v" medium)
  for c in $CONFIGS; do
    t=$(med "$v" "$c")
    printf '| %s | %s | %s | %.2f | %s |\n' "$v" "$(label "$c")" "$t" "$(echo "$t $m" | awk '{print $1/$2}')" \
      "$(err "$v" "$c")"
  done
done
echo
echo "($ROUNDS rounds, $SIZE, LP_NUM_THREADS=${LP_NUM_THREADS:-unset}, load $(cut -d' ' -f1-3 /proc/loadavg))"
