#!/bin/sh
# Find Home with the home switch and the limits driven through sysfs.
# (tests/vm/daemon_vm_test.cpp, sub-command homing)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test homing
