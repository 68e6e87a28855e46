#!/bin/sh
# tests/vm/run-vm.sh: boots build/vm/bzImage under qemu (TCG: no KVM needed) with the host's root file system shared
# read-only over 9p as the guest's root and build/vm/scratch shared writable at /tmp/scratch, runs a guest script
# from this tree (path relative to the top of the tree) with its arguments, and exits with the guest script's
# status. The serial console (kernel messages and the script's output) goes to stdout and to
# build/vm/console.log.  Usage: sh tests/vm/run-vm.sh tests/vm/guest/all.sh [ARGS...]
# Environment: VM_TIMEOUT (seconds, default 2400), VM_MEM (MiB, default 1024), VM_CPUS (default 1), VM_CPU (qemu
# -cpu model, default max).
set -u
repo=$(pwd)
VM=$repo/build/vm
if ! command -v qemu-system-x86_64 >/dev/null 2>&1; then
  echo "vm: qemu-system-x86_64 is not installed (apt-get install qemu-system-x86, or make deps)" >&2
  exit 3
fi
if [ ! -f "$VM/bzImage" ]; then
  echo "vm: no kernel at $VM/bzImage: run sh tests/vm/build-kernel.sh first" >&2
  exit 3
fi
[ $# -ge 1 ] || { echo "usage: $0 GUEST_SCRIPT [ARGS...]" >&2; exit 2; }
rm -rf "$VM/scratch"
mkdir -p "$VM/scratch"
# Kernel command line: the 9p root, a quiet console, panic -> reboot -> qemu exits (-no-reboot); what follows "--"
# is handed to init as its arguments.
append="console=ttyS0 loglevel=4 panic=1 root=hostroot rootfstype=9p rootflags=trans=virtio,version=9p2000.L,msize=262144 ro init=/bin/sh -- $repo/tests/vm/guest-init.sh $repo $*"
start=$(date +%s)
{
  timeout "${VM_TIMEOUT:-2400}" qemu-system-x86_64 -machine pc -accel tcg -cpu "${VM_CPU:-max}" -smp "${VM_CPUS:-1}" \
    -m "${VM_MEM:-1024}" -display none -monitor none -serial stdio -no-reboot -nodefaults \
    -kernel "$VM/bzImage" -append "$append" \
    -virtfs local,path=/,mount_tag=hostroot,readonly=on,multidevs=remap,security_model=none \
    -virtfs "local,path=$VM/scratch,mount_tag=scratch,security_model=none" \
    -device isa-debug-exit,iobase=0xf4,iosize=0x04 </dev/null 2>&1
  echo $? >"$VM/qemu.rc"
} | tee "$VM/console.log"
secs=$(( $(date +%s) - start ))
qemu_rc=$(cat "$VM/qemu.rc")
guest_rc=$(cat "$VM/scratch/rc" 2>/dev/null)
# The status file is the truth; qemu's own status must agree with it (isa-debug-exit: status*2+1), else the
# guest did not power off the way it should (a timeout is 124, a panic reboot 0).
if [ -z "$guest_rc" ]; then
  echo "vm: the guest did not finish within ${VM_TIMEOUT:-2400} s or crashed (qemu status $qemu_rc; console:" \
       "build/vm/console.log)" >&2
  exit 4
fi
if [ "$qemu_rc" -ne $(( (guest_rc > 127 ? 127 : guest_rc) * 2 + 1 )) ]; then
  echo "vm: guest status $guest_rc but qemu exited with $qemu_rc: the guest did not power off cleanly" >&2
  exit 4
fi
echo "vm: guest finished in $secs s with status $guest_rc"
exit "$guest_rc"
