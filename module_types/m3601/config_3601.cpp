#include "module_types/m3601/config_3601.hpp"

#include "module_types/m3601/words_3601.hpp"

namespace stepmod::module::m3601 {
using namespace words::m3601;  // this module's words: module_types/m3601/words_3601.hpp

// kNone = 0, then the checklist in order from CFG-02.
unsigned checklist_item(ConfigFault f) noexcept {
  const auto n = static_cast<unsigned>(f);
  return n == 0 ? 0u : n + 1u;
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
    case ConfigFault::kStartingSpeedLswRange:
      return "#7 starting speed LSW outside 0..999";
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

ConfigCheck check_config(const ImageWords& out) noexcept {
  ConfigCheck r;
  const auto msw = static_cast<std::uint16_t>(out.w[out_word::kMsw]);
  const auto lsw = static_cast<std::uint16_t>(out.w[out_word::kLsw]);
  const auto vs_msw = static_cast<std::int16_t>(out.w[out_word::kTargetMsw]);
  const auto vs_lsw = static_cast<std::int16_t>(out.w[out_word::kTargetLsw]);
  const bool home = msw & cfg_msw::kHomeUsed;
  const bool proximity = msw & cfg_msw::kBackplaneProximity;
  const bool marker = msw & cfg_msw::kMarkerHoming;
  const bool encoder = msw & cfg_msw::kQuadratureEncoder;
  const bool diagnostic = msw & cfg_msw::kDiagnosticFeedback;

  // Checked in the manual's order; the first failing item is reported.
  auto fail = [&r](ConfigFault f) {
    r.fault = f;
    return r;
  };
  // #1: limit-switch homing needs the home input; marker homing is a way to home by itself (its
  // proximity source is checked by #9/#10). 3601 manual ch. 3 (inferred).
  if (!marker && !home) return fail(ConfigFault::kNoHoming);
  if (!(msw & (cfg_msw::kCwLimitUsed | cfg_msw::kCcwLimitUsed))) {
    return fail(ConfigFault::kNoEndLimit);
  }
  if (encoder && diagnostic) return fail(ConfigFault::kEncoderAndDiagnostic);
  if (marker && !encoder) return fail(ConfigFault::kMarkerWithoutEncoder);
  if (diagnostic && !(msw & cfg_msw::kStepDirOutput)) {
    return fail(ConfigFault::kDiagnosticWithCwCcw);
  }
  // #7 before #6: an LSW outside 0..999 makes the value meaningless, whatever it sums to.
  if (vs_lsw < 0 || vs_lsw > 999) return fail(ConfigFault::kStartingSpeedLswRange);
  // A negative MSW makes the speed negative: below 1.
  const std::optional<std::int32_t> vs = words::decode_3601_unsigned(vs_msw, vs_lsw);
  if (!vs || *vs < 1 || *vs > 1'000'000) return fail(ConfigFault::kStartingSpeedRange);
  if ((msw & cfg_msw::kReserved) || (lsw & cfg_lsw::kReserved)) {
    return fail(ConfigFault::kReservedBits);
  }
  if (marker && !home && !proximity) return fail(ConfigFault::kMarkerWithoutProximity);
  if (marker && home && proximity) return fail(ConfigFault::kMarkerWithBothProximities);
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
  a.quadrature_encoder = c.has(cfg_msw::kQuadratureEncoder);
  a.diagnostic_feedback = c.has(cfg_msw::kDiagnosticFeedback);
  a.step_dir_output = c.has(cfg_msw::kStepDirOutput);
  a.backplane_proximity = c.has(cfg_msw::kBackplaneProximity);
  // Homing option (3601 manual ch. 3 table); CFG-10/11 guarantee exactly one proximity source with
  // marker homing.
  const bool marker = c.has(cfg_msw::kMarkerHoming);
  if (marker) {
    a.homing = a.backplane_proximity ? axis::HomingVariant::kMarkerWithBackplane
                                     : axis::HomingVariant::kMarkerWithHome;
  } else {
    a.homing = a.backplane_proximity ? axis::HomingVariant::kSwitchWithBackplane
                                     : axis::HomingVariant::kSwitch;
  }
  a.starting_speed = c.starting_speed;
  return a;
}

}  // namespace stepmod::module::m3601
