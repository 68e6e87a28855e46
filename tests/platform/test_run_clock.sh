# platform/test_run_clock.sh: `cumulo run --clock` end to end, headless: the time shown is the wall clock's (shifted by
# --clock-offset, sped up by --time-scale), the sun is the solar position at that time and the scene's place (as
# `cumulo sun` gives it), the knob and stdin offset the time, and bad values are usage errors. Needs GNU date -d.
# RUN and PARIS are word lists, split on purpose where they are used:
# shellcheck disable=SC2086
. tests/lib.sh
C=build/cumulo
S=scenes/cumulus.scene
OUT=build/test-output/run_clock
mkdir -p "$OUT"
PARIS="--set sun.latitude=48.85 --set sun.longitude=2.35"
RUN="$C run $S --platform headless --size 32x24"
epoch() { date -u -d "$1" +%s 2>/dev/null; }
# field NAME LINE: the value of NAME=... in a log line
field() { printf '%s\n' "$2" | sed -n "s/.* $1=\([^ ]*\).*/\1/p"; }
if [ "$(epoch 2026-06-21T12:00:00Z)" != 1782043200 ]; then
  t_skip run_clock "this date cannot read ISO 8601 times (date -u -d; GNU coreutils)"
  t_summary; exit
fi

# The clock line at the start shows the wall clock's UTC time, to a second or two; the header says clock mode, the
# place and the offsets; a scene that gives its place gets no warning.
t0=$(date -u +%s)
$RUN --clock --frames 2 --no-stdin $PARIS >"$OUT/c.out" 2>"$OUT/c.err"; rc=$?
t1=$(date -u +%s)
line=$(grep '^clock utc=.* offset=+0min elevation=.* azimuth=.* source=start$' "$OUT/c.err")
t=$(epoch "$(field utc "$line")")
if [ $rc -eq 0 ] && [ -n "$t" ] && [ "$t" -ge $((t0 - 2)) ] && [ "$t" -le $((t1 + 2)) ]; then t_ok clock_line_is_the_wall_clock
else t_fail clock_line_is_the_wall_clock "exit $rc, date -u $t0..$t1, got '$line' ($(cat "$OUT/c.err"))"; fi
if grep -q '^    Sun: *clock utc=.* latitude=48.8500 longitude=2.3500 clock-offset=+0s time-scale=1$' "$OUT/c.out" &&
   grep -q '^ *offset=+0min step=10min elevation=' "$OUT/c.out" && ! grep -q 'warning' "$OUT/c.err"; then
  t_ok clock_header
else t_fail clock_header "$(cat "$OUT/c.out" "$OUT/c.err")"; fi

# No place in the scene: the keys' defaults, 0 N 0 E, and a warning that says so.
$RUN --clock --frames 1 --no-stdin >"$OUT/z.out" 2>"$OUT/z.err"; rc=$?
if [ $rc -eq 0 ] && grep -q "warning: $S gives no \[sun\] latitude or longitude: --clock shows the sun of 0 N 0 E" "$OUT/z.err" &&
   grep -q 'latitude=0.0000 longitude=0.0000' "$OUT/z.out"; then t_ok clock_without_place_warns
else t_fail clock_without_place_warns "exit $rc: $(cat "$OUT/z.err")"; fi

# --clock-offset shifts the clock: an hour later.
t0=$(date -u +%s)
$RUN --clock --clock-offset 3600 --frames 1 --no-stdin $PARIS >"$OUT/o.out" 2>"$OUT/o.err"; rc=$?
t1=$(date -u +%s)
t=$(epoch "$(field utc "$(grep '^clock .*source=start' "$OUT/o.err")")")
if [ $rc -eq 0 ] && [ -n "$t" ] && [ "$t" -ge $((t0 + 3598)) ] && [ "$t" -le $((t1 + 3602)) ] &&
   grep -q 'clock-offset=+3600s' "$OUT/o.out"; then t_ok clock_offset_shifts
else t_fail clock_offset_shifts "exit $rc, date -u $t0..$t1 + 3600, got $t: $(cat "$OUT/o.err")"; fi

# stdin: 'offset 90' moves the time shown by 90 minutes and the sun with it, to what `cumulo sun` gives for that time
# and place; the angles are refused; the button puts the offset back; a detent is --step minutes.
printf 'offset 90\nstatus\nsun 10 10\nelevation 5\ntoggle\nturn 2\nquit\n' |
  $RUN --clock --frames 1000 --step 15 --accel 0 $PARIS >"$OUT/s.out" 2>"$OUT/s.err"; rc=$?
start=$(grep '^clock .*source=start' "$OUT/s.err")
moved=$(grep '^clock .*offset=+90min .*source=stdin$' "$OUT/s.err")
ta=$(epoch "$(field utc "$start")"); tb=$(epoch "$(field utc "$moved")")
if [ $rc -eq 0 ] && [ -n "$ta" ] && [ -n "$tb" ] && [ $((tb - ta)) -ge 5400 ] && [ $((tb - ta)) -le 5403 ]; then
  t_ok offset_90_moves_the_time
