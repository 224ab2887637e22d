#!/bin/sh
# A relative move on the gpiod backend: step/dir sampled through sysfs agree with the VCD; pulse count exact.
# (tests/vm/daemon_vm_test.cpp, sub-command move)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test move
