#include "planner/path_book.hpp"

#include <algorithm>
#include <limits>

#include "planner/axis_planner.hpp"

namespace stepmod::planner {

void PathBook::before(const Command& c) noexcept {
  if (c.kind() != RequestKind::kPathResume && c.kind() != RequestKind::kPathHold) return;
  // An immediate stop of either axis (seen by its planner only when it next runs) discards the
  // path: take every axis' aborts into account before the path is held or resumed.
  for (const auto& a : axes_) a->poll_abort();
  if (c.kind() != RequestKind::kPathResume || held_ == 0) return;
  // A resume before the hold has stopped every axis of the path (the module resumes only from
  // its Hold state, when both have stopped): the axes are not at the stop point the resume
  // would start from, so the path is given up rather than jump there.
  for (const auto& a : axes_) {
    if (a->path_id() == held_ && a->path_active()) {
      broken_ = held_;
      held_ = 0;
      break;
    }
  }
}

std::optional<Ramp> PathBook::path_stop(const Command& c) const noexcept {
  if (const auto* h = std::get_if<PathHold>(&c.what)) return h->ramp;
  // A controlled stop of one axis of a path stops the whole path along it.
  const auto* st = std::get_if<StopSpec>(&c.what);
  if (st != nullptr && axes_[c.axis]->follows_path(c.epoch)) return st->ramp;
  return std::nullopt;
}

void PathBook::hold(const Command& c, const Ramp& ramp, Nanos now) noexcept {
  AxisPlanner& sender = *axes_[c.axis];
  if (!sender.follows_path(c.epoch)) return;  // stale: its path is no longer the newest motion
  const std::uint32_t id = sender.path_id();
  const auto member = [&](unsigned i) {
    return i == c.axis || (id != 0 && axes_[i]->path_id() == id);
  };
  // One time for all: no step either axis has planned may be replanned. The axes of a path share
  // one slip (rt/slip.hpp): `now` on their time base.
  Nanos t = now - sender.slip() + start_delay_;
  for (unsigned i = 0; i < axes_.size(); ++i) {
    if (member(i)) t = std::max(t, axes_[i]->path_frontier());
  }
  for (unsigned i = 0; i < axes_.size(); ++i) {
    if (member(i)) axes_[i]->hold_path(t, ramp);
  }
  if (id != 0 && broken_ != id) held_ = id;
}

}  // namespace stepmod::planner
