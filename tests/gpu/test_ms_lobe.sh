# tests/gpu/test_ms_lobe.sh: ms.lobe (src/core/ms_lobe.c, shaders_gles/ms_diffusion.glsl), the light the phase
# function's forward lobe alone carries to the eye, against the path tracer on the wide slab of
# tools/bench/diffusion_accuracy.sh (3000 x 100 x 3000 m, HG 0.853, boundary 62 m, a black sky, an 8x8 view):
# - seen from 10 degrees above its top toward a sun 20 degrees high, where delta-M diffusion alone is 32 % dark
#   (the lobe's deflections it counts as none): the lobe brings the renderer at least 5 points nearer (measured
#   0.678 -> 0.763 of cumulo-pt);
# - seen from below with the sun 60 degrees high (the light through 18 optical depths): within 6 % with and without
#   it (measured +1.3 % off, +4.3 % on). Attenuated toward the eye by the scaled optical depth instead of the
#   chopped one, the lobe's light is counted once for every lobe scattering on its way out (+49 %);
# - isotropic scattering has no lobe (the image with it is the image without), and outside ms.mode = diffusion the
#   key changes nothing (the variant is not compiled). From the repository root.
. tests/lib.sh
C=${CUMULO:-build/cumulo}
PT=${CUMULO_PT:-build/cumulo-pt}
T=build/test-output/ms_lobe
rm -rf "$T"; mkdir -p "$T"
# slab G CAMERA ELEVATION
slab() {
  printf '[output]\nsize = 8 8\n[camera]\nposition = %s\nlook_at = 0 0 0\nfov = 10\n' "$2"
  printf '[sun]\nelevation = %s\nazimuth = 180\nirradiance = 100 100 100\n' "$3"
  printf '[sky]\nmodel = constant\ncolor = 0 0 0\n'
  printf '[cloud]\ndensity = 400\ndroplet_radius = 6\nboundary = 62\nphase = hg\ng = %s\n' "$1"
  printf '[ellipsoid]\ncenter = 0 0 0\nradii = 3000 100 3000\n[quality]\nnoise = off\n'
}
# render SCENE OUT LOBE [MODE]
render() {
  $C render "$1" -o "$2" --set quality.preset=high --set ms.mode="${4:-diffusion}" --set ms.lobe="$3" \
    >/dev/null 2>"$T/err" || { cat "$T/err" >&2; return 1; }
}

slab 0.853 "0 520 -2950" 20 > "$T/grazing.scene"
slab 0.853 "0 -1500 -600" 60 > "$T/below.scene"
for v in grazing below; do
  if $PT "$T/$v.scene" -o "$T/${v}_pt.pfm" --spp 2048 -q 2>"$T/err" && render "$T/$v.scene" "$T/${v}_on.pfm" on &&
     render "$T/$v.scene" "$T/${v}_off.pfm" off; then
    eval "${v}_pt=\$(t_pfm_mean \"$T/${v}_pt.pfm\") ${v}_on=\$(t_pfm_mean \"$T/${v}_on.pfm\")"
    eval "${v}_off=\$(t_pfm_mean \"$T/${v}_off.pfm\")"
  else cat "$T/err" >&2; t_fail "$v slab" "path tracer or render failed"; fi
done
if awk -v p="${grazing_pt:-0}" -v a="${grazing_on:-nan}" -v b="${grazing_off:-nan}" \
     'BEGIN { e1 = a / p - 1; e0 = b / p - 1; if (e1 < 0) e1 = -e1; if (e0 < 0) e0 = -e0
              exit !(p > 0 && a == a && b == b && e1 < e0 - 0.05) }'; then
  t_ok "grazing toward the sun: with the lobe $grazing_on, without $grazing_off, path tracer $grazing_pt"
else t_fail "grazing toward the sun: the lobe brings the renderer 5 points nearer the path tracer" \
            "on '$grazing_on', off '$grazing_off', path tracer '$grazing_pt'"; fi
for x in on off; do
  eval "d=\${below_$x:-nan}"
  if awk -v p="${below_pt:-0}" -v d="$d" 'BEGIN { e = d / p - 1; exit !(p > 0 && d == d && e < 0.06 && e > -0.06) }'
  then t_ok "from below, ms.lobe = $x: $d within 6 % of the path tracer's $below_pt"
  else t_fail "from below, ms.lobe = $x: within 6 % of the path tracer" "renderer '$d', path tracer '$below_pt'"; fi
done

# No lobe, no light: g = 0. And only diffusion compiles the lobe in.
slab 0 "0 520 -2950" 20 > "$T/iso.scene"
if render "$T/iso.scene" "$T/iso_on.pfm" on && render "$T/iso.scene" "$T/iso_off.pfm" off &&
   cmp -s "$T/iso_on.pfm" "$T/iso_off.pfm"; then t_ok "isotropic scattering: the same image with and without the lobe"
else t_fail "isotropic scattering: the same image with and without the lobe" "the images differ"; fi
if render "$T/grazing.scene" "$T/oct_on.pfm" on octaves && render "$T/grazing.scene" "$T/oct_off.pfm" off octaves &&
   cmp -s "$T/oct_on.pfm" "$T/oct_off.pfm"; then t_ok "ms.mode = octaves: ms.lobe changes nothing"
else t_fail "ms.mode = octaves: ms.lobe changes nothing" "the images differ"; fi
if ! cmp -s "$T/grazing_on.pfm" "$T/grazing_off.pfm"; then t_ok "ms.mode = diffusion: ms.lobe changes the image"
else t_fail "ms.mode = diffusion: ms.lobe changes the image" "the same image"; fi
t_summary
