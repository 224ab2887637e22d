#!/bin/sh
# The gpiod backend's own GoogleTests (tests/gpio/gpiod_backend_test.cpp and
# line_event_reader_test.cpp) against the board's gpio-sim chip: outputs, input edges and their
# CLOCK_MONOTONIC timestamps, error messages (offset out of range, busy, used twice), release.
. /vm/lib.sh
need test_gpiod_backend
export STEPMOD_TEST_GPIOSIM_CHIP="$BOARD_CHIP"
export STEPMOD_TEST_GPIOSIM_SYSFS="$GPIO_SIM_DIR"
test_gpiod_backend >/tmp/test_gpiod_backend.log 2>&1
rc=$?
cat /tmp/test_gpiod_backend.log
[ "$rc" -eq 0 ] || fail "test_gpiod_backend exit status $rc"
if grep -q "SKIPPED" /tmp/test_gpiod_backend.log; then
  fail "gpio-sim tests were skipped (STEPMOD_TEST_GPIOSIM_CHIP/SYSFS not seen)"
fi
ok "gpiod backend: $(grep -c '^\[       OK \]' /tmp/test_gpiod_backend.log) tests passed on $BOARD_CHIP"
