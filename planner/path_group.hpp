#pragma once
// An interpolated path's two axes as one group, the module's side (control thread): both
// coordinates start or resume on one time base (one GroupTag of size 2, submitted back to back)
// or neither does. The planner's side of the same group is planner/path_book.hpp: a hold on
// either axis (MotionPort::hold_path) stops the whole path along it, and only the path it held
// resumes.
#include <cstdint>

#include "planner/motion_port.hpp"
#include "planner/motion_request.hpp"
#include "planner/path_spec.hpp"

namespace stepmod::planner {

class PathGroupPort {
 public:
  // x: the axis following the path's X coordinate, y: its Y.
  PathGroupPort(MotionPort& x, MotionPort& y) noexcept : x_(x), y_(y) {}
  PathGroupPort(const PathGroupPort&) = delete;
  PathGroupPort& operator=(const PathGroupPort&) = delete;

  // The path `p` (relative to the axes' present positions). False: the planner queue refused a
  // coordinate and nothing runs (a coordinate already queued is cut at once).
  bool start(const PathSpec& p) noexcept {
    return both(
        [&](MotionPort& port, PathCoordinate k, GroupTag g) { return port.start_path(p, k, g); });
  }
  // The held path, from where the hold stopped it to its end with a new vector profile. False as
  // for start().
  bool resume(double vp, const Ramp& accel, const Ramp& decel) noexcept {
    return both([&](MotionPort& port, PathCoordinate k, GroupTag g) {
      return port.resume_path(k, vp, accel, decel, g);
    });
  }

 private:
  template <class StartOne>
  bool both(StartOne start_one) noexcept {
    const GroupTag group = ids_.next(2);
    const std::uint32_t ex = start_one(x_, PathCoordinate::kX, group);
    const std::uint32_t ey = ex != 0 ? start_one(y_, PathCoordinate::kY, group) : 0;
    if (ex != 0 && ey == 0) x_.immediate_stop();  // the planner queue is full: start nothing
    return ex != 0 && ey != 0;
  }

  MotionPort& x_;
  MotionPort& y_;
  GroupIds ids_;
};

}  // namespace stepmod::planner
