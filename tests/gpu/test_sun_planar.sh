# tests/gpu/test_sun_planar.sh: the opacity map read below each texel's own entry (light.sun_planar, sunmap.glsl).
# A wide flat layer (6 km across, 200 m thick, the sweep's density and fuzzy 62 m boundary, no noise, HG 0.853, a
# black sky) under a sun 20 degrees high, seen from 10 degrees above its top, 8x8 pixels of the middle of its top:
# single scattering alone (ms.mode = none) against cumulo-pt's first order (--max-depth 1, 4096 spp). At the default
# 128 texels a texel is 47 m wide and its ray enters the top up to 64 m along the sun before or after a sample's own,
# in a lit skin where the sun's optical depth grows by 1 in about 37 m: read at the sample's depth along the texel's
# ray, single scattering came out 24 % (bilinear, `high`) and 49 % (nearest, `medium`) of the path tracer's looking
# toward the sun, 21 % and 69 % with the sun behind the eye (the nearest texel's error partly cancels there). Read
# below each texel's entry it must be within 10 % (measured -3 % and -4 %), and off it must still miss by more than a
# quarter (so this scene tests the read). Then auto: off for the default cumulus alone (its texels are 5.5 m against
# an eighth of its 62 m skin) and for a field of cumuli (16-texel maps, texels too coarse for a plane across 200 m
# lobes), on for the layer, each the same image as the explicit setting. And on a thick cloud
# from below (sweep_below_hg) at 64 texels, the read brings single scattering closer to the same renderer's with 1024
# texels (where the texels no longer matter). From the repository root.
. tests/lib.sh
C=${CUMULO:-build/cumulo}
PT=${CUMULO_PT:-build/cumulo-pt}
T=build/test-output/sun_planar
rm -rf "$T"; mkdir -p "$T"
# layer AZIMUTH: the sun at AZIMUTH (180: the eye looks toward it, scattering angle 30 degrees; 0: behind the eye)
layer() {
  printf '[output]\nsize = 8 8\n[camera]\nposition = 0 520 -2950\nlook_at = 0 0 0\nfov = 10\n'
  printf '[sun]\nelevation = 20\nazimuth = %s\nirradiance = 100 100 100\n[sky]\nmodel = constant\ncolor = 0 0 0\n' "$1"
  printf '[cloud]\ndensity = 400\ndroplet_radius = 6\nboundary = 62\nphase = hg\ng = 0.853\n'
  printf '[ellipsoid]\ncenter = 0 0 0\nradii = 3000 100 3000\n[quality]\nnoise = off\n'
}
# within A B LO HI: A / B - 1 lies in [LO, HI]
within() {
  awk -v a="$1" -v b="$2" -v lo="$3" -v hi="$4" 'BEGIN { r = a / b - 1; exit !(b > 0 && a == a && r >= lo && r <= hi) }'
}
for az in 180 0; do
  layer "$az" > "$T/layer$az.scene"
  if ! $PT "$T/layer$az.scene" -o "$T/pt$az.pfm" --spp 4096 --max-depth 1 -q >/dev/null 2>"$T/err"; then
    cat "$T/err" >&2; t_fail "layer, sun at azimuth $az: path tracer" "failed"; continue
  fi
  pt=$(t_pfm_mean "$T/pt$az.pfm")
  for preset in high medium; do
    for planar in on off; do
      $C render "$T/layer$az.scene" -o "$T/${preset}_$planar$az.pfm" --set quality.preset=$preset --set ms.mode=none \
        --set light.sun_planar=$planar >/dev/null 2>"$T/err" || { cat "$T/err" >&2; t_fail "render" "failed"; }
    done
    on=$(t_pfm_mean "$T/${preset}_on$az.pfm"); off=$(t_pfm_mean "$T/${preset}_off$az.pfm")
    if within "$on" "$pt" -0.10 0.10; then
      t_ok "layer, sun at azimuth $az, $preset: single scattering read planar $on within 10 % of the path tracer's $pt"
    else t_fail "layer, sun at azimuth $az, $preset: single scattering read planar within 10 % of the path tracer's" \
                "renderer '$on', path tracer '$pt'"; fi
    if within "$off" "$pt" -10 -0.25; then
      t_ok "layer, sun at azimuth $az, $preset: read at the sample's depth ($off) it misses by more than a quarter"
    else t_fail "layer, sun at azimuth $az, $preset: read at the sample's depth it misses by more than a quarter" \
                "renderer '$off', path tracer '$pt'"; fi
  done
done
# auto: what it picks (the debug log) and that the picture is the explicit setting's
for c in "scenes/cumulus.scene off" "scenes/field_noon.scene off" "$T/layer180.scene on"; do
  set -- $c
  if $C render "$1" -o "$T/auto.pfm" --size 16x12 -v >/dev/null 2>"$T/log" &&
     $C render "$1" -o "$T/explicit.pfm" --size 16x12 --set light.sun_planar=$2 >/dev/null 2>&1 &&
     grep -q "light.sun_planar = auto: $2 " "$T/log" && cmp -s "$T/auto.pfm" "$T/explicit.pfm"; then
    t_ok "light.sun_planar = auto on $1: $2"
  else t_fail "light.sun_planar = auto on $1: $2" "$(grep sun_planar "$T/log")"; fi
done
# A thick cloud from below at 64 texels: the planar read nearer the 1024-texel map's single scattering (mean of the
# whole 64x48 image; measured off -25 %, on -6 %)
S=scenes/sweep_below_hg.scene
sets="--size 64x48 --set quality.preset=high --set ms.mode=none"
if $C render $S -o "$T/below_ref.pfm" $sets --set "sky.color=0 0 0" --set quality.sun_map_size=1024 >/dev/null 2>&1 &&
   $C render $S -o "$T/below_on.pfm" $sets --set "sky.color=0 0 0" --set quality.sun_map_size=64 \
     --set light.sun_planar=on >/dev/null 2>&1 &&
   $C render $S -o "$T/below_off.pfm" $sets --set "sky.color=0 0 0" --set quality.sun_map_size=64 \
     --set light.sun_planar=off >/dev/null 2>&1; then
  ref=$(t_pfm_mean "$T/below_ref.pfm" 3072); on=$(t_pfm_mean "$T/below_on.pfm" 3072)
  off=$(t_pfm_mean "$T/below_off.pfm" 3072)
  if awk -v r="$ref" -v a="$on" -v b="$off" 'BEGIN { x = a / r - 1; y = b / r - 1; x = x < 0 ? -x : x
       y = y < 0 ? -y : y; exit !(r > 0 && x < 0.12 && x < y) }'; then
    t_ok "thick cloud from below, 64 texels: planar $on nearer the 1024-texel map's $ref than $off"
  else t_fail "thick cloud from below, 64 texels: planar nearer the 1024-texel map's single scattering" \
              "planar '$on', not '$off', 1024 texels '$ref'"; fi
else t_fail "thick cloud from below" "render failed"; fi
t_summary
