# platform/test_soak.sh: kiosk soak: `cumulo run` headless for N frames (default 10 000, CUMULO_SOAK_FRAMES to change)
# at 64x48 while the sun moves from stdin every 200 ms; the resident set must not grow after warm-up (leaks in the
# frame loop or in the sun pass would show here long before months on a wall).
. tests/lib.sh
C=build/cumulo
N=${CUMULO_SOAK_FRAMES:-10000}
LIMIT_KB=${CUMULO_SOAK_RSS_KB:-3072}
OUT=build/test-output/soak
mkdir -p "$OUT"
# The command pipe lives in a private directory: two `make check` runs on one tree must not share it.
FIFO_DIR=$(mktemp -d) || { t_fail soak "mktemp -d failed"; t_summary; exit 1; }
FIFO=$FIFO_DIR/commands
mkfifo "$FIFO" || { t_fail soak "cannot make a fifo in $FIFO_DIR"; t_summary; exit 1; }

# A 64-texel sun map: every sun command redoes the sun's opacity pass, whose cost grows with the map's area; the
# code paths (and any leak in them) are the same at any size, and the run must fit in make check.
$C run scenes/cumulus.scene --platform headless --frames "$N" --size 64x48 --set quality.sun_map_size=64 <"$FIFO" >"$OUT/run.out" 2>"$OUT/run.err" &
pid=$!
# The sun walks around the sky and up and down, one command per 200 ms (each costs a sun pass), while it runs; the
# first 20 commands of each 120 turn it a degree of azimuth at a time (0.87 degrees at 30 degrees up: a creep, whose
# maps are made a band a frame into spares, quality.sun_map_frames), the rest jump (maps made whole at once).
(
  i=0
  while kill -0 $pid 2>/dev/null; do
    if [ $((i % 120)) -lt 20 ]; then echo "sun 30 $((100 + i % 120))"
    else echo "sun $(( (i % 120) - 20 )) $(( (i * 7) % 360 ))"; fi
    i=$((i + 1))
    sleep 0.2
  done
) >"$FIFO" 2>/dev/null &
gen=$!

samples=""
while kill -0 $pid 2>/dev/null; do
  kb=$(awk '/^VmRSS:/ {print $2}' /proc/$pid/status 2>/dev/null)
  [ -n "$kb" ] && samples="$samples $kb"
  sleep 2
done
wait $pid; rc=$?
kill $gen 2>/dev/null; wait $gen 2>/dev/null
rm -rf "$FIFO_DIR"
echo "RSS samples (kB):$samples" >"$OUT/rss.txt"

set -- $samples
count=$#
if [ $rc -ne 0 ]; then
  t_fail soak_runs "exit $rc: $(tail -3 "$OUT/run.err")"
elif ! grep -q "^\[run\] .*frames=$N FPS:" "$OUT/run.out"; then
  t_fail soak_runs "did not render $N frames: $(tail -2 "$OUT/run.out")"
else
  t_ok soak_runs
fi
changes=$(grep -c '^sun elevation=' "$OUT/run.err")
[ "$changes" -gt 10 ] && t_ok soak_sun_changes || t_fail soak_sun_changes "only $changes sun changes logged"
if [ "$count" -lt 4 ]; then
  t_skip soak_rss_growth "run too short for RSS samples ($count); raise CUMULO_SOAK_FRAMES"
else
  # Baseline after a quarter of the run (allocators and the driver's caches warmed up), against the last sample.
  base=$(echo $samples | awk '{print $(int(NF / 4) + 1)}')
  last=$(echo $samples | awk '{print $NF}')
  growth=$((last - base))
  echo "soak: $N frames, $changes sun changes, RSS $base kB -> $last kB (growth $growth kB, limit $LIMIT_KB kB)"
  [ "$growth" -le "$LIMIT_KB" ] && t_ok soak_rss_growth || t_fail soak_rss_growth "RSS grew $growth kB ($base -> $last)"
fi
t_summary
