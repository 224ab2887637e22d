#pragma once
// Which CPUs the kernel has online (/sys/devices/system/cpu/online, e.g. "0-3" or "0,2-3"), for
// the check of `[rt] cpu`: pinning the pulse thread to a CPU the board does not have would
// leave it unpinned, so a configuration naming one is refused (by `stepmodd --check` and at
// start) instead of warned about. CPUs isolated with isolcpus= are online: they count.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stepmod::rt {

// The CPU numbers of a kernel CPU list ("0-3,6"); nullopt if it is not one.
std::optional<std::vector<int>> parse_cpu_list(std::string_view text);

// The online CPUs as the kernel lists them in `file`; nullopt if it cannot be read.
std::optional<std::vector<int>> cpus_online(
    const std::string& file = "/sys/devices/system/cpu/online");

// "" when `cpu` (-1: not pinned) is fine for `online`, else why not, naming the CPUs there are.
std::string rt_cpu_problem(int cpu, const std::vector<int>& online);

}  // namespace stepmod::rt
