# tests/vm/guest/all.sh: runs in the VM (from tests/vm/guest-init.sh): every guest test script, each one's output
# into /tmp/scratch/NAME.log (the host reads the cmocka-style lines there) and on the console, and its time into
# /tmp/scratch/times.txt. Exit status: 0 when every script passed. Arguments: the scripts to run (default all).
[ $# -gt 0 ] || set -- drm gpio evdev
mkdir -p /tmp/scratch
rc=0
for t in "$@"; do
  s=$(cut -d' ' -f1 /proc/uptime)
  echo "===== guest test $t"
  sh tests/vm/guest/$t.sh 2>&1 | tee /tmp/scratch/$t.log
  r=$(grep -c '^\[  FAILED  \]' /tmp/scratch/$t.log)
  grep -q '^\[  PASSED  \]' /tmp/scratch/$t.log || r=1
  [ "$r" -eq 0 ] || rc=1
  e=$(cut -d' ' -f1 /proc/uptime)
  awk -v n="$t" -v a="$s" -v b="$e" 'BEGIN { printf "%s %.1f\n", n, b - a }' >>/tmp/scratch/times.txt
done
exit $rc
