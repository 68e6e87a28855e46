#!/bin/sh
# scripts/sweep_plot.sh DIR: draws DIR/pareto.png (time ratio vs mean relative RMSE on the cloud's pixels) from DIR/pareto.dat, which
# `cumulo sweep` writes (columns: time ratio, relative RMSE, kind, label; kind 0 = one knob changed from high,
# 1 = greedy combination, 2 = preset, 9 = the reference's own noise level). Needs gnuplot (Debian: gnuplot-nox);
# without it says so and exits 3 (the CSV and tables are still there).
set -e
dir=${1:?usage: sh scripts/sweep_plot.sh DIR}
dat="$dir/pareto.dat"
[ -f "$dat" ] || { echo "sweep_plot: no $dat (run cumulo sweep first)" >&2; exit 2; }
if ! command -v gnuplot >/dev/null 2>&1; then
    echo "sweep_plot: gnuplot not found: $dir/pareto.png not drawn (install gnuplot-nox; $dir/sweep.csv is written)" >&2
    exit 3
fi
term="pngcairo noenhanced size 1200,800 font 'DejaVu Sans,10'"
gnuplot -e "set terminal" 2>/dev/null | grep -q pngcairo || term="png noenhanced size 1200,800"
noise=$(awk '$3 == 9 { print $2 }' "$dat")
noiseline=
[ -n "$noise" ] && noiseline="set arrow from graph 0, first $noise to graph 1, first $noise nohead dt 2 lc rgb '#888888'
set label 'reference (path tracer) noise level, whole image' at graph 0.01, first $noise offset 0,0.7 tc rgb '#888888'"
gnuplot <<GP
set terminal $term
set output "$dir/pareto.png"
set title "cumulo: speed vs accuracy against the path tracer (means over the views; time relative to high, same run)"
set xlabel "frame time / high"
set ylabel "mean relative RMSE on the cloud's pixels (3x3 box)"
set logscale y
set grid
set key top right
$noiseline
set datafile commentschars "#"
plot "$dat" using (\$3==0?\$1:1/0):2 with points pt 7 ps 0.8 lc rgb "#4477aa" title "one knob changed from high", \
     "" using (\$3==0?\$1:1/0):2:4 with labels font ",7" offset 0.5,0.3 left tc rgb "#4477aa" notitle, \
     "" using (\$3==1?\$1:1/0):2 with linespoints pt 6 ps 0.9 lc rgb "#999999" title "greedy combinations (re-measured)", \
     "" using (\$3==1?\$1:1/0):2:4 with labels font ",7" offset 0.5,-0.5 left tc rgb "#999999" notitle, \
     "" using (\$3==2?\$1:1/0):2 with points pt 5 ps 1.8 lc rgb "#cc3311" title "presets", \
     "" using (\$3==2 && strcol(4) eq "low" ? \$1 : 1/0):2:4 with labels font ",11" offset 0,-1.2 tc rgb "#cc3311" notitle, \
     "" using (\$3==2 && strcol(4) eq "medium" ? \$1 : 1/0):2:4 with labels font ",11" offset 0,1.2 tc rgb "#cc3311" notitle, \
     "" using (\$3==2 && strcol(4) eq "high" ? \$1 : 1/0):2:4 with labels font ",11" offset 0,1.2 tc rgb "#cc3311" notitle
GP
echo "sweep_plot: wrote $dir/pareto.png"
