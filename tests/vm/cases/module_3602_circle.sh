#!/bin/sh
# The 3602's interpolated full circle (centre method) and a line on the gpiod backend: sysfs
# levels = VCD, and from the VCD exact end points and per-axis counts, every step point near the
# ideal path, Move Complete on both axes. (tests/vm/modules_vm_test.cpp, m3602_circle)
. /vm/lib.sh
need stepmodd
need modules_vm_test
exec modules_vm_test m3602_circle
