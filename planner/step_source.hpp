#pragma once
// The one interface of every step source (the model: Klipper's itersolve, where a kinematics is
// one callback and the solver is shared). A source knows its motion law; asked for the next step
// it answers the same way whatever the kind: the step's time, its direction and its share of the
// motion (accelerating, cruising, decelerating) — or that the motion ends, or that its next step
// comes later. The axis planner asks in one loop (planner/step_loop.hpp) and hands every step to
// the edge emitter, which alone knows lines: direction set-up, pulse width, pulse format
// (planner/edge_emitter.hpp).
//
// Sources: ProfileSource (moves, runs, blends), PathSource (one coordinate of an interpolated
// path), FollowServo (the encoder follower). A new motion kind is a new source plus its start
// command (planner/axis_start.cpp picks the source).
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/clock.hpp"
#include "planner/motion_request.hpp"
#include "rt/edge.hpp"

namespace stepmod::planner {

inline constexpr std::int64_t kEndless = std::numeric_limits<std::int64_t>::max();

// A law's time (s) as nanoseconds, rounded to the nearest.
inline Nanos seconds_to_ns(double seconds) noexcept {
  return std::llround(seconds * 1e9);
}

// The motion's progress, kept by the axis planner: the newest step and the motion's time base.
struct StepProgress {
  std::int64_t k = 0;           // steps made so far
  std::int64_t end = kEndless;  // the step count at which the motion ends
  Nanos origin = 0;             // the motion's time 0
  double tk = 0.0;              // time of step k, s from origin
  Nanos tk_ns = 0;              // the same, absolute
};

// When the source is asked: planning time and how far ahead steps are planned (both on the
// motion's time base), and the newest edge the emitter holds for the axis.
struct StepWindow {
  Nanos now = 0;
  Nanos horizon = 0;
  Nanos last_edge = 0;
};

// A source's answer.
struct SourceStep {
  Nanos t = 0;      // leading edge (absolute, the motion's time base); kLater: the step's time
  double ts = 0.0;  // the law's time of the step, s from the motion's time 0
  Direction dir = Direction::kCw;
  rt::Phase phase = rt::Phase::kCruise;  // its share of the motion
  // 0: the pulse stays open until the next step (whose time ends it); > 0: a whole pulse this
  // wide (the next step is not known yet).
  Nanos width = 0;
  // No edge of this step, nor the direction set-up before it, earlier than this.
  Nanos not_before = std::numeric_limits<Nanos>::min();
};

enum class Answer : std::uint8_t {
  kStep,   // `out` is the next step, taken: the source has moved on
  kLater,  // the next step lies beyond the horizon, at out.t in out.dir: not taken yet
  kWait,   // no step until a command changes the motion (the follower at rest on its target)
  kEnd,    // the motion ends where it is
};

class StepLoop;  // planner/step_loop.hpp

// Where the first step of a motion lies, asked when the motion is set up (for the direction
// line's set-up before it).
struct FirstStep {
  bool known = false;  // false: the source sets its direction up with its first step
  double t = 0.0;      // s from the motion's time 0
  rt::Phase phase = rt::Phase::kCruise;
};

class StepSource {
 public:
  StepSource() = default;
  StepSource(const StepSource&) = default;
  StepSource& operator=(const StepSource&) = default;
  virtual ~StepSource() = default;

  // The next step after `p`'s newest one.
  virtual Answer next(const StepProgress& p, const StepWindow& w, SourceStep& out) noexcept = 0;
  // Runs the one fill loop with this source's own type: `return loop.run(*this);` (the loop then
  // calls next() directly, step after step).
  virtual Answer plan(StepLoop& loop) noexcept = 0;
  // The motion's first step (its `end` steps planned), before time 0 is fixed.
  virtual FirstStep first_step(std::int64_t end) noexcept = 0;
  // Starting speed (steps/s), published for the pulse thread's guard (rt/slip.hpp).
  virtual double start_speed() const noexcept = 0;
  // Speed at the newest step, time tk (steps/s; a path: its vector speed).
  virtual double speed_at(double tk) const noexcept = 0;
  // The time an ending without a pending pulse is marked at (the marker edge).
  virtual Nanos end_time(const StepProgress& p, Nanos now) const noexcept {
    (void)now;
    return p.tk_ns;
  }
  // A controlled stop: true if the source stops by its own law (it will answer kEnd); false:
  // the axis planner replans the motion's profile (cut or frontier stop, planner/axis_stops.cpp),
  // which only a ProfileSource has (a path's stop is its hold, planner/path_book.hpp).
  virtual bool stop_by_own_law() noexcept { return false; }
};

}  // namespace stepmod::planner
