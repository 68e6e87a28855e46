#!/bin/sh
# Writes scenes/bench_eN.scene: one cumulus of N ellipsoids (N = 8, 16, 32) with the same overall extent, placed by a
# fixed linear congruential generator so the files are reproducible; radii shrink as N^(-1/3) to keep the volume.
set -eu
for n in 8 16 32; do
  awk -v n="$n" 'BEGIN {
    seed = 12345
    printf "# scenes/bench_e%d.scene: benchmark cloud of %d ellipsoids (made by scripts/gen_bench_scenes.sh)\n", n, n
    printf "[output]\nsize = 640 480\n[camera]\nposition = 0 200 -750\nlook_at = 0 300 0\nfov = 50\n"
    printf "[sun]\nelevation = 30\nazimuth = 135\n[cloud]\ndensity = 400\ndroplet_radius = 6\nboundary = 62\n"
    printf "phase = mie\n"
    s = (8.0 / n) ^ (1.0 / 3.0)
    for (i = 0; i < n; i++) {
      x = rnd() * 420 - 210; y = 260 + rnd() * 120 - 60; z = rnd() * 240 - 120
      printf "[ellipsoid]\ncenter = %.1f %.1f %.1f\nradii = %.1f %.1f %.1f\n", x, y, z, \
             s * (110 + rnd() * 90), s * (70 + rnd() * 50), s * (90 + rnd() * 70)
    }
  }
  function rnd() { seed = (seed * 1103515245 + 12345) % 2147483648; return seed / 2147483648 }' > "scenes/bench_e$n.scene"
done
