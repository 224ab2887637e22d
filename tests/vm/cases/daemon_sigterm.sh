#!/bin/sh
# SIGTERM mid-move: outputs go idle, then the lines are released (follow their pull) and can be had again.
# (tests/vm/daemon_vm_test.cpp, sub-command sigterm)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test sigterm
