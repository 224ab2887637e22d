#!/bin/sh
# stepmodd --check with a line the chip does not have (issue 33): axis1.enc_z one past the last
# line. Exit 1, one problem, naming the chip, the line, its key and the chip's range.
. /vm/lib.sh
need stepmodd
sed "s|^enc_z = .*|enc_z = $BOARD_LINES|" /vm/board00-board.toml >/tmp/past.toml
expect_check /tmp/past.toml 1 \
  "GPIO chip $BOARD_CHIP [$BOARD_LABEL], line $BOARD_LINES (axis1.enc_z): offset out of range (the chip has $BOARD_LINES lines, 0..$((BOARD_LINES - 1)); the right chip? \`gpiodetect\` lists them)"
n=$(grep -c "GPIO chip .*, line " /tmp/past.toml.log)
[ "$n" = 1 ] || { cat /tmp/past.toml.log; fail "$n problems reported, expected 1 (axis1.enc_z)"; }
ok "line $BOARD_LINES: exit 1 naming axis1.enc_z and the chip's 0..$((BOARD_LINES - 1))"
