# tools/pathtrace/test_pt_cli.sh: build/cumulo-pt end to end: outputs, thread-count independence, density dump, the
# renderer's noise seed, and one-line errors with exit 1 (bad scene) or 2 (bad arguments). Run from the repo root.
. tests/lib.sh
P=${CUMULO_PT:-build/cumulo-pt}
T=build/test-output/pathtrace
mkdir -p "$T"
S=scenes/cumulus.scene

# The path tracer must see the renderer's clouds: its noise seed is the renderer's (private) NOISE_SEED.
rs=$(sed -n 's/^#define NOISE_SEED \([0-9]*\)u.*/\1/p' src/gpu/renderer.c)
ps=$(sed -n 's/^#define PT_NOISE_SEED \([0-9]*\)u.*/\1/p' tools/pathtrace/pt.h)
if [ -n "$rs" ] && [ "$rs" = "$ps" ]; then t_ok "noise seed matches the renderer ($rs)"
else t_fail "noise seed matches the renderer" "renderer '$rs', path tracer '$ps'"; fi

if $P $S -o "$T/a.pfm" --size 16x12 --spp 2 --threads 1 --seed 5 >"$T/out1" 2>"$T/err1" &&
   $P $S -o "$T/b.pfm" --size 16x12 --spp 2 --threads 2 --seed 5 --quiet >"$T/out2" 2>"$T/err2"; then
  t_ok "render 16x12"
else t_fail "render 16x12" "$(cat "$T/err1" "$T/err2")"; fi
if [ "$(head -c 2 "$T/a.pfm")" = "PF" ] && [ "$(wc -c < "$T/a.pfm")" -ge $((16 * 12 * 12)) ] &&
   [ -s "$T/a.pfm.stderr.pfm" ]; then t_ok "PFM and standard-error PFM written"
else t_fail "PFM and standard-error PFM written" "$(ls -l "$T")"; fi
if cmp -s "$T/a.pfm" "$T/b.pfm" && cmp -s "$T/a.pfm.stderr.pfm" "$T/b.pfm.stderr.pfm"; then
  t_ok "1 and 2 threads give identical files"
else t_fail "1 and 2 threads give identical files" "outputs differ"; fi
case "$(cat "$T/err1")" in *"ETA"*) t_ok "progress bar with ETA" ;; *) t_fail "progress bar with ETA" "$(cat "$T/err1")" ;; esac
if [ ! -s "$T/err2" ]; then t_ok "--quiet is quiet on stderr"; else t_fail "--quiet is quiet on stderr" "$(cat "$T/err2")"; fi
case "$(cat "$T/out1")" in *"wrote $T/a.pfm"*"0 of 384 paths cut"*) t_ok "summary line" ;;
  *) t_fail "summary line" "$(cat "$T/out1")" ;; esac

if $P $S -o "$T/t.pfm" --size 8x6 --spp 4 --mode transmittance --quiet >/dev/null 2>"$T/err"; then
  t_ok "transmittance mode"
else t_fail "transmittance mode" "$(cat "$T/err")"; fi

if $P $S --dump-density "$T/d.raw" --grid 8,6,4 >/dev/null 2>"$T/err" && [ "$(wc -c < "$T/d.raw")" -eq 768 ] &&
   grep -q '^dims 8 6 4$' "$T/d.raw.txt" && grep -q '^noise_seed 20130612$' "$T/d.raw.txt" &&
   grep -q '^units k_e m^-1$' "$T/d.raw.txt" && grep -q '^origin_m -290 130 -160$' "$T/d.raw.txt"; then
  t_ok "density dump"
else t_fail "density dump" "$(cat "$T/err" "$T/d.raw.txt" 2>&1)"; fi

