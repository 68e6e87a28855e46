# tests/gpu/test_octaves_thin.sh: the octave model's multiple scattering vanishes in the thin limit as it must. Light
# scattered twice in a cloud of optical size tau_c goes as tau_c times light scattered once (the chance of a second
# scattering before leaving), so in a thin slab the octaves' share of the image, R = (octaves - none) / none, must
# grow in proportion to the density: 10x the density, 10x R (1 - e^-10t over 1 - e^-t, 9.5-10 for tau_c < 0.01).
# Wrenninge's octaves without the weight (1 - e^-tau_c)^o add the same share to any cloud, however thin: R would stay
# put. Also: R is positive and finite at every density, and large in a thick slab. Run from the repository root.
. tests/lib.sh
C=${CUMULO:-build/cumulo}
T=build/test-output/octaves_thin
rm -rf "$T"; mkdir -p "$T"
cat > "$T/slab.scene" <<'SCENE'
[output]
size = 8 8
[camera]
position = 0 0 0
look_at = 0 1000 300
fov = 10
[sun]
elevation = 50
azimuth = 180
[sky]
model = constant
color = 0 0 0
[cloud]
density = 1
boundary = 1
phase = hg
g = 0.85
[ellipsoid]
center = 0 1000 0
radii = 40000 10 40000
[quality]
noise = off
SCENE
share() { # density -> R
  for m in none octaves; do
    $C render "$T/slab.scene" -o "$T/$m$1.pfm" --set cloud.density="$1" --set ms.mode=$m >/dev/null 2>"$T/err" ||
      { cat "$T/err" >&2; return 1; }
  done
  awk -v n="$(t_pfm_mean "$T/none$1.pfm")" -v o="$(t_pfm_mean "$T/octaves$1.pfm")" \
    'BEGIN { if (n > 0 && o == o) printf "%.6g", (o - n) / n; else print "bad" }'
}
r1=$(share 0.5); r2=$(share 5); r3=$(share 500)
if awk -v a="$r1" -v b="$r2" 'BEGIN { exit !(a > 0 && b > 0 && b / a >= 8.5 && b / a <= 10.5) }'; then
  t_ok "octaves' share grows with the density in a thin slab: R = $r1 at 0.5, $r2 at 5 (ratio in [8.5, 10.5])"
else t_fail "octaves' share in a thin slab" "R = '$r1' at 0.5, '$r2' at 5: not in proportion to the density"; fi
if awk -v a="$r1" -v c="$r3" 'BEGIN { exit !(a < 0.01 && c > 1 && c < 100) }'; then
  t_ok "octaves are small in a thin slab (R = $r1) and large in a thick one (R = $r3 at density 500)"
else t_fail "thin against thick" "R = '$r1' at 0.5, '$r3' at 500"; fi
t_summary
