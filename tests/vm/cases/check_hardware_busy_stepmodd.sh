#!/bin/sh
# stepmodd --check while a stepmodd runs on the same lines (issue 33): exit 1, every line named
# busy with its key, the holder 'stepmod' and the hint that a stepmodd runs.
. /vm/lib.sh
need stepmodd
cp /vm/board00-board.toml /tmp/busy.toml
sed 's|^name = .*|name = "holder"|' /vm/board00-board.toml >/tmp/holder.toml
stepmodd --config /tmp/holder.toml >/tmp/holder.log 2>&1 &
holder=$!
wait_for /tmp/holder.log "running" $holder
step=$(line 1 step)
expect_check_beside $holder /tmp/busy.toml 1 \
  "GPIO chip $BOARD_CHIP [$BOARD_LABEL], line $step (axis1.step): line busy (used by 'stepmod': a stepmodd running?; \`gpioinfo $BOARD_CHIP\` shows it)"
ok "lines of a running stepmodd: exit 1 naming axis1.step and 'stepmod'"
