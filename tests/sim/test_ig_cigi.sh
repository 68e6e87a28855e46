# sim/test_ig_cigi.sh: `cumulo ig` driven end to end by a CIGI 3.3 host of our own (tests/sim/cigi_host.c, its script
# is in its header): the eyepoint follows the ownship (against WGS84 worked here in awk, and against a scene file's
# camera rendered by `cumulo render`), the sun follows the host's date and time (against `cumulo sun`), a cloud layer's
# coverage going 0 -> 60 % draws what the same layer in a scene file draws, Start of Frame echoes the host's frames
# (the host checks each), and hostile datagrams are counted and skipped while the IG goes on drawing, the frames their
# IG Controls have drawn again at the host's time. The exchange is
# captured on the loopback interface and decoded by Wireshark's CIGI dissector (tshark): every field it reads must
# be what was meant.
# shellcheck disable=SC2086
. tests/lib.sh
C=build/cumulo
OUT=build/test-output/ig_cigi
rm -rf "$OUT"; mkdir -p "$OUT/frames"
W=96; H=64; FOV=50; LAT0=47; LON0=8; ALT0=400
P=$((20000 + $$ % 20000)); Q=$((P + 1))
ORIGIN="--set scene.origin_latitude=$LAT0 --set scene.origin_longitude=$LON0 --set scene.origin_altitude=$ALT0"
SCENE=scenes/clear.scene

# The capture, when this machine lets us (root or CAP_NET_RAW, tshark installed).
CAP=""
if command -v tshark >/dev/null 2>&1; then
  tshark -i lo -f "udp port $P or udp port $Q" -w "$OUT/cigi.pcapng" -q >"$OUT/tshark_capture.log" 2>&1 &
  CAP=$!
  for _ in 1 2 3 4 5 6 7 8 9 10; do grep -q "Capturing on" "$OUT/tshark_capture.log" 2>/dev/null && break; sleep 0.5; done
  if ! kill -0 "$CAP" 2>/dev/null; then CAP=""; fi
fi

$C ig $SCENE --input "cigi:127.0.0.1:$P,host=127.0.0.1:$Q" --size ${W}x$H --set camera.fov=$FOV $ORIGIN \
   --frame-timeout 60 --trace --save "$OUT/frames" --dump-scene "$OUT/dumped.scene" >"$OUT/ig.out" 2>"$OUT/ig.err" &
IG=$!
t_wait_line "$OUT/ig.err" "cumulo ig: cigi 3.3 listen=" 120 $IG
timeout 600 build/cigi_host "127.0.0.1:$P" $Q $W $H $FOV $LAT0 $LON0 $ALT0 >"$OUT/host.log" 2>"$OUT/host.err"
hrc=$?
sleep 1
kill -TERM $IG 2>/dev/null
wait $IG; igrc=$?
[ -n "$CAP" ] && { sleep 1; kill -INT $CAP 2>/dev/null; wait $CAP; }

if [ $hrc -eq 0 ] && [ $igrc -eq 0 ] && [ "$(grep -c '^host frame=' "$OUT/host.log")" -eq 24 ]; then
  t_ok start_of_frame_each_frame
else t_fail start_of_frame_each_frame "host exit $hrc, ig exit $igrc: $(cat "$OUT/host.err" "$OUT/ig.err" | tail -5)"; fi

# ig_line HOST_FRAME: the last trace line of the IG that drew it; field NAME LINE: its value
ig_line() { grep " host_frame=$1 " "$OUT/ig.out" | tail -1; }
host_line() { grep "^host frame=$1 " "$OUT/host.log"; }
field() { printf '%s\n' "$2" | sed -n "s/.* $1=\([^ ]*\).*/\1/p"; }
frame_png() { printf '%s/frames/frame_%06d.png' "$OUT" "$(field frame "$(ig_line "$1")")"; }

# The eyepoint against WGS84 worked here (tests/sim/geo.sh).
. tests/sim/geo.sh
bad=""
for k in 1 2 3 4 13; do
  hl=$(host_line $k); il=$(ig_line $k)
  set -- $(wgs84 "$(field lat "$hl")" "$(field lon "$hl")" "$(field alt "$hl")" "$(field yaw "$hl")" \
                 "$(field pitch "$hl")" "$(field roll "$hl")" "$(field view0 "$hl")")
  close "$1" "$(field eye "$il")" 0.01 && close "$2" "$(field fwd "$il")" 2e-6 && close "$3" "$(field up "$il")" 2e-6 ||
    bad="$bad frame $k: expected $1 $2 $3, ig '$(field eye "$il") $(field fwd "$il") $(field up "$il")';"
done
if [ -z "$bad" ] && [ -n "$(ig_line 4)" ]; then t_ok eyepoint_follows_the_ownship_wgs84
else t_fail eyepoint_follows_the_ownship_wgs84 "${bad:-no trace of host frame 4}"; fi

