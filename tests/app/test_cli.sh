# tests/app/test_cli.sh: the cumulo program end to end: renders to PNG and PFM, bench output format, and clear errors with
# the right exit status for bad scenes, bad options and bad values. Run from the repository root.
. tests/lib.sh
C=${CUMULO:-build/cumulo}
T=build/test-output/cli
mkdir -p "$T"

if $C render scenes/cumulus.scene -o "$T/a.png" --size 64x48 >/dev/null 2>"$T/err" && [ -s "$T/a.png" ] &&
   [ "$(head -c 8 "$T/a.png" | od -An -c | tr -d ' \n')" = "211PNG\r\n032\n" ]; then
  t_ok "render PNG"
else t_fail "render PNG" "$(cat "$T/err")"; fi

if $C render scenes/cumulus.scene -o "$T/a.pfm" --size 64x48 --backend osmesa >/dev/null 2>"$T/err" &&
   [ "$(head -c 2 "$T/a.pfm")" = "PF" ] && [ "$(wc -c < "$T/a.pfm")" -ge $((64 * 48 * 12)) ]; then
  t_ok "render PFM through OSMesa"
else t_fail "render PFM through OSMesa" "$(cat "$T/err")"; fi

out=$($C bench scenes/cumulus.scene --frames 3 --warmup 1 --size 64x48 --set quality.segments=2 2>&1)
case "$out" in
  *"GL_RENDERER:"*"[cumulus.scene] size=64x48:quality.segments=2: FPS: "*" FrameTime: "*" ms p95: "*" ms mean: "*" ms frames: 3"*)
    t_ok "bench output" ;;
  *) t_fail "bench output" "$out" ;;
esac
out=$($C bench scenes/cumulus.scene --frames 3 --warmup 0 --size 32x24 --camera both --orbit-step 30 2>&1)
case "$out" in
  *"camera=orbit:orbit-step=30: FPS: "*"camera=orbit:orbit-step=30:unmoved: FPS: "*"moving/unmoved median frame time: "*)
    t_ok "bench --camera both output" ;;
  *) t_fail "bench --camera both output" "$out" ;;
esac
# --passes: every pass timed (llvmpipe: by the wall clock, glFinish between them); the clouds take time, the upsample
# only with a downsample, the sky by itself only without one (with one the sky pass composites the clouds and its time
# is the upsample's), and the passes' medians do not exceed the frame's by more than the clock's noise.
for n in 1 2; do
  out=$($C bench scenes/cumulus.scene --frames 3 --warmup 1 --size 96x72 --passes --set quality.cloud_downsample=$n 2>&1)
  line=$(printf '%s\n' "$out" | grep ': passes (median ms, wall clock, glFinish between passes): maps=')
  frame=$(printf '%s\n' "$out" | sed -n 's/.* FrameTime: \([0-9.]*\) ms.*/\1/p')
  if printf '%s\n' "$line" | awk -v n=$n -v fr="$frame" '{ for (i = 1; i <= NF; i++) if (split($i, kv, "=") == 2) { v[kv[1]] = kv[2]; sum += kv[2] } }
      END { ok = v["clouds"] > 0 && v["tonemap"] >= 0 && (n == 1 ? v["upsample"] == 0 && v["sky"] > 0 : v["upsample"] > 0)
            exit !(ok && sum <= 1.05 * fr + 0.5) }'; then t_ok "bench --passes, downsample $n"
  else t_fail "bench --passes, downsample $n" "frame $frame ms: $line"; fi
done
t_expect "bench bad camera" 2 "--camera expects static, orbit or both" -- $C bench scenes/cumulus.scene --camera spin
# --sun-blocks: the sun turned for 6 frames and held for 6, in turn; every turning frame counts, and of the held ones
# only those drawn once the picture had settled (the maps made again over 4 frames finish in the first held ones).
out=$($C bench scenes/cumulus.scene --frames 24 --warmup 0 --size 48x32 --sun-step 0.6 --sun-blocks 6 2>&1)
held=$(printf '%s\n' "$out" | sed -n 's/.*sun-step=0.6:sun-blocks=6: turning: mean [0-9.]* ms (12 frames) held: mean [0-9.]* ms (\([0-9]*\) settled frames)$/\1/p')
if [ -n "$held" ] && [ "$held" -gt 0 ] && [ "$held" -lt 12 ] &&
   printf '%s\n' "$out" | grep -q '^turning/held mean frame time: [0-9.]* (blocks of 6 frames, interleaved)$'; then
  t_ok "bench --sun-blocks output"
