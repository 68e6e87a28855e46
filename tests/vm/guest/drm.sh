# tests/vm/guest/drm.sh (in the VM): the kiosk path (DRM/KMS + GBM + EGL) on vkms, a real KMS driver with a virtual
# connector. Independent witnesses, not cumulo's own word: the kernel's drm_vblank_event_delivered tracepoint counts
# the page-flip events delivered, tests/vm/vm_kms.c shows a pattern on the CRTC first (as a console would) and
# checks it is back after the run, and reads the scanned-out buffer to compare with the headless render.
. tests/lib.sh
. tests/vm/guest/lib.sh
TR=/sys/kernel/tracing
# On a real machine (tests/vm/README.md): the card cumulo should probe, its connector and driver.
CARD=${VM_DRM_CARD:-/dev/dri/card0}
CONN=${VM_DRM_CONNECTOR:-Virtual-1}
DRIVER=${VM_DRM_DRIVER:-vkms}
MODE=${VM_DRM_MODE:-640x480}
if [ -c $CARD ] && $H/vm_kms info $CARD >$OUT/kms-info.txt 2>&1 && grep -q "^driver=$DRIVER " $OUT/kms-info.txt; then
  t_ok drm_vkms_present
else t_fail drm_vkms_present "$(ls -l /dev/dri 2>&1; cat $OUT/kms-info.txt)"; t_summary; exit 1; fi
cat $OUT/kms-info.txt

# Only events sent to a client count: the atomic helpers also complete their internal commits (mode sets, the
# restore) with an event of their own that has no file, filtered out in the kernel.
flips_reset() {
  echo 'file != 0' >$TR/events/drm/drm_vblank_event_delivered/filter
  echo 1 >$TR/events/drm/drm_vblank_event_delivered/enable
  echo >$TR/trace
}
flips() { grep -c 'drm_vblank_event_delivered:' $TR/trace; }

# hold_start: a pattern on the screen, master dropped; hold_check NAME: did the run put it back?
hold_start() {
  rm -f $F/hold.fifo; mkfifo $F/hold.fifo
  $H/vm_kms hold $CARD <$F/hold.fifo >$OUT/hold.out 2>&1 &
  holdpid=$!
  exec 7>$F/hold.fifo
  wait_for $OUT/hold.out '^holding ' 30 || echo "drm: vm_kms hold did not start: $(cat $OUT/hold.out)"
}
hold_check() {
  exec 7>&-
  wait $holdpid
  if grep -q '^restored ' $OUT/hold.out; then t_ok "$1"; else t_fail "$1" "$(cat $OUT/hold.out)"; fi
}

# kiosk RUN_NAME MODESETTING [env...]: NF frames through the back end, flips counted by the kernel. Few frames, and
# cheap settings: under emulation a 640x480 frame of llvmpipe at the default settings takes about two minutes, and
# what is tested here is the display path, not the shading (the headless render below uses the same settings). The
# low preset with the octaves' multiple scattering, 2 segments and hull tessellation 6 (low before 2026-12-06): the
# diffusion grids of today's low are solved again over several frames after the sun turns, drawing frames the
# flip counts below do not expect, and their solves are slow under emulation. VM_DRM_QUALITY: space-separated keys.
NF=${VM_DRM_FRAMES:-4}
Q=${VM_DRM_QUALITY:-quality.preset=low ms.mode=octaves quality.segments=2 quality.hull_tessellation=6}
QS=$(for q in $Q; do printf ' --set %s' "$q"; done)
kiosk() {
  name=$1; how=$2; shift 2
  hold_start
  flips_reset
  t=$(elapsed)
  env "$@" $C run $S --platform drm --mode $MODE --frames $NF --no-stdin $QS >$OUT/$name.out 2>$OUT/$name.err
  rc=$?
  n=$(flips)
  cp $TR/trace $OUT/$name.trace
  echo "drm: $name: exit $rc, $n flip events, $(awk -v a="$t" -v b="$(elapsed)" 'BEGIN { printf "%.1f", b - a }') s"
  cat $OUT/$name.out $OUT/$name.err
  if [ $rc -eq 0 ] && grep -q "^    Surface: .* $MODE@[0-9.]* fullscreen on $CONN via $CARD ($how modesetting)" \
       $OUT/$name.out && grep -q "^\[run\] .*frames=$NF " $OUT/$name.out; then t_ok ${name}_renders_${NF}_frames
  else t_fail ${name}_renders_${NF}_frames "exit $rc: $(tail -2 $OUT/$name.err)"; fi
  # The first frame sets the mode (a blocking commit, no event); each of the others is a flip with an event.
  if [ "$n" -eq $((NF - 1)) ]; then t_ok ${name}_$((NF - 1))_page_flips_counted_by_kernel
  else t_fail ${name}_$((NF - 1))_page_flips_counted_by_kernel "kernel delivered $n flip events, expected $((NF - 1))"; fi
  hold_check ${name}_crtc_restored
}
kiosk drm_atomic atomic
kiosk drm_legacy legacy CUMULO_DRM_LEGACY=1

