#include "planner/axis_planner.hpp"

#include <memory>

namespace stepmod::planner {

AxisPlanner::AxisPlanner(const PlannerAxis& axis, const PlannerOptions& options) noexcept
    : control_(axis.control),
      feedback_(axis.feedback),
      timing_(axis.timing),
      opt_(options),
      out_(axis.edges, axis.timing),
      follow_(options.start_delay_ns, axis.timing.step_pulse_ns) {}

Nanos AxisPlanner::slip() const noexcept {
  if (feedback_ == nullptr || m_.epoch == 0) return 0;
  const std::uint64_t s = feedback_->slip.load(std::memory_order_acquire);
  // Another motion's (the pulse thread has not reached this one yet): none yet.
  if (rt::packed_epoch(s) != m_.epoch) return 0;
  return static_cast<Nanos>(rt::packed_value(s)) * kNsPerUs;
}

double AxisPlanner::frontier_speed() const noexcept {
  return m_.active ? source_->speed_at(m_.at.tk) : 0.0;
}

std::int64_t AxisPlanner::planned_steps_at(Nanos t) const noexcept {
  return out_.steps_at(t, m_.at.k);
}

}  // namespace stepmod::planner
