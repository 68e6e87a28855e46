#!/bin/sh
# Runs every test program given on the command line and prints the totals as "N passed, N failed, N skipped".
# Each program prints cmocka's summary lines ("[  PASSED  ] N test(s).", "[  FAILED  ] N test(s)", "[  SKIPPED ] N
# test(s)"); shell tests print the same lines through tests/lib.sh. A program that dies without a summary counts as
# one failure, so a crash can never pass.
passed=0; failed=0; skipped=0
logdir=build/test-output
mkdir -p "$logdir"
export CMOCKA_MESSAGE_OUTPUT=stdout
for t in "$@"; do
  name=$(basename "$t")
  log="$logdir/$name.log"
  start=$(date +%s)
  case "$t" in
    *.sh) sh "$t" >"$log" 2>&1 ;;
    *)    "$t" >"$log" 2>&1 ;;
  esac
  rc=$?
  secs=$(( $(date +%s) - start ))
  p=$(sed -n 's/^\[  PASSED  \] \([0-9][0-9]*\) test.*/\1/p' "$log" | awk '{s+=$1} END {print s+0}')
  f=$(sed -n 's/^\[  FAILED  \] \([0-9][0-9]*\) test.*/\1/p' "$log" | awk '{s+=$1} END {print s+0}')
  s=$(sed -n 's/^\[  SKIPPED \] \([0-9][0-9]*\) test.*/\1/p' "$log" | awk '{s+=$1} END {print s+0}')
  if ! grep -q '^\[  PASSED  \]\|^\[  FAILED  \]\|^\[  SKIPPED \]' "$log"; then f=1; fi
  if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
  passed=$((passed + p)); failed=$((failed + f)); skipped=$((skipped + s))
  status=ok; [ "$f" -eq 0 ] || status=FAIL
  printf '%-28s %4d passed %3d failed %3d skipped %4ds  %s\n' "$name" "$p" "$f" "$s" "$secs" "$status"
  if [ "$f" -ne 0 ]; then
    grep -E '^\[  (FAILED|ERROR) |^\[  FAILED  \]|error|Error|FAIL' "$log" | head -20 | sed 's/^/    /'
    echo "    (full log: $log)"
  fi
done
echo "$passed passed, $failed failed, $skipped skipped" | tee "$logdir/summary.txt"
[ "$failed" -eq 0 ]
