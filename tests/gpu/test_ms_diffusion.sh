# tests/gpu/test_ms_diffusion.sh: ms.mode = diffusion in the renderer against the path tracer and its own closed form.
# A wide slab seen from above, the sun behind it (scattering angle 128 degrees), an 8x8 view of its interior: the
# light it sends back, all orders, from cumulo-pt at 4096 samples a pixel, against the renderer's (the delta-M medium
# solved on the cloud's diffusion grid, single scattering split after Nakajima & Tanaka; ms_diffusion.glsl). Two
# slabs. A thin one with a sharp edge (optical depth 4.5, boundary 5 m) is where delta-Eddington is weakest: its
# scaled optical depth is 1.2, and the model's own plane-parallel answer (eddington(), below) is 24 % under the path
# tracer. There the renderer must (a) reproduce that closed form within 12 % (it checks the grid, the split and the
# source integration; measured +9 %, of which Wilson's limiter, which the closed form lacks, is 6) and (b) come closer
# to the path tracer than the octave model (measured -16 % against the octaves' -30 %). A thick one with the sweep's
# fuzzy 62 m boundary (optical depth 18): within 10 % of the path tracer (measured -6 %, its own plane-parallel
# closed form -10 %; the octave model misses 74 %).
# A sphere lit from three sides: within 8 % of the path tracer; a dense layer from below on a fine grid: within 15 %
# (below).
# Also: the grid is solved (the debug log says so), and a frame in which many clouds' maps follow the sun spends at
# most ms.frame_work on solving their grids again, spreading a solve over frames (pass_msd.h). From the repository
# root.
. tests/lib.sh
C=${CUMULO:-build/cumulo}
PT=${CUMULO_PT:-build/cumulo-pt}
T=build/test-output/ms_diffusion
rm -rf "$T"; mkdir -p "$T"
# scene DENSITY BOUNDARY [RADII SIZE CAMERA FOV SUN]: one ellipsoid at the origin, HG, no noise, a black sky; by
# default the wide slab seen from above with the sun behind it
scene() {
  cat <<SCENE
[output]
size = ${4:-8 8}
[camera]
position = ${5:-0 1500 -600}
look_at = 0 0 0
fov = ${6:-10}
[sun]
${7:-elevation = 60
azimuth = 180}
irradiance = 100 100 100
[sky]
model = constant
color = 0 0 0
[cloud]
density = $1
droplet_radius = 6
boundary = $2
phase = hg
g = 0.853
[ellipsoid]
center = 0 0 0
radii = ${3:-3000 100 3000}
[quality]
noise = off
SCENE
}
# The delta-Eddington radiance the model predicts for a plane-parallel slab of optical depth $1 (irradiance 100, HG g
# 0.853, conservative; the sun at mu0 = sin 60 deg, the eye at mu = 1500 / |(1500, 600)|, cos of the scattering angle
# -0.618): the scaled medium (f = g^2, g' = g / (1 + g), depth (1 - f) tau) solved in closed form with Marshak's
# conditions (F = A - E0 mu0 e^-t/mu0, phi = B - 3 (1 - g') A t - 3 mu0^2 E0 e^-t/mu0), its source (phi - 3 g' F mu) /
# 4pi plus the split single scattering integrated toward the eye.
eddington() {
  awk -v tau="$1" 'function hg(g, c) { return (1 - g * g) / (4 * 3.14159265 * (1 + g * g - 2 * g * c) ^ 1.5) }
    BEGIN { g = 0.853; m0 = sqrt(3) / 2; mu = 1500 / sqrt(1500 ^ 2 + 600 ^ 2); c = -0.618; E = 100
      f = g * g; gp = g / (1 + g); T = (1 - f) * tau; eT = exp(-T / m0)
      a21 = 1 + 1.5 * (1 - gp) * T; b1 = E * m0 + 1.5 * m0 * m0 * E; b2 = E * m0 * eT - 1.5 * m0 * m0 * E * eT
      det = -0.5 - 0.5 * a21; A = (-0.5 * b1 - 0.5 * b2) / det; B = (b2 - a21 * b1) / det
      p0 = hg(g, c); ps = (1 - f) * hg(gp, c); if (ps > p0) ps = p0
      L = (p0 - ps) * E * m0 / (m0 + mu) * (1 - exp(-tau * (1 / m0 + 1 / mu)))
      n = 4000; dt = T / n
      for (i = 0; i < n; i++) { t = (i + 0.5) * dt; e = exp(-t / m0); F = A - E * m0 * e
        phi = B - 3 * (1 - gp) * A * t - 3 * m0 * m0 * E * e; S = (phi - 3 * gp * F * mu) / (4 * 3.14159265)
        L += ((S > 0 ? S : 0) + ps / (1 - f) * E * e) * exp(-t / mu) * dt / mu }
      printf "%.4f", L }'
}
for s in "thin 100 5" "thick 400 62"; do
  set -- $s
  scene "$2" "$3" > "$T/$1.scene"
  $PT "$T/$1.scene" -o "$T/$1_pt.pfm" --spp 4096 -q 2>"$T/err" || { cat "$T/err" >&2; t_fail "$1: path tracer" "failed"; continue; }
  $C render "$T/$1.scene" -o "$T/$1_diffusion.pfm" --set quality.preset=high --set ms.mode=diffusion -v \
    >/dev/null 2>"$T/$1_log" || { cat "$T/$1_log" >&2; t_fail "$1: render" "failed"; continue; }
  $C render "$T/$1.scene" -o "$T/$1_octaves.pfm" --set quality.preset=medium --set ms.mode=octaves >/dev/null 2>&1
  pt=$(t_pfm_mean "$T/$1_pt.pfm"); di=$(t_pfm_mean "$T/$1_diffusion.pfm"); oc=$(t_pfm_mean "$T/$1_octaves.pfm")
  if grep -q "ms.mode = diffusion: .* sweeps" "$T/$1_log"; then t_ok "$1 slab: the diffusion grid is solved"
  else t_fail "$1 slab: the diffusion grid is solved" "no solve in the debug log"; fi
  if [ "$1" = thin ]; then
    ed=$(eddington 4.5)
    if awk -v e="$ed" -v d="$di" 'BEGIN { r = d / e - 1; exit !(e > 0 && d == d && r < 0.12 && r > -0.12) }'; then
      t_ok "thin slab: diffusion $di against its plane-parallel closed form $ed"
    else t_fail "thin slab: diffusion within 12 % of its plane-parallel closed form" \
                "diffusion '$di', closed form '$ed'"; fi
  fi
  # thin: closer to the path tracer than the octaves; thick: within 10 % of it
  bound=0; [ "$1" = thick ] && bound=0.10
  if awk -v p="$pt" -v d="$di" -v o="$oc" -v b="$bound" 'BEGIN { e = d / p - 1; f = o / p - 1; e = e < 0 ? -e : e;
       f = f < 0 ? -f : f; exit !(p > 0 && d == d && e < f && (b == 0 || e < b)) }'; then
    t_ok "$1 slab: diffusion $di against the path tracer's $pt (octaves $oc)"
  else t_fail "$1 slab: diffusion against the path tracer (thin: closer than the octaves; thick: within 10 %)" \
              "diffusion '$di', path tracer '$pt', octaves '$oc'"; fi
