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
t_summary() {
  echo "[  PASSED  ] $T_PASS test(s)."
  [ "$T_SKIP" -eq 0 ] || echo "[  SKIPPED ] $T_SKIP test(s)."
  [ "$T_FAIL" -eq 0 ] || echo "[  FAILED  ] $T_FAIL test(s)."
  [ "$T_FAIL" -eq 0 ]
}
