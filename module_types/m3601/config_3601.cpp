#include "module_types/m3601/config_3601.hpp"

#include "module/shared/invalid_configs.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {
using namespace words::m3601;  // this module's words: module_types/m3601/words_3601.hpp

// kNone = 0, then the checklist in order from CFG-02.
unsigned checklist_item(ConfigFault f) noexcept {
  return shared::checklist_item_in_order(f);
}

std::string_view describe(ConfigFault f) noexcept {
  // #7 is the 3601's own (its decimal split); the rest is the list the 3202 shares.
  if (f == ConfigFault::kStartingSpeedLswRange) return "#7 starting speed LSW outside 0..999";
  return shared::invalid_config_text(checklist_item(f));
}

ConfigCheck check_config(const ImageWords& out) noexcept {
  ConfigCheck r;
  const auto msw = static_cast<std::uint16_t>(out.w[out_word::kMsw]);
  const auto lsw = static_cast<std::uint16_t>(out.w[out_word::kLsw]);
  const auto vs_msw = static_cast<std::int16_t>(out.w[out_word::kTargetMsw]);
  const auto vs_lsw = static_cast<std::int16_t>(out.w[out_word::kTargetLsw]);
  const shared::ConfigBits bits = shared::read_config_bits(msw, cfg_msw::kShared);

  // Checked in the manual's order; the first failing item is reported.
  auto fail = [&r](ConfigFault f) {
    r.fault = f;
    return r;
  };
  if (auto f = shared::homing_and_feedback_fault<ConfigFault>(bits)) return fail(*f);
  // #7 before #6: an LSW outside 0..999 makes the value meaningless, whatever it sums to.
  if (vs_lsw < 0 || vs_lsw > 999) return fail(ConfigFault::kStartingSpeedLswRange);
  // A negative MSW makes the speed negative: below 1.
  const std::optional<std::int32_t> vs = words::decode_3601_unsigned(vs_msw, vs_lsw);
  if (!vs || *vs < 1 || *vs > 1'000'000) return fail(ConfigFault::kStartingSpeedRange);
  if ((msw & cfg_msw::kReserved) || (lsw & cfg_lsw::kReserved)) {
    return fail(ConfigFault::kReservedBits);
  }
  if (auto f = shared::proximity_fault<ConfigFault>(bits)) return fail(*f);
  for (unsigned w = 4; w < kWords; ++w) {
    if (out.w[w] != 0) return fail(ConfigFault::kUnusedWordsNonZero);
  }
  r.config = Config3601{msw, lsw, vs_msw, vs_lsw, *vs};
  return r;
}

axis::AxisConfig to_axis_config(const Config3601& c) noexcept {
  axis::AxisConfig a;
  // The "used" bits of the MSW and the active-level bits of the LSW sit at the same positions,
  // in InputLine order (capture, external, home, E-stop, CW limit, CCW limit), 3601 manual ch. 3.
  constexpr std::uint16_t kInputBits = cfg_msw::kCaptureUsed | cfg_msw::kExternalUsed |
                                       cfg_msw::kHomeUsed | cfg_msw::kEStopUsed |
                                       cfg_msw::kCwLimitUsed | cfg_msw::kCcwLimitUsed;
  a.inputs_used = c.msw & kInputBits;
  a.inputs_active_high = c.lsw & kInputBits;
  shared::apply_config_bits(shared::read_config_bits(c.msw, cfg_msw::kShared), a);
  a.starting_speed = c.starting_speed;
  return a;
}

}  // namespace stepmod::module::m3601
