#!/bin/sh
# Kernel behaviour under a burst of input edges (200 pull toggles back to back). With the reader
# running (another process toggles), every edge must arrive, in order. With the reader idle
# during the burst, the v1 uAPI keeps only what fits its 16-event buffer per line: reported, not
# failed (a fact the gpiod backend has to live with: read events promptly).
. /vm/lib.sh
need gpiod_check
idle=$(gpiod_check burst "$BOARD_CHIP" "$GPIO_SIM_DIR" "$(line 1 capture)" 200 idle)
echo "$idle"
echo "$idle" | grep -q 'NOT alternating' && fail "reader idle: events out of order"
gpiod_check burst "$BOARD_CHIP" "$GPIO_SIM_DIR" "$(line 1 capture)" 200 reading || exit 1
ok "reader running: 200 of 200 edges; reader idle: $(echo "$idle" | sed -n 's/.*: \([0-9]* events\) read.*/\1/p') kept"
