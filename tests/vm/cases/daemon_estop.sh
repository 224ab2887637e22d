#!/bin/sh
# A pull change on the E-stop line stops a running move: Input Error, Position Invalid, Stopped, no motion bits.
# (tests/vm/daemon_vm_test.cpp, sub-command estop)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test estop
