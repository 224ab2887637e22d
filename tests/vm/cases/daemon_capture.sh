#!/bin/sh
# Capture edges (kernel-stamped) latch the step count the VCD shows at the edge's time (no encoder).
# (tests/vm/daemon_vm_test.cpp, sub-command capture)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test capture
