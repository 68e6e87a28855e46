#!/bin/sh
# Markdown fit-error table for tools/slab/README.md from the gen_tables.sh reports (data/slab_fit_{report,holdout}_*.txt).
# MC noise column: cell-weighted median over the (group, t) slices of each slice's median relative MC SE (eq. 3.32 report).
set -eu
D=${1:-data}
echo "| group | cells | MC noise median | eq. 3.32 median / p90 | eq. 3.32 held-out φ_V = 90° median / p90 | log-separable median / p90 |"
echo "| --- | --- | --- | --- | --- | --- |"
for g in 1 2 3 4 5-6 7-9 10-15 16+; do
  b=$(awk -v g="$g" '$1 == "GROUP" && $2 == "bouthors" && $3 == g { print $6, $8, $10 }' "$D/slab_fit_report_bouthors.txt")
  h=$(awk -v g="$g" '$1 == "GROUP" && $2 == "bouthors" && $3 == g { print $16, $18 }' "$D/slab_fit_holdout_bouthors.txt")
  l=$(awk -v g="$g" '$1 == "GROUP" && $2 == "logsep" && $3 == g { print $8, $10 }' "$D/slab_fit_report_logsep.txt")
  nz=$(awk -v g="$g" '$1 == g && NF >= 8 { print $6, $3 }' "$D/slab_fit_report_bouthors.txt" | sort -g |
       awk '{ v[NR] = $1; w[NR] = $2; tot += $2 } END { c = 0; for (i = 1; i <= NR; i++) { c += w[i]; if (c >= tot / 2) { print v[i]; exit } } }')
  echo "$g $b $nz $h $l" | awk '{ bm = $3 + 0; lm = $8 + 0
    printf "| %s | %s | %.4f | %s%.3f%s / %.3f | %.3f / %.3f | %s%.3f%s / %.3f |\n", $1, $2, $5, (bm <= lm ? "**" : ""), $3,
      (bm <= lm ? "**" : ""), $4, $6, $7, (lm < bm ? "**" : ""), $8, (lm < bm ? "**" : ""), $9 }'
done
