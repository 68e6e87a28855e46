#!/bin/sh
# tools/bench/downsample.sh: what quality.cloud_downsample buys (README "Performance"): the frame time of each preset
# with the clouds at 1/1, 1/2 and 1/4 resolution, on a view a cloud fills (silver_lining) and on a field
# (field_noon), rounds interleaved (every configuration once per round), the median over rounds, and the ratio to
# N = 1. Usage: tools/bench/downsample.sh [ROUNDS] [SIZE] [PRESETS]; LP_NUM_THREADS as in the environment.
set -eu
ROUNDS=${1:-3}
SIZE=${2:-800x480}
PRESETS=${3:-high medium}
C=${CUMULO:-build/cumulo}
T=${TMPDIR:-/tmp}/cumulo-ds-bench.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
r=1
while [ "$r" -le "$ROUNDS" ]; do
  for s in silver_lining field_noon; do
    for p in $PRESETS; do
      for n in 1 2 4; do
        ms=$($C bench scenes/$s.scene --size "$SIZE" --frames 5 --warmup 2 --set quality.preset=$p \
               --set quality.cloud_downsample=$n | sed -n 's/.*FrameTime: \([0-9.]*\) ms.*/\1/p')
        echo "$s $p $n $ms" >>"$T/all"
      done
    done
  done
  r=$((r + 1))
done
printf '%-14s %-7s %10s %10s %10s %9s %9s\n' scene preset "N=1 ms" "N=2 ms" "N=4 ms" "1/2 gain" "1/4 gain"
for s in silver_lining field_noon; do
  for p in $PRESETS; do
    med() { awk -v s=$s -v p=$p -v n=$1 '$1 == s && $2 == p && $3 == n { print $4 }' "$T/all" | sort -n |
            awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
    a=$(med 1); b=$(med 2); c=$(med 4)
    printf '%-14s %-7s %10s %10s %10s %8.2fx %8.2fx\n' $s $p "$a" "$b" "$c" "$(echo "$a $b" | awk '{print $1/$2}')" \
      "$(echo "$a $c" | awk '{print $1/$2}')"
  done
done
