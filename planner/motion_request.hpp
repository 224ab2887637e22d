#pragma once
// What the module layer asks of the planner. Units are physical: steps, steps/s, steps/s^2 (the
// module converts the manuals' steps/ms/s). Commands are trivially copyable so they cross threads
// through an SpscRing without allocation.
#include <array>
#include <cstdint>

#include "core/clock.hpp"

namespace stepmod::planner {

enum class Direction : std::int8_t { kCw = 1, kCcw = -1 };
inline constexpr int sign(Direction d) noexcept {
  return static_cast<int>(d);
}
inline constexpr Direction opposite(Direction d) noexcept {
  return d == Direction::kCw ? Direction::kCcw : Direction::kCw;
}

// The manuals' acceleration types (digest section 7.2). k = ramp time factor: 1, 2, 4/3.
enum class AccelShape : std::uint8_t { kConstant = 0, kTriangularS = 1, kTrapezoidalS = 2 };

struct Ramp {
  double rate = 0.0;  // steps/s^2, > 0
  AccelShape shape = AccelShape::kConstant;
};

// A finite move of `steps` (> 0) steps: jump to vs, ramp to vp (or a lower peak: triangle), ramp
// down, last step at vs (digest 7.2, 7.3). vp <= vs means no ramps (constant speed vs... vp).
struct MoveSpec {
  std::int64_t steps = 0;
  Direction dir = Direction::kCw;
  double vs = 1.0;
  double vp = 1.0;
  Ramp accel;
  Ramp decel;
};

// A move without an end (manual/jog move, homing search): runs until stopped. With vp <= vs the
// axis jumps straight to vp ("constant-speed mode", digest 7.8).
struct RunSpec {
  Direction dir = Direction::kCw;
  double vs = 1.0;
  double vp = 1.0;
  Ramp accel;
  Ramp decel;
};

// One blend segment (digest 7.10): reach `speed` within `length` steps using `ramp`.
struct BlendSegment {
  std::int64_t length = 0;
  double speed = 0.0;
  Ramp ramp;
};
inline constexpr std::size_t kMaxBlendSegments = 16;

struct BlendSpec {
  Direction dir = Direction::kCw;
  double vs = 1.0;
  std::uint8_t count = 0;
  std::array<BlendSegment, kMaxBlendSegments> segments{};
  Ramp final_decel;
};

// Encoder follower (3601 fw 4.1, digest 7.12): a motion without an end whose goal moves. `target`
// is the net step count (CW positive) from the follow motion's start that the axis must reach; the
// module sends a new target as the master encoder counts. The planner closes the gap like a
// velocity servo: each step is taken at the highest speed the ramps allow that still lets the axis
// stop on the target (speed^2 <= vs^2 + 2 decel (remaining - 1)), so the steps never run ahead of
// the known target unless the target moves back; a target behind the axis is reached by
// decelerating to vs, reversing and following again. The count is exact: the axis ends on the
// last target it was given.
struct FollowSpec {
  std::int64_t target = 0;
  double vs = 1.0;            // speed jumped to from rest and decelerated to (starting speed)
  double vmax = 1'000'000.0;  // speed limit with a non-zero accel
  double speed = 1.0;         // accel = 0: the speed pending steps are output at (the master's)
  double accel = 0.0;         // steps/s^2; 0 = jump to `speed`
  double decel = 0.0;         // steps/s^2; 0 = stop (and reverse) without a ramp
};

enum class CommandKind : std::uint8_t {
  kMove,            // start `move` as motion `epoch`
  kRun,             // start `run` as motion `epoch`
  kBlend,           // start `blend` as motion `epoch`
  kChangeSpeed,     // running motion `epoch`: ramp to run.vp with run.accel / run.decel
  kStop,            // controlled stop of `epoch`: decelerate to vs with `ramp`, then end
  kStopAfter,       // registration: end `epoch` exactly `steps` steps after the step count at `t`
  kAbort,           // immediate stop of `epoch` (the pulse thread already drops its edges)
  kSetGpo,          // general-purpose output level `level` (3602)
  kSetPulseFormat,  // `level` = true: step + direction outputs, false: CW + CCW pulse outputs
  kFollow,          // start `follow` as motion `epoch` (encoder follower; ends with kStop/kAbort)
  kFollowUpdate,    // follow motion `epoch`: new target, speed and ramps from `follow`
};

struct Command {
  CommandKind kind = CommandKind::kMove;
  std::uint8_t axis = 0;
  std::uint32_t epoch = 0;
  MoveSpec move;
  RunSpec run;
  Ramp ramp;
  std::int64_t steps = 0;
  Nanos t = 0;
  bool level = false;
  BlendSpec blend;
  FollowSpec follow;
};

}  // namespace stepmod::planner