else t_fail offset_90_moves_the_time "exit $rc: $(cat "$OUT/s.err")"; fi
want=$($C sun --time-utc "$(field utc "$moved")" --latitude 48.85 --longitude 2.35)
if printf '%s\n%s\n' "$want" "$moved" | awk '
     NR == 1 { el = $2; az = $4 }
     NR == 2 { for (i = 1; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
               d = v["azimuth"] - az; if (d > 180) d -= 360; if (d < -180) d += 360
               e = v["elevation"] - el
               exit !(e <= 0.01 && e >= -0.01 && d <= 0.01 && d >= -0.01) }'; then
  t_ok offset_sun_is_the_solar_position
else t_fail offset_sun_is_the_solar_position "cumulo sun: '$want', run: '$moved'"; fi
status=$(grep '^status ' "$OUT/s.out")
if [ "$(field offset "$status")" = "+90min" ] && [ "$(field utc "$status")" = "$(field utc "$moved")" ] &&
   [ "$(field elevation "$status")" = "$(field elevation "$moved")" ]; then t_ok status_shows_time_offset_and_sun
else t_fail status_shows_time_offset_and_sun "status '$status', clock line '$moved'"; fi
if [ "$(grep -c "^stdin: with --clock the clock sets the sun: 'sun', 'elevation' and 'azimuth' are refused" "$OUT/s.err")" -eq 2 ] &&
   ! grep -q '^sun ' "$OUT/s.err"; then t_ok angles_refused_with_clock
else t_fail angles_refused_with_clock "$(cat "$OUT/s.err")"; fi
offsets=$(grep '^clock .*source=stdin$' "$OUT/s.err" | sed 's/.* offset=\([^ ]*\) .*/\1/' | tr '\n' ' ')
if [ "$offsets" = "+90min +0min +30min " ]; then t_ok button_resets_and_detents_are_minutes
else t_fail button_resets_and_detents_are_minutes "offsets: $offsets"; fi

# Without --clock, 'offset' says what it needs and the sun stays.
printf 'offset 5\n' | $RUN --frames 2 >/dev/null 2>"$OUT/n.err"; rc=$?
if [ $rc -eq 0 ] && grep -q "^stdin: 'offset' needs --clock" "$OUT/n.err" && ! grep -q '^sun \|^clock ' "$OUT/n.err"; then
  t_ok offset_needs_clock
else t_fail offset_needs_clock "exit $rc: $(cat "$OUT/n.err")"; fi

# --time-scale 3600: about an hour of the clock shown a second. Two status commands 2 s apart, sent once the header is
# out (the display is open); each is answered at the next frame, so a clear sky keeps the frames (and the slack) short:
# a cloud's sun maps are redrawn every frame when the sun moves this fast.
TMPD=$(mktemp -d)
mkfifo "$TMPD/fifo"
$C run scenes/clear.scene --platform headless --size 32x24 --clock --time-scale 3600 $PARIS <"$TMPD/fifo" \
  >"$OUT/k.out" 2>"$OUT/k.err" &
pid=$!
exec 9>"$TMPD/fifo"
i=0; while [ $i -lt 100 ] && ! grep -q '^=====' "$OUT/k.out" 2>/dev/null; do sleep 0.1; i=$((i + 1)); done
sleep 0.5 # past the header's second '=====' line and the first frames
echo status >&9; sleep 2; echo status >&9; echo quit >&9
wait $pid; rc=$?
exec 9>&-
ta=$(epoch "$(field utc "$(grep '^status ' "$OUT/k.out" | sed -n 1p)")")
tb=$(epoch "$(field utc "$(grep '^status ' "$OUT/k.out" | sed -n 2p)")")
if [ $rc -eq 0 ] && [ -n "$ta" ] && [ -n "$tb" ] && [ $((tb - ta)) -ge 6300 ] && [ $((tb - ta)) -le 8100 ] &&
   grep -q 'time-scale=3600$' "$OUT/k.out"; then t_ok time_scale_3600_an_hour_a_second
else t_fail time_scale_3600_an_hour_a_second "exit $rc, $ta -> $tb: $(cat "$OUT/k.out" "$OUT/k.err" | tail -4)"; fi
rm -rf "$TMPD"

# Bad values: exit 2, one line naming the option, before any display opens.
t_expect bad_clock_offset 2 "cumulo run: --clock-offset expects seconds in -1e9..1e9, got 'soon'" -- \
  $RUN --clock --clock-offset soon
t_expect clock_offset_too_far 2 "cumulo run: --clock-offset expects seconds in -1e9..1e9, got '1e10'" -- \
  $RUN --clock --clock-offset 1e10
for k in 0 -1 2e6 nan 1x ""; do
  t_expect "bad_time_scale_'$k'" 2 "cumulo run: --time-scale expects a factor K with 0 < K <= 1e6, got '$k'" -- \
    $RUN --clock --time-scale "$k"
done
t_expect time_scale_needs_clock 2 "cumulo run: --time-scale needs --clock" -- $RUN --time-scale 60
t_expect clock_offset_needs_clock 2 "cumulo run: --clock-offset needs --clock" -- $RUN --clock-offset 60
t_expect clock_step_is_minutes 2 "cumulo run: --step expects a number in 0.001..1440, got '2000'" -- \
  $RUN --step 2000 --clock
t_summary