# Host frame 1 puts the eye 500 m above the origin, heading north, 5 degrees up: the picture of a scene file's camera.
render_as() { # OUT.png POSITION LOOK_AT SUN_EL SUN_AZ [--set ...]
  _o=$1; _p=$2; _l=$3; _e=$4; _a=$5; shift 5
  $C render $SCENE --size ${W}x$H --set camera.fov=$FOV --set "camera.position=$_p" --set "camera.look_at=$_l" \
     --set sun.elevation=$_e --set sun.azimuth=$_a "$@" -o "$_o" >/dev/null 2>"$_o.err"
}
sun1=$(field sun "$(ig_line 1)")
render_as "$OUT/file1.png" "0 500 0" "0 500.0871557427 -0.9961946981" "${sun1%,*}" "${sun1#*,}"
d=$(build/png_diff "$OUT/file1.png" "$(frame_png 1)" 1); rc=$?
if [ $rc -eq 0 ]; then t_ok eyepoint_draws_as_the_scene_camera
else t_fail eyepoint_draws_as_the_scene_camera "host frame 1 against cumulo render: $d (limit 1/255)"; fi

# The sun of each hour of 21 June at the ownship's place, as `cumulo sun` gives it.
bad=""
for k in 5 6 7 8 9 10 11 12; do
  hl=$(host_line $k); il=$(ig_line $k)
  want=$($C sun --time-utc "$(field utc "$hl")" --latitude $LAT0 --longitude $LON0 --height 700 |
         awk '{ printf "%s,%s", $2, $4 }')
  [ "$(field sun "$il")" = "$want" ] && [ "$(field utc "$il")" = "$(field utc "$hl")" ] ||
    bad="$bad frame $k: $(field utc "$hl") cumulo sun $want, ig $(field sun "$il") at $(field utc "$il");"
done
if [ -z "$bad" ]; then t_ok sun_follows_the_host_date_and_time; else t_fail sun_follows_the_host_date_and_time "$bad"; fi

# Coverage 0 draws the clear sky; 60 % (host frame 24: rebuilds wait 0.5 s after the last) draws the scene file with the same [layer] (cumulus 1500 m thick is
# mediocris; the base is above sea level, so 1200 m above the origin's 400 m); 20 % is neither.
sun=$(field sun "$(ig_line 24)"); look="0 300.2588190451 -0.9659258263"
{ cat $SCENE; printf '[layer]\ntype = cumulus-mediocris\nbase = 1200\nthickness = 1500\ncoverage = 0.6\n'
  printf 'extent = 20000\nseed = 1\nwind = 10 0\n'; } >"$OUT/layer.scene"
render_as "$OUT/clear.png" "0 300 0" "$look" "${sun%,*}" "${sun#*,}"
SCENE="$OUT/layer.scene" render_as "$OUT/layer.png" "0 300 0" "$look" "${sun%,*}" "${sun#*,}"
d0=$(build/png_diff "$OUT/clear.png" "$(frame_png 13)" 1); r0=$?
d6=$(build/png_diff "$OUT/layer.png" "$(frame_png 24)" 1); r6=$?
d2=$(build/png_diff "$OUT/layer.png" "$(frame_png 14)" 1); r2=$?
d02=$(build/png_diff "$OUT/clear.png" "$(frame_png 14)" 1); r02=$?
if [ $r0 -eq 0 ] && [ $r6 -eq 0 ] && [ $r2 -eq 1 ] && [ $r02 -eq 1 ]; then t_ok coverage_0_to_60_draws_the_scene_file_layer
else t_fail coverage_0_to_60_draws_the_scene_file_layer "0 %: $d0 (exit $r0); 60 %: $d6 (exit $r6); 20 % against 60 %: $d2, against clear: $d02"; fi

# The scene the IG drew last (--dump-scene): the file's, with the host's layer, whose wind is the global west wind of
# 10 m/s (Atmosphere Control) blowing toward the east.
lay=$(sed -n '/^\[layer\]/,$p' "$OUT/dumped.scene")
case "$lay" in *"type = cumulus-mediocris"*"base = 1200.000"*"coverage = 0.600000"*"wind = 10.0000 "*)
  w_n=$(printf '%s\n' "$lay" | sed -n 's/^wind = [^ ]* //p')
  if awk -v n="$w_n" 'BEGIN { exit !(n < 1e-3 && n > -1e-3) }'; then t_ok dumped_scene_has_the_host_layer_and_wind
  else t_fail dumped_scene_has_the_host_layer_and_wind "north wind $w_n"; fi ;;
  *) t_fail dumped_scene_has_the_host_layer_and_wind "'$lay'" ;; esac

