#!/bin/sh
# Both 3602 axes stepping at once (exact counts, sysfs levels = VCD), each axis' GPO line read
# back through the gpio-sim sysfs. (tests/vm/modules_vm_test.cpp, m3602)
. /vm/lib.sh
need stepmodd
need modules_vm_test
exec modules_vm_test m3602
