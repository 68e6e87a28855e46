# tests/app/test_sun_cli.sh: `cumulo sun` end to end: the one-line output, Reda & Andreas' SPA test point through the
# command line, and usage errors: one line on stderr starting "cumulo sun: ", exit 2. Run from the repository root.
. tests/lib.sh
C=${CUMULO:-build/cumulo}
T=build/test-output/sun_cli
mkdir -p "$T"

# SPA's test point (Reda & Andreas 2004, Table A4.1): Golden, Colorado, 2003-10-17 12:30:30 at time zone -7, 1830.14 m.
# Published with Delta T = 67 s: e0 = 39.872046 (no refraction), azimuth 194.340241; the command uses the Delta T model
# (64.5 s here), which moves the sun by < 0.0001 degrees: checked to 0.01 degrees.
GOLDEN="--latitude 39.742476 --longitude -105.1786 --height 1830.14"

# near NAME GOT WANT TOL
near() {
  if awk -v g="$2" -v w="$3" -v t="$4" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(g != "" && d <= t) }'; then
    t_ok "$1"; else t_fail "$1" "got '$2', want $3 +- $4"; fi
}

out=$($C sun --time-utc 2003-10-17T12:30:30-07:00 $GOLDEN 2>"$T/err"); rc=$?
if [ $rc -eq 0 ] && [ ! -s "$T/err" ] && [ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] &&
   printf '%s\n' "$out" | grep -Eq '^elevation -?[0-9]+\.[0-9]{4} azimuth [0-9]+\.[0-9]{4}$'; then
  t_ok "one line: elevation E azimuth A, 4 decimals"
else t_fail "one line: elevation E azimuth A, 4 decimals" "exit $rc, stdout '$out', stderr '$(cat "$T/err")'"; fi
el=$(echo "$out" | awk '{print $2}'); az=$(echo "$out" | awk '{print $4}')
near "SPA test point: elevation (e0)" "$el" 39.872046 0.01
near "SPA test point: azimuth" "$az" 194.340241 0.01

same=$($C sun --time-utc 2003-10-17T19:30:30Z $GOLDEN 2>&1)
[ "$same" = "$out" ] && t_ok "the offset -07:00 and Z give one answer" || t_fail "the offset -07:00 and Z" "'$same' vs '$out'"
same=$($C sun --time-utc "2003-10-17 19:30:30.000Z" --longitude=-105.1786 --latitude=39.742476 --height=1830.14 2>&1)
[ "$same" = "$out" ] && t_ok "space for T, fractional seconds, --opt=value" || t_fail "space for T, --opt=value" "'$same'"

# Refraction at 1010 hPa and 10 C: SPA's formula is proportional to P / 1010 * 283 / (273 + T), so its 0.016332 degrees
# at 820 hPa and 11 C become 0.016332 * (1010 / 820) * (284 / 283) = 0.020188 degrees; the azimuth does not change.
ref=$($C sun --time-utc 2003-10-17T19:30:30Z $GOLDEN --refraction 2>&1)
near "--refraction lifts the sun by 0.0202" "$(echo "$ref" | awk -v e="$el" '{print $2 - e}')" 0.020188 0.00015
[ "$(echo "$ref" | awk '{print $4}')" = "$az" ] && t_ok "--refraction keeps the azimuth" || t_fail "--refraction azimuth" "$ref"

# Polar day: at 78 N the June solstice's midnight sun (local time CEST) is above the horizon.
mid=$($C sun --time-utc 2026-06-21T00:00:00+02:00 --latitude 78 --longitude 15.6 2>&1)
case "$mid" in "elevation "[0-9]*) t_ok "midnight sun at 78 N" ;; *) t_fail "midnight sun at 78 N" "$mid" ;; esac
# The date line: -180 and 180 are one meridian.
a=$($C sun --time-utc 2026-01-01T00:00:00Z --latitude -17 --longitude 180 2>&1)
b=$($C sun --time-utc 2026-01-01T00:00:00Z --latitude -17 --longitude -180 2>&1)
[ "$a" = "$b" ] && t_ok "longitude 180 = -180" || t_fail "longitude 180 = -180" "'$a' vs '$b'"

