#include "module_types/m3602/plc_3602.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "plc/bit_names.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "plc/command_answer.hpp"

namespace stepmod::plc {

namespace m = words::m3602;

std::uint16_t Plc3602::gpo_bit(unsigned axis) const {
  const auto lsw =
      static_cast<std::uint16_t>(port_.outputs().w[m3602::base(axis) + m::out_word::kLsw]);
  return lsw & m::cmd_lsw::kGpo;
}

bool Plc3602::release_msw(unsigned axis) {
  const unsigned msw_word = m3602::base(axis) + m::out_word::kMsw;
  // A command bit left at 1 would hide the next 0->1 edge: release it first.
  if (!seq_.release_stale_bits || port_.outputs().w[msw_word] == 0) return true;
  port_.update_outputs([&](ImageWords& w) { w.w[msw_word] = 0; });
  return port_.wait_scans(seq_.release_scans);
}

bool Plc3602::set_lsw(unsigned axis, std::uint16_t lsw) {
  const unsigned lsw_word = m3602::base(axis) + m::out_word::kLsw;
  port_.update_outputs([&](ImageWords& w) { w.w[lsw_word] = static_cast<std::int16_t>(lsw); });
  return port_.wait_scans(seq_.release_scans);
}

Outcome Plc3602::edge(unsigned axis, std::uint16_t msw, std::uint32_t error_mask, const char* what,
                      const std::function<void(ImageWords&, unsigned)>& edit) {
  if (!release_msw(axis)) return finish(axis, error_mask, true, "release");
  const unsigned b = m3602::base(axis);
  const std::uint16_t gpo = gpo_bit(axis);
  port_.update_outputs([&](ImageWords& w) {
    edit(w, b);
    w.w[b + m::out_word::kMsw] = static_cast<std::int16_t>(msw);
    w.w[b + m::out_word::kLsw] = static_cast<std::int16_t>(
        (static_cast<std::uint16_t>(w.w[b + m::out_word::kLsw]) & ~m::cmd_lsw::kGpo) | gpo);
  });
  const bool seen = port_.wait_scans(seq_.hold_scans);
  // Edge-triggered: release the bit so that the next command is a new edge; the parameters stay,
  // as a PLC program leaves them.
  port_.update_outputs([&](ImageWords& w) { w.w[b + m::out_word::kMsw] = 0; });
  const bool released = port_.wait_scans(seq_.release_scans);
  return finish(axis, error_mask, !(seen && released), what);
}

Outcome Plc3602::pulse(unsigned axis, std::uint16_t msw, std::uint16_t lsw, std::int32_t w23,
                       std::int32_t w45, std::int16_t w6, std::int16_t w7) {
  return edge(axis, msw, kCommandErrors, "command", [&](ImageWords& w, unsigned) {
    m3602::put_command(w, axis, msw, lsw, w23, w45, w6, w7);
  });
}

Outcome Plc3602::configure(unsigned axis, std::uint16_t cfg_msw, std::uint16_t cfg_lsw,
                           std::int32_t start_speed, std::int16_t homing_timeout_s) {
  port_.update_outputs([&](ImageWords& w) {
    m3602::put_configuration(w, axis, cfg_msw, cfg_lsw, start_speed, homing_timeout_s);
  });
  if (!port_.wait_scans(seq_.config_scans)) {
    return finish(axis, m::status_msw::kConfigurationError, true, "configure");
  }
  Outcome in_config = finish(axis, m::status_msw::kConfigurationError, false, "configure");
  // Back to command mode: the axis' words all 0 in one write.
  port_.update_outputs([&](ImageWords& w) { m3602::put_command(w, axis, 0, 0, 0, 0, 0, 0); });
  if (!port_.wait_scans(seq_.config_scans)) {
    return finish(axis, m::status_msw::kConfigurationError, true, "command mode");
  }
  if (!in_config.ok) return in_config;
  return finish(axis, m::status_msw::kConfigurationError, false, "configure");
}

Outcome Plc3602::move(unsigned axis, bool absolute, std::int32_t target, const Profile& p) {
  return pulse(axis, absolute ? m::cmd_msw::kAbsoluteMove : m::cmd_msw::kRelativeMove,
               m3602::accel_bits(p.type), target, p.speed, static_cast<std::int16_t>(p.accel),
               static_cast<std::int16_t>(p.decel));
}

Outcome Plc3602::home(unsigned axis, bool cw, const Profile& p) {
  const std::uint16_t bit = cw ? m::cmd_msw::kFindHomeCw : m::cmd_msw::kFindHomeCcw;
  // The proximity bit is the PLC's input to homing: keep it as the PLC left it.
  const auto lsw = static_cast<std::uint16_t>(
      port_.outputs().w[m3602::base(axis) + m::out_word::kLsw] & m::cmd_lsw::kBackplaneProximity);
  return edge(axis, bit, kCommandErrors | m::status_msw::kHomeInvalid, "home",
              [&](ImageWords& w, unsigned) {
                m3602::put_command(w, axis, bit, lsw, 0, p.speed,
                                   static_cast<std::int16_t>(p.accel),
                                   static_cast<std::int16_t>(p.decel));
              });
}

Outcome Plc3602::jog_press(unsigned axis, bool cw, const Profile& p, std::int32_t registration) {
  if (!release_msw(axis)) return finish(axis, kCommandErrors, true, "release");
  const std::uint16_t bit = cw ? m::cmd_msw::kJogCw : m::cmd_msw::kJogCcw;
  const std::uint16_t lsw = m3602::accel_bits(p.type) | gpo_bit(axis);
  port_.update_outputs([&](ImageWords& w) {
    m3602::put_command(w, axis, bit, lsw, registration, p.speed, static_cast<std::int16_t>(p.accel),
                       static_cast<std::int16_t>(p.decel));
  });
  return finish(axis, kCommandErrors, !port_.wait_scans(seq_.hold_scans), "jog");
}

Outcome Plc3602::jog_release(unsigned axis) {
  const unsigned msw_word = m3602::base(axis) + m::out_word::kMsw;
  port_.update_outputs([&](ImageWords& w) { w.w[msw_word] = 0; });
  return finish(axis, kCommandErrors, !port_.wait_scans(seq_.release_scans), "jog release");
}

Outcome Plc3602::jog(unsigned axis, bool cw, const Profile& p, std::chrono::milliseconds duration,
                     std::int32_t registration) {
  const Outcome pressed = jog_press(axis, cw, p, registration);
  // Level-held: keep the bit for the duration (the port keeps the PLC's heartbeat meanwhile).
  if (!pressed.timed_out) port_.pass(duration);
  const Outcome released = jog_release(axis);
  if (pressed.timed_out) return pressed;
  if (released.timed_out) return released;
  Outcome idle = wait_idle(axis, timeout_ + std::chrono::seconds(30));
  if (idle.timed_out) return idle;
  return finish(axis, kCommandErrors, false, "jog");
}

Outcome Plc3602::hold(unsigned axis) {
  const StaleIsNote note(stale_);
  return edge(axis, m::cmd_msw::kHold, m::status_msw::kCommandError, "hold",
              [](ImageWords&, unsigned) {});
}

Outcome Plc3602::resume(unsigned axis, const std::optional<Profile>& p) {
  const StaleIsNote note(stale_);
  return edge(axis, m::cmd_msw::kResume, kCommandErrors, "resume", [&](ImageWords& w, unsigned b) {
    if (!p) return;
    m3602::put_split(w, b, m::out_word::kSpeedMsw, p->speed);
    w.w[b + m::out_word::kAccel] = static_cast<std::int16_t>(p->accel);
    w.w[b + m::out_word::kDecel] = static_cast<std::int16_t>(p->decel);
    // The acceleration type is supplied again with Resume (3602 manual ch. 9 table 9.2).
    constexpr std::uint16_t kTypeBits = m::cmd_lsw::kSCurve | m::cmd_lsw::kTrapezoidalS;
    const auto lsw = static_cast<std::uint16_t>(w.w[b + m::out_word::kLsw]);
    w.w[b + m::out_word::kLsw] =
        static_cast<std::int16_t>((lsw & ~kTypeBits) | m3602::accel_bits(p->type));
  });
}

Outcome Plc3602::preset_position(unsigned axis, std::int32_t position) {
  return pulse(axis, m::cmd_msw::kPresetPosition, 0, position, 0, 0, 0);
}

Outcome Plc3602::reset_errors(unsigned axis) {
  return pulse(axis, m::cmd_msw::kResetErrors, 0, 0, 0, 0, 0);
}

Outcome Plc3602::immediate_stop(unsigned axis) {
  const StaleIsNote note(stale_);
  return pulse(axis, m::cmd_msw::kImmediateStop, 0, 0, 0, 0, 0);
}

Outcome Plc3602::set_min_registration(unsigned axis, std::int32_t distance) {
  const std::uint16_t gpo = gpo_bit(axis);
  if (!release_msw(axis) || !set_lsw(axis, gpo)) {
    return finish(axis, kCommandErrors, true, "release");
  }
  port_.update_outputs([&](ImageWords& w) {
    m3602::put_command(w, axis, 0, m::cmd_lsw::kProgramMinRegistration | gpo, distance, 0, 0, 0);
  });
  const bool seen = port_.wait_scans(seq_.hold_scans);
  return finish(axis, kCommandErrors, !(seen && set_lsw(axis, gpo)), "min-registration");
}

Outcome Plc3602::blend_program(unsigned axis, const BlendProfile& b) {
  constexpr std::uint16_t kProgram = m::cmd_lsw::kProgramBlend;
  constexpr std::uint16_t kTransmit = m::cmd_lsw::kBlendTransmit;
  const std::uint16_t gpo = gpo_bit(axis);
  if (!release_msw(axis) || !set_lsw(axis, gpo)) {
    return finish(axis, kCommandErrors, true, "release");
  }
  const auto acknowledged = [axis](bool want) {
    return [axis, want](const ImageWords& in) {
      return m3602::decode_status(in, axis).has_lsw(m::status_lsw::kBlendAcknowledge) == want;
    };
  };
  const auto abandon = [&] {
    port_.update_outputs([&](ImageWords& w) { m3602::put_command(w, axis, 0, gpo, 0, 0, 0, 0); });
  };
  const std::vector<m3602::AxisWords> blocks = m3602::blend_blocks(b);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    m3602::AxisWords a = blocks[i];
    a[m::out_word::kLsw] = kProgram | kTransmit | gpo;
    port_.update_outputs([&](ImageWords& w) { m3602::put_axis(w, axis, a); });
    if (!port_.wait_inputs(acknowledged(true), timeout_)) {
      abandon();
      return finish(axis, kCommandErrors, true, "blend block");
    }
    const unsigned lsw_word = m3602::base(axis) + m::out_word::kLsw;
    port_.update_outputs(
        [&](ImageWords& w) { w.w[lsw_word] = static_cast<std::int16_t>(kProgram | gpo); });
    if (!port_.wait_inputs(acknowledged(false), timeout_)) {
      abandon();
      return finish(axis, kCommandErrors, true, "blend block");
    }
  }
  abandon();  // program bit off, words 0: the profile is complete
  return finish(axis, kCommandErrors, !port_.wait_scans(seq_.release_scans), "blend program");
}

