# Shell-test helpers: t_ok/t_fail/t_skip record results, t_summary prints cmocka-style totals for run_tests.sh.
T_PASS=0; T_FAIL=0; T_SKIP=0
t_ok()   { T_PASS=$((T_PASS + 1)); echo "[       OK ] $1"; }
t_fail() { T_FAIL=$((T_FAIL + 1)); echo "[  FAILED  ] $1: $2"; }
t_skip() { T_SKIP=$((T_SKIP + 1)); echo "[  SKIPPED ] $1: $2"; }
# t_expect NAME EXPECTED_RC EXPECTED_STDERR_SUBSTRING -- command...
t_expect() {
  _n=$1; _rc=$2; _msg=$3; shift 4
  _err=$("$@" 2>&1 >/dev/null); _got=$?
  if [ "$_got" -ne "$_rc" ]; then t_fail "$_n" "exit $_got, expected $_rc ($_err)"; return; fi
  case "$_err" in *"$_msg"*) t_ok "$_n" ;; *) t_fail "$_n" "stderr '$_err' lacks '$_msg'" ;; esac
}
# t_wait_line FILE TEXT SECONDS PID: waits until FILE holds TEXT (a program says it is ready, e.g. bound to its port),
# at most SECONDS, and fails early when PID has exited; a fixed sleep instead races a slow start (sanitizers, load).
t_wait_line() {
  _w=0
  while ! grep -qF "$2" "$1" 2>/dev/null; do
    kill -0 "$4" 2>/dev/null || return 1
    [ "$_w" -ge $(($3 * 10)) ] && return 1
    sleep 0.1; _w=$((_w + 1))
  done
}
# t_pfm_mean FILE [N]: the mean of the green channel of a little-endian PFM's last N pixels (default 64: 8x8);
# nothing when it holds fewer
t_pfm_mean() {
  tail -c $((12 * ${2:-64})) "$1" | od -An -f -w12 -v |
    awk -v want="${2:-64}" '{ s += $2; n++ } END { if (n == want) printf "%.9g", s / n }'
}
t_summary() {
  echo "[  PASSED  ] $T_PASS test(s)."
  [ "$T_SKIP" -eq 0 ] || echo "[  SKIPPED ] $T_SKIP test(s)."
  [ "$T_FAIL" -eq 0 ] || echo "[  FAILED  ] $T_FAIL test(s)."
  [ "$T_FAIL" -eq 0 ]
}
# t_help_version PROGRAM BIN OPTION...: `BIN --help` exits 0 with the usage on stdout (nothing on stderr) naming every
# OPTION, and `BIN --version` exits 0 printing "PROGRAM VERSION (git describe)" with the tree's VERSION.
t_help_version() {
  _p=$1; _b=$2; shift 2
  _out=$("$_b" --help 2>"${TMPDIR:-/tmp}/t_help_err.$$"); _got=$?; _err=$(cat "${TMPDIR:-/tmp}/t_help_err.$$")
  rm -f "${TMPDIR:-/tmp}/t_help_err.$$"
  _miss=
  for _o in "$@"; do case "$_out" in *"$_o"*) ;; *) _miss="$_miss $_o" ;; esac; done
  if [ "$_got" -eq 0 ] && [ -z "$_err" ] && [ -z "$_miss" ] && case "$_out" in "usage: $_p"*) true ;; *) false ;; esac
  then t_ok "$_p --help"; else t_fail "$_p --help" "exit $_got, stderr '$_err', options not described:$_miss"; fi
  _out=$("$_b" --version 2>&1); _got=$?
  case "$_out" in "$_p $(cat VERSION) ("*")") [ "$_got" -eq 0 ] && t_ok "$_p --version" ||
                                                 t_fail "$_p --version" "exit $_got" ;;
    *) t_fail "$_p --version" "got '$_out' (exit $_got)" ;; esac
}
