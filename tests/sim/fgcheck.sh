# sim/fgcheck.sh (`make fgcheck`, not in make check: FlightGear and its 1.8 GB of data): a real fgfs drives cumulo ig.
# fgfs (Debian's flightgear, run under Xvfb and a D-Bus session) starts at KSFO with data/flightgear/cumulo.xml as two
# --generic outputs, one to the IG and one recorded here; every frame the IG draws has its eye where WGS84 puts one
# of the recorded lines (tests/sim/geo.sh), and the IG's sun is `cumulo sun` at that line's UTC time. FGCHECK_INSTALL=1
# installs flightgear first.
# shellcheck disable=SC2086
. tests/lib.sh
. tests/sim/geo.sh
FGFS=${FGFS:-/usr/games/fgfs}
OUT=build/test-output/fgcheck
rm -rf "$OUT"; mkdir -p "$OUT/root/Protocol" "$OUT/home" "$OUT/rt"; chmod 700 "$OUT/rt"
if [ ! -x "$FGFS" ] && [ -n "$FGCHECK_INSTALL" ]; then sh scripts/install-deps.sh flightgear xvfb dbus; fi
for need in "$FGFS" Xvfb dbus-run-session; do
  if ! command -v "$need" >/dev/null 2>&1; then
    t_skip fgfs_drives_cumulo_ig "no $need (Debian: flightgear, xvfb, dbus; FGCHECK_INSTALL=1 installs them)"
    t_summary; exit
  fi
done
# FlightGear reads protocols from $FG_ROOT/Protocol only: a root of links to Debian's data with ours added.
DATA=/usr/share/games/flightgear
for e in "$DATA"/*; do [ "$(basename "$e")" = Protocol ] || ln -s "$e" "$OUT/root/"; done
ln -s "$DATA"/Protocol/* "$OUT/root/Protocol/"
cp data/flightgear/cumulo.xml "$OUT/root/Protocol/"
P=$((20000 + ($$ + 11) % 20000)); Q=$((P + 1)); D=$((90 + $$ % 100))
LAT0=37.6189; LON0=-122.375; ALT0=0
Xvfb :$D -screen 0 640x480x24 >"$OUT/xvfb.log" 2>&1 &
XV=$!
sleep 1
build/sim_replay record $Q "$OUT/recorded.txt" 300 &
REC=$!
build/cumulo ig scenes/clear.scene --input fg:127.0.0.1:$P --size 64x48 --frames 200 --frame-timeout 60 --trace \
  --set scene.origin_latitude=$LAT0 --set scene.origin_longitude=$LON0 >"$OUT/ig.out" 2>"$OUT/ig.err" &
IG=$!
DISPLAY=:$D FG_HOME="$PWD/$OUT/home" XDG_RUNTIME_DIR="$PWD/$OUT/rt" timeout 900 dbus-run-session -- "$FGFS" \
  --fg-root="$PWD/$OUT/root" --aircraft=ufo --airport=KSFO --disable-sound --disable-terrasync \
  --disable-splash-screen --disable-random-objects --disable-ai-models --geometry=320x240 --timeofday=noon \
  --generic=socket,out,10,127.0.0.1,$P,udp,cumulo --generic=socket,out,10,127.0.0.1,$Q,udp,cumulo \
  >"$OUT/fgfs.log" 2>&1 &
FG=$!
wait $IG; igrc=$?
kill $FG $REC 2>/dev/null; wait $REC 2>/dev/null; kill $XV 2>/dev/null
frames=$(grep -c '^ig frame' "$OUT/ig.out")
# each frame's eye against the recorded lines (the same lines, sent to both ports at once)
bad=0; checked=0
grep '^ig frame' "$OUT/ig.out" | tail -20 >"$OUT/last.txt"
while read -r il; do
  eye=$(printf '%s\n' "$il" | sed -n 's/.* eye=\([^ ]*\).*/\1/p'); found=0
  while IFS=, read -r la lo al hd pt rl rest; do
    set -- $(wgs84 $la $lo $al $hd $pt $rl)
    if close "$1" "$eye" 0.01; then found=1; break; fi
  done <"$OUT/recorded.txt"
  checked=$((checked + 1)); [ $found -eq 1 ] || bad=$((bad + 1))
done <"$OUT/last.txt"
if [ $igrc -eq 0 ] && [ "$frames" -ge 200 ] && [ $checked -eq 20 ] && [ $bad -eq 0 ]; then t_ok fgfs_drives_cumulo_ig
else t_fail fgfs_drives_cumulo_ig "ig exit $igrc, $frames frames, $bad of $checked eyes match no recorded line; $(tail -2 "$OUT/ig.err")"; fi
t_summary
