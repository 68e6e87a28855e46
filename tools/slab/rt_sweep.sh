#!/bin/sh
# R and T vs geometric thickness (k_e = 0.0905 m^-1) for README plots: writes data/slab_RT_vs_thickness.txt.
# Usage: sh tools/slab/rt_sweep.sh [PHOTONS] [PHASE]
set -eu
N=${1:-4e4}; PHASE=${2:-hg:0.85}
out=data/slab_RT_vs_thickness.txt
{
  echo "# R and T (T includes the unscattered beam) vs thickness; build/cumulo-slab --phase $PHASE --photons $N --seed 1"
  echo "# thickness_m mu0 R R_se T T_se"
  for mu in 1 0.5; do
    for t in 10 20 35 50 75 100 150 200 300 400 500 700 1000 1500 2000; do
      build/cumulo-slab --thickness $t --mu0 $mu --phase "$PHASE" --photons "$N" --seed 1 --threads "${THREADS:-1}" --quiet |
        awk -v t=$t -v mu=$mu '/^R /{r=$2; rs=$4} /^T /{tt=$2; ts=$4} END {print t, mu, r, rs, tt, ts}'
    done
  done
} >"$out"
cat "$out"
