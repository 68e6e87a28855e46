#!/bin/sh
# tests/vm/vmcheck.sh: `make vmcheck`. Builds the VM kernel (cached) and runs the guest tests (tests/vm/guest/*.sh)
# in one boot of the VM, then prints each guest test's cmocka-style lines, one row per script like
# tests/run_tests.sh, the times, and the totals "vmcheck: N passed, N failed, N skipped", also written to
# build/test-output/vm-summary.txt for .ci/run. Exit status 0 only if every guest test passed.
# Missing qemu or kernel source is a failure, said loudly: these tests are the only ones that touch real drivers.
# Arguments: the guest scripts to run (drm gpio evdev; default all).
set -u
OUT=build/test-output
rm -rf $OUT/vm $OUT/vm-summary.txt
mkdir -p $OUT/vm
fail() {
  echo "vmcheck: FAILED: $1" >&2
  echo "[  FAILED  ] vmcheck: $1" >$OUT/vm/setup.log
  echo "0 passed, 1 failed, 0 skipped" >$OUT/vm-summary.txt
  echo "vmcheck: 0 passed, 1 failed, 0 skipped"
  exit 1
}
command -v qemu-system-x86_64 >/dev/null 2>&1 ||
  fail "qemu-system-x86_64 is not installed: apt-get install qemu-system-x86 (make deps installs it)"
[ -f /usr/src/linux-source-6.1.tar.xz ] ||
  fail "no kernel source /usr/src/linux-source-6.1.tar.xz: apt-get install linux-source-6.1 (make deps installs it)"
# The guest sees the host's root read-only but mounts tmpfs over /tmp, /run and /dev/shm (guest-init.sh): a tree
# there is invisible to it, and every guest test would fail with "no tree".
case $(pwd)/ in
  /tmp/* | /run/* | /dev/shm/*) fail "the tree is at $(pwd), which the guest hides under a tmpfs: clone it elsewhere" ;;
esac
for f in build/cumulo build/vm/vm_kms build/vm/vm_uinput; do
  [ -x $f ] || fail "$f is not built (make all vm-helpers)"
done
t0=$(date +%s)
sh tests/vm/build-kernel.sh -j "${VM_JOBS:-2}" || fail "the VM kernel did not build (build/vm/build.log)"
t1=$(date +%s)
sh tests/vm/run-vm.sh tests/vm/guest/all.sh "$@" >$OUT/vm/console.log 2>&1
vmrc=$?
t2=$(date +%s)
# Guest output is kept beside the other test logs.
cp build/vm/scratch/*.log build/vm/scratch/times.txt $OUT/vm/ 2>/dev/null
cp -r build/vm/scratch/out $OUT/vm/files 2>/dev/null
boot=$(sed -n 's/.*guest: up after \([0-9.]*\) s.*/\1/p' $OUT/vm/console.log | head -1)
passed=0; failed=0; skipped=0
[ $# -gt 0 ] || set -- drm gpio evdev
for t in "$@"; do
  log=$OUT/vm/$t.log
  if [ -f $log ]; then
    p=$(grep -c '^\[       OK \]' $log); f=$(grep -c '^\[  FAILED  \]' $log); s=$(grep -c '^\[  SKIPPED \]' $log)
    grep -q '^\[  PASSED  \]' $log || f=$((f + 1))  # died before its summary
  else
    p=0; f=1; s=0
  fi
  secs=$(sed -n "s/^$t //p" $OUT/vm/times.txt 2>/dev/null)
  status=ok; [ "$f" -eq 0 ] || status=FAIL
  printf 'vm:%-25s %4d passed %3d failed %3d skipped %6ss  %s\n' "$t" "$p" "$f" "$s" "${secs:-?}" "$status"
  grep '^\[       OK \]\|^\[  FAILED  \]\|^\[  SKIPPED \]' $log 2>/dev/null | sed 's/^/    /'
  passed=$((passed + p)); failed=$((failed + f)); skipped=$((skipped + s))
done
if [ $vmrc -ne 0 ] && [ $failed -eq 0 ]; then
  echo "vmcheck: the VM run failed (status $vmrc) though no test reported a failure:"
  tail -5 $OUT/vm/console.log | sed 's/^/    /'
  failed=$((failed + 1))
fi
echo "vmcheck: kernel $((t1 - t0)) s, VM $((t2 - t1)) s (boot to guest script ${boot:-?} s); console: $OUT/vm/console.log"
echo "$passed passed, $failed failed, $skipped skipped" >$OUT/vm-summary.txt
echo "vmcheck: $passed passed, $failed failed, $skipped skipped"
[ $failed -eq 0 ]
