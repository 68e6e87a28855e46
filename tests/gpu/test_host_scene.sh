# tests/gpu/test_host_scene.sh: examples/host_scene, the example host renderer, flies its path through the cloud of
# scenes/cumulus.scene: every frame written as a PNG, the clouds composited over part of the host's picture from
# outside, over all of it from inside the cloud, and over none of it once the cloud is behind the camera.
. tests/lib.sh
X=${HOST_SCENE:-build/host_scene}
T=build/test-output/host_scene
rm -rf "$T"; mkdir -p "$T"
out=$("$X" scenes/cumulus.scene "$T" 6 160x120 2>&1); rc=$?
echo "$out"
[ $rc -eq 0 ] && t_ok "host_scene runs 6 frames" || t_fail "host_scene runs" "exit $rc: $out"
n=0
for k in 0 1 2 3 4 5; do [ -s "$T/frame_00$k.png" ] && n=$((n + 1)); done
[ $n -eq 6 ] && t_ok "6 PNG frames written" || t_fail "PNG frames" "$n of 6"
changed() { echo "$out" | sed -n "s/^frame $1: .*clouds changed \([0-9]*\) of \([0-9]*\) pixels.*/\1 \2/p"; }
set -- $(changed 2); [ -n "$1" ] && [ "$1" -gt $(($2 / 50)) ] && [ "$1" -lt $(($2 / 2)) ] &&
  t_ok "approaching: the cloud covers part of the picture ($1 of $2)" || t_fail "approaching" "changed '$1' of '$2'"
set -- $(changed 3); [ -n "$1" ] && [ "$1" -gt $(($2 * 95 / 100)) ] &&
  t_ok "inside the cloud: it veils the whole picture ($1 of $2)" || t_fail "inside" "changed '$1' of '$2'"
set -- $(changed 5); [ "$1" = 0 ] && t_ok "past the cloud: the host's picture untouched" || t_fail "past" "changed '$1'"
t_summary