else t_fail "bench --sun-blocks output" "$out"; fi
t_expect "bench sun blocks without a sun" 2 "--sun-blocks needs --sun-every-frame or --sun-step" -- $C bench scenes/cumulus.scene --sun-blocks 4
t_expect "bench bad sun blocks" 2 "--sun-blocks expects a count" -- $C bench scenes/cumulus.scene --sun-step 1 --sun-blocks 0
# a held frame right after a turning one: the maps still being made again, so no held frame counts
t_expect "bench sun blocks that never settle" 1 "the picture never settled in a held block" -- $C bench scenes/cumulus.scene --frames 2 --warmup 2 --size 16x12 --sun-step 0.6 --sun-blocks 1

printf '[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 nan 1\n' > "$T/bad.scene"
t_expect "bad scene value" 1 "$T/bad.scene:8:9: 'radii' is NaN" -- $C render "$T/bad.scene" -o "$T/x.png"
head -c 300 /dev/urandom > "$T/garbage.scene"; printf '\000' >> "$T/garbage.scene"
t_expect "binary garbage" 1 "not a text file" -- $C render "$T/garbage.scene" -o "$T/x.png"
: > "$T/empty.scene"
t_expect "empty scene" 1 "$T/empty.scene:1:1: empty scene file" -- $C render "$T/empty.scene" -o "$T/x.png"
t_expect "missing scene" 1 "nope.scene: cannot open" -- $C render nope.scene -o "$T/x.png"
t_expect "bad --set key" 2 "unknown key 'cloud.colour'" -- $C render scenes/cumulus.scene -o "$T/x.png" --set cloud.colour=1
t_expect "bad --set value" 2 "'radii' must be in [0.1, 100000] m, got -5" -- $C render scenes/cumulus.scene -o "$T/x.png" --set "ellipsoid.1.radii=1 -5 1"
t_expect "bad --size" 2 "--size expects WxH" -- $C render scenes/cumulus.scene -o "$T/x.png" --size 0x10
t_expect "bad output type" 2 "must end in .png or .pfm" -- $C render scenes/cumulus.scene -o "$T/x.jpg"
t_expect "unknown back end" 2 "unknown back end 'vulkan'" -- $C render scenes/cumulus.scene -o "$T/x.png" --backend vulkan
t_expect "missing -o value" 2 "-o needs a value" -- $C render scenes/cumulus.scene -o
t_expect "unknown render option" 2 "unknown option '--colour'" -- $C render scenes/cumulus.scene --colour
t_expect "size overflow" 2 "--size expects WxH" -- $C render scenes/cumulus.scene -o "$T/x.png" --size 4294967360x48
t_expect "bench unwritable csv" 1 "cannot write /nonexistent/d/x.csv" -- $C bench scenes/cumulus.scene --frames 1 --warmup 0 --size 8x8 --csv /nonexistent/d/x.csv
# --help and --version: stdout, exit 0, every option of the subcommand described.
for sub in "" render bench run; do
  out=$($C $sub --help 2>&1); rc=$?
  if [ $rc -eq 0 ] && [ -n "$out" ]; then t_ok "cumulo $sub --help"; else t_fail "cumulo $sub --help" "exit $rc: $out"; fi
done
for opt in --output --size --backend --set --data-dir --verbose; do
  case "$($C render --help)" in *"$opt"*) t_ok "render --help describes $opt" ;; *) t_fail "render --help describes $opt" "missing" ;; esac
done
for opt in --frames --warmup --csv --sun-every-frame --sun-step --sun-blocks --camera --orbit-step; do
  case "$($C bench --help)" in *"$opt"*) t_ok "bench --help describes $opt" ;; *) t_fail "bench --help describes $opt" "missing" ;; esac
done
v=$($C --version); rc=$?
case "$v" in "cumulo "*"display back ends: headless egl"*"inputs: stdin evdev"*) [ $rc -eq 0 ] && t_ok "cumulo --version" || t_fail "cumulo --version" "exit $rc" ;;
  *) t_fail "cumulo --version" "$v" ;; esac
# The tables come from the build tree's data/ when run from it, whatever the working directory.
if (cd / && env -u CUMULO_DATA_DIR "$OLDPWD/$C" render "$OLDPWD/scenes/cumulus.scene" --size 8x8 -o "$OLDPWD/$T/cwd.png" >/dev/null 2>"$OLDPWD/$T/cwd.err"); then
  t_ok "build-tree data found from another directory"
