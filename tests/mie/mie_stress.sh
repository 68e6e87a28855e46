#!/bin/sh
# Full-table convergence of the Mie table (issue 3: "the tables stop changing at the 4th digit"): builds the default
# table, the same with half the radius step and with half the wavelength step, and fails if any value (every angle
# and channel, sigma_ext, g, f) changes by 1e-4 relative or more. About 3 CPU minutes; `make mie-stress` (part of
# `make stress`). tools/mie/test_mie.c makes the same check on 34 angles within make check.
# Usage: sh tools/mie/mie_stress.sh [BASE.tbl]  (BASE: an already built default table, e.g. data/mie_cloud.tbl)
. tests/lib.sh
BIN=build/cumulo-mie
OUT=build/test-output
mkdir -p $OUT
if [ ! -x "$BIN" ]; then
  t_fail build "$BIN missing (make build/cumulo-mie)"
  t_summary
  exit 1
fi
base=${1:-$OUT/mie_stress_base.tbl}
if [ -z "$1" ]; then
  $BIN --table "$base" 2>$OUT/mie_stress_base.log || { t_fail base "$(cat $OUT/mie_stress_base.log)"; t_summary; exit 1; }
fi

# compare A B: prints the largest relative change by region and exits 1 if any is >= 1e-4.
compare() {
  awk '
    function rel(a, b) { a += 0; b += 0; return (a == b) ? 0 : (a > b ? a - b : b - a) / (b > 0 ? b : -b) }
    function upd(k, e) { if (e > m[k]) m[k] = e }
    FNR == 1 { file++ }
    /^#/ || /^(channels|chop_deg|angles|lambda_nm)/ { next }
    file == 1 { line1[++n1] = $0; next }
    { n2++; split(line1[n2], a, " ")
      if ($1 == "sigma_ext_um2" || $1 == "g" || $1 == "f") {
        for (i = 2; i <= 4; i++) upd($1, rel(a[i], $i)); next }
      th = $1 + 0
      for (i = 2; i <= 4; i++) {
        if (th == 0) peak[i] = $i + 0
        e = rel(a[i], $i); upd("all", e)
        if ($i + 0 > 1e-3 * peak[i]) upd("fwd", e)
        if (th >= 170) upd("glory", e)
        if (th == 180) upd("p180", e)
      } }
    END {
      printf "P > 1e-3 peak %.2e | all angles %.2e | 170-180 deg %.2e | 180 deg %.2e | sigma_ext %.2e | g %.2e | f %.2e\n",
             m["fwd"], m["all"], m["glory"], m["p180"], m["sigma_ext_um2"], m["g"], m["f"]
      worst = 0; for (k in m) if (m[k] > worst) worst = m[k]
      exit !(n1 == n2 && n1 > 1000 && worst < 1e-4) }' "$1" "$2"
}

for case in "dx --dx 0.025" "band --band 400,700,10"; do
  set -- $case
  name=$1; shift
  $BIN --table $OUT/mie_stress_$name.tbl "$@" 2>$OUT/mie_stress_$name.log
  if res=$(compare "$base" $OUT/mie_stress_$name.tbl); then
    t_ok "refine-$name"; echo "  $name refined ($*): $res"
  else
    t_fail "refine-$name" "$res"
  fi
done
t_summary
