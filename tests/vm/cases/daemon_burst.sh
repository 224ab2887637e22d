#!/bin/sh
# Hundreds of input edges during a move: every edge in the VCD in order, none lost, the pulse count exact.
# (tests/vm/daemon_vm_test.cpp, sub-command burst)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
BURST_NICE=${BURST_NICE:-0} exec daemon_vm_test burst
