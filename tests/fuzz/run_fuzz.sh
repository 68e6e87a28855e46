#!/bin/sh
# tests/fuzz/run_fuzz.sh [--pending] TARGET...: runs $B/fuzz/fuzz_TARGET for FUZZ_SECONDS each (FUZZ_JOBS at a time),
# first on its regressions (tests/fuzz/regressions/TARGET/), then from its seeds; prints one line per target (exec/s,
# runs, corpus) and "N passed, N failed, 0 skipped" into $B/fuzz/summary.txt. A finding (crash, sanitizer report,
# broken invariant, leak, a run over 10 s, over 2 GB) fails the target and leaves the input in $B/fuzz/findings/.
# --pending replays tests/fuzz/pending/TARGET/ against the checks that fail today instead (expected to fail).
. tests/lib.sh
B=${B:-build}
F=$B/fuzz
SECS=${FUZZ_SECONDS:-60}
JOBS=${FUZZ_JOBS:-2}
pending=0
[ "${1:-}" = --pending ] && { pending=1; shift; }
mkdir -p "$F/logs" "$F/findings"

# seeds TARGET DIR: the seed corpus, from the tree's own files; the slab and collector tables are cut to small complete grids
# (tests/fuzz/seed_tables.sh) so that a run spends its time on mutations, not on reading 15,000 lines.
seeds() {
  rm -rf "$2"; mkdir -p "$2"
  [ -d "tests/fuzz/seeds/$1" ] && cp tests/fuzz/seeds/"$1"/* "$2"/
  case "$1" in
    scene) cp scenes/*.scene "$2"/ ;;
    set) for f in scenes/*.scene; do  # each scene file as the --set lines that say the same
           awk '{sub(/[#;].*/, "")} /^\[/ {s = substr($1, 2, length($1) - 2); n[s]++; next}
                /=/ {k = $0; sub(/ *=.*/, "", k); v = $0; sub(/^[^=]*= */, "", v); sub(/[ \t]+$/, "", v)
                     print (s == "ellipsoid" ? s "." n[s] : s) "." k "=" v}' "$f" >"$2/$(basename "$f")"
         done ;;
    mie) cp data/mie_cloud.tbl "$2"/ ;;
    slab) sh tests/fuzz/seed_tables.sh slab data/slab_fit_bouthors.txt >"$2/small" ;;
    collector) sh tests/fuzz/seed_tables.sh collector data/slab_collector.txt >"$2/small" ;;
  esac
}

# run TARGET: one target's whole run, its result line in $F/logs/TARGET.result
run() {
  t=$1 bin=$F/fuzz_$t log=$F/logs/$t.log res=$F/logs/$t.result
  opts="-timeout=10 -rss_limit_mb=2048 -max_len=131072 -artifact_prefix=$F/findings/$t- -print_final_stats=1"
  if [ "$pending" -eq 1 ]; then
    bin=$F/pending/fuzz_$t
    set -- tests/fuzz/pending/"$t"/*
    [ -e "$1" ] || { echo "ok $t: no pending reproducers" >"$res"; return; }
    if "$bin" $opts "$@" >"$log" 2>&1; then echo "ok $t: $# pending reproducer(s) pass now" >"$res"
    else echo "FAIL $t: $(grep -m1 'invariant\|ERROR' "$log")" >"$res"; fi
    return
  fi
  set -- tests/fuzz/regressions/"$t"/*
  if [ -e "$1" ] && ! "$bin" $opts "$@" >"$log.regressions" 2>&1; then
    echo "FAIL $t: a regression input fails again ($log.regressions)" >"$res"; return
  fi
  seeds "$t" "$F/seeds/$t"
  mkdir -p "$F/corpus/$t"
  if "$bin" $opts -max_total_time="$SECS" "$F/corpus/$t" "$F/seeds/$t" >"$log" 2>&1; then
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
    echo "ok $t: ${SECS} s, $execs runs, $rate exec/s, $cov, corpus $(ls "$F/corpus/$t" | wc -l)" >"$res"
  else
    echo "FAIL $t: $(grep -m1 'invariant\|ERROR: \|runtime error' "$log") (input in $F/findings, log $log)" >"$res"
  fi
}

# FUZZ_JOBS targets at a time: each is one process, so two share the two cores of a small machine.
running=0
for t in "$@"; do
  rm -f "$F/logs/$t.result"
  run "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$JOBS" ]; then wait; running=0; fi
done
wait
for t in "$@"; do
  r=$(cat "$F/logs/$t.result" 2>/dev/null || echo "FAIL $t: no result")
  case "$r" in ok*) t_ok "fuzz_${r#ok }" ;; *) t_fail "fuzz_$t" "${r#FAIL $t: }" ;; esac
done
sum=$F/summary.txt; [ "$pending" -eq 0 ] || sum=$F/pending/summary.txt
echo "$T_PASS passed, $T_FAIL failed, 0 skipped" | tee "$sum"
t_summary >/dev/null
