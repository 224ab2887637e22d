// The 3601 personality: mode handling, the scan, and the status image. Commands are in
// commands_3601.cpp, input events in inputs_3601.cpp.
#include "module/m3601/personality_3601.hpp"

#include "ipc/codec.hpp"
#include "module/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {

namespace {
constexpr ModuleShape kShape = shape_of(ModuleType::k3601);
}  // namespace

Personality3601::Personality3601(gpio::Backend& backend, planner::MotionPort& motion)
    : backend_(backend), motion_(motion) {
  inputs_.init(backend_, motion_.axis());
  quadrature_.reset(inputs_.level(InputLine::kEncA), inputs_.level(InputLine::kEncB));
}

const ModuleShape& Personality3601::shape() const noexcept {
  return kShape;
}

void Personality3601::scan(const ImageWords& out, ImageWords& in, Nanos now) {
  const auto msw = static_cast<std::uint16_t>(out.w[out_word::kMsw]);
  lsw_ = static_cast<std::uint16_t>(out.w[out_word::kLsw]);
  poll_motion_end();

  if (config_mode_) {
    if (msw & cmd_msw::kConfigMode) {
      scan_configuration_mode(out);
    } else {
      enter_command_mode();
    }
  } else if (msw & cmd_msw::kConfigMode) {
    // 3601-CE-01: the mode bit while moving raises CE; the move finishes first, then the module
    // enters configuration mode and CE clears (Ch.3 "the stepper controller will finish its
    // current operation").
    if (moving()) {
      if (!config_after_motion_) status_.command_error = true;
      config_after_motion_ = true;
      if (activity_ == Activity::kHoming) homing_timers(now);  // its 2-s pauses go on meanwhile
    } else {
      if (config_after_motion_) status_.command_error = false;
      config_after_motion_ = false;
      config_mode_ = true;
      config_words_seen_ = false;
      scan_configuration_mode(out);
    }
  } else {
    config_after_motion_ = false;
    command_mode_scan(out, msw, now);
  }
  prev_msw_ = msw;
  prev_lsw_ = lsw_;

  if (config_mode_) {
    compose_configuration_image(in);
  } else {
    compose_command_image(in);
  }
}

// One command-mode scan: level bits and runtime monitors first (a released manual bit stops the
// axis even while CE is set), then the command edges.
void Personality3601::command_mode_scan(const ImageWords& out, std::uint16_t msw, Nanos now) {
  handle_levels(out);
  if (!configured_) {
    const std::uint16_t rising = msw & static_cast<std::uint16_t>(~prev_msw_);
    if (rising & (cmd_msw::kCommandMask | cmd_msw::kReserved14)) handle_command_edge(out, rising);
    return;
  }
  manual_scan(out, now);
  encoder_scan(out);
  if (activity_ == Activity::kHoming) homing_scan(now);
  blend_programming_scan(out);
  const std::uint16_t rising = msw & static_cast<std::uint16_t>(~prev_msw_);
  if (rising & (cmd_msw::kCommandMask | cmd_msw::kReserved14)) {
    handle_command_edge(out, rising);
  } else if (msw == 0 && (lsw_ & cmd_lsw::kStoreMinRegistration) &&
             !(prev_lsw_ & cmd_lsw::kStoreMinRegistration) && !status_.command_error) {
    command_min_registration(out);  // MSW = 0, LSW bit 10 rising (digest 3.8)
  }
}

void Personality3601::scan_configuration_mode(const ImageWords& out) {
  // The words are evaluated when they change; an unchanged image keeps its verdict.
  if (config_words_seen_ && out == last_config_words_) return;
  config_words_seen_ = true;
  last_config_words_ = out;
  const ConfigCheck check = check_config(out);
  if (check.fault == ConfigFault::kNone) {
    pending_ = check.config;
    status_.configuration_error = false;
    // A26: the mirror shows the accepted configuration (a rejected one leaves the last mirror).
    mirror_[0] = check.config.msw;
    mirror_[1] = check.config.lsw;
    mirror_[2] = static_cast<std::uint16_t>(check.config.vs_msw);
    mirror_[3] = static_cast<std::uint16_t>(check.config.vs_lsw);
  } else {
    pending_.reset();
    status_.configuration_error = true;
  }
}

