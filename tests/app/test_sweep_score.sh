# tests/app/test_sweep_score.sh: `cumulo-sweep --score DIR`, images rendered elsewhere scored against the references
# with the sweep's metrics: the reference scored against itself has no error, an image of this build's renderer has
# the error the sweep itself measures for it, and bad images (missing, the wrong size, NaN, negative) are refused
# with the file named. Run from the repository root.
. tests/lib.sh
S=${SWEEP:-build/cumulo-sweep}
C=${CUMULO:-build/cumulo}
T=build/test-output/sweep_score
rm -rf "$T"; mkdir -p "$T/img" "$T/self" "$T/bad"

t_expect "--score needs a directory" 2 "needs a value" -- $S --score
t_expect "--score and --methods are two runs" 2 "different runs" -- $S --score "$T/img" --methods
t_expect "--score and --fit-octaves are two runs" 2 "different runs" -- $S --fit-octaves --score "$T/img"

# 40x30, 4 spp: seconds. This build's `high` as `cumulo render` writes it, and the reference itself.
A="--scenes cumulus --size 40x30 --spp 4 --ref-dir $T/ref"
$C render scenes/cumulus.scene --size 40x30 -o "$T/img/cumulus.pfm" >/dev/null 2>"$T/render.txt" ||
  t_fail "cumulo render writes the image" "$(cat "$T/render.txt")"
# shellcheck disable=SC2086 # $A is a list of options
$S --score "$T/img" $A --out "$T/img_out" >"$T/img.txt" 2>&1
rc=$?
row=$(grep '^| cumulus |' "$T/img_out/score.md" 2>/dev/null)
err=$(printf '%s\n' "$row" | awk -F'|' '{gsub(/ /, "", $3); print $3}')
if [ $rc -eq 0 ] && [ -n "$err" ] && awk -v e="$err" 'BEGIN { exit !(e > 0.01 && e < 2) }'; then
  t_ok "this build's image scored: cloud rel. RMSE $err"
else t_fail "this build's image scored" "exit $rc, row '$row': $(tail -2 "$T/img.txt")"; fi
ref=$(ls "$T"/ref/cumulus-*.pfm 2>/dev/null | grep -v stderr | head -1)
cp "$ref" "$T/self/cumulus.pfm" 2>/dev/null
# shellcheck disable=SC2086
$S --score "$T/self" $A --out "$T/self_out" >"$T/self.txt" 2>&1
row=$(grep '^| cumulus |' "$T/self_out/score.md" 2>/dev/null)
# the cloud's error 0, the contrast the reference's, SSIM 1, the image's error 0
same=$(printf '%s\n' "$row" | awk -F'|' '{gsub(/ /, ""); print ($3 == "0.0000" && $4 == $5 && $6 == "1.0000" &&
                                                               $7 == "0.0000") ? "yes" : "no"}')
[ "$same" = yes ] && t_ok "the reference against itself: no error ($row)" ||
  t_fail "the reference against itself" "'$row': $(tail -2 "$T/self.txt")"

# The sweep's own measurement of `high` on the same view and reference: the same cloud error as the scored image.
# shellcheck disable=SC2086
$S --methods $A --time-size 40x30 --frames 1 --warmup 0 --out "$T/methods" >"$T/methods.txt" 2>&1
mhigh=$(awk -F, '$1 == "cumulus" && $2 == "kol" && $3 == "\"high\"" { printf "%.4f", $7 }' "$T/methods/methods.csv" \
        2>/dev/null)
[ -n "$mhigh" ] && [ "$mhigh" = "$err" ] && t_ok "the score is the sweep's own error of high ($mhigh)" ||
  t_fail "the score is the sweep's own error of high" "sweep '$mhigh', score '$err'"

# Bad images: missing, the wrong size, NaN, negative.
# shellcheck disable=SC2086
t_expect "a missing image is named" 1 "$T/bad/cumulus.pfm" -- $S --score "$T/bad" $A --out "$T/bad_out"
$C render scenes/cumulus.scene --size 20x15 -o "$T/bad/cumulus.pfm" >/dev/null 2>&1
# shellcheck disable=SC2086
t_expect "an image of the wrong size is refused" 1 "is 20x15; the references are 40x30" -- \
  $S --score "$T/bad" $A --out "$T/bad_out"
pfm() { # BYTES: a 40x30 PFM, every channel 1.0 but the file's first (the bottom row's first pixel's red), given as
  # four little-endian bytes
  { printf 'PF\n40 30\n-1.0\n'; printf "$1"; i=1
    while [ $i -lt 3600 ]; do printf '\000\000\200\077'; i=$((i + 1)); done; } >"$T/bad/cumulus.pfm"
}
pfm '\000\000\300\177'
# shellcheck disable=SC2086
t_expect "a NaN is refused" 1 "pixel x 0, y 29 (from the top), channel 0 is nan" -- \
  $S --score "$T/bad" $A --out "$T/bad_out"
pfm '\000\000\200\277'
# shellcheck disable=SC2086
t_expect "a negative radiance is refused" 1 "pixel x 0, y 29 (from the top), channel 0 is -1" -- \
  $S --score "$T/bad" $A --out "$T/bad_out"
t_summary
