#!/bin/sh
# tests/vm/guest-init.sh: PID 1 of the test VM (the kernel runs it from the host's root, shared read-only over 9p).
# Arguments (after the kernel command line's "--"): the tree's absolute path, then the guest script and its
# arguments. Mounts what a read-only root lacks, runs the script from the tree with its output on the serial
# console, writes its exit status to the scratch share, and powers off through qemu's isa-debug-exit port so that
# qemu's own exit status carries the script's (status*2+1).
export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
export HOME=/tmp TMPDIR=/tmp LANG=C.UTF-8
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
mkdir -p /dev/shm /dev/pts
mount -t tmpfs -o mode=1777 shm /dev/shm
mount -t tmpfs -o mode=1777 tmp /tmp
mount -t tmpfs -o mode=755 run /run
mount -t configfs configfs /sys/kernel/config
mount -t tracefs tracefs /sys/kernel/tracing
mkdir -p /tmp/scratch /tmp/xdg
chmod 700 /tmp/xdg
export XDG_RUNTIME_DIR=/tmp/xdg
mount -t 9p -o trans=virtio,version=9p2000.L,msize=262144 scratch /tmp/scratch
repo=$1
shift
cd "$repo" || { echo "guest: no tree at $repo"; }
echo "guest: up after $(cut -d' ' -f1 /proc/uptime) s; kernel $(uname -r); running $*"
sh "$@"
rc=$?
echo "guest: $1 exited with status $rc"
echo $rc >/tmp/scratch/rc
[ $rc -le 127 ] || rc=127
# isa-debug-exit at port 0xf4: qemu exits at once with (byte << 1) | 1.
printf "\\$(printf %03o $rc)" | dd of=/dev/port bs=1 seek=244 count=1 conv=notrunc 2>/dev/null
echo "guest: isa-debug-exit did not stop qemu; panicking to reboot (qemu -no-reboot exits)"
exit $rc
