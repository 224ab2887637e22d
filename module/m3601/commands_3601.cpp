// 3601 command mode: decoding of the command words and the commands of the 3601 manual Ch.4.
// Every rejection names the checklist item of digest 6.1 it implements.
#include <bit>

#include "ipc/codec.hpp"
#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"
#include "module/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {

// Level-sensitive command bits: the manual move runs while its bit is held.
void Personality3601::handle_levels(const ImageWords& out) {
  const auto msw = static_cast<std::uint16_t>(out.w[out_word::kMsw]);
  if (activity_ != Activity::kManual || stop_cause_ != StopCause::kNone) return;
  if (manual_owns_release()) return;  // one-shot / registration: manual_scan (manual_3601.cpp)
  const std::uint16_t bit =
      dir_ == planner::Direction::kCw ? cmd_msw::kManualCw : cmd_msw::kManualCcw;
  if (!(msw & bit)) {
    // 3601-STP-01: releasing the bit is a controlled stop to the starting speed. Acted on even
    // while CE is set: a stop request is never ignored. A11: only the command word needs to be
    // cleared; on current firmware zeroing all eight words is not an error.
    stop_cause_ = StopCause::kRelease;
    motion_.stop(move_decel_);
  }
}

void Personality3601::handle_command_edge(const ImageWords& out, std::uint16_t rising) {
  const auto msw = static_cast<std::uint16_t>(out.w[out_word::kMsw]);
  // 3601-CE-L1: while CE is set, only Reset Errors is looked at.
  if (status_.command_error && !(rising & cmd_msw::kResetErrors)) return;
  // 3601-CE-02 / CE-12: more than one command bit at a time. A33: the reserved bit 14 counts as
  // a command bit.
  if (std::popcount(static_cast<unsigned>(msw & (cmd_msw::kCommandMask | cmd_msw::kReserved14))) >
      1) {
    reject();
    return;
  }
  if (rising & cmd_msw::kReserved14) {
    reject();  // A33
    return;
  }
  // The manual: "The 3601 module has to be configured before starting any operations."
  if (!configured_) {
    reject();
    return;
  }
  switch (rising & cmd_msw::kCommandMask) {
    case cmd_msw::kAbsoluteMove:
      command_move(out, true);
      break;
    case cmd_msw::kRelativeMove:
      command_move(out, false);
      break;
    case cmd_msw::kHold:
      command_hold();
      break;
    case cmd_msw::kResume:
      command_resume(out);
      break;
    case cmd_msw::kImmediateStop:
      command_immediate_stop();
      break;
    case cmd_msw::kFindHomeCw:
      command_home(out, planner::Direction::kCw);
      break;
    case cmd_msw::kFindHomeCcw:
      command_home(out, planner::Direction::kCcw);
      break;
    case cmd_msw::kManualCw:
    case cmd_msw::kManualCcw: {
      const auto dir =
          (rising & cmd_msw::kManualCw) ? planner::Direction::kCw : planner::Direction::kCcw;
      if (lsw_ & cmd_lsw::kEncoderFollower) {
        command_follower(out, dir);
      } else {
        command_manual(out, dir);
      }
      break;
    }
    case cmd_msw::kPresetPosition:
      command_preset_position(out);
      break;
    case cmd_msw::kPresetEncoder:
      command_preset_encoder(out);
      break;
    case cmd_msw::kResetErrors:
      command_reset_errors(out);
      break;
    case cmd_msw::kRunBlendCw:
      command_run_blend(out, planner::Direction::kCw);
      break;
    case cmd_msw::kRunBlendCcw:
      command_run_blend(out, planner::Direction::kCcw);
      break;
    default:
      break;  // bits 0..13 are all handled above; 14 was refused before
  }
}

