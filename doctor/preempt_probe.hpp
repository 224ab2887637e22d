#pragma once
// The kernel's preemption model: PREEMPT_RT (/sys/kernel/realtime reads 1, or the version string
// says PREEMPT_RT), else what the version string (uname -v, /proc/sys/kernel/version) names and,
// on a PREEMPT_DYNAMIC kernel, the mode chosen at boot (/sys/kernel/debug/sched/preempt, root
// only: "none voluntary (full) lazy").
#include <string>
#include <string_view>

#include "doctor/sys_root.hpp"

namespace stepmod::doctor {

struct PreemptModel {
  bool rt = false;
  std::string version;       // uname -v ("#1 SMP PREEMPT_DYNAMIC ..."); "" unread
  std::string model;         // "PREEMPT_RT", "PREEMPT_DYNAMIC", "PREEMPT", "voluntary", "none"
  std::string dynamic_mode;  // the (chosen) word of debugfs' sched/preempt; "" unread
};

// The model the version string names ("PREEMPT_RT" before "PREEMPT_DYNAMIC" before "PREEMPT").
std::string model_of_version(std::string_view version);
// The parenthesised word of sched/preempt: "none voluntary (full) lazy" -> "full"; "" if none.
std::string chosen_preempt_mode(std::string_view text);

PreemptModel probe_preempt(const SysRoot& root);

}  // namespace stepmod::doctor