// Leaving configuration mode (digest 7.15, 3601-CFG-13, 3601-PI-01).
void Personality3601::enter_command_mode() {
  config_mode_ = false;
  // Edges are detected against the command words from here on, not the configuration words.
  prev_msw_ = 0;
  // 3601 Ch.4 "Registration Move": the minimum registration distance is reset by every
  // configuration (3601-LSW-01 then reads 0).
  min_registration_ = 0;
  blend_erase();  // 3601-CE-20: any configuration erases the stored blend profile
  if (!pending_) {
    configured_ = false;  // CfgE stays set; commands are refused until a valid configuration
    return;
  }
  cfg_ = *pending_;
  configured_ = true;
  inputs_.configure(cfg_.msw & 0x3F, cfg_.lsw & 0x3F);
  const bool step_dir = cfg_.has(cfg_msw::kStepDirOutput);
  backend_.set_pulse_format(motion_.axis(),
                            step_dir ? gpio::PulseFormat::kStepDir : gpio::PulseFormat::kCwCcw);
  motion_.set_pulse_format(step_dir);
  set_position(0);
  // A18 (b): the encoder and capture registers are zeroed by a configuration too.
  encoder_ = 0;
  capture_ = 0;
  status_ = Status{};
  status_.configuration_error = false;
  status_.position_invalid = true;
  held_ = HeldMove{};
}

void Personality3601::poll_motion_end() {
  // Late-edge guard (issue 12; rt::PulseEngine::set_late_limit): the pulse thread cut the motion
  // rather than burst its late steps out. The PLC sees what an Immediate Stop gives (3601-STP-03,
  // PI-02: Stopped, Position Invalid), so its program re-homes; immediate_stop() also ends the
  // planner's side of the motion. Once: afterwards the cause is kImmediate or the axis is idle.
  if (moving() && stop_cause_ != StopCause::kImmediate && stop_cause_ != StopCause::kFault &&
      motion_.late_faulted()) {
    immediate_stop(StopCause::kImmediate);
  }
  if (activity_ == Activity::kIdle || activity_ == Activity::kFollower || motion_.busy()) return;
  if (activity_ == Activity::kHoming) {
    // A homing sequence is several motions and pauses; it ends when homing_motion_ended says.
    const StopCause cause = stop_cause_;
    stop_cause_ = StopCause::kNone;
    homing_motion_ended(cause);
    return;
  }
  const Activity ended = activity_;
  activity_ = Activity::kIdle;
  const StopCause cause = stop_cause_;
  stop_cause_ = StopCause::kNone;
  if (ended == Activity::kBlend) {
    blend_motion_ended(cause);  // MC / Stopped / CE-23 self-clear (blend_3601.cpp)
    return;
  }
  switch (cause) {
    case StopCause::kNone:
      // 3601-MC-01: an absolute/relative, encoder or blend move that reached its target.
      if (ended == Activity::kMove || ended == Activity::kEncoderMove ||
          ended == Activity::kBlend) {
        status_.move_complete = true;
      }
      // 3601-STP-N1: a one-shot manual move ends without Stopped.
      break;
    case StopCause::kHold:
    case StopCause::kExternal:
      if (ended == Activity::kMove) {
        // 3601-HLD-01/02/03: a held move keeps its target for Resume.
        status_.hold = true;
        held_.target = move_target_;
      } else {
        status_.stopped = true;  // 3601-STP-01: manual move stopped by the External input
      }
      break;
    case StopCause::kRelease:    // 3601-STP-01
    case StopCause::kImmediate:  // 3601-STP-03
    case StopCause::kFault:      // 3601-STP-02/04
      status_.stopped = true;
      break;
  }
}

