#!/bin/sh
# tests/vm/add-summary.sh TOTALS VM_TOTALS: adds the VM tests' "N passed, N failed, N skipped" (VM_TOTALS, written
# by tests/vm/vmcheck.sh) into TOTALS (make check's build/test-output/summary.txt), so that the one totals line CI
# reads counts both; .ci/run adds make sanitize's and make fuzz's totals the same way. A missing VM_TOTALS (vmcheck
# died before it wrote one) counts as one failure. A missing TOTALS is left missing: .ci/run then reports make
# check's own failure.
[ -f "$1" ] || exit 0
if [ -f "$2" ]; then vm=$(cat "$2"); else vm="0 passed, 1 failed, 0 skipped"; fi
tot=$(cat "$1")
# num LINE WORD: the count before WORD in LINE, 0 when absent (make check prints no "skipped" when none are).
num() { _v=$(echo "$1" | tr ',' '\n' | sed -n "s/^ *\([0-9][0-9]*\) $2\$/\1/p" | head -1); echo "${_v:-0}"; }
p=$(( $(num "$tot" passed) + $(num "$vm" passed) ))
f=$(( $(num "$tot" failed) + $(num "$vm" failed) ))
s=$(( $(num "$tot" skipped) + $(num "$vm" skipped) ))
echo "$p passed, $f failed, $s skipped" >"$1"
