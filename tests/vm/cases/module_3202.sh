#!/bin/sh
# Both 3202 channels stepping at once (exact counts, sysfs levels = VCD), then an E-stop on channel 1
# stops channel 1 only: channel 2 completes its move. (tests/vm/modules_vm_test.cpp, m3202)
. /vm/lib.sh
need stepmodd
need modules_vm_test
exec modules_vm_test m3202
