#include "module_types/m3202/plc_3202.hpp"

#include <stdexcept>

#include "plc/bit_names.hpp"
#include "module_types/m3202/words_3202.hpp"
#include "plc/command_answer.hpp"

namespace stepmod::plc {

namespace m = words::m3202;
using m3202::ChannelWords;

namespace {
constexpr std::uint32_t kCommandBits = 0x3FFFu;  // bits 0..13
}  // namespace

void Plc3202::write_channel(unsigned ch, const ChannelWords& words) {
  port_.update_outputs([&](ImageWords& w) {
    for (unsigned i = 0; i < m::kWordsPerChannel; ++i) w.w[m::channel_base(ch) + i] = words[i];
  });
}

Outcome Plc3202::edge_command(unsigned ch, const ChannelWords& words, std::uint32_t edge_bit,
                              std::uint32_t error_mask) {
  const unsigned w0 = m::channel_base(ch) + m::out_word::kCommand;
  if (seq_.release_stale_bits && (port_.outputs().w[w0] & kCommandBits) != 0) {
    port_.update_outputs(
        [&](ImageWords& w) { w.w[w0] &= ~static_cast<std::int32_t>(kCommandBits); });
    if (!port_.wait_scans(seq_.release_scans)) return finish(ch, error_mask, true, "release");
  }
  write_channel(ch, words);
  const bool seen = port_.wait_scans(seq_.hold_scans);
  // Edge-triggered: release the bit; the parameters stay, as a PLC program leaves them.
  port_.update_outputs([&](ImageWords& w) { w.w[w0] &= ~static_cast<std::int32_t>(edge_bit); });
  const bool released = port_.wait_scans(seq_.release_scans);
  return finish(ch, error_mask, !(seen && released), "command");
}

Outcome Plc3202::configure(unsigned ch, std::uint32_t bits, std::int32_t start_speed) {
  write_channel(ch, m3202::configuration_words(bits, start_speed));
  if (!port_.wait_scans(seq_.config_scans)) return finish(ch, 0, true, "configure");
  // The verdict is read in configuration mode, where bit 13 reports this configuration.
  Outcome cfg = finish(ch, m::status_bit::kConfigurationError, false, "configure");
  write_channel(ch, ChannelWords{});
  if (!port_.wait_scans(seq_.config_scans)) return finish(ch, 0, true, "command mode");
  Outcome o = finish(ch, m::status_bit::kConfigurationError, false, "configure");
  if (!cfg.ok) {
    o.ok = false;
    o.message = cfg.message;
  }
  return o;
}

Outcome Plc3202::move(unsigned ch, bool absolute, std::int32_t target, const Profile& p,
                      bool encoder_move) {
  const std::uint32_t bit = absolute ? m::cmd_bit::kAbsoluteMove : m::cmd_bit::kRelativeMove;
  const std::uint32_t word =
      bit | m3202::accel_bits(p.type) | (encoder_move ? m::cmd_bit::kEncoderMove : 0);
  return edge_command(ch, m3202::command_words(word, target, p.speed, p.accel, p.decel), bit,
                      kCommandErrors);
}

Outcome Plc3202::jog_press(unsigned ch, bool cw, const Profile& p) {
  const std::uint32_t bit = cw ? m::cmd_bit::kManualCw : m::cmd_bit::kManualCcw;
  // The target must be 0: the 3202 has no registration move.
  write_channel(
      ch, m3202::command_words(bit | m3202::accel_bits(p.type), 0, p.speed, p.accel, p.decel));
  return finish(ch, kCommandErrors, !port_.wait_scans(seq_.hold_scans), "jog");
}

Outcome Plc3202::jog_release(unsigned ch) {
  constexpr std::uint32_t kManualBits = m::cmd_bit::kManualCw | m::cmd_bit::kManualCcw;
  const unsigned w0 = m::channel_base(ch) + m::out_word::kCommand;
  port_.update_outputs([&](ImageWords& w) { w.w[w0] &= ~static_cast<std::int32_t>(kManualBits); });
  return finish(ch, kCommandErrors, !port_.wait_scans(seq_.release_scans), "jog release");
}

Outcome Plc3202::jog(unsigned ch, bool cw, const Profile& p, std::chrono::milliseconds duration) {
  Outcome pressed = jog_press(ch, cw, p);
  // Level-held: keep the bit for the duration (the port keeps the PLC's heartbeat meanwhile).
  if (!pressed.timed_out) port_.pass(duration);
  Outcome released = jog_release(ch);
  if (pressed.timed_out) return pressed;
  if (released.timed_out) return released;
  Outcome idle = wait_idle(ch, timeout_ + std::chrono::seconds(30));
  if (idle.timed_out) return idle;
  return finish(ch, kCommandErrors, false, "jog");
}

Outcome Plc3202::home(unsigned ch, bool cw, const Profile& p) {
  const std::uint32_t bit = cw ? m::cmd_bit::kFindHomeCw : m::cmd_bit::kFindHomeCcw;
  // Keep the backplane proximity bit as the PLC left it: it is the PLC's input to homing.
  const auto prox = static_cast<std::uint32_t>(port_.outputs().w[m::channel_base(ch)]) &
                    m::cmd_bit::kBackplaneProximity;
  return edge_command(ch, m3202::command_words(bit | prox, 0, p.speed, p.accel, p.decel), bit,
                      kCommandErrors | m::status_bit::kHomeInvalid);
}

Outcome Plc3202::hold(unsigned ch) {
  const StaleIsNote note(stale_);
  // Hold ignores the parameters: leave them, so that a Resume without new ones finds the held
  // move's speed and rates (zeros would make it an Invalid Profile).
  ChannelWords w{};
  const unsigned b = m::channel_base(ch);
  const ImageWords now = port_.outputs();
  for (unsigned i = 0; i < m::kWordsPerChannel; ++i) w[i] = now.w[b + i];
  w[m::out_word::kCommand] = static_cast<std::int32_t>(m::cmd_bit::kHold);
  return edge_command(ch, w, m::cmd_bit::kHold, m::status_bit::kCommandError);
}

Outcome Plc3202::resume(unsigned ch, const std::optional<Profile>& p) {
  const StaleIsNote note(stale_);
  ChannelWords w{};
  const unsigned b = m::channel_base(ch);
  const ImageWords now = port_.outputs();
  for (unsigned i = 0; i < m::kWordsPerChannel; ++i) w[i] = now.w[b + i];
  std::uint32_t word = m::cmd_bit::kResume;
  if (p) {
    w[m::out_word::kSpeed] = p->speed;
    w[m::out_word::kAccel] = p->accel;
    w[m::out_word::kDecel] = p->decel;
    word |= m3202::accel_bits(p->type);  // the S-curve bits are given again with Resume
  }
  w[m::out_word::kCommand] = static_cast<std::int32_t>(word);
  return edge_command(ch, w, m::cmd_bit::kResume, kCommandErrors);
}

Outcome Plc3202::immediate_stop(unsigned ch) {
  const StaleIsNote note(stale_);
  return edge_command(ch, m3202::command_words(m::cmd_bit::kImmediateStop, 0, 0, 0, 0),
                      m::cmd_bit::kImmediateStop, m::status_bit::kCommandError);
}

Outcome Plc3202::preset_position(unsigned ch, std::int32_t position) {
  return edge_command(ch, m3202::command_words(m::cmd_bit::kPresetPosition, position, 0, 0, 0),
                      m::cmd_bit::kPresetPosition, m::status_bit::kCommandError);
}

Outcome Plc3202::preset_encoder(unsigned ch, std::int32_t value) {
  return edge_command(ch, m3202::command_words(m::cmd_bit::kPresetEncoder, value, 0, 0, 0),
                      m::cmd_bit::kPresetEncoder, m::status_bit::kCommandError);
}

Outcome Plc3202::reset_errors(unsigned ch) {
  return edge_command(ch, m3202::command_words(m::cmd_bit::kResetErrors, 0, 0, 0, 0),
                      m::cmd_bit::kResetErrors, m::status_bit::kCommandError);
}

Outcome Plc3202::blend_run(unsigned ch, bool cw) {
  const std::uint32_t bit = cw ? m::cmd_bit::kRunBlendCw : m::cmd_bit::kRunBlendCcw;
  return edge_command(ch, m3202::command_words(bit, 0, 0, 0, 0), bit, kCommandErrors);
}

Outcome Plc3202::wait_idle(unsigned ch, std::chrono::nanoseconds timeout) {
  const auto idle = [ch](const ImageWords& in) {
    const m3202::Status s = m3202::decode_status(in, ch);
    return !s.moving() && !s.has(m::status_bit::kBlendRunning);
  };
  return wait_until(ch, idle, timeout, "wait-idle");
}

Outcome Plc3202::status(unsigned ch) {
  return finish(ch, 0, false, "status");
}

}  // namespace stepmod::plc