# t_usage NAME STDERR_SUBSTRING -- args: exit 2, nothing on stdout, one line on stderr starting "cumulo sun: ".
t_usage() {
  _n=$1; _m=$2; shift 3
  _o=$($C sun "$@" 2>"$T/err"); _rc=$?; _e=$(cat "$T/err")
  if [ $_rc -ne 2 ] || [ -n "$_o" ] || [ "$(wc -l <"$T/err")" -ne 1 ]; then
    t_fail "$_n" "exit $_rc, stdout '$_o', stderr '$_e'"
  else case "$_e" in "cumulo sun: "*"$_m"*) t_ok "$_n" ;; *) t_fail "$_n" "stderr '$_e' lacks '$_m'" ;; esac; fi
}
P="--time-utc 2026-06-21T12:00:00Z"
t_usage "no options" "missing --time-utc" --
t_usage "missing --latitude" "missing --latitude" -- $P --longitude 0
t_usage "missing --longitude" "missing --longitude" -- $P --latitude 0
t_usage "missing value" "--longitude needs a value" -- $P --latitude 0 --longitude
t_usage "unknown option" "unknown option '--colour'" -- $P --latitude 0 --longitude 0 --colour
t_usage "extra argument" "unexpected argument 'now'" -- $P --latitude 0 --longitude 0 now
t_usage "not a number" "--latitude expects a number, got 'north'" -- $P --latitude north --longitude 0
t_usage "trailing text" "--latitude expects a number, got '45deg'" -- $P --latitude 45deg --longitude 0
t_usage "empty number" "--longitude expects a number, got ''" -- $P --latitude 0 --longitude ""
t_usage "leading blank" "--longitude expects a number, got ' 5'" -- $P --latitude 0 --longitude " 5"
t_usage "NaN" "--latitude expects a number, got 'nan'" -- $P --latitude nan --longitude 0
t_usage "infinity" "--height expects a number, got '-inf'" -- $P --latitude 0 --longitude 0 --height -inf
t_usage "overflow" "--height expects a number, got '1e999'" -- $P --latitude 0 --longitude 0 --height 1e999
t_usage "hex" "--latitude expects a number, got '0x10'" -- $P --latitude 0x10 --longitude 0
t_usage "latitude out of range" "latitude 90.5 is not in [-90, 90] degrees (north positive)" -- $P --latitude 90.5 --longitude 0
t_usage "longitude out of range" "longitude -180.5 is not in [-180, 180] degrees (east positive)" -- $P --latitude 0 --longitude -180.5
t_usage "height out of range" "height -2000 is not in [-1000, 100000] m" -- $P --latitude 0 --longitude 0 --height -2000
t_usage "bad date" "time_utc '2026-02-30T00:00:00Z': day 30 is not in February 2026" -- --time-utc 2026-02-30T00:00:00Z --latitude 0 --longitude 0
t_usage "no time zone" "no time zone: end with Z (UTC) or an offset such as +02:00" -- --time-utc 2026-06-21T12:00:00 --latitude 0 --longitude 0
t_usage "year out of range" "year 2101 (UTC) is outside 1900..2100" -- --time-utc 2101-01-01T00:00:00Z --latitude 0 --longitude 0
t_usage "control bytes escaped" "got '1\\x1b[2J'" -- $P --latitude "$(printf '1\033[2J')" --longitude 0
t_usage "control bytes escaped in the time" "time_utc '\\x07'" -- --time-utc "$(printf '\a')" --latitude 0 --longitude 0

out=$($C sun --help 2>"$T/err"); rc=$?
miss=""
for o in --time-utc --latitude --longitude --height --refraction --help; do case "$out" in *"$o"*) ;; *) miss="$miss $o" ;; esac; done
if [ $rc -eq 0 ] && [ ! -s "$T/err" ] && [ -z "$miss" ] && case "$out" in "usage: cumulo sun "*) true ;; *) false ;; esac
then t_ok "cumulo sun --help"; else t_fail "cumulo sun --help" "exit $rc, stderr '$(cat "$T/err")', missing:$miss"; fi
case "$($C --help)" in *"  sun "*) t_ok "cumulo --help lists sun" ;; *) t_fail "cumulo --help lists sun" "" ;; esac
t_summary
