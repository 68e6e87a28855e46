#!/bin/sh
# scripts/methods_plot.sh DIR: draws DIR/methods.png from DIR/methods.dat, which `cumulo-sweep --methods` writes
# (columns: view index, family 0 = Kol's method / 1 = uniform ray march / 2, 3 = their controls, time / high, cloud relative RMSE, contrast /
# the path tracer's, SSIM, "label", "view"): one panel a view, both families on the same axes. Needs gnuplot
# (Debian: gnuplot-nox); without it says so and exits 3 (the tables are still there).
set -e
dir=${1:?usage: sh scripts/methods_plot.sh DIR}
dat="$dir/methods.dat"
[ -f "$dat" ] || { echo "methods_plot: no $dat (run cumulo-sweep --methods first)" >&2; exit 2; }
if ! command -v gnuplot >/dev/null 2>&1; then
    echo "methods_plot: gnuplot not found: $dir/methods.png not drawn (install gnuplot-nox)" >&2
    exit 3
fi
term="pngcairo noenhanced size 1400,1000 font 'DejaVu Sans,10'"
gnuplot -e "set terminal" 2>/dev/null | grep -q pngcairo || term="png noenhanced size 1400,1000"
views=$(awk '!/^#/ { print $1 }' "$dat" | sort -un)
n=$(echo "$views" | wc -l)
cols=2; rows=$(( (n + 1) / 2 ))
{
  echo "set terminal $term"
  echo "set output '$dir/methods.png'"
  echo "set multiplot layout $rows,$cols title \"Kol's method against the uniform ray march: time (relative to high, one interleaved run) vs error on the cloud's pixels (against the path tracer)\""
  echo "set logscale x"
  echo "set grid"
  echo "set xlabel 'frame time / high'"
  echo "set ylabel 'relative RMSE on cloud pixels (3x3 box)'"
  echo "set key top right"
  for v in $views; do
    name=$(awk -v v="$v" '!/^#/ && $1 == v { n = $NF; gsub(/"/, "", n); print n; exit }' "$dat")
    echo "set title '$name'"
    echo "plot '$dat' using (\$1==$v && \$2==0 ? \$3 : 1/0):4 with points pt 7 ps 1.2 lc rgb '#cc3311' title \"Kol's method\", \\"
    echo "     '' using (\$1==$v && \$2==1 ? \$3 : 1/0):4 with points pt 6 ps 1.2 lc rgb '#4477aa' title 'uniform march', \\"
    echo "     '' using (\$1==$v && \$2==2 ? \$3 : 1/0):4 with points pt 7 ps 0.8 lc rgb '#aaaaaa' title 'Kol, controls (defaults replaced, no lobe)', \\"
    echo "     '' using (\$1==$v && \$2==3 ? \$3 : 1/0):4 with points pt 6 ps 0.8 lc rgb '#aaaaaa' title 'uniform, exact noise'"
  done
  echo "unset multiplot"
} | gnuplot
echo "methods_plot: wrote $dir/methods.png"
