// The table of an axis' transitions (docs/axis-states.md; drawn in docs/axis-states.dot) and the
// only code that writes the activity, the stop cause and the latches.
#include "module/axis/axis_transitions.hpp"

#include <array>

namespace stepmod::module::axis {

namespace {

using A = Activity;
using C = StopCause;
using E = AxisEvent;
using L = Latch;

constexpr ActivitySet kAbsRelOrManual = in(A::kMove) | in(A::kEncoderMove) | in(A::kManual);
constexpr CauseSet kControlledStop = when(C::kHold) | when(C::kExternal);
constexpr CauseSet kCutStop = when(C::kImmediate) | when(C::kFault);
constexpr std::optional<Activity> kSame{};
constexpr std::optional<StopCause> kKeep{};

// Starting: a motion accepted and handed to the planner.
constexpr Transition kStarts[] = {
    {in(A::kIdle), kAnyCause, E::kMoveStarted, A::kMove, C::kNone, 0, 0, 0,
     "3601 Ch.4 Absolute & Relative Moves"},
    {in(A::kIdle), kAnyCause, E::kEncoderMoveStarted, A::kEncoderMove, C::kNone, 0, 0, 0,
     "3601 Ch.4 Encoder Move"},
    {in(A::kIdle), kAnyCause, E::kManualStarted, A::kManual, C::kNone, 0, 0, 0,
     "3601 Ch.4 Manual Move, Registration Move"},
    {in(A::kIdle), kAnyCause, E::kHomingStarted, A::kHoming, C::kNone, 0, 0, 0,
     "3601 Ch.4 Find Home"},
    {in(A::kHoming), kAnyCause, E::kHomingSegmentStarted, kSame, C::kNone, 0, 0, 0,
     "3601 Ch.4 Find Home (each motion)"},
    {in(A::kIdle), kAnyCause, E::kBlendStarted, A::kBlend, C::kNone, 0, 0, 0,
     "3601 Ch.4 Blend Move"},
    {in(A::kIdle), kAnyCause, E::kFollowerEntered, A::kFollower, C::kNone, 0, 0, 0,
     "3601 Ch.4 Encoder Follower"},
    {kAnyActivity, kAnyCause, E::kCoordinatedBegun, A::kCoordinated, C::kNone, 0, 0, 0,
     "3602 Ch.3 Interpolated Move Profiles"},
};

// Stopping: the motion runs on until the pulse thread reports its end (kMotionEnded).
constexpr Transition kStops[] = {
    {in(A::kMove) | in(A::kCoordinated), when(C::kNone), E::kHoldRequested, kSame, C::kHold, 0, 0,
     0, "3601-HLD-01, 3602-HLD-01"},
    {in(A::kBlend), when(C::kNone), E::kBlendBroughtDown, kSame, C::kHold, 0, 0, 0,
     "3601-CE-22, 3202-CE-19"},
    {kAbsRelOrManual | in(A::kCoordinated), when(C::kNone), E::kExternalStop, kSame, C::kExternal,
     0, 0, 0, "3601-HLD-02/03, STP-01"},
    {in(A::kManual), when(C::kNone), E::kReleaseStop, kSame, C::kRelease, 0, 0, 0,
     "3601-STP-01, CE-07, CE-26"},
    {kMoving, kAnyCause, E::kImmediateStop, kSame, C::kImmediate, latch_set(L::kPositionInvalid),
     latch_set(L::kMoveComplete), 0, "3601-STP-03, PI-02, PI-07"},
    {kMoving, kAnyCause, E::kPathFault, kSame, C::kFault, latch_set(L::kPositionInvalid),
     latch_set(L::kMoveComplete), 0, "3602-PI-04, PI-07"},
    {kMoving, kAnyCause, E::kInputFault, kSame, C::kFault,
     latch_set(L::kPositionInvalid, L::kInputError), latch_set(L::kMoveComplete), 0,
     "3601-IE-01/02, PI-03/04, STP-02/04"},
    {in(A::kManual), kAnyCause, E::kInvalidChange, kSame, C::kImmediate, 0, 0, 0,
     "3601-CE-17/19/30..33 (A10: no PI)"},
};

// Ending: the outcome of a motion by its activity and stop cause.
constexpr Transition kEnds[] = {
    {in(A::kMove) | in(A::kEncoderMove), when(C::kNone), E::kMotionEnded, A::kIdle, C::kNone,
     latch_set(L::kMoveComplete), 0, 0, "3601-MC-01"},
    {in(A::kManual), when(C::kNone), E::kMotionEnded, A::kIdle, C::kNone, 0, 0, 0,
     "3601-STP-N1 (one-shot)"},
    {in(A::kMove), kControlledStop, E::kMotionEnded, A::kIdle, C::kNone, latch_set(L::kHold), 0, 0,
     "3601-HLD-01/02/03"},
    {in(A::kEncoderMove) | in(A::kManual), kControlledStop, E::kMotionEnded, A::kIdle, C::kNone,
     latch_set(L::kStopped), 0, 0, "3601-STP-01"},
    {kAbsRelOrManual, when(C::kRelease) | kCutStop, E::kMotionEnded, A::kIdle, C::kNone,
     latch_set(L::kStopped), 0, 0, "3601-STP-01/02/03/04"},
    {in(A::kBlend), when(C::kNone), E::kMotionEnded, A::kIdle, C::kNone,
     latch_set(L::kMoveComplete), 0, 0, "3601-MC-01"},
    {in(A::kBlend), kCutStop, E::kMotionEnded, A::kIdle, C::kNone, latch_set(L::kStopped), 0, 0,
     "3601-STP-02/03/04"},
    {in(A::kBlend), kControlledStop | when(C::kRelease), E::kMotionEnded, A::kIdle, C::kNone, 0, 0,
     0, "3601-MC-02, STP-N1"},
    {in(A::kHoming), kAnyCause, E::kMotionEnded, kSame, C::kNone, 0, 0, 0,
     "3601 Ch.4 Find Home (the sequence goes on)"},
    {in(A::kHoming), kAnyCause, E::kHomingStalled, A::kIdle, kKeep, latch_set(L::kPositionInvalid),
     0, 0, "3601 Ch.4 Find Home (planner full)"},
    {in(A::kHoming), kAnyCause, E::kHomingEndedEarly, A::kIdle, kKeep,
     latch_set(L::kPositionInvalid, L::kStopped), 0, 0, "3601-PI-03 (re-home)"},
    {in(A::kHoming), kAnyCause, E::kHomingCompleted, A::kIdle, kKeep, latch_set(L::kAtHome),
     latch_set(L::kPositionInvalid, L::kHomeInvalid), 0, "3601-AH-01, PI-C1, HI-C1"},
    {in(A::kHoming), kAnyCause, E::kHomingTimedOut, kSame, kKeep, latch_set(L::kHomeInvalid), 0, 0,
     "3602-HI-07"},
    {in(A::kHoming), kAnyCause, E::kHomingOver, A::kIdle, kKeep, 0, 0, 0, "3602-HI-07"},
    {in(A::kHoming), kAnyCause, E::kHomingAborted, A::kIdle, kKeep, latch_set(L::kStopped), 0, 0,
     "3601-STP-02/03"},
    {in(A::kHoming), kAnyCause, E::kHomingAbortedByLimit, A::kIdle, kKeep, 0, 0, 0, "3601-STP-04"},
    {in(A::kFollower), kAnyCause, E::kFollowerLeft, A::kIdle, C::kNone, latch_set(L::kStopped), 0,
     0, "3601-STP-05"},
    {in(A::kCoordinated), kAnyCause, E::kCoordinatedCompleted, A::kIdle, C::kNone,
     latch_set(L::kMoveComplete), 0, 0, "3602-MC-01"},
    {in(A::kCoordinated), kAnyCause, E::kCoordinatedHeld, A::kIdle, C::kNone,
     latch_set(L::kHold, L::kHoldCoordinated), 0, 0, "3602-HLD-01"},
    {in(A::kCoordinated), kAnyCause, E::kCoordinatedStopped, A::kIdle, C::kNone, 0, 0, 0,
     "3602-HLD-01 (the other axis)"},
};

// Status only, in any state.
constexpr Transition kStatus[] = {
    {kAnyActivity, kAnyCause, E::kNewMove, kSame, kKeep, 0,
     latch_set(L::kMoveComplete, L::kHold, L::kHoldCoordinated, L::kStopped, L::kAtHome,
               L::kInputError),
     0, "3601-MC-03, HLD-C1, IE-C1, STP-C1"},
    {kAnyActivity, kAnyCause, E::kNewMoveInputsActive, kSame, kKeep, 0,
     latch_set(L::kMoveComplete, L::kHold, L::kHoldCoordinated, L::kStopped, L::kAtHome),
     latch_set(L::kInputError), "3602-IE-C1"},
    {kAnyActivity, kAnyCause, E::kAtTarget, kSame, kKeep, latch_set(L::kMoveComplete), 0, 0,
     "3601-MC-01"},
    {kAnyActivity, kAnyCause, E::kCommandRefused, kSame, kKeep, latch_set(L::kCommandError), 0, 0,
     "3601 Ch.6 Command Error list"},
    {kAnyActivity, kAnyCause, E::kProfileRefused, kSame, kKeep,
     latch_set(L::kCommandError, L::kInvalidProfile), 0, 0, "3601 Ch.6 Invalid Profile list"},
    {kAnyActivity, kAnyCause, E::kProfileInvalid, kSame, kKeep, latch_set(L::kInvalidProfile), 0, 0,
     "3601-IP-21, 3202-IP-11/15"},
    {kAnyActivity, kAnyCause, E::kHomeInvalid, kSame, kKeep, latch_set(L::kHomeInvalid), 0, 0,
     "3601 Ch.6 Home Invalid list"},
    {kAnyActivity, kAnyCause, E::kStartBlocked, kSame, kKeep, latch_set(L::kInputError), 0, 0,
     "3601-IE-03 (A15)"},
    {kAnyActivity, kAnyCause, E::kResumed, kSame, kKeep, 0, latch_set(L::kHold, L::kInputError), 0,
     "3601 Ch.4 Resume Move, HLD-C1"},
    {kAnyActivity, kAnyCause, E::kPositionPreset, kSame, kKeep, 0, latch_set(L::kPositionInvalid),
     latch_set(L::kMoveComplete), "3601-PI-C1, MC-03, 3602-MC-02"},
    {kAnyActivity, kAnyCause, E::kErrorsReset, kSame, kKeep, 0,
     latch_set(L::kCommandError, L::kInputError, L::kHomeInvalid, L::kInvalidProfile), 0,
     "3601-CE-L2, IE-C1, HI-C1 (A7)"},
    {kAnyActivity, kAnyCause, E::kCommandErrorCleared, kSame, kKeep, 0, latch_set(L::kCommandError),
     0, "3601-CE-01, CE-23"},
    {kAnyActivity, kAnyCause, E::kConfigured, kSame, kKeep, latch_set(L::kPositionInvalid),
     kAllLatches, 0, "3601-CFG-13, PI-01"},
    {kAnyActivity, kAnyCause, E::kConfigurationAccepted, kSame, kKeep, 0,
     latch_set(L::kConfigurationError), 0, "3601 Ch.3 Configuration Mode"},
    {kAnyActivity, kAnyCause, E::kConfigurationRefused, kSame, kKeep,
     latch_set(L::kConfigurationError), 0, 0, "3601 Ch.6 Configuration Error list"},
};

template <std::size_t... N>
constexpr auto join(const Transition (&... parts)[N]) {
  std::array<Transition, (N + ...)> all{};
  std::size_t i = 0;
  ((std::copy(std::begin(parts), std::end(parts), all.begin() + static_cast<std::ptrdiff_t>(i)),
    i += N),
   ...);
  return all;
}

constexpr auto kTable = join(kStarts, kStops, kEnds, kStatus);

constexpr std::string_view kActivityNames[] = {"Idle",   "Move",  "EncoderMove", "Manual",
                                               "Homing", "Blend", "Follower",    "Coordinated"};
constexpr std::string_view kCauseNames[] = {"none",    "hold",      "external",
                                            "release", "immediate", "fault"};
constexpr std::string_view kEventNames[] = {"MoveStarted",
                                            "EncoderMoveStarted",
                                            "ManualStarted",
                                            "HomingStarted",
                                            "HomingSegmentStarted",
                                            "BlendStarted",
                                            "FollowerEntered",
                                            "CoordinatedBegun",
                                            "HoldRequested",
                                            "BlendBroughtDown",
                                            "ExternalStop",
                                            "ReleaseStop",
                                            "ImmediateStop",
                                            "PathFault",
                                            "InputFault",
                                            "InvalidChange",
                                            "MotionEnded",
                                            "HomingStalled",
                                            "HomingEndedEarly",
                                            "HomingCompleted",
                                            "HomingTimedOut",
                                            "HomingOver",
                                            "HomingAborted",
                                            "HomingAbortedByLimit",
                                            "FollowerLeft",
                                            "CoordinatedCompleted",
                                            "CoordinatedHeld",
                                            "CoordinatedStopped",
                                            "NewMove",
                                            "NewMoveInputsActive",
                                            "AtTarget",
                                            "CommandRefused",
                                            "ProfileRefused",
                                            "ProfileInvalid",
                                            "HomeInvalid",
                                            "StartBlocked",
                                            "Resumed",
                                            "PositionPreset",
                                            "ErrorsReset",
                                            "CommandErrorCleared",
                                            "Configured",
                                            "ConfigurationAccepted",
                                            "ConfigurationRefused"};
constexpr std::string_view kLatchNames[] = {
    "MC", "Hold", "HoldCoordinated", "Stopped", "AtHome", "HI", "IP", "PI", "IE", "CE", "CfgE"};
static_assert(std::size(kActivityNames) == static_cast<std::size_t>(Activity::kCount));
static_assert(std::size(kCauseNames) == static_cast<std::size_t>(StopCause::kCount));
static_assert(std::size(kEventNames) == static_cast<std::size_t>(AxisEvent::kCount));
static_assert(std::size(kLatchNames) == static_cast<std::size_t>(Latch::kCount));

bool has(ActivitySet s, Activity a) noexcept {
  return (s & in(a)) != 0;
}
bool has(CauseSet s, StopCause c) noexcept {
  return (s & when(c)) != 0;
}

}  // namespace

std::span<const Transition> transitions() noexcept {
  return kTable;
}

std::string_view name_of(Activity a) noexcept {
  return kActivityNames[static_cast<std::size_t>(a)];
}
std::string_view name_of(StopCause c) noexcept {
  return kCauseNames[static_cast<std::size_t>(c)];
}
std::string_view name_of(AxisEvent e) noexcept {
  return kEventNames[static_cast<std::size_t>(e)];
}
std::string_view name_of(Latch l) noexcept {
  return kLatchNames[static_cast<std::size_t>(l)];
}

AxisStateMachine::AxisStateMachine(const ModuleRules& rules) noexcept : rules_(rules) {
  // 3601-CFG-01: power-up in command mode with Configuration Error (the 3202: without).
  if (rules_.powers_up_with_configuration_error) fire(AxisEvent::kConfigurationRefused);
}

bool AxisStateMachine::fire(AxisEvent ev) noexcept {
  for (const Transition& t : kTable) {
    if (t.on != ev || !has(t.from, activity_) || !has(t.cause_in, cause_)) continue;
    if (t.to) activity_ = *t.to;
    if (t.cause_to) cause_ = *t.cause_to;
    LatchSet clear = t.clear;
    for (unsigned l = 0; l < static_cast<unsigned>(Latch::kCount); ++l) {
      const auto latch = static_cast<Latch>(l);
      if ((t.clear_per_module & bit(latch)) != 0 && module_clears(latch)) clear |= bit(latch);
    }
    latches_ = static_cast<LatchSet>((latches_ & ~clear) | t.set);
    return true;
  }
  return false;
}

bool AxisStateMachine::module_clears(Latch l) const noexcept {
  switch (l) {
    case Latch::kMoveComplete:
      return rules_.preset_clears_move_complete;  // 3602-MC-02
    case Latch::kInputError:
      return !rules_.input_error_kept_while_inputs_active;  // 3602-IE-C1
    default:
      return true;
  }
}

}  // namespace stepmod::module::axis
