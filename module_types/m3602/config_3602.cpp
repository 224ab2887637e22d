#include "module_types/m3602/config_3602.hpp"
#include "module_types/m3602/rules_3602.hpp"

#include "core/enum_names.hpp"
#include "module/axis/rules.hpp"
#include "module/shared/invalid_configs.hpp"
#include "module_types/m3602/words_3602.hpp"

namespace stepmod::module::m3602 {
using namespace words::m3602;  // this module's words: module_types/m3602/words_3602.hpp

namespace {

unsigned cw_field(std::uint16_t msw) noexcept {
  return (msw & cfg_msw::kCwFunction) >> cfg_msw::kCwFunctionShift;
}
unsigned ccw_field(std::uint16_t msw) noexcept {
  return (msw & cfg_msw::kCcwFunction) >> cfg_msw::kCcwFunctionShift;
}

axis::LimitFunction function_of(unsigned field) noexcept {
  switch (field) {
    case cfg_msw::kFunctionLimit:
      return axis::LimitFunction::kLimit;
    case cfg_msw::kFunctionEStop:
      return axis::LimitFunction::kEStop;
    default:
      return axis::LimitFunction::kUnused;  // 11 never gets here (3602-CFG-03/04)
  }
}

}  // namespace

// kNone = 0, then the checklist in order from CFG-02.
unsigned checklist_item(ConfigFault f) noexcept {
  return shared::checklist_item_in_order(f);
}

std::string_view describe(ConfigFault f) noexcept {
  // In enumerator order (config_3602.hpp).
  static constexpr std::array<std::string_view, 8> kTexts = {
      "valid",
      "reserved configuration MSW bit set (8, 9, 11, 12, 13)",
      "CW input function 11",
      "CCW input function 11",
      "reserved configuration LSW bit set (5..15)",
      "starting speed outside 1..1,000,000",
      "homing timeout outside 0..300 s",
      "reserved configuration word (5..7) not zero"};
  static_assert(static_cast<std::size_t>(ConfigFault::kReservedWords) + 1 == kTexts.size());
  return enum_name(f, kTexts);
}

ConfigFault check_config(const ImageWords& out, Config3602& decoded) noexcept {
  const auto msw = static_cast<std::uint16_t>(out.w[out_word::kMsw]);
  const auto lsw = static_cast<std::uint16_t>(out.w[out_word::kLsw]);
  // Binary split (3602 manual Ch.8 "Starting Speed"): a set MSW sign bit makes the value negative,
  // hence below 1.
  const std::int32_t vs =
      words::decode_3602(out.w[out_word::kStartingSpeedMsw], out.w[out_word::kStartingSpeedLsw]);
  const auto timeout = static_cast<std::int16_t>(out.w[out_word::kHomingTimeout]);
  const axis::ModuleRules& r = kRules3602;

  // A19: a configuration that disables the axis is accepted without further checks (the axis
  // ignores commands and stays idle; CfgE = 0, 3602-CFG-N2).
  if (msw & cfg_msw::kDisableAxis) {
    decoded = Config3602{msw, lsw, vs, timeout};
    return ConfigFault::kNone;
  }
  // Checked in the order of the manual's tables (8.6 MSW, 8.7 LSW, then the parameters).
  if (msw & cfg_msw::kReserved) return ConfigFault::kReservedMswBits;
  if (cw_field(msw) == cfg_msw::kFunctionInvalid) return ConfigFault::kCwInputFunction;
  if (ccw_field(msw) == cfg_msw::kFunctionInvalid) return ConfigFault::kCcwInputFunction;
  if (lsw & cfg_lsw::kReserved) return ConfigFault::kReservedLswBits;
  if (vs < r.starting_speed_min || vs > r.starting_speed_max) {
    return ConfigFault::kStartingSpeedRange;
  }
  if (timeout < 0 || timeout > r.homing_timeout_max_s) return ConfigFault::kHomingTimeoutRange;
  for (unsigned w = out_word::kSpeedLsw; w <= out_word::kDecel; ++w) {
    if (static_cast<std::int16_t>(out.w[w]) != 0) return ConfigFault::kReservedWords;
  }
  decoded = Config3602{msw, lsw, vs, timeout};
  return ConfigFault::kNone;
}

axis::AxisConfig to_axis_config(const Config3602& c) noexcept {
  axis::AxisConfig a;
  const auto line_bit = [](InputLine l) {
    return static_cast<std::uint16_t>(1u << static_cast<unsigned>(l));
  };
  // The 3602's capture/external/home enables and active levels sit at bits 0..2 like InputLine
  // 0..2; its CW / CCW inputs (active levels in LSW bits 3 / 4) are the axis' CW / CCW limit
  // lines, whatever function they are configured for. The 3602 has no separate E-stop terminal.
  a.inputs_used =
      c.msw & (cfg_msw::kCaptureEnabled | cfg_msw::kExternalEnabled | cfg_msw::kHomeEnabled);
  a.inputs_active_high = c.lsw & (cfg_lsw::kCaptureActiveHigh | cfg_lsw::kExternalActiveHigh |
                                  cfg_lsw::kHomeActiveHigh);
  a.cw_input = function_of(cw_field(c.msw));
  a.ccw_input = function_of(ccw_field(c.msw));
  if (a.cw_input != axis::LimitFunction::kUnused) a.inputs_used |= line_bit(InputLine::kCwLimit);
  if (a.ccw_input != axis::LimitFunction::kUnused) {
    a.inputs_used |= line_bit(InputLine::kCcwLimit);
  }
  if (c.lsw & cfg_lsw::kCwActiveHigh) a.inputs_active_high |= line_bit(InputLine::kCwLimit);
  if (c.lsw & cfg_lsw::kCcwActiveHigh) a.inputs_active_high |= line_bit(InputLine::kCcwLimit);
  a.step_dir_output = (c.msw & cfg_msw::kStepDirOutput) != 0;
  a.backplane_proximity = (c.msw & cfg_msw::kBackplaneProximity) != 0;
  a.homing = a.backplane_proximity ? axis::HomingVariant::kSwitchWithBackplane
                                   : axis::HomingVariant::kSwitch;
  a.starting_speed = c.starting_speed;
  a.homing_timeout = static_cast<Nanos>(c.homing_timeout_s) * kNsPerSec;
  a.disabled = (c.msw & cfg_msw::kDisableAxis) != 0;
  return a;
}

}  // namespace stepmod::module::m3602
