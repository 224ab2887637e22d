# shellcheck shell=sh
# In the VM: helpers for the test cases (busybox sh). A case does `. /vm/lib.sh`.
# Board: see board-setup.sh for the variables (BOARD_CHIP, GPIO_SIM_DIR, AX1_STEP, ...).
. /run/board.env

# sim_value OFFSET           -> 0|1: the level of the line (an output's value, an input's pull)
sim_value() { cat "$GPIO_SIM_DIR/sim_gpio$1/value"; }
# sim_pull OFFSET up|down    drives an input (and is the level a released line returns to)
sim_pull() { echo "pull-$2" >"$GPIO_SIM_DIR/sim_gpio$1/pull"; }
# line AXIS KEY              -> offset of that line of the board, e.g. `line 1 estop`
line() { eval "echo \${AX$1_$(echo "$2" | tr "[:lower:]" "[:upper:]")}"; }

ok() { echo "ok: $*"; exit 0; }
fail() { echo "FAIL: $*"; exit 1; }
skip() { echo "skip: $*"; exit 77; }
# need PROGRAM              skips the case when a program is not in the VM
need() { command -v "$1" >/dev/null 2>&1 || skip "$1 is not in this VM image"; }
