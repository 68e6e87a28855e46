# tests/vm/guest/lib.sh: helpers for the guest tests (sourced after tests/lib.sh): where the binaries are, where
# output goes (the writable scratch share), and waiting for a log line under emulation's slow clock.
C=build/cumulo
S=scenes/cumulus.scene
H=build/vm
OUT=/tmp/scratch/out
# FIFOs cannot live on the 9p share: they go to the guest's tmpfs.
F=/tmp/fifo
mkdir -p "$OUT" $F
# The same software-GL environment as `make check`.
export LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=llvmpipe LP_NUM_THREADS=1 MESA_DEBUG=silent EGL_LOG_LEVEL=fatal

# now: seconds since boot (whole). Deadlines use it, not loop counts: under emulation a grep over 9p is slow.
now() { cut -d. -f1 /proc/uptime; }

# wait_for FILE REGEX [SECONDS]: 0 once a line of FILE matches (grep -E), 1 after SECONDS (default 60).
wait_for() {
  _end=$(( $(now) + ${3:-60} ))
  while [ "$(now)" -le $_end ]; do
    grep -Eq -- "$2" "$1" 2>/dev/null && return 0
    sleep 0.2
  done
  return 1
}

# last_sun FILE SOURCE: the last "sun elevation=E azimuth=A source=SOURCE" line of FILE.
last_sun() { grep "^sun .* source=$2\$" "$1" | tail -1; }

# wait_sun FILE SOURCE EXPECTED_LINE [SECONDS]: waits until the last sun line of SOURCE is EXPECTED_LINE and stays so
# for a second more (a late extra detent would show), then compares. 0 if equal.
wait_sun() {
  _end=$(( $(now) + ${4:-30} ))
  while [ "$(now)" -le $_end ] && [ "$(last_sun "$1" "$2")" != "$3" ]; do sleep 0.2; done
  sleep 1
  [ "$(last_sun "$1" "$2")" = "$3" ]
}

# elapsed: seconds since the script started, for the timing lines.
T0=$(cut -d' ' -f1 /proc/uptime)
elapsed() { awk -v a="$T0" -v b="$(cut -d' ' -f1 /proc/uptime)" 'BEGIN { printf "%.1f", b - a }'; }
