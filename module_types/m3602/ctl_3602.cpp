// stepmodctl's 3602 dialect: two axes (--axis 1|2), numbers as the binary split of two 16-bit
// words (3602 manual ch. 9: every int32 fits, the module refuses what is out of its ranges),
// accelerations in steps/ms/s in one 16-bit word each. Interpolated moves (`path`) are
// module_types/m3602/ctl_path_3602.cpp's.
#include "module_types/m3602/ctl_3602.hpp"
#include "module_types/m3602/ctl_path_3602.hpp"
#include "module_types/m3602/plc_3602.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "tools/ctl_args.hpp"
#include "tools/ctl_blend.hpp"

namespace stepmod::tools::ctl {

namespace {

constexpr Limits kSplit{INT32_MIN, INT32_MAX, "the 3602's two words"};
constexpr Limits kWord{INT16_MIN, INT16_MAX, "the 3602's 16-bit word"};
constexpr ProfileLimits kProfile{kSplit, kWord};

std::uint16_t configuration_msw(const ConfigureArgs& a) {
  namespace cm = words::m3602::cfg_msw;
  if (a.estop || a.encoder || a.diagnostic || a.marker) {
    throw UsageError(
        "the 3602 has no E-stop terminal, encoder or marker homing (use --cw-estop / "
        "--ccw-estop)");
  }
  const auto function = [](bool limit, bool estop) -> unsigned {
    if (limit && estop) throw UsageError("a CW/CCW input is a limit or an E-stop, not both");
    return estop ? cm::kFunctionEStop : limit ? cm::kFunctionLimit : cm::kFunctionUnused;
  };
  std::uint16_t msw = 0;
  msw |= a.capture ? cm::kCaptureEnabled : 0;
  msw |= a.external ? cm::kExternalEnabled : 0;
  msw |= a.home ? cm::kHomeEnabled : 0;
  msw |= static_cast<std::uint16_t>(function(a.cw_limit, a.cw_estop) << cm::kCwFunctionShift);
  msw |= static_cast<std::uint16_t>(function(a.ccw_limit, a.ccw_estop) << cm::kCcwFunctionShift);
  msw |= a.proximity ? cm::kBackplaneProximity : 0;
  msw |= a.cw_ccw ? 0 : cm::kStepDirOutput;
  msw |= a.disable ? cm::kDisableAxis : 0;
  return msw;
}

// Active levels of capture, external, home, CW, CCW in bits 0..4 (3602 manual ch. 8 table 8.3);
// active high unless named.
std::uint16_t configuration_lsw(const ConfigureArgs& a) {
  std::uint16_t lsw = 0x1F;
  for (const auto& in : a.active_low) {
    const unsigned i = input_index(in);
    if (i == 3) throw UsageError("the 3602 has no estop input (--cw-estop / --ccw-estop)");
    lsw = static_cast<std::uint16_t>(lsw & ~(1u << (i < 3 ? i : i - 1)));
  }
  return lsw;
}

plc::BlendProfile blend_profile(const CtlRequest& c) {
  plc::BlendProfile b = blend_from_options(c.blend_file, c.segments, c.final_decel, c.final_type);
  for (const plc::BlendSegment& s : b.segments) {
    check_range(s.accel, "segment ACCEL", kWord.lo, kWord.hi, kWord.words);
  }
  // Word 5 of the first block: the type in bits 15..14, bits 13..11 zero, the value in 10..0.
  check_range(b.final_decel, "--final-decel", 0, 0x07FF, "bits 10..0 of the 3602's word 5");
  return b;
}

}  // namespace

template <>
plc::Outcome CtlOf<ModuleType::k3602>::run_command(const CtlRequest& c, plc::Port& port,
                                                   ipc::Client& /*client*/,
                                                   std::chrono::milliseconds timeout) {
  plc::Plc3602 plc(port, timeout);
  const unsigned ax = c.unit;
  switch (c.verb) {
    case Verb::kConfigure: {
      const ConfigureArgs& a = c.configure;
      const std::uint16_t msw = configuration_msw(a);
      const std::uint16_t lsw = configuration_lsw(a);
      const std::int32_t vs = parse_limited(a.start_speed, "--start-speed", kSplit);
      const std::int32_t timeout_s =
          a.homing_timeout.empty()
              ? 0
              : parse_limited(a.homing_timeout, "--homing-timeout", {0, INT16_MAX, "word 4"});
      return plc.configure(ax, msw, lsw, vs, static_cast<std::int16_t>(timeout_s));
    }
    case Verb::kMove:
      if (c.encoder_move) throw UsageError("the 3602 has no encoder: no --encoder move");
      return plc.move(ax, c.kind == "abs", parse_limited(c.value, "TARGET", kSplit),
                      parse_profile(c.profile, kProfile));
    case Verb::kJog: {
      const plc::Profile p = parse_profile(c.profile, kProfile);
      const std::int32_t reg =
          c.registration.empty() ? 0 : parse_limited(c.registration, "--registration", kSplit);
      return plc.jog(ax, parse_direction(c.direction), p, millis(c.jog_seconds), reg);
    }
    case Verb::kHome: {
      const bool cw = parse_direction(c.direction);
      return plc.home(ax, cw, parse_profile(c.profile, kProfile));
    }
    case Verb::kHold:
      return plc.hold(ax);
    case Verb::kResume:
      return plc.resume(ax, parse_optional_profile(c.profile, kProfile));
    case Verb::kStop:
      return plc.immediate_stop(ax);
    case Verb::kPreset:
      return plc.preset_position(ax, parse_limited(c.value, "POSITION", kSplit));
    case Verb::kReset:
      return plc.reset_errors(ax);
    case Verb::kMinRegistration:
      return plc.set_min_registration(ax, parse_limited(c.value, "DISTANCE", kSplit));
    case Verb::kBlendProgram:
      return plc.blend_program(ax, blend_profile(c));
    case Verb::kBlendRun:
      return plc.blend_run(ax, parse_direction(c.direction));
    case Verb::kWaitIdle:
      return plc.wait_idle(ax, millis(c.wait_seconds));
    case Verb::kGpo:
      return plc.set_gpo(ax, c.gpo_on);
    case Verb::kPath:
    case Verb::kPathWait:
      return run_path_3602(c, port, timeout, kProfile);
    case Verb::kPresetEncoder:
      throw UsageError("the 3602 has no encoder: no preset-encoder");
    case Verb::kFollow:
      break;
  }
  throw UsageError("the 3602 has no encoder follower");
}

}  // namespace stepmod::tools::ctl
