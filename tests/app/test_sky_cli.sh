# tests/app/test_sky_cli.sh: the living sky from the command line: `cumulo expand` writes a scene's layers as
# [cloud] sections that render bit for bit as the layers do (at two times), render sequences and --time, a clear sky,
# and clear errors for bad sequences, oversized expansions and scenes the path tracer cannot render.
. tests/lib.sh
C=${CUMULO:-build/cumulo}
T=build/test-output/sky_cli
mkdir -p "$T"
rm -f "$T"/*.png "$T"/*.pfm

# a small layer, wind and life cycle on
cat > "$T/layer.scene" <<'S'
[camera]
position = 0 300 -2500
look_at = 0 900 0
fov = 60
[sun]
elevation = 40
azimuth = 150
[layer]
type = cumulus-humilis
base = 700
thickness = 400
coverage = 0.3
extent = 3000
seed = 4
wind = 12 3
lifetime = 200
S
if $C expand "$T/layer.scene" -o "$T/expanded.scene" 2>"$T/err" &&
   n=$(grep -c '^\[cloud\]' "$T/expanded.scene") && [ "$n" -gt 5 ] && ! grep -q '^\[layer\]' "$T/expanded.scene"; then
  t_ok "expand writes $n [cloud] sections and no [layer]"
else t_fail "expand" "$(cat "$T/err")"; fi
same=1
for t in 0 137; do
  $C render "$T/layer.scene" -o "$T/a$t.pfm" --size 64x48 --time $t >/dev/null 2>"$T/err" &&
  $C render "$T/expanded.scene" -o "$T/b$t.pfm" --size 64x48 --time $t >/dev/null 2>>"$T/err" &&
  cmp -s "$T/a$t.pfm" "$T/b$t.pfm" || same=0
done
if [ $same -eq 1 ]; then t_ok "the expanded scene renders as the layer, bit for bit, at t = 0 and 137 s"
else t_fail "expanded render" "$(cat "$T/err")"; fi
if ! cmp -s "$T/a0.pfm" "$T/a137.pfm"; then t_ok "the sky changes with --time"
else t_fail "--time" "the frames at 0 and 137 s are identical"; fi
# --time is --set scene.time
$C render "$T/layer.scene" -o "$T/c137.pfm" --size 64x48 --set scene.time=137 >/dev/null 2>&1
if cmp -s "$T/a137.pfm" "$T/c137.pfm"; then t_ok "--time T equals --set scene.time=T"
else t_fail "--time" "differs from --set scene.time"; fi

# sequences
if out=$($C render "$T/layer.scene" -o "$T/f%03d.png" --size 32x24 --frames 3 --fps 0.5 2>&1) &&
   [ -s "$T/f000.png" ] && [ -s "$T/f001.png" ] && [ -s "$T/f002.png" ] && [ ! -e "$T/f003.png" ]; then
  case "$out" in *"wrote 3 frames"*"scene time 0 .. 4 s"*) t_ok "a sequence of 3 frames at 0.5 fps" ;;
    *) t_fail "sequence" "$out" ;; esac
else t_fail "sequence" "$out"; fi
out=$($C render "$T/layer.scene" -o "$T/p%d.png" --size 16x12 --frames 2 --progress 2>&1 >/dev/null)
case "$out" in *"2/2 frames"*) t_ok "--progress draws the bar" ;; *) t_fail "--progress" "$out" ;; esac
t_expect "sequence without %d" 2 "needs exactly one %d" -- $C render "$T/layer.scene" -o "$T/x.png" --frames 2
t_expect "sequence with %s" 2 "needs exactly one %d" -- $C render "$T/layer.scene" -o "$T/x%s%d.png" --frames 2
t_expect "sequence with two %d" 2 "needs exactly one %d" -- $C render "$T/layer.scene" -o "$T/x%d%d.png" --frames 2
t_expect "bad --frames" 2 "--frames expects 1..1000000" -- $C render "$T/layer.scene" -o "$T/x%d.png" --frames 0
t_expect "bad --fps" 2 "--fps expects a number" -- $C render "$T/layer.scene" -o "$T/x%d.png" --frames 2 --fps -1
t_expect "bad --time" 2 "'time' is NaN" -- $C render "$T/layer.scene" -o "$T/x.png" --time nan
t_expect "huge --time" 2 "'time' must be in" -- $C render "$T/layer.scene" -o "$T/x.png" --time 1e12

# a clear sky
printf '[camera]\nposition = 0 2 0\nlook_at = 0 300 -1000\n[sun]\nelevation = 20\n' > "$T/clear.scene"
if $C render "$T/clear.scene" -o "$T/clear.png" --size 32x24 >/dev/null 2>"$T/err"; then t_ok "a clear sky renders"
else t_fail "clear sky" "$(cat "$T/err")"; fi

# expansions that do not fit a file, and what the path tracer refuses
sed 's/extent = 3000/extent = 60000/' "$T/layer.scene" > "$T/big.scene"
t_expect "expand beyond a file's limits" 1 "a file holds at most 1024 clouds" -- $C expand "$T/big.scene" -o "$T/x.scene"
t_expect "expand to an unwritable file" 1 "cannot write /nonexistent/d/x.scene" -- $C expand "$T/layer.scene" -o /nonexistent/d/x.scene
t_expect "expand without a scene" 2 "usage: cumulo expand" -- $C expand
if [ -x build/cumulo-pt ]; then
  t_expect "the path tracer refuses a field" 1 "the path tracer renders one cloud" -- build/cumulo-pt "$T/layer.scene" -o "$T/x.pfm"
fi
t_summary
