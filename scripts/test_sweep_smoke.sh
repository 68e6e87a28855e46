#!/bin/sh
# scripts/test_sweep_smoke.sh: smoke test of `cumulo sweep` (not in make check): a tiny quick sweep of one view
# writes its CSV, tables and presets, and bad arguments give one error line and exit 2. Run from the source tree:
#   LIBGL_ALWAYS_SOFTWARE=1 LP_NUM_THREADS=2 sh scripts/test_sweep_smoke.sh
set -u
bin=${CUMULO_SWEEP:-build/cumulo-sweep}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
check() { if eval "$2"; then echo "ok: $1"; else echo "FAIL: $1"; fail=1; fi; }

"$bin" --quick --scenes cumulus --size 16x12 --time-size 32x24 --spp 2 --frames 1 --warmup 0 --budgets 1,1 \
    --out "$tmp/out" --ref-dir "$tmp/ref" >"$tmp/log" 2>&1
rc=$?
check "tiny sweep exits 0" '[ $rc -eq 0 ] || { tail -5 "$tmp/log"; false; }'
check "sweep.csv has variant, greedy/ALL and preset rows" \
    'grep -q "^variant,cumulus,high" "$tmp/out/sweep.csv" && grep -q "^variant,ALL," "$tmp/out/sweep.csv" && [ $(grep -c "^preset,ALL," "$tmp/out/sweep.csv") -eq 3 ]'
check "no NaN in the CSV" '! grep -qi "nan" "$tmp/out/sweep.csv"'
check "presets.txt has low, medium, high" \
    'grep -q "^low: --set" "$tmp/out/presets.txt" && grep -q "^medium: --set" "$tmp/out/presets.txt" && grep -q "^high: --set" "$tmp/out/presets.txt"'
check "sweep.md has the knob table" 'grep -q "^| quality.segments | 2 |" "$tmp/out/sweep.md"'
check "the reference is cached" '[ $(ls "$tmp/ref"/cumulus-*.pfm | wc -l) -eq 2 ]'
for args in "--bogus" "--size 0x1" "--spp x" "--scenes nope" "--budgets 0.3,0.6" "--frames"; do
    # shellcheck disable=SC2086
    "$bin" $args >"$tmp/o" 2>"$tmp/e"
    r=$?
    check "sweep $args: exit 2 with one error line" '[ $r -eq 2 ] && [ $(wc -l <"$tmp/e") -eq 1 ] && [ ! -s "$tmp/o" ]'
done
[ $fail -eq 0 ] && echo "sweep smoke: all passed" || echo "sweep smoke: FAILED"
exit $fail
