#pragma once
// The homing sequence of one axis (Find Home + / -): its start checks, its steps and pauses, and
// what an input edge or the end of one of its motions does (3601 Ch.4 "Find Home"). It owns the
// sequence's state; the axis hands it the command, the scans, the input edges while it runs, and
// the end of each motion.
#include <cstdint>

#include "module/axis/axis_state.hpp"

namespace stepmod::module::axis {

class Homing {
 public:
  explicit Homing(AxisState& ax) noexcept : ax_(ax) {}

  // Find Home in `dir`: checks the command and starts the sequence (Activity::kHoming).
  void command(const AxisCommand& c, planner::Direction dir);
  // Every command-mode scan while homing: pause timers, backplane proximity bit edges.
  void scan(const AxisCommand& c, Nanos now);
  // The 2-s pauses; also called while a configuration request waits for the end (CE-01).
  void timers(Nanos now);
  // Every input edge while homing (home, limits, E-stop, marker); the generic rules are skipped.
  void on_input(const InputEvent& e, bool was_active, bool now_active);
  // A motion of the sequence has ended (the pulse thread finished or aborted it).
  void motion_ended(StopCause cause);

  // The steps of the sequence (the tables in homing.cpp say which event leads where).
  enum class Step : std::uint8_t {
    kSearch,       // Vp toward the commanded direction, looking for home / proximity
    kApproach,     // proximity seen: slowing to (or at) Vs, looking for the final edge
    kFoundStop,    // H-A: home found, controlled stop to Vs
    kPause1,       // 2 s before reversing (after the found-stop or an end limit)
    kReverse,      // Vp opposite, until the home (proximity) signal is passed
    kReverseStop,  // controlled stop after passing it
    kPause2,       // 2 s before the creep
    kCreep,        // Vs (no ramp) toward the commanded direction
    kLimitStop,    // immediate stop at the end limit ahead (H-C)
    kFinishing,    // immediate stop at the home event; completes when the motion has ended
    kTimedOut,     // 3602 homing timeout: controlled stop, then the sequence is over (HI)
  };
  enum class Event : std::uint8_t {
    kHomeRise,
    kHomeFall,
    kProxRise,
    kProxFall,
    kMarker,
    kMotionEnd,
    kPauseOver
  };

 private:
  bool admitted(const AxisCommand& c, planner::Direction dir);
  void start(const AxisCommand& c, planner::Direction dir);
  void event(Event ev);
  void limit(bool ahead);
  bool run(planner::Direction d, bool creep);
  void fail();
  void timeout(Nanos now);

  struct Sequence {
    planner::Direction dir = planner::Direction::kCw;  // commanded direction
    Step step = Step::kSearch;
    std::uint8_t variant = 0;     // index of the step table (HomingVariant)
    bool segment = false;         // a motion of the sequence is in progress
    bool limit_reversed = false;  // reversed from the end limit ahead (H-C) or started at it
    bool limit_error = false;     // ended by a limit error (no Stopped, 3601-STP-04)
    bool prox = false;            // backplane proximity bit as last seen
    Nanos pause_end = -1;         // end of the running pause; -1: starts at the next scan
    Nanos deadline = -1;          // homing timeout's expiry; -1: set at the first scan
    double vp = 0;
    planner::Ramp accel;
    planner::Ramp decel;
  };

  AxisState& ax_;
  Sequence h_;
};

}  // namespace stepmod::module::axis