done
# A dense layer (density 800, optical depth about 30, the fuzzy boundary) seen from below, the sun 60 degrees high
# behind it, at ms.grid = 96: the grid's cells are 65 m across and 9 m tall. Its faces to empty space leak by the
# surface's slant in metres; taken in cells (a step of one up over one across read as 45 degrees), the fuzzy top's
# small steps held the light in and the base sent out 22 % more than the path tracer's (+10 % now). At the default
# grid of 32 (cells 29 m tall, 1.5 transport mean free paths) the same view is +14 %: README, "Multiple scattering".
scene 800 62 "3000 100 3000" "8 8" "0 -1500 -600" > "$T/dense.scene"
if $PT "$T/dense.scene" -o "$T/dense_pt.pfm" --spp 2048 -q 2>"$T/err" &&
   $C render "$T/dense.scene" -o "$T/dense_diffusion.pfm" --set quality.preset=high --set ms.mode=diffusion \
     --set ms.grid=96 >/dev/null 2>"$T/err"; then
  pt=$(t_pfm_mean "$T/dense_pt.pfm"); di=$(t_pfm_mean "$T/dense_diffusion.pfm")
  if awk -v p="$pt" -v d="$di" 'BEGIN { e = d / p - 1; exit !(p > 0 && d == d && e < 0.15 && e > -0.15) }'; then
    t_ok "dense layer from below, ms.grid = 96: diffusion $di within 15 % of the path tracer's $pt"
  else t_fail "dense layer from below, ms.grid = 96: diffusion within 15 % of the path tracer" \
              "diffusion '$di', path tracer '$pt'"; fi
else cat "$T/err" >&2; t_fail "dense layer from below" "path tracer or render failed"; fi
# A sphere of cloud (radius 300 m, the sweep's density and fuzzy boundary, no noise), the sun 30 degrees high from in
# front of it, beside it and behind it: a round cloud's surface crosses the grid's cells at every slant, and the
# staircase of cell faces standing for it is about 1.5 times its area. Light leaks out through each face, so
# unweighted the grid's fluence, which the eye sees, came out 13-18 % low (-14.5, -13.1, -17.7 %); with the faces
# weighted to the true surface (ms_diffusion.c leak_weights) it is -2.5, -0.4 and -6.0 % off the path tracer.
# The grid's light alone: ms.lobe (test_ms_lobe.sh) adds the forward lobe's own light, which on this HG 0.853
# sphere lit from behind (azimuth 135) overshoots: +8.4 % against +0.5 % without it (README, "Where the light goes").
for az in 135 90 0; do
  scene 400 62 "300 300 300" "24 24" "0 0 -1500" 26 "elevation = 30
