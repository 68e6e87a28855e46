# tests/build/test_build.sh: the build as a new user meets it, in a copy of the tree: a first build with a pkg-config
# that fails, then with the real one (every back end this machine has is built), a back end asked for but missing, a
# configuration or PREFIX change rebuilding what reads it, make install (DESTDIR and a real PREFIX), a C program
# outside the tree built against the installed copy through pkg-config, uninstall, and `make OPT=-O0`.
. tests/lib.sh
SRC=$PWD
T=$SRC/build/test-output/build
rm -rf "$T"; mkdir -p "$T"
W=$T/tree
mkdir -p "$W"
# The tree as committed plus what is not ignored (so an uncommitted file is tested too), not the build outputs.
if git -C "$SRC" rev-parse >/dev/null 2>&1; then
  git -C "$SRC" ls-files -co --exclude-standard -z | (cd "$SRC" && xargs -0 tar -cf - --no-recursion) | tar -C "$W" -xf -
else
  tar -C "$SRC" --exclude=./build -cf - . | tar -C "$W" -xf -
fi
MK="make -C $W -j2 --no-print-directory"
log=$T/make.log

# 1. A pkg-config that fails: configure stops the build with a message that says what is missing and how to fix it.
mkdir -p "$T/stub"
printf '#!/bin/sh\nexit 1\n' >"$T/stub/pkg-config"; chmod +x "$T/stub/pkg-config"
if PATH=$T/stub:$PATH $MK build/cumulo >"$log" 2>&1; then
  t_fail "stub pkg-config fails the build" "make succeeded"
elif grep -q "configure: error: pkg-config (pkg-config) finds no: egl glesv2 libpng" "$log"; then
  t_ok "stub pkg-config fails the build at configure time"
else t_fail "stub pkg-config fails the build at configure time" "$(tail -3 "$log")"; fi

# 2. The real pkg-config: the same tree now builds every back end and input the installed packages allow.
if $MK build/cumulo >"$log" 2>&1; then t_ok "build after the stub"; else t_fail "build after the stub" "$(tail -5 "$log")"; fi
v=$("$W/build/cumulo" --version 2>&1)
want="egl"
pkg-config --exists osmesa && want="$want osmesa"
pkg-config --exists gbm libdrm && want="$want drm"
pkg-config --exists x11 && want="$want x11"
pkg-config --exists wayland-client wayland-egl wayland-protocols && command -v wayland-scanner >/dev/null && want="$want wayland"
inputs="stdin evdev"; pkg-config --exists libgpiod && inputs="$inputs gpio"
case "$v" in
  *"display back ends: headless $want"*"inputs: $inputs"*) t_ok "every available back end built ($want; $inputs)" ;;
  *) t_fail "every available back end built ($want; $inputs)" "$v" ;;
esac
run_help=$("$W/build/cumulo" run --help 2>&1); rc=$?
miss=""
for b in headless $want $inputs; do case "$run_help" in *"$b"*) ;; *) miss="$miss $b" ;; esac; done
if [ $rc -eq 0 ] && [ -z "$miss" ]; then t_ok "cumulo run --help lists them"
else t_fail "cumulo run --help lists them" "exit $rc, missing:$miss"; fi

# 3. A back end asked for that cannot be built fails loudly; asked off, it is left out and config.h says so.
real_pc=$(command -v pkg-config)
printf '#!/bin/sh\nfor a in "$@"; do [ "$a" = gbm ] && exit 1; done\nexec %s "$@"\n' "$real_pc" >"$T/stub/pkg-config"
if PATH=$T/stub:$PATH $MK build/cumulo WITH_DRM=yes >"$log" 2>&1; then
  t_fail "WITH_DRM=yes without gbm fails" "make succeeded"
elif grep -q "configure: error: --with-drm=yes but pkg-config finds no 'gbm libdrm'" "$log"; then
  t_ok "WITH_DRM=yes without gbm fails at configure time"
else t_fail "WITH_DRM=yes without gbm fails at configure time" "$(tail -3 "$log")"; fi
$MK build/cumulo WITH_X11=no >"$log" 2>&1
case "$("$W/build/cumulo" --version)" in
  *x11*) t_fail "WITH_X11=no rebuilds without x11" "$("$W/build/cumulo" --version | sed -n 2p)" ;;
  *) grep -q '^#define CU_HAVE_X11 0' "$W/build/gen/config.h" && t_ok "WITH_X11=no rebuilds without x11" ||
       t_fail "WITH_X11=no rebuilds without x11" "config.h: $(grep X11 "$W/build/gen/config.h")" ;;
