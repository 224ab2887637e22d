#!/bin/sh
# Edges the kernel dropped while stepmodd was stopped: health bit 5, the log, the count (libgpiod 2: exact).
# (tests/vm/daemon_vm_test.cpp, sub-command lost)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test lost