printf '[camera]\nposition = 0 0 -10\nlook_at = 0 0 0\n[sun]\n[cloud]\n[ellipsoid]\ncenter = 0 0 0\nradii = 1 nan 1\n' > "$T/bad.scene"
t_expect "bad scene value" 1 "$T/bad.scene:8:9: 'radii' is NaN" -- $P "$T/bad.scene" -o "$T/x.pfm"
head -c 300 /dev/urandom > "$T/garbage.scene"; printf '\000' >> "$T/garbage.scene"
t_expect "binary garbage" 1 "not a text file" -- $P "$T/garbage.scene" -o "$T/x.pfm"
: > "$T/empty.scene"
t_expect "empty scene" 1 "empty scene file" -- $P "$T/empty.scene" -o "$T/x.pfm"
t_expect "missing scene" 1 "nope.scene: cannot open" -- $P nope.scene -o "$T/x.pfm"
t_expect "bad --set key" 1 "unknown key 'cloud.colour'" -- $P $S -o "$T/x.pfm" --set cloud.colour=1
t_expect "bad --set value" 1 "'radii' must be in [0.1, 100000] m, got -5" -- $P $S -o "$T/x.pfm" --set "ellipsoid.1.radii=1 -5 1"
t_expect "unwritable output" 1 "/nonexistent/x.pfm" -- $P $S -o /nonexistent/x.pfm --size 2x2 --spp 1 --quiet
t_expect "unwritable dump" 1 "cannot write density grid" -- $P $S --dump-density /nonexistent/d.raw --grid 2,2,2
t_expect "no arguments" 2 "usage: cumulo-pt" -- $P
t_expect "no output" 2 "usage: cumulo-pt" -- $P $S
t_expect "unknown option" 2 "unknown option '--fast'" -- $P $S -o "$T/x.pfm" --fast
t_expect "two scenes" 2 "more than one scene" -- $P $S $S -o "$T/x.pfm"
t_expect "missing value" 2 "--spp needs a value" -- $P $S -o "$T/x.pfm" --spp
t_expect "spp zero" 2 "--spp expects a count" -- $P $S -o "$T/x.pfm" --spp 0
t_expect "spp negative" 2 "--spp expects a count" -- $P $S -o "$T/x.pfm" --spp -4
t_expect "spp junk" 2 "--spp expects a count" -- $P $S -o "$T/x.pfm" --spp 12abc
t_expect "spp huge" 2 "--spp expects a count" -- $P $S -o "$T/x.pfm" --spp 99999999999999999999999
t_expect "threads zero" 2 "--threads expects a count" -- $P $S -o "$T/x.pfm" --threads 0
t_expect "threads huge" 2 "--threads expects a count" -- $P $S -o "$T/x.pfm" --threads 100000
t_expect "seed negative" 2 "--seed expects" -- $P $S -o "$T/x.pfm" --seed -1
t_expect "max depth junk" 2 "--max-depth expects" -- $P $S -o "$T/x.pfm" --max-depth 1e3
t_expect "bad size" 2 "--size expects WxH" -- $P $S -o "$T/x.pfm" --size 0x10
t_expect "bad size form" 2 "--size expects WxH" -- $P $S -o "$T/x.pfm" --size 640
t_expect "bad mode" 2 "--mode must be" -- $P $S -o "$T/x.pfm" --mode fast
t_expect "bad grid" 2 "--grid expects" -- $P $S --dump-density "$T/d.raw" --grid 0,1,1
t_expect "grid too big" 2 "--grid expects" -- $P $S --dump-density "$T/d.raw" --grid 4096,4096,4096
t_expect "grid alone" 2 "--grid only applies" -- $P $S -o "$T/x.pfm" --grid 2,2,2
t_expect "bad peak-mis" 2 "--peak-mis expects" -- $P $S -o "$T/x.pfm" --peak-mis 1.5
t_expect "not a PFM" 2 "must end in .pfm" -- $P $S -o "$T/x.png"
t_expect "missing -o value" 2 "-o needs a value" -- $P $S -o
# Integers that overflow an int are errors, not wrapped (sscanf's %d made 4294967360x48 into 64x48).
t_expect "size overflow" 2 "--size expects" -- $P $S -o "$T/x.pfm" --size 4294967360x48
t_expect "size sign" 2 "--size expects" -- $P $S -o "$T/x.pfm" --size 8x-8
t_expect "grid overflow" 2 "--grid expects" -- $P $S --dump-density "$T/x.raw" --grid 4294967297,1,1
# A full disk is an error for every file written (/dev/full fails every write with ENOSPC).
ln -sf /dev/full "$T/full.pfm"; ln -sf /dev/full "$T/dfull.raw.txt"
t_expect "PFM onto a full disk" 1 "write failed" -- $P $S -o "$T/full.pfm" --size 2x2 --spp 1 --quiet
t_expect "density header onto a full disk" 1 "dfull.raw.txt: write failed" -- $P $S --dump-density "$T/dfull.raw" --grid 2,2,2
t_expect "max steps zero" 2 "--max-steps expects" -- $P $S -o "$T/x.pfm" --max-steps 0
# The legal extreme of optical thickness (radii 1e5 m, k_e 6e7 m^-1) at 8x8, 1 spp: every path is cut at the default
# step bound and the warning counts them; a minute's timeout stands for "never loops".
if timeout 60 $P $S -o "$T/ext.pfm" --size 8x8 --spp 1 --threads 2 -q --set ellipsoid.1.radii=1e5,1e5,1e5 \
     --set cloud.density=1e7 --set cloud.droplet_radius=1000 2>"$T/ext.err" >/dev/null &&
   grep -q "warning: 64 of 64 paths cut at --max-steps 100000" "$T/ext.err"; then
  t_ok "extreme optical thickness: finishes, cut paths reported"
else t_fail "extreme optical thickness: finishes, cut paths reported" "$(cat "$T/ext.err")"; fi
t_help_version cumulo-pt $P -o --spp --threads --seed --size --set --max-depth --max-steps --aa --mode --peak-mis \
  --dump-density --grid --quiet --help --version
t_summary
