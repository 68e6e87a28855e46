#!/bin/sh
# scripts/bench_light.sh: what sunlight and multiple scattering cost (issue 5), measured in one run so the numbers
# compare as ratios: each shadow method and each MS mode at 640x480 on the 8-ellipsoid benchmark cloud, against the
# cheapest baseline (light.shadow=front, ms.mode=none: there is no shadow-free mode), and the sun pass (opacity map +
# slab maps) per map size and per layer count, from frames that redo it (--sun-every-frame) minus frames that do
# not. Writes build/bench/light.csv and build/bench/light.md (the README's table).
set -eu
C=${CUMULO:-build/cumulo}
FRAMES=${FRAMES:-15}
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=${LP_NUM_THREADS:-2}
mkdir -p build/bench
CSV=build/bench/light.csv
rm -f "$CSV"
S=scenes/bench_e8.scene
b() { "$C" bench "$S" --frames "$FRAMES" --warmup 3 --csv "$CSV" "$@" | grep '^\['; }
b --set light.shadow=front --set ms.mode=none
for sh in front peel osm fom; do b --set light.shadow=$sh --set ms.mode=none; done
for ms in octaves slab collector; do b --set light.shadow=peel --set ms.mode=$ms; done
for m in 64 128 256; do
  b --set quality.sun_map_size=$m
  b --set quality.sun_map_size=$m --sun-every-frame
done
for j in 1 2 3; do
  b --set light.sun_intervals=$j
  b --set light.sun_intervals=$j --sun-every-frame
done
uptime | sed 's/^/load while measuring:/'
awk -F, 'NR > 1 { n++; ms[n] = $4; opt[n] = $2; sun[n] = ($0 ~ /sun-every-frame|sun_every/) }
  END {
    base = ms[1]
    print "| settings (bench_e8.scene, 640x480) | median frame (ms) | ratio to front + no MS |"
    print "| --- | --- | --- |"
    for (i = 2; i <= n; i++) { o = opt[i]; sub(/^size=640x480:?/, "", o); printf "| %s | %.1f | %.2f |\n", o, ms[i], ms[i] / base }
  }' "$CSV" > build/bench/light.md
cat build/bench/light.md
