#!/bin/sh
# The gpio-sim board is there as board.toml describes it: chip, label, 54 lines named GPIO<n>,
# every axis line of both axes (and the 3602's GPO lines), and a pull change is seen in the line's
# value.
. /vm/lib.sh
[ -c "/dev/$BOARD_CHIP" ] || fail "/dev/$BOARD_CHIP missing"
n=0
for ax in 1 2; do
  for key in step dir capture external home estop cw_limit ccw_limit enc_a enc_b enc_z; do
    off=$(line $ax $key)
    [ -n "$off" ] || fail "axis $ax has no $key line in the board configs"
    [ "$(sim_value "$off")" = 0 ] || fail "axis $ax $key (line $off) does not start low"
    n=$((n + 1))
  done
done
# The 3602's general-purpose outputs (board-3602.toml), one per axis.
for ax in 1 2; do
  off=$(line $ax gpo)
  [ -n "$off" ] || fail "axis $ax has no gpo line in the board configs"
  [ "$(sim_value "$off")" = 0 ] || fail "axis $ax gpo (line $off) does not start low"
  n=$((n + 1))
done
off=$(line 1 estop)
sim_pull "$off" up
[ "$(sim_value "$off")" = 1 ] || fail "pull-up on line $off: value stays $(sim_value "$off")"
sim_pull "$off" down
[ "$(sim_value "$off")" = 0 ] || fail "pull-down on line $off: value stays $(sim_value "$off")"
ok "$BOARD_CHIP: $BOARD_LINES lines, $n axis lines of 2 axes, pulls drive the values"