std::optional<Personality3601::Profile> Personality3601::read_profile(const ImageWords& out,
                                                                      bool ramped) {
  const auto speed = speed_words(out);
  const std::int32_t accel = static_cast<std::int16_t>(out.w[out_word::kAccel]);
  const std::int32_t decel = static_cast<std::int16_t>(out.w[out_word::kDecel]);
  // 3601-CE-04 / IP-02: speed, accel or decel outside its range.
  if (!speed || *speed > kMaxSpeed || !rate_in_range(accel) || !rate_in_range(decel)) {
    reject_profile();
    return std::nullopt;
  }
  // 3601-CE-05 / IP-01: Vp < Vs where the move ramps from the starting speed.
  if (ramped && *speed < cfg_.starting_speed) {
    reject_profile();
    return std::nullopt;
  }
  const planner::AccelShape shape = shape_from_lsw(lsw_);
  return Profile{
      static_cast<double>(*speed), {rate_from_word(accel), shape}, {rate_from_word(decel), shape}};
}

// 3601-HLD-03: with the External input active an absolute/relative move (or its resumption)
// outputs one step in the commanded direction, then holds.
void Personality3601::start_abs_rel(std::int64_t steps, const Profile& p) {
  if (inputs_.active(InputLine::kExternal)) {
    if (start_move_steps(steps < 0 ? -1 : 1, p)) stop_cause_ = StopCause::kExternal;
    return;
  }
  start_move_steps(steps, p);
}

bool Personality3601::inputs_block_start(planner::Direction dir) {
  const auto limit = dir == planner::Direction::kCw ? InputLine::kCwLimit : InputLine::kCcwLimit;
  if (!inputs_.active(InputLine::kEStop) && !inputs_.active(limit)) return false;
  status_.input_error = true;
  return true;
}

void Personality3601::clear_move_outcome() noexcept {
  status_.move_complete = false;
  status_.hold = false;
  status_.stopped = false;
  status_.at_home = false;
  status_.input_error = false;
}

bool Personality3601::words_zero(const ImageWords& out, unsigned first, unsigned last) noexcept {
  for (unsigned w = first; w <= last; ++w) {
    if (out.w[w] != 0) return false;
  }
  return true;
}

bool Personality3601::start_move_steps(std::int64_t steps, const Profile& p) {
  planner::MoveSpec spec;
  spec.steps = steps < 0 ? -steps : steps;
  spec.dir = steps < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  spec.vs = cfg_.starting_speed;
  spec.vp = p.vp;
  spec.accel = p.accel;
  spec.decel = p.decel;
  if (motion_.start_move(spec) == 0) {
    reject();  // the planner queue is full: refuse rather than lose the command
    return false;
  }
  activity_ = Activity::kMove;
  dir_ = spec.dir;
  move_decel_ = p.decel;
  stop_cause_ = StopCause::kNone;
  return true;
}

// Absolute (MSW bit 0) and Relative (bit 1) moves: 3601 manual Ch.4 "Absolute & Relative Moves".
void Personality3601::command_move(const ImageWords& out, bool absolute) {
  // 3601-CE-03: a move while another is in progress; the running move is unaffected.
  if (moving()) {
    reject();
    return;
  }
  const auto target = target_words(out);
  // 3601-CE-04 / IP-02: target outside -8,388,608..8,388,607, LSW outside -999..999 or the two
  // words of opposite signs.
  if (!target || *target < kMinTarget || *target > kMaxTarget) {
    reject_profile();
    return;
  }
  const auto profile = read_profile(out, true);
  if (!profile) return;
  // 3601-CE-14 / IP-11: an encoder move needs the quadrature encoder.
  if ((lsw_ & cmd_lsw::kEncoderMove) && !cfg_.has(cfg_msw::kQuadratureEncoder)) {
    reject_profile();
    return;
  }
  if (lsw_ & cmd_lsw::kEncoderMove) {
    command_encoder_move(out, absolute);
    return;
  }
  // 3601-CE-06: an absolute move needs a valid position.
  if (absolute && status_.position_invalid) {
    reject();
    return;
  }
  const std::int64_t steps = absolute ? *target - position() : *target;
  const planner::Direction dir = steps < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  if (inputs_block_start(dir)) return;
  clear_move_outcome();
  move_target_ = absolute ? *target : position() + *target;
  if (steps == 0) {
    status_.move_complete = true;  // already at the target: nothing to output
    return;
  }
  start_abs_rel(steps, *profile);
}

