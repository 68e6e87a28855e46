# tests/app/test_sweep_fit.sh: `cumulo-sweep --fit-octaves` end to end on one tiny training view: the report, the
# table of every configuration rendered and the chosen keys written; the chosen point is the most accurate
# configuration the descent rendered and no worse than the textbook start; fit.md's result agrees with fit.txt and
# fit.csv; usage errors. Run from the repository root.
. tests/lib.sh
S=${SWEEP:-build/cumulo-sweep}
T=build/test-output/sweep_fit
rm -rf "$T"; mkdir -p "$T"

t_expect "--fit-octaves takes no value" 2 "takes no value" -- $S --fit-octaves=1
t_expect "--fit-octaves with --methods is refused" 2 "different runs" -- $S --fit-octaves --methods

# 24x18, 4 spp: the bookkeeping, not the fit's quality (make fit-octaves runs the real one).
$S --fit-octaves --scenes scenes/fit/sphere_side.scene --size 24x18 --spp 4 --out "$T" --ref-dir "$T/ref" \
   >"$T/out.txt" 2>"$T/err.txt"
rc=$?
if [ $rc -eq 0 ] && [ -s "$T/fit.csv" ] && [ -s "$T/fit.md" ] && [ -s "$T/fit.txt" ]; then
  t_ok "a run writes fit.csv, fit.md, fit.txt"
else t_fail "a run writes its files" "exit $rc: $(tail -2 "$T/err.txt")"; fi

# fit.txt: the four keys, each once, each a number.
keys=$(grep -v '^#' "$T/fit.txt" | sed 's/=.*//' | tr '\n' ' ')
vals=$(grep -v '^#' "$T/fit.txt" | sed 's/^[^=]*=//' | tr '\n' ' ')
[ "$keys" = "ms.octaves ms.a ms.b ms.c " ] && echo "$vals" | grep -Eq '^([0-9.]+ ){4}$' &&
  t_ok "fit.txt holds ms.octaves, ms.a, ms.b, ms.c ($vals)" || t_fail "fit.txt's keys" "'$keys' = '$vals'"

# fit.csv: one row a configuration on the one view (view,octaves,a,b,c,error,...), no configuration twice, every
# error finite; as many rows as fit.md says were rendered.
C=$T/fit.csv
rows=$(grep -c '^sphere_side,' "$C"); uniq=$(grep '^sphere_side,' "$C" | cut -d, -f2-5 | sort -u | wc -l)
said=$(sed -n 's/.* \([0-9][0-9]*\) configurations rendered.*/\1/p' "$T/fit.md")
bad=$(awk -F, '/^sphere_side,/ && $6 !~ /^[0-9]+\.[0-9]+$/' "$C")
[ "$rows" -gt 100 ] && [ "$rows" -eq "$uniq" ] && [ "$rows" = "$said" ] && [ -z "$bad" ] &&
  t_ok "$rows configurations, each once, errors finite, as fit.md says" ||
  t_fail "fit.csv's rows" "$rows rows, $uniq distinct, fit.md '$said', bad '$bad'"

# The chosen point is the smallest error in the CSV (one view: its error is the mean), and no worse than the start.
n=$(sed -n 's/^ms.octaves=//p' "$T/fit.txt"); a=$(sed -n 's/^ms.a=//p' "$T/fit.txt")
b=$(sed -n 's/^ms.b=//p' "$T/fit.txt"); c=$(sed -n 's/^ms.c=//p' "$T/fit.txt")
chosen=$(awk -F, -v k="$n,$a,$b,$c" '$2","$3","$4","$5 == k { print $6 }' "$C")
least=$(awk -F, '/^sphere_side,/ && (m == "" || $6 < m) { m = $6 } END { print m }' "$C")
start=$(awk -F, '$2","$3","$4","$5 == "4,0.5,0.5,0.5" { print $6 }' "$C")
[ -n "$chosen" ] && [ "$chosen" = "$least" ] && awk -v x="$chosen" -v y="$start" 'BEGIN { exit !(y != "" && x <= y) }' &&
  t_ok "the chosen point has the least error rendered ($chosen; the textbook start $start)" ||
  t_fail "the chosen point" "chosen '$chosen', least '$least', start '$start'"

# fit.md's result line names the same keys.
grep -q "^\*\*Result: ms.octaves = $n, ms.a = $a, ms.b = $b, ms.c = $c\*\*" "$T/fit.md" &&
  t_ok "fit.md's result = fit.txt" || t_fail "fit.md's result" "$(grep '^\*\*Result' "$T/fit.md")"
t_summary
