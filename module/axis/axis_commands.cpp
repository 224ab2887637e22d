// Command mode: the scan's order, the command edges (3601 Ch.4 general note 3) and the plain
// commands of the
// 3601 manual Ch.4 (absolute/relative move, Hold, Resume, Immediate Stop, Preset Position, Reset
// Errors). Every rejection names the checklist item (the manual's Ch.6 lists) it implements.
#include <cstdint>
#include <limits>
#include <optional>

#include "module/axis/axis.hpp"

namespace stepmod::module::axis {
namespace {

// Whether a position fits the modules' signed 32-bit registers (A32).
constexpr bool fits_int32(std::int64_t v) noexcept {
  return v >= std::numeric_limits<std::int32_t>::min() &&
         v <= std::numeric_limits<std::int32_t>::max();
}
// Whether a step count fits: its magnitude, either way (a count of 2^31 does not, CW or CCW; the
// interpolated path draws the same line: tests/module/interp_3602_test.cpp, IP_03).
constexpr bool count_fits_int32(std::int64_t steps) noexcept {
  return steps >= -std::int64_t{std::numeric_limits<std::int32_t>::max()} &&
         steps <= std::numeric_limits<std::int32_t>::max();
}

}  // namespace

// One command-mode scan: level commands and runtime monitors first (a released manual command
// stops the axis even while CE is set), then the command edges.
void Axis::command_mode_scan(const AxisCommand& c, Nanos now) {
  // A19 (3602 config MSW bit 14, 3202 bit 28): a disabled axis ignores commands and stays idle.
  if (st_.configured && st_.cfg.disabled) return;
  manual_.levels(c);
  const CommandSet rising = c.commands.rising_since(prev_.commands);
  if (!st_.configured) {
    if (!rising.empty()) command_edge(c, rising, now);
    return;
  }
  manual_.scan(c, rising, now);
  encoder_.scan();
  follower_.scan(c, prev_);
  if (st_.activity() == Activity::kHoming) homing_.scan(c, now);
  blend_.programming_scan(c, prev_);
  if (!rising.empty()) {
    command_edge(c, rising, now);
  } else if (c.commands.empty() && c.store_min_registration && !prev_.store_min_registration &&
             !st_.latches().command_error) {
    manual_.store_min_registration(
        c);  // no command set, the store flag rising (3601 Ch.4 "New Command Bit")
  }
}

void Axis::command_edge(const AxisCommand& c, const CommandSet& rising, Nanos now) {
  if (const std::optional<CommandKind> kind = admitted_command(c, rising)) {
    dispatch_command(c, *kind, now);
  }
}

std::optional<CommandKind> Axis::admitted_command(const AxisCommand& c, const CommandSet& rising) {
  // 3601-CE-L1: while CE is set, only Reset Errors is looked at (Immediate Stop included).
  if (st_.latches().command_error && !rising.has(CommandKind::kResetErrors)) return {};
  // 3601-CE-02 / CE-12: more than one command at a time. A33: an undefined command bit counts as
  // a command.
  if (c.commands.count() > 1) {
    st_.reject(items::kSeveralCommands, "%u command bits set at once",
               static_cast<unsigned>(c.commands.count()));
    return {};
  }
  if (rising.has(CommandKind::kUndefined)) {
    st_.reject(items::kUndefinedCommand, "an undefined command bit is set");  // A33
    return {};
  }
  // The manual: "The 3601 module has to be configured before starting any operations."
  if (!st_.configured) {
    st_.reject(items::kNotConfigured, "not configured: configure the axis first");
    return {};
  }
  // The dialect's word-level rules for this command (3601-CE-09, CE-15, CE-21: words or the
  // command LSW that must be 0).
  if (c.words_invalid && c.words_item != nullptr) {
    st_.reject(*c.words_item);
    return {};
  }
  if (c.words_invalid) {
    st_.reject(items::kWordsNotZero, "words that must be 0 with this command are not");
    return {};
  }
  const auto kind = rising.single();
  if (!kind) return {};
  // 3202-CE-05 / IP-03 / HI-04: reserved command words not 0.
  if (c.reserved_words_nonzero) {
    st_.reject_profile(items::kReservedWords, "reserved command words are not 0");
    if (*kind == CommandKind::kFindHomeCw || *kind == CommandKind::kFindHomeCcw) {
      st_.fire(AxisEvent::kHomeInvalid);
    }
    return {};
  }
  return kind;
}

void Axis::dispatch_command(const AxisCommand& c, CommandKind kind, Nanos now) {
  switch (kind) {
    case CommandKind::kAbsoluteMove:
      command_move(c, true);
      break;
    case CommandKind::kRelativeMove:
      command_move(c, false);
      break;
    case CommandKind::kHold:
      command_hold(now);
      break;
    case CommandKind::kResume:
      command_resume(c);
      break;
    case CommandKind::kImmediateStop:
      command_immediate_stop();
      break;
    case CommandKind::kFindHomeCw:
      homing_.command(c, planner::Direction::kCw);
      break;
    case CommandKind::kFindHomeCcw:
      homing_.command(c, planner::Direction::kCcw);
      break;
    case CommandKind::kManualCw:
    case CommandKind::kManualCcw: {
      const auto dir =
          kind == CommandKind::kManualCw ? planner::Direction::kCw : planner::Direction::kCcw;
      if (c.follower) {
        follower_.command(c, dir);
      } else {
        manual_.command(c, dir, now);
      }
      break;
    }
    case CommandKind::kPresetPosition:
      command_preset_position(c);
      break;
    case CommandKind::kPresetEncoder:
      encoder_.preset(c);
      break;
    case CommandKind::kResetErrors:
      command_reset_errors();
      break;
    case CommandKind::kRunBlendCw:
      blend_.run(planner::Direction::kCw);
      break;
    case CommandKind::kRunBlendCcw:
      blend_.run(planner::Direction::kCcw);
      break;
    case CommandKind::kUndefined:
    case CommandKind::kCount:
      break;  // refused above
  }
}

// Absolute and Relative moves: 3601 manual Ch.4 "Absolute & Relative Moves".
void Axis::command_move(const AxisCommand& c, bool absolute) {
  // 3601-CE-03: a move while another is in progress; the running move is unaffected.
  if (st_.moving()) {
    st_.reject(items::kMoveWhileMoving, "a move while a motion is running");
    return;
  }
  // 3601-CE-04 / IP-02: target outside the module's range (3601: -8,388,608..8,388,607) or not a
  // valid number in the module's encoding.
  if (!st_.target_in_range(c.target)) {
    st_.reject_profile(items::kOutOfRange, "target out of range %d..%d", st_.rules.target_min,
                       st_.rules.target_max);
    return;
  }
  const auto profile = st_.read_profile(c, true);
  if (!profile) return;
  // 3601-CE-14 / IP-11: an encoder move needs the quadrature encoder.
  if (c.encoder_move && !st_.cfg.quadrature_encoder) {
    st_.reject_profile(items::kNoEncoder, "encoder move without the encoder configured");
    return;
  }
  if (c.encoder_move) {
    encoder_.move(c, absolute);
    return;
  }
  // 3601-CE-06: an absolute move needs a valid position.
  if (absolute && st_.latches().position_invalid) {
    st_.reject(items::kAbsoluteWithPi, "absolute move while the position is invalid");
    return;
  }
  const std::int64_t steps = absolute ? *c.target - st_.position() : *c.target;
  const std::int64_t end = absolute ? *c.target : st_.position() + *c.target;
  // 3601/3602-IP-03 "profile overflows internal registers" (A32): IP + CE when the planned step
  // count or the position at the end does not fit the firmware's signed 32-bit registers. Only
  // the 3602 gets there in practice: an absolute move from far outside the +-2^30 box of its
  // targets and presets, or a relative move past 2^31 - 1; elsewhere the ranges refuse it first.
  if (!count_fits_int32(steps) || !fits_int32(end)) {
    st_.reject_profile(items::kProfileOverflow, "the move does not fit 32-bit registers");
    return;
  }
  const planner::Direction dir = steps < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  if (st_.inputs_block_start(dir)) return;
  st_.clear_move_outcome();
  move_target_ = end;
  if (steps == 0) {
    st_.fire(AxisEvent::kAtTarget);  // already at the target: nothing to output
    return;
  }
  st_.start_abs_rel(steps, *profile);
}

// Hold: 3601 manual Ch.4 "Hold Move".
void Axis::command_hold(Nanos now) {
  const Activity running = st_.activity();
  if (running == Activity::kEncoderMove) return;  // A4: ignored, no CE (encoder.cpp)
  if (running == Activity::kMove) {
    // 3202-CE-07: "because the module is already decelerating" (rules.hpp).
    if (st_.rules.hold_ignored_while_decelerating &&
        st_.motion.phase() == planner::MotionPort::Phase::kDecelerating) {
      return;
    }
    // 3601-HLD-01. A hold already under way (or the External input's) needs nothing more: the
    // table has no row for it.
    if (st_.fire(AxisEvent::kHoldRequested)) st_.motion.stop(st_.move_decel, now);
    return;
  }
  if (running == Activity::kCoordinated) {
    // A coordinated motion stops along its path, all of its axes (3602-HLD-01).
    if (st_.fire(AxisEvent::kHoldRequested)) st_.motion.hold_path(st_.move_decel);
    return;
  }
  if (running == Activity::kBlend) {
    blend_.hold();  // 3601-CE-23: CE, the blend continues, CE clears at its end
    return;
  }
  // 3601-CE-07: Hold while no absolute/relative move is in progress. During a manual move the
  // motion also stops, controlled (A43).
  st_.reject(items::kHoldNotHoldable, "Hold without an absolute/relative move");
  if (running == Activity::kManual && st_.fire(AxisEvent::kReleaseStop)) {
    st_.motion.stop(st_.move_decel, now);
  }
}

// Resume: the remaining distance to the held move's target, with the speed, accel, decel and
// S-curve selection given now (3601 manual Ch.4 "Resume Move").
void Axis::command_resume(const AxisCommand& c) {
  // 3601-CE-08: Resume when not in the Hold state.
  if (!st_.latches().hold || st_.moving()) {
    st_.reject(items::kResumeNotHeld, "Resume while not in Hold");
    return;
  }
  const auto profile = st_.read_profile(c, true);
  if (!profile) return;
  if (st_.hold_coordinated()) {
    coordinated_resume_ = profile;  // its coordinator continues the path (A39)
    return;
  }
  const std::int64_t remaining = held_target_ - st_.position();
  const planner::Direction dir = remaining < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  if (st_.inputs_block_start(dir)) return;
  st_.fire(AxisEvent::kResumed);
  move_target_ = held_target_;
  if (remaining == 0) {
    st_.fire(AxisEvent::kAtTarget);
    return;
  }
  // 7.5: if the External input is still active the move again yields one step and holds.
  st_.start_abs_rel(remaining, *profile);
}

// Immediate Stop: no deceleration; position invalid. A6: at rest nothing changes.
void Axis::command_immediate_stop() {
  if (st_.moving()) st_.immediate_stop(StopCause::kImmediate);  // 3601-PI-02, STP-03
}

// Preset Position: 3601 manual Ch.4 "Preset Position". The dialect's word rules (3601-CE-09:
// speed, accel and decel words 0; 3601-CE-15: command LSW 0) were checked at dispatch.
void Axis::command_preset_position(const AxisCommand& c) {
  // The position register cannot be rewritten under a moving axis.
  if (st_.moving()) {
    st_.reject(items::kMoveWhileMoving, "Preset Position while moving");
    return;
  }
  if (!st_.target_in_range(c.target)) {
    st_.reject(items::kOutOfRange, "preset out of range %d..%d", st_.rules.target_min,
               st_.rules.target_max);  // 3601-CE-04
    return;
  }
  st_.set_position(*c.target);
  // 3601-PI-C1; 3601-MC-03: MC is left as it is, the 3602 clears it (3602-MC-02).
  st_.fire(AxisEvent::kPositionPreset);
  // 3601 Ch.4 "Diagnostic Feedback": with diagnostic feedback the encoder register (own pulse
  // count) is preset too.
  if (st_.cfg.diagnostic_feedback) st_.write_encoder(*c.target);
}

// Reset Errors: clears CE, IE, HI and IP, never PI or CfgE (A7). The dialect's word rule
// (3601-CE-15: command LSW 0) was checked at dispatch.
void Axis::command_reset_errors() {
  st_.fire(AxisEvent::kErrorsReset);  // 3601-CE-L2, IE-C1, HI-C1
}

}  // namespace stepmod::module::axis
