#!/bin/sh
# A line already in use gives EBUSY.
. /vm/lib.sh
need gpiod_check
exec gpiod_check busy "$BOARD_CHIP" "$(line 1 step)"
