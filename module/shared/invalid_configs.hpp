#pragma once
// The list of invalid configurations that the 3601 and the 3202 manuals share (ch. 3 "Invalid
// Configurations" #1..#11: the same bits, the same order; the 3202 reads #7 as a rule of old
// firmware only). Both dialects decode their own words into ConfigBits and ask these checks, so
// the list is written once; each keeps its own fault enum (checklist items 3601-CFG-nn,
// 3202-CFG-nn), whose enumerators for the shared items have the same names.
#include <cstdint>
#include <iterator>
#include <optional>
#include <string_view>

#include "module/axis/axis_config.hpp"
#include "words/shared_config_bits.hpp"

namespace stepmod::module::shared {

// What a configuration says about homing, limits and feedback, as both manuals define the bits.
struct ConfigBits {
  bool home = false;           // home input used
  bool proximity = false;      // backplane home proximity
  bool marker = false;         // marker homing
  bool encoder = false;        // quadrature encoder
  bool diagnostic = false;     // diagnostic feedback
  bool step_dir = false;       // step+direction outputs (0 = CW/CCW)
  bool any_end_limit = false;  // CW or CCW limit used
};

// Where a module's configuration word keeps those bits: words/shared_config_bits.hpp, looked up
// by name in the module's table (both manuals name these bits alike).
constexpr ConfigBits read_config_bits(std::uint32_t word,
                                      const words::SharedConfigMasks& m) noexcept {
  return {(word & m.home) != 0,        (word & m.proximity) != 0,  (word & m.marker) != 0,
          (word & m.encoder) != 0,     (word & m.diagnostic) != 0, (word & m.step_dir) != 0,
          (word & m.end_limits()) != 0};
}

// #1..#5 in the manual's order: the first failing item, or nothing.
template <typename Fault>
constexpr std::optional<Fault> homing_and_feedback_fault(const ConfigBits& b) noexcept {
  // #1: limit-switch homing needs the home input; marker homing is a way to home by itself (its
  // proximity source is checked by #9/#10). 3601 manual ch. 3 (inferred), the 3202 alike.
  if (!b.marker && !b.home) return Fault::kNoHoming;
  if (!b.any_end_limit) return Fault::kNoEndLimit;
  if (b.encoder && b.diagnostic) return Fault::kEncoderAndDiagnostic;
  if (b.marker && !b.encoder) return Fault::kMarkerWithoutEncoder;
  if (b.diagnostic && !b.step_dir) return Fault::kDiagnosticWithCwCcw;
  return std::nullopt;
}

// #9 and #10: marker homing needs exactly one proximity source (home input or backplane).
template <typename Fault>
constexpr std::optional<Fault> proximity_fault(const ConfigBits& b) noexcept {
  if (b.marker && !b.home && !b.proximity) return Fault::kMarkerWithoutProximity;
  if (b.marker && b.home && b.proximity) return Fault::kMarkerWithBothProximities;
  return std::nullopt;
}

// The feedback, output and homing options of a valid configuration into the shared axis' terms;
// the homing option by both manuals' ch. 3 table (#9/#10 guarantee exactly one proximity source
// with marker homing).
constexpr void apply_config_bits(const ConfigBits& b, axis::AxisConfig& a) noexcept {
  a.quadrature_encoder = b.encoder;
  a.diagnostic_feedback = b.diagnostic;
  a.step_dir_output = b.step_dir;
  a.backplane_proximity = b.proximity;
  if (b.marker) {
    a.homing = b.proximity ? axis::HomingVariant::kMarkerWithBackplane
                           : axis::HomingVariant::kMarkerWithHome;
  } else {
    a.homing =
        b.proximity ? axis::HomingVariant::kSwitchWithBackplane : axis::HomingVariant::kSwitch;
  }
}

// The text of checklist item CFG-`item` of the shared list (0 = "valid"; item n + 1 is #n). #7 is
// each module's own: the 3601 describes it itself, the 3202 never reports it.
constexpr std::string_view invalid_config_text(unsigned item) noexcept {
  constexpr std::string_view kTexts[] = {
      "#1 no way to home (neither home input nor marker homing)",
      "#2 neither CW nor CCW end limit configured",
      "#3 quadrature encoder and diagnostic feedback",
      "#4 marker homing without quadrature encoder",
      "#5 diagnostic feedback with CW/CCW outputs",
      "#6 starting speed outside 1..1,000,000",
      "?",
      "#8 reserved configuration bit set",
      "#9 marker homing without home input or backplane proximity",
      "#10 marker homing with both home input and backplane proximity",
      "#11 unused configuration word not zero",
  };
  if (item == 0) return "valid";
  return item >= 2 && item - 2 < std::size(kTexts) ? kTexts[item - 2] : "?";
}

// The checklist item of a fault enum written in checklist order from CFG-02 (kNone = 0 -> 0).
// `gap`: the first enumerator after an item the enum leaves out (the 3202's #7), if any.
template <typename Fault>
constexpr unsigned checklist_item_in_order(Fault f, std::optional<Fault> gap = {}) noexcept {
  const auto n = static_cast<unsigned>(f);
  if (n == 0) return 0;
  return n + 1u + (gap && f >= *gap ? 1u : 0u);
}

}  // namespace stepmod::module::shared
