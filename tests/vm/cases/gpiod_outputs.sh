#!/bin/sh
# Step and direction outputs of both axes, requested through libgpiod, read back through gpio-sim.
. /vm/lib.sh
need gpiod_check
exec gpiod_check outputs "$BOARD_CHIP" "$GPIO_SIM_DIR" \
  "$(line 1 step)" "$(line 1 dir)" "$(line 2 step)" "$(line 2 dir)"
