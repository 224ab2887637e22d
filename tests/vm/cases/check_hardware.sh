#!/bin/sh
# stepmodd --check against the kernel's gpio-sim chip (issue 33): the chip by its label passes
# and requests nothing; a wrong label (exit 1, the existing chips listed as gpiodetect does), a
# line past the chip's last one (exit 1, naming the key) and a line a running stepmodd holds
# (exit 1, "busy", its consumer) are refused.
. /vm/lib.sh
need stepmodd
cfg=/vm/board00-board.toml
[ -f "$cfg" ] || fail "$cfg missing"
t=/tmp/check
mkdir -p $t

# By label: valid, and every line still free afterwards (nothing was requested).
sed "s|^chip = .*|chip = \"$BOARD_LABEL\"|" "$cfg" >$t/label.toml
stepmodd --check --config $t/label.toml >$t/label.log 2>&1 || fail "by label '$BOARD_LABEL': exit $?: $(tail -n 1 $t/label.log)"
grep -q "\[$BOARD_LABEL\], $BOARD_LINES lines" $t/label.log || fail "the log does not name the label: $(cat $t/label.log)"

# A label no chip has.
sed "s|^chip = .*|chip = \"pinctrl-rp1-nothere\"|" "$cfg" >$t/wrong.toml
rc=0; stepmodd --check --config $t/wrong.toml >$t/wrong.log 2>&1 || rc=$?
[ $rc = 1 ] || fail "wrong label: exit $rc, expected 1: $(cat $t/wrong.log)"
grep -q "not found" $t/wrong.log && grep -q gpiodetect $t/wrong.log &&
  grep -q "$BOARD_CHIP \[$BOARD_LABEL\] ($BOARD_LINES lines)" $t/wrong.log ||
  fail "wrong label: the message does not list the chips: $(cat $t/wrong.log)"

# A line past the chip's last one.
sed "s|^enc_z = .*|enc_z = $BOARD_LINES|" "$cfg" >$t/past.toml
rc=0; stepmodd --check --config $t/past.toml >$t/past.log 2>&1 || rc=$?
[ $rc = 1 ] || fail "line $BOARD_LINES: exit $rc, expected 1: $(cat $t/past.log)"
grep -q "axis1.enc_z" $t/past.log && grep -q "out of range" $t/past.log ||
  fail "line $BOARD_LINES: the message does not name axis1.enc_z: $(cat $t/past.log)"

# A line in use: a stepmodd running on the board's config holds every line of it.
sed "s|^name = .*|name = \"holder\"|" "$cfg" >$t/holder.toml
stepmodd --config $t/holder.toml >$t/holder.log 2>&1 &
holder=$!
i=0
while ! grep -q "running" $t/holder.log; do
  i=$((i + 1))
  [ $i -lt 300 ] || { kill $holder; fail "the holding stepmodd did not start: $(cat $t/holder.log)"; }
  kill -0 $holder 2>/dev/null || fail "the holding stepmodd exited: $(cat $t/holder.log)"
  sleep 0.1
done
rc=0; stepmodd --check --config $t/label.toml >$t/busy.log 2>&1 || rc=$?
kill $holder
wait $holder || true
[ $rc = 1 ] || fail "busy lines: exit $rc, expected 1: $(cat $t/busy.log)"
grep -q "axis1.step" $t/busy.log && grep -q "busy (used by 'stepmod'" $t/busy.log ||
  fail "busy lines: the message does not name the line and its user: $(cat $t/busy.log)"
ok "--check by label '$BOARD_LABEL' passes; wrong label, line $BOARD_LINES and busy lines exit 1 naming them"
