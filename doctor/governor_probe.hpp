#pragma once
// The CPU frequency governor of a CPU (/sys/devices/system/cpu/cpuN/cpufreq/scaling_governor):
// anything but "performance" lets the clock drop between edges, and waking it costs latency.
#include <string>

#include "doctor/sys_root.hpp"

namespace stepmod::doctor {

// "" when the CPU has no cpufreq (a VM, a fixed clock).
std::string probe_governor(const SysRoot& root, int cpu);

}  // namespace stepmod::doctor
