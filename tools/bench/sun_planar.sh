#!/bin/sh
# tools/bench/sun_planar.sh: what reading the opacity map below each texel's entry (light.sun_planar) does to single
# scattering, by map size: each scene rendered with ms.mode = none under a black constant sky (the sun's first
# scattering alone) at quality.sun_map_size = SIZES, read planar and not, against the same renderer's with 1024
# texels (where the texels no longer matter, planar or not): the mean over the reference's cloud pixels (luminance
# above 1e-3 of its largest) and the relative RMSE there. Accuracy, not speed: the numbers do not depend on the load.
# README "What it computes" quotes them. Usage: tools/bench/sun_planar.sh [SCENES] [SIZES] [PRESET]
# (defaults "cumulus sweep_below_hg glory", "16 32 64 128", high).
set -eu
SCENES=${1:-cumulus sweep_below_hg glory}
SIZES=${2:-16 32 64 128}
PRESET=${3:-high}
C=${CUMULO:-build/cumulo}
T=${TMPDIR:-/tmp}/cumulo-sun-planar.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
render() { # SCENE OUT SIZE PLANAR
  $C render "scenes/$1.scene" -o "$2" --size 160x120 --set sky.model=constant --set "sky.color=0 0 0" \
    --set quality.preset="$PRESET" --set ms.mode=none --set quality.sun_map_size="$3" --set light.sun_planar="$4" \
    >/dev/null
}
# luminance of each of a 160x120 PFM's pixels, one a line
lum() {
  tail -c $((12 * 160 * 120)) "$1" | od -An -f -w12 -v | awk '{ print 0.2126 * $1 + 0.7152 * $2 + 0.0722 * $3 }'
}
echo "| scene ($PRESET) | map texels | planar: mean / 1024 texels' | RMSE | not planar: mean | RMSE |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for s in $SCENES; do
  render "$s" "$T/ref.pfm" 1024 on
  lum "$T/ref.pfm" > "$T/ref.txt"
  for m in $SIZES; do
    row="| $s | $m |"
    for p in on off; do
      render "$s" "$T/x.pfm" "$m" "$p"
      row="$row $(lum "$T/x.pfm" | paste -d' ' "$T/ref.txt" - |
        awk '{ r[NR] = $1; x[NR] = $2; if ($1 > most) most = $1 }
        END { for (i = 1; i <= NR; i++) if (r[i] > 1e-3 * most) { n++; sr += r[i]; sx += x[i]; d += (x[i] - r[i]) ^ 2 }
              printf "%.3f | %.3f |", sx / sr, sqrt(d / n) / (sr / n) }')"
    done
    echo "$row"
  done
done
