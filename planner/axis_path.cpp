// AxisPlanner: this axis' part of an interpolated path (planner/path_source.hpp): its start and
// resume, its hold along the path, and the path book shared with the path's other axes.
#include <variant>

#include "planner/axis_planner.hpp"

namespace stepmod::planner {

AxisPlanner::SourceStart AxisPlanner::start_path(const Command& c) noexcept {
  PathSource::Start st{Direction::kCw, 0};
  if (const auto* ps = std::get_if<PathStart>(&c.what)) {
    discard_path();  // a new path replaces a held one
    st = path_.start(ps->spec, ps->coordinate);
    path_state_ = PathState::kRunning;
    path_id_ = c.group.id;
  } else {
    const auto& r = std::get<PathResume>(c.what);
    const bool resumable = path_state_ == PathState::kHeld &&
                           (path_id_ == 0 || (book_ != nullptr && book_->resumable(path_id_)));
    if (resumable) {
      st = path_.resume(r.vp, r.accel, r.decel);
      path_state_ = PathState::kRunning;
      path_id_ = c.group.id;
    } else {
      discard_path();  // ends at once, no step
    }
  }
  return {&path_, st.dir, st.end};
}

void AxisPlanner::discard_path() noexcept {
  if (path_state_ == PathState::kNone) return;
  if (book_ != nullptr && path_id_ != 0) book_->discard(path_id_);
  path_state_ = PathState::kNone;
}

void AxisPlanner::hold_path(Nanos t, const Ramp& ramp) noexcept {
  if (path_state_ == PathState::kNone) return;
  path_state_ = PathState::kHeld;
  const std::int64_t left = path_.hold(static_cast<double>(t - m_.at.origin) * 1e-9, ramp);
  // Its steps are all made: only the point moved.
  if (!m_.active || source_ != &path_ || m_.held) return;
  m_.at.end = m_.at.k + left;
  if (left == 0) finish_at_frontier();
}

}  // namespace stepmod::planner