// Hold (MSW bit 2): 3601 manual Ch.4 "Hold Move".
void Personality3601::command_hold() {
  if (activity_ == Activity::kEncoderMove) return;  // A4: ignored, no CE (encoder_3601.cpp)
  if (activity_ == Activity::kMove) {
    // A hold already under way (or the External input's) needs nothing more.
    if (stop_cause_ == StopCause::kNone) {
      stop_cause_ = StopCause::kHold;  // 3601-HLD-01
      motion_.stop(move_decel_);
    }
    return;
  }
  if (activity_ == Activity::kBlend) {
    blend_hold();  // 3601-CE-23: CE, the blend continues, CE clears at its end
    return;
  }
  // 3601-CE-07: Hold while no absolute/relative move is in progress. During a manual move the
  // motion also stops, controlled (A43).
  reject();
  if (activity_ == Activity::kManual && stop_cause_ == StopCause::kNone) {
    stop_cause_ = StopCause::kRelease;
    motion_.stop(move_decel_);
  }
}

// Resume (MSW bit 3): the remaining distance to the held move's target, with the speed, accel,
// decel and S-curve bits given now (3601 manual Ch.4 "Resume Move").
void Personality3601::command_resume(const ImageWords& out) {
  // 3601-CE-08: Resume when not in the Hold state.
  if (!status_.hold || moving()) {
    reject();
    return;
  }
  const auto profile = read_profile(out, true);
  if (!profile) return;
  const std::int64_t remaining = held_.target - position();
  const planner::Direction dir = remaining < 0 ? planner::Direction::kCcw : planner::Direction::kCw;
  if (inputs_block_start(dir)) return;
  status_.hold = false;
  status_.input_error = false;
  move_target_ = held_.target;
  if (remaining == 0) {
    status_.move_complete = true;
    return;
  }
  // 7.5: if the External input is still active the move again yields one step and holds.
  start_abs_rel(remaining, *profile);
}

// Immediate Stop (MSW bit 4): no deceleration; position invalid. A6: at rest nothing changes.
void Personality3601::command_immediate_stop() {
  if (moving()) immediate_stop(StopCause::kImmediate);  // 3601-PI-02, STP-03
}

void Personality3601::immediate_stop(StopCause cause) {
  motion_.immediate_stop();
  stop_cause_ = cause;
  status_.position_invalid = true;
  status_.move_complete = false;
}

void Personality3601::fault_stop() {
  // Digest 7.7: limit / E-stop trip during a move: immediate stop, IE, PI, Stopped.
  immediate_stop(StopCause::kFault);
  status_.input_error = true;
}

// The value of Preset Position / Preset Encoder (words 2-3); nullopt after rejecting the command.
std::optional<std::int32_t> Personality3601::preset_value(const ImageWords& out) {
  // 3601-CE-09: speed, accel and decel words must be 0; 3601-CE-15: the command LSW must be 0.
  if (!words_zero(out, out_word::kSpeedMsw, out_word::kDecel) || lsw_ != 0) {
    reject();
    return std::nullopt;
  }
  const auto value = target_words(out);
  if (!value || *value < kMinTarget || *value > kMaxTarget) {
    reject();  // 3601-CE-04
    return std::nullopt;
  }
  return value;
}

// Preset Position (MSW bit 9): 3601 manual Ch.4 "Preset Position".
void Personality3601::command_preset_position(const ImageWords& out) {
  // The position register cannot be rewritten under a moving axis.
  if (moving()) {
    reject();
    return;
  }
  const auto value = preset_value(out);
  if (!value) return;
  set_position(*value);
  status_.position_invalid = false;  // 3601-PI-C1; 3601-MC-03: MC is left as it is
  // Digest 7.12: with diagnostic feedback the encoder register (own pulse count) is preset too.
  if (cfg_.has(cfg_msw::kDiagnosticFeedback)) encoder_ = *value;
}

// Reset Errors (MSW bit 11): clears CE, IE, HI and IP, never PI or CfgE (A7).
void Personality3601::command_reset_errors(const ImageWords& /*out*/) {
  if (lsw_ != 0) {
    status_.command_error = true;  // 3601-CE-15
    return;
  }
  status_.command_error = false;  // 3601-CE-L2
  status_.input_error = false;    // 3601-IE-C1
  status_.home_invalid = false;   // 3601-HI-C1
  status_.invalid_profile = false;
}

}  // namespace stepmod::module::m3601
