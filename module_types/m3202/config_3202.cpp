#include "module_types/m3202/config_3202.hpp"

#include "module/shared/invalid_configs.hpp"
#include "module_types/m3202/words_3202.hpp"

namespace stepmod::module::m3202 {
using namespace words::m3202;  // this module's words: module_types/m3202/words_3202.hpp

// kNone = 0, then the checklist in order from CFG-02 (CFG-08 is old firmware's only: skipped).
unsigned checklist_item(ConfigFault f) noexcept {
  return shared::checklist_item_in_order(f, std::optional(ConfigFault::kReservedBits));
}

std::string_view describe(ConfigFault f) noexcept {
  return shared::invalid_config_text(checklist_item(f));
}

ConfigCheck check_config(const ImageWords& out, unsigned channel) noexcept {
  ConfigCheck r;
  const unsigned b = channel_base(channel);
  const auto bits = static_cast<std::uint32_t>(out.w[b + out_word::kCommand]);
  const std::int32_t vs = out.w[b + out_word::kTarget];
  auto fail = [&r](ConfigFault f) {
    r.fault = f;
    return r;
  };
  // 3202-CFG-13, A19: a channel configured disabled never shows CfgE; the other checks are
  // skipped (the manual: bit 13 is never set while the channel is disabled).
  if (bits & cfg_bit::kDisable) {
    r.config = Config3202{bits, vs};
    return r;
  }
  const shared::ConfigBits shared_bits = shared::read_config_bits(bits, cfg_bit::kShared);
  // Checked in the manual's order; the first failing item is reported. #1 as on the 3601
  // (3202 manual ch. 3, inferred): marker homing is a way to home by itself.
  if (auto f = shared::homing_and_feedback_fault<ConfigFault>(shared_bits)) return fail(*f);
  if (vs < 1 || vs > 1'000'000) return fail(ConfigFault::kStartingSpeedRange);
  // #7 (capture without encoder) applies to firmware <= 2.2 only; this module reports 3.1
  // (words_3202.hpp), so it is no error (3202-CFG-08).
  if (bits & cfg_bit::kReserved) return fail(ConfigFault::kReservedBits);
  if (auto f = shared::proximity_fault<ConfigFault>(shared_bits)) return fail(*f);
  for (unsigned w = 2; w < kWordsPerChannel; ++w) {
    if (out.w[b + w] != 0) return fail(ConfigFault::kUnusedWordsNonZero);
  }
  r.config = Config3202{bits, vs};
  return r;
}

axis::AxisConfig to_axis_config(const Config3202& c) noexcept {
  axis::AxisConfig a;
  a.disabled = c.has(cfg_bit::kDisable);
  if (a.disabled) return a;  // A19: nothing else of a disabled channel's words is looked at
  // Bits 0..5 ("used") and 16..21 (active levels) are both in InputLine order (3202 manual ch. 3).
  a.inputs_used = static_cast<std::uint16_t>(c.bits & cfg_bit::kInputsUsed);
  a.inputs_active_high =
      static_cast<std::uint16_t>((c.bits & cfg_bit::kActiveLevels) >> cfg_bit::kActiveLevelShift);
  shared::apply_config_bits(shared::read_config_bits(c.bits, cfg_bit::kShared), a);
  a.starting_speed = c.starting_speed;
  return a;
}

}  // namespace stepmod::module::m3202
