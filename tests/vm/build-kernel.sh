#!/bin/sh
# tests/vm/build-kernel.sh: builds the test VM's kernel (tinyconfig + tests/vm/kernel.config) from Debian's
# linux-source-6.1 into build/vm/bzImage. Cached: rebuilt only when the fragment or the kernel source package
# changes (the key of the last build is kept in build/vm/bzImage.key). Each kernel built is also kept outside the
# tree, in $VM_KERNEL_CACHE (default ~/.cache/cumulo-vm), so a fresh clone on the same machine (CI) reuses it.
# Usage: sh tests/vm/build-kernel.sh [-j N]     (from the top of the tree; -j defaults to 2)
set -eu
JOBS=2
[ "${1:-}" = "-j" ] && JOBS=$2
VM=build/vm
FRAG=tests/vm/kernel.config
TAR=$(ls /usr/src/linux-source-6.1.tar.xz 2>/dev/null || true)
if [ -z "$TAR" ]; then
  echo "vm: no kernel source: /usr/src/linux-source-6.1.tar.xz is missing (apt-get install linux-source-6.1," \
       "or make deps)" >&2
  exit 1
fi
for tool in flex bison bc gcc make; do
  command -v $tool >/dev/null 2>&1 || { echo "vm: '$tool' is needed to build the kernel (make deps)" >&2; exit 1; }
done
pkgver=$(dpkg-query -W -f='${Version}' linux-source-6.1 2>/dev/null || stat -c '%s %Y' "$TAR")
key=$(sha256sum <"$FRAG" | cut -c1-16)-$pkgver
CACHE=${VM_KERNEL_CACHE:-${HOME:-/root}/.cache/cumulo-vm}
mkdir -p $VM
if [ -f $VM/bzImage ] && [ "$(cat $VM/bzImage.key 2>/dev/null)" = "$key" ]; then
  echo "vm: kernel up to date ($VM/bzImage, key $key)"
  exit 0
fi
if [ -f "$CACHE/bzImage-$key" ]; then
  cp "$CACHE/bzImage-$key" $VM/bzImage && echo "$key" >$VM/bzImage.key
  echo "vm: kernel for key $key taken from $CACHE"
  exit 0
fi
start=$(date +%s)
SRC=$VM/linux-source-6.1
if [ "$(cat $VM/src.key 2>/dev/null)" != "$pkgver" ]; then
  echo "vm: unpacking $TAR ($pkgver)"
  rm -rf $SRC $VM/obj
  tar -xJf "$TAR" -C $VM
  echo "$pkgver" >$VM/src.key
fi
OBJ=$(pwd)/$VM/obj
mkdir -p "$OBJ"
echo "vm: configuring (tinyconfig + $FRAG)"
make -s -C $SRC O="$OBJ" ARCH=x86_64 tinyconfig >/dev/null
(cd $SRC && ARCH=x86_64 scripts/kconfig/merge_config.sh -m -O "$OBJ" "$OBJ/.config" "$(cd - >/dev/null; pwd)/$FRAG") \
  >$VM/merge.log
make -s -C $SRC O="$OBJ" ARCH=x86_64 olddefconfig >/dev/null
# Every option the fragment asks for must have survived olddefconfig (a missing dependency drops it silently).
bad=0
grep '^CONFIG_' "$FRAG" | while IFS= read -r line; do
  grep -qx "$line" "$OBJ/.config" || { echo "vm: $FRAG asks for $line but the kernel config has:" \
    "$(grep "^${line%%=*}=\|^# ${line%%=*} " "$OBJ/.config" || echo 'nothing')" >&2; echo x; }
done >$VM/config-check.txt
if [ -s $VM/config-check.txt ]; then
  echo "vm: the configuration does not hold every option of $FRAG (see above); fix its dependencies" >&2
  exit 1
fi
echo "vm: building bzImage with -j$JOBS (a few minutes)"
if ! make -s -C $SRC O="$OBJ" ARCH=x86_64 -j"$JOBS" bzImage >$VM/build.log 2>&1; then
  tail -30 $VM/build.log >&2
  echo "vm: kernel build failed (full log: $VM/build.log)" >&2
  exit 1
fi
cp "$OBJ/arch/x86/boot/bzImage" $VM/bzImage
echo "$key" >$VM/bzImage.key
mkdir -p "$CACHE" 2>/dev/null && cp $VM/bzImage "$CACHE/bzImage-$key" 2>/dev/null || true
echo "vm: built $VM/bzImage in $(( $(date +%s) - start )) s"
