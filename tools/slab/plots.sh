#!/bin/sh
# Draws the README plots with gnuplot: R/T vs thickness, per-group C vs depth, and a fit-vs-simulation profile.
# Usage (repo root, after rt_sweep.sh and gen_tables.sh): sh tools/slab/plots.sh [TABLE]
set -eu
TAB=${1:-build/slab_tables/C_t00400_L30.txt}
FIT=${FIT:-data/slab_fit_bouthors.txt}
mkdir -p docs build/slab_plots
W=build/slab_plots
ph=$(sed -n 1p data/slab_RT_vs_thickness.txt | sed -n 's/.*--phase \([^ ]*\).*/\1/p')
case "$ph" in mie:*) ph="chopped Mie (${ph#mie:})" ;; hg:*) ph="HG g = ${ph#hg:}" ;; esac
gnuplot <<GP
set terminal pngcairo size 900,600 font "sans,11"
set output "docs/slab_RT_vs_thickness.png"
set logscale x
set xlabel "slab thickness t (m), k_e = 0.0905 m^{-1}"
set ylabel "flux fraction"
set key center right
set grid
set title "Non-absorbing slab, $ph: reflectance R and transmittance T (incl. unscattered), MC +- 1 SE" noenhanced
plot "data/slab_RT_vs_thickness.txt" u (\$2==1?\$1:1/0):3:4 w yerrorlines lw 2 t "R, {/Symbol m}_0 = 1", \
     "" u (\$2==1?\$1:1/0):5:6 w yerrorlines lw 2 t "T, {/Symbol m}_0 = 1", \
     "" u (\$2==0.5?\$1:1/0):3:4 w yerrorlines lw 2 dt 2 t "R, {/Symbol m}_0 = 0.5", \
     "" u (\$2==0.5?\$1:1/0):5:6 w yerrorlines lw 2 dt 2 t "T, {/Symbol m}_0 = 0.5"
GP
# Bouthors' "thicker than ~500 m reflects more than it transmits": slab R vs a finite cloud (sphere, sun at zenith)
if [ -f data/slab_sphere_updown.txt ]; then
gnuplot <<GP
set terminal pngcairo size 900,600 font "sans,11"
set output "docs/slab_sphere_updown.png"
set logscale x
set xlabel "slab thickness / sphere diameter (m)"
set ylabel "fraction of the intercepted sunlight"
set key bottom right
set grid
set yrange [0:1]
set title "Sun at zenith, $ph: light leaving upwards (slab: R) vs thickness" noenhanced
plot "data/slab_RT_vs_thickness.txt" u (\$2==1?\$1:1/0):3:4 w yerrorlines lw 2 t "slab R, k_e = 0.0905 m^{-1}", \
     "data/slab_sphere_updown.txt" u (\$1==0.0905?\$2:1/0):6:7 w yerrorlines lw 2 t "sphere, leaving upwards, k_e = 0.0905", \
     "" u (\$1==0.0692?\$2:1/0):6:7 w yerrorlines lw 2 t "sphere, leaving upwards, k_e = 0.0692 (Mie {/Symbol s}_{ext})", \
     "" u (\$1==0.0905?\$2:1/0):3:4 w yerrorlines lw 1 dt 2 t "sphere, leaving through the upper hemisphere, k_e = 0.0905", \
     0.5 w l lc rgb "black" dt 3 t ""
GP
echo "wrote docs/slab_sphere_updown.png"
fi
# per-group C vs depth for light going down (thetaV = 0) and up (thetaV = 180), phiV = 0
for g in 1 2 3 4 5 6 7 8; do
  awk -v g=$g '$1==g && $4==0 && $5==0 {print $3, $7, $8}' "$TAB" >"$W/down_$g.txt"
  awk -v g=$g '$1==g && $4==180 && $5==0 {print $3, $7, $8}' "$TAB" >"$W/up_$g.txt"
done
info=$(sed -n 2p "$TAB" | awk '{ for (i = 2; i <= NF; i++) if ($i ~ /^(tau|thickness_m|mu0|f|photons)=/) printf "%s ", $i }')
case "$(sed -n 2p "$TAB")" in *phase=mie:*) info="$info (chopped Mie)" ;; esac
gnuplot <<GP
set terminal pngcairo size 1100,500 font "sans,10"
set output "docs/slab_groups_vs_depth.png"
set multiplot layout 1,2 title "C(n, t, d) per scattering-order group: $info" noenhanced
set logscale y
set xlabel "viewpoint depth d (m)"
set ylabel "C = I / F_{sun} (sr^{-1})"
set key outside right
set grid
set yrange [1e-5:*]
set title "light going down ({/Symbol q}_V = 0: seen from below)"
plot for [g=1:8] "$W/down_".g.".txt" u 1:(\$2>0?\$2:1/0):3 w yerrorlines t word("1 2 3 4 5-6 7-9 10-15 16+", g)
set title "light going up ({/Symbol q}_V = 180: seen from above)"
plot for [g=1:8] "$W/up_".g.".txt" u 1:(\$2>0?\$2:1/0):3 w yerrorlines t word("1 2 3 4 5-6 7-9 10-15 16+", g)
unset multiplot
GP
echo "wrote docs/slab_RT_vs_thickness.png docs/slab_groups_vs_depth.png"
# fit vs simulation (needs: build/cumulo-slab-fit --model bouthors|logsep --predict build/slab_plots/pred TABLES(t=400))
PB=$W/pred_bouthors.txt; PL=$W/pred_logsep.txt
if [ -f "$PB" ] && [ -f "$PL" ]; then
  for g in 3 8; do for v in 0 180; do
    awk -v g=$g -v v=$v '$1==g && $4==v && $5==0 && $6>29 && $6<31 {print $3, $7, $8, $9}' "$PB" >"$W/fb_${g}_$v.txt"
    awk -v g=$g -v v=$v '$1==g && $4==v && $5==0 && $6>29 && $6<31 {print $3, $9}' "$PL" >"$W/fl_${g}_$v.txt"
  done; done
  gnuplot <<GP
set terminal pngcairo size 1100,800 font "sans,10"
set output "docs/slab_fit_profiles.png"
set multiplot layout 2,2 title "t = 400 m, {/Symbol q}_L = 30 deg, {/Symbol f}_V = 0: simulation (+-1 SE) vs fitted models"
set logscale y
set grid
set xlabel "d (m)"; set ylabel "C (sr^{-1})"; set yrange [1e-9:2]
do for [g in "3 8"] {
  do for [v in "0 180"] {
    set title sprintf("group %s, {/Symbol q}_V = %s", (g eq "8" ? "16+" : g), v)
    plot "$W/fb_".g."_".v.".txt" u 1:(\$2>0?\$2:1/0):3 w yerrorbars pt 7 t "MC", \
         "" u 1:(\$4>0?\$4:1/0) w l lw 2 t "eq. 3.32 (Bouthors)", \
         "$W/fl_".g."_".v.".txt" u 1:(\$2>0?\$2:1/0) w l lw 2 dt 2 t "log-separable"
  }
}
unset multiplot
GP
  echo "wrote docs/slab_fit_profiles.png"
fi
