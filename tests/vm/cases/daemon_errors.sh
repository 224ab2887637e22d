#!/bin/sh
# A missing chip, a line out of range and a line in use: stepmodd exits 1 naming the chip and line.
# (tests/vm/daemon_vm_test.cpp, sub-command errors)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test errors
