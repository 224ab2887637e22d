#include "planner/planner.hpp"

#include <algorithm>
#include <bit>

#include "planner/axis_planner.hpp"
#include "planner/wakeup.hpp"

namespace stepmod::planner {

Planner::Planner(std::span<const PlannerAxis> axes, PlannerOptions options)
    : options_(options),
      // The ring needs a power of two; round a configured size up rather than fail.
      queue_(std::bit_ceil(std::max<std::size_t>(options.command_queue, 2))) {
  axes_.reserve(axes.size());
  for (const PlannerAxis& a : axes) axes_.push_back(std::make_unique<AxisPlanner>(a, options_));
}

Planner::~Planner() = default;

bool Planner::submit(const Command& c) noexcept {
  if (!queue_.try_push(c)) return false;
  bump_and_wake(wake_);
  return true;
}

Nanos Planner::service(Nanos now) {
  Command c;
  while (queue_.try_pop(c)) {
    if (c.axis < axes_.size()) axes_[c.axis]->apply(c, now);
  }
  Nanos next = now + kIdleServiceInterval;
  for (auto& a : axes_) next = std::min(next, a->fill(now));
  return next;
}

}  // namespace stepmod::planner