azimuth = $az" > "$T/sphere$az.scene"
  $PT "$T/sphere$az.scene" -o "$T/sphere${az}_pt.pfm" --spp 2048 -q 2>"$T/err" ||
    { cat "$T/err" >&2; t_fail "sphere, sun at azimuth $az: path tracer" "failed"; continue; }
  $C render "$T/sphere$az.scene" -o "$T/sphere${az}_diffusion.pfm" --set quality.preset=high --set ms.mode=diffusion \
    --set ms.lobe=off \
    >/dev/null 2>"$T/err" || { cat "$T/err" >&2; t_fail "sphere, sun at azimuth $az: render" "failed"; continue; }
  pt=$(t_pfm_mean "$T/sphere${az}_pt.pfm" 576); di=$(t_pfm_mean "$T/sphere${az}_diffusion.pfm" 576)
  $C render "$T/sphere$az.scene" -o "$T/sphere${az}_lobe.pfm" --set quality.preset=high --set ms.mode=diffusion \
    >/dev/null 2>&1 && echo "sphere, sun at azimuth $az, with ms.lobe: $(t_pfm_mean "$T/sphere${az}_lobe.pfm" 576)"
  if awk -v p="$pt" -v d="$di" 'BEGIN { e = d / p - 1; exit !(p > 0 && d == d && e < 0.08 && e > -0.08) }'; then
    t_ok "sphere, sun at azimuth $az: diffusion $di within 8 % of the path tracer's $pt"
  else t_fail "sphere, sun at azimuth $az: diffusion within 8 % of the path tracer" "diffusion '$di', path tracer '$pt'"
  fi
done
# Five clouds in view, the sun from the date (2026-06-21 08:00 UTC, Zurich), a frame every 145 s of scene time: the
# sun turns about 0.6 degrees a frame, past a grid's 0.5 and short of the maps' 1-degree jump, so from the second
# frame on the maps follow it four clouds a frame (whole maps: quality.sun_map_frames = 1; made in bands, a grid is
# solved when its last band is in, and the count would follow the bands) and each of those grids is to be solved
# again. The first frame solves all five whole (12x10x12 cells, about 190 sweeps each). Later sampling and solves
# share ms.frame_work cell updates a frame (pass_msd.c): at the default 300 thousand, the second frame samples one
# cloud's density again (the noise boils on at 145 s a frame: 1440 cells at 120 updates each, 173 thousand), starts
# its solve (16 thousand) and runs 77 of its 134 sweeps, the rest in the third: 5 and 6 solves after 2 and 3 frames,
# one of them "in 2 frames". With no limit every grid whose maps follow the sun is sampled and solved at once: 9 and
# 14 (what the default would count without the limit); with the least work (a sweep a frame) none of the re-solves
# ends within 3 frames: 5.
{
  printf '[output]\nsize = 32 24\n[camera]\nposition = 0 300 0\nlook_at = 0 700 -3000\nfov = 70\n'
  printf '[sun]\ntime_utc = 2026-06-21T08:00:00Z\nlatitude = 47.37\nlongitude = 8.54\n[sky]\nmodel = constant\n'
  printf 'color = 6 7 9\n[ms]\nmode = diffusion\ngrid = 12\n[quality]\nsun_map_frames = 1\n'
  for x in -1500 -750 0 750 1500; do printf '[cloud]\n[ellipsoid]\ncenter = %s 900 -2600\nradii = 220 140 200\n' "$x"; done
} > "$T/five.scene"
for c in "300 2 5" "300 3 6" "1000000 2 9" "1000000 3 14" "1 3 5"; do
  set -- $c
  $C render "$T/five.scene" --frames $2 --fps 0.0069 -v --set ms.frame_work=$1 -o "$T/five%d.png" >/dev/null \
    2>"$T/five_log" || { cat "$T/five_log" >&2; t_fail "five clouds, $2 frames, work $1" "render failed"; continue; }
  got=$(grep -c "ms.mode = diffusion: .* sweeps in" "$T/five_log")
  [ "$got" = "$3" ] && t_ok "five clouds, the sun 0.6 degrees a frame, ms.frame_work = $1: $got grid solves in $2 frames" ||
    t_fail "five clouds, the sun 0.6 degrees a frame, ms.frame_work = $1, $2 frames" "$got grid solves, want $3"
  if [ "$1 $2" = "300 3" ]; then
    grep -q "sweeps in 2 frames" "$T/five_log" && t_ok "five clouds: a solve spread over 2 frames" ||
      t_fail "five clouds: a solve spread over 2 frames" "none in the log"
  fi
done
t_summary
