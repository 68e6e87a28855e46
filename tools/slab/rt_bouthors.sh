#!/bin/sh
# Where does a slab start to reflect more than it transmits?  Fluxes R, T and the radiances a viewer sees at the top
# (reflected, looking straight down) and at the base (transmitted, looking straight up), vs optical thickness tau
# (full Mie extinction; the chopped table transports (1 - f) tau), for the sun at zenith and at 60 deg.
# Writes data/slab_RT_crossover.txt and data/slab_sphere_updown.txt (finite cloud, below). Usage: sh tools/slab/rt_bouthors.sh [PHOTONS] [PHASE]
set -eu
N=${1:-4e4}; PHASE=${2:-mie:data/mie_cloud.tbl:g}
out=data/slab_RT_crossover.txt
{
  echo "# build/cumulo-slab --tau TAU --mu0 MU0 --phase $PHASE --photons $N --seed 1 --report totals,radiance --mu 1,0.5"
  echo "# radiance = pi I/(mu0 F), diffuse, azimuth-averaged; Rz/Tz: reflected/transmitted at mu = 1; R05/T05 at mu = 0.5"
  echo "# tau mu0 R R_se T T_se Rz Rz_se Tz Tz_se R05 R05_se T05 T05_se"
  for mu in 1 0.5; do
    for tau in 2 4 6 8 10 12 14 16 20 25 30 40 60; do
      build/cumulo-slab --tau $tau --mu0 $mu --phase "$PHASE" --photons "$N" --seed 1 --threads "${THREADS:-1}" \
        --report totals,radiance --mu 1,0.5 --quiet |
        awk -v t=$tau -v mu=$mu '/^R /{r=$2; rs=$4} /^T /{tt=$2; ts=$4}
          /^reflect mu=1 /{rz=$3; rzs=$5} /^transmit mu=1 /{tz=$3; tzs=$5}
          /^reflect mu=0.5 /{r5=$3; r5s=$5} /^transmit mu=0.5 /{t5=$3; t5s=$5}
          END {print t, mu, r, rs, tt, ts, rz, rzs, tz, tzs, r5, r5s, t5, t5s}'
    done
  done
} >"$out"
cat "$out"
# The same question for a finite cloud: a sphere of diameter D lit from the zenith (build/cumulo-slab-sphere), for the
# k_e of README (2 pi r_e^2 rho = 0.0905 m^-1) and of the Mie table (sigma_ext 173.1 um^2 x 400 cm^-3 = 0.0692 m^-1).
# top/base: fraction of the intercepted light leaving through the upper/lower hemisphere; up: leaving upwards.
out2=data/slab_sphere_updown.txt
{
  echo "# build/cumulo-slab-sphere --diameter D --ke KE --phase $PHASE --photons 1e5 --seed 1"
  echo "# ke D_m top top_se base up up_se down"
  for ke in 0.0905 0.0692; do
    for D in 100 150 200 225 300 350 400 450 500 550 700 900 1200; do
      build/cumulo-slab-sphere --diameter $D --ke $ke --phase "$PHASE" --photons 1e5 --seed 1 |
        awk -v D=$D -v k=$ke '/^top/{t=$2; ts=$4} /^base/{b=$2} /^up /{u=$2; us=$4} /^down /{dn=$2}
          END {print k, D, t, ts, b, u, us, dn}'
    done
  done
} >"$out2"
cat "$out2"
