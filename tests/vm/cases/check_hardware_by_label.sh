#!/bin/sh
# stepmodd --check against the kernel's gpio-sim chip named by its label (issue 33): exit 0, and
# the log names the chip, its label and its line count.
. /vm/lib.sh
need stepmodd
sed "s|^chip = .*|chip = \"$BOARD_LABEL\"|" /vm/board00-board.toml >/tmp/label.toml
expect_check /tmp/label.toml 0 \
  "GPIO chip '$BOARD_LABEL': /dev/$BOARD_CHIP [$BOARD_LABEL], $BOARD_LINES lines; the configured lines are there and free"
ok "--check by label '$BOARD_LABEL' passes and names $BOARD_CHIP, $BOARD_LINES lines"
