#pragma once
// A step source: the motion law of moves, runs and blends. Position is the piecewise cubic of the
// manuals' profiles (planner/profile.hpp; the manuals' ch. 2); the shared StepSolver finds the time
// of each step on it. Stops, registration counts and speed changes replan the law from a given
// step. Progress (the newest step k and its time) belongs to the caller (the axis planner), which
// hands each step to the edge emitter (the interface: planner/step_source.hpp).
#include <cstdint>
#include <limits>

#include "planner/motion_request.hpp"
#include "planner/profile.hpp"
#include "planner/step_loop.hpp"
#include "planner/step_source.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

class ProfileSource final : public StepSource {
 public:
  // StepSource (planner/step_source.hpp).
  Answer next(const StepProgress& p, const StepWindow& w, SourceStep& out) noexcept override;
  Answer plan(StepLoop& loop) noexcept override { return loop.run(*this); }
  FirstStep first_step(std::int64_t end) noexcept override;
  double start_speed() const noexcept override { return vs_; }
  double speed_at(double tk) const noexcept override { return velocity_at(tk); }

  struct Start {
    Direction dir;
    std::int64_t end;  // the step count at which the motion ends (kEndless: a run)
  };
  Start start(const MoveSpec& m) noexcept;
  Start start(const RunSpec& r) noexcept;
  Start start(const BlendSpec& b) noexcept;

  struct Step {
    double t;  // s from the motion's time 0
    rt::Phase phase;
  };
  // Step k of a motion ending at `end` (k increasing by one from call to call). Inline: the
  // planner's per-step path.
  Step step(std::int64_t k, std::int64_t end) noexcept {
    if (k >= end) {
      // The last step lands exactly at the profile's end (Tt), not at a rounded solve.
      return Step{phases_.end_time(),
                  phases_.empty() ? rt::Phase::kCruise : phases_[phases_.size() - 1].phase};
    }
    const double t = solver_.time_of(static_cast<double>(k));
    return Step{t, phases_[solver_.phase_index()].phase};
  }
  double velocity_at(double t) const noexcept { return phases_.velocity_at(t); }
  rt::Phase phase_at(double t) const noexcept;
  // The law was replanned at this time (s): nothing earlier can be evaluated any more.
  double start_time() const noexcept { return phases_.start_time(); }
  const Ramp& decel() const noexcept { return decel_; }
  bool can_change_speed() const noexcept { return can_change_speed_; }

  // A running motion at step k (time tk) ramps to c.vp and cruises.
  void change_speed(std::int64_t k, double tk, const SpeedChange& c) noexcept;
  // Where a stop from step k (time t) with `ramp` ends: k itself when there is nothing to ramp
  // down (constant-speed mode, at or below vs, no rate), else k + the ramp's steps (>= 1).
  std::int64_t stop_end(std::int64_t k, double t, const Ramp& ramp) const noexcept;
  // From step k (time tk): cruise at its speed, then ramp to vs so that the motion ends exactly
  // on step `end`. A ramp that does not fit is made steeper; with `exact_ramp` the ramp's rate is
  // always adjusted to cover the whole rest (no cruise).
  void replan_to_end(std::int64_t k, double tk, std::int64_t end, const Ramp& ramp,
                     bool exact_ramp) noexcept;

 private:
  // What every start does once phases_ holds the law: the solver on it and the motion's facts.
  struct Facts {
    Direction dir;
    double vs;
    Ramp decel;
    bool constant_speed;
    bool can_change_speed;
  };
  Start begin(const Facts& f, std::int64_t end) noexcept;

  PhaseList phases_;
  StepSolver solver_;
  double vs_ = 1.0;
  Direction dir_ = Direction::kCw;
  Ramp decel_;
  bool constant_speed_ = false;    // started with vp <= vs: stops end after the next step
  bool can_change_speed_ = false;  // a Run that no stop has ended yet
};

// The per-step path, inline (StepLoop::run calls it directly).
inline Answer ProfileSource::next(const StepProgress& p, const StepWindow& /*w*/,
                                  SourceStep& out) noexcept {
  auto [t, ph] = step(p.k + 1, p.end);
  if (t < p.tk) t = p.tk;
  Nanos ns = p.origin + seconds_to_ns(t);
  if (ns < p.tk_ns) ns = p.tk_ns;
  out.t = ns;
  out.ts = t;
  out.dir = dir_;
  out.phase = ph;
  out.width = 0;
  out.not_before = std::numeric_limits<Nanos>::min();
  return Answer::kStep;
}

}  // namespace stepmod::planner