Outcome Plc3602::blend_run(unsigned axis, bool cw) {
  // Every other word must be 0 with Run Blend (the LSW may hold the GPO bit).
  return pulse(axis, cw ? m::cmd_msw::kRunBlendCw : m::cmd_msw::kRunBlendCcw, 0, 0, 0, 0, 0);
}

Outcome Plc3602::set_gpo(unsigned axis, bool on) {
  const unsigned lsw_word = m3602::base(axis) + m::out_word::kLsw;
  port_.update_outputs([&](ImageWords& w) {
    auto lsw = static_cast<std::uint16_t>(w.w[lsw_word]);
    lsw = on ? (lsw | m::cmd_lsw::kGpo) : (lsw & ~m::cmd_lsw::kGpo);
    w.w[lsw_word] = static_cast<std::int16_t>(lsw);
  });
  return finish(axis, kCommandErrors, !port_.wait_scans(seq_.release_scans), "gpo");
}

Outcome Plc3602::wait_idle(unsigned axis, std::chrono::nanoseconds timeout) {
  const auto idle = [axis](const ImageWords& in) {
    const m3602::Status s = m3602::decode_status(in, axis);
    return !s.moving() && !s.has_lsw(m::status_lsw::kBlendRunning);
  };
  return wait_until(axis, idle, timeout, "wait-idle");
}

}  // namespace stepmod::plc
