#include "daemon/health_words.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <limits>

#include "daemon/daemon_trace.hpp"
#include "daemon/lost_input_watch.hpp"
#include "daemon/module_stack.hpp"

namespace stepmod::tools {

HealthWords::HealthWords(ModuleStack& stack, const Config& config,
                         const LostInputWatch& lost_inputs, ModuleTrace* trace)
    : stack_(stack),
      config_(config),
      lost_inputs_(lost_inputs),
      trace_(trace),
      faults_seen_(stack.shape().axes, 0) {}

ipc::Health HealthWords::scan(std::uint32_t supervisor_flags) {
  ipc::Health h;
  h.flags = supervisor_flags;
  Nanos worst = 0;
  for (unsigned a = 0; a < stack_.shape().axes; ++a) {
    const planner::MotionPort& m = stack_.motion(a);
    const planner::MotionPort::LateFault f = m.late_fault();
    if (f.count != faults_seen_[a]) {
      faults_seen_[a] = f.count;
      log_fault(a, f);
    }
    h.late_faults += f.count;
    worst = std::max(worst, f.worst_late_ns);
    if (late_fault_lasts(m)) h.flags |= STEPMOD_HEALTH_LATE_EDGE;
  }
  h.worst_late_us = static_cast<std::uint32_t>(
      std::min<Nanos>(worst / kNsPerUs, std::numeric_limits<std::uint32_t>::max()));
  if (lost_inputs_.lasts()) h.flags |= STEPMOD_HEALTH_INPUT_LOST;
  if (trace_ != nullptr && trace_->lost()) h.flags |= STEPMOD_HEALTH_TRACE_LOST;
  return h;
}

void HealthWords::log_fault(unsigned axis, const planner::MotionPort::LateFault& f) const {
  spdlog::error(
      "axis {}: late-edge fault at step {}: speed {} steps/s, pause {} us, lag {} steps "
      "(limits: {} steps above the starting speed, {} us at any speed); motion cut, no "
      "burst: the axis is stopped with position invalid (re-home). {} fault(s) on this "
      "axis so far",
      axis + 1, f.step, f.interval_ns > 0 ? kNsPerSec / f.interval_ns : 0, f.late_ns / kNsPerUs,
      f.lag, config_.axes[axis].lag_limit_steps, config_.late_limit_ns / kNsPerUs, f.count);
}

}  // namespace stepmod::tools
