// The table of an axis' transitions (docs/axis-states.md; drawn in docs/axis-states.dot) and the
// only code that writes the activity, the stop cause and the latches.
#include "module/axis/axis_transitions.hpp"

#include <array>

namespace stepmod::module::axis {

namespace {

using A = Activity;
using C = StopCause;
using E = AxisEvent;
using namespace action;

constexpr ActivitySet kAbsRelOrManual = in(A::kMove) | in(A::kEncoderMove) | in(A::kManual);
constexpr CauseSet kControlledStop = when(C::kHold) | when(C::kExternal);
constexpr CauseSet kCutStop = when(C::kImmediate) | when(C::kFault);
constexpr Set kClearOutcome =
    kClearMoveComplete | kClearHold | kClearHoldCoordinated | kClearStopped | kClearAtHome;
constexpr std::optional<Activity> kSame{};
constexpr std::optional<StopCause> kKeep{};

// Starting: a motion accepted and handed to the planner.
constexpr Transition kStarts[] = {
    {in(A::kIdle), kAnyCause, E::kMoveStarted, A::kMove, C::kNone, kNone,
     "3601 Ch.4 Absolute & Relative Moves"},
    {in(A::kIdle), kAnyCause, E::kEncoderMoveStarted, A::kEncoderMove, C::kNone, kNone,
     "3601 Ch.4 Encoder Move"},
    {in(A::kIdle), kAnyCause, E::kManualStarted, A::kManual, C::kNone, kNone,
     "3601 Ch.4 Manual Move, Registration Move"},
    {in(A::kIdle), kAnyCause, E::kHomingStarted, A::kHoming, C::kNone, kNone,
     "3601 Ch.4 Find Home"},
    {in(A::kHoming), kAnyCause, E::kHomingSegmentStarted, kSame, C::kNone, kNone,
     "3601 Ch.4 Find Home (each motion)"},
    {in(A::kIdle), kAnyCause, E::kBlendStarted, A::kBlend, C::kNone, kNone, "3601 Ch.4 Blend Move"},
    {in(A::kIdle), kAnyCause, E::kFollowerEntered, A::kFollower, C::kNone, kNone,
     "3601 Ch.4 Encoder Follower"},
    {kAnyActivity, kAnyCause, E::kCoordinatedBegun, A::kCoordinated, C::kNone, kNone,
     "3602 Ch.3 Interpolated Move Profiles"},
};

// Stopping: the motion runs on until the pulse thread reports its end (kMotionEnded).
constexpr Transition kStops[] = {
    {in(A::kMove) | in(A::kCoordinated), when(C::kNone), E::kHoldRequested, kSame, C::kHold, kNone,
     "3601-HLD-01, 3602-HLD-01"},
    {in(A::kBlend), when(C::kNone), E::kBlendBroughtDown, kSame, C::kHold, kNone,
     "3601-CE-22, 3202-CE-19"},
    {kAbsRelOrManual | in(A::kCoordinated), when(C::kNone), E::kExternalStop, kSame, C::kExternal,
     kNone, "3601-HLD-02/03, STP-01"},
    {in(A::kManual), when(C::kNone), E::kReleaseStop, kSame, C::kRelease, kNone,
     "3601-STP-01, CE-07, CE-26"},
    {kMoving, kAnyCause, E::kImmediateStop, kSame, C::kImmediate,
     kSetPositionInvalid | kClearMoveComplete, "3601-STP-03, PI-02, PI-07"},
    {kMoving, kAnyCause, E::kPathFault, kSame, C::kFault, kSetPositionInvalid | kClearMoveComplete,
     "3602-PI-04, PI-07"},
    {kMoving, kAnyCause, E::kInputFault, kSame, C::kFault,
     kSetPositionInvalid | kClearMoveComplete | kSetInputError,
     "3601-IE-01/02, PI-03/04, STP-02/04"},
    {in(A::kManual), kAnyCause, E::kInvalidChange, kSame, C::kImmediate, kNone,
     "3601-CE-17/19/30..33 (A10: no PI)"},
};

// Ending: the outcome of a motion by its activity and stop cause.
constexpr Transition kEnds[] = {
    {in(A::kMove) | in(A::kEncoderMove), when(C::kNone), E::kMotionEnded, A::kIdle, C::kNone,
     kSetMoveComplete, "3601-MC-01"},
    {in(A::kManual), when(C::kNone), E::kMotionEnded, A::kIdle, C::kNone, kNone,
     "3601-STP-N1 (one-shot)"},
    {in(A::kMove), kControlledStop, E::kMotionEnded, A::kIdle, C::kNone, kSetHold,
     "3601-HLD-01/02/03"},
    {in(A::kEncoderMove) | in(A::kManual), kControlledStop, E::kMotionEnded, A::kIdle, C::kNone,
     kSetStopped, "3601-STP-01"},
    {kAbsRelOrManual, when(C::kRelease) | kCutStop, E::kMotionEnded, A::kIdle, C::kNone,
     kSetStopped, "3601-STP-01/02/03/04"},
    {in(A::kBlend), when(C::kNone), E::kMotionEnded, A::kIdle, C::kNone, kSetMoveComplete,
     "3601-MC-01"},
    {in(A::kBlend), kCutStop, E::kMotionEnded, A::kIdle, C::kNone, kSetStopped,
     "3601-STP-02/03/04"},
    {in(A::kBlend), kControlledStop | when(C::kRelease), E::kMotionEnded, A::kIdle, C::kNone, kNone,
     "3601-MC-02, STP-N1"},
    {in(A::kHoming), kAnyCause, E::kMotionEnded, kSame, C::kNone, kNone,
     "3601 Ch.4 Find Home (the sequence goes on)"},
    {in(A::kHoming), kAnyCause, E::kHomingStalled, A::kIdle, kKeep, kSetPositionInvalid,
     "3601 Ch.4 Find Home (planner full)"},
    {in(A::kHoming), kAnyCause, E::kHomingEndedEarly, A::kIdle, kKeep,
     kSetPositionInvalid | kSetStopped, "3601-PI-03 (re-home)"},
    {in(A::kHoming), kAnyCause, E::kHomingCompleted, A::kIdle, kKeep,
     kSetAtHome | kClearPositionInvalid | kClearHomeInvalid, "3601-AH-01, PI-C1, HI-C1"},
    {in(A::kHoming), kAnyCause, E::kHomingTimedOut, kSame, kKeep, kSetHomeInvalid, "3602-HI-07"},
    {in(A::kHoming), kAnyCause, E::kHomingOver, A::kIdle, kKeep, kNone, "3602-HI-07"},
    {in(A::kHoming), kAnyCause, E::kHomingAborted, A::kIdle, kKeep, kSetStopped, "3601-STP-02/03"},
    {in(A::kHoming), kAnyCause, E::kHomingAbortedByLimit, A::kIdle, kKeep, kNone, "3601-STP-04"},
    {in(A::kFollower), kAnyCause, E::kFollowerLeft, A::kIdle, C::kNone, kSetStopped, "3601-STP-05"},
    {in(A::kCoordinated), kAnyCause, E::kCoordinatedCompleted, A::kIdle, C::kNone, kSetMoveComplete,
     "3602-MC-01"},
    {in(A::kCoordinated), kAnyCause, E::kCoordinatedHeld, A::kIdle, C::kNone,
     kSetHold | kSetHoldCoordinated, "3602-HLD-01"},
    {in(A::kCoordinated), kAnyCause, E::kCoordinatedStopped, A::kIdle, C::kNone, kNone,
     "3602-HLD-01 (the other axis)"},
};

// Status only, in any state.
constexpr Transition kStatus[] = {
    {kAnyActivity, kAnyCause, E::kNewMove, kSame, kKeep, kClearOutcome | kClearInputError,
     "3601-MC-03, HLD-C1, IE-C1, STP-C1"},
    {kAnyActivity, kAnyCause, E::kNewMoveInputsActive, kSame, kKeep,
     kClearOutcome | kClearInputErrorUnlessKept, "3602-IE-C1"},
    {kAnyActivity, kAnyCause, E::kAtTarget, kSame, kKeep, kSetMoveComplete, "3601-MC-01"},
    {kAnyActivity, kAnyCause, E::kCommandRefused, kSame, kKeep, kSetCommandError,
     "3601 Ch.6 Command Error list"},
    {kAnyActivity, kAnyCause, E::kProfileRefused, kSame, kKeep,
     kSetCommandError | kSetInvalidProfile, "3601 Ch.6 Invalid Profile list"},
    {kAnyActivity, kAnyCause, E::kProfileInvalid, kSame, kKeep, kSetInvalidProfile,
     "3601-IP-21, 3202-IP-11/15"},
    {kAnyActivity, kAnyCause, E::kHomeInvalid, kSame, kKeep, kSetHomeInvalid,
     "3601 Ch.6 Home Invalid list"},
    {kAnyActivity, kAnyCause, E::kStartBlocked, kSame, kKeep, kSetInputError, "3601-IE-03 (A15)"},
    {kAnyActivity, kAnyCause, E::kResumed, kSame, kKeep, kClearHold | kClearInputError,
     "3601 Ch.4 Resume Move, HLD-C1"},
    {kAnyActivity, kAnyCause, E::kPositionPreset, kSame, kKeep,
     kClearPositionInvalid | kClearMoveCompleteOnPreset, "3601-PI-C1, MC-03, 3602-MC-02"},
    {kAnyActivity, kAnyCause, E::kErrorsReset, kSame, kKeep,
     kClearCommandError | kClearInputError | kClearHomeInvalid | kClearInvalidProfile,
     "3601-CE-L2, IE-C1, HI-C1 (A7)"},
    {kAnyActivity, kAnyCause, E::kCommandErrorCleared, kSame, kKeep, kClearCommandError,
     "3601-CE-01, CE-23"},
    {kAnyActivity, kAnyCause, E::kConfigured, kSame, kKeep,
     kClearAllLatches | kClearHoldCoordinated | kSetPositionInvalid, "3601-CFG-13, PI-01"},
    {kAnyActivity, kAnyCause, E::kConfigurationAccepted, kSame, kKeep, kClearConfigurationError,
     "3601 Ch.3 Configuration Mode"},
    {kAnyActivity, kAnyCause, E::kConfigurationRefused, kSame, kKeep, kSetConfigurationError,
     "3601 Ch.6 Configuration Error list"},
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
constexpr std::string_view kActionNames[] = {"+MC",
                                             "-MC",
                                             "-MC(3602)",
                                             "+Hold",
                                             "-Hold",
                                             "+HoldCoordinated",
                                             "-HoldCoordinated",
                                             "+Stopped",
                                             "-Stopped",
                                             "+AtHome",
                                             "-AtHome",
                                             "+HI",
                                             "-HI",
                                             "+IP",
                                             "-IP",
                                             "+PI",
                                             "-PI",
                                             "+IE",
                                             "-IE",
                                             "-IE(unless kept)",
                                             "+CE",
                                             "-CE",
                                             "+CfgE",
                                             "-CfgE",
                                             "-all"};
static_assert(std::size(kActivityNames) == static_cast<std::size_t>(Activity::kCount));
static_assert(std::size(kCauseNames) == static_cast<std::size_t>(StopCause::kCount));
static_assert(std::size(kEventNames) == static_cast<std::size_t>(AxisEvent::kCount));
static_assert(std::size(kActionNames) == action::kCount);

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
std::string_view name_of_action(unsigned bit) noexcept {
  return bit < action::kCount ? kActionNames[bit] : std::string_view{};
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
    apply(t.actions);
    return true;
  }
  return false;
}

void AxisStateMachine::apply(action::Set a) noexcept {
  Latches& l = latches_;
  const auto on = [a](action::Set bit) { return (a & bit) != 0; };
  if (on(kClearAllLatches)) l = Latches{};
  if (on(kClearMoveComplete)) l.move_complete = false;
  if (on(kClearMoveCompleteOnPreset) && rules_.preset_clears_move_complete) {
    l.move_complete = false;
  }
  if (on(kClearHold)) l.hold = false;
  if (on(kClearHoldCoordinated)) hold_coordinated_ = false;
  if (on(kClearStopped)) l.stopped = false;
  if (on(kClearAtHome)) l.at_home = false;
  if (on(kClearHomeInvalid)) l.home_invalid = false;
  if (on(kClearInvalidProfile)) l.invalid_profile = false;
  if (on(kClearPositionInvalid)) l.position_invalid = false;
  if (on(kClearInputError)) l.input_error = false;
  if (on(kClearInputErrorUnlessKept) && !rules_.input_error_kept_while_inputs_active) {
    l.input_error = false;
  }
  if (on(kClearCommandError)) l.command_error = false;
  if (on(kClearConfigurationError)) l.configuration_error = false;
  if (on(kSetMoveComplete)) l.move_complete = true;
  if (on(kSetHold)) l.hold = true;
  if (on(kSetHoldCoordinated)) hold_coordinated_ = true;
  if (on(kSetStopped)) l.stopped = true;
  if (on(kSetAtHome)) l.at_home = true;
  if (on(kSetHomeInvalid)) l.home_invalid = true;
  if (on(kSetInvalidProfile)) l.invalid_profile = true;
  if (on(kSetPositionInvalid)) l.position_invalid = true;
  if (on(kSetInputError)) l.input_error = true;
  if (on(kSetCommandError)) l.command_error = true;
  if (on(kSetConfigurationError)) l.configuration_error = true;
}

}  // namespace stepmod::module::axis
