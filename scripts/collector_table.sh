#!/bin/sh
# scripts/collector_table.sh: the collector table of ms.mode = collector (Bouthors' iterative collector search, Kol
# eqs. 3.59-3.63) from the raw slab simulations in data/slab_C_tables.tar.gz (tools/slab, --report table).
# Per (thickness, theta_L, depth, theta_V, phi_V): the mean entry point (c_x, c_z) on the lit face relative to the
# viewpoint and its spread sigma (eqs. 3.29-3.31), averaged over the multiple-scattering orders 2..16+ with their
# radiances C as weights (a mixture: sigma^2 = sum C (sigma_g^2 + |c_g - c|^2 / 2) / sum C). Bouthors fitted eqs.
# 3.38-3.54 to these; we tabulate them directly (15400 cells) and interpolate, which is exact at the simulated cells.
# Usage: sh scripts/collector_table.sh [tarball] > data/slab_collector.txt
set -eu
tarball=${1:-data/slab_C_tables.tar.gz}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tar -C "$tmp" -xzf "$tarball"
echo "# cumulo collector table from $(basename "$tarball") (sha256 $(sha256sum "$tarball" | cut -c1-16)) by scripts/collector_table.sh"
echo "# t_m thetaL d_m thetaV phiV C_ms cx_m cz_m sigma_m   (orders 2..16+, C-weighted; lengths in metres at k_e = 0.0905 m^-1)"
cat "$tmp"/C_t*_L*.txt | awk '
  /^#/ || $1 < 2 { next }
  { k = $2 " " $6 " " $3 " " $4 " " $5
    w = $7; W[k] += w; X[k] += w * $9; Z[k] += w * $11; S[k] += w * $13 * $13
    n[k]++; g[k, n[k]] = w " " $9 " " $11 }
  END {
    for (k in W) {
      if (W[k] > 0) {
        cx = X[k] / W[k]; cz = Z[k] / W[k]; v = S[k]
        for (i = 1; i <= n[k]; i++) { split(g[k, i], a, " "); v += a[1] * ((a[2] - cx) ^ 2 + (a[3] - cz) ^ 2) / 2 }
        printf "%s %.6e %.4f %.4f %.4f\n", k, W[k], cx, cz, sqrt(v / W[k])
      } else printf "%s 0 0 0 0\n", k
    }
  }' | sort -k1,1g -k2,2g -k3,3g -k4,4g -k5,5g
