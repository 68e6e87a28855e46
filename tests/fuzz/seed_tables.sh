#!/bin/sh
# tests/fuzz/seed_tables.sh slab|collector FILE: prints a small but complete table cut from FILE (a committed table),
# a seed the loader accepts that a fuzz run can mutate quickly: the slab fit at its first two thicknesses, the
# collector table at its first thickness and the first two nodes of theta_L, theta_V and phi (all 11 depths).
case "$1" in
  slab) awk '/^#/ {print; next} !($3 in t) && n < 2 {t[$3]; n++} $3 in t' "$2" ;;
  collector) awk '/^#/ {print; next}
    { if (!($1 in T) && nt < 1) { T[$1]; nt++ }
      if (!($2 in L) && nl < 2) { L[$2]; nl++ }
      if (!($4 in V) && nv < 2) { V[$4]; nv++ }
      if (!($5 in P) && np < 2) { P[$5]; np++ }
      if (($1 in T) && ($2 in L) && ($4 in V) && ($5 in P)) print }' "$2" ;;
  *) echo "usage: $0 slab|collector FILE" >&2; exit 2 ;;
esac
