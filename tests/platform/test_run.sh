# platform/test_run.sh: `cumulo run` end to end on this machine: headless run loop for N frames, stdin commands and
# the sun log lines, bad --input values, missing devices (DRM without /dev/dri, GPIO chip, evdev), SIGTERM.
. tests/lib.sh
C=build/cumulo
S=scenes/cumulus.scene
OUT=build/test-output/run
mkdir -p "$OUT"

# Headless loop: exactly N frames, header with GL strings and the surface, a glmark2-style summary line.
if $C run $S --platform headless --frames 5 --size 64x48 --no-stdin >"$OUT/h.out" 2>"$OUT/h.err"; then
  if grep -q '^\[run\] .*frames=5 FPS:' "$OUT/h.out" && grep -q 'GL_RENDERER:' "$OUT/h.out" &&
     grep -q 'GL_VERSION: *OpenGL ES 3' "$OUT/h.out" && grep -q 'Surface:' "$OUT/h.out"; then
    t_ok headless_five_frames
  else t_fail headless_five_frames "unexpected output: $(cat "$OUT/h.out")"; fi
else t_fail headless_five_frames "exit $?: $(cat "$OUT/h.err")"; fi

# stdin commands: each sun change is one machine-readable line; limits clamp; quit ends early with status 0.
printf 'sun 35 120\nturn 5\ntoggle\nturn -4\nel 95\naz -30\nstatus\nbogus 1\nquit\n' |
  $C run $S --platform headless --frames 1000 --size 64x48 --accel 0 >"$OUT/s.out" 2>"$OUT/s.err"
rc=$?
want='sun elevation=35.000 azimuth=120.000 source=stdin
sun elevation=35.000 azimuth=125.000 source=stdin
sun elevation=33.000 azimuth=125.000 source=stdin
sun elevation=33.000 azimuth=330.000 source=stdin'
got=$(grep '^sun ' "$OUT/s.err")
if [ $rc -eq 0 ] && [ "$got" = "$want" ]; then t_ok stdin_sun_log_lines
else t_fail stdin_sun_log_lines "exit $rc, got: $got"; fi
if grep -q "^stdin: 'el' needs one number of degrees in -90..90" "$OUT/s.err" &&
   grep -q "^stdin: unknown command 'bogus'" "$OUT/s.err"; then t_ok stdin_bad_command_messages
else t_fail stdin_bad_command_messages "$(cat "$OUT/s.err")"; fi
if grep -q '^status elevation=33.000 azimuth=330.000 knob=elevation' "$OUT/s.out" &&
   ! grep -q 'frames=1000 ' "$OUT/s.out"; then t_ok stdin_status_and_quit
else t_fail stdin_status_and_quit "$(cat "$OUT/s.out")"; fi

# Nothing moved, nothing redrawn: headless without --frames, a frame in which nothing changed is not drawn; a sun
# move draws one. The move is sent once the first frame is drawn (a status line says frames=1 or more: a sanitizer
# build starts slowly, so fixed sleeps race it), and quit once eight more turns of the loop have passed: two frames
# drawn (the first and the move's), while the loop goes on counting the frames it held.
frames_seen() { sed -n 's/^status .*frames=\([0-9]*\).*/\1/p' "$1" 2>/dev/null | tail -1; }
# feed_move OUT COMMAND: stdin for `cumulo run` writing its stdout to OUT
feed_move() {
  _n=0
  while [ "$(frames_seen "$1")" = "" ] || [ "$(frames_seen "$1")" -lt 1 ]; do
    printf 'status\n'; sleep 0.2; _n=$((_n + 1)); [ $_n -ge 300 ] && break
  done
  _f0=$(frames_seen "$1"); printf '%s\n' "$2"; _n=0
  while [ "$(frames_seen "$1")" -lt $((${_f0:-0} + 8)) ]; do
    printf 'status\n'; sleep 0.2; _n=$((_n + 1)); [ $_n -ge 300 ] && break
  done
  printf 'quit\n'
}
rm -f "$OUT/i.out"
feed_move "$OUT/i.out" 'sun 30 100' | $C run $S --platform headless --size 64x48 >"$OUT/i.out" 2>"$OUT/i.err"
rc=$?
f1=$(sed -n 's/^status .*frames=\([0-9]*\).*/\1/p' "$OUT/i.out" | head -1)
f2=$(sed -n 's/^status .*frames=\([0-9]*\).*/\1/p' "$OUT/i.out" | tail -1)
if [ $rc -eq 0 ] && grep -q '^\[run\] .* drawn=2$' "$OUT/i.out" && [ -n "$f1" ] && [ "$f2" -gt "$f1" ]; then
  t_ok idle_kiosk_draws_only_changes
