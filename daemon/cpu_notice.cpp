#include "daemon/cpu_notice.hpp"

#include <spdlog/spdlog.h>

#include <string>

#include "daemon/module_stack.hpp"

namespace stepmod::tools {

CpuNotice::CpuNotice(ModuleStack& stack, const Config& config, const rt::StepOutput& pulse)
    : stack_(stack), config_(config), pulse_(pulse), noticed_epoch_(stack.shape().axes, 0) {}

// Once the motion is past its acceleration, naming its programmed speed there (the planned step
// interval, not a count of steps per scan, which a late scan inflates).
void CpuNotice::scan() {
  for (unsigned a = 0; a < stack_.shape().axes; ++a) {
    planner::MotionPort& m = stack_.motion(a);
    const Nanos interval = m.planned_interval();
    if (interval <= 0 || !m.busy() || noticed_epoch_[a] == m.epoch() ||
        m.phase() == planner::MotionPort::Phase::kAccelerating) {
      continue;
    }
    const Nanos edge_gap = interval / 2;  // two edges per step
    // Only once the thread has measured its wake-ups (before, its spin is a placeholder).
    if (pulse_.wake_p99() == 0 || edge_gap >= pulse_.stay_on_cpu_gap()) continue;
    noticed_epoch_[a] = m.epoch();
    warn(a, interval);
  }
}

void CpuNotice::warn(unsigned axis, Nanos interval) const {
  const Nanos edge_gap = interval / 2;
  spdlog::warn(
      "axis {}: programmed {} steps/s, an edge every {} us: closer than the pulse thread's "
      "wake-up ({} us early; measured p99 wake-up lateness {} us), so the thread stays on its "
      "CPU for this move. {}; a pause slips the move, and one of more than {} steps above the "
      "starting speed (or {} us at any speed) stops the axis (docs/slip.md)",
      axis + 1, kNsPerSec / interval, edge_gap / 1000.0, pulse_.spin_now() / kNsPerUs,
      pulse_.wake_p99() / kNsPerUs,
      config_.rt_cpu >= 0
          ? "Make sure no other thread runs on CPU " + std::to_string(config_.rt_cpu)
          : std::string("This axis needs a CPU of its own ([rt] cpu + isolcpus= "
                        "or a cpuset)"),
      config_.axes[axis].lag_limit_steps, config_.late_limit_ns / kNsPerUs);
}

}  // namespace stepmod::tools