# Hostile datagrams (host frames 20-24): each kind counted, none applied, the frames after them drawn as meant.
stats=$(grep '^\[ig\] cigi:' "$OUT/ig.out")
ok=1
for f in malformed wrong_version unknown untrusted nonfinite out_of_range; do
  [ "$(field $f " $stats")" -ge 1 ] 2>/dev/null || ok=0
done
il=$(ig_line 24)
if [ $ok -eq 1 ] && close "$(field eye "$il")" "0,300,0" 0.01 && [ -n "$(ig_line 23)" ] &&
   build/png_diff "$OUT/layer.png" "$(frame_png 24)" 1 >/dev/null; then t_ok hostile_datagrams_counted_and_skipped
else t_fail hostile_datagrams_counted_and_skipped "$stats; last frame: $il"; fi
# The frames the bursts' IG Controls (no timestamp) had the IG draw again, on their own: at the host's time (all its
# timestamps are 0), never the IG's own clock: a jump there and back moves every cloud, and the frame after it is
# not the scene file's picture until the clouds' maps are made again.
reps=$(grep -c '^repeat before' "$OUT/host.log")
moved=$(grep '^ig frame=' "$OUT/ig.out" | grep -v ' time=0.000 ' | head -2)
if [ "$reps" -ge 1 ] && [ -z "$moved" ]; then t_ok frames_without_timestamp_keep_the_host_time
else t_fail frames_without_timestamp_keep_the_host_time "$reps frames drawn again; at another time: '$moved'"; fi
lat=$(grep '^\[ig\] latency' "$OUT/ig.out")
case "$lat" in *"median="[0-9]*" p95="[0-9]*) t_ok latency_reported ;; *) t_fail latency_reported "'$lat'" ;; esac

# A second channel: view 1, turned right by the frustum's full width (the host defines it every frame), from its own
# IG on the same script. Its eye looks where the host's View Control says, and its left edge meets view 0's right
# edge: the columns either side of the seam are closer than view 0's right edge is to view 1's right edge.
mkdir -p "$OUT/frames1"
P1=$((Q + 1)); Q1=$((Q + 2))
$C ig $SCENE --input "cigi:127.0.0.1:$P1,host=127.0.0.1:$Q1,view=1" --size ${W}x$H --set camera.fov=$FOV $ORIGIN \
   --frame-timeout 60 --trace --save "$OUT/frames1" >"$OUT/ig1.out" 2>"$OUT/ig1.err" &
IG=$!
t_wait_line "$OUT/ig1.err" "cumulo ig: cigi 3.3 listen=" 120 $IG
timeout 600 build/cigi_host "127.0.0.1:$P1" $Q1 $W $H $FOV $LAT0 $LON0 $ALT0 >"$OUT/host1.log" 2>"$OUT/host1.err"
hrc=$?
sleep 1; kill -TERM $IG 2>/dev/null; wait $IG
bad=""
for k in 1 2 4 13; do
  hl=$(host_line $k); il=$(grep " host_frame=$k " "$OUT/ig1.out" | tail -1)
  set -- $(wgs84 "$(field lat "$hl")" "$(field lon "$hl")" "$(field alt "$hl")" "$(field yaw "$hl")" \
                 "$(field pitch "$hl")" "$(field roll "$hl")" "$(field view1 "$hl")")
  close "$1" "$(field eye "$il")" 0.01 && close "$2" "$(field fwd "$il")" 2e-6 && close "$3" "$(field up "$il")" 2e-6 ||
    bad="$bad frame $k: expected $1 $2 $3, ig '$(field eye "$il") $(field fwd "$il") $(field up "$il")';"
done
f1=$(printf '%s/frames1/frame_%06d.png' "$OUT" "$(field frame "$(grep " host_frame=24 " "$OUT/ig1.out" | tail -1)")")
seam=$(build/png_diff --columns "$(frame_png 24)" $((W - 1)) "$f1" 0); far=$(build/png_diff --columns "$(frame_png 24)" $((W - 1)) "$f1" $((W - 1)))
if [ $hrc -eq 0 ] && [ -z "$bad" ] && awk -v s="${seam#mean=}" -v f="${far#mean=}" 'BEGIN { exit !(s < 0.5 * f) }'; then
  t_ok second_channel_meets_the_first
else t_fail second_channel_meets_the_first "host exit $hrc ($(tail -2 "$OUT/host1.err" "$OUT/ig1.err" | tr '\n' ' '));$bad seam $seam, far $far"; fi

# Wireshark's decoder on the capture: the fields it reads are the ones the host meant and the IG sent.
if [ -z "$CAP" ]; then
  t_skip tshark_decodes_the_exchange "no capture on lo here (tshark missing or no permission: $(head -2 "$OUT/tshark_capture.log" 2>/dev/null))"
