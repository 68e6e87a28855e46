# platform/test_gpio_sim.sh: the GPIO knob end to end on the kernel's simulated GPIO chip (gpio-sim over configfs):
# three lines (A, B, button) driven through their simulated pulls, read by `cumulo run` through libgpiod.
# Skipped, with the reason, where the kernel has no gpio-sim or configfs, or without root.
. tests/lib.sh
C=build/cumulo
CFG=/sys/kernel/config/gpio-sim
OUT=build/test-output/gpio-sim
mkdir -p "$OUT"

if [ "$(id -u)" -ne 0 ]; then
  t_skip gpio_sim "needs root to create a simulated chip in configfs"; t_summary; exit 0
fi
[ -d /sys/kernel/config ] || mount -t configfs none /sys/kernel/config 2>/dev/null
[ -d $CFG ] || modprobe gpio-sim 2>/dev/null
if [ ! -d /sys/kernel/config ]; then
  t_skip gpio_sim "no configfs (/sys/kernel/config missing; kernel without CONFIG_CONFIGFS_FS)"; t_summary; exit 0
fi
if [ ! -d $CFG ]; then
  t_skip gpio_sim "kernel has no gpio-sim ($CFG missing; needs CONFIG_GPIO_SIM, modprobe gpio-sim)"; t_summary; exit 0
fi

dev=$CFG/cumulo-test-$$
cleanup() {
  [ -n "$pid" ] && kill $pid 2>/dev/null
  echo 0 >$dev/live 2>/dev/null
  rmdir $dev/gpio-bank0/line* $dev/gpio-bank0 $dev 2>/dev/null
  [ -n "$TMPD" ] && rm -rf "$TMPD"
}
trap cleanup EXIT
mkdir $dev $dev/gpio-bank0 || { t_fail gpio_sim "cannot create $dev"; t_summary; exit 1; }
echo 3 >$dev/gpio-bank0/num_lines
for l in 0 1 2; do mkdir $dev/gpio-bank0/line$l; done
echo ENC_A >$dev/gpio-bank0/line0/name
echo ENC_B >$dev/gpio-bank0/line1/name
echo ENC_SW >$dev/gpio-bank0/line2/name
echo 1 >$dev/live
chip=$(cat $dev/gpio-bank0/chip_name)
sysdir=/sys/devices/platform/$(cat $dev/dev_name)/$chip
pull() { echo "pull-$2" >$sysdir/sim_gpio$1/pull; sleep 0.02; }

# Lines by name for A and B, by offset for the button: both lookups are exercised.
TMPD=$(mktemp -d); mkfifo "$TMPD/fifo"
$C run scenes/cumulus.scene --platform headless --size 64x48 --accel 0 --step 1 \
   --input "gpio:chip=$chip,a=ENC_A,b=ENC_B,button=2" --input stdin <"$TMPD/fifo" >"$OUT/run.out" 2>"$OUT/run.err" &
pid=$!
exec 9>"$TMPD/fifo"
i=0
while [ $i -lt 100 ] && ! grep -q '^input: gpio' "$OUT/run.err"; do sleep 0.1; i=$((i + 1)); done
if ! grep -q '^input: gpio' "$OUT/run.err"; then
  t_fail gpio_sim_open "$(cat "$OUT/run.err")"; exec 9>&-; t_summary; exit 1
fi
t_ok gpio_sim_open
echo "sun 30 100" >&9
sleep 0.3
# Three detents clockwise (A falls, B falls, A rises, B rises), one back, with bounce on the first edge.
for k in 1 2 3; do
  pull 0 down; pull 0 up; pull 0 down; pull 1 down; pull 0 up; pull 1 up
done
pull 1 down; pull 0 down; pull 1 up; pull 0 up
# The button toggles the knob to elevation; one detent clockwise raises the sun half a degree.
pull 2 down; sleep 0.05; pull 2 up
pull 0 down; pull 1 down; pull 0 up; pull 1 up
sleep 0.3
echo quit >&9
exec 9>&-
wait $pid; rc=$?; pid=
last=$(grep 'source=gpio' "$OUT/run.err" | tail -1)
az=$(grep 'source=gpio' "$OUT/run.err" | grep -v 'elevation=30.500' | tail -1)
if [ $rc -eq 0 ] && [ "$az" = "sun elevation=30.000 azimuth=102.000 source=gpio" ]; then t_ok gpio_sim_detents
else t_fail gpio_sim_detents "exit $rc, last azimuth line '$az'"; fi
if grep -q '^knob axis=elevation source=gpio' "$OUT/run.err" &&
   [ "$last" = "sun elevation=30.500 azimuth=102.000 source=gpio" ]; then t_ok gpio_sim_button
else t_fail gpio_sim_button "last '$last'"; fi
t_summary