# SIGTERM mid-run while the sun is turned, with a look at the screen first. Without --frames the kiosk draws only when
# something changed (an idle kiosk leaves its last flip on screen): the first frame sets the mode (no event), then
# nothing is drawn until a sun command comes on stdin; two of them (away and back) each draw a frame, a flip the
# kernel counts, and the screen ends with the scene's own sun, compared below with the headless render.
hold_start
flips_reset
rm -f $F/term.fifo; mkfifo $F/term.fifo
$C run $S --platform drm --mode $MODE $QS <$F/term.fifo >$OUT/term.out 2>$OUT/term.err &
pid=$!
exec 6>$F/term.fifo
# wait_flips N SECONDS: 0 once the kernel delivered N flip events to a client.
wait_flips() {
  _end=$(( $(now) + $2 ))
  while [ "$(now)" -le $_end ] && [ "$(flips)" -lt "$1" ] && kill -0 $pid 2>/dev/null; do sleep 0.5; done
  [ "$(flips)" -ge "$1" ]
}
# The first frame is on screen once the loop answers `status` past it (frames counts presented frames).
end=$(( $(now) + 600 ))
while [ "$(now)" -le $end ] && kill -0 $pid 2>/dev/null && ! grep -q '^status .* frames=[1-9]' $OUT/term.out; do
  echo status >&6; sleep 5
done
echo "drm: first frame of the idle kiosk after $(elapsed) s"
sleep 3  # an idle kiosk: nothing changed, so nothing is drawn and nothing flips
n=$(flips)
if grep -q '^status .* frames=[1-9]' $OUT/term.out && [ "$n" -eq 0 ]; then t_ok drm_idle_kiosk_flips_nothing
else t_fail drm_idle_kiosk_flips_nothing "$n flip events with nothing changed; $(tail -1 $OUT/term.out)"; fi
echo "azimuth 140" >&6
wait_flips 1 600
echo "azimuth 135" >&6
wait_flips 2 600
$H/vm_kms snap $OUT/screen.ppm $CARD
snap=$?
kill -TERM $pid
wait $pid; rc=$?
exec 6>&-
cat $OUT/term.err
n=$(flips)
if [ $rc -eq 0 ] && grep -q 'terminated, stopping' $OUT/term.err && grep -q '^\[run\] .* drawn=3$' $OUT/term.out &&
   [ "$n" -eq 2 ]
then t_ok drm_sigterm_mid_run_clean_exit
else t_fail drm_sigterm_mid_run_clean_exit "exit $rc after $n flips: $(tail -1 $OUT/term.out) $(tail -2 $OUT/term.err)"; fi
hold_check drm_sigterm_crtc_restored

t=$(elapsed)
$C render $S --size $MODE $QS -o $OUT/headless.png >$OUT/render.out 2>&1 || cat $OUT/render.out
echo "drm: headless render took $(awk -v a="$t" -v b="$(elapsed)" 'BEGIN { printf "%.1f", b - a }') s"
if [ $snap -eq 0 ] && $H/vm_kms compare $OUT/screen.ppm $OUT/headless.png 1.5 0.005 >$OUT/compare.txt; then
  t_ok drm_screen_matches_headless_render
else t_fail drm_screen_matches_headless_render "$(cat $OUT/compare.txt)"; fi
cat $OUT/compare.txt

# No kernel warning or oops from the driver while we used it.
dmesg_bad=$(dmesg 2>/dev/null | grep -E 'WARNING|BUG|Oops|vkms.*error' | head -3)
if [ -z "$dmesg_bad" ]; then t_ok drm_no_kernel_warnings; else t_fail drm_no_kernel_warnings "$dmesg_bad"; fi
t_summary
