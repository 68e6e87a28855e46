#!/bin/sh
# scripts/test_sweep_smoke.sh: smoke test of cumulo-sweep (not in make check): a tiny quick sweep of one view writes
# its CSV, tables and presets with the reference path-traced in-process and cached; a second run finds the cache;
# `high` follows the baseline scene; --help and --version exit 0; bad arguments give one error line and exit 2, a
# failure while running exit 1. Run from the source tree:
#   LIBGL_ALWAYS_SOFTWARE=1 LP_NUM_THREADS=2 sh scripts/test_sweep_smoke.sh
set -u
bin=${CUMULO_SWEEP:-build/cumulo-sweep}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }
tiny="--quick --scenes cumulus --size 16x12 --time-size 32x24 --spp 2 --frames 1 --warmup 0 --budgets 1,1"

# shellcheck disable=SC2086
"$bin" $tiny --out "$tmp/out" --ref-dir "$tmp/ref" >"$tmp/log" 2>&1
rc=$?
check "tiny sweep exits 0" '[ $rc -eq 0 ] || { tail -5 "$tmp/log"; false; }'
check "sweep.csv has variant, greedy/ALL and preset rows" \
    'grep -q "^variant,cumulus,high" "$tmp/out/sweep.csv" && grep -q "^variant,ALL," "$tmp/out/sweep.csv" && [ $(grep -c "^preset,ALL," "$tmp/out/sweep.csv") -eq 3 ]'
check "no NaN in the CSV" '! grep -qi "nan" "$tmp/out/sweep.csv"'
check "presets.txt has low, medium, high" \
    'grep -q "^low: --set" "$tmp/out/presets.txt" && grep -q "^medium: --set" "$tmp/out/presets.txt" && grep -q "^high: --set" "$tmp/out/presets.txt"'
check "high is the default scene's settings" \
    'grep "^high:" "$tmp/out/presets.txt" | grep -q -- "--set quality.segments=5 --set quality.segment_ratio=1.6 "'
check "sweep.md has the knob table" \
    'grep -q "^| quality.segments | 2 |" "$tmp/out/sweep.md" && grep -q "(= the README defaults;" "$tmp/out/sweep.md"'
check "pareto.dat has the reference noise" 'grep -q " 9 \"reference noise\"$" "$tmp/out/pareto.dat"'
check "the reference is path-traced and cached" \
    'grep -q "^sweep: reference cumulus took" "$tmp/log" && [ $(ls "$tmp/ref"/cumulus-*.pfm | wc -l) -eq 2 ]'

# shellcheck disable=SC2086
"$bin" $tiny --out "$tmp/out2" --ref-dir "$tmp/ref" --refs-only >"$tmp/log2" 2>&1
rc=$?
check "--refs-only with the cache: exit 0, nothing rendered, no tables" \
    '[ $rc -eq 0 ] && ! grep -q "took" "$tmp/log2" && grep -q "^sweep: reference cumulus: PT noise" "$tmp/log2" && [ ! -e "$tmp/out2/sweep.csv" ]'

# a baseline with a value the knob table lacks: it becomes high, inserted in order
sed 's/^segments = 5/segments = 4/' scenes/cumulus.scene >"$tmp/base.scene"
# shellcheck disable=SC2086
"$bin" $tiny --baseline "$tmp/base.scene" --out "$tmp/out3" --ref-dir "$tmp/ref" >"$tmp/log3" 2>&1
rc=$?
check "--baseline: high follows the scene (segments = 4; 5 is a variant)" \
    '[ $rc -eq 0 ] && grep "^high:" "$tmp/out3/presets.txt" | grep -q -- "--set quality.segments=4 " && grep -q "^| quality.segments | 5 |" "$tmp/out3/sweep.md" && grep -q "^variant,cumulus,quality.segments,5," "$tmp/out3/sweep.csv" && grep -q "(= the settings of $tmp/base.scene;" "$tmp/out3/sweep.md"'

"$bin" --help >"$tmp/o" 2>"$tmp/e"
r=$?
check "--help: exit 0 on stdout" '[ $r -eq 0 ] && [ ! -s "$tmp/e" ] && grep -q "^usage: cumulo-sweep" "$tmp/o"'
missing=
for o in scenes out ref-dir baseline size time-size spp ref-threads frames warmup threshold budgets quick \
    sun-every-frame refs-only help version; do
    grep -q -- "--$o" "$tmp/o" || missing="$missing --$o"
done
check "--help describes every option" '[ -z "$missing" ] || { echo "  missing:$missing"; false; }'
"$bin" --version >"$tmp/o" 2>"$tmp/e"
r=$?
check "--version: exit 0, one line" '[ $r -eq 0 ] && [ ! -s "$tmp/e" ] && [ $(wc -l <"$tmp/o") -eq 1 ] && grep -q "^cumulo-sweep [0-9]" "$tmp/o"'

for args in "--bogus" "--size 0x1" "--size 4294967312x12" "--spp 4294967297" "--spp x" "--scenes nope" "--budgets 0.3,0.6" "--frames" "-x" "stray" \
    "--ref-threads 0" "--baseline nope.scene"; do
    # shellcheck disable=SC2086
    "$bin" $args >"$tmp/o" 2>"$tmp/e"
    r=$?
    check "sweep $args: exit 2 with one error line" '[ $r -eq 2 ] && [ $(wc -l <"$tmp/e") -eq 1 ] && [ ! -s "$tmp/o" ]'
done

printf '[camera]\nposition = 0 0\n' >"$tmp/bad.scene"
"$bin" --quick --scenes cumulus --baseline "$tmp/bad.scene" --out "$tmp/out4" --ref-dir "$tmp/ref" >"$tmp/o" 2>"$tmp/e"
r=$?
check "a baseline that does not parse: exit 1 with one error line" '[ $r -eq 1 ] && [ $(wc -l <"$tmp/e") -eq 1 ]'

[ $fail -eq 0 ] && echo "sweep smoke: all passed" || echo "sweep smoke: FAILED"
exit $fail
