#include "module_types/m3601/plc_3601.hpp"

#include <stdexcept>

#include "plc/bit_names.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "plc/command_answer.hpp"

namespace stepmod::plc {

namespace m = words::m3601;
using m3601::accel_bits;
using m3601::put_profile;
using m3601::put_split;

namespace {
std::uint16_t lsw_of(const ImageWords& in) {
  return static_cast<std::uint16_t>(in.w[m::in_word::kStatusLsw]);
}
}  // namespace

bool Plc3601::release_bits(unsigned word, std::uint16_t bits) {
  if ((static_cast<std::uint16_t>(port_.outputs().w[word]) & bits) == 0) return true;
  port_.update_outputs([&](ImageWords& w) { w.w[word] &= ~static_cast<std::int32_t>(bits); });
  return port_.wait_scans(seq_.release_scans);
}

bool Plc3601::release_stale() {
  return !seq_.release_stale_bits || release_bits(m::out_word::kMsw, m::cmd_msw::kCommandMask);
}

Outcome Plc3601::edge_command(const ImageWords& words, std::uint16_t edge_bit,
                              std::uint32_t error_mask) {
  if (!release_stale()) return finish(error_mask, true, "release");
  port_.write_outputs(words);
  const bool seen = port_.wait_scans(seq_.hold_scans);
  // Edge-triggered: release the bit so that the next command is a new edge. Parameters stay,
  // as a PLC program leaves them.
  port_.update_outputs([&](ImageWords& w) { w.w[m::out_word::kMsw] &= ~edge_bit; });
  const bool released = port_.wait_scans(seq_.release_scans);
  return finish(error_mask, !(seen && released), "command");
}

Outcome Plc3601::pulse(const ImageWords& words, std::uint16_t edge_bits) {
  return edge_command(words, edge_bits, kCommandErrors);
}

Outcome Plc3601::pulse_msw(std::uint16_t msw) {
  ImageWords w = port_.outputs();
  w.w[m::out_word::kMsw] = static_cast<std::int16_t>(msw);
  return edge_command(w, msw, kCommandErrors);
}

Outcome Plc3601::configure(std::uint16_t cfg_msw, std::uint16_t cfg_lsw, std::int32_t start_speed,
                           ImageWords* in_config) {
  port_.write_outputs(m3601::configuration_words(cfg_msw, cfg_lsw, start_speed));
  if (!port_.wait_scans(seq_.config_scans)) return finish(0, true, "configure");
  // The verdict is read in configuration mode, where bit 13 reports this configuration.
  Outcome cfg = finish(m::status_msw::kConfigurationError, false, "configure");
  if (in_config != nullptr) *in_config = cfg.in;
  port_.write_outputs(ImageWords{});  // back to command mode, all words 0
  if (!port_.wait_scans(seq_.config_scans)) return finish(0, true, "command mode");
  Outcome o = finish(m::status_msw::kConfigurationError, false, "configure");
  if (!cfg.ok) {
    o.ok = false;
    o.message = cfg.message;
  }
  return o;
}

Outcome Plc3601::move(bool absolute, std::int32_t target, const Profile& p, bool encoder_move) {
  ImageWords w;
  const std::uint16_t bit = absolute ? m::cmd_msw::kAbsoluteMove : m::cmd_msw::kRelativeMove;
  w.w[m::out_word::kMsw] = bit;
  w.w[m::out_word::kLsw] = accel_bits(p.type) | (encoder_move ? m::cmd_lsw::kEncoderMove : 0);
  put_split(w, m::out_word::kTargetMsw, target);
  put_profile(w, p);
  return edge_command(w, bit, kCommandErrors);
}

Outcome Plc3601::jog_press(bool cw, const Profile& p, std::int32_t registration) {
  if (!release_stale()) return finish(kCommandErrors, true, "release");
  ImageWords w;
  const std::uint16_t bit = cw ? m::cmd_msw::kManualCw : m::cmd_msw::kManualCcw;
  w.w[m::out_word::kMsw] = bit;
  w.w[m::out_word::kLsw] = accel_bits(p.type);
  put_split(w, m::out_word::kTargetMsw, registration);
  put_profile(w, p);
  port_.write_outputs(w);
  return finish(kCommandErrors, !port_.wait_scans(seq_.hold_scans), "jog");
}

Outcome Plc3601::jog_release() {
  constexpr std::uint16_t kManual = m::cmd_msw::kManualCw | m::cmd_msw::kManualCcw;
  port_.update_outputs([&](ImageWords& o) { o.w[m::out_word::kMsw] &= ~kManual; });
  return finish(kCommandErrors, !port_.wait_scans(seq_.release_scans), "jog release");
}

Outcome Plc3601::jog(bool cw, const Profile& p, std::chrono::milliseconds duration,
                     std::int32_t registration) {
  const Outcome pressed = jog_press(cw, p, registration);
  // Level-held: keep the bit for the duration (the port keeps the PLC's heartbeat meanwhile).
  if (!pressed.timed_out) port_.pass(duration);
  const Outcome released = jog_release();
  if (pressed.timed_out) return pressed;
  if (released.timed_out) return released;
  Outcome idle = wait_idle(timeout_ + std::chrono::seconds(30));
  if (idle.timed_out) return idle;
  return finish(kCommandErrors, false, "jog");
}

Outcome Plc3601::home(bool cw, const Profile& p) {
  ImageWords w;
  const std::uint16_t bit = cw ? m::cmd_msw::kFindHomeCw : m::cmd_msw::kFindHomeCcw;
  w.w[m::out_word::kMsw] = bit;
  // Homing is constant acceleration only and the target words must be 0 (3601 manual ch. 5).
  put_profile(w, p);
  // Keep the backplane proximity bit as the PLC left it: it is the PLC's input to homing.
  w.w[m::out_word::kLsw] = port_.outputs().w[m::out_word::kLsw] & m::cmd_lsw::kBackplaneProximity;
  return edge_command(w, bit, kCommandErrors | m::status_msw::kHomeInvalid);
}

Outcome Plc3601::hold() {
  const StaleIsNote note(stale_);
  ImageWords w = port_.outputs();  // parameters are ignored by Hold: leave them
  w.w[m::out_word::kMsw] = m::cmd_msw::kHold;
  return edge_command(w, m::cmd_msw::kHold, m::status_msw::kCommandError);
}

Outcome Plc3601::resume(const std::optional<Profile>& p) {
  const StaleIsNote note(stale_);
  ImageWords w = port_.outputs();
  w.w[m::out_word::kMsw] = m::cmd_msw::kResume;
  if (p) {
    put_profile(w, *p);
    // S-curve bits must be supplied again with Resume (3601 manual ch. 5).
    constexpr std::int32_t kTypeBits = m::cmd_lsw::kSCurve | m::cmd_lsw::kTrapezoidalS;
    w.w[m::out_word::kLsw] = (w.w[m::out_word::kLsw] & ~kTypeBits) | accel_bits(p->type);
  }
  return edge_command(w, m::cmd_msw::kResume, kCommandErrors);
}

Outcome Plc3601::immediate_stop() {
  const StaleIsNote note(stale_);
  ImageWords w = port_.outputs();
  w.w[m::out_word::kMsw] = m::cmd_msw::kImmediateStop;
  return edge_command(w, m::cmd_msw::kImmediateStop, m::status_msw::kCommandError);
}

Outcome Plc3601::preset_position(std::int32_t position) {
  ImageWords w;  // LSW and words 4..7 must be 0
  w.w[m::out_word::kMsw] = m::cmd_msw::kPresetPosition;
  put_split(w, m::out_word::kTargetMsw, position);
  return edge_command(w, m::cmd_msw::kPresetPosition, m::status_msw::kCommandError);
}

Outcome Plc3601::preset_encoder(std::int32_t value) {
  ImageWords w;
  w.w[m::out_word::kMsw] = m::cmd_msw::kPresetEncoder;
  put_split(w, m::out_word::kTargetMsw, value);
  return edge_command(w, m::cmd_msw::kPresetEncoder, m::status_msw::kCommandError);
}

Outcome Plc3601::reset_errors() {
  ImageWords w = port_.outputs();
  w.w[m::out_word::kMsw] = m::cmd_msw::kResetErrors;
  w.w[m::out_word::kLsw] = 0;  // must be 0 with Reset Errors
  return edge_command(w, m::cmd_msw::kResetErrors, m::status_msw::kCommandError);
}

Outcome Plc3601::set_min_registration(std::int32_t distance) {
  if (!release_stale() || !release_bits(m::out_word::kLsw, m::cmd_lsw::kStoreMinRegistration)) {
    return finish(kCommandErrors, true, "release");
  }
  ImageWords w;
  w.w[m::out_word::kLsw] = m::cmd_lsw::kStoreMinRegistration;
  put_split(w, m::out_word::kTargetMsw, distance);
  port_.write_outputs(w);
  const bool seen = port_.wait_scans(seq_.hold_scans);
  port_.update_outputs([](ImageWords& o) { o.w[m::out_word::kLsw] = 0; });
  return finish(kCommandErrors, !(seen && port_.wait_scans(seq_.release_scans)),
                "min-registration");
}

Outcome Plc3601::blend_program(const BlendProfile& b) {
  constexpr std::uint16_t kProgram = m::cmd_lsw::kProgramBlend;
  constexpr std::uint16_t kTransmit = m::cmd_lsw::kBlendTransmit;
  if (!release_stale() || !release_bits(m::out_word::kLsw, kProgram | kTransmit)) {
    return finish(kCommandErrors, true, "release");
  }
  const auto acknowledged = [](bool want) {
    return [want](const ImageWords& in) {
      return ((lsw_of(in) & m::status_lsw::kBlendAcknowledge) != 0) == want;
    };
  };
  const std::vector<ImageWords> blocks = m3601::blend_blocks(b);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    ImageWords w = blocks[i];
    w.w[m::out_word::kLsw] = kProgram | kTransmit;
    port_.write_outputs(w);
    if (!port_.wait_inputs(acknowledged(true), timeout_)) {
      port_.write_outputs(ImageWords{});
      return finish(kCommandErrors, true, "blend block " + std::to_string(i + 1));
    }
    port_.update_outputs([&](ImageWords& o) { o.w[m::out_word::kLsw] = kProgram; });
    if (!port_.wait_inputs(acknowledged(false), timeout_)) {
      port_.write_outputs(ImageWords{});
      return finish(kCommandErrors, true, "blend block " + std::to_string(i + 1));
    }
  }
  port_.write_outputs(ImageWords{});  // program bit off: the profile is complete
  return finish(kCommandErrors, !port_.wait_scans(seq_.release_scans), "blend program");
}

