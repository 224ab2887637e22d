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
# wait_for FILE TEXT PID     waits (up to 30 s) until the background program PID has written
#                            TEXT to FILE; fails the case (killing PID) if it exits or never does
wait_for() {
  i=0
  while ! grep -qF -- "$2" "$1" 2>/dev/null; do
    i=$((i + 1))
    kill -0 "$3" 2>/dev/null || { cat "$1"; fail "pid $3 exited before it printed '$2'"; }
    [ $i -lt 300 ] || { kill "$3"; cat "$1"; fail "pid $3 did not print '$2' in 30 s"; }
    sleep 0.1
  done
}
# expect_check CONFIG RC TEXT...   `stepmodd --check --config CONFIG` exits RC and prints every
#                                  TEXT (fixed strings, exactly); its output: CONFIG.log
expect_check() {
  ec_cfg=$1 ec_want=$2
  shift 2
  ec_rc=0
  stepmodd --check --config "$ec_cfg" >"$ec_cfg.log" 2>&1 || ec_rc=$?
  [ "$ec_rc" = "$ec_want" ] || { cat "$ec_cfg.log"; fail "$ec_cfg: exit $ec_rc, expected $ec_want"; }
  for ec_text in "$@"; do
    grep -qF -- "$ec_text" "$ec_cfg.log" || { cat "$ec_cfg.log"; fail "$ec_cfg: no '$ec_text'"; }
  done
}
# expect_check_beside PID CONFIG RC TEXT...   expect_check while the background program PID runs
#                                             (holding lines); PID is ended afterwards either way
expect_check_beside() {
  eb_pid=$1
  shift
  eb_rc=0
  (expect_check "$@") || eb_rc=$?
  kill "$eb_pid"
  wait "$eb_pid" 2>/dev/null || true
  [ $eb_rc = 0 ] || exit $eb_rc
}
