#pragma once
// What the module layer asks of the planner. Units are physical: steps, steps/s, steps/s^2 (the
// module converts the manuals' steps/ms/s). Commands are trivially copyable so they cross threads
// through an SpscRing without allocation.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <variant>

#include "core/clock.hpp"
#include "planner/path_spec.hpp"
#include "planner/ramp.hpp"

namespace stepmod::planner {

// The speeds of a motion from rest: its direction, starting speed vs, programmed speed vp and the
// two ramps between them (the manuals' ch. 2).
struct MotionSpeeds {
  Direction dir = Direction::kCw;
  double vs = 1.0;
  double vp = 1.0;
  Ramp accel;
  Ramp decel;
};

// A finite move of `steps` (> 0) steps: jump to vs, ramp to vp (or a lower peak: triangle), ramp
// down, last step at vs (the manuals' ch. 2). vp <= vs means no ramps (constant speed vs... vp).
struct MoveSpec : MotionSpeeds {
  std::int64_t steps = 0;
};

// A move without an end (manual/jog move, homing search): runs until stopped. With vp <= vs the
// axis jumps straight to vp ("constant-speed mode", manuals 3601/3202 ch. 4, 3602 ch. 2).
struct RunSpec : MotionSpeeds {};

// One blend segment (manuals 3601/3202 ch. 4-5, 3602 ch. 9): reach `speed` within `length` steps
// using `ramp`.
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

// Encoder follower (3601 fw 4.1, manuals 3601/3202 ch. 4): a motion without an end whose goal
// moves. `target` is the net step count (CW positive) from the follow motion's start that the axis
// must reach; the module sends a new target as the master encoder counts. The planner closes the
// gap like a velocity servo: each step is taken at the highest speed the ramps allow that still
// lets the axis stop on the target (speed^2 <= vs^2 + 2 decel (remaining - 1)), so the steps never
// run ahead of the known target unless the target moves back; a target behind the axis is reached
// by decelerating to vs, reversing and following again. The count is exact: the axis ends on the
// last target it was given.
struct FollowSpec {
  std::int64_t target = 0;
  double vs = 1.0;            // speed jumped to from rest and decelerated to (starting speed)
  double vmax = 1'000'000.0;  // speed limit with a non-zero accel
  double speed = 1.0;         // accel = 0: the speed pending steps are output at (the master's)
  double accel = 0.0;         // steps/s^2; 0 = jump to `speed`
  double decel = 0.0;         // steps/s^2; 0 = stop (and reverse) without a ramp
};

// The payload of each command kind: one small type per kind, so a command carries only what its
// kind needs. A blend's segment table (BlendSpec, 552 bytes) does not travel in a command: the
// control thread hands it over through the planner's per-axis blend slot (Planner::submit_blend)
// and the command only names it.
struct BlendStart {
  std::uint32_t seq = 0;  // the slot's hand-over number (Planner::submit_blend)
};
struct SpeedChange {  // running motion: ramp to vp with accel (up) or decel (down)
  double vp = 0.0;
  Ramp accel;
  Ramp decel;
};
// No trigger time: the stop is planned from the newest planned step (a lookahead late).
inline constexpr Nanos kNoTrigger = std::numeric_limits<Nanos>::min();
struct StopSpec {  // controlled stop: decelerate to vs with `ramp`, then end
  Ramp ramp;
  // When the stop's cause happened (an input edge's timestamp, the scan that saw a Hold):
  // the deceleration starts at max(trigger_t, planner now + a margin), replacing edges already
  // queued for later (AxisControl's cut). kNoTrigger: from the newest planned step.
  Nanos trigger_t = kNoTrigger;
};
struct StopAfterSpec {  // registration: end exactly `steps` steps after the step count at `t`
  Nanos t = 0;
  std::int64_t steps = 0;
  // The motion's own steps output up to `t`, read from the pulse thread's step history by the
  // caller (-1: unknown). Exact where the planner's own conversion of the wall-clock `t` to the
  // motion's time (with the slip of now) is not: after a slip that grew since `t`.
  std::int64_t done_at_t = -1;
};
struct AbortSpec {};  // immediate stop (the pulse thread already drops the motion's edges)
struct GpoSpec {      // general-purpose output level (3602)
  bool level = false;
};
struct PulseFormatSpec {  // true: step + direction outputs, false: CW + CCW pulse outputs
  bool step_dir = true;
};
struct FollowStart {  // encoder follower (ends with a stop or an abort)
  FollowSpec spec;
};
struct FollowUpdate {  // follow motion: new target, speed and ramps
  FollowSpec spec;
};

// The kind is the payload's index in CommandPayload: keep the two lists in the same order.
enum class RequestKind : std::uint8_t {
  kMove,            // MoveSpec: start as motion `epoch`
  kRun,             // RunSpec: start as motion `epoch`
  kBlend,           // BlendStart: start the slot's BlendSpec as motion `epoch`
  kChangeSpeed,     // SpeedChange of running motion `epoch`
  kStop,            // StopSpec: controlled stop of `epoch`
  kStopAfter,       // StopAfterSpec: registration end of `epoch`
  kAbort,           // AbortSpec: immediate stop of `epoch`
  kSetGpo,          // GpoSpec
  kSetPulseFormat,  // PulseFormatSpec
  kFollow,          // FollowStart: start as motion `epoch`
  kFollowUpdate,    // FollowUpdate of follow motion `epoch`
  kPath,            // PathStart: start as motion `epoch`, one coordinate of a path (group of 2)
  kPathResume,      // PathResume: continue the held path as motion `epoch` (group of 2)
  kPathHold,        // PathHold: controlled stop of the running path, both of its axes
};
using CommandPayload = std::variant<MoveSpec, RunSpec, BlendStart, SpeedChange, StopSpec,
                                    StopAfterSpec, AbortSpec, GpoSpec, PulseFormatSpec, FollowStart,
                                    FollowUpdate, PathStart, PathResume, PathHold>;
static_assert(std::variant_size_v<CommandPayload> ==
              static_cast<std::size_t>(RequestKind::kPathHold) + 1);

// Group start: the motions of `size` axes that start together on one time base. Each member's
// start command carries the same id; the planner starts none of them before it holds all (or
// until a command that is not a member arrives), then gives them all one time 0. Ids are the
// caller's: unique among the groups in flight (GroupIds hands them out).
struct GroupTag {
  std::uint32_t id = 0;  // 0: not part of a group
  std::uint8_t size = 0;
};
class GroupIds {
 public:
  GroupTag next(std::uint8_t size) noexcept {
    if (++last_ == 0) ++last_;
    return GroupTag{last_, size};
  }

 private:
  std::uint32_t last_ = 0;
};

struct Command {
  std::uint8_t axis = 0;
  std::uint32_t epoch = 0;
  GroupTag group;  // start commands only
  CommandPayload what;

  RequestKind kind() const noexcept { return static_cast<RequestKind>(what.index()); }
  bool starts_motion() const noexcept {
    const RequestKind k = kind();
    return k == RequestKind::kMove || k == RequestKind::kRun || k == RequestKind::kBlend ||
           k == RequestKind::kFollow || k == RequestKind::kPath || k == RequestKind::kPathResume;
  }
};
// Commands cross threads by copy through an SpscRing: small and trivially copyable.
static_assert(std::is_trivially_copyable_v<Command>);
// A path start (two points, a sweep and a profile) is the largest payload.
static_assert(sizeof(Command) <= 128);

}  // namespace stepmod::planner
