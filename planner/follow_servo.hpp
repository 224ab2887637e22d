#pragma once
// A step source: the encoder follower's servo (FollowSpec, manuals 3601/3202 ch. 4). It decides
// each next step of a follow motion (direction, speed, earliest time, status phase) from the latest
// target; the axis planner hands the decision to the edge emitter (the interface:
// planner/step_source.hpp).
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
#include "planner/step_loop.hpp"
#include "planner/step_source.hpp"
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

class FollowServo final : public StepSource {
 public:
  // A step from rest comes no sooner than start_delay after it is planned; `pulse_ns` is the
  // configured step pulse width.
  FollowServo(Nanos start_delay, Nanos pulse_ns) noexcept
      : start_delay_(start_delay), pulse_ns_(pulse_ns) {}

  // StepSource (planner/step_source.hpp). kWait: at rest on the target; kEnd: at rest on it and
  // told to stop. Its steps are whole pulses, and it sets its direction up with a step from rest
  // (not before the planning time).
  Answer next(const StepProgress& p, const StepWindow& w, SourceStep& out) noexcept override;
  Answer plan(StepLoop& loop) noexcept override { return loop.run(*this); }
  FirstStep first_step(std::int64_t /*end*/) noexcept override { return FirstStep{}; }
  double start_speed() const noexcept override { return spec_.vs; }
  double speed_at(double /*tk*/) const noexcept override { return v_; }
  // Its ending is marked when it is decided (every step's trailing edge is already staged).
  Nanos end_time(const StepProgress& /*p*/, Nanos now) const noexcept override { return now; }
  // A stop: the motion ends as soon as it rests on its target.
  bool stop_by_own_law() noexcept override {
    finishing_ = true;
    return true;
  }

  void start(const FollowSpec& s) noexcept {
    spec_ = s;
    pos_ = 0;
    dir_ = 0;
    v_ = 0.0;
    finishing_ = false;
  }
  void update(const FollowSpec& s) noexcept { spec_ = s; }

 private:
  // The follow law alone: the next step after the one at prev_t (`first`: none yet), planned at
  // `now`.
  enum class Next : std::uint8_t { kWait, kFinish, kStep };
  Next decide(Nanos prev_t, bool first, Nanos now, FollowStep& out) noexcept;
  // decide(): the time, phase and pulse width of a step at speed v in direction dir (`cap`: the
  // speed the law may reach).
  void time_step(Nanos prev_t, bool first, Nanos now, double v, int dir, double cap,
                 FollowStep& out) const noexcept;
  // The step `s` was planned: the servo's position and speed move on.
  void taken(const FollowStep& s) noexcept {
    pos_ += s.dir;
    dir_ = s.dir;
    v_ = s.v;
  }

  Nanos start_delay_;
  Nanos pulse_ns_;
  FollowSpec spec_;         // latest target, speed and ramps
  std::int64_t pos_ = 0;    // net steps planned (CW positive) since the motion's start
  int dir_ = 0;             // sense of the newest step: +1 CW, -1 CCW, 0 before the first
  double v_ = 0.0;          // speed of the newest step (steps/s); 0 = at rest
  bool finishing_ = false;  // stop seen: end as soon as the axis rests on its target
};

}  // namespace stepmod::planner
