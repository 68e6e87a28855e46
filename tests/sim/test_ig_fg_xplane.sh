# sim/test_ig_fg_xplane.sh: `cumulo ig` slaved to FlightGear and to X-Plane by their recorded streams
# (tests/sim/data/), replayed over UDP by tests/sim/sim_replay.c (for X-Plane, a stand-in that answers the IG's RREF
# subscriptions): the eyepoint follows the aircraft (against WGS84 worked in tests/sim/geo.sh), the sun follows the
# simulator's UTC date and time (against `cumulo sun`), X-Plane gets its ten subscriptions and, when the IG stops,
# ten unsubscriptions; a line FlightGear's XML would not send is counted and skipped. A real fgfs run is `make fgcheck`.
# shellcheck disable=SC2086
. tests/lib.sh
. tests/sim/geo.sh
C=build/cumulo
OUT=build/test-output/ig_fg_xplane
rm -rf "$OUT"; mkdir -p "$OUT"
P=$((20000 + ($$ + 7) % 20000)); Q=$((P + 1))
field() { printf '%s\n' "$2" | sed -n "s/.* $1=\([^ ]*\).*/\1/p"; }
ig() { # NAME INPUT ORIGIN...: cumulo ig in the background, its pid in IG
  _n=$1; _i=$2; shift 2
  $C ig scenes/clear.scene --input "$_i" --size 48x32 --frame-timeout 30 --trace "$@" >"$OUT/$_n.out" 2>"$OUT/$_n.err" &
  IG=$!
}
stop_ig() { sleep 1; kill -TERM $IG 2>/dev/null; wait $IG; }

# ---- The command line: every bad --input is a usage error naming the field; a port in use is a runtime error ----
help=$($C ig --help 2>"$OUT/help.err"); rc=$?; miss=""
for o in --input --frames --frame-timeout --layer-extent --save --trace cigi: fg: xplane: origin_latitude; do
  case "$help" in *"$o"*) ;; *) miss="$miss $o" ;; esac
done
if [ $rc -eq 0 ] && [ -z "$miss" ] && [ ! -s "$OUT/help.err" ] && case "$help" in "usage: cumulo ig"*) true ;; *) false ;; esac
then t_ok ig_help; else t_fail ig_help "exit $rc, not described:$miss"; fi
S=scenes/clear.scene
t_expect ig_unknown_protocol 2 "expected cigi:[ADDR:]PORT, fg:[ADDR:]PORT or xplane:HOST:PORT" -- $C ig $S --input udp:8004
t_expect ig_port_not_a_number 2 "the port must be a number in 0..65535" -- $C ig $S --input cigi:80x4
t_expect ig_port_too_large 2 "the port must be a number in 0..65535" -- $C ig $S --input fg:70000
t_expect ig_cigi_needs_port 2 "give the port to listen on" -- $C ig $S --input cigi
t_expect ig_xplane_needs_host 2 "xplane needs X-Plane's HOST:PORT" -- $C ig $S --input xplane:49000
t_expect ig_unknown_option 2 "unknown option 'colour=red'" -- $C ig $S --input cigi:8004,colour=red
t_expect ig_view_range 2 "'view=70000' is out of range" -- $C ig $S --input cigi:8004,view=70000
t_expect ig_bad_host 2 "cannot resolve" -- $C ig $S --input "cigi:8004,host=no.such.host.invalid:8005"
t_expect ig_bad_timeout 2 "--frame-timeout expects a number in 0.001..60" -- $C ig $S --frame-timeout 0
t_expect ig_bad_extent 2 "--layer-extent expects a number in 1000..200000" -- $C ig $S --layer-extent 5
t_expect ig_no_scene 2 "usage: cumulo ig" -- $C ig --input cigi:8004
t_expect ig_bad_origin 2 "origin_latitude" -- $C ig $S --set scene.origin_latitude=91 --frames 1
build/sim_replay xplane $P tests/sim/data/xplane_rref.hex 0 >/dev/null 2>&1 &
HOLD=$!; sleep 0.3
t_expect ig_port_in_use 1 "cannot listen on UDP 127.0.0.1:$P" -- $C ig $S --input "cigi:127.0.0.1:$P" --frames 1
kill $HOLD 2>/dev/null; wait $HOLD 2>/dev/null

# ---- FlightGear: 13 lines of a climb out of KSFO, and one bad line after them ----
LAT0=37.6189; LON0=-122.375; ALT0=0
ig fg "fg:127.0.0.1:$P" --set scene.origin_latitude=$LAT0 --set scene.origin_longitude=$LON0
t_wait_line "$OUT/fg.err" "cumulo ig: fg listen=" 120 $IG
{ cat tests/sim/data/fgfs_stream.txt; echo "37.7,-122.4,100,nan,0,0,2024,6,21,19,31,0,55"; } >"$OUT/fg_stream.txt"
build/sim_replay fg "127.0.0.1:$P" "$OUT/fg_stream.txt" 150 >"$OUT/fg_replay.out" 2>&1; rrc=$?
stop_ig; igrc=$?
last=$(grep -v nan tests/sim/data/fgfs_stream.txt | tail -1)
IFS=, read -r la lo al hd pt rl yy mo dd hh mi ss fov <<EOF2
$last
EOF2

