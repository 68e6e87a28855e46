#!/bin/sh
# scripts/sweep_plot.sh DIR: draws DIR/pareto.png (time ratio vs mean relative RMSE) from DIR/pareto.dat, which
# `cumulo sweep` writes. Needs gnuplot (Debian: gnuplot-nox); without it says so and exits 3 (the CSV is still there).
set -e
dir=${1:?usage: sh scripts/sweep_plot.sh DIR}
dat="$dir/pareto.dat"
[ -f "$dat" ] || { echo "sweep_plot: no $dat (run cumulo sweep first)" >&2; exit 2; }
if ! command -v gnuplot >/dev/null 2>&1; then
    echo "sweep_plot: gnuplot not found: $dir/pareto.png not drawn (install gnuplot-nox; $dir/sweep.csv is written)" >&2
    exit 3
fi
term="pngcairo size 1100,750 font 'DejaVu Sans,10'"
gnuplot -e "set terminal" 2>/dev/null | grep -q pngcairo || term="png size 1100,750"
gnuplot <<GP
set terminal $term
set output "$dir/pareto.png"
set title "cumulo: speed vs accuracy (mean over views; time relative to high in the same run)"
set xlabel "frame time / high"
set ylabel "mean relative RMSE vs path tracer"
set logscale y
set grid
set key top right
set datafile commentschars "#"
plot "$dat" using (\$3==0?\$1:1/0):2 with points pt 7 ps 0.8 lc rgb "#4477aa" title "one knob changed", \
     "" using (\$3==0?\$1:1/0):2:4 with labels font ",7" offset 0.6,0.35 left tc rgb "#4477aa" notitle, \
     "" using (\$3==1?\$1:1/0):2 with linespoints pt 6 ps 0.9 lc rgb "#999999" title "greedy combinations", \
     "" using (\$3==2?\$1:1/0):2 with points pt 5 ps 1.8 lc rgb "#cc3311" title "presets", \
     "" using (\$3==2?\$1:1/0):2:4 with labels font ",11" offset -0.8,0.9 tc rgb "#cc3311" notitle
GP
echo "sweep_plot: wrote $dir/pareto.png"