else
  TS="tshark -r $OUT/cigi.pcapng -d udp.port==$P,cigi -d udp.port==$Q,cigi -T fields -E separator=/t"
  # The host's frames (the datagrams with a Celestial Sphere Control: the hostile ones have none), as tshark reads
  # them, against what the host logged it meant to send.
  $TS -Y "udp.dstport == $P && cigi.celestial_sphere_control.hour" -e cigi.ig_control.host_frame_number \
      -e cigi.ig_control.minor_version -e cigi.entity_control.lat_xoff -e cigi.entity_control.lon_yoff \
      -e cigi.entity_control.alt_zoff -e cigi.entity_control.yaw -e cigi.entity_control.pitch \
      -e cigi.entity_control.roll -e cigi.celestial_sphere_control.hour -e cigi.celestial_sphere_control.minute \
      -e cigi.celestial_sphere_control.date -e cigi.weather_control.coverage -e cigi.view_def.left \
      -e cigi.view_def.top >"$OUT/tshark_host.txt" 2>"$OUT/tshark.err"
  bad=$(awk -F"\t" -v hlog="$OUT/host.log" 'BEGIN {
      while ((getline l < hlog) > 0) { if (l !~ /^host frame=/) continue; n = split(l, f, " ")
        for (i = 2; i <= n; i++) { split(f[i], kv, "="); v[kv[1]] = kv[2] }
        k = v["frame"]; want[k] = v["lat"] " " v["lon"] " " v["alt"] " " v["yaw"] " " v["pitch"] " " v["roll"]
        hh[k] = substr(v["utc"], 12, 2) + 0; mm[k] = substr(v["utc"], 15, 2) + 0; cov[k] = v["coverage"] }
    }
    { k = $1; seen[k] = 1; split(want[k], w, " ")
      if ($2 != 3) print "frame " k ": minor version " $2
      for (i = 1; i <= 6; i++) { d = $(i + 2) - w[i]; if (d < 0) d = -d
        if (d > (i <= 2 ? 1e-9 : 1e-3)) print "frame " k ": field " i " is " $(i + 2) ", sent " w[i] }
      if ($9 != hh[k] || $10 != mm[k] || $11 != 6212026) print "frame " k ": time " $9 ":" $10 " on " $11
      c = cov[k] < 0 ? "" : cov[k] * 100; if (($12 == "") != (c == "") || ($12 != "" && ($12 - c > 1e-3 || c - $12 > 1e-3)))
        print "frame " k ": coverage " $12 ", sent " c
      if ($13 >= 0 || $14 <= 0) print "frame " k ": half-angles " $13 " " $14 }
    END { for (k in want) if (!(k in seen)) print "frame " k " not in the capture" }' "$OUT/tshark_host.txt")
  # The IG's Start of Frame packets: CIGI 3.3, consecutive IG frames, the host frames echoed as the host logged them.
  $TS -Y "udp.dstport == $Q && cigi.sof.ig_frame_number" -e cigi.version -e cigi.sof.minor_version \
      -e cigi.byte_swap -e cigi.sof.ig_frame_number -e cigi.sof.last_host_frame_number -e cigi.sof.ig_mode \
      >"$OUT/tshark_sof.txt" 2>>"$OUT/tshark.err"
  grep '^sof ' "$OUT/host.log" | sed 's/.*ig_frame=\([0-9]*\) last_host_frame=\([0-9]*\).*/\1 \2/' >"$OUT/sof_logged.txt"
  awk -F"\t" '{ print $4, $5 }' "$OUT/tshark_sof.txt" >"$OUT/sof_decoded.txt"
  sofbad=$(awk -F"\t" 'NR > 1 && $4 != prev + 1 { print "IG frame " $4 " after " prev } { prev = $4 }
                $1 != 3 || $2 != 3 || $3 != "0x8000" || ($5 > 0 && $6 != 1) { print "SOF " $0 }' "$OUT/tshark_sof.txt")
  nh=$(wc -l <"$OUT/tshark_host.txt"); ns=$(wc -l <"$OUT/tshark_sof.txt")
  # every Start of Frame the host logged is one tshark decoded (the capture may hold frame 0's, sent before the host
  # listened, and the last one the host no longer waited for)
  missing=$(grep -vxFf "$OUT/sof_decoded.txt" "$OUT/sof_logged.txt" | head -3)
  if [ "$nh" -eq 24 ] && [ "$ns" -ge 24 ] && [ -z "$bad" ] && [ -z "$sofbad" ] && [ -z "$missing" ]; then
    t_ok tshark_decodes_the_exchange
  else t_fail tshark_decodes_the_exchange "host datagrams $nh, SOF $ns: $bad $sofbad ${missing:+logged SOF not decoded: $missing} $(head -3 "$OUT/tshark.err")"; fi
fi
t_summary