il=$(grep '^ig frame' "$OUT/fg.out" | tail -1)
set -- $(wgs84 $la $lo $al $hd $pt $rl)
utc=$(printf '%04d-%02d-%02dT%02d:%02d:%02dZ' $yy $mo $dd $hh $mi $ss)
want_sun=$($C sun --time-utc $utc --latitude $la --longitude $lo --height $al | awk '{ printf "%s,%s", $2, $4 }')
if [ $rrc -eq 0 ] && [ $igrc -eq 0 ] && close "$1" "$(field eye "$il")" 0.01 && close "$2" "$(field fwd "$il")" 2e-6 &&
   close "$3" "$(field up "$il")" 2e-6; then t_ok fg_eyepoint_follows_the_aircraft
else t_fail fg_eyepoint_follows_the_aircraft "replay $rrc, ig $igrc; expected $1 $2 $3 from '$last', got '$il' $(tail -2 "$OUT/fg.err")"; fi
if [ "$(field utc "$il")" = "$utc" ] && [ "$(field sun "$il")" = "$want_sun" ]; then t_ok fg_sun_follows_the_utc_time
else t_fail fg_sun_follows_the_utc_time "expected $utc $want_sun, got $(field utc "$il") $(field sun "$il")"; fi
if grep -q "rejected=1 " "$OUT/fg.out" && [ "$(grep -c '^sent ' "$OUT/fg_replay.out")" -eq 14 ]; then
  t_ok fg_bad_line_counted_and_skipped
else t_fail fg_bad_line_counted_and_skipped "$(grep '^\[ig\]' "$OUT/fg.out" | head -1)"; fi

# ---- X-Plane: the stand-in on Q; seven reply datagrams of a take-off from KSEA ----
build/sim_replay xplane $Q tests/sim/data/xplane_rref.hex 150 >"$OUT/xp_replay.out" 2>&1 &
XP=$!
sleep 0.5
LAT0=47.45; LON0=-122.31; ALT0=100
ig xp "xplane:127.0.0.1:$Q,year=2024" --set scene.origin_latitude=$LAT0 --set scene.origin_longitude=$LON0 \
   --set scene.origin_altitude=$ALT0
# the replay ends after the last datagram and the IG's unsubscriptions: stop the IG once the datagrams are out
for _ in $(seq 1 120); do [ "$(grep -c '^sent ' "$OUT/xp_replay.out")" -ge 7 ] && break; sleep 0.5; done
stop_ig; igrc=$?
wait $XP; xrc=$?
# the values the stand-in sent, decoded by it: the latest of each index
val() { grep '^sent ' "$OUT/xp_replay.out" | tr ' ' '\n' | awk -v i="index=$1" '$0 == i { getline; v = $0 } END { sub("value=", "", v); print v }'; }
subs=$(grep -c '^subscribe ' "$OUT/xp_replay.out"); unsubs=$(grep -c '^unsubscribe ' "$OUT/xp_replay.out")
paths=$(grep '^subscribe ' "$OUT/xp_replay.out" | sed 's/.*path=//' | sort | tr '\n' ' ')
if [ $xrc -eq 0 ] && [ "$subs" -eq 10 ] && [ "$unsubs" -eq 10 ] && case "$paths" in
     *sim/flightmodel/position/latitude*sim/flightmodel/position/true_psi*sim/time/zulu_time_sec*) true ;; *) false ;; esac
then t_ok xplane_subscribes_and_unsubscribes
else t_fail xplane_subscribes_and_unsubscribes "stand-in exit $xrc, $subs subscriptions, $unsubs unsubscriptions: $paths"; fi
il=$(grep '^ig frame' "$OUT/xp.out" | tail -1)
set -- $(wgs84 "$(val 0)" "$(val 1)" "$(val 2)" "$(val 3)" "$(val 4)" "$(val 5)")
z=$(val 6); day=$(val 8)
utc=$(awk -v z="$z" -v d="$day" 'BEGIN { split("31 29 31 30 31 30 31 31 30 31 30 31", m, " "); mo = 1; d = d + 0
  while (d >= m[mo]) { d -= m[mo]; mo++ } s = int(z); printf "2024-%02d-%02dT%02d:%02d:%02dZ", mo, d + 1, s / 3600,
  (s % 3600) / 60, s % 60 }')
want_sun=$($C sun --time-utc $utc --latitude "$(val 0)" --longitude "$(val 1)" --height "$(val 2)" |
           awk '{ printf "%s,%s", $2, $4 }')
if [ $igrc -eq 0 ] && close "$1" "$(field eye "$il")" 0.01 && close "$2" "$(field fwd "$il")" 2e-6 &&
   close "$3" "$(field up "$il")" 2e-6; then t_ok xplane_eyepoint_follows_the_aircraft
else t_fail xplane_eyepoint_follows_the_aircraft "ig $igrc; expected $1 $2 $3, got '$il' $(tail -2 "$OUT/xp.err")"; fi
if [ "$(field utc "$il")" = "$utc" ] && [ "$(field sun "$il")" = "$want_sun" ]; then t_ok xplane_sun_follows_zulu_time
else t_fail xplane_sun_follows_zulu_time "expected $utc $want_sun (zulu $z, day $day), got $(field utc "$il") $(field sun "$il")"; fi
t_summary
