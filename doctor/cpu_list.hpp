#pragma once
// The kernel's CPU list format ("0-2,5", "" for none): /sys/devices/system/cpu/online, isolated,
// nohz_full, a task's Cpus_allowed_list.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace stepmod::doctor {

// The CPUs named, ascending; nullopt for text that is no CPU list. Surrounding blanks and a
// trailing newline are ignored; "" and "(null)" are the empty list.
std::optional<std::vector<int>> parse_cpu_list(std::string_view text);
// The shortest list naming `cpus` (ascending): {0,1,2,5} -> "0-2,5"; {} -> "".
std::string format_cpu_list(const std::vector<int>& cpus);
bool contains(const std::vector<int>& cpus, int cpu);

}  // namespace stepmod::doctor