else t_fail "build-tree data found from another directory" "$(cat "$T/cwd.err")"; fi
t_expect "bad --data-dir" 1 "/nonexistent-data/mie_cloud.tbl" -- $C render scenes/cumulus.scene --size 8x8 -o "$T/x.png" --data-dir /nonexistent-data
# A full disk is an error, not "wrote" (/dev/full fails every write with ENOSPC).
ln -sf /dev/full "$T/full.png"; ln -sf /dev/full "$T/full.pfm"
t_expect "PNG onto a full disk" 1 "No space left on device" -- $C render scenes/cumulus.scene --size 8x8 -o "$T/full.png"
t_expect "PFM onto a full disk" 1 "write failed" -- $C render scenes/cumulus.scene --size 8x8 -o "$T/full.pfm"
t_expect "unknown command" 2 "unknown command 'paint'" -- $C paint
t_expect "bench bad frames" 2 "--frames expects a count" -- $C bench scenes/cumulus.scene --frames -3
# Counts are digits only and never wrap: strtol took " 5" and "+5"; --size must not wrap through an int either.
t_expect "bench frames with a blank" 2 "--frames expects a count" -- $C bench scenes/cumulus.scene --frames " 5"
t_expect "bench warmup with a sign" 2 "--warmup expects a count" -- $C bench scenes/cumulus.scene --warmup +1
t_expect "bench frames overflow" 2 "--frames expects a count" -- $C bench scenes/cumulus.scene --frames 18446744073709551617
t_expect "size with a sign" 2 "--size expects WxH" -- $C render scenes/cumulus.scene -o "$T/x.png" --size +8x8
ln -sf /dev/full "$T/full.csv"
t_expect "bench csv onto a full disk" 1 "cannot write $T/full.csv: No space left on device" -- $C bench scenes/cumulus.scene --frames 1 --warmup 0 --size 8x8 --csv "$T/full.csv"
t_expect "unwritable output" 1 "cannot write PNG" -- $C render scenes/cumulus.scene --size 8x8 -o /nonexistent/dir/x.png
# The presets compiled into the engine (src/core/presets.c) are the ones the sweep chose (docs/sweep_presets.txt): every
# key=value of each preset's --set line must appear in that preset's entry, except cloud.phase (a preset never changes
# the scene's phase function; the sweep lists it because it is one of its knobs).
bad=""
for p in high medium low; do
  want=$(grep "^$p:" docs/sweep_presets.txt | sed 's/ *#.*//; s/^[a-z]*: *//; s/--set //g')
  have=$(awk -v p="$p" '/^    \/\* / { cur = $2; sub(/:$/, "", cur) } cur == p && /"/ { gsub(/^ *"|" *,? *$/, ""); printf "%s", $0 }' src/core/presets.c | tr ';' ' ')
  [ -n "$want" ] || bad="$bad $p:missing-in-docs"
  for kv in $want; do case "$kv" in cloud.phase=*) continue ;; esac; case " $have " in *" $kv "*) ;; *) bad="$bad $p:$kv" ;; esac; done
done
if [ -z "$bad" ]; then t_ok "presets in src/core/presets.c match docs/sweep_presets.txt"
else t_fail "presets in src/core/presets.c match docs/sweep_presets.txt" "differ:$bad"; fi
# The sweep never chooses settings that change what is drawn (tools/sweep/knobs.c, knob_preset_eligible): no preset
# turns the noise off or keeps one interval per pixel (it cuts clouds where a ray leaves and re-enters them).
cut=$(grep -E '^(high|medium|low):' docs/sweep_presets.txt | grep -E 'quality\.max_intervals=1( |$)|quality\.noise_octaves=off')
[ -z "$cut" ] && t_ok "no preset cuts clouds or drops the noise" || t_fail "no preset cuts clouds or drops the noise" "$cut"

# The octave model's defaults (src/core/scene_keys.c, printed into README.md's key table, which test_keys.sh keeps in
# step) are the ones `cumulo-sweep --fit-octaves` chose (docs/ms_octaves_fit.txt).
bad=""
for k in octaves a b c; do
  want=$(sed -n "s/^ms\.$k=//p" docs/ms_octaves_fit.txt)
  have=$(awk -F' *[|] *' -v k="$k" '$2 == "ms" && $3 == k { print $5 }' README.md)
  [ -n "$want" ] && [ "$want" = "$have" ] || bad="$bad ms.$k:docs=$want,keys=$have"
done
if [ -z "$bad" ]; then t_ok "octave defaults match docs/ms_octaves_fit.txt"
else t_fail "octave defaults match docs/ms_octaves_fit.txt" "differ:$bad"; fi

t_summary
