// stepmodctl's 3202 dialect: two channels (--channel 1|2), native DINTs (3202 manual ch. 5) and
// rates in steps/s^2 (A31): the options are passed as given and the module judges them. The blend
// profile is a 52-DINT message through the image's mailbox (docs/interface.md 3).
#include "module_types/m3202/ctl_3202.hpp"
#include "module_types/m3202/plc_3202.hpp"
#include "module_types/m3202/words_3202.hpp"
#include "tools/ctl_args.hpp"
#include "tools/ctl_blend.hpp"

namespace stepmod::tools::ctl {

namespace {

constexpr Limits kDint{INT32_MIN, INT32_MAX, "the 3202's DINT"};
constexpr ProfileLimits kProfile{kDint, kDint};

std::uint32_t configuration_bits(const ConfigureArgs& a) {
  namespace cb = words::m3202::cfg_bit;
  if (a.cw_estop || a.ccw_estop || !a.homing_timeout.empty()) {
    throw UsageError("--cw-estop, --ccw-estop and --homing-timeout are the 3602's");
  }
  std::uint32_t bits = shared_config_bits(a, cb::kShared);
  bits |= a.disable ? cb::kDisable : 0;
  // Active levels in bits 16..21: active high unless named (3202 manual ch. 3).
  std::uint32_t levels = cb::kActiveLevels;
  for (const auto& in : a.active_low) levels &= ~(1u << (cb::kActiveLevelShift + input_index(in)));
  return bits | levels;
}

plc::Outcome program_blend(const CtlRequest& c, plc::Plc3202& plc, ipc::Client& client,
                           std::chrono::milliseconds timeout) {
  const plc::BlendProfile b =
      blend_from_options(c.blend_file, c.segments, c.final_decel, c.final_type);
  const auto data = plc::m3202::blend_message(static_cast<std::int32_t>(c.unit + 1), b);
  const auto result = client.send_message(data, timeout);
  plc::Outcome o = plc.status(c.unit);
  if (!result) {
    o.ok = false;
    o.timed_out = true;
    o.message = "blend: the module did not take the message (is stepmodd running?)";
  } else if (*result != words::m3202::kMessageAccepted) {
    o.ok = false;
    o.message = "blend: message refused (result " + std::to_string(*result) +
                "; see Invalid Profile / Command Error)";
  }
  return o;
}

}  // namespace

template <>
plc::Outcome CtlOf<ModuleType::k3202>::run_command(const CtlRequest& c, plc::Port& port,
                                                   ipc::Client& client,
                                                   std::chrono::milliseconds timeout) {
  plc::Plc3202 plc(port, timeout);
  const unsigned ch = c.unit;
  switch (c.verb) {
    case Verb::kConfigure: {
      const std::uint32_t bits = configuration_bits(c.configure);
      return plc.configure(ch, bits,
                           parse_limited(c.configure.start_speed, "--start-speed", kDint));
    }
    case Verb::kMove:
      return plc.move(ch, c.kind == "abs", parse_limited(c.value, "TARGET", kDint),
                      parse_profile(c.profile, kProfile), c.encoder_move);
    case Verb::kJog: {
      if (!c.registration.empty()) throw UsageError("the 3202 has no registration move");
      const plc::Profile p = parse_profile(c.profile, kProfile);
      return plc.jog(ch, parse_direction(c.direction), p, millis(c.jog_seconds));
    }
    case Verb::kHome: {
      const bool cw = parse_direction(c.direction);
      return plc.home(ch, cw, parse_profile(c.profile, kProfile));
    }
    case Verb::kHold:
      return plc.hold(ch);
    case Verb::kResume:
      return plc.resume(ch, parse_optional_profile(c.profile, kProfile));
    case Verb::kStop:
      return plc.immediate_stop(ch);
    case Verb::kPreset:
      return plc.preset_position(ch, parse_limited(c.value, "POSITION", kDint));
    case Verb::kPresetEncoder:
      return plc.preset_encoder(ch, c.value.empty() ? 0 : parse_limited(c.value, "VALUE", kDint));
    case Verb::kReset:
      return plc.reset_errors(ch);
    case Verb::kBlendProgram:
      return program_blend(c, plc, client, timeout);
    case Verb::kBlendRun:
      return plc.blend_run(ch, parse_direction(c.direction));
    case Verb::kWaitIdle:
      return plc.wait_idle(ch, millis(c.wait_seconds));
    case Verb::kMinRegistration:
      throw UsageError("the 3202 has no registration move: no min-registration");
    case Verb::kFollow:
      throw UsageError("the 3202 has no encoder follower");
    case Verb::kPath:
    case Verb::kPathWait:
      throw UsageError("the 3202 has no interpolated moves (path is the 3602's)");
    case Verb::kGpo:
      break;
  }
  throw UsageError("the 3202 has no general-purpose output (gpo is the 3602's)");
}

}  // namespace stepmod::tools::ctl
