#!/bin/sh
# Measures what the README reports for the core engine: frame time of the default scene at 640x480, how it grows
# with the number of ellipsoids (8, 16, 32 in one cloud) and with segments (2, 5, 10, 20). All variants run in one
# invocation, so compare them as ratios. Writes build/bench/core.csv and prints the glmark2-style lines.
set -eu
C=${CUMULO:-build/cumulo}
FRAMES=${FRAMES:-20}
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=${LP_NUM_THREADS:-2}
mkdir -p build/bench
CSV=build/bench/core.csv
rm -f "$CSV"
b() { "$C" bench "$@" --frames "$FRAMES" --warmup 3 --csv "$CSV" | grep '^\['; }
"$C" bench scenes/cumulus.scene --frames 1 --warmup 0 | sed -n '2,9p'
b scenes/cumulus.scene
for n in 8 16 32; do b "scenes/bench_e$n.scene"; done
for s in 2 5 10 20; do b scenes/bench_e8.scene --set "quality.segments=$s"; done
b scenes/bench_e8.scene --set ms.mode=none
b scenes/bench_e8.scene --set quality.noise=off
b scenes/bench_e8.scene --sun-every-frame
# Sun transmittance and multiple scattering (issue 5): each method per frame, and the sun pass itself (redone every
# frame with --sun-every-frame, as when a knob turns the sun) for map sizes and interval caps.
b scenes/bench_e8.scene --set light.shadow=front
b scenes/bench_e8.scene --set ms.mode=octaves
b scenes/bench_e8.scene --set light.shadow=front --sun-every-frame
for m in 128 256 512; do b scenes/bench_e8.scene --set quality.sun_map_size=$m --sun-every-frame; done
for j in 1 2 3; do b scenes/bench_e8.scene --set light.sun_intervals=$j --sun-every-frame; done
b scenes/bench_e8.scene --set light.sun_samples=16 --sun-every-frame
