#include "planner/planner.hpp"

#include <algorithm>
#include <bit>

#include "planner/axis_planner.hpp"
#include "planner/wakeup.hpp"

namespace stepmod::planner {

Planner::Planner(std::span<const PlannerAxis> axes, PlannerOptions options)
    : options_(options),
      blend_slots_(std::make_unique<BlendSlot[]>(axes.size())),
      // The ring needs a power of two; round a configured size up rather than fail.
      queue_(std::bit_ceil(std::max<std::size_t>(options.command_queue, 2))) {
  axes_.reserve(axes.size());
  for (const PlannerAxis& a : axes) {
    axes_.push_back(std::make_unique<AxisPlanner>(a, options_));
    axes_.back()->set_path_book(&paths_);
  }
  group_axes_.reserve(axes.size());
}

Planner::~Planner() = default;

bool Planner::submit(const Command& c) noexcept {
  if (!queue_.try_push(c)) return false;
  bump_and_wake(wake_);
  return true;
}

bool Planner::submit_blend(Command c, const BlendSpec& b) noexcept {
  if (c.axis >= axes_.size()) return false;
  BlendSlot& slot = blend_slots_[c.axis];
  // The planner may still be copying the previous blend's table: do not write under it.
  if (slot.taken.load(std::memory_order_acquire) != slot.handed) return false;
  slot.spec = b;
  const std::uint32_t seq = slot.handed + 1;
  c.what = BlendStart{seq};
  if (!submit(c)) return false;  // never handed over: the slot stays free
  slot.handed = seq;
  return true;
}

void Planner::apply(const Command& c, Nanos now) {
  AxisPlanner& axis = *axes_[c.axis];
  if (const auto* blend = std::get_if<BlendStart>(&c.what)) {
    BlendSlot& slot = blend_slots_[c.axis];
    axis.take_blend(slot.spec);
    slot.taken.store(blend->seq, std::memory_order_release);
  }
  paths_.before(c);
  if (const std::optional<Ramp> ramp = paths_.path_stop(c)) {
    if (group_.id != 0) launch_group(now);
    paths_.hold(c, *ramp, now);
    return;
  }
  const bool member = c.group.id != 0 && c.starts_motion();
  // A group is collected from consecutive commands; anything else ends the collection (a member
  // that was never submitted, e.g. a full queue, must not hold the others back).
  if (group_.id != 0 && (!member || c.group.id != group_.id)) launch_group(now);
  if (!member) {
    axis.apply(c, now);
    return;
  }
  if (group_.id == 0) {
    group_ = c.group;
    group_deadline_ = now + options_.start_delay_ns;
  }
  ++group_received_;
  if (axis.prepare_start(c, now)) group_axes_.push_back(c.axis);
  if (group_received_ >= group_.size) launch_group(now);
}

void Planner::launch_group(Nanos now) {
  // One time 0 for all: the latest of the members' earliest possible starts.
  Nanos origin = std::numeric_limits<Nanos>::min();
  for (unsigned a : group_axes_) origin = std::max(origin, axes_[a]->earliest_origin(now));
  for (unsigned a : group_axes_) axes_[a]->launch(origin);
  group_ = GroupTag{};
  group_received_ = 0;
  group_axes_.clear();
}

Nanos Planner::service(Nanos now) {
  Command c;
  while (queue_.try_pop(c)) {
    if (c.axis < axes_.size()) apply(c, now);
  }
  // The members of a group are submitted back to back; one that never comes (its submit failed)
  // holds the others no longer than a start delay.
  Nanos next = now + kIdleServiceInterval;
  if (group_.id != 0) {
    if (now >= group_deadline_) {
      launch_group(now);
    } else {
      next = group_deadline_;
    }
  }
  for (auto& a : axes_) next = std::min(next, a->fill(now));
  return next;
}

}  // namespace stepmod::planner
