#!/bin/sh
# [[axis]] line options on the kernel's lines: bias, active_low, drive, debounce_us (line info + sim_gpio pull).
# (tests/vm/daemon_vm_test.cpp, sub-command options)
. /vm/lib.sh
need stepmodd
need daemon_vm_test
exec daemon_vm_test options
