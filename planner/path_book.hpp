#pragma once
// The interpolated paths in the planner: the planner's side of a path group (the module's side is
// planner/path_group.hpp), one owner for everything that spans a path's axes. Which path is held
// and may be resumed (PathResume), which one an axis gave up; the hold of every axis of a path
// from one time (PathHold, or a controlled stop of any one of its axes); a resume that comes
// before the hold has stopped every axis. Paths are named by their group id. Each axis keeps its
// own part (planner/axis_path.cpp). Planner thread only.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/clock.hpp"
#include "planner/motion_request.hpp"

namespace stepmod::planner {

class AxisPlanner;  // planner/axis_planner.hpp

class PathBook {
 public:
  PathBook(const std::vector<std::unique_ptr<AxisPlanner>>& axes, Nanos start_delay) noexcept
      : axes_(axes), start_delay_(start_delay) {}
  PathBook(const PathBook&) = delete;
  PathBook& operator=(const PathBook&) = delete;

  // An axis gave path `id` up (another motion, an abort): it can never be resumed.
  void discard(std::uint32_t id) noexcept {
    if (held_ == id) held_ = 0;
    broken_ = id;
  }
  // Path `id` was held as a whole and none of its axes gave it up since.
  bool resumable(std::uint32_t id) const noexcept { return held_ == id; }

  // Before the planner applies `c`: a path command sees every axis' immediate stops, and a
  // resume that comes before the hold stopped every axis gives the path up.
  void before(const Command& c) noexcept;
  // The ramp if `c` stops a whole path along it (PathHold, or a StopSpec for an axis that
  // follows a path), else nullopt.
  std::optional<Ramp> path_stop(const Command& c) const noexcept;
  // Holds the path axis c.axis follows on every one of its axes from one time, at or after
  // every step any of them has planned.
  void hold(const Command& c, const Ramp& ramp, Nanos now) noexcept;

 private:
  const std::vector<std::unique_ptr<AxisPlanner>>& axes_;
  Nanos start_delay_;
  std::uint32_t held_ = 0;    // the path last held and not discarded since (0: none)
  std::uint32_t broken_ = 0;  // the path last discarded by one of its axes (never resumable)
};

}  // namespace stepmod::planner
