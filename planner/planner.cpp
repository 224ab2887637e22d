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
  fill_slip_.resize(axes.size());
}

Planner::~Planner() = default;

bool Planner::submit(const Command& c) noexcept {
  if (!queue_.try_push(c)) return false;
  bump_and_wake(*wake_);
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
  if (member && c.group.id == launched_.id && launched_.missing > 0) {
    // Issue 18: a member the control thread submitted after the start delay had run out (a
    // loaded machine: the thread was preempted between the members' starts) starts on its
    // group's time 0, not on one of its own: its edges are late from the first, the pulse
    // engine adds that lateness to the group's shared slip (rt/slip.hpp), and the group keeps
    // its relative timing (a path its shape) instead of one axis trailing by the delay.
    // (Never before its own last edge or its direction set-up: then the same as the group's.)
    --launched_.missing;
    if (axis.prepare_start(c, now)) {
      axis.launch(axis.earliest_origin(launched_.origin - options_.start_delay_ns));
    }
    return;
  }
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
  const bool incomplete = !group_axes_.empty() && group_.size > group_received_;
  launched_ = Launched{group_.id, incomplete ? group_.size - group_received_ : 0, origin};
  group_ = GroupTag{};
  group_received_ = 0;
  group_axes_.clear();
}

Nanos Planner::service(Nanos now) {
  // Before the queue is drained: a command submitted after this read is not counted as served.
  const std::uint32_t seen = wake_->load(std::memory_order_acquire);
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
  // The axes of a running path fill their rings to one horizon on their shared time base, from
  // one read of the group's slip: the pulse thread publishes it to the members one after the
  // other, two reads may straddle an increase, and the axis that read the smaller slip would
  // plan further ahead; held off after that, the planner would let it run ahead of the other
  // by as much (docs/slip.md). Slip only grows within a motion: the largest read is the newest.
  for (unsigned i = 0; i < axes_.size(); ++i) fill_slip_[i] = axes_[i]->slip();
  for (unsigned i = 0; i < axes_.size(); ++i) {
    const std::uint32_t id = axes_[i]->path_active() ? axes_[i]->path_id() : 0;
    for (unsigned j = 0; id != 0 && j < axes_.size(); ++j) {
      if (axes_[j]->path_active() && axes_[j]->path_id() == id) {
        fill_slip_[i] = std::max(fill_slip_[i], fill_slip_[j]);
      }
    }
  }
  for (unsigned i = 0; i < axes_.size(); ++i) {
    next = std::min(next, axes_[i]->fill(now, fill_slip_[i]));
  }
  if (group_.id == 0) served_.store(seen, std::memory_order_release);
  return next;
}

}  // namespace stepmod::planner