else t_fail idle_kiosk_draws_only_changes "exit $rc, status frames $f1 then $f2: $(tail -1 "$OUT/i.out")"; fi

# ... and a temporal grid draws until the picture has settled: a sun move of 0.1 deg from the scene's 30, 135 (less
# than the 0.25 deg that redraws the grid whole) marches a quarter of the cloud pixels of a 2 x 2 grid, so the move
# takes 4 frames, not 1 (at most four of the eight turns after it draw).
rm -f "$OUT/g.out"
feed_move "$OUT/g.out" 'sun 30.1 135' |
  $C run $S --platform headless --size 64x48 --set quality.temporal_grid=2 >"$OUT/g.out" 2>"$OUT/g.err"
rc=$?
if [ $rc -eq 0 ] && grep -q '^\[run\] .* drawn=5$' "$OUT/g.out"; then t_ok idle_kiosk_grid_draws_until_settled
else t_fail idle_kiosk_grid_draws_until_settled "exit $rc: $(tail -1 "$OUT/g.out") $(tail -2 "$OUT/g.err")"; fi

# Limits from the command line.
printf 'sun 80 300\n' | $C run $S --platform headless --frames 3 --size 64x48 --sun-elevation-range 5:60 \
  --sun-azimuth-range 90:270 >/dev/null 2>"$OUT/l.err"
if grep -q '^sun elevation=60.000 azimuth=270.000 source=stdin' "$OUT/l.err"; then t_ok sun_limits
else t_fail sun_limits "$(cat "$OUT/l.err")"; fi

# Bad option values: exit 2, one line naming the option.
t_expect bad_input_kind 2 "--input 'joystick:0': unknown input kind" -- $C run $S --platform headless --input joystick:0
t_expect bad_input_gpio 2 "needs both 'a=' and 'b='" -- $C run $S --platform headless --input gpio:a=17
t_expect bad_input_key 2 "unknown key 'x'" -- $C run $S --platform headless --input gpio:a=1,b=2,x=3
t_expect bad_range 2 "--sun-elevation-range '60:5'" -- $C run $S --platform headless --sun-elevation-range 60:5
t_expect bad_platform 2 "no display back end 'vga'" -- $C run $S --platform vga
if $C run --help | grep -q 'back ends in this build:.* drm'; then
  t_expect bad_mode 2 "--mode '1920x'" -- $C run $S --platform drm --mode 1920x
else
  t_skip bad_mode "this cumulo was built without DRM"
fi
t_expect bad_set 2 "unknown key 'cloud.colour'" -- $C run $S --platform headless --no-stdin --frames 1 --set cloud.colour=1
out=$($C run --version 2>&1); case "$out" in "cumulo "*"inputs: stdin evdev"*) t_ok run_version ;; *) t_fail run_version "$out" ;; esac
for opt in --wait-display --platform --frames --fullscreen --mode --device --input --no-stdin --knob --step --accel --sun-elevation-range \
           --sun-azimuth-range --clock --clock-offset --time-scale --size --set --data-dir; do
  case "$($C run --help)" in *"$opt"*) ;; *) t_fail "run --help describes $opt" "missing"; continue ;; esac
done
t_ok "run --help describes every option"
t_expect bad_frames 2 "--frames expects a whole number" -- $C run $S --platform headless --frames 0
t_expect frames_blank 2 "--frames expects a whole number" -- $C run $S --platform headless --frames " 3"

# DRM on a machine without /dev/dri: non-zero and a message that says what to do.
if [ -e /dev/dri ]; then
  t_skip drm_without_dev_dri "this machine has /dev/dri"
else
  t_expect drm_without_dev_dri 1 "drm: no DRM device: /dev/dri does not exist" -- \
    $C run $S --platform drm --frames 1 --no-stdin
fi
t_expect drm_missing_device 1 "drm: cannot open /nonexistent/card9" -- \
  $C run $S --platform drm --device /nonexistent/card9 --frames 1 --no-stdin
