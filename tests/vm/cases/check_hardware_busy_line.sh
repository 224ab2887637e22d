#!/bin/sh
# stepmodd --check while another program holds one configured line, axis1.home (issue 33): exit
# 1, one problem, naming the line, its key and the program holding it.
. /vm/lib.sh
need stepmodd
need gpiod_check
cp /vm/board00-board.toml /tmp/busy.toml
home=$(line 1 home)
gpiod_check hold "$BOARD_CHIP" "$home" >/tmp/hold.log 2>&1 &
holder=$!
wait_for /tmp/hold.log "held: line $home" $holder
expect_check_beside $holder /tmp/busy.toml 1 \
  "GPIO chip $BOARD_CHIP [$BOARD_LABEL], line $home (axis1.home): line busy (used by 'stepmod-vm-test'; \`gpioinfo $BOARD_CHIP\` shows it)"
n=$(grep -c "GPIO chip .*, line " /tmp/busy.toml.log)
[ "$n" = 1 ] || { cat /tmp/busy.toml.log; fail "$n problems reported, expected 1 (axis1.home)"; }
ok "line $home held by another program: exit 1 naming axis1.home and 'stepmod-vm-test'"
