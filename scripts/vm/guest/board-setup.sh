#!/bin/sh
# In the VM (busybox sh). Creates the gpio-sim chip of the test board and writes its description
# as shell variables to /run/board.env:
#   BOARD_CHIP      gpiochipN (checked against [gpio] chip of the first config)
#   BOARD_LABEL     the chip's label
#   BOARD_LINES     number of lines
#   GPIO_SIM_CFG    /sys/kernel/config/gpio-sim/<name>
#   GPIO_SIM_DIR    /sys/devices/platform/<dev_name>/<chip_name>  (sim_gpioN/{value,pull})
#   AX<n>_<KEY>     line offset of each line of each config's [[axis]] tables (first config wins)
# Usage: board-setup.sh CONFIG.toml...     (configfs mounted, gpio-sim loaded)
set -eu

NUM_LINES=${BOARD_NUM_LINES:-54}
LABEL=${BOARD_LABEL:-pinctrl-stepmod-vm}
CFG=/sys/kernel/config/gpio-sim/board

[ $# -ge 1 ] || { echo "board-setup: no config file" >&2; exit 1; }
[ -d /sys/kernel/config/gpio-sim ] || { echo "board-setup: /sys/kernel/config/gpio-sim missing (configfs mounted? gpio-sim loaded?)" >&2; exit 1; }

# The line keys of docs/interface.md section 2, per [[axis]] table, in every config file.
# shellcheck disable=SC2016
awk -v nlines="$NUM_LINES" '
  BEGIN { split("step dir capture external home estop cw_limit ccw_limit enc_a enc_b enc_z gpo", k, " ");
          for (i in k) linekey[k[i]] = 1; bad = 0 }
  FNR == 1 { axis = 0; sect = ""; file++ }
  { sub(/#.*/, ""); gsub(/^[ \t]+|[ \t]+$/, "") }
  $0 == "" { next }
  /^\[\[axis\]\]$/ { axis++; sect = "axis"; next }
  /^\[/ { sect = $0; next }
  {
    eq = index($0, "="); if (eq == 0) next
    key = substr($0, 1, eq - 1); val = substr($0, eq + 1)
    gsub(/[ \t]/, "", key); gsub(/^[ \t]+|[ \t]+$/, "", val)
    if (sect == "[gpio]" && key == "chip" && file == 1) { gsub(/"/, "", val); print "BOARD_CHIP=" val }
    if (sect != "axis" || !(key in linekey)) next
    if (val !~ /^[0-9]+$/ || val + 0 >= nlines) {
      printf "board-setup: %s: axis %d %s = %s is not a line of a %d-line chip\n", FILENAME, axis, key, val, nlines > "/dev/stderr"; bad = 1; next }
    if ((file, val) in used) {
      printf "board-setup: %s: line %d is both %s and %s\n", FILENAME, val, used[file, val], "axis" axis "." key > "/dev/stderr"; bad = 1; next }
    used[file, val] = "axis" axis "." key
    var = "AX" axis "_" toupper(key)
    if (!(var in seen)) { seen[var] = 1; print var "=" val }
  }
  END { exit bad }
' "$@" >/run/board.env.tmp

. /run/board.env.tmp
[ -n "${BOARD_CHIP:-}" ] || { echo "board-setup: $1 has no [gpio] chip" >&2; exit 1; }

mkdir "$CFG" "$CFG/bank0"
echo "$NUM_LINES" >"$CFG/bank0/num_lines"
echo "$LABEL" >"$CFG/bank0/label"
i=0
while [ "$i" -lt "$NUM_LINES" ]; do
  mkdir "$CFG/bank0/line$i"
  echo "GPIO$i" >"$CFG/bank0/line$i/name"
  i=$((i + 1))
done
echo 1 >"$CFG/live"

chip=$(cat "$CFG/bank0/chip_name")
dev=$(cat "$CFG/dev_name")
if [ "$chip" != "$BOARD_CHIP" ]; then
  echo "board-setup: gpio-sim chip is $chip but $1 says chip = \"$BOARD_CHIP\"" >&2
  exit 1
fi
[ -c "/dev/$chip" ] || { echo "board-setup: /dev/$chip missing (devtmpfs mounted?)" >&2; exit 1; }
dir=/sys/devices/platform/$dev/$chip
[ -f "$dir/sim_gpio0/value" ] || { echo "board-setup: $dir/sim_gpio0/value missing" >&2; exit 1; }
{
  cat /run/board.env.tmp
  echo "BOARD_LABEL=$LABEL"
  echo "BOARD_LINES=$NUM_LINES"
  echo "GPIO_SIM_CFG=$CFG"
  echo "GPIO_SIM_DIR=$dir"
} >/run/board.env
rm -f /run/board.env.tmp
