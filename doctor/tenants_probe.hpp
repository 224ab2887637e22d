#pragma once
// The other tenants of the pulse CPU: every task (thread) in /proc whose affinity allows that CPU
// (Cpus_allowed_list in /proc/PID/task/TID/status), and those the kernel last ran there
// (field 39 of .../stat). Kernel threads bound to the CPU (ksoftirqd/N, kworker/N, migration/N)
// are counted apart: no setup moves them.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "doctor/sys_root.hpp"

namespace stepmod::doctor {

// What /proc/PID/task/TID/stat says that the probe needs.
struct TaskStat {
  std::string comm;
  unsigned long flags = 0;  // PF_KTHREAD = 0x00200000
  int processor = -1;       // the CPU it last ran on
  bool kernel_thread() const { return (flags & 0x00200000UL) != 0; }
};
// nullopt for a line that is not a stat line. The name may hold blanks and parentheses.
std::optional<TaskStat> parse_task_stat(std::string_view line);
// The value of a "Key:\tvalue" line of a status file ("Cpus_allowed_list"), or nullopt.
std::optional<std::string> status_field(std::string_view status, std::string_view key);

struct CpuTenants {
  int cpu = -1;
  std::size_t user_tasks = 0;    // user threads allowed on the CPU (the caller's own excluded)
  std::size_t kernel_tasks = 0;  // kernel threads allowed on it
  std::size_t ran_there = 0;     // user threads that last ran on it
  std::vector<std::string> names;  // distinct names of those user threads, the first few
};

// `self_pid`: the doctor's own process, left out (0: none left out).
CpuTenants probe_tenants(const SysRoot& root, int cpu, int self_pid);

}  // namespace stepmod::doctor
