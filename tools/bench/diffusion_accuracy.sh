#!/bin/sh
# tools/bench/diffusion_accuracy.sh: ms.mode = diffusion against cumulo-pt on the plain shapes README's "Multiple
# scattering solved on the cloud's shape" quotes: wide slabs (3000 x 100 x 3000 m, HG 0.853, no noise, a black sky,
# an 8x8 view of the middle) lit 20 and 60 degrees high and seen from above and below, and a sphere (radius 300 m)
# lit from the side (sun 30 degrees high at azimuth 90) seen from 90 degrees at 64x64, whose profile is the mean
# luminance of rows 28-35 in columns of 4 from the lit limb, each over the path tracer's. `high` with ms.mode =
# diffusion at each of GRIDS (ms.grid). Accuracy, not speed: the numbers do not depend on the machine's load.
# Usage: tools/bench/diffusion_accuracy.sh [GRIDS] [SPP] [SPHERE_BOUNDARY]   (defaults "32", 2048, 62)
# Environment: G, the phase function's asymmetry (default 0.853; 0: isotropic, nothing for delta-M to truncate), and
# MS=1: the slabs' multiple scattering alone, the path tracer's all orders less its first (--max-depth 1) over
# diffusion's less its single scattering (ms.mode = none); LOBE=off: without the forward lobe's own light (ms.lobe).
set -eu
GRIDS=${1:-32}
SPP=${2:-2048}
BOUNDARY=${3:-62}
G=${G:-0.853}
MS=${MS:-0}
LOBE=${LOBE:-on}
C=${CUMULO:-build/cumulo}
PT=${CUMULO_PT:-build/cumulo-pt}
T=${TMPDIR:-/tmp}/cumulo-diffusion-accuracy.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT
# scene DENSITY BOUNDARY RADII SIZE CAMERA FOV ELEVATION AZIMUTH
scene() {
  printf '[output]\nsize = %s\n[camera]\nposition = %s\nlook_at = 0 0 0\nfov = %s\n' "$4" "$5" "$6"
  printf '[sun]\nelevation = %s\nazimuth = %s\nirradiance = 100 100 100\n' "$7" "$8"
  printf '[sky]\nmodel = constant\ncolor = 0 0 0\n'
  printf '[cloud]\ndensity = %s\ndroplet_radius = 6\nboundary = %s\nphase = hg\ng = %s\n' "$1" "$2" "$G"
  printf '[ellipsoid]\ncenter = 0 0 0\nradii = %s\n[quality]\nnoise = off\n' "$3"
}
# luminance of a W x W PFM's pixels: "row column value" lines (rows as stored)
pixels() {
  tail -c $((12 * $2 * $2)) "$1" | od -An -f -w12 -v |
    awk -v w="$2" '{ print int((NR - 1) / w), (NR - 1) % w, 0.2126 * $1 + 0.7152 * $2 + 0.0722 * $3 }'
}
render() { # SCENE OUT GRID [MODE]
  $C render "$1" -o "$2" --set quality.preset=high --set ms.mode="${4:-diffusion}" --set ms.grid="$3" \
    --set ms.lobe="$LOBE" >/dev/null 2>&1
}
mean8() { pixels "$1" 8 | awk '{ s += $3 } END { print s / NR }'; }
alone=; [ "$MS" = 1 ] && alone=", multiple scattering alone"
echo "Slabs (HG g = $G): diffusion's mean over the path tracer's ($SPP spp)$alone"
echo "| slab | camera | sun | path tracer |$(for g in $GRIDS; do printf ' %s cells |' "$g"; done)"
echo "| --- | --- | ---: | ---: |$(for g in $GRIDS; do printf ' ---: |'; done)"
# density, boundary (m), the camera's height and its z (the sun is at azimuth 180, on the +z side: a camera at -z
# looks toward it), sun elevation. The last four: the eye 10 or 20 degrees above the top (520 / 1030 m up, 2950 /
# 2820 m out), toward the sun and with it behind, where a lit face's limb meets the eye.
for c in "400 62 1500 -600 60" "400 62 -1500 -600 60" "400 62 1500 -600 20" "400 62 1500 600 20" \
         "400 62 -1500 -600 20" "800 62 -1500 -600 60" "1600 62 -1500 -600 60" "1600 5 -1500 -600 60" \
         "400 62 520 -2950 20" "400 62 520 2950 20" "400 62 1030 2820 20" "400 62 520 2950 45"; do
  set -- $c
  scene "$1" "$2" "3000 100 3000" "8 8" "0 $3 $4" 10 "$5" 180 > "$T/slab.scene"
  $PT "$T/slab.scene" -o "$T/pt.pfm" --spp "$SPP" -q >/dev/null 2>&1
  pt=$(mean8 "$T/pt.pfm") pt1=0 ss=0
  if [ "$MS" = 1 ]; then
    $PT "$T/slab.scene" -o "$T/pt1.pfm" --spp "$SPP" --max-depth 1 -q >/dev/null 2>&1
    pt1=$(mean8 "$T/pt1.pfm")
    render "$T/slab.scene" "$T/s.pfm" 32 none
    ss=$(mean8 "$T/s.pfm")
  fi
  row="| density $1, boundary $2 m | 0 $3 $4 | $5° | $pt |"
  for g in $GRIDS; do
    render "$T/slab.scene" "$T/d.pfm" "$g"
    row="$row $(mean8 "$T/d.pfm" |
      awk -v p="$pt" -v p1="$pt1" -v s="$ss" '{ printf "%.3f", ($1 - s) / (p - p1) }') |"
  done
  echo "$row"
done
echo
echo "Sphere (boundary $BOUNDARY m): diffusion over the path tracer by columns of 4 from the lit limb, then the mean"
scene 400 "$BOUNDARY" "300 300 300" "64 64" "0 0 -1500" 26 30 90 > "$T/sphere.scene"
$PT "$T/sphere.scene" -o "$T/pt.pfm" --spp "$SPP" -q >/dev/null 2>&1
pixels "$T/pt.pfm" 64 > "$T/pt.txt"
for g in $GRIDS; do
  render "$T/sphere.scene" "$T/d.pfm" "$g"
  pixels "$T/d.pfm" 64 | paste -d' ' "$T/pt.txt" - |
    awk -v g="$g" '$1 >= 28 && $1 < 36 && $2 >= 4 && $2 < 60 { b = int($2 / 4); p[b] += $3; d[b] += $6 }
      { sp += $3; sd += $6 }
      END { printf "%3s cells:", g; for (b = 1; b < 15; b++) printf " %.2f", d[b] / p[b]; printf "  mean %.3f\n", sd / sp }'
done
