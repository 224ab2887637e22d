#pragma once
// A step source: the encoder follower's servo (FollowSpec, digest 7.12). It decides each next
// step of a follow motion (direction, speed, earliest time, status phase) from the latest target;
// the axis planner turns the decision into edges (planner/edge_emitter.hpp).
//
// The law: the speed of the next step is the highest that
//   * the accel allows from the previous step's speed (v^2 + 2a per step; 0 = jump to `speed`),
//   * still lets the axis stop on the target (vs^2 + 2d (n - 1) for n steps left; 0 = no limit),
//   * stays within vmax (accel > 0) or the master's `speed` (accel = 0);
// the step interval is 2 / (v_prev + v_next), exact for a constant rate. A target behind the axis
// (it moved back) is handled by decelerating at d down to vs, stopping and reversing. Steps are
// decided when planned, at most the lookahead ahead of their time, so they only ever use a known
// target and the count stays exact.
#include <cstdint>

#include "core/clock.hpp"
#include "planner/motion_request.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

struct FollowStep {
  int dir = 0;     // +1 CW, -1 CCW
  double v = 0.0;  // speed of this step (steps/s)
  Nanos t = 0;     // earliest time of its leading edge
  rt::Phase phase = rt::Phase::kCruise;
  Nanos width = 0;  // pulse width: the next step may come after half the shortest period
  bool from_rest = false;
};

class FollowServo {
 public:
  enum class Next : std::uint8_t { kWait, kFinish, kStep };

  void start(const FollowSpec& s) noexcept {
    *this = FollowServo{};
    spec_ = s;
  }
  void update(const FollowSpec& s) noexcept { spec_ = s; }
  // A stop: the motion ends as soon as it rests on its target.
  void finish() noexcept { finishing_ = true; }
  double speed() const noexcept { return v_; }

  // The next step after the one at prev_t (`first`: none yet), planned at `now`; a step from rest
  // comes no sooner than now + start_delay. kWait: at rest on the target; kFinish: at rest on it
  // and told to stop.
  Next next(Nanos prev_t, bool first, Nanos now, Nanos start_delay, Nanos pulse_ns,
            FollowStep& out) noexcept;
  // The step `s` was planned: the servo's position and speed move on.
  void taken(const FollowStep& s) noexcept {
    pos_ += s.dir;
    dir_ = s.dir;
    v_ = s.v;
  }

 private:
  FollowSpec spec_;         // latest target, speed and ramps
  std::int64_t pos_ = 0;    // net steps planned (CW positive) since the motion's start
  int dir_ = 0;             // sense of the newest step: +1 CW, -1 CCW, 0 before the first
  double v_ = 0.0;          // speed of the newest step (steps/s); 0 = at rest
  bool finishing_ = false;  // stop seen: end as soon as the axis rests on its target
};

}  // namespace stepmod::planner
