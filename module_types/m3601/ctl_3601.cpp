// stepmodctl's 3601 dialect: one axis, numbers as the decimal split of two 16-bit words (3601
// manual ch. 5), accelerations in steps/ms/s in one 16-bit word each.
#include "module_types/m3601/ctl_3601.hpp"
#include "module_types/m3601/plc_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "tools/ctl_args.hpp"
#include "tools/ctl_blend.hpp"

namespace stepmod::tools::ctl {

namespace {

// MSW * 1000 + LSW in two INTs: beyond this range the MSW would wrap and the module would read
// another, possibly valid, number (65,537,000 would arrive as 1,000 and move the axis). Values
// the words carry but the module refuses (a target beyond 8,388,607) are sent: the module
// reports them.
constexpr Limits kSplit{-32'768'999, 32'767'999, "the 3601's two words"};
constexpr Limits kWord{INT16_MIN, INT16_MAX, "the 3601's 16-bit word"};
constexpr ProfileLimits kProfile{kSplit, kWord};

std::uint16_t configuration_msw(const ConfigureArgs& a) {
  namespace cm = words::m3601::cfg_msw;
  if (a.cw_estop || a.ccw_estop || a.disable || !a.homing_timeout.empty()) {
    throw UsageError("--cw-estop, --ccw-estop, --disable and --homing-timeout are the 3602's");
  }
  // Bits 0..12 are the ones the 3202 names alike; the 3601's MSW has no others but the mode bit.
  return static_cast<std::uint16_t>(shared_config_bits(a, cm::kShared));
}

// Active levels in bits 0..5 (InputLine order); the manual advises active-high bits even for
// unused inputs (3601 manual ch. 3).
std::uint16_t configuration_lsw(const ConfigureArgs& a) {
  std::uint16_t lsw = 0x3F;
  for (const auto& in : a.active_low)
    lsw = static_cast<std::uint16_t>(lsw & ~(1u << input_index(in)));
  return lsw;
}

plc::BlendProfile blend_profile(const CtlRequest& c) {
  plc::BlendProfile b = blend_from_options(c.blend_file, c.segments, c.final_decel, c.final_type);
  for (const plc::BlendSegment& s : b.segments) {
    check_range(s.length, "segment LENGTH", kSplit.lo, kSplit.hi, kSplit.words);
    check_range(s.speed, "segment SPEED", kSplit.lo, kSplit.hi, kSplit.words);
    check_range(s.accel, "segment ACCEL", kWord.lo, kWord.hi, kWord.words);
  }
  // Word 5: the type in bits 15..14, the value in bits 13..0.
  check_range(b.final_decel, "--final-decel", 0, 0x3FFF, "bits 13..0 of the 3601's word 5");
  return b;
}

}  // namespace

template <>
plc::Outcome CtlOf<ModuleType::k3601>::run_command(const CtlRequest& c, plc::Port& port,
                                                   ipc::Client& /*client*/,
                                                   std::chrono::milliseconds timeout) {
  if (c.unit != 0) throw UsageError("the 3601 has one axis: --axis 1");
  plc::Plc3601 plc(port, timeout);
  switch (c.verb) {
    case Verb::kConfigure: {
      const std::uint16_t msw = configuration_msw(c.configure);
      const std::uint16_t lsw = configuration_lsw(c.configure);
      return plc.configure(msw, lsw,
                           parse_limited(c.configure.start_speed, "--start-speed", kSplit));
    }
    case Verb::kMove:
      return plc.move(c.kind == "abs", parse_limited(c.value, "TARGET", kSplit),
                      parse_profile(c.profile, kProfile), c.encoder_move);
    case Verb::kJog: {
      const plc::Profile p = parse_profile(c.profile, kProfile);
      const std::int32_t reg =
          c.registration.empty() ? 0 : parse_limited(c.registration, "--registration", kSplit);
      return plc.jog(parse_direction(c.direction), p, millis(c.jog_seconds), reg);
    }
    case Verb::kHome: {
      const bool cw = parse_direction(c.direction);
      return plc.home(cw, parse_profile(c.profile, kProfile));
    }
    case Verb::kHold:
      return plc.hold();
    case Verb::kResume:
      return plc.resume(parse_optional_profile(c.profile, kProfile));
    case Verb::kStop:
      return plc.immediate_stop();
    case Verb::kPreset:
      return plc.preset_position(parse_limited(c.value, "POSITION", kSplit));
    case Verb::kPresetEncoder:
      return plc.preset_encoder(c.value.empty() ? 0 : parse_limited(c.value, "VALUE", kSplit));
    case Verb::kReset:
      return plc.reset_errors();
    case Verb::kMinRegistration:
      return plc.set_min_registration(parse_limited(c.value, "DISTANCE", kSplit));
    case Verb::kBlendProgram:
      return plc.blend_program(blend_profile(c));
    case Verb::kBlendRun:
      return plc.blend_run(parse_direction(c.direction));
    case Verb::kFollow: {
      if (c.follow_sense == "off") return plc.end_follow();
      const int sense = c.follow_sense == "+" ? 1 : c.follow_sense == "-" ? -1 : 0;
      return plc.follow(sense, static_cast<std::int16_t>(c.follow_multiplier),
                        static_cast<std::int16_t>(c.follow_divisor),
                        static_cast<std::int16_t>(c.follow_accel),
                        static_cast<std::int16_t>(c.follow_decel));
    }
    case Verb::kWaitIdle:
      return plc.wait_idle(millis(c.wait_seconds));
    case Verb::kPath:
    case Verb::kPathWait:
      throw UsageError("the 3601 has one axis: interpolated moves (path) are the 3602's");
    case Verb::kGpo:
      break;
  }
  throw UsageError("the 3601 has no general-purpose output (gpo is the 3602's)");
}

}  // namespace stepmod::tools::ctl
