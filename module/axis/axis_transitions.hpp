#pragma once
// The one owner of an axis' state: what it is doing (Activity), why its motion is ending early
// (StopCause) and the status latches. The feature objects (homing, manual_move, blend, encoder,
// follower, the axis' commands and inputs) never write them: they report an event, and the table
// of transitions (axis_transitions.cpp) says what it changes in the present state. The table is
// drawn in docs/axis-states.dot and explained in docs/axis-states.md; a unit test keeps the
// drawing and the table the same.
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "module/axis/rules.hpp"

namespace stepmod::module::axis {

// What the axis is doing; a motion is in progress from acceptance until the pulse thread reports
// its end (docs/axis-states.md "States"; the manuals' "Axis Moving" / Busy bits).
enum class Activity : std::uint8_t {
  kIdle,
  kMove,         // absolute / relative move (axis_commands.cpp)
  kEncoderMove,  // absolute / relative move to an encoder count (encoder.cpp)
  kManual,       // manual move, and registration move (manual_move.cpp)
  kHoming,       // Find Home + / - (homing.cpp)
  kBlend,        // blend move (blend.cpp)
  kFollower,     // encoder follower (follower.cpp)
  kCoordinated,  // one axis of a coordinated motion (the 3602's interpolated moves): started and
                 // ended by its coordinator (Axis, "Coordinated motion")
  kCount
};

// Why a motion is ending early; decides the status bits when it has ended.
enum class StopCause : std::uint8_t {
  kNone,
  kHold,
  kExternal,
  kRelease,
  kImmediate,
  kFault,
  kCount
};

// The status and error latches, named as in the manuals (AxisState::latches() reads them as a
// struct), and HoldCoordinated: the Hold state belongs to a coordinated motion, whose
// coordinator resumes it.
enum class Latch : std::uint8_t {
  kMoveComplete,
  kHold,
  kHoldCoordinated,
  kStopped,
  kAtHome,
  kHomeInvalid,
  kInvalidProfile,
  kPositionInvalid,
  kInputError,
  kCommandError,
  kConfigurationError,
  kCount
};
using LatchSet = std::uint16_t;
constexpr LatchSet bit(Latch l) noexcept {
  return static_cast<LatchSet>(1u << static_cast<unsigned>(l));
}
template <typename... L>
constexpr LatchSet latch_set(L... l) noexcept {
  return static_cast<LatchSet>((LatchSet{0} | ... | bit(l)));
}
inline constexpr LatchSet kAllLatches = (1u << static_cast<unsigned>(Latch::kCount)) - 1;

// What happened to the axis, as the feature that saw it reports it (docs/axis-states.md
// "Events"). Each is a row (or a few, by state) of the table.
enum class AxisEvent : std::uint8_t {
  // A motion has been handed to the planner.
  kMoveStarted,
  kEncoderMoveStarted,
  kManualStarted,
  kHomingStarted,
  kHomingSegmentStarted,  // the next motion of a homing sequence
  kBlendStarted,
  kFollowerEntered,
  kCoordinatedBegun,
  // A stop was asked for.
  kHoldRequested,
  kBlendBroughtDown,  // blend programming while the blend runs
  kExternalStop,
  kReleaseStop,
  kImmediateStop,
  kPathFault,      // a coordinated motion cut because of the other axis' fault
  kInputFault,     // an E-stop or an end limit during a motion
  kInvalidChange,  // an invalid runtime change of a manual move
  // A motion or sequence has ended.
  kMotionEnded,    // the pulse thread finished the motion
  kHomingStalled,  // the planner took no motion of the sequence
  kHomingEndedEarly,
  kHomingCompleted,
  kHomingTimedOut,
  kHomingOver,
  kHomingAborted,
  kHomingAbortedByLimit,
  kFollowerLeft,
  kCoordinatedCompleted,
  kCoordinatedHeld,
  kCoordinatedStopped,
  // Status only: the activity stays as it is.
  kNewMove,              // a move is accepted: the previous outcome is cleared
  kNewMoveInputsActive,  // the same, with an E-stop or end limit input active
  kAtTarget,             // a move accepted with nothing to output
  kCommandRefused,
  kProfileRefused,
  kProfileInvalid,
  kHomeInvalid,
  kStartBlocked,
  kResumed,
  kPositionPreset,
  kErrorsReset,
  kCommandErrorCleared,
  kConfigured,
  kConfigurationAccepted,
  kConfigurationRefused,
  kCount
};

// Sets of states, as bits of Activity / StopCause.
using ActivitySet = std::uint16_t;
using CauseSet = std::uint8_t;
constexpr ActivitySet in(Activity a) noexcept {
  return static_cast<ActivitySet>(1u << static_cast<unsigned>(a));
}
constexpr CauseSet when(StopCause c) noexcept {
  return static_cast<CauseSet>(1u << static_cast<unsigned>(c));
}
inline constexpr ActivitySet kAnyActivity = (1u << static_cast<unsigned>(Activity::kCount)) - 1;
inline constexpr ActivitySet kMoving = kAnyActivity & ~in(Activity::kIdle);
inline constexpr CauseSet kAnyCause = (1u << static_cast<unsigned>(StopCause::kCount)) - 1;

// A row: in an activity of `from`, stopping for a cause of `cause_in`, `on` leads to `to` (nullopt:
// unchanged) with the stop cause `cause_to` (nullopt: unchanged); the latches of `clear` are
// cleared, those of `clear_per_module` where the module's rules say so (Move Complete at a preset,
// 3602-MC-02; Input Error at a new move, 3602-IE-C1), then those of `set` are set. `item`: the
// manuals' checklist items the row implements.
struct Transition {
  ActivitySet from;
  CauseSet cause_in;
  AxisEvent on;
  std::optional<Activity> to;
  std::optional<StopCause> cause_to;
  LatchSet set;
  LatchSet clear;
  LatchSet clear_per_module;
  const char* item;
};

// The whole table, in the order rows are looked up (the first match wins).
std::span<const Transition> transitions() noexcept;

// Names for the drawing and the logs (docs/axis-states.dot).
std::string_view name_of(Activity a) noexcept;
std::string_view name_of(StopCause c) noexcept;
std::string_view name_of(AxisEvent e) noexcept;
std::string_view name_of(Latch l) noexcept;  // short: "MC", "PI", ...

// The present state and the only code that changes it (fire()).
class AxisStateMachine {
 public:
  // Power-up (3601-CFG-01): idle, with Configuration Error where the module powers up so.
  explicit AxisStateMachine(const ModuleRules& rules) noexcept;

  Activity activity() const noexcept { return activity_; }
  StopCause stop_cause() const noexcept { return cause_; }
  bool latched(Latch l) const noexcept { return (latches_ & bit(l)) != 0; }

  // Applies the table's row for `ev` in the present state; false (nothing changed) when it has
  // none, e.g. a stop asked for while the motion is stopping already.
  bool fire(AxisEvent ev) noexcept;

 private:
  bool module_clears(Latch l) const noexcept;  // Transition::clear_per_module

  const ModuleRules& rules_;
  Activity activity_ = Activity::kIdle;
  StopCause cause_ = StopCause::kNone;
  LatchSet latches_ = 0;
};

}  // namespace stepmod::module::axis
