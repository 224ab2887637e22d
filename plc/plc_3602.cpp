#include "plc/plc_3602.hpp"

#include <stdexcept>
#include <string>

#include "module/m3602/words_3602.hpp"
#include "plc/bit_names.hpp"

namespace stepmod::plc {

namespace m = module::m3602;

namespace {
constexpr std::uint16_t kCommandErrors =
    m::status_msw::kCommandError | m::status_msw::kInvalidProfile;
}  // namespace

Plc3602::Plc3602(Port& port, std::chrono::milliseconds timeout, Sequencing seq)
    : port_(port), timeout_(timeout), seq_(seq) {
  if (port.type() != ModuleType::k3602) {
    throw std::invalid_argument(
        "the module is a " + std::to_string(static_cast<unsigned>(port.type())) + ", not a 3602");
  }
}

std::uint16_t Plc3602::gpo_bit(unsigned axis) const {
  const auto lsw =
      static_cast<std::uint16_t>(port_.outputs().w[m3602::base(axis) + m::out_word::kLsw]);
  return lsw & m::cmd_lsw::kGpo;
}

Outcome Plc3602::finish(unsigned axis, std::uint16_t error_mask, bool timed_out, const char* what) {
  Outcome o;
  port_.read_inputs(o.in);
  if (timed_out) {
    o.ok = false;
    o.timed_out = true;
    o.message = std::string(what) + ": no answer from the module within " +
                std::to_string(timeout_.count()) + " ms (is stepmodd running?)";
    return o;
  }
  const std::uint16_t msw = m3602::decode_status(o.in, axis).msw;
  if (msw & error_mask) {
    o.ok = false;
    o.message = std::string(what) + ": " + set_bit_names(msw & error_mask, m::kStatusMswBits);
  }
  return o;
}

Outcome Plc3602::pulse(unsigned axis, std::uint16_t msw, std::uint16_t lsw, std::int32_t w23,
                       std::int32_t w45, std::int16_t w6, std::int16_t w7) {
  const unsigned msw_word = m3602::base(axis) + m::out_word::kMsw;
  // A command bit left at 1 would hide the next 0->1 edge: release it first.
  if (seq_.release_stale_bits && port_.outputs().w[msw_word] != 0) {
    port_.update_outputs([&](ImageWords& w) { w.w[msw_word] = 0; });
    if (!port_.wait_scans(seq_.release_scans)) return finish(axis, kCommandErrors, true, "release");
  }
  const std::uint16_t gpo = gpo_bit(axis);
  port_.update_outputs(
      [&](ImageWords& w) { m3602::put_command(w, axis, msw, lsw | gpo, w23, w45, w6, w7); });
  const bool seen = port_.wait_scans(seq_.hold_scans);
  port_.update_outputs([&](ImageWords& w) { w.w[msw_word] = 0; });
  const bool released = port_.wait_scans(seq_.release_scans);
  return finish(axis, kCommandErrors, !(seen && released), "command");
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

Outcome Plc3602::preset_position(unsigned axis, std::int32_t position) {
  return pulse(axis, m::cmd_msw::kPresetPosition, 0, position, 0, 0, 0);
}

Outcome Plc3602::reset_errors(unsigned axis) {
  return pulse(axis, m::cmd_msw::kResetErrors, 0, 0, 0, 0, 0);
}

Outcome Plc3602::immediate_stop(unsigned axis) {
  return pulse(axis, m::cmd_msw::kImmediateStop, 0, 0, 0, 0, 0);
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
  const bool idle = port_.wait_inputs(
      [axis](const ImageWords& in) { return !m3602::decode_status(in, axis).moving(); }, timeout);
  return finish(axis, 0, !idle, "wait-idle");
}

}  // namespace stepmod::plc