# At boot the KMS driver can come after the kiosk: --wait-display retries, bounded, then fails as without it.
t0=$(date +%s)
$C run $S --platform drm --device /nonexistent/card9 --frames 1 --no-stdin --wait-display 2 >/dev/null 2>"$OUT/wait.err"
rc=$?; t1=$(date +%s)
if [ $rc -eq 1 ] && [ $((t1 - t0)) -ge 2 ] && [ $((t1 - t0)) -le 10 ] &&
   grep -q "^cumulo: drm: cannot open /nonexistent/card9.*; retrying for up to 2 s" "$OUT/wait.err" &&
   grep -q "^cumulo: drm: cannot open /nonexistent/card9" "$OUT/wait.err"; then t_ok drm_wait_display_bounded
else t_fail drm_wait_display_bounded "exit $rc after $((t1 - t0)) s: $(cat "$OUT/wait.err")"; fi
t_expect bad_wait_display 2 "--wait-display expects" -- $C run $S --platform headless --wait-display 99999999999999999999

# A missing GPIO chip / evdev device: one line naming it and a warning; the sky still runs its frames and exits 0, with
# no input at all (a kiosk unit that exited here would restart into the same missing device forever).
for case in "gpio_missing_chip|gpio:chip=/nonexistent/gpiochip77,a=17,b=27|gpio: no GPIO chip '/nonexistent/gpiochip77'" \
            "evdev_missing|evdev:/dev/input/event99|evdev: /dev/input/event99: no such device"; do
  name=${case%%|*}; rest=${case#*|}; spec=${rest%%|*}; want=${rest#*|}
  $C run $S --platform headless --frames 3 --size 32x24 --no-stdin --input "$spec" >"$OUT/$name.out" 2>"$OUT/$name.err"
  rc=$?
  if [ $rc -eq 0 ] && grep -qF "$want" "$OUT/$name.err" &&
     grep -q "^cumulo: warning: none of the 1 requested inputs could be opened (see above); the sky keeps running with no input" "$OUT/$name.err" &&
     grep -q '^\[run\] .*frames=3 ' "$OUT/$name.out"; then t_ok "${name}_runs_without_input"
  else t_fail "${name}_runs_without_input" "exit $rc: $(cat "$OUT/$name.err" "$OUT/$name.out" | tail -4)"; fi
done
# The kiosk unit's own command, on the headless back end for 2 frames: where its GPIO chip is missing (as here) it
# still shows the sky and exits 0; and the unit waits for what it needs without systemd-udev-settle.
U=scripts/cumulo-kiosk.service.in
cmd=$(sed -n '/^ExecStart=/,/[^\\]$/p' $U | sed 's/^ExecStart=//; s/\\$//' | tr '\n' ' ' |
      sed "s|@BINDIR@/cumulo|$C|; s|@DATADIR@/scenes|scenes|; s|--platform drm|--platform headless|")
# shellcheck disable=SC2086
$cmd --frames 2 --size 32x24 >"$OUT/unit.out" 2>"$OUT/unit.err"; rc=$?
if [ $rc -eq 0 ] && grep -q 'frames=2 ' "$OUT/unit.out"; then t_ok kiosk_unit_command_runs_without_its_devices
else t_fail kiosk_unit_command_runs_without_its_devices "exit $rc ($cmd): $(tail -3 "$OUT/unit.err")"; fi
if ! grep -Eq '^(Wants|Requires|After)=.*udev-settle' $U && grep -q -- '--wait-display [1-9]' $U && grep -q '^ExecStartPre=-.*udevadm wait' $U; then
  t_ok kiosk_unit_waits_without_udev_settle
else t_fail kiosk_unit_waits_without_udev_settle "$(grep -n 'udev\|wait' $U)"; fi
# ...but with another input left the program continues.
out=$(printf 'sun 10 10\n' | $C run $S --platform headless --frames 3 --size 64x48 \
      --input gpio:chip=gpiochip77,a=17,b=27 --input stdin 2>&1 >/dev/null); rc=$?
case "$out" in
  *"gpio: no GPIO chip 'gpiochip77'"*"sun elevation=10.000 azimuth=10.000 source=stdin"*)
    [ $rc -eq 0 ] && t_ok missing_gpio_continues_with_stdin || t_fail missing_gpio_continues_with_stdin "exit $rc" ;;
  *) t_fail missing_gpio_continues_with_stdin "$out" ;;
