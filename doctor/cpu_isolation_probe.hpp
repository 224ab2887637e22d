#pragma once
// Which CPUs exist and which the kernel keeps others off: /sys/devices/system/cpu/online,
// isolated (isolcpus=) and nohz_full (no periodic tick).
#include <vector>

#include "doctor/sys_root.hpp"

namespace stepmod::doctor {

struct CpuIsolation {
  std::vector<int> online;     // empty: unread
  std::vector<int> isolated;   // isolcpus=
  std::vector<int> nohz_full;  // nohz_full= (the file is absent on kernels without it)
};

CpuIsolation probe_cpu_isolation(const SysRoot& root);

}  // namespace stepmod::doctor
