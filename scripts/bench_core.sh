#!/bin/sh
# Measures what the README reports for the core engine: frame time of the default scene at 640x480, how it grows
# with the number of ellipsoids (8, 16, 32 in one cloud) and with segments (2, 5, 10, 20), and what the sun pass,
# the shadow methods and the multiple-scattering modes cost. All variants run in one invocation, so compare them as
# ratios. Writes build/bench/core.csv and build/bench/core.md (the README's table) and prints glmark2-style lines.
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
b scenes/bench_e8.scene --set quality.noise=off
b scenes/bench_e8.scene --set ms.mode=none
b scenes/bench_e8.scene --set ms.mode=octaves
b scenes/bench_e8.scene --set light.shadow=front
# the sun pass redone every frame, as when a knob turns the sun
b scenes/bench_e8.scene --sun-every-frame
b scenes/bench_e8.scene --set light.shadow=front --sun-every-frame
for m in 64 256; do b scenes/bench_e8.scene --set quality.sun_map_size=$m --sun-every-frame; done
uptime | sed 's/^/load while measuring:/'
# README table: median frame time and ratio to the 8-ellipsoid benchmark cloud with default settings.
awk -F, 'NR > 1 { key = $1 " " $2; ms[NR] = $4; name[NR] = $1; opt[NR] = $2; if ($1 == "bench_e8.scene" && $2 == "size=640x480") base = $4 }
  END { print "| scene | settings | median frame (ms) | ratio to bench_e8 defaults |"; print "| --- | --- | --- | --- |";
        for (i = 2; i <= NR; i++) { o = opt[i]; sub(/^size=640x480:?/, "", o); if (o == "") o = "defaults";
          printf "| %s | %s | %.1f | %.2f |\n", name[i], o, ms[i], ms[i] / base } }' "$CSV" > build/bench/core.md
cat build/bench/core.md
