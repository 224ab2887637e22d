#pragma once
// The encoder follower of one axis (3601 Ch.4 "Encoder Follower", firmware 4.1): entering and
// leaving follower mode, the ratio and ramps that may change on the fly, and the planner's follow
// motion that the encoder counts steer. It owns the follower session's state.
#include <cstdint>
#include <optional>

#include "module/axis/axis_state.hpp"

namespace stepmod::module::axis {

class Follower {
 public:
  explicit Follower(AxisState& ax) noexcept : ax_(ax) {}

  // A rising Manual + / - with the follower flag set.
  void command(const AxisCommand& c, planner::Direction dir);
  // Every command-mode scan of a configured axis (`prev`: the previous scan's command image):
  // entering on the flag's rising edge, the per-scan rules, leaving.
  void scan(const AxisCommand& c, const AxisCommand& prev);
  // After every encoder count change while following, at the edge's time.
  void counted(Nanos t);

 private:
  bool enter(const AxisCommand& c);
  bool params(const AxisCommand& c);
  planner::FollowSpec spec() const noexcept;
  void start_motion();
  void send(Nanos t, bool force);
  void cut();   // a CE while following: output stops at once, follower mode is left
  void exit();  // follower mode is left: Stopped (3601-STP-05)
  // scan(), by situation: the flag rose outside follower mode; the flag cleared while following;
  // the flag held with a direction in force (its changes, ratio and ramps on the fly).
  void flag_rose(const AxisCommand& c);
  void flag_cleared(const AxisCommand& c);
  void steer(const AxisCommand& c);
  // No more output: the steps already owed still go out, then the follow motion stops.
  void stop_output();

  struct Session {
    std::optional<CommandKind> key;  // direction command in force: + same sense, - reverse
    int sense = 0;                   // +1 same, -1 reverse, 0 no output
    std::int32_t mul = 1;            // multiplier
    std::int32_t div = 1;            // divisor
    std::int64_t accel = 0;          // steps/s^2 (0 = jump)
    std::int64_t decel = 0;
    std::int64_t rem = 0;           // fraction of a step owed, in 1/div steps (0 <= rem < div)
    std::int64_t last_encoder = 0;  // encoder count already turned into steps
    std::int64_t target = 0;        // pulse count (motion.steps()) the axis must reach
    std::int64_t base = 0;          // pulse count at the running follow motion's start
    bool running = false;           // our follow motion takes new targets (not told to stop)
    bool motion = false;            // our follow motion may still be busy
    bool leaving = false;           // the flag cleared: leave once the owed steps are out
    bool dirty = false;             // target or parameters not yet sent to the planner
    Nanos sent_t = 0;               // time of the last update sent from an encoder edge
    Nanos count_t = 0;              // time of the last encoder count
    double speed = 0.0;             // master's rate x ratio (steps/s); 0 = not known yet
  };

  AxisState& ax_;
  Session f_;
};

}  // namespace stepmod::module::axis
