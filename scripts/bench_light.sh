#!/bin/sh
# scripts/bench_light.sh: what sunlight and multiple scattering cost (issue 5), measured in one run so the numbers
# compare as ratios: each shadow method and each MS mode at 640x480 on the 8-ellipsoid benchmark cloud, against the
# cheapest baseline (light.shadow=front, ms.mode=none: there is no shadow-free mode), and the sun pass (opacity map +
# slab maps) per map size and per layer count, from frames that redo it (--sun-every-frame) minus frames that do
# not, and the energy closure with it on and off, the sun turning 0.01 deg a frame (closure measured once a degree)
# and 2 deg a frame (measured every frame). ROUNDS rounds run every configuration in turn (interleaved, so load drifts hit all alike); the table takes
# each configuration's median over the rounds. Writes build/bench/light.csv and build/bench/light.md.
set -eu
C=${CUMULO:-build/cumulo}
FRAMES=${FRAMES:-8}
ROUNDS=${ROUNDS:-3}
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=${LP_NUM_THREADS:-2}
mkdir -p build/bench
CSV=build/bench/light.csv
rm -f "$CSV"
S=scenes/bench_e8.scene
configs='light.shadow=front,ms.mode=none
light.shadow=peel,ms.mode=none
light.shadow=osm,ms.mode=none
light.shadow=fom,ms.mode=none
light.shadow=peel,ms.mode=octaves
light.shadow=peel,ms.mode=slab
light.shadow=peel,ms.mode=collector
light.shadow=peel,quality.sun_map_size=64
light.shadow=peel,quality.sun_map_size=64,+sun
light.shadow=peel,quality.sun_map_size=128
light.shadow=peel,quality.sun_map_size=128,+sun
light.shadow=peel,quality.sun_map_size=256
light.shadow=peel,quality.sun_map_size=256,+sun
light.shadow=peel,light.sun_intervals=1
light.shadow=peel,light.sun_intervals=1,+sun
light.shadow=peel,light.sun_intervals=3
light.shadow=peel,light.sun_intervals=3,+sun
light.shadow=peel,ms.closure=off,+sun
light.shadow=peel,ms.closure=on,+sun
light.shadow=peel,ms.closure=off,+fast
light.shadow=peel,ms.closure=on,+fast'
r=0
while [ $r -lt "$ROUNDS" ]; do
  r=$((r + 1))
  echo "$configs" | while IFS= read -r cfg; do
    set --
    for kv in $(echo "$cfg" | tr ',' ' '); do
      case $kv in
        +sun) set -- "$@" --sun-every-frame ;;  # the sun turns 0.01 deg a frame
        +fast) set -- "$@" --sun-step 2 ;;      # 2 deg a frame: the closure is measured again every frame
        *) set -- "$@" --set "$kv" ;;
      esac
    done
    "$C" bench "$S" --frames "$FRAMES" --warmup 2 --csv "$CSV" "$@" | grep '^\[' | sed "s/^/round $r: /"
  done
done
uptime | sed 's/^/load while measuring:/'
# median over rounds per options string; ratio to the first configuration
awk -F, 'NR > 1 { o = $2; if (!(o in n)) order[++k] = o; v[o, ++n[o]] = $4 }
  END {
    for (i = 1; i <= k; i++) {
      o = order[i]; m = n[o]
      for (a = 1; a <= m; a++) for (b = a + 1; b <= m; b++) if (v[o, b] < v[o, a]) { t = v[o, a]; v[o, a] = v[o, b]; v[o, b] = t }
      med[o] = (m % 2) ? v[o, (m + 1) / 2] : (v[o, m / 2] + v[o, m / 2 + 1]) / 2
    }
    base = med[order[1]]
    print "| settings (bench_e8.scene, 640x480) | median frame (ms) | ratio to front + no MS |"
    print "| --- | --- | --- |"
    for (i = 1; i <= k; i++) { o = order[i]; s = o; sub(/^size=640x480:?/, "", s); printf "| %s | %.1f | %.2f |\n", s, med[o], med[o] / base }
  }' "$CSV" > build/bench/light.md
cat build/bench/light.md