void Personality3601::plc_stopped(Nanos /*now*/) {
  // 3601-PI-07: the PLC left Run mode while moving: motion stops, position invalid.
  if (moving()) immediate_stop(StopCause::kImmediate);
}

void Personality3601::shutdown() {
  if (moving()) immediate_stop(StopCause::kImmediate);
}

void Personality3601::compose_configuration_image(ImageWords& in) const {
  in = ImageWords{};
  std::uint16_t w0 = mirror_[0] & 0x1FFF;
  if (status_.configuration_error) w0 |= status_msw::kConfigurationError;
  w0 |= status_msw::kModuleOk | status_msw::kConfigMode;
  in.w[0] = static_cast<std::int16_t>(w0);
  in.w[1] = static_cast<std::int16_t>(mirror_[1]);
  in.w[2] = static_cast<std::int16_t>(mirror_[2]);
  in.w[3] = static_cast<std::int16_t>(mirror_[3]);
  in.w[in_word::kFirmwareMajor] = kFirmwareMajor;
  in.w[in_word::kFirmwareMinor] = kFirmwareMinor;
}

void Personality3601::compose_command_image(ImageWords& in) const {
  std::uint16_t msw = status_msw::kModuleOk;  // 3601-MOK-01: only a fatal fault clears it
  if (moving() && motion_.busy()) {
    // 3601-DIR-01: direction of the pulses being output.
    msw |= dir_ == planner::Direction::kCw ? status_msw::kMovingCw : status_msw::kMovingCcw;
    // 3601-ACC-01: the phase of the edge the pulse thread last wrote.
    const auto phase = motion_.phase();
    if (phase == planner::MotionPort::Phase::kAccelerating) msw |= status_msw::kAccelerating;
    if (phase == planner::MotionPort::Phase::kDecelerating) msw |= status_msw::kDecelerating;
  }
  msw |= manual_status_msw();  // 3601-DIR-01: a one-shot's direction while its bit is held
  if (status_.hold) msw |= status_msw::kHoldState;
  // 3601-STP-N1: never together with MC, AH or Hld.
  if (status_.stopped && !status_.move_complete && !status_.at_home && !status_.hold) {
    msw |= status_msw::kStopped;
  }
  if (status_.at_home) msw |= status_msw::kAtHome;
  if (status_.move_complete) msw |= status_msw::kMoveComplete;
  if (status_.home_invalid) msw |= status_msw::kHomeInvalid;
  if (status_.invalid_profile) msw |= status_msw::kInvalidProfile;
  if (status_.position_invalid) msw |= status_msw::kPositionInvalid;
  if (status_.input_error) msw |= status_msw::kInputError;
  if (status_.command_error) msw |= status_msw::kCommandError;
  if (status_.configuration_error) msw |= status_msw::kConfigurationError;

  // Status LSW: logical input states (A27: unused inputs read 0) and the proximity echo, which
  // is live whether or not homing is configured (A44).
  std::uint16_t lsw = inputs_.active_bits();
  if (lsw_ & cmd_lsw::kBackplaneProximity) lsw |= status_lsw::kProximityEcho;
  lsw |= blend_status_lsw();
  if (activity_ == Activity::kFollower) lsw |= status_lsw::kFollowerMode;
  if (min_registration_ != 0) lsw |= status_lsw::kMinRegistrationSet;

  in = ImageWords{};
  in.w[in_word::kStatusMsw] = static_cast<std::int16_t>(msw);
  in.w[in_word::kStatusLsw] = static_cast<std::int16_t>(lsw);
  const auto put = [&in](unsigned msw_index, std::int64_t value) {
    const auto split = ipc::codec::encode_3601(value);
    in.w[msw_index] = split.msw;
    in.w[msw_index + 1] = split.lsw;
  };
  put(in_word::kPositionMsw, position());
  put(in_word::kEncoderMsw, encoder_);
  put(in_word::kCaptureMsw, capture_);
}

}  // namespace stepmod::module::m3601
