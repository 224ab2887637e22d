#!/bin/sh
# An input driven through its pull gives edge events stamped on CLOCK_MONOTONIC (the E-stop line
# and the capture line of axis 1).
. /vm/lib.sh
need gpiod_check
gpiod_check edge "$BOARD_CHIP" "$GPIO_SIM_DIR" "$(line 1 estop)" || exit 1
exec gpiod_check edge "$BOARD_CHIP" "$GPIO_SIM_DIR" "$(line 1 capture)"
