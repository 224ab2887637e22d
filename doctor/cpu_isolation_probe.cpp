#include "doctor/cpu_isolation_probe.hpp"

#include "doctor/cpu_list.hpp"

namespace stepmod::doctor {

namespace {

std::vector<int> cpus_in(const SysRoot& root, const char* file) {
  const auto text = root.read(std::string("/sys/devices/system/cpu/") + file);
  if (!text) return {};
  return parse_cpu_list(*text).value_or(std::vector<int>{});
}

}  // namespace

CpuIsolation probe_cpu_isolation(const SysRoot& root) {
  return CpuIsolation{cpus_in(root, "online"), cpus_in(root, "isolated"),
                      cpus_in(root, "nohz_full")};
}

}  // namespace stepmod::doctor
