#include "doctor/governor_probe.hpp"

namespace stepmod::doctor {

std::string probe_governor(const SysRoot& root, int cpu) {
  return root
      .read_line("/sys/devices/system/cpu/cpu" + std::to_string(cpu < 0 ? 0 : cpu) +
                 "/cpufreq/scaling_governor")
      .value_or("");
}

}  // namespace stepmod::doctor
