#!/bin/sh
# scripts/docs_images.sh: the README's pictures, rendered by the current renderer (EGL, llvmpipe): the four scenes,
# and the side-by-side comparisons of multiple-scattering modes and shadow methods on a closer view of the cumulus.
set -eu
C=${CUMULO:-build/cumulo}
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe
for s in cumulus glory low_sun silver_lining; do "$C" render scenes/$s.scene -o docs/$s.png; done
"$C" render scenes/silver_lining.scene --set light.shadow=front -o docs/silver_lining_front.png
# closer view, exposure lowered so that the brightest mode does not clip
close() { out=$1; shift; "$C" render scenes/cumulus.scene --size 400x300 --set "camera.position=0 250 -700" \
          --set output.exposure=0.035 "$@" -o "$out"; }
for m in none octaves slab collector; do close docs/ms_$m.png --set ms.mode=$m; done
for s in front peel osm fom; do close docs/shadow_$s.png --set light.shadow=$s --set ms.mode=none; done
