#!/bin/sh
# stepmodd --check with a [gpio] chip label no chip has (issue 33): exit 1, the message names the
# label asked for and lists the chips there are, as gpiodetect does.
. /vm/lib.sh
need stepmodd
sed 's|^chip = .*|chip = "pinctrl-rp1-nothere"|' /vm/board00-board.toml >/tmp/wrong.toml
expect_check /tmp/wrong.toml 1 \
  "GPIO chip 'pinctrl-rp1-nothere' not found: [gpio] chip takes one of these names or labels (as \`gpiodetect\` lists them):" \
  "  $BOARD_CHIP [$BOARD_LABEL] ($BOARD_LINES lines)"
ok "wrong label: exit 1 naming 'pinctrl-rp1-nothere' and listing $BOARD_CHIP [$BOARD_LABEL]"