esac
$MK build/cumulo >"$log" 2>&1
case "$("$W/build/cumulo" --version)" in *x11*) t_ok "x11 back again by default" ;; *) t_fail "x11 back again by default" "" ;; esac

# 4. Nothing changed, nothing rebuilt; a PREFIX change rebuilds what embeds the data path and nothing else.
$MK build/cumulo >"$log" 2>&1
if grep -q '^cc\|-c ' "$log"; then t_fail "no-op build compiles nothing" "$(grep -c -- '-c ' "$log") compiles"
else t_ok "no-op build compiles nothing"; fi
$MK build/cumulo PREFIX=/opt/cumulo-test >"$log" 2>&1
compiled=$(grep -o -- '-c [^ ]*\.c' "$log" | sed 's/-c //' | sort | tr '\n' ' ')
if [ "$compiled" = "src/core/datadir.c " ] && strings "$W/build/cumulo" | grep -q '^/opt/cumulo-test/share/cumulo/data$'; then
  t_ok "PREFIX change rebuilds only src/core/datadir.c and relinks"
else t_fail "PREFIX change rebuilds only src/core/datadir.c and relinks" "compiled: $compiled"; fi

# 5. make install into a DESTDIR with PREFIX=/usr: what a Debian package holds.
D=$T/destdir
if $MK install DESTDIR="$D" PREFIX=/usr >"$log" 2>&1; then t_ok "make install DESTDIR PREFIX=/usr"
else t_fail "make install DESTDIR PREFIX=/usr" "$(tail -5 "$log")"; fi
miss=""
for f in usr/bin/cumulo usr/bin/cumulo-pt usr/lib/libcumulo.so.0 usr/lib/libcumulo.so usr/lib/libcumulo.a \
         usr/lib/pkgconfig/cumulo.pc usr/include/cumulo.h usr/share/cumulo/data/mie_cloud.tbl \
         usr/share/cumulo/data/slab_fit_bouthors.txt usr/share/cumulo/data/slab_collector.txt \
         usr/share/cumulo/scenes/cumulus.scene usr/share/man/man1/cumulo.1 usr/share/man/man5/cumulo.scene.5 \
         usr/share/cumulo/flightgear/cumulo.xml lib/systemd/system/cumulo-kiosk.service; do
  [ -e "$D/$f" ] || miss="$miss $f"
done
[ -z "$miss" ] && t_ok "installed files present" || t_fail "installed files present" "missing:$miss"
for f in cumulo-slab cumulo-slab-fit cumulo-mie cumulo-sweep; do
  [ ! -e "$D/usr/bin/$f" ] || miss="$miss $f"
