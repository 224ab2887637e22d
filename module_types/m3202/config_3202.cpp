#include "module_types/m3202/config_3202.hpp"

#include "module_types/m3202/words_3202.hpp"

namespace stepmod::module::m3202 {
using namespace words::m3202;  // this module's words: module_types/m3202/words_3202.hpp

// kNone = 0, then the checklist in order from CFG-02 (CFG-08 is old firmware's only: skipped).
unsigned checklist_item(ConfigFault f) noexcept {
  const auto n = static_cast<unsigned>(f);
  return n == 0 ? 0u : n + 1u + (f >= ConfigFault::kReservedBits ? 1u : 0u);
}

std::string_view describe(ConfigFault f) noexcept {
  switch (f) {
    case ConfigFault::kNone:
      return "valid";
    case ConfigFault::kNoHoming:
      return "#1 no way to home (neither home input nor marker homing)";
    case ConfigFault::kNoEndLimit:
      return "#2 neither CW nor CCW end limit configured";
    case ConfigFault::kEncoderAndDiagnostic:
      return "#3 quadrature encoder and diagnostic feedback";
    case ConfigFault::kMarkerWithoutEncoder:
      return "#4 marker homing without quadrature encoder";
    case ConfigFault::kDiagnosticWithCwCcw:
      return "#5 diagnostic feedback with CW/CCW outputs";
    case ConfigFault::kStartingSpeedRange:
      return "#6 starting speed outside 1..1,000,000";
    case ConfigFault::kReservedBits:
      return "#8 reserved configuration bit set";
    case ConfigFault::kMarkerWithoutProximity:
      return "#9 marker homing without home input or backplane proximity";
    case ConfigFault::kMarkerWithBothProximities:
      return "#10 marker homing with both home input and backplane proximity";
    case ConfigFault::kUnusedWordsNonZero:
      return "#11 unused configuration word not zero";
  }
  return "?";
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
  const bool home = bits & cfg_bit::kHomeUsed;
  const bool proximity = bits & cfg_bit::kBackplaneProximity;
  const bool marker = bits & cfg_bit::kMarkerHoming;
  const bool encoder = bits & cfg_bit::kQuadratureEncoder;
  const bool diagnostic = bits & cfg_bit::kDiagnosticFeedback;
  // Checked in the manual's order; the first failing item is reported. #1 as on the 3601
  // (3202 manual ch. 3, inferred): marker homing is a way to home by itself.
  if (!marker && !home) return fail(ConfigFault::kNoHoming);
  if (!(bits & (cfg_bit::kCwLimitUsed | cfg_bit::kCcwLimitUsed))) {
    return fail(ConfigFault::kNoEndLimit);
  }
  if (encoder && diagnostic) return fail(ConfigFault::kEncoderAndDiagnostic);
  if (marker && !encoder) return fail(ConfigFault::kMarkerWithoutEncoder);
  if (diagnostic && !(bits & cfg_bit::kStepDirOutput)) {
    return fail(ConfigFault::kDiagnosticWithCwCcw);
  }
  if (vs < 1 || vs > 1'000'000) return fail(ConfigFault::kStartingSpeedRange);
  // #7 (capture without encoder) applies to firmware <= 2.2 only; this module reports 3.1
  // (words_3202.hpp), so it is no error (3202-CFG-08).
  if (bits & cfg_bit::kReserved) return fail(ConfigFault::kReservedBits);
  if (marker && !home && !proximity) return fail(ConfigFault::kMarkerWithoutProximity);
  if (marker && home && proximity) return fail(ConfigFault::kMarkerWithBothProximities);
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
  a.quadrature_encoder = c.has(cfg_bit::kQuadratureEncoder);
  a.diagnostic_feedback = c.has(cfg_bit::kDiagnosticFeedback);
  a.step_dir_output = c.has(cfg_bit::kStepDirOutput);
  a.backplane_proximity = c.has(cfg_bit::kBackplaneProximity);
  // Homing option by bits 12 / 2 / 6, as on the 3601 (3202 manual ch. 3);
  // CFG-10/11 guarantee exactly one proximity source with marker homing.
  if (c.has(cfg_bit::kMarkerHoming)) {
    a.homing = a.backplane_proximity ? axis::HomingVariant::kMarkerWithBackplane
                                     : axis::HomingVariant::kMarkerWithHome;
  } else {
    a.homing = a.backplane_proximity ? axis::HomingVariant::kSwitchWithBackplane
                                     : axis::HomingVariant::kSwitch;
  }
  a.starting_speed = c.starting_speed;
  return a;
}

}  // namespace stepmod::module::m3202
