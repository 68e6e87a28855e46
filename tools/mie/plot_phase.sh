#!/bin/sh
# Plots the RGB phase functions of a cumulo Mie table on a log scale (like Kol 2013 Fig. 2.15) into a PNG.
# Needs gnuplot with the pngcairo terminal (Debian: gnuplot-nox). The resulting docs/mie_phase.png is committed,
# so neither the build nor the tests need gnuplot.
# usage: sh tools/mie/plot_phase.sh [data/mie_cloud.tbl] [docs/mie_phase.png]
set -e
tbl=${1:-data/mie_cloud.tbl}
png=${2:-docs/mie_phase.png}
command -v gnuplot >/dev/null || { echo "plot_phase.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
# Only the angle rows: four numbers, after the 'angles N' line.
awk 'p && NF == 4 { print } $1 == "angles" { p = 1 }' "$tbl" > "$tmp"
f=$(awk '$1 == "f" { printf "f = %.3f / %.3f / %.3f", $2, $3, $4 }' "$tbl")
g=$(awk '$1 == "g" { printf "g = %.4f / %.4f / %.4f", $2, $3, $4 }' "$tbl")
drop=$(awk '/^# droplets:/ { sub(/^# droplets: /, ""); sub(/;.*/, ""); gsub(/_eff/, "_{eff}"); print }' "$tbl")
mkdir -p "$(dirname "$png")"
gnuplot <<GP
set terminal pngcairo size 1200,520 font "DejaVu Sans,11"
set output "$png"
set multiplot layout 1,2 title "Mie phase function of cloud droplets ($drop), R/G/B; $g; $f (chop at 8 deg)"
set logscale y
set format y "10^{%L}"
set grid
set xlabel "scattering angle (deg)"
set ylabel "P(theta) (sr^{-1}), integral over sphere = 1"
set xrange [0:180]
set xtics 20
set key top right
plot "$tmp" using 1:2 with lines lw 1.5 lc rgb "#d62728" title "R", \
     "$tmp" using 1:3 with lines lw 1.5 lc rgb "#2ca02c" title "G", \
     "$tmp" using 1:4 with lines lw 1.5 lc rgb "#1f77b4" title "B"
set xrange [0:20]
set xtics 2
set arrow 1 from 8, graph 0 to 8, graph 1 nohead dt 2 lc rgb "black"
set label 1 "chop 8 deg" at 8.3, graph 0.9
set title "forward peak"
plot "$tmp" using 1:2 with lines lw 1.5 lc rgb "#d62728" title "R", \
     "$tmp" using 1:3 with lines lw 1.5 lc rgb "#2ca02c" title "G", \
     "$tmp" using 1:4 with lines lw 1.5 lc rgb "#1f77b4" title "B"
unset multiplot
GP
echo "plot_phase.sh: wrote $png"