done
[ -z "$miss" ] && t_ok "developer tools not installed" || t_fail "developer tools not installed" "$miss"
soname=$(readelf -d "$D/usr/lib/libcumulo.so.0" 2>/dev/null | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
[ "$soname" = libcumulo.so.0 ] && t_ok "soname libcumulo.so.0" || t_fail "soname libcumulo.so.0" "got '$soname'"
# The shared library exports exactly the functions of the public header.
hdr=$(sed -n 's/^[a-z].*[ *]\(cu_[a-z_0-9]*\)(.*/\1/p' "$D/usr/include/cumulo.h" | sort -u | tr '\n' ' ')
exp=$(nm -D --defined-only "$D/usr/lib/libcumulo.so.0" | awk '$2 == "T" {print $3}' | sed 's/@.*//' | sort -u | tr '\n' ' ')
[ "$hdr" = "$exp" ] && t_ok "exports = include/cumulo.h" || t_fail "exports = include/cumulo.h" "header: $hdr; exported: $exp"
unit=$D/lib/systemd/system/cumulo-kiosk.service
if grep -q '^ExecStart=/usr/bin/cumulo run /usr/share/cumulo/scenes/cumulus.scene' "$unit" && ! grep -q '@[A-Z]*@' "$unit"; then
  t_ok "systemd unit has the installed paths"
else t_fail "systemd unit has the installed paths" "$(grep ExecStart "$unit")"; fi
man -l "$D/usr/share/man/man1/cumulo.1" >/dev/null 2>"$T/man.err" && [ ! -s "$T/man.err" ] &&
  t_ok "cumulo(1) renders" || t_fail "cumulo(1) renders" "$(head -2 "$T/man.err")"
man -l "$D/usr/share/man/man5/cumulo.scene.5" >/dev/null 2>"$T/man.err" && [ ! -s "$T/man.err" ] &&
  t_ok "cumulo.scene(5) renders" || t_fail "cumulo.scene(5) renders" "$(head -2 "$T/man.err")"
# The staged copy works as it stands: the example built through pkg-config with the DESTDIR as sysroot, run against
# the staged library and tables.
mkdir -p "$T/staged"; cp "$SRC/tests/build/embed_example.c" "$T/staged/"
pcs="env PKG_CONFIG_PATH=$D/usr/lib/pkgconfig PKG_CONFIG_SYSROOT_DIR=$D pkg-config"
if (cd "$T/staged" && cc -std=c99 -Wall -Wextra -Werror embed_example.c -o embed $($pcs --cflags --libs cumulo) \
      -lEGL -lGLESv2) >"$log" 2>&1 &&
   out=$(cd "$T/staged" && LD_LIBRARY_PATH=$D/usr/lib CUMULO_DATA_DIR=$D/usr/share/cumulo/data \
           ./embed "$D/usr/share/cumulo/scenes/cumulus.scene" 2>&1); then
  t_ok "example against the DESTDIR copy (pkg-config with the DESTDIR as sysroot)"
else t_fail "example against the DESTDIR copy" "$(tail -3 "$log") $out"; fi
$MK uninstall DESTDIR="$D" PREFIX=/usr >"$log" 2>&1
left=$(find "$D" -type f -o -type l | sed "s|^$D/||" | tr '\n' ' ')
[ -z "$left" ] && t_ok "make uninstall removes every file" || t_fail "make uninstall removes every file" "left: $left"

# 6. A real PREFIX, then a program outside the tree built through pkg-config: it finds the installed tables by itself.
P=$T/prefix
if $MK install PREFIX="$P" >"$log" 2>&1; then t_ok "make install PREFIX=$P"; else t_fail "make install PREFIX" "$(tail -5 "$log")"; fi
mkdir -p "$T/outside"; cp "$SRC/tests/build/embed_example.c" "$T/outside/"
if (cd "$T/outside" && PKG_CONFIG_PATH=$P/lib/pkgconfig cc -std=c99 -Wall -Wextra -Werror embed_example.c -o embed \
      $(PKG_CONFIG_PATH=$P/lib/pkgconfig pkg-config --cflags --libs cumulo) -lEGL -lGLESv2) >"$log" 2>&1; then
  t_ok "example builds outside the tree with pkg-config --cflags --libs cumulo"
else t_fail "example builds outside the tree with pkg-config" "$(tail -5 "$log")"; fi
# The example host renderer, installed as documentation, builds the way its first comment says.
if (cd "$T/outside" && PKG_CONFIG_PATH=$P/lib/pkgconfig cc -std=c99 -Wall -Wextra -Werror \
      "$P/share/doc/cumulo/examples/host_scene.c" -o host_scene \
      $(PKG_CONFIG_PATH=$P/lib/pkgconfig pkg-config --cflags --libs cumulo egl glesv2) -lm) >"$log" 2>&1; then
  t_ok "installed examples/host_scene.c builds with pkg-config cumulo egl glesv2"
else t_fail "installed host_scene.c builds" "$(tail -5 "$log")"; fi
out=$(cd "$T/outside" && env -u CUMULO_DATA_DIR LD_LIBRARY_PATH=$P/lib ./embed "$P/share/cumulo/scenes/cumulus.scene" 2>&1); rc=$?
case "$out" in
  *"data $P/share/cumulo/data"*) [ $rc -eq 0 ] && t_ok "example renders against the installed library and tables" ||
                                   t_fail "example renders against the installed library" "$out" ;;
  *) t_fail "example renders against the installed library" "exit $rc: $out" ;;
esac
out=$(cd / && env -u CUMULO_DATA_DIR "$P/bin/cumulo" render "$P/share/cumulo/scenes/cumulus.scene" --size 32x24 -o "$T/inst.png" 2>&1)
[ $? -eq 0 ] && t_ok "installed cumulo renders from / with its installed tables" || t_fail "installed cumulo renders" "$out"

# 7. Other optimisation levels build warning-free (-Werror) and rebuild everything (flags are a dependency).
if $MK all OPT=-O0 >"$log" 2>&1; then t_ok "make OPT=-O0 all"; else t_fail "make OPT=-O0 all" "$(grep -m3 'error' "$log")"; fi
grep -q -- '-O0 .*-c src/core/scene_parse.c' "$log" && t_ok "a flags change recompiles" || t_fail "a flags change recompiles" ""
rm -rf "$W" "$D" "$P"
t_summary
