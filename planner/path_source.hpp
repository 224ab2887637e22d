#pragma once
// A step source: one coordinate of an interpolated path (planner/path_spec.hpp, 3602 manual ch. 3).
// The manuals' profile (ch. 2) runs on the path length s, s(t) a PhaseList like a move's;
// the coordinate q(s) comes from the path's geometry (planner/path_law.hpp). The axis steps when
// q reaches its next integer in its direction of travel, so its count n is always within one
// step of q (hysteresis), and it turns where q reverses. X along an arc on which it rises from 0
// to a peak of 2.6 and falls back to 0:
//
//   s        0 ...... s1 ...... s2 ...... sp ...... s2' ...... s3 ...... s4
//   q(s)     0        1         2         2.6       2          1         0
//   event             step +1   step +1   turn      (none)     step -1   step -1
//   n        0        1         2         2         2          1         0
//                      ____      ____                           ____      ____
//   STEP  ____________|    |____|    |_________________________|    |____|    |____
//         _________________________________
//   DIR                                    |__________________________________________  (1 = CW)
//                                          |<--- dir_setup --->| s3
//
//   The time of each step is the profile's time of its s: t_k = t(s_k) on s(t) (the shared
//   StepSolver), the same function on both axes. A turn writes the direction line after the
//   previous pulse and at least dir_setup_ns before the turned step (EdgeEmitter::reverse); only
//   a turn sooner than that (a radius of a few steps at a high speed) delays the turned step.
//
// Both axes of a path run their own PathSource with the same spec and the same time 0 (a group
// start), so they compute the identical s(t) and their steps interleave as the path demands,
// without talking to each other. The last step of the last segment lands exactly on the end
// count at the profile's end time, whatever the rounding.
//
// Hold (PathHold): from a time T both axes replan s(t) alike (the law up to T kept, then the
// ramp down to vs), so both stop at the same point of the path; resume continues from there to
// the path's end with a new profile. T is at or after every step either axis has planned, and the
// axis planner plans a path step only once it lies within the lookahead (peek() before take()),
// so T is never more than a lookahead away even when an axis waits long for its next crossing:
// next() answers kLater for a step beyond the horizon and keeps it unplanned.
// Progress (the newest step's time) belongs to the caller (the interface:
// planner/step_source.hpp).
#include <cstddef>
#include <cstdint>
#include <limits>

#include "planner/path_law.hpp"
#include "planner/path_spec.hpp"
#include "planner/profile.hpp"
#include "planner/ramp.hpp"
#include "planner/step_loop.hpp"
#include "planner/step_source.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

class PathSource final : public StepSource {
 public:
  // StepSource (planner/step_source.hpp).
  Answer next(const StepProgress& p, const StepWindow& w, SourceStep& out) noexcept override;
  Answer plan(StepLoop& loop) noexcept override { return loop.run(*this); }
  FirstStep first_step(std::int64_t end) noexcept override;
  double start_speed() const noexcept override { return vs_; }
  double speed_at(double tk) const noexcept override { return vector_speed_at(tk); }

  struct Start {
    Direction dir;     // of the first step (kCw if there is none)
    std::int64_t end;  // the number of steps this motion makes (0: none)
  };
  // A new path: coordinate `c` of `spec`, from its start point to its end point.
  Start start(const PathSpec& spec, PathCoordinate c) noexcept;
  // Continues the held path (hold()) from its stop point to the path's end with a new profile
  // (the path's vs). The steps count from 0 again (a new motion).
  Start resume(double vp, const Ramp& accel, const Ramp& decel) noexcept;
  // Controlled stop along the path from time t (s from the motion's time 0, at or after every
  // step already taken): the law is kept up to t, then ramps down to vs with `ramp`. Returns the
  // steps this motion still makes (from the ones taken so far). A ramp that would end at or
  // beyond the path's end changes nothing (the path ends as soon).
  std::int64_t hold(double t, const Ramp& ramp) noexcept;
  // Where the present law stops: the fraction of the path (1: its end).
  double stop_point() const noexcept { return u_lim_; }
  double length() const noexcept { return law_.length(); }

  // The net count (the coordinate's step count from the path's start) after the steps taken.
  std::int64_t count() const noexcept { return count_; }
  // Path length at the newest step taken.
  double s() const noexcept { return u_ * law_.length(); }

  double vector_speed_at(double t) const noexcept { return phases_.velocity_at(t); }
  double path_position_at(double t) const noexcept { return phases_.position_at(t); }
  const PathLaw& law() const noexcept { return law_; }

 private:
  struct Step {
    double t;  // s from the motion's time 0
    rt::Phase phase;
    Direction dir;
  };
  // The next step (while steps remain): computed once, taken by take().
  const Step& peek() noexcept {
    if (!next_valid_) plan_next();
    return next_.step;
  }
  Step take() noexcept {
    if (!next_valid_) plan_next();
    next_valid_ = false;
    seg_ = next_.seg;
    count_ = next_.n;
    u_ = next_.u;
    return next_.step;
  }
  struct Next {
    std::size_t seg = 0;
    std::int64_t n = 0;
    double u = 0.0;
    Step step{};
  };
  void plan_next() noexcept;
  // Steps from the present count to the stop point's count.
  std::int64_t remaining() const noexcept;
  Start begin() noexcept;

  PathLaw law_;
  PhaseList phases_;
  StepSolver solver_;
  double vs_ = 1.0;
  // Progress: the segment, count and point of the newest step taken.
  std::size_t seg_ = 0;
  std::int64_t count_ = 0;
  double u_ = 0.0;
  // The stop point: its fraction of the path, its segment and the count reached there.
  double u_lim_ = 1.0;
  std::size_t lim_seg_ = 0;
  std::int64_t lim_target_ = 0;
  Next next_;
  bool next_valid_ = false;
};

// The per-step path, inline (StepLoop::run calls it directly).
inline Answer PathSource::next(const StepProgress& p, const StepWindow& w,
                               SourceStep& out) noexcept {
  const Step& nx = peek();
  Nanos ns = p.origin + seconds_to_ns(nx.t);
  if (ns < p.tk_ns) ns = p.tk_ns;
  out.t = ns;
  out.ts = nx.t;
  out.dir = nx.dir;
  out.phase = nx.phase;
  out.width = 0;
  out.not_before = std::numeric_limits<Nanos>::min();
  // An axis that crawls near its coordinate's reversal may wait long for its next crossing:
  // planned now, that step could not be replanned by a hold any more.
  if (ns > w.horizon) return Answer::kLater;
  take();
  return Answer::kStep;
}

}  // namespace stepmod::planner