Outcome Plc3601::blend_run(bool cw) {
  ImageWords w;  // every other word must be 0 with Run Blend
  const std::uint16_t bit = cw ? m::cmd_msw::kRunBlendCw : m::cmd_msw::kRunBlendCcw;
  w.w[m::out_word::kMsw] = bit;
  return edge_command(w, bit, kCommandErrors);
}

Outcome Plc3601::follow(int sense, std::int16_t multiplier, std::int16_t divisor,
                        std::int16_t accel, std::int16_t decel) {
  if (!release_stale()) return finish(kCommandErrors, true, "release");
  const std::uint16_t dir = sense > 0   ? m::cmd_msw::kManualCw
                            : sense < 0 ? m::cmd_msw::kManualCcw
                                        : std::uint16_t{0};
  port_.write_outputs(
      m3601::follower_words(dir, multiplier, divisor, accel, decel, m::cmd_lsw::kEncoderFollower));
  return finish(kCommandErrors, !port_.wait_scans(seq_.hold_scans), "follow");
}

Outcome Plc3601::end_follow() {
  port_.write_outputs(ImageWords{});
  return finish(kCommandErrors, !port_.wait_scans(seq_.release_scans), "end follow");
}

Outcome Plc3601::wait_idle(std::chrono::nanoseconds timeout) {
  const bool idle = port_.wait_inputs(
      [](const ImageWords& in) {
        const m3601::Status s = m3601::decode_status(in);
        return !s.moving() && !s.has_lsw(m::status_lsw::kBlendRunning);
      },
      timeout);
  Outcome o = finish(0, false, "wait-idle");
  if (!idle) {
    o.ok = false;
    o.timed_out = true;
    o.message =
        "wait-idle: still moving after " +
        std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(timeout).count()) +
        " ms";
  }
  return o;
}

Outcome Plc3601::status() {
  return finish(0, false, "status");
}

}  // namespace stepmod::plc
