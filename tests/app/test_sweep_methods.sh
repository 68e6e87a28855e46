# tests/app/test_sweep_methods.sh: `cumulo-sweep --methods` end to end on one tiny view: every configuration of both
# families measured and written (CSV, table, plot data), every metric finite, the summary's best errors and its
# largest Kol / uniform ratio at equal error worked out again from the plot data, and usage errors. Run from the
# repository root.
. tests/lib.sh
S=${SWEEP:-build/cumulo-sweep}
T=build/test-output/sweep_methods
rm -rf "$T"; mkdir -p "$T"

t_expect "--methods takes no value" 2 "takes no value" -- $S --methods=1
t_expect "--frames 0 is refused" 2 "--frames" -- $S --methods --frames 0

# 40x30, 4 spp, one frame: seconds; what is checked is the bookkeeping, not the numbers' quality.
$S --methods --scenes sweep_cumulus_hg --size 40x30 --time-size 40x30 --spp 4 --frames 1 --warmup 0 --out "$T" \
   --ref-dir "$T/ref" >"$T/out.txt" 2>"$T/err.txt"
rc=$?
if [ $rc -eq 0 ] && [ -s "$T/methods.csv" ] && [ -s "$T/methods.md" ] && [ -s "$T/methods.dat" ]; then
  t_ok "a run writes methods.csv, methods.md, methods.dat"
else t_fail "a run writes its files" "exit $rc: $(tail -2 "$T/err.txt")"; fi

# --scenes of one's own: `high` is the first view's settings (the default views are Henyey-Greenstein; a Mie view
# rendered with them would be compared with a reference it is not)
$S --methods --scenes cumulus,sweep_cumulus_hg --refs-only --size 8x6 --spp 1 --out "$T/own" --ref-dir "$T/ref" \
   >"$T/own.txt" 2>&1
grep -q "high = scenes/cumulus.scene$" "$T/own.txt" && t_ok "--scenes: high is the first view's settings" ||
  t_fail "--scenes: high is the first view's settings" "$(grep 'high = ' "$T/own.txt")"

# One row a configuration: 47 of Kol's method, 19 of the uniform march (methods.c's tables).
kol=$(grep -c '^sweep_cumulus_hg,kol,' "$T/methods.csv"); uni=$(grep -c '^sweep_cumulus_hg,uniform,' "$T/methods.csv")
[ "$kol" -eq 47 ] && [ "$uni" -eq 19 ] && t_ok "66 configurations in the CSV: 47 Kol, 19 uniform" ||
  t_fail "66 configurations" "$kol Kol, $uni uniform"

# methods.dat: view, family (0 Kol, 1 uniform, 2 and 3 their controls), time / high, cloud error, contrast / the
# path tracer's, SSIM, then the quoted label and view. Every number finite and in range; high's time ratio 1.
D=$T/methods.dat
bad=$(awk '!/^#/ { for (i = 1; i <= 6; i++) if ($i !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/) { print NR ": " $0; next }
                   if ($2 > 3 || $3 <= 0 || $4 < 0 || $6 < -1 || $6 > 1) print NR ": " $0 }' "$D")
n=$(grep -vc '^#' "$D")
[ -z "$bad" ] && [ "$n" -eq 66 ] && t_ok "every metric finite and in range (66 rows)" ||
  t_fail "every metric finite and in range" "$n rows; $bad"
# Where the light goes: five numbers a row in the CSV (the light over the path tracer's in each fifth of the cloud's
# pixels by brightness), each finite and positive, and the same five in the view's table.
bad=$(awk -F, 'NR > 2 { n = NF; for (i = n - 4; i <= n; i++) if ($i !~ /^[0-9.]+(e[-+]?[0-9]+)?$/ || $i <= 0) {
                 print NR ": " $0; next } }' "$T/methods.csv")
csv5=$(awk -F, '$2 == "kol" && $3 == "\"high\"" { printf "%.2f %.2f %.2f %.2f %.2f", $(NF-4), $(NF-3), $(NF-2), $(NF-1), $NF }' \
       "$T/methods.csv")
md5=$(awk -F'|' '$2 ~ /kol/ && $3 ~ /^ high $/ { gsub(/^ +| +$/, "", $10); print $10 }' "$T/methods.md")
[ -z "$bad" ] && [ -n "$csv5" ] && [ "$csv5" = "$md5" ] && t_ok "light by brightness fifth in the CSV and the table ($md5)" ||
  t_fail "light by brightness fifth" "csv '$csv5', table '$md5'; $bad"

high=$(awk '$7 == "\"high\"" { print $3 }' "$D")
[ "$high" = "1.00000" ] && t_ok "high is the time reference (ratio 1)" || t_fail "high's ratio" "'$high'"

# The summary's best errors: each family's smallest cloud error, controls aside.
want=$(awk '!/^#/ && $2 < 2 { if (!($2 in m) || $4 < m[$2]) m[$2] = $4 } END { printf "%.3f %.3f", m[0], m[1] }' "$D")
got=$(awk -F'|' '$2 ~ /sweep_cumulus_hg/ && NF > 6 { gsub(/ /, ""); printf "%.3f %.3f", $5, $6; exit }' "$T/methods.md")
[ -n "$got" ] && [ "$got" = "$want" ] && t_ok "summary best errors = the data's ($got)" ||
  t_fail "summary best errors" "table '$got', data '$want'"

# The largest Kol / uniform time at equal error: at the error of every point off the controls, each family's fastest
# point at least as accurate, where both exist.
want=$(awk '!/^#/ && $2 < 2 { n++; f[n] = $2; e[n] = $4; t[n] = $3 }
       END { w = -1
             for (i = 1; i <= n; i++) {
               bk = -1; bu = -1
               for (j = 1; j <= n; j++) if (e[j] <= e[i]) {
                 if (f[j] == 0 && (bk < 0 || t[j] < bk)) bk = t[j]
                 if (f[j] == 1 && (bu < 0 || t[j] < bu)) bu = t[j] }
               if (bk > 0 && bu > 0 && bk / bu > w) w = bk / bu }
             if (w < 0) print "none"; else printf "%.4f", w }' "$D")
got=$(awk -F'|' '$2 ~ /sweep_cumulus_hg/ && NF > 6 { gsub(/ /, ""); print $4; exit }' "$T/methods.md")
if [ "$want" = none ]; then
  case "$got" in *nolevel*) t_ok "no error level both reach, as the data says" ;;
    *) t_fail "equal error" "table '$got', data: none" ;; esac
elif awk -v g="$got" -v w="$want" 'BEGIN { d = g - w; exit !(g != "" && d <= 0.006 && d >= -0.006) }'; then
  t_ok "largest Kol / uniform at equal error = the data's ($got)"
else t_fail "largest ratio" "table '$got', data '$want'"; fi
t_summary
