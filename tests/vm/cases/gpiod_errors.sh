#!/bin/sh
# A missing chip and an out-of-range offset fail with clear errors.
. /vm/lib.sh
need gpiod_check
exec gpiod_check errors "$BOARD_CHIP"
