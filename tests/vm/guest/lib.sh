# tests/vm/guest/lib.sh: helpers for the guest tests (sourced after tests/lib.sh): where the binaries are, where
# output goes (the writable scratch share), and waiting for a log line under emulation's slow clock.
C=build/cumulo
S=scenes/cumulus.scene
H=build/vm
OUT=/tmp/scratch/out
mkdir -p "$OUT"
# The same software-GL environment as `make check`.
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=1 MESA_DEBUG=silent EGL_LOG_LEVEL=fatal

# wait_for FILE REGEX [SECONDS]: 0 once a line of FILE matches (grep -E), 1 after SECONDS (default 60).
wait_for() {
  _n=$(( ${3:-60} * 10 )); _i=0
  while [ $_i -lt $_n ]; do
    grep -Eq -- "$2" "$1" 2>/dev/null && return 0
    sleep 0.1; _i=$((_i + 1))
  done
  return 1
}

# last_sun FILE SOURCE: the last "sun elevation=E azimuth=A source=SOURCE" line of FILE.
last_sun() { grep "^sun .* source=$2\$" "$1" | tail -1; }

# wait_sun FILE SOURCE EXPECTED_LINE [SECONDS]: waits until the last sun line of SOURCE is EXPECTED_LINE and stays so
# for half a second more (a late extra detent would show), then compares. 0 if equal.
wait_sun() {
  _n=$(( ${4:-30} * 10 )); _i=0
  while [ $_i -lt $_n ] && [ "$(last_sun "$1" "$2")" != "$3" ]; do sleep 0.1; _i=$((_i + 1)); done
  sleep 0.5
  [ "$(last_sun "$1" "$2")" = "$3" ]
}

# elapsed: seconds since the script started, for the timing lines.
T0=$(cut -d' ' -f1 /proc/uptime)
elapsed() { awk -v a="$T0" -v b="$(cut -d' ' -f1 /proc/uptime)" 'BEGIN { printf "%.1f", b - a }'; }
