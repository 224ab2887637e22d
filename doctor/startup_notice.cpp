#include "doctor/startup_notice.hpp"

#include <unistd.h>

namespace stepmod::doctor {

std::string pulse_cpu_notice(const BoardFacts& f) {
  std::string shared;
  if (f.pulse_cpu < 0) {
    shared = "not pinned ([rt] cpu = -1): it shares every CPU";
  } else if (!pulse_cpu_alone(f)) {
    shared = "CPU " + std::to_string(f.pulse_cpu) + " is shared with " +
             std::to_string(f.tenants.user_tasks) + " other threads";
  }
  std::string problems;
  const auto add = [&](const std::string& p) { problems += (problems.empty() ? "" : "; ") + p; };
  if (!shared.empty()) add(shared);
  if (!f.throttle.off() && f.throttle.withheld_us_per_s() > 0) {
    add("real-time throttling takes " + std::to_string(f.throttle.withheld_us_per_s() / 1000) +
        " ms of each second (sched_rt_runtime_us " + std::to_string(*f.throttle.runtime_us) + ")");
  }
  if (!f.preempt.rt) add("the kernel is not PREEMPT_RT (" + f.preempt.model + ")");
  if (problems.empty()) return "";
  return "pulse thread: " + problems +
         ": fast axes may fault on late edges; `stepmodctl doctor` measures the safe step rate "
         "(docs/performance.md, \"A CPU of its own\")";
}

std::string pulse_cpu_notice(int pulse_cpu, const SysRoot& root) {
  return pulse_cpu_notice(probe_board(root, pulse_cpu, static_cast<int>(getpid()),
                                      static_cast<int>(getuid())));
}

}  // namespace stepmod::doctor