esac

# SIGTERM: a clean stop (status 0) through the same path that restores the CRTC on DRM.
TMPD=$(mktemp -d)   # private: two `make check` runs on one tree must not share a pipe or an X display
mkfifo "$TMPD/fifo"
$C run $S --platform headless --size 64x48 <"$TMPD/fifo" >"$OUT/t.out" 2>"$OUT/t.err" &
pid=$!
exec 9>"$TMPD/fifo"
sleep 2
kill -TERM $pid
wait $pid; rc=$?
exec 9>&-
if [ $rc -eq 0 ] && grep -q 'terminated, stopping' "$OUT/t.err" && grep -q '^\[run\]' "$OUT/t.out"; then
  t_ok sigterm_clean_exit
else t_fail sigterm_clean_exit "exit $rc: $(cat "$OUT/t.err")"; fi

# The X11 window back end, where an X server can be started here (Xvfb; not a dependency: skipped without it).
if DISPLAY= $C run $S --platform x11 --no-stdin --frames 1 2>&1 | grep -q "no display back end 'x11'"; then
  t_skip x11_window "this cumulo was built without X11 (libx11-dev missing)"
elif ! command -v Xvfb >/dev/null 2>&1; then
  t_skip x11_window "no Xvfb to start a virtual X server (apt-get install xvfb)"
else
  # -displayfd: the server picks a free display number and writes it, so parallel runs do not collide.
  Xvfb -displayfd 5 -screen 0 320x240x24 -nolisten tcp 5>"$TMPD/display" >"$OUT/xvfb.log" 2>&1 &
  xpid=$!
  i=0; while [ $i -lt 50 ] && [ ! -s "$TMPD/display" ]; do sleep 0.1; i=$((i + 1)); done
  XD=:$(cat "$TMPD/display")
  if DISPLAY=$XD $C run $S --platform x11 --frames 3 --size 160x120 --no-stdin >"$OUT/x.out" 2>"$OUT/x.err" &&
     grep -q 'Surface: *EGL .*160x120 window on X11' "$OUT/x.out" && grep -q 'frames=3 ' "$OUT/x.out"; then
    t_ok x11_window
  else t_fail x11_window "$(cat "$OUT/x.err" "$OUT/x.out" | tail -3)"; fi
  # A GLES-2-only device (Mesa capped at ES 2.0): one line saying so and what the device offers.
  t_expect gles2_only_device 1 "the device offers 'OpenGL ES 2.0" -- \
    env DISPLAY=$XD MESA_GLES_VERSION_OVERRIDE=2.0 $C run $S --platform x11 --frames 1 --no-stdin
  kill $xpid 2>/dev/null; wait $xpid 2>/dev/null
fi

# The Wayland window back end, on a headless Weston where one can be started here (not a dependency).
if WAYLAND_DISPLAY= XDG_RUNTIME_DIR= $C run $S --platform wayland --no-stdin --frames 1 2>&1 |
   grep -q "no display back end 'wayland'"; then
  t_skip wayland_window "this cumulo was built without Wayland (libwayland-dev, wayland-protocols missing)"
elif ! command -v weston >/dev/null 2>&1; then
  t_skip wayland_window "no weston to start a headless compositor (apt-get install weston)"
else
  rt=$(mktemp -d)
  XDG_RUNTIME_DIR=$rt weston --backend=headless-backend.so --socket=wl-test --width=320 --height=240 \
    --idle-time=0 >"$OUT/weston.log" 2>&1 &
  wpid=$!
  i=0; while [ $i -lt 50 ] && [ ! -S "$rt/wl-test" ]; do sleep 0.1; i=$((i + 1)); done
  if XDG_RUNTIME_DIR=$rt WAYLAND_DISPLAY=wl-test $C run $S --platform wayland --frames 3 --size 160x120 --no-stdin \
       >"$OUT/w.out" 2>"$OUT/w.err" && grep -q 'Surface: *EGL .*160x120 window on Wayland' "$OUT/w.out"; then
    t_ok wayland_window
  else t_fail wayland_window "$(cat "$OUT/w.err" "$OUT/w.out" | tail -3)"; fi
  kill $wpid 2>/dev/null; wait $wpid 2>/dev/null
  rm -rf "$rt"
fi

rm -rf "$TMPD"
t_summary
